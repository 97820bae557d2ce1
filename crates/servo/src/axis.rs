//! A servo axis: a motor and the load it moves through a transmission, read from TOML.
//!
//! # The model
//!
//! The slave moves by `y` — metres for a translating follower (a cycle in `mm`), radians for a
//! swinging one (a cycle in `deg`). The transmission turns the motor by `θ = k·y`: for a
//! translating slave `k = 2π / ℓ` with `ℓ` the travel per motor revolution (`travel_mm_per_rev`:
//! pinion circumference over gear ratio, screw lead, belt pulley circumference …); for a swinging
//! slave `k = i`, the gear ratio (`gear_ratio`, motor turns per slave turn). The load resists with
//!
//! $$ F = m\ddot y + c\dot y + F_\mu\,\mathrm{sgn}\,\dot y + k_s y + F_0 $$
//!
//! (`m` the moving mass in kg or the load inertia in kg·m², `c` viscous friction, `F_μ` Coulomb
//! friction, `k_s` a spring, `F₀` its preload plus any constant force such as a weight; N and N·m
//! alike), and the motor gives
//!
//! $$ T = (J_m + J_x)\,k\,\ddot y + \frac{F}{k\,\eta}, $$
//!
//! `J_m` the rotor inertia, `J_x` any extra inertia on the motor shaft (coupling, gearbox input),
//! `η` the transmission efficiency. Dividing by `η` at every instant (also while braking) errs on
//! the safe side, as the needle-rack [`crate::Drive`] does; a [`Drive`](crate::Drive) is such an
//! axis ([`Axis::from_drive`]). In a dwell the Coulomb friction is taken as zero (the axis holds).
//!
//! The inertia ratio is the load's inertia reflected to the motor over the rotor's,
//! `(m/k² + J_x) / J_m`.
//!
//! # The motor envelope
//!
//! Continuous (S1): the rated torque up to the rated speed. Peak: the peak torque up to the rated
//! speed, then a straight line to `torque_at_max_speed_nm` (default: the rated torque) at the
//! maximum speed — a simplified voltage-limit line; beyond the maximum speed, nothing.

use crate::{Drive, Result, ServoError};
use loomkin_laws::StrokeUnit;
use loomkin_units::Range;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The motor's data.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Motor {
    /// Rated (continuous, S1) torque (N·m), > 0.
    pub rated_torque_nm: f64,
    /// Peak torque (N·m), ≥ rated.
    pub peak_torque_nm: f64,
    /// Rated speed (rpm), > 0.
    pub rated_speed_rpm: f64,
    /// Maximum speed (rpm), ≥ rated.
    pub max_speed_rpm: f64,
    /// Rotor inertia `J_m` (kg·m²), > 0.
    pub rotor_inertia_kg_m2: f64,
    /// Peak torque available at the maximum speed (N·m); default the rated torque.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torque_at_max_speed_nm: Option<f64>,
}

/// The load and the transmission. Forces in N for a translating slave, torques in N·m for a
/// swinging one (the keys keep the names `_n`, read them as N·m there).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Load {
    /// Moving mass (kg) of a translating slave.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub moving_mass_kg: Option<f64>,
    /// Inertia (kg·m²) of a swinging slave about its pivot.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub load_inertia_kg_m2: Option<f64>,
    /// Slave travel per motor revolution (mm/rev) of a translating slave.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub travel_mm_per_rev: Option<f64>,
    /// Motor turns per slave turn of a swinging slave.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gear_ratio: Option<f64>,
    /// Efficiency `η` of the transmission, 0 < η ≤ 1 (default 1).
    #[serde(default = "one")]
    pub efficiency: f64,
    /// Coulomb friction `F_μ` (N, or N·m), ≥ 0.
    #[serde(default)]
    pub friction_n: f64,
    /// Viscous friction `c` (N·s/m, or N·m·s/rad), ≥ 0.
    #[serde(default)]
    pub viscous_n_s_m: f64,
    /// Spring stiffness `k_s` (N/m, or N·m/rad).
    #[serde(default)]
    pub spring_n_m: f64,
    /// Spring force at `y = 0` plus any constant force (N, or N·m), `F₀`.
    #[serde(default)]
    pub constant_force_n: f64,
    /// Extra inertia on the motor shaft `J_x` (kg·m²), ≥ 0.
    #[serde(default)]
    pub extra_inertia_kg_m2: f64,
}

fn one() -> f64 {
    1.0
}

fn default_ratio() -> f64 {
    10.0
}

/// Limits of the check.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Limits {
    /// Largest admissible inertia ratio (default 10).
    #[serde(default = "default_ratio")]
    pub max_inertia_ratio: f64,
}

impl Default for Limits {
    fn default() -> Self {
        Self { max_inertia_ratio: default_ratio() }
    }
}

/// A servo axis: motor, load, limits (an axis file: `[motor]`, `[load]`, optional `[limits]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Axis {
    /// The motor.
    pub motor: Motor,
    /// The load and transmission.
    pub load: Load,
    /// The limits.
    #[serde(default)]
    pub limits: Limits,
}

impl Axis {
    /// Reads an axis file and checks it against the slave unit of the motion it will move.
    pub fn from_toml(text: &str, unit: StrokeUnit) -> Result<Self> {
        let axis: Axis = toml::from_str(text).map_err(|e| ServoError::Parse {
            field: "axis file".into(),
            text: loomkin_units::toml_reason(text, &e),
            expected: "TOML with [motor] (rated_torque_nm, peak_torque_nm, rated_speed_rpm, max_speed_rpm, \
                           rotor_inertia_kg_m2) and [load] tables"
                .into(),
        })?;
        axis.validate(unit)?;
        Ok(axis)
    }

    /// The needle-rack drive as an axis (translating slave): mass, pinion and gear, motor inertia,
    /// spring, preload and constant force, viscous damping and efficiency carried over; the motor
    /// data are not part of a drive and come from `motor`.
    pub fn from_drive(drive: &Drive, motor: Motor) -> Self {
        Self {
            motor: Motor { rotor_inertia_kg_m2: drive.motor_inertia_kg_m2, ..motor },
            load: Load {
                moving_mass_kg: Some(drive.moving_mass_kg),
                load_inertia_kg_m2: None,
                travel_mm_per_rev: Some(2.0 * PI * drive.pinion_radius_m / drive.gear_ratio * 1e3),
                gear_ratio: None,
                efficiency: drive.efficiency,
                friction_n: 0.0,
                viscous_n_s_m: drive.damping_n_s_m,
                spring_n_m: drive.spring_n_m,
                constant_force_n: drive.spring_preload_n + drive.constant_force_n,
                extra_inertia_kg_m2: 0.0,
            },
            limits: Limits::default(),
        }
    }

    /// Checks every field, and that the load is given in the terms of `unit` (mass and travel per
    /// revolution for `mm`, inertia and gear ratio for `deg`).
    pub fn validate(&self, unit: StrokeUnit) -> Result<()> {
        let c = |field: &str, v: f64, lo: f64, hi: f64, unit: &'static str| Range::closed(lo, hi, unit).check(field, v);
        let m = &self.motor;
        c("motor.rated_torque_nm", m.rated_torque_nm, 1e-9, 1e9, "N·m")?;
        c("motor.peak_torque_nm", m.peak_torque_nm, m.rated_torque_nm, 1e9, "N·m")?;
        c("motor.rated_speed_rpm", m.rated_speed_rpm, 1e-6, 1e7, "rpm")?;
        c("motor.max_speed_rpm", m.max_speed_rpm, m.rated_speed_rpm, 1e7, "rpm")?;
        c("motor.rotor_inertia_kg_m2", m.rotor_inertia_kg_m2, 1e-12, 1e6, "kg·m²")?;
        if let Some(t) = m.torque_at_max_speed_nm {
            c("motor.torque_at_max_speed_nm", t, 0.0, m.peak_torque_nm, "N·m")?;
        }
        let l = &self.load;
        let (mass_key, ratio_key, other_mass, other_ratio) = match unit {
            StrokeUnit::Mm => ("moving_mass_kg", "travel_mm_per_rev", l.load_inertia_kg_m2, l.gear_ratio),
            StrokeUnit::Deg => ("load_inertia_kg_m2", "gear_ratio", l.moving_mass_kg, l.travel_mm_per_rev),
        };
        if other_mass.is_some() || other_ratio.is_some() {
            let (a, b) = match unit {
                StrokeUnit::Mm => ("load_inertia_kg_m2 or gear_ratio", "a translating (mm) motion"),
                StrokeUnit::Deg => ("moving_mass_kg or travel_mm_per_rev", "a swinging (deg) motion"),
            };
            return Err(ServoError::Parse {
                field: format!("load.{}", a.split(' ').next().unwrap_or(a)),
                text: a.into(),
                expected: format!("{mass_key} and {ratio_key} for {b}"),
            });
        }
        let (mass, ratio) = match unit {
            StrokeUnit::Mm => (l.moving_mass_kg, l.travel_mm_per_rev),
            StrokeUnit::Deg => (l.load_inertia_kg_m2, l.gear_ratio),
        };
        let need = |key: &str, v: Option<f64>| {
            v.ok_or_else(|| ServoError::Parse {
                field: format!("load.{key}"),
                text: "missing".into(),
                expected: format!("a number (the load needs {mass_key} and {ratio_key})"),
            })
        };
        c(&format!("load.{mass_key}"), need(mass_key, mass)?, 0.0, 1e9, "")?;
        c(&format!("load.{ratio_key}"), need(ratio_key, ratio)?, 1e-9, 1e9, "")?;
        c("load.efficiency", l.efficiency, 1e-3, 1.0, "")?;
        c("load.friction_n", l.friction_n, 0.0, 1e9, "")?;
        c("load.viscous_n_s_m", l.viscous_n_s_m, 0.0, 1e9, "")?;
        c("load.spring_n_m", l.spring_n_m, -1e12, 1e12, "")?;
        c("load.constant_force_n", l.constant_force_n, -1e9, 1e9, "")?;
        c("load.extra_inertia_kg_m2", l.extra_inertia_kg_m2, 0.0, 1e6, "kg·m²")?;
        c("limits.max_inertia_ratio", self.limits.max_inertia_ratio, 1e-6, 1e9, "")?;
        Ok(())
    }

    /// `k`, motor radians per slave SI unit (rad/m, or rad/rad).
    pub fn motor_rad_per_unit(&self) -> f64 {
        match (self.load.travel_mm_per_rev, self.load.gear_ratio) {
            (Some(l), _) => 2.0 * PI / (l * 1e-3),
            (None, Some(i)) => i,
            (None, None) => 1.0,
        }
    }

    /// The load's mass or inertia `m`.
    pub fn load_mass(&self) -> f64 {
        self.load.moving_mass_kg.or(self.load.load_inertia_kg_m2).unwrap_or(0.0)
    }

    /// The inertia ratio `(m/k² + J_x) / J_m`.
    pub fn inertia_ratio(&self) -> f64 {
        let k = self.motor_rad_per_unit();
        (self.load_mass() / (k * k) + self.load.extra_inertia_kg_m2) / self.motor.rotor_inertia_kg_m2
    }

    /// The motor torque (N·m) with the slave at position `s`, velocity `v` and acceleration `a`
    /// (SI: m, m/s, m/s² or rad, rad/s, rad/s²): `T = (J_m + J_x)·k·a + F/(k·η)` with the load
    /// force `F` of the model above (the Coulomb friction zero where `v = 0`). What
    /// [`crate::operating_points`] and [`crate::check_axis`] evaluate.
    pub fn torque_at(&self, s: f64, v: f64, a: f64) -> f64 {
        let k = self.motor_rad_per_unit();
        let ke = k * self.load.efficiency;
        let l = &self.load;
        let fric = if v == 0.0 { 0.0 } else { l.friction_n * v.signum() };
        self.torque_inertia() * a + (l.viscous_n_s_m * v + fric + l.spring_n_m * s + l.constant_force_n) / ke
    }

    /// The time derivative of [`Axis::torque_at`] away from a sign change of the velocity (N·m/s),
    /// from the velocity, acceleration and jerk: `(J_m + J_x)·k·j + (c·a + k_s·v)/(k·η)`.
    pub fn torque_rate(&self, v: f64, a: f64, j: f64) -> f64 {
        let ke = self.motor_rad_per_unit() * self.load.efficiency;
        self.torque_inertia() * j + (self.load.viscous_n_s_m * a + self.load.spring_n_m * v) / ke
    }

    /// The motor torque per unit slave acceleration, `(J_m + J_x)·k + m/(k·η)` (N·m per m/s², or
    /// per rad/s²).
    pub fn torque_inertia(&self) -> f64 {
        let k = self.motor_rad_per_unit();
        (self.motor.rotor_inertia_kg_m2 + self.load.extra_inertia_kg_m2) * k
            + self.load_mass() / (k * self.load.efficiency)
    }

    /// The peak-torque line at motor speed `|n|` (rpm) and its slope (N·m per rpm); `None` beyond
    /// the maximum speed.
    pub fn peak_envelope(&self, n_rpm: f64) -> Option<(f64, f64)> {
        let m = &self.motor;
        let n = n_rpm.abs();
        if n <= m.rated_speed_rpm {
            return Some((m.peak_torque_nm, 0.0));
        }
        if n > m.max_speed_rpm * (1.0 + 1e-12) {
            return None;
        }
        let t_max = m.torque_at_max_speed_nm.unwrap_or(m.rated_torque_nm);
        let span = m.max_speed_rpm - m.rated_speed_rpm;
        if span <= 0.0 {
            return Some((m.peak_torque_nm, 0.0));
        }
        let slope = (t_max - m.peak_torque_nm) / span;
        Some((m.peak_torque_nm + slope * (n - m.rated_speed_rpm), slope))
    }
}
