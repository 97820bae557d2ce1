//! The API fuzzer: every route of a workbench on 127.0.0.1 (only) with mutated JSON bodies
//! (hostile numbers, wrong types, deleted and unknown keys, huge arrays, truncated text, junk after
//! the object, random bytes), wrong methods and odd paths.
//!
//! Every answer must be JSON, never 5xx (a 503 "busy" is retried as its `Retry-After` asks), carry
//! no `NaN` or `inf`, and a refusal must be `{"error", "field"}` with a one-line message; the
//! server must keep answering `GET /api/info`.
//!
//! Bounded for CI: `LOOMKIN_FUZZ_CASES` requests (default 150) within `LOOMKIN_FUZZ_SECONDS`
//! (default 60 s); `LOOMKIN_FUZZ_SEED` picks another sequence.

mod common;

use loomkin_web::{DobbyRequest, ServoDesign};
use serde_json::{Value, json};
use std::net::SocketAddr;
use std::time::{Duration, Instant};

/// Every route with a valid body (`None` for GET). Add new routes here.
fn routes() -> Vec<(&'static str, &'static str, Option<Value>)> {
    let design = serde_json::to_value(ServoDesign::default()).unwrap();
    vec![
        ("GET", "/api/info", None),
        ("GET", "/api/laws", None),
        ("GET", "/api/servo/default", None),
        ("GET", "/api/picking/settings", None),
        ("GET", "/api/dobby/default", None),
        ("GET", "/api/dynamics/example", None),
        ("GET", "/api/cam/examples", None),
        ("GET", "/api/loom/examples", None),
        ("GET", "/", None),
        ("GET", "/cam.js", None),
        ("GET", "/loom.js", None),
        ("GET", "/drive.js", None),
        ("GET", "/insertion.js", None),
        ("GET", "/eshed.js", None),
        (
            "POST",
            "/api/laws/compare",
            Some(
                json!({"laws": [{"name": "modified-trapezoid", "params": {"ramp": 0.1}}, {"name": "cycloidal"}], "samples": 50}),
            ),
        ),
        ("POST", "/api/servo/evaluate", Some(json!({"design": design, "samples": 50}))),
        ("POST", "/api/servo/optimize", Some(json!({"design": design, "objective": "peak"}))),
        ("POST", "/api/servo/export", Some(json!({"design": design, "format": "csv", "rows": 20}))),
        ("POST", "/api/servo/design/save", Some(json!({"design": design}))),
        ("POST", "/api/servo/design/load", Some(json!({"text": design.to_string(), "format": "json"}))),
        ("POST", "/api/picking/simulate", Some(json!({"samples": 50}))),
        (
            "POST",
            "/api/shed/law",
            Some(json!({"family": "trapezoid", "lengths": [0.25, 0.25, 0.5], "motion_deg": 300})),
        ),
        ("POST", "/api/shed/pareto", Some(json!({"family": "trapezoid", "step": 0.25, "motions_deg": [300]}))),
        ("POST", "/api/dobby/synthesize", Some(serde_json::to_value(DobbyRequest::default()).unwrap())),
        (
            "POST",
            "/api/dynamics/response",
            Some(json!({"speed_rpm": 600, "natural_hz": 54, "damping_ratio": 0.05, "samples": 50,
                        "sweep": {"from_rpm": 300, "to_rpm": 900, "points": 20}})),
        ),
        (
            "POST",
            "/api/dynamics/response",
            Some(json!({"speed_rpm": 600, "natural_hz": 54, "law": {"law": {"name": "cycloidal"}, "stroke_mm": 80,
                        "motion_deg": 120}})),
        ),
        (
            "POST",
            "/api/cam/profile",
            Some(json!({"design": {"follower": "translating", "roller_radius_mm": 15, "max_pressure_deg": 30,
                                   "offset_mm": 5}, "step_deg": 2})),
        ),
        (
            "POST",
            "/api/cam/profile",
            Some(json!({"source": {"law": {"law": {"name": "modified-sine"}, "stroke_deg": 15, "motion_deg": 120}},
                        "design": {"follower": "oscillating", "closure": "conjugate", "arm_mm": 160, "pivot_mm": 190,
                                   "roller_radius_mm": 10, "max_pressure_deg": 40}, "step_deg": 3})),
        ),
        (
            "POST",
            "/api/cam/profile",
            Some(json!({"source": {"shed": {"preset": "dobby", "stroke_mm": 100, "motion_deg": 280}},
                        "design": {"follower": "flat", "prime_radius_mm": 150}, "step_deg": 4})),
        ),
        (
            "POST",
            "/api/cam/dxf",
            Some(json!({"design": {"follower": "translating", "closure": "groove", "roller_radius_mm": 12,
                                   "prime_radius_mm": 130}, "chord_tol_mm": 0.05, "bore_mm": 30})),
        ),
        ("POST", "/api/cam/table", Some(json!({"format": "st", "step_deg": 5}))),
        (
            "POST",
            "/api/cam/table",
            Some(json!({"source": {"cycle_toml": loomkin_web::CAM_EXAMPLES[0].1}, "format": "twincat",
                        "tolerance": 0.001})),
        ),
        (
            "POST",
            "/api/loom/evaluate",
            Some(json!({"loom_toml": loomkin_web::LOOM_EXAMPLES[1].1,
                        "pattern": {"lift_plan": "1 2 3\n2 3 4\n3 4 1\n4 1 2\n"}, "picks": 2, "step_deg": 2})),
        ),
        (
            "POST",
            "/api/loom/stagger",
            Some(json!({"loom_toml": loomkin_web::LOOM_EXAMPLES[1].1,
                        "pattern": {"wif": loomkin_web::PATTERN_EXAMPLES[1].1}, "objective": "rms"})),
        ),
    ]
}

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

fn hostile_value(rng: &mut Rng) -> Value {
    let pick = rng.below(22);
    match pick {
        0 => json!(0),
        1 => json!(-1),
        2 => json!(1e308),
        3 => json!(-1e308),
        4 => json!(5e-324),
        5 => json!(1e-300),
        6 => json!(18_446_744_073_709_551_615u64),
        7 => json!(-9_223_372_036_854_775_807i64),
        8 => json!(""),
        9 => json!("nan"),
        10 => Value::Null,
        11 => json!([]),
        12 => json!({}),
        13 => json!(true),
        14 => json!(vec![0.5; 10_000]),
        15 => json!("x".repeat(100_000)),
        16 => json!(0.5),
        17 => json!(360),
        18 => json!(1e-9),
        19 => json!(1e9),
        20 => json!([[0, 0], [0.5, 0]]),
        _ => json!(-0.0),
    }
}

/// Paths to every leaf (and inner node) of a JSON value.
fn paths(v: &Value, here: Vec<String>, out: &mut Vec<Vec<String>>) {
    out.push(here.clone());
    match v {
        Value::Object(m) => m.iter().for_each(|(k, x)| paths(x, [here.clone(), vec![k.clone()]].concat(), out)),
        Value::Array(a) => {
            a.iter().enumerate().for_each(|(i, x)| paths(x, [here.clone(), vec![i.to_string()]].concat(), out))
        }
        _ => {}
    }
}

fn at_mut<'a>(v: &'a mut Value, path: &[String]) -> Option<&'a mut Value> {
    path.iter().try_fold(v, |cur, k| match cur {
        Value::Object(m) => m.get_mut(k),
        Value::Array(a) => k.parse::<usize>().ok().and_then(|i| a.get_mut(i)),
        _ => None,
    })
}

/// A mutated body: mostly structured changes of a valid body, sometimes broken text.
fn mutate(rng: &mut Rng, body: &Value) -> Vec<u8> {
    let mut v = body.clone();
    for _ in 0..1 + rng.below(3) {
        let mut all = Vec::new();
        paths(&v, vec![], &mut all);
        let p = all[rng.below(all.len())].clone();
        match rng.below(6) {
            0..=2 => {
                if let Some(slot) = at_mut(&mut v, &p) {
                    *slot = hostile_value(rng);
                }
            }
            3 => {
                if let Some((last, parent)) = p.split_last()
                    && let Some(Value::Object(m)) = at_mut(&mut v, parent)
                {
                    m.remove(last);
                }
            }
            4 => {
                if let Some(Value::Object(m)) = at_mut(&mut v, &p) {
                    m.insert("unknown_key".into(), json!(1));
                }
            }
            _ => {
                if let Some(Value::Array(a)) = at_mut(&mut v, &p)
                    && let Some(first) = a.first().cloned()
                {
                    a.extend(std::iter::repeat_n(first, 2000));
                }
            }
        }
    }
    let text = v.to_string().into_bytes();
    match rng.below(12) {
        0 => text[..rng.below(text.len() + 1)].to_vec(),
        1 => [text, b" junk".to_vec()].concat(),
        2 => (0..rng.below(512)).map(|_| rng.below(256) as u8).collect(),
        _ => text,
    }
}

fn env_usize(name: &str, default: usize) -> usize {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

fn non_finite_word(text: &str) -> Option<&str> {
    text.split(|c: char| !c.is_ascii_alphanumeric())
        .find(|w| matches!(w.to_ascii_lowercase().as_str(), "nan" | "inf" | "infinity"))
}

/// Sends one request, retrying a 503 after a short wait; returns what is wrong, if anything.
fn check(addr: SocketAddr, method: &str, path: &str, body: Option<&[u8]>) -> Option<String> {
    let t0 = Instant::now();
    let r = loop {
        match common::request(addr, method, path, body) {
            Ok(r) if r.status == 503 && t0.elapsed() < Duration::from_secs(60) => {
                std::thread::sleep(Duration::from_millis(50));
            }
            Ok(r) => break r,
            Err(e) => return Some(format!("no answer: {e}")),
        }
    };
    if r.status >= 500 {
        return Some(format!("status {}: {}", r.status, r.body));
    }
    if !path.starts_with("/api") {
        return None;
    }
    let Ok(v) = serde_json::from_str::<Value>(&r.body) else {
        return Some(format!("status {}: not JSON: {:.200}", r.status, r.body));
    };
    if r.status >= 400 {
        let (Some(e), Some(_)) = (v["error"].as_str(), v["field"].as_str()) else {
            return Some(format!("status {}: refusal without error/field: {:.200}", r.status, r.body));
        };
        if e.contains('\n') || e.chars().count() > 1000 {
            return Some(format!("status {}: error not one short line ({} chars)", r.status, e.chars().count()));
        }
        // A refusal may quote the value sent (`"nan"`); only an answer must be finite.
        return None;
    }
    non_finite_word(&r.body).map(|w| format!("status {}: '{w}' in the answer", r.status))
}

#[test]
fn every_route_survives_hostile_requests() {
    let addr = common::spawn_server();
    assert!(addr.ip().is_loopback());
    let cases = env_usize("LOOMKIN_FUZZ_CASES", 150);
    let budget = Duration::from_secs(env_usize("LOOMKIN_FUZZ_SECONDS", 60) as u64);
    let mut rng = Rng((env_usize("LOOMKIN_FUZZ_SEED", 0x5eed) as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    let routes = routes();
    let mut findings = Vec::new();
    let t0 = Instant::now();
    let mut sent = 0;
    // The valid bodies first: each must answer 200.
    for (method, path, body) in &routes {
        let text = body.as_ref().map(|b| b.to_string().into_bytes());
        let r = common::request(addr, method, path, text.as_deref()).unwrap();
        assert_eq!(r.status, 200, "{method} {path}: {}", r.body);
    }
    while sent < cases && t0.elapsed() < budget {
        let (method, path, body) = &routes[rng.below(routes.len())];
        let (m, p, b): (&str, String, Option<Vec<u8>>) = match (rng.below(20), body) {
            (0, _) => (if *method == "GET" { "POST" } else { "GET" }, path.to_string(), None),
            (1, _) => (*method, format!("{path}/../{}", ["x", "%00", "..", "api"][rng.below(4)]), None),
            (_, Some(b)) => (*method, path.to_string(), Some(mutate(&mut rng, b))),
            (_, None) => (*method, format!("{path}?{}", "a=1&".repeat(rng.below(100))), None),
        };
        if let Some(what) = check(addr, m, &p, b.as_deref()) {
            let shown =
                b.as_ref().map(|b| String::from_utf8_lossy(&b[..b.len().min(300)]).to_string()).unwrap_or_default();
            findings.push(format!("{what}\n    {m} {p} {shown}"));
        }
        sent += 1;
        if sent % 50 == 0 {
            let r = common::request(addr, "GET", "/api/info", None);
            assert!(r.is_ok_and(|r| r.status == 200), "the server stopped answering after {sent} requests");
        }
    }
    println!("API fuzz: {sent} requests in {:.1} s, {} findings", t0.elapsed().as_secs_f64(), findings.len());
    assert!(findings.is_empty(), "{} of {sent} requests misbehaved:\n{}", findings.len(), findings.join("\n"));
}
