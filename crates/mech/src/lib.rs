//! # loomkin-mech — planar vector loops and the rotary-dobby modulator
//!
//! A general planar vector-loop solver ([`VectorLoop`], [`LoopSystem`]: position by Newton with
//! continuation, velocities and accelerations from the differentiated loops, closed-form dyads,
//! RK4 integration of the velocity equations as an independent check), closed curves ([`Ellipse`],
//! [`ClosedSpline`] through a point table) and, built on them, the modulator of a Stäubli-type
//! rotary dobby: analysis of a given cam ([`analyze`]) and synthesis of the conjugate cams for an
//! output law ([`synthesize`]).
//!
//! ```
//! use loomkin_mech::{AnalysisOptions, Cam, ModulatorGeometry, OutputLawSpec, SynthesisOptions, analyze, synthesize};
//!
//! // Task 1: the paper's ellipse cam, α = 47°, ω2 = 1 rad/s.
//! let g = ModulatorGeometry::default();
//! let a = analyze(&g, &Cam::paper(), &AnalysisOptions::default())?;
//! assert!((a.summary.checks.phi6_turn_deg - 360.0).abs() < 1e-9); // one output turn per input turn
//!
//! // Task 2: two dwells of 40° centred at 90° and 270°, cycloidal rises of 180°.
//! let s = synthesize(&g, &OutputLawSpec::default(), &SynthesisOptions::default())?;
//! let row = &s.rows[90]; // φ2 = 90°: φ2 = φ3 = φ6 = 90°, S53 = l2 − l6 (the paper's start)
//! assert!((row.phi6_deg - 90.0).abs() < 1e-9 && (row.phi3_deg - 90.0).abs() < 1e-9);
//! assert!((row.s53_m - (g.l2_m - g.l6_m)).abs() < 1e-12);
//! # Ok::<(), loomkin_mech::MechError>(())
//! ```
//!
//! Angles are anticlockwise from +x, `e(x) = (cos x, sin x)`; lengths in m, angles in rad inside
//! (deg where a name says so), rates per second at the input speed ω2.
#![deny(missing_docs)]

mod curve;
mod dobby;
mod dyad;
mod error;
mod integrate;
mod linalg;
mod newton;
mod planar;
mod spline;
mod vloop;

pub use curve::{CurvePoint, Ellipse, PlaneCurve};
pub use dobby::analysis::{
    Analysis, AnalysisOptions, AnalysisReport, AnalysisRow, AnalysisSummary, DobbyInputs, MAX_INPUT_SPEED_RAD_S,
    MAX_INPUT_SPEED_RPM, ROLLER_M_RANGE, STEP_DEG_RANGE, analyze, analyze_into, assemble, cam_loop, modulator_loops,
};
pub use dobby::cam::{Cam, parse_point_table};
pub use dobby::checks::{
    Crossing, Warning, WarningCode, output_pressure_angle_deg, roller_pressure_angle_deg, self_intersections,
};
pub use dobby::curvature::{CamCurvaturePoint, cam_curvature};
pub use dobby::drawing::DOBBY_CHORD_TOL_RANGE;
pub use dobby::export as dobby_export;
pub use dobby::geometry::ModulatorGeometry;
pub use dobby::kinematics::ModulatorState;
pub use dobby::law::{OutputLaw, OutputLawSpec, OutputState, max_dwell_deg};
pub use dobby::pose::{MechanismPose, nearest_state};
pub use dobby::report::{CamChecks, CamProfile};
pub use dobby::sweep::{AlphaSweep, SweepReport, SweepRow, alpha_sweep};

/// The descriptors of this crate's inputs.
pub const FIELDS: loomkin_units::FieldList = loomkin_units::field_list![
    ModulatorGeometry::L2_M,
    ModulatorGeometry::L3_M,
    ModulatorGeometry::L3P_M,
    ModulatorGeometry::L6_M,
    ModulatorGeometry::ALPHA_DEG,
    ModulatorGeometry::THETA_DEG,
    OutputLawSpec::CYCLES,
    OutputLawSpec::DWELL_DEG,
    OutputLawSpec::DWELL_CENTRE_DEG,
    DobbyInputs::STEP_DEG,
    DobbyInputs::PLOT_STEP_DEG,
    DobbyInputs::SPEED_RPM,
    DobbyInputs::PRESSURE_LIMIT_DEG,
    DobbyInputs::ROLLER_M,
    DobbyInputs::ROLLER_MM,
    DobbyInputs::AT_DEG,
    AlphaSweep::FROM,
    AlphaSweep::TO,
    AlphaSweep::BY,
    AlphaSweep::ALPHAS,
    Synthesis::CHORD_TOL_MM,
    Synthesis::BORE_MM,
];
pub use dobby::synthesis::{
    GivenLength, Synthesis, SynthesisOptions, SynthesisReport, SynthesisRow, SynthesisSummary, synthesize,
    synthesize_into,
};
pub use dobby::tolerance;
pub use dobby::tolerance::Tolerance;
pub use dyad::{circle_circle, line_circle};
pub use error::{MechError, Result};
pub use newton::{LoopState, NewtonOptions, Position};
pub use planar::{Vec2, cross, curvature, e, e_perp, perp, unwrap_near, wrap_pi};
pub use spline::{ClosedSpline, MIN_SPLINE_POINTS, PeriodicSpline};
pub use vloop::{Linearization, LoopSystem, Scalar, Term, Var, VectorLoop};
