//! Every endpoint of the JSON API, good and bad requests, through the router (`oneshot`) and
//! through a real loopback server that must keep serving after bad requests.

mod common;

use axum::body::{Body, to_bytes};
use axum::http::{Request, StatusCode, header};
use loomkin_web::{MAX_BODY_BYTES, MAX_SAMPLES, ServoDesign, router};
use serde_json::{Value, json};
use tower::ServiceExt;

use common::oneshot as call;

async fn post(path: &str, body: Value) -> (StatusCode, Value) {
    let (s, _, text) = call("POST", path, Some(body.to_string())).await;
    (s, serde_json::from_str(&text).unwrap_or_else(|e| panic!("{path}: not JSON ({e}): {text}")))
}

async fn get(path: &str) -> (StatusCode, Value) {
    let (s, _, text) = call("GET", path, None).await;
    (s, serde_json::from_str(&text).unwrap_or_else(|e| panic!("{path}: not JSON ({e}): {text}")))
}

/// A refusal: the status, a JSON `error` message, and `field` naming what was wrong.
fn assert_refused(res: &(StatusCode, Value), status: StatusCode, field: &str) {
    assert_eq!(res.0, status, "{}", res.1);
    assert_eq!(res.1["field"], field, "{}", res.1);
    let msg = res.1["error"].as_str().expect("error message");
    assert!(!msg.is_empty() && !msg.contains("NaN"), "{msg}");
}

fn design() -> Value {
    serde_json::to_value(ServoDesign::default()).expect("design")
}

#[tokio::test]
async fn page_and_assets_are_served_with_their_types() {
    for (path, ctype, needle) in [
        ("/", "text/html", "<script src=\"/app.js\">"),
        ("/app.js", "text/javascript", "/servo/evaluate"),
        ("/charts.js", "text/javascript", "class Chart"),
        ("/style.css", "text/css", ".chart"),
    ] {
        let (s, t, body) = call("GET", path, None).await;
        assert_eq!(s, StatusCode::OK, "{path}");
        assert!(t.starts_with(ctype), "{path}: {t}");
        assert!(body.contains(needle), "{path} lacks {needle}");
    }
    let (s, _, _) = call("GET", "/favicon.ico", None).await;
    assert_eq!(s, StatusCode::NO_CONTENT);
}

#[tokio::test]
async fn info_lists_views_and_limits() {
    let (s, v) = get("/api/info").await;
    assert_eq!(s, StatusCode::OK);
    assert_eq!(v["name"], "loomkin");
    assert_eq!(v["views"][0], "servo");
    assert_eq!(v["limits"]["max_samples"], MAX_SAMPLES);
    assert_eq!(v["limits"]["max_body_bytes"], MAX_BODY_BYTES);
}

#[tokio::test]
async fn unknown_endpoints_and_methods_are_refused() {
    let r = get("/api/nothing-here").await;
    assert_refused(&r, StatusCode::NOT_FOUND, "path");
    assert!(r.1["error"].as_str().unwrap().contains("GET /api/nothing-here"), "{}", r.1);
    assert_refused(&get("/no-such-page").await, StatusCode::NOT_FOUND, "path");
    // A wrong method answers 405 with a JSON body saying which method the endpoint takes.
    for (method, path, takes) in [
        ("GET", "/api/servo/evaluate", "POST"),
        ("POST", "/api/info", "GET"),
        ("POST", "/api/servo/default", "GET"),
        ("PUT", "/api/laws/compare", "GET or POST"),
        ("DELETE", "/api/picking/settings", "GET or POST"),
    ] {
        let (s, ctype, text) = call(method, path, Some("{}".into())).await;
        assert!(ctype.starts_with("application/json"), "{method} {path}: {ctype}");
        let v: Value = serde_json::from_str(&text).expect("JSON");
        assert_refused(&(s, v.clone()), StatusCode::METHOD_NOT_ALLOWED, "method");
        assert!(v["error"].as_str().unwrap().contains(takes), "{method} {path}: {v}");
    }
}

#[tokio::test]
async fn requests_from_other_pages_are_refused() {
    let body = json!({"laws": [{"name": "cycloidal"}], "samples": 3}).to_string();
    for (origin, status) in [
        ("http://127.0.0.1:8765", StatusCode::OK),
        ("http://localhost:8765", StatusCode::OK),
        ("https://evil.example", StatusCode::FORBIDDEN),
        ("http://127.0.0.1.evil.example", StatusCode::FORBIDDEN),
        ("null", StatusCode::FORBIDDEN),
    ] {
        let req = Request::builder()
            .method("POST")
            .uri("/api/laws/compare")
            .header(header::ORIGIN, origin)
            .header(header::CONTENT_TYPE, "text/plain")
            .body(Body::from(body.clone()))
            .expect("request");
        let res = router().oneshot(req).await.expect("infallible");
        let code = res.status();
        let bytes = to_bytes(res.into_body(), usize::MAX).await.expect("body");
        let v: Value = serde_json::from_slice(&bytes).expect("JSON");
        assert_eq!(code, status, "{origin}: {v}");
        if status == StatusCode::FORBIDDEN {
            assert_eq!(v["field"], "origin", "{v}");
        }
    }
}

#[tokio::test]
async fn catalogue_lists_every_law() {
    let (s, v) = get("/api/laws").await;
    assert_eq!(s, StatusCode::OK);
    let names: Vec<&str> = v["laws"].as_array().expect("laws").iter().filter_map(|l| l["name"].as_str()).collect();
    let expected: Vec<&str> = loomkin_laws::CATALOGUE.iter().map(|e| e.name).collect();
    assert_eq!(names, expected);
}

#[tokio::test]
async fn compare_overlays_laws_with_exact_metrics() {
    let (s, v) = post(
        "/api/laws/compare",
        json!({"laws": [{"name": "harmonic"}, {"name": "modified-trapezoid", "params": {"ramp": "0.125"}},
                         {"name": "piecewise", "params": {"segments": "0.5:constant:1,0.5:constant:-1"}}],
               "samples": 21}),
    )
    .await;
    assert_eq!(s, StatusCode::OK, "{v}");
    let laws = v["laws"].as_array().expect("laws");
    assert_eq!(laws.len(), 3);
    // Harmonic: Cv = π/2, Ca = π²/2 (closed form).
    let pi = std::f64::consts::PI;
    assert!((laws[0]["metrics"]["cv"].as_f64().unwrap() - pi / 2.0).abs() < 1e-12);
    assert!((laws[0]["metrics"]["ca"].as_f64().unwrap() - pi * pi / 2.0).abs() < 1e-9);
    // Piecewise ±1 acceleration is the constant-acceleration law: Ca = 4, Cv = 2.
    assert!((laws[2]["metrics"]["ca"].as_f64().unwrap() - 4.0).abs() < 1e-12);
    assert_eq!(laws[1]["samples"]["x"].as_array().unwrap().len(), 21);
}

#[tokio::test]
async fn compare_refuses_bad_requests_naming_the_field() {
    let huge = json!({"laws": [{"name": "cycloidal"}], "samples": 1_000_000_000u64});
    assert_refused(&post("/api/laws/compare", huge).await, StatusCode::UNPROCESSABLE_ENTITY, "samples");
    let neg = json!({"laws": [{"name": "cycloidal"}], "samples": -3});
    assert_refused(&post("/api/laws/compare", neg).await, StatusCode::BAD_REQUEST, "samples");
    let typo = json!({"laws": [{"name": 7}]});
    assert_refused(&post("/api/laws/compare", typo).await, StatusCode::BAD_REQUEST, "laws[0].name");
    let unknown = json!({"laws": [{"name": "parabolic-ish"}]});
    assert_refused(&post("/api/laws/compare", unknown).await, StatusCode::UNPROCESSABLE_ENTITY, "laws[0]");
    let ramp = json!({"laws": [{"name": "modified-trapezoid", "params": {"ramp": 0.9}}]});
    let r = post("/api/laws/compare", ramp).await;
    assert_refused(&r, StatusCode::UNPROCESSABLE_ENTITY, "laws[0]");
    assert!(r.1["error"].as_str().unwrap().contains("ramp"));
    let many = json!({"laws": vec![json!({"name": "cycloidal"}); 9]});
    assert_refused(&post("/api/laws/compare", many).await, StatusCode::UNPROCESSABLE_ENTITY, "laws");
    let extra = json!({"laws": [{"name": "cycloidal"}], "sampels": 5});
    assert_refused(&post("/api/laws/compare", extra).await, StatusCode::BAD_REQUEST, "sampels");
    let (s, _, text) = call("POST", "/api/laws/compare", Some("not JSON at all".into())).await;
    assert_eq!(s, StatusCode::BAD_REQUEST);
    assert!(text.contains("\"field\":\"body\""), "{text}");
}

#[tokio::test]
async fn default_design_evaluates() {
    let (s, v) = get("/api/servo/default").await;
    assert_eq!(s, StatusCode::OK);
    assert_eq!(v["design"], design());
    let (s, r) = post("/api/servo/evaluate", json!({"design": v["design"], "samples": 1000})).await;
    assert_eq!(s, StatusCode::OK, "{r}");
    let speeds = r["speeds"].as_array().expect("speeds");
    assert_eq!(speeds.len(), 2);
    for key in ["speed_rpm", "peak_torque_nm", "rms_torque_nm", "peak_power_w"] {
        assert!(speeds[0][key].as_f64().is_some_and(f64::is_finite), "{key}");
    }
    assert_eq!(speeds[1]["torque_nm"].as_array().unwrap().len(), 1000);
    // Peak torque grows with the square of the speed for an inertia-dominated drive; here the
    // damping term is small, so the ratio lies just below (750/600)² = 1.5625.
    let ratio = speeds[1]["peak_torque_nm"].as_f64().unwrap() / speeds[0]["peak_torque_nm"].as_f64().unwrap();
    assert!(ratio > 1.45 && ratio < 1.5625, "{ratio}");
}

#[tokio::test]
async fn evaluate_refuses_bad_designs_naming_the_field() {
    let mut d = design();
    d["drive"]["stroke_m"] = json!(-0.1);
    assert_refused(
        &post("/api/servo/evaluate", json!({"design": d})).await,
        StatusCode::UNPROCESSABLE_ENTITY,
        "design.drive.stroke_m",
    );
    let mut d = design();
    d["drive"]["stroke_m"] = json!("eighty");
    assert_refused(
        &post("/api/servo/evaluate", json!({"design": d})).await,
        StatusCode::BAD_REQUEST,
        "design.drive.stroke_m",
    );
    let mut d = design();
    d["points"][3] = json!([0.05, 0.5]);
    assert_refused(
        &post("/api/servo/evaluate", json!({"design": d})).await,
        StatusCode::UNPROCESSABLE_ENTITY,
        "design.points[3]",
    );
    let mut d = design();
    d["points"][2][1] = json!(7.0);
    assert_refused(
        &post("/api/servo/evaluate", json!({"design": d})).await,
        StatusCode::UNPROCESSABLE_ENTITY,
        "design.points[2][1]",
    );
    let mut d = design();
    d["speeds_rpm"] = json!([600, 1e9]);
    assert_refused(
        &post("/api/servo/evaluate", json!({"design": d})).await,
        StatusCode::UNPROCESSABLE_ENTITY,
        "design.speeds_rpm[1]",
    );
    let mut d = design();
    d["speeds_rpm"] = json!([]);
    assert_refused(
        &post("/api/servo/evaluate", json!({"design": d})).await,
        StatusCode::UNPROCESSABLE_ENTITY,
        "design.speeds_rpm",
    );
    let mut d = design();
    d["points"] = json!(vec![[0.0, 0.0]; 100]);
    assert_refused(
        &post("/api/servo/evaluate", json!({"design": d})).await,
        StatusCode::UNPROCESSABLE_ENTITY,
        "design.points",
    );
    let huge = json!({"design": design(), "samples": MAX_SAMPLES + 1});
    assert_refused(&post("/api/servo/evaluate", huge).await, StatusCode::UNPROCESSABLE_ENTITY, "samples");
    let mut d = design();
    d["drive"]["motion_angle_deg"] = json!(300.0);
    assert_refused(
        &post("/api/servo/evaluate", json!({"design": d})).await,
        StatusCode::UNPROCESSABLE_ENTITY,
        "design.drive.motion_angle_deg",
    );
    let mut d = design();
    d["end"] = json!("sideways");
    assert_refused(&post("/api/servo/evaluate", json!({"design": d})).await, StatusCode::BAD_REQUEST, "design.end");
    // A huge value is named and written short, not in 301 digits.
    let mut d = design();
    d["drive"]["moving_mass_kg"] = json!(-1e300);
    let r = post("/api/servo/evaluate", json!({"design": d})).await;
    assert_refused(&r, StatusCode::UNPROCESSABLE_ENTITY, "design.drive.moving_mass_kg");
    let msg = r.1["error"].as_str().unwrap();
    assert!(msg.contains("-1e300") && msg.len() < 160, "{msg}");
    // Not-a-number spellings JSON does not have: NaN, Infinity, an overflowing literal.
    let text = json!({"design": design()}).to_string();
    for bad in ["NaN", "Infinity", "-Infinity", "1e999", "\"inf\"", "null"] {
        let body = text.replacen("\"stroke_m\":0.08", &format!("\"stroke_m\":{bad}"), 1);
        assert_ne!(body, text);
        let (s, _, answer) = call("POST", "/api/servo/evaluate", Some(body)).await;
        let v: Value = serde_json::from_str(&answer).expect("JSON refusal");
        assert_refused(&(s, v), StatusCode::BAD_REQUEST, "design.drive.stroke_m");
    }
}

#[tokio::test]
async fn optimise_lowers_the_peak_torque() {
    let (s, r) = post("/api/servo/optimize", json!({"design": design(), "objective": "peak"})).await;
    assert_eq!(s, StatusCode::OK, "{r}");
    for k in 0..2 {
        let before = r["before"][k]["peak_torque_nm"].as_f64().unwrap();
        let after = r["after"][k]["peak_torque_nm"].as_f64().unwrap();
        assert!(after <= before, "speed {k}: {after} > {before}");
    }
    // The worst speed (750 1/min) improves measurably.
    assert!(
        r["after"][1]["peak_torque_nm"].as_f64().unwrap() < 0.99 * r["before"][1]["peak_torque_nm"].as_f64().unwrap()
    );
    assert_eq!(r["def_points"].as_array().unwrap().len(), 7);
    // The answer's points evaluate to the reported torque.
    let mut d = design();
    d["points"] = r["def_points"].clone();
    let (_, e) = post("/api/servo/evaluate", json!({"design": d, "samples": 10})).await;
    assert_eq!(e["speeds"][1]["peak_torque_nm"], r["after"][1]["peak_torque_nm"]);
    assert_refused(
        &post("/api/servo/optimize", json!({"design": design(), "objective": "cheapest"})).await,
        StatusCode::BAD_REQUEST,
        "objective",
    );
}

#[tokio::test]
async fn export_every_format() {
    for (format, name, needle) in [
        ("coeffs", "servo-coefficients.txt", "# columns: j x_start x_end"),
        ("json", "servo-coefficients.json", "\"intervals\""),
        ("csv", "servo-cam.csv", "master_deg,slave_mm,slave_v_mm_per_deg"),
        ("xyva", "servo-cam-xyva.csv", "X,Y,V,A"),
        ("poly5", "servo-cam-poly5.csv", "master_start_deg"),
    ] {
        let (s, r) = post("/api/servo/export", json!({"design": design(), "format": format, "rows": 91})).await;
        assert_eq!(s, StatusCode::OK, "{format}: {r}");
        assert_eq!(r["filename"], name);
        assert!(r["text"].as_str().unwrap().contains(needle), "{format}");
    }
    let (_, r) = post("/api/servo/export", json!({"design": design(), "format": "csv", "rows": 91})).await;
    // 91 rows over 0…360°: a 4° step from each joint of the law, and a point on every joint (the
    // cam-table engine of `loomkin cam table`): a header and at least 91 data lines.
    let text = r["text"].as_str().unwrap();
    assert!(text.lines().count() > 92, "{text}");
    let note = r["note"].as_str().unwrap();
    assert!(note.starts_with(&format!("{} rows, step 4.0000°", text.lines().count() - 1)), "{note}");
    assert_eq!(r["interpolation"].as_array().unwrap().len(), 3);
    // Both front ends' names: `interpolation[].mode` (this API's) and
    // `reinterpolation[].interpolation` (`loomkin servo export --json`'s), the same rows.
    assert_eq!(r["reinterpolation"], r["interpolation"]);
    let modes: Vec<&str> = r["interpolation"].as_array().unwrap().iter().map(|e| e["mode"].as_str().unwrap()).collect();
    assert_eq!(modes, ["linear", "cubic-spline", "quintic-hermite"]);
    for row in r["interpolation"].as_array().unwrap() {
        assert_eq!(row["interpolation"], row["mode"], "{row}");
        assert!(row["max_position_error_m"].as_f64().unwrap() >= 0.0, "{row}");
    }
    assert_refused(
        &post("/api/servo/export", json!({"design": design(), "format": "csv", "rows": 100_000_000})).await,
        StatusCode::UNPROCESSABLE_ENTITY,
        "rows",
    );
    assert_refused(
        &post("/api/servo/export", json!({"design": design(), "format": "pdf"})).await,
        StatusCode::BAD_REQUEST,
        "format",
    );
}

#[tokio::test]
async fn save_and_load_round_trip_without_loss() {
    let mut d = design();
    d["points"][1] = json!([0.0712345678901234, 0.4187654321]);
    d["drive"]["return_angle_deg"] = json!(120.5);
    d["end"] = json!("clamped");
    for format in ["json", "toml"] {
        let (s, saved) = post("/api/servo/design/save", json!({"design": d, "format": format})).await;
        assert_eq!(s, StatusCode::OK, "{saved}");
        assert!(saved["filename"].as_str().unwrap().ends_with(format));
        let (s, loaded) = post("/api/servo/design/load", json!({"text": saved["text"], "format": "auto"})).await;
        assert_eq!(s, StatusCode::OK, "{loaded}");
        assert_eq!(loaded["design"], d, "{format}");
    }
    let bad = "points = [[0.0, 0.0], [0.1, 0.5], [0.3, 1.0], [0.5, 0.0]]\nspeeds_rpm = [600.0]\n[drive]\nstroke_m = 0.08\n\
               motion_angle_deg = 150.0\npinion_radius_m = 0.0\n";
    assert_refused(
        &post("/api/servo/design/load", json!({"text": bad, "format": "toml"})).await,
        StatusCode::UNPROCESSABLE_ENTITY,
        "drive.pinion_radius_m",
    );
    assert_refused(
        &post("/api/servo/design/load", json!({"text": "{oops", "format": "json"})).await,
        StatusCode::BAD_REQUEST,
        "text",
    );
    assert_refused(
        &post("/api/servo/design/load", json!({"text": "points = \"many\"", "format": "toml"})).await,
        StatusCode::BAD_REQUEST,
        "points",
    );
    let invalid =
        post("/api/servo/design/save", json!({"design": {"points": [], "speeds_rpm": [600], "drive": d["drive"]}}));
    assert_refused(&invalid.await, StatusCode::UNPROCESSABLE_ENTITY, "design.points");
    // A TOML syntax error is one line with its position.
    let r = post("/api/servo/design/load", json!({"text": "# design\npoints = [[0, 0]", "format": "toml"})).await;
    assert_refused(&r, StatusCode::BAD_REQUEST, "text");
    let msg = r.1["error"].as_str().unwrap();
    assert!(msg.starts_with("text: line 2, column ") && !msg.contains('\n'), "{msg}");
}

#[tokio::test]
async fn oversized_bodies_are_refused() {
    let big = format!("{{\"laws\": [{{\"name\": \"cycloidal\"}}], \"pad\": \"{}\"}}", "x".repeat(MAX_BODY_BYTES));
    let (s, _, text) = call("POST", "/api/laws/compare", Some(big)).await;
    assert_eq!(s, StatusCode::PAYLOAD_TOO_LARGE, "{text}");
    assert!(text.contains("\"field\":\"body\""), "{text}");
}

#[test]
fn real_server_keeps_serving_after_bad_requests() {
    let addr = common::spawn_server();
    let bad: [&[u8]; 5] = [
        b"{",
        b"\xff\xfe not utf8",
        br#"{"design": {"points": "x"}}"#,
        br#"{"design": null, "samples": 99999999999999999999999}"#,
        &[b'['; 100_000],
    ];
    for body in bad {
        let r = common::request(addr, "POST", "/api/servo/evaluate", Some(body)).expect("answer");
        assert!((400..500).contains(&r.status), "{} {}", r.status, r.body);
        assert!(r.json()["field"].is_string(), "{}", r.body);
    }
    let big = vec![b' '; MAX_BODY_BYTES + 10];
    let r = common::request(addr, "POST", "/api/servo/evaluate", Some(&big)).expect("answer");
    assert_eq!(r.status, 413);
    // Another host name (DNS rebinding) is refused.
    let r = common::request_with_host(addr, "GET", "/api/info", None, "evil.example:80").expect("answer");
    assert_eq!(r.status, 403);
    assert_eq!(r.json()["field"], "host");
    // The Host read as an authority: a user part or a longer name is not a loopback name, and the
    // names docs/web.md lists pass with or without a port (issue 27).
    for (host, status) in [
        ("localhost:80@evil.com", 403),
        ("127.0.0.1.evil.com", 403),
        ("[::1]", 200),
        ("[::1]:8765", 200),
        ("LOCALHOST", 200),
    ] {
        let r = common::request_with_host(addr, "GET", "/api/info", None, host).expect("answer");
        assert_eq!(r.status, status, "Host: {host}: {}", r.body);
    }
    // Wrong methods and unknown paths.
    for (method, path, status) in
        [("GET", "/api/servo/evaluate", 405), ("DELETE", "/api/info", 405), ("GET", "/api/x", 404), ("GET", "/x", 404)]
    {
        let r = common::request(addr, method, path, None).expect("answer");
        assert_eq!(r.status, status, "{method} {path}: {}", r.body);
        assert!(r.json()["field"].is_string(), "{}", r.body);
    }
    // And a good request still works.
    let body = json!({"design": design(), "samples": 50}).to_string();
    let r = common::request(addr, "POST", "/api/servo/evaluate", Some(body.as_bytes())).expect("answer");
    assert_eq!(r.status, 200, "{}", r.body);
    assert!(r.json()["speeds"][0]["peak_torque_nm"].as_f64().unwrap() > 0.0);
    assert!(addr.ip().is_loopback());
}

#[tokio::test]
async fn picking_settings_and_simulation() {
    let (s, info) = get("/api/picking/settings").await;
    assert_eq!(s, StatusCode::OK);
    let keys: Vec<&str> = info["settings"].as_array().unwrap().iter().filter_map(|s| s["key"].as_str()).collect();
    assert_eq!(keys, ["speed_rpm", "play_mm", "shuttle_g", "checking_kgf", "strap_cm"]);
    let (s, r) = post("/api/picking/simulate", json!({"samples": 30})).await;
    assert_eq!(s, StatusCode::OK, "{r}");
    assert!((r["outcome"]["velocity_m_s"].as_f64().unwrap() - 17.0).abs() < 1e-9);
    assert_eq!(r["curves"]["t_ms"].as_array().unwrap().len(), 30);
    // A faster loom throws the shuttle faster; the numerical route agrees with the closed form.
    let fast = json!({"settings": {"speed_rpm": 220.0}, "samples": 10});
    let (_, closed) = post("/api/picking/simulate", fast.clone()).await;
    let mut ode = fast;
    ode["method"] = json!("ode");
    let (_, ode) = post("/api/picking/simulate", ode).await;
    let (vc, vo) =
        (closed["outcome"]["velocity_m_s"].as_f64().unwrap(), ode["outcome"]["velocity_m_s"].as_f64().unwrap());
    assert!(vc > 17.0 && (vc / vo - 1.0).abs() < 1e-6, "{vc} {vo}");
    let bad = json!({"settings": {"shuttle_g": "heavy"}});
    assert_refused(&post("/api/picking/simulate", bad).await, StatusCode::BAD_REQUEST, "settings.shuttle_g");
    let bad = json!({"settings": {"speed_rpm": 1e7}});
    assert_refused(&post("/api/picking/simulate", bad).await, StatusCode::UNPROCESSABLE_ENTITY, "settings.speed_rpm");
    let bad = json!({"settings": {"colour": 1}});
    assert_refused(&post("/api/picking/simulate", bad).await, StatusCode::BAD_REQUEST, "settings.colour");
    let bad = json!({"samples": 10_000_000});
    assert_refused(&post("/api/picking/simulate", bad).await, StatusCode::UNPROCESSABLE_ENTITY, "samples");
}

#[tokio::test]
async fn shedding_pareto_and_law() {
    let req = json!({"family": "trapezoid", "step": 0.05, "motions_deg": [240, 300],
                     "conditions": {"threshold": 0.95, "stroke_m": 0.1, "speed_rpm": 300}});
    let (s, r) = post("/api/shed/pareto", req).await;
    assert_eq!(s, StatusCode::OK, "{r}");
    let front = r["front"].as_array().expect("front");
    assert!(!front.is_empty());
    // Sorted by window, largest first, with the acceleration falling along it.
    let w: Vec<f64> = front.iter().map(|c| c["criteria"]["window_deg"].as_f64().unwrap()).collect();
    let a: Vec<f64> = front.iter().map(|c| c["criteria"]["peak_accel_m_s2"].as_f64().unwrap()).collect();
    assert!(w.windows(2).all(|p| p[0] >= p[1]) && a.windows(2).all(|p| p[0] >= p[1]), "{w:?} {a:?}");
    let pick = &front[front.len() / 2];
    let law = json!({"family": "trapezoid", "lengths": pick["lengths"], "motion_deg": pick["criteria"]["motion_deg"], "samples": 181});
    let (s, l) = post("/api/shed/law", law).await;
    assert_eq!(s, StatusCode::OK, "{l}");
    assert_eq!(l["angle_deg"].as_array().unwrap().len(), 181);
    assert!(
        (l["criteria"]["window_deg"].as_f64().unwrap() - pick["criteria"]["window_deg"].as_f64().unwrap()).abs() < 1e-6
    );
    // The stroke in mm (the CLI's `--stroke-mm`, the page's unit) gives the same law as in m; one
    // of the two only; a bad one is named and bounded in the unit it was given in.
    let in_mm = |cond: serde_json::Value| {
        json!({"family": "trapezoid", "lengths": pick["lengths"], "motion_deg": pick["criteria"]["motion_deg"],
               "samples": 181, "conditions": cond})
    };
    let (_, m) = post("/api/shed/law", in_mm(json!({"stroke_m": 0.08}))).await;
    let (s, mm) = post("/api/shed/law", in_mm(json!({"stroke_mm": 80}))).await;
    assert_eq!(s, StatusCode::OK, "{mm}");
    assert_eq!(m["criteria"], mm["criteria"]);
    assert!(
        (mm["criteria"]["peak_accel_m_s2"].as_f64().unwrap()
            - 0.8 * l["criteria"]["peak_accel_m_s2"].as_f64().unwrap())
        .abs()
            < 1e-9 * l["criteria"]["peak_accel_m_s2"].as_f64().unwrap()
    );
    let both = in_mm(json!({"stroke_m": 0.08, "stroke_mm": 80}));
    assert_refused(&post("/api/shed/law", both).await, StatusCode::UNPROCESSABLE_ENTITY, "conditions.stroke_mm");
    let (s, e) = post("/api/shed/law", in_mm(json!({"stroke_mm": -5}))).await;
    assert_eq!((s, e["field"].as_str()), (StatusCode::UNPROCESSABLE_ENTITY, Some("conditions.stroke_mm")), "{e}");
    assert!(
        e["error"].as_str().unwrap().contains("stroke_mm = -5 is out of range")
            && e["error"].as_str().unwrap().contains("mm"),
        "{e}"
    );
    let fine = json!({"family": "lead-trapezoid", "step": 0.005, "motions_deg": [300]});
    assert_refused(&post("/api/shed/pareto", fine).await, StatusCode::UNPROCESSABLE_ENTITY, "step");
    let angles = json!({"family": "trapezoid", "step": 0.1, "motions_deg": vec![300; 13]});
    assert_refused(&post("/api/shed/pareto", angles).await, StatusCode::UNPROCESSABLE_ENTITY, "motions_deg");
    let t = json!({"family": "trapezoid", "step": 0.1, "motions_deg": [300], "conditions": {"threshold": 2}});
    assert_refused(&post("/api/shed/pareto", t).await, StatusCode::UNPROCESSABLE_ENTITY, "conditions.threshold");
    let wrong = json!({"family": "trapezoid", "lengths": [0.5, 0.5], "motion_deg": 300});
    assert_refused(&post("/api/shed/law", wrong).await, StatusCode::UNPROCESSABLE_ENTITY, "lengths");
    let sum = json!({"family": "trapezoid", "lengths": [0.5, 0.5, 0.5], "motion_deg": 300});
    assert_refused(&post("/api/shed/law", sum).await, StatusCode::UNPROCESSABLE_ENTITY, "lengths");
    let flat = json!({"family": "lead-trapezoid", "lengths": [1, 0, 0, 0], "motion_deg": 300});
    assert_refused(&post("/api/shed/law", flat).await, StatusCode::UNPROCESSABLE_ENTITY, "lengths");
}

#[tokio::test]
async fn dobby_default_and_synthesis() {
    let (s, d) = get("/api/dobby/default").await;
    assert_eq!(s, StatusCode::OK);
    assert_eq!(d["law"]["rise"]["name"], "cycloidal");
    let mut req = d.clone();
    req["step_deg"] = json!(5.0);
    let (s, r) = post("/api/dobby/synthesize", req.clone()).await;
    assert_eq!(s, StatusCode::OK, "{r}");
    assert_eq!(r["poses"].as_array().unwrap().len(), 73);
    assert_eq!(r["curves"]["phi2_deg"].as_array().unwrap().len(), 73);
    // The limit the checks used: a warning names a pressure angle only above it.
    let limit = r["pressure_limit_deg"].as_f64().unwrap();
    assert_eq!(limit, loomkin_mech::SynthesisOptions::default().pressure_limit_deg);
    let summary = &r["summary"];
    let checks = if summary["checks"].is_object() { &summary["checks"] } else { summary };
    let worst = ["mu_b_max_deg", "mu_c_max_deg", "mu_out_max_deg"].map(|k| checks[k].as_f64().unwrap());
    let warned = r["warnings"].as_array().unwrap().iter().any(|w| w["code"] == "pressure-angle");
    assert_eq!(worst.iter().any(|&m| m > limit), warned, "{worst:?} against {limit}: {}", r["warnings"]);
    assert!(!r["cam"]["centre"].as_array().unwrap().is_empty());
    let mut bad = req.clone();
    bad["geometry"]["l6_m"] = json!(-1.0);
    let res = post("/api/dobby/synthesize", bad).await;
    assert_eq!(res.0, StatusCode::UNPROCESSABLE_ENTITY, "{}", res.1);
    assert!(res.1["field"].as_str().unwrap().contains("l6"), "{}", res.1);
    let mut bad = req.clone();
    bad["law"]["cycles"] = json!(40);
    assert_refused(&post("/api/dobby/synthesize", bad).await, StatusCode::UNPROCESSABLE_ENTITY, "law.cycles");
    let mut bad = req.clone();
    bad["roller_m"] = json!("big");
    assert_refused(&post("/api/dobby/synthesize", bad).await, StatusCode::BAD_REQUEST, "roller_m");
    // The library's names are placed where they are in the request.
    let mut bad = req.clone();
    bad["geometry"]["l2_m"] = json!(0.0);
    assert_refused(&post("/api/dobby/synthesize", bad).await, StatusCode::UNPROCESSABLE_ENTITY, "geometry.l2_m");
    let mut bad = req.clone();
    bad["law"]["dwell_centre_deg"] = json!(1e300);
    let r = post("/api/dobby/synthesize", bad).await;
    assert_refused(&r, StatusCode::UNPROCESSABLE_ENTITY, "law.dwell_centre_deg");
    assert!(r.1["error"].as_str().unwrap().contains("= 1e300 "), "{}", r.1);
    let mut bad = req;
    bad["geometry"]["alpha_deg"] = json!(5.0);
    bad["geometry"]["theta_deg"] = json!(5.0);
    assert_refused(&post("/api/dobby/synthesize", bad).await, StatusCode::UNPROCESSABLE_ENTITY, "geometry.alpha_deg");
}
