//! The one number format of loomkin's messages.

/// A number for a message: plain for ordinary magnitudes, in exponent form for huge or tiny ones, so
/// that `1e308` is not written out in 309 digits, with at most 12 significant digits so that
/// representation noise (`0.1 + 0.2`) does not show. The largest finite values stand for open bounds
/// and print as `∞`; NaN prints as `not-a-number` (never `NaN`).
///
/// ```
/// use loomkin_units::compact;
/// assert_eq!(compact(1e308), "1e308");
/// assert_eq!(compact(0.1 + 0.2), "0.3");
/// assert_eq!(compact(-2.5e-7), "-2.5e-7");
/// assert_eq!(compact(f64::MAX), "∞");
/// ```
pub fn compact(v: f64) -> String {
    if v.is_nan() {
        return "not-a-number".into();
    }
    if v >= f64::MAX {
        return "∞".into();
    }
    if v <= f64::MIN {
        return "-∞".into();
    }
    let rounded: f64 = format!("{v:.11e}").parse().unwrap_or(v);
    // `+ 0.0` turns -0 into 0.
    if v == 0.0 || (1e-4..1e9).contains(&v.abs()) { format!("{}", rounded + 0.0) } else { format!("{rounded:e}") }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_stay_short_and_never_nan() {
        assert_eq!(compact(0.25), "0.25");
        assert_eq!(compact(-0.0), "0");
        assert_eq!(compact(123_456_789.0), "123456789");
        assert_eq!(compact(1.5e9), "1.5e9");
        assert_eq!(compact(5e-324), "5e-324");
        assert_eq!(compact(f64::NAN), "not-a-number");
        assert_eq!(compact(f64::INFINITY), "∞");
        assert_eq!(compact(f64::NEG_INFINITY), "-∞");
    }
}
