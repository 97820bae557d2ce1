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

use crate::crank_lever::{CrankLever, Linkage, MotorMotion};
use crate::{Drive, LinearDrive, Result, ServoError};
use loomkin_cams::profile::Jet;
use loomkin_laws::StrokeUnit;
use loomkin_units::{Field, Range};
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
    /// A crank-and-lever transmission (`[load.crank_lever]`) in place of `travel_mm_per_rev`, for
    /// a translating slave: the ratio then changes with the position ([`crate::crank_lever`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crank_lever: Option<CrankLever>,
}

fn one() -> f64 {
    Load::EFFICIENCY.default_value()
}

fn default_ratio() -> f64 {
    Limits::MAX_INERTIA_RATIO.default_value()
}

/// The bounds of an axis file's keys: wide enough for any servo motor from a few grams to a press
/// drive; what they exclude is what the model cannot take (a zero rated torque or speed, a zero
/// rotor inertia in the inertia ratio, a zero efficiency the torque divides by).
impl Motor {
    /// `rated_torque_nm`: 10⁻⁹ … 10⁹ N·m; positive (the S1 check divides by it).
    pub const RATED_TORQUE_NM: Field = Field::new(
        "motor.rated_torque_nm",
        Range::closed(1e-9, 1e9, "N·m"),
        "Rated (continuous, S1) torque of the motor: 10⁻⁹ … 10⁹ N·m; positive (the margins divide by it).",
    );
    /// `peak_torque_nm`: the rated torque … 10⁹ N·m.
    pub const PEAK_TORQUE_NM: Field = Field::new(
        "motor.peak_torque_nm",
        Range::closed(1e-9, 1e9, "N·m"),
        "Peak torque of the motor: at least the rated torque, at most 10⁹ N·m.",
    );
    /// `rated_speed_rpm`: 10⁻⁶ … 10⁷ rpm.
    pub const RATED_SPEED_RPM: Field = Field::new(
        "motor.rated_speed_rpm",
        Range::closed(1e-6, 1e7, "rpm"),
        "Rated speed of the motor (the end of its constant-torque range): 10⁻⁶ … 10⁷ rpm.",
    );
    /// `max_speed_rpm`: the rated speed … 10⁷ rpm.
    pub const MAX_SPEED_RPM: Field = Field::new(
        "motor.max_speed_rpm",
        Range::closed(1e-6, 1e7, "rpm"),
        "Maximum speed of the motor: at least the rated speed, at most 10⁷ rpm.",
    );
    /// `rotor_inertia_kg_m2`: 10⁻¹² … 10⁶ kg·m²; positive (the inertia ratio divides by it).
    pub const ROTOR_INERTIA_KG_M2: Field = Field::new(
        "motor.rotor_inertia_kg_m2",
        Range::closed(1e-12, 1e6, "kg·m²"),
        "Rotor inertia J_m of the motor: 10⁻¹² … 10⁶ kg·m²; positive (the inertia ratio divides by it).",
    );
    /// `torque_at_max_speed_nm`: 0 … the peak torque; left out, the rated torque.
    pub const TORQUE_AT_MAX_SPEED_NM: Field = Field::new(
        "motor.torque_at_max_speed_nm",
        Range::closed(0.0, 1e9, "N·m"),
        "Peak torque available at the maximum speed (the voltage-limit line's end): 0 … the peak torque; \
         the rated torque when left out.",
    );
}

impl Load {
    /// `moving_mass_kg`: 0 … 10⁹ kg (a translating slave).
    pub const MOVING_MASS_KG: Field = Field::new(
        "load.moving_mass_kg",
        Range::closed(0.0, 1e9, "kg"),
        "Moving mass of a translating slave: 0 … 10⁹ kg.",
    );
    /// `load_inertia_kg_m2`: 0 … 10⁹ kg·m² (a swinging slave).
    pub const LOAD_INERTIA_KG_M2: Field = Field::new(
        "load.load_inertia_kg_m2",
        Range::closed(0.0, 1e9, "kg·m²"),
        "Inertia of a swinging slave about its pivot: 0 … 10⁹ kg·m².",
    );
    /// `travel_mm_per_rev`: 10⁻⁹ … 10⁹ mm/rev; positive (the transmission ratio divides by it).
    pub const TRAVEL_MM_PER_REV: Field = Field::new(
        "load.travel_mm_per_rev",
        Range::closed(1e-9, 1e9, "mm/rev"),
        "Slave travel per motor revolution of a translating slave: 10⁻⁹ … 10⁹ mm/rev; positive.",
    );
    /// `gear_ratio`: 10⁻⁹ … 10⁹ motor turns per slave turn.
    pub const GEAR_RATIO: Field = Field::new(
        "load.gear_ratio",
        Range::closed(1e-9, 1e9, ""),
        "Motor turns per slave turn of a swinging slave: 10⁻⁹ … 10⁹; positive.",
    );
    /// `efficiency`: 0.001 … 1; 1 when left out (the motor torque divides by it).
    pub const EFFICIENCY: Field = Field::new(
        "load.efficiency",
        Range::closed(1e-3, 1.0, ""),
        "Efficiency η of the transmission: 0.001 … 1 (the motor torque divides by it); 1 when left out.",
    )
    .with_default(1.0);
    /// `friction_n`: 0 … 10⁹ N (or N·m).
    pub const FRICTION_N: Field = Field::new(
        "load.friction_n",
        Range::closed(0.0, 1e9, ""),
        "Coulomb friction F_μ (N, or N·m for a swinging slave): 0 … 10⁹; 0 when left out.",
    )
    .with_default(0.0);
    /// `viscous_n_s_m`: 0 … 10⁹ N·s/m (or N·m·s/rad).
    pub const VISCOUS_N_S_M: Field = Field::new(
        "load.viscous_n_s_m",
        Range::closed(0.0, 1e9, ""),
        "Viscous friction c (N·s/m, or N·m·s/rad): 0 … 10⁹; 0 when left out.",
    )
    .with_default(0.0);
    /// `spring_n_m`: ±10¹² N/m (or N·m/rad).
    pub const SPRING_N_M: Field = Field::new(
        "load.spring_n_m",
        Range::closed(-1e12, 1e12, ""),
        "Spring stiffness k_s (N/m, or N·m/rad): ±10¹²; 0 when left out.",
    )
    .with_default(0.0);
    /// `constant_force_n`: ±10⁹ N (or N·m).
    pub const CONSTANT_FORCE_N: Field = Field::new(
        "load.constant_force_n",
        Range::closed(-1e9, 1e9, ""),
        "Spring force at rest plus any constant force F₀ (N, or N·m): ±10⁹; 0 when left out.",
    )
    .with_default(0.0);
    /// `extra_inertia_kg_m2`: 0 … 10⁶ kg·m².
    pub const EXTRA_INERTIA_KG_M2: Field = Field::new(
        "load.extra_inertia_kg_m2",
        Range::closed(0.0, 1e6, "kg·m²"),
        "Extra inertia J_x on the motor shaft (coupling, gearbox input): 0 … 10⁶ kg·m²; 0 when left out.",
    )
    .with_default(0.0);
}

impl Limits {
    /// `max_inertia_ratio`: 10⁻⁶ … 10⁹; 10 when left out (a common rule for a stiff coupling).
    pub const MAX_INERTIA_RATIO: Field = Field::new(
        "limits.max_inertia_ratio",
        Range::closed(1e-6, 1e9, ""),
        "Largest admissible ratio of the load's reflected inertia to the rotor's: 10⁻⁶ … 10⁹; 10 when left \
         out (a common rule for a stiff coupling).",
    )
    .with_default(10.0);
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
                crank_lever: None,
            },
            limits: Limits::default(),
        }
    }

    /// Checks every field, and that the load is given in the terms of `unit` (mass and travel per
    /// revolution for `mm`, inertia and gear ratio for `deg`).
    pub fn validate(&self, unit: StrokeUnit) -> Result<()> {
        let m = &self.motor;
        Motor::RATED_TORQUE_NM.check(m.rated_torque_nm)?;
        Motor::PEAK_TORQUE_NM.at_least(m.rated_torque_nm).check(m.peak_torque_nm)?;
        Motor::RATED_SPEED_RPM.check(m.rated_speed_rpm)?;
        Motor::MAX_SPEED_RPM.at_least(m.rated_speed_rpm).check(m.max_speed_rpm)?;
        Motor::ROTOR_INERTIA_KG_M2.check(m.rotor_inertia_kg_m2)?;
        if let Some(t) = m.torque_at_max_speed_nm {
            Motor::TORQUE_AT_MAX_SPEED_NM.at_most(m.peak_torque_nm).check(t)?;
        }
        let l = &self.load;
        if let Some(cl) = &l.crank_lever {
            if unit != StrokeUnit::Mm || l.travel_mm_per_rev.is_some() || l.gear_ratio.is_some() {
                return Err(ServoError::Parse {
                    field: "load.crank_lever".into(),
                    text: "a crank and lever".into(),
                    expected: "a translating (mm) motion, without travel_mm_per_rev or gear_ratio (the crank and \
                               lever is the transmission)"
                        .into(),
                });
            }
            let mass = l.moving_mass_kg.ok_or_else(|| ServoError::Parse {
                field: Load::MOVING_MASS_KG.name.into(),
                text: "missing".into(),
                expected: "a number (the load needs moving_mass_kg)".into(),
            })?;
            Load::MOVING_MASS_KG.check(mass)?;
            cl.check("load.crank_lever")?;
        } else {
            self.validate_linear(unit)?;
        }
        Load::EFFICIENCY.check(l.efficiency)?;
        Load::FRICTION_N.check(l.friction_n)?;
        Load::VISCOUS_N_S_M.check(l.viscous_n_s_m)?;
        Load::SPRING_N_M.check(l.spring_n_m)?;
        Load::CONSTANT_FORCE_N.check(l.constant_force_n)?;
        Load::EXTRA_INERTIA_KG_M2.check(l.extra_inertia_kg_m2)?;
        Limits::MAX_INERTIA_RATIO.check(self.limits.max_inertia_ratio)?;
        Ok(())
    }

    /// The load's keys of a linear transmission for `unit`.
    fn validate_linear(&self, unit: StrokeUnit) -> Result<()> {
        let l = &self.load;
        let (mass_field, ratio_field, other_mass, other_ratio) = match unit {
            StrokeUnit::Mm => (Load::MOVING_MASS_KG, Load::TRAVEL_MM_PER_REV, l.load_inertia_kg_m2, l.gear_ratio),
            StrokeUnit::Deg => (Load::LOAD_INERTIA_KG_M2, Load::GEAR_RATIO, l.moving_mass_kg, l.travel_mm_per_rev),
        };
        let key = |f: &Field| f.name.strip_prefix("load.").unwrap_or(f.name);
        let (mass_key, ratio_key) = (key(&mass_field), key(&ratio_field));
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
        let need = |f: &Field, v: Option<f64>| {
            v.ok_or_else(|| ServoError::Parse {
                field: f.name.into(),
                text: "missing".into(),
                expected: format!("a number (the load needs {mass_key} and {ratio_key})"),
            })
        };
        mass_field.check(need(&mass_field, mass)?)?;
        ratio_field.check(need(&ratio_field, ratio)?)?;
        Ok(())
    }

    /// The crank-and-lever's linkage (`None` for a linear transmission or a geometry that does not
    /// close at mid-stroke, which [`Axis::validate`] refuses).
    pub fn linkage(&self) -> Option<Linkage> {
        self.load.crank_lever.as_ref().and_then(|c| c.linkage().ok())
    }

    /// The motor's motion and torque while the slave moves by `s` (a series in time of the slave
    /// position, SI; orders 0 … 5): `(T, α)` as series in time (`T` exact to the order of `s` less
    /// two). For a linear transmission `α = k·s` and `T` is [`Axis::torque_at`]'s formula; for a
    /// crank and lever `T = (J_m + J_x)·i·α̈ + (F·y' + J_L·φ̈·φ')/(i·η)` and the motor at `i·α`
    /// ([`crate::crank_lever`]). `None`
    /// where a crank and lever cannot reach the slave's position.
    pub fn motor_series(&self, s: Jet) -> Option<(Jet, Jet)> {
        self.motor_series_via(self.linkage().as_ref(), s)
    }

    /// [`Axis::motor_series`] on the crank and lever's linkage `link` built once by the caller (it
    /// must be [`Axis::linkage`]: a caller evaluating many points saves building it at each).
    pub fn motor_series_via(&self, link: Option<&Linkage>, s: Jet) -> Option<(Jet, Jet)> {
        let v = s.d(1);
        self.motor_series_signed_via(link, s, if v == 0.0 { 0.0 } else { v.signum() })
    }

    /// [`Axis::motor_series`] with the Coulomb friction's sign given (`±1`, or 0: none).
    pub fn motor_series_signed(&self, s: Jet, vsign: f64) -> Option<(Jet, Jet)> {
        self.motor_series_signed_via(self.linkage().as_ref(), s, vsign)
    }

    /// [`Axis::motor_series_signed`] on `link` = [`Axis::linkage`].
    fn motor_series_signed_via(&self, link: Option<&Linkage>, s: Jet, vsign: f64) -> Option<(Jet, Jet)> {
        let l = &self.load;
        let fric = l.friction_n * vsign;
        let sd = s.deriv();
        let sdd = sd.deriv();
        let force = sdd.scale(self.load_mass())
            + sd.scale(l.viscous_n_s_m)
            + s.scale(l.spring_n_m)
            + Jet::cst(fric + l.constant_force_n);
        let j_motor = self.motor.rotor_inertia_kg_m2 + l.extra_inertia_kg_m2;
        match link {
            None if l.crank_lever.is_some() => None,
            None => {
                let k = self.motor_rad_per_unit();
                let alpha = s.scale(k);
                let t = sdd.scale(j_motor * k) + force.scale(1.0 / (k * l.efficiency));
                Some((t, alpha))
            }
            Some(link) => {
                let MotorMotion { alpha, dy_dalpha, lever, dlever_dalpha } = link.motor(s)?;
                let i = link.gear;
                let acc = alpha.deriv().deriv();
                let lever_acc = lever.deriv().deriv();
                let t = acc.scale(j_motor * i)
                    + (force * dy_dalpha + lever_acc * dlever_dalpha.scale(link.lever_inertia))
                        .scale(1.0 / (i * l.efficiency));
                Some((t, alpha.scale(i)))
            }
        }
    }

    /// The slave's series in time from its position, velocity, acceleration and jerk.
    fn series(s: f64, v: f64, a: f64, j: f64) -> Jet {
        Jet([s, v, 0.5 * a, j / 6.0, 0.0, 0.0])
    }

    /// The motor speed (rad/s) with the slave at `s` moving at `v`: `k·v`, or `v/y'` for a crank
    /// and lever.
    pub fn motor_speed_at(&self, s: f64, v: f64) -> f64 {
        if self.load.crank_lever.is_none() {
            return self.motor_rad_per_unit() * v;
        }
        self.motor_series(Self::series(s, v, 0.0, 0.0)).map_or(f64::NAN, |(_, a)| a.d(1))
    }

    /// The time derivative of the motor torque at slave position `s` (N·m/s): [`Axis::torque_rate`]
    /// for a linear transmission, the crank and lever's from its series.
    pub fn torque_rate_at(&self, s: f64, v: f64, a: f64, j: f64) -> f64 {
        if self.load.crank_lever.is_none() {
            return self.torque_rate(v, a, j);
        }
        self.motor_series(Self::series(s, v, a, j)).map_or(f64::NAN, |(t, _)| t.d(1))
    }

    /// `k`, motor radians per slave SI unit (rad/m, or rad/rad); for a crank and lever, `i/y'` at
    /// mid-stroke (`i` the gear ratio).
    pub fn motor_rad_per_unit(&self) -> f64 {
        if let Some(l) = self.linkage() {
            return l.gear / l.height(Jet::var(l.alpha_mid)).0.d(1);
        }
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

    /// The inertia ratio `(m/k² + J_x) / J_m`; for a crank and lever `((m·y'² + J_L·φ'²)/i² + J_x) / J_m`
    /// at mid-stroke (the output arm horizontal; `i` the gear ratio).
    pub fn inertia_ratio(&self) -> f64 {
        if let Some(l) = self.linkage() {
            let (y, phi) = l.height(Jet::var(l.alpha_mid));
            let (g, p) = (y.d(1), phi.d(1));
            return ((self.load_mass() * g * g + l.lever_inertia * p * p) / (l.gear * l.gear)
                + self.load.extra_inertia_kg_m2)
                / self.motor.rotor_inertia_kg_m2;
        }
        let k = self.motor_rad_per_unit();
        (self.load_mass() / (k * k) + self.load.extra_inertia_kg_m2) / self.motor.rotor_inertia_kg_m2
    }

    /// The motor torque (N·m) with the slave at position `s`, velocity `v` and acceleration `a`
    /// (SI: m, m/s, m/s² or rad, rad/s, rad/s²): `T = (J_m + J_x)·k·a + F/(k·η)` with the load
    /// force `F` of the model above (the Coulomb friction zero where `v = 0`). What
    /// [`crate::operating_points`] and [`crate::check_axis`] evaluate.
    pub fn torque_at(&self, s: f64, v: f64, a: f64) -> f64 {
        match self.linear_drive() {
            Some(d) => d.torque_at(s, v, a),
            None => self.motor_series(Self::series(s, v, a, 0.0)).map_or(f64::NAN, |(t, _)| t.v()),
        }
    }

    /// The constants of the torque with a linear transmission, worked out once ([`LinearDrive`]);
    /// `None` for a crank and lever.
    pub fn linear_drive(&self) -> Option<LinearDrive> {
        LinearDrive::of(self)
    }

    /// The time derivative of [`Axis::torque_at`] away from a sign change of the velocity (N·m/s),
    /// from the velocity, acceleration and jerk: `(J_m + J_x)·k·j + (c·a + k_s·v)/(k·η)`.
    pub fn torque_rate(&self, v: f64, a: f64, j: f64) -> f64 {
        match self.linear_drive() {
            Some(d) => d.torque_rate(v, a, j),
            // The crank and lever's ratio at mid-stroke (`k`), as the linear formula reads it.
            None => {
                let ke = self.motor_rad_per_unit() * self.load.efficiency;
                self.torque_inertia() * j + (self.load.viscous_n_s_m * a + self.load.spring_n_m * v) / ke
            }
        }
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
