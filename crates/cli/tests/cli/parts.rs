//! `--parts DIR`, `loomkin merge` and the reduce steps (`shed pareto --from`, `--from-draws` of
//! parts): the failure scenarios of issue 28 and the byte identity with the one-machine run at
//! N = 2, 3, 7 and more shards than rows.

use crate::common::{loomkin, usage_error};
use std::path::{Path, PathBuf};
use std::process::Output;

fn repo() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("loomkin-parts-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn exec(args: &[&str]) -> Output {
    loomkin().current_dir(repo()).args(args).output().unwrap()
}

fn ok(args: &[&str]) -> Vec<u8> {
    let out = exec(args);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    out.stdout
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Runs `args` as shards 1…n into `dir` with `--parts`.
fn parts(args: &[&str], n: u32, dir: &Path) {
    for i in 1..=n {
        let shard = format!("{i}/{n}");
        let mut a = args.to_vec();
        a.extend(["--shard", &shard, "--parts", s(dir)]);
        let out = exec(&a);
        assert!(out.status.success(), "{a:?}: {}", String::from_utf8_lossy(&out.stderr));
        assert!(out.stdout.is_empty(), "a part goes to its file, not to standard output");
    }
}

const SWEEP: &[&str] = &["pick", "sweep", "play", "--from", "0", "--to", "20", "--points", "5"];

/// `loomkin merge` of the parts is the one-machine output byte for byte, CSV and JSON Lines, at
/// N = 2, 3, 7 and 12 (> 5 rows: empty parts); every CSV part starts with the header (a glob
/// reader sees a table in each).
#[test]
fn merged_parts_are_the_one_machine_output() {
    for (format, ext) in [("--csv", "csv"), ("--json", "jsonl")] {
        let mut args = SWEEP.to_vec();
        args.push(format);
        let whole = if format == "--csv" { ok(&args) } else { ok(&[&args[..], &["--shard", "1/1"]].concat()) };
        for n in [2, 3, 7, 12] {
            let dir = tmp(&format!("merge-{ext}-{n}"));
            parts(&args, n, &dir.join("p"));
            let out = dir.join("all");
            ok(&["merge", s(&dir.join("p")), "-o", s(&out)]);
            assert_eq!(std::fs::read(&out).unwrap(), whole, "{format} N = {n}");
            assert!(dir.join("all.manifest.json").exists());
            // To standard output too, and from the part files named one by one.
            let mut files: Vec<PathBuf> = std::fs::read_dir(dir.join("p"))
                .unwrap()
                .map(|e| e.unwrap().path())
                .filter(|p| p.extension().is_some_and(|e| e == ext))
                .collect();
            files.sort();
            assert_eq!(files.len(), n as usize);
            if format == "--csv" {
                let header = std::str::from_utf8(&whole).unwrap().lines().next().unwrap().to_string();
                for f in &files {
                    assert!(std::fs::read_to_string(f).unwrap().starts_with(&(header.clone() + "\n")), "{f:?}");
                }
            }
            let mut a = vec!["merge"];
            a.extend(files.iter().map(|f| s(f)));
            a.extend(["-o", "-"]);
            assert_eq!(ok(&a), whole);
            std::fs::remove_dir_all(&dir).unwrap();
        }
    }
}

/// A missing part is named with the shards to rerun (exit 1); a part cut short or changed is
/// refused (exit 1), and nothing is written; usage errors exit 2. On main, `cat shards/part-*`
/// gave a too-short or too-long file with exit 0.
#[test]
fn merge_names_what_is_missing_or_damaged() {
    let dir = tmp("missing");
    let p = dir.join("p");
    let mut args = SWEEP.to_vec();
    args.push("--csv");
    parts(&args, 4, &p);
    let part = |i: u32| p.join(format!("part-{i:05}-of-00004.csv"));
    let manifest = |i: u32| p.join(format!("part-{i:05}-of-00004.csv.manifest.json"));
    let out = dir.join("all.csv");
    // A task that died before its rename leaves a part without a manifest: not a part.
    std::fs::remove_file(manifest(2)).unwrap();
    std::fs::remove_file(part(3)).unwrap();
    std::fs::remove_file(manifest(3)).unwrap();
    let o = exec(&["merge", s(&p), "-o", s(&out)]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("2 of 4 parts missing: shards 2-3 (rerun: sbatch --array=2-3"), "{err}");
    assert!(!out.exists(), "no output after a failed check");
    // Rerun exactly the missing shards: the merge is whole again.
    for i in [2, 3] {
        let shard = format!("{i}/4");
        ok(&[&args[..], &["--shard", &shard, "--parts", s(&p)]].concat());
    }
    ok(&["merge", s(&p), "-o", s(&out)]);
    assert_eq!(std::fs::read(&out).unwrap(), ok(&args));
    // A part cut short.
    let text = std::fs::read(part(4)).unwrap();
    std::fs::write(part(4), &text[..text.len() - 3]).unwrap();
    let o = exec(&["merge", s(&p), "-o", s(&dir.join("b.csv"))]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("rerun shard 4"), "{}", String::from_utf8_lossy(&o.stderr));
    // The same size, other bytes: the checksum.
    let mut changed = text.clone();
    let at = changed.len() - 2;
    changed[at] = if changed[at] == b'1' { b'2' } else { b'1' };
    std::fs::write(part(4), &changed).unwrap();
    let o = exec(&["merge", s(&p), "-o", s(&dir.join("b.csv"))]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("does not match its manifest"));
    assert!(!dir.join("b.csv").exists());
    usage_error(&["merge", s(&p)], &["--output"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Two studies cannot share a directory (on main, `rm -f shards/part-*` of one study destroyed
/// the other's); parts of two runs named together are refused.
#[test]
fn one_directory_per_study() {
    let dir = tmp("two");
    let p = dir.join("p");
    let mut a = SWEEP.to_vec();
    a.push("--csv");
    parts(&a, 2, &p);
    let o = exec(&[
        "pick",
        "sweep",
        "play",
        "--from",
        "0",
        "--to",
        "30",
        "--points",
        "5",
        "--csv",
        "--shard",
        "1/2",
        "--parts",
        s(&p),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("give each study its own directory"));
    parts(&["pick", "sweep", "play", "--from", "0", "--to", "30", "--points", "5", "--csv"], 2, &dir.join("q"));
    let o = exec(&[
        "merge",
        s(&p.join("part-00001-of-00002.csv")),
        s(&dir.join("q").join("part-00002-of-00002.csv")),
        "-o",
        "-",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("parts of different runs"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A shard that fails leaves no part behind (on main, a failed task left a partial file that
/// looked valid).
#[test]
fn a_failed_shard_leaves_no_part() {
    let dir = tmp("fail");
    let p = dir.join("p");
    let o = exec(&["pick", "montecarlo", s(&dir.join("no-such.toml")), "--csv", "--shard", "1/2", "--parts", s(&p)]);
    assert_eq!(o.status.code(), Some(2));
    let left: Vec<_> = std::fs::read_dir(&p).map(|d| d.map(|e| e.unwrap().path()).collect()).unwrap_or_default();
    assert!(left.is_empty(), "{left:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

fn study(dir: &Path, name: &str, body: &str) -> PathBuf {
    let f = dir.join(name);
    std::fs::write(&f, body).unwrap();
    f
}

const MC: &str = "draws = 9\nseed = 3\n[settings]\nspeed_rpm = { dist = \"normal\", mean = 200, sd = 4 }\n\
                  play_mm = { dist = \"uniform\", min = 0, max = 10 }\n[limits]\nvelocity_m_s = { max = 19 }\n";

/// The report from the parts (a directory, standard input, the merged file) is the one-machine
/// report at N = 2, 3, 7 and 12 (> 9 draws); draws of another seed, spread or model are refused
/// (on main they were reported without a word).
#[test]
fn montecarlo_reduce_from_parts() {
    let dir = tmp("mc");
    let st = study(&dir, "mc.toml", MC);
    let st = s(&st);
    let direct = ok(&["pick", "montecarlo", st, "--json"]);
    let text = ok(&["pick", "montecarlo", st]);
    for n in [2, 3, 7, 12] {
        let p = dir.join(format!("p{n}"));
        parts(&["pick", "montecarlo", st, "--csv"], n, &p);
        assert_eq!(ok(&["pick", "montecarlo", st, "--json", "--from-draws", s(&p)]), direct, "N = {n}");
        assert_eq!(ok(&["pick", "montecarlo", st, "--from-draws", s(&p)]), text, "N = {n}");
    }
    let merged = dir.join("draws.csv");
    ok(&["merge", s(&dir.join("p3")), "-o", s(&merged)]);
    assert_eq!(ok(&["pick", "montecarlo", st, "--json", "--from-draws", s(&merged)]), direct);
    let piped = loomkin()
        .args(["pick", "montecarlo", st, "--json", "--from-draws", "-"])
        .write_stdin(std::fs::read(&merged).unwrap())
        .output()
        .unwrap();
    assert_eq!(piped.stdout, direct, "{}", String::from_utf8_lossy(&piped.stderr));
    // Limits only shape the report: other limits are allowed.
    let other_limit = study(&dir, "limit.toml", &MC.replace("max = 19", "max = 18"));
    ok(&["pick", "montecarlo", s(&other_limit), "--from-draws", s(&merged)]);
    for (name, body, key) in [
        ("seed.toml", MC.replace("seed = 3", "seed = 4"), "seed = 3, the study has seed = 4"),
        ("sd.toml", MC.replace("sd = 4", "sd = 5"), "inputs = "),
    ] {
        let f = study(&dir, name, &body);
        usage_error(&["pick", "montecarlo", s(&f), "--from-draws", s(&merged)], &[key, "another study's draws"]);
    }
    usage_error(
        &["pick", "montecarlo", st, "--from-draws", s(&merged), "--retardation-pct", "20"],
        &["model = ", "another study's draws"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The same for `dobby tolerance`.
#[test]
fn tolerance_reduce_from_parts() {
    let dir = tmp("tol");
    let st = study(
        &dir,
        "tol.toml",
        "draws = 5\nseed = 8\nstep_deg = 10\n[dimensions]\nl6_m = { dist = \"normal\", mean = 0.4, sd = 0.001 }\n",
    );
    let st = s(&st);
    let direct = ok(&["dobby", "tolerance", st, "--json"]);
    for n in [2, 3, 7] {
        let p = dir.join(format!("p{n}"));
        parts(&["dobby", "tolerance", st, "--csv"], n, &p);
        assert_eq!(ok(&["dobby", "tolerance", st, "--json", "--from-draws", s(&p)]), direct, "N = {n}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A per-draw table over 16 MiB (100,000 draws, ~20 MB) reduces to the one-machine report (on
/// main: "larger than the input limit of 16 MiB").
#[test]
fn montecarlo_reduce_past_16_mib() {
    let dir = tmp("big");
    let st = study(&dir, "big.toml", &MC.replace("draws = 9", "draws = 100000"));
    let st = s(&st);
    let draws = ok(&["pick", "montecarlo", st, "--csv"]);
    assert!(draws.len() > 16 << 20, "{} bytes", draws.len());
    let f = dir.join("draws.csv");
    std::fs::write(&f, &draws).unwrap();
    assert_eq!(
        ok(&["pick", "montecarlo", st, "--json", "--from-draws", s(&f)]),
        ok(&["pick", "montecarlo", st, "--json"])
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `shed pareto --from` the table's parts (or its CSV, or standard input) is the one-machine
/// front, byte for byte, at N = 2, 3, 7 and more shards than laws; the union of per-shard fronts
/// is not (on main there was no reduce).
#[test]
fn pareto_reduce_from_a_table() {
    let dir = tmp("pareto");
    let design = ["--design", "fig1", "--step", "0.05", "--motion-deg", "200:360:40"];
    let table: Vec<&str> = [&["shed", "table"][..], &design, &["--csv"]].concat();
    let csv = dir.join("t.csv");
    std::fs::write(&csv, ok(&table)).unwrap();
    for format in ["--csv", "--json", "--text"] {
        let f: &[&str] = if format == "--text" { &[] } else { &[format] };
        let want = ok(&[&["shed", "pareto"][..], &design, f].concat());
        assert_eq!(ok(&[&["shed", "pareto", "--from", s(&csv)][..], f].concat()), want, "{format}");
        for n in [2, 3, 7, 15] {
            let p = dir.join(format!("p{n}"));
            if !p.exists() {
                parts(&table, n, &p);
            }
            assert_eq!(ok(&[&["shed", "pareto", "--from", s(&p)][..], f].concat()), want, "{format} N = {n}");
        }
    }
    // Presets: the named laws keep their lengths.
    let presets = dir.join("presets.csv");
    std::fs::write(&presets, ok(&["shed", "table", "--csv"])).unwrap();
    assert_eq!(
        ok(&["shed", "pareto", "--from", s(&presets), "--json"]),
        ok(&["shed", "pareto", "--design", "presets", "--json"])
    );
    // A table made at another speed is refused.
    usage_error(&["shed", "pareto", "--from", s(&csv), "--speed-rpm", "400"], &["other conditions", "--speed-rpm"]);
    usage_error(&["shed", "pareto", "--from", s(&csv), "--step", "0.1"], &["--from", "--step"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The front of the shards' fronts, as docs/scale.md gives it (on main a part named alone was
/// refused as an incomplete run): each task's front from its own part file, then the front of
/// those small files — the one-machine front. A directory still stands for the whole run.
#[test]
fn pareto_front_of_the_shards_fronts() {
    let dir = tmp("fronts");
    let design = ["--design", "fig1", "--step", "0.05", "--motion-deg", "200:360:40"];
    let table: Vec<&str> = [&["shed", "table"][..], &design, &["--csv"]].concat();
    let want = ok(&[&["shed", "pareto"][..], &design, &["--csv"]].concat());
    for n in [2u32, 3, 7] {
        let p = dir.join(format!("p{n}"));
        parts(&table, n, &p);
        let fronts = dir.join(format!("fronts{n}"));
        std::fs::create_dir_all(&fronts).unwrap();
        let mut files = Vec::new();
        for i in 1..=n {
            let part = p.join(format!("part-{i:05}-of-{n:05}.csv"));
            let front = fronts.join(format!("{i}.csv"));
            std::fs::write(&front, ok(&["shed", "pareto", "--from", s(&part), "--csv"])).unwrap();
            files.push(front);
        }
        let args: Vec<&str> =
            [&["shed", "pareto", "--from"][..], &files.iter().map(|f| s(f)).collect::<Vec<_>>(), &["--csv"]].concat();
        assert_eq!(String::from_utf8(ok(&args)).unwrap(), String::from_utf8(want.clone()).unwrap(), "N = {n}");
        // One part missing from the directory: the run is incomplete, and said so.
        std::fs::remove_file(p.join(format!("part-{n:05}-of-{n:05}.csv.manifest.json"))).unwrap();
        std::fs::remove_file(p.join(format!("part-{n:05}-of-{n:05}.csv"))).unwrap();
        let out = exec(&["shed", "pareto", "--from", s(&p), "--csv"]);
        assert!(!out.status.success() && String::from_utf8_lossy(&out.stderr).contains("parts missing"), "N = {n}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A batch task may lift the per-run limit (on main no option did): the same run refused at the
/// interactive limit starts with `--budget` or `LOOMKIN_BUDGET` (read until its first line, then
/// the pipe is closed); a budget below the interactive one is a usage error.
#[test]
fn a_budget_lifts_the_per_run_limit() {
    use std::io::BufRead;
    let args = ["law", "sample", "cycloidal", "--points", "100000000", "--csv"];
    usage_error(&args, &["points = 100000000 needs about", "the limit is 1 GB and 1 min"]);
    usage_error(&[&["--budget", "500MB,1h"][..], &args].concat(), &["--budget", "memory ≥ 1 GB"]);
    let bin = assert_cmd::cargo::cargo_bin("loomkin");
    for (flag, env) in [(Some("64GB,2h"), None), (None, Some("64GB,2h"))] {
        let mut cmd = std::process::Command::new(&bin);
        if let Some(b) = flag {
            cmd.args(["--budget", b]);
        }
        if let Some(e) = env {
            cmd.env("LOOMKIN_BUDGET", e);
        }
        let mut child =
            cmd.args(args).stdout(std::process::Stdio::piped()).stderr(std::process::Stdio::piped()).spawn().unwrap();
        let mut first = String::new();
        std::io::BufReader::new(child.stdout.take().unwrap()).read_line(&mut first).unwrap();
        assert!(first.starts_with("x,"), "{first:?}");
        // The reader goes away: the run ends quietly.
        assert!(child.wait().unwrap().success());
    }
}

/// `want`, the one-machine report, with what summaries cannot merge (percentiles, histograms)
/// left out; `got` the report from the summaries: every number equal (counts, failing share,
/// extremes, limits) except `mean` and `sd`, equal to 1e-12 relative.
fn same_report_but_rounding(got: &serde_json::Value, want: &serde_json::Value, at: &str) {
    use serde_json::Value;
    match (got, want) {
        (Value::Object(g), Value::Object(w)) => {
            let keys = |m: &serde_json::Map<String, Value>| {
                m.keys().filter(|k| *k != "percentiles" && *k != "histogram").cloned().collect::<Vec<_>>()
            };
            assert_eq!(keys(g), keys(w), "{at}");
            assert!(!g.contains_key("percentiles") && !g.contains_key("histogram"), "{at}");
            for k in keys(w) {
                if k == "mean" || k == "sd" {
                    let (a, b) = (g[&k].as_f64().unwrap(), w[&k].as_f64().unwrap());
                    assert!(a == b || (a - b).abs() <= 1e-12 * a.abs().max(b.abs()), "{at}.{k}: {a} vs {b}");
                } else {
                    same_report_but_rounding(&g[&k], &w[&k], &format!("{at}.{k}"));
                }
            }
        }
        (Value::Array(g), Value::Array(w)) => {
            assert_eq!(g.len(), w.len(), "{at}");
            for (i, (a, b)) in g.iter().zip(w).enumerate() {
                same_report_but_rounding(a, b, &format!("{at}[{i}]"));
            }
        }
        _ => assert_eq!(got, want, "{at}"),
    }
}

/// `--summary` per shard and `--from-summaries`: the one-machine report without percentiles and
/// histograms at N = 2, 3, 7 and 12 (> 9 draws), the summaries in any order, in files or on
/// standard input; a missing shard, a shard twice, another seed or other limits are refused.
#[test]
fn montecarlo_reduce_from_summaries() {
    let dir = tmp("sum");
    let st = study(&dir, "mc.toml", MC);
    let st = s(&st);
    let json = |args: &[&str]| serde_json::from_slice::<serde_json::Value>(&ok(args)).unwrap();
    let direct = json(&["pick", "montecarlo", st, "--json"]);
    let summary = |n: u32, i: u32| ok(&["pick", "montecarlo", st, "--shard", &format!("{i}/{n}"), "--summary"]);
    for n in [1, 2, 3, 7, 12] {
        let files: Vec<PathBuf> = (1..=n)
            .rev()
            .map(|i| {
                let f = dir.join(format!("s{n}-{i}.json"));
                std::fs::write(&f, summary(n, i)).unwrap();
                f
            })
            .collect();
        let mut args = vec!["pick", "montecarlo", st, "--json", "--from-summaries"];
        args.extend(files.iter().map(|f| s(f)));
        same_report_but_rounding(&json(&args), &direct, &format!("N = {n}"));
        // Concatenated on standard input, and as text.
        let cat: Vec<u8> = files.iter().flat_map(|f| std::fs::read(f).unwrap()).collect();
        let piped =
            loomkin().args(["pick", "montecarlo", st, "--from-summaries", "-"]).write_stdin(cat).output().unwrap();
        let text = String::from_utf8(piped.stdout).unwrap();
        assert!(text.contains("percentiles and histograms need the draws"), "{text}");
    }
    let three: Vec<PathBuf> = (1..=3)
        .map(|i| {
            let f = dir.join(format!("t{i}.json"));
            std::fs::write(&f, summary(3, i)).unwrap();
            f
        })
        .collect();
    let reduce = |st: &str, files: &[&PathBuf]| {
        let mut a = vec!["pick", "montecarlo", st, "--from-summaries"];
        a.extend(files.iter().map(|f| s(f)));
        a.into_iter().map(String::from).collect::<Vec<_>>()
    };
    let refused = |args: Vec<String>, needles: &[&str]| {
        usage_error(&args.iter().map(String::as_str).collect::<Vec<_>>(), needles);
    };
    refused(reduce(st, &[&three[0], &three[2]]), &["are in no summary"]);
    refused(reduce(st, &[&three[0], &three[1], &three[2], &three[1]]), &["in two summaries"]);
    let seed = study(&dir, "seed.toml", &MC.replace("seed = 3", "seed = 4"));
    refused(reduce(s(&seed), &[&three[0], &three[1], &three[2]]), &["another study's summary"]);
    let limit = study(&dir, "limit.toml", &MC.replace("max = 19", "max = 18"));
    refused(reduce(s(&limit), &[&three[0], &three[1], &three[2]]), &["[limits] changed"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The same for `dobby tolerance`.
#[test]
fn tolerance_reduce_from_summaries() {
    let dir = tmp("tolsum");
    let st = study(
        &dir,
        "tol.toml",
        "draws = 5\nseed = 8\nstep_deg = 10\n[dimensions]\nl6_m = { dist = \"normal\", mean = 0.4, sd = 0.001 }\n",
    );
    let st = s(&st);
    let direct: serde_json::Value = serde_json::from_slice(&ok(&["dobby", "tolerance", st, "--json"])).unwrap();
    for n in [2, 7] {
        let cat: Vec<u8> = (1..=n)
            .flat_map(|i| ok(&["dobby", "tolerance", st, "--shard", &format!("{i}/{n}"), "--summary"]))
            .collect();
        let out = loomkin()
            .args(["dobby", "tolerance", st, "--json", "--from-summaries", "-"])
            .write_stdin(cat)
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        same_report_but_rounding(&serde_json::from_slice(&out.stdout).unwrap(), &direct, &format!("N = {n}"));
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
