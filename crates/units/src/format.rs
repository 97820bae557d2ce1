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
    plain_or_exponent(v, to_12_digits(v))
}

/// A value a user typed, for a message that refuses it: as [`compact`] (plain for ordinary
/// magnitudes, the exponent form for huge or tiny ones) but with every digit the number needs to
/// read back as itself, so a value just past a bound is not shown rounded onto it.
///
/// ```
/// use loomkin_units::exact;
/// assert_eq!(exact(9.999999999999998e-4), "0.0009999999999999998");
/// assert_eq!(exact(1000.0000000000001), "1000.0000000000001");
/// assert_eq!(exact(5e-324), "5e-324");
/// assert_eq!(exact(-0.0), "0");
/// ```
pub fn exact(v: f64) -> String {
    if v.is_nan() {
        return "not-a-number".into();
    }
    if v.is_infinite() {
        return if v > 0.0 { "∞".into() } else { "-∞".into() };
    }
    plain_or_exponent(v, v)
}

/// `shown` (`v` or `v` rounded) written plainly where `v` is 0 or between 10⁻⁴ and 10⁹ in size,
/// else in exponent form; never `-0`.
fn plain_or_exponent(v: f64, shown: f64) -> String {
    // `+ 0.0` turns -0 into 0.
    if v == 0.0 || (1e-4..1e9).contains(&v.abs()) { format!("{}", shown + 0.0) } else { format!("{shown:e}") }
}

/// `v` with `decimals` places, as `format!("{v:.decimals$}")` writes it, except that a value
/// which rounds to zero never shows a minus sign (`-0.0004` to three places is `0.000`, not
/// `-0.000`).
///
/// ```
/// use loomkin_units::fixed;
/// assert_eq!(fixed(-0.0004, 3), "0.000");
/// assert_eq!(fixed(-0.0006, 3), "-0.001");
/// assert_eq!(fixed(2.345, 2), format!("{:.2}", 2.345));
/// ```
pub fn fixed(v: f64, decimals: usize) -> String {
    let text = format!("{v:.decimals$}");
    match text.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => text,
    }
}

/// `v` to 12 significant digits: a length worked out from a given one (`90 mm` through metres and a
/// ratio) without its representation noise (`89.99999999999999` → `90`).
///
/// ```
/// assert_eq!(loomkin_units::to_12_digits(0.08999999999999999 * 1e3), 90.0);
/// assert_eq!(loomkin_units::to_12_digits(95.40000000000001), 95.4);
/// ```
pub fn to_12_digits(v: f64) -> f64 {
    format!("{v:.11e}").parse().unwrap_or(v)
}

/// A value for a note, a title or a message in words: four significant digits, no trailing zeros
/// (`12.35`, `0.001235`, `1.235e−7`, `−3`, with a true minus sign), where [`compact`] keeps up to
/// twelve for values a user types back.
///
/// ```
/// use loomkin_units::sig4;
/// assert_eq!(sig4(0.00123456), "0.001235");
/// assert_eq!(sig4(-3.0), "−3");
/// assert_eq!(sig4(1.23456e-7), "1.235e−7");
/// ```
pub fn sig4(v: f64) -> String {
    if !v.is_finite() {
        return if v.is_nan() {
            "not-a-number".into()
        } else if v > 0.0 {
            "∞".into()
        } else {
            "−∞".into()
        };
    }
    if v == 0.0 {
        return "0".into();
    }
    let mag = v.abs().log10().floor();
    let text = if (-3.0..6.0).contains(&mag) {
        let decimals = (3.0 - mag).max(0.0) as usize;
        let t = format!("{v:.decimals$}");
        if t.contains('.') { t.trim_end_matches('0').trim_end_matches('.').to_string() } else { t }
    } else {
        format!("{v:.3e}")
    };
    text.replace('-', "−")
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
