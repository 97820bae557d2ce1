//! The exact response over one or more cycles, from rest or in the periodic steady state.

use crate::excitation::Excitation;
use crate::follower::channel_forcing;
use crate::oscillator::{Forcing, Oscillator, PieceSolution};
use crate::{DynError, Result};
use loomkin_units::compact;

/// One oscillator coordinate driven by the excitation: `y'' + 2ζω y' + ω² y = g_a·s'' + g_s·s + g_0`.
///
/// The single-mass follower is `(g_a, g_s, g_0) = (−1, −k_r/m, −F₀/m)`; each mode of the two-mass model
/// is `(−Γᵢ, 0, 0)` with its participation factor Γᵢ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Channel {
    /// The oscillator.
    pub osc: Oscillator,
    /// Gain on the input acceleration s''.
    pub g_a: f64,
    /// Gain on the input position s (1/s²).
    pub g_s: f64,
    /// Constant term (SI/s²).
    pub g_0: f64,
}

impl Channel {
    /// The forcing on one piece of the excitation.
    pub fn forcing(&self, exc: &Excitation, piece: usize) -> Forcing {
        channel_forcing(&exc.pieces[piece], self.g_a, self.g_s, self.g_0)
    }

    /// The coordinate at rest with the input standing at `s`: `(g_s·s + g_0)/ω²`.
    pub fn rest(&self, s: f64) -> f64 {
        (self.g_s * s + self.g_0) / (self.osc.omega_n() * self.osc.omega_n())
    }
}

/// Where the motion starts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Start {
    /// At rest at the start of the cycle: `x' = s'`, and `x = s` up to the static deflection of the loads.
    Rest,
    /// The periodic steady state: the initial state that repeats after one cycle.
    Steady,
    /// A given initial `(y, y')`.
    State(f64, f64),
}

/// One solved piece.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Solved {
    /// Index of the excitation piece.
    pub piece: usize,
    /// Cycle number (0-based).
    pub cycle: usize,
    /// Start time from the start of the computation (s).
    pub t0: f64,
    /// The exact solution on the piece.
    pub sol: PieceSolution,
}

/// Propagates `(y, y')` over one cycle from `y0` to the start of the next cycle, pushing every solved
/// piece to `out` if given.
fn one_cycle(
    exc: &Excitation,
    ch: &Channel,
    forcings: &[Forcing],
    cycle: usize,
    mut y: (f64, f64),
    mut out: Option<&mut Vec<Solved>>,
) -> (f64, f64) {
    for (i, (p, f)) in exc.pieces.iter().zip(forcings).enumerate() {
        let sol = ch.osc.solve(f, p.duration, y.0, y.1);
        y = sol.end();
        // x and x' are continuous; the error y = x − s takes any jump of s or s' at the joint (none for
        // a law's cycle; a compensated input may have a jump in s').
        let (ds, dv) = exc.joint_jump(i);
        y = (y.0 + ds, y.1 + dv);
        if let Some(o) = out.as_deref_mut() {
            o.push(Solved { piece: i, cycle, t0: cycle as f64 * exc.period_s + p.t0, sol });
        }
    }
    y
}

/// The initial state of the periodic steady state: `(I − Φ)·y₀ = b`, with `Φ` the one-cycle free
/// transition matrix (closed form) and `b` the state after one cycle from zero.
///
/// Fails when `det(I − Φ) = |1 − e^{λT}|²` vanishes: undamped with `f_n·T` an integer.
pub fn steady_state(exc: &Excitation, ch: &Channel, forcings: &[Forcing]) -> Result<(f64, f64)> {
    let t = exc.period_s;
    let (p00, p10) = ch.osc.free(1.0, 0.0, t);
    let (p01, p11) = ch.osc.free(0.0, 1.0, t);
    let b = one_cycle(exc, ch, forcings, 0, (0.0, 0.0), None);
    let (m00, m01, m10, m11) = (1.0 - p00, -p01, -p10, 1.0 - p11);
    let det = m00 * m11 - m01 * m10;
    if det.is_nan() || det.abs() <= 1e-12 {
        let ratio = ch.osc.omega_d() / std::f64::consts::TAU * t;
        return Err(DynError::NoSteadyState { speed_rpm: compact(exc.speed_rpm), ratio: compact(ratio) });
    }
    Ok(((m11 * b.0 - m01 * b.1) / det, (m00 * b.1 - m10 * b.0) / det))
}

/// The exact response of a channel over `cycles` cycles.
pub fn trajectory(exc: &Excitation, ch: &Channel, start: Start, cycles: usize) -> Result<Vec<Solved>> {
    let forcings: Vec<Forcing> = (0..exc.pieces.len()).map(|i| ch.forcing(exc, i)).collect();
    let y0 = match start {
        Start::Rest => {
            let s0 = exc.pieces.first().map_or(0.0, |p| p.derivs(0.0)[0]);
            (ch.rest(s0), 0.0)
        }
        Start::Steady => steady_state(exc, ch, &forcings)?,
        Start::State(y, v) => (y, v),
    };
    let mut out = Vec::with_capacity(cycles * exc.pieces.len());
    let mut y = y0;
    for c in 0..cycles.max(1) {
        y = one_cycle(exc, ch, &forcings, c, y, Some(&mut out));
    }
    Ok(out)
}
