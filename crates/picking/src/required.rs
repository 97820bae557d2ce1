//! The required shuttle velocity from the free shed opening (Jederán's V_r formula, §3.1).

use crate::Result;
use loomkin_units::{Field, Range};
use serde::{Deserialize, Serialize};

/// Inputs of the required-velocity formula
/// V_r = 100/(100 − p) · 6·n·s / φ_s  (m/s, with n in rev/min, s in m, φ_s in degrees).
///
/// The shuttle must cover the path s (shuttle length plus shuttle race) while the shed is open,
/// i.e. during φ_s degrees of crank rotation, which last φ_s/(6n) seconds; p % is the loss of
/// velocity in the shed. The paper prints the factor as "s6π/φ_v" — an OCR/print error for
/// 6·n·s/φ_s (the required velocity "increases linearly with the loom speed", so n must appear).
///
/// The paper gives p ≈ 10 % but neither s nor φ_s; the defaults s = 1.53 m, φ_s = 120° are chosen
/// so that V_r = 17 m/s at the designed 200 rev/min, as the paper's Fig. 5 requires (the design
/// velocity is the required one at the designed speed).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RequiredVelocity {
    /// p: retardation of the shuttle in the shed, percent (0 ≤ p < 100).
    pub retardation_pct: f64,
    /// s: shuttle length plus the length of the shuttle race, m.
    pub path_m: f64,
    /// φ_s: free shed opening as crank angle, degrees.
    pub free_shed_deg: f64,
}

impl Default for RequiredVelocity {
    fn default() -> Self {
        Self {
            retardation_pct: Self::RETARDATION_PCT.default_value(),
            path_m: Self::PATH_M.default_value(),
            free_shed_deg: Self::FREE_SHED_DEG.default_value(),
        }
    }
}

impl RequiredVelocity {
    /// `retardation_pct`: p, 0 ≤ p < 100 (at 100 % the shuttle would stop in the shed); the paper's 10 %.
    pub const RETARDATION_PCT: Field = Field::new(
        "retardation_pct",
        Range::closed_open(0.0, 100.0, "%"),
        "Retardation p of the shuttle in the shed: 0 ≤ p < 100 % (the formula divides by 100 − p); the \
         paper's 10 %.",
    )
    .with_default(10.0);
    /// `path_m`: s, 0.01 ≤ s ≤ 100 m; 1.53 m (with φ_s = 120°, V_r = 17 m/s at 200 rpm as Fig. 5
    /// requires). The path is at least the carrier's own length, so 1 cm is below any shuttle or
    /// projectile; a shorter path made the comparison with V_r a 310-digit percentage (1e-300 m).
    pub const PATH_M: Field = Field::new(
        "path_m",
        Range::closed(0.01, 100.0, "m"),
        "Shuttle length plus shuttle race s: 0.01 ≤ s ≤ 100 m (the path includes the shuttle's own \
         length); 1.53 m, which with φ_s = 120° gives the paper's V_r = 17 m/s at 200 rpm.",
    )
    .with_default(1.53);
    /// `free_shed_deg`: φ_s, 0 < φ_s ≤ 360°; 120°.
    pub const FREE_SHED_DEG: Field = Field::new(
        "free_shed_deg",
        Range::open_closed(0.0, 360.0, "°"),
        "Free shed opening φ_s as crank angle: 0 < φ_s ≤ 360° (one turn); 120°, with s = 1.53 m the \
         paper's V_r = 17 m/s at 200 rpm.",
    )
    .with_default(120.0);

    /// Checks 0 ≤ p < 100, 0.01 ≤ s ≤ 100 m, 0 < φ_s ≤ 360.
    pub fn validate(&self) -> Result<()> {
        Self::RETARDATION_PCT.check(self.retardation_pct)?;
        Self::PATH_M.check(self.path_m)?;
        Self::FREE_SHED_DEG.check(self.free_shed_deg)?;
        Ok(())
    }

    /// V_r at loom speed `speed_rpm`, m/s.
    pub fn at(&self, speed_rpm: f64) -> f64 {
        100.0 / (100.0 - self.retardation_pct) * 6.0 * speed_rpm * self.path_m / self.free_shed_deg
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_gives_the_design_velocity_and_is_linear() {
        let r = RequiredVelocity::default();
        assert!((r.at(200.0) - 17.0).abs() < 1e-12);
        assert!((r.at(240.0) / r.at(200.0) - 1.2).abs() < 1e-12);
        // Independent route: path over the free-shed time, raised by the retardation.
        let t_free_s = 120.0 / 360.0 * 60.0 / 200.0;
        assert!((1.53 / t_free_s / 0.9 - r.at(200.0)).abs() < 1e-12);
    }

    #[test]
    fn bad_inputs() {
        let r = RequiredVelocity { retardation_pct: 100.0, ..Default::default() };
        assert!(r.validate().unwrap_err().to_string().contains("retardation_pct"));
        let r = RequiredVelocity { free_shed_deg: 0.0, ..Default::default() };
        assert!(r.validate().is_err());
    }

    #[test]
    fn path_range_ends_give_finite_comparisons() {
        // A path far below a shuttle's length (1e-300 m) gave a 310-digit percentage: refused,
        // naming the field; the ends of the range give finite, modest velocities.
        for bad in [1e-300, 5e-324, 0.009_999, 100.000_001] {
            let r = RequiredVelocity { path_m: bad, ..Default::default() };
            assert!(r.validate().unwrap_err().to_string().contains("path_m"), "{bad}");
        }
        for ok in [0.01, 100.0] {
            let r = RequiredVelocity { path_m: ok, ..Default::default() };
            r.validate().unwrap();
            // Linear in s: the end's velocity is the default's scaled by s / 1.53.
            let v = r.at(200.0);
            assert!((v - 17.0 * ok / 1.53).abs() <= 1e-12 * v, "{ok}: {v}");
        }
    }
}
