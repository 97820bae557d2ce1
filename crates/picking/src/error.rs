//! Errors of the picking study.

use loomkin_units::{FieldError, RangeError, compact};
use thiserror::Error;

/// Everything that can go wrong when describing or simulating a picking mechanism.
///
/// Each variant names the offending field and, where there is one, the allowed range and unit.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum PickError {
    /// A number outside its allowed range, or not a finite number.
    #[error(transparent)]
    Range(#[from] RangeError),
    /// An input inside its range that makes a derived quantity overflow or underflow (found by
    /// putting the paper's value back in its place, one input at a time).
    #[error(
        "{field} = {} makes {quantity} not a finite positive number (an overflow or underflow): choose a less \
         extreme {field}",
        compact(*value)
    )]
    NonFiniteResult {
        /// The input to blame.
        field: String,
        /// Its value.
        value: f64,
        /// The derived quantity that is not finite.
        quantity: String,
    },
    /// The strap-loop play is larger than the cam can take up before the end of its rise.
    #[error(
        "play_mm = {} is beyond the cam's reach: the play at the picker ({play_picker_mm:.2} mm = play·l/k) \
         must be less than the cam's remaining travel {reach_mm:.2} mm",
        compact(*play_mm)
    )]
    PlayBeyondReach {
        /// Play of the strap loop s'₀ in mm.
        play_mm: f64,
        /// Play referred to the picker, s₀ = s'₀·l/k, in mm.
        play_picker_mm: f64,
        /// Nominal picker travel available over the cam's rise, in mm.
        reach_mm: f64,
    },
    /// With `--start equilibrium` the picker must take up the play and the extra static
    /// deflection D' − D under the checking force before the shuttle moves; together they exceed
    /// the cam's travel.
    #[error(
        "checking_kgf = {} with the equilibrium start is beyond the cam's reach: the play at the \
         picker ({play_picker_mm:.2} mm) plus the extra static deflection D' − D = {extra_mm:.2} mm under the \
         checking force must be less than the cam's travel {reach_mm:.2} mm",
        compact(*checking_kgf)
    )]
    CheckingBeyondReach {
        /// Checking force F₀ in kgf.
        checking_kgf: f64,
        /// Play referred to the picker, s₀ = s'₀·l/k, in mm.
        play_picker_mm: f64,
        /// D' − D, in mm.
        extra_mm: f64,
        /// Nominal picker travel over the cam's rise, in mm.
        reach_mm: f64,
    },
    /// The strap position is so close to the pivot that B', C', D' (∝ 1/k²) overflow.
    #[error(
        "strap_cm = {} is out of range: the constants B', C', D' of eq. 4 (∝ 1/k²) are not finite; \
         allowed 0 < strap_cm < {} cm with finite constants",
        compact(*strap_cm),
        compact(*l_cm)
    )]
    StrapTooLow {
        /// Strap-loop height k in cm.
        strap_cm: f64,
        /// Stick length l in cm.
        l_cm: f64,
    },
    /// The mechanism oscillates too fast, or too many times over the pick, for the routes to
    /// follow it accurately (real picking mechanisms have ψ of 10²–10³ 1/s and a few cycles).
    #[error(
        "the setting gives a natural frequency ψ = {natural_1_s:.4e} 1/s and {cycles:.4e} oscillations over the \
         pick of {duration_s:.4e} s: allowed ψ ≤ {max_natural_1_s:e} 1/s and at most {max_cycles} oscillations \
         (check the compliances, masses, the design velocity and the loom speed)"
    )]
    TooManyOscillations {
        /// ψ = √((C'+1)/B') in 1/s.
        natural_1_s: f64,
        /// Duration of the cam's rise in real time, s.
        duration_s: f64,
        /// ψ·duration/(2π).
        cycles: f64,
        /// Largest ψ accepted, 1/s.
        max_natural_1_s: f64,
        /// Largest number of oscillations accepted.
        max_cycles: f64,
    },
    /// The closed form cannot answer: the forcing frequency μ·q meets the natural frequency ψ.
    #[error(
        "resonance: the cam's sine frequency μ·q = {forcing_1_s:.4} 1/s is within {rel_gap:.2e} of the natural \
         frequency ψ = {natural_1_s:.4} 1/s; the closed form's denominator C'+1−μ²q²B' vanishes"
    )]
    Resonance {
        /// Natural circular frequency ψ = √((C'+1)/B') in 1/s.
        natural_1_s: f64,
        /// Forcing circular frequency μ·q in 1/s.
        forcing_1_s: f64,
        /// |C'+1−μ²q²B'| / (C'+1).
        rel_gap: f64,
    },
    /// The closed form exists only for the paper's compound law.
    #[error("the closed form (eqs. 21–47) exists only for the compound law, not for the cam law '{law}'")]
    NoClosedForm {
        /// Name of the cam law.
        law: String,
    },
    /// An unknown setting name in a sweep.
    #[error(
        "unknown setting '{name}': known settings are speed (rpm), play (mm), strap (cm), shuttle (g), checking (kgf)"
    )]
    UnknownSetting {
        /// The name given.
        name: String,
    },
    /// A malformed mechanism description.
    #[error("mechanism file: {reason}")]
    Toml {
        /// What is wrong.
        reason: String,
    },
    /// A Monte-Carlo study file that cannot be run (the message names the key).
    #[error("Monte-Carlo study: {reason}")]
    Study {
        /// The key of the study file at fault (`draws`, `bins`, `settings.speed_rpm`, …; `study`
        /// when the file is not TOML).
        field: String,
        /// What is wrong.
        reason: String,
    },
    /// The numerical integrator failed.
    #[error("numerical integration failed: {reason}")]
    Solver {
        /// The solver's message.
        reason: String,
    },
    /// An error of the law core (cam laws from the catalogue).
    #[error(transparent)]
    Law(#[from] loomkin_laws::LawError),
}

impl FieldError for PickError {
    fn field(&self) -> Option<&str> {
        match self {
            Self::Range(e) => Some(&e.field),
            Self::NonFiniteResult { field, .. } => Some(field),
            Self::PlayBeyondReach { .. } => Some("play_mm"),
            Self::CheckingBeyondReach { .. } => Some("checking_kgf"),
            Self::StrapTooLow { .. } => Some("strap_cm"),
            Self::UnknownSetting { .. } => Some("setting"),
            Self::Study { field, .. } => Some(field),
            Self::Law(e) => e.field(),
            _ => None,
        }
    }
}

/// Result alias of the picking study.
pub type Result<T, E = PickError> = std::result::Result<T, E>;
