//! The four kinematic quantities of a law at one point.

use serde::Serialize;

/// Displacement and its first three derivatives at one point of a law.
///
/// For a normalised law these are dimensionless: `s` is the fraction of the stroke,
/// `v = ds/dx`, `a = d²s/dx²`, `j = d³s/dx³`, with `x` the fraction of the motion angle.
///
/// The layout is `repr(C)`: four `f64` in the order s, v, a, j (the large-table sampler writes
/// records in that order).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
#[repr(C)]
pub struct Kinematics {
    /// Displacement s.
    pub s: f64,
    /// Velocity v = ds/dx.
    pub v: f64,
    /// Acceleration a = d²s/dx².
    pub a: f64,
    /// Jerk j = d³s/dx³.
    pub j: f64,
}

impl Kinematics {
    /// The quantity of derivative order `k` (0 = s, 1 = v, 2 = a, 3 = j).
    ///
    /// # Panics
    /// Never: orders above 3 return the jerk.
    pub fn order(&self, k: usize) -> f64 {
        match k {
            0 => self.s,
            1 => self.v,
            2 => self.a,
            _ => self.j,
        }
    }
}

/// Anything that maps a position `x` to [`Kinematics`].
///
/// The one required method is [`MotionLaw::eval`]; sampling comes for free.
pub trait MotionLaw {
    /// Kinematics at `x`.
    fn eval(&self, x: f64) -> Kinematics;

    /// `n` evenly spaced samples from `x = 0` to `x = 1`, both ends included (`n ≥ 2`).
    fn sample_uniform(&self, n: usize) -> Vec<(f64, Kinematics)> {
        let n = n.max(2);
        let h = 1.0 / (n - 1) as f64;
        (0..n)
            .map(|i| {
                let x = if i == n - 1 { 1.0 } else { i as f64 * h };
                (x, self.eval(x))
            })
            .collect()
    }
}
