//! The catalogue of named laws.

use crate::polynomial::{PolySegment, format_poly_segments, parse_poly_segments};
use crate::shape::{format_segments, parse_segments};
use crate::{AccelPiece, EndCondition, Law, LawError, Result, Shape, ShapeSegment, Sine};
use loomkin_units::Range;
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, PI};

/// The modified trapezoid's ramp fraction, `1e-6 ≤ ramp ≤ 0.25`.
///
/// Above 0.25 the plateaus would be negative. The lower end is derived from the joints: they sit
/// at sums of the widths, each rounded to within an ulp of 1 (2.2e-16), so a ramp of width `r`
/// has a relative error of about `2.2e-16 / r` in its width and phase — and so in the jerk
/// `Cj = Ca·π/(2r)` and in the continuity of `a` judged to [`crate::CONTINUITY_TOL`] = 1e-9. That
/// error stays below 1e-9 for `r ≥ 2.2e-7`; 1e-6 keeps a margin of 4. (Measured against 40-digit
/// quadrature: Cj is off by 6e-9 at 1e-8 and the law is wrongly reported C1 at 1e-9; at 1e-20
/// the crossover had no width left and the build failed.) Below 1e-6 the law is constant
/// acceleration for every purpose: Ca = 4 + 5.8e-6.
pub const RAMP: Range = Range::closed(1e-6, 0.25, "");

/// A law chosen from the catalogue with its parameters; [`LawSpec::build`] makes the [`Law`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "law", rename_all = "kebab-case")]
pub enum LawSpec {
    /// Constant acceleration then constant deceleration (parabolic).
    ConstantAcceleration,
    /// Simple harmonic: `s = (1 − cos πx)/2`.
    Harmonic,
    /// Cycloidal: `s = x − sin(2πx)/(2π)`.
    Cycloidal,
    /// 3-4-5 polynomial: `s = 10x³ − 15x⁴ + 6x⁵`.
    Poly345,
    /// 4-5-6-7 polynomial: `s = 35x⁴ − 84x⁵ + 70x⁶ − 20x⁷`.
    Poly4567,
    /// Modified trapezoid: quarter-sine ramps of relative width `ramp`, constant plateaus,
    /// a half-cosine crossover of width `2·ramp`.
    ModifiedTrapezoid {
        /// Ramp fraction, 1e-6 ≤ ramp ≤ 0.25 (standard 1/8); see [`RAMP`] for the lower end.
        ramp: f64,
    },
    /// Modified sine: quarter sines over the first and last eighths, a half cosine in between.
    ModifiedSine,
    /// A general piecewise-acceleration law from (relative length, shape) segments.
    Piecewise {
        /// The segments (lengths sum to 1).
        segments: Vec<ShapeSegment>,
    },
    /// A polynomial-acceleration law: segments of relative length with the acceleration a
    /// polynomial of degree ≤ 5 in each segment's relative coordinate (any polynomial law, e.g. a
    /// servo spline law, in a cycle file).
    Polynomial {
        /// The segments (lengths sum to 1).
        segments: Vec<PolySegment>,
    },
}

/// One line of the catalogue.
#[derive(Debug, Clone, Copy)]
pub struct CatalogueEntry {
    /// Name used in the library and the CLI.
    pub name: &'static str,
    /// One-line description.
    pub description: &'static str,
    /// Parameters as `key=default (range)`, or empty.
    pub params: &'static str,
    /// The parameters' keys (`ramp`, `segments`), listed by the law itself.
    pub keys: &'static [&'static str],
    /// Whether the law needs its parameters (no defaults: `segments`).
    pub required: bool,
}

impl CatalogueEntry {
    /// Whether the law takes the parameter `key`.
    pub fn has_param(&self, key: &str) -> bool {
        self.keys.contains(&key)
    }
}

/// A parameter's value: a number (`ramp`) or text (`segments`); untagged in JSON, so
/// `{"ramp": 0.1}` and `{"segments": "0.5:constant:1,…"}`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(untagged)]
pub enum ParamValue {
    /// A number.
    Number(f64),
    /// Text.
    Text(String),
}

impl ParamValue {
    /// The value as the text [`LawSpec::parse`] reads.
    pub fn text(&self) -> String {
        match self {
            ParamValue::Number(v) => v.to_string(),
            ParamValue::Text(t) => t.clone(),
        }
    }
}

/// Every named law, in catalogue order.
pub const CATALOGUE: &[CatalogueEntry] = &[
    CatalogueEntry {
        name: "constant-acceleration",
        description: "parabolic: +a then −a",
        params: "",
        keys: &[],
        required: false,
    },
    CatalogueEntry {
        name: "harmonic",
        description: "simple harmonic, s = (1 − cos πx)/2",
        params: "",
        keys: &[],
        required: false,
    },
    CatalogueEntry {
        name: "cycloidal", description: "s = x − sin(2πx)/2π", params: "", keys: &[], required: false
    },
    CatalogueEntry { name: "poly345", description: "3-4-5 polynomial", params: "", keys: &[], required: false },
    CatalogueEntry { name: "poly4567", description: "4-5-6-7 polynomial", params: "", keys: &[], required: false },
    CatalogueEntry {
        name: "modified-trapezoid",
        description: "sine ramps, constant plateaus",
        params: "ramp=0.125 (1e-6 ≤ ramp ≤ 0.25)",
        keys: &["ramp"],
        required: false,
    },
    CatalogueEntry {
        name: "modified-sine",
        description: "quarter sines over 1/8, half cosine between",
        params: "",
        keys: &[],
        required: false,
    },
    CatalogueEntry {
        name: "piecewise",
        description: "general piecewise acceleration",
        params: "segments=LEN:SHAPE[:LEVEL…],… (lengths sum to 1)",
        keys: &["segments"],
        required: true,
    },
    CatalogueEntry {
        name: "polynomial",
        description: "polynomial acceleration per segment (e.g. a servo spline law)",
        params: "segments=LEN:c0[:c1…],… (a = c0 + c1·u + … in each segment, degree ≤ 5, lengths sum to 1)",
        keys: &["segments"],
        required: true,
    },
];

/// The catalogue's laws that build without parameters (their defaults), in catalogue order, whose
/// continuity class in a dwell-rise-dwell cycle ([`Law::continuity`]) is at least `class`: the laws
/// that remove a jump of the derivative of order `class` (advice names them).
pub fn laws_of_class(class: i32) -> Vec<LawSpec> {
    CATALOGUE
        .iter()
        .filter(|e| !e.required)
        .filter_map(|e| LawSpec::parse::<&str, &str>(e.name, &[]).ok())
        .filter(|spec| spec.build().is_ok_and(|law| law.continuity().class >= class))
        .collect()
}

fn names() -> String {
    CATALOGUE.iter().map(|e| e.name).collect::<Vec<_>>().join(", ")
}

impl LawSpec {
    /// The catalogue name.
    pub fn name(&self) -> &'static str {
        match self {
            LawSpec::ConstantAcceleration => "constant-acceleration",
            LawSpec::Harmonic => "harmonic",
            LawSpec::Cycloidal => "cycloidal",
            LawSpec::Poly345 => "poly345",
            LawSpec::Poly4567 => "poly4567",
            LawSpec::ModifiedTrapezoid { .. } => "modified-trapezoid",
            LawSpec::ModifiedSine => "modified-sine",
            LawSpec::Piecewise { .. } => "piecewise",
            LawSpec::Polynomial { .. } => "polynomial",
        }
    }

    /// The parameters as `key=value` pairs (empty for laws without parameters).
    pub fn params(&self) -> Vec<(String, String)> {
        match self {
            LawSpec::ModifiedTrapezoid { ramp } => vec![("ramp".into(), ramp.to_string())],
            LawSpec::Piecewise { segments } => vec![("segments".into(), format_segments(segments))],
            LawSpec::Polynomial { segments } => vec![("segments".into(), format_poly_segments(segments))],
            _ => Vec::new(),
        }
    }

    /// The parameters, typed: numbers as numbers (`ramp`), text as text (`segments`).
    pub fn param_values(&self) -> std::collections::BTreeMap<String, ParamValue> {
        match self {
            LawSpec::ModifiedTrapezoid { ramp } => [("ramp".to_string(), ParamValue::Number(*ramp))].into(),
            _ => self.params().into_iter().map(|(k, v)| (k, ParamValue::Text(v))).collect(),
        }
    }

    /// A human label: the name and its parameters.
    pub fn label(&self) -> String {
        let p = self.params();
        if p.is_empty() {
            self.name().to_string()
        } else {
            let ps: Vec<String> = p.iter().map(|(k, v)| format!("{k}={v}")).collect();
            format!("{} ({})", self.name(), ps.join(", "))
        }
    }

    /// [`LawSpec::parse`] with the parameters as a TOML table, as loom and cycle files write them
    /// (`params = { ramp = 0.1 }`: numbers or text).
    pub fn parse_table(name: &str, params: &std::collections::BTreeMap<String, toml::Value>) -> Result<Self> {
        let params: Vec<(&str, String)> = params
            .iter()
            .map(|(k, v)| (k.as_str(), v.as_str().map_or_else(|| v.to_string(), str::to_string)))
            .collect();
        LawSpec::parse(name, &params)
    }

    /// Looks a law up by name and applies `key=value` parameters.
    pub fn parse<K: AsRef<str>, V: AsRef<str>>(name: &str, params: &[(K, V)]) -> Result<Self> {
        let mut spec = match name.trim() {
            "constant-acceleration" => LawSpec::ConstantAcceleration,
            "harmonic" => LawSpec::Harmonic,
            "cycloidal" => LawSpec::Cycloidal,
            "poly345" => LawSpec::Poly345,
            "poly4567" => LawSpec::Poly4567,
            "modified-trapezoid" => LawSpec::ModifiedTrapezoid { ramp: 0.125 },
            "modified-sine" => LawSpec::ModifiedSine,
            "piecewise" => LawSpec::Piecewise { segments: Vec::new() },
            "polynomial" => LawSpec::Polynomial { segments: Vec::new() },
            other => {
                return Err(LawError::UnknownLaw { name: other.into(), known: names() });
            }
        };
        // A parameter given twice is refused rather than the last one silently kept: two variants
        // of one law are compared by running the command once per variant.
        for (i, (k, _)) in params.iter().enumerate() {
            let k = k.as_ref().trim();
            if params[..i].iter().any(|(earlier, _)| earlier.as_ref().trim() == k) {
                return Err(LawError::Parse {
                    field: k.into(),
                    text: format!("{k} given twice"),
                    expected: "each parameter once (compare two variants of a law with one run each)".into(),
                });
            }
        }
        for (k, v) in params {
            let (k, v) = (k.as_ref().trim(), v.as_ref().trim());
            match (&mut spec, k) {
                (LawSpec::ModifiedTrapezoid { ramp }, "ramp") => {
                    *ramp = v.parse().map_err(|_| LawError::Parse {
                        field: "ramp".into(),
                        text: v.into(),
                        expected: "a number, 1e-6 ≤ ramp ≤ 0.25".into(),
                    })?;
                }
                (LawSpec::Piecewise { segments }, "segments") => *segments = parse_segments(v, "segments")?,
                (LawSpec::Polynomial { segments }, "segments") => *segments = parse_poly_segments(v, "segments")?,
                (s, _) => {
                    let allowed = CATALOGUE.iter().find(|e| e.name == s.name()).map(|e| e.params).unwrap_or("");
                    return Err(LawError::UnknownParam {
                        law: s.name().into(),
                        key: k.into(),
                        allowed: if allowed.is_empty() { "none".into() } else { allowed.into() },
                    });
                }
            }
        }
        spec.validate()?;
        Ok(spec)
    }

    /// Checks the parameters' ranges.
    pub fn validate(&self) -> Result<()> {
        match self {
            LawSpec::ModifiedTrapezoid { ramp } => {
                RAMP.check("ramp", *ramp)?;
                Ok(())
            }
            LawSpec::Piecewise { segments } if segments.is_empty() => Err(LawError::Parse {
                field: "segments".into(),
                text: String::new(),
                expected: "segments=LEN:SHAPE[:LEVEL…],… e.g. 0.5:constant:1,0.5:constant:-1".into(),
            }),
            LawSpec::Piecewise { segments } => check_lengths(segments.iter().map(|s| s.length)),
            LawSpec::Polynomial { segments } if segments.is_empty() => Err(LawError::Parse {
                field: "segments".into(),
                text: String::new(),
                expected: "segments=LEN:c0[:c1…],… e.g. 0.5:1,0.5:-1".into(),
            }),
            LawSpec::Polynomial { segments } => {
                for (i, seg) in segments.iter().enumerate() {
                    if seg.accel.is_empty() || seg.accel.len() > crate::polynomial::MAX_ACCEL_DEGREE + 1 {
                        return Err(LawError::Parse {
                            field: format!("segments[{i}]"),
                            text: format!("{} coefficients", seg.accel.len()),
                            expected: "1 to 6 acceleration coefficients".into(),
                        });
                    }
                }
                check_lengths(segments.iter().map(|s| s.length))
            }
            _ => Ok(()),
        }
    }

    /// Whether the law is odd-symmetric about its middle, `s(1 − x) = 1 − s(x)`, by construction.
    pub fn is_symmetric(&self) -> bool {
        !matches!(self, LawSpec::Piecewise { .. } | LawSpec::Polynomial { .. })
    }

    /// Builds the law in closed form, normalised to `s(1) = 1` and at rest at both ends.
    pub fn build(&self) -> Result<Law> {
        self.validate()?;
        let rest = EndCondition::Rest;
        let shapes = |segs: &[(f64, Shape)]| -> Vec<AccelPiece> {
            segs.iter().filter(|(w, _)| *w > 0.0).map(|(w, s)| s.to_piece(*w)).collect()
        };
        match self {
            LawSpec::ConstantAcceleration => {
                Law::from_accel_pieces(&[AccelPiece::poly(0.5, &[1.0]), AccelPiece::poly(0.5, &[-1.0])], rest, "law")
            }
            LawSpec::Harmonic => Law::from_accel_pieces(
                &[AccelPiece::with_sine(1.0, &[], Sine { amp: 1.0, omega: PI, phase: FRAC_PI_2 })],
                rest,
                "law",
            ),
            LawSpec::Cycloidal => Law::from_accel_pieces(
                &[AccelPiece::with_sine(1.0, &[], Sine { amp: 1.0, omega: 2.0 * PI, phase: 0.0 })],
                rest,
                "law",
            ),
            LawSpec::Poly345 => {
                Law::from_accel_pieces(&[AccelPiece::poly(1.0, &[0.0, 60.0, -180.0, 120.0])], rest, "law")
            }
            LawSpec::Poly4567 => Law::from_accel_pieces(
                &[AccelPiece::poly(1.0, &[0.0, 0.0, 420.0, -1680.0, 2100.0, -840.0])],
                rest,
                "law",
            ),
            LawSpec::ModifiedTrapezoid { ramp } => {
                let r = *ramp;
                let plateau = 0.5 - 2.0 * r;
                let segs = [
                    (r, Shape::SineRamp { from: 0.0, to: 1.0 }),
                    (plateau, Shape::Constant { level: 1.0 }),
                    (2.0 * r, Shape::HalfCosine { from: 1.0, to: -1.0 }),
                    (plateau, Shape::Constant { level: -1.0 }),
                    (1.0 - (r + 2.0 * plateau + 2.0 * r), Shape::CosineRamp { from: -1.0, to: 0.0 }),
                ];
                Law::from_accel_pieces(&shapes(&segs), rest, "law")
            }
            LawSpec::ModifiedSine => {
                let segs = [
                    (0.125, Shape::SineRamp { from: 0.0, to: 1.0 }),
                    (0.75, Shape::HalfCosine { from: 1.0, to: -1.0 }),
                    (0.125, Shape::CosineRamp { from: -1.0, to: 0.0 }),
                ];
                Law::from_accel_pieces(&shapes(&segs), rest, "law")
            }
            LawSpec::Piecewise { segments } => {
                let pieces: Vec<AccelPiece> = segments.iter().map(|s| s.shape.to_piece(s.length)).collect();
                Law::from_accel_pieces(&pieces, rest, "segments")
            }
            LawSpec::Polynomial { segments } => {
                let pieces: Vec<AccelPiece> = segments.iter().map(|s| s.to_piece(s.length)).collect();
                Law::from_accel_pieces(&pieces, rest, "segments")
            }
        }
    }
}

/// Each relative length in (0, 1], and their sum 1 (±1e-9).
fn check_lengths(lengths: impl Iterator<Item = f64>) -> Result<()> {
    let mut sum = 0.0;
    for (i, l) in lengths.enumerate() {
        Range::open_closed(0.0, 1.0, "").check(&format!("segments[{i}].length"), l)?;
        sum += l;
    }
    if (sum - 1.0).abs() > 1e-9 {
        return Err(LawError::LengthsDoNotSumToOne { field: "segments".into(), sum });
    }
    Ok(())
}

#[cfg(test)]
mod duplicate_tests {
    use super::*;

    #[test]
    fn a_parameter_given_twice_is_refused() {
        let e = LawSpec::parse("modified-trapezoid", &[("ramp", "0.1"), ("ramp", "0.2")]).unwrap_err().to_string();
        assert!(e.contains("ramp given twice"), "{e}");
        assert!(LawSpec::parse("modified-trapezoid", &[("ramp", "0.1")]).is_ok());
    }
}

#[cfg(test)]
mod param_tests {
    use super::*;

    #[test]
    fn each_law_lists_the_parameters_it_reads() {
        for e in CATALOGUE {
            // The description names exactly the listed keys.
            let described: Vec<&str> = e
                .params
                .split_whitespace()
                .filter_map(|w| w.split_once('='))
                .map(|(k, _)| k)
                .filter(|k| !k.is_empty())
                .collect();
            assert_eq!(described, e.keys, "{}", e.name);
            let bare = LawSpec::parse::<&str, &str>(e.name, &[]);
            assert_eq!(bare.is_err(), e.required, "{}", e.name);
            if let Ok(spec) = bare {
                let keys: Vec<String> = spec.param_values().into_keys().collect();
                assert_eq!(keys, e.keys, "{}", e.name);
                // A key the law does not list is refused.
                assert!(LawSpec::parse(e.name, &[("bogus", "1")]).is_err());
            }
        }
        let spec = LawSpec::parse("modified-trapezoid", &[("ramp", "0.1")]).unwrap();
        assert_eq!(spec.param_values()["ramp"], ParamValue::Number(0.1));
    }
}
