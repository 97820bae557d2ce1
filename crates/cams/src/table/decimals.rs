//! Fixed decimals for every column of a table, chosen from the resolution it needs.

use serde::Serialize;

/// The number of decimals of each column of a written table.
///
/// Every number is rounded to its column's decimals before anything is computed from it, so the
/// file holds exactly the values the reported error was computed with, and is printed with exactly
/// that many decimals: no exponent, no float noise (`12.5000`, never `1.2499999999999996e1`), and
/// no negative zero.
///
/// The choice ([`Decimals::choose`]):
/// * master angle `X`: the fewest decimals (0 to 9) that write every planned master angle exactly
///   (to 1e-9°); with a tolerance at least 3 (points on a 0.001° grid);
/// * slave position `Y`: the fewest decimals whose last digit is at most `10⁻⁶` of the largest
///   slave position (the stroke); with a tolerance `T` at most `T/100`; with a step at most
///   `r_v·h` and `r_a·h²` (`h` the shortest interval, `r_v`, `r_a` the last digits of V and A);
/// * `V`, `A`, `J`: the fewest decimals whose last digit is at most `10⁻⁶` of the column's largest
///   magnitude over the motion; with a step, V's also at most `r_a·h`;
/// * poly5 coefficients: per column, from the resolutions of Y, V, A and the shortest interval
///   (see [`super::poly5::coeff_decimals`]).
///
/// Each count of X, Y, V, A, J is clamped to 0…12.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Decimals {
    /// Master angle (deg).
    pub master: usize,
    /// Slave position.
    pub y: usize,
    /// Slave velocity dY/dX.
    pub v: usize,
    /// Slave acceleration d²Y/dX².
    pub a: usize,
    /// Slave jerk d³Y/dX³.
    pub j: usize,
}

/// Relative resolution of every column.
pub const RELATIVE_RESOLUTION: f64 = 1e-6;

/// The fewest decimals `d ≤ 12` with `10⁻ᵈ ≤ resolution` (0 for a non-positive resolution's
/// column of zeros, 12 at most).
pub fn decimals_for(resolution: f64) -> usize {
    if !(resolution.is_finite() && resolution > 0.0) {
        return 0;
    }
    let d = (-resolution.log10() - 1e-9).ceil();
    d.clamp(0.0, 12.0) as usize
}

/// The fewest decimals (0 to 9) that write every value of `xs` to within 1e-9 (9 if none does).
pub fn decimals_exact(xs: impl IntoIterator<Item = f64>) -> usize {
    let xs: Vec<f64> = xs.into_iter().collect();
    (0..=9).find(|&d| xs.iter().all(|&x| (round(x, d) - x).abs() <= 1e-9)).unwrap_or(9)
}

/// `x` rounded to `d` decimals (the nearest double to the decimal number), with `-0` made `0`.
pub fn round(x: f64, d: usize) -> f64 {
    let p = 10f64.powi(d as i32);
    let r = (x * p).round() / p;
    r + 0.0
}

/// `x` rounded to `d` decimals and printed with exactly `d` decimals.
pub fn fixed(x: f64, d: usize) -> String {
    format!("{:.*}", d, round(x, d))
}

impl Decimals {
    /// Chooses the decimals (see the type's documentation): `masters` the planned master angles,
    /// `stroke` the largest |slave position|, `peaks` the largest |V|, |A|, |J|, `tolerance` the
    /// position tolerance when points are placed for one. With a step, the planned masters' shortest
    /// interval `h` also bounds Y's last digit by `r_v·h` and `r_a·h²` and V's by `r_a·h` (`r_v`, `r_a`
    /// the last digits of V and A), so that the rounding of one column does not move the interpolated
    /// derivatives by more than their own resolution.
    pub fn choose(masters: &[f64], stroke: f64, peaks: [f64; 3], tolerance: Option<f64>) -> Self {
        let mut master = decimals_exact(masters.iter().copied());
        let a = decimals_for(RELATIVE_RESOLUTION * peaks[1]);
        let mut rv = RELATIVE_RESOLUTION * peaks[0];
        let mut ry = RELATIVE_RESOLUTION * stroke;
        match tolerance {
            Some(t) => {
                master = master.max(3);
                ry = ry.min(t / 100.0);
            }
            None => {
                let h = masters.windows(2).map(|w| w[1] - w[0]).filter(|d| *d > 0.0).fold(f64::INFINITY, f64::min);
                if h.is_finite() && peaks[1] > 0.0 {
                    let ra = 10f64.powi(-(a as i32));
                    rv = rv.min(ra * h);
                    ry = ry.min(ra * h * h);
                }
                if h.is_finite() && peaks[0] > 0.0 {
                    ry = ry.min(10f64.powi(-(decimals_for(rv) as i32)) * h);
                }
            }
        }
        Self { master, y: decimals_for(ry), v: decimals_for(rv), a, j: decimals_for(RELATIVE_RESOLUTION * peaks[2]) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_prints_exact_decimals_without_noise_or_negative_zero() {
        assert_eq!(fixed(12.499999999999996, 4), "12.5000");
        assert_eq!(fixed(-0.0, 3), "0.000");
        assert_eq!(fixed(-0.00001, 3), "0.000");
        assert_eq!(fixed(-1.23456, 2), "-1.23");
        // A rounded value parses back to the same double.
        for &(x, d) in &[(0.1 + 0.2, 6), (123.456789123, 9), (-7.000000001, 4)] {
            let r = round(x, d);
            assert_eq!(fixed(x, d).parse::<f64>().unwrap(), r);
        }
    }

    #[test]
    fn decimals_follow_the_resolution() {
        assert_eq!(decimals_for(1e-4), 4);
        assert_eq!(decimals_for(2e-4), 4);
        assert_eq!(decimals_for(9.9e-5), 5);
        assert_eq!(decimals_for(10.0), 0);
        assert_eq!(decimals_exact([0.0, 18.75, 150.0]), 2);
        assert_eq!(decimals_exact([1.0 / 3.0]), 9);
        let d = Decimals::choose(&[0.0, 150.0], 100.0, [1.3, 0.05, 0.003], None);
        assert_eq!((d.master, d.y, d.v, d.a, d.j), (0, 4, 6, 8, 9));
        // A 0.1° step: V's last digit at most 1e-8·0.1, Y's at most 1e-9·0.1 and 1e-8·0.01.
        let d = Decimals::choose(&[0.0, 0.1, 0.2], 100.0, [1.3, 0.05, 0.003], None);
        assert_eq!((d.v, d.y), (9, 10));
        let d = Decimals::choose(&[0.0, 150.0], 100.0, [1.3, 0.05, 0.003], Some(1e-5));
        assert_eq!((d.master, d.y), (3, 7));
    }
}
