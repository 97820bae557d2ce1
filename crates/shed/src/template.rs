//! A family of symmetric laws: fixed shapes of the positive phase, free relative lengths
//! `k_T1 … k_Tn`. Its criteria have a fast closed-form path used for large experiment tables.

use crate::fast::{self, levels};
use crate::{Dimensionless, Result, ShedError, ShedLaw, check_threshold};
use loomkin_laws::{Shape, ShapeSegment};
use loomkin_units::Range;
use serde::Serialize;

/// Most parts a template may have.
pub const MAX_PARTS: usize = 12;

/// Shapes of the positive phase of a symmetric law; the lengths are given per evaluation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Template {
    name: String,
    shapes: Vec<Shape>,
    /// All levels ≥ 0: the acceleration is non-negative over the positive phase, which the fast
    /// path needs (v then peaks at mid-motion and s is convex on the first half).
    fast: bool,
}

impl Template {
    /// A template from the shapes of the positive phase (1 … 12 of them).
    pub fn new(name: impl Into<String>, shapes: Vec<Shape>) -> Result<Self> {
        Range::closed(1.0, MAX_PARTS as f64, "").check("parts", shapes.len() as f64)?;
        let fast = shapes.iter().all(|s| levels(s).iter().all(|&l| l >= 0.0));
        Ok(Self { name: name.into(), shapes, fast })
    }

    /// Reads the shapes written `SHAPE[:LEVEL…],…`, e.g. `zero,sine-ramp:0:1,constant:1,cosine-ramp:1:0`.
    pub fn parse(name: impl Into<String>, text: &str) -> Result<Self> {
        let shapes = text
            .split(',')
            .enumerate()
            .map(|(i, t)| Shape::parse(t.trim(), &format!("shapes[{i}]")))
            .collect::<std::result::Result<Vec<_>, _>>()?;
        Self::new(name, shapes)
    }

    /// The three-part family of Table 1: quarter-sine rise, constant plateau, quarter-cosine fall
    /// (`k1 = k3 = k_r` gives the modified trapezoid, `k1 = k3 = 0.5` the cycloidal law).
    pub fn trapezoid() -> Self {
        Self::parse("trapezoid", "sine-ramp:0:1,constant:1,cosine-ramp:1:0").expect("valid shapes")
    }

    /// The four-part family of the paper's Fig. 1: a stretch of zero acceleration (extra dwell),
    /// then the three parts of [`Template::trapezoid`].
    pub fn lead_trapezoid() -> Self {
        Self::parse("lead-trapezoid", "zero,sine-ramp:0:1,constant:1,cosine-ramp:1:0").expect("valid shapes")
    }

    /// The simplest three-part family: linear rise, constant, linear fall.
    pub fn linear_trapezoid() -> Self {
        Self::parse("linear-trapezoid", "linear:0:1,constant:1,linear:1:0").expect("valid shapes")
    }

    /// The named families: `trapezoid`, `lead-trapezoid`, `linear-trapezoid`.
    pub fn named(name: &str) -> Result<Self> {
        match name.trim() {
            "trapezoid" => Ok(Self::trapezoid()),
            "lead-trapezoid" => Ok(Self::lead_trapezoid()),
            "linear-trapezoid" => Ok(Self::linear_trapezoid()),
            other => Err(ShedError::Parse {
                field: "family".into(),
                reason: format!("unknown family '{other}': known are trapezoid, lead-trapezoid, linear-trapezoid"),
            }),
        }
    }

    /// The family's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Number of parts `n`.
    pub fn parts(&self) -> usize {
        self.shapes.len()
    }

    /// The shapes.
    pub fn shapes(&self) -> &[Shape] {
        &self.shapes
    }

    /// Whether the fast closed-form path applies (every level ≥ 0).
    pub fn is_fast(&self) -> bool {
        self.fast
    }

    fn segments(&self, lengths: &[f64]) -> Result<Vec<ShapeSegment>> {
        if lengths.len() != self.parts() {
            return Err(ShedError::Parse {
                field: "lengths".into(),
                reason: format!("the family has {} parts, {} lengths given", self.parts(), lengths.len()),
            });
        }
        Ok(lengths.iter().zip(&self.shapes).map(|(&length, &shape)| ShapeSegment { length, shape }).collect())
    }

    /// The law with these lengths at a motion angle.
    pub fn law(&self, motion_deg: f64, lengths: &[f64]) -> Result<ShedLaw> {
        ShedLaw::symmetric(motion_deg, self.segments(lengths)?)
    }

    /// Dimensionless criteria of the law with these lengths: the fast closed-form path when the
    /// template allows it, else the generic path through the law core.
    pub fn evaluate(&self, lengths: &[f64], threshold: f64) -> Result<Dimensionless> {
        if self.fast {
            self.evaluate_fast(lengths, threshold)
        } else {
            let law = self.law(360.0, lengths)?.build()?;
            Dimensionless::of_law(&law, threshold)
        }
    }

    /// The generic path (through [`ShedLaw::build`] and [`loomkin_laws::Law::metrics`]), for checks.
    pub fn evaluate_generic(&self, lengths: &[f64], threshold: f64) -> Result<Dimensionless> {
        let law = self.law(360.0, lengths)?.build()?;
        Dimensionless::of_law(&law, threshold)
    }

    /// The fast path. On the positive phase (`x ∈ [0, ½]`) `a ≥ 0`, so `v` rises to its peak at
    /// `x = ½` and `s` is convex there; the negative phase is the mirror. Hence, with `k` the
    /// stroke normalisation `½/s(½)`:
    /// `Cv = k·v(½)`; `Ca = k·max level`; `Cj = k·max` of the closed-form per-shape jerk peaks;
    /// `∫a² = 2k²·Σ wᵢ·∫₀¹aᵢ²`; `Cm = k²·max v·a`, at a segment's end where `a` does not fall and
    /// at the root of `(v·a)' = a² + v·j` where it does; and `x_depart` solves `s(x) = (1 − T)/k`
    /// by Newton's method in the one segment that brackets it (`x_arrive = 1 − x_depart`).
    pub fn evaluate_fast(&self, lengths: &[f64], threshold: f64) -> Result<Dimensionless> {
        check_threshold(threshold)?;
        if !self.fast {
            return Err(ShedError::Parse {
                field: "template".into(),
                reason: "the fast path needs non-negative levels in the positive phase".into(),
            });
        }
        if lengths.len() != self.parts() {
            return Err(ShedError::Parse {
                field: "lengths".into(),
                reason: format!("the family has {} parts, {} lengths given", self.parts(), lengths.len()),
            });
        }
        fast::evaluate(&self.shapes, lengths, threshold)
    }
}
