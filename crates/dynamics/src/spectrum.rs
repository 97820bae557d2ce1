//! The residual-vibration spectrum of a law: the vibration a rise leaves in the following dwell,
//! against the ratio of motion time to natural period.
//!
//! A rise of stroke `h` over the motion time `T`, starting at rest (`x = s`, `x' = s'`), drives the
//! error `y = x − s` through `y'' + 2ζω_n y' + ω_n² y = −s''`. At the end of the rise the dwell starts
//! with `(δ, δ') = (y(T), y'(T))` and vibrates with amplitude `A = √(δ² + ((δ' + ζω_nδ)/ω_d)²)`. In
//! terms of the law `S(u)` (`s = h·S(t/T)`) the ratio `A/h` depends only on `r = T/T_n = f_n·T` and ζ:
//! the spectrum. For the cycloidal law, undamped,
//!
//! $$ \frac{A}{h} = \frac{|\sin πr|}{π\,r\,|r^2 - 1|} $$
//!
//! (Duhamel's integral of `a = (2πh/T²)·sin(2πt/T)`; `1/2` at `r = 1`), zero at every integer `r ≥ 2`.

use crate::excitation::Excitation;
use crate::oscillator::Oscillator;
use crate::trajectory::Channel;
use loomkin_laws::Law;
use loomkin_units::{Field, Range};

/// `ratio`: a spectrum's ratio of motion time to natural period T·f_n, 0 < r < 10⁴ (at 10⁴ natural
/// periods a motion the residual is rounding noise).
pub const RATIO: Field = Field::new(
    "ratio",
    Range::open(0.0, 1e4, ""),
    "Ratio of motion time to natural period T·f_n: 0 < r < 10⁴; 0.5:10:0.01 (FROM:TO:STEP) when left out.",
);
/// How many ratios a spectrum takes: 1 … 10⁶.
pub const RATIOS: Field = Field::count("ratio", Range::closed(1.0, 1e6, ""), "Ratios of one spectrum: 1 … 10⁶.");
/// The ratios of a spectrum when none are given, FROM:TO:STEP: 0.5 … 10 every 0.01 (the range of
/// VDI 2149's charts, fine enough to show each minimum).
pub const DEFAULT_RATIOS: &str = "0.5:10:0.01";

/// The ratios of [`DEFAULT_RATIOS`], as `dyn spectrum` takes them when none are given.
pub fn default_ratios() -> Vec<f64> {
    match loomkin_units::Span::parse(RATIO.name, DEFAULT_RATIOS, RATIO.range) {
        Ok(span) => span.values().collect(),
        Err(e) => unreachable!("the default ratios are a span: {e}"),
    }
}

/// `A/h` (fraction of the stroke) left by `law` at the ratio `r = T/T_n` (> 0) with damping ratio `zeta`.
pub fn residual_ratio(law: &Law, r: f64, zeta: f64) -> f64 {
    // Work with T = 1 s, so that f_n = r Hz.
    let exc = Excitation::rise_then_dwell(law, 1.0);
    let osc = Oscillator::new(std::f64::consts::TAU * r, zeta);
    let ch = Channel { osc, g_a: -1.0, g_s: 0.0, g_0: 0.0 };
    let mut y = (0.0, 0.0);
    for (i, p) in exc.pieces.iter().enumerate() {
        if p.dwell {
            break;
        }
        y = osc.solve(&ch.forcing(&exc, i), p.duration, y.0, y.1).end();
    }
    osc.amplitude(y.0, y.1)
}

/// The spectrum at every ratio of `ratios`.
pub fn spectrum(law: &Law, zeta: f64, ratios: &[f64]) -> Vec<f64> {
    ratios.iter().map(|&r| residual_ratio(law, r, zeta)).collect()
}

/// The cycloidal law's undamped spectrum in closed form, `|sin πr|/(π r |r² − 1|)` (1/2 at r = 1).
pub fn cycloidal_undamped(r: f64) -> f64 {
    let d = r * r - 1.0;
    if d.abs() < 1e-6 {
        // sin πr ≈ −π(r − 1)(1 − π²(r−1)²/6) and r² − 1 = (r − 1)(r + 1).
        let e = r - 1.0;
        return (1.0 - std::f64::consts::PI.powi(2) * e * e / 6.0) / (r * (r + 1.0));
    }
    (std::f64::consts::PI * r).sin().abs() / (std::f64::consts::PI * r * d.abs())
}

#[cfg(test)]
mod tests {
    use super::*;
    use loomkin_laws::{CATALOGUE, LawSpec, gauss_legendre};
    use proptest::prelude::*;

    fn cycloid() -> Law {
        LawSpec::Cycloidal.build().unwrap()
    }

    #[test]
    fn cycloid_vanishes_at_integer_ratios() {
        let law = cycloid();
        for n in 2..=12 {
            let a = residual_ratio(&law, n as f64, 0.0);
            assert!(a < 1e-13, "r = {n}: {a:e}");
        }
        assert!((residual_ratio(&law, 1.0, 0.0) - 0.5).abs() < 1e-13);
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]
        #[test]
        fn cycloid_matches_its_closed_form(r in 0.05f64..30.0) {
            let a = residual_ratio(&cycloid(), r, 0.0);
            let b = cycloidal_undamped(r);
            prop_assert!((a - b).abs() < 1e-12 * (1.0 + b), "r {}: {} vs {}", r, a, b);
        }

        /// Every catalogue law, undamped: the closed form against Duhamel's integral
        /// `A = |∫₀ᵀ s''(τ)·e^{iωτ} dτ| / ω` by Gauss–Legendre quadrature on each segment.
        #[test]
        fn catalogue_matches_duhamel_quadrature(i in 0usize..7, r in 0.2f64..8.0) {
            let spec = LawSpec::parse::<&str, &str>(CATALOGUE[i].name, &[]).unwrap();
            let law = spec.build().unwrap();
            let w = std::f64::consts::TAU * r;
            let nodes = gauss_legendre(40);
            let (mut re, mut im) = (0.0, 0.0);
            for seg in law.segments() {
                let (a, b) = (seg.x0(), seg.x1());
                for &(x, wt) in &nodes {
                    let t = 0.5 * (a + b) + 0.5 * (b - a) * x;
                    let acc = seg.eval(t).a;
                    re += 0.5 * (b - a) * wt * acc * (w * t).cos();
                    im += 0.5 * (b - a) * wt * acc * (w * t).sin();
                }
            }
            let duhamel = re.hypot(im) / w;
            let closed = residual_ratio(&law, r, 0.0);
            prop_assert!((duhamel - closed).abs() < 1e-11 * (1.0 + closed), "{}: r {} {} vs {}", CATALOGUE[i].name, r, closed, duhamel);
        }
    }
}

#[cfg(test)]
mod field_tests {
    use super::*;

    /// The default span is 0.5, 0.51, …, 10 (951 ratios), inside the range.
    #[test]
    fn the_default_ratios_span_the_charts() {
        let r = default_ratios();
        assert_eq!(r.len(), 951);
        assert_eq!((r[0], r[950]), (0.5, 10.0));
        assert!(r.iter().all(|&x| RATIO.range.contains(x)));
        assert!(RATIOS.check_count(r.len()).is_ok());
    }
}
