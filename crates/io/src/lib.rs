//! # loomkin-io — tables, files and drawings
//!
//! Shared output plumbing of the loomkin tools: numeric [`Table`]s written as CSV or JSON (headers
//! carry units, non-finite numbers are refused rather than printed), [`open_output`] where `-`
//! means standard output, every CSV file's framing ([`csv`]), and drawings written as DXF
//! ([`drawing`], [`dxf`]). Plots live in `loomkin-plot`, which reports its errors as [`IoError`].
//!
//! ```
//! use loomkin_io::Table;
//!
//! let mut t = Table::new(["x", "s"]);
//! t.push(vec![0.0, 0.0])?;
//! t.push(vec![1.0, 1.0])?;
//! let mut csv = Vec::new();
//! t.write_csv(&mut csv)?;
//! assert_eq!(String::from_utf8(csv).unwrap(), "x,s\n0,0\n1,1\n");
//! # Ok::<(), loomkin_io::IoError>(())
//! ```
#![deny(missing_docs)]

pub mod csv;
pub mod drawing;
pub mod dxf;
mod error;
mod output;
mod table;

pub use error::IoError;
pub use output::{create_file, open_output};
pub use table::{CsvRows, Table};
