//! Test helpers: a minimal HTTP/1.1 client over a TCP stream (for the loopback server and for
//! ChromeDriver's W3C WebDriver protocol) and a server on a free loopback port.
#![allow(dead_code)]

use axum::body::{Body, to_bytes};
use axum::http::{Request, StatusCode, header};
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::time::Duration;
use tower::ServiceExt;

/// A response: status code and body text.
#[derive(Debug)]
pub struct Response {
    pub status: u16,
    pub body: String,
}

impl Response {
    pub fn json(&self) -> serde_json::Value {
        serde_json::from_str(&self.body).unwrap_or_else(|e| panic!("not JSON ({e}): {}", self.body))
    }
}

/// Sends one request (`Connection: close`) and reads the whole response.
pub fn request(addr: SocketAddr, method: &str, path: &str, body: Option<&[u8]>) -> std::io::Result<Response> {
    request_with_host(addr, method, path, body, &addr.to_string())
}

/// Like [`request`] with an explicit `Host` header.
pub fn request_with_host(
    addr: SocketAddr,
    method: &str,
    path: &str,
    body: Option<&[u8]>,
    host: &str,
) -> std::io::Result<Response> {
    let mut s = TcpStream::connect_timeout(&addr, Duration::from_secs(5))?;
    s.set_read_timeout(Some(Duration::from_secs(60)))?;
    s.set_write_timeout(Some(Duration::from_secs(60)))?;
    let body = body.unwrap_or(b"");
    let head = format!(
        "{method} {path} HTTP/1.1\r\nHost: {host}\r\nConnection: close\r\nContent-Type: application/json\r\n\
         Content-Length: {}\r\n\r\n",
        body.len()
    );
    s.write_all(head.as_bytes())?;
    // A server may answer (413) before the whole body is sent and close: ignore write errors then.
    let _ = s.write_all(body);
    // Read until the body is complete by Content-Length (some servers ignore `Connection: close`).
    let mut raw = Vec::new();
    let mut buf = [0u8; 16384];
    loop {
        let n = s.read(&mut buf)?;
        if n == 0 {
            break;
        }
        raw.extend_from_slice(&buf[..n]);
        if let Some(split) = raw.windows(4).position(|w| w == b"\r\n\r\n") {
            let head = String::from_utf8_lossy(&raw[..split]).to_ascii_lowercase();
            let len = head
                .lines()
                .find_map(|l| l.strip_prefix("content-length:"))
                .and_then(|v| v.trim().parse::<usize>().ok());
            match len {
                Some(len) if raw.len() >= split + 4 + len => {
                    raw.truncate(split + 4 + len);
                    break;
                }
                None if head.contains("transfer-encoding: chunked") && raw.ends_with(b"\r\n0\r\n\r\n") => break,
                _ => {}
            }
        }
    }
    parse_response(&raw)
}

fn parse_response(raw: &[u8]) -> std::io::Result<Response> {
    let bad = |m: &str| std::io::Error::new(std::io::ErrorKind::InvalidData, m.to_string());
    let split = raw.windows(4).position(|w| w == b"\r\n\r\n").ok_or_else(|| bad("no header end"))?;
    let head = String::from_utf8_lossy(&raw[..split]).to_string();
    let mut body = raw[split + 4..].to_vec();
    let status: u16 =
        head.split_whitespace().nth(1).and_then(|s| s.parse().ok()).ok_or_else(|| bad("no status code"))?;
    if head.to_ascii_lowercase().contains("transfer-encoding: chunked") {
        body = dechunk(&body).ok_or_else(|| bad("bad chunked body"))?;
    }
    Ok(Response { status, body: String::from_utf8_lossy(&body).to_string() })
}

fn dechunk(mut b: &[u8]) -> Option<Vec<u8>> {
    let mut out = Vec::new();
    loop {
        let eol = b.windows(2).position(|w| w == b"\r\n")?;
        let size = usize::from_str_radix(std::str::from_utf8(&b[..eol]).ok()?.split(';').next()?.trim(), 16).ok()?;
        b = &b[eol + 2..];
        if size == 0 {
            return Some(out);
        }
        out.extend_from_slice(b.get(..size)?);
        b = b.get(size + 2..)?;
    }
}

/// A workbench server on a free loopback port, running on a thread of its own until the test ends.
pub fn spawn_server() -> SocketAddr {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let rt = tokio::runtime::Builder::new_multi_thread().worker_threads(2).enable_all().build().expect("runtime");
        rt.block_on(async move {
            let bound = loomkin_web::bind(0).await.expect("bind 127.0.0.1:0");
            tx.send(bound.addr()).expect("send address");
            bound.run_until(std::future::pending()).await.expect("serve");
        });
    });
    rx.recv_timeout(Duration::from_secs(10)).expect("server did not start")
}

/// One request through the router; a 503 (the heavy slots taken by another test running in
/// parallel) is retried after a short wait, as a client told `Retry-After` would.
pub async fn oneshot(method: &str, path: &str, body: Option<String>) -> (StatusCode, String, String) {
    let mut tries = 0;
    let res = loop {
        let req = Request::builder()
            .method(method)
            .uri(path)
            .header(header::CONTENT_TYPE, "application/json")
            .body(body.clone().map_or_else(Body::empty, Body::from))
            .expect("request");
        let res = loomkin_web::router().oneshot(req).await.expect("infallible");
        tries += 1;
        if res.status() != StatusCode::SERVICE_UNAVAILABLE || tries > 600 {
            break res;
        }
        assert!(res.headers().contains_key(header::RETRY_AFTER), "a 503 without Retry-After");
        tokio::time::sleep(std::time::Duration::from_millis(50)).await;
    };
    let status = res.status();
    let ctype = res.headers().get(header::CONTENT_TYPE).and_then(|v| v.to_str().ok()).unwrap_or("").to_string();
    let bytes = to_bytes(res.into_body(), usize::MAX).await.expect("body");
    (status, ctype, String::from_utf8_lossy(&bytes).to_string())
}

/// The schema of the request key `path` (`design.roller_radius_mm`) in a route's request schema
/// of `GET /api/schema`, its `$ref`s and optional values (`anyOf` with `null`) resolved.
pub fn schema_at<'a>(root: &'a serde_json::Value, path: &str) -> &'a serde_json::Value {
    use serde_json::Value;
    let deref = |mut s: &'a Value| loop {
        if let Some(r) = s.get("$ref").and_then(Value::as_str) {
            s = &root["$defs"][r.trim_start_matches("#/$defs/")];
        } else if let Some(a) = s.get("anyOf").and_then(Value::as_array) {
            s = a.iter().find(|b| b["type"] != "null").expect("a non-null branch");
        } else {
            return s;
        }
    };
    let mut s = deref(root);
    for key in path.split('.') {
        s = deref(&s["properties"][key]);
        assert!(s.is_object(), "no schema for {path}");
    }
    s
}
