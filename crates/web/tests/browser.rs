//! Drives the workbench page in a real headless Chromium through ChromeDriver (W3C WebDriver,
//! spoken over a small HTTP client), one browser session for every behaviour of the page: no
//! view logs an error to the console; dragging a definition point moves its Y only (X with Shift
//! or the lock box) and the torque follows the API; undo and redo (keys and buttons); the address
//! holds the view and the design (reload, back, forward, a typed hash); wheel zoom, drag pan and
//! double-click reset; PNG, SVG and CSV downloads of a chart; an invalid cell highlighted and named
//! by its table row; numeric fields beside sliders (15.5 mm of strap play); parameter variants in
//! the catalogue; jerk, jerk limit and log axis in the shedding view; closed dobby cams and their
//! DXF and CSV; the cam, loom and dynamics views' figures against the API, their undo and redo by
//! keys, their address (typed hash, reload), their numeric fields and refused fields, and their
//! downloads; every view at 1024, 1280 and 1920 px without horizontal overflow, with a save menu
//! on every chart and (from 1280 px) the header on one row.
//!
//! Needs Debian's `chromium` and `chromium-driver` (`apt-get install -y chromium chromium-driver`).
//! When either is missing at build time (see `build.rs`) the test is marked ignored, so the test
//! summary counts it as `1 ignored`; missing at run time it still prints why and returns.
//! `LOOMKIN_CHROMIUM` and `LOOMKIN_CHROMEDRIVER` override the paths. Screenshots of every view
//! and behaviour are written to `$CARGO_TARGET_TMPDIR/workbench-*.png` (the paths are printed).

mod common;

use serde_json::{Value, json};
use std::net::{SocketAddr, TcpListener};
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

fn find(env: &str, names: &[&str], extra: &[&str]) -> Option<PathBuf> {
    if let Some(p) = std::env::var_os(env) {
        // An explicit path that does not exist is a mistake to report, not a reason to skip.
        let p = PathBuf::from(p);
        assert!(p.is_file(), "{env}={} is not a file", p.display());
        return Some(p);
    }
    let path = std::env::var_os("PATH").unwrap_or_default();
    for dir in std::env::split_paths(&path) {
        for n in names {
            let p = dir.join(n);
            if p.is_file() {
                return Some(p);
            }
        }
    }
    extra.iter().map(PathBuf::from).find(|p| p.is_file())
}

fn free_port() -> u16 {
    TcpListener::bind("127.0.0.1:0").and_then(|l| l.local_addr()).map(|a| a.port()).expect("free port")
}

/// ChromeDriver child process, killed (by its own handle) when dropped.
struct Driver {
    child: Child,
    addr: SocketAddr,
    session: String,
    profile: TempDir,
}

struct TempDir(PathBuf);

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

impl Drop for Driver {
    fn drop(&mut self) {
        if !self.session.is_empty() {
            let _ = common::request(self.addr, "DELETE", &format!("/session/{}", self.session), None);
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Driver {
    /// Starts ChromeDriver on a free port (again on another port if it exits at once, e.g. when
    /// the port was taken between the check and the start), then a headless Chromium session.
    /// Every wait is bounded.
    fn start(chromium: &PathBuf, chromedriver: &PathBuf) -> Driver {
        let mut attempt = 0;
        let mut d = loop {
            attempt += 1;
            let port = free_port();
            let child = Command::new(chromedriver)
                .arg(format!("--port={port}"))
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn()
                .expect("start chromedriver");
            let addr: SocketAddr = ([127, 0, 0, 1], port).into();
            let profile = std::env::temp_dir().join(format!("loomkin-browser-test-{}-{port}", std::process::id()));
            let mut d = Driver { child, addr, session: String::new(), profile: TempDir(profile) };
            let t0 = Instant::now();
            let up = loop {
                if common::request(addr, "GET", "/status", None).is_ok_and(|r| r.status == 200) {
                    break true;
                }
                if d.child.try_wait().ok().flatten().is_some() {
                    break false;
                }
                assert!(t0.elapsed() < Duration::from_secs(20), "chromedriver did not answer on {addr}");
                std::thread::sleep(Duration::from_millis(100));
            };
            if up {
                break d;
            }
            assert!(attempt < 3, "chromedriver exited at start three times");
        };
        let profile = d.profile.0.clone();
        let caps = json!({"capabilities": {"alwaysMatch": {
            "browserName": "chrome",
            // The browser's console, read back through /se/log.
            "goog:loggingPrefs": {"browser": "ALL"},
            "goog:chromeOptions": {
                "binary": chromium,
                "args": ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                         "--disable-component-update", "--disable-sync", "--no-first-run",
                         "--disable-dev-shm-usage", "--window-size=1400,1300",
                         format!("--user-data-dir={}", profile.display())],
            },
            // Bounded waits inside the browser too (the defaults allow a 300 s page load).
            "timeouts": {"implicit": 0, "pageLoad": 30_000, "script": 15_000},
        }}});
        let r = d.cmd("POST", "/session", Some(caps));
        d.session = r["sessionId"].as_str().expect("session id").to_string();
        d
    }

    /// One WebDriver command; returns its `value`, panicking with the driver's message on error.
    fn cmd(&self, method: &str, path: &str, body: Option<Value>) -> Value {
        let path = if self.session.is_empty() { path.to_string() } else { format!("/session/{}{path}", self.session) };
        let body = body.map(|b| b.to_string());
        let r = common::request(self.addr, method, &path, body.as_deref().map(str::as_bytes).or(Some(b"{}")))
            .unwrap_or_else(|e| panic!("{method} {path}: {e}"));
        let v = r.json();
        assert_eq!(r.status, 200, "{method} {path}: {}", r.body);
        v["value"].clone()
    }

    fn script(&self, js: &str) -> Value {
        self.cmd("POST", "/execute/sync", Some(json!({"script": js, "args": []})))
    }

    fn wait_for(&self, what: &str, js: &str) -> Value {
        let t0 = Instant::now();
        loop {
            let v = self.script(js);
            if !v.is_null() && v != json!(false) {
                return v;
            }
            assert!(t0.elapsed() < Duration::from_secs(30), "timed out waiting for {what}");
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    fn text(&self, css: &str) -> String {
        let el = self.cmd("POST", "/element", Some(json!({"using": "css selector", "value": css})));
        let id =
            el.as_object().and_then(|o| o.values().next()).and_then(Value::as_str).expect("element id").to_string();
        self.cmd("GET", &format!("/element/{id}/text"), None).as_str().unwrap_or_default().to_string()
    }

    fn click(&self, css: &str) {
        let el = self.cmd("POST", "/element", Some(json!({"using": "css selector", "value": css})));
        let id =
            el.as_object().and_then(|o| o.values().next()).and_then(Value::as_str).expect("element id").to_string();
        self.cmd("POST", &format!("/element/{id}/click"), Some(json!({})));
    }

    fn element(&self, css: &str) -> String {
        let el = self.cmd("POST", "/element", Some(json!({"using": "css selector", "value": css})));
        el.as_object().and_then(|o| o.values().next()).and_then(Value::as_str).expect("element id").to_string()
    }

    /// Types `text` over a field's content as a user does (Ctrl+A, the text, Tab: one `change`).
    fn type_into(&self, css: &str, text: &str) {
        let id = self.element(css);
        self.cmd(
            "POST",
            &format!("/element/{id}/value"),
            Some(json!({"text": format!("\u{E009}a\u{E000}{text}\u{E004}")})),
        );
    }

    /// Input actions of one or more sources (W3C "perform actions").
    fn actions(&self, sources: Value) {
        self.cmd("POST", "/actions", Some(json!({ "actions": sources })));
    }

    /// Ctrl + `key` on the keyboard.
    fn ctrl(&self, key: &str) {
        self.actions(json!([{"type": "key", "id": "keyboard", "actions": [
            {"type": "keyDown", "value": "\u{E009}"}, {"type": "keyDown", "value": key},
            {"type": "keyUp", "value": key}, {"type": "keyUp", "value": "\u{E009}"}]}]));
    }

    /// A mouse drag from (x, y) by (dx, dy) in `steps` moves, with Shift held when `shift`.
    fn drag(&self, (x, y): (i64, i64), (dx, dy): (i64, i64), steps: i64, shift: bool) {
        let mut mouse = vec![
            json!({"type": "pointerMove", "duration": 0, "origin": "viewport", "x": x, "y": y}),
            json!({"type": "pointerDown", "button": 0}),
        ];
        for k in 1..=steps {
            mouse.push(json!({"type": "pointerMove", "duration": 40, "origin": "viewport",
                              "x": x + dx * k / steps, "y": y + dy * k / steps}));
        }
        mouse.push(json!({"type": "pointerUp", "button": 0}));
        let mut sources =
            vec![json!({"type": "pointer", "id": "mouse", "parameters": {"pointerType": "mouse"}, "actions": mouse})];
        if shift {
            let n = steps as usize + 3;
            let mut keys = vec![json!({"type": "keyDown", "value": "\u{E008}"})];
            keys.extend((0..n - 2).map(|_| json!({"type": "pause", "duration": 0})));
            keys.push(json!({"type": "keyUp", "value": "\u{E008}"}));
            sources.insert(0, json!({"type": "key", "id": "keyboard", "actions": keys}));
        }
        self.actions(Value::Array(sources));
        // Release everything (a pressed key or button would leak into the next actions).
        self.cmd("DELETE", "/actions", None);
    }

    /// The browser console's entries since the last call (chromedriver's log endpoint).
    fn console(&self) -> Vec<Value> {
        self.cmd("POST", "/se/log", Some(json!({"type": "browser"}))).as_array().cloned().unwrap_or_default()
    }

    fn num(&self, js: &str) -> f64 {
        let v = self.script(js);
        v.as_f64().unwrap_or_else(|| panic!("{js}: {v} is not a number"))
    }

    fn shot(&self, name: &str) -> PathBuf {
        let p = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("workbench-{name}.png"));
        self.screenshot(&p);
        eprintln!("screenshot {}", p.display());
        p
    }

    fn screenshot(&self, file: &PathBuf) {
        let b64 = self.cmd("GET", "/screenshot", None);
        let png = base64_decode(b64.as_str().unwrap_or_default());
        assert!(png.starts_with(b"\x89PNG"), "screenshot is not a PNG");
        std::fs::write(file, png).expect("write screenshot");
    }
}

fn base64_decode(s: &str) -> Vec<u8> {
    let val = |c: u8| match c {
        b'A'..=b'Z' => Some(c - b'A'),
        b'a'..=b'z' => Some(c - b'a' + 26),
        b'0'..=b'9' => Some(c - b'0' + 52),
        b'+' => Some(62),
        b'/' => Some(63),
        _ => None,
    };
    let mut out = Vec::with_capacity(s.len() * 3 / 4);
    let (mut acc, mut bits) = (0u32, 0);
    for c in s.bytes().filter_map(val) {
        acc = (acc << 6) | u32::from(c);
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
        }
    }
    out
}

const SETTLED: &str = "return window.loomkin && loomkin.ready && loomkin.evalCount > 0 && !loomkin.busy \
                       && document.querySelector('#peak-torque-0') !== null";

/// The element each view shows once its first result is in.
const VIEWS: [(&str, &str); 11] = [
    ("servo", "#peak-torque-0"),
    ("catalogue", "#catalogue-metrics tbody tr"),
    ("shed", "#shed-peak-jerk"),
    ("picking", "#pick-velocity"),
    ("dobby", "#dobby-summary tbody tr"),
    ("dynamics", "#dyn-residual"),
    ("cam", "#cam-max-pressure-angle"),
    ("loom", "#loom-peak-torque"),
    ("drive", "#shaft-ripple"),
    ("insertion", "#insert-max-picks"),
    ("eshed", "#eshed-peak-bus"),
];

/// Replaces the page's file download by a recorder: `window.saved` gets name, type, size and
/// text of every file the page would save.
const RECORD_DOWNLOADS: &str = "window.saved = []; LoomkinCharts.download = (name, data, type) => { \
     const rec = {name, type, size: data.size !== undefined ? data.size : data.length, text: typeof data === 'string' ? data : null, \
     blob: data instanceof Blob ? data : null}; \
     window.saved.push(rec); }; return true";

/// Holds the answer to the next request whose path ends in `suffix` until the request after it
/// has been answered and drawn, then delivers it (`window.lateDone` once it has been handled): a
/// slow earlier answer arriving after a later one, on demand. Every request's path and body is
/// recorded in `window.asked`.
const HOLD_NEXT: &str = "window.asked = window.asked || []; if (!window.realFetch) window.realFetch = window.fetch; \
     window.lateDone = false; const f = window.realFetch, suffix = SUFFIX; let release = null; \
     const held = new Promise((res) => { release = res; }); let n = 0; \
     window.fetch = (u, init) => { \
       window.asked.push({ path: String(u), body: init && init.body ? JSON.parse(init.body) : null }); \
       const p = f(u, init); if (!String(u).endsWith(suffix)) return p; n++; \
       if (n === 1) return p.then((r) => held.then(() => r)); \
       window.fetch = (u2, i2) => { window.asked.push({ path: String(u2), body: i2 && i2.body ? JSON.parse(i2.body) : null }); return f(u2, i2); }; \
       return p.then((r) => { setTimeout(() => { release(); setTimeout(() => { window.lateDone = true; }, 600); }, 600); return r; }); }; \
     return true";

/// [`HOLD_NEXT`] for the requests whose path ends in `suffix`.
fn hold_next(suffix: &str) -> String {
    HOLD_NEXT.replace("SUFFIX", &format!("'{suffix}'"))
}

/// Records every request's path and body in `window.asked` (emptied).
const RECORD_REQUESTS: &str = "window.asked = []; if (!window.realFetch) window.realFetch = window.fetch; const f = window.realFetch; \
     window.fetch = (u, init) => { window.asked.push({ path: String(u), body: init && init.body ? JSON.parse(init.body) : null }); return f(u, init); }; \
     return true";

fn peak_torque(d: &Driver) -> f64 {
    let t = d.text("#peak-torque-0");
    t.trim().parse().unwrap_or_else(|_| panic!("peak torque '{t}' is not a number"))
}

fn point(d: &Driver, i: usize) -> (f64, f64) {
    let v = d.script(&format!(
        "return [+document.querySelector('#pt-x-{i}').value, +document.querySelector('#pt-y-{i}').value]"
    ));
    (v[0].as_f64().expect("X"), v[1].as_f64().expect("Y"))
}

fn point_px(d: &Driver, i: usize) -> (i64, i64) {
    let p = d.script(&format!("return loomkin.charts.editor.pointClientXY({i})"));
    (p["x"].as_f64().expect("x").round() as i64, p["y"].as_f64().expect("y").round() as i64)
}

/// Waits for the evaluation after the state changed (`evalCount` past `evals`).
fn settled_after(d: &Driver, what: &str, evals: i64) {
    d.wait_for(what, &format!("{SETTLED} && loomkin.evalCount > {evals}"));
}

/// Whether two JSON values hold the same numbers at the same places (the page writes 500 where
/// the server wrote 500.0).
fn same_numbers(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => x.as_f64() == y.as_f64(),
        (Value::Array(x), Value::Array(y)) => x.len() == y.len() && x.iter().zip(y).all(|(p, q)| same_numbers(p, q)),
        (Value::Object(x), Value::Object(y)) => {
            x.len() == y.len() && x.iter().all(|(k, v)| y.get(k).is_some_and(|w| same_numbers(v, w)))
        }
        _ => a == b,
    }
}

fn evals(d: &Driver) -> i64 {
    d.script("return loomkin.evalCount").as_i64().expect("count")
}

#[test]
#[cfg_attr(
    not(loomkin_browser),
    ignore = "chromium and chromedriver are not both installed (Debian: apt-get install -y chromium chromium-driver)"
)]
fn the_workbench_in_a_real_browser() {
    let chromium = find("LOOMKIN_CHROMIUM", &["chromium", "chromium-browser", "google-chrome"], &[]);
    let chromedriver = find("LOOMKIN_CHROMEDRIVER", &["chromedriver"], &["/usr/lib/chromium/chromedriver"]);
    let (Some(chromium), Some(chromedriver)) = (chromium, chromedriver) else {
        eprintln!(
            "SKIPPED browser test: chromium and chromedriver are not both installed \
             (Debian: apt-get install -y chromium chromium-driver)"
        );
        return;
    };
    let server = common::spawn_server();
    let d = Driver::start(&chromium, &chromedriver);
    let t0 = Instant::now();
    let lap = |what: &str| eprintln!("{what}: {:.1} s", t0.elapsed().as_secs_f64());

    // 1. No view logs an error: each opened fresh by its address, its first result waited for,
    // then the console read (script errors, failed requests, console.error all log SEVERE).
    for (view, ready) in VIEWS {
        d.cmd("POST", "/url", Some(json!({"url": format!("http://{server}/#{view}")})));
        d.wait_for(view, &format!("return document.querySelector(\"{ready}\") !== null && !loomkin.busy"));
        std::thread::sleep(Duration::from_millis(150));
        let severe: Vec<Value> = d.console().into_iter().filter(|e| e["level"] == "SEVERE").collect();
        assert!(severe.is_empty(), "the {view} view logged errors: {severe:?}");
        assert_eq!(d.script("return loomkin.errors"), json!([]), "{view}: script errors");
        assert_ne!(
            d.script("return document.querySelector('#status').className"),
            json!("error"),
            "{view}: {}",
            d.text("#status")
        );
        assert_eq!(d.script("return loomkin.view"), json!(view), "the address #{view} opens that view");
    }
    lap("every view opened without a console error");

    // 2. Drag definition point 3 down: Y follows the mouse, X stays; torque = the API's.
    d.cmd("POST", "/url", Some(json!({"url": format!("http://{server}/#servo")})));
    d.wait_for("the first evaluation", SETTLED);
    d.script(RECORD_DOWNLOADS);
    let before_nm = peak_torque(&d);
    let (x_before, y_before) = point(&d, 2);
    let url_before = d.script("return location.href");
    let n = evals(&d);
    d.drag(point_px(&d, 2), (25, 90), 6, false);
    settled_after(&d, "the redraw after the drag", n);
    let (x_after, y_after) = point(&d, 2);
    assert!(y_after < y_before - 0.2, "the point did not follow the mouse: Y {y_before} → {y_after}");
    assert_eq!(x_after, x_before, "a plain drag moves Y only");
    let after_nm = peak_torque(&d);
    assert_ne!(before_nm, after_nm, "the peak torque figure did not change");
    let design = d.script("return loomkin.design()");
    let body = json!({"design": design, "samples": 10}).to_string();
    let api = common::request(server, "POST", "/api/servo/evaluate", Some(body.as_bytes())).expect("evaluate");
    let api_nm = api.json()["speeds"][0]["peak_torque_nm"].as_f64().expect("peak torque");
    assert!((api_nm - after_nm).abs() < 1e-3 + 1e-6 * api_nm, "page {after_nm} vs API {api_nm}");
    // With Shift held, X moves too.
    let n = evals(&d);
    d.drag(point_px(&d, 2), (30, 0), 4, true);
    settled_after(&d, "the redraw after the Shift drag", n);
    let (x_shift, _) = point(&d, 2);
    assert!(x_shift > x_before + 0.01, "Shift-drag moves X: {x_before} → {x_shift}");
    // Hover over the torque chart: the read-out follows the mouse.
    let r = d.script("const r = loomkin.charts.torque.canvas.getBoundingClientRect(); return [r.left + r.width * 0.3, r.top + r.height / 2]");
    let (hx, hy) = (r[0].as_f64().expect("x").round() as i64, r[1].as_f64().expect("y").round() as i64);
    d.actions(json!([{"type": "pointer", "id": "mouse", "parameters": {"pointerType": "mouse"},
                      "actions": [{"type": "pointerMove", "duration": 0, "origin": "viewport", "x": hx, "y": hy}]}]));
    assert!(d.script("return loomkin.charts.torque.hoverX").as_f64().is_some_and(|x| x > 0.0 && x < 360.0));
    d.shot("drag");
    lap("drag (Y only, X with Shift)");

    // 3. Undo and redo, by keys and by buttons.
    let n = evals(&d);
    d.ctrl("z");
    settled_after(&d, "undo of the Shift drag", n);
    assert_eq!(point(&d, 2), (x_after, y_after), "Ctrl+Z undoes the Shift drag");
    let n = evals(&d);
    d.click("#undo");
    settled_after(&d, "undo of the drag", n);
    assert_eq!(point(&d, 2), (x_before, y_before), "Undo undoes the drag");
    assert_eq!(peak_torque(&d), before_nm);
    let n = evals(&d);
    d.ctrl("y");
    settled_after(&d, "redo", n);
    assert_eq!(point(&d, 2), (x_after, y_after), "Ctrl+Y redoes the drag");
    assert_eq!(peak_torque(&d), after_nm);
    let n = evals(&d);
    d.click("#redo");
    settled_after(&d, "redo by the button", n);
    assert_eq!(point(&d, 2).0, x_shift);
    lap("undo and redo");

    // 4. The address holds the design: reload keeps it, back returns to the earlier one, a typed
    // hash switches the view.
    let url = d.script("return location.href").as_str().expect("url").to_string();
    assert!(url.contains("#servo/") && Some(url.as_str()) != url_before.as_str(), "{url}");
    d.cmd("POST", "/refresh", None);
    d.wait_for("the reloaded page", SETTLED);
    assert_eq!(point(&d, 2).0, x_shift, "reload keeps the design of the address");
    assert_eq!(d.script("return location.href"), json!(url));
    let n = evals(&d);
    d.cmd("POST", "/back", None);
    settled_after(&d, "back", n);
    assert_eq!(point(&d, 2), (x_after, y_after), "back returns to the design before");
    let n = evals(&d);
    d.cmd("POST", "/forward", None);
    settled_after(&d, "forward", n);
    assert_eq!(point(&d, 2).0, x_shift, "forward returns to the later design");
    d.script("location.hash = '#catalogue'; return true");
    d.wait_for(
        "the hash to switch the view",
        "return loomkin.view === 'catalogue' && !document.querySelector('#view-catalogue').hidden",
    );
    d.cmd("POST", "/back", None);
    d.wait_for("back to the servo view", "return loomkin.view === 'servo'");
    d.wait_for("the page after back", SETTLED);
    d.script(RECORD_DOWNLOADS);
    lap("the address: reload, back, forward, typed hash");

    // 5. Zoom, pan and reset on the torque chart.
    let range = |d: &Driver| d.script("const L = loomkin.charts.torque.L; return [L.xt.lo, L.xt.hi, L.yt.lo, L.yt.hi]");
    let r = d.script("const r = loomkin.charts.torque.canvas.getBoundingClientRect(); return [r.left + r.width * 0.5, r.top + r.height * 0.55]");
    let (cx, cy) = (r[0].as_f64().expect("x").round() as i64, r[1].as_f64().expect("y").round() as i64);
    let full = range(&d);
    d.actions(json!([{"type": "wheel", "id": "wheel", "actions": [
        {"type": "scroll", "x": cx, "y": cy, "deltaX": 0, "deltaY": -300, "origin": "viewport"}]}]));
    let zoomed = d.wait_for(
        "the wheel zoom",
        "const c = loomkin.charts.torque; return c.view ? [c.L.xt.lo, c.L.xt.hi, c.L.yt.lo, c.L.yt.hi] : null",
    );
    let w = |v: &Value| v[1].as_f64().unwrap() - v[0].as_f64().unwrap();
    assert!(w(&zoomed) < 0.9 * w(&full), "wheel zooms in: {full} → {zoomed}");
    d.drag((cx, cy), (-120, 0), 4, false);
    let panned = range(&d);
    assert!(
        panned[0].as_f64().unwrap() > zoomed[0].as_f64().unwrap() + 1.0,
        "dragging left pans right: {zoomed} → {panned}"
    );
    assert!((w(&panned) - w(&zoomed)).abs() < 1e-6, "a pan keeps the span");
    d.shot("zoom");
    d.actions(json!([{"type": "pointer", "id": "mouse", "parameters": {"pointerType": "mouse"}, "actions": [
        {"type": "pointerMove", "duration": 0, "origin": "viewport", "x": cx, "y": cy},
        {"type": "pointerDown", "button": 0}, {"type": "pointerUp", "button": 0},
        {"type": "pointerDown", "button": 0}, {"type": "pointerUp", "button": 0}]}]));
    d.wait_for("double-click to reset", "return loomkin.charts.torque.view === null");
    assert_eq!(range(&d), full, "double-click restores the full ranges");
    lap("zoom, pan, reset");

    // 6. Downloads of a chart: PNG, SVG (well-formed, with the curves), CSV (units in the header).
    for tool in ["png", "svg", "csv"] {
        d.click("#torque [data-tool='save']");
        d.click(&format!("#torque [data-tool='{tool}']"));
    }
    // The PNG is made asynchronously: files are looked up by name, not by order.
    let saved = d.wait_for("three downloads", "return window.saved.length >= 3 ? window.saved : null");
    let file = |name: &str| {
        saved
            .as_array()
            .and_then(|a| a.iter().find(|f| f["name"] == name))
            .cloned()
            .unwrap_or_else(|| panic!("no {name} in {saved}"))
    };
    let png = file("torque.png");
    assert_eq!(png["type"], json!("image/png"));
    assert!(png["size"].as_f64().unwrap_or(0.0) > 2000.0, "{png}");
    // The PNG is opaque (issue 27: 92 % of it was transparent) and at twice the chart's size on screen.
    d.script(
        "window.pngCheck = null; const f = window.saved.find((f) => f.name === 'torque.png'); \
         createImageBitmap(f.blob).then((b) => { const c = document.createElement('canvas'); c.width = b.width; c.height = b.height; \
         const x = c.getContext('2d'); x.drawImage(b, 0, 0); const px = x.getImageData(0, 0, b.width, b.height).data; \
         let clear = 0; for (let i = 3; i < px.length; i += 4) if (px[i] < 255) clear++; \
         const cv = loomkin.charts.torque.canvas; window.pngCheck = [b.width, b.height, Math.round(2 * cv.clientWidth), Math.round(2 * cv.clientHeight), clear]; }); \
         return true",
    );
    let check = d.wait_for("the PNG decoded", "return window.pngCheck");
    assert_eq!((check[0].clone(), check[1].clone()), (check[2].clone(), check[3].clone()), "PNG size: {check}");
    assert_eq!(check[4], json!(0), "transparent pixels in the PNG: {check}");
    let ok = d.script(
        "const t = window.saved.find((f) => f.name === 'torque.svg').text; const doc = new DOMParser().parseFromString(t, 'image/svg+xml'); \
         return !doc.querySelector('parsererror') && doc.querySelectorAll('path').length > 10 \
         && doc.querySelectorAll('text').length > 10 && t.includes('rpm')",
    );
    assert_eq!(ok, json!(true), "the SVG is a drawing of the chart");
    let csv = file("torque.csv");
    let csv = csv["text"].as_str().expect("CSV text");
    let head = csv.lines().next().unwrap_or_default();
    assert_eq!(head, "main-shaft angle φ (°),600 rpm (N·m),750 rpm (N·m)");
    let rows = csv.lines().count() - 1;
    let samples = d.num("return loomkin.charts.torque.series[0].x.length");
    assert_eq!(rows as f64, samples, "one CSV row per sample");
    lap("PNG, SVG, CSV downloads");

    // 7. An invalid cell: X of point 3 below X of point 2 is highlighted and named by its row (3).
    let n = evals(&d);
    d.type_into("#pt-x-2", "0.01");
    settled_after(&d, "the refused design", n);
    let status = d.text("#status");
    assert!(status.starts_with("row 3: definition point 3"), "{status}");
    assert_eq!(d.script("return document.querySelector('#pt-row-2').classList.contains('bad') && document.querySelector('#pt-x-2').classList.contains('bad')"), json!(true));
    // The message is also at the field (below its table; the header scrolls away), numbered as the
    // table numbers its rows, and the charts are marked stale (issue 27).
    let note = d.script("const n = document.querySelector('#points-table + .field-msg'); return n && n.textContent");
    assert!(
        note.as_str().is_some_and(|t| t.starts_with("row 3: definition point 3") && !t.contains("design.")),
        "{note}"
    );
    assert_eq!(d.script("return document.querySelector('#torque').classList.contains('stale')"), json!(true));
    d.shot("invalid-cell");
    let n = evals(&d);
    d.ctrl("z");
    settled_after(&d, "undo of the invalid cell", n);
    assert_eq!(d.script("return document.querySelectorAll('#points-table .bad').length"), json!(0));
    assert_eq!(d.script("return document.querySelectorAll('.field-msg, .chart.stale').length"), json!(0));
    // Values that are not numbers are refused at the field, nothing is evaluated, the charts are
    // marked stale (issue 27: `abc` in the stroke or `600,,x` in the speeds gave a red field and
    // "evaluated").
    for (field, typed, says) in [
        ("#speeds", "600,,x", "main-shaft speeds: entry 2 ('x') is not a number"),
        ("#drive-stroke_m", "1e", "stroke H: is not a number"),
    ] {
        let before = d.script(&format!("return document.querySelector('{field}').value"));
        d.type_into(field, typed);
        let note = d.wait_for(
            "the message at the refused field",
            &format!("const n = document.querySelector('{field} + .field-msg'); return n && n.textContent"),
        );
        assert!(note.as_str().is_some_and(|t| t.starts_with(says)), "{field}: {note}");
        // Answers to the states typed on the way ("600,") do not clear the refusal.
        d.wait_for("the answers in flight", SETTLED);
        assert!(d.text("#status").starts_with(says), "{}", d.text("#status"));
        assert_eq!(d.script(&format!("return document.querySelector('{field} + .field-msg') !== null")), json!(true));
        assert_eq!(d.script("return document.querySelector('#torque').classList.contains('stale')"), json!(true));
        d.type_into(field, before.as_str().expect("value"));
        d.wait_for(
            "the corrected field",
            &format!("{SETTLED} && document.querySelectorAll('.field-msg, .chart.stale').length === 0"),
        );
    }
    assert_eq!(point(&d, 2).0, x_shift);
    let severe: Vec<Value> = d
        .console()
        .into_iter()
        .filter(|e| e["level"] == "SEVERE" && !e["message"].as_str().unwrap_or("").contains("422"))
        .collect();
    assert!(severe.is_empty(), "{severe:?}");
    lap("invalid cell");

    // 8. The catalogue compares two variants of one law.
    d.click("#tabs button[data-view='catalogue']");
    d.wait_for("the catalogue", "return document.querySelectorAll('#catalogue-metrics tbody tr').length === 3");
    d.click("#cat-variant-modified-trapezoid");
    d.wait_for("the variant", "return document.querySelectorAll('#catalogue-metrics tbody tr').length === 4");
    d.type_into("#cat-param-2", "0.2");
    let labels = d.wait_for(
        "the second variant's curves",
        "const t = [...document.querySelectorAll('#catalogue-metrics tbody tr td:first-child')].map((e) => e.textContent); \
         return t.includes('modified-trapezoid (ramp=0.2)') ? t : null",
    );
    assert!(labels.as_array().expect("labels").contains(&json!("modified-trapezoid (ramp=0.125)")), "{labels}");
    assert_eq!(d.num("return loomkin.charts.cat_a.series.length"), 4.0);
    d.ctrl("z");
    d.wait_for("undo back to one variant's parameter", "return [...document.querySelectorAll('#catalogue-metrics tbody tr td:first-child')].filter((e) => e.textContent === 'modified-trapezoid (ramp=0.125)').length === 2");
    // Two parameters in a row whose first comparison comes last (held back in the page): the table
    // and the curves stay the second's (the earlier answer was drawn over them).
    d.script(&hold_next("/laws/compare"));
    d.script(
        "const p = document.querySelector('#cat-param-2'); p.value = '0.15'; p.dispatchEvent(new Event('change')); \
         p.value = '0.2'; p.dispatchEvent(new Event('change')); return true",
    );
    d.wait_for("the late comparison", "return window.lateDone");
    let labels = d.script(
        "window.fetch = window.realFetch; return [...document.querySelectorAll('#catalogue-metrics tbody tr td:first-child')].map((e) => e.textContent)",
    );
    let labels: Vec<&str> = labels.as_array().expect("labels").iter().filter_map(Value::as_str).collect();
    assert!(
        labels.contains(&"modified-trapezoid (ramp=0.2)") && !labels.contains(&"modified-trapezoid (ramp=0.15)"),
        "the late comparison (ramp 0.15) replaced the newer one (0.2): {labels:?}"
    );
    d.shot("catalogue");
    lap("catalogue variants");

    // 9. Picking: the numeric field beside the slider takes 15.5 mm of play (the paper's Fig. 6:
    // 20.88 m/s), which the slider's steps cannot hit.
    d.click("#tabs button[data-view='picking']");
    d.wait_for("the picking view", "return document.querySelector('#pick-play_mm') !== null");
    d.type_into("#pick-play_mm", "15.5");
    let v1 = d.wait_for(
        "the pick at 15.5 mm of play",
        "const v = parseFloat(document.querySelector('#pick-velocity').textContent); return Math.abs(v - 20.88) < 0.05 ? v : null",
    );
    assert!((v1.as_f64().expect("velocity") - 20.88).abs() < 0.05);
    assert_eq!(d.script("return +document.querySelector('#pick-play_mm-range').step"), json!(0.2));
    // The slider spans the paper's 0 … 60 mm; the field takes the library's range (up to the
    // stick's length, 740 mm): 75 mm is computed, the slider resting at its end.
    d.type_into("#pick-play_mm", "75");
    d.wait_for(
        "the pick at 75 mm of play",
        "return !document.querySelector('#pick-play_mm').classList.contains('bad') && \
         document.querySelector('#status').textContent === 'pick simulated' && \
         +document.querySelector('#pick-play_mm-range').value === 60",
    );
    d.type_into("#pick-play_mm", "800");
    d.wait_for(
        "the out-of-range play refused",
        "return document.querySelector('#pick-play_mm').classList.contains('bad')",
    );
    assert!(d.text("#status").contains("0 ≤ strap-loop play ≤ 740 mm"), "{}", d.text("#status"));

    d.shot("picking");
    lap("picking numeric field");

    // 10. Shedding: the jerk chart, a jerk limit that greys the laws over it, the log axis for a
    // family whose accelerations span decades.
    d.click("#tabs button[data-view='shed']");
    d.wait_for(
        "the shedding view",
        "return document.querySelector('#shed-peak-jerk') !== null && loomkin.charts.shed_j.series.length === 1",
    );
    // The frame's motion is drawn over its whole period of two picks (0 … 720°), not cut at 360°.
    let span = d.script("const c = loomkin.charts.shed_s; return [c.L.xt.lo, c.L.xt.hi, Math.max(...c.series[0].x)]");
    assert_eq!(span, json!([0, 720, 720]), "shedding chart x range");
    let jpeak = d.num("return Math.max(...loomkin.charts.shed_j.series[0].y.map(Math.abs))");
    assert!(jpeak > 0.0);
    assert_eq!(
        d.script("return document.querySelector('#shed-stroke').value"),
        json!("100"),
        "stroke in mm as in the CLI"
    );
    d.type_into("#shed-jerk", "30000");
    d.wait_for("the jerk limit", "return document.querySelector('#shed-jerk-ok') !== null && loomkin.charts.shed_pareto.series.some((s) => s.label === 'over the jerk limit')");
    let front_jerk = d.script("return loomkin.charts.shed_j.hlines.map((h) => h.y)");
    assert_eq!(front_jerk, json!([30000, -30000]), "the limit drawn on the jerk chart");
    assert!(d.text("#shed-jerk-ok").starts_with("yes"), "the chosen law of the limited front keeps the limit");
    d.shot("shed-jerk");
    d.script("const f = document.querySelector('#shed-family'); f.value = 'lead-trapezoid'; f.dispatchEvent(new Event('change')); return true");
    d.wait_for(
        "the lead-trapezoid front on a log axis",
        "return loomkin.charts.shed_pareto.L.yt.log === true && document.querySelector('#shed-log').checked",
    );
    d.shot("shed-log");
    // A motion angle that is not a number is named by its place in the list (issue 27: it leaked
    // `invalid type: null, expected f64 at line 1 column 58`).
    d.type_into("#shed-motions", "180, abc, 200");
    d.wait_for("the refused motion angles", "return document.querySelector('#shed-motions + .field-msg') !== null");
    assert_eq!(d.text("#status"), "shedding: motion angles: entry 2 ('abc') is not a number");
    d.ctrl("z");
    d.wait_for(
        "undo of the motion angles",
        "return document.querySelectorAll('#view-shed .field-msg, #view-shed .chart.stale').length === 0",
    );
    // A stroke out of range is refused in the unit it is typed in (mm), marked; Ctrl+Z takes it back.
    d.type_into("#shed-stroke", "-5");
    // Typed key by key: "-" alone is refused first (not a number); wait for the refusal of "-5".
    d.wait_for(
        "the refused stroke",
        "return document.querySelector('#shed-stroke').classList.contains('bad') && document.querySelector('#status').textContent.includes('allowed 0 < stroke h ≤ 1000 mm')",
    );
    d.ctrl("z");
    d.wait_for(
        "undo of the refused stroke",
        "return document.querySelector('#shed-stroke').value === '100' && !document.querySelector('#shed-stroke').classList.contains('bad')",
    );
    lap("shedding jerk and log axis");

    // 11. Dobby: the cams are closed curves; DXF and CSV of the cams; the angle typed in.
    d.click("#tabs button[data-view='dobby']");
    d.wait_for("the dobby view", "return document.querySelector('#dobby-summary tbody tr') !== null");
    let closed = d.script("return loomkin.dobbyScene().items.filter((i) => i.kind === 'line' && i.pts.length > 100).every((i) => i.closed)");
    assert_eq!(closed, json!(true), "every cam curve closes 359° → 0°");
    d.script(RECORD_DOWNLOADS);
    d.click("#dobby-dxf");
    d.click("#dobby-csv");
    // The two exports are separate requests: they may finish in either order.
    let saved = d.wait_for("the cam files", "return window.saved.length >= 2 ? window.saved : null");
    let file = |name: &str| {
        let hit = saved.as_array().expect("saved files").iter().find(|f| f["name"] == json!(name));
        hit.unwrap_or_else(|| panic!("{name} among {saved}"))["text"].as_str().expect("text").to_string()
    };
    let dxf = file("dobby-cams.dxf");
    assert_eq!(dxf.matches("LWPOLYLINE").count(), 6, "six closed polylines: centre and walls of both cams");
    assert!(file("dobby-cams.csv").starts_with("phi2_deg,b_x_m,b_y_m"));
    d.type_into("#dobby-angle", "123.5");
    d.wait_for("the mechanism at 123.5°", "return loomkin.charts.dobby_phi.markerX === 123.5 || Math.abs(loomkin.charts.dobby_phi.markerX - 123.5) <= 0.5");
    // Two values of α in a row whose first answer comes last (held back in the page): the cams
    // shown stay the second's, as the field says (the earlier answer was drawn over them).
    let summary = "document.querySelector('#dobby-summary tbody').textContent";
    let at47 = d.script(&format!("return document.querySelector('#dobby-alpha').value === '47' ? {summary} : null"));
    assert!(at47.is_string(), "the default α is 47°: {at47}");
    d.type_into("#dobby-alpha", "50");
    let at50 = d.wait_for("the cams at α = 50°", &format!("const t = {summary}; return t !== {at47} ? t : null"));
    d.script(&hold_next("/dobby/synthesize"));
    d.script(
        "const a = document.querySelector('#dobby-alpha'); a.value = '47'; a.dispatchEvent(new Event('change')); \
         a.value = '50'; a.dispatchEvent(new Event('change')); return true",
    );
    d.wait_for("the late answer for α = 47°", "return window.lateDone");
    let shown = d.script(&format!(
        "window.fetch = window.realFetch; return [document.querySelector('#dobby-alpha').value, {summary}]"
    ));
    assert_eq!(shown, json!(["50", at50]), "the late answer for 47° replaced the cams of 50°");
    d.shot("dobby");
    lap("dobby cams");

    // Dynamics: a speed typed into the numeric field redraws the response; the residual shown is
    // the API's for that speed, and the sweep's marker follows.
    d.click("#tabs button[data-view='dynamics']");
    d.wait_for("the dynamics view", "return document.querySelector('#dyn-residual') !== null");
    d.type_into("#dyn-speed", "600");
    let shown = d.wait_for(
        "the dynamics response at 600 rpm",
        "return loomkin.charts.dyn_sweep.markerX === 600 ? document.querySelector('#dyn-residual').textContent : null",
    );
    let shown: f64 =
        shown.as_str().and_then(|t| t.split_whitespace().next()).and_then(|v| v.parse().ok()).expect("residual");
    let body = json!({"speed_rpm": 600, "natural_hz": 54, "damping_ratio": 0.05, "samples": 10}).to_string();
    let api = common::request(server, "POST", "/api/dynamics/response", Some(body.as_bytes())).expect("dynamics");
    let api_mm = api.json()["report"]["residual_amplitude_mm"].as_f64().expect("residual");
    assert!((shown - api_mm).abs() < 1e-4, "page {shown} mm vs API {api_mm} mm");
    lap("dynamics speed field");

    // 12. The cam view: the page's figures are the API's; the angle's numeric field; undo and
    // redo by keys; the address (a typed hash brings an earlier state back); a refused field
    // marked; the charts' downloads.
    d.click("#tabs button[data-view='cam']");
    d.wait_for("the first cam", "return document.querySelector('#cam-max-pressure-angle') !== null && loomkin.histories.cam && loomkin.histories.cam.isReady");
    let first = |text: String| -> f64 {
        text.split(|c: char| c.is_whitespace() || c == '°').next().and_then(|v| v.parse().ok()).unwrap_or(f64::NAN)
    };
    // A conjugate pair with an offset follower, sized for 30°: two edits, two states.
    d.script(
        "const c = document.querySelector('#cam-closure'); c.value = 'conjugate'; c.dispatchEvent(new Event('change')); \
         const o = document.querySelector('#cam-offset'); o.value = 10; o.dispatchEvent(new Event('change')); return true",
    );
    let shown = d.wait_for(
        "the conjugate pair",
        "const t = document.querySelector('#cam-max-pressure-angle'); \
         return t && t.textContent.includes('counter-cam') && location.hash.startsWith('#cam/') ? t.textContent : null",
    );
    let req = d.script("return loomkin.camRequest()");
    let api = common::request(server, "POST", "/api/cam/profile", Some(req.to_string().as_bytes())).expect("cam");
    let rep = api.json()["report"].clone();
    let api_deg = rep["max_pressure_angle_deg"].as_f64().expect("pressure angle");
    let page_deg = first(shown.as_str().unwrap_or("").to_string());
    assert!((page_deg - api_deg).abs() < 1e-3, "page {page_deg}° vs API {api_deg}°");
    let prime = first(d.text("#cam-prime-radius"));
    assert!((prime - rep["prime_radius_mm"].as_f64().expect("prime")).abs() < 1e-3, "{prime}");
    // The pressure-angle panel carries the cam, the counter-cam and the ±30° limit lines.
    let labels = d.script("return loomkin.charts.cam_pressure.series.map((s) => s.label)");
    assert_eq!(labels, json!(["cam", "counter-cam", "±30°", ""]));
    let offset_10 = d.script("return location.hash");
    // The angle typed into the field beside the slider: the contact follows (0.5° samples).
    d.type_into("#cam-angle", "123.25");
    d.wait_for("the contact at 123.25°", "return Math.abs(loomkin.charts.cam_lift.markerX - 123.25) <= 0.25");
    assert_eq!(d.script("return +document.querySelector('#cam-angle-range').value"), json!(123.5));
    d.type_into("#cam-angle", "400");
    d.wait_for(
        "the out-of-range angle refused",
        "return document.querySelector('#cam-angle').classList.contains('bad')",
    );
    assert!(d.text("#status").contains("0 … 360 °"), "{}", d.text("#status"));
    // Ctrl+Z first puts back the angle shown before the refused value (never recorded), then
    // undoes the angle, then the offset.
    d.ctrl("z");
    d.wait_for("the refused angle undone", "return document.querySelector('#cam-angle').value === '123.25' && !document.querySelector('#cam-angle').classList.contains('bad')");
    d.ctrl("z");
    d.wait_for("undo of the angle", "return document.querySelector('#cam-angle').value === '0'");
    assert_eq!(d.script("return location.hash"), offset_10, "undo writes the state it shows into the address");
    d.ctrl("z");
    d.wait_for(
        "undo of the offset",
        "return document.querySelector('#cam-offset').value === '0' && loomkin.camRequest().design.offset_mm === 0",
    );
    d.ctrl("y");
    d.wait_for("redo of the offset", "return document.querySelector('#cam-offset').value === '10'");
    // A refused value is marked and named; Ctrl+Z takes it back and clears the mark.
    d.type_into("#cam-roller", "-5");
    d.wait_for(
        "the refused roller",
        "return document.querySelector('#cam-roller').classList.contains('bad') && document.querySelector('#status').textContent.includes('roller radius')",
    );
    d.shot("cam-invalid");
    d.ctrl("z");
    d.wait_for(
        "undo of the refused roller",
        "return document.querySelector('#cam-roller').value === '15' && !document.querySelector('#cam-roller').classList.contains('bad') && document.querySelector('#status').className !== 'error'",
    );
    // A typed address with an earlier state shows it (hashchange): offset 20, then back to 10.
    d.type_into("#cam-offset", "20");
    d.wait_for(
        "offset 20",
        &format!("return loomkin.camRequest().design.offset_mm === 20 && location.hash !== {offset_10}"),
    );
    d.script(&format!("location.hash = {offset_10}; return true"));
    d.wait_for("the typed address's state", "return document.querySelector('#cam-offset').value === '10'");
    let shown = d.wait_for(
        "the cam of the typed address",
        "const t = document.querySelector('#cam-max-pressure-angle').textContent; return loomkin.camRequest().design.offset_mm === 10 ? t : null",
    );
    assert!((first(shown.as_str().unwrap_or("").to_string()) - api_deg).abs() < 1e-3, "{shown} vs {api_deg}");
    // A reload keeps the state of the address.
    d.cmd("POST", "/refresh", None);
    d.wait_for(
        "the reloaded cam",
        "return window.loomkin && loomkin.histories.cam && loomkin.histories.cam.isReady && document.querySelector('#cam-max-pressure-angle') !== null \
         && document.querySelector('#cam-offset').value === '10' && document.querySelector('#cam-closure').value === 'conjugate'",
    );
    assert_eq!(d.script("return location.hash"), offset_10, "reload keeps the address");
    // Downloads: the drawing's and each chart's CSV.
    d.script(RECORD_DOWNLOADS);
    for chart in ["cam-scene", "cam-lift", "cam-pressure", "cam-curvature"] {
        d.click(&format!("#{chart} [data-tool='save']"));
        d.click(&format!("#{chart} [data-tool='csv']"));
    }
    let saved = d.wait_for(
        "four CSV files",
        "return window.saved.length >= 4 ? window.saved.map((f) => [f.name, f.text.split('\\n')[0]]) : null",
    );
    assert_eq!(
        saved,
        json!([
            ["cam-scene.csv", "item,point,x_mm,y_mm,r_mm"],
            ["cam-lift.csv", "main-shaft angle (°),lift s (mm)"],
            ["cam-pressure.csv", "series,main-shaft angle (°),pressure angle (°)"],
            ["cam-curvature.csv", "series,main-shaft angle (°),curvature (1/mm)"]
        ]),
        "the cam's CSV files"
    );
    d.shot("cam");
    lap("cam view: figures, angle field, undo, address, refused field, downloads");

    // 13. The loom view: the API's figures, the stagger; undo and the address; a refused number
    // of picks; the pattern grid's downloads.
    d.click("#tabs button[data-view='loom']");
    d.wait_for("the loom", "return document.querySelector('#loom-peak-torque') !== null && loomkin.histories.loom && loomkin.histories.loom.isReady");
    d.script(
        "const l = document.querySelector('#loom-file'); l.value = 'shuttle-loom.toml'; l.dispatchEvent(new Event('change')); \
         const p = document.querySelector('#loom-pattern'); p.value = 'twill-2-2.wif'; p.dispatchEvent(new Event('change')); \
         return true",
    );
    let shown = d.wait_for(
        "the shuttle loom weaving the twill",
        "const t = document.querySelector('#loom-summary tbody'); \
         return t && t.textContent.includes('4 picks on 4 shafts') ? document.querySelector('#loom-peak-torque').textContent : null",
    );
    let req = d.script("return loomkin.loomRequest()");
    let api = common::request(server, "POST", "/api/loom/evaluate", Some(req.to_string().as_bytes())).expect("loom");
    let api_nm = api.json()["report"]["peak_torque_n_m"].as_f64().expect("peak");
    let page_nm = first(shown.as_str().unwrap_or("").to_string());
    assert!((page_nm - api_nm).abs() < 0.01, "page {page_nm} N·m vs API {api_nm} N·m");
    let twill = d.script("return location.hash");
    d.click("#loom-optimise");
    let note = d.wait_for(
        "the stagger",
        "const n = document.querySelector('#loom-stagger-note').textContent; \
         return n && loomkin.charts.loom_torque.series.length === 3 && loomkin.loomRequest().stagger_deg ? n : null",
    );
    let note = note.as_str().unwrap_or("").to_string();
    assert!(note.contains("window kept"), "{note}");
    let req = d.script("return loomkin.loomRequest()");
    let api = common::request(server, "POST", "/api/loom/evaluate", Some(req.to_string().as_bytes())).expect("loom");
    let staggered = api.json()["report"]["peak_torque_n_m"].as_f64().expect("peak");
    let shown = d.wait_for(
        "the staggered figures",
        &format!(
            "const v = parseFloat(document.querySelector('#loom-peak-torque').textContent); \
             return Math.abs(v - {staggered}) < 0.01 ? v : null"
        ),
    );
    assert!(shown.as_f64().is_some_and(|v| v <= page_nm + 0.01), "{shown} vs {page_nm}");
    d.shot("loom");
    // Ctrl+Z: the torque without the stagger again; Ctrl+Y: with it.
    d.ctrl("z");
    d.wait_for(
        "undo of the stagger",
        &format!("return !document.querySelector('#loom-apply-stagger').checked && Math.abs(parseFloat(document.querySelector('#loom-peak-torque').textContent) - {page_nm}) < 0.01"),
    );
    assert_eq!(d.script("return location.hash"), twill);
    d.ctrl("y");
    d.wait_for(
        "redo of the stagger",
        &format!("return document.querySelector('#loom-apply-stagger').checked && Math.abs(parseFloat(document.querySelector('#loom-peak-torque').textContent) - {staggered}) < 0.01"),
    );
    // A number of picks the timing diagram cannot draw: marked and named with the range.
    d.type_into("#loom-picks", "9");
    d.wait_for("the refused picks", "return document.querySelector('#loom-picks').classList.contains('bad')");
    assert!(d.text("#status").starts_with("loom: picks"), "{}", d.text("#status"));
    assert!(d.text("#status").contains('8'), "{}", d.text("#status"));
    d.shot("loom-invalid");
    d.type_into("#loom-from-pick", "0");
    d.wait_for("the refused first pick", "return document.querySelector('#loom-from-pick').classList.contains('bad')");
    assert!(d.text("#status").starts_with("loom: first pick: 0 is not a pick number"), "{}", d.text("#status"));
    d.type_into("#loom-from-pick", "1");
    d.type_into("#loom-picks", "3");
    d.wait_for(
        "three picks",
        "return !document.querySelector('#loom-picks').classList.contains('bad') && document.querySelector('#loom-to-pick').textContent === '3'",
    );
    // The typed address of the twill without the stagger: two picks again, stagger not drawn.
    d.script(&format!("location.hash = {twill}; return true"));
    d.wait_for(
        "the typed address's state",
        "return document.querySelector('#loom-picks').value === '2' && !document.querySelector('#loom-apply-stagger').checked && document.querySelector('#loom-to-pick').textContent === '2'",
    );
    // The pattern grid saves as the charts do.
    d.script(RECORD_DOWNLOADS);
    d.click("#loom-grid [data-tool='save']");
    d.click("#loom-grid [data-tool='csv']");
    d.click("#loom-grid [data-tool='save']");
    d.click("#loom-grid [data-tool='svg']");
    let saved = d.wait_for("the pattern files", "return window.saved.length >= 2 ? window.saved : null");
    let csv = saved[0]["text"].as_str().expect("pattern CSV");
    assert_eq!(saved[0]["name"], json!("loom-pattern.csv"));
    assert_eq!(
        csv.lines().next(),
        Some("pick,frame 1 raised (0/1),frame 2 raised (0/1),frame 3 raised (0/1),frame 4 raised (0/1)")
    );
    assert_eq!(csv.lines().count(), 5, "one row per pick of the 2/2 twill: {csv}");
    let ok = d.script(
        "const doc = new DOMParser().parseFromString(window.saved[1].text, 'image/svg+xml'); \
         return window.saved[1].name === 'loom-pattern.svg' && !doc.querySelector('parsererror') && doc.querySelectorAll('path').length >= 16",
    );
    assert_eq!(ok, json!(true), "the pattern as an SVG drawing");
    // Another loom chosen while the stagger search runs: the late stagger (the shuttle loom's four
    // frames) is not drawn with the rapier loom's 24, nor sent with it (it was applied and its
    // refusal, "stagger_deg" for 24 frames, replaced the page). The server, busy with the search,
    // refuses the rapier loom's figures meanwhile; asked again, they come without a stagger.
    d.script(RECORD_REQUESTS);
    d.script(
        "document.querySelector('#loom-optimise').click(); const l = document.querySelector('#loom-file'); \
         l.value = 'rapier-loom.toml'; l.dispatchEvent(new Event('change')); return true",
    );
    d.wait_for(
        "the late stagger",
        "return !document.querySelector('#loom-optimise').disabled && window.asked.some((a) => a.path.endsWith('/loom/stagger'))",
    );
    let late = d.script(
        "const a = document.querySelector('#loom-apply-stagger'); \
         return [a.checked, a.disabled, loomkin.loomRequest().stagger_deg === undefined, document.querySelector('#loom-stagger-note').textContent]",
    );
    assert_eq!(late, json!([false, true, true, ""]), "the late stagger was taken for the rapier loom: {late}");
    d.script("const l = document.querySelector('#loom-file'); l.dispatchEvent(new Event('change')); return true");
    d.wait_for(
        "the rapier loom's figures",
        "const r = loomkin.loomView().result; return r && r.report.frames.length === 24 && document.querySelector('#status').className === ''",
    );
    let sent = d.script(
        "return window.asked.filter((q) => q.path.endsWith('/loom/evaluate')).map((q) => q.body.stagger_deg === undefined)",
    );
    assert!(
        sent.as_array().is_some_and(|s| s.len() >= 2 && s.iter().all(|v| v == &json!(true))),
        "a stagger was sent: {sent}"
    );
    d.script(
        "window.fetch = window.realFetch; const l = document.querySelector('#loom-file'); l.value = 'shuttle-loom.toml'; \
         l.dispatchEvent(new Event('change')); return true",
    );
    d.wait_for(
        "the shuttle loom again",
        "const r = loomkin.loomView().result; return r && r.report.frames.length === 4",
    );
    lap("loom view: figures, stagger, undo, address, refused picks, pattern downloads, a late stagger");

    // 13a. An uploaded WIF travels in the address: the link opens it again in a fresh page (issue 27:
    // it reopened plain weave). The 2/2 twill's text under another name (the loom has 4 frames): the
    // link's selection is the upload, not an example or the plain-weave fallback.
    d.script(
        "const text = loomkin.loomView().examples.patterns.find((p) => p.name === 'twill-2-2.wif').text; \
         const dt = new DataTransfer(); dt.items.add(new File([text], 'my-twill.wif')); \
         const f = document.querySelector('#loom-pattern-upload'); f.files = dt.files; f.dispatchEvent(new Event('change')); return true",
    );
    let link = d.wait_for(
        "the uploaded pattern in the address",
        "return loomkin.charts.loom_torque && document.querySelector('#loom-pattern').value === 'upload' && \
         (loomkin.loomView().result || {pattern: {}}).pattern.picks === 4 && location.hash.startsWith('#loom/') && \
         (loomkin.decodeState(location.hash.slice(6)).pattern_file || {}).name === 'my-twill.wif' && location.href",
    );
    d.cmd("POST", "/url", Some(json!({"url": "about:blank"})));
    d.cmd("POST", "/url", Some(json!({"url": link})));
    d.wait_for(
        "the link's pattern",
        "return document.querySelector('#loom-pattern') && document.querySelector('#loom-pattern').value === 'upload' && \
         (loomkin.loomView().result || {pattern: {}}).pattern.picks === 4 && document.querySelector('#loom-pattern-upload-label').nextElementSibling.textContent.startsWith('my-twill.wif')",
    );
    lap("an uploaded pattern in the address");

    // 13b. A long request shows its progress against the server's budget and can be cancelled; the
    // server stops the computation, so the next heavy request gets a slot (issue 27). The servo
    // shedding optimiser on 1000 picks of 24 frames whose lifts never repeat (the top bit of a 32-bit
    // congruential generator: its low bits repeat every few steps, and a repeating draft is searched
    // on its short pattern in a second) runs past the 30 s budget uncancelled (the CLI: > 2 min).
    d.script(
        "let s = 12345, text = ''; for (let p = 0; p < 1000; p++) { const r = []; for (let f = 1; f <= 24; f++) { \
         s = (Math.imul(s, 1103515245) + 12345) >>> 0; if (s >>> 31) r.push(f); } text += (r.length ? r : [1]).join(' ') + '\\n'; } \
         window.cancelled = null; LoomkinApp.api('/loom/servo', {pattern: {lift_plan: text}, optimize: true}) \
         .then(() => { window.cancelled = 'finished'; }, (e) => { window.cancelled = e.cancelled ? 'cancelled' : e.message; }); return true",
    );
    let line = d.wait_for(
        "the progress line",
        "const b = document.querySelector('#progress'); return (b && !b.hidden && document.querySelector('#progress-text').textContent) || (window.cancelled && 'ended: ' + window.cancelled)",
    );
    assert!(
        line.as_str().is_some_and(|t| t.starts_with("computing loom/servo: ") && t.ends_with("(stopped after 30 s)")),
        "{line}"
    );
    d.shot("progress");
    d.click("#progress-cancel");
    assert_eq!(d.wait_for("the cancelled request", "return window.cancelled"), json!("cancelled"));
    d.wait_for("the progress line gone", "return document.querySelector('#progress').hidden");
    let t0 = Instant::now();
    d.script(
        "window.again = null; const q = (n) => LoomkinApp.api('/loom/stagger', {}).then(() => { window.again = 'ok'; }, \
         (e) => { if (/busy/.test(e.message) && n > 0) setTimeout(() => q(n - 1), 200); else window.again = e.message; }); q(100); return true",
    );
    assert_eq!(d.wait_for("a heavy request after the cancel", "return window.again"), json!("ok"));
    assert!(t0.elapsed() < Duration::from_secs(20), "the cancelled search held its slot {:?}", t0.elapsed());
    // The console: only the refusals seen so far and the busy answers (503) of the retries.
    let severe: Vec<Value> = d
        .console()
        .into_iter()
        .filter(|e| {
            let m = e["message"].as_str().unwrap_or("");
            e["level"] == "SEVERE" && !m.contains("422") && !m.contains("503")
        })
        .collect();
    assert!(severe.is_empty(), "console errors besides refusals and busy answers: {severe:?}");
    lap("progress and cancel of a long request");

    // 13c. The drive view (issue 29): the shuttle loom weaving the twill; the figures against the
    // API; the scrubber moves the side view to the API's positions at that angle; play advances
    // the angle; the flywheel slider asks for the ripple with the flywheel and lowers it.
    d.click("#tabs button[data-view='drive']");
    d.wait_for("the drive view", "return document.querySelector('#shaft-ripple') !== null && loomkin.histories.drive && loomkin.histories.drive.isReady");
    d.script(
        "const l = document.querySelector('#shaft-loom'); l.value = 'shuttle-loom.toml'; l.dispatchEvent(new Event('change')); \
         const p = document.querySelector('#shaft-pattern'); p.value = 'twill-2-2.wif'; p.dispatchEvent(new Event('change')); return true",
    );
    let shown = d.wait_for(
        "the shuttle loom's shaft",
        "const r = loomkin.driveView().result; return r && r.inertia.picks === 4 && r.loom.startsWith('shuttle') && !loomkin.busy \
         ? document.querySelector('#shaft-ripple').textContent : null",
    );
    let req = d.script("return loomkin.driveRequest(true)");
    let api =
        common::request(server, "POST", "/api/drive/evaluate", Some(req.to_string().as_bytes())).expect("drive").json();
    let api_pct = api["ripple"]["speed_ripple_pct"].as_f64().expect("ripple");
    let page_pct = first(shown.as_str().unwrap_or("").to_string());
    assert!((page_pct - api_pct).abs() < 1e-4, "page {page_pct} % vs API {api_pct} %");
    // The scrubber: a third of the way through the repeat.
    let side = &api["side"];
    let n = side["angle_deg"].as_array().expect("angles").len();
    let k = n / 3;
    d.script(&format!(
        "const s = document.querySelector('#shaft-scrub'); s.value = '{k}'; s.dispatchEvent(new Event('input')); return true"
    ));
    let angle = side["angle_deg"][k].as_f64().expect("angle");
    let reed = side["sley"]["reed"][k][0].as_f64().expect("reed");
    let text = d.wait_for(
        "the side view at the scrubbed angle",
        &format!("return loomkin.driveView().k === {k} && loomkin.charts.shaft_speed.markerX === {angle} ? document.querySelector('#shaft-angle').textContent : null"),
    );
    let text = text.as_str().unwrap_or("").to_string();
    assert!(text.starts_with(&format!("{angle:.1}°")), "{text} at {angle}°");
    assert!(text.contains(&format!("reed {reed:.1} mm behind the fell")), "{text}: reed {reed}");
    d.shot("drive-scrubbed");
    d.click("#shaft-play");
    d.wait_for("the animation playing", &format!("return loomkin.driveView().k !== {k}"));
    d.click("#shaft-play");
    assert_eq!(d.text("#shaft-play"), "▶ Play");
    // The flywheel slider at 2 kg·m².
    d.script(
        "const r = document.querySelector('#shaft-flywheel-range'); r.value = '2'; r.dispatchEvent(new Event('input')); \
         r.dispatchEvent(new Event('change')); return true",
    );
    let with_fw = d.wait_for(
        "the ripple with a flywheel",
        "const r = loomkin.driveView().result; return r && r.ripple.flywheel_kg_m2 === 2 && !loomkin.busy ? document.querySelector('#shaft-ripple').textContent : null",
    );
    let req = d.script("return loomkin.driveRequest(false)");
    assert_eq!(req["flywheel_kg_m2"].as_f64(), Some(2.0), "{req}");
    let api2 =
        common::request(server, "POST", "/api/drive/evaluate", Some(req.to_string().as_bytes())).expect("drive").json();
    let api2_pct = api2["ripple"]["speed_ripple_pct"].as_f64().expect("ripple");
    let page2 = first(with_fw.as_str().unwrap_or("").to_string());
    assert!(
        (page2 - api2_pct).abs() < 1e-4 && api2_pct < api_pct,
        "page {page2} % vs API {api2_pct} % (bare {api_pct} %)"
    );
    d.shot("drive");
    // Another loom chosen while the first one's answer is on its way: that answer fills no field,
    // so the loom chosen last is asked for with its own flywheel (none sent: the file's), not with
    // the loom's before it (0 here, as no example has one; a loom with a flywheel sent its value).
    d.script(RECORD_REQUESTS);
    d.script(
        "const l = document.querySelector('#shaft-loom'); l.value = 'rapier-loom.toml'; l.dispatchEvent(new Event('change')); \
         l.value = 'shuttle-loom.toml'; l.dispatchEvent(new Event('change')); return true",
    );
    d.wait_for(
        "the shuttle loom after the rapier loom",
        "const r = loomkin.driveView().result; return r && r.loom.startsWith('shuttle') && \
         window.asked.filter((a) => a.path.endsWith('/drive/evaluate')).length === 2 && document.querySelector('#shaft-flywheel').value !== ''",
    );
    let sent = d.script(
        "window.fetch = window.realFetch; \
         return window.asked.filter((a) => a.path.endsWith('/drive/evaluate')).map((a) => a.body.flywheel_kg_m2 === undefined)",
    );
    assert_eq!(sent, json!([true, true]), "a flywheel was sent with the loom chosen last");
    lap("drive view: figures, scrubber, play, flywheel slider, a late answer");

    // 13d. The insertion view (issue 30): the rapier loom weaving point-24, its figures the route's
    // (`insert rapier --json`); the least clearance marked where the route locates it; the air-jet
    // loom at another speed moves its tip's arrival on the chart; a reed width out of range is
    // refused at its field with the library's range. Every wait is for the answer asserted on.
    d.click("#tabs button[data-view='insertion']");
    d.wait_for("the insertion view", "return document.querySelector('#insert-max-picks') !== null && loomkin.histories.insertion && loomkin.histories.insertion.isReady && !loomkin.busy");
    d.script("const p = document.querySelector('#insert-pattern'); p.value = 'point-24.wif'; p.dispatchEvent(new Event('change')); return true");
    let shown = d.wait_for(
        "the rapier on point-24",
        "const r = loomkin.insertView().result; return r && r.kind === 'rapier' && r.check.picks === 48 && !loomkin.busy \
         ? document.querySelector('#insert-min-clearance').textContent : null",
    );
    let req = d.script("return loomkin.insertRequest()");
    let route = json!({"loom_toml": req["loom_toml"], "pattern": req["pattern"]});
    let api = common::request(server, "POST", "/api/insert/rapier", Some(route.to_string().as_bytes()))
        .expect("rapier")
        .json();
    let view = d.script("return loomkin.insertView().result.check");
    assert!(same_numbers(&view, &api), "the view's figures are insert rapier's: {view} vs {api}");
    let least = api["min_clearance_mm"].as_f64().expect("least clearance");
    assert!(first(shown.as_str().unwrap_or("").to_string()) - least < 1e-3, "{shown} vs {least}");
    let marked = d.script("const s = loomkin.charts.insert_clearance.series[1]; return [s.x[0], s.y[0]]");
    assert!(
        same_numbers(&marked, &json!([api["worst_angle_deg"], api["min_clearance_mm"]])),
        "the least clearance marked at {marked}"
    );
    d.shot("insertion-rapier");
    // The air jet at 700 rpm against the file's 800: the flight takes the same time, so fewer degrees.
    d.script("const l = document.querySelector('#insert-loom'); l.value = 'airjet-loom.toml'; l.dispatchEvent(new Event('change')); return true");
    let at_file = d.wait_for(
        "the air jet",
        "const r = loomkin.insertView().result; return r && r.kind === 'airjet' && !loomkin.busy && !document.querySelector('#insert-relay').hidden \
         ? r.check.arrival_deg : null",
    );
    d.type_into("#insert-speed", "700");
    let at_700 = d.wait_for(
        "the air jet at 700 rpm",
        "const r = loomkin.insertView().result; const s = loomkin.charts.insert_track.series[0]; \
         return r && r.speed_rpm === 700 && !loomkin.busy ? [r.check.arrival_deg, s.x[s.x.length - 1]] : null",
    );
    let route = json!({"loom_toml": d.script("return loomkin.insertRequest().loom_toml"), "speed_rpm": 700});
    let api = common::request(server, "POST", "/api/insert/airjet", Some(route.to_string().as_bytes()))
        .expect("airjet")
        .json();
    assert!(same_numbers(&at_700[0], &api["arrival_deg"]), "the arrival of insert airjet --speed-rpm 700: {at_700}");
    let (a_file, a_700) = (at_file.as_f64().expect("deg"), at_700[1].as_f64().expect("deg"));
    assert!(a_700 < a_file, "the tip's track did not move: {a_file}° at the file's speed, {a_700}° at 700 rpm");
    assert!((a_700 - api["arrival_deg"].as_f64().expect("deg")).abs() < 1e-9, "the track ends at the arrival");
    d.shot("insertion-airjet");
    d.type_into("#insert-reed-width-mm", "0");
    let msg = d.wait_for(
        "the refused reed width",
        "const f = document.querySelector('#insert-reed-width-mm'); const m = f.parentElement.querySelector('.field-msg'); \
         return f.classList.contains('bad') && m && !loomkin.busy && document.querySelector('#status').textContent.startsWith('insertion: reed width') ? m.textContent : null",
    );
    let schema = common::request(server, "GET", "/api/schema", None).expect("schema").json();
    let lo = common::schema_at(&schema["routes"]["/api/insert/evaluate"]["request"], "budget.reed_width_mm")["minimum"]
        .as_f64()
        .expect("minimum");
    assert!(msg.as_str().is_some_and(|m| m.contains(&format!("allowed {lo} ≤ reed width"))), "{msg} (minimum {lo})");
    d.shot("insertion-invalid");
    d.ctrl("z");
    d.wait_for("undo of the reed width", "return document.querySelector('#insert-reed-width-mm').value === '' && !document.querySelector('#insert-reed-width-mm').classList.contains('bad')");
    // A loaded loom file too large for the page's address (the picker the loom, insertion and
    // servo shedding views share): it stays in the page, the address keeps no copy of it, and the
    // page says so beside the file's name instead of dropping it from links silently (issue 27).
    d.script(
        "const text = loomkin.insertRequest().loom_toml + '\\n# ' + 'x'.repeat(200000) + '\\n'; \
         const dt = new DataTransfer(); dt.items.add(new File([text], 'big-loom.toml')); \
         const f = document.querySelector('#insert-loom-upload'); f.files = dt.files; f.dispatchEvent(new Event('change')); return true",
    );
    let note = d.wait_for(
        "the too-large loom file's note",
        "const name = document.querySelector('#insert-loom-upload-label').nextElementSibling.textContent; \
         const st = location.hash.startsWith('#insertion/') && loomkin.decodeState(location.hash.slice(11)); \
         return document.querySelector('#insert-loom').value === 'upload' && st && st.loom === 'upload' && !st.loom_file && \
         name.startsWith('big-loom.toml (') ? name : null",
    );
    assert!(note.as_str().is_some_and(|n| n.contains("too large for the page's address")), "{note}");
    d.ctrl("z");
    d.wait_for("undo of the loaded loom", "return document.querySelector('#insert-loom').value !== 'upload'");
    lap(
        "insertion view: rapier figures, least clearance, air jet speed, refused reed width, a loom file too large for a link",
    );

    // 13e. The servo shedding view (issue 31): the servo loom weaving the 2/2 twill after plain
    // weave — the lift grid, a torque per frame, the bus power changed; the figures the route's
    // (`loom servo --json`); Optimise (one request in flight) shows before → after as `loom servo
    // --optimize --json`, the least clearance typed sent and kept (`min_clearance_kept_mm`), one out of
    // its range refused at its field with the library's message; a dobby loom is refused at the loom
    // file's field.
    d.click("#tabs button[data-view='eshed']");
    let plain = d.wait_for(
        "the servo shedding view",
        "const r = loomkin.eshedView().result; return document.querySelector('#eshed-peak-bus') !== null && loomkin.histories.eshed && \
         loomkin.histories.eshed.isReady && r && !loomkin.busy ? r.result.peak_bus_power_w : null",
    );
    d.script("const p = document.querySelector('#eshed-pattern'); p.value = 'twill-2-2.wif'; p.dispatchEvent(new Event('change')); return true");
    let shown = d.wait_for(
        "the servo loom weaving the twill",
        "const r = loomkin.eshedView().result; return r && r.lifts.picks === 4 && !loomkin.busy ? document.querySelector('#eshed-peak-bus').textContent : null",
    );
    let req = d.script("return loomkin.eshedRequest(false)");
    let api =
        common::request(server, "POST", "/api/loom/servo", Some(req.to_string().as_bytes())).expect("servo").json();
    let view = d.script("return loomkin.eshedView().result.result");
    assert!(same_numbers(&view, &api), "the view's figures are loom servo's");
    let peak = api["peak_bus_power_w"].as_f64().expect("peak");
    assert!((first(shown.as_str().unwrap_or("").to_string()) - peak).abs() < 0.051, "{shown} vs {peak} W");
    assert_ne!(plain.as_f64(), Some(peak), "the twill's bus power is the plain weave's");
    let drawn = d.script(
        "const c = loomkin.charts.eshed_torque, b = loomkin.charts.eshed_bus; return [c.series.length, Math.max(...b.series[0].y)]",
    );
    assert_eq!(drawn[0].as_u64(), api["frames"].as_array().map(|f| f.len() as u64), "a torque curve per frame");
    assert!(
        drawn[1].as_f64().is_some_and(|m| m <= peak * (1.0 + 1e-9) && m >= 0.95 * peak),
        "bus curve {drawn} vs peak {peak}"
    );
    let limits = d.script("const f = document.querySelector('#eshed-min-clearance'); return [f.min, f.max]");
    assert_eq!(
        limits,
        json!(["0", "1000"]),
        "the least clearance's limits are the descriptor's (the request schema's)"
    );
    d.type_into("#eshed-min-clearance", "0.5");
    let busy = d.script("const b = document.querySelector('#eshed-optimise'); b.click(); return b.disabled && document.querySelector('#eshed-loom').disabled");
    assert_eq!(busy, json!(true), "one search in flight: the button and the loom wait for it");
    let gain = d.wait_for(
        "the optimum",
        "const o = loomkin.eshedView().optimum; return o && !loomkin.busy && !document.querySelector('#eshed-gain').hidden && \
         !document.querySelector('#eshed-optimise').disabled ? document.querySelector('#eshed-gain-peak').textContent : null",
    );
    let mut req = d.script("return loomkin.eshedRequest(true)");
    assert_eq!(req["optimize"], json!(true));
    assert_eq!(req["min_clearance_mm"], json!(0.5), "the least clearance typed is sent");
    req["objective"] = json!("peak");
    let api =
        common::request(server, "POST", "/api/loom/servo", Some(req.to_string().as_bytes())).expect("optimum").json();
    let view = d.script("return loomkin.eshedView().optimum.result");
    assert!(same_numbers(&view, &api), "the view's optimum is loom servo --optimize's");
    let (b, a) = (
        api["peak_bus_power_w_before"].as_f64().expect("before"),
        api["peak_bus_power_w_after"].as_f64().expect("after"),
    );
    assert!(a <= b, "{a} > {b}");
    assert_eq!(gain.as_str(), Some(format!("{b:.1} → {a:.1} W").as_str()));
    assert_eq!(d.script("return loomkin.charts.eshed_bus.series.length"), json!(3), "before, after and the peak drawn");
    assert_eq!(api["min_clearance_kept_mm"], json!(0.5), "{api}");
    assert!(api["min_clearance_mm_after"].as_f64().is_some_and(|c| c >= 0.5), "{api}");
    assert_eq!(d.script("return document.querySelector('#eshed-gain-kept').textContent"), json!("0.5 mm"));
    d.shot("eshed-optimised");
    d.type_into("#eshed-min-clearance", "-1");
    d.click("#eshed-optimise");
    let msg = d.wait_for(
        "the least clearance refused",
        "const f = document.querySelector('#eshed-min-clearance'); const m = f.nextElementSibling; \
         return f.classList.contains('bad') && !loomkin.busy && !document.querySelector('#eshed-optimise').disabled && m && \
         m.classList.contains('field-msg') ? m.textContent : null",
    );
    assert!(
        msg.as_str().is_some_and(|m| m.starts_with("least clearance kept") && m.contains("-1") && m.contains("1000")),
        "{msg}"
    );
    d.type_into("#eshed-min-clearance", "0.5");
    d.script("const l = document.querySelector('#eshed-loom'); l.value = 'rapier-loom.toml'; l.dispatchEvent(new Event('change')); return true");
    let msg = d.wait_for(
        "the dobby loom refused",
        "const f = document.querySelector('#eshed-loom'); const m = f.nextElementSibling; \
         return f.classList.contains('bad') && !loomkin.busy && m && m.classList.contains('field-msg') ? m.textContent : null",
    );
    assert!(msg.as_str().is_some_and(|m| m.starts_with("loom file: ") && m.contains("drive = \"servo\"")), "{msg}");
    d.shot("eshed-invalid");
    d.ctrl("z");
    d.wait_for("undo of the loom", "return document.querySelector('#eshed-loom').value === 'servo-shedding-loom.toml' && !document.querySelector('#eshed-loom').classList.contains('bad') && !loomkin.busy");
    lap("servo shedding view: lifts, torques, bus, optimise, refused dobby loom");

    // 14. Dynamics: undo of the typed speed, the address, a refused stroke marked.
    d.click("#tabs button[data-view='dynamics']");
    d.wait_for(
        "the dynamics view",
        "return document.querySelector('#dyn-residual') !== null && loomkin.histories.dynamics.isReady",
    );
    // (The page was reloaded in the cam view: this view starts afresh at the example's speed.)
    d.type_into("#dyn-speed", "600");
    d.wait_for("the response at 600 rpm", "return loomkin.charts.dyn_sweep.markerX === 600");
    let at_600 = d.script("return location.hash");
    d.type_into("#dyn-speed", "700");
    d.wait_for("the response at 700 rpm", "return loomkin.charts.dyn_sweep.markerX === 700");
    d.ctrl("z");
    d.wait_for(
        "undo of the speed",
        "return loomkin.charts.dyn_sweep.markerX === 600 && document.querySelector('#dyn-speed').value === '600' && +document.querySelector('#dyn-speed-range').value === 600",
    );
    assert_eq!(d.script("return location.hash"), at_600);
    d.ctrl("y");
    d.wait_for("redo of the speed", "return loomkin.charts.dyn_sweep.markerX === 700");
    d.script(&format!("location.hash = {at_600}; return true"));
    d.wait_for(
        "the typed address's speed",
        "return loomkin.charts.dyn_sweep.markerX === 600 && document.querySelector('#dyn-speed').value === '600'",
    );
    d.script("const s = document.querySelector('#dyn-source'); s.value = 'law'; s.dispatchEvent(new Event('change')); return true");
    d.type_into("#dyn-stroke", "0");
    d.wait_for(
        "the refused stroke",
        "return document.querySelector('#dyn-stroke').classList.contains('bad') && document.querySelector('#status').textContent.startsWith('dynamics: stroke')",
    );
    d.shot("dynamics-invalid");
    d.ctrl("z");
    d.wait_for("undo of the stroke", "return document.querySelector('#dyn-stroke').value === '100' && !document.querySelector('#dyn-stroke').classList.contains('bad')");
    let severe: Vec<Value> = d
        .console()
        .into_iter()
        .filter(|e| e["level"] == "SEVERE" && !e["message"].as_str().unwrap_or("").contains("422"))
        .collect();
    assert!(severe.is_empty(), "console errors besides the refused requests: {severe:?}");
    lap("dynamics: undo, address, refused stroke");

    // 15. Every view at 1024, 1280 and 1920 px wide: nothing wider than the window; the header
    // on one row from 1280 px; every chart and drawing has its save menu (PNG, SVG, CSV).
    for (w, h) in [(1024, 900), (1280, 1000), (1920, 1100)] {
        d.cmd("POST", "/window/rect", Some(json!({"width": w, "height": h})));
        for (view, ready) in VIEWS {
            d.click(&format!("#tabs button[data-view='{view}']"));
            d.wait_for(view, &format!("return document.querySelector(\"{ready}\") !== null"));
            std::thread::sleep(Duration::from_millis(100));
            let over = d.script(
                "const w = document.documentElement.clientWidth; \
                 return [...document.querySelectorAll('.view:not([hidden]) *')].filter((e) => e.getBoundingClientRect().right > w + 1 && e.getClientRects().length).map((e) => e.id || e.className || e.tagName).slice(0, 5)",
            );
            assert_eq!(over, json!([]), "{view} at {w} px: elements past the right edge");
            let unsaved = d.script(
                "return [...document.querySelectorAll('.view:not([hidden]) .chart')].filter((c) => \
                 !['save', 'png', 'svg', 'csv'].every((t) => c.querySelector(`[data-tool='${t}']`))).map((c) => c.id)",
            );
            assert_eq!(unsaved, json!([]), "{view}: charts without PNG, SVG and CSV downloads");
            if w >= 1280 {
                let rows = d.script(
                    "const t = (s) => document.querySelector(s).getBoundingClientRect(); \
                     return [t('header h1').top, t('#tabs').top, t('#history').top, t('#status').top].map(Math.round)",
                );
                let tops: Vec<f64> = rows.as_array().expect("tops").iter().filter_map(Value::as_f64).collect();
                let spread =
                    tops.iter().cloned().fold(f64::MIN, f64::max) - tops.iter().cloned().fold(f64::MAX, f64::min);
                assert!(spread < 16.0, "{view} at {w} px: the header wraps (tops {rows})");
            }
            d.shot(&format!("{view}-{w}"));
        }
    }
    lap("every view at 1024, 1280 and 1920 px");
    // Every field's limits are the request schema's (the library's ranges), not the page's.
    let limits = d.script(
        "const out = []; for (const e of document.querySelectorAll('input[data-schema]')) \
         out.push([e.id, e.dataset.schema, e.min, e.max, e.dataset.minOpen, e.dataset.maxOpen, e.dataset.unit || '']); return out",
    );
    let schema = common::request(server, "GET", "/api/schema", None).expect("schema").json();
    let fields = limits.as_array().expect("fields");
    assert!(fields.len() >= 8, "{limits}");
    for f in fields {
        let (id, key) = (f[0].as_str().unwrap_or(""), f[1].as_str().unwrap_or(""));
        let (route, path) = key.split_once(' ').expect("route and path");
        let s = common::schema_at(&schema["routes"][route]["request"], path);
        // A field in another unit than its key's (data-unit: mm of a key in m) is scaled by the
        // schema's factor of that unit, which must be a multiple of the key's unit.
        let k = match f[6].as_str().unwrap_or("") {
            "" => 1.0,
            unit => {
                let u = &schema["units"][unit];
                assert_eq!(u["of"], s["x-unit"], "{id}: {unit} is not a multiple of the key's unit");
                u["factor"].as_f64().expect("factor")
            }
        };
        for (i, closed, open) in [(2, "minimum", "exclusiveMinimum"), (3, "maximum", "exclusiveMaximum")] {
            let want = s.get(closed).or(s.get(open)).and_then(Value::as_f64).map(|v| v * k);
            let got = f[i].as_str().filter(|t| !t.is_empty()).map(|t| t.parse::<f64>().expect("number"));
            match (want, got) {
                (Some(w), Some(g)) => assert!((w - g).abs() <= 1e-9 * w.abs(), "{id}: {g} vs schema {w}"),
                (None, None) => {}
                _ => panic!("{id} ({key}): page {got:?}, schema {want:?}"),
            }
            assert_eq!(f[i + 2] == "true", s.get(open).is_some(), "{id}: open side");
        }
    }
    lap("every field's limits are the schema's");
    let errors = d.script("return loomkin.errors");
    assert_eq!(errors, json!([]), "script errors on the page");
}
