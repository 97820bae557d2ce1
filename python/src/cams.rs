//! Controller cam tables of a cycle, keyed as `loomkin cam table CYCLE --format F --json`.

use crate::cycles::Cycle;
use crate::errors::{Fault, OrRaise, raise};
use loomkin_cams::CamError;
use loomkin_cams::table::{CamTable, Format, INTERPOLATION, Motion, Spacing};
use loomkin_units::RangeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

impl Fault for CamError {
    fn range(&self) -> Option<&RangeError> {
        match self {
            Self::Range(e) => Some(e),
            _ => None,
        }
    }
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(cam_table, m)?)?;
    Ok(())
}

/// cam_table(cycle, format, step_deg=None, tolerance=None, source="") -> dict
/// --
///
/// `loomkin cam table CYCLE --format F --json` and the file it writes: text (the table, byte for
/// byte as `-o` writes it), source, format (xyvaj, poly5, csv, twincat, st), points, unit (the
/// slave's: mm or deg), spacing, interpolation, the exact re-interpolation errors
/// max_position_error_<unit> (at max_position_error_at_deg), max_velocity_error_<unit>_per_deg,
/// max_accel_error_<unit>_per_deg2 and the decimals written. Points every step_deg (default 1°)
/// or as few as keep the error within tolerance (slave unit). Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (cycle, format, step_deg=None, tolerance=None, source=""))]
fn cam_table<'py>(
    py: Python<'py>,
    cycle: PyRef<'py, Cycle>,
    format: &str,
    step_deg: Option<f64>,
    tolerance: Option<f64>,
    source: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let format = Format::ALL.into_iter().find(|f| f.name().eq_ignore_ascii_case(format.trim())).ok_or_else(|| {
        raise(CamError::Parse {
            field: "format".into(),
            reason: format!("'{format}': allowed {}", Format::ALL.map(|f| f.name()).join(", ")),
        })
    })?;
    if step_deg.is_some() && tolerance.is_some() {
        return Err(raise(CamError::Usage {
            field: "tolerance".into(),
            reason: "give step_deg or tolerance, not both".into(),
        }));
    }
    let spacing = match tolerance {
        Some(t) => Spacing::Tolerance(t),
        None => Spacing::StepDeg(step_deg.unwrap_or(1.0)),
    };
    let motion = Motion::from_cycle(&cycle.inner);
    let (table, out) = py
        .detach(|| -> Result<_, CamError> {
            let table = CamTable::new(motion, spacing)?;
            let out = table.export(format)?;
            Ok((table, out))
        })
        .or_raise()?;
    let u = table.unit_name();
    let e = &out.error;
    let d = table.decimals();
    let r = PyDict::new(py);
    r.set_item("text", &out.text)?;
    r.set_item("source", source)?;
    r.set_item("format", format.name())?;
    r.set_item("points", out.points)?;
    r.set_item("unit", u)?;
    r.set_item("spacing", crate::convert::to_py(py, &table.spacing())?)?;
    let interpolation = if format == Format::Poly5 { "poly5 segments as written" } else { INTERPOLATION };
    r.set_item("interpolation", interpolation)?;
    r.set_item(format!("max_position_error_{u}"), e.max_position_error)?;
    r.set_item("max_position_error_at_deg", e.max_position_error_at_deg)?;
    r.set_item(format!("max_velocity_error_{u}_per_deg"), e.max_velocity_error)?;
    r.set_item(format!("max_accel_error_{u}_per_deg2"), e.max_accel_error)?;
    let dec = PyDict::new(py);
    dec.set_item("master", d.master)?;
    dec.set_item("y", d.y)?;
    dec.set_item("v", d.v)?;
    dec.set_item("a", d.a)?;
    dec.set_item("j", d.j)?;
    r.set_item("decimals", dec)?;
    Ok(r)
}
