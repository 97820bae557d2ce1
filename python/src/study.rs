//! Monte-Carlo studies (`loomkin pick montecarlo`, `loomkin dobby tolerance`): the study file's
//! draws run a piece at a time (Ctrl-C stops between pieces), the report as the CLI's `--json`
//! and the per-draw table as its `--csv`; one shard of the draws (`--shard I/N --csv`), and the
//! report of a finished run from its per-draw tables or files (`--from-draws`).

use crate::convert::{columns, table, to_py};
use crate::errors::LoomkinError;
use loomkin_study::DrawRow;
use loomkin_study::draws::DrawSource;
use loomkin_study::parts::PartError;
use loomkin_study::summary::DrawSummary;
use loomkin_units::Shard;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde::Serialize;
use std::path::PathBuf;

/// Draws per piece between two checks for Ctrl-C (each piece runs in parallel).
const PIECE: u64 = 256;

/// What a Monte-Carlo call asks for.
pub enum Ask {
    /// The report of the whole run, with the per-draw table under `per_draw`.
    Report,
    /// Shard I of N of the draws: the per-draw table of `--shard I/N --csv`.
    Shard(Shard),
    /// The report of a finished run from its per-draw tables, in shard order.
    Tables(Vec<Vec<(String, Vec<f64>)>>),
    /// The report of a finished run from its files (`--from-draws`: parts, a directory, CSV).
    Files(Vec<PathBuf>),
    /// Shard I of N's mergeable summary (`--shard I/N --summary`).
    Summary(Shard),
    /// The report of a finished run from its shards' summaries (`--from-summaries`).
    Summaries(Vec<DrawSummary>),
}

impl Ask {
    /// The call's `shard` and `from_draws` (at most one of them): `from_draws` a list of tables
    /// (dicts of columns, as `per_draw` or a shard's table) or of paths.
    pub fn of(shard: Option<&Bound<'_, PyAny>>, from_draws: Option<&Bound<'_, PyAny>>) -> PyResult<Self> {
        let shard = shard.filter(|s| !s.is_none());
        let from = from_draws.filter(|f| !f.is_none());
        match (shard, from) {
            (Some(_), Some(_)) => {
                Err(error("from_draws", "give shard or from_draws, not both: from_draws reports a finished run"))
            }
            (Some(s), None) => Ok(Self::Shard(crate::convert::shard(Some(s))?)),
            (None, None) => Ok(Self::Report),
            (None, Some(f)) => {
                let items: Vec<Bound<'_, PyAny>> =
                    if f.is_instance_of::<PyList>() || f.is_instance_of::<pyo3::types::PyTuple>() {
                        f.try_iter()?.collect::<PyResult<_>>()?
                    } else {
                        vec![f.clone()]
                    };
                if items.is_empty() {
                    return Err(error("from_draws", "no per-draw tables given"));
                }
                let os = f.py().import("os")?;
                let is_path = |x: &Bound<'_, PyAny>| -> PyResult<bool> {
                    Ok(x.is_instance_of::<pyo3::types::PyString>() || x.is_instance(&os.getattr("PathLike")?)?)
                };
                if is_path(&items[0])? {
                    let paths = items
                        .iter()
                        .map(|x| {
                            if is_path(x)? {
                                Ok(PathBuf::from(os.call_method1("fspath", (x,))?.extract::<String>()?))
                            } else {
                                Err(error("from_draws", "give a list of paths or a list of tables, not both"))
                            }
                        })
                        .collect::<PyResult<_>>()?;
                    return Ok(Self::Files(paths));
                }
                let tables = items
                    .iter()
                    .enumerate()
                    .map(|(t, x)| {
                        let d = x.cast::<PyDict>().map_err(|_| {
                            error("from_draws", &format!("item {}: not a table (a dict of columns) or a path", t + 1))
                        })?;
                        d.iter()
                            .map(|(k, v)| {
                                let col = match v.extract::<numpy::PyReadonlyArray1<'_, f64>>() {
                                    Ok(a) => a.as_array().to_vec(),
                                    Err(_) => v.extract::<Vec<f64>>()?,
                                };
                                Ok((k.extract::<String>()?, col))
                            })
                            .collect::<PyResult<Vec<_>>>()
                    })
                    .collect::<PyResult<_>>()?;
                Ok(Self::Tables(tables))
            }
        }
    }
}

impl Ask {
    /// [`Ask::of`], or with `summary` the shard's summary, or with `from_summaries` (texts of
    /// summaries, JSON) the report of them.
    pub fn with_summaries(
        shard: Option<&Bound<'_, PyAny>>,
        from_draws: Option<&Bound<'_, PyAny>>,
        summary: bool,
        from_summaries: Option<Vec<String>>,
    ) -> PyResult<Self> {
        let given = |x: Option<&Bound<'_, PyAny>>| x.is_some_and(|x| !x.is_none());
        match (summary, from_summaries) {
            (false, None) => Self::of(shard, from_draws),
            (true, Some(_)) => Err(error("from_summaries", "give summary or from_summaries, not both")),
            (true, None) if given(from_draws) => {
                Err(error("summary", "give summary or from_draws, not both: from_draws reports a finished run"))
            }
            (true, None) => Ok(Self::Summary(crate::convert::shard(shard)?)),
            (false, Some(_)) if given(shard) || given(from_draws) => Err(error(
                "from_summaries",
                "from_summaries reports a finished run: give neither shard nor from_draws with it",
            )),
            (false, Some(texts)) => {
                let mut all = Vec::new();
                for (k, t) in texts.iter().enumerate() {
                    all.extend(
                        loomkin_study::summary::parse_summaries(&format!("summary {}", k + 1), t)
                            .map_err(|e| part_error_of("from_summaries", e))?,
                    );
                }
                Ok(Self::Summaries(all))
            }
        }
    }
}

/// A `LoomkinError` naming `field`.
pub fn error(field: &str, msg: &str) -> PyErr {
    Python::attach(|py| {
        let err = LoomkinError::new_err(msg.to_string());
        let v = err.value(py);
        let _ = v.setattr("field", field);
        let _ = v.setattr("allowed", py.None());
        err
    })
}

/// A reduce's error: the input's fault as a `LoomkinError` naming `from_draws`, a file that
/// cannot be read as `OSError`.
pub fn part_error(e: PartError) -> PyErr {
    part_error_of("from_draws", e)
}

/// [`part_error`] naming `field`.
fn part_error_of(field: &str, e: PartError) -> PyErr {
    match e {
        PartError::Io { .. } => pyo3::exceptions::PyOSError::new_err(e.to_string()),
        _ => error(field, &e.to_string()),
    }
}

/// A study's per-draw table as a `loomkin.Table` (the columns of `--csv`).
fn per_draw<'py, D: DrawRow>(py: Python<'py>, all: &[D]) -> PyResult<Bound<'py, PyAny>> {
    let names = D::columns();
    let rows: Vec<Vec<f64>> = all.iter().map(DrawRow::row).collect();
    let cols: Vec<(String, Vec<f64>)> =
        names.into_iter().enumerate().map(|(i, n)| (n, rows.iter().map(|r| r[i]).collect())).collect();
    table(py, columns(py, cols)?)
}

/// The callbacks of one kind of study.
pub struct Study<'a, D, R> {
    /// The study's command (`pick montecarlo`), named in messages.
    pub command: &'a str,
    /// The number of draws of the study.
    pub draws: u64,
    /// Runs the draws of a range of indices (each draw depends on its index only, so the pieces
    /// give the draws of one run).
    pub run: &'a (dyn Fn(std::ops::Range<u64>) -> Vec<D> + Sync),
    /// The report of every draw, in order.
    pub report: &'a dyn Fn(&[D]) -> R,
    /// The report of a finished run's files, streamed (facts checked).
    pub report_from: &'a (dyn Fn(&DrawSource) -> Result<R, PartError> + Sync),
    /// The mergeable summary of the draws of a range.
    pub summary: &'a dyn Fn(std::ops::Range<u64>, &[D]) -> DrawSummary,
    /// The report of the shards' summaries (checked and merged).
    pub report_from_summaries: &'a dyn Fn(&[DrawSummary]) -> Result<R, PartError>,
}

/// Answers `ask` for a study: the report with `per_draw` (the whole run), the per-draw table of a
/// shard, or the report of a finished run's tables or files.
pub fn answer<'py, D: DrawRow + Send, R: Serialize + Send>(
    py: Python<'py>,
    study: Study<'_, D, R>,
    ask: Ask,
) -> PyResult<Bound<'py, PyAny>> {
    let report = |r: &R| -> PyResult<Bound<'py, PyAny>> { Ok(to_py(py, r)?.into_bound(py)) };
    match ask {
        Ask::Report => {
            let all = crate::interrupt::chunks(py, 0..study.draws, PIECE, study.run)?;
            let out = report(&(study.report)(&all))?;
            out.set_item("per_draw", per_draw(py, &all)?)?;
            Ok(out)
        }
        Ask::Shard(shard) => {
            let items = shard.items(study.draws as usize);
            let all = crate::interrupt::chunks(py, items.start as u64..items.end as u64, PIECE, study.run)?;
            per_draw(py, &all)
        }
        Ask::Tables(tables) => {
            let draws =
                loomkin_study::draws::draws_of_tables::<D>(study.command, &tables, study.draws).map_err(part_error)?;
            report(&(study.report)(&draws))
        }
        Ask::Summary(shard) => {
            let items = shard.items(study.draws as usize);
            let items = items.start as u64..items.end as u64;
            let all = crate::interrupt::chunks(py, items.clone(), PIECE, study.run)?;
            Ok(to_py(py, &(study.summary)(items, &all))?.into_bound(py))
        }
        Ask::Summaries(parts) => {
            report(&(study.report_from_summaries)(&parts).map_err(|e| part_error_of("from_summaries", e))?)
        }
        Ask::Files(paths) => {
            let source = DrawSource::open(&paths).map_err(part_error)?;
            let r = py.detach(|| (study.report_from)(&source)).map_err(part_error)?;
            report(&r)
        }
    }
}
