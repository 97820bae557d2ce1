//! The double rapier: a bringer and a taker head, each on its own drive, meeting in the shed.
//!
//! **The heads.** Each head's tip moves along the weft from its outer reversing point, `outer_mm`
//! outside its selvedge, to its inner reversing point and back, once per turn of the main shaft.
//! Its drive gives the displacement `u(φ)` from the outer reversing point (`0 ≤ u ≤ S`, the
//! stroke) and its rates per radian of main shaft; the tip lies `x = u − outer` inside its
//! selvedge. The bringer enters from the left selvedge, the taker from the right, across the reed
//! space `W`: the tips overlap by `x_b + x_t − W` (negative: a gap).
//!
//! **The drives.**
//! * `crank`: a crank-rocker four-bar the main shaft turns (crank, rod, rocker to its pivot; the
//!   loop of [`loomkin_drive::fourbar`], shared with the sley) whose rocker carries a gear sector of
//!   pitch radius `R_s`; the sector turns a pinion `r_p` on the shaft of the rapier wheel `R_w`, which
//!   drives the tape: `u = R_w·(R_s/r_p)·|θ − θ_outer|`, the rates `u⁽ᵏ⁾ = ±R_w·(R_s/r_p)·θ⁽ᵏ⁾`. The
//!   inner reversing point is the linkage's extended dead centre (crank and rod in line) or its
//!   folded one (`inner_dead_centre`), placed at `inner_deg` of the main shaft.
//! * `cam`: a cycle (`[…cycle]`, the cycle files of `loomkin cycle`, a translating follower in mm)
//!   read as the head's displacement against the main-shaft angle as written.
//! * `servo`: a servo law — a catalogue law over `motion_deg` out to the inner reversing point at
//!   `inner_deg`, the same law back over `motion_deg`, the head resting outside for the rest of the turn.
//!
//! **Offset reversing points** (the idea of WO2011120820 as we model it; the patent text was not at
//! hand): the taker's inner reversing point may come `Δ` degrees before the bringer's. With equal
//! reversing points both heads stop together at the transfer and the yarn is handed over at rest;
//! with an offset the taker is already withdrawing while the bringer still advances, so at the
//! greatest overlap both move the same way at the same speed (the overlap's rate is zero) and the
//! yarn is handed over in motion, taken up by the taker without the bringer's stop.
//!
//! **What is reported.** `transfer_overlap_mm`: the greatest overlap of the tips over the turn
//! (the taker's hook must pass the bringer's yarn: it must be positive), at `transfer_deg`.
//! `transfer_relative_speed_m_s`: the speed at which the tips close on each other when they meet
//! (the overlap's rate where it crosses zero rising, `(u_b' + u_t')·ω`) — the speed of the
//! taker's hook over the bringer's head when it catches the yarn. `transfer_speed_m_s`: the
//! heads' common speed at the greatest overlap (0 for equal reversing points). Extremes are
//! located by [`loomkin_numeric::scan_max`] (a grid's peaks refined by golden section) and the
//! meeting by [`loomkin_numeric::refine_root`], not read off a grid.

use std::collections::BTreeMap;
use std::f64::consts::TAU;

use loomkin_drive::fourbar::{Breaks, CrankRocker};
use loomkin_laws::{Cycle, CycleSpec, LawError, LawSpec, SegmentKind, SegmentSpec, StrokeUnit};
use loomkin_units::{Field, Range, ShaftSpeed};
use serde::{Deserialize, Serialize};

/// A wrong rapier description: the one [`InsertionError`](crate::InsertionError) (the name kept
/// for the rapier's callers).
pub type RapierError = crate::InsertionError;

/// One head's drive as written in the loom file (`[insertion.rapier.bringer]`,
/// `[insertion.rapier.taker]`). Lengths in mm, angles in degrees of the main shaft.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DriveTable {
    /// `crank`, `cam` or `servo`.
    pub drive: String,
    /// The tip outside its selvedge at the outer reversing point, mm ([`DriveTable::OUTER_MM`]).
    #[serde(default)]
    pub outer_mm: Option<f64>,
    /// Main-shaft angle of the inner reversing point, deg (crank and servo drives).
    #[serde(default)]
    pub inner_deg: Option<f64>,
    /// Crank radius, mm.
    #[serde(default)]
    pub crank_mm: Option<f64>,
    /// Connecting rod, mm.
    #[serde(default)]
    pub rod_mm: Option<f64>,
    /// The sector lever: its pivot to the rod's pin, mm.
    #[serde(default)]
    pub rocker_mm: Option<f64>,
    /// The sector's pivot, x from the crank centre, mm.
    #[serde(default)]
    pub pivot_x_mm: Option<f64>,
    /// The sector's pivot, y from the crank centre, mm.
    #[serde(default)]
    pub pivot_y_mm: Option<f64>,
    /// The gear sector's pitch radius, mm.
    #[serde(default)]
    pub sector_mm: Option<f64>,
    /// The pinion's pitch radius, mm.
    #[serde(default)]
    pub pinion_mm: Option<f64>,
    /// The rapier wheel's radius (the tape's pitch line), mm.
    #[serde(default)]
    pub wheel_mm: Option<f64>,
    /// `extended` (default) or `folded`: the linkage's dead centre at the inner reversing point.
    #[serde(default)]
    pub inner_dead_centre: Option<String>,
    /// `left` (default) or `right`: the four-bar's branch.
    #[serde(default)]
    pub assembly: Option<String>,
    /// The cam drive's cycle (a translating follower, mm: the head's displacement).
    #[serde(default)]
    pub cycle: Option<CycleSpec>,
    /// The servo law's name (the law catalogue, `loomkin law list`).
    #[serde(default)]
    pub law: Option<String>,
    /// The servo law's parameters, e.g. `{ ramp = 0.2 }` for `modified-trapezoid` (as a cycle
    /// file's segment takes them; `loomkin law list`).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub params: BTreeMap<String, toml::Value>,
    /// The servo law's motion out (and back), deg.
    #[serde(default)]
    pub motion_deg: Option<f64>,
    /// The servo drive's stroke, mm.
    #[serde(default)]
    pub stroke_mm: Option<f64>,
}

/// A length of the rapier drive: 0 < L ≤ 10⁴ mm.
const LENGTH: Range = Range::open_closed(0.0, 1e4, "mm");

impl DriveTable {
    /// `outer_mm`: 0 ≤ a ≤ 10⁴ mm, default 0.
    pub const OUTER_MM: Field = Field::new(
        "outer_mm",
        Range::closed(0.0, 1e4, "mm"),
        "How far outside its selvedge the head's tip rests at its outer reversing point: 0 ≤ a ≤ 10000 mm; 0 \
         when left out (the tip reaches the selvedge).",
    )
    .with_default(0.0);
    /// `inner_deg`: 0 ≤ φ < 360°, default 180°.
    pub const INNER_DEG: Field = Field::new(
        "inner_deg",
        Range::closed_open(0.0, 360.0, "deg"),
        "Main-shaft angle of the head's inner reversing point (the transfer): 0 ≤ φ < 360°, 180° when left \
         out (the middle of the turn between two beat-ups).",
    )
    .with_default(180.0);
    /// `crank_mm` and the drive's other lengths: 0 < L ≤ 10⁴ mm.
    pub const CRANK_MM: Field = Field::new(
        "crank_mm",
        LENGTH,
        "The rapier drive's crank radius: 0 < r ≤ 10000 mm (it must be the four-bar's shortest link; checked \
         with the other lengths).",
    );
    /// `rod_mm`.
    pub const ROD_MM: Field = Field::new("rod_mm", LENGTH, "The rapier drive's connecting rod: 0 < b ≤ 10000 mm.");
    /// `rocker_mm`.
    pub const ROCKER_MM: Field =
        Field::new("rocker_mm", LENGTH, "The sector lever, its pivot to the rod's pin: 0 < c ≤ 10000 mm.");
    /// `pivot_x_mm`, `pivot_y_mm`: |q| ≤ 10⁴ mm.
    pub const PIVOT_MM: Field = Field::new(
        "pivot_x_mm",
        Range::closed(-1e4, 1e4, "mm"),
        "The sector's pivot from the crank centre (pivot_x_mm, pivot_y_mm): −10000 … 10000 mm, farther from \
         the crank centre than the crank radius.",
    );
    /// `sector_mm`.
    pub const SECTOR_MM: Field = Field::new("sector_mm", LENGTH, "The gear sector's pitch radius: 0 < R_s ≤ 10000 mm.");
    /// `pinion_mm`.
    pub const PINION_MM: Field = Field::new("pinion_mm", LENGTH, "The pinion's pitch radius: 0 < r_p ≤ 10000 mm.");
    /// `wheel_mm`.
    pub const WHEEL_MM: Field =
        Field::new("wheel_mm", LENGTH, "The rapier wheel's radius at the tape: 0 < R_w ≤ 10000 mm.");
    /// `stroke_mm` of a servo drive.
    pub const STROKE_MM: Field = Field::new("stroke_mm", LENGTH, "The servo-driven head's stroke: 0 < S ≤ 10000 mm.");
    /// `motion_deg` of a servo drive.
    pub const MOTION_DEG: Field = Field::new(
        "motion_deg",
        Range::open_closed(0.0, 180.0, "deg"),
        "The servo law's motion out to the inner reversing point (and back): 0 < φ_m ≤ 180°, so out and back fit \
         in one turn.",
    );
}

/// The head's displacement from its outer reversing point and its rates per radian of main shaft.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct HeadMotion {
    /// Displacement from the outer reversing point, m.
    pub u_m: f64,
    /// du/dφ, m/rad.
    pub du: f64,
    /// d²u/dφ², m/rad².
    pub d2u: f64,
    /// d³u/dφ³, m/rad³.
    pub d3u: f64,
}

/// A checked head drive.
#[derive(Debug, Clone)]
pub enum HeadDrive {
    /// A crank-rocker with a gear sector, pinion and rapier wheel.
    Crank {
        /// The four-bar, lengths in m.
        linkage: CrankRocker,
        /// Wheel radius times the sector-to-pinion ratio, m per rad of rocker, signed so that `u` grows
        /// from the outer reversing point.
        gain_m: f64,
        /// Crank angle at φ = 0, rad.
        phase: f64,
        /// Rocker angle at the outer reversing point, rad.
        theta_outer: f64,
    },
    /// A cam or servo law: a machine cycle of the head's displacement (mm), with its spec.
    Cycle(Box<(CycleSpec, Cycle)>),
}

impl PartialEq for HeadDrive {
    /// Crank drives by their numbers, cycles by their specs.
    fn eq(&self, other: &Self) -> bool {
        match (self, other) {
            (
                Self::Crank { linkage: a, gain_m: b, phase: c, theta_outer: d },
                Self::Crank { linkage: e, gain_m: f, phase: g, theta_outer: h },
            ) => (a, b, c, d) == (e, f, g, h),
            (Self::Cycle(a), Self::Cycle(b)) => a.0 == b.0,
            _ => false,
        }
    }
}

/// The speed at which a cycle's SI rates are the rates per radian (ω = 1 rad/s).
const PER_RAD_RPM: f64 = 60.0 / TAU;

impl HeadDrive {
    /// The head's motion at main-shaft angle φ (rad).
    pub fn motion(&self, phi_rad: f64) -> HeadMotion {
        match self {
            Self::Crank { linkage, gain_m, phase, theta_outer } => {
                let s = linkage.at_crank(phi_rad + phase);
                let d = s.rocker_rad - theta_outer;
                // θ − θ_outer wrapped to (−π, π]: the rocker swings less than a half turn.
                let d = d - TAU * (d / TAU).round();
                HeadMotion {
                    u_m: gain_m * d,
                    du: gain_m * s.rocker_d1,
                    d2u: gain_m * s.rocker_d2,
                    d3u: gain_m * s.rocker_d3,
                }
            }
            Self::Cycle(c) => {
                let k = c.1.eval(phi_rad, PER_RAD_RPM);
                HeadMotion { u_m: k.s, du: k.v, d2u: k.a, d3u: k.j }
            }
        }
    }

    /// Reads one head's table; errors name `{prefix}.{key}`.
    pub fn from_table(t: &DriveTable, prefix: &str) -> Result<Self, RapierError> {
        let name = |k: &str| format!("{prefix}.{k}");
        let need = |k: &str, v: Option<f64>| {
            v.ok_or_else(|| RapierError::field(name(k), format!("the {} drive needs {k}", t.drive.trim())))
        };
        let unused = |keys: &[(&str, bool)]| -> Result<(), RapierError> {
            match keys.iter().find(|(_, given)| *given) {
                Some((k, _)) => {
                    Err(RapierError::field(name(k), format!("does not go with drive = \"{}\"", t.drive.trim())))
                }
                None => Ok(()),
            }
        };
        let crank_keys = [
            ("crank_mm", t.crank_mm.is_some()),
            ("rod_mm", t.rod_mm.is_some()),
            ("rocker_mm", t.rocker_mm.is_some()),
            ("pivot_x_mm", t.pivot_x_mm.is_some()),
            ("pivot_y_mm", t.pivot_y_mm.is_some()),
            ("sector_mm", t.sector_mm.is_some()),
            ("pinion_mm", t.pinion_mm.is_some()),
            ("wheel_mm", t.wheel_mm.is_some()),
            ("inner_dead_centre", t.inner_dead_centre.is_some()),
            ("assembly", t.assembly.is_some()),
        ];
        let servo_keys = [
            ("law", t.law.is_some()),
            ("params", !t.params.is_empty()),
            ("motion_deg", t.motion_deg.is_some()),
            ("stroke_mm", t.stroke_mm.is_some()),
        ];
        match t.drive.trim() {
            "crank" => {
                unused(&[("cycle", t.cycle.is_some())])?;
                unused(&servo_keys)?;
                let len = |f: &Field, k: &str, v: Option<f64>| -> Result<f64, RapierError> {
                    Ok(f.check_as(&name(k), need(k, v)?)? * 1e-3)
                };
                let r = len(&DriveTable::CRANK_MM, "crank_mm", t.crank_mm)?;
                let b = len(&DriveTable::ROD_MM, "rod_mm", t.rod_mm)?;
                let c = len(&DriveTable::ROCKER_MM, "rocker_mm", t.rocker_mm)?;
                let qx = DriveTable::PIVOT_MM.check_as(&name("pivot_x_mm"), need("pivot_x_mm", t.pivot_x_mm)?)? * 1e-3;
                let qy = DriveTable::PIVOT_MM.check_as(&name("pivot_y_mm"), need("pivot_y_mm", t.pivot_y_mm)?)? * 1e-3;
                let sector = len(&DriveTable::SECTOR_MM, "sector_mm", t.sector_mm)?;
                let pinion = len(&DriveTable::PINION_MM, "pinion_mm", t.pinion_mm)?;
                let wheel = len(&DriveTable::WHEEL_MM, "wheel_mm", t.wheel_mm)?;
                let inner = DriveTable::INNER_DEG.check_as(&name("inner_deg"), t.inner_deg.unwrap_or(180.0))?;
                let kappa = match t.assembly.as_deref().map(str::trim) {
                    None | Some("left") => 1.0,
                    Some("right") => -1.0,
                    Some(o) => {
                        return Err(RapierError::field(name("assembly"), format!("'{o}': expected left or right")));
                    }
                };
                let extended = match t.inner_dead_centre.as_deref().map(str::trim) {
                    None | Some("extended") => true,
                    Some("folded") => false,
                    Some(o) => {
                        return Err(RapierError::field(
                            name("inner_dead_centre"),
                            format!("'{o}': expected extended or folded"),
                        ));
                    }
                };
                let linkage = CrankRocker::new(r, b, c, qx, qy, kappa).map_err(|e| {
                    let why = match e {
                        Breaks::CrankReachesPivot => "the crank reaches the sector's pivot: crank_mm must be less than the pivot's distance",
                        Breaks::OpensAway => "the loop does not close with the crank pointing away from the pivot: crank + pivot distance must be less than rod + rocker",
                        Breaks::OpensToward => "the loop does not close with the crank pointing toward the pivot: pivot distance − crank must exceed |rod − rocker|",
                    };
                    RapierError::field(name("crank_mm"), format!("not a crank-rocker: {why}"))
                })?;
                let (alpha_in, theta_in) = linkage.dead_centre(extended);
                let (_, theta_out) = linkage.dead_centre(!extended);
                let swing = theta_in - theta_out;
                let swing = swing - TAU * (swing / TAU).round();
                let gain_m = wheel * sector / pinion * swing.signum();
                Ok(Self::Crank { linkage, gain_m, phase: alpha_in - inner.to_radians(), theta_outer: theta_out })
            }
            "cam" => {
                unused(&crank_keys)?;
                unused(&servo_keys)?;
                unused(&[("inner_deg", t.inner_deg.is_some())])?;
                let spec = t
                    .cycle
                    .as_ref()
                    .ok_or_else(|| RapierError::field(name("cycle"), "the cam drive needs a [cycle]"))?;
                if spec.unit != StrokeUnit::Mm || spec.period_deg != 360.0 {
                    return Err(RapierError::field(
                        name("cycle"),
                        "the head's cycle is a translating follower (unit = \"mm\") over one turn (period_deg = 360)",
                    ));
                }
                let cycle =
                    Cycle::new(spec).map_err(|e| RapierError::Law { field: name("cycle"), reason: e.to_string() })?;
                Ok(Self::Cycle(Box::new((spec.clone(), cycle))))
            }
            "servo" => {
                unused(&crank_keys)?;
                unused(&[("cycle", t.cycle.is_some())])?;
                let law =
                    t.law.as_deref().ok_or_else(|| RapierError::field(name("law"), "the servo drive needs law"))?;
                let spec = LawSpec::parse_table(law, &t.params).map_err(|e| RapierError::Law {
                    field: name(if matches!(e, LawError::UnknownLaw { .. }) { "law" } else { "params" }),
                    reason: e.to_string(),
                })?;
                let m = DriveTable::MOTION_DEG.check_as(&name("motion_deg"), need("motion_deg", t.motion_deg)?)?;
                let stroke = DriveTable::STROKE_MM.check_as(&name("stroke_mm"), need("stroke_mm", t.stroke_mm)?)?;
                let inner = DriveTable::INNER_DEG.check_as(&name("inner_deg"), t.inner_deg.unwrap_or(180.0))?;
                let mut segment = vec![
                    SegmentSpec {
                        from_deg: Some((inner - m).rem_euclid(360.0)),
                        ..SegmentSpec::moving(SegmentKind::Rise, m, &spec)
                    },
                    SegmentSpec::moving(SegmentKind::Return, m, &spec),
                ];
                if m < 180.0 {
                    segment.push(SegmentSpec::dwell(360.0 - 2.0 * m));
                }
                let spec = CycleSpec {
                    period_deg: 360.0,
                    unit: StrokeUnit::Mm,
                    stroke: Some(stroke),
                    speed_rpm: None,
                    segment,
                };
                let cycle =
                    Cycle::new(&spec).map_err(|e| RapierError::Law { field: name("law"), reason: e.to_string() })?;
                Ok(Self::Cycle(Box::new((spec, cycle))))
            }
            other => Err(RapierError::field(name("drive"), format!("'{other}': expected crank, cam or servo"))),
        }
    }
}

/// The `[insertion.rapier]` table: the two heads' drives.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RapierTable {
    /// The bringer (the head entering from the weft's supply side).
    pub bringer: DriveTable,
    /// The taker.
    pub taker: DriveTable,
}

/// A checked double rapier across a reed space.
#[derive(Debug, Clone, PartialEq)]
pub struct Rapier {
    /// The bringer's drive.
    pub bringer: HeadDrive,
    /// The taker's drive.
    pub taker: HeadDrive,
    /// Each tip's distance outside its selvedge at its outer reversing point, m (bringer, taker).
    pub outer_m: [f64; 2],
    /// The reed space, m.
    pub reed_width_m: f64,
}

/// One head's figures.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HeadReport {
    /// The head's stroke, outer to inner reversing point, mm.
    pub stroke_mm: f64,
    /// Main-shaft angle of the inner reversing point, deg.
    pub inner_deg: f64,
    /// Where the tip turns, inside its selvedge, mm.
    pub inner_position_mm: f64,
    /// Main-shaft angle at which the tip enters the shed (passes its selvedge inward), deg.
    pub entry_deg: f64,
    /// Main-shaft angle at which it leaves, deg.
    pub exit_deg: f64,
    /// Largest speed, m/s.
    pub peak_speed_m_s: f64,
    /// Largest |acceleration|, m/s².
    pub peak_acceleration_m_s2: f64,
}

/// The rapier's kinematic figures at a loom speed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RapierReport {
    /// Loom speed, rpm.
    pub speed_rpm: f64,
    /// The greatest overlap of the tips, mm.
    pub transfer_overlap_mm: f64,
    /// Where, deg of main shaft.
    pub transfer_deg: f64,
    /// The speed at which the tips close on each other when they meet, m/s.
    pub transfer_relative_speed_m_s: f64,
    /// The heads' common speed at the greatest overlap, m/s (0 for equal reversing points).
    pub transfer_speed_m_s: f64,
    /// Where the tips meet, from the bringer's selvedge, mm.
    pub transfer_position_mm: f64,
    /// Main-shaft angle at which they meet, deg.
    pub meet_deg: f64,
    /// The larger of the heads' peak speeds, m/s.
    pub peak_head_speed_m_s: f64,
    /// The larger of the heads' peak accelerations, m/s².
    pub peak_head_acceleration_m_s2: f64,
    /// The bringer.
    pub bringer: HeadReport,
    /// The taker.
    pub taker: HeadReport,
}

/// Grid intervals per turn for the extremes' scans (each peak is then refined).
const SCAN: usize = 720;

impl Rapier {
    /// The rapier of a `[insertion.rapier]` table across `reed_width_m`; errors name
    /// `{prefix}.bringer.…` and `{prefix}.taker.…`.
    pub fn new(t: &RapierTable, reed_width_m: f64, prefix: &str) -> Result<Self, RapierError> {
        let pb = format!("{prefix}.bringer");
        let pt = format!("{prefix}.taker");
        let outer = |d: &DriveTable, p: &str| -> Result<f64, RapierError> {
            Ok(DriveTable::OUTER_MM.check_as(&format!("{p}.outer_mm"), d.outer_mm.unwrap_or(0.0))? * 1e-3)
        };
        Ok(Self {
            bringer: HeadDrive::from_table(&t.bringer, &pb)?,
            taker: HeadDrive::from_table(&t.taker, &pt)?,
            outer_m: [outer(&t.bringer, &pb)?, outer(&t.taker, &pt)?],
            reed_width_m,
        })
    }

    /// The head `k` (0 bringer, 1 taker).
    pub fn head(&self, k: usize) -> &HeadDrive {
        if k == 0 { &self.bringer } else { &self.taker }
    }

    /// The tip of head `k` inside its selvedge at φ (rad), m (negative: outside), with its rates.
    pub fn tip(&self, k: usize, phi_rad: f64) -> HeadMotion {
        let m = self.head(k).motion(phi_rad);
        HeadMotion { u_m: m.u_m - self.outer_m[k], ..m }
    }

    /// The tips' overlap at φ, m (`x_b + x_t − W`), and its rate per rad.
    pub fn overlap(&self, phi_rad: f64) -> (f64, f64) {
        let (b, t) = (self.tip(0, phi_rad), self.tip(1, phi_rad));
        (b.u_m + t.u_m - self.reed_width_m, b.du + t.du)
    }

    /// The head `k`'s stroke and inner reversing point: the largest displacement over the turn and
    /// where (rad in [0, 2π)).
    pub fn inner(&self, k: usize) -> (f64, f64) {
        let m = loomkin_numeric::scan_max(0.0, TAU, SCAN, |p| self.head(k).motion(p).u_m);
        (m.value, m.at.rem_euclid(TAU))
    }

    /// The angles (rad, `entry < exit`, `exit` possibly past 2π) between which head `k`'s tip is
    /// inside its selvedge, or `None` when it never enters. The tip moves monotonically between
    /// its reversing points, so each is the one root on its side of the inner reversing point.
    pub fn in_shed(&self, k: usize) -> Option<(f64, f64)> {
        let (umax, at) = self.inner(k);
        if umax <= self.outer_m[k] {
            return None;
        }
        let (umin, at_min) = {
            let m = loomkin_numeric::scan_max(at, at + TAU, SCAN, |p| -self.head(k).motion(p).u_m);
            (-m.value, m.at)
        };
        if umin >= self.outer_m[k] {
            return Some((at - TAU / 2.0, at + TAU / 2.0));
        }
        let g = |p: f64| {
            let t = self.tip(k, p);
            (t.u_m, t.du)
        };
        let entry = loomkin_numeric::refine_root(at_min - TAU, at, true, g);
        let exit = loomkin_numeric::refine_root(at, at_min, false, g);
        Some((entry, exit))
    }

    /// The kinematic report at `speed`. Fails when the tips never meet.
    pub fn report(&self, speed: ShaftSpeed) -> Result<RapierReport, RapierError> {
        let w = speed.rad_per_s();
        let over = loomkin_numeric::scan_max(0.0, TAU, SCAN, |p| self.overlap(p).0);
        if over.value < 0.0 {
            return Err(RapierError::field(
                "insertion.rapier",
                format!(
                    "the heads never meet: their tips stay at least {:.3} mm apart (lengthen the strokes or move the \
                     outer reversing points in)",
                    -over.value * 1e3
                ),
            ));
        }
        // The meeting: the overlap's zero before its peak (it rises from the last negative point).
        let at = over.at;
        let lo = loomkin_numeric::scan_max(at - TAU, at, SCAN, |p| -self.overlap(p).0);
        let meet =
            if lo.value > 0.0 { loomkin_numeric::refine_root(lo.at, at, true, |p| self.overlap(p)) } else { at - TAU };
        let (_, rate) = self.overlap(meet);
        let head = |k: usize| -> HeadReport {
            let (umax, inner) = self.inner(k);
            let umin = -loomkin_numeric::scan_max(0.0, TAU, SCAN, |p| -self.head(k).motion(p).u_m).value;
            let (entry, exit) = self.in_shed(k).unwrap_or((f64::NAN, f64::NAN));
            let v = loomkin_numeric::scan_max(0.0, TAU, SCAN, |p| self.head(k).motion(p).du.abs());
            let a = loomkin_numeric::scan_max(0.0, TAU, SCAN, |p| self.head(k).motion(p).d2u.abs());
            HeadReport {
                stroke_mm: (umax - umin) * 1e3,
                inner_deg: inner.to_degrees(),
                inner_position_mm: (umax - self.outer_m[k]) * 1e3,
                entry_deg: entry.rem_euclid(TAU).to_degrees(),
                exit_deg: exit.rem_euclid(TAU).to_degrees(),
                peak_speed_m_s: v.value * w,
                peak_acceleration_m_s2: a.value * w * w,
            }
        };
        let (b, t) = (head(0), head(1));
        Ok(RapierReport {
            speed_rpm: speed.rpm(),
            transfer_overlap_mm: over.value * 1e3,
            transfer_deg: at.rem_euclid(TAU).to_degrees(),
            transfer_relative_speed_m_s: rate * w,
            transfer_speed_m_s: self.tip(0, at).du * w,
            transfer_position_mm: self.tip(0, meet).u_m * 1e3,
            meet_deg: meet.rem_euclid(TAU).to_degrees(),
            peak_head_speed_m_s: b.peak_speed_m_s.max(t.peak_speed_m_s),
            peak_head_acceleration_m_s2: b.peak_acceleration_m_s2.max(t.peak_acceleration_m_s2),
            bringer: b,
            taker: t,
        })
    }
}
