//! Experiment designs: explicit tables, stepped axes, full Cartesian grids and simplex grids
//! (relative lengths `k_T1 … k_Tn` that sum to one).

use crate::{Result, StudyError};
use loomkin_units::Range;
use serde::Serialize;

/// Largest number of points a generated design may hold (guards against typing a tiny step).
pub const MAX_POINTS: usize = 50_000_000;

/// Tolerance on the sum of relative lengths and on the end of a stepped axis.
const TOL: f64 = 1e-9;

/// An experiment table: named columns, one row per experiment, stored row-major in one buffer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Design {
    names: Vec<String>,
    values: Vec<f64>,
}

/// The values `min, min + step, …` up to `max` (inclusive within 1e-9·step), each computed as
/// `min + i·step` so that no rounding accumulates.
///
/// Errors when `step ≤ 0`, `max < min`, a bound is not finite, or the axis would exceed
/// [`MAX_POINTS`].
pub fn stepped_axis(field: &str, min: f64, max: f64, step: f64) -> Result<Vec<f64>> {
    Range::finite("").check(&format!("{field}.min"), min)?;
    Range::at_least(min, "").check(&format!("{field}.max"), max)?;
    Range::above(0.0, "").check(&format!("{field}.step"), step)?;
    let n = ((max - min) / step + TOL).floor();
    if n + 1.0 > MAX_POINTS as f64 {
        return Err(StudyError::TooLarge { field: field.into(), points: (n + 1.0) as u128, limit: MAX_POINTS });
    }
    Ok((0..=n as usize).map(|i| round_sig12(min + i as f64 * step).min(max)).collect())
}

/// `v` rounded to 12 significant digits, so that `0.05 + 2·0.05` is the lattice value `0.15`
/// (not `0.15000000000000002`) when printed; the change is below 1e-12 relative.
fn round_sig12(v: f64) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    let scale = 10f64.powi(11 - v.abs().log10().floor() as i32);
    if !scale.is_finite() || scale == 0.0 {
        return v;
    }
    let r = (v * scale).round() / scale;
    if r.is_finite() { r } else { v }
}

impl Design {
    /// A design from explicit rows; every row must have one value per name.
    pub fn from_rows<S: Into<String>>(names: impl IntoIterator<Item = S>, rows: &[Vec<f64>]) -> Result<Self> {
        let names: Vec<String> = names.into_iter().map(Into::into).collect();
        let mut values = Vec::with_capacity(rows.len() * names.len());
        for (i, r) in rows.iter().enumerate() {
            if r.len() != names.len() {
                return Err(StudyError::Shape { field: format!("rows[{i}]"), expected: names.len(), found: r.len() });
            }
            values.extend_from_slice(r);
        }
        Ok(Self { names, values })
    }

    /// The full Cartesian product of the axes (the first axis varies slowest).
    pub fn cartesian<S: Into<String>>(axes: impl IntoIterator<Item = (S, Vec<f64>)>) -> Result<Self> {
        let axes: Vec<(String, Vec<f64>)> = axes.into_iter().map(|(n, v)| (n.into(), v)).collect();
        let total = axes.iter().fold(1u128, |p, (_, v)| p.saturating_mul(v.len() as u128));
        if total > MAX_POINTS as u128 {
            return Err(StudyError::TooLarge { field: "cartesian".into(), points: total, limit: MAX_POINTS });
        }
        let dim = axes.len();
        let mut values = Vec::with_capacity(total as usize * dim);
        let mut idx = vec![0usize; dim];
        if dim > 0 && total > 0 {
            loop {
                values.extend(idx.iter().zip(&axes).map(|(&i, (_, v))| v[i]));
                // Odometer increment, last axis fastest.
                let mut d = dim;
                loop {
                    if d == 0 {
                        let names = axes.into_iter().map(|(n, _)| n).collect();
                        return Ok(Self { names, values });
                    }
                    d -= 1;
                    idx[d] += 1;
                    if idx[d] < axes[d].1.len() {
                        break;
                    }
                    idx[d] = 0;
                }
            }
        }
        Ok(Self { names: axes.into_iter().map(|(n, _)| n).collect(), values })
    }

    /// All vectors `(k_1, …, k_n)` with `k_1 … k_{n−1}` on the axis `min, min + step, … ≤ max` and
    /// `k_n = 1 − Σ k_i` also within `[min, max]` (±1e-9): the full cube of the free lengths cut to
    /// the simplex `Σ k = 1`. Columns are named `k1 … kn`.
    ///
    /// `parts ≥ 1`; `0 ≤ min ≤ max ≤ 1`; `step > 0`. One part gives the single row `k1 = 1`
    /// when `1` lies in `[min, max]`.
    pub fn simplex(parts: usize, min: f64, max: f64, step: f64) -> Result<Self> {
        Range::closed(1.0, 16.0, "").check("parts", parts as f64)?;
        Range::closed(0.0, 1.0, "").check("k.min", min)?;
        Range::closed(min, 1.0, "").check("k.max", max)?;
        let axis = stepped_axis("k", min, max, step)?;
        let cube = (axis.len() as u128).saturating_pow(parts as u32 - 1);
        if cube > 4 * MAX_POINTS as u128 {
            return Err(StudyError::TooLarge { field: "simplex".into(), points: cube, limit: MAX_POINTS });
        }
        let names: Vec<String> = (1..=parts).map(|i| format!("k{i}")).collect();
        let mut values = Vec::new();
        let mut row = vec![0.0; parts];
        fill(&axis, &mut row, 0, 0.0, min, max, &mut values);
        if values.len() / parts > MAX_POINTS {
            return Err(StudyError::TooLarge {
                field: "simplex".into(),
                points: (values.len() / parts) as u128,
                limit: MAX_POINTS,
            });
        }
        Ok(Self { names, values })
    }

    /// Every row of `self` combined with every value of a new column `name` (the new column
    /// varies fastest).
    pub fn cross(&self, name: impl Into<String>, axis: &[f64]) -> Result<Self> {
        let total = (self.len() as u128) * axis.len() as u128;
        if total > MAX_POINTS as u128 {
            return Err(StudyError::TooLarge { field: "cross".into(), points: total, limit: MAX_POINTS });
        }
        let mut names = self.names.clone();
        names.push(name.into());
        let mut values = Vec::with_capacity(total as usize * names.len());
        for r in self.rows() {
            for &a in axis {
                values.extend_from_slice(r);
                values.push(a);
            }
        }
        Ok(Self { names, values })
    }

    /// Column names.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Number of columns.
    pub fn dim(&self) -> usize {
        self.names.len()
    }

    /// Number of rows (experiments).
    pub fn len(&self) -> usize {
        if self.names.is_empty() { 0 } else { self.values.len() / self.names.len() }
    }

    /// Whether the design has no rows.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Row `i` (panics if `i ≥ len()`, like slice indexing).
    pub fn row(&self, i: usize) -> &[f64] {
        let d = self.dim();
        &self.values[i * d..(i + 1) * d]
    }

    /// The rows in order.
    pub fn rows(&self) -> impl ExactSizeIterator<Item = &[f64]> + '_ {
        self.values.chunks_exact(self.dim().max(1)).take(self.len())
    }
}

/// The number of rows [`Design::simplex`] makes, counted without making them (for an estimate of
/// memory and time before a run): the lattice points `u ∈ {0…L}^(n−1)` with `Σu` in the range that
/// keeps `k_n` within `[min, max]`, by inclusion–exclusion,
/// `#{Σu ≤ T} = Σ_j (−1)^j C(n−1, j) C(T − j(L+1) + n − 1, n − 1)`.
///
/// Exact up to the 1e-9 tolerance of the bounds and f64 rounding of the binomials (a large count
/// is an estimate to a few parts in 10¹⁶). Invalid arguments give 0 (the design itself refuses them).
pub fn simplex_rows(parts: usize, min: f64, max: f64, step: f64) -> f64 {
    let valid = (1..=16).contains(&parts)
        && (0.0..=1.0).contains(&min)
        && (min..=1.0).contains(&max)
        && step.is_finite()
        && step > 0.0;
    if !valid {
        return 0.0;
    }
    let l = ((max - min) / step + TOL).floor();
    let n = (parts - 1) as i32;
    if n == 0 {
        return if (min - TOL..=max + TOL).contains(&1.0) { 1.0 } else { 0.0 };
    }
    // Σk_i = n·min + step·Σu must lie in [1 − max, 1 − min] (±TOL).
    let lo = ((1.0 - max - f64::from(n) * min - TOL) / step).ceil().max(0.0);
    let hi = ((1.0 - min - f64::from(n) * min + TOL) / step).floor();
    if hi < lo || hi.is_nan() || lo.is_nan() || !l.is_finite() {
        return 0.0;
    }
    let binom = |a: f64, b: i32| (0..b).fold(1.0, |acc, i| acc * (a - f64::from(i)) / f64::from(i + 1));
    let at_most = |t: f64| -> f64 {
        (0..=n)
            .map(|j| {
                let r = t - f64::from(j) * (l + 1.0);
                if r < 0.0 {
                    0.0
                } else {
                    (if j % 2 == 0 { 1.0 } else { -1.0 }) * binom(f64::from(n), j) * binom(r + f64::from(n), n)
                }
            })
            .sum()
    };
    (at_most(hi) - at_most(lo - 1.0)).max(0.0).round()
}

fn fill(axis: &[f64], row: &mut [f64], i: usize, sum: f64, min: f64, max: f64, out: &mut Vec<f64>) {
    let n = row.len();
    if i + 1 == n {
        let last = 1.0 - sum;
        if last >= min - TOL && last <= max + TOL {
            // Rounded to 12 decimals so that 1 − Σ prints as the lattice value it is meant to be
            // (the sum stays within 1e-12 of one).
            row[i] = ((last * 1e12).round() / 1e12).clamp(min, max).max(0.0);
            out.extend_from_slice(row);
        }
        return;
    }
    for &k in axis {
        // The remaining parts need at least `min` each.
        if sum + k + (n - i - 1) as f64 * min > 1.0 + TOL {
            break;
        }
        row[i] = k;
        fill(axis, row, i + 1, sum + k, min, max, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simplex_rows_counts_what_simplex_makes() {
        // Counted by the formula against the rows made (an independent route: enumeration).
        for parts in 1..=5 {
            for (min, max, step) in
                [(0.05, 0.9, 0.05), (0.0, 1.0, 0.1), (0.01, 0.98, 0.03), (0.2, 0.5, 0.1), (0.0, 0.3, 0.07)]
            {
                let made = Design::simplex(parts, min, max, step).map(|d| d.len()).unwrap_or(0);
                assert_eq!(simplex_rows(parts, min, max, step), made as f64, "parts {parts}, {min}…{max} by {step}");
            }
        }
        assert_eq!(simplex_rows(3, 0.5, 0.2, 0.1), 0.0);
        assert_eq!(simplex_rows(0, 0.0, 1.0, 0.1), 0.0);
        // Large grids are counted without being made: 4 parts by 1e-4 is C(10003, 3).
        let big = simplex_rows(4, 0.0, 1.0, 1e-4);
        assert!((big / 166_766_685_001.0 - 1.0).abs() < 1e-9, "{big}");
    }

    #[test]
    fn simplex_rows_sum_to_one_and_count_matches_the_formula() {
        // Lattice points of Σ k = 1 with k_i ≥ 0 on step 1/m: C(m + n − 1, n − 1).
        let d = Design::simplex(3, 0.0, 1.0, 0.1).unwrap();
        assert_eq!(d.len(), 66); // C(12, 2)
        for r in d.rows() {
            assert!((r.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            assert!(r.iter().all(|&k| (0.0..=1.0).contains(&k)));
        }
        let d4 = Design::simplex(4, 0.0, 1.0, 0.05).unwrap();
        assert_eq!(d4.len(), 1771); // C(23, 3)
    }

    #[test]
    fn simplex_respects_bounds() {
        let d = Design::simplex(3, 0.1, 0.6, 0.1).unwrap();
        assert!(!d.is_empty());
        for r in d.rows() {
            assert!(r.iter().all(|&k| (0.1 - 1e-12..=0.6 + 1e-12).contains(&k)), "{r:?}");
        }
        // Brute force over the cube agrees with the count.
        let axis = stepped_axis("k", 0.1, 0.6, 0.1).unwrap();
        let mut n = 0;
        for &a in &axis {
            for &b in &axis {
                let c = 1.0 - a - b;
                if (0.1 - 1e-9..=0.6 + 1e-9).contains(&c) {
                    n += 1;
                }
            }
        }
        assert_eq!(d.len(), n);
    }

    #[test]
    fn cartesian_and_cross() {
        let d = Design::cartesian([("a", vec![1.0, 2.0]), ("b", vec![10.0, 20.0, 30.0])]).unwrap();
        assert_eq!(d.len(), 6);
        assert_eq!(d.row(0), &[1.0, 10.0]);
        assert_eq!(d.row(5), &[2.0, 30.0]);
        let e = d.cross("c", &[0.5, 0.25]).unwrap();
        assert_eq!(e.len(), 12);
        assert_eq!(e.row(1), &[1.0, 10.0, 0.25]);
        assert_eq!(e.names(), &["a", "b", "c"]);
    }

    #[test]
    fn axis_has_no_drift_and_rejects_bad_steps() {
        let a = stepped_axis("x", 0.005, 0.95, 0.005).unwrap();
        assert_eq!(a.len(), 190);
        assert!((a[189] - 0.95).abs() < 1e-15);
        assert!(stepped_axis("x", 0.0, 1.0, 0.0).is_err());
        assert!(stepped_axis("x", 1.0, 0.0, 0.1).is_err());
        assert!(stepped_axis("x", 0.0, 1.0, 1e-12).is_err());
        // Lattice values print as such (0.05 + 2·0.05 is 0.15000000000000002 in floating point).
        let b = stepped_axis("k", 0.05, 0.9, 0.05).unwrap();
        assert!(b.iter().enumerate().all(|(i, &v)| format!("{v}") == format!("{}", (5 + 5 * i) as f64 / 100.0)));
        let m = stepped_axis("deg", 180.0, 360.0, 0.1).unwrap();
        assert!(
            m.iter()
                .enumerate()
                .all(|(i, &v)| format!("{v}").len() <= 5 && (v - (180.0 + i as f64 * 0.1)).abs() < 1e-9)
        );
        assert!(Design::from_rows(["a", "b"], &[vec![1.0]]).is_err());
    }
}
