//! Gauss–Legendre quadrature nodes, computed once by Newton's method on the Legendre polynomial.

use std::sync::OnceLock;

/// Number of Gauss–Legendre nodes per panel.
pub(crate) const ORDER: usize = 16;

/// Nodes and weights of the `n`-point Gauss–Legendre rule on `[−1, 1]`, exact for polynomials of
/// degree up to `2n − 1`; found by Newton's method on the Legendre polynomial `P_n` from a
/// Chebyshev-like first guess.
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                // Legendre recurrence for P_n(x) and P_{n−1}(x).
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// The 16-point rule used by the metrics, computed once.
pub(crate) fn rule16() -> &'static [(f64, f64)] {
    static RULE: OnceLock<Vec<(f64, f64)>> = OnceLock::new();
    RULE.get_or_init(|| gauss_legendre(ORDER))
}

/// ∫ f over `[a, b]`, split into `panels` equal panels.
pub(crate) fn integrate(a: f64, b: f64, panels: usize, f: impl Fn(f64) -> f64) -> f64 {
    let rule = rule16();
    let h = (b - a) / panels as f64;
    let mut sum = 0.0;
    for p in 0..panels {
        let mid = a + (p as f64 + 0.5) * h;
        for &(x, w) in rule.iter() {
            sum += w * f(mid + 0.5 * h * x);
        }
    }
    0.5 * h * sum
}

#[cfg(test)]
mod tests {
    #[test]
    fn integrates_polynomials_exactly_and_sines_accurately() {
        let i = super::integrate(0.0, 2.0, 1, |x| x.powi(29));
        assert!((i - 2f64.powi(30) / 30.0).abs() < 1e-9 * i);
        let s = super::integrate(0.0, std::f64::consts::PI, 1, f64::sin);
        assert!((s - 2.0).abs() < 1e-14);
    }
}
