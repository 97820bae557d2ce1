//! # loomkin-laws — motion laws in closed form
//!
//! Every law is a sequence of [`Segment`]s whose acceleration is a polynomial plus a sinusoid,
//! `a(x) = p(x) + A·sin(ωx + φ)`, integrated twice in closed form, so displacement, velocity,
//! acceleration and jerk are exact and cheap everywhere. Laws are normalised rises: `x ∈ [0, 1]`
//! is the fraction of the motion angle, `s ∈ [0, 1]` the fraction of the stroke.
//!
//! ```
//! use loomkin_laws::LawSpec;
//!
//! let law = LawSpec::Cycloidal.build()?;
//! let m = law.metrics();
//! assert!((m.cv - 2.0).abs() < 1e-12);                       // Cv = 2
//! assert!((m.ca - 2.0 * std::f64::consts::PI).abs() < 1e-12); // Ca = 2π
//! let k = law.eval(0.25);
//! assert!((k.s - (0.25 - 1.0 / (2.0 * std::f64::consts::PI))).abs() < 1e-15);
//! # Ok::<(), loomkin_laws::LawError>(())
//! ```
//!
//! A machine cycle (dwell / rise / dwell / return over a turn of the main shaft) is read from TOML
//! by [`Cycle::from_toml`] and evaluated in SI units at a shaft speed.
#![deny(missing_docs)]

mod catalogue;
mod continuity;
mod cycle;
mod cycle_report;
mod error;
mod extrema;
mod kinematics;
mod law;
mod metrics;
mod nontemporal;
mod polynomial;
mod quadrature;
mod report;
mod segment;
mod shape;

pub use catalogue::{CATALOGUE, CatalogueEntry, LawSpec, ParamValue, RAMP, laws_of_class};
pub use continuity::{CONTINUITY_TOL, Continuity, DerivativeScale, Joint, SCALE_SAMPLES};
pub use cycle::{Cycle, CyclePoint, CycleSegment, CycleSpec, SegmentKind, SegmentSpec, StrokeUnit};
pub use cycle_report::{CycleExtremes, CycleReport, SegmentPeaks, StreamedReport};
pub use error::{LawError, Result, compact};
pub use kinematics::{Kinematics, MotionLaw};
pub use law::{AccelPiece, EndCondition, Law, Samples};
pub use metrics::Metrics;
pub use polynomial::{MAX_ACCEL_DEGREE, PolySegment, format_poly_segments, parse_poly_segments, poly_segments_of};
pub use quadrature::gauss_legendre;
pub use report::{ContinuityReport, ContinuousFlags, InfoReport, JointReport, ListedLaw};
pub use segment::{MAX_DEGREE, Segment, Sine};
pub use shape::{Shape, ShapeSegment, format_segments, parse_segments};

/// The descriptors of this crate's inputs.
pub const FIELDS: loomkin_units::FieldList = loomkin_units::field_list![
    Law::SAMPLE_POINTS,
    Law::HELD_POINTS,
    Law::PLOT_POINTS,
    Cycle::POINTS,
    Cycle::HELD_POINTS,
    CycleSpec::MOTION_DEG,
    CycleSpec::STROKE_MM,
    CycleSpec::STROKE_DEG,
];
