//! The named laws of the paper's Tables 2 and 3.
//!
//! How the shapes of Table 3 are read (the positive phase of the acceleration; the negative phase
//! is its odd mirror, since the paper takes every law symmetric about the crossing point):
//!
//! * "sin(kφ) + cos(kφ)" — a quarter sine rising from 0 to the peak over the first half of the
//!   positive phase, then a quarter cosine falling back to 0 over the second half
//!   (`0.5:sine-ramp:0:1,0.5:cosine-ramp:1:0`). Together that is one half sine, i.e. the cycloidal
//!   law; it is also experiment 8 of Table 1 (`k1 = 0.5, k2 = 0`).
//! * "МТРАП k_r" (modified trapezoid) — a quarter-sine rise of relative length `k_r`, a constant
//!   plateau of `1 − 2k_r`, a quarter-cosine fall of `k_r`, all relative to the positive phase
//!   (the `k_Ti` convention of the paper). `k_r = 0.25` is then the classical modified trapezoid
//!   (ramps of 1/8 of the motion); `k_r = 1/3` gives three equal parts. Reading `k_r` as a
//!   fraction of the whole motion would make `k_r = 1/3` impossible (the ramps would overlap).

use crate::{Result, ShedError, ShedLaw};
use loomkin_laws::parse_segments;

/// One named law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Preset {
    /// Name used in the library and the CLI.
    pub name: &'static str,
    /// The paper's Russian name.
    pub name_ru: &'static str,
    /// Motion angle `φ_дв`, deg (Table 2).
    pub motion_deg: f64,
    /// Positive phase of the acceleration, `LEN:SHAPE[:LEVEL…],…`.
    pub positive: &'static str,
    /// The shape as Table 3 writes it.
    pub table_shape: &'static str,
}

const SIN_COS: &str = "0.5:sine-ramp:0:1,0.5:cosine-ramp:1:0";
const MTRAP_QUARTER: &str = "0.25:sine-ramp:0:1,0.5:constant:1,0.25:cosine-ramp:1:0";
const MTRAP_THIRD: &str =
    "0.3333333333333333:sine-ramp:0:1,0.3333333333333334:constant:1,0.3333333333333333:cosine-ramp:1:0";

/// The five named laws, in the order of Tables 2 and 3.
pub const PRESETS: &[Preset] = &[
    Preset {
        name: "basic",
        name_ru: "Базовый",
        motion_deg: 180.0,
        positive: SIN_COS,
        table_shape: "sin(kφ) + cos(kφ)",
    },
    Preset {
        name: "traditional",
        name_ru: "Традиционный",
        motion_deg: 270.0,
        positive: SIN_COS,
        table_shape: "sin(kφ) + cos(kφ)",
    },
    Preset {
        name: "dobby",
        name_ru: "Кареточный",
        motion_deg: 300.0,
        positive: MTRAP_QUARTER,
        table_shape: "modified trapezoid (MTRAP) k_r = 0.25",
    },
    Preset {
        name: "semi-smooth",
        name_ru: "Полуплавный",
        motion_deg: 330.0,
        positive: MTRAP_THIRD,
        table_shape: "modified trapezoid (MTRAP) k_r = 1/3",
    },
    Preset {
        name: "smooth",
        name_ru: "Плавный",
        motion_deg: 360.0,
        positive: MTRAP_THIRD,
        table_shape: "modified trapezoid (MTRAP) k_r = 1/3",
    },
];

/// Comma-separated preset names.
pub fn preset_names() -> String {
    PRESETS.iter().map(|p| p.name).collect::<Vec<_>>().join(", ")
}

impl Preset {
    /// Looks a preset up by name.
    pub fn find(name: &str) -> Result<&'static Preset> {
        PRESETS
            .iter()
            .find(|p| p.name == name.trim())
            .ok_or_else(|| ShedError::UnknownPreset { name: name.into(), known: preset_names() })
    }

    /// The law.
    pub fn law(&self) -> Result<ShedLaw> {
        ShedLaw::symmetric(self.motion_deg, parse_segments(self.positive, self.name)?)
    }
}

/// The law of a preset by name.
pub fn preset(name: &str) -> Result<ShedLaw> {
    Preset::find(name)?.law()
}
