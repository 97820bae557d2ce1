//! Drag-update latency while heavy optimisations run: a workbench on 127.0.0.1 (only), eight
//! clients asking for heavy optimisations without pause (64 definition points, six speeds, RMS;
//! a 503 is retried after 100 ms), and one client sending drag updates (`/api/servo/evaluate`,
//! 1000 samples, a point moved each time). Prints the drag latency p50/p99/max.
//!
//! `cargo run --release -p loomkin-web --example drag_under_load [-- DRAGS]` (default 400 drags;
//! bounded: at most 2000 drags and 120 s).

use loomkin_web::ServoDesign;
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

fn post(addr: SocketAddr, path: &str, body: &str) -> std::io::Result<u16> {
    let mut s = TcpStream::connect_timeout(&addr, Duration::from_secs(5))?;
    s.set_read_timeout(Some(Duration::from_secs(120)))?;
    let head = format!(
        "POST {path} HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\nContent-Type: application/json\r\n\
         Content-Length: {}\r\n\r\n",
        body.len()
    );
    s.write_all(head.as_bytes())?;
    s.write_all(body.as_bytes())?;
    let mut raw = Vec::new();
    s.read_to_end(&mut raw)?;
    let text = String::from_utf8_lossy(&raw);
    Ok(text.split_whitespace().nth(1).and_then(|c| c.parse().ok()).unwrap_or(0))
}

fn heavy_design() -> ServoDesign {
    let n = 64;
    let points = (0..n)
        .map(|j| {
            let x = 0.5 * j as f64 / (n - 1) as f64;
            [x, (2.0 * std::f64::consts::TAU * x).sin() * if j == 0 || j == n - 1 { 0.0 } else { 1.0 }]
        })
        .collect();
    ServoDesign { points, speeds_rpm: vec![400.0, 500.0, 600.0, 700.0, 800.0, 900.0], ..ServoDesign::default() }
}

fn main() {
    let drags: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(400).clamp(10, 2000);
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let rt = tokio::runtime::Builder::new_multi_thread().enable_all().build().expect("runtime");
        rt.block_on(async move {
            let bound = loomkin_web::bind(0).await.expect("bind 127.0.0.1:0");
            tx.send(bound.addr()).expect("send");
            bound.run_until(std::future::pending()).await.expect("serve");
        });
    });
    let addr = rx.recv_timeout(Duration::from_secs(10)).expect("server");
    assert!(addr.ip().is_loopback());
    let deadline = Instant::now() + Duration::from_secs(120);
    let done = Arc::new(AtomicBool::new(false));
    let (finished, busy) = (Arc::new(AtomicUsize::new(0)), Arc::new(AtomicUsize::new(0)));
    let heavy_body = serde_json::json!({"design": heavy_design(), "objective": "rms"}).to_string();
    let heavy: Vec<_> = (0..8)
        .map(|_| {
            let (done, finished, busy, body) = (done.clone(), finished.clone(), busy.clone(), heavy_body.clone());
            std::thread::spawn(move || {
                while !done.load(Ordering::Relaxed) && Instant::now() < deadline {
                    match post(addr, "/api/servo/optimize", &body) {
                        Ok(503) => {
                            busy.fetch_add(1, Ordering::Relaxed);
                            std::thread::sleep(Duration::from_millis(100));
                        }
                        _ => {
                            finished.fetch_add(1, Ordering::Relaxed);
                        }
                    }
                }
            })
        })
        .collect();
    std::thread::sleep(Duration::from_millis(500));
    let mut design = ServoDesign::default();
    let mut lat = Vec::with_capacity(drags);
    for k in 0..drags {
        if Instant::now() > deadline {
            break;
        }
        design.points[2][1] = 0.6 + 0.3 * (k % 100) as f64 / 100.0;
        let body = serde_json::json!({"design": design, "samples": 1000}).to_string();
        let t0 = Instant::now();
        let status = post(addr, "/api/servo/evaluate", &body).expect("drag answer");
        lat.push(t0.elapsed().as_secs_f64() * 1e3);
        assert_eq!(status, 200);
        std::thread::sleep(Duration::from_millis(10));
    }
    done.store(true, Ordering::Relaxed);
    lat.sort_by(f64::total_cmp);
    let q = |p: f64| lat[((lat.len() as f64 - 1.0) * p).round() as usize];
    println!(
        "drag updates: {} | p50 {:.2} ms | p99 {:.2} ms | max {:.2} ms | heavy slots {} | heavy answered {} | 503 refusals {}",
        lat.len(),
        q(0.5),
        q(0.99),
        lat[lat.len() - 1],
        loomkin_web::heavy_slots(),
        finished.load(Ordering::Relaxed),
        busy.load(Ordering::Relaxed)
    );
    // The heavy clients stop after their current request; do not wait for a long one.
    drop(heavy);
}
