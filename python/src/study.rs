//! Monte-Carlo studies (`loomkin pick montecarlo`, `loomkin dobby tolerance`): the study file's
//! draws run a piece at a time (Ctrl-C stops between pieces), the report as the CLI's `--json`
//! and the per-draw table as its `--csv`.

use crate::convert::{columns, to_py};
use loomkin_study::DrawRow;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde::Serialize;

/// Draws per piece between two checks for Ctrl-C (each piece runs in parallel).
const PIECE: u64 = 256;

/// Runs the `draws` of a study (`run` on a range of draw indices; each draw depends on its index
/// only, so the pieces give the draws of one run), then its report (`report` of every draw) with
/// the draws as a dict of arrays under `per_draw` (the columns of `--csv`).
pub fn run_study<'py, D: DrawRow + Send, R: Serialize>(
    py: Python<'py>,
    draws: u64,
    run: impl Fn(std::ops::Range<u64>) -> Vec<D> + Sync,
    report: impl FnOnce(&[D]) -> R,
) -> PyResult<Bound<'py, PyDict>> {
    let all = crate::interrupt::chunks(py, draws, PIECE, run)?;
    let out = to_py(py, &report(&all))?.into_bound(py).cast_into::<PyDict>()?;
    let names = D::columns();
    let rows: Vec<Vec<f64>> = all.iter().map(DrawRow::row).collect();
    let cols: Vec<(String, Vec<f64>)> =
        names.into_iter().enumerate().map(|(i, n)| (n, rows.iter().map(|r| r[i]).collect())).collect();
    out.set_item("per_draw", columns(py, cols)?)?;
    Ok(out)
}
