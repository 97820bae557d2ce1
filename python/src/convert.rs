//! Rust values into Python objects: anything `Serialize` into dicts, lists and numbers with the
//! keys the CLI's `--json` uses (both go through the same `Serialize` impls), and columns of numbers
//! into numpy arrays.

use loomkin_units::Shard;
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

/// A whole-number argument (a count of points, draws, cycles) as Python gave it, checked against
/// its field only in [`Count::check`]: any Python integer (negative, or past 64 bits) and anything
/// else are taken here, so a bad one raises the package's error naming the field and the allowed
/// range, not pyo3's `OverflowError` or `TypeError`.
pub struct Count(Result<i128, String>);

impl Count {
    /// The count `n` (a default).
    pub fn of(n: usize) -> Self {
        Self(Ok(n as i128))
    }

    /// The count, checked against `field`'s range (named by `field`'s name).
    pub fn check(&self, field: &loomkin_units::Field) -> PyResult<usize> {
        self.check_as(field, field.name)
    }

    /// The count, checked against `field`'s range under the name `name`.
    pub fn check_as(&self, field: &loomkin_units::Field, name: &str) -> PyResult<usize> {
        match &self.0 {
            Ok(n) => {
                // An integer beyond f64's exact range is still far outside every count's range.
                field.check_as(name, *n as f64).map_err(crate::errors::raise)?;
                usize::try_from(*n)
                    .map_err(|_| crate::errors::raise(loomkin_units::RangeError::new(name, *n as f64, field.range)))
            }
            Err(text) => Err(crate::errors::raise(loomkin_laws::LawError::Parse {
                field: name.into(),
                text: text.clone(),
                expected: format!("a whole number, {}", field.range.describe(name)),
            })),
        }
    }
}

impl<'a, 'py> FromPyObject<'a, 'py> for Count {
    type Error = PyErr;

    fn extract(obj: pyo3::Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        // Python's bool is an int: refused as a count.
        if obj.is_instance_of::<pyo3::types::PyBool>() || !obj.hasattr("__index__")? {
            let text = obj.repr().map(|r| r.to_string()).unwrap_or_else(|_| "?".into());
            return Ok(Self(Err(text.chars().take(80).collect())));
        }
        let n = match obj.extract::<i128>() {
            Ok(n) => n,
            // Past i128: only the sign matters for the range check.
            Err(_) => {
                if obj.lt(0)? {
                    i128::MIN
                } else {
                    i128::MAX
                }
            }
        };
        Ok(Self(Ok(n)))
    }
}

/// `shard=(I, N)` or `shard="I/N"`: shard I of N of the rows, as the CLI's `--shard I/N`, read and
/// checked by the library ([`Shard::parse`]); `None` is the whole run.
pub fn shard(arg: Option<&Bound<'_, PyAny>>) -> PyResult<Shard> {
    let Some(a) = arg.filter(|a| !a.is_none()) else { return Ok(Shard::WHOLE) };
    let text = if let Ok(s) = a.extract::<String>() {
        s
    } else if let Ok((i, n)) = a.extract::<(i128, i128)>() {
        format!("{i}/{n}")
    } else {
        a.repr().map(|r| r.to_string()).unwrap_or_else(|_| "?".into())
    };
    Shard::parse("shard", &text).map_err(crate::errors::raise)
}

/// Columns as the package's `loomkin.Table` (a dict of name to array, with `.frame()`): every
/// table-shaped result has this one type.
pub fn table<'py>(py: Python<'py>, columns: Bound<'py, PyDict>) -> PyResult<Bound<'py, PyAny>> {
    py.import("loomkin._table")?.getattr("Table")?.call1((columns,))
}

/// Columns computed at the points of an input of shape `shape` (in its logical order) as a
/// `loomkin.Table` of arrays of that shape, as numpy functions broadcast: a 0-d input (a number)
/// gives floats.
pub fn shaped_table<'py, K: AsRef<str>>(
    py: Python<'py>,
    cols: Vec<(K, Vec<f64>)>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyAny>> {
    let d = PyDict::new(py);
    for (k, v) in cols {
        if shape.is_empty() {
            d.set_item(k.as_ref(), v.first().copied().unwrap_or(f64::NAN))?;
        } else {
            d.set_item(k.as_ref(), PyArray1::from_vec(py, v).reshape(shape.to_vec())?)?;
        }
    }
    table(py, d)
}
