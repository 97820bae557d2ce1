//! The response's figures as users read them: in the cycle's own units (mm and m/s² for a
//! translating follower, deg and rad/s² for a swinging one), with the unit in every key.
//!
//! The CLI (`loomkin dyn response --json`, `loomkin dyn sweep --json`) and the workbench serialise
//! these same structs, so one value has one key everywhere.

use crate::optimize::Optimized;
use crate::response::{Located, Summary};
use crate::sweep::SweepPoint;
use crate::trajectory::Start;
use loomkin_laws::StrokeUnit;
use serde::Serialize;
use serde::ser::{SerializeMap, Serializer};

/// Display units of a cycle: the factor from SI, the position unit and the acceleration unit in keys.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Units {
    /// Factor from SI (m or rad) to the position unit (mm or deg).
    pub scale: f64,
    /// Position unit in keys: `mm` or `deg`.
    pub pos: &'static str,
    /// Acceleration unit in keys: `m_s2` or `rad_s2`.
    pub acc: &'static str,
}

impl Units {
    /// The units of a cycle written in `unit`.
    pub fn of(unit: StrokeUnit) -> Self {
        match unit {
            StrokeUnit::Mm => Units { scale: 1e3, pos: "mm", acc: "m_s2" },
            StrokeUnit::Deg => Units { scale: 180.0 / std::f64::consts::PI, pos: "deg", acc: "rad_s2" },
        }
    }

    /// The acceleration unit as text (`m/s²`, `rad/s²`).
    pub fn acc_text(&self) -> &'static str {
        if self.pos == "mm" { "m/s²" } else { "rad/s²" }
    }
}

/// The summary of one response with the run's settings (`loomkin dyn response --json`).
///
/// Keys (position unit `P` = `mm` or `deg`, acceleration unit `A` = `m_s2` or `rad_s2`):
/// `residual_amplitude_P` (largest over the dwells), `residual_amplitude_pct_of_stroke`,
/// `peak_dynamic_error_P` and `…_at_deg`, `peak_acceleration_A` and `…_at_deg`,
/// `peak_input_acceleration_A`, `rigidity_ratio`, `rigidity_warning`, `dwells` (each `segment`,
/// `cycle`, `angle_deg`, `residual_amplitude_P`), with a mass also `peak_force_n`,
/// `peak_force_at_deg`, `min_contact_force_n`, `min_contact_force_at_deg`, `loses_contact`; and
/// `speed_rpm`, `natural_hz`, `damping_ratio`, `start` (`rest` or `steady`), `cycles`.
#[derive(Debug, Clone, PartialEq)]
pub struct ResponseReport {
    /// The figures.
    pub summary: Summary,
    /// Units of the cycle.
    pub units: Units,
    /// Main-shaft speed (rpm).
    pub speed_rpm: f64,
    /// Natural frequency of the follower (Hz).
    pub natural_hz: f64,
    /// Damping ratio.
    pub damping_ratio: f64,
    /// From rest or the periodic steady state.
    pub start: Start,
    /// Cycles computed (1 in the steady state).
    pub cycles: usize,
}

impl Serialize for ResponseReport {
    fn serialize<S: Serializer>(&self, ser: S) -> Result<S::Ok, S::Error> {
        let (s, u) = (&self.summary, self.units);
        let (p, a) = (u.pos, u.acc);
        let mut m = ser.serialize_map(None)?;
        m.serialize_entry(&format!("residual_amplitude_{p}"), &(s.residual_amplitude_si * u.scale))?;
        m.serialize_entry("residual_amplitude_pct_of_stroke", &s.residual_pct_of_stroke)?;
        m.serialize_entry(&format!("peak_dynamic_error_{p}"), &(s.peak_dynamic_error.value * u.scale))?;
        m.serialize_entry("peak_dynamic_error_at_deg", &s.peak_dynamic_error.angle_deg)?;
        m.serialize_entry(&format!("peak_acceleration_{a}"), &s.peak_acceleration.value)?;
        m.serialize_entry("peak_acceleration_at_deg", &s.peak_acceleration.angle_deg)?;
        m.serialize_entry(&format!("peak_input_acceleration_{a}"), &s.peak_input_acceleration.value)?;
        m.serialize_entry("rigidity_ratio", &s.rigidity_ratio)?;
        m.serialize_entry("rigidity_warning", &s.rigidity_warning)?;
        let dwells: Vec<DwellEntry> = s.dwells.iter().map(|d| DwellEntry { d, units: u }).collect();
        m.serialize_entry("dwells", &dwells)?;
        if let (Some(f), Some(c)) = (s.peak_force_n, s.min_contact_force_n) {
            let Located { value, angle_deg } = f;
            m.serialize_entry("peak_force_n", &value)?;
            m.serialize_entry("peak_force_at_deg", &angle_deg)?;
            m.serialize_entry("min_contact_force_n", &c.value)?;
            m.serialize_entry("min_contact_force_at_deg", &c.angle_deg)?;
            m.serialize_entry("loses_contact", &s.loses_contact)?;
        }
        m.serialize_entry("speed_rpm", &self.speed_rpm)?;
        m.serialize_entry("natural_hz", &self.natural_hz)?;
        m.serialize_entry("damping_ratio", &self.damping_ratio)?;
        m.serialize_entry("start", start_name(self.start))?;
        m.serialize_entry("cycles", &self.cycles)?;
        m.end()
    }
}

/// The figures of a two-mass train over one cycle (`loomkin dyn two-mass --json`), SI inside and
/// in the cycle's units in the keys (`P` = `mm` or `deg`): `natural_hz` (both modes),
/// `peak_drive_error_P` and `…_at_deg`, `peak_frame_error_P` and `…_at_deg`,
/// `frame_residual_bound_P`, `rigidity_ratio` (f₁ / f_shaft), `speed_rpm`, `damping_ratio`, `start`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoMassReport {
    /// Natural frequencies of the two modes (Hz), lower first.
    pub natural_hz: [f64; 2],
    /// Largest |x₁ − s| of the drive (SI) and where (main-shaft deg).
    pub peak_drive_error: Located,
    /// Largest |x₂ − s| of the frame (SI) and where (main-shaft deg).
    pub peak_frame_error: Located,
    /// Bound on the frame's residual vibration in the dwells, largest (SI).
    pub frame_residual_bound_si: f64,
    /// f₁ / f_shaft (VDI 2149 asks for at least [`crate::VDI_2149_MIN_RATIO`]).
    pub rigidity_ratio: f64,
    /// Main-shaft speed (rpm).
    pub speed_rpm: f64,
    /// Modal damping ratio.
    pub damping_ratio: f64,
    /// From rest or the periodic steady state.
    pub start: Start,
    /// Units of the cycle.
    pub units: Units,
}

impl Serialize for TwoMassReport {
    fn serialize<S: Serializer>(&self, ser: S) -> Result<S::Ok, S::Error> {
        let u = self.units;
        let p = u.pos;
        let mut m = ser.serialize_map(Some(10))?;
        m.serialize_entry("natural_hz", &self.natural_hz)?;
        m.serialize_entry(&format!("peak_drive_error_{p}"), &(self.peak_drive_error.value * u.scale))?;
        m.serialize_entry("peak_drive_error_at_deg", &self.peak_drive_error.angle_deg)?;
        m.serialize_entry(&format!("peak_frame_error_{p}"), &(self.peak_frame_error.value * u.scale))?;
        m.serialize_entry("peak_frame_error_at_deg", &self.peak_frame_error.angle_deg)?;
        m.serialize_entry(&format!("frame_residual_bound_{p}"), &(self.frame_residual_bound_si * u.scale))?;
        m.serialize_entry("rigidity_ratio", &self.rigidity_ratio)?;
        m.serialize_entry("speed_rpm", &self.speed_rpm)?;
        m.serialize_entry("damping_ratio", &self.damping_ratio)?;
        m.serialize_entry("start", start_name(self.start))?;
        m.end()
    }
}

/// A speed sweep with the follower it ran on (`loomkin dyn sweep --json`): `natural_hz`,
/// `damping_ratio`, `start`, and `points`, each a row of [`sweep_columns`] as an object.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepReport<'a> {
    /// The sweep's points.
    pub points: &'a [SweepPoint],
    /// Units of the cycle.
    pub units: Units,
    /// Whether the points carry forces (a follower with a mass).
    pub forces: bool,
    /// Natural frequency of the follower (Hz).
    pub natural_hz: f64,
    /// Damping ratio.
    pub damping_ratio: f64,
    /// From rest or the periodic steady state.
    pub start: Start,
}

impl Serialize for SweepReport<'_> {
    fn serialize<S: Serializer>(&self, ser: S) -> Result<S::Ok, S::Error> {
        let mut m = ser.serialize_map(Some(4))?;
        m.serialize_entry("natural_hz", &self.natural_hz)?;
        m.serialize_entry("damping_ratio", &self.damping_ratio)?;
        m.serialize_entry("start", start_name(self.start))?;
        let rows: Vec<SweepEntry> =
            self.points.iter().map(|q| SweepEntry { q, units: self.units, forces: self.forces }).collect();
        m.serialize_entry("points", &rows)?;
        m.end()
    }
}

/// One point of a sweep as an object with the keys of [`sweep_columns`] (`loomkin dyn sweep --json`,
/// one per line with `--shard`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweepEntry<'a> {
    /// The point.
    pub q: &'a SweepPoint,
    /// Units of the cycle.
    pub units: Units,
    /// Whether to write the force columns.
    pub forces: bool,
}

impl Serialize for SweepEntry<'_> {
    fn serialize<S: Serializer>(&self, ser: S) -> Result<S::Ok, S::Error> {
        let cols = sweep_columns(self.units, self.forces);
        let row = sweep_row(self.q, self.units, self.forces);
        let mut m = ser.serialize_map(Some(cols.len()))?;
        for (k, v) in cols.iter().zip(row) {
            m.serialize_entry(k, &v)?;
        }
        m.end()
    }
}

/// A cycle shaped for quiet dwells with the run's settings (`loomkin dyn optimize --json`), the
/// position unit `P` (`mm` or `deg`) in the keys: `speed_rpm`, `band_pct`, `natural_hz`,
/// `damping_ratio`, `residual_amplitude_P`, `modified_sine_residual_amplitude_P`,
/// `improvement_factor`, `peak_acceleration_ratio`, `segments` (each a [`crate::SegmentFigures`]).
#[derive(Debug, Clone, Copy)]
pub struct OptimizeReport<'a> {
    /// The optimised cycle's figures.
    pub optimized: &'a Optimized,
    /// Units of the cycle.
    pub units: Units,
    /// Design speed (rpm).
    pub speed_rpm: f64,
    /// Half-width of the speed band (%).
    pub band_pct: f64,
    /// Natural frequency of the follower (Hz).
    pub natural_hz: f64,
    /// Damping ratio.
    pub damping_ratio: f64,
}

impl Serialize for OptimizeReport<'_> {
    fn serialize<S: Serializer>(&self, ser: S) -> Result<S::Ok, S::Error> {
        let (o, u) = (self.optimized, self.units);
        let p = u.pos;
        let mut m = ser.serialize_map(Some(9))?;
        m.serialize_entry("speed_rpm", &self.speed_rpm)?;
        m.serialize_entry("band_pct", &self.band_pct)?;
        m.serialize_entry("natural_hz", &self.natural_hz)?;
        m.serialize_entry("damping_ratio", &self.damping_ratio)?;
        m.serialize_entry(&format!("residual_amplitude_{p}"), &(o.cycle_residual_si * u.scale))?;
        m.serialize_entry(
            &format!("modified_sine_residual_amplitude_{p}"),
            &(o.cycle_residual_modified_sine_si * u.scale),
        )?;
        m.serialize_entry("improvement_factor", &o.improvement_factor())?;
        m.serialize_entry("peak_acceleration_ratio", &o.peak_acceleration_ratio)?;
        m.serialize_entry("segments", &o.segments)?;
        m.end()
    }
}

/// `rest`, `steady` or `state` (a given initial state), as the JSON names the start.
pub fn start_name(start: Start) -> &'static str {
    match start {
        Start::Rest => "rest",
        Start::Steady => "steady",
        Start::State(..) => "state",
    }
}

struct DwellEntry<'a> {
    d: &'a crate::response::DwellResidual,
    units: Units,
}

impl Serialize for DwellEntry<'_> {
    fn serialize<S: Serializer>(&self, ser: S) -> Result<S::Ok, S::Error> {
        let mut m = ser.serialize_map(Some(4))?;
        m.serialize_entry("segment", &self.d.segment)?;
        m.serialize_entry("cycle", &self.d.cycle)?;
        m.serialize_entry("angle_deg", &self.d.angle_deg)?;
        m.serialize_entry(
            &format!("residual_amplitude_{}", self.units.pos),
            &(self.d.amplitude_si * self.units.scale),
        )?;
        m.end()
    }
}

/// The column names of a speed sweep's table (`loomkin dyn sweep --csv`): `speed_rpm`,
/// `residual_amplitude_P`, `residual_amplitude_pct_of_stroke`, `peak_dynamic_error_P`,
/// `rigidity_ratio`, and with forces `peak_force_n`, `min_contact_force_n`.
pub fn sweep_columns(units: Units, forces: bool) -> Vec<String> {
    let p = units.pos;
    let mut cols = vec![
        "speed_rpm".to_string(),
        format!("residual_amplitude_{p}"),
        "residual_amplitude_pct_of_stroke".into(),
        format!("peak_dynamic_error_{p}"),
        "rigidity_ratio".into(),
    ];
    if forces {
        cols.push("peak_force_n".into());
        cols.push("min_contact_force_n".into());
    }
    cols
}

/// One row of a sweep's table in the order of [`sweep_columns`].
pub fn sweep_row(q: &SweepPoint, units: Units, forces: bool) -> Vec<f64> {
    let mut r = vec![
        q.speed_rpm,
        q.residual_amplitude_si * units.scale,
        q.residual_pct_of_stroke,
        q.peak_dynamic_error_si * units.scale,
        q.rigidity_ratio,
    ];
    if forces {
        r.push(q.peak_force_n.unwrap_or(0.0));
        r.push(q.min_contact_force_n.unwrap_or(0.0));
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Follower, Response};
    use loomkin_laws::Cycle;
    use loomkin_units::ShaftSpeed;

    #[test]
    fn keys_carry_the_cycles_units_and_values_are_scaled() {
        let text =
            std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/heald-frame-cycle.toml"))
                .unwrap();
        let cycle = Cycle::from_toml(&text).unwrap();
        let f = Follower::new(54.0, 0.05).unwrap().with_loads(20.0, 5e3, 200.0).unwrap();
        let r = Response::new(&cycle, ShaftSpeed::from_rpm(600.0).unwrap(), &f, Start::Rest, 1).unwrap();
        let summary = r.summary();
        let report = ResponseReport {
            summary: summary.clone(),
            units: Units::of(cycle.unit),
            speed_rpm: 600.0,
            natural_hz: 54.0,
            damping_ratio: 0.05,
            start: Start::Rest,
            cycles: 1,
        };
        let v = serde_json::to_value(&report).unwrap();
        assert_eq!(v["residual_amplitude_mm"].as_f64().unwrap(), summary.residual_amplitude_si * 1e3);
        assert_eq!(v["peak_dynamic_error_mm"].as_f64().unwrap(), summary.peak_dynamic_error.value * 1e3);
        assert_eq!(v["peak_acceleration_m_s2"].as_f64().unwrap(), summary.peak_acceleration.value);
        assert_eq!(v["peak_force_n"].as_f64().unwrap(), summary.peak_force_n.unwrap().value);
        assert_eq!(v["dwells"].as_array().unwrap().len(), summary.dwells.len());
        assert_eq!(v["start"], "rest");
        let d0 = &v["dwells"][0];
        assert_eq!(d0["residual_amplitude_mm"].as_f64().unwrap(), summary.dwells[0].amplitude_si * 1e3);
        let cols = sweep_columns(Units::of(cycle.unit), true);
        assert_eq!(cols[..2], ["speed_rpm".to_string(), "residual_amplitude_mm".to_string()]);
        let u = Units::of(StrokeUnit::Deg);
        assert!((u.scale * std::f64::consts::PI - 180.0).abs() < 1e-12);
    }
}
