//! The modulator of a Stäubli-type rotary dobby (series 2600): geometry, analysis (task 1),
//! synthesis (task 2), checks, the α sweep and tolerance studies.

pub(crate) mod analysis;
pub(crate) mod cam;
pub(crate) mod checks;
pub(crate) mod curvature;
pub(crate) mod drawing;
pub mod export;
pub(crate) mod geometry;
pub(crate) mod kinematics;
pub(crate) mod law;
pub(crate) mod pose;
pub(crate) mod refine;
pub(crate) mod report;
pub(crate) mod sweep;
pub(crate) mod synthesis;
pub mod tolerance;
