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
}
