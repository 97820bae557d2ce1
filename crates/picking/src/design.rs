//! Design of the compound picking law (sine, then constant acceleration), eqs. 6–20.

use crate::{Constants, PickError, Result};
use loomkin_units::{Field, Range, ShaftSpeed};
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, PI};

/// What the designer asks of the pick (the paper's §1.2 data).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DesignSpec {
    /// V: shuttle velocity at the end of the pick, m/s.
    pub velocity_m_s: f64,
    /// X: distance the shuttle travels during the pick, m.
    pub distance_m: f64,
    /// X₁: distance travelled during the first (sine) stage, m.
    pub first_stage_m: f64,
    /// n₁: designed loom speed, rev/min.
    pub speed_rpm: f64,
}

impl DesignSpec {
    /// `velocity_m_s`: V, 0 < V ≤ 1000 m/s (far above any shuttle); the paper's 17 m/s.
    pub const VELOCITY_M_S: Field = Field::new(
        "velocity_m_s",
        Range::open_closed(0.0, 1e3, "m/s"),
        "Shuttle velocity V at the end of the pick, the cam's design: 0 < V ≤ 1000 m/s; the paper's 17 m/s.",
    )
    .with_default(17.0);
    /// `distance_m`: X, 0 < X ≤ 100 m; the paper's 0.22 m.
    pub const DISTANCE_M: Field = Field::new(
        "distance_m",
        Range::open_closed(0.0, 100.0, "m"),
        "Pick distance X: 0 < X ≤ 100 m; the paper's 0.22 m.",
    )
    .with_default(0.22);
    /// `first_stage_m`: X₁, 0 < X₁ < X (the sine stage ends before the final velocity); 0.086 m.
    pub const FIRST_STAGE_M: Field = Field::new(
        "first_stage_m",
        Range::above(0.0, "m"),
        "Distance X₁ of the first (sine) stage: 0 < X₁ < X (so T' > τ and eq. 20's denominator stays \
         positive); the paper's 0.086 m.",
    )
    .with_default(0.086);
    /// `design_speed_rpm`: n₁, the shaft-speed range; the paper's 200 rpm.
    pub const SPEED_RPM: Field = Field::new(
        "design_speed_rpm",
        ShaftSpeed::RANGE,
        "Loom speed n₁ the cam is designed for: the main-shaft speed range; the paper's 200 rpm.",
    )
    .with_default(200.0);

    /// The paper's design: V = 17 m/s, X = 22 cm, X₁ = 8.6 cm, n = 200 rev/min.
    pub fn paper() -> Self {
        Self {
            velocity_m_s: Self::VELOCITY_M_S.default_value(),
            distance_m: Self::DISTANCE_M.default_value(),
            first_stage_m: Self::FIRST_STAGE_M.default_value(),
            speed_rpm: Self::SPEED_RPM.default_value(),
        }
    }

    /// Checks ranges: V, X, n positive and 0 < X₁ < X.
    ///
    /// X₁ < X is exactly the condition T' > τ (the sine stage ends below the final velocity,
    /// V·μ > A); it also keeps eq. 20's denominator 2X − X₁·(π−3)/(π/2−1) positive.
    pub fn validate(&self) -> Result<()> {
        Self::VELOCITY_M_S.check(self.velocity_m_s)?;
        Self::DISTANCE_M.check(self.distance_m)?;
        Range::open(0.0, self.distance_m, "m").check(Self::FIRST_STAGE_M.name, self.first_stage_m)?;
        ShaftSpeed::from_rpm(self.speed_rpm)?;
        Ok(())
    }
}

/// (π − 3)/(π/2 − 1), the shape factor of eq. 20.
const SHAPE: f64 = (PI - 3.0) / (FRAC_PI_2 - 1.0);

/// The designed compound law: the actual (shuttle) motion is ẍ = A·sin μt for t < τ = π/(2μ),
/// then ẍ = A up to T'; the cam's nominal motion s follows from eq. 5, s = B·ẍ + (C+1)·x + D.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Design {
    /// A = V² / (2X − X₁·(π−3)/(π/2−1)) (eq. 20): peak (and second-stage) acceleration, m/s².
    pub a_m_s2: f64,
    /// μ = √(A·(π/2 − 1)/X₁) (eq. 19): circular frequency of the sine stage, 1/s.
    pub mu_1_s: f64,
    /// τ = π/(2μ): end of the sine stage, s.
    pub tau_s: f64,
    /// T' = V/A − 1/μ + π/(2μ) (eq. 18): end of the pick, s.
    pub t_end_s: f64,
    /// The mechanism constants the cam is designed for.
    pub constants: Constants,
    /// The specification.
    pub spec: DesignSpec,
}

/// Nominal (cam) motion at one instant: displacement, velocity, acceleration of the picker.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Nominal {
    /// s, m.
    pub s_m: f64,
    /// ṡ, m/s.
    pub v_m_s: f64,
    /// s̈, m/s².
    pub a_m_s2: f64,
}

/// Actual motion (shuttle) at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct State {
    /// x, m.
    pub x_m: f64,
    /// ẋ, m/s.
    pub v_m_s: f64,
    /// ẍ, m/s².
    pub a_m_s2: f64,
}

impl Design {
    /// Designs the compound law for `spec` on a mechanism with constants `constants` (eqs. 18–20).
    pub fn new(spec: DesignSpec, constants: Constants) -> Result<Self> {
        spec.validate()?;
        let d = Self::compute(spec, constants);
        if let Some(quantity) = d.non_finite() {
            // Blame the input whose paper value, put back alone, makes every quantity finite.
            let paper = DesignSpec::paper();
            let with = |k: usize| {
                let mut t = spec;
                match k {
                    0 => t.velocity_m_s = paper.velocity_m_s,
                    1 => t.distance_m = paper.distance_m,
                    2 => t.first_stage_m = paper.first_stage_m,
                    _ => t.speed_rpm = paper.speed_rpm,
                }
                t
            };
            let fields = [
                ("velocity_m_s", spec.velocity_m_s),
                ("distance_m", spec.distance_m),
                ("first_stage_m", spec.first_stage_m),
                ("speed_rpm", spec.speed_rpm),
            ];
            let blame = (0..fields.len()).find(|&k| {
                let trial = with(k);
                trial.validate().is_ok() && Self::compute(trial, constants).non_finite().is_none()
            });
            let (field, value) = fields[blame.unwrap_or(0)];
            return Err(PickError::NonFiniteResult { field: field.into(), value, quantity: quantity.into() });
        }
        Ok(d)
    }

    fn compute(spec: DesignSpec, constants: Constants) -> Self {
        let a = spec.velocity_m_s * spec.velocity_m_s / (2.0 * spec.distance_m - SHAPE * spec.first_stage_m);
        let mu = (a / spec.first_stage_m * (FRAC_PI_2 - 1.0)).sqrt();
        let tau = FRAC_PI_2 / mu;
        let t_end = spec.velocity_m_s / a - 1.0 / mu + tau;
        Self { a_m_s2: a, mu_1_s: mu, tau_s: tau, t_end_s: t_end, constants, spec }
    }

    /// The first derived quantity (A, μ, τ, T′, B, C, D) that is not a finite positive (B, C, D:
    /// non-negative) number, if any.
    fn non_finite(&self) -> Option<&'static str> {
        let normal = |v: f64| v.is_finite() && v >= f64::MIN_POSITIVE;
        let c = &self.constants;
        [
            ("A (eq. 20)", normal(self.a_m_s2)),
            ("μ (eq. 19)", normal(self.mu_1_s)),
            ("τ = π/(2μ)", normal(self.tau_s)),
            ("T′ (eq. 18)", normal(self.t_end_s) && self.t_end_s > self.tau_s),
            ("B (eq. 4)", c.b_s2.is_finite() && c.b_s2 >= 0.0),
            ("C (eq. 4)", c.c.is_finite() && c.c >= 0.0),
            ("D (eq. 4)", c.d_m.is_finite() && c.d_m >= 0.0),
        ]
        .into_iter()
        .find(|(_, ok)| !ok)
        .map(|(name, _)| name)
    }

    /// The second form of eq. 19, μ = A·√((π − 3)/(2AX − V²)); equal to `mu_1_s` by construction.
    pub fn mu_from_distance(&self) -> f64 {
        let (a, x, v) = (self.a_m_s2, self.spec.distance_m, self.spec.velocity_m_s);
        a * ((PI - 3.0) / (2.0 * a * x - v * v)).sqrt()
    }

    /// Designed actual motion at design time `u` (eqs. 6–8 for u < τ, 12–14 after).
    pub fn actual(&self, u: f64) -> State {
        let (a, mu) = (self.a_m_s2, self.mu_1_s);
        if u < self.tau_s {
            let (sn, cs) = (mu * u).sin_cos();
            State { x_m: a / (mu * mu) * (mu * u - sn), v_m_s: a / mu * (1.0 - cs), a_m_s2: a * sn }
        } else {
            let w = u - self.tau_s;
            State { x_m: a / 2.0 * w * w + a / mu * u - a / (mu * mu), v_m_s: a * (w + 1.0 / mu), a_m_s2: a }
        }
    }

    /// Nominal (cam) motion at design time `u` (eqs. 9–11 for u < τ, 15–17 after).
    pub fn nominal(&self, u: f64) -> Nominal {
        let (a, mu) = (self.a_m_s2, self.mu_1_s);
        let Constants { b_s2: b, c, d_m: d } = self.constants;
        if u < self.tau_s {
            let g = (c + 1.0) / (mu * mu) - b;
            let (sn, cs) = (mu * u).sin_cos();
            Nominal {
                s_m: d + a / mu * (c + 1.0) * u - a * g * sn,
                v_m_s: a / mu * (c + 1.0) - a * mu * g * cs,
                a_m_s2: a * (c + 1.0 - b * mu * mu) * sn,
            }
        } else {
            let x = self.actual(u);
            Nominal { s_m: a * b + x.x_m * (c + 1.0) + d, v_m_s: x.v_m_s * (c + 1.0), a_m_s2: a * (c + 1.0) }
        }
    }

    /// Total nominal travel of the picker over the pick beyond the start, s(T') − s(0) = s(T') − D, m.
    pub fn stroke_m(&self) -> f64 {
        self.nominal(self.t_end_s).s_m - self.constants.d_m
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Params;

    fn paper() -> Design {
        Design::new(DesignSpec::paper(), Params::paper().constants()).unwrap()
    }

    #[test]
    fn paper_design_values() {
        let d = paper();
        assert!((d.a_m_s2 - 690.0).abs() < 0.5, "A = {}", d.a_m_s2); // paper: 690 m/s²
        assert!((d.t_end_s - 0.033).abs() < 1e-4, "T' = {}", d.t_end_s); // paper: 3.3e-2 s
        // The paper prints μ = 67.95 1/s and τ = 2.3116e-2 s; eq. 19 gives 67.687 and 2.3207e-2.
        assert!((d.mu_1_s - 67.687).abs() < 1e-3);
        assert!((d.mu_from_distance() / d.mu_1_s - 1.0).abs() < 1e-12);
    }

    #[test]
    fn designed_motion_meets_the_spec() {
        let d = paper();
        let end = d.actual(d.t_end_s);
        assert!((end.x_m - 0.22).abs() < 1e-12 && (end.v_m_s - 17.0).abs() < 1e-11);
        let t1 = d.actual(d.tau_s);
        assert!((t1.x_m - 0.086).abs() < 1e-12);
        let before = d.actual(d.tau_s * (1.0 - 1e-12));
        assert!((before.v_m_s - t1.v_m_s).abs() < 1e-8 && (before.a_m_s2 - t1.a_m_s2).abs() < 1e-6);
    }

    /// The nominal law satisfies eq. 5 with the designed actual law, and its derivatives agree
    /// with central finite differences.
    #[test]
    fn nominal_satisfies_eq5_and_differentiates() {
        let d = paper();
        let k = d.constants;
        for i in 1..200 {
            let u = d.t_end_s * i as f64 / 200.0;
            let (n, x) = (d.nominal(u), d.actual(u));
            let lhs = k.b_s2 * x.a_m_s2 + (k.c + 1.0) * x.x_m;
            assert!((lhs - (n.s_m - k.d_m)).abs() < 1e-14);
            let h = 1e-7;
            if (u - d.tau_s).abs() > 2.0 * h {
                let fd = (d.nominal(u + h).s_m - d.nominal(u - h).s_m) / (2.0 * h);
                assert!((fd - n.v_m_s).abs() < 1e-6 * n.v_m_s.abs().max(1.0));
                let fa = (d.nominal(u + h).v_m_s - d.nominal(u - h).v_m_s) / (2.0 * h);
                assert!((fa - n.a_m_s2).abs() < 1e-5 * n.a_m_s2.abs().max(1.0), "{u}: {fa} {}", n.a_m_s2);
            }
        }
    }

    /// X₁ < X is the condition T' > τ: as X₁ → X the constant-acceleration stage vanishes.
    #[test]
    fn first_stage_limit() {
        let k = Params::paper().constants();
        let mut s = DesignSpec::paper();
        s.first_stage_m = s.distance_m * (1.0 - 1e-9);
        let d = Design::new(s, k).unwrap();
        assert!((d.t_end_s - d.tau_s) / d.tau_s < 1e-6);
        assert!((d.actual(d.tau_s).v_m_s - s.velocity_m_s).abs() < 1e-6 * s.velocity_m_s);
    }

    #[test]
    fn bad_spec_is_an_error() {
        let mut s = DesignSpec::paper();
        s.first_stage_m = 0.3;
        assert!(Design::new(s, Params::paper().constants()).is_err());
        s = DesignSpec::paper();
        s.velocity_m_s = f64::NAN;
        assert!(Design::new(s, Params::paper().constants()).is_err());
    }
}
