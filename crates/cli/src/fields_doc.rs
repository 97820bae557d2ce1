//! The field reference, docs/reference/fields.md, generated from the libraries' descriptors
//! (`loomkin_*::FIELDS`) and the CLI's own command tree, and a check that it is current.
//!
//! A test rather than a command: it needs the CLI's private clap tree and every library crate,
//! both of which this crate has, and it runs in CI with the other tests without adding a command
//! users would take for a contract. Regenerate with
//! `LOOMKIN_WRITE_FIELDS=1 cargo test --release -p loomkin-cli fields_reference`.

use clap::CommandFactory;
use loomkin_units::{Bound, Field, FieldList};
use std::collections::BTreeMap;
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// Every library crate's descriptors, with the crate's name.
pub(crate) const LISTS: [(&str, FieldList); 13] = [
    ("loomkin-units", loomkin_units::FIELDS),
    ("loomkin-laws", loomkin_laws::FIELDS),
    ("loomkin-picking", loomkin_picking::FIELDS),
    ("loomkin-cams", loomkin_cams::FIELDS),
    ("loomkin-dynamics", loomkin_dynamics::FIELDS),
    ("loomkin-shed", loomkin_shed::FIELDS),
    ("loomkin-loom", loomkin_loom::FIELDS),
    ("loomkin-mech", loomkin_mech::FIELDS),
    ("loomkin-servo", loomkin_servo::FIELDS),
    ("loomkin-drive", loomkin_drive::FIELDS),
    ("loomkin-plot", loomkin_plot::FIELDS),
    ("loomkin-eshed", loomkin_eshed::FIELDS),
    ("loomkin-insertion", loomkin_insertion::FIELDS),
];

pub(crate) fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A bound's number as the reference writes it.
fn num(v: f64) -> String {
    loomkin_units::compact(v)
}

/// The range as `lo … hi` with `[`/`(` for closed/open sides.
fn range_text(f: &Field) -> String {
    let lo = match f.range.lo {
        Bound::Unbounded => "(−∞".to_string(),
        Bound::Closed(v) => format!("[{}", num(v)),
        Bound::Open(v) => format!("({}", num(v)),
    };
    let hi = match f.range.hi {
        Bound::Unbounded => "∞)".to_string(),
        Bound::Closed(v) => format!("{}]", num(v)),
        Bound::Open(v) => format!("{})", num(v)),
    };
    format!("{lo}, {hi}")
}

/// One CLI input: the command path, the flag (or `<NAME>` of a positional), its default as
/// `--help` shows it, the first line of its help.
pub(crate) struct CliInput {
    pub(crate) command: String,
    pub(crate) flag: String,
    pub(crate) key: String,
    pub(crate) default: String,
    help: String,
}

/// Every descriptor of every library, by key.
pub(crate) fn descriptors_by_key() -> BTreeMap<&'static str, Vec<&'static Field>> {
    let mut by_name: BTreeMap<&str, Vec<&Field>> = BTreeMap::new();
    for (_, list) in LISTS {
        for (_, f) in list {
            by_name.entry(f.name).or_default().push(f);
        }
    }
    by_name
}

/// The descriptor a CLI input takes, as crates/cli/src/flag_fields.rs names it (none for a flag
/// named there as taking none, or not named).
pub(crate) fn descriptor_of(c: &CliInput) -> Option<&'static Field> {
    match crate::flag_fields::takes(&c.command, &c.flag)? {
        crate::flag_fields::Takes::Field(f) => Some(f),
        crate::flag_fields::Takes::Nothing(_) => None,
    }
}

pub(crate) fn cli_inputs() -> Vec<CliInput> {
    fn walk(cmd: &clap::Command, path: &str, out: &mut Vec<CliInput>) {
        let subs: Vec<&clap::Command> = cmd.get_subcommands().filter(|c| c.get_name() != "help").collect();
        if !subs.is_empty() {
            for s in subs {
                let p = if path.is_empty() { s.get_name().to_string() } else { format!("{path} {}", s.get_name()) };
                walk(s, &p, out);
            }
            return;
        }
        for a in cmd.get_arguments() {
            let id = a.get_id().as_str();
            if id == "help" || id == "version" {
                continue;
            }
            let (flag, key) = match a.get_long() {
                Some(l) => (format!("--{l}"), l.replace('-', "_")),
                None => (format!("<{}>", id.to_uppercase()), id.to_string()),
            };
            let default: Vec<String> =
                a.get_default_values().iter().map(|v| v.to_string_lossy().into_owned()).collect();
            let help = a.get_help().map(|h| h.to_string()).unwrap_or_default();
            let help = help.lines().next().unwrap_or("").replace('|', "\\|");
            out.push(CliInput { command: path.to_string(), flag, key, default: default.join(","), help });
        }
    }
    let mut out = Vec::new();
    walk(&crate::Cli::command(), "", &mut out);
    out
}

/// The top-level functions of the Python module's stubs (`python/loomkin/_loomkin.pyi`) and their
/// keyword names.
pub(crate) fn python_functions() -> Vec<(String, Vec<String>)> {
    let text = std::fs::read_to_string(repo().join("python/loomkin/_loomkin.pyi")).unwrap_or_default();
    let mut out = Vec::new();
    let mut rest = text.as_str();
    while let Some(i) = rest.find("\ndef ") {
        rest = &rest[i + 5..];
        let Some(open) = rest.find('(') else { break };
        let name = rest[..open].trim().to_string();
        let (mut depth, mut params, mut cur) = (0usize, Vec::new(), String::new());
        let take = |cur: &str, params: &mut Vec<String>| {
            let p = cur.split([':', '=']).next().unwrap_or("").trim().trim_start_matches('*').to_string();
            if !p.is_empty() && p != "self" {
                params.push(p);
            }
        };
        for ch in rest[open..].chars() {
            match ch {
                '(' | '[' => {
                    depth += 1;
                    if depth == 1 {
                        continue;
                    }
                }
                ')' | ']' => {
                    depth -= 1;
                    if depth == 0 {
                        take(&cur, &mut params);
                        break;
                    }
                }
                ',' if depth == 1 => {
                    take(&cur, &mut params);
                    cur.clear();
                    continue;
                }
                _ => {}
            }
            cur.push(ch);
        }
        if !name.starts_with('_') {
            out.push((name, params));
        }
    }
    out
}

/// The workbench's requests as Markdown: every route that takes a body, each key of its request
/// (nested keys as `a.b`, array items as `a[]`) with its type, unit, range and default, read from
/// the JSON Schema the workbench serves (`GET /api/schema`, generated from the request types, whose
/// bounds are the library's ranges).
fn workbench_requests() -> String {
    use serde_json::Value;
    fn bound(v: &Value, key: &str) -> Option<String> {
        v.get(key).and_then(Value::as_f64).map(num)
    }
    fn range(v: &Value) -> String {
        let lo = bound(v, "minimum")
            .map(|b| format!("[{b}"))
            .or_else(|| bound(v, "exclusiveMinimum").map(|b| format!("({b}")));
        let hi = bound(v, "maximum")
            .map(|b| format!("{b}]"))
            .or_else(|| bound(v, "exclusiveMaximum").map(|b| format!("{b})")));
        match (lo, hi) {
            (None, None) => String::new(),
            (lo, hi) => format!("{}, {}", lo.unwrap_or_else(|| "(−∞".into()), hi.unwrap_or_else(|| "∞)".into())),
        }
    }
    fn resolve<'a>(v: &'a Value, defs: &'a Value) -> &'a Value {
        match v.get("$ref").and_then(Value::as_str).and_then(|r| r.strip_prefix("#/$defs/")) {
            Some(name) => defs.get(name).unwrap_or(v),
            None => v,
        }
    }
    fn kind(v: &Value, defs: &Value) -> String {
        let v = resolve(v, defs);
        let alternatives = v.get("oneOf").or_else(|| v.get("anyOf")).or_else(|| v.get("enum"));
        if let Some(Value::Array(alts)) = alternatives {
            let names: Vec<String> = alts
                .iter()
                .filter_map(|a| {
                    a.as_str()
                        .map(str::to_string)
                        .or_else(|| resolve(a, defs).get("const").and_then(Value::as_str).map(str::to_string))
                })
                .map(|n| format!("`{n}`"))
                .collect();
            if names.len() == alts.len() && !names.is_empty() {
                return format!("one of {}", names.join(", "));
            }
            return "one of several forms".into();
        }
        match v.get("type") {
            Some(Value::String(t)) => t.clone(),
            Some(Value::Array(ts)) => ts.iter().filter_map(Value::as_str).collect::<Vec<_>>().join(" or "),
            _ => String::new(),
        }
    }
    fn walk(path: &str, v: &Value, defs: &Value, depth: usize, out: &mut String) {
        let r = resolve(v, defs);
        let props = r.get("properties").and_then(Value::as_object);
        if let (Some(props), true) = (props, depth < 6) {
            for (key, p) in props {
                let sub = if path.is_empty() { key.clone() } else { format!("{path}.{key}") };
                walk(&sub, p, defs, depth + 1, out);
            }
            return;
        }
        if let (Some(items), true) = (r.get("items"), depth < 6) {
            let t = resolve(items, defs);
            if t.get("properties").is_some() {
                walk(&format!("{path}[]"), items, defs, depth + 1, out);
                return;
            }
        }
        if path.is_empty() {
            return;
        }
        let item = r.get("items").map(|i| resolve(i, defs));
        let (t, unit, range) = match item {
            Some(i) => {
                (format!("array of {}", kind(i, defs)), i.get("x-unit"), fields_doc_range_or(range(i), range(r)))
            }
            None => (kind(v, defs), r.get("x-unit"), range(r)),
        };
        let unit = unit.or_else(|| v.get("x-unit")).and_then(Value::as_str).unwrap_or("");
        let default = v.get("default").or_else(|| r.get("default")).map(|d| match d {
            Value::Number(n) => n.as_f64().map(num).unwrap_or_else(|| n.to_string()),
            other => other.to_string(),
        });
        let help = v
            .get("description")
            .or_else(|| r.get("description"))
            .and_then(Value::as_str)
            .unwrap_or("")
            .lines()
            .next()
            .unwrap_or("")
            .replace('|', "\\|");
        let _ = writeln!(
            out,
            "| `{path}` | {t} | {} | {range} | {} | {help} |",
            if unit.is_empty() { "—" } else { unit },
            default.map_or_else(|| "—".to_string(), |d| format!("`{d}`")),
        );
    }
    let schema = loomkin_web::api_schema();
    let mut s = String::from("\n## Workbench requests\n\n");
    s.push_str(
        "Every route of the workbench that takes a request body (`loomkin serve`; `GET /api/schema` serves these \
         schemas), each key of its request with its type, unit, range and default. The bounds are the library \
         ranges above, carried into the schema by the request types.\n",
    );
    for (route, r) in &schema.routes {
        let v = serde_json::to_value(&r.request).unwrap_or_default();
        let defs = v.get("$defs").cloned().unwrap_or_default();
        let _ = writeln!(s, "\n### `{} {route}`\n", r.method);
        s.push_str("| key | type | unit | range | default | help |\n|---|---|---|---|---|---|\n");
        walk("", &v, &defs, 0, &mut s);
    }
    s
}

/// An array's range: its items' when they have one, else the array's own (a length's).
fn fields_doc_range_or(items: String, own: String) -> String {
    if items.is_empty() { own } else { items }
}

/// The reference as Markdown.
fn reference() -> String {
    let cli = cli_inputs();
    let py = python_functions();
    let py_takes = crate::python_fields::python_takes();
    let by_name = descriptors_by_key();
    let mut s = String::new();
    s.push_str(
        "<!-- Generated by `LOOMKIN_WRITE_FIELDS=1 cargo test --release -p loomkin-cli fields_reference` from the \
         libraries' field descriptors and the CLI's command tree; do not edit by hand. -->\n\n",
    );
    s.push_str("# Field reference\n\n");
    s.push_str(
        "Every input quantity loomkin's libraries declare — its key, unit, allowed range, default and the reason \
         for its bounds — and every input of every command, workbench route and Python function. A range or default is declared once, on the library \
         type that owns it (`loomkin_units::Field`, see docs/design/fields.md); the CLI, the workbench and Python \
         read it from there. Ranges: `[a, b]` closed, `(a, b)` open. The key is the JSON and Python keyword; the \
         CLI flag is the same words joined with `-`. \"Taken by\" names the CLI's flags that take the descriptor \
         (crates/cli/src/flag_fields.rs) and the functions of the Python module (`loomkin._loomkin`, which the \
         `loomkin.*` modules wrap) whose keyword takes it, with the keyword where it is not the key: read from the \
         package's own signature defaults and checks, else named in crates/cli/src/python_fields.rs, else the flag \
         of the same words of the command the function runs.\n\n",
    );
    s.push_str("## Quantities\n\n");
    for (krate, list) in LISTS {
        let _ = writeln!(s, "### {krate}\n");
        s.push_str("| descriptor | key | unit | range | default | taken by | what and why |\n");
        s.push_str("|---|---|---|---|---|---|---|\n");
        for (path, f) in list {
            let default = match f.default {
                Some(v) => num(v),
                None => "—".into(),
            };
            // The flags that name this descriptor (crates/cli/src/flag_fields.rs) and the Python
            // keywords that take it (crates/cli/src/python_fields.rs).
            let shared = by_name.get(f.name).map_or(1, Vec::len) > 1;
            let mut takers: Vec<String> = cli
                .iter()
                .filter(|c| descriptor_of(c) == Some(f))
                .map(|c| format!("`{} {}`", c.command, c.flag))
                .collect();
            takers.dedup();
            let mut pyf: Vec<String> = py_takes
                .iter()
                .filter(|t| matches!(t.2, crate::flag_fields::Takes::Field(g) if g == f))
                .map(|t| if t.1 == f.name { format!("`{}`", t.0) } else { format!("`{}({})`", t.0, t.1) })
                .collect();
            pyf.dedup();
            let mut taken = Vec::new();
            if !takers.is_empty() {
                taken.push(format!("CLI {}", takers.join(", ")));
            }
            if !pyf.is_empty() {
                taken.push(format!("Python {}", pyf.join(", ")));
            }
            if shared && taken.is_empty() {
                taken.push("(a key several quantities share: see the commands below)".to_string());
            }
            let _ = writeln!(
                s,
                "| `{path}` | `{}`{} | {} | {} | {default} | {} | {} |",
                f.name,
                if f.count { " (count)" } else { "" },
                if f.unit().is_empty() { "—" } else { f.unit() },
                range_text(f),
                if taken.is_empty() { "—".into() } else { taken.join("; ") },
                f.doc.replace('|', "\\|"),
            );
        }
        s.push('\n');
    }
    s.push_str("## Command-line inputs\n\n");
    s.push_str(
        "Every flag and argument of every `loomkin` command, with the default `--help` shows and, where the key \
         names a library descriptor, its unit and range.\n\n",
    );
    let mut last = String::new();
    for c in &cli {
        if c.command != last {
            let _ = writeln!(s, "\n### `loomkin {}`\n", c.command);
            s.push_str("| input | unit | range | default | help |\n|---|---|---|---|---|\n");
            last.clone_from(&c.command);
        }
        let (unit, range) = match crate::flag_fields::takes(&c.command, &c.flag) {
            Some(crate::flag_fields::Takes::Field(f)) => {
                ((if f.unit().is_empty() { "—" } else { f.unit() }).to_string(), range_text(f))
            }
            Some(crate::flag_fields::Takes::Nothing(why)) => ("".into(), format!("({why})")),
            None => ("".into(), "".into()),
        };
        let _ = writeln!(
            s,
            "| `{}` | {unit} | {range} | {} | {} |",
            c.flag,
            if c.default.is_empty() { "—".to_string() } else { format!("`{}`", c.default) },
            c.help
        );
    }
    s.push_str(&workbench_requests());
    s.push_str("\n## Python functions\n\n");
    s.push_str("The keywords of each function of `loomkin._loomkin` (from its stubs); their defaults are the descriptors'.\n\n");
    for (name, params) in &py {
        let _ = writeln!(s, "- `{name}({})`", params.join(", "));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// docs/reference/fields.md is what the descriptors and the command tree give today.
    #[test]
    fn fields_reference() {
        let path = repo().join("docs/reference/fields.md");
        let text = reference();
        if std::env::var_os("LOOMKIN_WRITE_FIELDS").is_some() {
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(&path, &text).unwrap();
        }
        let on_disk = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            on_disk == text,
            "docs/reference/fields.md is not current: regenerate it with \
             `LOOMKIN_WRITE_FIELDS=1 cargo test --release -p loomkin-cli fields_reference` and commit it"
        );
    }

    /// `v` as a message prints it (`loomkin_units::compact`), or `None` for an open end (∞).
    fn printed(v: f64) -> Option<String> {
        Some(num(v)).filter(|t| !t.contains('∞'))
    }

    /// Significant digits of a number as printed (`0.0102` has 3, `1e-6` 1, `95000` 2).
    fn significant_digits(text: &str) -> usize {
        let mantissa = text.split(['e', 'E']).next().unwrap_or(text);
        let digits: String = mantissa.chars().filter(char::is_ascii_digit).collect();
        let digits = digits.trim_start_matches('0');
        // Trailing zeros of a whole number are its magnitude, not digits the user must type.
        let digits = if mantissa.contains('.') { digits } else { digits.trim_end_matches('0') };
        digits.len()
    }

    /// Every bound a user is shown — each descriptor's range and each bound of the workbench's
    /// request schemas — prints as a user would type it: the printed number reads back as the bound
    /// itself (so typing the bound shown is accepted), in at most 12 significant digits (no
    /// `0.010101010101` of a bound worked out as 1/0.99 − 1).
    #[test]
    fn every_bound_prints_as_typed() {
        let mut bad = Vec::new();
        let mut check = |at: String, v: f64| {
            if let Some(t) = printed(v)
                && (t.parse::<f64>() != Ok(v) || significant_digits(&t) > 12)
            {
                bad.push(format!("{at}: {v:?} prints as {t}"));
            }
        };
        let mut bounds = 0;
        for (_, list) in LISTS {
            for (path, f) in list {
                for b in [f.range.lo, f.range.hi] {
                    if let Bound::Closed(v) | Bound::Open(v) = b {
                        check(path.to_string(), v);
                        bounds += 1;
                    }
                }
            }
        }
        fn walk(at: &str, v: &serde_json::Value, out: &mut Vec<(String, f64)>) {
            match v {
                serde_json::Value::Object(m) => {
                    for (k, x) in m {
                        let here = format!("{at}.{k}");
                        match (k.as_str(), x.as_f64()) {
                            ("minimum" | "maximum" | "exclusiveMinimum" | "exclusiveMaximum", Some(b)) => {
                                out.push((here, b))
                            }
                            _ => walk(&here, x, out),
                        }
                    }
                }
                serde_json::Value::Array(xs) => {
                    for (i, x) in xs.iter().enumerate() {
                        walk(&format!("{at}[{i}]"), x, out);
                    }
                }
                _ => {}
            }
        }
        let mut schema_bounds = Vec::new();
        for (route, r) in &loomkin_web::api_schema().routes {
            walk(route, &serde_json::to_value(&r.request).unwrap(), &mut schema_bounds);
        }
        assert!(
            bounds > 300 && schema_bounds.len() > 100,
            "{bounds} descriptor bounds, {} in the schemas",
            schema_bounds.len()
        );
        for (at, v) in schema_bounds {
            check(at, v);
        }
        assert!(bad.is_empty(), "bounds that do not print as typed:\n{}", bad.join("\n"));
    }

    #[test]
    fn the_digit_count_counts_what_is_typed() {
        assert_eq!(significant_digits("0.0102"), 3);
        assert_eq!(significant_digits("95000"), 2);
        assert_eq!(significant_digits("1e-6"), 1);
        assert_eq!(significant_digits("-2.5e-7"), 2);
        assert_eq!(significant_digits("0.010101010101"), 11);
        assert_eq!(significant_digits("359.999"), 6);
    }

    /// Every descriptor's path is unique across the crates (Python looks them up by it) and every
    /// default lies inside its range (also checked at compile time).
    #[test]
    fn descriptors_are_unique_and_consistent() {
        let mut seen = std::collections::BTreeSet::new();
        for (_, list) in LISTS {
            for (path, f) in list {
                assert!(seen.insert(*path), "{path} is declared twice");
                if let Some(d) = f.default {
                    assert!(f.range.contains(d), "{path}: default {d} outside {}", f.describe());
                }
                assert!(!f.doc.is_empty(), "{path} has no doc");
            }
        }
    }
}
