//! The loom file (TOML): one machine on the main-shaft angle.

use crate::{FrameLaw, LoomError, Result};
use loomkin_drive::{CamSley, CamSleyTable, FourBarSley, Sley, SleyError, SleyTable};
use loomkin_insertion::{PickBudget, required_speed_m_s, window_needed_deg};
use loomkin_laws::{CycleSpec, LawSpec};
use loomkin_picking::{Mechanism, Method, Settings, simulate};
use loomkin_shed::{ShedLaw, preset};
use loomkin_units::{Range, ShaftSpeed};
use serde::Deserialize;
use std::collections::BTreeMap;

/// Most heald frames on one loom.
pub const MAX_FRAMES: usize = 64;
/// Standard gravity, m/s².
pub const G_M_S2: f64 = loomkin_units::STANDARD_GRAVITY_M_S2;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LoomFile<S = SleyTable> {
    name: Option<String>,
    speed_rpm: f64,
    efficiency: Option<f64>,
    motor_torque_n_m: Option<f64>,
    geometry: GeometryFile,
    frames: FramesFile,
    warp: Option<WarpFile>,
    shedding: SheddingFile,
    insertion: InsertionFile,
    beat_up: Option<BeatUpFile>,
    sley: Option<S>,
    drive: Option<DriveFile>,
}

/// A `[sley]` table as written: the four-bar, or a cam sley (`drive = "cam"`).
#[derive(Debug)]
enum SleyFile {
    FourBar(SleyTable),
    Cam(Box<CamSleyTable>),
}

impl<S> LoomFile<S> {
    fn map_sley(self, g: impl FnOnce(S) -> SleyFile) -> LoomFile<SleyFile> {
        LoomFile {
            name: self.name,
            speed_rpm: self.speed_rpm,
            efficiency: self.efficiency,
            motor_torque_n_m: self.motor_torque_n_m,
            geometry: self.geometry,
            frames: self.frames,
            warp: self.warp,
            shedding: self.shedding,
            insertion: self.insertion,
            beat_up: self.beat_up,
            sley: self.sley.map(g),
            drive: self.drive,
        }
    }
}

/// The loom file deserialised, its `[sley]` table as the four-bar's or (with `drive` given) the cam
/// sley's, so that errors in either carry their line and column.
fn parse_loom_file(text: &str) -> Result<LoomFile<SleyFile>> {
    let reason = |e: toml::de::Error| LoomError::field("loom file", loomkin_units::toml_reason(text, &e));
    let cam = toml::from_str::<toml::Table>(text)
        .ok()
        .is_some_and(|doc| doc.get("sley").and_then(|s| s.get("drive")).is_some());
    Ok(if cam {
        toml::from_str::<LoomFile<CamSleyTable>>(text).map_err(reason)?.map_sley(|t| SleyFile::Cam(Box::new(t)))
    } else {
        toml::from_str::<LoomFile>(text).map_err(reason)?.map_sley(SleyFile::FourBar)
    })
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct DriveFile {
    rotating_inertia_kg_m2: Option<f64>,
    friction_torque_n_m: Option<f64>,
    flywheel_kg_m2: Option<f64>,
    motor: Option<String>,
    motor_curve: Option<String>,
    synchronous_rpm: Option<f64>,
    rated_rpm: Option<f64>,
    rated_power_kw: Option<f64>,
    breakdown_ratio: Option<f64>,
    gear_ratio: Option<f64>,
    servo_gain_n_m_s: Option<f64>,
    servo_integral_s: Option<f64>,
    servo_torque_limit_n_m: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct GeometryFile {
    frame_distances_mm: Option<Vec<f64>>,
    first_frame_mm: Option<f64>,
    frame_pitch_mm: Option<f64>,
    frames: Option<i64>,
    reed_mm: f64,
    back_rest_mm: f64,
    #[serde(default)]
    warp_line_mm: f64,
    front_stroke_mm: Option<f64>,
    lifts: Option<String>,
    strokes_mm: Option<Vec<f64>>,
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum OneOrMany {
    One(f64),
    Many(Vec<f64>),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct FramesFile {
    mass_kg: OneOrMany,
    spring_n_per_mm: Option<OneOrMany>,
    spring_preload_n: Option<OneOrMany>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct WarpFile {
    ends: f64,
    tension_per_end_n: f64,
    #[serde(default)]
    stiffness_per_end_n: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SheddingFile {
    preset: Option<String>,
    law: Option<String>,
    params: Option<BTreeMap<String, toml::Value>>,
    positive: Option<toml::Value>,
    negative: Option<toml::Value>,
    positive_fraction: Option<f64>,
    cycle: Option<CycleSpec>,
    motion_deg: Option<f64>,
    crossing_deg: f64,
    stagger_deg: Option<Vec<f64>>,
    groups: Option<Vec<Vec<i64>>>,
    max_stagger_deg: Option<f64>,
    drive: Option<String>,
    servo: Option<toml::Value>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct InsertionFile {
    carrier_height_mm: f64,
    #[serde(default)]
    carrier_width_mm: f64,
    reed_width_mm: f64,
    #[serde(default)]
    carrier_length_mm: f64,
    entry_deg: Option<f64>,
    exit_deg: Option<f64>,
    window_deg: Option<f64>,
    centre_deg: Option<f64>,
    mean_speed_m_s: Option<f64>,
    shuttle: Option<toml::Table>,
    kind: Option<String>,
    rapier: Option<toml::Table>,
    projectile: Option<toml::Table>,
    airjet: Option<toml::Table>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BeatUpFile {
    #[serde(default)]
    angle_deg: f64,
}

/// How the lifts of the frames are set.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Lifts {
    /// Clean shed: every stroke proportional to the frame's distance from the fell.
    Clean,
    /// Every frame's largest warp strain equal to the front frame's.
    EqualStrain,
    /// The strokes given in the file.
    Given,
}

/// The geometry of the shed in the warp's vertical plane (SI units).
///
/// The fell is the origin, `x` runs back along the warp; the warp line is the straight line from
/// the fell to the back rest at height `warp_line_m`. Each heald eye sits on that line at mid-stroke.
#[derive(Debug, Clone, PartialEq)]
pub struct Geometry {
    /// Distance of each frame's heald eyes from the fell, front first, m.
    pub frame_m: Vec<f64>,
    /// Distance of the reed from the fell at weft insertion, m.
    pub reed_m: f64,
    /// Distance of the back rest from the fell, m.
    pub back_rest_m: f64,
    /// Height of the back rest over the fell, m.
    pub warp_line_m: f64,
    /// Full stroke of each frame (bottom to top), m.
    pub stroke_m: Vec<f64>,
    /// How the strokes were set.
    pub lifts: Lifts,
}

/// One heald frame's mass and return spring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameProps {
    /// Moving mass, kg.
    pub mass_kg: f64,
    /// Return-spring stiffness, N/m.
    pub spring_n_m: f64,
    /// Return-spring force with the frame at the bottom of its stroke, N.
    pub preload_n: f64,
}

/// The warp: ends, tension per end at the level shed and the per-end stiffness.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Warp {
    /// Warp ends on the loom (shared among the frames by the draft's threading, else equally).
    pub ends: f64,
    /// Tension per end with the shed level, N.
    pub tension_per_end_n: f64,
    /// Tension gained per end per unit strain, N (`T = T₀ + K·ε`).
    pub stiffness_per_end_n: f64,
}

/// Where the carrier's speed comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum CarrierSpeed {
    /// A mean speed across the shed given in the file, m/s.
    Mean(f64),
    /// The shuttle of the picking study: its velocity at the loom speed, less half its retardation.
    Shuttle {
        /// Velocity leaving the picker, m/s.
        release_m_s: f64,
        /// Retardation in the shed, %.
        retardation_pct: f64,
    },
    /// Implied by the entry and exit angles at the loom speed.
    FromWindow,
}

/// Which carrier inserts the weft: `[insertion] kind`, with the carrier's own sub-table
/// (`[insertion.rapier]`, `[insertion.projectile]`, `[insertion.airjet]`).
#[derive(Debug, Clone, PartialEq, Default)]
#[non_exhaustive]
pub enum InsertionKind {
    /// `kind = "shuttle"` (the default): a carrier known by its size and speed, the shuttle of the
    /// picking study (`[insertion.shuttle]`) or a mean speed.
    #[default]
    Shuttle,
    /// `kind = "rapier"`: a double rapier, its heads' drives in `[insertion.rapier]`.
    Rapier(Box<loomkin_insertion::Rapier>),
    /// `kind = "projectile"`: torsion-bar picking, `[insertion.projectile]`.
    Projectile(Box<loomkin_insertion::Projectile>),
    /// `kind = "airjet"`: a main nozzle and relay nozzles, `[insertion.airjet]`.
    Airjet(Box<loomkin_insertion::Airjet>),
}

impl InsertionKind {
    /// The kinds `[insertion] kind` takes.
    pub const NAMES: [&'static str; 4] = ["shuttle", "rapier", "projectile", "airjet"];

    /// The kind's name as the file writes it.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Shuttle => "shuttle",
            Self::Rapier(_) => "rapier",
            Self::Projectile(_) => "projectile",
            Self::Airjet(_) => "airjet",
        }
    }
}

/// The weft insertion: the carrier and the window it needs.
#[derive(Debug, Clone, PartialEq)]
pub struct Insertion {
    /// Which carrier (`kind`), with its model.
    pub kind: InsertionKind,
    /// Carrier height, m.
    pub carrier_height_m: f64,
    /// Carrier width along the warp, from the reed toward the fell, m.
    pub carrier_width_m: f64,
    /// Reed space (width of the warp in the reed), m.
    pub reed_width_m: f64,
    /// Carrier length (shuttle length), m.
    pub carrier_length_m: f64,
    /// The reed space and the carrier length in mm as the file gives them (the budget reports
    /// them in mm; mm → m → mm does not give back every number).
    pub written_mm: [f64; 2],
    /// Angle at which the carrier enters the shed, deg (within one turn).
    pub entry_deg: f64,
    /// Angle at which it leaves, deg.
    pub exit_deg: f64,
    /// Where its speed comes from.
    pub speed: CarrierSpeed,
}

impl Insertion {
    /// Mean speed across the shed at `speed_rpm`, m/s.
    pub fn mean_speed_m_s(&self, speed_rpm: f64) -> f64 {
        match self.speed {
            CarrierSpeed::Mean(v) => v,
            CarrierSpeed::Shuttle { release_m_s, retardation_pct } => release_m_s * (1.0 - retardation_pct / 200.0),
            CarrierSpeed::FromWindow => {
                required_speed_m_s(speed_rpm, self.exit_deg - self.entry_deg, self.reed_width_m, self.carrier_length_m)
            }
        }
    }
}

/// The shedding: the law, its crossing angle, and the stagger of every frame.
#[derive(Debug, Clone)]
pub struct Shedding {
    /// The law of a moving frame.
    pub law: FrameLaw,
    /// Angle in the turn at which a changing frame passes mid-stroke, deg (`[0, 360)`).
    pub crossing_deg: f64,
    /// Stagger of each frame, deg (added to its crossing angle).
    pub stagger_deg: Vec<f64>,
    /// The frame groups (0-based frame indices) when the file staggers by group.
    pub groups: Option<Vec<Vec<usize>>>,
    /// Largest stagger the optimiser may choose, deg.
    pub max_stagger_deg: f64,
    /// The frames' servo drives when `drive = "servo"` (`[shedding.servo]`); `None` for the
    /// mechanical dobby (the default, `drive = "dobby"`).
    pub servo: Option<loomkin_eshed::ServoShedding>,
}

/// A checked loom.
#[derive(Debug, Clone)]
pub struct Loom {
    /// Name from the file.
    pub name: String,
    /// Main-shaft speed.
    pub speed: ShaftSpeed,
    /// Efficiency of the shedding drive (torque = power / (ω·η)).
    pub efficiency: f64,
    /// Torque the shedding drive's motor may give at the main shaft, N·m (`motor_torque_n_m`,
    /// optional): the limit line of the torque plot.
    pub motor_torque_n_m: Option<f64>,
    /// The shed geometry.
    pub geometry: Geometry,
    /// The frames, front first.
    pub frames: Vec<FrameProps>,
    /// The warp.
    pub warp: Warp,
    /// The shedding law and stagger.
    pub shedding: Shedding,
    /// The weft insertion.
    pub insertion: Insertion,
    /// Beat-up angle, deg.
    pub beat_up_deg: f64,
    /// The sley (`[sley]`): a crank-rocker four-bar, or a cam sley (`drive = "cam"`), when the file
    /// describes it. Its `beat_up_deg` is the file's `[beat_up] angle_deg` when the table leaves it
    /// out, and must equal it when given.
    pub sley: Option<Sley>,
    /// The main-shaft drive (`[drive]`): rotating parts, friction, flywheel, motor.
    pub drive: crate::DriveSpec,
}

fn mm(v: f64) -> f64 {
    v * 1e-3
}

fn per_frame(field: &str, v: Option<&OneOrMany>, n: usize, default: f64, range: Range) -> Result<Vec<f64>> {
    let out = match v {
        None => vec![default; n],
        Some(OneOrMany::One(x)) => vec![range.check(field, *x)?; n],
        Some(OneOrMany::Many(xs)) => {
            if xs.len() != n {
                return Err(LoomError::field(
                    field,
                    format!("{} values for {n} frames: give one or one per frame", xs.len()),
                ));
            }
            xs.iter().enumerate().map(|(i, x)| range.check(&format!("{field}[{i}]"), *x)).collect::<Result<_, _>>()?
        }
    };
    Ok(out)
}

impl Loom {
    /// Reads and checks a loom file. Every number is range-checked and every error names its
    /// field as `section.key` (`geometry.frame_distances_mm[3]`).
    pub fn from_toml(text: &str) -> Result<Self> {
        let f = parse_loom_file(text)?;
        let speed = ShaftSpeed::from_rpm(f.speed_rpm)?;
        let efficiency = Range::open_closed(0.0, 1.0, "").check("efficiency", f.efficiency.unwrap_or(1.0))?;
        let motor_torque_n_m = match f.motor_torque_n_m {
            Some(t) => Some(Range::open_closed(0.0, 1e7, "N·m").check("motor_torque_n_m", t)?),
            None => None,
        };
        let g = &f.geometry;
        let back = Range::open_closed(0.0, 20_000.0, "mm").check("geometry.back_rest_mm", g.back_rest_mm)?;
        let distances = match (&g.frame_distances_mm, g.first_frame_mm, g.frame_pitch_mm, g.frames) {
            (Some(d), None, None, None) => d.clone(),
            (None, Some(first), Some(pitch), Some(n)) => {
                let n = usize::try_from(n).ok().filter(|n| (1..=MAX_FRAMES).contains(n)).ok_or_else(|| {
                    LoomError::field("geometry.frames", format!("{n}: allowed 1 to {MAX_FRAMES} frames"))
                })?;
                Range::finite("mm").check("geometry.first_frame_mm", first)?;
                Range::open_closed(0.0, 1000.0, "mm").check("geometry.frame_pitch_mm", pitch)?;
                (0..n).map(|i| first + i as f64 * pitch).collect()
            }
            _ => {
                return Err(LoomError::field(
                    "geometry.frame_distances_mm",
                    "give frame_distances_mm (front first), or first_frame_mm, frame_pitch_mm and frames",
                ));
            }
        };
        if distances.is_empty() || distances.len() > MAX_FRAMES {
            return Err(LoomError::field(
                "geometry.frame_distances_mm",
                format!("{} frames: allowed 1 to {MAX_FRAMES}", distances.len()),
            ));
        }
        let n = distances.len();
        let mut prev = 0.0;
        for (i, &d) in distances.iter().enumerate() {
            let field = format!("geometry.frame_distances_mm[{i}]");
            if !d.is_finite() || d <= 0.0 {
                return Err(LoomError::field(
                    field,
                    format!("{d} mm puts frame {} in front of the fell: allowed > 0 mm", i + 1),
                ));
            }
            if d >= back {
                return Err(LoomError::field(
                    field,
                    format!("{d} mm puts frame {} behind the back rest at {back} mm: allowed < {back} mm", i + 1),
                ));
            }
            if d <= prev {
                return Err(LoomError::field(
                    field,
                    format!("{d} mm: frames go front to back, each farther than the one before ({prev} mm)"),
                ));
            }
            prev = d;
        }
        let reed = Range::open(0.0, distances[0], "mm").check("geometry.reed_mm", g.reed_mm)?;
        let warp_line = Range::closed(-back, back, "mm").check("geometry.warp_line_mm", g.warp_line_mm)?;
        let lifts = match g.lifts.as_deref().map(str::trim) {
            None | Some("clean") => Lifts::Clean,
            Some("equal-strain") => Lifts::EqualStrain,
            Some("given") => Lifts::Given,
            Some(other) => {
                return Err(LoomError::field(
                    "geometry.lifts",
                    format!("'{other}': expected clean, equal-strain or given"),
                ));
            }
        };
        let stroke_range = Range::open_closed(0.0, 1000.0, "mm");
        let frame_m: Vec<f64> = distances.iter().map(|d| mm(*d)).collect();
        let (back_m, line_m) = (mm(back), mm(warp_line));
        let stroke_m = match (lifts, g.front_stroke_mm, &g.strokes_mm) {
            (Lifts::Given, None, Some(s)) => {
                if s.len() != n {
                    return Err(LoomError::field("geometry.strokes_mm", format!("{} strokes for {n} frames", s.len())));
                }
                s.iter()
                    .enumerate()
                    .map(|(i, h)| stroke_range.check(&format!("geometry.strokes_mm[{i}]"), *h).map(mm))
                    .collect::<Result<Vec<_>, _>>()?
            }
            (Lifts::Given, _, _) => {
                return Err(LoomError::field(
                    "geometry.strokes_mm",
                    "lifts = \"given\" takes strokes_mm (one per frame) and no front_stroke_mm",
                ));
            }
            (_, Some(h), None) => {
                let h = mm(stroke_range.check("geometry.front_stroke_mm", h)?);
                match lifts {
                    Lifts::Clean => crate::geometry::clean_strokes(&frame_m, h),
                    _ => crate::geometry::equal_strain_strokes(&frame_m, back_m, line_m, h),
                }
            }
            _ => {
                return Err(LoomError::field(
                    "geometry.front_stroke_mm",
                    "give front_stroke_mm (with lifts clean or equal-strain), not strokes_mm",
                ));
            }
        };
        for (i, h) in stroke_m.iter().enumerate() {
            if !(h.is_finite() && *h > 0.0 && *h <= 2.0 * frame_m[i].max(back_m - frame_m[i])) {
                return Err(LoomError::field(
                    format!("geometry.strokes_mm[{i}]"),
                    format!("a stroke of {:.3} mm cannot be set for frame {} at this geometry", h * 1e3, i + 1),
                ));
            }
        }
        let geometry =
            Geometry { frame_m, reed_m: mm(reed), back_rest_m: back_m, warp_line_m: line_m, stroke_m, lifts };

        let fr = &f.frames;
        let mass = per_frame("frames.mass_kg", Some(&fr.mass_kg), n, 0.0, Range::open_closed(0.0, 1000.0, "kg"))?;
        let spring =
            per_frame("frames.spring_n_per_mm", fr.spring_n_per_mm.as_ref(), n, 0.0, Range::closed(0.0, 1e4, "N/mm"))?;
        let preload =
            per_frame("frames.spring_preload_n", fr.spring_preload_n.as_ref(), n, 0.0, Range::closed(0.0, 1e5, "N"))?;
        let frames = (0..n)
            .map(|i| FrameProps { mass_kg: mass[i], spring_n_m: spring[i] * 1e3, preload_n: preload[i] })
            .collect();
        let warp = match &f.warp {
            None => Warp::default(),
            Some(w) => Warp {
                ends: Range::closed(0.0, 1e6, "").check("warp.ends", w.ends)?,
                tension_per_end_n: Range::closed(0.0, 1e3, "N").check("warp.tension_per_end_n", w.tension_per_end_n)?,
                stiffness_per_end_n: Range::closed(0.0, 1e7, "N")
                    .check("warp.stiffness_per_end_n", w.stiffness_per_end_n)?,
            },
        };
        let shedding = read_shedding(&f.shedding, n)?;
        let insertion = read_insertion(&f.insertion, &geometry, speed)?;
        let beat_up_deg = Range::closed_open(0.0, 360.0, "deg")
            .check("beat_up.angle_deg", f.beat_up.as_ref().map_or(0.0, |b| b.angle_deg))?;
        let sley = f.sley.map(|t| read_sley(text, t, beat_up_deg)).transpose()?;
        let name = f.name.unwrap_or_default();
        if name.chars().count() > 200 {
            return Err(LoomError::field("name", "longer than 200 characters"));
        }
        let drive = read_drive(f.drive.unwrap_or_default())?;
        Ok(Self {
            name,
            speed,
            efficiency,
            motor_torque_n_m,
            geometry,
            frames,
            warp,
            shedding,
            insertion,
            beat_up_deg,
            sley,
            drive,
        })
    }

    /// Number of heald frames.
    pub fn frame_count(&self) -> usize {
        self.geometry.frame_m.len()
    }

    /// The same loom with other staggers (deg, one per frame), each within `±max_stagger_deg`.
    pub fn with_stagger(&self, stagger_deg: &[f64]) -> Result<Self> {
        if stagger_deg.len() != self.frame_count() {
            return Err(LoomError::field(
                "shedding.stagger_deg",
                format!("{} values for {} frames", stagger_deg.len(), self.frame_count()),
            ));
        }
        let m = self.shedding.max_stagger_deg;
        for (i, s) in stagger_deg.iter().enumerate() {
            Range::closed(-m, m, "deg").check(&format!("shedding.stagger_deg[{i}]"), *s)?;
        }
        let mut out = self.clone();
        out.shedding.stagger_deg = stagger_deg.to_vec();
        Ok(out)
    }

    /// The loom file `text` with `[shedding] stagger_deg` (and `groups`) replaced: what
    /// `loomkin loom stagger -o` writes. `stagger_deg` is per frame; with `groups` the file gets
    /// one value per group (its first frame's). The other keys are kept (comments are not).
    pub fn stagger_toml(text: &str, stagger_deg: &[f64], groups: Option<&[Vec<usize>]>) -> Result<String> {
        let mut doc: toml::Table =
            toml::from_str(text).map_err(|e| LoomError::field("loom file", loomkin_units::toml_reason(text, &e)))?;
        let Some(toml::Value::Table(sh)) = doc.get_mut("shedding") else {
            return Err(LoomError::field("shedding", "missing"));
        };
        let round = |v: f64| toml::Value::Float((v * 1e6).round() / 1e6 + 0.0);
        let values: Vec<toml::Value> = match groups {
            Some(g) => g.iter().map(|grp| round(grp.first().map_or(0.0, |&i| stagger_deg[i]))).collect(),
            None => stagger_deg.iter().map(|v| round(*v)).collect(),
        };
        sh.insert("stagger_deg".into(), toml::Value::Array(values));
        match groups {
            Some(g) => {
                let arr = g
                    .iter()
                    .map(|grp| toml::Value::Array(grp.iter().map(|i| toml::Value::Integer(*i as i64 + 1)).collect()))
                    .collect();
                sh.insert("groups".into(), toml::Value::Array(arr));
            }
            None => {
                sh.remove("groups");
            }
        }
        toml::to_string(&doc).map_err(|e| LoomError::field("loom file", e.to_string()))
    }
}

/// The `[sley]` table checked by the drive crate (errors named `sley.…`); a left-out
/// `beat_up_deg` is the loom's beat-up angle, a given one must equal it.
fn read_sley(text: &str, table: SleyFile, beat_up_deg: f64) -> Result<Sley> {
    // Whether the table gives beat_up_deg (serde fills in the default when it does not).
    let given = toml::from_str::<toml::Table>(text)
        .ok()
        .and_then(|doc| doc.get("sley").and_then(|s| s.get("beat_up_deg")).map(|_| ()))
        .is_some();
    let named = |e: SleyError| match e {
        SleyError::Range(r) => LoomError::Range(r),
        SleyError::Infeasible { fields, reason } => LoomError::Infeasible { field: fields, reason },
        other => LoomError::field("sley", other.to_string()),
    };
    let (sley, given_deg): (Sley, f64) = match table {
        SleyFile::FourBar(mut t) => {
            if !given {
                t.beat_up_deg = beat_up_deg;
            }
            let s = FourBarSley::new(t).map_err(named)?;
            let deg = s.table().beat_up_deg;
            (s.into(), deg)
        }
        SleyFile::Cam(mut t) => {
            if !given {
                t.beat_up_deg = beat_up_deg;
            }
            let s = CamSley::new(*t).map_err(named)?;
            let deg = s.table().beat_up_deg;
            (s.into(), deg)
        }
    };
    if given_deg != beat_up_deg {
        return Err(LoomError::field(
            SleyTable::BEAT_UP_DEG.name,
            format!(
                "{}° but [beat_up] angle_deg is {}°: the reed's front dead centre is the beat-up (leave one out)",
                loomkin_units::compact(given_deg),
                loomkin_units::compact(beat_up_deg)
            ),
        ));
    }
    Ok(sley)
}

fn read_drive(d: DriveFile) -> Result<crate::DriveSpec> {
    use loomkin_drive::{MotorCurve, MotorKind, MotorSpec};
    let motor = MotorSpec {
        motor: d.motor.as_deref().map(|m| MotorKind::parse("drive.motor", m)).transpose()?,
        motor_curve: d.motor_curve.as_deref().map(|m| MotorCurve::parse("drive.motor_curve", m)).transpose()?,
        synchronous_rpm: d.synchronous_rpm,
        rated_rpm: d.rated_rpm,
        rated_power_kw: d.rated_power_kw,
        breakdown_ratio: d.breakdown_ratio,
        gear_ratio: d.gear_ratio,
        servo_gain_n_m_s: d.servo_gain_n_m_s,
        servo_integral_s: d.servo_integral_s,
        servo_torque_limit_n_m: d.servo_torque_limit_n_m,
    };
    crate::inertia::drive_spec(d.rotating_inertia_kg_m2, d.friction_torque_n_m, d.flywheel_kg_m2, motor)
}

fn read_shedding(s: &SheddingFile, n: usize) -> Result<Shedding> {
    let given = [s.preset.is_some(), s.law.is_some(), s.positive.is_some(), s.cycle.is_some()];
    if given.iter().filter(|g| **g).count() != 1 {
        return Err(LoomError::field(
            "shedding.preset",
            "give exactly one law: preset = \"NAME\", law = \"NAME\" (with params and motion_deg), positive = \"…\" (a piecewise shedding law) or a [shedding.cycle]",
        ));
    }
    if s.params.is_some() && s.law.is_none() {
        return Err(LoomError::field("shedding.params", "only with law = \"NAME\""));
    }
    if (s.negative.is_some() || s.positive_fraction.is_some()) && s.positive.is_none() {
        return Err(LoomError::field("shedding.negative", "only with positive = \"…\""));
    }
    let law = if let Some(name) = &s.preset {
        let l = preset(name)?;
        let l = match s.motion_deg {
            Some(m) => l.with_motion_deg(m)?,
            None => l,
        };
        FrameLaw::from_shed(&l, format!("{name} preset"))?
    } else if let Some(name) = &s.law {
        let params: Vec<(String, String)> = s
            .params
            .iter()
            .flatten()
            .map(|(k, v)| (k.clone(), v.as_str().map_or_else(|| v.to_string(), str::to_string)))
            .collect();
        let spec = LawSpec::parse(name, &params)?;
        let m =
            s.motion_deg.ok_or_else(|| LoomError::field("shedding.motion_deg", "a catalogue law needs motion_deg"))?;
        FrameLaw::from_spec(&spec, m)?
    } else if let Some(pos) = &s.positive {
        let mut t = toml::Table::new();
        let m =
            s.motion_deg.ok_or_else(|| LoomError::field("shedding.motion_deg", "a piecewise law needs motion_deg"))?;
        t.insert("motion_deg".into(), toml::Value::Float(m));
        t.insert("positive".into(), pos.clone());
        if let Some(neg) = &s.negative {
            t.insert("negative".into(), neg.clone());
        }
        if let Some(p) = s.positive_fraction {
            t.insert("positive_fraction".into(), toml::Value::Float(p));
        }
        let text = toml::to_string(&t).map_err(|e| LoomError::field("shedding.positive", e.to_string()))?;
        FrameLaw::from_shed(&ShedLaw::from_toml(&text)?, "piecewise law")?
    } else {
        let cycle = s.cycle.as_ref().ok_or_else(|| LoomError::field("shedding.cycle", "missing"))?;
        let l = FrameLaw::from_cycle(cycle)?;
        match s.motion_deg {
            Some(m) => l.with_motion_deg(m)?,
            None => l,
        }
    };
    let crossing_deg = Range::closed_open(0.0, 360.0, "deg").check("shedding.crossing_deg", s.crossing_deg)?;
    let max_stagger_deg =
        Range::closed(0.0, 90.0, "deg").check("shedding.max_stagger_deg", s.max_stagger_deg.unwrap_or(20.0))?;
    let groups = match &s.groups {
        None => None,
        Some(gs) => {
            if gs.is_empty() || gs.len() > n {
                return Err(LoomError::field("shedding.groups", format!("{} groups for {n} frames", gs.len())));
            }
            let mut seen = vec![false; n];
            let mut out = Vec::new();
            for (gi, g) in gs.iter().enumerate() {
                let mut grp = Vec::new();
                for &fr in g {
                    let field = format!("shedding.groups[{gi}]");
                    let idx = usize::try_from(fr).ok().filter(|f| (1..=n).contains(f)).ok_or_else(|| {
                        LoomError::field(&field, format!("frame {fr}: frames are numbered 1 to {n} from the front"))
                    })?;
                    if std::mem::replace(&mut seen[idx - 1], true) {
                        return Err(LoomError::field(field, format!("frame {fr} is in two groups")));
                    }
                    grp.push(idx - 1);
                }
                out.push(grp);
            }
            Some(out)
        }
    };
    let range = Range::closed(-max_stagger_deg, max_stagger_deg, "deg");
    let stagger_deg = match (&s.stagger_deg, &groups) {
        (None, _) => vec![0.0; n],
        (Some(v), Some(gs)) => {
            if v.len() != gs.len() {
                return Err(LoomError::field(
                    "shedding.stagger_deg",
                    format!("{} values for {} groups", v.len(), gs.len()),
                ));
            }
            let mut out = vec![0.0; n];
            for (gi, g) in gs.iter().enumerate() {
                let x = range.check(&format!("shedding.stagger_deg[{gi}]"), v[gi])?;
                for &fr in g {
                    out[fr] = x;
                }
            }
            out
        }
        (Some(v), None) => {
            if v.len() != n {
                return Err(LoomError::field(
                    "shedding.stagger_deg",
                    format!("{} values for {n} frames (or give groups)", v.len()),
                ));
            }
            v.iter()
                .enumerate()
                .map(|(i, x)| range.check(&format!("shedding.stagger_deg[{i}]"), *x))
                .collect::<Result<_, _>>()?
        }
    };
    let servo = read_servo(s, n)?;
    Ok(Shedding { law, crossing_deg, stagger_deg, groups, max_stagger_deg, servo })
}

/// `drive` and `[shedding.servo]`: the frames' servo drives, or none for the dobby.
fn read_servo(s: &SheddingFile, n: usize) -> Result<Option<loomkin_eshed::ServoShedding>> {
    match (s.drive.as_deref().unwrap_or("dobby"), &s.servo) {
        ("dobby", None) => Ok(None),
        ("dobby", Some(_)) => Err(LoomError::field("shedding.servo", "only with drive = \"servo\"")),
        ("servo", Some(t)) => Ok(Some(loomkin_eshed::ServoShedding::from_toml(t.clone(), n, "shedding.servo")?)),
        ("servo", None) => Err(LoomError::field(
            "shedding.servo",
            "drive = \"servo\" needs a [shedding.servo] table (motor, transmission, bus)",
        )),
        (other, _) => Err(LoomError::field("shedding.drive", format!("\"{other}\": allowed \"dobby\" or \"servo\""))),
    }
}

fn read_insertion(i: &InsertionFile, g: &Geometry, speed: ShaftSpeed) -> Result<Insertion> {
    let carrier_height_m =
        mm(Range::open_closed(0.0, 1000.0, "mm").check("insertion.carrier_height_mm", i.carrier_height_mm)?);
    let reed_mm = g.reed_m * 1e3;
    let carrier_width_m =
        mm(Range::closed_open(0.0, reed_mm, "mm").check("insertion.carrier_width_mm", i.carrier_width_mm)?);
    let written_mm = [
        PickBudget::REED_WIDTH_MM.check_as("insertion.reed_width_mm", i.reed_width_mm)?,
        PickBudget::CARRIER_LENGTH_MM.check_as("insertion.carrier_length_mm", i.carrier_length_mm)?,
    ];
    let (reed_width_m, carrier_length_m) = (mm(written_mm[0]), mm(written_mm[1]));
    let path = reed_width_m + carrier_length_m;
    let speed_src = match (i.mean_speed_m_s, &i.shuttle) {
        (Some(_), Some(_)) => {
            return Err(LoomError::field(
                "insertion.mean_speed_m_s",
                "give mean_speed_m_s or [insertion.shuttle], not both",
            ));
        }
        (Some(v), None) => CarrierSpeed::Mean(PickBudget::SPEED_M_S.check_as("insertion.mean_speed_m_s", v)?),
        (None, Some(t)) => {
            let text = toml::to_string(t).map_err(|e| LoomError::field("insertion.shuttle", e.to_string()))?;
            let mech = Mechanism::from_toml(&text)?;
            let st = Settings::designed(&mech).with_speed_rpm(speed.rpm());
            let out = simulate(&mech, &st, Method::Closed)?;
            CarrierSpeed::Shuttle { release_m_s: out.velocity_m_s, retardation_pct: mech.required().retardation_pct }
        }
        (None, None) => CarrierSpeed::FromWindow,
    };
    let centre = Range::open(0.0, 360.0, "deg").check("insertion.centre_deg", i.centre_deg.unwrap_or(180.0))?;
    let mean = match speed_src {
        CarrierSpeed::Mean(v) => Some(v),
        CarrierSpeed::Shuttle { release_m_s, retardation_pct } => Some(release_m_s * (1.0 - retardation_pct / 200.0)),
        CarrierSpeed::FromWindow => None,
    };
    let flight = |v: f64| window_needed_deg(speed.rpm(), path, v);
    let (entry, exit) = match (i.entry_deg, i.exit_deg, i.window_deg) {
        (Some(a), Some(b), None) => {
            let a = Range::closed_open(0.0, 360.0, "deg").check("insertion.entry_deg", a)?;
            let b = Range::open_closed(a, 360.0, "deg").check("insertion.exit_deg", b)?;
            (a, b)
        }
        (Some(a), None, None) if mean.is_some() => {
            let a = Range::closed_open(0.0, 360.0, "deg").check("insertion.entry_deg", a)?;
            (a, a + flight(mean.unwrap_or(1.0)))
        }
        (None, None, Some(w)) => {
            let w = PickBudget::WINDOW_DEG.check_as("insertion.window_deg", w)?;
            (centre - w / 2.0, centre + w / 2.0)
        }
        (None, None, None) if mean.is_some() => {
            let w = flight(mean.unwrap_or(1.0));
            (centre - w / 2.0, centre + w / 2.0)
        }
        _ => {
            return Err(LoomError::field(
                "insertion.entry_deg",
                "give entry_deg and exit_deg, or window_deg, or a carrier speed (mean_speed_m_s or [insertion.shuttle]) with entry_deg or centre_deg",
            ));
        }
    };
    if !(entry >= 0.0 && exit <= 360.0 && exit > entry) {
        return Err(LoomError::Infeasible {
            field: "insertion.exit_deg".into(),
            reason: format!("the carrier needs {entry:.2}° to {exit:.2}°, which does not fit in one turn (0° to 360°)"),
        });
    }
    let kind = read_kind(i, reed_width_m, carrier_length_m)?;
    Ok(Insertion {
        kind,
        carrier_height_m,
        carrier_width_m,
        reed_width_m,
        carrier_length_m,
        written_mm,
        entry_deg: entry,
        exit_deg: exit,
        speed: speed_src,
    })
}

/// `[insertion] kind` and the carrier's sub-table: a sub-table goes with its kind only.
fn read_kind(i: &InsertionFile, reed_width_m: f64, carrier_length_m: f64) -> Result<InsertionKind> {
    let kind = i.kind.as_deref().map(str::trim).unwrap_or("shuttle");
    let unknown = |kind: &str| {
        LoomError::field("insertion.kind", format!("'{kind}': expected one of {}", InsertionKind::NAMES.join(", ")))
    };
    if !InsertionKind::NAMES.contains(&kind) {
        return Err(unknown(kind));
    }
    let tables =
        [("rapier", i.rapier.is_some()), ("projectile", i.projectile.is_some()), ("airjet", i.airjet.is_some())];
    for (name, given) in tables {
        if given && kind != name {
            return Err(LoomError::field(
                format!("insertion.{name}"),
                format!("[insertion.{name}] goes with kind = \"{name}\" (the file's kind is \"{kind}\")"),
            ));
        }
    }
    if i.shuttle.is_some() && kind != "shuttle" {
        return Err(LoomError::field(
            "insertion.shuttle",
            format!("[insertion.shuttle] goes with kind = \"shuttle\" (the file's kind is \"{kind}\")"),
        ));
    }
    match kind {
        "shuttle" => Ok(InsertionKind::Shuttle),
        // Each carrier's arm reads its sub-table into its loomkin-insertion model.
        "rapier" => {
            let t = i.rapier.clone().ok_or_else(|| {
                LoomError::field(
                    "insertion.rapier",
                    "kind = \"rapier\" needs [insertion.rapier.bringer] and [insertion.rapier.taker]",
                )
            })?;
            let table: loomkin_insertion::RapierTable = toml::Value::Table(t)
                .try_into()
                .map_err(|e: toml::de::Error| LoomError::field("insertion.rapier", e.message().to_string()))?;
            let r = loomkin_insertion::Rapier::new(&table, reed_width_m, "insertion.rapier")
                .map_err(crate::insertion::insertion_error)?;
            Ok(InsertionKind::Rapier(Box::new(r)))
        }
        "projectile" => {
            let t = i.projectile.clone().ok_or_else(|| {
                LoomError::field("insertion.projectile", "kind = \"projectile\" needs [insertion.projectile]")
            })?;
            let table: loomkin_insertion::ProjectileTable = toml::Value::Table(t)
                .try_into()
                .map_err(|e: toml::de::Error| LoomError::field("insertion.projectile", e.message().to_string()))?;
            let p = loomkin_insertion::Projectile::new(&table, reed_width_m, carrier_length_m, "insertion.projectile")
                .map_err(crate::insertion::insertion_error)?;
            Ok(InsertionKind::Projectile(Box::new(p)))
        }
        "airjet" => {
            let t = i
                .airjet
                .clone()
                .ok_or_else(|| LoomError::field("insertion.airjet", "kind = \"airjet\" needs [insertion.airjet]"))?;
            let table: loomkin_insertion::AirjetTable = toml::Value::Table(t)
                .try_into()
                .map_err(|e: toml::de::Error| LoomError::field("insertion.airjet", e.message().to_string()))?;
            let a = loomkin_insertion::Airjet::new(&table, reed_width_m, "insertion.airjet")
                .map_err(crate::insertion::insertion_error)?;
            Ok(InsertionKind::Airjet(Box::new(a)))
        }
        other => Err(unknown(other)),
    }
}
