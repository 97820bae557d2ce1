//! Shed geometry: straight warp lines from the fell through each heald eye to the back rest.
//!
//! With the fell at the origin, `x` back along the warp and the back rest at `(l, h_b)`, frame
//! `i`'s eye sits at distance `d_i` on the warp line at mid-stroke, height `h_b·d_i/l`, and at
//! `e_i = h_b·d_i/l + y_i` when the frame is `y_i` above mid-stroke. One end of that frame runs
//!
//! $$ L(y) = \sqrt{d^2 + e^2} + \sqrt{(l - d)^2 + (h_b - e)^2}, \qquad L_0 = \sqrt{l^2 + h_b^2}, $$
//!
//! and its strain is `ε = L/L₀ − 1`. For a level warp line and a small lift this is the
//! textbook `ΔL ≈ (y²/2)·(1/d + 1/(l − d))`, i.e. `ΔL ≈ (H²/8)·(1/d + 1/(l − d))` at a full
//! shed of height `H` (docs/loom.md derives both).

use crate::Geometry;
use serde::Serialize;

/// The length of one end through an eye `y` above mid-stroke at distance `d` and its first two
/// derivatives with respect to `y`: `(L, dL/dy, d²L/dy²)`, m, –, 1/m.
pub fn thread_length(d: f64, back_rest: f64, warp_line: f64, y: f64) -> (f64, f64, f64) {
    let e = warp_line * d / back_rest + y;
    let (a, b) = (d, back_rest - d);
    let (r1, r2) = ((a * a + e * e).sqrt(), (b * b + (warp_line - e) * (warp_line - e)).sqrt());
    let dl = e / r1 - (warp_line - e) / r2;
    let d2l = a * a / (r1 * r1 * r1) + b * b / (r2 * r2 * r2);
    (r1 + r2, dl, d2l)
}

/// The straight length fell → back rest, m.
pub fn straight_length(back_rest: f64, warp_line: f64) -> f64 {
    back_rest.hypot(warp_line)
}

/// Warp strain of an end through an eye `y` above mid-stroke at distance `d` (exact).
///
/// Written so that nothing cancels however small the lift. With `c₁ = h_b·d/l` and
/// `c₂ = h_b − c₁` the straight line's rises in front of and behind the eye, `r₁`, `r₂` the two
/// legs and `s₁ = d·L₀/l`, `s₂ = (l − d)·L₀/l` their shares of the straight line,
/// `r₁² − s₁² = y(2c₁ + y)` and `r₂² − s₂² = y(y − 2c₂)`; their leading terms `±h_b·y/l` cancel
/// between the legs, and taking that out exactly (`d·c₂ = (l − d)·c₁ = K`) leaves
///
/// `ε·L₀ = y²·[1/R₁ + 1/R₂ − 2h_b(2K + (l − 2d)y) / ((d·r₂ + (l − d)·r₁)·R₁·R₂)]`, `R = r + s`,
///
/// whose bracket is `l⁴/(2L₀³·d(l − d))` at `y = 0` and loses at most a factor `L₀²/l² ≤ 2` to the
/// subtraction. (Each leg minus its share, summed, lost the strain's digits to those leading
/// terms and to `d² + y² − d²`: 2e-4 relative at a 1 µm lift, all of them below 1 nm.)
pub fn strain(d: f64, back_rest: f64, warp_line: f64, y: f64) -> f64 {
    let (l, hb) = (back_rest, warp_line);
    let l0 = straight_length(l, hb);
    let c1 = hb * d / l;
    let c2 = hb - c1;
    let (r1, r2) = (d.hypot(c1 + y), (l - d).hypot(c2 - y));
    let (big1, big2) = (r1 + d / l * l0, r2 + (l - d) / l * l0);
    let k = hb * d * (l - d) / l;
    let bracket =
        (1.0 / big1 + 1.0 / big2) - 2.0 * hb * (2.0 * k + (l - 2.0 * d) * y) / ((d * r2 + (l - d) * r1) * big1 * big2);
    y * y * bracket / l0
}

/// The small-lift strain of the textbooks for a level warp line: `ε ≈ y²/(2·d·(l − d))`.
pub fn strain_small_lift(d: f64, back_rest: f64, y: f64) -> f64 {
    y * y / (2.0 * d * (back_rest - d))
}

/// Clean-shed strokes: every stroke proportional to the frame's distance from the fell, so every
/// sheet lies in one plane in front of the frames (`H_i = H_1·d_i/d_1`).
pub fn clean_strokes(frame_m: &[f64], front_stroke_m: f64) -> Vec<f64> {
    frame_m.iter().map(|d| front_stroke_m * d / frame_m[0]).collect()
}

/// The larger strain of a frame at the top and at the bottom of a stroke `h` (centred on the warp line).
pub fn full_shed_strain(d: f64, back_rest: f64, warp_line: f64, h: f64) -> f64 {
    strain(d, back_rest, warp_line, h / 2.0).max(strain(d, back_rest, warp_line, -h / 2.0))
}

/// Strokes that give every frame the largest strain of the front frame at `front_stroke_m`
/// (bisection on each stroke: the full-shed strain grows with the stroke).
pub fn equal_strain_strokes(frame_m: &[f64], back_rest: f64, warp_line: f64, front_stroke_m: f64) -> Vec<f64> {
    let target = full_shed_strain(frame_m[0], back_rest, warp_line, front_stroke_m);
    frame_m
        .iter()
        .enumerate()
        .map(|(i, &d)| {
            if i == 0 {
                return front_stroke_m;
            }
            let f = |h: f64| full_shed_strain(d, back_rest, warp_line, h) - target;
            let (mut lo, mut hi) = (0.0, front_stroke_m);
            let mut n = 0;
            while f(hi) < 0.0 && n < 60 {
                (lo, hi) = (hi, 2.0 * hi);
                n += 1;
            }
            loomkin_numeric::bisect_within(lo, hi, 1e-15, |h| f(h) < 0.0)
        })
        .collect()
}

/// The shed of one frame at full lift.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FrameShed {
    /// Distance of the heald eyes from the fell (the front shed depth), mm.
    pub distance_mm: f64,
    /// Full stroke, bottom to top, mm (all four lengths to 12 significant digits: the loom file's
    /// millimetres without the noise of their way through metres).
    pub stroke_mm: f64,
    /// Front shed depth (fell to heald eye), mm.
    pub front_depth_mm: f64,
    /// Back shed depth (heald eye to back rest), mm.
    pub back_depth_mm: f64,
    /// Angle at the fell between this frame's upper and lower sheets, deg.
    pub shed_angle_deg: f64,
    /// Angle at the back rest between the sheets, deg.
    pub back_shed_angle_deg: f64,
    /// Strain of an end with the frame at the top of its stroke.
    pub strain_top: f64,
    /// Strain of an end with the frame at the bottom.
    pub strain_bottom: f64,
}

impl Geometry {
    /// Height of the warp line over the fell at distance `x`, m.
    pub fn warp_line_at(&self, x: f64) -> f64 {
        self.warp_line_m * x / self.back_rest_m
    }

    /// The full-lift shed of frame `i`.
    pub fn frame_shed(&self, i: usize) -> FrameShed {
        let (d, h, l, hb) = (self.frame_m[i], self.stroke_m[i], self.back_rest_m, self.warp_line_m);
        let w = self.warp_line_at(d);
        let front = ((w + h / 2.0) / d).atan() - ((w - h / 2.0) / d).atan();
        let back = ((hb - w + h / 2.0) / (l - d)).atan() - ((hb - w - h / 2.0) / (l - d)).atan();
        // Lengths the loom file gives in mm, back from metres to 12 digits (`90`, not
        // `89.99999999999999`: the noise of the way through metres and the lift ratio).
        let mm = |m: f64| loomkin_units::to_12_digits(m * 1e3);
        FrameShed {
            distance_mm: mm(d),
            stroke_mm: mm(h),
            front_depth_mm: mm(d),
            back_depth_mm: mm(l - d),
            shed_angle_deg: front.to_degrees(),
            back_shed_angle_deg: back.to_degrees(),
            strain_top: strain(d, l, hb, h / 2.0),
            strain_bottom: strain(d, l, hb, -h / 2.0),
        }
    }

    /// Strain of an end of frame `i` with its eye `y` above mid-stroke.
    pub fn strain_at(&self, i: usize, y: f64) -> f64 {
        strain(self.frame_m[i], self.back_rest_m, self.warp_line_m, y)
    }

    /// The clear opening of a shed at distance `x` in front of the front frame (`x ≤ d₁`), given
    /// each frame's height `y_i` over mid-stroke and whether it belongs to the upper sheet: from
    /// the lowest raised end down to the highest lowered end, `x·(min_up y_i/d_i − max_down y_j/d_j)`.
    /// `None` when one side has no frame.
    pub fn clear_height(&self, x: f64, y: &[f64], upper: &[bool]) -> Option<f64> {
        let mut sheets = Sheets::EMPTY;
        for ((&yi, &d), &up) in y.iter().zip(&self.frame_m).zip(upper) {
            sheets.add(yi, d, up);
        }
        sheets.clear_height(x)
    }
}

/// The two sheets of a shed at one instant, frame by frame: the lowest slope `y_i/d_i` of the
/// upper sheet and the highest of the lower ([`Geometry::clear_height`]). The least and the
/// largest of a set of slopes do not depend on the order the frames are added in (`min` and
/// `max` do not round), so the frames resting over a span can be added once for every instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sheets {
    lo_up: f64,
    hi_down: f64,
}

impl Sheets {
    /// No frame yet.
    pub const EMPTY: Self = Self { lo_up: f64::INFINITY, hi_down: f64::NEG_INFINITY };

    /// Adds a frame at distance `d` (m) from the fell, its eye `y` (m) over mid-stroke, in the
    /// upper sheet when `up`.
    #[inline]
    pub fn add(&mut self, y: f64, d: f64, up: bool) {
        let slope = y / d;
        if up { self.lo_up = self.lo_up.min(slope) } else { self.hi_down = self.hi_down.max(slope) }
    }

    /// The clear opening at distance `x` in front of the front frame, `x·(min_up y_i/d_i −
    /// max_down y_j/d_j)`; `None` when one side has no frame.
    #[inline]
    pub fn clear_height(&self, x: f64) -> Option<f64> {
        (self.lo_up.is_finite() && self.hi_down.is_finite()).then_some(x * (self.lo_up - self.hi_down))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shed's lengths are the loom file's millimetres without the noise of their way through
    /// metres (`loom check` printed `stroke_mm: 89.99999999999999`), and within 1e-14 relative of
    /// the metres the model computes with.
    #[test]
    fn the_sheds_lengths_are_the_files_mm_without_noise() {
        let loom = crate::Loom::from_toml(include_str!("../../../examples/rapier-loom.toml")).unwrap();
        let g = &loom.geometry;
        let (f1, f2) = (g.frame_shed(0), g.frame_shed(1));
        assert_eq!((f1.distance_mm, f1.stroke_mm, f1.back_depth_mm), (200.0, 90.0, 750.0));
        assert_eq!((f2.distance_mm, f2.stroke_mm, f2.back_depth_mm), (212.0, 95.4, 738.0));
        for i in 0..loom.frame_count() {
            let f = g.frame_shed(i);
            let close = |mm: f64, m: f64| (mm - m * 1e3).abs() <= 1e-14 * mm;
            assert!(close(f.stroke_mm, g.stroke_m[i]) && close(f.distance_mm, g.frame_m[i]), "frame {}", i + 1);
            assert!(close(f.back_depth_mm, g.back_rest_m - g.frame_m[i]), "frame {}", i + 1);
        }
    }

    /// Strain against a direct length computation (coordinates of the three points).
    #[test]
    fn strain_is_the_length_change_of_the_polyline() {
        for &(d, l, hb, y) in &[(0.2, 0.9, 0.0, 0.04), (0.35, 1.1, 0.05, -0.06), (0.15, 0.8, -0.03, 0.02)] {
            let p0 = (0.0f64, 0.0f64);
            let eye = (d, hb * d / l + y);
            let rest = (l, hb);
            let len = |a: (f64, f64), b: (f64, f64)| ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt();
            let direct = (len(p0, eye) + len(eye, rest)) / len(p0, rest) - 1.0;
            let ours = strain(d, l, hb, y);
            assert!((ours - direct).abs() < 1e-15 + 1e-12 * direct.abs(), "{ours} vs {direct}");
            let (ll, _, _) = thread_length(d, l, hb, y);
            assert!((ll / straight_length(l, hb) - 1.0 - direct).abs() < 1e-14);
        }
    }

    /// The textbook small-lift formula: relative error O(y²/d²).
    #[test]
    fn small_lifts_follow_the_textbook_formula() {
        let (d, l) = (0.25, 0.9);
        for y in [1e-4, 1e-3, 1e-2] {
            let exact = strain(d, l, 0.0, y);
            let approx = strain_small_lift(d, l, y);
            assert!((exact / approx - 1.0).abs() < (y / d).powi(2), "y {y}: {exact} vs {approx}");
        }
        // ΔL = H²/8·(1/d + 1/(l − d)) at a full shed H = 2y.
        let h = 0.002;
        let dl = strain(d, l, 0.0, h / 2.0) * l;
        assert!((dl / (h * h / 8.0 * (1.0 / d + 1.0 / (l - d))) - 1.0).abs() < 1e-4);
    }

    /// Lifts down to 1 nm: the strain against the second-order Taylor term of the thread length,
    /// `ε ≈ y²·l³(1/d + 1/(l − d))/(2L₀⁴)` (from `L″(0) = d²/r₁³ + (l − d)²/r₂³` with the legs at
    /// their shares of the straight line), whose relative error is of order `y/d` (cubic term),
    /// and against the textbook formula for a level line. The old sum of leg differences was
    /// 100 % off at 1 nm (its rounding, 1e-16 of L₀, is the whole strain).
    #[test]
    fn tiny_lifts_keep_their_digits() {
        for &(d, l, hb) in
            &[(0.25, 0.9, 0.0), (0.23, 0.9, 0.02), (0.5, 0.9, -0.9), (0.8999, 0.9, 0.3), (1e-4, 0.9, 0.05)]
        {
            let l0 = straight_length(l, hb);
            let taylor = |y: f64| y * y * l.powi(3) * (1.0 / d + 1.0 / (l - d)) / (2.0 * l0.powi(4));
            for y in [1e-9, -1e-9, 1e-7, -3e-8] {
                let ours = strain(d, l, hb, y);
                let tol = 4.0 * (y / d.min(l - d)).abs() + 1e-13;
                assert!((ours / taylor(y) - 1.0).abs() < tol, "d {d} hb {hb} y {y}: {ours} vs {}", taylor(y));
            }
        }
        let (d, l) = (0.25, 0.9);
        for y in [1e-9, 1e-6] {
            let exact = strain(d, l, 0.0, y);
            assert!((exact / strain_small_lift(d, l, y) - 1.0).abs() < 1e-13 + (y / d).powi(2), "{y}: {exact}");
        }
    }

    #[test]
    fn length_derivatives_match_finite_differences() {
        let (d, l, hb) = (0.3, 1.0, 0.04);
        for y in [-0.05, 0.0, 0.03] {
            let h = 1e-5;
            let (_, d1, d2) = thread_length(d, l, hb, y);
            let f = |y| thread_length(d, l, hb, y).0;
            let fd1 = (f(y + h) - f(y - h)) / (2.0 * h);
            let fd2 = (thread_length(d, l, hb, y + h).1 - thread_length(d, l, hb, y - h).1) / (2.0 * h);
            assert!((d1 - fd1).abs() < 1e-9 && (d2 - fd2).abs() < 1e-6 * d2.abs(), "{d1} {fd1} {d2} {fd2}");
        }
    }

    /// Clean shed: the lines from the fell through every raised eye coincide (one plane in front
    /// of the frames), checked by constructing the sheet of each frame.
    #[test]
    fn clean_shed_puts_every_sheet_in_one_plane() {
        let frames = [0.18, 0.2, 0.23, 0.27];
        let h = clean_strokes(&frames, 0.08);
        let slope0 = (h[0] / 2.0) / frames[0];
        for (d, hi) in frames.iter().zip(&h) {
            // The raised eye (d, h/2): the line from the fell to it has the front frame's slope.
            assert!(((hi / 2.0) / d - slope0).abs() < 1e-15);
        }
        let g = Geometry {
            frame_m: frames.to_vec(),
            reed_m: 0.1,
            back_rest_m: 0.9,
            warp_line_m: 0.0,
            stroke_m: h.clone(),
            lifts: crate::Lifts::Clean,
        };
        let y: Vec<f64> = h.iter().enumerate().map(|(i, hi)| if i % 2 == 0 { hi / 2.0 } else { -hi / 2.0 }).collect();
        let up: Vec<bool> = (0..4).map(|i| i % 2 == 0).collect();
        let clear = g.clear_height(0.1, &y, &up).unwrap();
        assert!((clear - 0.1 * 0.08 / 0.18).abs() < 1e-15);
        let a0 = g.frame_shed(0).shed_angle_deg;
        for i in 1..4 {
            assert!((g.frame_shed(i).shed_angle_deg - a0).abs() < 1e-12);
        }
    }

    #[test]
    fn equal_strain_strokes_equalise_the_strain() {
        let frames = [0.18, 0.22, 0.3, 0.4];
        for hb in [0.0, 0.05] {
            let h = equal_strain_strokes(&frames, 1.0, hb, 0.09);
            let e0 = full_shed_strain(frames[0], 1.0, hb, h[0]);
            for (d, hi) in frames.iter().zip(&h) {
                assert!((full_shed_strain(*d, 1.0, hb, *hi) / e0 - 1.0).abs() < 1e-12);
            }
            // Back frames lift more than the front one for equal strain at a level line… but less
            // than the clean shed asks (their strain there would be larger).
            let clean = clean_strokes(&frames, 0.09);
            assert!(h[3] < clean[3]);
        }
    }
}
