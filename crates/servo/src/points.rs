//! Definition points: validation, parsing and the built-in default set.

use crate::{Result, ServoError};
use loomkin_units::compact;

/// Fewest definition points the spline accepts (the paper uses N = 7).
pub const MIN_POINTS: usize = 4;

/// Smallest allowed gap between consecutive X (keeps the spline system well conditioned).
///
/// A gap written at the bound in decimals (`0.1:…,0.1001:…`) is accepted although its binary
/// difference may fall a few ulps short of `1e-4`: the check allows a relative slack of 1e-9.
pub const MIN_GAP: f64 = 1e-4;

/// Relative slack of the [`MIN_GAP`] check, far above the rounding of a decimal difference
/// (~1e-12 relative for X below 0.5) and far below any change in the spline's conditioning.
const GAP_SLACK: f64 = 1e-9;

/// Smallest allowed largest |Y|: the law is scale-free in Y (it is normalised to a unit
/// stroke), so only a set of all-but-zero Y, whose normalisation would overflow, is refused.
pub const MIN_Y_MAX: f64 = 1e-12;

/// Tolerance within which the fixed end values (X₁ = 0, X_N = 0.5, Y₁ = Y_N = 0) are accepted
/// and then snapped exactly.
pub const END_TOL: f64 = 1e-9;

/// The built-in default definition points (N = 7).
///
/// The default definition points in `--def` notation: [`default_points`], the cycloid's
/// acceleration sin(2πX) at X = j/12 (the paper does not list its points).
pub const DEFAULT_DEF: &str = "0:0,0.0833333333333333:0.5,0.1666666666666667:0.8660254037844386,0.25:1,\
0.3333333333333333:0.8660254037844387,0.4166666666666667:0.5,0.5:0";

/// The paper does not list its seven points, so the default is the acceleration of the cycloidal
/// law, `Y = sin(2πX)`, sampled at `X = j/12`, `j = 0…6`: a smooth "original" from which the
/// optimiser starts. In `--def` notation:
/// `0:0,0.083333:0.5,0.166667:0.866025,0.25:1,0.333333:0.866025,0.416667:0.5,0.5:0`.
///
/// [`DEFAULT_DEF`] is the same points as front ends take them (`--def`), written as the CLI has
/// always written them, so a call without definition points gives the same numbers everywhere.
pub fn default_points() -> Vec<[f64; 2]> {
    (0..7)
        .map(|j| {
            let x = j as f64 / 12.0;
            let y = if j == 0 || j == 6 { 0.0 } else { (2.0 * std::f64::consts::PI * x).sin() };
            [x, y]
        })
        .collect()
}

/// Checks definition points and returns them with the fixed end values snapped exactly.
///
/// Rules (point numbers `j` are 1-based, as in the paper):
/// - at least [`MIN_POINTS`] points, every coordinate finite;
/// - `X₁ = 0`, `X_N = 0.5`, X strictly increasing with gaps of at least [`MIN_GAP`];
/// - `Y₁ = Y_N = 0`, every other `Y ∈ [−1, 1]`, the largest |Y| at least [`MIN_Y_MAX`] (the paper uses `[0, 1]`; negative values are
///   allowed so that a designer can shape the acceleration freely, the net motion must still be
///   a rise).
pub fn check_points(points: &[[f64; 2]]) -> Result<Vec<[f64; 2]>> {
    let n = points.len();
    if n < MIN_POINTS {
        return Err(ServoError::TooFewPoints { count: n, min: MIN_POINTS });
    }
    let bad = |j: usize, reason: String| {
        let [x, y] = points[j];
        ServoError::Point { index: j + 1, x, y, reason }
    };
    let mut out = points.to_vec();
    for (j, &[x, y]) in points.iter().enumerate() {
        if !x.is_finite() || !y.is_finite() {
            return Err(bad(j, "X and Y must be finite numbers".into()));
        }
    }
    if points[0][0].abs() > END_TOL {
        return Err(bad(0, "the first point must have X = 0".into()));
    }
    if (points[n - 1][0] - 0.5).abs() > END_TOL {
        return Err(bad(n - 1, "the last point must have X = 0.5 (the middle of the motion)".into()));
    }
    for j in [0, n - 1] {
        if points[j][1].abs() > END_TOL {
            return Err(bad(j, "the first and last points must have Y = 0".into()));
        }
    }
    out[0] = [0.0, 0.0];
    out[n - 1] = [0.5, 0.0];
    for j in 1..n - 1 {
        if !(out[j][0] > 0.0 && out[j][0] < 0.5) {
            return Err(bad(j, "X must lie inside (0, 0.5) (the first half of the motion)".into()));
        }
    }
    for j in 1..n {
        let (prev, x) = (out[j - 1][0], out[j][0]);
        if x - prev < MIN_GAP * (1.0 - GAP_SLACK) {
            return Err(bad(
                j,
                format!("X must increase: it must be at least X{} + {MIN_GAP} = {}", j, compact(prev + MIN_GAP)),
            ));
        }
    }
    for j in 1..n - 1 {
        let y = out[j][1];
        if !(-1.0..=1.0).contains(&y) {
            return Err(bad(j, "Y must lie in [-1, 1]".into()));
        }
    }
    let y_max = out.iter().map(|p| p[1].abs()).fold(0.0, f64::max);
    if y_max < MIN_Y_MAX {
        return Err(ServoError::NoRise {
            reason: format!(
                "the largest |Y| is {}: the acceleration is (almost) zero, there is no motion \
                 (Y are relative accelerations: give at least one |Y| ≥ {MIN_Y_MAX}, e.g. in [0, 1] as the paper)",
                compact(y_max)
            ),
        });
    }
    Ok(out)
}

/// Reads definition points written as `"X:Y,X:Y,…"` (spaces allowed; `;` also separates points).
pub fn parse_points(text: &str) -> Result<Vec<[f64; 2]>> {
    let expected = "definition points as X:Y,X:Y,… (e.g. 0:0,0.1:0.8,0.25:1,0.4:0.6,0.5:0)";
    let mut out = Vec::new();
    for item in text.split([',', ';']).map(str::trim).filter(|s| !s.is_empty()) {
        let err = || ServoError::Parse { field: "def".into(), text: item.into(), expected: expected.into() };
        let (x, y) = item.split_once(':').ok_or_else(err)?;
        let x: f64 = x.trim().parse().map_err(|_| err())?;
        let y: f64 = y.trim().parse().map_err(|_| err())?;
        out.push([x, y]);
    }
    if out.is_empty() {
        return Err(ServoError::Parse { field: "def".into(), text: text.into(), expected: expected.into() });
    }
    Ok(out)
}

/// Writes definition points as `"X:Y,X:Y,…"` (shortest round-trip decimal form).
pub fn format_points(points: &[[f64; 2]]) -> String {
    points.iter().map(|[x, y]| format!("{x}:{y}")).collect::<Vec<_>>().join(",")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_format_round_trip() {
        let p = default_points();
        assert_eq!(parse_points(&format_points(&p)).unwrap(), p);
        assert_eq!(check_points(&p).unwrap(), p);
    }

    #[test]
    fn bad_points_are_named() {
        let mut p = default_points();
        p[3][0] = p[2][0];
        match check_points(&p) {
            Err(ServoError::Point { index: 4, .. }) => {}
            other => panic!("{other:?}"),
        }
        let mut p = default_points();
        p[2][1] = 1.5;
        assert!(matches!(check_points(&p), Err(ServoError::Point { index: 3, .. })));
        let mut p = default_points();
        p[6][1] = 0.1;
        assert!(matches!(check_points(&p), Err(ServoError::Point { index: 7, .. })));
        let mut p = default_points();
        p[1][0] = f64::NAN;
        assert!(matches!(check_points(&p), Err(ServoError::Point { index: 2, .. })));
        let mut p = default_points();
        p[6][0] = 0.6;
        assert!(matches!(check_points(&p), Err(ServoError::Point { index: 7, .. })));
        assert!(matches!(check_points(&p[..3]), Err(ServoError::TooFewPoints { count: 3, .. })));
        // An X outside the half is named as such, not as the next point's order.
        let mut p = default_points();
        p[1][0] = 0.6;
        let e = check_points(&p).unwrap_err();
        assert!(matches!(e, ServoError::Point { index: 2, .. }) && e.to_string().contains("(0, 0.5)"), "{e}");
        assert!(matches!(parse_points("0:0,0.2"), Err(ServoError::Parse { .. })));
        // A gap of exactly 1e-4 as written in decimals is at the bound and accepted (its binary
        // difference 0.1001 − 0.1 is 0.99999999999999e-4); one just below it is refused.
        let at_bound = [[0.0, 0.0], [0.1, 1.0], [0.1001, 0.5], [0.2, 1.0], [0.5, 0.0]];
        const { assert!(0.1001f64 - 0.1 < MIN_GAP, "the case must exercise a difference short of 1e-4") };
        assert_eq!(check_points(&at_bound).unwrap(), at_bound);
        let below = [[0.0, 0.0], [0.1, 1.0], [0.10009999, 0.5], [0.2, 1.0], [0.5, 0.0]];
        assert!(matches!(check_points(&below), Err(ServoError::Point { index: 3, .. })));
        let zero = [[0.0, 0.0], [0.1, 0.0], [0.3, 0.0], [0.5, 0.0]];
        assert!(matches!(check_points(&zero), Err(ServoError::NoRise { .. })));
    }
}

#[cfg(test)]
mod default_def_tests {
    use super::*;

    /// The text of the default points reads back as the points to the last bit but one.
    #[test]
    fn the_default_text_is_the_default_points() {
        let text = parse_points(DEFAULT_DEF).unwrap();
        let pts = default_points();
        assert_eq!(text.len(), pts.len());
        for (a, b) in text.iter().zip(&pts) {
            assert!(
                (a[0] - b[0]).abs() <= 2.0 * f64::EPSILON && (a[1] - b[1]).abs() <= 2.0 * f64::EPSILON,
                "{a:?} {b:?}"
            );
        }
    }
}
