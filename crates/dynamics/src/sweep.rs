//! Speed sweeps: the figures of the response against the shaft speed.

use crate::Result;
use crate::follower::Follower;
use crate::response::Response;
use crate::trajectory::Start;
use loomkin_laws::Cycle;
use loomkin_units::ShaftSpeed;
use rayon::prelude::*;
use serde::Serialize;

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
