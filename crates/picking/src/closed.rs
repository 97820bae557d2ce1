//! The closed-form actual motion under changed settings: the paper's eqs. 29–47, corrected.
//!
//! Corrections (see `docs/picking.md` for the reasons): eq. 34 takes `sin μq(t+t₀)` (the printed
//! `sin μ(t+t₀)` drops q); the stage switch is at u = τ, i.e. t₁ = τ/q − t₀ (printed t = τ − t₀);
//! in eq. 46, `+Hτ²` is `−Hτ²/q²`, `Iτ` is `Iτ/q`, `2Hτ` is `2Hτ/q`, and `sin(qπ/2)`, `cos(qπ/2)`
//! are `sin(π/2) = 1`, `cos(π/2) = 0`; eq. 47 reads T = (T' − u₀)/q with u₀ = q·t₀.

use crate::scenario::Scenario;
use crate::{PickError, Result, State};
use serde::Serialize;
use std::f64::consts::PI;

/// Relative gap |C'+1 − μ²q²B'|/(C'+1) below which the closed form is declared resonant.
///
/// Near resonance G and the homogeneous constants grow like 1/gap and cancel; with a gap of
/// 1e-6 the cancellation costs about six of the sixteen digits, still well inside the 1e-7
/// agreement the two routes are held to.
pub const RESONANCE_GAP: f64 = 1e-6;

/// Largest relative rounding error [`PaperConstants::cancellation`] may estimate at the end of the
/// cam's rise before the closed form hands over to numerical integration.
///
/// The closed form writes x, ẋ and ẍ as sums of terms that can be far larger than their sum: a
/// pick that lasts a small fraction of a natural period (a play that leaves the cam a few
/// microseconds of travel, or a loom speed of 10⁵ rev/min) sums terms of ~0.4 m to a distance of
/// 10⁻¹¹ m, and ε·Σ|terms|/|x| reached 10⁻³ (a scipy DOP853 integration of eq. 5 at rtol 10⁻¹³ and
/// the numerical route agreed with each other to 10⁻¹¹). The estimate runs about ten times above
/// the error found (2.2e-9 for an error of 2.5e-10 in a 56 µs pick), so at 10⁻¹⁰ the closed form
/// answers only where it keeps ten digits.
pub const CANCELLATION_LIMIT: f64 = 1e-10;

/// The constants of the paper's closed-form solution for one scenario (eqs. 33, 37, 41, 45, 46).
///
/// Stage 1 (0 ≤ t < t₁): x = K₁cos ψt + K₂sin ψt + E + (A/μ)·q·F·(t+t₀) − G·sin μq(t+t₀).
/// Stage 2 (t ≥ t₁): x = H(t+t₀)² + I(t+t₀) + M + K₃cos ψt + K₄sin ψt.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PaperConstants {
    /// E = (D − D' − s₀)/(C'+1), m.
    pub e: f64,
    /// F = (C+1)/(C'+1).
    pub f: f64,
    /// G = (A/μ²)·(C+1−μ²B)/(C'+1−μ²q²B'), m.
    pub g: f64,
    /// H = F·A·q²/2, m/s².
    pub h: f64,
    /// I = F·(A/μ)·q·(1 − π/2), m/s.
    pub i: f64,
    /// M = E + AB/(C'+1) + F·(A/μ²)(π²/8 − 1) − F·A·q²·B'/(C'+1), m.
    pub m: f64,
    /// K₁, m (eq. 37).
    pub k1: f64,
    /// K₂, m (eq. 37).
    pub k2: f64,
    /// K₃, m (eq. 45).
    pub k3: f64,
    /// K₄, m (eq. 45).
    pub k4: f64,
    /// N = x₁(t₁) − x_p2(t₁), m (eq. 46).
    pub n: f64,
    /// P = ẋ₁(t₁) − ẋ_p2(t₁), m/s (eq. 46).
    pub p: f64,
    /// ϱ = ψ·t₁.
    pub rho: f64,
    /// ψ = √((C'+1)/B'), 1/s.
    pub psi: f64,
    /// A, m/s², μ·q, 1/s.
    pub a: f64,
    /// Forcing circular frequency μ·q of the first stage, 1/s.
    pub mu_q: f64,
    /// q = n₂/n₁.
    pub q: f64,
    /// t₀ = u₀/q, real-time delay, s.
    pub t0: f64,
    /// t₁ = τ/q − t₀: end of the first stage in real time, s (≤ 0 when the play outlasts it).
    pub t1: f64,
}

impl PaperConstants {
    pub(crate) fn new(sc: &Scenario) -> Result<Self> {
        let d = match &sc.cam {
            crate::cam::BuiltCam::Compound(d) => d,
            crate::cam::BuiltCam::Law { label, .. } => return Err(PickError::NoClosedForm { law: label.clone() }),
        };
        let (a, mu, tau) = (d.a_m_s2, d.mu_1_s, d.tau_s);
        let (b, c, dd) = (d.constants.b_s2, d.constants.c, d.constants.d_m);
        let (bp, cp1, dp) = (sc.k.b_s2, sc.k.c + 1.0, sc.k.d_m);
        let q = sc.q;
        let t0 = sc.t0();
        let t1 = tau / q - t0;
        let psi = (cp1 / bp).sqrt();
        let e = (dd - dp - sc.s0) / cp1;
        let f = (c + 1.0) / cp1;
        let h = f * a * q * q / 2.0;
        let i = f * a / mu * q * (1.0 - PI / 2.0);
        let m = e + a * b / cp1 + f * a / (mu * mu) * (PI * PI / 8.0 - 1.0) - f * a * q * q * bp / cp1;
        let (g, k1, k2, rho, n, p);
        if t1 > 0.0 {
            let den = cp1 - mu * mu * q * q * bp;
            let gap = den.abs() / cp1;
            if gap < RESONANCE_GAP {
                return Err(PickError::Resonance { natural_1_s: psi, forcing_1_s: mu * q, rel_gap: gap });
            }
            g = a / (mu * mu) * (c + 1.0 - mu * mu * b) / den;
            let (s, co) = (mu * q * t0).sin_cos();
            k1 = g * s - a / mu * q * f * t0 - e;
            k2 = (g * mu * q * co - a / mu * q * f) / psi;
            rho = psi * t1;
            let (sr, cr) = rho.sin_cos();
            let w = PI / (2.0 - PI);
            n = w * i * tau / q - h * tau * tau / (q * q) - m + k1 * cr + k2 * sr + e - g;
            p = -2.0 * h * tau / q + w * i + k2 * psi * cr - k1 * psi * sr;
        } else {
            // The play outlasts the sine stage: only stage 2, from rest at t = 0.
            (g, k1, k2, rho) = (0.0, 0.0, 0.0, 0.0);
            n = -(h * t0 * t0 + i * t0 + m);
            p = -(2.0 * h * t0 + i);
        }
        let (sr, cr) = rho.sin_cos();
        let k3 = n * cr - p / psi * sr;
        let k4 = n * sr + p / psi * cr;
        Ok(Self { e, f, g, h, i, m, k1, k2, k3, k4, n, p, rho, psi, a, mu_q: mu * q, q, t0, t1 })
    }

    /// Actual motion at real time `t` ≥ 0 (eqs. 34–36 before t₁, 42–44 after).
    #[inline]
    pub fn state(&self, t: f64) -> State {
        let (sp, cp) = (self.psi * t).sin_cos();
        let (sm, cm) = if t < self.t1 { (self.mu_q * (t + self.t0)).sin_cos() } else { (0.0, 1.0) };
        self.state_from(t, [sp, cp], [sm, cm])
    }

    /// The state at `t` given sin/cos of ψt and of μq(t + t₀) (the latter read before t₁ only).
    #[inline]
    fn state_from(&self, t: f64, [sp, cp]: [f64; 2], [sm, cm]: [f64; 2]) -> State {
        let psi2 = self.psi * self.psi;
        let w = t + self.t0;
        if t < self.t1 {
            let lin = self.a / self.mu_q * self.q * self.q * self.f;
            State {
                x_m: self.k1 * cp + self.k2 * sp + self.e + lin * w - self.g * sm,
                v_m_s: -self.k1 * self.psi * sp + self.k2 * self.psi * cp + lin - self.g * self.mu_q * cm,
                a_m_s2: -self.k1 * psi2 * cp - self.k2 * psi2 * sp + self.g * self.mu_q * self.mu_q * sm,
            }
        } else {
            State {
                x_m: self.h * w * w + self.i * w + self.m + self.k3 * cp + self.k4 * sp,
                v_m_s: 2.0 * self.h * w + self.i - self.k3 * self.psi * sp + self.k4 * self.psi * cp,
                a_m_s2: 2.0 * self.h - self.k3 * psi2 * cp - self.k4 * psi2 * sp,
            }
        }
    }

    /// The relative rounding error the closed form carries at real time `t` ≥ 0: ε times the
    /// largest ratio, over x, ẋ and ẍ, of the sum of the magnitudes of the solution's terms to
    /// the magnitude of their sum (ẍ against at least the designed peak acceleration A, so that
    /// an acceleration passing through zero does not count as lost). The constants themselves
    /// (N, P, K₁…K₄) are sums of terms of the same size, so this also bounds their share.
    pub fn cancellation(&self, t: f64) -> f64 {
        let (sp, cp) = (self.psi * t).sin_cos();
        let psi2 = self.psi * self.psi;
        let w = t + self.t0;
        let ratio = |terms: &[f64], floor: f64| {
            let sum: f64 = terms.iter().sum();
            let size: f64 = terms.iter().map(|v| v.abs()).sum();
            if size == 0.0 { 0.0 } else { size / sum.abs().max(floor) }
        };
        let (rx, rv, ra) = if t < self.t1 {
            let (sm, cm) = (self.mu_q * (t + self.t0)).sin_cos();
            let lin = self.a / self.mu_q * self.q * self.q * self.f;
            (
                ratio(&[self.k1 * cp, self.k2 * sp, self.e, lin * w, -self.g * sm], 0.0),
                ratio(&[-self.k1 * self.psi * sp, self.k2 * self.psi * cp, lin, -self.g * self.mu_q * cm], 0.0),
                ratio(&[-self.k1 * psi2 * cp, -self.k2 * psi2 * sp, self.g * self.mu_q * self.mu_q * sm], self.a.abs()),
            )
        } else {
            (
                ratio(&[self.h * w * w, self.i * w, self.m, self.k3 * cp, self.k4 * sp], 0.0),
                ratio(&[2.0 * self.h * w, self.i, -self.k3 * self.psi * sp, self.k4 * self.psi * cp], 0.0),
                ratio(&[2.0 * self.h, -self.k3 * psi2 * cp, -self.k4 * psi2 * sp], self.a.abs()),
            )
        };
        f64::EPSILON * rx.max(rv).max(ra)
    }

    /// Jerk ȧ and its rate ä at real time `t` ≥ 0 (the derivatives of [`PaperConstants::state`]'s
    /// acceleration).
    #[inline]
    pub fn jerk(&self, t: f64) -> [f64; 2] {
        let (sp, cp) = (self.psi * t).sin_cos();
        let psi3 = self.psi * self.psi * self.psi;
        let psi4 = psi3 * self.psi;
        if t < self.t1 {
            let (sm, cm) = (self.mu_q * (t + self.t0)).sin_cos();
            let m3 = self.mu_q * self.mu_q * self.mu_q;
            let m4 = m3 * self.mu_q;
            [
                self.k1 * psi3 * sp - self.k2 * psi3 * cp + self.g * m3 * cm,
                self.k1 * psi4 * cp + self.k2 * psi4 * sp - self.g * m4 * sm,
            ]
        } else {
            [psi3 * (self.k3 * sp - self.k4 * cp), psi4 * (self.k3 * cp + self.k4 * sp)]
        }
    }

    /// States at `t_end·i/n`, i = 0…n, and at the sorted times `joints` (the cam's joints inside
    /// the pick), merged in increasing order into `ts` and `states` (a time equal to the one before
    /// it is not repeated). Sin/cos of both phases advance by the angle-addition recurrence and are
    /// re-seeded by `sin_cos` every [`RESEED`] points, so the rounding drift stays within a few
    /// dozen ulps of the directly evaluated states; the joints' states are evaluated directly.
    pub(crate) fn scan_uniform(
        &self,
        t_end: f64,
        n: usize,
        joints: &[f64],
        ts: &mut Vec<f64>,
        states: &mut Vec<State>,
    ) {
        let h = t_end / n as f64;
        let (sh, ch) = (self.psi * h).sin_cos();
        let (smh, cmh) = (self.mu_q * h).sin_cos();
        let (mut p, mut m) = ([0.0, 1.0], [0.0, 1.0]);
        let mut jn = joints.iter().copied().peekable();
        let mut push = |t: f64, st: State| {
            if ts.last() != Some(&t) {
                ts.push(t);
                states.push(st);
            }
        };
        for i in 0..=n {
            let t = t_end * i as f64 / n as f64;
            while let Some(tj) = jn.next_if(|&tj| tj < t) {
                push(tj, self.state(tj));
            }
            if i % RESEED == 0 {
                let (s, c) = (self.psi * t).sin_cos();
                p = [s, c];
                if t < self.t1 {
                    let (s, c) = (self.mu_q * (t + self.t0)).sin_cos();
                    m = [s, c];
                }
            }
            push(t, self.state_from(t, p, m));
            p = [p[0] * ch + p[1] * sh, p[1] * ch - p[0] * sh];
            m = [m[0] * cmh + m[1] * smh, m[1] * cmh - m[0] * smh];
        }
        for tj in jn {
            push(tj, self.state(tj));
        }
    }
}

/// Points between exact `sin_cos` seeds in [`PaperConstants::scan_uniform`].
const RESEED: usize = 32;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Mechanism, Settings};

    fn constants(st: &Settings, m: &Mechanism) -> (Scenario, PaperConstants) {
        let sc = Scenario::new(m, st).unwrap();
        let p = PaperConstants::new(&sc).unwrap();
        (sc, p)
    }

    /// The recurrence scan against the directly evaluated closed form.
    #[test]
    fn uniform_scan_matches_direct_evaluation() {
        let m = Mechanism::paper_default();
        for st in [Settings::designed(&m).with_play_mm(15.5), Settings::designed(&m).with_speed_rpm(230.0)] {
            let (sc, p) = constants(&st, &m);
            let n = 700;
            let (mut ts, mut out) = (Vec::new(), Vec::new());
            p.scan_uniform(sc.t_cam_end, n, &[], &mut ts, &mut out);
            assert_eq!(out.len(), n + 1);
            assert!(ts.iter().enumerate().all(|(i, &t)| t == sc.t_cam_end * i as f64 / n as f64));
            let direct: Vec<State> = (0..=n).map(|i| p.state(sc.t_cam_end * i as f64 / n as f64)).collect();
            // Errors against the scale of each quantity over the pick (x starts from 0 as the small
            // difference of terms of about 0.1 m, so a relative test at each point would ask too much).
            let scale = |f: fn(&State) -> f64| direct.iter().map(|s| f(s).abs()).fold(0.0, f64::max);
            let (sx, sv, sa) = (scale(|s| s.x_m), scale(|s| s.v_m_s), scale(|s| s.a_m_s2));
            for (i, (s, d)) in out.iter().zip(&direct).enumerate() {
                let ok = (s.x_m - d.x_m).abs() <= 1e-14 * sx
                    && (s.v_m_s - d.v_m_s).abs() <= 1e-14 * sv
                    && (s.a_m_s2 - d.a_m_s2).abs() <= 1e-14 * sa;
                assert!(ok, "{i}: {s:?} vs {d:?}");
            }
        }
    }

    /// The jerk and its rate against central differences of the closed-form acceleration.
    #[test]
    fn jerk_matches_finite_differences() {
        let m = Mechanism::paper_default();
        let (sc, p) = constants(&Settings::designed(&m).with_play_mm(15.5), &m);
        let h = 1e-7;
        for k in 1..20 {
            let t = sc.t_cam_end * f64::from(k) / 20.0;
            if (t - p.t1).abs() < 1e-5 {
                continue;
            }
            let fd = (p.state(t + h).a_m_s2 - p.state(t - h).a_m_s2) / (2.0 * h);
            let [j, snap] = p.jerk(t);
            assert!((fd - j).abs() < 1e-6 * j.abs().max(1e3), "t = {t}: jerk {j} vs {fd}");
            let fs = (p.jerk(t + h)[0] - p.jerk(t - h)[0]) / (2.0 * h);
            assert!((fs - snap).abs() < 1e-6 * snap.abs().max(1e6), "t = {t}: snap {snap} vs {fs}");
        }
    }
}
