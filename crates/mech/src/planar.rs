//! Small planar helpers: unit vectors, the perpendicular, the 2-D cross product, angle wrapping.

use nalgebra::Vector2;

/// A point or a vector of the plane, in metres unless stated.
pub type Vec2 = Vector2<f64>;

/// Unit vector at angle `a` (rad) anticlockwise from +x: `e(a) = (cos a, sin a)`.
#[inline]
pub fn e(a: f64) -> Vec2 {
    let (s, c) = a.sin_cos();
    Vec2::new(c, s)
}

/// Unit vector `e⊥(a) = e(a + π/2) = (−sin a, cos a)` = `de/da`.
#[inline]
pub fn e_perp(a: f64) -> Vec2 {
    let (s, c) = a.sin_cos();
    Vec2::new(-s, c)
}

/// `u` turned by the angle of the unit vector `by`: `e(φ + β)` from `e(φ)` and `e(β)` (angle
/// addition).
#[inline]
pub(crate) fn rotate(u: Vec2, by: Vec2) -> Vec2 {
    Vec2::new(u.x * by.x - u.y * by.y, u.x * by.y + u.y * by.x)
}

/// The vector turned a quarter turn anticlockwise: `(x, y) ↦ (−y, x)`.
#[inline]
pub fn perp(v: Vec2) -> Vec2 {
    Vec2::new(-v.y, v.x)
}

/// The scalar 2-D cross product `u × v = uₓ v_y − u_y vₓ`.
#[inline]
pub fn cross(u: Vec2, v: Vec2) -> f64 {
    u.x * v.y - u.y * v.x
}

/// The angle wrapped into `(−π, π]`.
#[inline]
pub fn wrap_pi(a: f64) -> f64 {
    let t = std::f64::consts::TAU;
    let r = a - t * round(a / t);
    if r <= -std::f64::consts::PI { r + t } else { r }
}

/// `x.round()` (halves away from zero, the sign of zero kept), bit for bit, without the library
/// call the portable x86-64 build makes for it (no `roundsd` before SSE4.1): below 2⁵² the integer
/// part is exact by conversion and the fraction `x − trunc x` exact by subtraction; larger values,
/// infinities and NaN go to `f64::round`.
#[inline]
pub(crate) fn round(x: f64) -> f64 {
    if x.abs() < 4_503_599_627_370_496.0 {
        let t = x as i64 as f64;
        let f = x - t;
        let r = if f >= 0.5 {
            t + 1.0
        } else if f <= -0.5 {
            t - 1.0
        } else {
            t
        };
        r.copysign(x)
    } else {
        x.round()
    }
}

/// `x.floor()`, bit for bit, without the library call the portable x86-64 build makes for it (as
/// [`round`]): below 2⁵² the truncation `x as i64` is exact, and one less where it lies above `x`;
/// zeros (either sign), large values, infinities and NaN go to `f64::floor`.
#[inline]
pub(crate) fn floor(x: f64) -> f64 {
    if x.abs() < 4_503_599_627_370_496.0 && x != 0.0 {
        let t = x as i64 as f64;
        if t > x { t - 1.0 } else { t }
    } else {
        x.floor()
    }
}

/// The angle of `v` (rad) as `reference + δ`, where `unit` = `e(reference)` and δ is the small angle
/// from `unit` to `v`: `δ = atan(t)`, `t = (unit × v)/(unit · v)`, by its Maclaurin series while
/// `|t| ≤ 10⁻²` (five terms; the next, t¹¹/11, is below 10⁻²³), so no `atan2`. `None` where δ is not
/// that small (the caller takes `atan2`). The result carries the rounding of `reference` and of
/// `unit`'s direction (a few 1e-16 rad), as an `atan2` unwrapped near `reference` carries its own.
#[inline]
pub(crate) fn angle_near(reference: f64, unit: Vec2, v: Vec2) -> Option<f64> {
    let (c, d) = (cross(unit, v), unit.dot(&v));
    if !(d > 0.0 && c.abs() <= 1e-2 * d) {
        return None;
    }
    let t = c / d;
    let t2 = t * t;
    let series = t * (1.0 + t2 * (-1.0 / 3.0 + t2 * (1.0 / 5.0 + t2 * (-1.0 / 7.0 + t2 * (1.0 / 9.0)))));
    Some(reference + series)
}

/// The representative of `a + 2πk` nearest to `reference` (for unwrapping a continuous angle).
#[inline]
pub fn unwrap_near(a: f64, reference: f64) -> f64 {
    reference + wrap_pi(a - reference)
}

/// Signed curvature `κ = (r′ × r″)/|r′|³` (1/m) of a curve from its first two derivatives;
/// `None` at a stationary point (`r′ = 0`).
#[inline]
pub fn curvature(d1: Vec2, d2: Vec2) -> Option<f64> {
    let n = d1.norm();
    if n < 1e-300 || !n.is_finite() {
        return None;
    }
    let k = cross(d1, d2) / (n * n * n);
    k.is_finite().then_some(k)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Independent route: `f64::round`, bit for bit, on halves, near-halves, signed zeros, the
    /// 2⁵² boundary, non-finite values and random values of every magnitude.
    #[test]
    fn round_matches_the_library_bit_for_bit() {
        use proptest::prelude::*;
        let same = |x: f64| round(x).to_bits() == x.round().to_bits() || (x.is_nan() && round(x).is_nan());
        let half = 0.5f64;
        for x in [
            0.0,
            -0.0,
            half,
            -half,
            1.5,
            -2.5,
            half.next_down(),
            (-half).next_up(),
            0.3,
            -0.3,
            4_503_599_627_370_495.5,
            -4_503_599_627_370_495.5,
            4_503_599_627_370_496.0,
            9.1e15,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE / 4.0,
        ] {
            assert!(same(x), "{x:e}: {} vs {}", round(x), x.round());
        }
        proptest::test_runner::TestRunner::new(proptest::test_runner::Config { cases: 5000, ..Default::default() })
            .run(&any::<f64>(), |x| {
                prop_assert!(same(x), "{:e}", x);
                prop_assert!(same(x * 1e-300 * 1e300), "{:e}", x);
                Ok(())
            })
            .unwrap();
        proptest::test_runner::TestRunner::new(proptest::test_runner::Config { cases: 5000, ..Default::default() })
            .run(&(-1e6f64..1e6), |x| {
                prop_assert!(same(x) && same(x.trunc() + 0.5) && same(x.trunc() - 0.5), "{:e}", x);
                Ok(())
            })
            .unwrap();
    }

    /// Independent route: `f64::floor`, bit for bit, on integers, their neighbours, signed zeros,
    /// values between −1 and 0 (whose truncation is +0), 2⁵², infinities, NaN and random values.
    #[test]
    fn floor_matches_the_library_bit_for_bit() {
        use proptest::prelude::*;
        let same = |x: f64| floor(x).to_bits() == x.floor().to_bits() || (x.is_nan() && floor(x).is_nan());
        for x in [
            0.0,
            -0.0,
            0.3,
            -0.3,
            1.0,
            -1.0,
            1.0f64.next_down(),
            (-1.0f64).next_down(),
            (-1.0f64).next_up(),
            -2.5,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            4_503_599_627_370_495.5,
            -4_503_599_627_370_495.5,
            4_503_599_627_370_496.0,
            -9.1e15,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ] {
            assert!(same(x), "{x:e}: {} vs {}", floor(x), x.floor());
        }
        proptest::test_runner::TestRunner::new(proptest::test_runner::Config { cases: 5000, ..Default::default() })
            .run(&(any::<f64>(), -1e6f64..1e6), |(x, y)| {
                prop_assert!(same(x) && same(y) && same(y.trunc()) && same(-y.trunc()), "{:e} {:e}", x, y);
                Ok(())
            })
            .unwrap();
    }

    /// Independent route for the small-angle form: `atan2` unwrapped near the reference, for
    /// references over several turns and small angles on both sides up to the series' limit;
    /// beyond it (or behind the reference) the form declines.
    #[test]
    fn angle_near_matches_atan2() {
        use proptest::prelude::*;
        proptest::test_runner::TestRunner::new(proptest::test_runner::Config { cases: 5000, ..Default::default() })
            .run(&(-20.0f64..20.0, -0.0099f64..0.0099, 1e-3f64..10.0), |(r, t, len)| {
                let delta = t.atan();
                let v = len * e(r + delta);
                let near = angle_near(r, e(r), v).unwrap();
                let direct = unwrap_near(v.y.atan2(v.x), r);
                // Both carry the rounding of r + δ and of v's components (a few ε·|r|).
                prop_assert!((near - direct).abs() <= 8.0 * f64::EPSILON * (r.abs() + 1.0), "{near} vs {direct}");
                Ok(())
            })
            .unwrap();
        assert_eq!(angle_near(1.0, e(1.0), e(1.0 + 0.02)), None);
        assert_eq!(angle_near(1.0, e(1.0), -e(1.0)), None);
        assert_eq!(angle_near(0.3, e(0.3), 2.0 * e(0.3)), Some(0.3));
    }

    #[test]
    fn wrap_and_unwrap() {
        use std::f64::consts::PI;
        assert!((wrap_pi(3.0 * PI) - PI).abs() < 1e-12);
        assert!((wrap_pi(-PI) - PI).abs() < 1e-12);
        assert!((wrap_pi(0.5) - 0.5).abs() < 1e-15);
        assert!((unwrap_near(0.1, 2.0 * PI) - (2.0 * PI + 0.1)).abs() < 1e-12);
    }

    #[test]
    fn e_perp_is_the_derivative_of_e() {
        let h = 1e-6;
        for a in [-2.0, 0.3, 1.7] {
            let fd = (e(a + h) - e(a - h)) / (2.0 * h);
            assert!((fd - e_perp(a)).norm() < 1e-9);
            assert!((perp(e(a)) - e_perp(a)).norm() < 1e-15);
        }
    }

    #[test]
    fn circle_curvature_is_one_over_radius() {
        // r(p) = R e(p): r' = R e⊥, r'' = −R e; κ = 1/R for an anticlockwise circle.
        let r = 0.25;
        let k = curvature(r * e_perp(0.4), -r * e(0.4)).unwrap();
        assert!((k - 1.0 / r).abs() < 1e-12);
        assert!(curvature(Vec2::zeros(), Vec2::new(1.0, 0.0)).is_none());
    }
}
