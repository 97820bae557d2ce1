//! Errors of the output plumbing.

use thiserror::Error;

/// What can go wrong while writing tables, files or plots.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum IoError {
    /// A file could not be created or written.
    #[error("cannot write {path}: {cause}")]
    File {
        /// The path.
        path: String,
        /// The cause (printed in the message, not chained, so it is said once).
        cause: std::io::Error,
    },
    /// Writing to a stream failed.
    #[error("write failed: {0}")]
    Write(#[from] std::io::Error),
    /// A row of the wrong width.
    #[error("table row {row} has {got} values, the header has {want} columns")]
    RowWidth {
        /// Row index.
        row: usize,
        /// Values given.
        got: usize,
        /// Columns in the header.
        want: usize,
    },
    /// A value that is not a finite number.
    #[error("column '{column}' row {row} is not a finite number ({value}); refusing to print it")]
    NotFinite {
        /// Column name.
        column: String,
        /// Row index.
        row: usize,
        /// The value.
        value: f64,
    },
    /// A plot file whose extension is neither `.svg` nor `.png`.
    #[error("plot file '{path}': the extension must be .svg or .png")]
    PlotFormat {
        /// The path.
        path: String,
    },
    /// A figure that cannot be drawn, or a page setting that is not allowed.
    #[error("plot: {0}")]
    Plot(String),
    /// A page setting (width, height, DPI) out of its range.
    #[error(transparent)]
    Range(#[from] loomkin_units::RangeError),
    /// A page size (width or height) too small for the figure: the range from the least size that
    /// lays out, and what does not fit at the size given (`the legend of panel 1 runs off the
    /// canvas`).
    #[error("{range} (at {} px, {reason})", loomkin_units::compact(range.value))]
    TooSmall {
        /// The size given and the sizes that lay out.
        range: loomkin_units::RangeError,
        /// What does not fit at the size given.
        reason: String,
    },
}

impl loomkin_units::FieldError for IoError {
    fn field(&self) -> Option<&str> {
        match self {
            IoError::Range(e) | IoError::TooSmall { range: e, .. } => Some(&e.field),
            IoError::NotFinite { column, .. } => Some(column),
            _ => None,
        }
    }
}
