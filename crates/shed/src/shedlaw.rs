//! The heald-frame law over one pick: a motion angle `φ_дв`, a dwell `φ_вр = 360° − φ_дв`, and the
//! acceleration of the motion given by its positive phase (relative lengths `k_Ti` and shapes) and
//! a negative phase that mirrors it or is given separately.

use crate::{Result, ShedError};
use loomkin_laws::{AccelPiece, EndCondition, Law, Segment, Shape, ShapeSegment, format_segments, parse_segments};
use loomkin_units::{Field, Range};
use serde::{Deserialize, Serialize};

/// Tolerance on the sum of the relative lengths.
const SUM_TOL: f64 = 1e-9;

/// The negative phase of the acceleration.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum NegativePhase {
    /// The odd mirror of the positive phase about the middle of the motion, `a(1 − x) = −a(x)`:
    /// a symmetric law (the positive phase is the first half of the motion).
    Mirrored,
    /// A separate negative phase: an asymmetric law.
    Given {
        /// Segments of the negative phase (lengths relative to the negative phase, summing to 1).
        /// Their levels are relative: the phase is rescaled so that the velocity returns to zero.
        segments: Vec<ShapeSegment>,
        /// Fraction of the motion taken by the positive phase, `φ_пу / φ_дв`, in (0, 1).
        positive_fraction: f64,
    },
}

/// A heald-frame law: the frame moves over the motion angle `φ_дв` and dwells over
/// `φ_вр = 360° − φ_дв` of every main-shaft turn (one pick).
///
/// The acceleration over the motion is piecewise: the positive phase is split into segments of
/// relative length `k_Ti = φ_i / φ_пу` (each in [0, 1], summing to 1; a zero length drops the
/// segment) with a [`Shape`] each; the negative phase mirrors it ([`NegativePhase::Mirrored`]) or is
/// given separately. [`ShedLaw::build`] integrates it in closed form into a normalised rise of the
/// law core (`x = θ/φ_дв ∈ [0, 1]`, `s ∈ [0, 1]` the fraction of the frame's stroke).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ShedLaw {
    motion_deg: f64,
    positive: Vec<ShapeSegment>,
    negative: NegativePhase,
}

/// A list of segments in a TOML file: either the text form `LEN:SHAPE[:LEVEL…],…` or an array of
/// tables `{ length = …, shape = "…", from = …, to = … }`.
fn read_segments(value: toml::Value, field: &str) -> Result<Vec<ShapeSegment>> {
    match value {
        toml::Value::String(t) => Ok(parse_segments(&t, field)?),
        toml::Value::Array(items) => items
            .into_iter()
            .enumerate()
            .map(|(i, item)| {
                ShapeSegment::deserialize(item).map_err(|e| ShedError::Parse {
                    field: format!("{field}[{i}]"),
                    reason: format!(
                        "{} (expected a table {{ length = …, shape = \"…\", from = …, to = … }})",
                        e.message()
                    ),
                })
            })
            .collect(),
        other => Err(ShedError::Parse {
            field: field.into(),
            reason: format!(
                "found {}, expected a text \"LEN:SHAPE[:LEVEL…],…\" or an array of tables {{ length, shape, … }}",
                other.type_str()
            ),
        }),
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SpecFile {
    motion_deg: f64,
    positive: toml::Value,
    negative: Option<toml::Value>,
    positive_fraction: Option<f64>,
}

fn check_lengths(field: &str, segs: &[ShapeSegment]) -> Result<()> {
    if segs.is_empty() {
        return Err(ShedError::NotARise { field: field.into(), reason: "no segments given".into() });
    }
    for (i, s) in segs.iter().enumerate() {
        Range::closed(0.0, 1.0, "").check(&format!("{field}[{i}].length"), s.length)?;
    }
    let sum: f64 = segs.iter().map(|s| s.length).sum();
    if (sum - 1.0).abs() > SUM_TOL {
        return Err(ShedError::LengthsDoNotSumToOne { field: field.into(), sum });
    }
    Ok(())
}

/// The motion angle's range, `1° ≤ φ_дв ≤ 360°`.
///
/// The upper end is one turn. The lower end is derived from what is reported of a law: its
/// angles (motion, dwell, conditional dwell, window) are printed and compared to 0.001°, so a
/// motion of `Φ` degrees is resolved to `0.001/Φ` of itself; at 1° that is 0.1 %, below it the
/// criteria are no longer read to three significant digits, while the frame's velocity and
/// acceleration (∝ 1/Φ, 1/Φ²) run away (the `dobby` law over 0.001°: 3.6·10⁵ m/s). No loom moves a
/// frame in less than a degree of the main shaft.
pub const MOTION_DEG: Range = Range::closed(1.0, 360.0, "deg");

/// The motion angle as an input (`shed law/table/pareto/best --motion-deg`): [`MOTION_DEG`], no
/// default (a law's own angle, or the study's list, when left out).
pub const MOTION_DEG_FIELD: Field = Field::new(
    "motion_deg",
    MOTION_DEG,
    "Motion angle φ_дв of a shedding law, deg: 1 … 360 (one turn; below 1° the criteria are no longer read to \
     three significant digits and the frame's acceleration runs away).",
);

/// Checks a motion angle against [`MOTION_DEG_FIELD`].
pub fn check_motion_deg(motion_deg: f64) -> Result<f64> {
    Ok(MOTION_DEG_FIELD.check(motion_deg)?)
}

/// The mirror image of positive-phase segments: reversed order, each shape reversed in time and
/// negated, so that `a(1 − x) = −a(x)`.
pub fn mirror(positive: &[ShapeSegment]) -> Vec<ShapeSegment> {
    positive
        .iter()
        .rev()
        .map(|s| ShapeSegment { length: s.length, shape: positive_zero(s.shape.reversed().scaled(-1.0)) })
        .collect()
}

/// The same shape with every `-0` level written as `0` (so that texts read `0`, not `-0`).
fn positive_zero(shape: Shape) -> Shape {
    let z = |v: f64| v + 0.0;
    match shape {
        Shape::Zero => Shape::Zero,
        Shape::Constant { level } => Shape::Constant { level: z(level) },
        Shape::Linear { from, to } => Shape::Linear { from: z(from), to: z(to) },
        Shape::SineRamp { from, to } => Shape::SineRamp { from: z(from), to: z(to) },
        Shape::CosineRamp { from, to } => Shape::CosineRamp { from: z(from), to: z(to) },
        Shape::HalfCosine { from, to } => Shape::HalfCosine { from: z(from), to: z(to) },
        Shape::SineArc { peak } => Shape::SineArc { peak: z(peak) },
    }
}

/// Net area `∫ a du` of a shape over a segment of the given width.
pub(crate) fn shape_area(shape: &Shape, width: f64) -> f64 {
    let p = shape.to_piece(width);
    Segment::from_accel(0.0, width, &p.poly, p.sine, 0.0, 0.0).map_or(f64::NAN, |s| s.end().v)
}

impl ShedLaw {
    /// A symmetric law: the positive phase (the first half of the motion) and its odd mirror.
    pub fn symmetric(motion_deg: f64, positive: Vec<ShapeSegment>) -> Result<Self> {
        check_motion_deg(motion_deg)?;
        check_lengths("positive", &positive)?;
        let law = Self { motion_deg, positive, negative: NegativePhase::Mirrored };
        law.build()?;
        Ok(law)
    }

    /// An asymmetric law: the positive phase takes `positive_fraction` of the motion, the negative
    /// phase the rest; the negative levels are rescaled so that the frame comes to rest.
    pub fn asymmetric(
        motion_deg: f64,
        positive: Vec<ShapeSegment>,
        negative: Vec<ShapeSegment>,
        positive_fraction: f64,
    ) -> Result<Self> {
        check_motion_deg(motion_deg)?;
        check_lengths("positive", &positive)?;
        check_lengths("negative", &negative)?;
        Range::closed(0.01, 0.99, "").check("positive_fraction", positive_fraction)?;
        let law =
            Self { motion_deg, positive, negative: NegativePhase::Given { segments: negative, positive_fraction } };
        law.build()?;
        Ok(law)
    }

    /// Reads a law from TOML:
    ///
    /// ```toml
    /// motion_deg = 300
    /// positive = "0.25:sine-ramp:0:1,0.5:constant:1,0.25:cosine-ramp:1:0"
    /// # optional, for an asymmetric law (levels relative, rescaled to bring the frame to rest):
    /// # negative = "0.5:sine-ramp:0:-1,0.5:cosine-ramp:-1:0"
    /// # positive_fraction = 0.4
    /// ```
    pub fn from_toml(text: &str) -> Result<Self> {
        let spec: SpecFile = toml::from_str(text)
            .map_err(|e| ShedError::Parse { field: "spec".into(), reason: loomkin_units::toml_reason(text, &e) })?;
        let positive = read_segments(spec.positive, "positive")?;
        match (spec.negative, spec.positive_fraction) {
            (None, None) => Self::symmetric(spec.motion_deg, positive),
            (None, Some(_)) => Err(ShedError::Parse {
                field: "positive_fraction".into(),
                reason: "only allowed together with a negative phase".into(),
            }),
            (Some(n), f) => {
                Self::asymmetric(spec.motion_deg, positive, read_segments(n, "negative")?, f.unwrap_or(0.5))
            }
        }
    }

    /// The same law with another motion angle.
    pub fn with_motion_deg(&self, motion_deg: f64) -> Result<Self> {
        check_motion_deg(motion_deg)?;
        Ok(Self { motion_deg, ..self.clone() })
    }

    /// Motion angle `φ_дв`, degrees of the main shaft.
    pub fn motion_deg(&self) -> f64 {
        self.motion_deg
    }

    /// Nominal dwell `φ_вр = 360° − φ_дв`, degrees.
    pub fn nominal_dwell_deg(&self) -> f64 {
        360.0 - self.motion_deg
    }

    /// The positive-phase segments.
    pub fn positive(&self) -> &[ShapeSegment] {
        &self.positive
    }

    /// The negative phase.
    pub fn negative(&self) -> &NegativePhase {
        &self.negative
    }

    /// Whether the law is odd-symmetric about the middle of the motion.
    pub fn is_symmetric(&self) -> bool {
        self.negative == NegativePhase::Mirrored
    }

    /// The positive phase in the text form `LEN:SHAPE[:LEVEL…],…`.
    pub fn positive_text(&self) -> String {
        format_segments(&self.positive)
    }

    /// The negative phase in the text form (the mirror for a symmetric law).
    pub fn negative_text(&self) -> String {
        match &self.negative {
            NegativePhase::Mirrored => format_segments(&mirror(&self.positive)),
            NegativePhase::Given { segments, .. } => format_segments(segments),
        }
    }

    /// `φ_пу / φ_дв`, the fraction of the motion with positive acceleration.
    pub fn positive_fraction(&self) -> f64 {
        match &self.negative {
            NegativePhase::Mirrored => 0.5,
            NegativePhase::Given { positive_fraction, .. } => *positive_fraction,
        }
    }

    /// The segments of the whole motion on `x ∈ [0, 1]`: the positive phase with its lengths scaled
    /// by `φ_пу/φ_дв`, then the negative phase (the mirror, or the given one with its levels scaled so
    /// that the frame comes to rest) scaled by the rest; zero-length segments dropped. As a
    /// `piecewise` law of the core these make exactly the law [`ShedLaw::build`] makes.
    pub fn motion_segments(&self) -> Result<Vec<ShapeSegment>> {
        let p = self.positive_fraction();
        let scaled = |segs: &[ShapeSegment], f: f64| -> Vec<ShapeSegment> {
            segs.iter()
                .filter(|s| s.length > 0.0)
                .map(|s| ShapeSegment { length: s.length * f, shape: s.shape })
                .collect()
        };
        let mut out = scaled(&self.positive, p);
        let negative = match &self.negative {
            NegativePhase::Mirrored => mirror(&self.positive),
            NegativePhase::Given { segments, .. } => {
                let area_pos: f64 =
                    self.positive.iter().filter(|s| s.length > 0.0).map(|s| shape_area(&s.shape, s.length * p)).sum();
                let area_neg: f64 = segments
                    .iter()
                    .filter(|s| s.length > 0.0)
                    .map(|s| shape_area(&s.shape, s.length * (1.0 - p)))
                    .sum();
                if !(area_pos.is_finite() && area_neg.is_finite() && area_pos > 0.0 && area_neg < 0.0) {
                    return Err(ShedError::NotARise {
                        field: "negative".into(),
                        reason: format!(
                            "the positive phase must have a positive velocity gain and the negative phase a negative one \
                             (found {area_pos:.4} and {area_neg:.4})"
                        ),
                    });
                }
                let k = -area_pos / area_neg;
                segments.iter().map(|s| ShapeSegment { length: s.length, shape: s.shape.scaled(k) }).collect()
            }
        };
        out.extend(scaled(&negative, 1.0 - p));
        Ok(out)
    }

    /// The acceleration pieces of the whole motion on `x ∈ [0, 1]` (zero-length segments dropped).
    pub fn pieces(&self) -> Result<Vec<AccelPiece>> {
        Ok(self.motion_segments()?.iter().map(|s| s.shape.to_piece(s.length)).collect())
    }

    /// Integrates the acceleration twice in closed form into a normalised rise (`s(0) = 0`,
    /// `s(1) = 1`, at rest at both ends).
    pub fn build(&self) -> Result<Law> {
        let pieces = self.pieces()?;
        // The widths sum to 1 within rounding; renormalise them to the core's tolerance.
        Law::from_accel_pieces(&pieces, EndCondition::Rest, "positive").map_err(|e| match e {
            loomkin_laws::LawError::NotARise { reason, .. } => ShedError::NotARise { field: "positive".into(), reason },
            other => other.into(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use loomkin_laws::LawSpec;

    fn trapezoid(kr: f64) -> Vec<ShapeSegment> {
        parse_segments(&format!("{kr}:sine-ramp:0:1,{}:constant:1,{kr}:cosine-ramp:1:0", 1.0 - 2.0 * kr), "t").unwrap()
    }

    #[test]
    fn mirrored_trapezoid_is_the_core_modified_trapezoid() {
        for kr in [0.25, 1.0 / 3.0, 0.4] {
            let a = ShedLaw::symmetric(300.0, trapezoid(kr)).unwrap().build().unwrap();
            let b = LawSpec::ModifiedTrapezoid { ramp: kr / 2.0 }.build().unwrap();
            for i in 0..=200 {
                let x = i as f64 / 200.0;
                let (ka, kb) = (a.eval(x), b.eval(x));
                assert!((ka.s - kb.s).abs() < 1e-13 && (ka.a - kb.a).abs() < 1e-11, "kr {kr} x {x}");
            }
        }
    }

    #[test]
    fn spec_errors_name_the_segment() {
        let e = ShedLaw::from_toml("motion_deg = 300\npositive = [ { length = 1.0, shape = \"sine-ramp\" } ]")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("positive[0]: missing field `from`"), "{e}");
        let e = ShedLaw::from_toml("motion_deg = 300\npositive = 5").unwrap_err().to_string();
        assert!(e.starts_with("positive: found integer"), "{e}");
        let ok = ShedLaw::from_toml(
            "motion_deg = 300\npositive = [ { length = 0.5, shape = \"constant\", level = 1.0 }, \
             { length = 0.5, shape = \"zero\" } ]",
        )
        .unwrap();
        assert_eq!(ok.positive_text(), "0.5:constant:1,0.5:zero");
    }

    #[test]
    fn rejects_bad_definitions() {
        assert!(matches!(ShedLaw::symmetric(0.0, trapezoid(0.25)), Err(ShedError::Range(_))));
        assert!(matches!(ShedLaw::symmetric(361.0, trapezoid(0.25)), Err(ShedError::Range(_))));
        let bad = parse_segments("0.3:sine-ramp:0:1,0.3:cosine-ramp:1:0", "t").unwrap();
        assert!(matches!(ShedLaw::symmetric(300.0, bad), Err(ShedError::LengthsDoNotSumToOne { .. })));
        let zero = parse_segments("1:zero", "t").unwrap();
        assert!(ShedLaw::symmetric(300.0, zero).is_err());
        assert!(ShedLaw::from_toml("motion_deg = 300\npositive = 3").is_err());
        assert!(ShedLaw::from_toml("motion_deg = 300\npositive = \"1:constant:1\"\npositive_fraction = 0.4").is_err());
    }

    #[test]
    fn asymmetric_law_comes_to_rest_and_reads_from_toml() {
        let text = r#"
            motion_deg = 320
            positive = [ { length = 0.5, shape = "sine-ramp", from = 0.0, to = 1.0 },
                         { length = 0.5, shape = "cosine-ramp", from = 1.0, to = 0.0 } ]
            negative = "0.2:sine-ramp:0:-1,0.6:constant:-1,0.2:cosine-ramp:-1:0"
            positive_fraction = 0.4
        "#;
        let law = ShedLaw::from_toml(text).unwrap();
        assert!(!law.is_symmetric());
        let l = law.build().unwrap();
        let e = l.eval(1.0);
        assert!((e.s - 1.0).abs() < 1e-12 && e.v.abs() < 1e-9);
        // The acceleration changes sign at x = 0.4.
        assert!(l.eval(0.39).a > 0.0 && l.eval(0.41).a < 0.0);
    }
}
