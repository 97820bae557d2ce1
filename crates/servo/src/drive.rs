//! The servo drive of the needle rack: parameters, TOML file, built-in default, machine cycle.
//!
//! # The model
//!
//! A rack of mass `m` moves by `u` (m) along its guide, driven through a pinion of radius `r` (m)
//! that the motor turns through a gear of ratio `i` (motor turns per pinion turn). The motor angle
//! is `θ_m = i·u/r`. The rack feels the inertia force `m·ü`, a viscous guide force `c·u̇`, a
//! spring `k·u + F_pre` (stiffness `k`, preload `F_pre` at `u = 0`) and a constant force `F_c`
//! (e.g. a process or weight force), all counted positive when they oppose a positive `u`. The
//! torque the motor must give is
//!
//! $$ M = J_m\,\ddot\theta_m + \frac{r}{i\,\eta}\,\bigl(m\ddot u + c\dot u + k u + F_{pre} + F_c\bigr),
//!    \qquad \ddot\theta_m = \frac{i}{r}\ddot u, $$
//!
//! with `J_m` the motor inertia (kg·m², including the pinion reduced to the motor shaft) and `η`
//! the efficiency of the gear and rack. Dividing by `η` at every instant (also while the rack
//! brakes and power flows back) errs on the safe side for sizing. The power is
//! `P = M·θ̇_m` (W), `θ̇_m = (i/r)·u̇`.
//!
//! # The machine cycle
//!
//! The paper's law `u°(x)` makes the stroke `H` while the main shaft turns through the motion
//! angle `φ` (`motion_angle_deg`). A needle goes in and comes back once per pick, so one turn
//! (360°) of the main shaft is: rise over `φ`, a dwell in the inserted position, the return over
//! `φ_r` (`return_angle_deg`, default `φ`) by the same law run backwards, `u = H(1 − u°)`, and a
//! dwell at the start position. The two dwells share the rest of the turn equally unless
//! `dwell_after_rise_deg` is given. In the dwells the motor holds the static force
//! `k·u + F_pre + F_c`. The RMS torque is taken over this whole turn.

use crate::{Result, ServoError};
use serde::{Deserialize, Serialize};

/// Parameters of the drive (SI units). See the module documentation for the model.
///
/// In a TOML file they sit under `[drive]`; a key left out is 0, except `gear_ratio` and
/// `efficiency` (default 1) and the cycle keys `return_angle_deg` (default `motion_angle_deg`)
/// and `dwell_after_rise_deg` (default: half of what rise and return leave of the turn).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Drive {
    /// Stroke `H` of the rack (m), > 0.
    #[serde(default)]
    pub stroke_m: f64,
    /// Main-shaft angle `φ` during which the stroke is made (deg), 0 < φ < 360.
    #[serde(default)]
    pub motion_angle_deg: f64,
    /// Moving mass `m` reduced to the rack (kg), ≥ 0.
    #[serde(default)]
    pub moving_mass_kg: f64,
    /// Pinion pitch radius `r` (m), > 0.
    #[serde(default)]
    pub pinion_radius_m: f64,
    /// Gear ratio `i`, motor turns per pinion turn, > 0 (default 1: direct drive).
    #[serde(default = "one")]
    pub gear_ratio: f64,
    /// Motor (and pinion, reduced to the motor) inertia `J_m` (kg·m²), ≥ 0.
    #[serde(default)]
    pub motor_inertia_kg_m2: f64,
    /// Spring stiffness `k` acting on the rack (N/m).
    #[serde(default)]
    pub spring_n_m: f64,
    /// Spring force at `u = 0`, `F_pre` (N).
    #[serde(default)]
    pub spring_preload_n: f64,
    /// Viscous damping `c` of the rack guide (N·s/m).
    #[serde(default)]
    pub damping_n_s_m: f64,
    /// Constant force `F_c` opposing a positive `u` (N).
    #[serde(default)]
    pub constant_force_n: f64,
    /// Efficiency `η` of gear and rack, 0 < η ≤ 1 (default 1).
    #[serde(default = "one")]
    pub efficiency: f64,
    /// Main-shaft angle of the return stroke (deg); default: `motion_angle_deg`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub return_angle_deg: Option<f64>,
    /// Dwell between the end of the rise and the start of the return (deg); default: half of
    /// `360 − rise − return`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dwell_after_rise_deg: Option<f64>,
}

fn one() -> f64 {
    1.0
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct DriveFile {
    drive: Drive,
}

/// The four phases of one main-shaft turn, with their angles (deg).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CycleLayout {
    /// Rise (forward stroke) angle `φ`.
    pub rise_deg: f64,
    /// Dwell in the end position.
    pub dwell_after_rise_deg: f64,
    /// Return stroke angle `φ_r`.
    pub return_deg: f64,
    /// Dwell in the start position (to 360°).
    pub dwell_after_return_deg: f64,
}

impl CycleLayout {
    /// Start angles of the four phases (deg): rise, dwell, return, dwell.
    pub fn starts_deg(&self) -> [f64; 4] {
        let a = self.rise_deg;
        let b = a + self.dwell_after_rise_deg;
        [0.0, a, b, b + self.return_deg]
    }
}

/// The angle of one cycle of the main shaft (deg).
pub const CYCLE_DEG: f64 = 360.0;

impl Drive {
    /// The built-in needle-rack drive, used when no drive file is given.
    ///
    /// The paper gives no drive data (only the peak torques of Table 1: 5 N·m at 600 1/min for
    /// the original law), so these are assumptions of a plausible direct-drive needle rack of a
    /// narrow-fabric needle loom, chosen so that the default definition points (≈ cycloidal
    /// acceleration) need about 5 N·m at 600 1/min, as the paper's original law did:
    /// stroke 80 mm over a motion angle of 150° (return over another 150°, dwells of 30°),
    /// moving mass 0.45 kg reduced to the rack, pinion radius 25 mm, direct drive (`i = 1`), motor
    /// inertia 0.9·10⁻⁴ kg·m² (a small servo motor), viscous guide losses 5 N·s/m, efficiency
    /// 0.9, no spring and no constant force.
    pub fn needle_rack_default() -> Self {
        Self {
            stroke_m: 0.08,
            motion_angle_deg: 150.0,
            moving_mass_kg: 0.45,
            pinion_radius_m: 0.025,
            gear_ratio: 1.0,
            motor_inertia_kg_m2: 0.9e-4,
            spring_n_m: 0.0,
            spring_preload_n: 0.0,
            damping_n_s_m: 5.0,
            constant_force_n: 0.0,
            efficiency: 0.9,
            return_angle_deg: None,
            dwell_after_rise_deg: None,
        }
    }

    /// A drive with only the rack mass, pinion and stroke (no motor inertia, no losses): its
    /// torque is `M = r·m·ü`. Used in tests and as a simple reference.
    pub fn pure_inertia(stroke_m: f64, motion_angle_deg: f64, moving_mass_kg: f64, pinion_radius_m: f64) -> Self {
        Self {
            stroke_m,
            motion_angle_deg,
            moving_mass_kg,
            pinion_radius_m,
            gear_ratio: 1.0,
            motor_inertia_kg_m2: 0.0,
            spring_n_m: 0.0,
            spring_preload_n: 0.0,
            damping_n_s_m: 0.0,
            constant_force_n: 0.0,
            efficiency: 1.0,
            return_angle_deg: None,
            dwell_after_rise_deg: None,
        }
    }

    /// Reads a drive from TOML text with a `[drive]` table, and checks it.
    pub fn from_toml(text: &str) -> Result<Self> {
        let file: DriveFile = toml::from_str(text).map_err(|e| ServoError::Parse {
            field: "drive file".into(),
            text: e.message().to_string(),
            expected: "TOML with a [drive] table (stroke_m, motion_angle_deg, moving_mass_kg, pinion_radius_m, …)"
                .into(),
        })?;
        file.drive.validate()?;
        Ok(file.drive)
    }

    /// The drive as TOML text with a `[drive]` table.
    pub fn to_toml(&self) -> String {
        let mut table = toml::Table::new();
        table.insert("drive".into(), toml::Value::try_from(self).unwrap_or(toml::Value::Table(toml::Table::new())));
        toml::to_string(&table).unwrap_or_default()
    }

    /// Checks every field's range (finite, positive where it must be, angles fit in one turn).
    pub fn validate(&self) -> Result<()> {
        let c = ServoError::check_range;
        c("drive.stroke_m", self.stroke_m, 1e-9, 100.0, "m")?;
        c("drive.pinion_radius_m", self.pinion_radius_m, 1e-9, 100.0, "m")?;
        c("drive.gear_ratio", self.gear_ratio, 1e-6, 1e6, "")?;
        c("drive.efficiency", self.efficiency, 1e-3, 1.0, "")?;
        c("drive.moving_mass_kg", self.moving_mass_kg, 0.0, 1e6, "kg")?;
        c("drive.motor_inertia_kg_m2", self.motor_inertia_kg_m2, 0.0, 1e6, "kg·m²")?;
        c("drive.spring_n_m", self.spring_n_m, -1e12, 1e12, "N/m")?;
        c("drive.spring_preload_n", self.spring_preload_n, -1e9, 1e9, "N")?;
        c("drive.damping_n_s_m", self.damping_n_s_m, -1e9, 1e9, "N·s/m")?;
        c("drive.constant_force_n", self.constant_force_n, -1e9, 1e9, "N")?;
        self.layout().map(|_| ())
    }

    /// The phases of one main-shaft turn (see the module documentation).
    pub fn layout(&self) -> Result<CycleLayout> {
        let rise = ServoError::check_range("drive.motion_angle_deg", self.motion_angle_deg, 1e-6, 359.0, "deg")?;
        let ret = match self.return_angle_deg {
            Some(r) => ServoError::check_range("drive.return_angle_deg", r, 1e-6, 359.0, "deg")?,
            None => rise,
        };
        let rest = CYCLE_DEG - rise - ret;
        if rest < 0.0 {
            return Err(ServoError::Cycle {
                field: "drive.motion_angle_deg".into(),
                reason: format!(
                    "rise {rise}° and return {ret}° together exceed the {CYCLE_DEG}° of one turn of the main shaft"
                ),
            });
        }
        let d1 = match self.dwell_after_rise_deg {
            Some(d) => ServoError::check_range("drive.dwell_after_rise_deg", d, 0.0, rest, "deg")?,
            None => rest / 2.0,
        };
        Ok(CycleLayout { rise_deg: rise, dwell_after_rise_deg: d1, return_deg: ret, dwell_after_return_deg: rest - d1 })
    }

    /// Factor `r/(i·η)` (m) from the rack force to the motor torque.
    pub fn force_to_torque_m(&self) -> f64 {
        self.pinion_radius_m / (self.gear_ratio * self.efficiency)
    }

    /// Factor `i/r` (rad/m) from the rack displacement to the motor angle.
    pub fn motor_rad_per_m(&self) -> f64 {
        self.gear_ratio / self.pinion_radius_m
    }

    /// Effective inertia coefficient `A = J_m·i/r + m·r/(i·η)` (kg·m): torque per rack acceleration.
    pub fn inertia_coefficient(&self) -> f64 {
        self.motor_inertia_kg_m2 * self.motor_rad_per_m() + self.moving_mass_kg * self.force_to_torque_m()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn toml_defaults_and_round_trip() {
        let d = Drive::from_toml("[drive]\nstroke_m = 0.1\nmotion_angle_deg = 120\npinion_radius_m = 0.02\n").unwrap();
        assert_eq!(d.gear_ratio, 1.0);
        assert_eq!(d.efficiency, 1.0);
        assert_eq!(d.moving_mass_kg, 0.0);
        let l = d.layout().unwrap();
        assert_eq!(
            (l.rise_deg, l.dwell_after_rise_deg, l.return_deg, l.dwell_after_return_deg),
            (120.0, 60.0, 120.0, 60.0)
        );
        let def = Drive::needle_rack_default();
        assert_eq!(Drive::from_toml(&def.to_toml()).unwrap(), def);
    }

    #[test]
    fn bad_drives_name_the_field() {
        let e = Drive::from_toml("[drive]\nstroke_m = 0.1\nmotion_angle_deg = 120\n").unwrap_err();
        assert!(e.to_string().contains("pinion_radius_m"), "{e}");
        let e = Drive::from_toml("[drive]\nstroke = 0.1\n").unwrap_err();
        assert!(matches!(e, ServoError::Parse { .. }), "{e}");
        let mut d = Drive::needle_rack_default();
        d.motion_angle_deg = 200.0;
        assert!(matches!(d.validate(), Err(ServoError::Cycle { .. })));
        d.motion_angle_deg = 150.0;
        d.efficiency = 1.5;
        assert!(d.validate().unwrap_err().to_string().contains("efficiency"));
    }
}
