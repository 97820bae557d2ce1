//! The loom file's carrier on the timing diagram's angle axis: where each carrier is across the
//! reed over a turn, when it is in the shed, the rapier's transfer, the air jet's relay plan and
//! the sley's back dwell — what `loom timing` draws under the frames and the shed.

use crate::insertion::{CarrierPath, insertion_error};
use crate::{InsertionKind, Loom, LoomError, Result};
use loomkin_drive::SleyAnalysis;
use loomkin_insertion::RelayOpen;
use loomkin_units::ShaftSpeed;
use serde::Serialize;

/// One carrier's (or one rapier head's) position across the reed against the main-shaft angle.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CarrierTrack {
    /// What it is: `"shuttle"`, `"bringer"`, `"taker"`, `"projectile"`, `"yarn tip"`.
    pub label: &'static str,
    /// Main-shaft angles in a pick's turn, deg (0° = the previous beat-up; a flight may end past 360°).
    pub angle_deg: Vec<f64>,
    /// The position at each angle, m from the selvedge where the weft enters (outside the reed
    /// below 0 or above the reed width: a rapier head at rest).
    pub position_m: Vec<f64>,
}

/// The rapier's transfer: where the bringer hands the yarn to the taker.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TransferPoint {
    /// The main-shaft angle of the transfer (greatest overlap), deg.
    pub angle_deg: f64,
    /// The bringer's tip then, m from the bringer's selvedge.
    pub position_m: f64,
}

/// The loom file's carrier over one turn of the main shaft, as the timing diagram draws it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CarrierTiming {
    /// The `[insertion] kind`: `shuttle`, `rapier`, `projectile` or `airjet`.
    pub kind: &'static str,
    /// The carriers' paths across the reed (the shuttle's straight entry-to-exit path; the rapier's
    /// two heads; the projectile's head from launch to arrival; the air jet's yarn tip from the
    /// launch to the far selvedge).
    pub tracks: Vec<CarrierTrack>,
    /// The angles between which a carrier is in the shed, deg (the shuttle's entry and exit; from
    /// the first rapier head's entry to the last one's exit; the projectile from its head at the
    /// entering selvedge to its tail at the far one; the yarn tip from the reed's entry to the far
    /// selvedge).
    pub in_shed_deg: [f64; 2],
    /// The rapier's transfer (none for other carriers).
    pub transfer: Option<TransferPoint>,
    /// The air jet's relay groups, each open from `open_deg` to `close_deg` (empty for other carriers).
    pub relay_plan: Vec<RelayOpen>,
    /// The sley's back dwell within the default tolerance of `loomkin sley analyze`, deg (`end >
    /// start`; none without a `[sley]`).
    pub sley_back_dwell_deg: Option<[f64; 2]>,
}

/// Points per drawn track.
const TRACK_POINTS: usize = 720;

/// `n + 1` angles from `a` to `b`, both ends included.
fn angles(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|k| if k == n { b } else { a + (b - a) * k as f64 / n as f64 }).collect()
}

/// The sley's back dwell within [`SleyAnalysis::DWELL_TOLERANCE_MM`]'s default, deg, when the
/// loom has a `[sley]`.
pub fn sley_back_dwell_deg(loom: &Loom) -> Result<Option<[f64; 2]>> {
    let Some(sley) = &loom.sley else { return Ok(None) };
    let tol = SleyAnalysis::DWELL_TOLERANCE_MM.default_value();
    let (start, end) = sley.back_dwell_rad(tol * 1e-3).map_err(|e| LoomError::field("sley", e.to_string()))?;
    Ok(Some([start.to_degrees(), end.to_degrees()]))
}

/// The loom file's carrier at its own speed (`[speed]`) over a turn: see [`CarrierTiming`].
pub fn carrier_timing(loom: &Loom) -> Result<CarrierTiming> {
    carrier_timing_at(loom, loom.speed)
}

/// The loom file's carrier at `speed` over a turn: see [`CarrierTiming`].
pub fn carrier_timing_at(loom: &Loom, speed: ShaftSpeed) -> Result<CarrierTiming> {
    let ins = &loom.insertion;
    let w = ins.reed_width_m;
    let sley_back_dwell_deg = sley_back_dwell_deg(loom)?;
    let mut transfer = None;
    let mut relay_plan = Vec::new();
    let (tracks, in_shed_deg) = match &ins.kind {
        InsertionKind::Shuttle => (
            vec![CarrierTrack {
                label: "shuttle",
                angle_deg: vec![ins.entry_deg, ins.exit_deg],
                position_m: vec![0.0, w],
            }],
            [ins.entry_deg, ins.exit_deg],
        ),
        InsertionKind::Rapier(r) => {
            let report = r.report(speed).map_err(insertion_error)?;
            let a = angles(0.0, 360.0, TRACK_POINTS);
            let head = |k: usize, label| {
                let position_m = a
                    .iter()
                    .map(|&t| {
                        let u = r.tip(k, t.to_radians()).u_m;
                        if k == 0 { u } else { r.reed_width_m - u }
                    })
                    .collect();
                CarrierTrack { label, angle_deg: a.clone(), position_m }
            };
            let at = report.transfer_deg;
            transfer = Some(TransferPoint { angle_deg: at, position_m: r.tip(0, at.to_radians()).u_m });
            let (from, to) = r.in_shed_deg();
            (vec![head(0, "bringer"), head(1, "taker")], [from, to])
        }
        InsertionKind::Projectile(p) => {
            let report = p.report(speed);
            let path = p.path(speed);
            let a = angles(report.launch_deg, report.arrival_deg, TRACK_POINTS);
            let position_m = a.iter().map(|&t| path.position_m(t)).collect();
            let (from, to) = CarrierPath::in_shed_deg(&path);
            (vec![CarrierTrack { label: "projectile", angle_deg: a, position_m }], [from, to])
        }
        InsertionKind::Airjet(j) => {
            let report = j.report(speed).map_err(insertion_error)?;
            let points = j.trajectory(speed).map_err(insertion_error)?;
            // Every integration step is a point; a drawing needs a few hundred.
            let every = (points.len() / TRACK_POINTS).max(1);
            let kept: Vec<_> = points
                .iter()
                .enumerate()
                .filter(|(i, _)| i % every == 0 || i + 1 == points.len())
                .map(|(_, p)| p)
                .collect();
            let angle = |t_s: f64| report.launch_deg + speed.deg_per_s() * t_s;
            let track = CarrierTrack {
                label: "yarn tip",
                angle_deg: kept.iter().map(|p| angle(p.t_s)).collect(),
                position_m: kept.iter().map(|p| p.x_m - j.reed_entry_m).collect(),
            };
            let span = [report.reed_entry_deg, report.arrival_deg];
            relay_plan = report.relay_plan;
            (vec![track], span)
        }
    };
    Ok(CarrierTiming { kind: ins.kind.name(), tracks, in_shed_deg, transfer, relay_plan, sley_back_dwell_deg })
}
