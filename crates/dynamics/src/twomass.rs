//! The two-mass variant: a drive train (stiffness k₁ from the input to mass m₁ — the dobby or cam-box
//! output) and a frame (stiffness k₂ from m₁ to the frame's mass m₂).
//!
//! With the errors `yᵢ = xᵢ − s`, `M·y'' + C·y' + K·y = −M·1·s''`, `M = diag(m₁, m₂)`,
//! `K = [[k₁ + k₂, −k₂], [−k₂, k₂]]`. Method: **modal decomposition**. The eigenvalues `λ = ω²` of
//! `K·φ = λ·M·φ` are the roots of `m₁m₂λ² − (m₁k₂ + m₂(k₁ + k₂))λ + k₁k₂ = 0`, the mode shapes
//! `φ = (1, k₂/(k₂ − λm₂))`; with modal damping (one ratio ζ for both modes, `C = MΦ·diag(2ζωᵢ/μᵢ)·ΦᵀM`)
//! each modal coordinate obeys `ηᵢ'' + 2ζωᵢηᵢ' + ωᵢ²ηᵢ = −Γᵢ·s''`, `Γᵢ = φᵢᵀM1/μᵢ`, `μᵢ = φᵢᵀMφᵢ`, and is
//! solved exactly by the single-mass machinery ([`Channel`]); `y = Σ φᵢηᵢ`. The periodic steady state
//! is each mode's (the 4×4 one-cycle map is block-diagonal in modal coordinates).

use crate::excitation::Excitation;
use crate::peaks::{Extremes, grid_size};
use crate::report::{TwoMassReport, Units};
use crate::response::Located;
use crate::trajectory::{Channel, Solved, Start, trajectory};
use crate::{Oscillator, Result};
use loomkin_numeric::extremes_of;
use loomkin_units::{Range, ShaftSpeed};

/// Highest natural frequency of either mode, Hz (the single-mass model's bound,
/// [`crate::Follower::NATURAL_HZ`]).
const MAX_HZ: f64 = 1e6;
/// Largest mass, kg.
const MAX_KG: f64 = 1e6;

/// A two-mass follower.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoMass {
    /// Circular natural frequencies ω₁ < ω₂ (rad/s).
    pub omega: [f64; 2],
    /// Frame (m₂) component of each mode shape, the drive (m₁) component being 1.
    pub phi2: [f64; 2],
    /// Participation factors Γᵢ.
    pub gamma: [f64; 2],
    /// Modal damping ratio.
    pub zeta: f64,
}

impl TwoMass {
    /// From the masses (kg), stiffnesses (N/m) and the modal damping ratio (0 ≤ ζ < 1).
    pub fn new(m1: f64, k1: f64, m2: f64, k2: f64, zeta: f64) -> Result<Self> {
        let mass = Range::open(0.0, MAX_KG, "kg");
        let stiff = Range::open(0.0, 1e13, "N/m");
        let (m1, m2) = (mass.check("drive_mass_kg", m1)?, mass.check("frame_mass_kg", m2)?);
        let (k1, k2) = (stiff.check("drive_stiffness_n_m", k1)?, stiff.check("frame_stiffness_n_m", k2)?);
        let zeta = crate::Follower::DAMPING_RATIO.check(zeta)?;
        let (l1, l2) = Self::eigenvalues(m1, k1, m2, k2);
        // The second mode within the single-mass model's frequency range: a mass too light for its
        // stiffness is refused by name, with the least mass that keeps f₂ ≤ 10⁶ Hz.
        let top = (std::f64::consts::TAU * MAX_HZ).powi(2);
        if l2.is_nan() || l2 > top {
            let drive = (k1 + k2) / m1 >= k2 / m2;
            let (field, m) = if drive { ("drive_mass_kg", m1) } else { ("frame_mass_kg", m2) };
            let l2_of =
                |x: f64| if drive { Self::eigenvalues(x, k1, m2, k2).1 } else { Self::eigenvalues(m1, k1, x, k2).1 };
            // λ₂ falls as either mass grows: bisection on log m for λ₂ = (2π·10⁶ Hz)².
            let (_, hi) = loomkin_numeric::bisect_bracket(m.ln(), MAX_KG.ln(), |x| l2_of(x.exp()) > top);
            let least = hi.exp();
            return Err(loomkin_units::RangeError::new(
                field,
                m,
                Range::closed_open(least, MAX_KG, "kg (a lighter mass puts the second natural frequency above 10⁶ Hz)"),
            )
            .into());
        }
        let mut out = Self { omega: [0.0; 2], phi2: [0.0; 2], gamma: [0.0; 2], zeta };
        for (i, l) in [l1, l2].into_iter().enumerate() {
            let p2 = k2 / (k2 - l * m2);
            let mu = m1 + m2 * p2 * p2;
            out.omega[i] = l.sqrt();
            out.phi2[i] = p2;
            out.gamma[i] = (m1 + m2 * p2) / mu;
        }
        Ok(out)
    }

    /// The eigenvalues `λ₁ ≤ λ₂` (ω², rad²/s²), both roots without cancellation:
    /// `λ₂ = (b + √(b² − 4m₁m₂k₁k₂))/(2m₁m₂)`, `λ₁ = k₁k₂/(m₁m₂λ₂)`, `b = m₁k₂ + m₂(k₁ + k₂)`.
    fn eigenvalues(m1: f64, k1: f64, m2: f64, k2: f64) -> (f64, f64) {
        let b = m1 * k2 + m2 * (k1 + k2);
        let disc = (b * b - 4.0 * m1 * m2 * k1 * k2).max(0.0).sqrt();
        let l2 = (b + disc) / (2.0 * m1 * m2);
        (k1 * k2 / (m1 * m2 * l2), l2)
    }

    /// The modal channels.
    pub fn channels(&self) -> [Channel; 2] {
        [0, 1].map(|i| Channel {
            osc: Oscillator::new(self.omega[i], self.zeta),
            g_a: -self.gamma[i],
            g_s: 0.0,
            g_0: 0.0,
        })
    }

    /// The exact modal responses over `cycles` cycles (from rest or in the periodic steady state).
    pub fn respond(&self, exc: &Excitation, start: Start, cycles: usize) -> Result<[Vec<Solved>; 2]> {
        let [a, b] = self.channels();
        Ok([trajectory(exc, &a, start, cycles)?, trajectory(exc, &b, start, cycles)?])
    }

    /// `(y₁, y₁', y₂, y₂')` — drive and frame errors and their rates — at global time `t` from modal solutions.
    pub fn errors(&self, modes: &[Vec<Solved>; 2], t: f64) -> [f64; 4] {
        let mut out = [0.0; 4];
        for (i, m) in modes.iter().enumerate() {
            let k = m.partition_point(|p| p.t0 <= t).saturating_sub(1);
            let p = &m[k];
            let (eta, deta) = p.sol.state((t - p.t0).clamp(0.0, p.sol.duration()));
            out[0] += eta;
            out[1] += deta;
            out[2] += self.phi2[i] * eta;
            out[3] += self.phi2[i] * deta;
        }
        out
    }

    /// Extremes of the drive error `y₁` and the frame error `y₂` over the computed motion, located exactly:
    /// on every piece both modes are closed-form, so `yⱼ = Σᵢ φⱼᵢ·ηᵢ` and its two derivatives are too; the
    /// roots of `yⱼ'` are bracketed on a grid finer than a third of the faster mode's half period and
    /// refined by Newton. Locations are global times (s).
    pub fn error_extremes(&self, modes: &[Vec<Solved>; 2]) -> [Extremes; 2] {
        let mut out = [Extremes::EMPTY; 2];
        let w_fast = self.omega[1].max(self.omega[0]);
        for (a, b) in modes[0].iter().zip(&modes[1]) {
            let dur = a.sol.duration();
            let [e1, e2] = extremes_of(0.0, dur, grid_size(dur, w_fast), |t| {
                let (ya, yb) = (a.sol.derivs_n::<3>(t), b.sol.derivs_n::<3>(t));
                [
                    [ya[0] + yb[0], ya[1] + yb[1], ya[2] + yb[2]],
                    [
                        self.phi2[0] * ya[0] + self.phi2[1] * yb[0],
                        self.phi2[0] * ya[1] + self.phi2[1] * yb[1],
                        self.phi2[0] * ya[2] + self.phi2[1] * yb[2],
                    ],
                ]
            });
            out[0].merge(&e1, a.t0);
            out[1].merge(&e2, a.t0);
        }
        out
    }

    /// The train's figures over one cycle of `exc` (run at `speed`) from `start`, in `units`: the
    /// natural frequencies, the drive's and the frame's largest errors and where, the frame's
    /// residual bound in the dwells and the rigidity ratio. Refuses figures that are not finite
    /// (masses and stiffnesses whose modes overflow).
    pub fn report(&self, exc: &Excitation, speed: ShaftSpeed, start: Start, units: Units) -> Result<TwoMassReport> {
        let modes = self.respond(exc, start, 1)?;
        let [drive, frame] = self.error_extremes(&modes);
        let residual = self.frame_residual_bound(exc, &modes);
        let hz = self.omega.map(|w| w / std::f64::consts::TAU);
        let (d, f) = (drive.peak_abs(), frame.peak_abs());
        if [d.0, f.0, residual, hz[0], hz[1]].iter().any(|v| !v.is_finite()) {
            return Err(crate::DynError::Input {
                field: "two_mass".into(),
                reason: "the two-mass figures are not finite numbers at these masses and stiffnesses (an overflow)"
                    .into(),
            });
        }
        Ok(TwoMassReport {
            natural_hz: hz,
            peak_drive_error: Located { value: d.0, angle_deg: exc.angle_deg(d.1) },
            peak_frame_error: Located { value: f.0, angle_deg: exc.angle_deg(f.1) },
            frame_residual_bound_si: residual,
            rigidity_ratio: hz[0] / speed.hz(),
            speed_rpm: speed.rpm(),
            damping_ratio: self.zeta,
            start,
            units,
        })
    }

    /// Bound on the frame's residual vibration at the start of each dwell: `Σᵢ |φ₂ᵢ|·Aᵢ` with `Aᵢ` the
    /// modal amplitudes (the frame's free vibration never exceeds it). Largest over the dwells (SI).
    pub fn frame_residual_bound(&self, exc: &Excitation, modes: &[Vec<Solved>; 2]) -> f64 {
        let mut worst: f64 = 0.0;
        for k in 0..modes[0].len() {
            let piece = &exc.pieces[modes[0][k].piece];
            let starts = piece.dwell && (k == 0 || !exc.pieces[modes[0][k - 1].piece].dwell);
            if !starts {
                continue;
            }
            let mut bound = 0.0;
            for (i, m) in modes.iter().enumerate() {
                let (eta, deta) = m[k].sol.state(0.0);
                bound += self.phi2[i].abs() * m[k].sol.oscillator().amplitude(eta, deta);
            }
            worst = worst.max(bound);
        }
        worst
    }
}

#[cfg(test)]
mod range_tests {
    use super::*;

    /// A mass too light for its stiffness is refused by name; the least mass the message gives is
    /// the boundary: just above it is accepted with f₂ ≤ 10⁶ Hz, just below it is refused.
    #[test]
    fn a_too_light_mass_is_refused_with_the_least_allowed() {
        for (light_drive, (m1, m2)) in [(true, (1e-300, 10.0)), (false, (10.0, 1e-12))] {
            let e = TwoMass::new(m1, 1e6, m2, 1e6, 0.0).unwrap_err().to_string();
            let field = if light_drive { "drive_mass_kg" } else { "frame_mass_kg" };
            assert!(e.starts_with(&format!("{field} = ")) && !e.contains('\n'), "{e}");
            // The least mass from the message: "allowed L ≤ field < 1000000 kg …".
            let least: f64 = e.split("allowed ").nth(1).unwrap().split(' ').next().unwrap().parse().unwrap();
            let with = |m: f64| {
                if light_drive { TwoMass::new(m, 1e6, m2, 1e6, 0.0) } else { TwoMass::new(m1, 1e6, m, 1e6, 0.0) }
            };
            let ok = with(least * 1.001).expect("just above the least mass");
            assert!(ok.omega[1] / std::f64::consts::TAU <= MAX_HZ);
            assert!(with(least * 0.99).is_err());
        }
    }
}
