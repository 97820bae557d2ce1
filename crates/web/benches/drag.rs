//! The server's work for one drag update of the servo law editor: rebuild the spline law from the
//! definition points, sample it at 1000 points, torque curves and summaries at two speeds.
//!
//! `cargo bench -p loomkin-web --bench drag`

use loomkin_web::{EvaluateRequest, ServoDesign, evaluate, parse_json};

fn main() {
    divan::main();
}

fn request() -> EvaluateRequest {
    EvaluateRequest { design: ServoDesign::default(), samples: 1000 }
}

/// The computation alone (what the handler runs on the blocking pool).
#[divan::bench]
fn evaluate_1000_samples_two_speeds(bencher: divan::Bencher) {
    let mut req = request();
    let mut k = 0u32;
    bencher.bench_local(|| {
        // A different point position every call, as while dragging.
        k = k.wrapping_add(1);
        req.design.points[2][1] = 0.6 + 0.3 * f64::from(k % 100) / 100.0;
        divan::black_box(evaluate(divan::black_box(&req)).ok())
    });
}

/// The whole request as the server sees it: decode the JSON body, compute, encode the answer.
#[divan::bench]
fn decode_evaluate_encode(bencher: divan::Bencher) {
    let body = serde_json::to_vec(&serde_json::json!({ "design": ServoDesign::default(), "samples": 1000 }))
        .unwrap_or_default();
    bencher.bench_local(|| {
        let req: EvaluateRequest = match parse_json(divan::black_box(&body)) {
            Ok(r) => r,
            Err(_) => return 0,
        };
        evaluate(&req).ok().and_then(|r| serde_json::to_vec(&r).ok()).map_or(0, |v| v.len())
    });
}

/// The answer's encoding alone (the JSON the page receives on every drag: 274 006 bytes for the
/// default design at 1000 samples, counted as bytes).
#[divan::bench]
fn encode_answer(bencher: divan::Bencher) {
    let Ok(answer) = evaluate(&request()) else { return };
    let len = serde_json::to_vec(&answer).map_or(0, |v| v.len());
    bencher
        .counter(divan::counter::BytesCount::new(len))
        .bench_local(|| serde_json::to_vec(divan::black_box(&answer)).map_or(0, |v| v.len()));
}
