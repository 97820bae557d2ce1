//! Disc cam profiles from any closed motion: translating (radial or offset) and oscillating roller
//! followers, the flat-faced translating follower, the conjugate pair and the groove cam — pitch
//! curves, working profiles, pressure angle, curvature, undercut, every extreme located exactly,
//! and sizing (least prime circle for a largest pressure angle, largest roller without undercut).
//!
//! Conventions (see `docs/cams.md`): the cam turns counter-clockwise, once per cycle period, at
//! the main-shaft angle of the cycle; the prime circle radius `R_p` is the least radius of the
//! pitch curve (base circle + roller); the pressure angle of a translating roller follower with
//! offset ε is `atan((ds/dψ − ε) / (s + √(R_p² − ε²)))`, `ds/dψ` in mm per radian of cam.

mod cam;
mod design;
mod drawing;
mod extremes;
mod jet;
mod lift;
mod report;
mod sizing;
mod track;
mod undercut;

pub use cam::{
    CamPoint, CamProfile, Curve, DEFAULT_SAMPLE_STEP_DEG, FlatExtremes, SAMPLE_STEP_RANGE, TrackExtremes, Wall,
};
pub use design::{
    CamDesign, Closure, DEFAULT_MAX_PRESSURE_DEG, DesignInputs, Follower, FollowerKind, LENGTH_RANGE, OFFSET_RANGE,
    PRESSURE_RANGE, ROLLER_RANGE, Size,
};
pub use drawing::{BORE_RANGE, CHORD_TOL_RANGE, DEFAULT_BORE_PER_BASE_RADIUS, DEFAULT_CHORD_TOL_MM};
pub use extremes::Extremes;
pub use jet::Jet;
pub use lift::Lift;
/// The drawing's shapes (here in mm, cam frame: the cam centre at the origin, the follower at
/// main-shaft angle 0° along the phase mark), the one drawing type of loomkin-io.
pub use loomkin_io::drawing::{Layered, Shape};
pub use report::{CamReport, PointReport, ProfileExtremes, ProfileReport};
pub use track::{Track, TrackJets, curvature, offset};
pub use undercut::{Undercut, UndercutKind};
