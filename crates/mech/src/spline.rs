//! Periodic cubic splines and the closed curve through a point table.
//!
//! The second derivatives `Mᵢ` at the knots solve the cyclic tridiagonal system
//!
//! `h_{i−1} M_{i−1} + 2(h_{i−1} + hᵢ) Mᵢ + hᵢ M_{i+1} = 6[(y_{i+1} − yᵢ)/hᵢ − (yᵢ − y_{i−1})/h_{i−1}]`
//!
//! (indices modulo n), solved by the Thomas algorithm with a Sherman–Morrison correction for the
//! two corner entries. The spline is C² and periodic.

use crate::curve::{CurvePoint, PlaneCurve};
use crate::planar::Vec2;
use crate::{MechError, Result};

/// A periodic cubic spline `y(u)` through `(uᵢ, yᵢ)`, `i = 0…n−1`, with period `L`
/// (`y(u + L) = y(u)`), C² everywhere.
#[derive(Debug, Clone, PartialEq)]
pub struct PeriodicSpline {
    knots: Vec<f64>,
    /// Per interval: `y = c0 + c1 t + c2 t² + c3 t³`, `t = u − uᵢ`.
    coef: Vec<[f64; 4]>,
    period: f64,
}

impl PeriodicSpline {
    /// Fits the spline through `values` at strictly increasing `knots` with period `period`
    /// (`period > knots[n−1] − knots[0]`, the last interval closes the loop). Needs n ≥ 3.
    pub fn new(knots: &[f64], values: &[f64], period: f64) -> Result<Self> {
        let n = knots.len();
        if n < 3 || values.len() != n {
            return Err(MechError::Invalid {
                field: "spline".into(),
                reason: format!("needs at least 3 knots and as many values (got {n} knots, {} values)", values.len()),
            });
        }
        let mut h = vec![0.0; n];
        for i in 0..n {
            let next = if i + 1 < n { knots[i + 1] } else { knots[0] + period };
            h[i] = next - knots[i];
            let ok = h[i] > 0.0 && h[i].is_finite() && values[i].is_finite();
            if !ok {
                return Err(MechError::PointTable {
                    location: format!("point {i}"),
                    reason: "knots must be finite and strictly increasing within one period".into(),
                });
            }
        }
        let y = |i: usize| values[i % n];
        let (mut a, mut b, mut c, mut r) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        for i in 0..n {
            let hp = h[(i + n - 1) % n];
            a[i] = hp;
            b[i] = 2.0 * (hp + h[i]);
            c[i] = h[i];
            r[i] = 6.0 * ((y(i + 1) - y(i)) / h[i] - (y(i) - y(i + n - 1)) / hp);
        }
        let m = loomkin_numeric::solve_cyclic_tridiagonal(&a, &b, &c, &r);
        let coef = (0..n)
            .map(|i| {
                let (mi, mj, hi) = (m[i], m[(i + 1) % n], h[i]);
                let slope = (y(i + 1) - y(i)) / hi - hi * (2.0 * mi + mj) / 6.0;
                [y(i), slope, mi / 2.0, (mj - mi) / (6.0 * hi)]
            })
            .collect();
        Ok(Self { knots: knots.to_vec(), coef, period })
    }

    /// The period `L` of the parameter.
    pub fn period(&self) -> f64 {
        self.period
    }

    /// Interval index and local coordinate of `u` (reduced into one period).
    #[inline]
    fn locate(&self, u: f64) -> (usize, f64) {
        let u0 = self.knots[0];
        let mut w = (u - u0).rem_euclid(self.period) + u0;
        if !w.is_finite() {
            w = u0;
        }
        let i = self.knots.partition_point(|&k| k <= w).saturating_sub(1);
        (i, w - self.knots[i])
    }

    /// `(y, y′, y″)` at `u`.
    #[inline]
    pub fn eval(&self, u: f64) -> (f64, f64, f64) {
        let (i, t) = self.locate(u);
        let [c0, c1, c2, c3] = self.coef[i];
        (c0 + t * (c1 + t * (c2 + t * c3)), c1 + t * (2.0 * c2 + 3.0 * c3 * t), 2.0 * c2 + 6.0 * c3 * t)
    }
}

/// A closed curve through a table of points: two periodic cubic splines `x(u)`, `y(u)` in the
/// cumulative chord length `u` (m), so the period is the closed polygon's perimeter.
#[derive(Debug, Clone, PartialEq)]
pub struct ClosedSpline {
    x: PeriodicSpline,
    y: PeriodicSpline,
    points: Vec<Vec2>,
}

/// Fewest points accepted for a closed spline.
pub const MIN_SPLINE_POINTS: usize = 8;

impl ClosedSpline {
    /// Fits the closed curve through `points` (m), in order. A last point equal to the first is
    /// dropped; consecutive coincident points and fewer than [`MIN_SPLINE_POINTS`] are errors.
    pub fn new(points: &[Vec2]) -> Result<Self> {
        let mut pts: Vec<Vec2> = points.to_vec();
        for (i, p) in pts.iter().enumerate() {
            if !(p.x.is_finite() && p.y.is_finite()) {
                return Err(MechError::PointTable {
                    location: format!("point {i}"),
                    reason: "not a finite number".into(),
                });
            }
        }
        let scale = pts.iter().fold(0.0f64, |m, p| m.max(p.norm())).max(1e-300);
        if pts.len() > 1 && (pts[0] - pts[pts.len() - 1]).norm() <= 1e-12 * scale {
            pts.pop();
        }
        if pts.len() < MIN_SPLINE_POINTS {
            return Err(MechError::PointTable {
                location: format!("{} points", pts.len()),
                reason: format!("a closed cam needs at least {MIN_SPLINE_POINTS} distinct points"),
            });
        }
        let n = pts.len();
        let mut knots = Vec::with_capacity(n);
        let mut u = 0.0;
        for i in 0..n {
            knots.push(u);
            let d = (pts[(i + 1) % n] - pts[i]).norm();
            if d <= 1e-12 * scale {
                return Err(MechError::PointTable {
                    location: format!("point {}", (i + 1) % n),
                    reason: format!("coincides with point {i}; the points must be distinct and in order"),
                });
            }
            u += d;
        }
        let xs: Vec<f64> = pts.iter().map(|p| p.x).collect();
        let ys: Vec<f64> = pts.iter().map(|p| p.y).collect();
        Ok(Self { x: PeriodicSpline::new(&knots, &xs, u)?, y: PeriodicSpline::new(&knots, &ys, u)?, points: pts })
    }

    /// The fitted points (without a repeated closing point).
    pub fn points(&self) -> &[Vec2] {
        &self.points
    }
}

impl PlaneCurve for ClosedSpline {
    #[inline]
    fn eval(&self, p: f64) -> CurvePoint {
        let (x, dx, ddx) = self.x.eval(p);
        let (y, dy, ddy) = self.y.eval(p);
        CurvePoint { r: Vec2::new(x, y), d1: Vec2::new(dx, dy), d2: Vec2::new(ddx, ddy) }
    }

    fn period(&self) -> f64 {
        self.x.period()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::Ellipse;
    use std::f64::consts::TAU;

    #[test]
    fn periodic_spline_interpolates_and_is_c2() {
        let n = 12;
        let knots: Vec<f64> = (0..n).map(|i| i as f64 * 0.5 + 0.05 * (i as f64).sin()).collect();
        let period = n as f64 * 0.5;
        let vals: Vec<f64> = knots.iter().map(|u| (TAU * u / period).cos() + 0.3).collect();
        let s = PeriodicSpline::new(&knots, &vals, period).unwrap();
        for (u, v) in knots.iter().zip(&vals) {
            assert!((s.eval(*u).0 - v).abs() < 1e-12);
        }
        // Continuity of y, y', y'' at every knot, including the wrap-around one.
        let eps = 1e-9;
        for &u in knots.iter().chain(std::iter::once(&(knots[0] + period))) {
            let (l, r) = (s.eval(u - eps), s.eval(u + eps));
            assert!((l.0 - r.0).abs() < 1e-8 && (l.1 - r.1).abs() < 1e-7 && (l.2 - r.2).abs() < 1e-6);
        }
    }

    #[test]
    fn spline_through_ellipse_points_converges_at_fourth_order() {
        let el = Ellipse::PAPER;
        let err = |n: usize| {
            let sp = ClosedSpline::new(&el.points(n)).unwrap();
            // Distance of spline points from the ellipse, via the implicit form (x/a)² + (y/b)² = 1.
            let mut worst = 0.0f64;
            for k in 0..997 {
                let r = sp.eval(sp.period() * k as f64 / 997.0).r;
                let f = ((r.x / el.a_m).powi(2) + (r.y / el.b_m).powi(2)).sqrt() - 1.0;
                worst = worst.max(f.abs());
            }
            worst
        };
        let (e1, e2) = (err(40), err(80));
        assert!(e2 < 1e-5, "error {e2}");
        let order = (e1 / e2).log2();
        assert!(order > 3.5, "observed order {order}");
    }

    #[test]
    fn closed_spline_rejects_bad_tables() {
        let el = Ellipse::PAPER;
        assert!(matches!(ClosedSpline::new(&el.points(5)), Err(MechError::PointTable { .. })));
        let mut pts = el.points(20);
        pts[5] = pts[4];
        assert!(matches!(ClosedSpline::new(&pts), Err(MechError::PointTable { .. })));
        let mut closed = el.points(20);
        closed.push(closed[0]);
        assert_eq!(ClosedSpline::new(&closed).unwrap().points().len(), 20);
    }
}
