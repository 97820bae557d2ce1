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

/// Coefficients of `q(τ) = p(h − τ)` (a local polynomial read backwards from the far end), added
/// into `q` (zeroed, as long as `p`).
pub(crate) fn reflect_into(p: &[f64], h: f64, q: &mut [f64]) {
    for (k, &c) in p.iter().enumerate() {
        // c·(h − τ)^k = c·Σ_m C(k, m) h^(k−m) (−τ)^m
        let mut binom = 1.0;
        for m in 0..=k {
            let sign = if m % 2 == 0 { 1.0 } else { -1.0 };
            q[m] += c * binom * h.powi((k - m) as i32) * sign;
            binom = binom * (k - m) as f64 / (m + 1) as f64;
        }
    }
}

/// Largest `|p(t)|` on `[0, w]` and where it occurs (see [`abs_max_by`]).
///
/// The polynomials of the torque models (up to 16 coefficients) go to a kernel of their exact
/// length, where the Horner loops have a fixed trip count (unrolled, no slice iterators); the
/// arithmetic is the same as [`eval`]'s (a Horner sum started from the leading coefficient equals
/// one started from 0), so the results are bit-identical to the general path.
pub(crate) fn abs_max(p: &[f64], w: f64, n: usize) -> (f64, f64) {
    macro_rules! by_length {
        ($($len:literal)*) => {
            match p.len() {
                $($len => abs_max_fixed::<$len>(p.try_into().expect("length matched"), w, n),)*
                _ => abs_max_slice(p, w, n),
            }
        };
    }
    by_length!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16)
}

/// `Σ_{k<len} c_k t^k` by Horner, for a fixed `len ≤ N` (the same sums as [`eval`]).
#[inline(always)]
fn horner_fixed<const N: usize>(c: &[f64; N], len: usize, t: f64) -> f64 {
    let mut acc = 0.0;
    for k in (0..N).rev() {
        if k < len {
            acc = if k + 1 == len { c[k] } else { acc * t + c[k] };
        }
    }
    acc
}

/// [`abs_max`] for a polynomial of exactly `N` coefficients.
fn abs_max_fixed<const N: usize>(p: &[f64; N], w: f64, n: usize) -> (f64, f64) {
    // p' (N − 1 coefficients) and p'' (N − 2), as `deriv` computes them.
    let (mut dp, mut ddp) = ([0.0; N], [0.0; N]);
    for k in 1..N {
        dp[k - 1] = k as f64 * p[k];
    }
    for k in 1..N.saturating_sub(1) {
        ddp[k - 1] = k as f64 * dp[k];
    }
    let (l1, l2) = (N - 1, N.saturating_sub(2));
    let g = |t: f64| horner_fixed(p, N, t);
    let d = |t: f64| horner_fixed(&dp, l1, t);
    let dd = |t: f64| horner_fixed(&ddp, l2, t);
    // Newton on p' with p'' (kept in the bracket, secant fallback): quadratic convergence.
    scan(
        0.0,
        w,
        n,
        |t| (g(t), d(t)),
        g,
        |t0, t1, d0, _| loomkin_numeric::refine_root(t0, t1, d0 < 0.0, |t| (d(t), dd(t))),
    )
}

/// [`abs_max`] for any length, on the heap.
fn abs_max_slice(p: &[f64], w: f64, n: usize) -> (f64, f64) {
    let dp = deriv(p);
    let ddp = deriv(&dp);
    scan(
        0.0,
        w,
        n,
        |t| (eval(p, t), eval(&dp, t)),
        |t| eval(p, t),
        |t0, t1, d0, _| loomkin_numeric::refine_root(t0, t1, d0 < 0.0, |t| (eval(&dp, t), eval(&ddp, t))),
    )
}

/// An upper bound of `|p(t)|` on `[0, w]` that covers the rounding of [`abs_max`]'s sums, for `p`
/// of at most 8 coefficients (zeros past its degree): the Taylor coefficients `q_k` at the middle
/// `c = w/2` give `|p(c + τ)| ≤ Σ |q_k| (w/2)^k`, plus `1e-13·Σ |p_k| w^k`, far above the rounding
/// of the shift, of this sum and of a Horner sum of `p` on `[0, w]` (each below `32·ε·Σ |p_k| w^k`
/// for 8 coefficients). `+∞` or NaN when a sum is not finite.
pub(crate) fn abs_bound(p: &[f64; 8], w: f64) -> f64 {
    let c = 0.5 * w;
    let mut q = *p;
    // Repeated synthetic division by (t − c): q becomes the coefficients in τ = t − c.
    for i in 0..7 {
        for j in (i..7).rev() {
            q[j] += c * q[j + 1];
        }
    }
    let (mut taylor, mut scale) = (0.0, 0.0);
    for k in (0..8).rev() {
        taylor = taylor * c + q[k].abs();
        scale = scale * w + p[k].abs();
    }
    taylor + 1e-13 * scale
}

/// Largest `|g(t)|` on `[0, w]` and where it occurs, for `f(t) = (g(t), g'(t))`.
///
/// The sign changes of `g'` are bracketed on `n` equal sub-intervals and refined by regula falsi
/// ([`loomkin_numeric::illinois_root`]); both ends are included. `n` must be large enough to separate
/// the roots of `g'` (more than the polynomial degree; more for oscillating terms).
pub(crate) fn abs_max_by(w: f64, n: usize, f: impl Fn(f64) -> (f64, f64)) -> (f64, f64) {
    scan(0.0, w, n, &f, |t| f(t).0, |t0, t1, d0, d1| loomkin_numeric::illinois_root(t0, t1, d0, d1, |t| f(t).1))
}

/// Largest `|g(t)|` on `[a, b]` and where it occurs (the first of equal maxima): both ends, and
/// every sign change of `g'` between the ends of `n` equal sub-intervals, located by
/// `root(t0, t1, g'(t0), g'(t1))` and `g` taken there. `gd(t) = (g(t), g'(t))`; `n = 0` counts
/// as 1.
///
/// The one scan behind [`abs_max`], [`abs_max_by`] and the servo axis check: the callers pass in
/// their evaluators and root finder, so each is compiled with its own (the fixed-length kernels
/// keep their unrolled Horner sums).
#[inline(always)]
pub(crate) fn scan(
    a: f64,
    b: f64,
    n: usize,
    gd: impl Fn(f64) -> (f64, f64),
    g: impl Fn(f64) -> f64,
    mut root: impl FnMut(f64, f64, f64, f64) -> f64,
) -> (f64, f64) {
    let (g0, mut d0) = gd(a);
    let mut best = (g0.abs(), a);
    let mut take = |v: f64, t: f64| {
        if v.abs() > best.0 {
            best = (v.abs(), t);
        }
    };
    let n = n.max(1);
    let h = (b - a) / n as f64;
    let mut t0 = a;
    for i in 1..=n {
        let t1 = if i == n { b } else { a + i as f64 * h };
        let (g1, d1) = gd(t1);
        take(g1, t1);
        if d0 != 0.0 && d1 != 0.0 && (d0 < 0.0) != (d1 < 0.0) {
            let t = root(t0, t1, d0, d1);
            take(g(t), t);
        }
        t0 = t1;
        d0 = d1;
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shift_and_reflect_agree_with_direct_evaluation() {
        let p = [0.3, -1.2, 2.5, 0.7, -0.4, 1.1];
        let q = shift(&p, 0.37);
        let mut r = [0.0; 6];
        reflect_into(&p, 0.21, &mut r);
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

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig { cases: 256, ..Default::default() })]
        /// The bound holds over every value `abs_max` reports and a dense grid, for polynomials
        /// with large cancelling coefficients (as narrow spline segments have).
        #[test]
        fn abs_bound_is_an_upper_bound(
            p in proptest::collection::vec(-1e4f64..1e4, 1..=8),
            w in 1e-3f64..1.0,
        ) {
            let mut q = [0.0; 8];
            q[..p.len()].copy_from_slice(&p);
            let bound = abs_bound(&q, w);
            let (peak, _) = abs_max(&p, w, 2 * p.len());
            proptest::prop_assert!(bound >= peak, "{bound} < {peak}");
            for i in 0..=1000 {
                let t = w * i as f64 / 1000.0;
                proptest::prop_assert!(bound >= eval(&p, t).abs());
            }
        }
    }

    /// The fixed-length kernels equal the slice path bit for bit.
    #[test]
    fn abs_max_fixed_and_slice_paths_agree() {
        for len in 1..=16 {
            let p: Vec<f64> = (0..len).map(|k| ((k * 5 % 7) as f64 - 3.0) * 1.7f64.powi(k as i32 % 4)).collect();
            for w in [0.05, 0.7, 1.3] {
                let a = abs_max(&p, w, 2 * len + 2);
                let b = abs_max_slice(&p, w, 2 * len + 2);
                assert_eq!((a.0.to_bits(), a.1.to_bits()), (b.0.to_bits(), b.1.to_bits()), "len {len} w {w}");
            }
        }
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
