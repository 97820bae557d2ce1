//! Time-true cams: laws corrected for the main shaft's real speed.
//!
//! A cam on the main shaft moves its follower by `y = c(φ)`. A law `s` designed for a constant
//! speed `ω̄` prescribes the follower's motion in time, `y(t) = s(ω̄·t)`. The shaft turns at `ω(φ)`
//! (the speed ripple's periodic solution), so it reaches angle `φ` at time
//!
//! $$ t(\varphi) = \int_0^\varphi \frac{d\phi}{\omega(\phi)}, $$
//!
//! and the cam that moves the follower in time as designed is `c(φ) = s(ψ(φ))` with the
//! **time-true angle** `ψ(φ) = a + ω̄·(t(φ) − t(a))`: the angle the shaft would have turned at the
//! constant mean speed `ω̄` = repeat/repeat's time in the time it really takes (the idea of
//! EP1061284). `a` is the anchor, an angle the correction keeps (`ψ(a) = a`); over a whole repeat
//! `ψ` gains exactly the repeat, so it maps the repeat onto itself. A move designed over
//! `[a − Φ/2, a + Φ/2]` in `ψ` occupies `[ψ⁻¹(a − Φ/2), ψ⁻¹(a + Φ/2)]` in the shaft's angle — not
//! `Φ` long — and its law there is `s((ψ(φ) − a + Φ/2)/Φ)`; rates by the chain rule,
//! `dψ/dφ = ω̄/ω`, `d²ψ/dφ² = −ω̄·ω′/ω²`.
//!
//! [`TimeMap`] is `t(φ)` from a [`crate::Solution`]; [`correct_move`] writes a corrected move as a
//! polynomial-acceleration law of the law core (quintic Hermite panels: the law's value, slope and
//! acceleration met at every panel end, so a cycle file carries it); [`time_excitation`] turns a
//! follower's input given against the shaft's angle into the time pieces of the elastic model
//! (loomkin-dynamics), for its residual vibration at the real speed.

use crate::RippleError;
use loomkin_dynamics::{Excitation, NCOEF, TimePiece};
use loomkin_laws::{Law, LawSpec, PolySegment};

/// The time the shaft takes to reach each angle, `t(φ)`, over its repeat (and periodically beyond).
///
/// At the grid points of the periodic solution it holds `t`, `dt/dφ = 1/ω` and
/// `d²t/dφ² = −ω′/ω²`; between them the quintic Hermite interpolant of the three (sixth order, C²).
#[derive(Debug, Clone)]
pub struct TimeMap {
    phi: Vec<f64>,
    t: Vec<f64>,
    dt: Vec<f64>,
    d2t: Vec<f64>,
}

/// A quintic's coefficients in `u ∈ [0, 1]` from value, slope and second derivative (all in `u`)
/// at both ends.
fn quintic(p0: f64, d0: f64, a0: f64, p1: f64, d1: f64, a1: f64) -> [f64; 6] {
    let big_a = p1 - p0 - d0 - 0.5 * a0;
    let big_b = d1 - d0 - a0;
    let big_c = a1 - a0;
    [
        p0,
        d0,
        0.5 * a0,
        10.0 * big_a - 4.0 * big_b + 0.5 * big_c,
        -15.0 * big_a + 7.0 * big_b - big_c,
        6.0 * big_a - 3.0 * big_b + 0.5 * big_c,
    ]
}

/// Value and first two derivatives (in `u`) of a quintic at `u`.
fn quintic_eval(c: &[f64; 6], u: f64) -> [f64; 3] {
    let p = c[0] + u * (c[1] + u * (c[2] + u * (c[3] + u * (c[4] + u * c[5]))));
    let d = c[1] + u * (2.0 * c[2] + u * (3.0 * c[3] + u * (4.0 * c[4] + u * 5.0 * c[5])));
    let a = 2.0 * c[2] + u * (6.0 * c[3] + u * (12.0 * c[4] + u * 20.0 * c[5]));
    [p, d, a]
}

impl TimeMap {
    /// The map through grid points `phi` (0 to the period, rad) with the shaft's speed `omega`
    /// (rad/s) and its rate `d_omega` (rad/s per rad) there, and the times `t` (s, from 0).
    pub fn new(phi: Vec<f64>, t: Vec<f64>, omega: Vec<f64>, d_omega: Vec<f64>) -> Self {
        let dt = omega.iter().map(|w| 1.0 / w).collect();
        let d2t = omega.iter().zip(&d_omega).map(|(w, dw)| -dw / (w * w)).collect();
        Self { phi, t, dt, d2t }
    }

    /// The repeat, rad.
    pub fn period_rad(&self) -> f64 {
        self.phi[self.phi.len() - 1]
    }

    /// The repeat's time, s.
    pub fn period_s(&self) -> f64 {
        self.t[self.t.len() - 1]
    }

    /// The mean speed `ω̄`, rad/s: the repeat over its time.
    pub fn mean_speed_rad_s(&self) -> f64 {
        self.period_rad() / self.period_s()
    }

    fn coefficients(&self, k: usize) -> ([f64; 6], f64) {
        let h = self.phi[k + 1] - self.phi[k];
        let c = quintic(
            self.t[k],
            h * self.dt[k],
            h * h * self.d2t[k],
            self.t[k + 1],
            h * self.dt[k + 1],
            h * h * self.d2t[k + 1],
        );
        (c, h)
    }

    /// `t(φ)`, `dt/dφ` and `d²t/dφ²` at any angle (s, s/rad, s/rad²), periodic beyond the repeat.
    pub fn time(&self, phi_rad: f64) -> [f64; 3] {
        let p = self.period_rad();
        let q = (phi_rad / p).floor();
        let r = phi_rad - q * p;
        let n = self.phi.len() - 1;
        let k = self.phi.partition_point(|x| *x <= r).clamp(1, n) - 1;
        let (c, h) = self.coefficients(k);
        let [t, d, a] = quintic_eval(&c, ((r - self.phi[k]) / h).clamp(0.0, 1.0));
        [q * self.period_s() + t, d / h, a / (h * h)]
    }

    /// The shaft's angle at time `t_s` (the inverse of [`TimeMap::time`]), rad.
    pub fn angle(&self, t_s: f64) -> f64 {
        let tp = self.period_s();
        let q = (t_s / tp).floor();
        let r = t_s - q * tp;
        let n = self.t.len() - 1;
        let k = self.t.partition_point(|x| *x <= r).clamp(1, n) - 1;
        let (c, h) = self.coefficients(k);
        // Newton on the monotone quintic from the chord's guess, kept inside the interval.
        let span = self.t[k + 1] - self.t[k];
        let mut u = if span > 0.0 { ((r - self.t[k]) / span).clamp(0.0, 1.0) } else { 0.0 };
        for _ in 0..8 {
            let [v, d, _] = quintic_eval(&c, u);
            if d <= 0.0 {
                break;
            }
            let step = (v - r) / d;
            u = (u - step).clamp(0.0, 1.0);
            if step.abs() <= 1e-16 {
                break;
            }
        }
        q * self.period_rad() + self.phi[k] + u * h
    }

    /// The speed `ω` and its rate `dω/dφ` at any angle (rad/s, rad/s per rad), from the map.
    pub fn speed(&self, phi_rad: f64) -> (f64, f64) {
        let [_, d, a] = self.time(phi_rad);
        (1.0 / d, -a / (d * d))
    }

    /// The time-true angle `ψ(φ) = a + ω̄·(t(φ) − t(a))` with its first two derivatives in `φ`,
    /// for anchor `a` (rad).
    pub fn time_true(&self, phi_rad: f64, anchor_rad: f64) -> [f64; 3] {
        let w = self.mean_speed_rad_s();
        let [t, d, a] = self.time(phi_rad);
        [anchor_rad + w * (t - self.time(anchor_rad)[0]), w * d, w * a]
    }

    /// The shaft's angle whose time-true angle (anchor `a`) is `psi_rad`.
    pub fn time_true_inverse(&self, psi_rad: f64, anchor_rad: f64) -> f64 {
        let t = self.time(anchor_rad)[0] + (psi_rad - anchor_rad) / self.mean_speed_rad_s();
        self.angle(t)
    }
}

/// A move corrected to run in time: where it starts and how long it lasts in the shaft's angle,
/// and its law (normalised, `x ∈ [0, 1]` over that length).
#[derive(Debug, Clone)]
pub struct CorrectedMove {
    /// Start, rad of the shaft (may lie outside the repeat, as the design's start may).
    pub start_rad: f64,
    /// Length, rad of the shaft.
    pub length_rad: f64,
    /// The law as the law core's polynomial-acceleration segments (what a cycle file holds).
    pub spec: LawSpec,
    /// The law built from them.
    pub law: Law,
}

/// The most a panel of a corrected law spans, rad of the shaft (1°): quintic Hermite panels of
/// this width carry a corrected law to ~1e-11 of its stroke (measured 5e-12 for a 90° modified
/// trapezoid, 1e-14 for a 280° one; crates/drive/tests/timetrue.rs).
pub const PANEL_RAD: f64 = std::f64::consts::PI / 180.0;

/// The design law `law` of a move over `[start, start + motion]` (rad), corrected for the shaft of
/// `map` with anchor `anchor` (rad; the move's middle keeps its angle when the anchor is there):
/// panels at the law's joints and at most [`PANEL_RAD`] apart, on each the quintic that meets the
/// corrected law's value, slope and acceleration at both ends.
pub fn correct_move(
    map: &TimeMap,
    law: &Law,
    start_rad: f64,
    motion_rad: f64,
    anchor_rad: f64,
) -> Result<CorrectedMove, RippleError> {
    let begin = map.time_true_inverse(start_rad, anchor_rad);
    let end = map.time_true_inverse(start_rad + motion_rad, anchor_rad);
    let length = end - begin;
    if !(length.is_finite() && length > 0.0) {
        return Err(RippleError::field("motion_deg", "the corrected move has no length"));
    }
    // Knots in the shaft's angle: the ends, the law's joints mapped, and subdivisions.
    let mut joints: Vec<f64> = vec![begin];
    for u in law.joints() {
        joints.push(map.time_true_inverse(start_rad + u * motion_rad, anchor_rad));
    }
    joints.push(end);
    let mut knots: Vec<f64> = Vec::new();
    for w in joints.windows(2) {
        let n = ((w[1] - w[0]) / PANEL_RAD).ceil().max(1.0) as usize;
        knots.extend((0..n).map(|j| w[0] + (w[1] - w[0]) * j as f64 / n as f64));
    }
    knots.push(end);
    // Value, slope and acceleration in x (x = (φ − begin)/length) at a knot, the law's acceleration
    // taken on the side `side` (−1 left, +1 right) of a joint.
    let at = |phi: f64, side: f64| -> [f64; 3] {
        let [psi, d1, d2] = map.time_true(phi, anchor_rad);
        let u = if phi == begin {
            0.0
        } else if phi == end {
            1.0
        } else {
            ((psi - start_rad) / motion_rad).clamp(0.0, 1.0)
        };
        let k = law.eval(u);
        let a = law.eval((u + side * 1e-13).clamp(0.0, 1.0)).a;
        let g = d1 * length / motion_rad;
        [k.s, k.v * g, a * g * g + k.v * d2 * length * length / motion_rad]
    };
    let xs: Vec<f64> = knots.iter().map(|p| if *p == end { 1.0 } else { (p - begin) / length }).collect();
    let mut segments = Vec::with_capacity(knots.len() - 1);
    for k in 0..knots.len() - 1 {
        let w = xs[k + 1] - xs[k];
        let l = at(knots[k], 1.0);
        let r = at(knots[k + 1], -1.0);
        let c = quintic(l[0], w * l[1], w * w * l[2], r[0], w * r[1], w * w * r[2]);
        // The acceleration in x as a cubic in the panel's u: S''(u)/w².
        let w2 = w * w;
        let accel = vec![l[2], 6.0 * c[3] / w2, 12.0 * c[4] / w2, 20.0 * c[5] / w2];
        segments.push(PolySegment { length: w, accel });
    }
    let spec = LawSpec::Polynomial { segments };
    let law = spec.build().map_err(|e| RippleError::field("law", e.to_string()))?;
    Ok(CorrectedMove { start_rad: begin, length_rad: length, spec, law })
}

/// A stretch of a follower's input over the repeat: moving or standing, between two shaft angles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Span {
    /// Start, rad of the shaft.
    pub start_rad: f64,
    /// End, rad.
    pub end_rad: f64,
    /// Whether the follower moves over it.
    pub moving: bool,
}

/// A follower's input over one repeat in time, at the speed of `map`: `spans` cover the repeat in
/// order from `spans[0].start_rad`; `input(span, φ)` gives `y`, `dy/dφ`, `d²y/dφ²` (SI) against the
/// shaft's angle. On a moving span, pieces at most [`PANEL_RAD`] of the shaft long, each the
/// quintic in time meeting `y`, `ẏ = y′ω`, `ÿ = y″ω² + y′ω·dω/dφ` at its ends; a standing span is
/// one dwell piece. `stroke_si` is the reference of "% of stroke".
pub fn time_excitation(
    map: &TimeMap,
    spans: &[Span],
    input: impl Fn(usize, f64) -> [f64; 3],
    stroke_si: f64,
) -> Excitation {
    let t_start = map.time(spans[0].start_rad)[0];
    let in_time = |s: usize, phi: f64| -> (f64, [f64; 3]) {
        let [y, d1, d2] = input(s, phi);
        let (w, dw) = map.speed(phi);
        (map.time(phi)[0] - t_start, [y, d1 * w, d2 * w * w + d1 * w * dw])
    };
    let mut pieces = Vec::new();
    for (s, span) in spans.iter().enumerate() {
        if !span.moving {
            let (t0, y) = in_time(s, span.start_rad);
            let t1 = map.time(span.end_rad)[0] - t_start;
            let mut poly = [0.0; NCOEF];
            poly[0] = y[0];
            pieces.push(TimePiece { t0, duration: t1 - t0, poly, accel_sine: None, dwell: true, segment: s });
            continue;
        }
        let n = ((span.end_rad - span.start_rad) / PANEL_RAD).ceil().max(1.0) as usize;
        let phis: Vec<f64> = (0..=n)
            .map(|j| {
                if j == n {
                    span.end_rad
                } else {
                    span.start_rad + (span.end_rad - span.start_rad) * j as f64 / n as f64
                }
            })
            .collect();
        let vals: Vec<(f64, [f64; 3])> = phis.iter().map(|p| in_time(s, *p)).collect();
        for j in 0..n {
            let (t0, l) = vals[j];
            let (t1, r) = vals[j + 1];
            let d = t1 - t0;
            let c = quintic(l[0], d * l[1], d * d * l[2], r[0], d * r[1], d * d * r[2]);
            let mut poly = [0.0; NCOEF];
            let mut scale = 1.0;
            for (k, ck) in c.iter().enumerate() {
                poly[k] = ck * scale;
                scale /= d;
            }
            pieces.push(TimePiece { t0, duration: d, poly, accel_sine: None, dwell: false, segment: s });
        }
    }
    Excitation {
        pieces,
        period_s: map.period_s(),
        start_deg: spans[0].start_rad.to_degrees(),
        period_deg: map.period_rad().to_degrees(),
        stroke_si,
        speed_rpm: loomkin_units::rpm_from_rad_per_s(map.mean_speed_rad_s()),
    }
}
