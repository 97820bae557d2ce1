//! The servo-shedding table of a loom file: `[shedding.servo]` with the motor, the transmission,
//! the winding and the bus, for all frames, and `[[shedding.servo.frame]]` overrides.
//!
//! ```toml
//! [shedding]
//! drive = "servo"
//! # … the law, crossing_deg, stagger as for the dobby
//!
//! [shedding.servo]
//! pass_through = true              # consecutive changes as one move without a stop
//! [shedding.servo.motor]           # as `loomkin servo check` takes it
//! rated_torque_nm = 12
//! peak_torque_nm = 36
//! rated_speed_rpm = 3000
//! max_speed_rpm = 4500
//! rotor_inertia_kg_m2 = 1.1e-3
//! [shedding.servo.transmission]    # a linear drive: travel per motor revolution
//! travel_mm_per_rev = 200
//! efficiency = 0.95
//! # or a crank and lever (loomkin_servo::CrankLever; the frame at mid-stroke with the output arm
//! # horizontal):
//! # kind = "crank_lever"
//! # crank_radius_mm = 45
//! # rod_length_mm = 200
//! # lever_input_arm_mm = 100
//! # lever_output_arm_mm = 300
//! # rocking_shaft_x_mm = -100
//! # rocking_shaft_y_mm = 200
//! # frame_link_mm = 500            # optional
//! # gear_ratio = 8                 # motor turns per crank turn, 1 when left out
//! [shedding.servo.winding]         # copper loss R·(T/k_t)²
//! resistance_ohm = 1.4
//! torque_constant_n_m_a = 1.6
//! [shedding.servo.bus]
//! voltage_v = 560
//! regeneration_efficiency = 0.9
//! braking_resistor_ohm = 33
//! [[shedding.servo.frame]]         # frames 1 and 2 (from the front) get their own motor
//! frames = [1, 2]
//! motor = { rated_torque_nm = 8, peak_torque_nm = 24, rated_speed_rpm = 3000, max_speed_rpm = 4500, rotor_inertia_kg_m2 = 8e-4 }
//! ```

use crate::moves::MoveKindsFile;
use crate::{EshedError, MoveKinds, Result};
use loomkin_servo::{CrankBranch, CrankLever, Motor, ServoError};
use loomkin_units::{Field, Range, RangeError};
use serde::{Deserialize, Serialize};

/// The transmission from the motor to the frame: a linear drive (rack and pinion, belt, screw;
/// the default, `kind = "linear"`) or a crank and lever (`kind = "crank_lever"`, the geometry of
/// [`loomkin_servo::CrankLever`] as keys of the same table; `mid_stroke_mm` is the frame's own).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "TransmissionFile")]
pub struct Transmission {
    /// Frame travel per motor revolution, mm/rev ([`Transmission::TRAVEL_MM_PER_REV`]); not read
    /// with a crank and lever (0 there).
    pub travel_mm_per_rev: f64,
    /// Efficiency η ([`Transmission::EFFICIENCY`]).
    #[serde(default = "Transmission::default_efficiency")]
    pub efficiency: f64,
    /// Coulomb friction of the frame's guides, N ([`Transmission::FRICTION_N`]).
    #[serde(default)]
    pub friction_n: f64,
    /// Viscous friction, N·s/m ([`Transmission::VISCOUS_N_S_M`]).
    #[serde(default)]
    pub viscous_n_s_m: f64,
    /// Extra inertia on the motor shaft (coupling, pulley, gearbox input), kg·m²
    /// ([`Transmission::EXTRA_INERTIA_KG_M2`]).
    #[serde(default)]
    pub extra_inertia_kg_m2: f64,
    /// The crank and lever in place of the linear drive (`kind = "crank_lever"`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crank_lever: Option<CrankLever>,
}

/// `kind` of a transmission.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
enum TransmissionKind {
    #[default]
    Linear,
    CrankLever,
}

/// `[shedding.servo.transmission]` as written: the linear drive's keys or the crank and lever's.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TransmissionFile {
    #[serde(default)]
    kind: TransmissionKind,
    travel_mm_per_rev: Option<f64>,
    #[serde(default = "Transmission::default_efficiency")]
    efficiency: f64,
    #[serde(default)]
    friction_n: f64,
    #[serde(default)]
    viscous_n_s_m: f64,
    #[serde(default)]
    extra_inertia_kg_m2: f64,
    crank_radius_mm: Option<f64>,
    rod_length_mm: Option<f64>,
    lever_input_arm_mm: Option<f64>,
    lever_output_arm_mm: Option<f64>,
    lever_angle_deg: Option<f64>,
    rocking_shaft_x_mm: Option<f64>,
    rocking_shaft_y_mm: Option<f64>,
    frame_link_mm: Option<f64>,
    lever_inertia_kg_m2: Option<f64>,
    crank_branch: Option<CrankBranch>,
    gear_ratio: Option<f64>,
}

impl TryFrom<TransmissionFile> for Transmission {
    type Error = String;

    fn try_from(f: TransmissionFile) -> std::result::Result<Self, String> {
        let geometry = [
            ("crank_radius_mm", f.crank_radius_mm),
            ("rod_length_mm", f.rod_length_mm),
            ("lever_input_arm_mm", f.lever_input_arm_mm),
            ("lever_output_arm_mm", f.lever_output_arm_mm),
            ("rocking_shaft_x_mm", f.rocking_shaft_x_mm),
            ("rocking_shaft_y_mm", f.rocking_shaft_y_mm),
        ];
        let optional = [
            ("lever_angle_deg", f.lever_angle_deg.is_some()),
            ("frame_link_mm", f.frame_link_mm.is_some()),
            ("lever_inertia_kg_m2", f.lever_inertia_kg_m2.is_some()),
            ("crank_branch", f.crank_branch.is_some()),
            ("gear_ratio", f.gear_ratio.is_some()),
        ];
        let crank_lever = match f.kind {
            TransmissionKind::Linear => {
                let given = geometry.iter().map(|(k, v)| (*k, v.is_some())).chain(optional).find(|(_, g)| *g);
                if let Some((key, _)) = given {
                    return Err(format!("transmission.{key}: a key of a crank and lever: give kind = \"crank_lever\""));
                }
                None
            }
            TransmissionKind::CrankLever => {
                if f.travel_mm_per_rev.is_some() {
                    return Err(
                        "transmission.travel_mm_per_rev: a key of a linear drive, not of kind = \"crank_lever\"".into(),
                    );
                }
                let need = |i: usize| {
                    geometry[i].1.ok_or_else(|| {
                        format!("transmission: missing field `{}` (kind = \"crank_lever\" needs {})", geometry[i].0, {
                            let keys: Vec<&str> = geometry.iter().map(|g| g.0).collect();
                            keys.join(", ")
                        })
                    })
                };
                Some(CrankLever {
                    crank_radius_mm: need(0)?,
                    rod_length_mm: need(1)?,
                    lever_input_arm_mm: need(2)?,
                    lever_output_arm_mm: need(3)?,
                    rocking_shaft_x_mm: need(4)?,
                    rocking_shaft_y_mm: need(5)?,
                    lever_angle_deg: f.lever_angle_deg.unwrap_or(CrankLever::LEVER_ANGLE_DEG.default_value()),
                    frame_link_mm: f.frame_link_mm,
                    lever_inertia_kg_m2: f
                        .lever_inertia_kg_m2
                        .unwrap_or(CrankLever::LEVER_INERTIA_KG_M2.default_value()),
                    crank_branch: f.crank_branch.unwrap_or_default(),
                    gear_ratio: f.gear_ratio.unwrap_or(CrankLever::GEAR_RATIO.default_value()),
                    mid_stroke_mm: CrankLever::MID_STROKE_MM.default_value(),
                })
            }
        };
        let travel_mm_per_rev = match (crank_lever, f.travel_mm_per_rev) {
            (Some(_), _) => 0.0,
            (None, Some(t)) => t,
            (None, None) => return Err("missing field `travel_mm_per_rev`".into()),
        };
        Ok(Self {
            travel_mm_per_rev,
            efficiency: f.efficiency,
            friction_n: f.friction_n,
            viscous_n_s_m: f.viscous_n_s_m,
            extra_inertia_kg_m2: f.extra_inertia_kg_m2,
            crank_lever,
        })
    }
}

impl Transmission {
    /// `travel_mm_per_rev`: the frame's travel per motor revolution, 10⁻³ … 10⁵ mm/rev (from a
    /// fine screw to a belt pulley well beyond any frame stroke; the servo axis model takes the same).
    pub const TRAVEL_MM_PER_REV: Field = Field::new(
        "travel_mm_per_rev",
        Range::closed(1e-3, 1e5, "mm/rev"),
        "Frame travel per motor revolution (pinion or pulley circumference over the gear ratio, screw \
         lead): 10⁻³ … 10⁵ mm/rev; required.",
    );
    /// `efficiency`: of the transmission, 10⁻³ … 1 (the servo axis model's range); 1 when left out.
    pub const EFFICIENCY: Field = Field::new(
        "efficiency",
        Range::closed(1e-3, 1.0, ""),
        "Transmission efficiency η: the motor gives F/(k·η) for a load force F, while driving and \
         while braking (the servo axis model's conservative rule): 10⁻³ … 1; 1 when left out.",
    )
    .with_default(1.0);
    /// `friction_n`: Coulomb friction of the frame's guides, 0 … 10⁶ N; 0 when left out.
    pub const FRICTION_N: Field = Field::new(
        "friction_n",
        Range::closed(0.0, 1e6, "N"),
        "Coulomb friction of the frame's guides while it moves (zero in a dwell): 0 … 10⁶ N; 0 when left out.",
    )
    .with_default(0.0);
    /// `viscous_n_s_m`: viscous friction, 0 … 10⁶ N·s/m; 0 when left out.
    pub const VISCOUS_N_S_M: Field = Field::new(
        "viscous_n_s_m",
        Range::closed(0.0, 1e6, "N·s/m"),
        "Viscous friction of the frame's guides: 0 … 10⁶ N·s/m; 0 when left out.",
    )
    .with_default(0.0);
    /// `extra_inertia_kg_m2`: on the motor shaft, 0 … 10³ kg·m²; 0 when left out.
    pub const EXTRA_INERTIA_KG_M2: Field = Field::new(
        "extra_inertia_kg_m2",
        Range::closed(0.0, 1e3, "kg·m²"),
        "Extra inertia on the motor shaft (coupling, pulley, gearbox input): 0 … 10³ kg·m²; 0 when left out.",
    )
    .with_default(0.0);

    fn default_efficiency() -> f64 {
        Self::EFFICIENCY.default_value()
    }

    fn check(&self, at: &str) -> Result<()> {
        let f = |field: Field, v: f64| field.check_as(&format!("{at}.{}", field.name), v).map(|_| ());
        match &self.crank_lever {
            Some(cl) => cl.check(at)?,
            None => f(Self::TRAVEL_MM_PER_REV, self.travel_mm_per_rev)?,
        }
        f(Self::EFFICIENCY, self.efficiency)?;
        f(Self::FRICTION_N, self.friction_n)?;
        f(Self::VISCOUS_N_S_M, self.viscous_n_s_m)?;
        f(Self::EXTRA_INERTIA_KG_M2, self.extra_inertia_kg_m2)?;
        Ok(())
    }
}

/// The motor's winding, for the copper loss `P_cu = R·(T/k_t)²`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Winding {
    /// Resistance `R`, Ω ([`Winding::RESISTANCE_OHM`]).
    #[serde(default)]
    pub resistance_ohm: f64,
    /// Torque constant `k_t`, N·m/A ([`Winding::TORQUE_CONSTANT_N_M_A`]).
    pub torque_constant_n_m_a: f64,
}

impl Winding {
    /// `resistance_ohm`: the winding resistance in `P_cu = R·(T/k_t)²`, 0 … 10⁴ Ω.
    pub const RESISTANCE_OHM: Field = Field::new(
        "resistance_ohm",
        Range::closed(0.0, 1e4, "Ω"),
        "Winding resistance R of the copper loss P_cu = R·(T/k_t)², the resistance the torque-producing \
         current I = T/k_t flows through (for a three-phase motor whose k_t refers to the RMS phase \
         current: 3·R_phase, or 1.5 times the line-to-line resistance): 0 … 10⁴ Ω; 0 (no copper loss) \
         when left out.",
    )
    .with_default(0.0);
    /// `torque_constant_n_m_a`: `k_t`, 10⁻⁴ … 10³ N·m/A.
    pub const TORQUE_CONSTANT_N_M_A: Field = Field::new(
        "torque_constant_n_m_a",
        Range::closed(1e-4, 1e3, "N·m/A"),
        "Torque constant k_t (torque per ampere of the current R is given for): 10⁻⁴ … 10³ N·m/A; \
         required with a winding.",
    );

    /// No copper loss (a winding left out).
    pub const NONE: Self = Self { resistance_ohm: 0.0, torque_constant_n_m_a: 1.0 };

    /// `R/k_t²`, W per (N·m)².
    pub fn loss_w_per_n_m2(&self) -> f64 {
        self.resistance_ohm / (self.torque_constant_n_m_a * self.torque_constant_n_m_a)
    }

    fn check(&self, at: &str) -> Result<()> {
        Self::RESISTANCE_OHM.check_as(&format!("{at}.resistance_ohm"), self.resistance_ohm)?;
        Self::TORQUE_CONSTANT_N_M_A.check_as(&format!("{at}.torque_constant_n_m_a"), self.torque_constant_n_m_a)?;
        Ok(())
    }
}

/// The shared DC bus.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Bus {
    /// Bus voltage, V ([`Bus::VOLTAGE_V`]).
    #[serde(default = "Bus::default_voltage")]
    pub voltage_v: f64,
    /// Share of a braking drive's electrical power that reaches the bus ([`Bus::REGENERATION_EFFICIENCY`]).
    #[serde(default = "Bus::default_regeneration")]
    pub regeneration_efficiency: f64,
    /// Braking resistor, Ω ([`Bus::BRAKING_RESISTOR_OHM`]); none when left out.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub braking_resistor_ohm: Option<f64>,
}

impl Default for Bus {
    fn default() -> Self {
        Self {
            voltage_v: Self::VOLTAGE_V.default_value(),
            regeneration_efficiency: Self::REGENERATION_EFFICIENCY.default_value(),
            braking_resistor_ohm: None,
        }
    }
}

impl Bus {
    /// `voltage_v`: the DC bus voltage, 1 … 10⁴ V; 560 V (400 V three-phase mains rectified) when left out.
    pub const VOLTAGE_V: Field = Field::new(
        "voltage_v",
        Range::closed(1.0, 1e4, "V"),
        "DC bus voltage (peak bus current = peak bus power / voltage; the braking resistor takes at most \
         V²/R): 1 … 10⁴ V; 560 V (400 V three-phase mains, rectified) when left out.",
    )
    .with_default(560.0);
    /// `regeneration_efficiency`: 0 … 1; 1 when left out.
    pub const REGENERATION_EFFICIENCY: Field = Field::new(
        "regeneration_efficiency",
        Range::closed(0.0, 1.0, ""),
        "Share of a braking drive's electrical power that reaches the bus (inverter losses while \
         regenerating): 0 (none returns) … 1; 1 when left out.",
    )
    .with_default(1.0);
    /// `braking_resistor_ohm`: 10⁻³ … 10⁵ Ω; none when left out.
    pub const BRAKING_RESISTOR_OHM: Field = Field::new(
        "braking_resistor_ohm",
        Range::closed(1e-3, 1e5, "Ω"),
        "Braking resistor across the bus: it takes at most V²/R, which the peak braking power must not \
         exceed: 10⁻³ … 10⁵ Ω; none (not checked) when left out.",
    );

    fn default_voltage() -> f64 {
        Self::VOLTAGE_V.default_value()
    }

    fn default_regeneration() -> f64 {
        Self::REGENERATION_EFFICIENCY.default_value()
    }

    fn check(&self, at: &str) -> Result<()> {
        Self::VOLTAGE_V.check_as(&format!("{at}.voltage_v"), self.voltage_v)?;
        Self::REGENERATION_EFFICIENCY
            .check_as(&format!("{at}.regeneration_efficiency"), self.regeneration_efficiency)?;
        if let Some(r) = self.braking_resistor_ohm {
            Self::BRAKING_RESISTOR_OHM.check_as(&format!("{at}.braking_resistor_ohm"), r)?;
        }
        Ok(())
    }
}

/// One frame's servo drive.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrameServo {
    /// The motor (as `loomkin servo check` takes it).
    pub motor: Motor,
    /// The transmission.
    pub transmission: Transmission,
    /// The winding (copper loss).
    pub winding: Winding,
    /// The frame's own motion angle, deg (`None`: the shedding law's).
    pub motion_deg: Option<f64>,
    /// The laws and motion angles by kind of move the loom file gives for this frame (its own,
    /// else all frames'; `motion_deg` counts for both ways) ([`crate::moves`]).
    #[serde(skip)]
    pub moves: MoveKinds,
}

/// The servo drives of every frame and their bus (`[shedding.servo]`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ServoShedding {
    /// One per frame, front first.
    pub frames: Vec<FrameServo>,
    /// The shared bus.
    pub bus: Bus,
    /// Consecutive changes as one move without a stop ([`crate::FramePlan`]).
    pub pass_through: bool,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ServoFile {
    #[serde(default)]
    pass_through: bool,
    motor: Option<Motor>,
    transmission: Option<Transmission>,
    winding: Option<Winding>,
    #[serde(default)]
    bus: Bus,
    #[serde(default)]
    frame: Vec<FrameFile>,
    rise_law: Option<toml::Value>,
    fall_law: Option<toml::Value>,
    through_law: Option<toml::Value>,
    rise_motion_deg: Option<f64>,
    fall_motion_deg: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct FrameFile {
    frames: Vec<i64>,
    motor: Option<Motor>,
    transmission: Option<Transmission>,
    winding: Option<Winding>,
    motion_deg: Option<f64>,
    rise_law: Option<toml::Value>,
    fall_law: Option<toml::Value>,
    through_law: Option<toml::Value>,
    rise_motion_deg: Option<f64>,
    fall_motion_deg: Option<f64>,
}

/// A servo error's field under the table it was read from (`motor.peak_torque_nm` →
/// `shedding.servo.motor.peak_torque_nm`).
fn prefixed(at: &str, e: ServoError) -> EshedError {
    match e {
        ServoError::Range(r) => {
            let field = format!("{at}.{}", r.field);
            EshedError::Range(RangeError { field, ..r })
        }
        ServoError::Parse { field, text, expected } => {
            EshedError::field(format!("{at}.{field}"), format!("{text}: expected {expected}"))
        }
        other => EshedError::Servo(other),
    }
}

impl ServoShedding {
    /// Reads `[shedding.servo]` (`value`, read under the name `at`) for `frames` frames. Every
    /// number is range-checked; the motor by the servo axis model's rules.
    pub fn from_toml(value: toml::Value, frames: usize, at: &str) -> Result<Self> {
        let file: ServoFile = value.try_into().map_err(|e: toml::de::Error| EshedError::field(at, e.message()))?;
        let mut out: Vec<Option<FrameServo>> = vec![None; frames];
        let base = |m: Option<Motor>, t: Option<Transmission>, w: Option<Winding>| {
            (m.or(file.motor.clone()), t.or(file.transmission), w.or(file.winding))
        };
        let mut assigned = vec![false; frames];
        let all = MoveKindsFile {
            rise_law: file.rise_law.clone(),
            fall_law: file.fall_law.clone(),
            through_law: file.through_law.clone(),
            rise_motion_deg: file.rise_motion_deg,
            fall_motion_deg: file.fall_motion_deg,
        }
        .read(at)?;
        for (gi, g) in file.frame.iter().enumerate() {
            let here = format!("{at}.frame[{gi}]");
            if g.frames.is_empty() {
                return Err(EshedError::field(format!("{here}.frames"), "name at least one frame (1 = front)"));
            }
            for &f in &g.frames {
                let i = usize::try_from(f).ok().filter(|i| (1..=frames).contains(i)).ok_or_else(|| {
                    EshedError::field(
                        format!("{here}.frames"),
                        format!("frame {f}: frames are numbered 1 to {frames} from the front"),
                    )
                })?;
                if std::mem::replace(&mut assigned[i - 1], true) {
                    return Err(EshedError::field(format!("{here}.frames"), format!("frame {f} is named twice")));
                }
                let own = MoveKindsFile {
                    rise_law: g.rise_law.clone(),
                    fall_law: g.fall_law.clone(),
                    through_law: g.through_law.clone(),
                    rise_motion_deg: g.rise_motion_deg,
                    fall_motion_deg: g.fall_motion_deg,
                }
                .read(&here)?;
                let mut f = Self::frame(base(g.motor.clone(), g.transmission, g.winding), g.motion_deg, &here)?;
                f.moves = MoveKinds::over(own, g.motion_deg, &all);
                out[i - 1] = Some(f);
            }
        }
        let frames = out
            .into_iter()
            .map(|f| match f {
                Some(f) => Ok(f),
                None => Self::frame(base(None, None, None), None, at).map(|f| FrameServo { moves: all.clone(), ..f }),
            })
            .collect::<Result<Vec<_>>>()?;
        file.bus.check(&format!("{at}.bus"))?;
        Ok(Self { frames, bus: file.bus, pass_through: file.pass_through })
    }

    fn frame(
        (motor, transmission, winding): (Option<Motor>, Option<Transmission>, Option<Winding>),
        motion_deg: Option<f64>,
        at: &str,
    ) -> Result<FrameServo> {
        let motor = motor.ok_or_else(|| {
            EshedError::field(
                format!("{at}.motor"),
                "missing: rated_torque_nm, peak_torque_nm, rated_speed_rpm, max_speed_rpm, rotor_inertia_kg_m2",
            )
        })?;
        let transmission = transmission.ok_or_else(|| {
            EshedError::field(format!("{at}.transmission"), "missing: travel_mm_per_rev (and efficiency)")
        })?;
        transmission.check(&format!("{at}.transmission"))?;
        let winding = winding.unwrap_or(Winding::NONE);
        winding.check(&format!("{at}.winding"))?;
        // The motor by the servo axis model's rules (with a unit load standing for the frame).
        let axis = crate::drive::axis(&motor, &transmission, &crate::FrameLoad::UNIT);
        axis.validate(loomkin_laws::StrokeUnit::Mm).map_err(|e| prefixed(at, e))?;
        Ok(FrameServo { motor, transmission, winding, motion_deg, moves: MoveKinds::default() })
    }
}
