//! CSV text, written one way: `#` comment lines, one header line, then one line of fields per
//! row, joined by commas. Every CSV file loomkin writes goes through here — tables of samples
//! ([`crate::Table`], [`crate::CsvRows`]), the servo cam tables, the cam tables for a controller
//! and the shedding study tables — so the framing, the header and the row width are checked in
//! one place. The number format belongs to the file (a contract of each format) and is chosen
//! with [`shortest`], [`exponent`] or the caller's own (fixed decimals of a cam table).
//!
//! ```
//! use loomkin_io::csv::{CsvText, exponent};
//!
//! let mut t = CsvText::new(&["servo cam"], &["master_deg", "slave_m"]);
//! t.push([exponent(0.0), exponent(0.0015)]);
//! assert_eq!(t.finish(), "# servo cam\nmaster_deg,slave_m\n0e0,1.5e-3\n");
//! ```

/// Shortest text that reads back to the same number, `-0` written as `0`: plain decimals from
/// 10⁻⁷ to 10²¹, the exponent form outside (as JavaScript's `Number.prototype.toString` switches),
/// so a value of 10⁻²⁵ is not 0.000…0001692 with 24 zeros, nor 10³⁰⁰ 301 digits.
pub fn shortest(v: f64) -> String {
    if v == 0.0 {
        "0".to_string()
    } else if (1e-7..1e21).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// Exponent form with the shortest mantissa that reads back to the same number (`1.5e-3`, `0e0`).
pub fn exponent(v: f64) -> String {
    format!("{v:e}")
}

/// Appends one CSV line (fields joined by commas, then a newline) to `line`.
pub fn push_line<I>(line: &mut String, fields: I)
where
    I: IntoIterator,
    I::Item: AsRef<str>,
{
    for (i, f) in fields.into_iter().enumerate() {
        if i > 0 {
            line.push(',');
        }
        line.push_str(f.as_ref());
    }
    line.push('\n');
}

/// A CSV file built in memory: comment lines, the header, the rows.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CsvText {
    text: String,
    width: usize,
}

impl CsvText {
    /// Starts a file with `comments` (each written as `# line`) and the header `columns`.
    pub fn new<S: AsRef<str>>(comments: &[S], columns: &[S]) -> Self {
        let mut text = String::new();
        for c in comments {
            text.push_str("# ");
            text.push_str(c.as_ref());
            text.push('\n');
        }
        push_line(&mut text, columns);
        Self { text, width: columns.len() }
    }

    /// Continues a file whose header was written elsewhere (a later shard): rows of `width` fields.
    pub fn continuing(width: usize) -> Self {
        Self { text: String::new(), width }
    }

    /// Appends a row. Its width is the header's (a different width is a bug of the writer, caught
    /// in debug builds).
    pub fn push<I>(&mut self, fields: I)
    where
        I: IntoIterator,
        I::Item: AsRef<str>,
    {
        let start = self.text.len();
        push_line(&mut self.text, fields);
        debug_assert_eq!(self.text[start..].matches(',').count() + 1, self.width, "CSV row width");
    }

    /// The text.
    pub fn finish(self) -> String {
        self.text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_back_exactly() {
        for v in [0.1 + 0.2, -7.25e-300, 1e300, 123456.789, -0.0, 5e-324] {
            assert_eq!(shortest(v).parse::<f64>().unwrap(), v);
            assert_eq!(exponent(v).parse::<f64>().unwrap(), v);
        }
        assert_eq!(shortest(-0.0), "0");
        assert_eq!(exponent(-0.0), "-0e0");
        assert_eq!(exponent(1500.0), "1.5e3");
        // Decimals inside [1e-7, 1e21), the exponent form outside, never longer than 27 characters
        // (a sign, `0.`, six zeros and 17 digits).
        assert_eq!(shortest(1.6924487330661563e-25), "1.6924487330661563e-25");
        assert_eq!(shortest(1e-7), "0.0000001");
        assert_eq!(shortest(9e-8), "9e-8");
        assert_eq!(shortest(-123456.789), "-123456.789");
        assert_eq!(shortest(1e21), "1e21");
        let mut v = 1e-320;
        while v < 1e300 {
            for x in [v, -v, v * std::f64::consts::PI] {
                assert!(shortest(x).len() <= 27, "{x}: {}", shortest(x));
                assert_eq!(shortest(x).parse::<f64>().unwrap(), x);
            }
            v *= 7.3;
        }
    }

    #[test]
    fn comments_header_rows() {
        let mut t = CsvText::new(&["a", "b c"], &["x_m", "y_s"]);
        t.push(["1", "2"]);
        t.push(vec![shortest(0.5), shortest(-0.0)]);
        assert_eq!(t.finish(), "# a\n# b c\nx_m,y_s\n1,2\n0.5,0\n");
        let mut c = CsvText::continuing(2);
        c.push(["3", "4"]);
        assert_eq!(c.finish(), "3,4\n");
    }
}
