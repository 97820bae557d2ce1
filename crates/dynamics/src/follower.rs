//! The single-mass follower model: natural frequency, damping ratio and optional loads.

use crate::excitation::TimePiece;
use crate::oscillator::{Forcing, Harmonic, NCOEF, Oscillator};
use crate::trajectory::Channel;
use crate::{DynError, Result};
use loomkin_units::{Field, Range, RangeError};
use serde::Serialize;

/// Standard gravity (m/s²), for a follower's weight.
pub const STANDARD_GRAVITY: f64 = loomkin_units::STANDARD_GRAVITY_M_S2;

/// A follower train as one mass on a spring and damper, driven through the law (base excitation):
///
/// $$ m x'' + c\,(x' - s') + k\,(x - s) = -k_r\,x - F_0 $$
///
/// * `x` — follower (heald-frame) position, `s` — the law (the cam's or drive's input), m or rad;
/// * `k` — stiffness of the train between input and mass (N/m), `c` — its damping (N·s/m);
/// * `k_r` — an optional return spring acting on the mass (N/m, its zero at x = 0), and `F₀` — a constant
///   closing force (N: spring preload + weight + any constant force), both pulling the follower back
///   onto the cam (towards −s).
///
/// The model is given as the natural frequency of the whole follower, `f_n = ω_n/2π` with
/// `ω_n² = (k + k_r)/m`, and the damping ratio `ζ = c/(2mω_n)`. With the error `y = x − s`:
///
/// $$ y'' + 2ζω_n y' + ω_n^2 y = -s'' - ε s - f_0, \qquad ε = k_r/m,\; f_0 = F_0/m. $$
///
/// Without loads (`k_r = F₀ = 0`, the default) only `f_n` and `ζ` matter and no mass is needed. The
/// force in the train, `F = k(s − x) + c(s' − x') = −k y − c y'` (N, compression positive), is the
/// contact force of a force-closed follower, which loses contact where it would become negative.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Follower {
    natural_hz: f64,
    damping_ratio: f64,
    mass_kg: Option<f64>,
    return_spring_n_m: f64,
    closing_force_n: f64,
}

impl Follower {
    /// `natural_hz`: f_n, 10⁻³ … 10⁶ Hz. The lower bound keeps ω_n² representable (no overflow of
    /// 1/ω_n²); the closed-form response is exact up to 10⁶ Hz (checked against Duhamel integrals
    /// at 300 rpm, where a cycle holds 2·10⁵ natural periods). A workbench slider's narrower span
    /// (5 … 300 Hz) is a view of this range, not another bound.
    pub const NATURAL_HZ: Field = Field::new(
        "natural_hz",
        Range::closed(1e-3, 1e6, "Hz"),
        "Natural frequency f_n of the follower: 0.001 … 10⁶ Hz (the lower bound keeps 1/ω_n² finite; the \
         closed-form response holds to 10⁶ Hz). Required.",
    );
    /// `damping_ratio`: ζ, 0 ≤ ζ < 1 (the closed form is that of an underdamped oscillator); 0.
    pub const DAMPING_RATIO: Field = Field::new(
        "damping_ratio",
        Range::closed_open(0.0, 1.0, ""),
        "Damping ratio ζ: 0 ≤ ζ < 1 (the closed-form response is the underdamped oscillator's); 0 when left out.",
    )
    .with_default(0.0);
    /// `mass_kg`: the moving mass, 10⁻⁶ ≤ m < 10⁶ kg; it makes forces available. The lower bound
    /// keeps the static deflection F/(m·ω_n²) finite: at the ends of the other ranges (F = 10⁹ N,
    /// f_n = 10⁻³ Hz) it is 2.5·10¹⁹ m at 1 mg, while 5·10⁻³²⁴ kg (accepted before) overflowed to
    /// a non-finite deflection and printed NaN.
    pub const MASS_KG: Field = Field::new(
        "mass_kg",
        Range::closed_open(1e-6, 1e6, "kg"),
        "Moving mass: 10⁻⁶ ≤ m < 10⁶ kg (below a milligram a closing force's static deflection F/(m·ω_n²) \
         overflows); given, the forces (train, contact, loss of contact) are computed.",
    );
    /// `return_spring_n_m`: k_r, 0 … 10¹² N/m, and below m·ω_n² (checked with the mass); 0.
    pub const RETURN_SPRING_N_M: Field = Field::new(
        "return_spring_n_m",
        Range::closed(0.0, 1e12, "N/m"),
        "Return spring on the mass: 0 … 10¹² N/m and below m·ω_n² (else the train would have no stiffness); \
         0 when left out.",
    )
    .with_default(0.0);
    /// `closing_force_n`: the constant closing force, ±10⁹ N (front ends take it as `preload_n`,
    /// the weight and `force_n`, [`Follower::with_front_loads`]).
    pub const CLOSING_FORCE_N: Field = Field::new(
        "closing_force_n",
        Range::closed(-1e9, 1e9, "N"),
        "Constant force closing the follower on the cam: ±10⁹ N.",
    );
    /// `preload_n`: the spring preload, a part of the closing force; 0.
    pub const PRELOAD_N: Field = Self::CLOSING_FORCE_N
        .within(
            Range::closed(-1e9, 1e9, "N"),
            "Spring preload pulling the follower onto the cam: ±10⁹ N; 0 when left out.",
        )
        .named("preload_n")
        .with_default(0.0);
    /// `force_n`: a further constant closing force; 0.
    pub const FORCE_N: Field = Self::CLOSING_FORCE_N
        .within(Range::closed(-1e9, 1e9, "N"), "A further constant closing force: ±10⁹ N; 0 when left out.")
        .named("force_n")
        .with_default(0.0);

    /// A follower of natural frequency `natural_hz` (Hz, 10⁻³…10⁶) and damping ratio `damping_ratio`
    /// (0 ≤ ζ < 1), without loads.
    pub fn new(natural_hz: f64, damping_ratio: f64) -> Result<Self> {
        Ok(Self {
            natural_hz: Self::NATURAL_HZ.check(natural_hz)?,
            damping_ratio: Self::DAMPING_RATIO.check(damping_ratio)?,
            mass_kg: None,
            return_spring_n_m: 0.0,
            closing_force_n: 0.0,
        })
    }

    /// The same follower with a mass (kg), a return spring (N/m) and a constant closing force (N):
    /// the mass makes forces available; the train stiffness `k = m·ω_n² − k_r` must stay positive.
    pub fn with_loads(mut self, mass_kg: f64, return_spring_n_m: f64, closing_force_n: f64) -> Result<Self> {
        let m = Self::MASS_KG.check(mass_kg)?;
        let kr = Self::RETURN_SPRING_N_M.check(return_spring_n_m)?;
        let f0 = Self::CLOSING_FORCE_N.check(closing_force_n)?;
        let w = std::f64::consts::TAU * self.natural_hz;
        let k_total = m * w * w;
        if kr >= k_total {
            return Err(DynError::Range(RangeError::new(
                "return_spring_n_m",
                kr,
                Range::closed_open(0.0, k_total, "N/m (below m·ω_n², else the train would have no stiffness)"),
            )));
        }
        self.mass_kg = Some(m);
        self.return_spring_n_m = kr;
        self.closing_force_n = f0;
        Ok(self)
    }

    /// The follower of a front end's model options: with `mass_kg`, its loads — the return spring
    /// and the closing force `preload_n + force_n`, plus the weight m·g when `weight` (a follower
    /// rising upwards); without a mass, the options of the loads are not used.
    pub fn with_front_loads(
        self,
        mass_kg: Option<f64>,
        return_spring_n_m: f64,
        preload_n: f64,
        weight: bool,
        force_n: f64,
    ) -> Result<Self> {
        match mass_kg {
            Some(m) => {
                // Each force against its own range first: a sum out of range would name neither.
                let preload_n = Self::PRELOAD_N.check(preload_n)?;
                let force_n = Self::FORCE_N.check(force_n)?;
                let w = if weight { m * STANDARD_GRAVITY } else { 0.0 };
                self.with_loads(m, return_spring_n_m, preload_n + w + force_n)
            }
            None => Ok(self),
        }
    }

    /// f_n (Hz).
    pub fn natural_hz(&self) -> f64 {
        self.natural_hz
    }

    /// ζ.
    pub fn damping_ratio(&self) -> f64 {
        self.damping_ratio
    }

    /// The mass (kg), when given.
    pub fn mass_kg(&self) -> Option<f64> {
        self.mass_kg
    }

    /// The oscillator of the error `y = x − s`.
    pub fn oscillator(&self) -> Oscillator {
        Oscillator::new(std::f64::consts::TAU * self.natural_hz, self.damping_ratio)
    }

    /// Train stiffness `k = m·ω_n² − k_r` (N/m) and damping `c = 2ζmω_n` (N·s/m), when a mass is given.
    pub fn train(&self) -> Option<(f64, f64)> {
        let m = self.mass_kg?;
        let w = std::f64::consts::TAU * self.natural_hz;
        Some((m * w * w - self.return_spring_n_m, 2.0 * self.damping_ratio * m * w))
    }

    /// The channel of the error equation, `q = −s'' − ε·s − f₀` (ε = k_r/m, f₀ = F₀/m).
    pub fn channel(&self) -> Channel {
        let (eps, f0) = match self.mass_kg {
            Some(m) => (self.return_spring_n_m / m, self.closing_force_n / m),
            None => (0.0, 0.0),
        };
        Channel { osc: self.oscillator(), g_a: -1.0, g_s: -eps, g_0: -f0 }
    }
}

/// The forcing `q = g_a·s'' + g_s·s + g_0` of a piece (polynomial and sinusoid mapped exactly).
pub(crate) fn channel_forcing(piece: &TimePiece, g_a: f64, g_s: f64, g_0: f64) -> Forcing {
    let p = &piece.poly;
    let mut poly = [0.0; NCOEF];
    for k in 0..NCOEF {
        let acc = if k + 2 < NCOEF { ((k + 2) * (k + 1)) as f64 * p[k + 2] } else { 0.0 };
        poly[k] = g_a * acc + g_s * p[k];
    }
    poly[0] += g_0;
    let sine = piece.accel_sine.map(|h| Harmonic { amp: h.amp * (g_a - g_s / (h.omega * h.omega)), ..h });
    Forcing { poly, sine }
}
