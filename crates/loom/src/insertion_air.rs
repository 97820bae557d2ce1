//! The projectile and the air jet on the whole loom: their flights on the main-shaft angle, the
//! projectile's clearance in the shed over a pattern repeat and its fit in the sley's back dwell.

use crate::insertion::{
    CarrierPath, CarrierShed, Clearance, clearance, clearance_panel, insertion_error, with_selvedges,
};
use crate::{InsertionKind, Loom, LoomError, Motion, Pattern, Result};
use loomkin_drive::SleyAnalysis;
use loomkin_insertion::{Airjet, AirjetReport, Projectile, ProjectilePath, ProjectileReport, TipPoint};
use loomkin_plot::{Figure, Note, Panel, Series, XBand, sig4};
use loomkin_units::ShaftSpeed;
use serde::Serialize;

impl CarrierPath for ProjectilePath {
    /// From the head at the entering selvedge to the tail at the far one.
    fn in_shed_deg(&self) -> (f64, f64) {
        ProjectilePath::in_shed_deg(self)
    }

    /// The projectile's head, from the entering selvedge.
    fn position_m(&self, angle_deg: f64) -> f64 {
        ProjectilePath::position_m(self, angle_deg)
    }
}

/// The loom file's projectile, or an error naming `insertion.kind` when its carrier is another.
pub fn projectile_of(loom: &Loom) -> Result<&Projectile> {
    match &loom.insertion.kind {
        InsertionKind::Projectile(p) => Ok(p),
        other => Err(LoomError::field(
            "insertion.kind",
            format!(
                "the loom's carrier is a {}: give kind = \"projectile\" with [insertion.projectile] \
                 (docs/insertion.md)",
                other.name()
            ),
        )),
    }
}

/// The sley's back dwell and whether a carrier's span in the shed lies inside it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DwellFit {
    /// Where the back dwell starts and ends, deg (within `dwell_tolerance_mm` of the back dead
    /// centre; the end past the start, in the turn of the carrier's span when they overlap).
    pub sley_back_dwell_deg: [f64; 2],
    /// The dwell's tolerance, mm (the default of `loomkin sley analyze`).
    pub dwell_tolerance_mm: f64,
    /// Whether the carrier is in the shed only while the reed dwells at the back.
    pub fits_sley_dwell: bool,
}

/// The fit of the span `[from, to]` (deg) in the back dwell of the loom's `[sley]`, when it has one.
pub fn dwell_fit(loom: &Loom, from: f64, to: f64) -> Result<Option<DwellFit>> {
    let Some([start, end]) = crate::insertion_timing::sley_back_dwell_deg(loom)? else { return Ok(None) };
    let tol = SleyAnalysis::DWELL_TOLERANCE_MM.default_value();
    // The dwell's turn nearest the span (their middles closest).
    let k = (((from + to) - (start + end)) / 720.0).round();
    let (s, e) = (start + 360.0 * k, end + 360.0 * k);
    Ok(Some(DwellFit { sley_back_dwell_deg: [s, e], dwell_tolerance_mm: tol, fits_sley_dwell: s <= from && to <= e }))
}

/// The projectile of a loom on its shed: the picking, the flight, the brake, the clearance of its
/// guide-teeth path over the repeat, and the sley's dwell.
#[derive(Debug, Clone, Serialize)]
pub struct ProjectileCheck {
    /// The picking, the flight and the brake.
    #[serde(flatten)]
    pub projectile: ProjectileReport,
    /// The clearance over every pick.
    #[serde(flatten)]
    pub clearance: Clearance,
    /// The sley's back dwell and the flight's fit in it (none without a `[sley]`).
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub dwell: Option<DwellFit>,
    /// Picks in the repeat.
    pub picks: usize,
}

/// The projectile of `loom` at `speed` weaving `pattern`.
pub fn projectile_check(loom: &Loom, pattern: &Pattern, speed: ShaftSpeed) -> Result<ProjectileCheck> {
    let p = projectile_of(loom)?;
    let report = p.report(speed);
    let path = p.path(speed);
    let clearance = clearance(loom, pattern, &path)?;
    let dwell = dwell_fit(loom, report.shed_entry_deg, report.shed_exit_deg)?;
    Ok(ProjectileCheck { projectile: report, clearance, dwell, picks: pattern.picks() })
}

/// Points of the flight's plot.
const PLOT_POINTS: usize = 600;

/// The projectile's plot: its head across the reed and its speed from the launch to the brake, the
/// clearance of the worst pick while it is in the shed, the sley's back dwell as a band.
pub fn projectile_figure(loom: &Loom, pattern: &Pattern, c: &ProjectileCheck, speed: ShaftSpeed) -> Result<Figure> {
    let p = projectile_of(loom)?;
    let path = p.path(speed);
    let motion = Motion::new(loom, pattern)?;
    let shed = CarrierShed::new(loom, &motion, pattern)?;
    let r = &c.projectile;
    let (a0, a1) = (r.launch_deg, r.arrival_deg);
    let angles: Vec<f64> = (0..=PLOT_POINTS).map(|k| a0 + (a1 - a0) * k as f64 / PLOT_POINTS as f64).collect();
    let head: Vec<(f64, f64)> = angles.iter().map(|&a| (a, path.position_m(a) * 1e3)).collect();
    let v: Vec<(f64, f64)> = angles.iter().map(|&a| (a, p.flight.v_at((a - a0) / (6.0 * speed.rpm())))).collect();
    let cl = &c.clearance;
    let [from, to] = cl.in_shed_deg;
    let bands = |label: &str| {
        let mut b = vec![XBand::new(from, to, label, XBand::WINDOW)];
        if let Some(d) = &c.dwell {
            b.push(XBand::new(d.sley_back_dwell_deg[0], d.sley_back_dwell_deg[1], "sley back dwell", XBand::DWELL));
        }
        b
    };
    let width_mm = p.reed_width_m * 1e3;
    let panels = vec![
        with_selvedges(
            Panel::new("head across the reed [mm]", vec![Series::line("projectile", head)]),
            width_mm,
            "entering selvedge",
            "far selvedge",
        )
        .with_x_bands(bands("in the shed")),
        Panel::new("speed [m/s]", vec![Series::line("projectile", v)]).with_notes([Note::new(
            a1,
            r.arrival_speed_m_s,
            format!("{} m/s into the brake", sig4(r.arrival_speed_m_s)),
        )]),
        clearance_panel(&shed, cl, bands("in the shed")),
    ];
    let title = format!(
        "projectile at {} rpm: {} m/s, flight {} ms, arrives at {}°, least clearance {} mm (pick {})",
        sig4(speed.rpm()),
        sig4(r.projectile_speed_m_s),
        sig4(r.flight_time_ms),
        sig4(r.arrival_deg),
        sig4(cl.min_clearance_mm),
        cl.worst_pick
    );
    Ok(Figure::new(title, "main-shaft angle [deg]", panels))
}

/// The loom file's air jet, or an error naming `insertion.kind` when its carrier is another.
pub fn airjet_of(loom: &Loom) -> Result<&Airjet> {
    match &loom.insertion.kind {
        InsertionKind::Airjet(a) => Ok(a),
        other => Err(LoomError::field(
            "insertion.kind",
            format!(
                "the loom's carrier is a {}: give kind = \"airjet\" with [insertion.airjet] (docs/insertion.md)",
                other.name()
            ),
        )),
    }
}

/// The air jet of `loom` at `speed`: the tip's flight and the relay plan.
pub fn airjet_check(loom: &Loom, speed: ShaftSpeed) -> Result<AirjetReport> {
    airjet_of(loom)?.report(speed).map_err(insertion_error)
}

/// The air jet's plot: the tip across the reed, and its speed with the air's at the tip, against
/// the main-shaft angle, each relay group's opening as a band.
pub fn airjet_figure(loom: &Loom, r: &AirjetReport, speed: ShaftSpeed) -> Result<Figure> {
    let a = airjet_of(loom)?;
    let points = a.trajectory(speed).map_err(insertion_error)?;
    let angle = |t: f64| r.launch_deg + 6.0 * speed.rpm() * t;
    // Every step is a point; a plot needs a few hundred.
    let every = (points.len() / PLOT_POINTS).max(1);
    let pick: Vec<&TipPoint> =
        points.iter().enumerate().filter(|(i, _)| i % every == 0 || *i + 1 == points.len()).map(|(_, p)| p).collect();
    let entry = a.reed_entry_m;
    let tip: Vec<(f64, f64)> = pick.iter().map(|p| (angle(p.t_s), (p.x_m - entry) * 1e3)).collect();
    let v: Vec<(f64, f64)> = pick.iter().map(|p| (angle(p.t_s), p.v_m_s)).collect();
    let air: Vec<(f64, f64)> = pick.iter().map(|p| (angle(p.t_s), p.air_m_s)).collect();
    let bands = || -> Vec<XBand> {
        r.relay_plan
            .iter()
            .enumerate()
            .map(|(i, o)| {
                let color = if i % 2 == 0 { XBand::WINDOW } else { XBand::DWELL };
                XBand::new(o.open_deg, o.close_deg, format!("{}", o.group), color)
            })
            .collect()
    };
    let panels = vec![
        with_selvedges(
            Panel::new("tip across the reed [mm]", vec![Series::line("yarn tip", tip)]),
            a.reed_width_m * 1e3,
            "entering selvedge",
            "far selvedge",
        )
        .with_x_bands(bands()),
        Panel::new("speed [m/s]", vec![Series::line("yarn tip", v), Series::line("air at the tip", air)])
            .with_x_bands(bands())
            .with_notes([Note::new(
                r.arrival_deg,
                r.tip_speed_at_exit_m_s,
                format!("{} m/s at the far selvedge", sig4(r.tip_speed_at_exit_m_s)),
            )]),
    ];
    let title = format!(
        "air jet at {} rpm: arrives at {}° after {} ms, {} relay groups open {} ms in all",
        sig4(speed.rpm()),
        sig4(r.arrival_deg),
        sig4(r.flight_time_ms),
        r.relay_plan.len(),
        sig4(r.relay_open_ms)
    );
    Ok(Figure::new(title, "main-shaft angle [deg] (bands: relay groups open)", panels))
}
