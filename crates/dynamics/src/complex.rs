//! The few complex-number operations the closed forms need.

use std::ops::{Add, Div, Mul, Sub};

/// A complex number `re + i·im`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct C {
    pub re: f64,
    pub im: f64,
}

impl C {
    pub const fn new(re: f64, im: f64) -> Self {
        Self { re, im }
    }

    /// `e^z`.
    pub fn exp(self) -> Self {
        let m = self.re.exp();
        let (s, c) = self.im.sin_cos();
        Self::new(m * c, m * s)
    }

    pub fn scale(self, k: f64) -> Self {
        Self::new(self.re * k, self.im * k)
    }

    pub fn norm(self) -> f64 {
        self.re.hypot(self.im)
    }
}

impl Add for C {
    type Output = C;
    fn add(self, o: C) -> C {
        C::new(self.re + o.re, self.im + o.im)
    }
}

impl Sub for C {
    type Output = C;
    fn sub(self, o: C) -> C {
        C::new(self.re - o.re, self.im - o.im)
    }
}

impl Mul for C {
    type Output = C;
    fn mul(self, o: C) -> C {
        C::new(self.re * o.re - self.im * o.im, self.re * o.im + self.im * o.re)
    }
}

impl Div for C {
    type Output = C;
    fn div(self, o: C) -> C {
        let d = o.re * o.re + o.im * o.im;
        C::new((self.re * o.re + self.im * o.im) / d, (self.im * o.re - self.re * o.im) / d)
    }
}

/// `φ₁(z) = (e^z − 1)/z`, with `φ₁(0) = 1`: a Taylor series for `|z| < 0.5` (no cancellation), the
/// direct quotient otherwise (where `|e^z − 1| ≥ 0.39·|z|`, so at most a few ulps are lost).
pub(crate) fn phi1(z: C) -> C {
    if z.norm() < 0.5 {
        // Σ z^k/(k+1)!, k = 0…17: the first omitted term is below 0.5^18/19! ≈ 3e-23.
        let mut term = C::new(1.0, 0.0);
        let mut sum = term;
        for k in 1..18 {
            term = (term * z).scale(1.0 / (k + 1) as f64);
            sum = sum + term;
        }
        sum
    } else {
        (z.exp() - C::new(1.0, 0.0)) / z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phi1_is_continuous_across_the_switch() {
        // Near the switch both routes are accurate: they must agree to rounding.
        for &(re, im) in &[(0.3, 0.39), (0.0, 0.4999), (-0.49, 0.01), (0.2, -0.45)] {
            let z = C::new(re, im);
            let direct = (z.exp() - C::new(1.0, 0.0)) / z;
            assert!((phi1(z) - direct).norm() < 4e-16, "{re} {im}");
        }
        // Near zero: 1 + z/2 + z²/6 + z³/24.
        let z = C::new(1e-5, -2e-5);
        let taylor = C::new(1.0, 0.0) + z.scale(0.5) + (z * z).scale(1.0 / 6.0) + (z * z * z).scale(1.0 / 24.0);
        assert!((phi1(z) - taylor).norm() < 1e-16);
        assert_eq!(phi1(C::new(0.0, 0.0)), C::new(1.0, 0.0));
    }
}
