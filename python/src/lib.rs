//! # loomkin for Python — the extension module `loomkin._loomkin`
//!
//! This crate only converts: Python arguments into the libraries' types, the libraries' results
//! into Python objects (dicts keyed as the CLI's `--json`, numpy arrays for sampled curves), and
//! library errors into Python exceptions carrying the field and the allowed range. Every number is
//! computed by the loomkin crates; long computations run with the GIL released
//! ([`Python::detach`]), so other Python threads go on meanwhile.
//!
//! The Python package around it (`python/loomkin/`) arranges the functions in modules, adds type
//! stubs and turns tables into pandas DataFrames when pandas is installed.

mod cams;
mod convert;
mod cycles;
mod dobby;
mod drive;
mod dynamics;
mod errors;
mod fields;
mod insertion;
mod interrupt;
mod laws;
mod loom;
mod picking;
mod servo;
mod shed;
mod study;

use pyo3::prelude::*;

/// The extension module.
#[pymodule]
fn _loomkin(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    errors::register(m)?;
    fields::register(m)?;
    laws::register(m)?;
    servo::register(m)?;
    cycles::register(m)?;
    picking::register(m)?;
    dobby::register(m)?;
    shed::register(m)?;
    loom::register(m)?;
    drive::register(m)?;
    dynamics::register(m)?;
    cams::register(m)?;
    insertion::register(m)?;
    Ok(())
}
