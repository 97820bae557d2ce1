//! Rust values into Python objects: anything `Serialize` into dicts, lists and numbers with the
//! keys the CLI's `--json` uses (both go through the same `Serialize` impls), and columns of numbers
//! into numpy arrays.

use numpy::{PyArray1, PyArrayMethods, PyReadwriteArray1};
use pyo3::IntoPyObjectExt;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde::Serialize;
use serde_json::Value;

/// A serialisable value as Python objects (dict, list, float, int, str, bool, None).
pub fn to_py<T: Serialize + ?Sized>(py: Python<'_>, v: &T) -> PyResult<Py<PyAny>> {
    let value = serde_json::to_value(v).map_err(|e| PyRuntimeError::new_err(format!("internal: {e}")))?;
    value_to_py(py, &value)
}

/// A JSON value as Python objects.
pub fn value_to_py(py: Python<'_>, v: &Value) -> PyResult<Py<PyAny>> {
    Ok(match v {
        Value::Null => py.None(),
        Value::Bool(b) => b.into_py_any(py)?,
        Value::Number(n) => {
            if let Some(i) = n.as_i64() {
                i.into_py_any(py)?
            } else if let Some(u) = n.as_u64() {
                u.into_py_any(py)?
            } else {
                n.as_f64().unwrap_or(f64::NAN).into_py_any(py)?
            }
        }
        Value::String(s) => s.into_py_any(py)?,
        Value::Array(a) => {
            let items: PyResult<Vec<Py<PyAny>>> = a.iter().map(|x| value_to_py(py, x)).collect();
            PyList::new(py, items?)?.into_any().unbind()
        }
        Value::Object(o) => {
            let d = PyDict::new(py);
            for (k, x) in o {
                d.set_item(k, value_to_py(py, x)?)?;
            }
            d.into_any().unbind()
        }
    })
}

/// Named columns of numbers as a dict of 1-D float64 numpy arrays, in the given order.
pub fn columns<'py, K: AsRef<str>>(py: Python<'py>, cols: Vec<(K, Vec<f64>)>) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (k, v) in cols {
        d.set_item(k.as_ref(), PyArray1::from_vec(py, v))?;
    }
    Ok(d)
}

/// `n` rows of named float64 columns written straight into new numpy arrays: the arrays are
/// allocated (zeroed) with the GIL held, then `fill` writes every column's buffer with the GIL
/// released. No intermediate copy of the data is made, whatever `n`.
pub fn fill_columns<'py, K: AsRef<str>>(
    py: Python<'py>,
    names: &[K],
    n: usize,
    fill: impl FnOnce(&mut [&mut [f64]]) + Send,
) -> PyResult<Bound<'py, PyDict>> {
    let arrays: Vec<Bound<'py, PyArray1<f64>>> = names.iter().map(|_| PyArray1::zeros(py, n, false)).collect();
    {
        // Exclusive borrows of the new arrays (numpy's borrow checker: nothing else holds them).
        let mut guards: Vec<PyReadwriteArray1<'py, f64>> = arrays.iter().map(|a| a.readwrite()).collect();
        let mut slices: Vec<&mut [f64]> = guards
            .iter_mut()
            .map(|g| g.as_slice_mut())
            .collect::<Result<_, _>>()
            .map_err(|e| PyRuntimeError::new_err(format!("internal: {e}")))?;
        py.detach(|| fill(&mut slices));
    }
    let d = PyDict::new(py);
    for (k, a) in names.iter().zip(arrays) {
        d.set_item(k.as_ref(), a)?;
    }
    Ok(d)
}

/// `points` evenly spaced samples of a law from x = 0 to 1 as arrays x, s, v, a, j, written
/// straight into the arrays a block at a time ([`loomkin_laws::Law::sample_columns`], bit-identical
/// to `loomkin law sample`) with the GIL released.
pub fn law_samples<'py>(py: Python<'py>, law: &loomkin_laws::Law, points: usize) -> PyResult<Bound<'py, PyDict>> {
    fill_columns(py, &["x", "s", "v", "a", "j"], points, |c| {
        let [x, s, v, a, j] = c else { return };
        law.sample_columns([x, s, v, a, j]);
    })
}

/// A list of records (serialised structs of numbers) as a dict of numpy arrays, one per key; a key
/// whose values are not all numbers stays a list. An empty list gives an empty dict.
pub fn records_to_columns<T: Serialize>(py: Python<'_>, rows: &[T]) -> PyResult<Py<PyAny>> {
    let value = serde_json::to_value(rows).map_err(|e| PyRuntimeError::new_err(format!("internal: {e}")))?;
    value_records_to_columns(py, &value)
}

/// A JSON array of objects as a dict of numpy arrays (see [`records_to_columns`]).
pub fn value_records_to_columns(py: Python<'_>, value: &Value) -> PyResult<Py<PyAny>> {
    let d = PyDict::new(py);
    let Some(rows) = value.as_array() else { return value_to_py(py, value) };
    // Every key of every row, in order of first appearance (a key some rows lack, e.g. a note,
    // is None in those rows).
    let mut keys: Vec<&String> = Vec::new();
    for r in rows.iter().filter_map(Value::as_object) {
        for k in r.keys() {
            if !keys.contains(&k) {
                keys.push(k);
            }
        }
    }
    for key in keys {
        let cells: Vec<&Value> = rows.iter().map(|r| r.get(key).unwrap_or(&Value::Null)).collect();
        if cells.iter().all(|c| c.is_number()) {
            let v: Vec<f64> = cells.iter().map(|c| c.as_f64().unwrap_or(f64::NAN)).collect();
            d.set_item(key, PyArray1::from_vec(py, v))?;
        } else {
            let items: PyResult<Vec<Py<PyAny>>> = cells.iter().map(|c| value_to_py(py, c)).collect();
            d.set_item(key, PyList::new(py, items?)?)?;
        }
    }
    Ok(d.into_any().unbind())
}

/// Keyword parameters (`ramp=0.1`, `segments="…"`) as the `KEY=VALUE` text pairs the libraries
/// parse (the CLI's `--param KEY=VALUE`): strings as they are, numbers in Rust's shortest
/// round-trip form, so a float reaches the library bit for bit.
pub fn params(kw: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(String, String)>> {
    let mut out = Vec::new();
    if let Some(kw) = kw {
        for (k, v) in kw.iter() {
            let key: String = k.extract()?;
            let text = if let Ok(s) = v.extract::<String>() {
                s
            } else if let Ok(i) = v.extract::<i64>() {
                i.to_string()
            } else if let Ok(x) = v.extract::<f64>() {
                x.to_string()
            } else {
                return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                    "parameter '{key}': expected a number or a string"
                )));
            };
            out.push((key, text));
        }
    }
    Ok(out)
}
