//! The main shaft (issue 29): the reduced inertia of the loom's mechanisms, the speed ripple under a
//! motor and the time-true cams, keyed as `loomkin drive inertia|ripple|correct --json`, with the
//! curves of their `--csv` as numpy columns.

use crate::convert::{columns, table, to_py};
use crate::errors::{Fault, OrRaise, raise};
use crate::loom::{Wif, read};
use loomkin_drive::ripple::{FLYWHEEL_KG_M2, STEP_DEG};
use loomkin_drive::{MotorCurve, MotorKind, MotorSpec, RippleError, Table, flywheel_for, solve};
use loomkin_dynamics::Follower;
use loomkin_loom::{Drive, Loom, LoomError, LoomShaft, Motion, Pattern};
use loomkin_units::RangeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

impl Fault for RippleError {
    fn range(&self) -> Option<&RangeError> {
        match self {
            Self::Range(e) => Some(e),
            _ => None,
        }
    }
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(drive_inertia, m)?)?;
    m.add_function(wrap_pyfunction!(drive_ripple, m)?)?;
    m.add_function(wrap_pyfunction!(drive_correct, m)?)?;
    Ok(())
}

/// The loom file's `[drive]` motor with the keywords' `over` it; refusals name the keys as the
/// CLI does (`drive.rated_power_kw`).
fn motor_of(loom: &Loom, over: &MotorSpec) -> PyResult<loomkin_drive::Motor> {
    loom.drive.motor.overridden(over).build(loom.speed.rpm(), "drive.").or_raise()
}

/// The flywheel: the keyword when given (checked against [`FLYWHEEL_KG_M2`]), else the file's.
fn flywheel(loom: &Loom, flywheel_kg_m2: Option<f64>) -> PyResult<f64> {
    match flywheel_kg_m2 {
        Some(v) => FLYWHEEL_KG_M2.check(v).map_err(raise),
        None => Ok(loom.drive.flywheel_kg_m2),
    }
}

/// drive_inertia(loom_toml, wif=None, lift_plan=None, step_deg=...) -> dict
/// --
///
/// `loomkin drive inertia LOOM.toml --json`: picks, repeat_deg, the total J's least, largest and
/// mean (kg·m²) and where (deg), each mechanism's under `mechanisms`; and `curve`, the columns of
/// `--csv` (angle_deg, then j_NAME_kg_m2 and dj_NAME_kg_m2_per_rad for every mechanism and the
/// total) on the grid of `step_deg`. Runs on a worker thread (Ctrl-C stops the wait).
#[pyfunction]
#[pyo3(signature = (loom_toml, wif=None, lift_plan=None, step_deg=Drive::STEP_DEG.default_value()))]
fn drive_inertia<'py>(
    py: Python<'py>,
    loom_toml: &str,
    wif: Option<Wif>,
    lift_plan: Option<&str>,
    step_deg: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let (loom, pattern) = read(py, loom_toml, wif, lift_plan)?;
    Drive::STEP_DEG.check(step_deg).map_err(raise)?;
    let (report, cols) = crate::interrupt::detached(py, move || -> Result<_, LoomError> {
        let motion = Motion::new(&loom, &pattern)?;
        let shaft = LoomShaft::new(&loom, &motion, &pattern);
        Ok((shaft.report(step_deg)?, shaft.inertia_columns(step_deg)?))
    })?
    .or_raise()?;
    let out = to_py(py, &report)?.into_bound(py);
    out.set_item("curve", table(py, columns(py, cols)?)?)?;
    Ok(out)
}

/// What one ripple run gives the caller: the report and the `--csv` columns.
type Ripple = (loomkin_drive::RippleReport, Vec<(&'static str, Vec<f64>)>);

/// The steady running of `loom` weaving `pattern` (owned: it runs on a worker thread).
fn ripple_of(
    loom: Loom,
    pattern: Pattern,
    motor: loomkin_drive::Motor,
    flywheel_kg_m2: f64,
    target_ripple_pct: Option<f64>,
    step_deg: f64,
) -> Result<Ripple, LoomError> {
    let motion = Motion::new(&loom, &pattern)?;
    let shaft = LoomShaft::new(&loom, &motion, &pattern);
    let table = Table::new(&shaft, step_deg)?;
    let sol = match target_ripple_pct {
        Some(t) => flywheel_for(&table, &motor, t)?.1,
        None => solve(&table, &motor, flywheel_kg_m2)?,
    };
    Ok((sol.report.clone(), sol.columns()))
}

/// drive_ripple(loom_toml, wif=None, lift_plan=None, flywheel_kg_m2=None, target_ripple_pct=None, step_deg=..., **motor) -> dict
/// --
///
/// `loomkin drive ripple LOOM.toml --json`: the main shaft's periodic running under the motor
/// (the file's `[drive]` motor with the keywords `motor`, `motor_curve`, `synchronous_rpm`,
/// `rated_rpm`, `rated_power_kw`, `breakdown_ratio`, `gear_ratio`, `servo_gain_n_m_s`,
/// `servo_integral_s`, `servo_torque_limit_n_m` over it): mean, least and largest speed (rpm),
/// speed_ripple_pct, energy_swing_j, motor torques (N·m), the works (J), flywheel_kg_m2 (the
/// least that holds `target_ripple_pct` when that is given, which is then echoed); and `curve`,
/// the columns of `--csv` (angle_deg, speed_rpm, motor_torque_n_m, load_torque_n_m, energy_j).
/// Runs on a worker thread (Ctrl-C stops the wait).
#[pyfunction]
#[pyo3(signature = (loom_toml, wif=None, lift_plan=None, flywheel_kg_m2=None, target_ripple_pct=None,
    step_deg=STEP_DEG.default_value(), **motor))]
fn drive_ripple<'py>(
    py: Python<'py>,
    loom_toml: &str,
    wif: Option<Wif>,
    lift_plan: Option<&str>,
    flywheel_kg_m2: Option<f64>,
    target_ripple_pct: Option<f64>,
    step_deg: f64,
    motor: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyAny>> {
    let (loom, pattern) = read(py, loom_toml, wif, lift_plan)?;
    STEP_DEG.check(step_deg).map_err(raise)?;
    let motor = motor_of(&loom, &motor_kw(motor)?)?;
    if flywheel_kg_m2.is_some() && target_ripple_pct.is_some() {
        return Err(crate::study::error(
            "target_ripple_pct",
            "target_ripple_pct: give either flywheel_kg_m2 or target_ripple_pct (it sizes the flywheel)",
        ));
    }
    let jf = flywheel(&loom, flywheel_kg_m2)?;
    let (report, cols) =
        crate::interrupt::detached(py, move || ripple_of(loom, pattern, motor, jf, target_ripple_pct, step_deg))?
            .or_raise()?;
    let out = to_py(py, &report)?.into_bound(py);
    if let Some(t) = target_ripple_pct {
        out.set_item("target_ripple_pct", t)?;
    }
    out.set_item("curve", table(py, columns(py, cols)?)?)?;
    Ok(out)
}

/// The motor keywords out of `**motor` (the CLI's motor flags, every one optional); an unknown
/// one or a value of the wrong type is refused naming it.
fn motor_kw(kw: Option<&Bound<'_, PyDict>>) -> PyResult<MotorSpec> {
    let Some(kw) = kw else { return Ok(MotorSpec::default()) };
    const KNOWN: [&str; 10] = [
        "motor",
        "motor_curve",
        "synchronous_rpm",
        "rated_rpm",
        "rated_power_kw",
        "breakdown_ratio",
        "gear_ratio",
        "servo_gain_n_m_s",
        "servo_integral_s",
        "servo_torque_limit_n_m",
    ];
    for k in kw.keys() {
        let k: String = k.extract()?;
        if !KNOWN.contains(&k.as_str()) {
            return Err(crate::study::error(
                &k,
                &format!("{k}: not a keyword of the drive (the motor's: {})", KNOWN.join(", ")),
            ));
        }
    }
    // A value of the wrong type is named by its keyword.
    let name = |k: &str| -> PyResult<Option<String>> {
        match kw.get_item(k)? {
            Some(v) if !v.is_none() => v.extract::<String>().map(Some).map_err(|_| {
                crate::study::error(
                    k,
                    &format!("{k}: expected a name, got {}", v.repr().map(|r| r.to_string()).unwrap_or_default()),
                )
            }),
            _ => Ok(None),
        }
    };
    let number = |k: &str| -> PyResult<Option<f64>> {
        match kw.get_item(k)? {
            Some(v) if !v.is_none() => v.extract::<f64>().map(Some).map_err(|_| {
                crate::study::error(
                    k,
                    &format!("{k}: expected a number, got {}", v.repr().map(|r| r.to_string()).unwrap_or_default()),
                )
            }),
            _ => Ok(None),
        }
    };
    Ok(MotorSpec {
        motor: name("motor")?.map(|m| MotorKind::parse("motor", &m)).transpose().or_raise()?,
        motor_curve: name("motor_curve")?.map(|c| MotorCurve::parse("motor_curve", &c)).transpose().or_raise()?,
        synchronous_rpm: number("synchronous_rpm")?,
        rated_rpm: number("rated_rpm")?,
        rated_power_kw: number("rated_power_kw")?,
        breakdown_ratio: number("breakdown_ratio")?,
        gear_ratio: number("gear_ratio")?,
        servo_gain_n_m_s: number("servo_gain_n_m_s")?,
        servo_integral_s: number("servo_integral_s")?,
        servo_torque_limit_n_m: number("servo_torque_limit_n_m")?,
    })
}

/// drive_correct(loom_toml, wif=None, lift_plan=None, title=None, flywheel_kg_m2=None, step_deg=..., natural_hz=None, damping_ratio=..., **motor) -> dict
/// --
///
/// `loomkin drive correct LOOM.toml --json`: the frames' cam laws corrected for the shaft's speed
/// ripple (time-true cams): the timing errors before and after (deg), the ripple with the design
/// and the corrected cams (%), the rounds, per frame the errors and, with `natural_hz` (Hz) and
/// `damping_ratio`, the residual vibrations (mm); `not_corrected`; and `cycles`, the cycle files
/// `-o DIR` writes as a dict of file name (`frame-01.toml` …, `sley.toml` for a cam sley, with its
/// timing under `sley`) to text, headed by `title` (the
/// loom's name, else the given title). Motor keywords as `drive_ripple`. Runs on a worker thread
/// (Ctrl-C stops the wait).
#[pyfunction]
#[pyo3(signature = (loom_toml, wif=None, lift_plan=None, title=None, flywheel_kg_m2=None,
    step_deg=STEP_DEG.default_value(), natural_hz=None,
    damping_ratio=Follower::DAMPING_RATIO.default_value(), **motor))]
#[allow(clippy::too_many_arguments)]
fn drive_correct<'py>(
    py: Python<'py>,
    loom_toml: &str,
    wif: Option<Wif>,
    lift_plan: Option<&str>,
    title: Option<String>,
    flywheel_kg_m2: Option<f64>,
    step_deg: f64,
    natural_hz: Option<f64>,
    damping_ratio: f64,
    motor: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyAny>> {
    let (loom, pattern) = read(py, loom_toml, wif, lift_plan)?;
    STEP_DEG.check(step_deg).map_err(raise)?;
    let motor = motor_of(&loom, &motor_kw(motor)?)?;
    let jf = flywheel(&loom, flywheel_kg_m2)?;
    let follower = natural_hz.map(|f| Follower::new(f, damping_ratio)).transpose().or_raise()?;
    let title = if loom.name.is_empty() { title.unwrap_or_default() } else { loom.name.clone() };
    let (report, files) = crate::interrupt::detached(py, move || -> Result<_, LoomError> {
        let motion = Motion::new(&loom, &pattern)?;
        let c = loomkin_loom::correct(&loom, &motion, &pattern, &motor, jf, step_deg, follower.as_ref())?;
        let files = c.cycle_files(&title)?;
        Ok((c.report, files))
    })?
    .or_raise()?;
    let out = to_py(py, &report)?.into_bound(py);
    let cycles = PyDict::new(py);
    for (name, text) in files {
        cycles.set_item(name, text)?;
    }
    out.set_item("cycles", cycles)?;
    Ok(out)
}
