//! The one way a TOML file's syntax or type error becomes part of a one-line message.

/// `line L, column C: message` of a TOML error: the parser's message on one line (its own line
/// breaks and runs of spaces collapsed), placed by the line and column (in characters) where its
/// span starts, without quoting the source. Every loomkin file reader (cycles, loom files, study
/// files, axis and drive files, mechanisms) words its parse errors through this, so a user reads
/// the same form whatever the file.
///
/// ```
/// let text = "a = 1\nb = \"x\nc = 2\n";
/// let e = text.parse::<toml::Table>().unwrap_err();
/// let line = loomkin_units::toml_reason(text, &e);
/// assert!(line.starts_with("line 2, column "), "{line}");
/// assert!(!line.contains('\n'));
/// ```
pub fn toml_reason(text: &str, e: &toml::de::Error) -> String {
    let mut message = e.message().split_whitespace().collect::<Vec<_>>().join(" ");
    match e.span() {
        Some(span) => {
            // The parser says `duplicate key` alone: the key is the text its span covers.
            if message == "duplicate key"
                && let Some(key) = text.get(span.clone()).and_then(|k| k.lines().next()).map(str::trim)
                && !key.is_empty()
            {
                let key: String = key.chars().take(MAX_KEY_CHARS).collect();
                message = format!("duplicate key `{key}` (given a second time here)");
            }
            let before = text.get(..span.start.min(text.len())).unwrap_or(text);
            let line = before.matches('\n').count() + 1;
            let column = before.rsplit('\n').next().unwrap_or("").chars().count() + 1;
            format!("line {line}, column {column}: {message}")
        }
        None => message,
    }
}

/// Longest key quoted in a message (characters): a key of a megabyte is cut.
const MAX_KEY_CHARS: usize = 80;

#[cfg(test)]
mod tests {
    use super::toml_reason;

    #[test]
    fn a_duplicate_key_is_named_where_it_is_given_again() {
        for (text, line) in [
            ("draws = 4\nseed = 1\nseed = 3\n", "line 3, column 1: duplicate key `seed`"),
            ("[limits]\na = 1\n\n[limits]\nb = 2\n", "line 4, column 2: duplicate key `limits`"),
            ("x = { a = 1, a = 2 }\n", "line 1, column 14: duplicate key `a`"),
        ] {
            let e = text.parse::<toml::Table>().unwrap_err();
            let got = toml_reason(text, &e);
            assert!(got.starts_with(line), "{text:?}: {got}");
        }
    }

    #[test]
    fn places_the_error_by_line_and_character_column() {
        // A type error in the third line, after a two-byte character: the column counts characters.
        let text = "# é\nname = \"x\"\nspeed = \"fast\"\n";
        #[derive(serde::Deserialize)]
        #[allow(dead_code)]
        struct F {
            name: String,
            speed: f64,
        }
        let e = toml::from_str::<F>(text).err().expect("a type error");
        let line = toml_reason(text, &e);
        assert!(line.starts_with("line 3, column 9: "), "{line}");
        assert!(!line.contains('\n'), "{line}");
    }

    #[test]
    fn an_error_without_a_place_is_its_message() {
        let e = <toml::de::Error as serde::de::Error>::custom("missing field `x`\n  and more");
        assert_eq!(toml_reason("", &e), "missing field `x` and more");
    }
}
