//! Truncated Taylor series ("jets") in one variable: exact derivatives of the cam geometry.
//!
//! A jet holds the Taylor coefficients `c_k = f⁽ᵏ⁾(ψ)/k!`, `k = 0…N−1`, of a quantity at one cam
//! angle. Sums, products, quotients, square roots, sines, cosines and arctangents of jets follow the
//! usual recurrences of automatic differentiation, so the pitch curve, its normal, curvature and
//! pressure angle come with their derivatives in closed form from those of the motion — no finite
//! differences anywhere in the geometry.

use std::ops::{Add, Mul, Neg, Sub};

/// Number of Taylor coefficients kept (orders 0 to 5: the motion's s … d⁵s/dψ⁵).
pub const N: usize = 6;

/// A truncated Taylor series in the cam angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jet(pub [f64; N]);

const FACT: [f64; N] = [1.0, 1.0, 2.0, 6.0, 24.0, 120.0];

impl Jet {
    /// A constant.
    #[inline]
    pub fn cst(c: f64) -> Self {
        let mut a = [0.0; N];
        a[0] = c;
        Self(a)
    }

    /// The independent variable at `x`.
    #[inline]
    pub fn var(x: f64) -> Self {
        let mut a = [0.0; N];
        a[0] = x;
        a[1] = 1.0;
        Self(a)
    }

    /// From the derivatives `f, f′, f″, …`.
    #[inline]
    pub fn from_derivs(d: [f64; N]) -> Self {
        let mut a = [0.0; N];
        for k in 0..N {
            a[k] = d[k] / FACT[k];
        }
        Self(a)
    }

    /// The value.
    #[inline]
    pub fn v(&self) -> f64 {
        self.0[0]
    }

    /// The derivative of order `k`.
    #[inline]
    pub fn d(&self, k: usize) -> f64 {
        self.0[k] * FACT[k]
    }

    /// The derivative as a jet (one order fewer is exact: the top coefficient becomes 0).
    #[inline]
    pub fn deriv(&self) -> Self {
        let mut a = [0.0; N];
        for k in 0..N - 1 {
            a[k] = (k + 1) as f64 * self.0[k + 1];
        }
        Self(a)
    }

    /// `self · k`.
    #[inline]
    pub fn scale(&self, k: f64) -> Self {
        Self(self.0.map(|c| c * k))
    }

    /// `self / g`.
    #[inline]
    pub fn div(&self, g: &Self) -> Self {
        let mut h = [0.0; N];
        for k in 0..N {
            let mut acc = self.0[k];
            for i in 1..=k {
                acc -= g.0[i] * h[k - i];
            }
            h[k] = acc / g.0[0];
        }
        Self(h)
    }

    /// `√self` (value > 0).
    #[inline]
    pub fn sqrt(&self) -> Self {
        let mut r = [0.0; N];
        r[0] = self.0[0].sqrt();
        for k in 1..N {
            let mut acc = self.0[k];
            for i in 1..k {
                acc -= r[i] * r[k - i];
            }
            r[k] = acc / (2.0 * r[0]);
        }
        Self(r)
    }

    /// `(sin self, cos self)`.
    #[inline]
    pub fn sin_cos(&self) -> (Self, Self) {
        let (mut s, mut c) = ([0.0; N], [0.0; N]);
        (s[0], c[0]) = self.0[0].sin_cos();
        for k in 1..N {
            let (mut ss, mut cc) = (0.0, 0.0);
            for i in 1..=k {
                let iu = i as f64 * self.0[i];
                ss += iu * c[k - i];
                cc -= iu * s[k - i];
            }
            s[k] = ss / k as f64;
            c[k] = cc / k as f64;
        }
        (Self(s), Self(c))
    }

    /// `atan self`.
    #[inline]
    pub fn atan(&self) -> Self {
        // a′ = u′ / (1 + u²), integrated term by term.
        let one_u2 = Jet::cst(1.0) + *self * *self;
        let d = self.deriv().div(&one_u2);
        let mut a = [0.0; N];
        a[0] = self.0[0].atan();
        for k in 1..N {
            a[k] = d.0[k - 1] / k as f64;
        }
        Self(a)
    }

    /// The dot product of two jet vectors.
    #[inline]
    pub fn dot(a: [Jet; 2], b: [Jet; 2]) -> Jet {
        a[0] * b[0] + a[1] * b[1]
    }

    /// The cross product `a × b` of two jet vectors.
    #[inline]
    pub fn cross(a: [Jet; 2], b: [Jet; 2]) -> Jet {
        a[0] * b[1] - a[1] * b[0]
    }
}

impl Add for Jet {
    type Output = Jet;
    #[inline]
    fn add(self, o: Jet) -> Jet {
        let mut a = self.0;
        for (x, y) in a.iter_mut().zip(o.0) {
            *x += y;
        }
        Jet(a)
    }
}

impl Sub for Jet {
    type Output = Jet;
    #[inline]
    fn sub(self, o: Jet) -> Jet {
        let mut a = self.0;
        for (x, y) in a.iter_mut().zip(o.0) {
            *x -= y;
        }
        Jet(a)
    }
}

impl Neg for Jet {
    type Output = Jet;
    #[inline]
    fn neg(self) -> Jet {
        Jet(self.0.map(|c| -c))
    }
}

impl Mul for Jet {
    type Output = Jet;
    #[inline]
    fn mul(self, o: Jet) -> Jet {
        let mut h = [0.0; N];
        for (k, hk) in h.iter_mut().enumerate() {
            for i in 0..=k {
                *hk += self.0[i] * o.0[k - i];
            }
        }
        Jet(h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every operation against the derivatives of known functions (by hand) at one point.
    #[test]
    fn derivatives_of_known_functions() {
        let x = Jet::var(0.7);
        let (s, c) = x.sin_cos();
        // d³/dx³ sin = −cos, d⁵/dx⁵ cos = −sin
        assert!((s.d(3) + 0.7f64.cos()).abs() < 1e-14);
        assert!((c.d(5) + 0.7f64.sin()).abs() < 1e-14);
        // (x² + 1)^{1/2}: derivative x / √(x²+1)
        let r = (x * x + Jet::cst(1.0)).sqrt();
        assert!((r.d(1) - 0.7 / 1.49f64.sqrt()).abs() < 1e-14);
        // d²/dx² of √(x²+1) = (x²+1)^{-3/2}
        assert!((r.d(2) - 1.49f64.powf(-1.5)).abs() < 1e-14);
        // atan x: derivative 1/(1+x²), second −2x/(1+x²)²
        let a = x.atan();
        assert!((a.d(1) - 1.0 / 1.49).abs() < 1e-14);
        assert!((a.d(2) + 1.4 / (1.49 * 1.49)).abs() < 1e-14);
        // 1/x: fourth derivative 24/x⁵
        let q = Jet::cst(1.0).div(&x);
        assert!((q.d(4) - 24.0 / 0.7f64.powi(5)).abs() < 1e-9);
        // sin(x²): derivative 2x cos x²
        let (s2, _) = (x * x).sin_cos();
        assert!((s2.d(1) - 1.4 * 0.49f64.cos()).abs() < 1e-14);
        assert!((x.deriv().v() - 1.0).abs() < 1e-15);
    }
}
