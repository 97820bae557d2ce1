//! Machine cycles in SI units at a speed, from a TOML file's text or a dict (as JSON text).

use crate::convert::{Count, fill_columns, to_py};
use crate::errors::OrRaise;
use loomkin_laws::{CycleSpec, LawError};
use loomkin_units::ShaftSpeed;
use numpy::{AllowTypeChange, PyArrayLikeDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Cycle>()?;
    Ok(())
}

/// A checked machine cycle: dwells, rises and returns over one turn of the main shaft, each
/// moving segment a catalogue law; results in SI units (m, m/s, m/s², m/s³ for `unit = "mm"`;
/// rad, rad/s … for `unit = "deg"`).
///
/// Build it with `Cycle.from_toml(text)` or `Cycle.from_json(text)` (the Python layer's
/// `loomkin.cycles.load(path)` and `loomkin.cycles.from_dict(d)` call these).
#[pyclass(module = "loomkin", frozen)]
pub struct Cycle {
    pub(crate) inner: loomkin_laws::Cycle,
    /// The checked file's keys (what `to_toml` writes and `dyn optimize` reshapes).
    pub(crate) spec: CycleSpec,
}

impl Cycle {
    /// A cycle of a spec, checked.
    pub(crate) fn from_spec(spec: CycleSpec) -> PyResult<Self> {
        Ok(Self { inner: loomkin_laws::Cycle::new(&spec).or_raise()?, spec })
    }

    /// The spec as a cycle file's TOML text.
    pub(crate) fn toml_text(&self) -> PyResult<String> {
        toml::to_string(&self.spec).map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(format!("internal: {e}")))
    }

    /// `points` samples over the cycle at `speed` as arrays angle_deg, time_s and s, v, a, j named
    /// with their SI units (`s_m`, `v_m_s`, … or `s_rad`, …), written straight into the arrays.
    fn sample_arrays<'py>(&self, py: Python<'py>, speed: ShaftSpeed, points: usize) -> PyResult<Bound<'py, PyDict>> {
        let names = self.inner.unit.sample_keys();
        let inner = &self.inner;
        fill_columns(py, &names, points, |c| {
            let [th, t, s, v, a, j] = c else { return };
            for (i, p) in inner.samples(points, speed.rpm()).enumerate() {
                th[i] = p.angle_deg;
                t[i] = p.time_s;
                s[i] = p.kin.s;
                v[i] = p.kin.v;
                a[i] = p.kin.a;
                j[i] = p.kin.j;
            }
        })
    }
    pub(crate) fn speed(&self, speed_rpm: Option<f64>) -> PyResult<ShaftSpeed> {
        let rpm = self.inner.speed_rpm_or(speed_rpm);
        ShaftSpeed::from_rpm_field("speed_rpm", rpm).or_raise()
    }
}

#[pymethods]
impl Cycle {
    /// from_toml(text) -> Cycle
    /// --
    ///
    /// Reads and checks a cycle file's TOML text (the format of `loomkin cycle FILE.toml`).
    #[staticmethod]
    fn from_toml(text: &str) -> PyResult<Self> {
        let inner = loomkin_laws::Cycle::from_toml(text).or_raise()?;
        // The text parsed above, so it parses here too.
        let spec: CycleSpec = toml::from_str(text).map_err(|e| {
            crate::errors::raise(LawError::Parse {
                field: "cycle file".into(),
                text: e.message().into(),
                expected: "TOML".into(),
            })
        })?;
        Ok(Self { inner, spec })
    }

    /// from_json(text) -> Cycle
    /// --
    ///
    /// Reads and checks a cycle given as JSON text with the cycle file's keys (unit, stroke,
    /// speed_rpm, period_deg, segment: [{kind, to_deg | length_deg, law, params, stroke}, …]).
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        let spec: CycleSpec = serde_json::from_str(text)
            .map_err(|e| LawError::Parse {
                field: "cycle".into(),
                text: e.to_string(),
                expected: "the cycle file's keys: unit, stroke, speed_rpm, period_deg, segment (a list of tables)"
                    .into(),
            })
            .or_raise()?;
        Self::from_spec(spec)
    }

    /// laws() -> list[tuple[int, Law]]
    /// --
    ///
    /// The law of each rise and return, with the segment's index.
    fn laws(&self) -> Vec<(usize, crate::laws::Law)> {
        let mut out = Vec::new();
        for (i, seg) in self.inner.segments.iter().enumerate() {
            if let Some((spec, law)) = &seg.law {
                out.push((i, crate::laws::Law::wrap(spec.name(), spec.label(), spec.param_values(), law.clone())));
            }
        }
        out
    }

    /// to_toml() -> str
    /// --
    ///
    /// The cycle as a cycle file's TOML text (`Cycle.from_toml` reads it back to the same cycle).
    fn to_toml(&self) -> PyResult<String> {
        self.toml_text()
    }

    /// The unit of the file's strokes: "mm" (translating follower) or "deg" (swinging).
    #[getter]
    fn unit(&self) -> &'static str {
        match self.inner.unit {
            loomkin_laws::StrokeUnit::Mm => "mm",
            loomkin_laws::StrokeUnit::Deg => "deg",
        }
    }

    /// Angle of one cycle of the main shaft (deg).
    #[getter]
    fn period_deg(&self) -> f64 {
        self.inner.period_rad.to_degrees()
    }

    /// The speed given in the file (rpm), or None.
    #[getter]
    fn speed_rpm(&self) -> Option<f64> {
        self.inner.speed_rpm
    }

    /// report(speed_rpm=None, points=...) -> dict
    /// --
    ///
    /// `loomkin cycle FILE --json`: speed_rpm, period_deg, cycle_time_s (s), unit (SI unit of
    /// position), segments (kind, from_deg, to_deg, law, stroke and peak velocity, acceleration,
    /// jerk with their units in the keys) and samples as a dict of numpy arrays (angle_deg, time_s,
    /// s_m, v_m_s, a_m_s2, j_m_s3 or the rad forms). speed_rpm: the call's, else the file's, else 300.
    /// Runs with the GIL released.
    #[pyo3(signature = (speed_rpm=None, points=Count::of(loomkin_laws::Cycle::HELD_POINTS.default_count())))]
    fn report(&self, py: Python<'_>, speed_rpm: Option<f64>, points: Count) -> PyResult<Py<PyAny>> {
        let speed = self.speed(speed_rpm)?;
        let points = points.check(&loomkin_laws::Cycle::HELD_POINTS)?;
        // The report's head without samples, then the samples straight into numpy arrays.
        let out = to_py(py, &self.inner.report(speed, 0))?;
        out.bind(py).set_item("samples", self.sample_arrays(py, speed, points)?)?;
        Ok(out)
    }

    /// sample(speed_rpm=None, points=...) -> Table
    /// --
    ///
    /// The samples of `report` alone as a Table (angle_deg, time_s, s_m, v_m_s, a_m_s2, j_m_s3 or
    /// the rad forms; `points` evenly spaced over the cycle, both ends included), written straight
    /// into the arrays with the GIL released.
    #[pyo3(signature = (speed_rpm=None, points=Count::of(loomkin_laws::Cycle::HELD_POINTS.default_count())))]
    fn sample<'py>(&self, py: Python<'py>, speed_rpm: Option<f64>, points: Count) -> PyResult<Bound<'py, PyAny>> {
        let speed = self.speed(speed_rpm)?;
        let points = points.check(&loomkin_laws::Cycle::HELD_POINTS)?;
        crate::convert::table(py, self.sample_arrays(py, speed, points)?)
    }

    /// segments(speed_rpm=None) -> list[dict]
    /// --
    ///
    /// The per-segment peaks of `report` without the samples.
    #[pyo3(signature = (speed_rpm=None))]
    fn segments(&self, py: Python<'_>, speed_rpm: Option<f64>) -> PyResult<Py<PyAny>> {
        let speed = self.speed(speed_rpm)?;
        to_py(py, &self.inner.segment_peaks(speed))
    }

    /// __call__(angle_deg, speed_rpm=None) -> Table
    /// --
    ///
    /// The cycle at main-shaft angles (deg, wrapped into the cycle; a number or an array of any
    /// shape) as a Table angle_deg, s, v, a, j in SI units: floats for a number, arrays of the
    /// input's shape otherwise. Runs with the GIL released.
    #[pyo3(signature = (angle_deg, speed_rpm=None))]
    fn __call__<'py>(
        &self,
        py: Python<'py>,
        angle_deg: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
        speed_rpm: Option<f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let rpm = self.speed(speed_rpm)?.rpm();
        let shape = angle_deg.shape().to_vec();
        let th: Vec<f64> = angle_deg.as_array().iter().copied().collect();
        let cols = py.detach(|| {
            let k: Vec<_> = th.iter().map(|&t| self.inner.eval(t.to_radians(), rpm)).collect();
            vec![
                ("angle_deg", th.clone()),
                ("s", k.iter().map(|k| k.s).collect()),
                ("v", k.iter().map(|k| k.v).collect()),
                ("a", k.iter().map(|k| k.a).collect()),
                ("j", k.iter().map(|k| k.j).collect()),
            ]
        });
        crate::convert::shaped_table(py, cols, &shape)
    }

    fn __repr__(&self) -> String {
        format!("Cycle(unit={}, period_deg={}, segments={})", self.unit(), self.period_deg(), self.inner.segments.len())
    }
}
