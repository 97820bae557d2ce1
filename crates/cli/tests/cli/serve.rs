//! `loomkin serve`: prints its URL on 127.0.0.1, serves the page and the API, refuses bad ports.

use assert_cmd::Command as AssertCommand;
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

struct Server(Child);

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// One request with `Connection: close`; every wait is bounded.
fn send(host_port: &str, method: &str, path: &str, body: &str) -> String {
    let addr: std::net::SocketAddr = host_port.parse().expect("address");
    let mut s = TcpStream::connect_timeout(&addr, Duration::from_secs(10)).expect("connect");
    s.set_read_timeout(Some(Duration::from_secs(30))).expect("timeout");
    write!(
        s,
        "{method} {path} HTTP/1.1\r\nHost: {host_port}\r\nConnection: close\r\nContent-Length: {}\r\n\r\n{body}",
        body.len()
    )
    .expect("write");
    let mut out = String::new();
    s.read_to_string(&mut out).expect("read");
    out
}

fn get(host_port: &str, path: &str) -> String {
    send(host_port, "GET", path, "")
}

#[test]
fn serve_prints_a_loopback_url_and_answers() {
    let bin = assert_cmd::cargo::cargo_bin!("loomkin");
    let child = Command::new(bin)
        .args(["serve", "--port", "0"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("start loomkin serve");
    let mut server = Server(child);
    // The first line, waited for at most 30 s (a server that never starts fails, not hangs).
    let stdout = server.0.stdout.take().expect("stdout");
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let mut line = String::new();
        let _ = BufReader::new(stdout).read_line(&mut line);
        let _ = tx.send(line);
    });
    let line = rx.recv_timeout(Duration::from_secs(30)).expect("loomkin serve printed nothing in 30 s");
    assert!(line.contains("127.0.0.1 only"), "{line}");
    let url = line.split_whitespace().find(|w| w.starts_with("http://127.0.0.1:")).expect("URL in the first line");
    let host_port = url.trim_start_matches("http://").trim_end_matches('/');
    let page = get(host_port, "/");
    assert!(page.starts_with("HTTP/1.1 200"), "{page}");
    assert!(page.contains("loomkin workbench"));
    let info = get(host_port, "/api/info");
    let body = info.split("\r\n\r\n").nth(1).expect("body");
    let v: serde_json::Value = serde_json::from_str(body).expect("JSON");
    assert_eq!(v["views"][0], "servo");
    // Bad requests get a 4xx naming the field, and the server keeps serving.
    for (method, path, body, status, field) in [
        ("POST", "/api/servo/evaluate", "{oops", "400", "body"),
        ("POST", "/api/laws/compare", r#"{"laws": [{"name": "cycloidal"}], "samples": 99999999}"#, "422", "samples"),
        ("GET", "/api/servo/evaluate", "", "405", "method"),
    ] {
        let answer = send(host_port, method, path, body);
        assert!(answer.starts_with(&format!("HTTP/1.1 {status}")), "{answer}");
        assert!(answer.contains(&format!("\"field\":\"{field}\"")), "{answer}");
    }
    assert!(get(host_port, "/api/info").starts_with("HTTP/1.1 200"));
}

#[test]
fn bad_port_is_a_usage_error() {
    let out = AssertCommand::new(assert_cmd::cargo::cargo_bin!("loomkin"))
        .args(["serve", "--port", "70000"])
        .assert()
        .code(2);
    let err = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(err.contains("--port"), "{err}");
}

#[test]
fn busy_port_fails_with_one_line() {
    let taken = std::net::TcpListener::bind("127.0.0.1:0").expect("bind");
    let port = taken.local_addr().expect("addr").port().to_string();
    let out = AssertCommand::new(assert_cmd::cargo::cargo_bin!("loomkin"))
        .args(["serve", "--port", &port])
        .timeout(Duration::from_secs(20))
        .assert()
        .code(1);
    let err = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(err.contains(&format!("cannot serve on 127.0.0.1:{port}")) && err.lines().count() == 1, "{err}");
}

/// Starts `loomkin serve --open --port 0` with `envs` (and no display unless given one), returns
/// the server and a receiver of its standard-error lines.
fn serve_open(envs: &[(&str, &std::ffi::OsStr)]) -> (Server, std::sync::mpsc::Receiver<String>) {
    let bin = assert_cmd::cargo::cargo_bin!("loomkin");
    let mut cmd = Command::new(bin);
    cmd.args(["serve", "--open", "--port", "0"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    for (k, v) in envs {
        cmd.env(k, v);
    }
    let mut server = Server(cmd.spawn().expect("start loomkin serve"));
    let stderr = server.0.stderr.take().expect("stderr");
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            let _ = tx.send(line);
        }
    });
    (server, rx)
}

/// Children of `pid` that are zombies (state Z in /proc), on Linux.
#[cfg(target_os = "linux")]
fn zombie_children(pid: u32) -> Vec<String> {
    let mut out = Vec::new();
    for e in std::fs::read_dir("/proc").into_iter().flatten().flatten() {
        let Ok(stat) = std::fs::read_to_string(e.path().join("stat")) else { continue };
        // pid (comm) state ppid …
        let Some(rest) = stat.rsplit_once(") ").map(|(_, r)| r) else { continue };
        let f: Vec<&str> = rest.split_whitespace().collect();
        if f.len() > 1 && f[0] == "Z" && f[1] == pid.to_string() {
            out.push(stat);
        }
    }
    out
}

#[test]
fn open_without_a_display_warns_in_one_line_and_serves_on() {
    let (mut server, rx) = serve_open(&[]);
    let line = rx.recv_timeout(Duration::from_secs(30)).expect("a warning within 30 s");
    assert!(line.starts_with("loomkin: warning: no display"), "{line}");
    assert!(line.contains("open http://127.0.0.1:"), "{line}");
    assert!(rx.recv_timeout(Duration::from_millis(500)).is_err(), "more than one line");
    assert!(server.0.try_wait().expect("status").is_none(), "the server stopped");
    #[cfg(target_os = "linux")]
    assert!(zombie_children(server.0.id()).is_empty());
}

#[cfg(target_os = "linux")]
#[test]
fn a_failing_opener_is_reaped_and_reported_in_one_line() {
    // An `xdg-open` that fails, first on PATH, with a display named.
    let dir = std::env::temp_dir().join(format!("loomkin-open-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let opener = dir.join("xdg-open");
    std::fs::write(&opener, "#!/bin/sh\nexit 3\n").expect("write the stub");
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&opener, std::fs::Permissions::from_mode(0o755)).expect("chmod");
    let path = std::env::join_paths(
        std::iter::once(dir.clone()).chain(std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default())),
    )
    .expect("PATH");
    let (mut server, rx) = serve_open(&[("PATH", path.as_os_str()), ("DISPLAY", std::ffi::OsStr::new(":99"))]);
    let line = rx.recv_timeout(Duration::from_secs(30)).expect("a warning within 30 s");
    assert!(line.starts_with("loomkin: warning: xdg-open could not open a browser"), "{line}");
    assert!(line.contains("exit status: 3"), "{line}");
    // The stub has been waited for: no zombie child, and the server still runs.
    assert!(zombie_children(server.0.id()).is_empty());
    assert!(server.0.try_wait().expect("status").is_none(), "the server stopped");
    let _ = std::fs::remove_dir_all(&dir);
}
