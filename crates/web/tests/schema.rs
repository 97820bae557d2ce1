//! The request schemas `GET /api/schema` serves: every route's example validates against its
//! schema and is answered 200; the schemas' bounds are the library's ranges; a value the schema
//! refuses the API refuses, naming the field; and no range or default literal is left in the API's
//! source.

mod common;

use axum::http::StatusCode;
use loomkin_units::{Bound, Range, ShaftSpeed};
use loomkin_web::api_schema;
use serde_json::{Value, json};

async fn call(method: &str, path: &str, body: Option<String>) -> (StatusCode, Value) {
    let (status, _, text) = common::oneshot(method, path, body).await;
    (status, serde_json::from_str(&text).unwrap_or(Value::Null))
}

/// A JSON Schema 2020-12 validator for the keywords schemars writes; a keyword it does not know
/// fails the test (it never passes a value it has not checked).
struct Validator<'a> {
    root: &'a Value,
}

impl Validator<'_> {
    fn check(&self, s: &Value, v: &Value, at: &str) -> Result<(), String> {
        let Some(obj) = s.as_object() else {
            return match s {
                Value::Bool(true) => Ok(()),
                _ => Err(format!("{at}: schema false")),
            };
        };
        for (k, kw) in obj {
            match k.as_str() {
                "$schema" | "title" | "description" | "default" | "format" | "x-unit" | "$defs" | "examples" => {}
                "$ref" => {
                    let name = kw.as_str().and_then(|r| r.strip_prefix("#/$defs/")).expect("local $ref");
                    self.check(&self.root["$defs"][name], v, at)?;
                }
                "type" => {
                    let types: Vec<&str> = match kw {
                        Value::String(t) => vec![t.as_str()],
                        Value::Array(a) => a.iter().filter_map(Value::as_str).collect(),
                        _ => panic!("{at}: type {kw}"),
                    };
                    let ok = types.iter().any(|t| match *t {
                        "null" => v.is_null(),
                        "boolean" => v.is_boolean(),
                        "string" => v.is_string(),
                        "number" => v.is_number(),
                        "integer" => v.as_f64().is_some_and(|x| x.fract() == 0.0),
                        "object" => v.is_object(),
                        "array" => v.is_array(),
                        t => panic!("{at}: type {t}"),
                    });
                    if !ok {
                        return Err(format!("{at}: {v} is not of type {kw}"));
                    }
                }
                "minimum" | "maximum" | "exclusiveMinimum" | "exclusiveMaximum" => {
                    if let (Some(x), Some(b)) = (v.as_f64(), kw.as_f64()) {
                        let ok = match k.as_str() {
                            "minimum" => x >= b,
                            "maximum" => x <= b,
                            "exclusiveMinimum" => x > b,
                            _ => x < b,
                        };
                        if !ok {
                            return Err(format!("{at}: {x} fails {k} {b}"));
                        }
                    }
                }
                "enum" => {
                    if !kw.as_array().expect("enum").contains(v) {
                        return Err(format!("{at}: {v} not in {kw}"));
                    }
                }
                "const" => {
                    if kw != v {
                        return Err(format!("{at}: {v} is not {kw}"));
                    }
                }
                "anyOf" | "oneOf" => {
                    let n = kw.as_array().expect(k).iter().filter(|b| self.check(b, v, at).is_ok()).count();
                    if n == 0 || (k == "oneOf" && n > 1) {
                        return Err(format!("{at}: {v} matches {n} branches of {k}"));
                    }
                }
                "allOf" => {
                    for b in kw.as_array().expect("allOf") {
                        self.check(b, v, at)?;
                    }
                }
                "required" => {
                    if let Some(o) = v.as_object() {
                        for r in kw.as_array().expect("required").iter().filter_map(Value::as_str) {
                            if !o.contains_key(r) {
                                return Err(format!("{at}: `{r}` is required"));
                            }
                        }
                    }
                }
                "properties" => {
                    if let Some(o) = v.as_object() {
                        for (key, sub) in kw.as_object().expect("properties") {
                            if let Some(x) = o.get(key) {
                                self.check(sub, x, &format!("{at}.{key}"))?;
                            }
                        }
                    }
                }
                "additionalProperties" => {
                    if let Some(o) = v.as_object() {
                        let known = obj.get("properties").and_then(Value::as_object);
                        for (key, x) in o {
                            if !known.is_some_and(|p| p.contains_key(key)) {
                                self.check(kw, x, &format!("{at}.{key}"))?;
                            }
                        }
                    }
                }
                "items" => {
                    if let Some(a) = v.as_array() {
                        let skip = obj.get("prefixItems").and_then(Value::as_array).map_or(0, Vec::len);
                        for (i, x) in a.iter().enumerate().skip(skip) {
                            self.check(kw, x, &format!("{at}[{i}]"))?;
                        }
                    }
                }
                "prefixItems" => {
                    if let Some(a) = v.as_array() {
                        for (i, (sub, x)) in kw.as_array().expect("prefixItems").iter().zip(a).enumerate() {
                            self.check(sub, x, &format!("{at}[{i}]"))?;
                        }
                    }
                }
                "minItems" | "maxItems" => {
                    if let (Some(a), Some(n)) = (v.as_array(), kw.as_u64()) {
                        let ok = if k == "minItems" { a.len() as u64 >= n } else { a.len() as u64 <= n };
                        if !ok {
                            return Err(format!("{at}: {} items fail {k} {n}", a.len()));
                        }
                    }
                }
                other => panic!("{at}: the test's validator does not know the keyword `{other}`"),
            }
        }
        Ok(())
    }
}

/// A unit factor written as a number after `*` or `/` (`u * 1000`, `t / 1e3`): the page converts
/// with the schema's `units` (`convert(v, "m", "mm")`).
fn js_factor(line: &str) -> bool {
    const FACTORS: [&str; 9] = ["1000", "1e3", "1e-3", "0.001", "1e6", "1e-6", "60", "3600", "1e-9"];
    let b = line.as_bytes();
    (0..b.len())
        .filter(|&i| {
            matches!(b[i], b'*' | b'/')
                && b.get(i + 1).is_some_and(|c| *c != b'/' && *c != b'*')
                && (i == 0 || b[i - 1] != b'/')
        })
        .any(|i| {
            let rest = line[i + 1..].trim_start();
            FACTORS.iter().any(|f| {
                rest.strip_prefix(f).is_some_and(|after| {
                    !after.starts_with(|c: char| c.is_ascii_alphanumeric() || c == '.' || c == '_')
                })
            })
        })
}

/// A number where the page names a unit's scale: the last argument of `applyLimits(…)` or a
/// `scale:` option.
fn js_scale(line: &str) -> bool {
    let number = |t: &str| t.trim().trim_start_matches(['-', '+']).starts_with(|c: char| c.is_ascii_digit());
    let in_apply = line.match_indices("applyLimits(").any(|(k, _)| {
        let args = line[k + "applyLimits(".len()..].split(')').next().unwrap_or("");
        args.split(',').count() == 4 && args.rsplit(',').next().is_some_and(number)
    });
    let scale = line.match_indices("scale:").any(|(k, _)| number(&line[k + "scale:".len()..]));
    in_apply || scale
}

/// The keys of a request written in an `api("/route", { … })` call with a number literal that the
/// route's schema gives as its default: the request's default written a second time.
fn js_request_defaults(line: &str, schemas: &Value) -> Vec<String> {
    let mut out = Vec::new();
    for (k, _) in line.match_indices("api(\"/") {
        let rest = &line[k + 5..];
        let Some(end) = rest.find('"') else { continue };
        let route = format!("/api{}", &rest[..end]);
        let props = &schemas["routes"][route.as_str()]["request"]["properties"];
        let Some(props) = props.as_object() else { continue };
        for (key, p) in props {
            let Some(default) = p.get("default").and_then(Value::as_f64) else { continue };
            for (j, _) in rest.match_indices(&format!("{key}:")) {
                let before = rest[..j].chars().next_back();
                if before.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_') {
                    continue;
                }
                let value = rest[j + key.len() + 1..].trim_start();
                let lit: String =
                    value.chars().take_while(|c| c.is_ascii_digit() || matches!(c, '.' | 'e' | '-' | '+')).collect();
                if lit.parse::<f64>().is_ok_and(|v| v == default) {
                    out.push(format!("{route} {key}: {lit} (the schema's default)"));
                }
            }
        }
    }
    out
}

/// What a page script writes of its own: unit factors, scales and request defaults,
/// `file:line: why: text`.
fn page_offences(file: &str, js: &str, schemas: &Value) -> Vec<String> {
    let mut found = Vec::new();
    for (n, line) in js.lines().enumerate() {
        let code = line.trim_start();
        if code.starts_with("//") {
            continue;
        }
        // A trailing comment says what it likes (` // ` is never inside the page's strings).
        let line = line.split(" // ").next().unwrap_or("");
        let mut why = js_request_defaults(line, schemas);
        if js_factor(line) {
            why.push("a unit factor".into());
        }
        if js_scale(line) {
            why.push("a scale".into());
        }
        for w in why {
            found.push(format!("{file}:{}: {w}: {}", n + 1, code));
        }
    }
    found
}

/// Every script of the page as (file name, text): each `.js` under crates/web/assets, read from
/// the directory so that a new view is scanned without being listed here, and checked against what
/// the server serves.
fn page_scripts() -> Vec<(String, String)> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets");
    let mut out: Vec<(String, String)> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "js"))
        .map(|p| {
            let name = p.file_name().expect("a file name").to_string_lossy().into_owned();
            let text = std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            (name, text)
        })
        .collect();
    out.sort();
    out
}

/// The page's scripts (every .js under crates/web/assets: app.js and each view's) write no unit
/// factor, unit scale or request default of their own (issue 27): they convert with the schema's
/// `units` (from loomkin_units, `LoomkinApp.convert`) and leave a request's default to the request
/// type.
#[test]
fn no_unit_factor_or_request_default_in_the_page() {
    let s = schemas();
    let scripts = page_scripts();
    // The directory holds the scripts the server serves (so the scan reads what users get).
    let served = [
        ("app.js", loomkin_web::APP_JS),
        ("cam.js", loomkin_web::CAM_JS),
        ("charts.js", loomkin_web::CHARTS_JS),
        ("drive.js", loomkin_web::DRIVE_JS),
        ("eshed.js", loomkin_web::ESHED_JS),
        ("insertion.js", loomkin_web::INSERTION_JS),
        ("loom.js", loomkin_web::LOOM_JS),
    ];
    for (name, text) in served {
        assert!(scripts.iter().any(|(n, t)| n == name && t == text), "{name} is served but not scanned");
    }
    let found: Vec<String> = scripts.iter().flat_map(|(name, js)| page_offences(name, js, &s)).collect();
    assert!(
        found.is_empty(),
        "numbers the page should read from GET /api/schema (units, defaults):\n{}",
        found.join("\n")
    );
    // The scanner finds what the page wrote before (issue 27's lines) and passes what it writes now.
    for bad in [
        r#"  applyLimits(inputs.stroke, pareto, "conditions.stroke_m", 1000);"#,
        r#"  return { threshold: +i.threshold.value, stroke_m: +i.stroke.value / 1000, speed_rpm: +i.speed.value };"#,
        r#"  if (r.speeds.length) ch.rack.setSeries([{ label: "", x: r.speeds[0].angle_deg, y: r.speeds[0].u_m.map((u) => u * 1000) }]);"#,
        r#"        ["picking distance", `${num(o.distance_m * 1e3, 1)} mm`],"#,
        r#"  api("/servo/evaluate", { design: servo.design, samples: 1000 })"#,
        r#"  dobby.scene = new LoomkinCharts.Scene(charts, { id: "dobby-scene", unit: "mm", scale: 1000 });"#,
        r#"  const s = (performance.now() - j.t0) / 1000, budget = 3;"#,
        r#"      drv.acc = (drv.acc || 0) + (t - drv.last) / 1000 * PLAY_DEG_PER_S / h;"#,
        r#"      status(`servo shedding optimised in ${((performance.now() - t0) / 1000).toFixed(1)} s`);"#,
        r#"  cam.scene = new Scene(top, { id: "cam-scene", height: 420, unit: "mm", scale: 1 });"#,
    ] {
        assert_eq!(page_offences("test", bad, &s).len(), 1, "not found: {bad}");
    }
    for good in [
        r#"  applyLimits(inputs.roller, "/api/dobby/synthesize", "roller_m", "mm");"#,
        r#"  y: r.speeds[0].u_m.map((u) => convert(u, "m", "mm")) }"#,
        r#"  const r = await api("/laws/compare", { laws, samples: 801 });"#,
        r#"  const w = a / 2, h = b * 1000.5; // u * 1000 in a comment"#,
        r#"  // u * 1000"#,
    ] {
        assert_eq!(page_offences("test", good, &s), Vec::<String>::new(), "{good}");
    }
    // The units the page converts with are loomkin_units' factors.
    assert_eq!(s["units"]["mm"], json!({"of": "m", "factor": loomkin_units::mm_from_m(1.0)}));
    assert_eq!(s["units"]["ms"], json!({"of": "s", "factor": loomkin_units::ms_from_s(1.0)}));
}

fn validate(schema: &Value, v: &Value) -> Result<(), String> {
    Validator { root: schema }.check(schema, v, "")
}

fn schemas() -> Value {
    serde_json::to_value(api_schema()).expect("schema")
}

/// The schema of the request key `path` (`design.roller_radius_mm`) of a route.
fn at<'a>(schemas: &'a Value, route: &str, path: &str) -> &'a Value {
    common::schema_at(&schemas["routes"][route]["request"], path)
}

/// The range a number's schema states.
fn range_of(s: &Value) -> (Bound, Bound, String) {
    let side = |closed: &str, open: &str| match (s.get(closed), s.get(open)) {
        (Some(v), None) => Bound::Closed(v.as_f64().expect("bound")),
        (None, Some(v)) => Bound::Open(v.as_f64().expect("bound")),
        (None, None) => Bound::Unbounded,
        _ => panic!("both {closed} and {open}: {s}"),
    };
    (
        side("minimum", "exclusiveMinimum"),
        side("maximum", "exclusiveMaximum"),
        s["x-unit"].as_str().unwrap_or("").into(),
    )
}

fn assert_is(s: &Value, r: Range, what: &str) {
    assert_eq!(range_of(s), (r.lo, r.hi, r.unit.to_string()), "{what}: {s}");
}

/// Every route that takes a body has a schema and an example: the example validates and the route
/// answers it with 200. The routes are those docs/web.md lists with POST.
#[tokio::test]
async fn every_route_example_validates_and_is_answered() {
    let s = schemas();
    assert_eq!(s["dialect"], "https://json-schema.org/draft/2020-12/schema");
    let routes = s["routes"].as_object().expect("routes");
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/web.md")).expect("docs/web.md");
    let documented: Vec<&str> =
        doc.lines().filter_map(|l| l.strip_prefix("| `POST ")).filter_map(|l| l.split('`').next()).collect();
    let mut served: Vec<&str> = routes.keys().map(String::as_str).collect();
    let mut want = documented.clone();
    served.sort_unstable();
    want.sort_unstable();
    assert_eq!(served, want, "routes with a schema vs docs/web.md's POST routes");
    for (route, r) in routes {
        assert_eq!(r["method"], "POST");
        let schema = &r["request"];
        assert_eq!(schema["$schema"], "https://json-schema.org/draft/2020-12/schema", "{route}");
        validate(schema, &r["example"]).unwrap_or_else(|e| panic!("{route}: example refused by its schema: {e}"));
        let (status, answer) = call("POST", route, Some(r["example"].to_string())).await;
        assert_eq!(status, StatusCode::OK, "{route}: {answer}");
    }
    // The schema is served as built.
    let (status, served) = call("GET", "/api/schema", None).await;
    assert_eq!((status, served), (StatusCode::OK, s));
}

/// The bounds in the schemas are the library's ranges, for a sample of fields of five routes.
#[test]
fn schema_bounds_are_the_library_ranges() {
    let s = schemas();
    let dynamics = "/api/dynamics/response";
    assert_is(at(&s, dynamics, "speed_rpm"), ShaftSpeed::RANGE, "speed");
    assert_is(at(&s, dynamics, "natural_hz"), loomkin_dynamics::Follower::NATURAL_HZ.range, "f_n");
    assert_is(at(&s, dynamics, "damping_ratio"), loomkin_dynamics::Follower::DAMPING_RATIO.range, "ζ");
    assert_is(at(&s, dynamics, "sweep.from_rpm"), ShaftSpeed::RANGE, "sweep speed");
    let mech = loomkin_picking::Mechanism::paper_default();
    for setting in loomkin_picking::Setting::ALL {
        let key = setting.key();
        assert_is(at(&s, "/api/picking/simulate", &format!("settings.{key}")), setting.range(&mech), &key);
    }
    let play = at(&s, "/api/picking/simulate", "settings.play_mm");
    assert_eq!(play["maximum"].as_f64(), Some(mech.params().l_m * 1e3), "play up to the stick's length");
    assert_is(at(&s, "/api/shed/pareto", "conditions.speed_rpm"), ShaftSpeed::RANGE, "shed speed");
    assert_eq!(at(&s, "/api/shed/pareto", "conditions.speed_rpm")["default"], json!(ShaftSpeed::DEFAULT_RPM));
    assert_is(at(&s, "/api/cam/profile", "step_deg"), loomkin_cams::profile::SAMPLE_STEP_RANGE, "cam step");
    assert_is(at(&s, "/api/cam/table", "step_deg"), loomkin_cams::table::STEP_RANGE, "table step");
    assert_is(at(&s, "/api/loom/evaluate", "step_deg"), loomkin_loom::TIMING_STEP_RANGE, "timing step");
    assert_is(at(&s, "/api/dobby/synthesize", "step_deg"), loomkin_mech::STEP_DEG_RANGE, "dobby step");
    assert_is(at(&s, "/api/cam/profile", "design.max_pressure_deg"), loomkin_cams::profile::PRESSURE_RANGE, "pressure");
    // Defaults are the library's.
    assert_eq!(
        at(&s, "/api/cam/profile", "step_deg")["default"],
        json!(loomkin_cams::profile::DEFAULT_SAMPLE_STEP_DEG)
    );
    assert_eq!(at(&s, "/api/cam/dxf", "chord_tol_mm")["default"], json!(loomkin_cams::profile::DEFAULT_CHORD_TOL_MM));
    assert_eq!(at(&s, "/api/loom/evaluate", "step_deg")["default"], json!(loomkin_loom::DEFAULT_TIMING_STEP_DEG));
}

/// The upper end of a range closed above.
fn closed_hi(r: Range) -> f64 {
    match r.hi {
        Bound::Closed(v) => v,
        b => panic!("not closed above: {b:?}"),
    }
}

/// The largest double below `x` and the smallest above.
fn down(x: f64) -> f64 {
    x.next_down()
}
fn up(x: f64) -> f64 {
    x.next_up()
}

/// Just outside a bound, the schema refuses and so does the API, naming the field; at a closed
/// bound both accept. (The API's answer for the accepted value is not computed here: the schema
/// is checked, not the physics.)
#[tokio::test]
async fn the_api_refuses_what_the_schema_refuses() {
    let s = schemas();
    let cases: Vec<(&str, Value, &str, f64, f64)> = vec![
        // (route, request with the key to vary as null, key path, outside, inside)
        (
            "/api/dynamics/response",
            json!({"speed_rpm": 300, "natural_hz": 54, "samples": 10}),
            "speed_rpm",
            up(closed_hi(ShaftSpeed::RANGE)),
            closed_hi(ShaftSpeed::RANGE),
        ),
        (
            "/api/dynamics/response",
            json!({"speed_rpm": 300, "natural_hz": 54, "samples": 10}),
            "natural_hz",
            down(1e-3),
            1e-3,
        ),
        ("/api/cam/profile", json!({"design": {"roller_radius_mm": 15}, "step_deg": 1}), "step_deg", up(90.0), 45.0),
        ("/api/picking/simulate", json!({"settings": {"play_mm": 1}, "samples": 10}), "settings.play_mm", -1e-9, 0.0),
        ("/api/loom/evaluate", json!({"step_deg": 1}), "step_deg", down(0.1), 10.0),
    ];
    for (route, base, path, outside, inside) in cases {
        let schema = &s["routes"][route]["request"];
        let with = |x: f64| {
            let mut q = base.clone();
            let mut slot = &mut q;
            let keys: Vec<&str> = path.split('.').collect();
            for k in &keys[..keys.len() - 1] {
                slot = &mut slot[*k];
            }
            slot[keys[keys.len() - 1]] = json!(x);
            q
        };
        assert!(validate(schema, &with(outside)).is_err(), "{route} {path} = {outside} passes the schema");
        validate(schema, &with(inside)).unwrap_or_else(|e| panic!("{route} {path} = {inside}: {e}"));
        let (status, answer) = call("POST", route, Some(with(outside).to_string())).await;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{route} {path} = {outside}: {answer}");
        assert_eq!(answer["field"], path, "{answer}");
        assert!(answer["error"].as_str().unwrap_or("").contains("allowed"), "{answer}");
    }
}

/// The API's source holds no range or default literal: a `Range::…(` with a number in it, or a
/// `fn default_…` whose body is a number (its tests excepted).
#[test]
fn no_range_or_default_literal_in_the_api_source() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/src");
    let mut found = Vec::new();
    for entry in std::fs::read_dir(dir).expect("src") {
        let path = entry.expect("entry").path();
        let text = std::fs::read_to_string(&path).expect("source");
        let code = text.split("#[cfg(test)]").next().unwrap_or("");
        let lines: Vec<&str> = code.lines().collect();
        for (i, line) in lines.iter().enumerate() {
            let literal_range = line.find("Range::").is_some_and(|k| {
                let rest = &line[k..];
                rest.find('(').is_some_and(|p| {
                    let args = rest[p + 1..].split(')').next().unwrap_or("");
                    args.split(',').any(|a| a.trim().trim_start_matches('-').starts_with(|c: char| c.is_ascii_digit()))
                })
            });
            let literal_default = line.trim_start().starts_with("fn default_")
                && lines.get(i + 1).is_some_and(|n| n.trim().starts_with(|c: char| c.is_ascii_digit() || c == '-'));
            if literal_range || literal_default {
                found.push(format!("{}:{}: {}", path.display(), i + 1, line.trim()));
            }
        }
    }
    assert!(found.is_empty(), "range or default literals in crates/web/src:\n{}", found.join("\n"));
}
