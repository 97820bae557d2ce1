//! A cam profile's figures as users read them (`loomkin cam profile --json`): one struct that
//! serialises itself, so the CLI and any other front end name each value the same way.

use super::cam::{CamPoint, CamProfile};
use super::design::{Closure, Follower};
use loomkin_units::compact;
use serde::Serialize;

impl Follower {
    /// The follower in words: `radial translating roller follower`, `oscillating roller follower
    /// (arm 100 mm, pivot 150 mm)`, ….
    pub fn description(&self) -> String {
        match *self {
            Follower::Translating { offset_mm: 0.0 } => "radial translating roller follower".into(),
            Follower::Translating { offset_mm } => {
                format!("translating roller follower offset {} mm", compact(offset_mm))
            }
            Follower::Oscillating { arm_mm, pivot_mm } => {
                format!("oscillating roller follower (arm {} mm, pivot {} mm)", compact(arm_mm), compact(pivot_mm))
            }
            Follower::Flat => "flat-faced translating follower".into(),
        }
    }
}

impl Closure {
    /// The closure in words: `single cam`, `conjugate pair`, `groove cam`.
    pub fn description(self) -> &'static str {
        match self {
            Closure::Single => "single cam",
            Closure::Conjugate => "conjugate pair",
            Closure::Groove => "groove cam",
        }
    }
}

/// One printed point of a track: pitch point, pressure angle, pitch curvature and profile point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PointReport {
    /// Main-shaft angle (deg).
    pub angle_deg: f64,
    /// Pitch point x (mm).
    pub x_mm: f64,
    /// Pitch point y (mm).
    pub y_mm: f64,
    /// Pressure angle (deg).
    pub pressure_angle_deg: f64,
    /// Curvature of the pitch curve, positive where convex (1/mm).
    pub curvature_pitch_per_mm: f64,
    /// Working profile x (mm).
    pub profile_x_mm: f64,
    /// Working profile y (mm).
    pub profile_y_mm: f64,
}

impl From<&CamPoint> for PointReport {
    fn from(p: &CamPoint) -> Self {
        Self {
            angle_deg: p.angle_deg,
            x_mm: p.pitch_mm[0],
            y_mm: p.pitch_mm[1],
            pressure_angle_deg: p.pressure_angle_deg,
            curvature_pitch_per_mm: p.curvature_pitch_per_mm,
            profile_x_mm: p.profile_mm[0],
            profile_y_mm: p.profile_mm[1],
        }
    }
}

/// The extremes every report of a cam states (keys of `loomkin cam profile --json`, flattened into
/// [`ProfileReport`] and the web's cam report). For a conjugate pair each is the pair's: the
/// larger pressure angle, the smaller radius, of the two cams (each cam's own are in
/// [`ProfileReport::cams`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ProfileExtremes {
    /// Largest |pressure angle| of every track (deg): a conjugate pair's larger of its two cams'.
    pub max_pressure_angle_deg: f64,
    /// Where it occurs (main-shaft deg).
    pub max_pressure_angle_at_deg: f64,
    /// Least radius of curvature of the pitch curve where it is convex (mm): a conjugate pair's
    /// smaller of its two cams'.
    pub min_convex_radius_pitch_mm: f64,
    /// Where it occurs (main-shaft deg).
    pub min_convex_radius_pitch_at_deg: f64,
    /// Whether the profile is undercut (or has a cusp).
    pub undercut: bool,
}

/// One cam of a conjugate pair with its own extremes (`loomkin cam profile --conjugate --json`,
/// key `cams`: the cam, then the counter-cam).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CamReport {
    /// `cam` (the main cam, whose points are `points`) or `counter` (the counter-cam, `counter_points`).
    pub cam: &'static str,
    /// Largest |pressure angle| of this cam (deg).
    pub max_pressure_angle_deg: f64,
    /// Where it occurs (main-shaft deg).
    pub max_pressure_angle_at_deg: f64,
    /// Least radius of curvature of this cam's pitch curve where it is convex (mm).
    pub min_convex_radius_pitch_mm: f64,
    /// Where it occurs (main-shaft deg).
    pub min_convex_radius_pitch_at_deg: f64,
    /// Roller follower: least convex radius of this cam's working profile (mm), pitch radius less
    /// the roller.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_convex_radius_profile_mm: Option<f64>,
}

impl CamReport {
    /// `cam` or `counter` in words: `main cam`, `counter-cam`.
    pub fn description(&self) -> &'static str {
        if self.cam == "cam" { "main cam" } else { "counter-cam" }
    }
}

/// A cam profile's report: the design, the sizes and extremes, and the points of each track.
/// Keys that apply to one kind of follower or closure only are left out elsewhere.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ProfileReport {
    /// What the motion came from (a file name, `law cycloidal (…)`).
    pub source: String,
    /// [`Follower::description`].
    pub follower: String,
    /// [`Closure::description`].
    pub closure: &'static str,
    /// Prime circle radius (mm).
    pub prime_radius_mm: f64,
    /// Base circle radius (mm).
    pub base_radius_mm: f64,
    /// Roller radius (mm; 0 for a flat face).
    pub roller_radius_mm: f64,
    /// The pressure angle's and the pitch curve's extremes, and the undercut.
    #[serde(flatten)]
    pub extremes: ProfileExtremes,
    /// Oscillating follower: arm length (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub arm_mm: Option<f64>,
    /// Oscillating follower: pivot distance (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pivot_mm: Option<f64>,
    /// Translating follower: offset (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub offset_mm: Option<f64>,
    /// Stroke of a translating or flat-faced follower (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stroke_mm: Option<f64>,
    /// Swing of an oscillating follower (deg).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stroke_deg: Option<f64>,
    /// Roller follower: the largest roller without undercut (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub roller_max_mm: Option<f64>,
    /// Roller follower: least convex radius of the working profile (mm), pitch radius less the roller.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_convex_radius_profile_mm: Option<f64>,
    /// Where the profile is undercut (main-shaft deg).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub undercut_at_deg: Option<f64>,
    /// Flat face: least radius of curvature of the profile (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_radius_profile_mm: Option<f64>,
    /// Flat face: where it occurs (main-shaft deg).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_radius_profile_at_deg: Option<f64>,
    /// Flat face: the least prime radius without a cusp (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub least_prime_radius_no_cusp_mm: Option<f64>,
    /// Flat face: contact point's least offset on the face (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub face_min_mm: Option<f64>,
    /// Flat face: contact point's largest offset on the face (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub face_max_mm: Option<f64>,
    /// Conjugate pair: the counter-cam's largest |pressure angle| (deg).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub counter_max_pressure_angle_deg: Option<f64>,
    /// Conjugate pair: where it occurs (main-shaft deg).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub counter_max_pressure_angle_at_deg: Option<f64>,
    /// Conjugate pair: each cam's own extremes, the cam then the counter-cam ([`CamProfile::cam_reports`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cams: Option<Vec<CamReport>>,
    /// The cam's points.
    pub points: Vec<PointReport>,
    /// Conjugate pair: the counter-cam's points.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub counter_points: Option<Vec<PointReport>>,
}

impl CamProfile {
    /// A conjugate pair's two cams, each with its own extremes; `None` for a single or groove cam.
    pub fn cam_reports(&self) -> Option<Vec<CamReport>> {
        if self.track_count() != 2 {
            return None;
        }
        let roller = self.roller_max_mm().map(|_| self.design().roller_radius_mm);
        let cams = self.track_extremes_all().iter().zip(["cam", "counter"]).map(|(e, cam)| {
            let radius = 1.0 / e.max_convex_curvature_per_mm;
            CamReport {
                cam,
                max_pressure_angle_deg: e.max_pressure_angle_deg,
                max_pressure_angle_at_deg: e.max_pressure_angle_at_deg,
                min_convex_radius_pitch_mm: radius,
                min_convex_radius_pitch_at_deg: e.max_convex_curvature_at_deg,
                min_convex_radius_profile_mm: roller.map(|r| radius - r),
            }
        });
        Some(cams.collect())
    }

    /// The report of this cam with its points every `step_deg` (see [`CamProfile::sample`]);
    /// `source` names where the motion came from.
    pub fn report(&self, source: impl Into<String>, step_deg: f64) -> ProfileReport {
        let design = self.design();
        let (pmax, pat, _) = self.max_pressure_angle();
        let (rmin, rat) = self.min_convex_radius_pitch();
        let r = design.roller_radius_mm;
        let points = |track| self.sample(track, step_deg).iter().map(PointReport::from).collect::<Vec<_>>();
        let counter = (self.track_count() == 2).then(|| self.track_extremes_all()[1]);
        let flat = self.flat_extremes_report();
        let roller_max = self.roller_max_mm();
        let (arm, pivot, offset) = match design.follower {
            Follower::Oscillating { arm_mm, pivot_mm } => (Some(arm_mm), Some(pivot_mm), None),
            Follower::Translating { offset_mm } => (None, None, Some(offset_mm)),
            Follower::Flat => (None, None, None),
        };
        let swing = matches!(design.follower, Follower::Oscillating { .. });
        ProfileReport {
            source: source.into(),
            follower: design.follower.description(),
            closure: design.closure.description(),
            prime_radius_mm: self.prime_radius_mm(),
            base_radius_mm: self.base_radius_mm(),
            roller_radius_mm: if design.follower == Follower::Flat { 0.0 } else { r },
            extremes: ProfileExtremes {
                max_pressure_angle_deg: pmax,
                max_pressure_angle_at_deg: pat,
                min_convex_radius_pitch_mm: rmin,
                min_convex_radius_pitch_at_deg: rat,
                undercut: self.undercut_at_deg().is_some(),
            },
            arm_mm: arm,
            pivot_mm: pivot,
            offset_mm: offset,
            stroke_mm: (!swing).then(|| self.stroke()),
            stroke_deg: swing.then(|| self.stroke()),
            roller_max_mm: roller_max,
            min_convex_radius_profile_mm: roller_max.map(|_| rmin - r),
            undercut_at_deg: self.undercut_at_deg(),
            min_radius_profile_mm: flat.map(|f| f.min_radius_profile_mm),
            min_radius_profile_at_deg: flat.map(|f| f.min_radius_profile_at_deg),
            least_prime_radius_no_cusp_mm: flat.map(|f| f.least_prime_radius_mm),
            face_min_mm: flat.map(|f| f.face_min_mm),
            face_max_mm: flat.map(|f| f.face_max_mm),
            counter_max_pressure_angle_deg: counter.map(|e| e.max_pressure_angle_deg),
            counter_max_pressure_angle_at_deg: counter.map(|e| e.max_pressure_angle_at_deg),
            cams: self.cam_reports(),
            points: points(0),
            counter_points: counter.map(|_| points(1)),
        }
    }
}
