//! A crank-rocker sley for a target reed stroke and back dwell, with the largest least
//! transmission angle.
//!
//! **Construction.** In a frame with the rocking shaft Q at the origin and the sword upright at
//! mid-swing, the stroke S fixes the rocker's swing `Δ = S/h` and so the sword's pin at both dead
//! centres, `B± = c·e(π/2 ∓ Δ/2)` (front, toward the fell, first). Any crank centre O then makes a
//! four-bar with exactly these dead positions: with `L± = |O − B±|`, the rod is `b = (L₊ + L₋)/2`
//! and the crank `r = |L₊ − L₋|/2` (crank and rod collinear at both). So the stroke is met by
//! construction, and the design space is the plane of O: along each ray `O = M + ρ·e(u)` from the
//! middle M of the chord B₊B₋, the back dwell is a function of ρ whose crossings of the target are
//! located by bisection to adjacent doubles ([`loomkin_numeric::bisect`]) between the points of a
//! logarithmic grid where it changes side; the least transmission angle (closed form) of those
//! linkages, as a function of the ray's direction u, is maximised by [`loomkin_numeric::scan_max`]
//! (a grid over the turn whose peaks golden-section search refines). Every candidate is checked
//! by [`FourBarSley::new`] and its stroke and dwell recomputed from it.
//!
//! The shape of θ(φ) depends only on the ratios of the lengths, so the sword `c` only scales the
//! linkage (crank, rod and pivot distance in proportion).

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use loomkin_units::{Field, Range};
use serde::Serialize;

use super::{Assembly, FourBarSley, SleyAnalysis, SleyError, SleyTable};

/// What `loomkin sley synthesize` is asked for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SleyTarget {
    /// The reed's stroke (arc of the beating point), mm.
    pub stroke_mm: f64,
    /// The back dwell wanted, deg of main shaft.
    pub back_dwell_deg: f64,
    /// The dwell tolerance, mm ([`SleyAnalysis::DWELL_TOLERANCE_MM`]).
    pub dwell_tolerance_mm: f64,
    /// Rocking shaft to the reed's beating point, mm.
    pub reed_height_mm: f64,
    /// The sword (rocking shaft to the rod's pin), mm; `None`: [`SleyTarget::SWORD_SHARE`] of the reed height.
    pub sword_mm: Option<f64>,
}

/// A synthesised sley.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SleySynthesis {
    /// The linkage's `[sley]` table (its `mass_kg` and `gyration_mm` are placeholders: the
    /// synthesis is kinematic).
    #[serde(skip)]
    pub table: SleyTable,
    /// Crank radius, mm.
    pub crank_mm: f64,
    /// Rod, mm.
    pub rod_mm: f64,
    /// Sword, mm.
    pub sword_mm: f64,
    /// Rocking shaft's x from the crank centre, mm.
    pub pivot_x_mm: f64,
    /// Rocking shaft's y from the crank centre, mm.
    pub pivot_y_mm: f64,
    /// Rocking shaft to the beating point, mm.
    pub reed_height_mm: f64,
    /// The assembly branch, `left` or `right`.
    pub assembly: Assembly,
    /// The stroke the linkage gives, mm (the target to rounding).
    pub reed_stroke_mm: f64,
    /// The back dwell it gives, deg (the target to rounding).
    pub back_dwell_deg: f64,
    /// The dwell tolerance, mm.
    pub dwell_tolerance_mm: f64,
    /// Its least transmission angle over the cycle, deg: the quantity maximised.
    pub min_transmission_angle_deg: f64,
    /// Main-shaft angle from front to back dead centre, deg (180° for a linkage without quick return).
    pub back_dead_centre_deg: f64,
    /// Linkages evaluated by the search.
    pub evaluations: usize,
}

impl SleyTarget {
    /// `reed_stroke_mm`: 0 < S ≤ 10⁴ mm; the swing S/h must also stay below 120°.
    pub const STROKE_MM: Field = Field::new(
        "reed_stroke_mm",
        Range::open_closed(0.0, 1e4, "mm"),
        "The reed's stroke wanted (arc of the beating point between its dead centres): 0 < S ≤ 10000 mm, and \
         the sword's swing S/reed_height below 120° (a crank-rocker swings less than 180°, and one near it \
         transmits badly).",
    );
    /// `back_dwell_deg`: 0 < D < 360°; what a crank-rocker can give is found by the search.
    pub const BACK_DWELL_DEG: Field = Field::new(
        "back_dwell_deg",
        Range::open(0.0, 360.0, "deg"),
        "The back dwell wanted (main-shaft angle within dwell_tolerance_mm of the back position): 0 < D < 360°; \
         what a crank-rocker can give for the stroke and tolerance is found by the search and a target outside \
         it refused with the range.",
    );
    /// `reed_height_mm`: 0 < h ≤ 10⁴ mm, default 400 mm.
    pub const REED_HEIGHT_MM: Field = Field::new(
        "reed_height_mm",
        Range::open_closed(0.0, 1e4, "mm"),
        "Rocking shaft to the reed's beating point: 0 < h ≤ 10000 mm; 400 mm when left out (an estimate between \
         the short sleys of modern looms, about 250–300 mm, and a shuttle loom's long swords, about 750 mm).",
    )
    .with_default(400.0);
    /// `sword_mm`: 0 < c ≤ 10⁴ mm; left out, [`SleyTarget::SWORD_SHARE`] of the reed height.
    pub const SWORD_MM: Field = Field::new(
        "sword_mm",
        Range::open_closed(0.0, 1e4, "mm"),
        "Rocking shaft to the rod's pin: 0 < c ≤ 10000 mm; 0.7 of reed_height_mm when left out (the pin below \
         the race board). It scales the crank, rod and pivot distance only: the motion's shape does not \
         depend on it.",
    );

    /// The sword as a share of the reed height when `sword_mm` is left out.
    pub const SWORD_SHARE: f64 = 0.7;

    /// Largest swing of the sword, rad (120°).
    const MAX_SWING: f64 = 2.0 * PI / 3.0;

    /// Farthest crank centre from the middle of the sword's pin chord, in swords: a rod of at most
    /// about four swords, a mechanism that fits beside the loom's frame.
    pub const MAX_REACH: f64 = 4.0;

    /// Points of the logarithmic grid along a ray and intervals of the grid over the directions.
    const RAY_POINTS: usize = 48;
    const DIRECTIONS: usize = 144;

    /// Finds the sley: the four-bar meeting the stroke and the back dwell with the largest least
    /// transmission angle. Refuses, naming `back_dwell_deg` with the dwells found, a target no
    /// linkage of the search meets.
    pub fn synthesize(&self) -> Result<SleySynthesis, SleyError> {
        let s = Self::STROKE_MM.check(self.stroke_mm)?;
        let d = Self::BACK_DWELL_DEG.check(self.back_dwell_deg)?;
        let h = Self::REED_HEIGHT_MM.check(self.reed_height_mm)?;
        let c = match self.sword_mm {
            Some(c) => Self::SWORD_MM.check(c)?,
            None => Self::SWORD_SHARE * h,
        };
        let tol = SleyAnalysis::DWELL_TOLERANCE_MM.check(self.dwell_tolerance_mm)?;
        Range::open(0.0, s, "mm").check(SleyAnalysis::DWELL_TOLERANCE_MM.name, tol)?;
        let swing = s / h;
        if swing >= Self::MAX_SWING {
            return Err(SleyError::infeasible(
                "reed_stroke_mm, reed_height_mm",
                format!(
                    "a stroke of {} mm at a reed height of {} mm swings the sword {}°: allowed below 120°",
                    loomkin_units::compact(s),
                    loomkin_units::compact(h),
                    loomkin_units::compact(swing.to_degrees())
                ),
            ));
        }
        let space = Space { c, h, swing, tol_m: tol * 1e-3 };
        let target = d.to_radians();
        let evaluations = std::cell::Cell::new(0usize);
        let (lo_seen, hi_seen) = (std::cell::Cell::new(f64::INFINITY), std::cell::Cell::new(0.0f64));
        let dwell_at = |u: f64, rho: f64| {
            evaluations.set(evaluations.get() + 1);
            let dw = space.linkage(u, rho).map(|(_, dw)| dw);
            if let Some(dw) = dw {
                lo_seen.set(lo_seen.get().min(dw));
                hi_seen.set(hi_seen.get().max(dw));
            }
            dw
        };
        // Every linkage on the ray u whose dwell is the target: (ρ, least transmission angle).
        let on_ray = |u: f64| -> Option<(f64, f64)> {
            let (lo, hi) = (1e-2 * c, Self::MAX_REACH * c);
            let n = Self::RAY_POINTS;
            let rho = |i: usize| lo * (hi / lo).powf(i as f64 / n as f64);
            let mut best: Option<(f64, f64)> = None;
            let mut prev: Option<(f64, f64)> = None;
            for i in 0..=n {
                let r1 = rho(i);
                let g1 = dwell_at(u, r1).map(|dw| dw - target);
                if let (Some((r0, g0)), Some(g1)) = (prev, g1)
                    && (g0 < 0.0) != (g1 < 0.0)
                {
                    // Bisection between two linkages on either side of the target; the side test
                    // treats a linkage that fails to assemble as beyond the far end.
                    let root = loomkin_numeric::bisect(r0, r1, |r| {
                        dwell_at(u, r).is_some_and(|dw| (dw - target < 0.0) == (g0 < 0.0))
                    });
                    if let Some((sley, dw)) = space.linkage(u, root)
                        && (dw - target).abs() <= 1e-9 * target
                    {
                        let mu = sley.min_transmission_rad();
                        if best.is_none_or(|(_, m)| mu > m) {
                            best = Some((root, mu));
                        }
                    }
                }
                prev = g1.map(|g| (r1, g));
            }
            best
        };
        let m = loomkin_numeric::scan_max(0.0, TAU, Self::DIRECTIONS, |u| on_ray(u).map_or(f64::NEG_INFINITY, |b| b.1));
        let found = if m.value.is_finite() { on_ray(m.at).map(|(rho, _)| (m.at, rho)) } else { None };
        let Some((u, rho)) = found else {
            let seen = if hi_seen.get() > 0.0 {
                format!(
                    "the search's linkages give {}° … {}°",
                    loomkin_units::compact(lo_seen.get().to_degrees()),
                    loomkin_units::compact(hi_seen.get().to_degrees())
                )
            } else {
                "no linkage of the search assembles".into()
            };
            return Err(SleyError::infeasible(
                "back_dwell_deg",
                format!(
                    "no crank-rocker gives a back dwell of {}° within {} mm at a stroke of {} mm: {seen}",
                    loomkin_units::compact(d),
                    loomkin_units::compact(tol),
                    loomkin_units::compact(s)
                ),
            ));
        };
        let (sley, dwell) = space.linkage(u, rho).ok_or_else(|| {
            SleyError::infeasible("back_dwell_deg", "the search's best linkage does not assemble".into())
        })?;
        let t = *sley.table();
        Ok(SleySynthesis {
            table: t,
            crank_mm: t.crank_mm,
            rod_mm: t.rod_mm,
            sword_mm: t.sword_mm,
            pivot_x_mm: t.pivot_x_mm,
            pivot_y_mm: t.pivot_y_mm,
            reed_height_mm: t.reed_height_mm,
            assembly: t.assembly,
            reed_stroke_mm: sley.stroke_m() * 1e3,
            back_dwell_deg: dwell.to_degrees(),
            dwell_tolerance_mm: tol,
            min_transmission_angle_deg: sley.min_transmission_rad().to_degrees(),
            back_dead_centre_deg: sley.back_dead_centre_rad().to_degrees(),
            evaluations: evaluations.get(),
        })
    }
}

/// The synthesis frame: sword `c`, reed height `h`, swing, dwell tolerance (m); lengths in mm.
struct Space {
    c: f64,
    h: f64,
    swing: f64,
    tol_m: f64,
}

impl Space {
    /// The linkage with its crank centre at `M + ρ·e(u)` and its back dwell (rad), if it is a
    /// crank-rocker whose dead centres are the constructed ones.
    fn linkage(&self, u: f64, rho: f64) -> Option<(FourBarSley, f64)> {
        let c = self.c;
        let half = 0.5 * self.swing;
        let front = [c * (FRAC_PI_2 - half).cos(), c * (FRAC_PI_2 - half).sin()];
        let back = [c * (FRAC_PI_2 + half).cos(), c * (FRAC_PI_2 + half).sin()];
        let mid = [0.5 * (front[0] + back[0]), 0.5 * (front[1] + back[1])];
        let o = [mid[0] + rho * u.cos(), mid[1] + rho * u.sin()];
        let dist = |p: [f64; 2]| (p[0] - o[0]).hypot(p[1] - o[1]);
        let (lf, lb) = (dist(front), dist(back));
        let (b, r) = (0.5 * (lf + lb), 0.5 * (lf - lb).abs());
        // The crank pin at each dead centre: toward B when extended (the longer), away when folded.
        let pin = |p: [f64; 2], l: f64, extended: bool| {
            let k = if extended { r / l } else { -r / l };
            [o[0] + k * (p[0] - o[0]), o[1] + k * (p[1] - o[1])]
        };
        let side = |p: [f64; 2], a: [f64; 2]| a[0] * p[1] - a[1] * p[0];
        let sf = side(front, pin(front, lf, lf > lb));
        let sb = side(back, pin(back, lb, lb >= lf));
        if sf * sb <= 0.0 {
            return None;
        }
        let table = SleyTable {
            crank_mm: r,
            rod_mm: b,
            sword_mm: c,
            pivot_x_mm: -o[0],
            pivot_y_mm: -o[1],
            reed_height_mm: self.h,
            mass_kg: 1.0,
            gyration_mm: c,
            centre_mm: None,
            beat_up_deg: 0.0,
            beat_up_force_n: 0.0,
            beat_up_range_deg: 0.0,
            assembly: if sf > 0.0 { Assembly::Left } else { Assembly::Right },
        };
        let sley = FourBarSley::new(table).ok()?;
        // The dead centres found by the linkage are the constructed ones (the front toward the fell).
        let stroke = self.swing * self.h * 1e-3;
        if (sley.stroke_m() - stroke).abs() > 1e-9 * stroke {
            return None;
        }
        let (a, e) = sley.back_dwell_rad(self.tol_m).ok()?;
        Some((sley, e - a))
    }
}
