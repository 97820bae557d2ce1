//! The base excitation `s(t)`: a cycle (or one law) at a shaft speed, written as time pieces.

use crate::oscillator::{Harmonic, NCOEF, poly_derivs};
use loomkin_laws::{Cycle, DerivativeScale, Law, SegmentKind};
use loomkin_units::ShaftSpeed;

/// One piece of the excitation in time: `s(t) = Σ p_k t^k − (A/Ω²)·sin(Ωt + φ)` for
/// `t ∈ [0, duration]` (s), so that `s''(t) = (poly)'' + A·sin(Ωt + φ)`.
///
/// A law segment of local coordinate `u` (fraction of the motion) becomes a time piece through
/// `u = r·t`, `r = ω_shaft/Δθ` (1/s): `p_k ← h·p_k·r^k`, `A ← h·A·r²`, `Ω ← Ω·r`, with `h` the
/// signed stroke (m or rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimePiece {
    /// Start time from the start of the cycle (s).
    pub t0: f64,
    /// Duration (s).
    pub duration: f64,
    /// Displacement polynomial in local time, lowest power first (SI).
    pub poly: [f64; NCOEF],
    /// The sinusoidal acceleration term `A·sin(Ωt + φ)` (SI/s², Ω in rad/s).
    pub accel_sine: Option<Harmonic>,
    /// True when the follower stands still (a dwell of the cycle).
    pub dwell: bool,
    /// Index of the cycle segment it belongs to.
    pub segment: usize,
}

impl TimePiece {
    /// `s, s', s'', s''', s''''` at local time `t`.
    #[inline]
    pub fn derivs(&self, t: f64) -> [f64; 5] {
        let mut out = poly_derivs::<5>(&self.poly, t);
        if let Some(h) = self.accel_sine {
            let (s, c) = (h.omega * t + h.phase).sin_cos();
            let w = h.omega;
            out[0] -= h.amp / (w * w) * s;
            out[1] -= h.amp / w * c;
            out[2] += h.amp * s;
            out[3] += h.amp * w * c;
            out[4] -= h.amp * w * w * s;
        }
        out
    }

    /// The magnitudes of the terms that make up `s, s', …, s⁽⁵⁾` at local time `t`:
    /// `Σ |p_k·k!/(k−n)!·t^(k−n)| + |A|·|Ω|^(n−2)` for order `n`. An evaluated derivative is within
    /// a few ulps of its sum however small the value itself is (Horner's rule on degree ≤ 7 and the
    /// sine stay within `32·ε` of it).
    pub fn term_magnitudes(&self, t: f64) -> [f64; 6] {
        let mut out = [0.0; 6];
        for (n, o) in out.iter_mut().enumerate() {
            let mut tk = 1.0;
            for k in 0..NCOEF - n {
                // (k + n)!/k! · p_{k+n} · t^k, the n-th derivative's k-th term.
                let falling = ((k + 1)..=(k + n)).map(|m| m as f64).product::<f64>();
                *o += (falling * self.poly[k + n] * tk).abs();
                tk *= t;
            }
            if let Some(h) = self.accel_sine {
                *o += match n {
                    0 => (h.amp / (h.omega * h.omega)).abs(),
                    1 => (h.amp / h.omega).abs(),
                    _ => (h.amp * h.omega.powi(n as i32 - 2)).abs(),
                };
            }
        }
        out
    }

    /// Bounds on the rounding error of `s` and `s'` as [`TimePiece::derivs`] evaluates them at `t`:
    /// `32·ε` times the sum of the magnitudes of their terms ([`TimePiece::term_magnitudes`]).
    fn rounding(&self, t: f64) -> [f64; 2] {
        let m = self.term_magnitudes(t);
        [32.0 * f64::EPSILON * m[0], 32.0 * f64::EPSILON * m[1]]
    }
}

/// The whole excitation over one cycle.
#[derive(Debug, Clone, PartialEq)]
pub struct Excitation {
    /// The pieces in time order, covering `[0, period_s]`.
    pub pieces: Vec<TimePiece>,
    /// Duration of one cycle (s).
    pub period_s: f64,
    /// Main-shaft angle at the start of the cycle (deg).
    pub start_deg: f64,
    /// Angle of one cycle (deg).
    pub period_deg: f64,
    /// The largest stroke of the cycle (SI, > 0), the reference of "% of stroke".
    pub stroke_si: f64,
    /// Shaft speed (rpm): one cycle per revolution of `period_deg`.
    pub speed_rpm: f64,
}

/// Pieces of one law of duration `time_s`, stroke `h` (signed), starting at `t0` and height `base`.
fn law_pieces(law: &Law, time_s: f64, h: f64, base: f64, t0: f64, segment: usize, out: &mut Vec<TimePiece>) {
    let r = 1.0 / time_s;
    for seg in law.segments() {
        let p = seg.displacement_poly();
        let mut poly = [0.0; NCOEF];
        let mut rk = 1.0;
        for k in 0..NCOEF {
            poly[k] = h * p[k] * rk;
            rk *= r;
        }
        poly[0] += base;
        let accel_sine =
            seg.sine().map(|sn| Harmonic { amp: h * sn.amp * r * r, omega: sn.omega * r, phase: sn.phase }.positive());
        out.push(TimePiece {
            t0: t0 + seg.x0() * time_s,
            duration: seg.width() * time_s,
            poly,
            accel_sine,
            dwell: false,
            segment,
        });
    }
}

impl Excitation {
    /// The cycle at a shaft speed: `t = (θ − θ_start)/ω_shaft`.
    pub fn from_cycle(cycle: &Cycle, speed: ShaftSpeed) -> Self {
        let w = speed.rad_per_s();
        let start = cycle.segments.first().map_or(0.0, |s| s.start_rad);
        let mut pieces = Vec::new();
        for (i, seg) in cycle.segments.iter().enumerate() {
            let t0 = (seg.start_rad - start) / w;
            let dur = seg.length_rad / w;
            match (&seg.law, seg.kind) {
                (Some((_, law)), SegmentKind::Rise | SegmentKind::Return) => {
                    law_pieces(law, dur, seg.stroke_si, seg.base_si, t0, i, &mut pieces)
                }
                _ => {
                    let mut poly = [0.0; NCOEF];
                    poly[0] = seg.base_si;
                    pieces.push(TimePiece { t0, duration: dur, poly, accel_sine: None, dwell: true, segment: i });
                }
            }
        }
        let stroke_si = cycle.segments.iter().map(|s| s.stroke_si.abs()).fold(0.0, f64::max);
        Self {
            pieces,
            period_s: cycle.period_rad / w,
            start_deg: start.to_degrees(),
            period_deg: cycle.period_rad.to_degrees(),
            stroke_si: if stroke_si > 0.0 { stroke_si } else { 1.0 },
            speed_rpm: speed.rpm(),
        }
    }

    /// One normalised law as a rise of stroke 1 over `motion_time_s`, followed by a dwell of the same
    /// length (the setting of a residual-vibration spectrum). The "speed" is one rise per two motion times.
    pub fn rise_then_dwell(law: &Law, motion_time_s: f64) -> Self {
        let mut pieces = Vec::new();
        law_pieces(law, motion_time_s, 1.0, 0.0, 0.0, 0, &mut pieces);
        let mut poly = [0.0; NCOEF];
        poly[0] = 1.0;
        pieces.push(TimePiece {
            t0: motion_time_s,
            duration: motion_time_s,
            poly,
            accel_sine: None,
            dwell: true,
            segment: 1,
        });
        Self {
            pieces,
            period_s: 2.0 * motion_time_s,
            start_deg: 0.0,
            period_deg: 360.0,
            stroke_si: 1.0,
            speed_rpm: 60.0 / (2.0 * motion_time_s),
        }
    }

    /// The jumps of `s` and `s'` from the end of piece `i` to the start of the next (the first piece
    /// after the last), as the follower's error `y = x − s` takes them with `x`, `x'` continuous.
    ///
    /// A jump within the rounding of the two evaluations is none: a law's cycle is continuous in `s`
    /// and `s'` by construction, and its two sides, each evaluated to a few ulps of the stroke,
    /// differ by ~1e-17 m. Kept, that difference started a free vibration whose acceleration
    /// `ω_n²·1e-17 m` swamped a stiff follower at low speed (f_n = 1 MHz at 0.001 rpm: |x''| of
    /// 1e-3 m/s² where the input's is 1.4e-9) and floored residuals at ~2e-16 of the stroke.
    pub fn joint_jump(&self, i: usize) -> (f64, f64) {
        let l = &self.pieces[i];
        let r = &self.pieces[(i + 1) % self.pieces.len()];
        let (dl, dr) = (l.derivs(l.duration), r.derivs(0.0));
        let (el, er) = (l.rounding(l.duration), r.rounding(0.0));
        let jump = |k: usize| {
            let d = dl[k] - dr[k];
            if d.abs() <= el[k] + er[k] { 0.0 } else { d }
        };
        (jump(0), jump(1))
    }

    /// The scale of each derivative (`s` … `s⁽⁴⁾`) of every cycle segment, indexed by
    /// [`TimePiece::segment`]: the sampled peaks over its pieces ([`DerivativeScale`]), the scale a
    /// jump at one of its joints is judged against.
    pub fn segment_scales(&self) -> Vec<DerivativeScale<5>> {
        let n = self.pieces.iter().map(|p| p.segment + 1).max().unwrap_or(0);
        let mut out = vec![DerivativeScale::default(); n];
        for p in &self.pieces {
            out[p.segment] = out[p.segment].max(DerivativeScale::of_piece(p.duration, |t| p.derivs(t)));
        }
        out
    }

    /// The lowest derivative order (0…4) that jumps at some joint of the cycle (wrap-around
    /// included), with the joint's time and the jump (right − left); `None` when `s` … `s⁽⁴⁾` are
    /// all continuous.
    ///
    /// The one continuity judgement of the laws ([`DerivativeScale::first_jump`]): a difference is a
    /// jump when it exceeds [`loomkin_laws::CONTINUITY_TOL`] of the peak of that derivative over the
    /// motions on either side (the cycle segments' [`Excitation::segment_scales`]: a law's own scale,
    /// not the values at the joints, which are zero where a law meets a dwell) plus the rounding of
    /// the two evaluations: `32·ε` of their terms and `8·ε·t` of the next order's, `t` the joint's
    /// time (each side's end is placed to an ulp of its position).
    pub fn first_jump(&self) -> Option<(usize, f64, f64)> {
        let n = self.pieces.len();
        let scales = self.segment_scales();
        let joints: Vec<_> = (0..n)
            .map(|i| {
                let (l, r) = (&self.pieces[i], &self.pieces[(i + 1) % n]);
                let t = if i + 1 == n { self.period_s } else { r.t0 };
                let (tl, tr) = (l.term_magnitudes(l.duration), r.term_magnitudes(0.0));
                let rounding: [f64; 5] = std::array::from_fn(|k| {
                    f64::EPSILON * (32.0 * (tl[k] + tr[k]) + 8.0 * t.abs() * tl[k + 1].max(tr[k + 1]))
                });
                let scale = scales[l.segment].max(scales[r.segment]);
                // The wrap-around joint is at the cycle's start.
                (if i + 1 == n { 0.0 } else { t }, l.derivs(l.duration), r.derivs(0.0), rounding, scale)
            })
            .collect();
        (0..5).find_map(|order| {
            joints.iter().find_map(|(t, left, right, rounding, scale)| {
                scale
                    .jumps(order, left[order], right[order], rounding[order])
                    .then(|| (order, *t, right[order] - left[order]))
            })
        })
    }

    /// The main-shaft angle (deg) at time `t` from the start of the cycle.
    pub fn angle_deg(&self, t: f64) -> f64 {
        self.start_deg + t / self.period_s * self.period_deg
    }

    /// The piece containing time `t` of the cycle (`t` wrapped into one cycle).
    pub fn piece_at(&self, t: f64) -> usize {
        let t = t.rem_euclid(self.period_s);
        self.pieces.partition_point(|p| p.t0 <= t).saturating_sub(1)
    }
}
