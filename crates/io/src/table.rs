//! A numeric table with named columns, written as CSV or JSON.

use crate::IoError;
use std::io::Write;

/// A rectangular table of finite numbers; column names carry their units (`velocity_m_s`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Table {
    columns: Vec<String>,
    rows: Vec<Vec<f64>>,
}

impl Table {
    /// An empty table with these columns.
    pub fn new<S: Into<String>>(columns: impl IntoIterator<Item = S>) -> Self {
        Self { columns: columns.into_iter().map(Into::into).collect(), rows: Vec::new() }
    }

    /// Appends a row; it must be as wide as the header and hold only finite numbers.
    pub fn push(&mut self, row: Vec<f64>) -> Result<(), IoError> {
        let r = self.rows.len();
        if row.len() != self.columns.len() {
            return Err(IoError::RowWidth { row: r, got: row.len(), want: self.columns.len() });
        }
        if let Some((c, &value)) = row.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(IoError::NotFinite { column: self.columns[c].clone(), row: r, value });
        }
        self.rows.push(row);
        Ok(())
    }

    /// Column names.
    pub fn columns(&self) -> &[String] {
        &self.columns
    }

    /// Rows.
    pub fn rows(&self) -> &[Vec<f64>] {
        &self.rows
    }

    /// Writes the table as CSV: a header line, then one line per row, numbers in the shortest
    /// form that reads back exactly.
    pub fn write_csv(&self, w: &mut dyn Write) -> Result<(), IoError> {
        let mut out = CsvRows::new(w, &self.columns)?;
        for row in &self.rows {
            out.push(row)?;
        }
        Ok(())
    }

    /// The rows as a JSON array of objects keyed by column name.
    pub fn to_json_rows(&self) -> serde_json::Value {
        let rows = self
            .rows
            .iter()
            .map(|row| {
                let obj: serde_json::Map<String, serde_json::Value> =
                    self.columns.iter().cloned().zip(row.iter().map(|v| serde_json::json!(v))).collect();
                serde_json::Value::Object(obj)
            })
            .collect();
        serde_json::Value::Array(rows)
    }
}

/// A CSV table written row by row as the rows are made, so a table of 10⁷ rows never sits in
/// memory: the same text as [`Table::write_csv`], the same checks as [`Table::push`].
pub struct CsvRows<W: Write> {
    w: W,
    columns: Vec<String>,
    row: usize,
    line: String,
}

impl<W: Write> CsvRows<W> {
    /// Writes the header line.
    pub fn new<S: AsRef<str>>(mut w: W, columns: &[S]) -> Result<Self, IoError> {
        let columns: Vec<String> = columns.iter().map(|c| c.as_ref().to_string()).collect();
        let mut line = String::new();
        crate::csv::push_line(&mut line, &columns);
        w.write_all(line.as_bytes())?;
        Ok(Self { w, columns, row: 0, line })
    }

    /// Continues a table whose header was written elsewhere (a later shard): no header line.
    pub fn continuing<S: AsRef<str>>(w: W, columns: &[S]) -> Result<Self, IoError> {
        let columns: Vec<String> = columns.iter().map(|c| c.as_ref().to_string()).collect();
        Ok(Self { w, columns, row: 0, line: String::new() })
    }

    /// Writes one row; it must be as wide as the header and hold only finite numbers.
    pub fn push(&mut self, row: &[f64]) -> Result<(), IoError> {
        if row.len() != self.columns.len() {
            return Err(IoError::RowWidth { row: self.row, got: row.len(), want: self.columns.len() });
        }
        if let Some((c, &value)) = row.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(IoError::NotFinite { column: self.columns[c].clone(), row: self.row, value });
        }
        self.line.clear();
        crate::csv::push_line(&mut self.line, row.iter().map(|v| crate::csv::shortest(*v)));
        self.w.write_all(self.line.as_bytes())?;
        self.row += 1;
        Ok(())
    }

    /// Rows written so far.
    pub fn rows(&self) -> usize {
        self.row
    }

    /// Flushes and hands back the writer.
    pub fn finish(mut self) -> Result<W, IoError> {
        self.w.flush()?;
        Ok(self.w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_nan_and_ragged_rows() {
        let mut t = Table::new(["a_m", "b_s"]);
        assert!(matches!(t.push(vec![1.0]), Err(IoError::RowWidth { .. })));
        let e = t.push(vec![1.0, f64::NAN]).unwrap_err().to_string();
        assert!(e.contains("b_s"), "{e}");
        t.push(vec![0.5, -0.0]).unwrap();
        let mut out = Vec::new();
        t.write_csv(&mut out).unwrap();
        assert_eq!(String::from_utf8(out).unwrap(), "a_m,b_s\n0.5,0\n");
        assert_eq!(t.to_json_rows()[0]["a_m"], 0.5);
    }

    #[test]
    fn streamed_rows_are_the_table_text() {
        let mut t = Table::new(["x", "y_m"]);
        let rows = [[0.0, -0.0], [0.1 + 0.2, 1e-300], [2.5, -7.0]];
        for r in rows {
            t.push(r.to_vec()).unwrap();
        }
        let mut whole = Vec::new();
        t.write_csv(&mut whole).unwrap();
        let mut out = CsvRows::new(Vec::new(), t.columns()).unwrap();
        for r in rows {
            out.push(&r).unwrap();
        }
        assert_eq!(out.rows(), 3);
        assert!(matches!(out.push(&[1.0, f64::INFINITY]), Err(IoError::NotFinite { row: 3, .. })));
        assert!(matches!(out.push(&[1.0]), Err(IoError::RowWidth { .. })));
        assert_eq!(out.finish().unwrap(), whole);
    }
}
