//! The elastic follower: the response of a cycle driven through a spring-mass-damper at a speed,
//! keyed as `loomkin dyn response FILE --json`.

use crate::convert::{columns, to_py};
use crate::cycles::Cycle;
use crate::errors::{Fault, OrRaise, check_count};
use loomkin_dynamics::{
    DynError, Follower, Response, ResponseReport, STANDARD_GRAVITY, Start, Units, sweep, sweep_columns, sweep_row,
};
use loomkin_units::{Range, RangeError};
use numpy::{AllowTypeChange, PyArrayLike1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

impl Fault for DynError {
    fn range(&self) -> Option<&RangeError> {
        match self {
            Self::Range(e) => Some(e),
            _ => None,
        }
    }
}

/// Cycles simulated from rest (as the CLI's `--cycles`).
const CYCLES: Range = Range::closed(1.0, 10_000.0, "");
/// Samples per cycle (as the CLI's `--points`).
const POINTS: Range = Range::closed(2.0, 1e6, "");

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(dyn_response, m)?)?;
    m.add_function(wrap_pyfunction!(dyn_sweep, m)?)?;
    Ok(())
}

/// The follower of the CLI's model flags.
fn follower(
    natural_hz: f64,
    damping_ratio: f64,
    mass_kg: Option<f64>,
    return_spring_n_m: f64,
    preload_n: f64,
    weight: bool,
    force_n: f64,
) -> PyResult<Follower> {
    let f = Follower::new(natural_hz, damping_ratio).or_raise()?;
    match mass_kg {
        Some(m) => {
            let w = if weight { m * STANDARD_GRAVITY } else { 0.0 };
            f.with_loads(m, return_spring_n_m, preload_n + w + force_n).or_raise()
        }
        None => Ok(f),
    }
}

/// dyn_response(cycle, natural_hz, damping_ratio=0, mass_kg=None, return_spring_n_m=0,
/// preload_n=0, weight=False, force_n=0, speed_rpm=None, cycles=1, steady=False, points=721) -> dict
/// --
///
/// `loomkin dyn response FILE --json` for a `Cycle`: the follower as a spring-mass-damper of
/// natural frequency natural_hz (Hz) and damping ratio, optionally with its mass (kg), return
/// spring (N/m), preload and force (N) and weight; from rest over `cycles` turns or in steady
/// state. The report (summary with the peak error and residual vibration in the cycle's units,
/// units, speed_rpm, natural_hz, damping_ratio, start, cycles) and `samples`: arrays angle_deg,
/// s, x (driven and actual position), error (in mm or deg) and a (m/s² or rad/s²).
/// Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (cycle, natural_hz, damping_ratio=0.0, mass_kg=None, return_spring_n_m=0.0, preload_n=0.0,
    weight=false, force_n=0.0, speed_rpm=None, cycles=1, steady=false, points=721))]
fn dyn_response<'py>(
    py: Python<'py>,
    cycle: PyRef<'py, Cycle>,
    natural_hz: f64,
    damping_ratio: f64,
    mass_kg: Option<f64>,
    return_spring_n_m: f64,
    preload_n: f64,
    weight: bool,
    force_n: f64,
    speed_rpm: Option<f64>,
    cycles: usize,
    steady: bool,
    points: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let speed = cycle.speed(speed_rpm)?;
    let follower = follower(natural_hz, damping_ratio, mass_kg, return_spring_n_m, preload_n, weight, force_n)?;
    check_count("cycles", cycles, CYCLES)?;
    check_count("points", points, POINTS)?;
    let start = if steady { Start::Steady } else { Start::Rest };
    let inner = &cycle.inner;
    let (summary, samples) = py
        .detach(|| -> Result<_, DynError> {
            let r = Response::new(inner, speed, &follower, start, cycles)?;
            Ok((r.summary(), r.samples(points)))
        })
        .or_raise()?;
    let u = Units::of(inner.unit);
    let report = ResponseReport {
        summary,
        units: u,
        speed_rpm: speed.rpm(),
        natural_hz: follower.natural_hz(),
        damping_ratio: follower.damping_ratio(),
        start,
        cycles: if steady { 1 } else { cycles },
    };
    let out = to_py(py, &report)?.into_bound(py).cast_into::<PyDict>()?;
    let col = |i: usize, k: f64| samples.iter().map(|s| s[i] * k).collect::<Vec<f64>>();
    let p = u.pos;
    let cols = vec![
        ("angle_deg".to_string(), col(0, 1.0)),
        (format!("s_{p}"), col(1, u.scale)),
        (format!("x_{p}"), col(2, u.scale)),
        (format!("error_{p}"), col(3, u.scale)),
        (format!("a_{}", u.acc), col(4, 1.0)),
    ];
    out.set_item("samples", columns(py, cols)?)?;
    Ok(out)
}

/// The most speeds of one sweep (each is one response, a few µs to ms).
const SWEEP_SPEEDS: Range = Range::closed(1.0, 1e6, "");

/// dyn_sweep(cycle, speed_rpm, natural_hz, damping_ratio=0, mass_kg=None, return_spring_n_m=0,
/// preload_n=0, weight=False, force_n=0, steady=False) -> dict
/// --
///
/// `loomkin dyn sweep FILE --speed-rpm … --json` at the speeds of an array (rpm, any order):
/// natural_hz, damping_ratio, start and points, a dict of arrays with the CLI's columns
/// (speed_rpm, residual amplitude, peak error, … in the cycle's units; forces in N with a mass).
/// The speeds run in parallel with the GIL released.
#[pyfunction]
#[pyo3(signature = (cycle, speed_rpm, natural_hz, damping_ratio=0.0, mass_kg=None, return_spring_n_m=0.0,
    preload_n=0.0, weight=false, force_n=0.0, steady=false))]
fn dyn_sweep<'py>(
    py: Python<'py>,
    cycle: PyRef<'py, Cycle>,
    speed_rpm: PyArrayLike1<'py, f64, AllowTypeChange>,
    natural_hz: f64,
    damping_ratio: f64,
    mass_kg: Option<f64>,
    return_spring_n_m: f64,
    preload_n: f64,
    weight: bool,
    force_n: f64,
    steady: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let speeds: Vec<f64> = speed_rpm.as_array().iter().copied().collect();
    check_count("speed_rpm", speeds.len(), SWEEP_SPEEDS)?;
    let follower = follower(natural_hz, damping_ratio, mass_kg, return_spring_n_m, preload_n, weight, force_n)?;
    let start = if steady { Start::Steady } else { Start::Rest };
    let inner = &cycle.inner;
    let pts = py.detach(|| sweep(inner, &follower, &speeds, start)).or_raise()?;
    let u = Units::of(inner.unit);
    let forces = follower.mass_kg().is_some();
    let names = sweep_columns(u, forces);
    let rows: Vec<Vec<f64>> = pts.iter().map(|q| sweep_row(q, u, forces)).collect();
    let cols: Vec<(String, Vec<f64>)> =
        names.into_iter().enumerate().map(|(i, n)| (n, rows.iter().map(|r| r[i]).collect())).collect();
    let out = PyDict::new(py);
    out.set_item("natural_hz", follower.natural_hz())?;
    out.set_item("damping_ratio", follower.damping_ratio())?;
    out.set_item("start", if steady { "steady" } else { "rest" })?;
    out.set_item("points", columns(py, cols)?)?;
    Ok(out)
}
