//! The elastic follower: the response of a cycle driven through a spring-mass-damper at a speed,
//! keyed as `loomkin dyn response FILE --json`.

use crate::convert::{Count, columns, to_py};
use crate::cycles::Cycle;
use crate::errors::{Fault, OrRaise};
use loomkin_dynamics::{DynError, Follower, Response, ResponseReport, Start, Units, sweep, sweep_columns, sweep_row};
use loomkin_units::RangeError;
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

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(dyn_response, m)?)?;
    m.add_function(wrap_pyfunction!(dyn_sweep, m)?)?;
    m.add_function(wrap_pyfunction!(dyn_spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(dyn_compensate, m)?)?;
    m.add_function(wrap_pyfunction!(dyn_optimize, m)?)?;
    m.add_function(wrap_pyfunction!(dyn_two_mass, m)?)?;
    m.add_function(wrap_pyfunction!(dyn_default_ratios, m)?)?;
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
    Follower::new(natural_hz, damping_ratio)
        .and_then(|f| f.with_front_loads(mass_kg, return_spring_n_m, preload_n, weight, force_n))
        .or_raise()
}

/// dyn_response(cycle, natural_hz, damping_ratio=..., mass_kg=None, return_spring_n_m=...,
/// preload_n=..., weight=False, force_n=..., speed_rpm=None, cycles=..., steady=False, points=...) -> dict
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
#[pyo3(signature = (cycle, natural_hz, damping_ratio=Follower::DAMPING_RATIO.default_value(), mass_kg=None, return_spring_n_m=Follower::RETURN_SPRING_N_M.default_value(), preload_n=Follower::PRELOAD_N.default_value(),
    weight=false, force_n=Follower::FORCE_N.default_value(), speed_rpm=None, cycles=Count::of(Response::CYCLES.default_count()), steady=false,
    points=Count::of(Response::POINTS.default_count())))]
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
    cycles: Count,
    steady: bool,
    points: Count,
) -> PyResult<Bound<'py, PyDict>> {
    let speed = cycle.speed(speed_rpm)?;
    let follower = follower(natural_hz, damping_ratio, mass_kg, return_spring_n_m, preload_n, weight, force_n)?;
    let cycles = cycles.check(&Response::CYCLES)?;
    let points = points.check(&Response::POINTS)?;
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

/// dyn_sweep(cycle, speed_rpm, natural_hz, damping_ratio=..., mass_kg=None, return_spring_n_m=...,
/// preload_n=..., weight=False, force_n=..., steady=False, shard=None) -> dict
/// --
///
/// `loomkin dyn sweep FILE --speed-rpm … --json` at the speeds of an array (rpm, any order):
/// natural_hz, damping_ratio, start and points, a dict of arrays with the CLI's columns
/// (speed_rpm, residual amplitude, peak error, … in the cycle's units; forces in N with a mass).
/// `shard=(I, N)` computes only shard I of N of the speeds (`--shard I/N`). The speeds run in
/// parallel with the GIL released.
#[pyfunction]
#[pyo3(signature = (cycle, speed_rpm, natural_hz, damping_ratio=Follower::DAMPING_RATIO.default_value(), mass_kg=None, return_spring_n_m=Follower::RETURN_SPRING_N_M.default_value(),
    preload_n=Follower::PRELOAD_N.default_value(), weight=false, force_n=Follower::FORCE_N.default_value(), steady=false, shard=None))]
#[allow(clippy::too_many_arguments)]
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
    shard: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let all = speed_rpm.as_array();
    loomkin_dynamics::SweepPoint::SPEEDS.check_count(all.len()).or_raise()?;
    // Shard I of N: the rows of `dyn sweep --shard I/N` when the array holds the CLI's speeds.
    let items = crate::convert::shard(shard)?.items(all.len());
    let speeds: Vec<f64> = all.iter().copied().skip(items.start).take(items.len()).collect();
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

/// dyn_spectrum(law, ratio, damping_ratio=...) -> numpy.ndarray
/// --
///
/// The residual-vibration spectrum of a law (`loomkin dyn spectrum` for one law and one damping
/// ratio): the residual amplitude after a rise from rest, in % of the stroke, at each ratio of
/// motion time to natural period T·f_n of the array `ratio` (each 0 < r < 1e4, at most 1e6 of
/// them). Exact (closed-form response per segment). Runs with the GIL released; Ctrl-C stops it.
#[pyfunction]
#[pyo3(signature = (law, ratio, damping_ratio=Follower::DAMPING_RATIO.default_value()))]
fn dyn_spectrum<'py>(
    py: Python<'py>,
    law: PyRef<'py, crate::laws::Law>,
    ratio: PyArrayLike1<'py, f64, AllowTypeChange>,
    damping_ratio: f64,
) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
    let z = Follower::DAMPING_RATIO.check(damping_ratio).or_raise()?;
    let ratios: Vec<f64> = ratio.as_array().iter().copied().collect();
    loomkin_dynamics::RATIOS.check_count(ratios.len()).or_raise()?;
    for &r in &ratios {
        loomkin_dynamics::RATIO.check(r).or_raise()?;
    }
    let law = law.inner.clone();
    let pct = crate::interrupt::detached(py, move || {
        loomkin_dynamics::spectrum(&law, z, &ratios).into_iter().map(|v| 100.0 * v).collect::<Vec<f64>>()
    })?;
    Ok(numpy::PyArray1::from_vec(py, pct))
}

/// dyn_compensate(cycle, natural_hz, damping_ratio=..., mass_kg=None, return_spring_n_m=...,
/// preload_n=..., weight=False, force_n=..., speed_rpm=None, points=...) -> dict
/// --
///
/// `loomkin dyn compensate FILE`: the input law (polydyne) that makes the follower follow the
/// cycle exactly. designed_class and input_class (continuity: highest continuous derivative),
/// period_s, pieces (each t0 and duration in s, from_deg, to_deg, poly: SI coefficients of t^k with
/// t in s from the piece's start, sine: [b_s, b_c, Ω rad/s] or None, exp: [C, a 1/s] or None —
/// the `.toml` output's pieces) and samples (the `.csv` output): arrays angle_deg, x_<P> (the
/// designed motion), s_<P> (the input), s_velocity and s_acceleration in SI (m/s, m/s² or rad/s,
/// rad/s²), P the cycle's unit. A cycle whose input would jump raises LoomkinError (field cycle).
#[pyfunction]
#[pyo3(signature = (cycle, natural_hz, damping_ratio=Follower::DAMPING_RATIO.default_value(), mass_kg=None, return_spring_n_m=Follower::RETURN_SPRING_N_M.default_value(), preload_n=Follower::PRELOAD_N.default_value(),
    weight=false, force_n=Follower::FORCE_N.default_value(), speed_rpm=None,
    points=Count::of(loomkin_dynamics::Compensation::POINTS.default_count())))]
fn dyn_compensate<'py>(
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
    points: Count,
) -> PyResult<Bound<'py, PyDict>> {
    let speed = cycle.speed(speed_rpm)?;
    let follower = follower(natural_hz, damping_ratio, mass_kg, return_spring_n_m, preload_n, weight, force_n)?;
    let points = points.check(&loomkin_dynamics::Compensation::POINTS)?;
    let exc = loomkin_dynamics::Excitation::from_cycle(&cycle.inner, speed);
    let (comp, samples) = py
        .detach(|| -> Result<_, DynError> {
            let comp = loomkin_dynamics::compensate(&exc, &follower)?;
            let samples = comp.samples(&exc, points);
            Ok((comp, samples))
        })
        .or_raise()?;
    let u = Units::of(cycle.inner.unit);
    let p = u.pos;
    let (vel, acc) = if p == "mm" { ("m_s", "m_s2") } else { ("rad_s", "rad_s2") };
    let out = PyDict::new(py);
    out.set_item("designed_class", comp.designed_class)?;
    out.set_item("input_class", comp.input_class)?;
    out.set_item("period_s", comp.period_s)?;
    out.set_item("speed_rpm", speed.rpm())?;
    out.set_item("natural_hz", follower.natural_hz())?;
    out.set_item("damping_ratio", follower.damping_ratio())?;
    let pieces = pyo3::types::PyList::empty(py);
    for piece in &comp.pieces {
        let d = to_py(py, piece)?.into_bound(py).cast_into::<PyDict>()?;
        d.set_item("from_deg", exc.angle_deg(piece.t0))?;
        d.set_item("to_deg", exc.angle_deg(piece.t0 + piece.duration))?;
        pieces.append(d)?;
    }
    out.set_item("pieces", pieces)?;
    let col = |i: usize, k: f64| samples.iter().map(|s| s[i] * k).collect::<Vec<f64>>();
    let cols = vec![
        ("angle_deg".to_string(), col(0, 1.0)),
        (format!("x_{p}"), col(1, u.scale)),
        (format!("s_{p}"), col(2, u.scale)),
        (format!("s_velocity_{vel}"), col(3, 1.0)),
        (format!("s_acceleration_{acc}"), col(4, 1.0)),
    ];
    out.set_item("samples", columns(py, cols)?)?;
    Ok(out)
}

/// dyn_optimize(cycle, natural_hz, damping_ratio=..., mass_kg=None, return_spring_n_m=...,
/// preload_n=..., weight=False, force_n=..., speed_rpm=None, band_pct=...) -> dict
/// --
///
/// `loomkin dyn optimize FILE --json`: every rise and return of the cycle shaped for the least
/// residual vibration across speed_rpm·(1 ± band_pct/100), peak acceleration at most 110 % of the
/// modified sine's. speed_rpm, band_pct, natural_hz, damping_ratio, residual_amplitude_<P> and
/// modified_sine_residual_amplitude_<P> (largest dwell residual over the band, P the cycle's unit),
/// improvement_factor, peak_acceleration_ratio, segments (per moving segment: ratio_band, residual
/// fractions of the stroke, ca_ratio), and cycle_toml (the optimised cycle file `-o` writes).
/// Runs with the GIL released (seconds); Ctrl-C stops waiting for it.
#[pyfunction]
#[pyo3(signature = (cycle, natural_hz, damping_ratio=Follower::DAMPING_RATIO.default_value(), mass_kg=None, return_spring_n_m=Follower::RETURN_SPRING_N_M.default_value(), preload_n=Follower::PRELOAD_N.default_value(),
    weight=false, force_n=Follower::FORCE_N.default_value(), speed_rpm=None,
    band_pct=loomkin_dynamics::Optimized::BAND_PCT.default_value()))]
fn dyn_optimize<'py>(
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
    band_pct: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let speed = cycle.speed(speed_rpm)?;
    let follower = follower(natural_hz, damping_ratio, mass_kg, return_spring_n_m, preload_n, weight, force_n)?;
    let text = cycle.toml_text()?;
    let opt =
        crate::interrupt::detached(py, move || loomkin_dynamics::optimize_cycle(&text, speed, band_pct, &follower))?
            .or_raise()?;
    let report = loomkin_dynamics::OptimizeReport {
        optimized: &opt,
        units: Units::of(cycle.inner.unit),
        speed_rpm: speed.rpm(),
        band_pct,
        natural_hz: follower.natural_hz(),
        damping_ratio: follower.damping_ratio(),
    };
    let out = to_py(py, &report)?.into_bound(py).cast_into::<PyDict>()?;
    out.set_item("cycle_toml", &opt.cycle_toml)?;
    Ok(out)
}

/// dyn_two_mass(cycle, drive_mass_kg, drive_stiffness_n_m, frame_mass_kg, frame_stiffness_n_m,
/// damping_ratio=..., speed_rpm=None, steady=False) -> dict
/// --
///
/// `loomkin dyn two-mass FILE --json`: the cycle drives a drive mass (kg) through a stiffness
/// (N/m), which drives the heald frame (kg) through a second stiffness (N/m), both modes damped by
/// damping_ratio. natural_hz (both modes, Hz), peak_drive_error_<P> and peak_frame_error_<P> with
/// where (…_at_deg), frame_residual_bound_<P> (in the dwells), rigidity_ratio (f₁/f_shaft),
/// speed_rpm, damping_ratio, start; P the cycle's unit. Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (cycle, drive_mass_kg, drive_stiffness_n_m, frame_mass_kg, frame_stiffness_n_m,
    damping_ratio=Follower::DAMPING_RATIO.default_value(), speed_rpm=None, steady=false))]
#[allow(clippy::too_many_arguments)]
fn dyn_two_mass(
    py: Python<'_>,
    cycle: PyRef<'_, Cycle>,
    drive_mass_kg: f64,
    drive_stiffness_n_m: f64,
    frame_mass_kg: f64,
    frame_stiffness_n_m: f64,
    damping_ratio: f64,
    speed_rpm: Option<f64>,
    steady: bool,
) -> PyResult<Py<PyAny>> {
    let speed = cycle.speed(speed_rpm)?;
    let tm = loomkin_dynamics::TwoMass::new(
        drive_mass_kg,
        drive_stiffness_n_m,
        frame_mass_kg,
        frame_stiffness_n_m,
        damping_ratio,
    )
    .or_raise()?;
    let start = if steady { Start::Steady } else { Start::Rest };
    let exc = loomkin_dynamics::Excitation::from_cycle(&cycle.inner, speed);
    let u = Units::of(cycle.inner.unit);
    let r = py.detach(|| tm.report(&exc, speed, start, u)).or_raise()?;
    to_py(py, &r)
}

/// dyn_default_ratios() -> numpy.ndarray
/// --
///
/// The ratios `dyn spectrum` takes when none are given (the span loomkin_dynamics::DEFAULT_RATIOS).
#[pyfunction]
fn dyn_default_ratios(py: Python<'_>) -> Bound<'_, numpy::PyArray1<f64>> {
    numpy::PyArray1::from_vec(py, loomkin_dynamics::default_ratios())
}
