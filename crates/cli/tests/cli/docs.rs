//! Every `loomkin …` command quoted in README.md and docs/*.md works as printed.
//!
//! The commands of each page run in order (a later one may read a file an earlier one wrote) in a
//! scratch directory holding a copy of the repository's `examples/`, so the paths they name resolve
//! as they do from the repository root, and nothing is written into the repository. A command
//! whose next line in the page is `loomkin: error: …` is documented to fail: it must exit with 2.
//! `loomkin serve` is skipped (it runs until stopped).

use std::path::{Path, PathBuf};
use std::process::Command;

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().unwrap()
}

/// A quoted command: where it is, the shell line, and whether the page shows it failing.
struct Quoted {
    place: String,
    line: String,
    fails: bool,
}

/// The `loomkin …` lines of a Markdown page: in fenced blocks and in indented blocks, with or
/// without a leading `$ `, trailing `# comments` removed.
fn quoted_commands(page: &Path) -> Vec<Quoted> {
    let text = std::fs::read_to_string(page).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let mut fenced = false;
    let mut out = Vec::new();
    for (i, raw) in lines.iter().enumerate() {
        if raw.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if !fenced && !raw.starts_with("    ") {
            continue;
        }
        let t = raw.trim();
        let t = t.strip_prefix("$ ").unwrap_or(t);
        if !t.starts_with("loomkin ") || t.starts_with("loomkin serve") || t.starts_with("loomkin workbench") {
            continue;
        }
        // A line ending in `\` continues on the next.
        let mut full = t.to_string();
        let mut j = i;
        while full.ends_with('\\') && j + 1 < lines.len() {
            full.pop();
            j += 1;
            full.push(' ');
            full.push_str(lines[j].trim());
        }
        let command = match full.find("  #") {
            Some(k) => full[..k].trim_end(),
            None => full.as_str(),
        };
        let fails = lines.get(j + 1).is_some_and(|next| next.trim().starts_with("loomkin: error"));
        out.push(Quoted { place: format!("{}:{}", page.display(), i + 1), line: command.to_string(), fails });
    }
    out
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        if e.file_type().unwrap().is_file() {
            std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
        }
    }
}

#[test]
fn every_documented_command_works_as_printed() {
    let root = repo_root();
    let bin = assert_cmd::cargo::cargo_bin("loomkin");
    let path = format!("{}:{}", bin.parent().unwrap().display(), std::env::var("PATH").unwrap_or_default());
    let mut pages = vec![root.join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .collect();
    docs.sort();
    pages.extend(docs);
    let mut count = 0;
    let mut failures = Vec::new();
    for page in &pages {
        let scratch = std::env::temp_dir().join(format!(
            "loomkin-docs-{}-{}",
            std::process::id(),
            page.file_stem().unwrap().to_string_lossy()
        ));
        let _ = std::fs::remove_dir_all(&scratch);
        copy_dir(&root.join("examples"), &scratch.join("examples"));
        for q in quoted_commands(page) {
            count += 1;
            let out =
                Command::new("sh").arg("-c").arg(&q.line).current_dir(&scratch).env("PATH", &path).output().unwrap();
            let code = out.status.code();
            let want_ok = !q.fails;
            let ok = if want_ok { code == Some(0) } else { code == Some(2) };
            if !ok {
                let err = String::from_utf8_lossy(&out.stderr);
                failures.push(format!("{} `{}`: exit {:?}: {}", q.place, q.line, code, err.trim()));
            }
            // `--json` to standard output: it parses (JSON, or JSON Lines with --shard), and every
            // number it carries names its unit or is listed as dimensionless (units.rs).
            let words: Vec<&str> = q.line.split_whitespace().collect();
            if ok && want_ok && words.contains(&"--json") && !q.line.contains(['>', '|']) {
                let text = String::from_utf8_lossy(&out.stdout);
                let docs: Result<Vec<serde_json::Value>, _> = if words.contains(&"--shard") {
                    text.lines().filter(|l| !l.trim().is_empty()).map(serde_json::from_str).collect()
                } else {
                    serde_json::from_str(&text).map(|v| vec![v])
                };
                match docs {
                    Ok(docs) => {
                        for v in &docs {
                            for key in crate::units::keys_without_unit(v) {
                                failures
                                    .push(format!("{} `{}`: the number under `{key}` names no unit", q.place, q.line));
                            }
                        }
                    }
                    Err(e) => failures.push(format!("{} `{}`: --json does not parse: {e}", q.place, q.line)),
                }
            }
        }
        let _ = std::fs::remove_dir_all(&scratch);
    }
    assert!(count >= 40, "only {count} documented commands found");
    assert!(failures.is_empty(), "{} of {count} documented commands failed:\n{}", failures.len(), failures.join("\n"));
}

/// Every relative link of README.md, CHANGELOG.md, CONTRIBUTING.md, docs/*.md and docs/design/*.md
/// names a file or directory of the repository (a link into a retired or renamed page fails here by
/// page and line; the anchor after `#` is not checked; code spans and blocks are not prose).
#[test]
fn relative_links_resolve() {
    let root = repo_root();
    let mut pages: Vec<PathBuf> =
        ["README.md", "CHANGELOG.md", "CONTRIBUTING.md"].iter().map(|p| root.join(p)).filter(|p| p.exists()).collect();
    for dir in ["docs", "docs/design"] {
        let mut found: Vec<PathBuf> = std::fs::read_dir(root.join(dir))
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "md"))
            .collect();
        found.sort();
        pages.extend(found);
    }
    let mut links = 0;
    let mut broken = Vec::new();
    for page in &pages {
        let text = std::fs::read_to_string(page).unwrap();
        let mut fenced = false;
        for (n, line) in text.lines().enumerate() {
            if line.trim_start().starts_with("```") {
                fenced = !fenced;
            }
            if fenced {
                continue;
            }
            // Outside code spans (`e[iΩ, λ₁](t)` is a formula, not a link).
            let prose: String = line.split('`').step_by(2).collect::<Vec<_>>().join(" ");
            let mut rest = prose.as_str();
            while let Some(k) = rest.find("](") {
                rest = &rest[k + 2..];
                let Some(end) = rest.find(')') else { break };
                let target = &rest[..end];
                rest = &rest[end..];
                if target.is_empty()
                    || target.starts_with('#')
                    || target.contains("://")
                    || target.starts_with("mailto:")
                {
                    continue;
                }
                links += 1;
                let path = target.split('#').next().unwrap();
                if !page.parent().unwrap().join(path).exists() {
                    broken.push(format!("{}:{}: {target}", page.strip_prefix(&root).unwrap().display(), n + 1));
                }
            }
        }
    }
    assert!(links >= 30, "only {links} relative links found");
    assert!(broken.is_empty(), "links to nothing:\n{}", broken.join("\n"));
}
