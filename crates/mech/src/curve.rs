//! Closed parametric plane curves: the cam profiles a vector loop can run on.

use crate::Result;
use crate::planar::{Vec2, curvature};
use loomkin_units::Range;
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// A point of a parametric curve `r(p)` with its first two derivatives in the parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurvePoint {
    /// Position `r(p)` (m).
    pub r: Vec2,
    /// Tangent `dr/dp` (m per unit of p).
    pub d1: Vec2,
    /// `d²r/dp²` (m per unit of p²).
    pub d2: Vec2,
}

impl CurvePoint {
    /// Signed curvature `κ = (r′ × r″)/|r′|³` (1/m); `None` at a stationary point.
    pub fn curvature(&self) -> Option<f64> {
        curvature(self.d1, self.d2)
    }
}

/// A closed plane curve `r(p)`, periodic in its parameter `p` with period [`PlaneCurve::period`].
///
/// Implemented by [`Ellipse`] and by [`crate::ClosedSpline`] (a curve through a point table).
pub trait PlaneCurve: std::fmt::Debug + Send + Sync {
    /// Position and derivatives at parameter `p` (any real `p`; the curve is periodic).
    fn eval(&self, p: f64) -> CurvePoint;

    /// Period of the parameter (rad for an ellipse, m of chord length for a spline).
    fn period(&self) -> f64;

    /// The positions `r(pᵢ)` at `pᵢ = period·i/n`, `i = 0..=n` (both ends), for scanning the
    /// curve: each within a few units of rounding of `eval(pᵢ).r`, and cheaper where the curve can
    /// step along a uniform grid of its parameter ([`Ellipse`]: no `sin_cos` per point).
    fn scan(&self, n: usize) -> Vec<Vec2> {
        let n = n.max(1);
        (0..=n).map(|i| self.eval(self.period() * i as f64 / n as f64).r).collect()
    }

    /// `n` points evenly spaced in the parameter over one period (the last one not repeated).
    fn points(&self, n: usize) -> Vec<Vec2> {
        let h = self.period() / n.max(1) as f64;
        (0..n).map(|i| self.eval(i as f64 * h).r).collect()
    }
}

/// The ellipse `r(p) = c + (a cos p, b sin p)` (semi-axes `a` along x, `b` along y, in m).
///
/// This is the cam Γ of the paper's task 1, eq. (12): `a = 0.366 m`, `b = 0.577 m`, centred on O.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Ellipse {
    /// Semi-axis along x (m).
    pub a_m: f64,
    /// Semi-axis along y (m).
    pub b_m: f64,
    /// Centre x (m).
    pub cx_m: f64,
    /// Centre y (m).
    pub cy_m: f64,
}

impl Ellipse {
    /// The paper's cam: `a = 0.366 m`, `b = 0.577 m`, centred on the frame axis O.
    pub const PAPER: Ellipse = Ellipse { a_m: 0.366, b_m: 0.577, cx_m: 0.0, cy_m: 0.0 };

    /// A centred ellipse with semi-axes `a_m`, `b_m` (each in (0, 100] m).
    pub fn new(a_m: f64, b_m: f64) -> Result<Self> {
        Self::with_centre(a_m, b_m, 0.0, 0.0)
    }

    /// An ellipse with semi-axes `a_m`, `b_m` centred at `(cx_m, cy_m)`.
    pub fn with_centre(a_m: f64, b_m: f64, cx_m: f64, cy_m: f64) -> Result<Self> {
        for (f, v) in [("a_m", a_m), ("b_m", b_m)] {
            Range::open_closed(0.0, 100.0, "m").check(f, v)?;
        }
        Range::closed(-100.0, 100.0, "m").check("cx_m", cx_m)?;
        Range::closed(-100.0, 100.0, "m").check("cy_m", cy_m)?;
        Ok(Self { a_m, b_m, cx_m, cy_m })
    }
}

impl PlaneCurve for Ellipse {
    #[inline]
    fn eval(&self, p: f64) -> CurvePoint {
        let (s, c) = p.sin_cos();
        CurvePoint {
            r: Vec2::new(self.cx_m + self.a_m * c, self.cy_m + self.b_m * s),
            d1: Vec2::new(-self.a_m * s, self.b_m * c),
            d2: Vec2::new(-self.a_m * c, -self.b_m * s),
        }
    }

    fn period(&self) -> f64 {
        TAU
    }

    /// `(cos pᵢ, sin pᵢ)` from `sin_cos` at every 32nd point (an anchor), the points between
    /// turned from it by a table of `e(2π·j/n)`, `j < 32` (one rotation, no accumulation).
    fn scan(&self, n: usize) -> Vec<Vec2> {
        const K: usize = 32;
        let n = n.max(1);
        let unit = |i: usize| {
            let (s, c) = (TAU * i as f64 / n as f64).sin_cos();
            Vec2::new(c, s)
        };
        let offsets: Vec<Vec2> = (0..K.min(n + 1)).map(unit).collect();
        let mut out = Vec::with_capacity(n + 1);
        let mut anchor = unit(0);
        for i in 0..=n {
            let j = i % K;
            let u = if j == 0 {
                anchor = unit(i);
                anchor
            } else {
                crate::planar::rotate(anchor, offsets[j])
            };
            out.push(Vec2::new(self.cx_m + self.a_m * u.x, self.cy_m + self.b_m * u.y));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::MechError;

    #[test]
    fn ellipse_derivatives_match_finite_differences() {
        let el = Ellipse::PAPER;
        let h = 1e-6;
        for p in [0.0, 0.7, 2.5, -1.2] {
            let k = el.eval(p);
            let d1 = (el.eval(p + h).r - el.eval(p - h).r) / (2.0 * h);
            let d2 = (el.eval(p + h).d1 - el.eval(p - h).d1) / (2.0 * h);
            assert!((d1 - k.d1).norm() < 1e-9);
            assert!((d2 - k.d2).norm() < 1e-9);
        }
        // Curvature at the end of the major axis b: κ = b/a²; at the end of a: κ = a/b².
        let k_top = el.eval(std::f64::consts::FRAC_PI_2).curvature().unwrap();
        assert!((k_top - el.b_m / (el.a_m * el.a_m)).abs() < 1e-12);
        let k_side = el.eval(0.0).curvature().unwrap();
        assert!((k_side - el.a_m / (el.b_m * el.b_m)).abs() < 1e-12);
    }

    /// Independent route for the scan: `eval` at every point, for point counts that are and are
    /// not multiples of the anchor spacing; the anchors are `eval` itself.
    #[test]
    fn ellipse_scan_matches_eval() {
        let el = Ellipse::with_centre(0.366, 0.577, 0.01, -0.02).unwrap();
        for n in [1usize, 5, 31, 32, 100, 2048, 2049] {
            let pts = el.scan(n);
            assert_eq!(pts.len(), n + 1);
            for (i, p) in pts.iter().enumerate() {
                let r = el.eval(TAU * i as f64 / n as f64).r;
                // The angle's own rounding (½ ulp of 2π), the anchor's and the offset's unit vector
                // components and one rotation, times the semi-axes; centre added once.
                assert!((p - r).amax() <= 4.0 * f64::EPSILON, "n = {n}, i = {i}: {p:?} vs {r:?}");
                if i % 32 == 0 {
                    assert_eq!(*p, r);
                }
            }
        }
    }

    #[test]
    fn ellipse_rejects_bad_axes() {
        assert!(matches!(Ellipse::new(0.0, 1.0), Err(MechError::Range(_))));
        assert!(matches!(Ellipse::new(f64::NAN, 1.0), Err(MechError::Range(_))));
    }
}
