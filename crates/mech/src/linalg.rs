//! A small dense LU factorisation with partial pivoting for fixed-size systems of any `N`
//! (nalgebra's own LU needs type-level bounds that a `const N` generic cannot name).

use nalgebra::{SMatrix, SVector};

/// `P·M = L·U` of an `N × N` matrix, `L` unit lower triangular, stored in one matrix.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Lu<const N: usize> {
    lu: SMatrix<f64, N, N>,
    perm: [usize; N],
    det: f64,
}

impl<const N: usize> Lu<N> {
    /// Factorises `m`; a zero pivot leaves `det = 0` and makes [`Lu::solve`] return `None`.
    pub(crate) fn new(m: &SMatrix<f64, N, N>) -> Self {
        let mut lu = *m;
        let mut perm = [0usize; N];
        for (i, p) in perm.iter_mut().enumerate() {
            *p = i;
        }
        let mut det = 1.0;
        for k in 0..N {
            let mut piv = k;
            for i in k + 1..N {
                if lu[(i, k)].abs() > lu[(piv, k)].abs() {
                    piv = i;
                }
            }
            if piv != k {
                lu.swap_rows(piv, k);
                perm.swap(piv, k);
                det = -det;
            }
            let d = lu[(k, k)];
            det *= d;
            if d == 0.0 || !d.is_finite() {
                return Self { lu, perm, det: if d.is_finite() { 0.0 } else { d } };
            }
            for i in k + 1..N {
                let f = lu[(i, k)] / d;
                lu[(i, k)] = f;
                for j in k + 1..N {
                    lu[(i, j)] -= f * lu[(k, j)];
                }
            }
        }
        Self { lu, perm, det }
    }

    /// The determinant of the factorised matrix.
    pub(crate) fn det(&self) -> f64 {
        self.det
    }

    /// Solves `M x = b`; `None` for a singular matrix or a non-finite result.
    pub(crate) fn solve(&self, b: &SVector<f64, N>) -> Option<SVector<f64, N>> {
        if self.det == 0.0 || !self.det.is_finite() {
            return None;
        }
        let mut x = SVector::<f64, N>::zeros();
        for i in 0..N {
            let mut s = b[self.perm[i]];
            for j in 0..i {
                s -= self.lu[(i, j)] * x[j];
            }
            x[i] = s;
        }
        for i in (0..N).rev() {
            let mut s = x[i];
            for j in i + 1..N {
                s -= self.lu[(i, j)] * x[j];
            }
            x[i] = s / self.lu[(i, i)];
        }
        x.iter().all(|v| v.is_finite()).then_some(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lu_solves_and_gives_the_determinant() {
        let m = SMatrix::<f64, 3, 3>::new(0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0);
        let b = SVector::<f64, 3>::new(1.0, 2.0, 3.0);
        let lu = Lu::new(&m);
        let x = lu.solve(&b).unwrap();
        assert!((m * x - b).norm() < 1e-14);
        // det = 0·(1·1 − 0·0) − 2·(1·1 − 0·3) + 1·(1·0 − 1·3) = −5.
        assert!((lu.det() + 5.0).abs() < 1e-14);
        let sing = SMatrix::<f64, 2, 2>::new(1.0, 2.0, 2.0, 4.0);
        assert!(Lu::new(&sing).solve(&SVector::<f64, 2>::new(1.0, 1.0)).is_none());
    }
}
