//! The rotary-dobby modulator (Stäubli 2600 type): analysis of a given cam and synthesis of the
//! conjugate cams for an output law, keyed as `loomkin dobby analyze|synthesize --json`.

use crate::convert::{Count, to_py, value_records_to_columns};
use crate::errors::{Fault, OrRaise};
use loomkin_laws::{LawError, LawSpec};
use loomkin_mech::{
    AlphaSweep, AnalysisOptions, Cam, CamProfile, DobbyInputs, MechError, ModulatorGeometry, OutputLawSpec,
    SynthesisOptions, analyze, parse_point_table, synthesize,
};
use loomkin_units::RangeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde::Serialize;

impl Fault for MechError {
    fn range(&self) -> Option<&RangeError> {
        match self {
            Self::Range(e) => Some(e),
            Self::Law(e) => e.range(),
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
    m.add_function(wrap_pyfunction!(dobby_analyze, m)?)?;
    m.add_function(wrap_pyfunction!(dobby_synthesize, m)?)?;
    m.add_function(wrap_pyfunction!(dobby_tolerance, m)?)?;
    m.add_function(wrap_pyfunction!(dobby_sweep, m)?)?;
    Ok(())
}

/// The modulator's dimensions and speed, as the CLI's geometry flags.
struct Geometry {
    alpha_deg: Option<f64>,
    theta_deg: Option<f64>,
    l2_m: f64,
    l3_m: f64,
    l3p_m: f64,
    l6_m: f64,
    speed_rpm: Option<f64>,
}

impl Geometry {
    fn build(&self) -> PyResult<ModulatorGeometry> {
        ModulatorGeometry::from_inputs(self.l2_m, self.l3_m, self.l3p_m, self.l6_m, self.alpha_deg, self.theta_deg)
            .or_raise()
    }
    /// The input speed (rad/s): 1 rad/s (per-radian values) unless a speed is given.
    fn speed_rad_s(&self) -> PyResult<f64> {
        DobbyInputs::speed_rad_s("speed_rpm", self.speed_rpm).or_raise()
    }
}

fn parse_err(field: &str, text: &str, expected: &str) -> PyErr {
    crate::errors::raise(LawError::Parse { field: field.into(), text: text.into(), expected: expected.into() })
}

/// The cam: None (the paper's ellipse), `"ellipse:a=A,b=B"` (semi-axes in m), or a point table's
/// text (x_m, y_m per line: what `cam_points` becomes in the Python layer).
fn cam(spec: Option<&str>, points_text: Option<&str>) -> PyResult<Cam> {
    if let Some(text) = points_text {
        let pts = parse_point_table(text).or_raise()?;
        return Cam::from_points(&pts).or_raise();
    }
    let Some(spec) = spec else { return Ok(Cam::paper()) };
    let usage = "ellipse:a=A,b=B with the semi-axes in m, e.g. ellipse:a=0.366,b=0.577";
    let Some(rest) = spec.trim().strip_prefix("ellipse:") else { return Err(parse_err("cam", spec, usage)) };
    let (mut a, mut b) = (None, None);
    for kv in rest.split(',') {
        let (k, v) = kv.split_once('=').ok_or_else(|| parse_err("cam", spec, usage))?;
        let v: f64 = v.trim().parse().map_err(|_| parse_err("cam", spec, usage))?;
        match k.trim() {
            "a" => a = Some(v),
            "b" => b = Some(v),
            _ => return Err(parse_err("cam", spec, usage)),
        }
    }
    let (Some(a), Some(b)) = (a, b) else { return Err(parse_err("cam", spec, usage)) };
    Cam::ellipse(a, b).or_raise()
}

/// A report (summary, warnings, rows) with the rows as a dict of numpy arrays.
fn report<'py, S: Serialize, W: Serialize, R: Serialize>(
    py: Python<'py>,
    summary: &S,
    warnings: &W,
    rows: &R,
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("summary", to_py(py, summary)?)?;
    out.set_item("warnings", to_py(py, warnings)?)?;
    let rows = serde_json::to_value(rows).map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
    out.set_item("rows", value_records_to_columns(py, &rows)?)?;
    Ok(out)
}

/// dobby_analyze(...) -> dict
/// --
///
/// `loomkin dobby analyze --json` (task 1): the given cam's output motion, pressure angles,
/// curvature and closure checks (summary, warnings) and rows (phi2_deg, t_s, phi3_deg, phi6_deg,
/// s53_m, omega*_rad_s, eps*_rad_s2, … as numpy arrays). Lengths in m, angles in deg; speeds per
/// rad/s of input unless speed_rpm is given. Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (alpha_deg=None, theta_deg=None, l2_m=ModulatorGeometry::L2_M.default_value(), l3_m=ModulatorGeometry::L3_M.default_value(),
    l3p_m=ModulatorGeometry::L3P_M.default_value(), l6_m=ModulatorGeometry::L6_M.default_value(), speed_rpm=None,
    pressure_limit_deg=DobbyInputs::PRESSURE_LIMIT_DEG.default_value(), cam_spec=None, cam_points_text=None, step_deg=DobbyInputs::STEP_DEG.default_value(), roller_m=None))]
fn dobby_analyze<'py>(
    py: Python<'py>,
    alpha_deg: Option<f64>,
    theta_deg: Option<f64>,
    l2_m: f64,
    l3_m: f64,
    l3p_m: f64,
    l6_m: f64,
    speed_rpm: Option<f64>,
    pressure_limit_deg: f64,
    cam_spec: Option<&str>,
    cam_points_text: Option<&str>,
    step_deg: f64,
    roller_m: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let geo = Geometry { alpha_deg, theta_deg, l2_m, l3_m, l3p_m, l6_m, speed_rpm };
    let g = geo.build()?;
    let c = cam(cam_spec, cam_points_text)?;
    let opts = AnalysisOptions {
        step_deg,
        input_speed_rad_s: geo.speed_rad_s()?,
        roller_m,
        pressure_limit_deg,
        ..AnalysisOptions::default()
    };
    let res = py.detach(|| analyze(&g, &c, &opts)).or_raise()?;
    report(py, &res.summary, &res.warnings, &res.rows)
}

fn profile<'py>(py: Python<'py>, p: &CamProfile) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let xy = |v: &[[f64; 2]]| -> PyResult<Py<PyAny>> {
        let rows: Vec<Vec<f64>> = v.iter().map(|p| p.to_vec()).collect();
        if rows.is_empty() {
            return Ok(numpy::PyArray2::<f64>::zeros(py, [0, 2], false).into_any().unbind());
        }
        Ok(numpy::PyArray2::from_vec2(py, &rows)
            .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?
            .into_any()
            .unbind())
    };
    d.set_item("centre_m", xy(&p.centre)?)?;
    d.set_item("wall_left_m", xy(&p.wall_left)?)?;
    d.set_item("wall_right_m", xy(&p.wall_right)?)?;
    Ok(d)
}

/// dobby_synthesize(...) -> dict
/// --
///
/// `loomkin dobby synthesize --json` (task 2): the cam Γ and counter-cam Γ′ for an output law of
/// `cycles` motions with dwells of dwell_deg centred on dwell_centre_deg (law: a catalogue rise
/// law with params). summary, warnings and rows as `--json`, plus cam and counter_cam: the
/// roller-centre curves and groove walls as (N, 2) arrays in m (what `--dxf` draws). Runs with
/// the GIL released.
#[pyfunction]
#[pyo3(signature = (dwell_deg=OutputLawSpec::DWELL_DEG.default_value(),
    dwell_centre_deg=OutputLawSpec::DWELL_CENTRE_DEG.default_value(), cycles=Count::of(OutputLawSpec::CYCLES.default_count()),
    law=OutputLawSpec::DEFAULT_LAW, params=None, roller_m=DobbyInputs::ROLLER_M.default_value(),
    step_deg=DobbyInputs::STEP_DEG.default_value(), alpha_deg=None, theta_deg=None, l2_m=ModulatorGeometry::L2_M.default_value(), l3_m=ModulatorGeometry::L3_M.default_value(),
    l3p_m=ModulatorGeometry::L3P_M.default_value(), l6_m=ModulatorGeometry::L6_M.default_value(), speed_rpm=None,
    pressure_limit_deg=DobbyInputs::PRESSURE_LIMIT_DEG.default_value()))]
fn dobby_synthesize<'py>(
    py: Python<'py>,
    dwell_deg: f64,
    dwell_centre_deg: f64,
    cycles: Count,
    law: &str,
    params: Option<&Bound<'py, PyDict>>,
    roller_m: f64,
    step_deg: f64,
    alpha_deg: Option<f64>,
    theta_deg: Option<f64>,
    l2_m: f64,
    l3_m: f64,
    l3p_m: f64,
    l6_m: f64,
    speed_rpm: Option<f64>,
    pressure_limit_deg: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let geo = Geometry { alpha_deg, theta_deg, l2_m, l3_m, l3p_m, l6_m, speed_rpm };
    let g = geo.build()?;
    let rise = LawSpec::parse(law, &crate::convert::params(params)?).or_raise()?;
    // At most 6 (the field's range), so the u32 holds it.
    let cycles = cycles.check(&OutputLawSpec::CYCLES)? as u32;
    let spec = OutputLawSpec { cycles, dwell_deg, dwell_centre_deg, rise };
    let opts = SynthesisOptions { step_deg, input_speed_rad_s: geo.speed_rad_s()?, roller_m, pressure_limit_deg };
    let res = py.detach(|| synthesize(&g, &spec, &opts)).or_raise()?;
    let out = report(py, &res.summary, &res.warnings, &res.rows)?;
    out.set_item("cam", profile(py, &res.cam)?)?;
    out.set_item("counter_cam", profile(py, &res.counter_cam)?)?;
    Ok(out)
}

/// dobby_tolerance(study_toml, shard=None, from_draws=None, summary=False, from_summaries=None) -> dict | Table
/// --
///
/// `loomkin dobby tolerance STUDY --json` for the study file's text (draws, seed, step_deg,
/// `[dimensions]` distributions in m and deg, `[limits]`): draws, seed, step_deg, not_assembled,
/// failing, fail_share, dimensions and results (output-angle error in deg, pressure angle in
/// deg, dead-point margin in deg: mean, sd, percentiles, histogram, limit, count failing), and
/// `per_draw`, the per-draw table of `--csv` as a Table. `shard=(I, N)` runs only shard I of N
/// of the draws and returns their per-draw Table (`--shard I/N --csv`); `from_draws` (a list of
/// such tables in shard order, or of paths as `--from-draws` takes) returns the report of the
/// finished run without `per_draw`. `summary=True` and `from_summaries` as `pick_montecarlo`'s.
/// The draws run in parallel with the GIL released, a piece at a time: Ctrl-C stops the study
/// between pieces.
#[pyfunction]
#[pyo3(signature = (study_toml, shard=None, from_draws=None, summary=false, from_summaries=None))]
fn dobby_tolerance<'py>(
    py: Python<'py>,
    study_toml: &str,
    shard: Option<&Bound<'py, PyAny>>,
    from_draws: Option<&Bound<'py, PyAny>>,
    summary: bool,
    from_summaries: Option<Vec<String>>,
) -> PyResult<Bound<'py, PyAny>> {
    let ask = crate::study::Ask::with_summaries(shard, from_draws, summary, from_summaries)?;
    let t = loomkin_mech::Tolerance::from_toml(study_toml).or_raise()?;
    crate::study::answer(
        py,
        crate::study::Study {
            command: "dobby tolerance",
            draws: t.draws,
            run: &|items| t.run(items, loomkin_study::Progress::Hidden),
            report: &|d| t.report(d),
            report_from: &|source| t.report_from(source),
            summary: &|items, d| t.summary(items, d),
            report_from_summaries: &|parts| t.report_from_summaries(parts),
        },
        ask,
    )
}

/// dobby_sweep(alpha_deg, dwell_deg=..., dwell_centre_deg=..., cycles=..., law="cycloidal", params=None,
/// roller_m=..., step_deg=..., l2_m=..., l3_m=..., l3p_m=..., l6_m=..., speed_rpm=None,
/// pressure_limit_deg=..., cam_spec=None, cam_points_text=None, shard=None) -> dict
/// --
///
/// `loomkin dobby sweep --json` (the paper's α sweep) at the lever angles of an array (deg, α = θ):
/// `rows`, per α the analysis of the given cam (an_ok, an_omega6_min/max_rad_s, pressure angles in
/// deg, …) and the synthesis of the law (syn_ok, …), as a dict of columns (numbers as numpy arrays,
/// errors and flags as lists). `shard=(I, N)` computes only shard I of N of the angles (`--shard
/// I/N`). Lengths in m, angles in deg. Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (alpha_deg, dwell_deg=OutputLawSpec::DWELL_DEG.default_value(),
    dwell_centre_deg=OutputLawSpec::DWELL_CENTRE_DEG.default_value(), cycles=Count::of(OutputLawSpec::CYCLES.default_count()),
    law=OutputLawSpec::DEFAULT_LAW, params=None,
    roller_m=DobbyInputs::ROLLER_M.default_value(), step_deg=DobbyInputs::STEP_DEG.default_value(), l2_m=ModulatorGeometry::L2_M.default_value(), l3_m=ModulatorGeometry::L3_M.default_value(),
    l3p_m=ModulatorGeometry::L3P_M.default_value(), l6_m=ModulatorGeometry::L6_M.default_value(), speed_rpm=None,
    pressure_limit_deg=DobbyInputs::PRESSURE_LIMIT_DEG.default_value(), cam_spec=None, cam_points_text=None, shard=None))]
#[allow(clippy::too_many_arguments)]
fn dobby_sweep<'py>(
    py: Python<'py>,
    alpha_deg: Vec<f64>,
    dwell_deg: f64,
    dwell_centre_deg: f64,
    cycles: Count,
    law: &str,
    params: Option<&Bound<'py, PyDict>>,
    roller_m: f64,
    step_deg: f64,
    l2_m: f64,
    l3_m: f64,
    l3p_m: f64,
    l6_m: f64,
    speed_rpm: Option<f64>,
    pressure_limit_deg: f64,
    cam_spec: Option<&str>,
    cam_points_text: Option<&str>,
    shard: Option<&Bound<'py, PyAny>>,
) -> PyResult<Py<PyAny>> {
    AlphaSweep::ALPHAS.check_count(alpha_deg.len()).or_raise()?;
    // Shard I of N: the rows of `dobby sweep --shard I/N` when the array holds the CLI's angles.
    let alpha_deg = &alpha_deg[crate::convert::shard(shard)?.items(alpha_deg.len())];
    let geo = Geometry { alpha_deg: None, theta_deg: None, l2_m, l3_m, l3p_m, l6_m, speed_rpm };
    let g = geo.build()?;
    let c = cam(cam_spec, cam_points_text)?;
    let rise = LawSpec::parse(law, &crate::convert::params(params)?).or_raise()?;
    // At most 6 (the field's range), so the u32 holds it.
    let cycles = cycles.check(&OutputLawSpec::CYCLES)? as u32;
    let spec = OutputLawSpec { cycles, dwell_deg, dwell_centre_deg, rise };
    let speed = geo.speed_rad_s()?;
    let an = AnalysisOptions {
        step_deg,
        input_speed_rad_s: speed,
        roller_m: None,
        pressure_limit_deg,
        ..AnalysisOptions::default()
    };
    let syn = SynthesisOptions { step_deg, input_speed_rad_s: speed, roller_m, pressure_limit_deg };
    let rows = py.detach(|| loomkin_mech::alpha_sweep(&g, &c, &spec, alpha_deg, &an, &syn)).or_raise()?;
    let out = PyDict::new(py);
    out.set_item("rows", crate::convert::records_to_columns(py, &rows)?)?;
    Ok(out.into_any().unbind())
}
