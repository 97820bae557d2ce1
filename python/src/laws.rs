//! Normalised laws: the catalogue, `Law` objects (catalogue, piecewise, polynomial, servo spline)
//! with metrics, continuity and sampling into numpy arrays.

use crate::convert::{self, Count, fill_columns, to_py};
use crate::errors::OrRaise;
use loomkin_laws::{ContinuityReport, InfoReport, Kinematics, LawSpec, ListedLaw, ParamValue};
use loomkin_units::Shard;
use numpy::{AllowTypeChange, PyArrayLikeDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::collections::BTreeMap;

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Law>()?;
    m.add_function(wrap_pyfunction!(law_catalogue, m)?)?;
    Ok(())
}

/// law_catalogue() -> list[dict]
/// --
///
/// The catalogue of laws that need no parameters given, as `loomkin law list --json`'s `laws`:
/// name, description, params, the metrics cv, x_cv, ca, ca_pos, x_ca_pos, ca_neg, x_ca_neg, cj,
/// x_cj, cm, x_cm, ca_rms (dimensionless: per unit stroke and unit motion angle; x a fraction of
/// the motion angle) and continuity_class.
#[pyfunction]
fn law_catalogue(py: Python<'_>) -> PyResult<Py<PyAny>> {
    to_py(py, &ListedLaw::catalogue().or_raise()?)
}

/// A normalised rise law: x ∈ [0, 1] (fraction of the motion angle) to s ∈ [0, 1] (fraction of
/// the stroke), with v = ds/dx, a = d²s/dx², j = d³s/dx³ (all dimensionless), exact in closed form.
///
/// `Law(name, **params)` takes a catalogue name (`loomkin.laws.names()`) and its parameters as
/// keywords, e.g. `Law("modified-trapezoid", ramp=0.1)` or
/// `Law("piecewise", segments="0.5:constant:1,0.5:constant:-1")`. Servo spline laws come from
/// `loomkin.servo.spline_law`.
#[pyclass(module = "loomkin", frozen)]
pub struct Law {
    name: String,
    label: String,
    params: BTreeMap<String, ParamValue>,
    pub(crate) inner: loomkin_laws::Law,
}

impl Law {
    /// A law object around a law built elsewhere (the servo spline).
    pub fn wrap(name: &str, label: String, params: BTreeMap<String, ParamValue>, inner: loomkin_laws::Law) -> Self {
        Self { name: name.to_string(), label, params, inner }
    }
}

fn kin_columns(x: Vec<f64>, k: &[Kinematics]) -> Vec<(&'static str, Vec<f64>)> {
    vec![
        ("x", x),
        ("s", k.iter().map(|k| k.s).collect()),
        ("v", k.iter().map(|k| k.v).collect()),
        ("a", k.iter().map(|k| k.a).collect()),
        ("j", k.iter().map(|k| k.j).collect()),
    ]
}

/// Samples of a law, `points` evenly spaced from 0 to 1 (shard `shard` of them, as `loomkin law
/// sample --shard I/N`), as a [`Table`](crate::convert::table) of arrays x, s, v, a, j; the GIL is
/// released while they are computed.
pub fn sample_table<'py>(
    py: Python<'py>,
    law: &loomkin_laws::Law,
    points: &Count,
    shard: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let points = points.check(&loomkin_laws::Law::HELD_POINTS)?;
    let shard = crate::convert::shard(shard)?;
    let cols = if shard == Shard::WHOLE {
        crate::convert::law_samples(py, law, points)?
    } else {
        // The share of the whole run's samples, bit for bit: the stream `law sample --shard` prints.
        let items = shard.items(points);
        fill_columns(py, &["x", "s", "v", "a", "j"], items.len(), |c| {
            let [x, s, v, a, j] = c else { return };
            for (i, (xi, k)) in law.samples(points).skip(items.start).take(items.len()).enumerate() {
                (x[i], s[i], v[i], a[i], j[i]) = (xi, k.s, k.v, k.a, k.j);
            }
        })?
    };
    crate::convert::table(py, cols)
}

#[pymethods]
impl Law {
    #[new]
    #[pyo3(signature = (name, **params))]
    fn new(name: &str, params: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let params = convert::params(params)?;
        let spec = LawSpec::parse(name, &params).or_raise()?;
        let inner = spec.build().or_raise()?;
        Ok(Self { name: spec.name().to_string(), label: spec.label(), params: spec.param_values(), inner })
    }

    /// The catalogue name (`"cycloidal"`, `"servo-spline"` for a spline law).
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// The name with its parameters, e.g. `modified-trapezoid (ramp=0.1)`.
    #[getter]
    fn label(&self) -> &str {
        &self.label
    }

    /// The parameters, typed: numbers as floats, text as str.
    #[getter]
    fn params(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        to_py(py, &self.params)
    }

    /// Number of closed-form segments.
    #[getter]
    fn segments(&self) -> usize {
        self.inner.segments().len()
    }

    /// The positions x of the joints between segments (fractions of the motion angle).
    #[getter]
    fn joints(&self) -> Vec<f64> {
        self.inner.joints().collect()
    }

    /// metrics() -> dict
    /// --
    ///
    /// Exact metrics (dimensionless, per unit stroke and unit motion angle; x a fraction of the
    /// motion angle): cv = max v at x_cv; ca = max |a|, ca_pos at x_ca_pos, ca_neg at x_ca_neg;
    /// cj = max |j| inside segments at x_cj; cm = max v·a at x_cm; ca_rms = √∫a²dx. Extremes are
    /// located per segment (bracketing and Newton), not read on a grid.
    fn metrics(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let m = py.detach(|| self.inner.metrics());
        to_py(py, &m)
    }

    /// continuity() -> dict
    /// --
    ///
    /// The jumps (right − left) ds, dv, da, dj at x = 0 against a dwell at s = 0 (`start`), at
    /// every joint (`joints`) and at x = 1 against a dwell at s = 1 (`end`), each with the flags
    /// `continuous` {s, v, a, j} and `continuous_up_to`; `class` is the law's continuity class in a
    /// dwell-rise-dwell cycle (2: C2, −1: s jumps). As `loomkin law info --json`'s `continuity`.
    fn continuity(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let c = self.inner.continuity();
        to_py(py, &ContinuityReport::from(&c))
    }

    /// info() -> dict
    /// --
    ///
    /// Everything `loomkin law info NAME --json` prints: law, params, the metrics (flattened),
    /// segments and continuity.
    fn info(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let r = py.detach(|| InfoReport::new(&self.name, self.params.clone(), &self.inner));
        to_py(py, &r)
    }

    /// sample(points, shard=None) -> Table
    /// --
    ///
    /// `points` (2 ≤ points ≤ 1e8) evenly spaced samples from x = 0 to 1, both ends included, as
    /// a Table of float64 arrays x, s, v, a, j (dimensionless). The same numbers as `loomkin law
    /// sample`; `shard=(I, N)` (or "I/N") gives only the rows of `--shard I/N`. Runs with the GIL
    /// released.
    #[pyo3(signature = (points, shard=None))]
    fn sample<'py>(
        &self,
        py: Python<'py>,
        points: Count,
        shard: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        sample_table(py, &self.inner, &points, shard)
    }

    /// __call__(x) -> Table
    /// --
    ///
    /// The law at the positions `x` (a number, or an array of any shape, or anything numpy turns
    /// into one) as a Table x, s, v, a, j: floats for a number, arrays of `x`'s shape otherwise.
    /// Outside [0, 1] the follower dwells: s is the law's end value, v, a and j are 0. Runs with
    /// the GIL released.
    fn __call__<'py>(
        &self,
        py: Python<'py>,
        x: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let shape = x.shape().to_vec();
        let xs: Vec<f64> = x.as_array().iter().copied().collect();
        let cols = py.detach(|| {
            let k: Vec<Kinematics> = xs.iter().map(|&x| self.inner.eval(x)).collect();
            kin_columns(xs, &k)
        });
        crate::convert::shaped_table(py, cols, &shape)
    }

    fn __repr__(&self) -> String {
        format!("Law({})", self.label)
    }
}
