//! Cam tables for the controllers: one per frame over the pattern repeat, written by the
//! workspace's one cam-table engine ([`loomkin_cams::table`]), and a manifest of the master axis
//! they share.
//!
//! **Master and slave.** The master is the main-shaft angle in degrees, `0` at the beat-up of the
//! repeat's first pick, over an axis of `master_axis_deg = 360 · picks` that wraps around. A
//! frame's table starts where its plan starts — its first move's start, so that no move is cut —
//! at `master_start_deg` (it may be negative: the move into the first pick begins before its
//! beat-up), and runs over one repeat. The slave is the frame's position in mm from where it
//! stands at that start; `slave_offset_mm` (`−H/2` down, `+H/2` up) is that place over
//! mid-stroke.
//!
//! **A crank and lever.** A frame driven through a crank and lever (`kind = "crank_lever"`) has
//! its tables in the motor's position: the slave is the motor's angle in degrees from where it
//! stands with the frame at mid-stroke (`gear_ratio · (α − α_mid)`, α the crank's angle), the
//! frame's law taken through the linkage's inverse with every derivative exact (a
//! [`loomkin_cams::table::SlaveMap`] on the same engine); the manifest marks the frame
//! `slave_unit = "deg"` with `crank_mid_stroke_deg` (α_mid), and its cycle file still holds the
//! frame's law in mm.
//!
//! **One engine.** Each table is [`CamTable`] on [`Motion::from_cycle`] of the frame's cycle
//! ([`FramePlan::cycle`](crate::FramePlan::cycle)); where the repeat fits a cycle file (36 000°,
//! 100 picks) the cycle file is written too, and `loomkin cam table` run on it writes the same
//! table byte for byte (the plan's cycle is built with the cycle file's own arithmetic).

use crate::{FrameSetup, Result};
use loomkin_cams::profile::Jet;
use loomkin_cams::table::{CamTable, Format, Motion, SlaveMap, Spacing, TableReport};
use loomkin_laws::StrokeUnit;
use loomkin_numeric::WordMap;
use loomkin_servo::Linkage;
use serde::Serialize;
use std::sync::{Arc, Mutex};

/// The formats `--emit-tables` writes when none is named: every point or segment format a
/// controller loads (CSV, XYVAJ, poly5, TwinCAT points, Structured Text).
pub const TABLE_FORMATS: [Format; 5] = [Format::Csv, Format::Xyvaj, Format::Poly5, Format::Twincat, Format::St];

/// The manifest's file name.
pub const MANIFEST_FILE: &str = "manifest.json";

/// A file to write: its name in the output directory and its text.
#[derive(Debug, Clone, PartialEq)]
pub struct TableFile {
    /// File name (`frame-01.csv`).
    pub name: String,
    /// The text.
    pub text: String,
}

/// One table of a frame in the manifest: the file and the cam-table report of `loomkin cam
/// table --json` (points, spacing, decimals, the exact re-interpolation error).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TableEntry {
    /// The file name.
    pub file: String,
    /// The report (its `source` names the frame's cycle file, or the frame).
    #[serde(flatten)]
    pub report: TableReport,
}

/// One frame of the manifest.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrameTables {
    /// The frame (1 = front).
    pub frame: usize,
    /// Master angle of the table's first point, deg (the first move's start; `0` without moves).
    pub master_start_deg: f64,
    /// The frame's height over mid-stroke where its table's slave position is `0`, mm.
    pub slave_offset_mm: f64,
    /// Full stroke, mm.
    pub stroke_mm: f64,
    /// Moves over the repeat.
    pub moves: usize,
    /// The frame's cycle file (absent when the repeat is longer than a cycle file holds).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cycle_file: Option<String>,
    /// The tables, one per format.
    pub tables: Vec<TableEntry>,
    /// `deg` for a frame driven through a crank and lever: its tables hold the motor's angle in
    /// degrees from where it stands with the frame at mid-stroke (`gear_ratio · (α − α_mid)`), not
    /// the frame's height (absent: mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slave_unit: Option<&'static str>,
    /// The crank's angle from +x with the frame at mid-stroke, deg (`α_mid`; a crank and lever only):
    /// where the motor's table is 0.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub crank_mid_stroke_deg: Option<f64>,
}

/// A frame's height (mm, the cycle's position) to its motor's angle (deg, from mid-stroke's)
/// through its crank and lever: the closed-form inverse and the reverted series
/// ([`loomkin_servo::Linkage::motor`]), ~1 µs a series. The formats' re-interpolation checks scan
/// the same angles of the same table intervals, so the series are remembered by the position's
/// series, bit for bit (forgotten at once beyond [`MotorDegrees::REMEMBERED`]).
#[derive(Debug)]
struct MotorDegrees(Linkage, Mutex<WordMap<[u64; 6], Jet>>);

impl MotorDegrees {
    /// Series remembered (about 100 bytes each).
    const REMEMBERED: usize = 1 << 18;

    fn new(l: Linkage) -> Self {
        Self(l, Mutex::default())
    }

    fn degrees(&self, position: Jet) -> Jet {
        let l = &self.0;
        match l.crank_series(position.scale(1e-3)) {
            Some(alpha) => {
                let mut a = alpha;
                a.0[0] -= l.alpha_mid;
                a.scale(l.gear.to_degrees())
            }
            None => Jet::cst(f64::NAN),
        }
    }
}

impl SlaveMap for MotorDegrees {
    fn map(&self, position: Jet) -> Jet {
        let key = position.0.map(f64::to_bits);
        if let Some(j) = self.1.lock().ok().and_then(|m| m.get(&key).copied()) {
            return j;
        }
        let j = self.degrees(position);
        if let Ok(mut m) = self.1.lock() {
            if m.len() >= Self::REMEMBERED {
                m.clear();
            }
            m.insert(key, j);
        }
        j
    }
}

/// What a controller needs besides the tables (the manifest of `--emit-tables`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TablesManifest {
    /// Length of the master axis: the pattern repeat, deg of the main shaft (`360 · picks`).
    pub master_axis_deg: f64,
    /// Picks in the repeat.
    pub picks: usize,
    /// Main-shaft speed, rpm.
    pub speed_rpm: f64,
    /// The slave unit: `mm` (the frames' heights), `deg` (every frame through a crank and lever:
    /// the motors' angles) or `mixed` (each frame's `slave_unit`).
    pub slave_unit: &'static str,
    /// Per frame, front first.
    pub frames: Vec<FrameTables>,
}

/// Every frame's tables and the manifest.
#[derive(Debug, Clone, PartialEq)]
pub struct Tables {
    /// The files, the manifest last.
    pub files: Vec<TableFile>,
    /// The manifest (also in `files`, as JSON).
    pub manifest: TablesManifest,
}

/// The name of frame `frame`'s file with extension `ext` (`frame-01.csv`).
pub fn table_file_name(frame: usize, ext: &str) -> String {
    format!("frame-{frame:02}.{ext}")
}

/// Every frame's cam table in each of `formats` (every one of [`TABLE_FORMATS`] when empty),
/// points placed by `spacing`, over the repeat of `frames` (front first) moving by their laws; the
/// frames' cycle files where they can be written; and the manifest (the shaft at `speed_rpm`).
pub fn frame_tables(frames: &[FrameSetup], spacing: Spacing, formats: &[Format], speed_rpm: f64) -> Result<Tables> {
    let first = frames.first().ok_or_else(|| crate::EshedError::field("frames", "no frames"))?;
    crate::report::check_strokes(frames)?;
    let formats = if formats.is_empty() { &TABLE_FORMATS[..] } else { formats };
    let mut files = Vec::new();
    let mut entries = Vec::with_capacity(frames.len());
    for (i, f) in frames.iter().enumerate() {
        let frame = i + 1;
        let spec = f.plan.cycle_spec(&f.laws);
        let cycle_file = match loomkin_laws::Cycle::new(&spec) {
            Ok(_) => {
                let name = table_file_name(frame, "cycle.toml");
                files.push(TableFile { name: name.clone(), text: spec.to_toml()? });
                Some(name)
            }
            Err(_) => None,
        };
        let motion = Motion::from_cycle(&f.plan.cycle(&f.laws));
        let axis = crate::drive::axis(&f.servo.motor, &f.servo.transmission, &f.load);
        let linkage = axis.linkage();
        let motion = match linkage {
            // A crank and lever: the slave is the motor's angle, deg.
            Some(l) => motion.mapped(Arc::new(MotorDegrees::new(l)), StrokeUnit::Deg),
            None => motion,
        };
        let table = CamTable::new(motion, spacing).map_err(|e| in_frame(frame, e))?;
        let source = cycle_file.clone().unwrap_or_else(|| format!("frame {frame}"));
        let mut tables = Vec::with_capacity(formats.len());
        for &format in formats {
            let export = table.export(format).map_err(|e| in_frame(frame, e))?;
            let name = table_file_name(frame, format.name());
            tables.push(TableEntry { file: name.clone(), report: table.report(source.clone(), format, &export) });
            files.push(TableFile { name, text: export.text });
        }
        entries.push(FrameTables {
            frame,
            master_start_deg: f.plan.start_deg,
            slave_offset_mm: f.plan.start_level_m() * 1e3,
            stroke_mm: f.plan.stroke_mm(),
            moves: f.plan.moves.len(),
            cycle_file,
            tables,
            slave_unit: linkage.map(|_| "deg"),
            crank_mid_stroke_deg: linkage.map(|l| l.alpha_mid.to_degrees()),
        });
    }
    let cranks = entries.iter().filter(|e| e.slave_unit.is_some()).count();
    let slave_unit = match cranks {
        0 => "mm",
        n if n == entries.len() => "deg",
        _ => "mixed",
    };
    let manifest = TablesManifest {
        master_axis_deg: first.plan.period_deg,
        picks: (first.plan.period_deg / 360.0).round() as usize,
        speed_rpm,
        slave_unit,
        frames: entries,
    };
    let text =
        serde_json::to_string_pretty(&manifest).map_err(|e| crate::EshedError::field("manifest", e.to_string()))?;
    files.push(TableFile { name: MANIFEST_FILE.to_string(), text: text + "\n" });
    Ok(Tables { files, manifest })
}

/// A cam-table error of frame `frame`, naming the frame.
fn in_frame(frame: usize, e: loomkin_cams::CamError) -> crate::EshedError {
    use loomkin_units::FieldError;
    let field = e.field().map_or_else(|| "table".to_string(), str::to_string);
    let text = e.to_string();
    let reason = text.strip_prefix(&format!("{field}: ")).unwrap_or(&text);
    crate::EshedError::field(field, format!("frame {frame}: {reason}"))
}
