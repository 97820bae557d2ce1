//! Weft insertion beyond the shuttle: the time budget of any carrier, the rapier, the projectile
//! and the air jet, keyed as `loomkin insert budget|rapier|projectile|airjet --json`.

use crate::convert::to_py;
use crate::errors::OrRaise;
use crate::loom::{Wif, read};
use loomkin_insertion::BudgetInputs;
use loomkin_loom::{Loom, LoomError, Pattern, insertion, insertion_air};
use loomkin_units::ShaftSpeed;
use pyo3::prelude::*;

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(insert_budget, m)?)?;
    m.add_function(wrap_pyfunction!(insert_rapier, m)?)?;
    m.add_function(wrap_pyfunction!(insert_projectile, m)?)?;
    m.add_function(wrap_pyfunction!(insert_airjet, m)?)?;
    Ok(())
}

/// The speed: `speed_rpm` when given (checked under that name), else the loom file's.
fn speed_of(loom: &Loom, speed_rpm: Option<f64>) -> PyResult<ShaftSpeed> {
    match speed_rpm {
        Some(v) => ShaftSpeed::from_rpm_field("speed_rpm", v).or_raise(),
        None => Ok(loom.speed),
    }
}

/// insert_budget(loom_toml=None, wif=None, lift_plan=None, reed_width_mm=None, carrier_length_mm=None, window_deg=None, speed_m_s=None, speed_rpm=None, carrier_mass_g=None) -> dict
/// --
///
/// `loomkin insert budget [LOOM.toml] --json`: the highest loom speed (max_picks_per_min) for the
/// reed width, carrier length, window and mean carrier speed, the carrier speed needed at the
/// loom's speed, energy per pick and drive power for a carrier mass. Every keyword given replaces
/// the loom file's; without a file the reed width, carrier length, window and speed are needed.
/// With a pattern the window is its clear-shed window.
#[pyfunction]
#[pyo3(signature = (loom_toml=None, wif=None, lift_plan=None, reed_width_mm=None, carrier_length_mm=None,
    window_deg=None, speed_m_s=None, speed_rpm=None, carrier_mass_g=None))]
#[allow(clippy::too_many_arguments)]
fn insert_budget(
    py: Python<'_>,
    loom_toml: Option<&str>,
    wif: Option<Wif>,
    lift_plan: Option<&str>,
    reed_width_mm: Option<f64>,
    carrier_length_mm: Option<f64>,
    window_deg: Option<f64>,
    speed_m_s: Option<f64>,
    speed_rpm: Option<f64>,
    carrier_mass_g: Option<f64>,
) -> PyResult<Py<PyAny>> {
    let given = wif.is_some() || lift_plan.is_some();
    let base = match loom_toml {
        Some(text) => {
            let (loom, pattern) = if given {
                let (l, p) = read(py, text, wif, lift_plan)?;
                (l, Some(p))
            } else {
                (Loom::from_toml(text).or_raise()?, None)
            };
            Some(py.detach(|| insertion::budget_of(&loom, pattern.as_ref())).or_raise()?)
        }
        None if given => {
            return Err(crate::study::error(
                "wif",
                &format!("wif, lift_plan: {}", loomkin_insertion::budget::PATTERN_NEEDS_LOOM),
            ));
        }
        None => None,
    };
    let inputs = BudgetInputs { reed_width_mm, carrier_length_mm, window_deg, speed_m_s, speed_rpm, carrier_mass_g };
    let b = inputs.onto(base).map_err(|m| crate::study::error(m.field, &m.message(m.field)))?;
    to_py(py, &b.report().or_raise()?)
}

/// A carrier's check of the loom file on its pattern at `speed_rpm` (the file's when None), with
/// the GIL released, as a dict.
fn on_pattern<T: serde::Serialize + Send>(
    py: Python<'_>,
    (loom_toml, wif, lift_plan, speed_rpm): (&str, Option<Wif>, Option<&str>, Option<f64>),
    check: impl FnOnce(&Loom, &Pattern, ShaftSpeed) -> Result<T, LoomError> + Send,
) -> PyResult<Py<PyAny>> {
    let (loom, pattern) = read(py, loom_toml, wif, lift_plan)?;
    let speed = speed_of(&loom, speed_rpm)?;
    let r = py.detach(|| check(&loom, &pattern, speed)).or_raise()?;
    to_py(py, &r)
}

/// insert_rapier(loom_toml, wif=None, lift_plan=None, speed_rpm=None) -> dict
/// --
///
/// `loomkin insert rapier LOOM.toml --json`: the transfer (transfer_overlap_mm,
/// transfer_relative_speed_m_s, …), each head's stroke, reversing point and peaks, and the least
/// clearance over every pick of the pattern (min_clearance_mm, worst_pick, worst_angle_deg,
/// worst_position_mm) at speed_rpm (the file's when None). Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (loom_toml, wif=None, lift_plan=None, speed_rpm=None))]
fn insert_rapier(
    py: Python<'_>,
    loom_toml: &str,
    wif: Option<Wif>,
    lift_plan: Option<&str>,
    speed_rpm: Option<f64>,
) -> PyResult<Py<PyAny>> {
    on_pattern(py, (loom_toml, wif, lift_plan, speed_rpm), insertion::rapier_check)
}

/// insert_projectile(loom_toml, wif=None, lift_plan=None, speed_rpm=None) -> dict
/// --
///
/// `loomkin insert projectile LOOM.toml --json`: the bar's energy, projectile_speed_m_s,
/// flight_time_ms, arrival_deg, the brake, the guide teeth's least clearance over every pick and,
/// with a `[sley]`, the fit in its back dwell, at speed_rpm (the file's when None). Runs with the
/// GIL released.
#[pyfunction]
#[pyo3(signature = (loom_toml, wif=None, lift_plan=None, speed_rpm=None))]
fn insert_projectile(
    py: Python<'_>,
    loom_toml: &str,
    wif: Option<Wif>,
    lift_plan: Option<&str>,
    speed_rpm: Option<f64>,
) -> PyResult<Py<PyAny>> {
    on_pattern(py, (loom_toml, wif, lift_plan, speed_rpm), insertion_air::projectile_check)
}

/// insert_airjet(loom_toml, speed_rpm=None) -> dict
/// --
///
/// `loomkin insert airjet LOOM.toml --json`: the yarn tip's arrival_deg, flight_time_ms,
/// tip_speed_at_exit_m_s and the relay_plan (group, open_deg, close_deg per group) with the air
/// consumed (relay_open_ms), at speed_rpm (the file's when None). Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (loom_toml, speed_rpm=None))]
fn insert_airjet(py: Python<'_>, loom_toml: &str, speed_rpm: Option<f64>) -> PyResult<Py<PyAny>> {
    let loom = Loom::from_toml(loom_toml).or_raise()?;
    let speed = speed_of(&loom, speed_rpm)?;
    let r = py.detach(|| insertion_air::airjet_check(&loom, speed)).or_raise()?;
    to_py(py, &r)
}
