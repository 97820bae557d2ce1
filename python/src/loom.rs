//! The whole loom: pattern, shed geometry, shedding torque and the stagger of the frames, keyed
//! as `loomkin loom check|torque|stagger --json`.

use crate::convert::{Count, columns, to_py};
use crate::errors::{Fault, OrRaise, raise};
use loomkin_loom::{
    Drive, Loom, LoomError, Motion, Objective, Pattern, ServoOptions, StaggerOptions, check, optimise_servo_with,
    optimise_stagger, servo_study,
};
use loomkin_units::RangeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

impl Fault for loomkin_drive::SleyError {
    fn range(&self) -> Option<&RangeError> {
        match self {
            Self::Range(e) => Some(e),
            _ => None,
        }
    }
}

impl Fault for LoomError {
    fn range(&self) -> Option<&RangeError> {
        match self {
            Self::Range(e) => Some(e),
            Self::Law(e) => e.range(),
            Self::Shed(e) => e.range(),
            Self::Pick(e) => e.range(),
            _ => None,
        }
    }
    fn accepted(&self) -> Option<String> {
        match self {
            Self::Law(e) => e.accepted(),
            _ => None,
        }
    }
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(loom_check, m)?)?;
    m.add_function(wrap_pyfunction!(loom_torque, m)?)?;
    m.add_function(wrap_pyfunction!(loom_stagger, m)?)?;
    m.add_function(wrap_pyfunction!(loom_servo, m)?)?;
    m.add_function(wrap_pyfunction!(loom_sley, m)?)?;
    m.add_function(wrap_pyfunction!(loom_sley_synthesize, m)?)?;
    Ok(())
}

/// A WIF as its text or as the file's bytes (decoded as every front end decodes a WIF:
/// `Pattern::from_wif_bytes`).
#[derive(FromPyObject)]
pub(crate) enum Wif {
    Text(String),
    Bytes(Vec<u8>),
}

/// The loom file's text and the pattern (a WIF's text or bytes, a lift plan's text, or neither:
/// plain weave over the loom's frames), as the CLI reads `LOOM.toml --wif | --lift-plan`. A WIF
/// read in the Windows code page gives a `UserWarning` with the library's note.
pub(crate) fn read(
    py: Python<'_>,
    loom_toml: &str,
    wif: Option<Wif>,
    lift_plan: Option<&str>,
) -> PyResult<(Loom, Pattern)> {
    let loom = Loom::from_toml(loom_toml).or_raise()?;
    let pattern = match (wif, lift_plan) {
        (Some(Wif::Text(w)), _) => Pattern::from_wif(&w).or_raise()?,
        (Some(Wif::Bytes(w)), _) => {
            let (pattern, note) = Pattern::from_wif_bytes(&w).or_raise()?;
            if let Some(note) = note {
                let message = std::ffi::CString::new(format!("wif: {note}")).expect("the note has no NUL");
                PyErr::warn(py, &py.get_type::<pyo3::exceptions::PyUserWarning>(), &message, 2)?;
            }
            pattern
        }
        (None, Some(l)) => Pattern::from_lift_plan(l).or_raise()?,
        (None, None) => Pattern::plain(loom.frame_count()).or_raise()?,
    };
    Ok((loom, pattern))
}

/// loom_check(loom_toml, wif=None, lift_plan=None) -> dict
/// --
///
/// `loomkin loom check LOOM.toml --json`: per frame the stroke (mm), shed angle (deg), largest
/// warp strain and the equal-strain stroke; the peak and RMS shedding torque (N·m) over the
/// repeat, the weft-insertion window (deg) and the least clearance (mm). Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (loom_toml, wif=None, lift_plan=None))]
fn loom_check(py: Python<'_>, loom_toml: &str, wif: Option<Wif>, lift_plan: Option<&str>) -> PyResult<Py<PyAny>> {
    let (loom, pattern) = read(py, loom_toml, wif, lift_plan)?;
    let r = py.detach(|| check(&loom, &pattern)).or_raise()?;
    to_py(py, &r)
}

/// loom_torque(loom_toml, wif=None, lift_plan=None, step_deg=...) -> dict
/// --
///
/// `loomkin loom torque LOOM.toml --json`: speed_rpm, picks, repeat_deg, peak_torque_n_m and its
/// peak_angle_deg, rms_torque_n_m, step_deg, and points as arrays angle_deg, torque_n_m (the
/// shedding torque over the whole repeat). Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (loom_toml, wif=None, lift_plan=None, step_deg=Drive::STEP_DEG.default_value()))]
fn loom_torque<'py>(
    py: Python<'py>,
    loom_toml: &str,
    wif: Option<Wif>,
    lift_plan: Option<&str>,
    step_deg: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let (loom, pattern) = read(py, loom_toml, wif, lift_plan)?;
    Drive::STEP_DEG.check(step_deg).map_err(raise)?;
    let (curve, peak, rms, repeat_deg) = py
        .detach(|| -> Result<_, LoomError> {
            let motion = Motion::new(&loom, &pattern)?;
            let drive = Drive::new(&loom, &motion, &pattern);
            let curve = drive.torque_curve(step_deg);
            let peak = drive.peak_of(&curve);
            Ok((curve, peak, drive.rms(), motion.repeat_deg()))
        })
        .or_raise()?;
    let out = PyDict::new(py);
    out.set_item("speed_rpm", loom.speed.rpm())?;
    out.set_item("picks", pattern.picks())?;
    out.set_item("repeat_deg", repeat_deg)?;
    out.set_item("peak_torque_n_m", peak.torque_n_m.abs())?;
    out.set_item("peak_angle_deg", peak.angle_deg)?;
    out.set_item("rms_torque_n_m", rms)?;
    out.set_item("step_deg", repeat_deg / curve.len() as f64)?;
    let cols =
        vec![("angle_deg", curve.iter().map(|c| c.0).collect()), ("torque_n_m", curve.iter().map(|c| c.1).collect())];
    out.set_item("points", columns(py, cols)?)?;
    Ok(out)
}

/// loom_stagger(loom_toml, wif=None, lift_plan=None, objective="peak") -> dict
/// --
///
/// `loomkin loom stagger LOOM.toml --json`: the crossing offsets of the frames (deg) that least
/// the peak (or RMS) shedding torque with the window kept, beside no stagger and two groups;
/// the reductions in %. Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (loom_toml, wif=None, lift_plan=None, objective="peak"))]
fn loom_stagger(
    py: Python<'_>,
    loom_toml: &str,
    wif: Option<Wif>,
    lift_plan: Option<&str>,
    objective: &str,
) -> PyResult<Py<PyAny>> {
    let objective = objective_of(objective)?;
    let (loom, pattern) = read(py, loom_toml, wif, lift_plan)?;
    let r = py.detach(|| optimise_stagger(&loom, &pattern, objective)).or_raise()?;
    to_py(py, &r)
}

/// `peak` or `rms` (any case, spaces trimmed), else the error naming the field.
fn objective_of(objective: &str) -> PyResult<Objective> {
    match objective.trim().to_ascii_lowercase().as_str() {
        "peak" => Ok(Objective::Peak),
        "rms" => Ok(Objective::Rms),
        other => Err(raise(LoomError::Field {
            field: "objective".into(),
            reason: format!("'{other}': allowed peak or rms"),
        })),
    }
}

/// loom_servo(loom_toml, wif=None, lift_plan=None, optimize=False, objective="peak", min_clearance_mm=...) -> dict
/// --
///
/// `loomkin loom servo LOOM.toml --json` (`[shedding] drive = "servo"`): the bus (peak and mean
/// power in W, regenerated and braking energy in J per repeat), the shed the carrier passes
/// (window in deg, least clearance in mm), and `frames` in shaft order (torques in N·m, speeds in
/// rpm, powers in W, the motor checks; `rise_law`, `fall_law`, `through_law`: each kind of move's
/// law as the loom file names it). With `optimize`, `--optimize [--objective]
/// [--min-clearance-mm]`: every frame's stagger and motion angle for the least peak bus power (or
/// "rms": the worst frame's RMS torque) keeping at least `min_clearance_mm` of clearance to the
/// carrier (the design's own when it keeps less), with the before/after keys, and the study of the
/// optimum. `min_clearance_mm` is checked against its range either way. Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (loom_toml, wif=None, lift_plan=None, optimize=false, objective="peak", min_clearance_mm=StaggerOptions::MIN_CLEARANCE_MM.default_value()))]
fn loom_servo(
    py: Python<'_>,
    loom_toml: &str,
    wif: Option<Wif>,
    lift_plan: Option<&str>,
    optimize: bool,
    objective: &str,
    min_clearance_mm: f64,
) -> PyResult<Py<PyAny>> {
    let options = ServoOptions { objective: objective_of(objective)?, min_clearance_mm };
    options.validate().or_raise()?;
    let (loom, pattern) = read(py, loom_toml, wif, lift_plan)?;
    if optimize {
        let stop = loomkin_units::StopFlag::default();
        let r = py.detach(|| optimise_servo_with(&loom, &pattern, &options, &stop, &|_, _| {})).or_raise()?;
        to_py(py, &r)
    } else {
        let r = py.detach(|| servo_study(&loom, &pattern)).or_raise()?;
        to_py(py, &r)
    }
}

/// loom_sley(loom_toml, speed_rpm=None, dwell_tolerance_mm=..., points=...) -> dict
/// --
///
/// `loomkin sley analyze LOOM.toml --json`: the loom file's `[sley]` four-bar at `speed_rpm` (the
/// file's when None): reed stroke (mm) and back dwell (deg) within `dwell_tolerance_mm`, dead
/// centres, peak reed velocity (m/s), acceleration (m/s²) and jerk (m/s³), inertia force (N), rod
/// and rocking-shaft forces (N), peak crank torque (N·m) with their angles (deg); and `curve`, the
/// rows of `--csv` over one turn at `points` angles (angle_deg, reed_mm, velocity_m_s,
/// acceleration_m_s2, jerk_m_s3, inertia_force_n, rod_force_n, crank_torque_n_m).
#[pyfunction]
#[pyo3(signature = (loom_toml, speed_rpm=None,
    dwell_tolerance_mm=loomkin_drive::SleyAnalysis::DWELL_TOLERANCE_MM.default_value(),
    points=Count::of(loomkin_drive::SleyAnalysis::POINTS.default_count())))]
fn loom_sley<'py>(
    py: Python<'py>,
    loom_toml: &str,
    speed_rpm: Option<f64>,
    dwell_tolerance_mm: f64,
    points: Count,
) -> PyResult<Bound<'py, PyAny>> {
    use loomkin_drive::SleyAnalysis;
    let loom = Loom::from_toml(loom_toml).or_raise()?;
    let speed = match speed_rpm {
        Some(v) => loomkin_units::ShaftSpeed::from_rpm_field("speed_rpm", v).or_raise()?,
        None => loom.speed,
    };
    SleyAnalysis::DWELL_TOLERANCE_MM.check(dwell_tolerance_mm).map_err(raise)?;
    let points = points.check(&SleyAnalysis::POINTS)?;
    let Some(sley) = loom.sley else {
        return Err(crate::study::error(
            "sley",
            "sley: the loom file has no [sley] table (crank_mm, rod_mm, sword_mm, …; see docs/drive.md)",
        ));
    };
    let (r, rows) = py
        .detach(|| sley.analyze(speed, dwell_tolerance_mm).map(|r| (r, sley.curve(points, speed.rad_per_s()))))
        .or_raise()?;
    let out = to_py(py, &r)?.into_bound(py);
    // The columns of `sley analyze --csv`, in its order.
    let col = |f: fn(&loomkin_drive::SleyRow) -> f64| rows.iter().map(f).collect::<Vec<f64>>();
    let mut cols = vec![
        ("angle_deg", col(|q| q.angle_deg)),
        ("reed_mm", col(|q| q.reed_mm)),
        ("velocity_m_s", col(|q| q.velocity_m_s)),
        ("acceleration_m_s2", col(|q| q.acceleration_m_s2)),
        ("jerk_m_s3", col(|q| q.jerk_m_s3)),
        ("inertia_force_n", col(|q| q.inertia_force_n)),
    ];
    // A cam sley has no rod (the CLI's table leaves that column out too).
    if rows.first().is_some_and(|q| q.rod_force_n.is_some()) {
        cols.push(("rod_force_n", rows.iter().filter_map(|q| q.rod_force_n).collect()));
    }
    cols.push(("crank_torque_n_m", col(|q| q.crank_torque_n_m)));
    out.set_item("curve", crate::convert::table(py, columns(py, cols)?)?)?;
    Ok(out)
}

/// loom_sley_synthesize(stroke_mm, back_dwell_deg, dwell_tolerance_mm=..., reed_height_mm=..., sword_mm=None) -> dict
/// --
///
/// `loomkin sley synthesize --json`: the crank-rocker sley for a reed stroke (mm) and back dwell
/// (deg of main shaft, within `dwell_tolerance_mm`) with the largest least transmission angle;
/// `reed_height_mm` from the rocking shaft to the beating point, `sword_mm` to the rod's pin
/// (None: the library's share of the reed height).
#[pyfunction]
#[pyo3(signature = (stroke_mm, back_dwell_deg,
    dwell_tolerance_mm=loomkin_drive::SleyAnalysis::DWELL_TOLERANCE_MM.default_value(),
    reed_height_mm=loomkin_drive::SleyTarget::REED_HEIGHT_MM.default_value(), sword_mm=None))]
fn loom_sley_synthesize(
    py: Python<'_>,
    stroke_mm: f64,
    back_dwell_deg: f64,
    dwell_tolerance_mm: f64,
    reed_height_mm: f64,
    sword_mm: Option<f64>,
) -> PyResult<Py<PyAny>> {
    let target = loomkin_drive::SleyTarget { stroke_mm, back_dwell_deg, dwell_tolerance_mm, reed_height_mm, sword_mm };
    let r = py.detach(|| target.synthesize()).or_raise()?;
    to_py(py, &r)
}
