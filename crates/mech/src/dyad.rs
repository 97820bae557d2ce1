//! Closed-form dyads: where a vector loop has a direct solution.

use crate::planar::{Vec2, cross, perp};
use crate::{MechError, Result};

/// The two intersections of circle `(c1, r1)` and circle `(c2, r2)` (an RRR dyad), in m.
///
/// With `d = |c2 − c1|`, `a = (r1² − r2² + d²)/(2d)` and `h = √(r1² − a²)`, the points are
/// `c1 + a·u ± h·u⊥` (`u` the unit vector from c1 to c2). Index 0 lies to the left of c1→c2
/// (`+u⊥`), index 1 to the right. Fails when `|r1 − r2| ≤ d ≤ r1 + r2` is violated.
pub fn circle_circle(c1: Vec2, r1: f64, c2: Vec2, r2: f64, what: &str) -> Result<[Vec2; 2]> {
    let dv = c2 - c1;
    let d = dv.norm();
    if d.is_nan() || d <= 0.0 || !d.is_finite() {
        return Err(MechError::NoIntersection { what: what.into(), reason: "the two centres coincide".into() });
    }
    let a = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d);
    let h2 = r1 * r1 - a * a;
    if h2 < 0.0 {
        return Err(MechError::NoIntersection {
            what: what.into(),
            reason: format!(
                "centre distance {d:.6} m is outside [{:.6}, {:.6}] m (|r1 − r2| to r1 + r2)",
                (r1 - r2).abs(),
                r1 + r2
            ),
        });
    }
    let u = dv / d;
    let h = h2.sqrt();
    Ok([c1 + a * u + h * perp(u), c1 + a * u - h * perp(u)])
}

/// Distances `s` along the line `a + s·u` (`u` a unit vector) to the circle `(c, r)`:
/// `s² + 2s·u·(a − c) + |a − c|² − r² = 0`, returned as `[smaller, larger]`.
///
/// Fails when the line misses the circle: the distance `|u × (a − c)|` from the centre to the line
/// exceeds `r`.
pub fn line_circle(a: Vec2, u: Vec2, c: Vec2, r: f64, what: &str) -> Result<[f64; 2]> {
    let w = a - c;
    let b = u.dot(&w);
    let disc = r * r - cross(u, w).powi(2);
    if disc < 0.0 || !disc.is_finite() {
        return Err(MechError::NoIntersection {
            what: what.into(),
            reason: format!(
                "the line passes {:.6} m from the centre, more than the radius {r:.6} m",
                cross(u, w).abs()
            ),
        });
    }
    let s = disc.sqrt();
    Ok([-b - s, -b + s])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planar::e;

    #[test]
    fn circle_circle_points_lie_on_both_circles() {
        let (c1, c2) = (Vec2::new(0.1, -0.2), Vec2::new(0.5, 0.3));
        for p in circle_circle(c1, 0.4, c2, 0.5, "t").unwrap() {
            assert!(((p - c1).norm() - 0.4).abs() < 1e-14);
            assert!(((p - c2).norm() - 0.5).abs() < 1e-14);
        }
        assert!(circle_circle(c1, 0.1, c2, 0.1, "t").is_err());
    }

    #[test]
    fn line_circle_roots_lie_on_the_circle() {
        let (a, u, c) = (Vec2::new(0.0, 0.66), e(-1.9), Vec2::zeros());
        let s = line_circle(a, u, c, 0.4, "t").unwrap();
        for si in s {
            assert!(((a + si * u).norm() - 0.4).abs() < 1e-14);
        }
        assert!(s[0] <= s[1]);
        assert!(line_circle(a, e(0.0), c, 0.4, "t").is_err());
    }
}
