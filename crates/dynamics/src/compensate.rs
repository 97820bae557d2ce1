//! Compensation (polydyne): the input law `s` that makes the follower follow the designed law `x` exactly.
//!
//! From the model `m x'' + c(x' − s') + k(x − s) = −k_r x − F₀`, divided by `m`:
//!
//! $$ κ\,s + 2ζω_n\,s' = x'' + 2ζω_n x' + ω_n^2 x + f_0, \qquad κ = k/m = ω_n^2 − k_r/m. $$
//!
//! * Undamped (ζ = 0) this is the classic polydyne `s = (x'' + ω_n² x + f₀)/κ` (`s = x + x''/ω_n²` without
//!   loads): the input has the continuity of `x''` — it **jumps** where `x''` jumps, so such a design is
//!   refused.
//! * Damped, it is the first-order equation `s' + a·s = g(t)`, `a = κ/(2ζω_n)`, solved exactly per piece
//!   (polynomial particular solution by `a·s_k = g_k − (k+1)·s_{k+1}`, the sinusoid by `1/(a + iΩ)`,
//!   plus `C·e^{−at}`), **periodic**: the cam must close, so `s(T_cycle) = s(0)`, which fixes the one free
//!   constant, `s₀ = b/(1 − e^{−aT})` with `b` the end value from `s₀ = 0`. The input is one order
//!   smoother than `x''`; it never jumps for a cycle whose `x` and `x'` are continuous.

use crate::excitation::{Excitation, TimePiece};
use crate::follower::Follower;
use crate::oscillator::{NCOEF, poly_derivs};
use crate::{DynError, Result};
use loomkin_units::Field;
use serde::Serialize;

/// The compensated input on one piece: `s(t) = Σ p_k t^k + Im(q·e^{iΩt}) + C·e^{−a t}`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct InputPiece {
    /// Start time from the cycle's start (s).
    pub t0: f64,
    /// Duration (s).
    pub duration: f64,
    /// Polynomial coefficients (SI, t in s).
    pub poly: [f64; NCOEF],
    /// The sinusoid `b_s·sin(Ωt) + b_c·cos(Ωt)` as `(b_s, b_c, Ω)`.
    pub sine: Option<(f64, f64, f64)>,
    /// The exponential `C·e^{−at}` as `(C, a)` (damped only).
    pub exp: Option<(f64, f64)>,
}

impl InputPiece {
    /// `s, s', s''` at local time `t`.
    pub fn derivs(&self, t: f64) -> [f64; 3] {
        let mut out = poly_derivs::<3>(&self.poly, t);
        if let Some((bs, bc, w)) = self.sine {
            let (sn, cs) = (w * t).sin_cos();
            out[0] += bs * sn + bc * cs;
            out[1] += w * (bs * cs - bc * sn);
            out[2] -= w * w * (bs * sn + bc * cs);
        }
        if let Some((c, a)) = self.exp {
            let e = c * (-a * t).exp();
            out[0] += e;
            out[1] -= a * e;
            out[2] += a * a * e;
        }
        out
    }
}

/// The compensated input over one cycle, and the continuity it has.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Compensation {
    /// The pieces, in time order (those of the designed cycle).
    pub pieces: Vec<InputPiece>,
    /// Continuity class of the designed motion `x` over the cycle (highest continuous derivative, ≤ 4).
    pub designed_class: usize,
    /// Continuity class of the input `s`: `designed − 2` undamped, `designed − 1` damped.
    pub input_class: usize,
    /// Cycle time (s).
    pub period_s: f64,
}

impl Compensation {
    /// `points`: samples per cycle of the compensated input's table, as [`crate::Response::POINTS`].
    pub const POINTS: Field = crate::Response::POINTS;

    /// `s, s', s''` at time `t` of the cycle.
    pub fn eval(&self, t: f64) -> [f64; 3] {
        let t = t.clamp(0.0, self.period_s);
        let i = self.pieces.partition_point(|p| p.t0 <= t).saturating_sub(1);
        let p = &self.pieces[i];
        p.derivs((t - p.t0).clamp(0.0, p.duration))
    }

    /// `n ≥ 2` samples over the cycle `exc` this input compensates, both ends included, each
    /// `[angle (deg), designed x, input s, s', s'']` in SI units (`loomkin dyn compensate`'s CSV
    /// before its unit scaling).
    pub fn samples(&self, exc: &Excitation, n: usize) -> Vec<[f64; 5]> {
        let n = n.max(2);
        (0..n)
            .map(|i| {
                let time = exc.period_s * i as f64 / (n - 1) as f64;
                let k = exc.piece_at(time.min(exc.period_s * (1.0 - 1e-15)));
                let piece = &exc.pieces[k];
                let x = piece.derivs((time - piece.t0).clamp(0.0, piece.duration))[0];
                let s = self.eval(time);
                [exc.angle_deg(time), x, s[0], s[1], s[2]]
            })
            .collect()
    }
}

/// The compensated input for the designed cycle `exc` and the follower's model.
///
/// Refuses (with the joint's angle, the jump and the catalogue laws smooth enough to remove it) when
/// the input would jump: undamped and `x''` discontinuous, or (damped) `x` or `x'` discontinuous, as
/// [`Excitation::first_jump`] judges it (relative to each law's own peak).
pub fn compensate(exc: &Excitation, follower: &Follower) -> Result<Compensation> {
    let ch = follower.channel();
    let osc = ch.osc;
    let (w, z) = (osc.omega_n(), osc.zeta());
    let kappa = w * w + ch.g_s; // g_s = −k_r/m
    let f0 = -ch.g_0;
    let jump = exc.first_jump();
    let designed_class = jump.map_or(4, |(k, _, _)| k.saturating_sub(1));
    let need = if z == 0.0 { 2 } else { 1 };
    if let Some((order, t, dj)) = jump
        && order <= need
    {
        let names = ["x", "x'", "x''"];
        let what = ["a continuous position", "a continuous velocity", "a continuous acceleration"];
        let laws: Vec<&str> = loomkin_laws::laws_of_class(need as i32).iter().map(|l| l.name()).collect();
        return Err(DynError::NoCompensation {
            field: "cycle".into(),
            reason: format!(
                "the designed {} jumps by {} at {:.4}° of the cycle, so the input would jump there ({}); give the \
                 designed motion {}, with laws of class C{need} or higher ({}){}",
                names[order],
                loomkin_units::compact(dj),
                exc.angle_deg(t),
                if z == 0.0 { "undamped polydyne s = (x'' + ω²x + f₀)/κ" } else { "first-order input equation" },
                what[need],
                laws.join(", "),
                if z == 0.0 { ", or damping_ratio > 0" } else { "" },
            ),
        });
    }
    let input_class = designed_class.saturating_sub(if z == 0.0 { 2 } else { 1 });
    // g(t) = (x'' + 2ζω x' + ω² x + f₀) per piece, as polynomial + (sin, cos) of Ωt.
    let rhs = |p: &TimePiece| {
        let mut g = [0.0; NCOEF];
        for k in 0..NCOEF {
            let acc = if k + 2 < NCOEF { ((k + 2) * (k + 1)) as f64 * p.poly[k + 2] } else { 0.0 };
            let vel = if k + 1 < NCOEF { (k + 1) as f64 * p.poly[k + 1] } else { 0.0 };
            g[k] = acc + 2.0 * z * w * vel + w * w * p.poly[k];
        }
        g[0] += f0;
        // x_sine = −(A/Ω²)·sin(Ωt + φ): x'' = A sin, x' = −(A/Ω) cos.
        let sine = p.accel_sine.map(|h| {
            let (sp, cp) = h.phase.sin_cos();
            let sin_part = h.amp - w * w * h.amp / (h.omega * h.omega); // coefficient of sin(Ωt+φ)
            let cos_part = -2.0 * z * w * h.amp / h.omega; // coefficient of cos(Ωt+φ)
            // a·sin(θ+φ) + b·cos(θ+φ) = (a cos φ − b sin φ) sin θ + (a sin φ + b cos φ) cos θ
            (sin_part * cp - cos_part * sp, sin_part * sp + cos_part * cp, h.omega)
        });
        (g, sine)
    };
    let mut pieces: Vec<InputPiece> = Vec::with_capacity(exc.pieces.len());
    if z == 0.0 {
        for p in &exc.pieces {
            let (g, sine) = rhs(p);
            pieces.push(InputPiece {
                t0: p.t0,
                duration: p.duration,
                poly: g.map(|c| c / kappa),
                sine: sine.map(|(s, c, om)| (s / kappa, c / kappa, om)),
                exp: None,
            });
        }
    } else {
        let c2 = 2.0 * z * w;
        let a = kappa / c2;
        // Particular solutions (C to be fixed by continuity).
        for p in &exc.pieces {
            let (g, sine) = rhs(p);
            let g = g.map(|c| c / c2);
            let mut s = [0.0; NCOEF];
            for k in (0..NCOEF).rev() {
                let next = if k + 1 < NCOEF { (k + 1) as f64 * s[k + 1] } else { 0.0 };
                s[k] = (g[k] - next) / a;
            }
            // Im-free form: s_p = u sin Ωt + v cos Ωt with Ω(u cos − v sin) + a(u sin + v cos) = gs sin + gc cos.
            let sine = sine.map(|(gs, gc, om)| {
                let (gs, gc) = (gs / c2, gc / c2);
                let det = a * a + om * om;
                ((a * gs + om * gc) / det, (a * gc - om * gs) / det, om)
            });
            pieces.push(InputPiece { t0: p.t0, duration: p.duration, poly: s, sine, exp: Some((0.0, a)) });
        }
        // Propagate from s(0) = s0: C_i = s_start − particular(0). Linear in s0: do s0 = 0, then fix.
        let run = |pieces: &mut [InputPiece], s0: f64| {
            let mut s = s0;
            for p in pieces.iter_mut() {
                p.exp = Some((0.0, a));
                let part = p.derivs(0.0)[0];
                p.exp = Some((s - part, a));
                s = p.derivs(p.duration)[0];
            }
            s
        };
        let b = run(&mut pieces, 0.0);
        let decay = (-a * exc.period_s).exp();
        let s0 = b / (1.0 - decay);
        run(&mut pieces, s0);
    }
    let finite = |p: &InputPiece| {
        p.poly.iter().all(|c| c.is_finite())
            && p.sine.is_none_or(|(a, b, c)| a.is_finite() && b.is_finite() && c.is_finite())
            && p.exp.is_none_or(|(a, b)| a.is_finite() && b.is_finite())
    };
    if !pieces.iter().all(finite) {
        // ω² and 1/κ over- or underflow for a follower inside its range but extreme (5e-324 Hz).
        return Err(DynError::Input {
            field: "natural_hz".into(),
            reason: format!(
                "natural_hz = {} gives a compensated input that is not finite (an overflow): the follower is too \
                 extreme for this model",
                loomkin_units::compact(follower.natural_hz())
            ),
        });
    }
    Ok(Compensation { pieces, designed_class, input_class, period_s: exc.period_s })
}

/// The compensated input as an excitation (undamped only: polynomial + sinusoid pieces), to be simulated.
pub fn input_excitation(exc: &Excitation, comp: &Compensation) -> Option<Excitation> {
    let mut out = exc.clone();
    for (p, c) in out.pieces.iter_mut().zip(&comp.pieces) {
        if c.exp.is_some() {
            return None;
        }
        p.poly = c.poly;
        p.accel_sine = c.sine.map(|(bs, bc, om)| {
            // s_sine = bs sin + bc cos = R sin(Ωt + φ) = −(A/Ω²) sin(Ωt + φ) with A = −R Ω².
            let r = bs.hypot(bc);
            crate::oscillator::Harmonic { amp: -r * om * om, omega: om, phase: bc.atan2(bs) }
        });
    }
    Some(out)
}
