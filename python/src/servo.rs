//! Servo motion functions from definition points: the spline law, drive torque, optimisation and
//! the controller exports, keyed as `loomkin servo … --json`.

use crate::convert::{Count, records_to_columns, to_py};
use crate::cycles::Cycle;
use crate::errors::{OrRaise, raise};
use crate::laws::Law;
use loomkin_laws::ParamValue;
use loomkin_servo::{
    Axis, Drive, ExportFormat, LawReport, Objective, OptimizeOptions, ReinterpolationRow, ServoError, ServoInputs,
    SplineEnd, SplineLaw, TorqueReport, check_axis, format_points, parse_points, torque_curve,
};
use loomkin_units::ShaftSpeed;
use pyo3::prelude::*;
use pyo3::types::PyDict;

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(servo_spline_law, m)?)?;
    m.add_function(wrap_pyfunction!(servo_law, m)?)?;
    m.add_function(wrap_pyfunction!(servo_torque, m)?)?;
    m.add_function(wrap_pyfunction!(servo_torque_curve, m)?)?;
    m.add_function(wrap_pyfunction!(servo_optimize, m)?)?;
    m.add_function(wrap_pyfunction!(servo_export, m)?)?;
    m.add_function(wrap_pyfunction!(servo_check, m)?)?;
    Ok(())
}

/// Definition points from Python: `None` (the CLI's default), `"X:Y,X:Y,…"` or a sequence of
/// (x, y) pairs (a list, or an (N, 2) numpy array).
fn def_points(def: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<[f64; 2]>> {
    match def {
        None => parse_points(loomkin_servo::DEFAULT_DEF).or_raise(),
        Some(d) => {
            if let Ok(text) = d.extract::<String>() {
                parse_points(&text).or_raise()
            } else {
                let rows: Vec<Vec<f64>> = d.extract().map_err(|_| {
                    pyo3::exceptions::PyTypeError::new_err("def: expected 'X:Y,X:Y,…' or a sequence of (x, y) pairs")
                })?;
                rows.iter()
                    .map(|r| match r.as_slice() {
                        [x, y] => Ok([*x, *y]),
                        _ => Err(raise(ServoError::Parse {
                            field: "def".into(),
                            text: format!("{r:?}"),
                            expected: "(x, y) pairs".into(),
                        })),
                    })
                    .collect()
            }
        }
    }
}

fn spline(def: Option<&Bound<'_, PyAny>>, end: &str) -> PyResult<SplineLaw> {
    let pts = def_points(def)?;
    let end = SplineEnd::parse(end).or_raise()?;
    SplineLaw::new(&pts, end).or_raise()
}

fn drive(text: Option<&str>) -> PyResult<Drive> {
    match text {
        None => Ok(Drive::needle_rack_default()),
        Some(t) => Drive::from_text(t).or_raise(),
    }
}

fn speeds(v: &[f64]) -> PyResult<()> {
    if v.is_empty() {
        return Err(raise(ServoError::Parse {
            field: "speed_rpm".into(),
            text: String::new(),
            expected: "at least one speed".into(),
        }));
    }
    for &n in v {
        ShaftSpeed::from_rpm_field("speed_rpm", n).or_raise()?;
    }
    Ok(())
}

/// servo_spline_law(def_points=None, end="natural") -> Law
/// --
///
/// The servo motion law through the definition points (Sivčák 2017) as a `Law`: unit stroke on
/// x = 0…1 (dimensionless), with metrics, continuity and sampling like any catalogue law.
#[pyfunction]
#[pyo3(signature = (def_points=None, end="natural"))]
fn servo_spline_law(def_points: Option<&Bound<'_, PyAny>>, end: &str) -> PyResult<Law> {
    let sl = spline(def_points, end)?;
    let def_text = format_points(sl.points());
    let params = [
        ("def".to_string(), ParamValue::Text(def_text.clone())),
        ("end".to_string(), ParamValue::Text(sl.end().name().to_string())),
    ]
    .into();
    let label = format!("servo-spline (def={def_text}, end={})", sl.end().name());
    Ok(Law::wrap("servo-spline", label, params, sl.into_law()))
}

/// servo_law(def_points=None, end="natural") -> dict
/// --
///
/// `loomkin servo law --json`: the definition points, d (slope of the acceleration image at
/// x = 0.5), d_unit, scale, the metrics (dimensionless), continuity_class, intervals and the
/// spline coefficients spline_b.
#[pyfunction]
#[pyo3(signature = (def_points=None, end="natural"))]
fn servo_law(py: Python<'_>, def_points: Option<&Bound<'_, PyAny>>, end: &str) -> PyResult<Py<PyAny>> {
    let sl = spline(def_points, end)?;
    let report = py.detach(|| LawReport::of(&sl));
    to_py(py, &report)
}

/// servo_torque(speed_rpm=..., def_points=None, end="natural", drive=None) -> dict
/// --
///
/// `loomkin servo torque --json`: per speed (rpm) the peak motor torque (N·m) and its angle (deg),
/// the RMS torque, peak power (W), peak rack velocity and acceleration, peak motor speed (rpm),
/// rise and cycle time (s); `drive` is the drive file's text (TOML or JSON; None: the built-in
/// needle-rack drive). Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (speed_rpm=ServoInputs::speeds(ServoInputs::TORQUE_SPEEDS_RPM), def_points=None, end="natural", drive_text=None))]
fn servo_torque(
    py: Python<'_>,
    speed_rpm: Vec<f64>,
    def_points: Option<&Bound<'_, PyAny>>,
    end: &str,
    drive_text: Option<&str>,
) -> PyResult<Py<PyAny>> {
    speeds(&speed_rpm)?;
    let sl = spline(def_points, end)?;
    let d = drive(drive_text)?;
    let report = py.detach(|| TorqueReport::compute(&sl, &d, &speed_rpm)).or_raise()?;
    to_py(py, &report)
}

/// servo_torque_curve(speed_rpm=..., points=..., def_points=None, end="natural", drive=None) -> dict
/// --
///
/// The drive over one main-shaft turn at `points` evenly spaced angles, as arrays angle_deg,
/// time_s, u_m, v_m_s, a_m_s2, torque_nm, power_w and the list phase. Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (speed_rpm=ServoInputs::speeds(ServoInputs::DESIGN_SPEEDS_RPM)[0],
    points=Count::of(ServoInputs::CURVE_POINTS.default_count()), def_points=None, end="natural", drive_text=None))]
fn servo_torque_curve(
    py: Python<'_>,
    speed_rpm: f64,
    points: Count,
    def_points: Option<&Bound<'_, PyAny>>,
    end: &str,
    drive_text: Option<&str>,
) -> PyResult<Py<PyAny>> {
    speeds(&[speed_rpm])?;
    let points = points.check(&ServoInputs::CURVE_POINTS)?;
    let sl = spline(def_points, end)?;
    let d = drive(drive_text)?;
    let curve = py.detach(|| torque_curve(sl.law(), &d, speed_rpm, points)).or_raise()?;
    records_to_columns(py, &curve)
}

/// servo_optimize(speed_rpm=..., objective="peak", starts=..., fixed_x=False, def_points=None,
/// end="natural", drive=None) -> dict
/// --
///
/// `loomkin servo optimize --json`: moves the free definition points to minimise the worst peak
/// (or RMS) motor torque (N·m) over the speeds (rpm); before, after, the optimised def_points and
/// def text, evaluations. Deterministic (seeded starts). Runs with the GIL released; Ctrl-C
/// (a notebook's interrupt) stops it and raises KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (speed_rpm=ServoInputs::speeds(ServoInputs::DESIGN_SPEEDS_RPM), objective="peak",
    starts=Count::of(ServoInputs::STARTS.default_count()), fixed_x=false, def_points=None, end="natural", drive_text=None))]
fn servo_optimize(
    py: Python<'_>,
    speed_rpm: Vec<f64>,
    objective: &str,
    starts: Count,
    fixed_x: bool,
    def_points: Option<&Bound<'_, PyAny>>,
    end: &str,
    drive_text: Option<&str>,
) -> PyResult<Py<PyAny>> {
    speeds(&speed_rpm)?;
    let starts = starts.check(&ServoInputs::STARTS)?;
    let objective = Objective::parse(objective).or_raise()?;
    let sl = spline(def_points, end)?;
    let d = drive(drive_text)?;
    let opts = OptimizeOptions {
        objective,
        speeds_rpm: speed_rpm.clone(),
        starts,
        move_x: !fixed_x,
        ..OptimizeOptions::default()
    };
    let r = interruptible(py, || opts.stop.stop(), || loomkin_servo::optimize(&sl, &d, &opts))?.or_raise()?;
    to_py(py, &r.summary(&speed_rpm))
}

/// Runs `work` on a scoped thread with the GIL released, and on the calling thread checks Python's
/// signals every 50 ms: on Ctrl-C (KeyboardInterrupt in a notebook) `stop` is called, the work is
/// waited for (it ends at once when stopped) and the exception is raised instead of its result.
fn interruptible<T: Send>(py: Python<'_>, stop: impl FnOnce(), work: impl FnOnce() -> T + Send) -> PyResult<T> {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::scope(|s| {
        s.spawn(move || {
            let _ = tx.send(work());
        });
        // The receiver is moved into each wait and back (it is `Send`, not `Sync`).
        let mut rx = rx;
        loop {
            let (got, back) = py.detach(move || (rx.recv_timeout(std::time::Duration::from_millis(50)), rx));
            rx = back;
            match got {
                Ok(v) => return Ok(v),
                Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => {
                    return Err(pyo3::exceptions::PyRuntimeError::new_err("internal: the computation panicked"));
                }
                Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
                    if let Err(e) = py.check_signals() {
                        stop();
                        // The stopped work finishes quickly; its result is dropped.
                        let _ = py.detach(move || rx.recv());
                        return Err(e);
                    }
                }
            }
        }
    })
}

fn export_format(name: &str) -> PyResult<ExportFormat> {
    const ALL: [ExportFormat; 6] = [
        ExportFormat::Coeffs,
        ExportFormat::Json,
        ExportFormat::Csv,
        ExportFormat::Xyva,
        ExportFormat::Poly5,
        ExportFormat::Cycle,
    ];
    ALL.into_iter().find(|f| f.name().eq_ignore_ascii_case(name.trim())).ok_or_else(|| {
        raise(ServoError::Parse {
            field: "format".into(),
            text: name.into(),
            expected: ALL.map(|f| f.name()).join(", "),
        })
    })
}

/// servo_export(format, step_deg=..., def_points=None, end="natural", drive=None) -> dict
/// --
///
/// Every controller export of `loomkin servo export`: format one of coeffs, json, csv, xyva,
/// poly5, cycle (the tables written by the cam-table engine of `loomkin cam table`, in mm). Returns
/// text (the file `-o` writes, byte for byte), filename, media_type and, for
/// the cam tables (csv, xyva), points, step_deg and reinterpolation (also as interpolation, the
/// workbench API's key; each row names its mode as interpolation and as mode: the worst errors when the
/// controller interpolates: m, m/deg, m/deg²; as `--json` prints).
#[pyfunction]
#[pyo3(signature = (format, step_deg=ServoInputs::EXPORT_STEP_DEG.default_value(), def_points=None, end="natural", drive_text=None))]
fn servo_export<'py>(
    py: Python<'py>,
    format: &str,
    step_deg: f64,
    def_points: Option<&Bound<'_, PyAny>>,
    end: &str,
    drive_text: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    let format = export_format(format)?;
    let sl = spline(def_points, end)?;
    let d = drive(drive_text)?;
    let file = py.detach(|| loomkin_servo::export(&sl, &d, format, step_deg)).or_raise()?;
    let out = PyDict::new(py);
    out.set_item("format", format.name())?;
    out.set_item("filename", file.filename)?;
    out.set_item("media_type", file.media_type)?;
    out.set_item("text", file.text)?;
    if let Some(t) = file.table {
        out.set_item("points", t.points)?;
        out.set_item("step_deg", t.step_deg)?;
        let rows: Vec<ReinterpolationRow> = t.reinterpolation.iter().map(ReinterpolationRow::from).collect();
        out.set_item("reinterpolation", to_py(py, &rows)?)?;
        // The workbench API's key for the same rows (`servo export --json` writes both).
        out.set_item("interpolation", to_py(py, &rows)?)?;
    }
    Ok(out)
}

/// servo_check(axis_toml, cycle, speed_rpm=None) -> dict
/// --
///
/// `loomkin servo check AXIS --cycle CYCLE --json`: a servo axis (the axis file's text: [motor],
/// [load], optional [limits]) moving the cycle at speed_rpm (default: the cycle's, else 300 rpm).
/// Peak torque (N·m) and its angle (deg), RMS torque, peak motor speed (rpm), the envelope ratio,
/// the inertia ratio, each check (name, value, limit, unit, margin, pass) and pass. Runs with the
/// GIL released.
#[pyfunction]
#[pyo3(signature = (axis_toml, cycle, speed_rpm=None))]
fn servo_check(
    py: Python<'_>,
    axis_toml: &str,
    cycle: PyRef<'_, Cycle>,
    speed_rpm: Option<f64>,
) -> PyResult<Py<PyAny>> {
    let c = &cycle.inner;
    let axis = Axis::from_toml(axis_toml, c.unit).or_raise()?;
    let rpm = c.speed_rpm_or(speed_rpm);
    let report = py.detach(|| check_axis(&axis, c, rpm)).or_raise()?;
    to_py(py, &report)
}
