//! The CLI fuzzer: every subcommand run with mutated numbers and strings, malformed and hostile
//! input files, a closed stdout pipe and a full disk (`/dev/full`).
//!
//! Every run must exit with 0, 1 or 2 (never a panic, a signal or a hang), print no `NaN` or `inf`,
//! and, when it fails, say so in one line of at most 1000 characters on stderr.
//!
//! Bounded for CI: `LOOMKIN_FUZZ_CASES` runs (default 120) within `LOOMKIN_FUZZ_SECONDS` (default
//! 60 s), each run at most 60 s. `LOOMKIN_FUZZ_SEED` picks another sequence. A large run:
//! `LOOMKIN_FUZZ_CASES=10000 LOOMKIN_FUZZ_SECONDS=3000 cargo test --release -p loomkin-cli --test fuzz -- --nocapture`.
//!
//! `LOOMKIN_FUZZ_BIN=target/release/loomkin` fuzzes that binary instead of this build's.
//!
//! To fuzz a new subcommand, add working invocations of it to [`SEEDS`].

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Working invocations, one per line of use; `{cycle}`, `{axis}`, `{drive}`, `{mechanism}`, `{cam}`,
/// `{spec}`, `{mc}`, `{tol}`, `{loom}`, `{wif}`, `{liftplan}` are valid input files and `{out}` a fresh output path
/// without extension.
const SEEDS: &[&str] = &[
    "law list",
    "law list --json",
    "law info cycloidal --json",
    "law info modified-trapezoid --param ramp=0.1",
    "law info piecewise --param segments=0.5:constant:1,0.5:constant:-1 --json",
    "law sample cycloidal --points 11 --csv",
    "law sample harmonic --points 5 --json",
    "law sample poly345 --points 7",
    "law plot cycloidal -o {out}.svg",
    "cycle {cycle}",
    "cycle {cycle} --speed-rpm 600 --json",
    "cycle {cycle} --points 50 --csv",
    "pick design",
    "pick design --json --velocity-m-s 17 --distance-cm 22",
    "pick design --law modified-sine",
    "pick simulate --json",
    "pick simulate --mechanism {mechanism} --json",
    "pick simulate --play-mm 5 --speed-rpm 220",
    "pick sweep speed --from 160 --to 240 --steps 3 --json",
    "pick sweep play --from 0 --to 10 --steps 3",
    "pick plot -o {out}.svg",
    "servo law --json",
    "servo law --def 0:0,0.1:0.5,0.3:1,0.5:0",
    "servo torque --drive {drive} --speed-rpm 600 --json",
    "servo torque --speed-rpm 600",
    "servo optimize --speed-rpm 600 --starts 1 --json",
    "servo export --format csv -o -",
    "servo export --format json -o {out}.json",
    "servo plot -o {out}.svg",
    "shed list",
    "shed list --json",
    "shed law basic --json",
    "shed law --spec {spec} --json",
    "shed law dobby --motion-deg 200",
    "shed table --design presets",
    "shed pareto --design presets --json",
    "shed best --window-deg 100",
    "shed plot basic -o {out}.svg",
    "dobby analyze --step-deg 5 --json",
    "dobby analyze --cam-file {cam} --step-deg 10",
    "dobby synthesize --step-deg 5",
    "dobby synthesize --step-deg 10 --json --roller-m 0.02",
    "dobby plot -o {out}.svg",
    "dobby sweep --step-deg 10 --json",
    "dyn response --natural-hz 80 --speed-rpm 300 {cycle} --json",
    "dyn response --natural-hz 80 --speed-rpm 300 --damping-ratio 0.05 {cycle}",
    "dyn sweep --speed-rpm 200:400:100 --natural-hz 80 {cycle} --json",
    "dyn spectrum cycloidal modified-trapezoid:ramp=0.1",
    "dyn compensate --natural-hz 80 -o {out}.csv {cycle}",
    "dyn two-mass {cycle} --drive-mass-kg 8 --drive-stiffness-n-m 3e6 --frame-mass-kg 20 --frame-stiffness-n-m 2.2e6 --json",
    "cam table --format csv -o {out}.csv {cycle}",
    "cam table --format xyvaj -o - --law cycloidal --stroke-mm 100 --motion-deg 120",
    "cam table --format st -o {out}.txt --law poly345 --stroke-mm 50 --motion-deg 90 --json",
    "cam table {cycle} --format st --tolerance 0.01 -o -",
    "cam table --law harmonic --stroke-deg 20 --motion-deg 90 --format twincat --tolerance 0.001 -o {out}.txt",
    "cam profile {cycle} --follower translating --max-pressure-deg 30 --roller-radius-mm 10 --json",
    "cam profile {cycle} --follower translating --prime-radius-mm 90 --offset-mm 10 --roller-radius-mm 12 --conjugate --dxf {out}.dxf",
    "cam profile {cycle} --follower flat --prime-radius-mm 150 --csv --step-deg 5",
    "cam profile --law cycloidal --stroke-deg 20 --motion-deg 120 --follower oscillating --arm-mm 100 --pivot-mm 120 --roller-radius-mm 8 --groove -o {out}.svg",
    "servo check {axis} --cycle {cycle} --json",
    "servo check {axis} --law cycloidal --stroke-mm 80 --motion-deg 150 --speed-rpm 600 -o {out}.svg",
    "servo export --format cycle -o {out}.toml",
    "shed law dobby --emit-cycle {out}.toml",
    "loom check {loom} --wif {wif}",
    "loom check {loom} --lift-plan {liftplan} --json",
    "loom check {loom}",
    "loom torque {loom} --wif {wif} --csv",
    "loom torque {loom} --wif {wif} --json --step-deg 2",
    "loom torque {loom} --lift-plan {liftplan} -o {out}.svg",
    "loom stagger {loom} --wif {wif} --json",
    "loom stagger {loom} --wif {wif} --objective rms -o {out}.toml",
    "loom timing {loom} --wif {wif} -o {out}.svg",
    "shed best --window-deg 120 --emit-cycle {out}.toml",
    "pick montecarlo {mc}",
    "pick montecarlo {mc} --json",
    "pick montecarlo {mc} --csv --shard 2/3",
    "pick montecarlo {mc} --json --shard 1/2",
    "pick sweep speed --from 160 --to 240 --steps 5 --csv --shard 2/3",
    "law sample cycloidal --points 11 --json --shard 3/4",
    "shed table --csv --shard 1/2",
    "dyn sweep --speed-rpm 200:400:100 --natural-hz 80 {cycle} --csv --shard 2/2",
    "dobby sweep --step-deg 10 --json --shard 2/7",
    "dobby tolerance {tol}",
    "dobby tolerance {tol} --json",
    "dobby tolerance {tol} --csv --shard 1/2",
    "dyn optimize {cycle} --speed-rpm 300 --band-pct 10 --natural-hz 54 --damping-ratio 0.05 -o {out}.toml",
    "dyn optimize {cycle} --speed-rpm 300 --natural-hz 54 --json",
    "servo law --points 7 --json",
    "servo law --sample 9 --csv",
    "servo optimize --speed-rpm 600,750 --starts 2 --objective rms --fixed-x",
    "cycle {cycle} --points 40 -o {out}.svg",
    "shed table --design grid --step 0.2 --motion-deg 240,300 --json",
    "shed table --design fig1 --step 0.1 --csv",
    "shed table --design table1 --motion-deg 200:300:50",
    "shed table --design grid --family lead-trapezoid --step 0.25 --json --shard 2/3",
    "shed pareto --design grid --step 0.2 --motion-deg 240:300:30 --json",
    "shed best --window-deg 120 --design grid --step 0.05 --max-jerk-m-s3 50000 --json",
    "pick sweep speed --from 160 --to 240 --points 4 --csv",
    "cam profile --law poly345 --stroke-mm 30 --motion-deg 100 --follower translating --max-pressure-deg 25 --csv",
    "loom torque {loom} --wif {wif} --step-deg 5 --csv",
];

const NUMBERS: &[&str] = &[
    "0",
    "-0",
    "-5",
    "-1",
    "1",
    "2",
    "1e-320",
    "5e-324",
    "1e-300",
    "1e-20",
    "1e-9",
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "1e999",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "infinity",
    "0x10",
    "1_000",
    "99999999999999999999",
    "3.",
    ".5",
    "+2",
    "1e",
    "",
    " 7",
    "7 ",
    "0.5",
    "360",
    "361",
    "-360",
    "1000000",
    "10000000",
    "4294967296",
    "18446744073709551616",
    // The ends of accepted ranges and their neighbouring doubles (issue 27's second fuzz pass).
    "0.001",
    "0.0009999999999999998",
    "100000",
    "100000.00000000001",
    "1e-12",
    "0.01",
    "10",
    "89.99999999999999",
    "90",
    "0.9999999999999999",
    "1000",
    "8000",
    "2.2250738585072014e-308",
];

const STRINGS: &[&str] = &[
    "",
    " ",
    "-",
    "--",
    "💥",
    "ä",
    "../../../../etc/passwd",
    "/dev/null",
    "%s%s%n",
    "{}",
    "a=b=c",
    "=",
    ",",
    ":",
    "cycloidal",
    "no-such-thing",
    "--json",
    "--help",
    "-o",
    "segments=",
    "ramp=",
    "ramp=nan",
];

/// The seed files and the hostile ones, in a private temporary directory.
struct Files {
    dir: PathBuf,
    valid: Vec<(&'static str, PathBuf)>,
    hostile: Vec<PathBuf>,
}

fn example(name: &str) -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(name)).unwrap()
}

fn files() -> Files {
    static CALLS: AtomicUsize = AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("loomkin-fuzz-{}-{call}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cycle =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/heald-frame-cycle.toml"))
            .unwrap();
    let axis =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/servo-axis.toml")).unwrap();
    let texts: Vec<(&str, String)> = vec![
        ("cycle", cycle),
        ("axis", axis),
        (
            "drive",
            "[drive]\nstroke_m = 0.1\nmotion_angle_deg = 180\nmoving_mass_kg = 1\npinion_radius_m = 0.02\n".into(),
        ),
        (
            "mechanism",
            "[mechanism]\nc1_m_per_n = 3.6098e-5\nc23_m_per_n = 2.9072e-6\nc4_m_per_n = 6.3222e-4\ntheta_kg_m2 = \
             0.181835\nshuttle_kg = 0.419725\nl_m = 0.74\nk_m = 0.23\nr_m = 0.083\nchecking_n = 49.0332\n\n[design]\n\
             velocity_m_s = 17.0\ndistance_m = 0.22\nfirst_stage_m = 0.086\nspeed_rpm = 200.0\n\n[required]\n\
             retardation_pct = 10.0\npath_m = 1.53\nfree_shed_deg = 120.0\n"
                .into(),
        ),
        (
            "cam",
            (0..72)
                .map(|i| {
                    let p = std::f64::consts::TAU * f64::from(i) / 72.0;
                    format!("{},{}\n", 0.366 * p.cos(), 0.577 * p.sin())
                })
                .collect::<String>(),
        ),
        ("spec", "motion_deg = 180\npositive = \"0.5:sine-ramp:0:1,0.5:cosine-ramp:1:0\"\n".into()),
        // The draw count in hexadecimal: the number mutations below would otherwise make it 10⁶.
        (
            "mc",
            "draws = 0x5\nseed = 3\n[settings]\nspeed_rpm = { dist = \"normal\", mean = 200, sd = 4 }\n\
             play_mm = { dist = \"uniform\", min = 0, max = 10 }\n[limits]\nvelocity_m_s = { max = 19 }\n"
                .into(),
        ),
        ("loom", example("shuttle-loom.toml")),
        ("wif", example("twill-2-2.wif")),
        ("liftplan", example("twill-3-1.txt")),
        (
            "tol",
            "draws = 0x3\nseed = 3\nstep_deg = 10\n[dimensions]\nl6_m = { dist = \"normal\", mean = 0.4, sd = 0.001 }\n\
             alpha_deg = { dist = \"uniform\", min = 46, max = 48 }\n[limits]\npressure_angle_deg = { max = 60 }\n"
                .into(),
        ),
    ];
    let mut valid = Vec::new();
    let mut hostile =
        vec![PathBuf::from("/dev/null"), PathBuf::from("/dev/zero"), dir.clone(), dir.join("missing.toml")];
    let write = |name: String, bytes: &[u8]| {
        let p = dir.join(name);
        std::fs::write(&p, bytes).unwrap();
        p
    };
    let mut rng = Rng(0x1234_5678);
    for (kind, text) in &texts {
        valid.push((*kind, write(format!("{kind}.txt"), text.as_bytes())));
        hostile.push(write(format!("{kind}-half.txt"), &text.as_bytes()[..text.len() / 2]));
        // Every number of the file replaced by a hostile one, a few variants each.
        for k in 0..4 {
            let mutated: String = text
                .split_inclusive(['\n', ',', ' ', '='])
                .map(|tok| {
                    let core = tok.trim_end_matches(['\n', ',', ' ', '=']);
                    if core.parse::<f64>().is_ok() && rng.below(3) == 0 {
                        format!("{}{}", NUMBERS[rng.below(NUMBERS.len())], &tok[core.len()..])
                    } else {
                        tok.to_string()
                    }
                })
                .collect();
            hostile.push(write(format!("{kind}-num{k}.txt"), mutated.as_bytes()));
        }
    }
    hostile.push(write("empty.txt".into(), b""));
    hostile.push(write("garbage.bin".into(), &(0..4096).map(|_| rng.below(256) as u8).collect::<Vec<_>>()));
    hostile.push(write("long-line.toml".into(), &[b'x'; 2_000_000]));
    hostile.push(write("long-key.toml".into(), format!("{} = 1\n", "k".repeat(1_000_000)).as_bytes()));
    hostile.push(write("deep.toml".into(), format!("a = {}1{}\n", "[".repeat(10_000), "]".repeat(10_000)).as_bytes()));
    hostile.push(write("many-points.csv".into(), "0.1,0.2\n".repeat(200_000).as_bytes()));
    Files { dir, valid, hostile }
}

/// xorshift64*, deterministic.
#[derive(Clone)]
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Where stdout goes.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Sink {
    Pipe,
    Closed,
    Full,
}

struct Case {
    args: Vec<String>,
    sink: Sink,
}

fn env_usize(name: &str, default: usize) -> usize {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

fn substitute(seed: &str, f: &Files, out: &Path) -> Vec<String> {
    seed.split_whitespace()
        .map(|t| {
            let mut t = t.to_string();
            for (kind, p) in &f.valid {
                t = t.replace(&format!("{{{kind}}}"), p.to_str().unwrap());
            }
            t.replace("{out}", out.to_str().unwrap())
        })
        .collect()
}

fn mutate(rng: &mut Rng, f: &Files, mut args: Vec<String>) -> Vec<String> {
    for _ in 0..1 + rng.below(3) {
        if args.len() < 2 {
            break;
        }
        // Never the first word (the command group): the fuzzer aims at the arguments.
        let i = 1 + rng.below(args.len() - 1);
        let is_file = f.valid.iter().any(|(_, p)| p.to_str() == Some(args[i].as_str()));
        match rng.below(10) {
            0..=3 if is_file => args[i] = f.hostile[rng.below(f.hostile.len())].to_str().unwrap().to_string(),
            0..=3 if args[i].contains('/') => args[i] = NUMBERS[rng.below(NUMBERS.len())].to_string(),
            0..=3 => {
                // A number inside the token (a flag value or a KEY=VALUE) made hostile.
                let tok = args[i].clone();
                let pos: Vec<usize> = tok
                    .char_indices()
                    .filter(|&(k, c)| {
                        c.is_ascii_digit() && (k == 0 || !tok[..k].ends_with(|d: char| d.is_ascii_digit()))
                    })
                    .map(|(k, _)| k)
                    .collect();
                if pos.is_empty() {
                    args[i] = NUMBERS[rng.below(NUMBERS.len())].to_string();
                } else {
                    let start = pos[rng.below(pos.len())];
                    let end = tok[start..]
                        .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == 'e' || c == '-'))
                        .map_or(tok.len(), |e| start + e);
                    let new = if rng.below(2) == 0 {
                        NUMBERS[rng.below(NUMBERS.len())].to_string()
                    } else {
                        let v: f64 = tok[start..end].parse().unwrap_or(1.0);
                        format!("{:e}", v * 10f64.powi(rng.below(641) as i32 - 320))
                    };
                    args[i] = format!("{}{}{}", &tok[..start], new, &tok[end..]);
                }
            }
            4 | 5 => args[i] = STRINGS[rng.below(STRINGS.len())].to_string(),
            6 => {
                args.remove(i);
            }
            7 => {
                let t = args[i].clone();
                args.insert(i, t);
            }
            8 => {
                let j = 1 + rng.below(args.len() - 1);
                args.swap(i, j);
            }
            _ => {
                let extra = ["--json", "--csv", "--help", "--points", "--step-deg", "--speed-rpm", "-o", "--param"];
                args.insert(i, extra[rng.below(extra.len())].to_string());
            }
        }
    }
    args
}

/// Words that mean a non-finite number in output text.
fn non_finite_word(text: &str) -> Option<String> {
    text.split(|c: char| !c.is_ascii_alphanumeric())
        .find(|w| matches!(w.to_ascii_lowercase().as_str(), "nan" | "inf" | "infinity"))
        .map(str::to_string)
}

/// Runs one case and returns what is wrong with it, if anything.
fn run(bin: &Path, case: &Case, out_files: &[PathBuf], cwd: &Path) -> Option<String> {
    let mut cmd = Command::new(bin);
    // A mutated `-o` may name any relative path: run inside the fuzzer's temporary directory.
    cmd.current_dir(cwd).args(&case.args).stdin(Stdio::null()).stderr(Stdio::piped()).env("RUST_BACKTRACE", "0");
    match case.sink {
        Sink::Pipe | Sink::Closed => cmd.stdout(Stdio::piped()),
        Sink::Full => cmd.stdout(std::fs::OpenOptions::new().write(true).open("/dev/full").unwrap()),
    };
    let mut child = cmd.spawn().unwrap();
    let stdout_reader = child.stdout.take().map(|mut s| {
        let closed = case.sink == Sink::Closed;
        std::thread::spawn(move || {
            let mut buf = Vec::new();
            if !closed {
                // Bounded: keep at most 64 MiB of output to check.
                let _ = (&mut s).take(64 << 20).read_to_end(&mut buf);
                let _ = std::io::copy(&mut s, &mut std::io::sink());
            }
            buf
        })
    });
    let mut stderr = child.stderr.take().unwrap();
    let err_reader = std::thread::spawn(move || {
        let mut buf = Vec::new();
        let _ = (&mut stderr).take(1 << 20).read_to_end(&mut buf);
        let _ = std::io::copy(&mut stderr, &mut std::io::sink());
        buf
    });
    let t0 = Instant::now();
    let status = loop {
        if let Some(st) = child.try_wait().unwrap() {
            break Some(st);
        }
        if t0.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    let stdout = stdout_reader.map(|h| h.join().unwrap()).unwrap_or_default();
    let stderr = String::from_utf8_lossy(&err_reader.join().unwrap()).to_string();
    let Some(status) = status else { return Some("ran over 60 s".into()) };
    let Some(code) = status.code() else { return Some(format!("killed by a signal ({status})")) };
    if !(0..=2).contains(&code) {
        return Some(format!("exit code {code}: {}", stderr.lines().next().unwrap_or("")));
    }
    if stderr.contains("panicked") || stderr.contains("RUST_BACKTRACE") {
        return Some(format!("panic: {}", stderr.lines().take(2).collect::<Vec<_>>().join(" | ")));
    }
    // Information lines ("wrote FILE", a summary) may precede the error: exactly one error line.
    let errors = stderr.lines().filter(|l| l.starts_with("loomkin: error")).count();
    let help = case.args.iter().any(|a| a == "--help" || a == "-h");
    if code != 0 && errors != 1 && !help {
        return Some(format!(
            "exit {code} with {errors} error lines: {}",
            stderr.lines().take(3).collect::<Vec<_>>().join(" | ")
        ));
    }
    if let Some(long) = stderr.lines().find(|l| l.chars().count() > 1000) {
        return Some(format!("a stderr line of {} characters", long.chars().count()));
    }
    if case.sink == Sink::Full && code == 2 && errors == 1 && stderr.contains("No space") {
        return Some(format!("a full disk is not a usage error: {stderr}"));
    }
    if let Some(w) = non_finite_word(&String::from_utf8_lossy(&stdout)) {
        return Some(format!("'{w}' on stdout"));
    }
    // A run failure that is the input's fault says so (exit 2 naming the option), never
    // "internal …" or a solver's failure (the output was a pipe, so no write failed).
    let failed_inside = stderr.contains("error: internal") || stderr.contains("numerical integration failed");
    if code == 1 && case.sink == Sink::Pipe && failed_inside {
        return Some(format!("exit 1 for an input: {}", stderr.trim()));
    }
    // On stderr a message may quote an argument or a file the user gave ('nan'); anything else
    // non-finite is a finding.
    let quoted = |w: &str| case.args.iter().any(|a| a.to_ascii_lowercase().contains(&w.to_ascii_lowercase()));
    let from_file = case.args.iter().any(|a| a.contains("-num"));
    if let Some(w) = non_finite_word(&stderr).filter(|w| !quoted(w) && !stderr.contains(&format!("`{w}`")))
        && !from_file
    {
        return Some(format!("'{w}' on stderr: {}", stderr.trim()));
    }
    for f in out_files {
        if let Ok(text) = std::fs::read_to_string(f)
            && let Some(w) = non_finite_word(&text)
        {
            return Some(format!("'{w}' in {}", f.display()));
        }
        let _ = std::fs::remove_file(f);
    }
    None
}

#[test]
fn every_seed_invocation_works() {
    let bin = PathBuf::from(env!("CARGO_BIN_EXE_loomkin"));
    let f = files();
    let mut failures = Vec::new();
    for (k, seed) in SEEDS.iter().enumerate() {
        let out = f.dir.join(format!("seed{k}"));
        let args = substitute(seed, &f, &out);
        let o = Command::new(&bin).current_dir(&f.dir).args(&args).output().unwrap();
        if !o.status.success() {
            failures.push(format!("{seed}: {}", String::from_utf8_lossy(&o.stderr).trim()));
        }
    }
    assert!(failures.is_empty(), "seed invocations that fail:\n{}", failures.join("\n"));
}

/// The binary fuzzed: this build's, or `LOOMKIN_FUZZ_BIN` (a release build for a large run).
fn fuzzed_binary() -> PathBuf {
    std::env::var_os("LOOMKIN_FUZZ_BIN").map_or_else(|| PathBuf::from(env!("CARGO_BIN_EXE_loomkin")), PathBuf::from)
}

#[test]
fn the_cli_survives_hostile_input() {
    let bin = fuzzed_binary();
    let cases = env_usize("LOOMKIN_FUZZ_CASES", 120);
    let budget = Duration::from_secs(env_usize("LOOMKIN_FUZZ_SECONDS", 60) as u64);
    let seed = env_usize("LOOMKIN_FUZZ_SEED", 0x5eed) as u64;
    let f = Arc::new(files());
    let (next, done) = (Arc::new(AtomicUsize::new(0)), Arc::new(AtomicUsize::new(0)));
    let findings = Arc::new(Mutex::new(Vec::<String>::new()));
    let t0 = Instant::now();
    let workers = std::thread::available_parallelism().map_or(2, |n| n.get()).min(8);
    let handles: Vec<_> = (0..workers)
        .map(|_| {
            let (f, next, done, findings, bin) = (f.clone(), next.clone(), done.clone(), findings.clone(), bin.clone());
            std::thread::spawn(move || {
                loop {
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    if k >= cases || t0.elapsed() > budget {
                        break;
                    }
                    let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15).wrapping_add(k as u64 * 2 + 1) | 1);
                    let s = SEEDS[rng.below(SEEDS.len())];
                    let out = f.dir.join(format!("case{k}"));
                    let args = mutate(&mut rng, &f, substitute(s, &f, &out));
                    let sink = match rng.below(10) {
                        0 => Sink::Closed,
                        1 => Sink::Full,
                        _ => Sink::Pipe,
                    };
                    let outs: Vec<PathBuf> =
                        ["svg", "json", "csv", "png", "txt"].iter().map(|e| out.with_extension(e)).collect();
                    if let Some(what) = run(&bin, &Case { args: args.clone(), sink }, &outs, &f.dir) {
                        findings
                            .lock()
                            .unwrap()
                            .push(format!("{what}\n    loomkin {} (stdout: {sink:?})", args.join(" ")));
                    }
                    done.fetch_add(1, Ordering::Relaxed);
                }
            })
        })
        .collect();
    for h in handles {
        h.join().unwrap();
    }
    let ran = done.load(Ordering::Relaxed);
    let findings = findings.lock().unwrap();
    println!("CLI fuzz: {ran} invocations in {:.1} s, {} findings", t0.elapsed().as_secs_f64(), findings.len());
    let _ = std::fs::remove_dir_all(&f.dir);
    assert!(findings.is_empty(), "{} of {ran} invocations misbehaved:\n{}", findings.len(), findings.join("\n"));
}

/// Every hostile file given to every command that reads a file: exit 2 with one short line (or 0
/// when the mutated file happens to be valid), never a hang, `/dev/zero` included.
#[test]
fn every_hostile_file_in_every_file_argument() {
    let bin = PathBuf::from(env!("CARGO_BIN_EXE_loomkin"));
    let f = files();
    let file_seeds: Vec<&str> = SEEDS
        .iter()
        .copied()
        .filter(|s| {
            s.contains("{cycle}")
                || s.contains("{drive}")
                || s.contains("{axis}")
                || s.contains("{mechanism}")
                || s.contains("{cam}")
                || s.contains("{spec}")
                || s.contains("{mc}")
                || s.contains("{tol}")
        })
        .collect();
    let mut findings = Vec::new();
    for seed in &file_seeds {
        for h in &f.hostile {
            let out = f.dir.join("hostile-out");
            let mut args = substitute(seed, &f, &out);
            for a in args.iter_mut() {
                if f.valid.iter().any(|(_, p)| p.to_str() == Some(a.as_str())) {
                    *a = h.to_str().unwrap().to_string();
                }
            }
            if let Some(what) = run(&bin, &Case { args: args.clone(), sink: Sink::Pipe }, &[], &f.dir) {
                findings.push(format!("{what}\n    loomkin {}", args.join(" ")));
            }
        }
    }
    let _ = std::fs::remove_dir_all(&f.dir);
    assert!(findings.is_empty(), "{}", findings.join("\n"));
}

/// What the fuzzer found, kept fixed: inputs inside their ranges whose results would overflow are
/// usage errors naming the input, in text and JSON alike.
#[test]
fn fuzz_findings_stay_fixed() {
    let bin = PathBuf::from(env!("CARGO_BIN_EXE_loomkin"));
    let cycle = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/heald-frame-cycle.toml");
    let cycle = cycle.to_str().unwrap();
    let dir = std::env::temp_dir().join(format!("loomkin-fuzz-fixed-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("x.csv");
    let out = out.to_str().unwrap();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["pick", "design", "--velocity-m-s", "1e-300"], "velocity_m_s"),
        (vec!["pick", "design", "--velocity-m-s", "1e-300", "--json"], "velocity_m_s"),
        (vec!["pick", "design", "--first-stage-cm", "1e-320"], "first_stage_m"),
        (
            vec![
                "cam",
                "table",
                "--format",
                "xyvaj",
                "-o",
                "-",
                "--law",
                "cycloidal",
                "--stroke-mm",
                "100",
                "--motion-deg",
                "1e-300",
            ],
            "motion_deg",
        ),
        (vec!["dyn", "compensate", "--natural-hz", "1e-320", "-o", out, cycle], "natural_hz"),
        (vec!["dyn", "sweep", "--speed-rpm", "200:400:100", "--natural-hz", "8e-174", cycle, "--json"], "natural_hz"),
        (vec!["cycle", "/dev/zero"], "16 MiB"),
        (vec!["servo", "export", "--format", "csv", "-o", ""], "--output is empty"),
        (vec!["dobby", "sweep", "--alpha-deg", "50"], "--alpha-deg"),
        (vec!["pick", "simulate", "--speed-rpm", "-5"], "speed"),
        (vec!["law", "info", "modified-trapezoid", "--param", "ramp=0.1", "--param", "ramp=0.2"], "given twice"),
        (vec!["cycle", cycle, "--speed-rpm", "5e-324"], "speed-rpm"),
        (vec!["shed", "best", "--window-deg", "175", "--max-jerk-m-s3", "1"], "--max-jerk-m-s3"),
    ];
    for (args, field) in cases {
        let o = Command::new(&bin).current_dir(&dir).args(&args).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        let lines: Vec<&str> = err.lines().filter(|l| l.starts_with("loomkin: error")).collect();
        assert!(lines.len() == 1 && lines[0].contains(field), "{args:?}: {err}");
        assert!(non_finite_word(&err).is_none(), "{args:?}: {err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
