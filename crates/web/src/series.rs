//! Sampled curves in the column layout the page draws from.

use loomkin_laws::{Kinematics, Law};
use serde::Serialize;

/// A law sampled on a uniform grid: one array per quantity (dimensionless, normalised rise).
///
/// `x` is the fraction of the motion angle, `s` the fraction of the stroke, `v = ds/dx`,
/// `a = d²s/dx²`, `j = d³s/dx³`.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct LawSamples {
    /// Positions, 0 … 1.
    pub x: Vec<f64>,
    /// Displacement.
    pub s: Vec<f64>,
    /// Velocity.
    pub v: Vec<f64>,
    /// Acceleration.
    pub a: Vec<f64>,
    /// Jerk.
    pub j: Vec<f64>,
}

impl LawSamples {
    /// Samples `law` at `n ≥ 2` evenly spaced points including both ends.
    pub fn of(law: &Law, n: usize) -> Self {
        let n = n.max(2);
        let mut k = vec![Kinematics::default(); n];
        law.sample_into(&mut k);
        Self::from_kinematics(&k)
    }

    /// Columns from kinematics on a uniform grid over `[0, 1]`.
    pub fn from_kinematics(k: &[Kinematics]) -> Self {
        let n = k.len();
        let h = if n > 1 { 1.0 / (n - 1) as f64 } else { 0.0 };
        Self {
            x: (0..n).map(|i| if i + 1 == n { 1.0 } else { i as f64 * h }).collect(),
            s: k.iter().map(|k| finite(k.s)).collect(),
            v: k.iter().map(|k| finite(k.v)).collect(),
            a: k.iter().map(|k| finite(k.a)).collect(),
            j: k.iter().map(|k| finite(k.j)).collect(),
        }
    }
}

/// `v` if finite, else 0 — the page never receives NaN (JSON has no NaN; serde would write null).
pub fn finite(v: f64) -> f64 {
    if v.is_finite() { v } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use loomkin_laws::LawSpec;

    #[test]
    fn columns_match_pointwise_evaluation() {
        let law = LawSpec::Poly345.build().unwrap();
        let c = LawSamples::of(&law, 11);
        assert_eq!(c.x.len(), 11);
        for i in 0..11 {
            let k = law.eval(c.x[i]);
            assert!((k.s - c.s[i]).abs() < 1e-12 && (k.v - c.v[i]).abs() < 1e-12);
            assert!((k.a - c.a[i]).abs() < 1e-9 && (k.j - c.j[i]).abs() < 1e-9);
        }
        assert_eq!(c.x[10], 1.0);
        assert!((c.s[10] - 1.0).abs() < 1e-12);
    }
}
