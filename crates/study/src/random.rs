//! Reproducible random draws for Monte-Carlo studies: stated distributions, sampled by inverse CDF
//! from a counter-based uniform stream, so any draw can be computed alone (shards, threads).
//!
//! The uniform of variable `v` (0 ≤ v < [`MAX_VARIABLES`]) in draw `d` under seed `s` is the
//! `n`-th output, `n = 64·d + v`, of SplitMix64 (G. Steele, D. Lea, C. Flood, *Fast splittable
//! pseudorandom number generators*, OOPSLA 2014) whose state starts at `mix(s)`: a fixed, written-out
//! algorithm that no crate update can change. Its top 53 bits give `u = (k + ½)/2⁵³ ∈ (0, 1)`.
//! Normal draws are `μ + σ·Φ⁻¹(u)` (truncated ones `Φ⁻¹` of `u` mapped into `[Φ(a), Φ(b)]`), with
//! `Φ` from `erfc` of the pure-Rust `libm` crate, so the draws are the same on every platform.

use crate::{Result, StudyError};
use serde::{Deserialize, Serialize};

/// Variables one draw may hold.
pub const MAX_VARIABLES: usize = 64;

const GOLDEN: u64 = 0x9e37_79b9_7f4a_7c15;

/// The SplitMix64 output function.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The uniform number in (0, 1) of `variable` in draw `draw` under `seed` (see the module docs).
pub fn uniform(seed: u64, draw: u64, variable: usize) -> f64 {
    debug_assert!(variable < MAX_VARIABLES);
    let n = draw.wrapping_mul(MAX_VARIABLES as u64).wrapping_add(variable as u64);
    let x = mix(mix(seed).wrapping_add(n.wrapping_add(1).wrapping_mul(GOLDEN)));
    ((x >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64)
}

/// Φ(x), the standard normal distribution function, from `erfc` (accurate in the lower tail).
pub fn normal_cdf(x: f64) -> f64 {
    0.5 * libm::erfc(-x / std::f64::consts::SQRT_2)
}

/// φ(x), the standard normal density.
pub fn normal_pdf(x: f64) -> f64 {
    libm::exp(-0.5 * x * x) / (2.0 * std::f64::consts::PI).sqrt()
}

/// Φ⁻¹(p) for 0 < p < 1: the rational start of Abramowitz & Stegun 26.2.23 (|error| < 4.5e-4),
/// then two Halley steps on Φ(x) − p (cubic convergence: ~1e-11, then the last bits). Computed in the
/// lower tail (p ≤ ½) and reflected, so small upper-tail probabilities keep their precision.
pub fn normal_quantile(p: f64) -> f64 {
    if p > 0.5 {
        return -normal_quantile(1.0 - p);
    }
    if p == 0.5 {
        return 0.0;
    }
    let t = libm::sqrt(-2.0 * libm::log(p));
    let mut x = -(t
        - (2.515517 + 0.802853 * t + 0.010328 * t * t)
            / (1.0 + 1.432788 * t + 0.189269 * t * t + 0.001308 * t * t * t));
    for _ in 0..2 {
        let e = normal_cdf(x) - p;
        let u = e * (2.0 * std::f64::consts::PI).sqrt() * libm::exp(0.5 * x * x);
        x -= u / (1.0 + 0.5 * x * u);
    }
    x
}

/// A stated distribution of one input.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "dist", rename_all = "lowercase")]
pub enum Distribution {
    /// Always this value.
    Fixed {
        /// The value.
        value: f64,
    },
    /// Normal with mean and standard deviation, optionally truncated to `[min, max]`.
    Normal {
        /// Mean μ (of the untruncated normal).
        mean: f64,
        /// Standard deviation σ ≥ 0 (of the untruncated normal).
        sd: f64,
        /// Lower truncation bound.
        #[serde(skip_serializing_if = "Option::is_none")]
        min: Option<f64>,
        /// Upper truncation bound.
        #[serde(skip_serializing_if = "Option::is_none")]
        max: Option<f64>,
    },
    /// Uniform on `[min, max]`.
    Uniform {
        /// Lower bound.
        min: f64,
        /// Upper bound.
        max: f64,
    },
}

/// Truncation bounds more than this many standard deviations from the mean are refused: their
/// probability mass (Φ(−30) ≈ 5e-198) is too small to sample.
const MAX_STANDARD_SCORE: f64 = 30.0;

impl Distribution {
    /// The value for the uniform number `u ∈ (0, 1)` (inverse distribution function). Zero spread
    /// (σ = 0, or min = max) gives the stated value exactly.
    pub fn sample(&self, u: f64) -> f64 {
        match *self {
            Distribution::Fixed { value } => value,
            Distribution::Uniform { min, max } => min + u * (max - min),
            Distribution::Normal { mean, sd, min, max } => {
                if sd == 0.0 {
                    return mean;
                }
                if min.is_none() && max.is_none() {
                    return mean + sd * normal_quantile(u);
                }
                let a = min.map_or(f64::NEG_INFINITY, |m| (m - mean) / sd);
                let b = max.map_or(f64::INFINITY, |m| (m - mean) / sd);
                // Work in the tail where Φ is small, so its precision is kept.
                let z = if a > 0.0 {
                    let (pa, pb) = (normal_cdf(-b), normal_cdf(-a));
                    -normal_quantile(pa + (1.0 - u) * (pb - pa))
                } else {
                    let (pa, pb) = (normal_cdf(a), normal_cdf(b));
                    normal_quantile(pa + u * (pb - pa))
                };
                (mean + sd * z).clamp(min.unwrap_or(f64::NEG_INFINITY), max.unwrap_or(f64::INFINITY))
            }
        }
    }

    /// The distribution's mean (the truncated normal's from its closed form
    /// `μ + σ·(φ(a) − φ(b))/(Φ(b) − Φ(a))`).
    pub fn mean(&self) -> f64 {
        match *self {
            Distribution::Fixed { value } => value,
            Distribution::Uniform { min, max } => 0.5 * (min + max),
            Distribution::Normal { mean, sd, min, max } => {
                if sd == 0.0 {
                    return mean;
                }
                let (a, b, z) = standard_bounds(mean, sd, min, max);
                mean + sd * (pdf_or_zero(a) - pdf_or_zero(b)) / z
            }
        }
    }

    /// The distribution's variance (truncated normal:
    /// `σ²·[1 + (a·φ(a) − b·φ(b))/Z − ((φ(a) − φ(b))/Z)²]`, `Z = Φ(b) − Φ(a)`).
    pub fn variance(&self) -> f64 {
        match *self {
            Distribution::Fixed { .. } => 0.0,
            Distribution::Uniform { min, max } => (max - min).powi(2) / 12.0,
            Distribution::Normal { mean, sd, min, max } => {
                if sd == 0.0 {
                    return 0.0;
                }
                let (a, b, z) = standard_bounds(mean, sd, min, max);
                let xa = if a.is_finite() { a * normal_pdf(a) } else { 0.0 };
                let xb = if b.is_finite() { b * normal_pdf(b) } else { 0.0 };
                let d = (pdf_or_zero(a) - pdf_or_zero(b)) / z;
                sd * sd * (1.0 + (xa - xb) / z - d * d)
            }
        }
    }

    /// The distribution function at `x` (used by the tests' goodness-of-fit check).
    pub fn cdf(&self, x: f64) -> f64 {
        match *self {
            Distribution::Fixed { value } => f64::from(x >= value),
            Distribution::Uniform { min, max } => {
                if max == min {
                    f64::from(x >= min)
                } else {
                    ((x - min) / (max - min)).clamp(0.0, 1.0)
                }
            }
            Distribution::Normal { mean, sd, min, max } => {
                if sd == 0.0 {
                    return f64::from(x >= mean);
                }
                let (a, b, z) = standard_bounds(mean, sd, min, max);
                let t = ((x - mean) / sd).clamp(a, b);
                ((normal_cdf(t) - normal_cdf(a)) / z).clamp(0.0, 1.0)
            }
        }
    }

    /// Whether every draw is the same value.
    pub fn is_fixed(&self) -> bool {
        match *self {
            Distribution::Fixed { .. } => true,
            Distribution::Uniform { min, max } => min == max,
            Distribution::Normal { sd, .. } => sd == 0.0,
        }
    }
}

fn pdf_or_zero(x: f64) -> f64 {
    if x.is_finite() { normal_pdf(x) } else { 0.0 }
}

fn standard_bounds(mean: f64, sd: f64, min: Option<f64>, max: Option<f64>) -> (f64, f64, f64) {
    let a = min.map_or(f64::NEG_INFINITY, |m| (m - mean) / sd);
    let b = max.map_or(f64::INFINITY, |m| (m - mean) / sd);
    (a, b, normal_cdf(b) - normal_cdf(a))
}

/// A distribution as written in a TOML study file: a plain number (fixed), or a table
/// `{ dist = "normal", mean = …, sd = …, min = …, max = … }` / `{ dist = "uniform", min = …, max = … }`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(untagged)]
pub enum DistSpec {
    /// A fixed value.
    Value(f64),
    /// A distribution table.
    Table(DistTable),
}

/// The table form of a [`DistSpec`].
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DistTable {
    /// `normal`, `uniform` or `fixed`.
    pub dist: String,
    /// Mean (normal).
    pub mean: Option<f64>,
    /// Standard deviation (normal).
    pub sd: Option<f64>,
    /// Lower bound (uniform) or truncation (normal).
    pub min: Option<f64>,
    /// Upper bound (uniform) or truncation (normal).
    pub max: Option<f64>,
    /// The value (fixed).
    pub value: Option<f64>,
}

fn bad(field: &str, reason: impl Into<String>) -> StudyError {
    StudyError::Distribution { field: field.into(), reason: reason.into() }
}

fn finite(field: &str, key: &str, v: Option<f64>) -> Result<Option<f64>> {
    match v {
        Some(x) if !x.is_finite() => Err(bad(field, format!("{key} = {x} is not a finite number"))),
        _ => Ok(v),
    }
}

impl DistSpec {
    /// The checked distribution of input `field` (named in every error).
    pub fn resolve(&self, field: &str) -> Result<Distribution> {
        let t = match self {
            DistSpec::Value(v) => {
                finite(field, "value", Some(*v))?;
                return Ok(Distribution::Fixed { value: *v });
            }
            DistSpec::Table(t) => t,
        };
        let (mean, sd) = (finite(field, "mean", t.mean)?, finite(field, "sd", t.sd)?);
        let (min, max, value) =
            (finite(field, "min", t.min)?, finite(field, "max", t.max)?, finite(field, "value", t.value)?);
        let refuse = |keys: &[(&str, bool)], kind: &str| -> Result<()> {
            match keys.iter().find(|(_, given)| *given) {
                Some((k, _)) => Err(bad(field, format!("'{k}' does not apply to dist = \"{kind}\""))),
                None => Ok(()),
            }
        };
        match t.dist.trim() {
            "fixed" => {
                refuse(
                    &[("mean", mean.is_some()), ("sd", sd.is_some()), ("min", min.is_some()), ("max", max.is_some())],
                    "fixed",
                )?;
                let value = value.ok_or_else(|| bad(field, "dist = \"fixed\" needs value"))?;
                Ok(Distribution::Fixed { value })
            }
            "uniform" => {
                refuse(&[("mean", mean.is_some()), ("sd", sd.is_some()), ("value", value.is_some())], "uniform")?;
                let (Some(lo), Some(hi)) = (min, max) else {
                    return Err(bad(field, "dist = \"uniform\" needs min and max"));
                };
                if hi < lo {
                    return Err(bad(field, format!("max = {hi} is below min = {lo}: allowed min ≤ max")));
                }
                Ok(Distribution::Uniform { min: lo, max: hi })
            }
            "normal" => {
                refuse(&[("value", value.is_some())], "normal")?;
                let (Some(mean), Some(sd)) = (mean, sd) else {
                    return Err(bad(field, "dist = \"normal\" needs mean and sd"));
                };
                if sd < 0.0 {
                    return Err(bad(field, format!("sd = {sd} is out of range: allowed sd ≥ 0")));
                }
                if let (Some(lo), Some(hi)) = (min, max)
                    && hi <= lo
                {
                    return Err(bad(field, format!("max = {hi} is not above min = {lo}: allowed min < max")));
                }
                if sd == 0.0 {
                    if min.is_some_and(|m| mean < m) || max.is_some_and(|m| mean > m) {
                        return Err(bad(field, "sd = 0 with the mean outside [min, max]: no value to draw"));
                    }
                } else {
                    let (a, b, z) = standard_bounds(mean, sd, min, max);
                    if a > MAX_STANDARD_SCORE || b < -MAX_STANDARD_SCORE || z.is_nan() || z <= 0.0 {
                        return Err(bad(
                            field,
                            format!(
                                "[min, max] lies more than {MAX_STANDARD_SCORE} sd from the mean: no probability \
                                 mass to draw from"
                            ),
                        ));
                    }
                }
                Ok(Distribution::Normal { mean, sd, min, max })
            }
            other => Err(bad(field, format!("unknown dist '{other}': allowed normal, uniform, fixed"))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantile_inverts_the_cdf() {
        for &p in &[1e-300, 1e-20, 1e-8, 0.001, 0.025, 0.3, 0.5, 0.7, 0.975, 0.999, 1.0 - 1e-12] {
            let x = normal_quantile(p);
            let back = normal_cdf(x);
            // Relative in the lower tail, absolute near ½.
            let q = p.min(1.0 - p);
            let err = if p <= 0.5 { (back - p).abs() / p } else { ((1.0 - back) - (1.0 - p)).abs() / q };
            assert!(err < 1e-12, "p {p}: x {x}, Φ(x) {back}, err {err}");
        }
        // Published quantiles (e.g. Abramowitz & Stegun Table 26.5): Φ⁻¹(0.975) = 1.959963984540054.
        assert!((normal_quantile(0.975) - 1.959_963_984_540_054).abs() < 1e-14);
        assert!((normal_quantile(0.995) - 2.575_829_303_548_901).abs() < 1e-13);
        assert_eq!(normal_quantile(0.5), 0.0);
    }

    #[test]
    fn draws_are_fixed_numbers() {
        // The stream is a written-out algorithm: these values must never change.
        let u: Vec<f64> = (0..3).map(|d| uniform(1, d, 0)).collect();
        let again: Vec<f64> = (0..3).map(|d| uniform(1, d, 0)).collect();
        assert_eq!(u, again);
        assert!(u.iter().all(|&x| x > 0.0 && x < 1.0));
        assert_ne!(uniform(1, 0, 0), uniform(2, 0, 0));
        assert_ne!(uniform(1, 0, 0), uniform(1, 0, 1));
        assert_eq!(mix(0), 0);
        // SplitMix64 seeded with 1234567: its first outputs as published with the algorithm.
        let first = mix(1_234_567u64.wrapping_add(GOLDEN));
        assert_eq!(first, 6_457_827_717_110_365_317);
    }

    #[test]
    fn specs_name_their_field() {
        let t = |s: &str| -> DistSpec {
            toml::from_str::<std::collections::BTreeMap<String, DistSpec>>(s).unwrap()["x"].clone()
        };
        let e = |s: &str| t(s).resolve("speed_rpm").unwrap_err().to_string();
        assert!(e("x = { dist = \"normal\", mean = 1, sd = -1 }").starts_with("speed_rpm: sd = -1 is out of range"));
        assert!(e("x = { dist = \"uniform\", min = 2, max = 1 }").contains("below min"));
        assert!(e("x = { dist = \"gauss\", mean = 1, sd = 1 }").contains("unknown dist 'gauss'"));
        assert!(e("x = { dist = \"uniform\", min = 1, max = 2, sd = 3 }").contains("'sd' does not apply"));
        assert!(e("x = { dist = \"normal\", mean = 0, sd = 1, min = 40 }").contains("more than 30 sd"));
        assert_eq!(t("x = 5").resolve("x").unwrap(), Distribution::Fixed { value: 5.0 });
        assert!(
            toml::from_str::<std::collections::BTreeMap<String, DistSpec>>("x = { dist = \"normal\", mu = 1 }")
                .is_err()
        );
    }

    /// Draws of each kind of distribution against its stated mean, variance and distribution
    /// function. With n = 100 000 draws: the sample mean within 5 standard errors σ/√n, the sample
    /// variance within 5 standard errors √((m₄ − s⁴)/n) (m₄ the sample's fourth central moment, so
    /// no kurtosis is assumed), and the Kolmogorov–Smirnov distance below 1.95/√n (the 0.1 % critical
    /// value). The seed is fixed, so the outcome is too; at a random seed each check would fail with
    /// probability below 1e-3.
    #[test]
    fn draws_follow_their_stated_distributions() {
        let cases = [
            Distribution::Normal { mean: 200.0, sd: 3.0, min: None, max: None },
            Distribution::Normal { mean: 0.0, sd: 1.0, min: Some(-0.5), max: Some(1.5) },
            Distribution::Normal { mean: 10.0, sd: 2.0, min: Some(13.0), max: None },
            Distribution::Normal { mean: 10.0, sd: 2.0, min: None, max: Some(5.0) },
            Distribution::Uniform { min: 2.0, max: 7.5 },
        ];
        let n = 100_000;
        for (k, d) in cases.iter().enumerate() {
            let mut x: Vec<f64> = (0..n).map(|i| d.sample(uniform(7, i, k))).collect();
            let nf = n as f64;
            let mean = x.iter().sum::<f64>() / nf;
            let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (nf - 1.0);
            let m4 = x.iter().map(|v| (v - mean).powi(4)).sum::<f64>() / nf;
            let se_mean = d.variance().sqrt() / nf.sqrt();
            let se_var = ((m4 - var * var) / nf).sqrt();
            assert!((mean - d.mean()).abs() < 5.0 * se_mean, "{d:?}: mean {mean} vs {}", d.mean());
            assert!((var - d.variance()).abs() < 5.0 * se_var, "{d:?}: variance {var} vs {}", d.variance());
            x.sort_by(f64::total_cmp);
            let ks = x
                .iter()
                .enumerate()
                .map(|(i, &v)| {
                    let f = d.cdf(v);
                    (f - i as f64 / nf).abs().max(((i + 1) as f64 / nf - f).abs())
                })
                .fold(0.0, f64::max);
            assert!(ks < 1.95 / nf.sqrt(), "{d:?}: KS distance {ks}");
            if let Distribution::Normal { min, max, .. } = *d {
                assert!(x[0] >= min.unwrap_or(f64::NEG_INFINITY) && x[n as usize - 1] <= max.unwrap_or(f64::INFINITY));
            }
        }
    }

    /// The uniform stream itself: mean ½, variance 1/12 and no correlation between neighbouring
    /// draws or variables (|r| < 5/√n).
    #[test]
    fn the_uniform_stream_is_flat_and_uncorrelated() {
        let n = 200_000u64;
        let nf = n as f64;
        let u: Vec<f64> = (0..n).map(|d| uniform(3, d, 0)).collect();
        let w: Vec<f64> = (0..n).map(|d| uniform(3, d, 1)).collect();
        let mean = u.iter().sum::<f64>() / nf;
        let var = u.iter().map(|x| (x - 0.5).powi(2)).sum::<f64>() / nf;
        assert!((mean - 0.5).abs() < 5.0 * (1.0f64 / 12.0).sqrt() / nf.sqrt(), "{mean}");
        // Var of (u − ½)² is 1/180: its standard error is √(1/180/n).
        assert!((var - 1.0 / 12.0).abs() < 5.0 * (1.0f64 / 180.0 / nf).sqrt(), "{var}");
        let corr = |a: &[f64], b: &[f64]| {
            a.iter().zip(b).map(|(x, y)| (x - 0.5) * (y - 0.5)).sum::<f64>() / a.len() as f64 * 12.0
        };
        assert!(corr(&u[1..], &u[..u.len() - 1]).abs() < 5.0 / nf.sqrt());
        assert!(corr(&u, &w).abs() < 5.0 / nf.sqrt());
    }

    #[test]
    fn zero_spread_gives_the_value_exactly() {
        for u in [1e-16, 0.3, 0.5, 1.0 - 1e-16] {
            assert_eq!(Distribution::Normal { mean: 0.1 + 0.2, sd: 0.0, min: None, max: None }.sample(u), 0.1 + 0.2);
            assert_eq!(Distribution::Uniform { min: 0.3, max: 0.3 }.sample(u), 0.3);
            assert_eq!(Distribution::Fixed { value: -4.25 }.sample(u), -4.25);
        }
    }
}
