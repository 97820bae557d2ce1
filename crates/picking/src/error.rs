//! Errors of the picking study.

use thiserror::Error;

/// Everything that can go wrong when describing or simulating a picking mechanism.
///
/// Each variant names the offending field and, where there is one, the allowed range and unit.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum PickError {
    /// A numeric input outside its allowed range.
    #[error("{field} = {} is out of range: allowed {} {lo} {field} {hi} {}{unit}", num(*value), num(*min), num(*max))]
    OutOfRange {
        /// Name of the field (with its unit suffix, e.g. `play_mm`).
        field: String,
        /// Offending value.
        value: f64,
        /// Lower bound.
        min: f64,
        /// Upper bound.
        max: f64,
        /// `"<"` or `"≤"` for the lower bound.
        lo: &'static str,
        /// `"<"` or `"≤"` for the upper bound.
        hi: &'static str,
        /// Unit suffix with a leading space, or empty.
        unit: String,
    },
    /// An input that is not a finite number.
    #[error("{field} is not a finite number")]
    NotFinite {
        /// Name of the field.
        field: String,
    },
    /// An input inside its range that makes a derived quantity overflow or underflow (found by
    /// putting the paper's value back in its place, one input at a time).
    #[error(
        "{field} = {} makes {quantity} not a finite positive number (an overflow or underflow): choose a less \
         extreme {field}",
        num(*value)
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
        num(*play_mm)
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
        num(*checking_kgf)
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
        num(*strap_cm),
        num(*l_cm)
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

impl PickError {
    /// Checks `min ≤ value ≤ max` (closed) and finiteness.
    pub fn check_closed(field: &str, value: f64, min: f64, max: f64, unit: &str) -> Result<f64> {
        Self::check(field, value, min, max, unit, false, false)
    }

    /// Checks `min < value < max` (open) and finiteness.
    pub fn check_open(field: &str, value: f64, min: f64, max: f64, unit: &str) -> Result<f64> {
        Self::check(field, value, min, max, unit, true, true)
    }

    /// Checks `min < value ≤ max` and finiteness.
    pub fn check_positive(field: &str, value: f64, max: f64, unit: &str) -> Result<f64> {
        Self::check(field, value, 0.0, max, unit, true, false)
    }

    /// Checks `min ≤ value < max` and finiteness.
    pub fn check_below(field: &str, value: f64, min: f64, max: f64, unit: &str) -> Result<f64> {
        Self::check(field, value, min, max, unit, false, true)
    }

    fn check(field: &str, value: f64, min: f64, max: f64, unit: &str, open_lo: bool, open_hi: bool) -> Result<f64> {
        if !value.is_finite() {
            return Err(Self::NotFinite { field: field.into() });
        }
        let bad_lo = if open_lo { value <= min } else { value < min };
        let bad_hi = if open_hi { value >= max } else { value > max };
        if bad_lo || bad_hi {
            return Err(Self::OutOfRange {
                field: field.into(),
                value,
                min,
                max,
                lo: if open_lo { "<" } else { "≤" },
                hi: if open_hi { "<" } else { "≤" },
                unit: if unit.is_empty() { String::new() } else { format!(" {unit}") },
            });
        }
        Ok(value)
    }
}

/// A number for an error line: plain when of ordinary size, in exponent form when very large
/// or very small (so that 1e308 does not print as 309 digits).
fn num(v: f64) -> String {
    if v == 0.0 || (1e-4..1e7).contains(&v.abs()) { format!("{v}") } else { format!("{v:e}") }
}

/// Result alias of the picking study.
pub type Result<T, E = PickError> = std::result::Result<T, E>;
