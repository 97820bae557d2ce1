//! The range-end sweep (issue 27): every flag of every command that takes a library descriptor
//! (`loomkin_units::Field`, named in crates/cli/src/flag_fields.rs, as docs/reference/fields.md shows them) run at the ends of
//! its range and the neighbouring numbers, the other inputs at their defaults, on the example
//! files.
//!
//! At each closed end the end itself and the next number inside are accepted and the next number
//! outside is refused; at an open end the end is refused and the next number inside accepted (for
//! a count the neighbours are ±1, for a real number the neighbouring doubles). An accepted value
//! must run (exit 0), or be refused with exit 2 and one `error:` line where it does not fit the
//! other inputs or the run's limit; a refused one must exit 2 with one line naming the input and
//! its allowed range. No run may panic, exit 1, print `NaN`, `inf` or a negative zero, or print a
//! number of more than [`LONGEST_NUMBER`] digits, on stdout, stderr or in the files it writes.
//!
//! Each case runs in a child process: this test binary started again on [`child`], which runs the
//! CLI's [`crate::cli_main`] on the arguments it is given (the binary's own code, this build's,
//! in-process calls would share one stdout and one panic). Bounded for CI: the cases are run
//! `LOOMKIN_RANGE_JOBS` at a time (default 2), each killed after `LOOMKIN_RANGE_SECONDS`
//! (default 120 s: twice the interactive budget's minute, for a loaded CI machine; `loom servo
//! --tolerance 1e-9` takes 21 s of CPU and ran past 60 s once on the shared machine).

use crate::fields_doc::{CliInput, cli_inputs, descriptor_of};
use loomkin_units::{Bound, Field};
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// The variable that makes [`child`] run the CLI: the arguments, separated by `\u{1f}`.
const CHILD_ARGS: &str = "LOOMKIN_RANGE_CHILD_ARGS";

/// Longest number an output may print, characters: a double in full is 17 significant digits
/// with a sign, a point and an exponent, and a small one printed without an exponent
/// (`0.00000000000001499403799451058`) about 30; 310-digit numbers were a finding.
const LONGEST_NUMBER: usize = 40;

/// The required inputs of each command that has some, and small settings that keep a run short
/// (`--step-deg 5` for the dobby); `{ex}` is the examples directory, `{out}` a fresh output path
/// without extension. A flag swept is taken out of these first.
const BASES: &[(&str, &str)] = &[
    ("law info", "cycloidal"),
    ("law sample", "cycloidal --points 11"),
    ("law plot", "cycloidal -o {out}.svg"),
    ("cycle", "{ex}/heald-frame-cycle.toml"),
    ("pick sweep", "speed --from 160 --to 240 --points 3"),
    ("pick montecarlo", "{ex}/pick-montecarlo.toml"),
    ("pick plot", "-o {out}.svg"),
    ("servo optimize", "--starts 1"),
    ("servo export", "--format csv -o -"),
    ("servo plot", "-o {out}.svg"),
    ("servo check", "{ex}/servo-axis.toml --cycle {ex}/heald-frame-cycle.toml"),
    ("shed law", "basic"),
    ("shed best", "--window-deg 100"),
    ("shed window", "--carrier-speed-m-s 20 --reed-width-m 1.9"),
    ("shed plot", "basic -o {out}.svg"),
    ("dobby analyze", "--step-deg 5"),
    ("dobby synthesize", "--step-deg 5"),
    ("dobby plot", "-o {out}.svg"),
    ("dobby sweep", "--step-deg 10"),
    ("dobby tolerance", "{ex}/dobby-tolerance.toml"),
    ("cam table", "{ex}/heald-frame-cycle.toml --format csv -o {out}.csv"),
    ("cam profile", "{ex}/heald-frame-cycle.toml --follower translating"),
    ("dyn response", "{ex}/heald-frame-cycle.toml --natural-hz 80 --speed-rpm 300"),
    ("dyn sweep", "{ex}/heald-frame-cycle.toml --natural-hz 80 --speed-rpm 200:400:100"),
    ("dyn spectrum", "cycloidal"),
    ("dyn compensate", "{ex}/heald-frame-cycle.toml --natural-hz 80 -o {out}.csv"),
    ("dyn optimize", "{ex}/heald-frame-cycle.toml --natural-hz 54 --speed-rpm 300"),
    (
        "dyn two-mass",
        "{ex}/heald-frame-cycle.toml --drive-mass-kg 8 --drive-stiffness-n-m 3e6 --frame-mass-kg 20 \
         --frame-stiffness-n-m 2.2e6",
    ),
    ("loom check", "{ex}/shuttle-loom.toml --wif {ex}/twill-2-2.wif"),
    ("loom torque", "{ex}/shuttle-loom.toml --wif {ex}/twill-2-2.wif"),
    ("loom stagger", "{ex}/shuttle-loom.toml --wif {ex}/twill-2-2.wif"),
    ("loom timing", "{ex}/shuttle-loom.toml --wif {ex}/twill-2-2.wif -o {out}.svg"),
    ("loom servo", "{ex}/servo-shedding-loom.toml"),
    ("sley analyze", "{ex}/shuttle-loom.toml"),
    ("sley synthesize", "--reed-stroke-mm 80 --back-dwell-deg 60"),
    ("drive inertia", "{ex}/shuttle-loom.toml"),
    ("drive ripple", "{ex}/shuttle-loom.toml"),
    ("drive correct", "{ex}/shuttle-loom.toml --wif {ex}/twill-2-2.wif -o {out}"),
    ("insert budget", "{ex}/rapier-loom.toml"),
    ("insert rapier", "{ex}/rapier-loom.toml"),
    ("insert projectile", "{ex}/projectile-loom.toml"),
    ("insert airjet", "{ex}/airjet-loom.toml"),
];

/// Commands left out: `serve` listens until stopped; `merge` reads the parts of another run.
const SKIPPED: &[&str] = &["serve", "merge"];

/// Flags a command refuses whatever their value (`dobby sweep` sets α = θ itself).
const REFUSED_FLAGS: &[(&str, &str)] = &[("dobby sweep", "--alpha-deg"), ("dobby sweep", "--theta-deg")];

/// What a flag needs beside it to be read at all (a servo motor's gain needs `--motor servo`, a
/// preload a moving mass), added to the command's base invocation.
const NEEDS: &[(&str, &[&str], &str)] = &[
    ("cam profile", &["--chord-tol-mm", "--bore-mm"], "--dxf {out}.dxf"),
    ("dobby synthesize", &["--chord-tol-mm", "--bore-mm"], "--dxf {out}.dxf"),
    ("dyn response", &["--force-n", "--preload-n", "--return-spring-n-m"], "--mass-kg 1"),
    ("dyn sweep", &["--force-n", "--preload-n", "--return-spring-n-m"], "--mass-kg 1"),
    ("dyn compensate", &["--force-n", "--preload-n", "--return-spring-n-m"], "--mass-kg 1"),
    ("dyn optimize", &["--force-n", "--preload-n", "--return-spring-n-m"], "--mass-kg 1"),
    ("loom servo", &["--tolerance", "--step-deg"], "--emit-tables {out}"),
    ("loom servo", &["--min-clearance-mm"], "--optimize"),
    ("shed table", &["--motion-deg"], "--design grid --step 0.25"),
    ("drive ripple", &["--servo-gain-n-m-s", "--servo-integral-s", "--servo-torque-limit-n-m"], SERVO),
    ("drive correct", &["--servo-gain-n-m-s", "--servo-integral-s", "--servo-torque-limit-n-m"], SERVO),
    ("drive ripple", &["--synchronous-rpm", "--rated-rpm", "--rated-power-kw", "--gear-ratio"], "--motor induction"),
    ("drive correct", &["--synchronous-rpm", "--rated-rpm", "--rated-power-kw", "--gear-ratio"], "--motor induction"),
    ("drive ripple", &["--breakdown-ratio"], "--motor induction --motor-curve kloss"),
    ("drive correct", &["--breakdown-ratio"], "--motor induction --motor-curve kloss"),
    ("drive correct", &["--damping-ratio"], "--natural-hz 80"),
];

/// A servo motor on the main shaft with its required gain and torque limit.
const SERVO: &str = "--motor servo --servo-gain-n-m-s 100 --servo-torque-limit-n-m 1000";

/// Flags read only in another form of the command: a base invocation of that form instead.
const FORMS: &[(&str, &[&str], &str)] = &[
    (
        "cam profile",
        &["--arm-mm", "--pivot-mm", "--stroke-deg"],
        "--law cycloidal --stroke-deg 20 --motion-deg 120 --follower oscillating --arm-mm 100 --pivot-mm 120",
    ),
    (
        "cam profile",
        &["--motion-deg", "--stroke-mm"],
        "--law cycloidal --stroke-mm 30 --motion-deg 100 --follower translating",
    ),
    (
        "cam table",
        &["--motion-deg", "--stroke-mm"],
        "--law cycloidal --stroke-mm 100 --motion-deg 120 --format csv -o {out}.csv",
    ),
    ("pick sweep", &["--speed-rpm"], "play --from 0 --to 10 --points 3"),
    ("cam table", &["--stroke-deg"], "--law cycloidal --stroke-deg 20 --motion-deg 120 --format csv -o {out}.csv"),
    (
        "servo check",
        &["--stroke-deg"],
        "{ex}/servo-axis.toml --law cycloidal --stroke-deg 20 --motion-deg 150 --speed-rpm 600",
    ),
    (
        "servo check",
        &["--motion-deg", "--stroke-mm"],
        "{ex}/servo-axis.toml --law cycloidal --stroke-mm 80 --motion-deg 150 --speed-rpm 600",
    ),
    (
        "shed best",
        &[
            "--carrier-speed-m-s",
            "--reed-width-m",
            "--carrier-length-m",
            "--cloth-width-m",
            "--crossing-range-deg",
            "--shed-excess",
        ],
        "--carrier-speed-m-s 20 --reed-width-m 1.9",
    ),
];

/// The arguments of `command` with the example files and `out` put in, `flag` (and its value)
/// taken out.
fn base(command: &str, out: &Path, flag: Option<&str>) -> Vec<String> {
    let ex = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let listed = |list: &'static [(&str, &[&str], &str)]| {
        list.iter().filter(move |(c, flags, _)| *c == command && flag.is_some_and(|f| flags.contains(&f)))
    };
    let text = listed(FORMS)
        .map(|(_, _, b)| *b)
        .next()
        .unwrap_or_else(|| BASES.iter().find(|(c, _)| *c == command).map_or("", |(_, b)| b));
    let needs: Vec<&str> = listed(NEEDS).map(|(_, _, n)| *n).collect();
    let text = format!("{text} {}", needs.join(" "));
    let words: Vec<String> = text
        .split_whitespace()
        .map(|w| w.replace("{ex}", ex.to_str().unwrap_or_default()).replace("{out}", out.to_str().unwrap_or_default()))
        .collect();
    let mut args: Vec<String> = command.split_whitespace().map(str::to_string).collect();
    let mut k = 0;
    while k < words.len() {
        if Some(words[k].as_str()) == flag {
            k += 2;
            continue;
        }
        args.push(words[k].clone());
        k += 1;
    }
    args
}

/// A value and whether the range accepts it.
#[derive(Debug, Clone)]
struct Probe {
    text: String,
    inside: bool,
}

/// The numbers at and around each end of `f`'s range.
fn probes(f: &Field) -> Vec<Probe> {
    let text = |v: f64| {
        if f.count { format!("{v:.0}") } else { format!("{v:e}") }
    };
    let up = |v: f64| if f.count { v + 1.0 } else { v.next_up() };
    let down = |v: f64| if f.count { v - 1.0 } else { v.next_down() };
    let mut out = Vec::new();
    match f.range.lo {
        Bound::Closed(v) => {
            out.push(Probe { text: text(v), inside: true });
            out.push(Probe { text: text(up(v)), inside: true });
            out.push(Probe { text: text(down(v)), inside: false });
        }
        Bound::Open(v) => {
            out.push(Probe { text: text(v), inside: false });
            out.push(Probe { text: text(up(v)), inside: true });
        }
        Bound::Unbounded => {}
    }
    match f.range.hi {
        Bound::Closed(v) => {
            out.push(Probe { text: text(v), inside: true });
            out.push(Probe { text: text(down(v)), inside: true });
            out.push(Probe { text: text(up(v)), inside: false });
        }
        Bound::Open(v) => {
            out.push(Probe { text: text(v), inside: false });
            out.push(Probe { text: text(down(v)), inside: true });
        }
        Bound::Unbounded => {}
    }
    // A count's bound beyond what a count can hold (∞ as f64::MAX) is not a number to type.
    out.retain(|p| p.text.parse::<f64>().is_ok_and(f64::is_finite) && p.text.len() < 40);
    out
}

/// One run: the arguments, what the range says of the value, and the files it may write.
struct Case {
    args: Vec<String>,
    probe: Probe,
    field: &'static Field,
    flag: String,
    outs: Vec<PathBuf>,
}

/// What a run printed and how it ended.
struct Ran {
    code: Option<i32>,
    stdout: String,
    stderr: String,
    over_time: bool,
}

/// Runs the CLI on `args` in a child process of this test binary.
fn run_child(args: &[String], cwd: &Path, limit: Duration) -> Ran {
    let me = std::env::current_exe().expect("the test binary's path");
    let mut cmd = Command::new(me);
    cmd.args(["range_ends::child", "--exact", "--ignored", "--nocapture", "--test-threads=1", "-q"])
        .env(CHILD_ARGS, args.join("\u{1f}"))
        .env("RUST_BACKTRACE", "0")
        .current_dir(cwd)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let mut child = cmd.spawn().expect("the test binary starts");
    let mut out = child.stdout.take().expect("piped");
    let mut err = child.stderr.take().expect("piped");
    let out_reader = std::thread::spawn(move || {
        let mut buf = Vec::new();
        let _ = (&mut out).take(64 << 20).read_to_end(&mut buf);
        let _ = std::io::copy(&mut out, &mut std::io::sink());
        buf
    });
    let err_reader = std::thread::spawn(move || {
        let mut buf = Vec::new();
        let _ = (&mut err).take(1 << 20).read_to_end(&mut buf);
        let _ = std::io::copy(&mut err, &mut std::io::sink());
        buf
    });
    let t0 = Instant::now();
    let (status, over_time) = loop {
        if let Some(st) = child.try_wait().expect("wait") {
            break (Some(st), false);
        }
        if t0.elapsed() > limit {
            let _ = child.kill();
            break (child.wait().ok(), true);
        }
        std::thread::sleep(Duration::from_millis(3));
    };
    let stdout = String::from_utf8_lossy(&out_reader.join().unwrap_or_default()).into_owned();
    // The test harness's own first line.
    let stdout = stdout.strip_prefix("\nrunning 1 test\n").map_or(stdout.clone(), str::to_string);
    let stderr = String::from_utf8_lossy(&err_reader.join().unwrap_or_default()).into_owned();
    Ran { code: status.and_then(|s| s.code()), stdout, stderr, over_time }
}

/// The first word of `text` that is a non-finite number, a negative zero or a number longer than
/// [`LONGEST_NUMBER`] characters.
fn bad_number(text: &str) -> Option<String> {
    let mut words = text.split(|c: char| !(c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '+')));
    words.find_map(|w| {
        let lower = w.to_ascii_lowercase();
        if matches!(lower.trim_start_matches(['-', '+']), "nan" | "inf" | "infinity") {
            return Some(w.to_string());
        }
        // A number's digits: a run of digits and points, the exponent's digits apart.
        let mantissa = w.split(['e', 'E']).next().unwrap_or("");
        let digits = mantissa.trim_start_matches(['-', '+']).chars().filter(char::is_ascii_digit).count();
        let numeric = mantissa.trim_start_matches(['-', '+']).chars().all(|c| c.is_ascii_digit() || c == '.');
        if numeric && digits > 0 && w.len() > LONGEST_NUMBER {
            return Some(w.to_string());
        }
        (w.starts_with('-') && numeric && digits > 0 && w.parse::<f64>().is_ok_and(|v| v == 0.0)).then(|| w.to_string())
    })
}

/// What is wrong with one run, if anything.
fn judge(case: &Case, ran: &Ran) -> Option<String> {
    let Ran { code, stdout, stderr, over_time } = ran;
    if *over_time {
        return Some("ran over its time".into());
    }
    let Some(code) = *code else { return Some("killed by a signal".into()) };
    if stderr.contains("panicked") {
        return Some(format!("panic: {}", stderr.lines().take(2).collect::<Vec<_>>().join(" | ")));
    }
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("loomkin: error")).collect();
    match (code, case.probe.inside) {
        (0, true) => {}
        (0, false) => return Some("accepted a value outside the range".into()),
        (2, _) if errors.len() != 1 => return Some(format!("exit 2 with {} error lines: {stderr}", errors.len())),
        (2, true) => {}
        (2, false) => {
            let line = errors[0];
            let key = case.flag.trim_start_matches("--").replace('-', "_");
            let named = line.contains(&case.flag) || line.contains(&key);
            let bounds: Vec<String> = [case.field.range.lo, case.field.range.hi]
                .iter()
                .filter_map(|b| match b {
                    Bound::Closed(v) | Bound::Open(v) => Some(loomkin_units::compact(*v)),
                    Bound::Unbounded => None,
                })
                .collect();
            if !named || !bounds.iter().all(|b| line.contains(b.as_str())) {
                return Some(format!("the refusal names neither the input nor its range: {line}"));
            }
        }
        (c, _) => return Some(format!("exit {c}: {}", stderr.trim())),
    }
    if let Some(w) = bad_number(stdout) {
        return Some(format!("'{w}' on stdout"));
    }
    // The refusal quotes the value given.
    if let Some(w) = bad_number(stderr).filter(|w| *w != case.probe.text) {
        return Some(format!("'{w}' on stderr: {}", stderr.trim()));
    }
    for f in &case.outs {
        // A drawing's coordinates are pixels (`-0.00` there is a place, not a value shown): only
        // non-finite numbers count in an SVG.
        let svg = f.extension().is_some_and(|e| e == "svg");
        if let Ok(text) = std::fs::read_to_string(f)
            && let Some(w) = bad_number(&text).filter(|w| {
                !svg || w.parse::<f64>().is_ok_and(|v| !v.is_finite()) || w.to_ascii_lowercase().contains("nan")
            })
        {
            return Some(format!("'{w}' in the file it wrote ({})", f.display()));
        }
        let _ = std::fs::remove_file(f);
    }
    None
}

/// Every numeric flag with a descriptor, as (command, flag, descriptor).
fn swept_inputs() -> Vec<(CliInput, &'static Field)> {
    cli_inputs()
        .into_iter()
        .filter(|c| c.flag.starts_with("--") && !SKIPPED.contains(&c.command.as_str()))
        .filter(|c| !REFUSED_FLAGS.contains(&(c.command.as_str(), c.flag.as_str())))
        .filter_map(|c| descriptor_of(&c).map(|f| (c, f)))
        .collect()
}

fn env_number(name: &str, default: u64) -> u64 {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

/// The child process: runs the CLI on the arguments in [`CHILD_ARGS`] and exits with its code.
#[test]
#[ignore = "the child process of the range-end sweep: it runs only when the sweep starts it"]
fn child() {
    let Ok(args) = std::env::var(CHILD_ARGS) else { return };
    let args = std::iter::once("loomkin".to_string()).chain(args.split('\u{1f}').map(str::to_string));
    let code = crate::cli_main(args.map(std::ffi::OsString::from));
    std::process::exit(i32::from(code));
}

/// Every command's base invocation runs as it is (the sweep's starting point is valid).
#[test]
fn every_base_invocation_runs() {
    let dir = std::env::temp_dir().join(format!("loomkin-range-bases-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut commands: Vec<String> = swept_inputs().into_iter().map(|(c, _)| c.command).collect();
    commands.dedup();
    let mut failures = Vec::new();
    for command in &commands {
        let args = base(command, &dir.join("out"), None);
        let ran = run_child(&args, &dir, Duration::from_secs(60));
        if ran.code != Some(0) {
            failures.push(format!("loomkin {}: {:?} {}", args.join(" "), ran.code, ran.stderr.trim()));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(commands.len() > 30, "only {} commands found", commands.len());
    assert!(failures.is_empty(), "base invocations that fail:\n{}", failures.join("\n"));
}

/// Every flag at the ends of its range and their neighbours (see the module's text).
#[test]
fn every_flag_at_the_ends_of_its_range() {
    let dir = std::env::temp_dir().join(format!("loomkin-range-ends-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut cases = Vec::new();
    for (input, field) in swept_inputs() {
        for probe in probes(field) {
            let out = dir.join(format!("case{}", cases.len()));
            let mut args = base(&input.command, &out, Some(&input.flag));
            args.push(format!("{}={}", input.flag, probe.text));
            let outs =
                ["svg", "png", "csv", "json", "toml", "txt", "dxf"].iter().map(|e| out.with_extension(e)).collect();
            cases.push(Case { args, probe, field, flag: input.flag.clone(), outs });
        }
    }
    let limit = Duration::from_secs(env_number("LOOMKIN_RANGE_SECONDS", 120));
    let jobs = env_number("LOOMKIN_RANGE_JOBS", 2).max(1);
    let next = AtomicUsize::new(0);
    let findings = Mutex::new(Vec::new());
    let t0 = Instant::now();
    std::thread::scope(|s| {
        for _ in 0..jobs {
            s.spawn(|| {
                loop {
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    let Some(case) = cases.get(k) else { break };
                    let t = Instant::now();
                    let ran = run_child(&case.args, &dir, limit);
                    if std::env::var_os("LOOMKIN_RANGE_TIMES").is_some() {
                        println!("{:.2} s  loomkin {}", t.elapsed().as_secs_f64(), case.args.join(" "));
                    }
                    if let Some(what) = judge(case, &ran) {
                        findings.lock().unwrap().push(format!("{what}\n    loomkin {}", case.args.join(" ")));
                    }
                }
            });
        }
    });
    let findings = findings.into_inner().unwrap();
    println!("range ends: {} runs in {:.1} s, {} findings", cases.len(), t0.elapsed().as_secs_f64(), findings.len());
    let _ = std::fs::remove_dir_all(&dir);
    assert!(cases.len() > 1000, "only {} cases", cases.len());
    assert!(findings.is_empty(), "{} of {} runs misbehaved:\n{}", findings.len(), cases.len(), findings.join("\n"));
}

/// The checks of outputs find what they must and pass what they must.
#[test]
fn the_number_check_knows_bad_numbers() {
    let long = format!("0.{}5", "0".repeat(60));
    for bad in ["NaN", "x = -inf", "-0", "a -0.000 b", &long, "v=inf"] {
        assert!(bad_number(bad).is_some(), "{bad}");
    }
    for good in [
        "0",
        "-0.5",
        "1e-300",
        "frame-01.toml",
        "2026-01-01",
        "-1.2345678901234567e-308",
        "0.00000000000001499403799451058",
        "infinite",
    ] {
        assert!(bad_number(good).is_none(), "{good}");
    }
}
