//! Small helpers for real polynomials stored lowest power first.

/// `p(t)` by Horner's rule.
#[inline]
pub(crate) fn eval(p: &[f64], t: f64) -> f64 {
    // Plain `*` and `+`: without the `fma` target feature `mul_add` is a slow library call.
    p.iter().rev().fold(0.0, |acc, &c| acc * t + c)
}

/// The derivative `p'`.
pub(crate) fn deriv(p: &[f64]) -> Vec<f64> {
    p.iter().enumerate().skip(1).map(|(k, c)| k as f64 * c).collect()
}

/// The product `p·q`.
pub(crate) fn mul(p: &[f64], q: &[f64]) -> Vec<f64> {
    if p.is_empty() || q.is_empty() {
        return Vec::new();
    }
    let mut r = vec![0.0; p.len() + q.len() - 1];
    mul_into(p, q, &mut r);
    r
}

/// The product `p·q` written into `r` (zeroed, at least `p.len() + q.len() − 1` long); the same
/// sums in the same order as [`mul`].
pub(crate) fn mul_into(p: &[f64], q: &[f64], r: &mut [f64]) {
    for (i, a) in p.iter().enumerate() {
        for (j, b) in q.iter().enumerate() {
            r[i + j] += a * b;
        }
    }
}

/// `∫₀ʷ p(t) dt`, exactly.
pub(crate) fn integral(p: &[f64], w: f64) -> f64 {
    p.iter().enumerate().rev().fold(0.0, |acc, (k, c)| acc * w + c / (k + 1) as f64) * w
}

/// Coefficients of `q(x) = p(x − x0)` (a Taylor shift: local coordinate `t = x − x0` to global `x`).
pub(crate) fn shift(p: &[f64], x0: f64) -> Vec<f64> {
    let n = p.len();
    let mut q = vec![0.0; n];
    for (k, &c) in p.iter().enumerate() {
        // c·(x − x0)^k = c·Σ_m C(k, m) x^m (−x0)^(k−m)
        let mut binom = 1.0;
        for m in 0..=k {
            q[m] += c * binom * (-x0).powi((k - m) as i32);
            binom = binom * (k - m) as f64 / (m + 1) as f64;
        }
    }
    q
}

/// Coefficients of `q(τ) = p(h − τ)` (a local polynomial read backwards from the far end).
pub(crate) fn reflect(p: &[f64], h: f64) -> Vec<f64> {
    let n = p.len();
    let mut q = vec![0.0; n];
    for (k, &c) in p.iter().enumerate() {
        // c·(h − τ)^k = c·Σ_m C(k, m) h^(k−m) (−τ)^m
        let mut binom = 1.0;
        for m in 0..=k {
            let sign = if m % 2 == 0 { 1.0 } else { -1.0 };
            q[m] += c * binom * h.powi((k - m) as i32) * sign;
            binom = binom * (k - m) as f64 / (m + 1) as f64;
        }
    }
    q
}

/// Largest `|p(t)|` on `[0, w]` and where it occurs (see [`abs_max_by`]).
pub(crate) fn abs_max(p: &[f64], w: f64, n: usize) -> (f64, f64) {
    // The two derivatives on the stack for the degrees the torque models have (≤ 16), as `deriv`
    // computes them; the heap beyond.
    let (mut d1, mut d2) = ([0.0; 16], [0.0; 16]);
    let (heap1, heap2);
    let (dp, ddp): (&[f64], &[f64]) = if p.len() <= 17 {
        let n1 = p.len().saturating_sub(1);
        for k in 1..p.len() {
            d1[k - 1] = k as f64 * p[k];
        }
        for k in 1..n1 {
            d2[k - 1] = k as f64 * d1[k];
        }
        (&d1[..n1], &d2[..n1.saturating_sub(1)])
    } else {
        heap1 = deriv(p);
        heap2 = deriv(&heap1);
        (&heap1, &heap2)
    };
    let (g0, mut d0) = (eval(p, 0.0), eval(dp, 0.0));
    let mut best = (g0.abs(), 0.0);
    let mut take = |v: f64, t: f64| {
        if v.abs() > best.0 {
            best = (v.abs(), t);
        }
    };
    let n = n.max(1);
    let h = w / n as f64;
    let mut t0 = 0.0;
    for i in 1..=n {
        let t1 = if i == n { w } else { i as f64 * h };
        let (g1, d1) = (eval(p, t1), eval(dp, t1));
        take(g1, t1);
        if d0 != 0.0 && d1 != 0.0 && (d0 < 0.0) != (d1 < 0.0) {
            // Newton on p' with p'' (kept in the bracket, secant fallback): quadratic convergence.
            let t = loomkin_laws::refine_root(t0, t1, d0 < 0.0, |t| (eval(dp, t), eval(ddp, t)));
            take(eval(p, t), t);
        }
        t0 = t1;
        d0 = d1;
    }
    best
}

/// Largest `|g(t)|` on `[0, w]` and where it occurs, for `f(t) = (g(t), g'(t))`.
///
/// The sign changes of `g'` are bracketed on `n` equal sub-intervals and refined by bisection to
/// rounding (at most 60 halvings); both ends are included. `n` must be large enough to separate
/// the roots of `g'` (more than the polynomial degree; more for oscillating terms).
pub(crate) fn abs_max_by(w: f64, n: usize, f: impl Fn(f64) -> (f64, f64)) -> (f64, f64) {
    let (g0, mut d0) = f(0.0);
    let mut best = (g0.abs(), 0.0);
    let mut take = |v: f64, t: f64| {
        if v.abs() > best.0 {
            best = (v.abs(), t);
        }
    };
    let n = n.max(1);
    let h = w / n as f64;
    let mut t0 = 0.0;
    for i in 1..=n {
        let t1 = if i == n { w } else { i as f64 * h };
        let (g1, d1) = f(t1);
        take(g1, t1);
        if d0 != 0.0 && d1 != 0.0 && (d0 < 0.0) != (d1 < 0.0) {
            let t = root_illinois(t0, t1, d0, d1, |t| f(t).1);
            take(f(t).0, t);
        }
        t0 = t1;
        d0 = d1;
    }
    best
}

/// A root of `d` in `[a, b]` where `d(a) = da` and `d(b) = db` have opposite signs: regula falsi
/// with the Illinois modification (superlinear, always bracketed), until a step is below about
/// 1e-14 of the bracket.
fn root_illinois(mut a: f64, mut b: f64, mut da: f64, mut db: f64, d: impl Fn(f64) -> f64) -> f64 {
    let tol = 1e-14 * (b - a).abs() + 4.0 * f64::EPSILON * a.abs().max(b.abs());
    let mut side = 0i8;
    let mut prev = a;
    for _ in 0..100 {
        let c = (a * db - b * da) / (db - da);
        let c = if c > a.min(b) && c < a.max(b) { c } else { 0.5 * (a + b) };
        let dc = d(c);
        if dc == 0.0 || (c - prev).abs() <= tol {
            return c;
        }
        prev = c;
        if (dc < 0.0) == (db < 0.0) {
            b = c;
            db = dc;
            if side == -1 {
                da *= 0.5;
            }
            side = -1;
        } else {
            a = c;
            da = dc;
            if side == 1 {
                db *= 0.5;
            }
            side = 1;
        }
    }
    0.5 * (a + b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shift_and_reflect_agree_with_direct_evaluation() {
        let p = [0.3, -1.2, 2.5, 0.7, -0.4, 1.1];
        let q = shift(&p, 0.37);
        let r = reflect(&p, 0.21);
        for &x in &[0.0, 0.4, 0.8, 1.0] {
            assert!((eval(&q, x) - eval(&p, x - 0.37)).abs() < 1e-13);
            assert!((eval(&r, x) - eval(&p, 0.21 - x)).abs() < 1e-13);
        }
    }

    #[test]
    fn integral_and_product_agree_with_simpson() {
        let p = [1.0, -2.0, 0.5, 3.0];
        let q = [0.2, 1.0, -1.0];
        let pq = mul(&p, &q);
        let w = 0.8;
        let n = 2000;
        let h = w / n as f64;
        let f = |t: f64| eval(&p, t) * eval(&q, t);
        let simpson: f64 = (0..n)
            .map(|i| {
                let a = i as f64 * h;
                h / 6.0 * (f(a) + 4.0 * f(a + h / 2.0) + f(a + h))
            })
            .sum();
        assert!((integral(&pq, w) - simpson).abs() < 1e-12);
    }

    #[test]
    fn gauss_legendre_is_exact_to_degree_2n_minus_1() {
        let rule = loomkin_laws::gauss_legendre(8);
        for k in 0..16 {
            let q: f64 = rule.iter().map(|(x, w)| w * x.powi(k)).sum();
            let exact = if k % 2 == 0 { 2.0 / (k + 1) as f64 } else { 0.0 };
            assert!((q - exact).abs() < 1e-14, "x^{k}: {q} vs {exact}");
        }
    }

    #[test]
    fn abs_max_finds_an_interior_peak() {
        // p = 0.5 − (t − 0.3)²: on [0, 0.6] the peak is the vertex, on [0, 2] the far end.
        let p = [0.5 - 0.09, 0.6, -1.0];
        let (v, t) = abs_max(&p, 0.6, 8);
        assert!((v - 0.5).abs() < 1e-14 && (t - 0.3).abs() < 1e-7, "{v} {t}");
        let (v, t) = abs_max(&p, 2.0, 8);
        assert!((v - (1.7f64.powi(2) - 0.5)).abs() < 1e-12 && t == 2.0);
    }

    /// The stack path (degree ≤ 16) and the heap path give the same peak: the same polynomial
    /// padded with zero coefficients past 17 takes the heap path; both against the root-finding
    /// route `abs_max_by` with the derivative written out.
    #[test]
    fn abs_max_stack_and_heap_paths_agree() {
        let p: Vec<f64> = (0..9).map(|k| ((k * 7 % 5) as f64 - 2.0) / (k + 1) as f64).collect();
        let mut long = p.clone();
        long.resize(20, 0.0);
        let (a, ta) = abs_max(&p, 1.3, 40);
        let (b, tb) = abs_max(&long, 1.3, 40);
        assert_eq!((a, ta), (b, tb));
        let dp = deriv(&p);
        let (c, tc) = abs_max_by(1.3, 40, |t| (eval(&p, t), eval(&dp, t)));
        assert!((a - c).abs() < 1e-13 * a && (ta - tc).abs() < 1e-6, "{a} at {ta} vs {c} at {tc}");
        assert_eq!(mul(&p, &dp), {
            let mut r = vec![0.0; p.len() + dp.len() - 1];
            mul_into(&p, &dp, &mut r);
            r
        });
    }
}
