//! Where output goes: a file, or standard output for `-`.

use crate::IoError;
use std::io::{BufWriter, Write};
use std::path::Path;

/// Opens `path` for writing, buffered; `-` is standard output.
pub fn open_output(path: &str) -> Result<Box<dyn Write>, IoError> {
    if path == "-" {
        return Ok(Box::new(BufWriter::new(std::io::stdout().lock())));
    }
    Ok(Box::new(create_file(Path::new(path))?))
}

/// Creates a file, naming the path in the error.
pub fn create_file(path: &Path) -> Result<BufWriter<std::fs::File>, IoError> {
    std::fs::File::create(path)
        .map(BufWriter::new)
        .map_err(|cause| IoError::File { path: path.display().to_string(), cause })
}
