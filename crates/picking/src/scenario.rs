//! A mechanism under given settings, resolved into the equation B'·ẍ + (C'+1)·x = s(t) − s₀ − D'.

use crate::cam::BuiltCam;
use crate::units::{M_PER_CM, M_PER_MM, N_PER_KGF};
use crate::{Constants, Mechanism, Nominal, PickError, Result, Settings, StartRule};
use std::f64::consts::PI;

/// Largest natural frequency ψ = √((C'+1)/B') accepted, 1/s (real mechanisms: 10²–10³ 1/s).
///
/// Above it the equation is so stiff that the integrator's rounding noise (ẍ is the small
/// difference of two terms of size ψ²·x) forces ever smaller steps, and the closed form's
/// accelerations lose digits the same way.
pub const MAX_NATURAL_1_S: f64 = 3e4;

/// Largest number of natural oscillations ψ·T/(2π) over the cam's rise accepted. The paper's
/// mechanism stays below 750 at any accepted setting (1 rev/min, k next to l); beyond a few
/// thousand the numerical route's step count grows past its budget.
pub const MAX_CYCLES: f64 = 1000.0;

/// Everything the two routes need about one scenario.
///
/// Time: t is real time from the instant the shuttle starts; the cam's design time is
/// u = q·t + u₀ = q·(t + t₀) (eq. 21) with q = n₂/n₁ and t₀ = u₀/q the real-time delay.
/// The picker's nominal motion is s(u) − s₀ (eq. 21, s' = s + s₀ read with the play subtracted).
#[derive(Debug, Clone)]
pub(crate) struct Scenario {
    pub(crate) cam: BuiltCam,
    /// B', C', D' at the setting.
    pub(crate) k: Constants,
    /// q = n₂/n₁.
    pub(crate) q: f64,
    /// Design-time delay u₀, s.
    pub(crate) u0: f64,
    /// Play at the picker s₀ = s'₀·l/k (eq. 47a), m.
    pub(crate) s0: f64,
    /// Real time at which the cam's rise ends, (u_end − u₀)/q, s.
    pub(crate) t_cam_end: f64,
    /// Real times of the cam's stage joints inside (0, t_cam_end).
    pub(crate) joints: Vec<f64>,
    /// Shuttle mass, kg, and checking force, N (for the contact force m·ẍ + F₀).
    pub(crate) shuttle_kg: f64,
    pub(crate) checking_n: f64,
}

impl Scenario {
    pub(crate) fn new(m: &Mechanism, st: &Settings) -> Result<Self> {
        st.validate(m)?;
        let p = m.params();
        let cam = m.built_cam()?;
        let design = *m.design();
        let k = p.constants_at(st.strap_m, st.shuttle_kg, st.checking_n);
        if !(k.b_s2.is_finite() && k.b_s2 > 0.0 && k.c.is_finite() && k.d_m.is_finite()) {
            return Err(PickError::StrapTooLow { strap_cm: st.strap_m / M_PER_CM, l_cm: p.l_m / M_PER_CM });
        }
        let q = st.speed_rpm / m.design_spec().speed_rpm;
        let s0 = st.play_m * p.l_m / st.strap_m;
        let travel = match st.start {
            StartRule::Paper => s0,
            StartRule::Equilibrium => (s0 + k.d_m - design.constants.d_m).max(0.0),
        };
        let reach = cam.reach_m();
        let u0 = match cam.time_of_travel(travel) {
            Some(u0) if travel < reach => u0,
            _ if s0 >= reach || st.start == StartRule::Paper => {
                return Err(PickError::PlayBeyondReach {
                    play_mm: st.play_m / M_PER_MM,
                    play_picker_mm: s0 / M_PER_MM,
                    reach_mm: reach / M_PER_MM,
                });
            }
            _ => {
                return Err(PickError::CheckingBeyondReach {
                    checking_kgf: st.checking_n / N_PER_KGF,
                    play_picker_mm: s0 / M_PER_MM,
                    extra_mm: (k.d_m - design.constants.d_m) / M_PER_MM,
                    reach_mm: reach / M_PER_MM,
                });
            }
        };
        let t_cam_end = (cam.end_u() - u0) / q;
        let psi = k.natural_1_s();
        let cycles = psi * t_cam_end / (2.0 * PI);
        if !(psi <= MAX_NATURAL_1_S && cycles <= MAX_CYCLES) {
            return Err(PickError::TooManyOscillations {
                natural_1_s: psi,
                duration_s: t_cam_end,
                cycles,
                max_natural_1_s: MAX_NATURAL_1_S,
                max_cycles: MAX_CYCLES,
            });
        }
        let joints = cam.joints_u().into_iter().map(|u| (u - u0) / q).filter(|&t| t > 0.0 && t < t_cam_end).collect();
        Ok(Self { cam, k, q, u0, s0, t_cam_end, joints, shuttle_kg: st.shuttle_kg, checking_n: st.checking_n })
    }

    /// Right-hand side of eq. 28: s(q·t + u₀) − s₀ − D', m.
    #[inline]
    pub(crate) fn forcing(&self, t: f64) -> f64 {
        self.cam.eval(self.q * t + self.u0).s_m - self.s0 - self.k.d_m
    }

    /// The picker's nominal motion in real time: s − s₀, q·ṡ, q²·s̈ (eqs. 22–27).
    pub(crate) fn nominal(&self, t: f64) -> Nominal {
        let n = self.cam.eval(self.q * t + self.u0);
        Nominal { s_m: n.s_m - self.s0, v_m_s: self.q * n.v_m_s, a_m_s2: self.q * self.q * n.a_m_s2 }
    }

    /// Real-time delay t₀ = u₀/q, s.
    pub(crate) fn t0(&self) -> f64 {
        self.u0 / self.q
    }

    /// ψ = √((C'+1)/B'), 1/s.
    pub(crate) fn psi(&self) -> f64 {
        self.k.natural_1_s()
    }

    /// Acceleration from the equation of motion: ẍ = (forcing − (C'+1)·x)/B'.
    #[inline]
    pub(crate) fn accel(&self, t: f64, x: f64) -> f64 {
        (self.forcing(t) - (self.k.c + 1.0) * x) / self.k.b_s2
    }
}
