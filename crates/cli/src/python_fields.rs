//! Which library descriptor (`loomkin_units::Field`) each keyword of the Python module's functions
//! (`loomkin._loomkin`, python/src) takes, for the "taken by" column of docs/reference/fields.md.
//!
//! Matching a keyword to a descriptor by its key listed nothing for a key several descriptors share
//! (`motion_deg`, `stroke_mm`, `window_deg`, `step_deg`, `points`, `speed_rpm`, `cycles`) and would
//! list the wrong function for a keyword named like another quantity. Here each keyword's descriptor
//! is read, in this order, from:
//!
//! 1. **the package's own source** ([`package_links`]): a keyword whose signature default is a
//!    descriptor's (`step_deg=Drive::STEP_DEG.default_value()`,
//!    `points=Count::of(History::POINTS.default_count())`) or which the function checks through one
//!    (`Drive::STEP_DEG.check(step_deg)`, `points.check(&History::POINTS)`);
//! 2. **[`ONE`]**, named here, for a keyword the function hands to a library call that checks it
//!    (`rise_return_cycle`'s `stroke_mm` goes to `CycleSpec::rise_return`);
//! 3. **the flag of the CLI command the function runs** ([`MIRRORS`]; crates/cli/src/flag_fields.rs),
//!    the flag of the same words (`speed_rpm` → `--speed-rpm`), when the command has that flag.
//!
//! The tests keep the three together: every keyword whose key is some descriptor's is linked (or
//! named as taking none, with the reason), an entry of [`ONE`] never repeats or contradicts the
//! source, the CLI command's flag takes the same descriptor as the package's source wherever both
//! name one, and every entry names a function and keyword of the stubs.

use crate::fields_doc::{python_functions, repo};
use crate::flag_fields::Takes;
use loomkin_units::Field;

/// The CLI command each function of `loomkin._loomkin` runs (python/tests/test_api.py pairs the
/// public wrappers with the same commands).
pub(crate) const MIRRORS: &[(&str, &str)] = &[
    ("law_catalogue", "law list"),
    ("servo_law", "servo law"),
    ("servo_torque", "servo torque"),
    ("servo_torque_curve", "servo plot"),
    ("servo_optimize", "servo optimize"),
    ("servo_export", "servo export"),
    ("servo_check", "servo check"),
    ("pick_design", "pick design"),
    ("pick_simulate", "pick simulate"),
    ("pick_history", "pick simulate"),
    ("pick_sweep", "pick sweep"),
    ("pick_montecarlo", "pick montecarlo"),
    ("dobby_tolerance", "dobby tolerance"),
    ("dobby_sweep", "dobby sweep"),
    ("dobby_analyze", "dobby analyze"),
    ("dobby_synthesize", "dobby synthesize"),
    ("shed_presets", "shed list"),
    ("shed_law", "shed law"),
    ("shed_table", "shed table"),
    ("shed_pareto", "shed pareto"),
    ("shed_best", "shed best"),
    ("shed_window", "shed window"),
    ("loom_check", "loom check"),
    ("loom_torque", "loom torque"),
    ("loom_stagger", "loom stagger"),
    ("loom_servo", "loom servo"),
    ("loom_sley", "sley analyze"),
    ("loom_sley_synthesize", "sley synthesize"),
    ("drive_inertia", "drive inertia"),
    ("drive_ripple", "drive ripple"),
    ("drive_correct", "drive correct"),
    ("dyn_response", "dyn response"),
    ("dyn_sweep", "dyn sweep"),
    ("dyn_spectrum", "dyn spectrum"),
    ("dyn_compensate", "dyn compensate"),
    ("dyn_optimize", "dyn optimize"),
    ("dyn_two_mass", "dyn two-mass"),
    ("cam_table", "cam table"),
    ("cam_profile", "cam profile"),
    ("rise_return_cycle", "cam profile"),
    ("insert_budget", "insert budget"),
    ("insert_rapier", "insert rapier"),
    ("insert_projectile", "insert projectile"),
    ("insert_airjet", "insert airjet"),
];

/// Keywords the function hands to a library call that checks them, where the CLI command has no
/// flag of the same words or its flag takes another descriptor.
pub(crate) const ONE: &[(&str, &str, Takes)] = &[
    // `SleyTarget::synthesize` checks `stroke_mm` through `SleyTarget::STROKE_MM` (the CLI's flag
    // is `--reed-stroke-mm`, the descriptor's key `reed_stroke_mm`).
    ("loom_sley_synthesize", "stroke_mm", Takes::Field(&loomkin_drive::SleyTarget::STROKE_MM)),
];

/// Where a keyword's descriptor was read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Source {
    /// The package's source (a signature default or a check).
    Package,
    /// [`ONE`].
    Named,
    /// The flag of the CLI command of [`MIRRORS`].
    Cli,
}

/// Every descriptor with the path of its `const` (`Follower::DAMPING_RATIO`).
fn all_fields() -> impl Iterator<Item = (&'static str, &'static Field)> {
    crate::fields_doc::LISTS.iter().flat_map(|(_, list)| list.iter().map(|(p, f)| (*p, f)))
}

/// The descriptor a path written in the package's source names (`loomkin_laws::Cycle::HELD_POINTS`,
/// `Follower::DAMPING_RATIO`, or an imported `STEP_DEG` resolved through the file's `use` lines).
fn resolve(path: &str, file: &str) -> Option<(&'static str, &'static Field)> {
    let full = if path.contains("::") {
        path.to_string()
    } else {
        // `use a::b::{C, STEP_DEG};` or `use a::b::STEP_DEG;`
        file.lines().map(str::trim).filter(|l| l.starts_with("use ")).find_map(|l| {
            let body = l.trim_start_matches("use ").trim_end_matches(';');
            match body.split_once("::{") {
                Some((prefix, items)) => items
                    .trim_end_matches('}')
                    .split(',')
                    .any(|i| i.trim() == path)
                    .then(|| format!("{prefix}::{path}")),
                None => body.ends_with(&format!("::{path}")).then(|| body.to_string()),
            }
        })?
    };
    all_fields().filter(|(p, _)| full == *p || full.ends_with(&format!("::{p}"))).max_by_key(|(p, _)| p.len())
}

/// The identifier path ending just before byte `end` of `s` (`Drive::STEP_DEG` of
/// `Drive::STEP_DEG.check(`).
fn path_before(s: &str, end: usize) -> &str {
    let start = s[..end].rfind(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == ':')).map_or(0, |i| i + 1);
    &s[start..end]
}

/// The identifier starting at byte `at` of `s`.
fn ident_at(s: &str, at: usize) -> &str {
    let rest = &s[at..];
    let n = rest.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).unwrap_or(rest.len());
    &rest[..n]
}

/// The keywords the package's source links to a descriptor, `(function, keyword, descriptor path,
/// descriptor)`: signature defaults and checks in the function's body, in every python/src file.
pub(crate) fn package_links() -> Vec<(String, String, &'static str, &'static Field)> {
    let mut out = Vec::new();
    let Ok(dir) = std::fs::read_dir(repo().join("python/src")) else { return out };
    for entry in dir.flatten() {
        let Ok(text) = std::fs::read_to_string(entry.path()) else { continue };
        let code = text.split("#[cfg(test)]").next().unwrap_or("");
        let mut rest = code;
        while let Some(i) = rest.find("#[pyo3(signature = (") {
            let sig_start = i + "#[pyo3(signature = (".len();
            let after = &rest[sig_start..];
            let Some(sig_end) = after.find("))]") else { break };
            let signature = &after[..sig_end];
            let tail = &after[sig_end..];
            let Some(fn_at) = tail.find("fn ") else { break };
            let name = ident_at(tail, fn_at + 3).to_string();
            let body_end = tail[fn_at..].find("#[pyo3(signature").map_or(tail.len(), |e| fn_at + e);
            let body = &tail[fn_at..body_end];
            // The keywords: depth-0 items of the signature, `kw=EXPR` or `kw`.
            let (mut depth, mut items, mut cur) = (0i32, Vec::new(), String::new());
            for ch in signature.chars() {
                match ch {
                    '(' | '[' | '{' => depth += 1,
                    ')' | ']' | '}' => depth -= 1,
                    ',' if depth == 0 => {
                        items.push(std::mem::take(&mut cur));
                        continue;
                    }
                    _ => {}
                }
                cur.push(ch);
            }
            items.push(cur);
            let keywords: Vec<String> = items
                .iter()
                .map(|it| it.split('=').next().unwrap_or("").trim().trim_start_matches('*').to_string())
                .filter(|k| !k.is_empty())
                .collect();
            for it in &items {
                let Some((kw, expr)) = it.split_once('=') else { continue };
                for marker in [".default_value()", ".default_count()"] {
                    if let Some(at) = expr.find(marker)
                        && let Some((p, f)) = resolve(path_before(expr, at), code)
                    {
                        out.push((name.clone(), kw.trim().to_string(), p, f));
                    }
                }
            }
            // `PATH.check(kw)` and `kw.check(&PATH)` in the body.
            for (at, _) in body.match_indices(".check(") {
                let arg_at = at + ".check(".len();
                let before = path_before(body, at);
                let arg = ident_at(body, arg_at);
                let link = if keywords.iter().any(|k| k == arg) {
                    resolve(before, code).map(|pf| (arg.to_string(), pf))
                } else if keywords.iter().any(|k| k == before) && body[arg_at..].starts_with('&') {
                    resolve(path_before(body, arg_at + 1 + ident_path_len(&body[arg_at + 1..])), code)
                        .map(|pf| (before.to_string(), pf))
                } else {
                    None
                };
                if let Some((kw, (p, f))) = link {
                    out.push((name.clone(), kw, p, f));
                }
            }
            rest = &tail[fn_at..];
        }
    }
    out.sort_by(|a, b| (&a.0, &a.1, a.2).cmp(&(&b.0, &b.1, b.2)));
    out.dedup_by(|a, b| a.0 == b.0 && a.1 == b.1 && a.2 == b.2);
    out
}

/// The length of the identifier path (`a::B::C`) at the start of `s`.
fn ident_path_len(s: &str) -> usize {
    s.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == ':')).unwrap_or(s.len())
}

/// What the CLI flag of the same words of the function's command takes, when the command has it.
fn mirrored(function: &str, keyword: &str, cli: &[crate::fields_doc::CliInput]) -> Option<Takes> {
    let command = MIRRORS.iter().find(|(f, _)| *f == function)?.1;
    let flag = format!("--{}", keyword.replace('_', "-"));
    cli.iter().any(|c| c.command == command && c.flag == flag).then(|| crate::flag_fields::takes(command, &flag))?
}

/// Every keyword's descriptor (or why none): `(function, keyword) → (what it takes, where read)`,
/// for the keywords of the stubs whose key is some descriptor's or which the package links.
pub(crate) fn python_takes() -> Vec<(String, String, Takes, Source)> {
    let links = package_links();
    let cli = crate::fields_doc::cli_inputs();
    let keys: std::collections::BTreeSet<&str> = all_fields().map(|(_, f)| f.name).collect();
    let mut out = Vec::new();
    for (function, params) in python_functions() {
        for kw in params {
            let from_package: Vec<&Field> =
                links.iter().filter(|l| l.0 == function && l.1 == kw).map(|l| l.3).collect();
            let taken = if let Some(f) = from_package.first() {
                Some((Takes::Field(f), Source::Package))
            } else if let Some((_, _, t)) = ONE.iter().find(|(f, k, _)| *f == function && *k == kw) {
                Some((*t, Source::Named))
            } else if keys.contains(kw.as_str()) {
                mirrored(&function, &kw, &cli).map(|t| (t, Source::Cli))
            } else {
                None
            };
            if let Some((t, from)) = taken {
                out.push((function.clone(), kw, t, from));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn field_path(f: &Field) -> &'static str {
        all_fields().find(|(_, g)| std::ptr::eq(*g, f) || *g == f).map_or("?", |(p, _)| p)
    }

    /// Whether the package's descriptor `python` is the held variant of the CLI's `cli` (the CLI
    /// streams rows, Python holds them as arrays and checks the memory bound declared beside the
    /// streamed one: `Sweep::HELD_POINTS` beside `Sweep::POINTS`, docs/design/fields.md rule 2).
    fn held_variant(python: &str, cli: &str) -> bool {
        let (Some((t, c)), Some((u, p))) = (cli.rsplit_once("::"), python.rsplit_once("::")) else { return false };
        t == u && p == format!("HELD_{c}")
    }

    /// Every keyword whose key is some descriptor's names what it takes.
    #[test]
    fn every_keyword_with_a_descriptor_key_is_linked() {
        let keys: std::collections::BTreeSet<&str> = all_fields().map(|(_, f)| f.name).collect();
        let taken = python_takes();
        let missing: Vec<String> = python_functions()
            .into_iter()
            .flat_map(|(f, ps)| ps.into_iter().map(move |p| (f.clone(), p)))
            .filter(|(f, p)| keys.contains(p.as_str()) && !taken.iter().any(|t| &t.0 == f && &t.1 == p))
            .map(|(f, p)| format!("{f}({p})"))
            .collect();
        assert!(missing.is_empty(), "keywords to name in crates/cli/src/python_fields.rs ONE: {missing:?}");
    }

    /// The package's own source links keywords (a sample that must be found), and where a
    /// keyword is linked twice in one function, both links name one descriptor.
    #[test]
    fn the_package_links_are_read_and_agree() {
        let links = package_links();
        for (f, k, p) in [
            ("loom_torque", "step_deg", "Drive::STEP_DEG"),
            ("drive_ripple", "step_deg", "ripple::STEP_DEG"),
            ("pick_history", "points", "History::POINTS"),
            ("dyn_response", "cycles", "Response::CYCLES"),
            ("dobby_synthesize", "cycles", "OutputLawSpec::CYCLES"),
            ("cam_profile", "step_deg", "CamProfile::STEP_DEG"),
        ] {
            assert!(links.iter().any(|l| l.0 == f && l.1 == k && l.2 == p), "{f}({k}) → {p} not read: {links:?}");
        }
        for a in &links {
            for b in &links {
                assert!(!(a.0 == b.0 && a.1 == b.1 && a.2 != b.2), "{}({}) → {} and {}", a.0, a.1, a.2, b.2);
            }
        }
    }

    /// An entry of ONE never stands where the package's source names the descriptor, and where the
    /// CLI command's flag and the package both name one, it is the same.
    #[test]
    fn the_named_entries_and_the_cli_agree_with_the_package() {
        let links = package_links();
        let cli = crate::fields_doc::cli_inputs();
        for (f, k, _) in ONE {
            assert!(!links.iter().any(|l| l.0 == *f && l.1 == *k), "{f}({k}): the package's source names it");
        }
        let mut differ = Vec::new();
        for (f, k, p, field) in &links {
            if let Some(Takes::Field(g)) = mirrored(f, k, &cli)
                && g != *field
                && !held_variant(p, field_path(g))
            {
                differ.push(format!("{f}({k}): package {p}, CLI {}", field_path(g)));
            }
        }
        assert!(differ.is_empty(), "Python and the CLI take different descriptors: {differ:?}");
    }

    /// Every entry names a function and keyword of the stubs, every mirror a CLI command.
    #[test]
    fn every_entry_names_what_exists() {
        let py = python_functions();
        let has = |f: &str, k: &str| py.iter().any(|(n, ps)| n == f && ps.iter().any(|p| p == k));
        for (f, k, _) in ONE {
            assert!(has(f, k), "{f}({k}) is not a keyword of the stubs");
        }
        let commands: std::collections::BTreeSet<String> =
            crate::fields_doc::cli_inputs().into_iter().map(|c| c.command).collect();
        for (f, c) in MIRRORS {
            assert!(py.iter().any(|(n, _)| n == f), "{f} is not a function of the stubs");
            assert!(commands.contains(*c), "{c} is not a CLI command");
        }
    }
}
