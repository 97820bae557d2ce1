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
use loomkin_units::{Field, Range};
use serde::{Deserialize, Serialize};

/// Parameters of the drive (SI units). See the module documentation for the model.
///
/// In a TOML file they sit under `[drive]`; a key left out is 0, except `gear_ratio` and
/// `efficiency` (default 1) and the cycle keys `return_angle_deg` (default `motion_angle_deg`)
/// and `dwell_after_rise_deg` (default: half of what rise and return leave of the turn).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
    #[serde(default = "default_gear_ratio")]
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
    #[serde(default = "default_efficiency")]
    pub efficiency: f64,
    /// Main-shaft angle of the return stroke (deg); default: `motion_angle_deg`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub return_angle_deg: Option<f64>,
    /// Dwell between the end of the rise and the start of the return (deg); default: half of
    /// `360 − rise − return`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dwell_after_rise_deg: Option<f64>,
}

fn default_gear_ratio() -> f64 {
    Drive::GEAR_RATIO.default_value()
}

fn default_efficiency() -> f64 {
    Drive::EFFICIENCY.default_value()
}

/// The top-level keys of a workbench design file besides `drive` (definition points, spline
/// start condition, speeds); a drive file may hold them, [`Drive::from_toml`] ignores them.
pub const DESIGN_KEYS: [&str; 3] = ["points", "end", "speeds_rpm"];

/// A value of the `[drive]` table: a number, or the (shortened) text of something else.
enum Entry {
    Number(f64),
    Other(String),
}

impl Entry {
    fn from_toml(v: &toml::Value) -> Self {
        match v {
            toml::Value::Integer(i) => Self::Number(*i as f64),
            toml::Value::Float(x) => Self::Number(*x),
            other => Self::Other(short(&other.to_string())),
        }
    }

    fn from_json(v: &serde_json::Value) -> Self {
        match v.as_f64() {
            Some(x) => Self::Number(x),
            None => Self::Other(short(&v.to_string())),
        }
    }
}

/// At most 40 characters of a value's text, on one line.
fn short(text: &str) -> String {
    let one: String = text.split_whitespace().collect::<Vec<_>>().join(" ");
    if one.chars().count() > 40 { format!("{}…", one.chars().take(40).collect::<String>()) } else { one }
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
    ///
    /// A key left out is 0, except `gear_ratio` and `efficiency` (1) and the optional cycle keys.
    /// Besides `[drive]` the file may hold the other top-level keys of a workbench design file
    /// ([`DESIGN_KEYS`]: `points`, `end`, `speeds_rpm`), which are ignored here, so a design
    /// saved by the workbench serves as a drive file. Every other key, and every value that is
    /// not a number, is an error naming the key.
    pub fn from_toml(text: &str) -> Result<Self> {
        let table: toml::Table = text.parse().map_err(|e: toml::de::Error| ServoError::Parse {
            field: "drive file".into(),
            text: loomkin_units::toml_reason(text, &e),
            expected: "TOML with a [drive] table".into(),
        })?;
        let top: Vec<String> = table.keys().cloned().collect();
        let drive = table.get("drive").map(|v| match v {
            toml::Value::Table(t) => Ok(t.iter().map(|(k, v)| (k.clone(), Entry::from_toml(v))).collect()),
            other => Err(short(&other.to_string())),
        });
        Self::from_entries(&top, drive)
    }

    /// Reads a drive from JSON text, `{"drive": {…}}` (the JSON form of a workbench design file
    /// also serves); the same rules as [`Drive::from_toml`].
    pub fn from_json(text: &str) -> Result<Self> {
        let value: serde_json::Value = serde_json::from_str(text).map_err(|e| ServoError::Parse {
            field: "drive file".into(),
            text: format!("{e}"),
            expected: "JSON with a \"drive\" object".into(),
        })?;
        let Some(obj) = value.as_object() else {
            return Err(ServoError::Parse {
                field: "drive file".into(),
                text: short(&value.to_string()),
                expected: "a JSON object with a \"drive\" object".into(),
            });
        };
        let top: Vec<String> = obj.keys().cloned().collect();
        let drive = obj.get("drive").map(|v| match v {
            serde_json::Value::Object(o) => Ok(o.iter().map(|(k, v)| (k.clone(), Entry::from_json(v))).collect()),
            other => Err(short(&other.to_string())),
        });
        Self::from_entries(&top, drive)
    }

    /// Reads a drive file in JSON (text starting with `{`) or TOML, see [`Drive::from_toml`].
    pub fn from_text(text: &str) -> Result<Self> {
        if text.trim_start().starts_with('{') { Self::from_json(text) } else { Self::from_toml(text) }
    }

    /// Builds and checks a drive from the top-level keys of a file and the entries of its
    /// `drive` table (`Err` holds the text of a `drive` value that is not a table).
    fn from_entries(top: &[String], drive: Option<std::result::Result<Vec<(String, Entry)>, String>>) -> Result<Self> {
        let expected_top =
            format!("a [drive] table (a workbench design file may also hold {})", DESIGN_KEYS.join(", "));
        if let Some(k) = top.iter().find(|k| *k != "drive" && !DESIGN_KEYS.contains(&k.as_str())) {
            return Err(ServoError::Parse {
                field: k.clone(),
                text: format!("unknown top-level key '{k}'"),
                expected: expected_top,
            });
        }
        let entries = match drive {
            None => {
                return Err(ServoError::Parse {
                    field: "drive".into(),
                    text: "no [drive] table".into(),
                    expected: expected_top,
                });
            }
            Some(Err(text)) => {
                return Err(ServoError::Parse { field: "drive".into(), text, expected: expected_top });
            }
            Some(Ok(e)) => e,
        };
        let mut d = Self {
            gear_ratio: default_gear_ratio(),
            efficiency: default_efficiency(),
            ..Self::pure_inertia(0.0, 0.0, 0.0, 0.0)
        };
        for (key, entry) in entries {
            let Some(unit) =
                Drive::TABLE.iter().find(|f| f.name.strip_prefix("drive.") == Some(key.as_str())).map(|f| f.range.unit)
            else {
                let keys: Vec<&str> = Drive::TABLE.iter().filter_map(|f| f.name.strip_prefix("drive.")).collect();
                return Err(ServoError::Parse {
                    field: format!("drive.{key}"),
                    text: format!("unknown key '{key}'"),
                    expected: format!("one of {}", keys.join(", ")),
                });
            };
            let x = match entry {
                Entry::Number(x) => x,
                Entry::Other(text) => {
                    let unit = if unit.is_empty() { String::new() } else { format!(" in {unit}") };
                    return Err(ServoError::Parse {
                        field: format!("drive.{key}"),
                        text,
                        expected: format!("a number{unit}"),
                    });
                }
            };
            let slot = match key.as_str() {
                "stroke_m" => &mut d.stroke_m,
                "motion_angle_deg" => &mut d.motion_angle_deg,
                "moving_mass_kg" => &mut d.moving_mass_kg,
                "pinion_radius_m" => &mut d.pinion_radius_m,
                "gear_ratio" => &mut d.gear_ratio,
                "motor_inertia_kg_m2" => &mut d.motor_inertia_kg_m2,
                "spring_n_m" => &mut d.spring_n_m,
                "spring_preload_n" => &mut d.spring_preload_n,
                "damping_n_s_m" => &mut d.damping_n_s_m,
                "constant_force_n" => &mut d.constant_force_n,
                "efficiency" => &mut d.efficiency,
                "return_angle_deg" => d.return_angle_deg.insert(0.0),
                // The last key of Drive::TABLE (the key was found there above).
                _ => d.dwell_after_rise_deg.insert(0.0),
            };
            *slot = x;
        }
        d.validate()?;
        Ok(d)
    }

    /// The drive as TOML text with a `[drive]` table.
    pub fn to_toml(&self) -> String {
        let mut table = toml::Table::new();
        table.insert("drive".into(), toml::Value::try_from(self).unwrap_or(toml::Value::Table(toml::Table::new())));
        toml::to_string(&table).unwrap_or_default()
    }

    /// `stroke_m`: 1 nm … 100 m, far beyond any slave's stroke; positive (the torque divides by it).
    pub const STROKE_M: Field = Field::new(
        "drive.stroke_m",
        Range::closed(1e-9, 100.0, "m"),
        "Stroke of the slave (rack): 1 nm … 100 m, far beyond any slave's; positive (the torque divides by it).",
    );
    /// `pinion_radius_m`: 1 nm … 100 m; positive (force = torque / radius).
    pub const PINION_RADIUS_M: Field = Field::new(
        "drive.pinion_radius_m",
        Range::closed(1e-9, 100.0, "m"),
        "Pitch radius of the pinion on the rack: 1 nm … 100 m; positive (force = torque / radius).",
    );
    /// `gear_ratio`: 10⁻⁶ … 10⁶.
    pub const GEAR_RATIO: Field = Field::new(
        "drive.gear_ratio",
        Range::closed(1e-6, 1e6, ""),
        "Gear ratio i between the motor and the pinion (motor turns per pinion turn): 10⁻⁶ … 10⁶; 1 (a direct \
         drive) when left out.",
    )
    .with_default(1.0);
    /// `efficiency`: 0.001 … 1 (the torque divides by it).
    pub const EFFICIENCY: Field = Field::new(
        "drive.efficiency",
        Range::closed(1e-3, 1.0, ""),
        "Efficiency η of the gear and rack: 0.001 … 1 (the motor torque divides by it); 1 when left out.",
    )
    .with_default(1.0);
    /// `moving_mass_kg`: 0 … 10⁶ kg.
    pub const MOVING_MASS_KG: Field =
        Field::new("drive.moving_mass_kg", Range::closed(0.0, 1e6, "kg"), "Mass moved with the rack: 0 … 10⁶ kg.");
    /// `motor_inertia_kg_m2`: 0 … 10⁶ kg·m².
    pub const MOTOR_INERTIA_KG_M2: Field = Field::new(
        "drive.motor_inertia_kg_m2",
        Range::closed(0.0, 1e6, "kg·m²"),
        "Moment of inertia of the motor's rotor (and what turns with it): 0 … 10⁶ kg·m².",
    );
    /// `spring_n_m`: ±10¹² N/m (a negative rate is a spring pushing away from its rest).
    pub const SPRING_N_M: Field = Field::new(
        "drive.spring_n_m",
        Range::closed(-1e12, 1e12, "N/m"),
        "Spring rate on the slave: ±10¹² N/m (a negative rate is a spring pushing away from its rest).",
    );
    /// `spring_preload_n`: ±10⁹ N.
    pub const SPRING_PRELOAD_N: Field = Field::new(
        "drive.spring_preload_n",
        Range::closed(-1e9, 1e9, "N"),
        "Spring force at the slave's rest: ±10⁹ N.",
    );
    /// `constant_force_n`: ±10⁹ N.
    pub const CONSTANT_FORCE_N: Field = Field::new(
        "drive.constant_force_n",
        Range::closed(-1e9, 1e9, "N"),
        "A constant force on the slave (weight, a process force): ±10⁹ N.",
    );
    /// `damping_n_s_m`: ±10⁹ N·s/m.
    pub const DAMPING_N_S_M: Field = Field::new(
        "drive.damping_n_s_m",
        Range::closed(-1e9, 1e9, "N·s/m"),
        "Viscous damping on the slave: ±10⁹ N·s/m.",
    );
    /// `motion_angle_deg`: 10⁻⁶ … 359° (the phases fit in one turn).
    pub const MOTION_ANGLE_DEG: Field = Field::new(
        "drive.motion_angle_deg",
        Range::closed(1e-6, 359.0, "deg"),
        "Main-shaft angle of the rise: 10⁻⁶ … 359° (with the return it fits in one turn).",
    );
    /// `return_angle_deg`: as [`Drive::MOTION_ANGLE_DEG`]; left out, the rise's.
    pub const RETURN_ANGLE_DEG: Field = Field::new(
        "drive.return_angle_deg",
        Range::closed(1e-6, 359.0, "deg"),
        "Main-shaft angle of the return: 10⁻⁶ … 359° (with the rise it fits in one turn); left out, the rise's.",
    );

    /// `dwell_after_rise_deg`: 0 … 359°, and at most what rise and return leave of the turn (checked
    /// with the layout); left out, half of that.
    pub const DWELL_AFTER_RISE_DEG: Field = Field::new(
        "drive.dwell_after_rise_deg",
        Range::closed(0.0, 359.0, "deg"),
        "Main-shaft angle of the dwell after the rise: at most what rise and return leave of the turn; left out, \
         half of that.",
    );

    /// The keys of a `[drive]` table, in the order files write them: each key is the descriptor's
    /// name without `drive.`, its unit the descriptor's.
    pub const TABLE: [Field; 13] = [
        Self::STROKE_M,
        Self::MOTION_ANGLE_DEG,
        Self::MOVING_MASS_KG,
        Self::PINION_RADIUS_M,
        Self::GEAR_RATIO,
        Self::MOTOR_INERTIA_KG_M2,
        Self::SPRING_N_M,
        Self::SPRING_PRELOAD_N,
        Self::DAMPING_N_S_M,
        Self::CONSTANT_FORCE_N,
        Self::EFFICIENCY,
        Self::RETURN_ANGLE_DEG,
        Self::DWELL_AFTER_RISE_DEG,
    ];

    /// Checks every field's range (finite, positive where it must be, angles fit in one turn).
    pub fn validate(&self) -> Result<()> {
        Self::STROKE_M.check(self.stroke_m)?;
        Self::PINION_RADIUS_M.check(self.pinion_radius_m)?;
        Self::GEAR_RATIO.check(self.gear_ratio)?;
        Self::EFFICIENCY.check(self.efficiency)?;
        Self::MOVING_MASS_KG.check(self.moving_mass_kg)?;
        Self::MOTOR_INERTIA_KG_M2.check(self.motor_inertia_kg_m2)?;
        Self::SPRING_N_M.check(self.spring_n_m)?;
        Self::SPRING_PRELOAD_N.check(self.spring_preload_n)?;
        Self::DAMPING_N_S_M.check(self.damping_n_s_m)?;
        Self::CONSTANT_FORCE_N.check(self.constant_force_n)?;
        self.layout().map(|_| ())
    }

    /// The phases of one main-shaft turn (see the module documentation).
    pub fn layout(&self) -> Result<CycleLayout> {
        let rise = Self::MOTION_ANGLE_DEG.check(self.motion_angle_deg)?;
        let ret = match self.return_angle_deg {
            Some(r) => Self::RETURN_ANGLE_DEG.check(r)?,
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
            Some(d) => Self::DWELL_AFTER_RISE_DEG
                .within(Range::closed(0.0, rest, "deg"), Self::DWELL_AFTER_RISE_DEG.doc)
                .check(d)?,
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

    /// Every kind of bad file names the key (or the line) at fault.
    #[test]
    fn bad_files_name_the_key() {
        let base = "[drive]\nstroke_m = 0.1\nmotion_angle_deg = 120\npinion_radius_m = 0.02\n";
        let msg = |text: &str| Drive::from_toml(text).unwrap_err().to_string();
        let e = msg(&format!("{base}stroke_mm = 0.1\n"));
        assert!(e.starts_with("drive.stroke_mm:") && e.contains("unknown key"), "{e}");
        let e = msg(&format!("{base}moving_mass_kg = \"heavy\"\n"));
        assert!(e.starts_with("drive.moving_mass_kg:") && e.contains("a number in kg"), "{e}");
        let e = msg(&format!("{base}efficiency = nan\n"));
        assert!(e.contains("drive.efficiency is not a finite number"), "{e}");
        let e = msg(&format!("{base}stroke_m = 0.2\n"));
        assert!(e.contains("line 5"), "{e}");
        let e = msg(&format!("speed = 3\n{base}"));
        assert!(e.starts_with("speed:") && e.contains("unknown top-level key"), "{e}");
        let e = msg("stroke_m = 0.1\n");
        assert!(e.starts_with("stroke_m:"), "{e}");
        let e = msg("drive = 3\n");
        assert!(e.starts_with("drive:"), "{e}");
        let e = msg("");
        assert!(e.starts_with("drive:") && e.contains("no [drive] table"), "{e}");
        let e = Drive::from_json("{\"drive\": {\"stroke_m\": null}}").unwrap_err().to_string();
        assert!(e.starts_with("drive.stroke_m:"), "{e}");
        let e = Drive::from_json("[1, 2]").unwrap_err().to_string();
        assert!(e.starts_with("drive file:"), "{e}");
    }

    /// A workbench design file (points, end, speeds and the drive) serves as a drive file, in
    /// TOML and in JSON; its points and speeds are ignored.
    #[test]
    fn a_design_file_serves_as_a_drive_file() {
        let toml_text = "# design\npoints = [[0.0, 0.0], [0.2, 1.0], [0.3, 1.0], [0.5, 0.0]]\nend = \"clamped\"\n\
                         speeds_rpm = [600.0]\n\n[drive]\nstroke_m = 0.05\nmotion_angle_deg = 140\n\
                         pinion_radius_m = 0.02\nmoving_mass_kg = 0.3\nreturn_angle_deg = 150\n";
        let d = Drive::from_text(toml_text).unwrap();
        assert_eq!((d.stroke_m, d.motion_angle_deg, d.return_angle_deg), (0.05, 140.0, Some(150.0)));
        assert_eq!((d.gear_ratio, d.efficiency, d.damping_n_s_m), (1.0, 1.0, 0.0));
        let json_text = "{\"points\": [[0, 0], [0.2, 1], [0.3, 1], [0.5, 0]], \"end\": \"natural\", \
                         \"speeds_rpm\": [600], \"drive\": {\"stroke_m\": 0.05, \"motion_angle_deg\": 140, \
                         \"pinion_radius_m\": 0.02, \"moving_mass_kg\": 0.3, \"return_angle_deg\": 150}}";
        assert_eq!(Drive::from_text(json_text).unwrap(), d);
    }
}
