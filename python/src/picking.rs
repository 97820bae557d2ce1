//! Shuttle picking dynamics (Jederán 1959): design, simulation and sweeps, keyed as
//! `loomkin pick … --json`.

use crate::convert::{Count, columns, to_py, value_records_to_columns, value_to_py};
use crate::errors::{Fault, OrRaise};
use loomkin_laws::LawSpec;
use loomkin_picking::units::M_PER_CM;
use loomkin_picking::{History, Mechanism, Method, PickError, Setting, Settings, StartRule, Sweep, history, simulate};
use loomkin_units::RangeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde_json::Value;

impl Fault for PickError {
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
    m.add_function(wrap_pyfunction!(pick_design, m)?)?;
    m.add_function(wrap_pyfunction!(pick_simulate, m)?)?;
    m.add_function(wrap_pyfunction!(pick_history, m)?)?;
    m.add_function(wrap_pyfunction!(pick_sweep, m)?)?;
    m.add_function(wrap_pyfunction!(pick_montecarlo, m)?)?;
    Ok(())
}

/// The mechanism options of `loomkin pick` (the CLI's flags, same names with `_`).
#[derive(Default)]
struct Model {
    mechanism_toml: Option<String>,
    law: Option<String>,
    params: Vec<(String, String)>,
    velocity_m_s: Option<f64>,
    distance_m: Option<f64>,
    first_stage_m: Option<f64>,
    design_speed_rpm: Option<f64>,
    retardation_pct: Option<f64>,
    path_m: Option<f64>,
    free_shed_deg: Option<f64>,
}

/// What a call's keywords say: the mechanism, the settings changed, the start rule, the route.
struct Call {
    model: Model,
    set: Vec<(Setting, f64)>,
    start: StartRule,
    method: Method,
}

impl Model {
    fn from_kw(kw: Option<&Bound<'_, PyDict>>) -> PyResult<Call> {
        let mut m = Model::default();
        let mut set = Vec::new();
        let (mut start, mut method) = (StartRule::Paper, Method::Closed);
        let Some(kw) = kw else { return Ok(Call { model: m, set, start, method }) };
        for (k, v) in kw.iter() {
            let key: String = k.extract()?;
            if v.is_none() {
                continue;
            }
            let num = || v.extract::<f64>();
            match key.as_str() {
                "mechanism_toml" => m.mechanism_toml = Some(v.extract()?),
                "law" => m.law = Some(v.extract()?),
                "params" => {
                    let d = v.cast::<PyDict>()?;
                    m.params = crate::convert::params(Some(d))?;
                }
                "velocity_m_s" => m.velocity_m_s = Some(num()?),
                "distance_m" => m.distance_m = Some(num()?),
                "distance_cm" => m.distance_m = Some(num()? * M_PER_CM),
                "first_stage_m" => m.first_stage_m = Some(num()?),
                "first_stage_cm" => m.first_stage_m = Some(num()? * M_PER_CM),
                "design_speed_rpm" => m.design_speed_rpm = Some(num()?),
                "retardation_pct" => m.retardation_pct = Some(num()?),
                "path_m" => m.path_m = Some(num()?),
                "free_shed_deg" => m.free_shed_deg = Some(num()?),
                "speed_rpm" => set.push((Setting::Speed, num()?)),
                "play_mm" => set.push((Setting::Play, num()?)),
                "strap_cm" => set.push((Setting::Strap, num()?)),
                "shuttle_g" => set.push((Setting::Shuttle, num()?)),
                "checking_kgf" => set.push((Setting::Checking, num()?)),
                "start" => {
                    start = match v.extract::<String>()?.as_str() {
                        "paper" => StartRule::Paper,
                        "equilibrium" => StartRule::Equilibrium,
                        other => return Err(parse_err("start", other, "paper or equilibrium")),
                    }
                }
                "method" => {
                    method = match v.extract::<String>()?.as_str() {
                        "closed" => Method::Closed,
                        "ode" => Method::Ode,
                        other => return Err(parse_err("method", other, "closed or ode")),
                    }
                }
                other => {
                    return Err(parse_err(
                        other,
                        other,
                        "mechanism, law, params, velocity_m_s, distance_m, distance_cm, first_stage_m, \
                         first_stage_cm, design_speed_rpm, retardation_pct, path_m, free_shed_deg, speed_rpm, \
                         play_mm, strap_cm, shuttle_g, checking_kgf, start, method",
                    ));
                }
            }
        }
        Ok(Call { model: m, set, start, method })
    }

    /// The mechanism, as the CLI builds it from its flags.
    fn build(&self) -> PyResult<Mechanism> {
        let mech = match &self.mechanism_toml {
            Some(text) => Mechanism::from_toml(text).or_raise()?,
            None => Mechanism::paper_default(),
        };
        let design = [self.velocity_m_s, self.distance_m, self.first_stage_m, self.design_speed_rpm];
        let mech = if design.iter().any(Option::is_some) {
            let mut spec = *mech.design_spec();
            spec.velocity_m_s = self.velocity_m_s.unwrap_or(spec.velocity_m_s);
            spec.distance_m = self.distance_m.unwrap_or(spec.distance_m);
            spec.first_stage_m = self.first_stage_m.unwrap_or(spec.first_stage_m);
            spec.speed_rpm = self.design_speed_rpm.unwrap_or(spec.speed_rpm);
            let required = *mech.required();
            Mechanism::new(*mech.params(), spec).and_then(|n| n.with_required(required)).or_raise()?
        } else {
            mech
        };
        let mech = if self.retardation_pct.is_some() || self.path_m.is_some() || self.free_shed_deg.is_some() {
            let mut r = *mech.required();
            r.retardation_pct = self.retardation_pct.unwrap_or(r.retardation_pct);
            r.path_m = self.path_m.unwrap_or(r.path_m);
            r.free_shed_deg = self.free_shed_deg.unwrap_or(r.free_shed_deg);
            mech.with_required(r).or_raise()?
        } else {
            mech
        };
        if self.law.as_deref().is_none_or(|l| l == "compound") && !self.params.is_empty() {
            return Err(parse_err(
                "params",
                "given",
                "params need a catalogue law: the compound law has none (it is designed from V, X, X1)",
            ));
        }
        match &self.law {
            Some(name) if name != "compound" => {
                let spec = LawSpec::parse(name, &self.params).or_raise()?;
                mech.with_law(spec).or_raise()
            }
            _ => Ok(mech),
        }
    }
}

fn parse_err(field: &str, text: &str, expected: &str) -> PyErr {
    crate::errors::raise(loomkin_laws::LawError::Parse {
        field: field.into(),
        text: text.into(),
        expected: expected.into(),
    })
}

fn settings(mech: &Mechanism, set: &[(Setting, f64)], start: StartRule) -> PyResult<Settings> {
    let mut st = Settings::designed(mech);
    for (s, v) in set {
        st = s.set(st, *v, mech).or_raise()?;
    }
    Ok(st.with_start(start))
}

/// pick_design(**model) -> dict
/// --
///
/// `loomkin pick design --json`: the compound picking law designed for V, X, X1 at the design
/// speed (A m/s², μ 1/s, τ s, T′ s) and the mechanism constants B (s²), C, D (m), natural_1_s.
#[pyfunction]
#[pyo3(signature = (**model))]
fn pick_design(py: Python<'_>, model: Option<&Bound<'_, PyDict>>) -> PyResult<Py<PyAny>> {
    let mech = Model::from_kw(model)?.model.build()?;
    to_py(py, &mech.design_report())
}

/// pick_simulate(**model_and_settings) -> dict
/// --
///
/// `loomkin pick simulate --json`: the end of the pick (t_end_s, t0_s, distance_m, velocity_m_s,
/// accelerations m/s², required velocity and the shortfall in %, the route used, B′, C′, D′, and a
/// note when the closed form fell back to the ODE). Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (**kw))]
fn pick_simulate(py: Python<'_>, kw: Option<&Bound<'_, PyDict>>) -> PyResult<Py<PyAny>> {
    let Call { model, set, start, method } = Model::from_kw(kw)?;
    let mech = model.build()?;
    let st = settings(&mech, &set, start)?;
    let o = py.detach(|| simulate(&mech, &st, method)).or_raise()?;
    to_py(py, &o)
}

/// pick_history(points=..., **model_and_settings) -> (dict, dict)
/// --
///
/// The pick over time, as `loomkin pick simulate --csv`: arrays t_s, s_m, v_s_m_s, a_s_m_s2
/// (nominal picker motion) and x_m, v_m_s, a_m_s2 (the shuttle), with the outcome dict.
/// Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (points=Count::of(History::POINTS.default_count()), **kw))]
fn pick_history<'py>(
    py: Python<'py>,
    points: Count,
    kw: Option<&Bound<'py, PyDict>>,
) -> PyResult<(Bound<'py, PyDict>, Py<PyAny>)> {
    let points = points.check(&History::POINTS)?;
    let Call { model, set, start, method } = Model::from_kw(kw)?;
    let mech = model.build()?;
    let st = settings(&mech, &set, start)?;
    let h = py.detach(|| history(&mech, &st, method, points)).or_raise()?;
    let col = |f: &dyn Fn(&loomkin_picking::Sample) -> f64| h.samples.iter().map(f).collect::<Vec<f64>>();
    let cols = vec![
        ("t_s", col(&|s| s.t_s)),
        ("s_m", col(&|s| s.nominal.s_m)),
        ("v_s_m_s", col(&|s| s.nominal.v_m_s)),
        ("a_s_m_s2", col(&|s| s.nominal.a_m_s2)),
        ("x_m", col(&|s| s.actual.x_m)),
        ("v_m_s", col(&|s| s.actual.v_m_s)),
        ("a_m_s2", col(&|s| s.actual.a_m_s2)),
    ];
    Ok((columns(py, cols)?, to_py(py, &h.outcome)?))
}

/// pick_sweep(setting, start, stop, points, shard=None, **model_and_settings) -> dict
/// --
///
/// `loomkin pick sweep SETTING --from --to --points --json`: setting, unit, method,
/// fallback_values and rows, here a dict of columns (the outcome keys of `pick_simulate` and the
/// swept value under `<setting>_<unit>`; numbers as numpy arrays, text as lists, a missing note
/// None). `shard=(I, N)` computes only the rows of `--shard I/N`. The points run in parallel with
/// the GIL released.
#[pyfunction]
#[pyo3(signature = (setting, start, stop, points, shard=None, **kw))]
#[allow(clippy::too_many_arguments)]
fn pick_sweep(
    py: Python<'_>,
    setting: &str,
    start: f64,
    stop: f64,
    points: Count,
    shard: Option<&Bound<'_, PyAny>>,
    kw: Option<&Bound<'_, PyDict>>,
) -> PyResult<Py<PyAny>> {
    let setting = Setting::parse(setting).or_raise()?;
    let points = points.check(&Sweep::HELD_POINTS)?;
    let items = crate::convert::shard(shard)?.items(points);
    let Call { model, set, start: start_rule, method } = Model::from_kw(kw)?;
    let mech = model.build()?;
    let st = settings(&mech, &set, start_rule)?;
    let s = py
        .detach(|| loomkin_picking::sweep_items(&mech, &st, setting, start, stop, points, method, items))
        .or_raise()?;
    // The report as `loomkin pick sweep --json` prints it, its rows as columns.
    let mut report = serde_json::to_value(s.report(method))
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(format!("internal: {e}")))?;
    let rows = report.as_object_mut().and_then(|m| m.remove("rows")).unwrap_or(Value::Array(Vec::new()));
    let out = value_to_py(py, &report)?;
    out.bind(py).set_item("rows", value_records_to_columns(py, &rows)?)?;
    Ok(out)
}

/// pick_montecarlo(study_toml, shard=None, from_draws=None, summary=False, from_summaries=None, **model) -> dict | Table
/// --
///
/// `loomkin pick montecarlo STUDY --json` for the study file's text (draws, seed, `[settings]`
/// distributions, `[limits]`) and the mechanism keywords of `pick_design`: draws, seed, method,
/// ode_draws, not_simulated, separation_draws, failing, fail_share, inputs and results (each
/// quantity's mean, sd, percentiles, histogram, limit and count failing), and `per_draw`, the
/// per-draw table of `--csv` as a Table (draw, the settings drawn, simulated 1/0, the end-of-pick
/// results, flags 1/0). `shard=(I, N)` runs only shard I of N of the draws and returns their
/// per-draw Table (`--shard I/N --csv`); `from_draws` (a list of such tables in shard order, or
/// of paths as `--from-draws` takes) returns the report of the finished run without `per_draw`,
/// equal to the unsharded report. `summary=True` returns the shard's mergeable summary (`--summary`,
/// a dict) and `from_summaries` (their JSON texts) the report merged from them
/// (`--from-summaries`: no percentiles or histograms). The draws run in parallel with the GIL
/// released, a piece at a time: Ctrl-C stops the study between pieces.
#[pyfunction]
#[pyo3(signature = (study_toml, shard=None, from_draws=None, summary=false, from_summaries=None, **model))]
fn pick_montecarlo<'py>(
    py: Python<'py>,
    study_toml: &str,
    shard: Option<&Bound<'py, PyAny>>,
    from_draws: Option<&Bound<'py, PyAny>>,
    summary: bool,
    from_summaries: Option<Vec<String>>,
    model: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyAny>> {
    let call = Model::from_kw(model)?;
    if let Some((s, _)) = call.set.first() {
        return Err(parse_err(
            s.name(),
            "given",
            "the loom settings of a Monte-Carlo study come from its file ([settings]); give only mechanism keywords",
        ));
    }
    let ask = crate::study::Ask::with_summaries(shard, from_draws, summary, from_summaries)?;
    let mc = loomkin_picking::MonteCarlo::from_toml(study_toml).or_raise()?;
    let mech = call.model.build()?;
    crate::study::answer(
        py,
        crate::study::Study {
            command: "pick montecarlo",
            draws: mc.draws,
            run: &|items| mc.run(&mech, items, loomkin_study::Progress::Hidden),
            report: &|d| mc.report(d),
            report_from: &|source| mc.report_from(&mech, source),
            summary: &|items, d| mc.summary(&mech, items, d),
            report_from_summaries: &|parts| mc.report_from_summaries(&mech, parts),
        },
        ask,
    )
}
