//! Library errors as Python exceptions.
//!
//! `LoomkinError(ValueError)` carries `.field` (the input field at fault, as the libraries name it
//! through [`FieldError`]) and `.allowed` (the allowed range in words, or what is accepted, or
//! `None`); `OutOfRangeError(LoomkinError)` is raised for a number outside its range and adds
//! `.value`, `.unit`, `.low` and `.high` (the bounds, `None` when a side is unbounded) and
//! `.low_inclusive`, `.high_inclusive`.

use loomkin_units::{Bound as Side, FieldError, RangeError};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

create_exception!(
    loomkin,
    LoomkinError,
    PyValueError,
    "Bad input to a loomkin function. Attributes: field (str or None), allowed (str or None)."
);
create_exception!(
    loomkin,
    OutOfRangeError,
    LoomkinError,
    "A number outside its allowed range. Adds value, unit, low, high, low_inclusive, high_inclusive."
);

/// Registers the exception classes.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("LoomkinError", py.get_type::<LoomkinError>())?;
    m.add("OutOfRangeError", py.get_type::<OutOfRangeError>())?;
    Ok(())
}

/// A library error the module can raise: its field (from [`FieldError`]), the range error inside it
/// when it is about a number out of range, and otherwise what is accepted, when the error says.
pub trait Fault: FieldError {
    /// The range error inside, if the error is about a number out of range.
    fn range(&self) -> Option<&RangeError>;
    /// What is accepted, in words, for errors that are not about a range (known names, forms).
    fn accepted(&self) -> Option<String> {
        None
    }
}

impl Fault for RangeError {
    fn range(&self) -> Option<&RangeError> {
        Some(self)
    }
}

impl Fault for loomkin_laws::LawError {
    fn range(&self) -> Option<&RangeError> {
        match self {
            Self::Range(e) => Some(e),
            _ => None,
        }
    }
    fn accepted(&self) -> Option<String> {
        match self {
            Self::UnknownLaw { known, .. } => Some(known.clone()),
            Self::UnknownParam { allowed, .. } => Some(allowed.clone()),
            Self::Parse { expected, .. } => Some(expected.clone()),
            _ => None,
        }
    }
}

impl Fault for loomkin_servo::ServoError {
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
            Self::Parse { expected, .. } => Some(expected.clone()),
            _ => None,
        }
    }
}

/// The Python exception for a library error.
pub fn raise<E: Fault>(e: E) -> PyErr {
    Python::attach(|py| {
        let msg = e.to_string();
        let field = e.field().map(str::to_string);
        match e.range() {
            Some(r) => {
                let err = OutOfRangeError::new_err(msg);
                let v = err.value(py);
                let _ = fill_range(v, field, r);
                err
            }
            None => {
                let err = LoomkinError::new_err(msg);
                let v = err.value(py);
                let _ = v.setattr("field", field);
                let _ = v.setattr("allowed", e.accepted());
                err
            }
        }
    })
}

fn fill_range(v: &Bound<'_, pyo3::exceptions::PyBaseException>, field: Option<String>, r: &RangeError) -> PyResult<()> {
    let side = |b: Side| match b {
        Side::Unbounded => (None, false),
        Side::Closed(x) => (Some(x), true),
        Side::Open(x) => (Some(x), false),
    };
    let (lo, lo_in) = side(r.range.lo);
    let (hi, hi_in) = side(r.range.hi);
    v.setattr("field", field.unwrap_or_else(|| r.field.clone()))?;
    v.setattr("allowed", r.range.describe(&r.field))?;
    v.setattr("value", r.value)?;
    v.setattr("unit", r.range.unit)?;
    v.setattr("low", lo)?;
    v.setattr("high", hi)?;
    v.setattr("low_inclusive", lo_in)?;
    v.setattr("high_inclusive", hi_in)?;
    Ok(())
}

/// Extension: `result.map_err(raise)` as a method.
pub trait OrRaise<T> {
    /// The value, or the Python exception for the error.
    fn or_raise(self) -> PyResult<T>;
}

impl<T, E: Fault> OrRaise<T> for Result<T, E> {
    fn or_raise(self) -> PyResult<T> {
        self.map_err(raise)
    }
}

impl Fault for loomkin_units::SweepError {
    fn range(&self) -> Option<&RangeError> {
        match self {
            Self::Range(e) => Some(e),
            _ => None,
        }
    }
    fn accepted(&self) -> Option<String> {
        match self {
            Self::Parse { expected, .. } => Some((*expected).to_string()),
            _ => None,
        }
    }
}
