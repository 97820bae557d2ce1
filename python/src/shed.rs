//! Shedding laws: dwell and window criteria, experiment tables, Pareto fronts and the best law
//! for a window, keyed as `loomkin shed … --json` (tables as dicts of numpy arrays).

use crate::convert::{to_py, value_records_to_columns};
use crate::errors::{Fault, OrRaise};
use loomkin_shed::{
    BestReport, BestSearch, Conditions, DesignKind, Family, GridSpec, LawReport, LoomRequirement, PRESETS,
    PresetReport, Progress, RowReport, ShedError, ShedLaw, Study, StudyTable, Template, WindowReport, evaluate, preset,
    preset_table_in,
};
use loomkin_study::StudyError;
use loomkin_units::{RangeError, ShaftSpeed};
use pyo3::prelude::*;

impl Fault for StudyError {
    fn range(&self) -> Option<&RangeError> {
        match self {
            Self::Range(e) => Some(e),
            _ => None,
        }
    }
}

impl Fault for ShedError {
    fn range(&self) -> Option<&RangeError> {
        match self {
            Self::Range(e) => Some(e),
            Self::Law(e) => e.range(),
            Self::Study(e) => e.range(),
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
    m.add_function(wrap_pyfunction!(shed_presets, m)?)?;
    m.add_function(wrap_pyfunction!(shed_law, m)?)?;
    m.add_function(wrap_pyfunction!(shed_table, m)?)?;
    m.add_function(wrap_pyfunction!(shed_pareto, m)?)?;
    m.add_function(wrap_pyfunction!(shed_best, m)?)?;
    m.add_function(wrap_pyfunction!(shed_window, m)?)?;
    Ok(())
}

fn parse_err(field: &str, reason: String) -> PyErr {
    crate::errors::raise(ShedError::Parse { field: field.into(), reason })
}

/// The conditions of the CLI's `--threshold --stroke-mm --speed-rpm`.
fn conditions(threshold: f64, stroke_mm: f64, speed_rpm: f64) -> PyResult<Conditions> {
    Conditions::from_stroke_mm(threshold, stroke_mm, speed_rpm).or_raise()
}

/// shed_presets() -> list[dict]
/// --
///
/// `loomkin shed list --json`'s laws: name, name_ru, motion_deg, dwell_deg (deg of the main
/// shaft), table_shape and the positive phase of the acceleration.
#[pyfunction]
fn shed_presets(py: Python<'_>) -> PyResult<Py<PyAny>> {
    to_py(py, &PresetReport::all())
}

/// shed_law(name=None, spec_toml=None, motion_deg=None, threshold=..., stroke_mm=..., speed_rpm=...) -> dict
/// --
///
/// `loomkin shed law NAME --json`: the window, absolute and conditional dwell (deg), the
/// dimensionless cv, ca, cj, cm, ca_rms and the physical peaks (m/s, m/s², m/s³, W/kg) at the
/// stroke (mm) and speed (rpm), with the law's definition.
#[pyfunction]
#[pyo3(signature = (name=None, spec_toml=None, motion_deg=None, threshold=Conditions::THRESHOLD_FIELD.default_value(),
    stroke_mm=Conditions::STROKE_MM.default_value(), speed_rpm=ShaftSpeed::DEFAULT_RPM, label=None))]
fn shed_law(
    py: Python<'_>,
    name: Option<&str>,
    spec_toml: Option<&str>,
    motion_deg: Option<f64>,
    threshold: f64,
    stroke_mm: f64,
    speed_rpm: f64,
    label: Option<String>,
) -> PyResult<Py<PyAny>> {
    let (name, mut law) = match (spec_toml, name) {
        (Some(text), _) => (label.unwrap_or_else(|| "spec".into()), ShedLaw::from_toml(text).or_raise()?),
        (None, Some(n)) => (n.to_string(), preset(n).or_raise()?),
        (None, None) => return Err(parse_err("name", "give a law name or a spec".into())),
    };
    if let Some(m) = motion_deg {
        law = law.with_motion_deg(m).or_raise()?;
    }
    let cond = conditions(threshold, stroke_mm, speed_rpm)?;
    let c = evaluate(&law, &cond).or_raise()?;
    to_py(py, &LawReport::new(name, &law, &c, &cond))
}

/// The CLI's design flags.
struct DesignArgs<'a> {
    family: Option<&'a str>,
    shapes: Option<&'a str>,
    step: Option<f64>,
    min_k: Option<f64>,
    max_k: Option<f64>,
}

fn kebab<T: serde::de::DeserializeOwned>(field: &str, text: &str, allowed: &str) -> PyResult<T> {
    serde_json::from_value(serde_json::Value::String(text.trim().to_ascii_lowercase()))
        .map_err(|_| parse_err(field, format!("'{text}': allowed {allowed}")))
}

fn design_kind(text: &str) -> PyResult<DesignKind> {
    kebab("design", text, "presets, table1, fig1, grid")
}

fn template(d: &DesignArgs) -> PyResult<Option<Template>> {
    Ok(match (d.shapes, d.family) {
        (Some(s), _) => Some(Template::parse("custom", s).or_raise()?),
        (None, Some(f)) => {
            let f: Family = kebab("family", f, "trapezoid, lead-trapezoid, linear-trapezoid")?;
            Some(f.template())
        }
        (None, None) => None,
    })
}

fn study(kind: DesignKind, d: &DesignArgs, g: GridSpec) -> PyResult<Study> {
    if kind != DesignKind::Grid && (d.min_k.is_some() || d.max_k.is_some()) {
        return Err(parse_err("min_k", "min_k and max_k apply to design grid only".into()));
    }
    let grid = GridSpec {
        step: d.step.unwrap_or(g.step),
        min_k: d.min_k.unwrap_or(g.min_k),
        max_k: d.max_k.unwrap_or(g.max_k),
    };
    Study::new(kind, template(d)?, grid).or_raise()
}

fn rows_columns(py: Python<'_>, t: &StudyTable, cond: &Conditions) -> PyResult<Py<PyAny>> {
    let rows: Vec<RowReport> = t.rows.iter().map(|r| r.report(cond)).collect();
    let v = serde_json::to_value(&rows).map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
    value_records_to_columns(py, &v)
}

/// Which table [`study_rows`] builds.
#[derive(Clone, Copy)]
enum Build {
    /// `shed table`: every law of the design (at motion angles `motion_deg`, default 300), or
    /// one shard's share of the laws.
    Table(loomkin_units::Shard),
    /// `shed pareto`: the laws not dominated over the motion angles (default 180:360:10).
    Pareto,
}

/// The rows of `shed table` or `shed pareto` as columns, for the presets or a design, at the
/// threshold, stroke (mm) and speed (rpm).
fn study_rows(
    py: Python<'_>,
    build: Build,
    design: &str,
    d: &DesignArgs,
    motion_deg: Option<&str>,
    (threshold, stroke_mm, speed_rpm): (f64, f64, f64),
) -> PyResult<Py<PyAny>> {
    let kind = design_kind(design)?;
    let cond = conditions(threshold, stroke_mm, speed_rpm)?;
    let motions = |default: &str| loomkin_shed::parse_motion_angles(motion_deg.unwrap_or(default)).or_raise();
    let t = match (build, kind == DesignKind::Presets) {
        (Build::Table(shard), true) => {
            if d.family.is_some() || d.shapes.is_some() || motion_deg.is_some() || d.step.is_some() {
                return Err(parse_err("design", "design presets takes no family, shapes, step or motion_deg".into()));
            }
            py.detach(|| preset_table_in(&cond, shard.items(PRESETS.len()))).or_raise()?
        }
        (Build::Table(shard), false) => {
            let s = study(kind, d, GridSpec::TABLE)?;
            let motions = motions(loomkin_shed::TABLE_MOTION_DEG)?;
            py.detach(|| s.table_in(&motions, &cond, Progress::Hidden, shard.items(s.design.len()))).or_raise()?
        }
        (Build::Pareto, presets) => {
            // The angles are checked whatever the design (as the CLI does).
            let motions = motions(loomkin_shed::PARETO_MOTION_DEG)?;
            if presets {
                let all = py.detach(|| preset_table_in(&cond, 0..PRESETS.len())).or_raise()?;
                let pts: Vec<[f64; 2]> = all
                    .rows
                    .iter()
                    .map(|r| [r.candidate.criteria.window_deg, r.candidate.criteria.peak_accel_m_s2])
                    .collect();
                all.select(&loomkin_shed::pareto_indices(&pts).or_raise()?)
            } else {
                let s = study(kind, d, GridSpec::TABLE)?;
                py.detach(|| s.pareto(&motions, &cond, Progress::Hidden)).or_raise()?
            }
        }
    };
    rows_columns(py, &t, &cond)
}

/// shed_table(design="presets", ..., shard=None) -> dict[str, array]
/// --
///
/// `loomkin shed table --json`'s rows as columns: law (presets) or row (a design), the criteria
/// (window_deg, dwell_deg, conditional_dwell_deg, ca, peak_accel_m_s2, …), stroke_mm, speed_rpm and
/// lengths (the relative lengths k of each law, a list per row). `shard=(I, N)` gives only the
/// rows of `--shard I/N` (shard I of N of the laws, each at every motion angle). Runs with the GIL
/// released.
#[pyfunction]
#[pyo3(signature = (design="presets", family=None, shapes=None, step=None, min_k=None, max_k=None, motion_deg=None,
    threshold=Conditions::THRESHOLD_FIELD.default_value(), stroke_mm=Conditions::STROKE_MM.default_value(), speed_rpm=ShaftSpeed::DEFAULT_RPM, shard=None))]
#[allow(clippy::too_many_arguments)]
fn shed_table(
    py: Python<'_>,
    design: &str,
    family: Option<&str>,
    shapes: Option<&str>,
    step: Option<f64>,
    min_k: Option<f64>,
    max_k: Option<f64>,
    motion_deg: Option<&str>,
    threshold: f64,
    stroke_mm: f64,
    speed_rpm: f64,
    shard: Option<&Bound<'_, PyAny>>,
) -> PyResult<Py<PyAny>> {
    let d = DesignArgs { family, shapes, step, min_k, max_k };
    let shard = crate::convert::shard(shard)?;
    study_rows(py, Build::Table(shard), design, &d, motion_deg, (threshold, stroke_mm, speed_rpm))
}

/// shed_pareto(design="grid", ...) -> dict[str, array]
/// --
///
/// `loomkin shed pareto --json`'s rows as columns: the laws of the family not dominated in
/// (largest window_deg, least peak_accel_m_s2) over the motion angles `motion_deg`
/// ("FROM:TO:STEP" or a list "A,B,…"; default 180:360:10). Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (design="grid", family=None, shapes=None, step=None, min_k=None, max_k=None, motion_deg=None,
    threshold=Conditions::THRESHOLD_FIELD.default_value(), stroke_mm=Conditions::STROKE_MM.default_value(), speed_rpm=ShaftSpeed::DEFAULT_RPM))]
fn shed_pareto(
    py: Python<'_>,
    design: &str,
    family: Option<&str>,
    shapes: Option<&str>,
    step: Option<f64>,
    min_k: Option<f64>,
    max_k: Option<f64>,
    motion_deg: Option<&str>,
    threshold: f64,
    stroke_mm: f64,
    speed_rpm: f64,
) -> PyResult<Py<PyAny>> {
    let d = DesignArgs { family, shapes, step, min_k, max_k };
    study_rows(py, Build::Pareto, design, &d, motion_deg, (threshold, stroke_mm, speed_rpm))
}

/// shed_best(window_deg, threshold=..., max_jerk_m_s3=None, design="grid", ...) -> dict
/// --
///
/// `loomkin shed best --window-deg W --json`: the law of the family with the least peak
/// acceleration (m/s²) among those giving a window ≥ window_deg (deg) at the threshold, with its
/// lengths, definition and criteria; max_jerk_m_s3 bounds the peak jerk. Runs with the GIL
/// released.
#[pyfunction]
#[pyo3(signature = (window_deg, threshold=Conditions::THRESHOLD_FIELD.default_value(), max_jerk_m_s3=None, design="grid",
    family=None, shapes=None, step=None, min_k=None, max_k=None, motion_deg=None, stroke_mm=Conditions::STROKE_MM.default_value(), speed_rpm=ShaftSpeed::DEFAULT_RPM))]
fn shed_best(
    py: Python<'_>,
    window_deg: f64,
    threshold: f64,
    max_jerk_m_s3: Option<f64>,
    design: &str,
    family: Option<&str>,
    shapes: Option<&str>,
    step: Option<f64>,
    min_k: Option<f64>,
    max_k: Option<f64>,
    motion_deg: Option<&str>,
    stroke_mm: f64,
    speed_rpm: f64,
) -> PyResult<Py<PyAny>> {
    let kind = design_kind(design)?;
    let d = DesignArgs { family, shapes, step, min_k, max_k };
    let cond = conditions(threshold, stroke_mm, speed_rpm)?;
    loomkin_shed::check_window_deg(window_deg).or_raise()?;
    if kind == DesignKind::Presets {
        return Err(parse_err("design", "design presets is not searched by best; use table1, fig1 or grid".into()));
    }
    let s = study(kind, &d, GridSpec::BEST)?;
    let motions = match motion_deg {
        Some(m) => Some(loomkin_shed::parse_motion_angles(m).or_raise()?),
        None => None,
    };
    let found = py
        .detach(|| {
            let dims = s.evaluate(threshold, Progress::Hidden)?;
            loomkin_shed::best(&s.design, &dims, motions.as_deref(), window_deg, max_jerk_m_s3, &cond)
        })
        .or_raise()?;
    let Some(b) = found else {
        return Err(parse_err(
            "window_deg",
            format!(
                "no law of the family '{}' gives a window of {window_deg} deg at T = {threshold}{}",
                s.template.name(),
                if max_jerk_m_s3.is_some() { " within max_jerk_m_s3" } else { "" }
            ),
        ));
    };
    let law = s.template.law(b.criteria.motion_deg, &b.lengths).or_raise()?;
    let search = BestSearch {
        template: &s.template,
        laws_searched: s.design.len(),
        required_window_deg: window_deg,
        max_jerk_m_s3,
        loom: None,
    };
    to_py(py, &BestReport::new(search, &b, &law, &cond))
}

/// shed_window(carrier_speed_m_s, reed_width_m, cloth_width_m=None, carrier_length_m=...,
/// crossing_range_deg=..., shed_excess=..., speed_rpm=...) -> dict
/// --
///
/// `loomkin shed window --carrier-speed-m-s V --reed-width-m L --json`: the loom data (the
/// carrier's mean speed in m/s, reed and cloth width and carrier length in m, the crossing-point
/// range in deg, the shed-height excess as a fraction, the speed in rpm), the carrier's flight
/// through the warp and the window it needs (deg of the main shaft), and the dwell threshold
/// T = 1/(1 + excess) with the one for both sheets moving.
#[pyfunction]
#[pyo3(signature = (carrier_speed_m_s, reed_width_m, cloth_width_m=None,
    carrier_length_m=LoomRequirement::CARRIER_LENGTH_M.default_value(),
    crossing_range_deg=LoomRequirement::CROSSING_RANGE_DEG.default_value(),
    shed_excess=LoomRequirement::SHED_EXCESS.default_value(), speed_rpm=ShaftSpeed::DEFAULT_RPM))]
fn shed_window(
    py: Python<'_>,
    carrier_speed_m_s: f64,
    reed_width_m: f64,
    cloth_width_m: Option<f64>,
    carrier_length_m: f64,
    crossing_range_deg: f64,
    shed_excess: f64,
    speed_rpm: f64,
) -> PyResult<Py<PyAny>> {
    let loom = LoomRequirement::from_inputs(
        carrier_speed_m_s,
        reed_width_m,
        cloth_width_m,
        Some(carrier_length_m),
        Some(crossing_range_deg),
        Some(shed_excess),
        speed_rpm,
    );
    to_py(py, &WindowReport::of(&loom).or_raise()?)
}
