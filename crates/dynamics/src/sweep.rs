//! Speed sweeps: the figures of the response against the shaft speed.

use crate::Result;
use crate::follower::Follower;
use crate::response::Response;
use crate::trajectory::Start;
use loomkin_laws::Cycle;
use loomkin_units::{Field, Range, ShaftSpeed};
use rayon::prelude::*;
use serde::Serialize;

impl SweepPoint {
    /// `speed_rpm` of a sweep held as arrays (Python): how many speeds, 1 … 10⁶ (each one response,
    /// µs to ms); the CLI streams its rows and its time budget bounds how many.
    pub const SPEEDS: Field = Field::count(
        "speed_rpm",
        Range::closed(1.0, 1e6, ""),
        "Speeds of a sweep held as arrays: 1 … 10⁶ of them (each one response), each in the shaft-speed range; a streamed sweep is bounded by the time budget.",
    );
    /// `residual_limit_pct`: the residual amplitude a design accepts, 0 < L ≤ 100 % of the stroke;
    /// 1 % (a heald frame's usual allowance).
    pub const RESIDUAL_LIMIT_PCT: Field = Field::new(
        "residual_limit_pct",
        Range::open_closed(0.0, 100.0, "%"),
        "Residual amplitude a design accepts, % of the stroke: 0 < L ≤ 100; 1 % when left out.",
    )
    .with_default(1.0);

    /// CPU seconds per speed and cycle segment (one closed-form response), measured on the
    /// reference machine (release, one core): 5 µs.
    pub const CPU_S_PER_SEGMENT: f64 = 5e-6;
    /// Bytes a front end holds per speed for a JSON row until it prints the array (an object of
    /// a dozen keys and numbers, rounded up).
    pub const JSON_ROW_BYTES: f64 = 1000.0;
    /// Bytes held per speed: the point, its table row and the list of speeds.
    pub const BYTES_PER_SPEED: f64 = 96.0 + 104.0 + 8.0;

    /// What a sweep of `speeds` speeds over a cycle of `segments` segments on `threads` threads
    /// costs, estimated before it runs ([`loomkin_units::Cost::cpu_items`]), each speed holding its
    /// point and `row_bytes` more (the text a front end keeps for it).
    pub fn cost(speeds: f64, segments: usize, threads: f64, row_bytes: f64) -> loomkin_units::Cost {
        let per = Self::CPU_S_PER_SEGMENT * segments as f64 / threads.max(1.0);
        loomkin_units::Cost::cpu_items(speeds, Self::BYTES_PER_SPEED + row_bytes, per)
    }
}

/// The response's figures at one speed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SweepPoint {
    /// Shaft speed (rpm).
    pub speed_rpm: f64,
    /// Largest residual amplitude over the dwells (SI).
    pub residual_amplitude_si: f64,
    /// The same in % of the largest stroke.
    pub residual_pct_of_stroke: f64,
    /// Largest |x − s| (SI).
    pub peak_dynamic_error_si: f64,
    /// Largest |train force| (N), when a mass is given.
    pub peak_force_n: Option<f64>,
    /// Smallest contact force (N), when a mass is given.
    pub min_contact_force_n: Option<f64>,
    /// f_n / f_shaft.
    pub rigidity_ratio: f64,
}

/// The figures at one speed.
pub fn sweep_point(cycle: &Cycle, follower: &Follower, speed: ShaftSpeed, start: Start) -> Result<SweepPoint> {
    let r = Response::new(cycle, speed, follower, start, 1)?;
    let s = r.summary_of(false);
    // An extreme follower (natural_hz = 8e-174) inside its range may overflow the figures: refuse
    // it naming the input rather than hand on a non-finite number.
    let figures = [s.residual_amplitude_si, s.residual_pct_of_stroke, s.peak_dynamic_error.value, s.rigidity_ratio];
    if figures.iter().any(|v| !v.is_finite()) {
        return Err(crate::DynError::Input {
            field: "natural_hz".into(),
            reason: format!(
                "natural_hz = {} gives non-finite figures at {} rpm (an overflow): the follower is too soft for this \
                 model",
                loomkin_units::compact(follower.natural_hz()),
                loomkin_units::compact(speed.rpm())
            ),
        });
    }
    Ok(SweepPoint {
        speed_rpm: speed.rpm(),
        residual_amplitude_si: s.residual_amplitude_si,
        residual_pct_of_stroke: s.residual_pct_of_stroke,
        peak_dynamic_error_si: s.peak_dynamic_error.value,
        peak_force_n: s.peak_force_n.map(|f| f.value),
        min_contact_force_n: s.min_contact_force_n.map(|f| f.value),
        rigidity_ratio: s.rigidity_ratio,
    })
}

/// The figures at every speed (rpm), in parallel; the first failing speed's error is returned.
pub fn sweep(cycle: &Cycle, follower: &Follower, speeds_rpm: &[f64], start: Start) -> Result<Vec<SweepPoint>> {
    speeds_rpm.par_iter().map(|&rpm| sweep_point(cycle, follower, ShaftSpeed::from_rpm(rpm)?, start)).collect()
}

/// The speed ranges of a sweep over which the residual amplitude exceeds `level_si` (the speeds
/// to avoid), `[from_rpm, to_rpm]` each. `points` is a sweep in increasing speed; where the
/// residual crosses the level between two of its speeds the crossing is found by bisection on the
/// model itself ([`sweep_point`] at the midpoint, to 1e-9 of the speed), not interpolated. A range
/// that starts or ends with the sweep starts or ends at its first or last speed.
pub fn speeds_above(
    cycle: &Cycle,
    follower: &Follower,
    points: &[SweepPoint],
    start: Start,
    level_si: f64,
) -> Result<Vec<[f64; 2]>> {
    let above = |p: &SweepPoint| p.residual_amplitude_si > level_si;
    let crossing = |lo: f64, hi: f64, lo_above: bool| -> Result<f64> {
        let (a, b) = loomkin_numeric::try_bisect_bracket_within(lo, hi, 1e-9, |m| -> Result<bool> {
            Ok(above(&sweep_point(cycle, follower, ShaftSpeed::from_rpm(m)?, start)?) == lo_above)
        })?;
        Ok(0.5 * (a + b))
    };
    let mut out = Vec::new();
    let mut open: Option<f64> = None;
    for (i, p) in points.iter().enumerate() {
        let now = above(p);
        if i == 0 {
            if now {
                open = Some(p.speed_rpm);
            }
            continue;
        }
        let prev = &points[i - 1];
        if now != above(prev) {
            let x = crossing(prev.speed_rpm, p.speed_rpm, above(prev))?;
            match open.take() {
                Some(from) => out.push([from, x]),
                None => open = Some(x),
            }
        }
    }
    if let (Some(from), Some(last)) = (open, points.last()) {
        out.push([from, last.speed_rpm]);
    }
    Ok(out)
}

#[cfg(test)]
mod finite_tests {
    use super::*;

    /// A follower so soft that the figures overflow is refused naming `natural_hz`, not handed on.
    #[test]
    fn an_overflowing_follower_is_refused_by_name() {
        let text =
            std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/heald-frame-cycle.toml"))
                .unwrap();
        let cycle = Cycle::from_toml(&text).unwrap();
        // Since natural_hz ≥ 1e-3 Hz such a follower is refused when it is built.
        let e = Follower::new(8e-174, 0.0).unwrap_err().to_string();
        assert!(e.starts_with("natural_hz = ") && !e.contains("inf"), "{e}");
        // The softest allowed follower stays finite.
        let soft = sweep(&cycle, &Follower::new(1e-3, 0.0).unwrap(), &[200.0, 1e5], Start::Rest).unwrap();
        assert!(soft.iter().all(|p| p.residual_amplitude_si.is_finite() && p.peak_dynamic_error_si.is_finite()));
        let ok = sweep(&cycle, &Follower::new(80.0, 0.05).unwrap(), &[200.0], Start::Rest).unwrap();
        assert!(ok[0].residual_amplitude_si.is_finite());
    }
}

#[cfg(test)]
mod above_tests {
    use super::*;

    /// Every sweep speed inside a reported range is above the level and every one outside is not;
    /// at each inner edge the model itself gives the level (the crossing is located, not
    /// interpolated between the sweep's speeds).
    #[test]
    fn speeds_above_a_level_are_bracketed_by_located_crossings() {
        let text =
            std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/heald-frame-cycle.toml"))
                .unwrap();
        let cycle = Cycle::from_toml(&text).unwrap();
        let f = Follower::new(54.0, 0.05).unwrap();
        let speeds: Vec<f64> = (0..=80).map(|i| 200.0 + 10.0 * f64::from(i)).collect();
        let pts = sweep(&cycle, &f, &speeds, Start::Rest).unwrap();
        // The residual rises above 4 mm near 470 rpm, falls below it near 560 and rises again.
        let level = 4e-3;
        let ranges = speeds_above(&cycle, &f, &pts, Start::Rest, level).unwrap();
        assert!(ranges.len() >= 2, "the heald example crosses 4 mm several times: {ranges:?}");
        for p in &pts {
            let inside = ranges.iter().any(|[a, b]| p.speed_rpm >= *a && p.speed_rpm <= *b);
            assert_eq!(inside, p.residual_amplitude_si > level, "at {} rpm", p.speed_rpm);
        }
        let (lo, hi) = (speeds[0], speeds[speeds.len() - 1]);
        for edge in ranges.iter().flatten().filter(|e| **e != lo && **e != hi) {
            let q = sweep_point(&cycle, &f, ShaftSpeed::from_rpm(*edge).unwrap(), Start::Rest).unwrap();
            assert!(
                (q.residual_amplitude_si - level).abs() < 1e-6 * level,
                "{} at {edge} rpm",
                q.residual_amplitude_si
            );
            // Not a sweep speed: the edge lies strictly between two of them.
            assert!(speeds.iter().all(|s| (s - edge).abs() > 1e-6));
        }
    }
}
