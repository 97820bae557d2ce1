//! Acceleration shapes of a piecewise-acceleration law, in a segment's relative coordinate.

use crate::{AccelPiece, LawError, Result, Sine};
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, PI};

/// The shape of the acceleration over one segment, in its relative coordinate `u ∈ [0, 1]`.
///
/// Levels are relative: the law is scaled afterwards so that the stroke is 1.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "shape", rename_all = "kebab-case")]
pub enum Shape {
    /// `a = 0` (a constant-velocity stretch).
    Zero,
    /// `a = level`.
    Constant {
        /// Level.
        level: f64,
    },
    /// Straight line `a = from + (to − from)·u`.
    Linear {
        /// Level at the start.
        from: f64,
        /// Level at the end.
        to: f64,
    },
    /// Quarter sine `a = from + (to − from)·sin(πu/2)`: steep at the start, flat at the end.
    SineRamp {
        /// Level at the start.
        from: f64,
        /// Level at the end.
        to: f64,
    },
    /// Quarter cosine `a = from + (to − from)·(1 − cos(πu/2))`: flat at the start, steep at the end.
    CosineRamp {
        /// Level at the start.
        from: f64,
        /// Level at the end.
        to: f64,
    },
    /// Half cosine `a = from + (to − from)·(1 − cos πu)/2`: flat at both ends (an S-shaped ramp).
    HalfCosine {
        /// Level at the start.
        from: f64,
        /// Level at the end.
        to: f64,
    },
    /// Half sine arc `a = peak·sin(πu)`: zero at both ends.
    SineArc {
        /// Peak level in the middle.
        peak: f64,
    },
}

impl Shape {
    /// Names accepted by [`Shape::parse`].
    pub const NAMES: &'static str =
        "zero, constant:L, linear:A:B, sine-ramp:A:B, cosine-ramp:A:B, half-cosine:A:B, sine-arc:P";

    /// The acceleration level at `u = 0` and `u = 1`.
    pub fn end_levels(&self) -> (f64, f64) {
        match *self {
            Shape::Zero => (0.0, 0.0),
            Shape::Constant { level } => (level, level),
            Shape::Linear { from, to }
            | Shape::SineRamp { from, to }
            | Shape::CosineRamp { from, to }
            | Shape::HalfCosine { from, to } => (from, to),
            Shape::SineArc { .. } => (0.0, 0.0),
        }
    }

    /// The same shape with its levels multiplied by `k`.
    pub fn scaled(&self, k: f64) -> Self {
        match *self {
            Shape::Zero => Shape::Zero,
            Shape::Constant { level } => Shape::Constant { level: level * k },
            Shape::Linear { from, to } => Shape::Linear { from: from * k, to: to * k },
            Shape::SineRamp { from, to } => Shape::SineRamp { from: from * k, to: to * k },
            Shape::CosineRamp { from, to } => Shape::CosineRamp { from: from * k, to: to * k },
            Shape::HalfCosine { from, to } => Shape::HalfCosine { from: from * k, to: to * k },
            Shape::SineArc { peak } => Shape::SineArc { peak: peak * k },
        }
    }

    /// The shape mirrored in time (`u → 1 − u`), e.g. to build a return phase.
    pub fn reversed(&self) -> Self {
        match *self {
            Shape::Linear { from, to } => Shape::Linear { from: to, to: from },
            // A quarter sine run backwards is a quarter cosine (flat end first).
            Shape::SineRamp { from, to } => Shape::CosineRamp { from: to, to: from },
            Shape::CosineRamp { from, to } => Shape::SineRamp { from: to, to: from },
            Shape::HalfCosine { from, to } => Shape::HalfCosine { from: to, to: from },
            other => other,
        }
    }

    /// The acceleration of this shape over a segment of the given width, as an [`AccelPiece`]
    /// (the local coordinate is `t = u · width`).
    pub fn to_piece(&self, width: f64) -> AccelPiece {
        let w = width;
        match *self {
            Shape::Zero => AccelPiece::poly(w, &[]),
            Shape::Constant { level } => AccelPiece::poly(w, &[level]),
            Shape::Linear { from, to } => AccelPiece::poly(w, &[from, (to - from) / w]),
            Shape::SineRamp { from, to } => {
                AccelPiece::with_sine(w, &[from], Sine { amp: to - from, omega: FRAC_PI_2 / w, phase: 0.0 })
            }
            // from + d(1 − cos(πu/2)) = to − d·sin(πu/2 + π/2)
            Shape::CosineRamp { from, to } => {
                AccelPiece::with_sine(w, &[to], Sine { amp: -(to - from), omega: FRAC_PI_2 / w, phase: FRAC_PI_2 })
            }
            // from + d(1 − cos πu)/2 = (from+to)/2 − d/2·sin(πu + π/2)
            Shape::HalfCosine { from, to } => AccelPiece::with_sine(
                w,
                &[(from + to) / 2.0],
                Sine { amp: -(to - from) / 2.0, omega: PI / w, phase: FRAC_PI_2 },
            ),
            Shape::SineArc { peak } => AccelPiece::with_sine(w, &[], Sine { amp: peak, omega: PI / w, phase: 0.0 }),
        }
    }

    /// Reads a shape written as `NAME[:LEVEL[:LEVEL]]`, e.g. `sine-ramp:0:1`, `constant:1`, `zero`.
    pub fn parse(text: &str, field: &str) -> Result<Self> {
        let err = || LawError::Parse { field: field.into(), text: text.into(), expected: Self::NAMES.into() };
        let mut it = text.split(':').map(str::trim);
        let name = it.next().ok_or_else(err)?;
        let nums: Vec<f64> = it.map(|t| t.parse::<f64>().map_err(|_| err())).collect::<Result<_>>()?;
        if nums.iter().any(|v| !v.is_finite()) {
            return Err(err());
        }
        let two = |ctor: fn(f64, f64) -> Shape| {
            if nums.len() == 2 { Ok(ctor(nums[0], nums[1])) } else { Err(err()) }
        };
        match name {
            "zero" if nums.is_empty() => Ok(Shape::Zero),
            "constant" if nums.len() == 1 => Ok(Shape::Constant { level: nums[0] }),
            "linear" => two(|from, to| Shape::Linear { from, to }),
            "sine-ramp" => two(|from, to| Shape::SineRamp { from, to }),
            "cosine-ramp" => two(|from, to| Shape::CosineRamp { from, to }),
            "half-cosine" => two(|from, to| Shape::HalfCosine { from, to }),
            "sine-arc" if nums.len() == 1 => Ok(Shape::SineArc { peak: nums[0] }),
            _ => Err(err()),
        }
    }
}

impl std::fmt::Display for Shape {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let n = number_text;
        match *self {
            Shape::Zero => write!(f, "zero"),
            Shape::Constant { level } => write!(f, "constant:{}", n(level)),
            Shape::Linear { from, to } => write!(f, "linear:{}:{}", n(from), n(to)),
            Shape::SineRamp { from, to } => write!(f, "sine-ramp:{}:{}", n(from), n(to)),
            Shape::CosineRamp { from, to } => write!(f, "cosine-ramp:{}:{}", n(from), n(to)),
            Shape::HalfCosine { from, to } => write!(f, "half-cosine:{}:{}", n(from), n(to)),
            Shape::SineArc { peak } => write!(f, "sine-arc:{}", n(peak)),
        }
    }
}

/// The shortest text that reads back as `v`: plain for ordinary magnitudes, with an exponent
/// below 1e-4 and from 1e16 on (a level of 1e-308 is not written in 310 digits).
pub(crate) fn number_text(v: f64) -> String {
    if v != 0.0 && !(1e-4..1e16).contains(&v.abs()) { format!("{v:e}") } else { format!("{v}") }
}

/// One segment of a piecewise-acceleration law: a relative length and a shape.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ShapeSegment {
    /// Relative length (fraction of the motion, > 0; all lengths sum to 1).
    pub length: f64,
    /// Acceleration shape.
    #[serde(flatten)]
    pub shape: Shape,
}

/// Reads segments written `LEN:SHAPE[:LEVEL…],LEN:SHAPE…`, e.g.
/// `0.25:sine-ramp:0:1,0.5:half-cosine:1:-1,0.25:cosine-ramp:-1:0`.
pub fn parse_segments(text: &str, field: &str) -> Result<Vec<ShapeSegment>> {
    text.split(',')
        .enumerate()
        .map(|(i, part)| {
            let f = format!("{field}[{i}]");
            let (len, shape) = part.trim().split_once(':').ok_or_else(|| LawError::Parse {
                field: f.clone(),
                text: part.into(),
                expected: "LENGTH:SHAPE[:LEVEL…]".into(),
            })?;
            let length = len.trim().parse::<f64>().map_err(|_| LawError::Parse {
                field: format!("{f}.length"),
                text: len.into(),
                expected: "a number in (0, 1]".into(),
            })?;
            Ok(ShapeSegment { length, shape: Shape::parse(shape, &f)? })
        })
        .collect()
}

/// Writes segments in the form [`parse_segments`] reads.
pub fn format_segments(segs: &[ShapeSegment]) -> String {
    segs.iter().map(|s| format!("{}:{}", number_text(s.length), s.shape)).collect::<Vec<_>>().join(",")
}
