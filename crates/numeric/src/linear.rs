//! Linear systems of the splines.

/// Solves the tridiagonal system `lower[i]·z[i−1] + diag[i]·z[i] + upper[i]·z[i+1] = rhs[i]` by
/// the Thomas algorithm (no pivoting: for strictly diagonally dominant systems, as the cubic
/// splines' are).
/// `lower[0]` and `upper[n−1]` are ignored. Returns the solution in `rhs`.
pub fn solve_tridiagonal(lower: &[f64], diag: &[f64], upper: &[f64], rhs: &mut [f64]) {
    let n = rhs.len();
    let mut c = vec![0.0; n];
    let mut beta = diag[0];
    rhs[0] /= beta;
    for i in 1..n {
        c[i - 1] = upper[i - 1] / beta;
        beta = diag[i] - lower[i] * c[i - 1];
        rhs[i] = (rhs[i] - lower[i] * rhs[i - 1]) / beta;
    }
    for i in (0..n - 1).rev() {
        rhs[i] -= c[i] * rhs[i + 1];
    }
}

/// Solves the cyclic tridiagonal system `lower[i]·z[i−1] + diag[i]·z[i] + upper[i]·z[i+1] = rhs[i]`
/// with indices taken mod n (the corners `lower[0]` and `upper[n−1]` couple the first and last
/// unknowns, as a periodic spline's equations do), n ≥ 3, by the Sherman–Morrison formula on two
/// [`solve_tridiagonal`] solves. Like it, no pivoting: for strictly diagonally dominant systems.
pub fn solve_cyclic_tridiagonal(lower: &[f64], diag: &[f64], upper: &[f64], rhs: &[f64]) -> Vec<f64> {
    let n = diag.len();
    assert!(n >= 3 && lower.len() == n && upper.len() == n && rhs.len() == n, "n ≥ 3 equations of equal length");
    // A = T + u·vᵀ with u = (γ, 0, …, 0, upper[n−1]) and v = (1, 0, …, 0, lower[0]/γ); T is A
    // without its corners and with the first and last diagonal entries corrected.
    let (corner_low, corner_up) = (upper[n - 1], lower[0]);
    let gamma = -diag[0];
    let mut d = diag.to_vec();
    d[0] -= gamma;
    d[n - 1] -= corner_low * corner_up / gamma;
    let mut x = rhs.to_vec();
    solve_tridiagonal(lower, &d, upper, &mut x);
    let mut z = vec![0.0; n];
    z[0] = gamma;
    z[n - 1] = corner_low;
    solve_tridiagonal(lower, &d, upper, &mut z);
    let fact = (x[0] + corner_up * x[n - 1] / gamma) / (1.0 + z[0] + corner_up * z[n - 1] / gamma);
    for (xi, zi) in x.iter_mut().zip(&z) {
        *xi -= fact * zi;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tridiagonal_matches_dense_product() {
        let lo = [0.0, 1.0, 0.5, 2.0];
        let di = [4.0, 5.0, 3.0, 6.0];
        let up = [1.0, 2.0, 0.7, 0.0];
        let z = [1.0, -2.0, 0.5, 3.0];
        let mut r: Vec<f64> = (0..4)
            .map(|i| {
                di[i] * z[i] + if i > 0 { lo[i] * z[i - 1] } else { 0.0 } + if i < 3 { up[i] * z[i + 1] } else { 0.0 }
            })
            .collect();
        solve_tridiagonal(&lo, &di, &up, &mut r);
        for i in 0..4 {
            assert!((r[i] - z[i]).abs() < 1e-14);
        }
    }

    #[test]
    fn cyclic_tridiagonal_matches_the_dense_product() {
        for n in [3, 4, 7, 40] {
            let lo: Vec<f64> = (0..n).map(|i| 1.0 + 0.1 * i as f64).collect();
            let up: Vec<f64> = (0..n).map(|i| 0.7 - 0.01 * i as f64).collect();
            let di: Vec<f64> = (0..n).map(|i| 4.0 + 0.2 * i as f64).collect();
            let r: Vec<f64> = (0..n).map(|i| (i as f64).cos()).collect();
            let x = solve_cyclic_tridiagonal(&lo, &di, &up, &r);
            for i in 0..n {
                let lhs = lo[i] * x[(i + n - 1) % n] + di[i] * x[i] + up[i] * x[(i + 1) % n];
                assert!((lhs - r[i]).abs() < 1e-13, "n {n}, row {i}: {lhs} vs {}", r[i]);
            }
        }
    }
}
