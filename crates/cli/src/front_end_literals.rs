//! No range or default literal in the front ends: every bound, default and unit of an input lives on
//! the library type that owns it (`loomkin_units::Field`, docs/design/fields.md). This test reads the
//! front ends' sources — crates/cli/src, python/src, python/loomkin — and fails on a range built
//! there (`Range::`), a clap default given as a number (`default_value_t = 0.5`,
//! `default_value = "600"`), or a numeric default in a Python signature (`points=721` in a
//! `#[pyo3(signature …)]` or a text signature, `step_deg: float = 1.0` in a `.py` or `.pyi`).

use std::path::{Path, PathBuf};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn files(dir: &Path, ext: &[&str], out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else { return };
    for e in rd.flatten() {
        let p = e.path();
        if p.is_dir() {
            files(&p, ext, out);
        } else if p.extension().and_then(|x| x.to_str()).is_some_and(|x| ext.contains(&x)) {
            out.push(p);
        }
    }
}

/// Whether a number starts after `at` in `s` (blanks, `(`, `[`, `"` and a sign skipped).
fn number_at(s: &str, at: usize) -> bool {
    s[at..].trim_start_matches([' ', '(', '[', '"', '-', '+']).starts_with(|c: char| c.is_ascii_digit())
}

/// Every place in `line` where `key` is followed by `=` and a number.
fn numeric_default(line: &str, key: &str) -> bool {
    let mut from = 0;
    while let Some(i) = line[from..].find(key) {
        let after = from + i + key.len();
        let rest = line[after..].trim_start();
        if let Some(r) = rest.strip_prefix('=')
            && !r.starts_with('=')
            && number_at(r, 0)
        {
            return true;
        }
        from = after;
    }
    false
}

/// `name=<number>` anywhere in a Python signature's text (`a=0.5`, `b = (600,)`).
fn keyword_number(text: &str) -> bool {
    let b = text.as_bytes();
    (0..b.len()).any(|i| {
        b[i] == b'='
            && i > 0
            && !matches!(b[i - 1], b'=' | b'!' | b'<' | b'>')
            && b.get(i + 1) != Some(&b'=')
            && (b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_' || b[i - 1] == b' ')
            && number_at(text, i + 1)
    })
}

/// A unit conversion written as a number (`x * 1e3`, `t / 1000.0`, `rpm / 60.0`): the factor lives
/// once in `loomkin_units` (`mm_from_m`, `ms_from_s`, `MM_PER_M`, `rad_per_s_from_rpm`, …).
fn conversion_literal(line: &str) -> bool {
    const FACTORS: [&str; 7] = ["1e3", "1e-3", "1000.0", "1_000.0", "0.001", "60.0", "1e6"];
    let b = line.as_bytes();
    (0..b.len()).filter(|&i| matches!(b[i], b'*' | b'/')).any(|i| {
        let rest = line[i + 1..].trim_start();
        FACTORS.iter().any(|f| {
            rest.strip_prefix(f)
                .is_some_and(|after| !after.starts_with(|c: char| c.is_ascii_alphanumeric() || c == '.'))
        })
    })
}

/// The offending lines of one front-end source, `path:line: text`.
fn offences(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    let ext = path.extension().and_then(|x| x.to_str()).unwrap_or("");
    let mut out = Vec::new();
    let mut in_signature = false;
    let mut in_text_signature = false;
    let mut in_def = false;
    for (n, line) in text.lines().enumerate() {
        let t = line.trim_start();
        let mut bad = false;
        match ext {
            "rs" => {
                // A unit's tests may check against numbers; the front end's code may not.
                if t.starts_with("#[cfg(test)]") {
                    break;
                }
                if t.starts_with("//") && !t.starts_with("///") {
                    continue;
                }
                if !t.starts_with("///") {
                    bad |= line.contains("Range::");
                    bad |= conversion_literal(line);
                    bad |= numeric_default(line, "default_value_t");
                    bad |= numeric_default(line, "default_value");
                    bad |= numeric_default(line, "default_values_t");
                }
                if t.starts_with("#[pyo3(signature") {
                    in_signature = true;
                }
                if in_signature {
                    bad |= keyword_number(t);
                    if t.contains(")]") {
                        in_signature = false;
                    }
                }
                // A text signature: the doc lines before `/// --` of a #[pyfunction] or method.
                if let Some(doc) = t.strip_prefix("///") {
                    let doc = doc.trim();
                    if doc.contains('(')
                        && doc.split('(').next().is_some_and(|w| {
                            !w.is_empty() && w.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '.')
                        })
                    {
                        in_text_signature = true;
                    }
                    if doc == "--" {
                        in_text_signature = false;
                    }
                    if in_text_signature {
                        bad |= keyword_number(doc);
                    }
                } else {
                    in_text_signature = false;
                }
            }
            _ => {
                if t.starts_with("def ") {
                    in_def = true;
                }
                if in_def {
                    // `name: type = 1.0` or `name=1.0` inside the signature (up to its `:` line end).
                    bad |= keyword_number(t);
                    if t.ends_with(':') || t.contains(") ->") || t.ends_with("...") {
                        in_def = false;
                    }
                }
            }
        }
        if bad {
            out.push(format!("{}:{}: {}", path.display(), n + 1, line.trim()));
        }
    }
    out
}

#[test]
fn no_range_or_default_literal_in_the_front_ends() {
    let root = repo();
    let mut paths = Vec::new();
    files(&root.join("crates/cli/src"), &["rs"], &mut paths);
    files(&root.join("crates/web/src"), &["rs"], &mut paths);
    files(&root.join("python/src"), &["rs"], &mut paths);
    files(&root.join("python/loomkin"), &["py", "pyi"], &mut paths);
    assert!(paths.len() > 30, "only {} front-end sources found", paths.len());
    // This file's own examples of what the scanner finds are not front-end code.
    paths.retain(|p| !p.ends_with("front_end_literals.rs"));
    let found: Vec<String> = paths.iter().flat_map(|p| offences(p)).collect();
    assert!(
        found.is_empty(),
        "range, default or unit-conversion literals in the front ends: put the bound or default on the library \
         type that owns the quantity (a loomkin_units::Field) and read it from there, convert units with \
         loomkin_units' functions:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_scanner_finds_what_it_should() {
    assert!(numeric_default("#[arg(long, default_value_t = 0.5)]", "default_value_t"));
    assert!(numeric_default(r#"#[arg(long, default_value = "600,750")]"#, "default_value"));
    assert!(!numeric_default("#[arg(long, default_value_t = Drive::STEP_DEG.default_value())]", "default_value_t"));
    assert!(!numeric_default(r#"#[arg(long, default_value = "peak")]"#, "default_value"));
    assert!(keyword_number("#[pyo3(signature = (points=721, **kw))]"));
    assert!(keyword_number("speed_rpm: Union[float, Sequence[float]] = (600.0,), objective: str = \"peak\","));
    assert!(keyword_number("def history(points: int = 201, mechanism=None):"));
    assert!(!keyword_number("def history(points: int = _default(\"History::POINTS\")):"));
    assert!(!keyword_number("if a == 0: pass"));
    assert!(conversion_literal("t_ms: s.iter().map(|p| finite(p.t_s * 1e3)).collect(),"));
    assert!(conversion_literal("let w = rpm / 60.0 * tau;"));
    assert!(conversion_literal("band_mm = marks.band_m *1000.0;"));
    assert!(!conversion_literal("let n = items * 1e30;"));
    assert!(!conversion_literal("let x = loomkin_units::mm_from_m(s_m);"));
    assert!(!conversion_literal("let q = a / 60.05;"));
}
