//! The time budget every carrier shares: how fast the loom may run for a reed width.
//!
//! A carrier of length `L` must cross the reed space `W` — its tip enters at one selvedge, its
//! tail leaves at the other, so it travels `W + L` — at a mean speed `v̄` while the main shaft turns
//! through the insertion window `θ` (degrees) in which the shed lets it pass. At `n` rpm the shaft
//! turns `6·n` degrees per second, so the crossing takes `θ/(6·n)` seconds and
//!
//! $$ n_{max} = \frac{\bar v\,\theta}{6\,(W + L)} \quad [\mathrm{picks/min}], \qquad
//!    \bar v_{req} = \frac{6\,n\,(W + L)}{\theta} \quad [\mathrm{m/s}] $$
//!
//! (lengths in m; the textbooks write it `n = v̄·θ/(6·(K_b + L_s))` with `K_b` the reed space and
//! `L_s` the shuttle's length). The lecture example docs/loom.md quotes: a shuttle of 0.30 m at
//! 13.75 m/s through a 135° window across 1.15 m runs at most 213 picks/min (213.36).
//!
//! **Energy per pick** is the kinetic energy the drive gives the carrier to carry it across at its
//! mean speed, `E = ½·m·v̄²`, and the **drive power** that energy times the picks per second,
//! `P = E·n/60`. The mean speed is the only speed the budget knows: a carrier that flies freely
//! (a shuttle or a projectile, launched at about `v̄` and braked in the receiver) takes this
//! energy once per pick and loses it in the brake. A carrier that starts and stops on its drive (a
//! rapier head) peaks above its mean — `π/2·v̄` on a harmonic stroke, so `(π/2)² ≈ 2.47` times
//! this energy — and its drive returns part of it; the rapier's own model reports its peak speed.

use loomkin_units::{Field, Range, RangeError, ShaftSpeed};
use serde::Serialize;

/// The highest loom speed at which a carrier of mean speed `mean_speed_m_s` crosses a reed space
/// `reed_width_m` plus its length `carrier_length_m` within `window_deg` of the main shaft, rpm
/// (picks per minute).
///
/// ```
/// // The textbook case: 13.75 m/s, 135°, 1.15 m reed space, a 0.30 m shuttle.
/// let n = loomkin_insertion::max_speed_rpm(13.75, 135.0, 1.15, 0.30);
/// assert_eq!(n.floor(), 213.0);
/// ```
pub fn max_speed_rpm(mean_speed_m_s: f64, window_deg: f64, reed_width_m: f64, carrier_length_m: f64) -> f64 {
    mean_speed_m_s * window_deg / (6.0 * (reed_width_m + carrier_length_m))
}

/// The mean speed a carrier needs to cross `reed_width_m + carrier_length_m` within `window_deg`
/// at `speed_rpm`, m/s: the converse of [`max_speed_rpm`].
pub fn required_speed_m_s(speed_rpm: f64, window_deg: f64, reed_width_m: f64, carrier_length_m: f64) -> f64 {
    6.0 * speed_rpm * (reed_width_m + carrier_length_m) / window_deg
}

/// The window (deg of main shaft) a carrier of mean speed `mean_speed_m_s` needs to cross
/// `path_m` (reed space plus carrier length) at `speed_rpm`.
pub fn window_needed_deg(speed_rpm: f64, path_m: f64, mean_speed_m_s: f64) -> f64 {
    6.0 * speed_rpm * path_m / mean_speed_m_s
}

/// Where the insertion window of a budget comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum WindowSource {
    /// Given as a number (`--window-deg`, `window_deg`).
    #[default]
    Given,
    /// The loom file's entry and exit angles (`[insertion] entry_deg`, `exit_deg`, or the window
    /// its carrier speed implies).
    EntryExit,
    /// The clear-shed window `loom check` finds for the pattern: the angles common to every pick
    /// in which the shed clears the carrier.
    ClearShed,
}

/// The inputs of the time budget, in the units a designer gives them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PickBudget {
    /// Reed space (the warp's width in the reed), mm ([`PickBudget::REED_WIDTH_MM`]).
    pub reed_width_mm: f64,
    /// Carrier length along the weft, mm ([`PickBudget::CARRIER_LENGTH_MM`]).
    pub carrier_length_mm: f64,
    /// The insertion window, deg of main shaft ([`PickBudget::WINDOW_DEG`]).
    pub window_deg: f64,
    /// Where the window comes from.
    pub window_source: WindowSource,
    /// The carrier's mean speed across the shed, m/s ([`PickBudget::SPEED_M_S`]).
    pub speed_m_s: f64,
    /// The loom's speed, rpm, for the required carrier speed and the drive power (none: the
    /// power is given at the highest speed).
    pub speed_rpm: Option<f64>,
    /// The carrier's mass, g ([`PickBudget::CARRIER_MASS_G`]), for the energy and power.
    pub carrier_mass_g: Option<f64>,
}

/// What the time budget answers.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BudgetReport {
    /// Reed space, mm.
    pub reed_width_mm: f64,
    /// Carrier length, mm.
    pub carrier_length_mm: f64,
    /// The insertion window used, deg.
    pub window_deg: f64,
    /// Where it comes from: `given`, `entry_exit` (the loom file's entry and exit angles) or
    /// `clear_shed` (the clear-shed window of the pattern, as `loom check` finds it).
    pub window_source: WindowSource,
    /// The carrier's mean speed, m/s.
    pub speed_m_s: f64,
    /// The highest loom speed at which the carrier crosses in the window, picks/min.
    pub max_picks_per_min: f64,
    /// The loom speed the next keys are given at, rpm (the loom's, else `max_picks_per_min`).
    pub speed_rpm: f64,
    /// The mean carrier speed needed at `speed_rpm`, m/s.
    pub required_speed_m_s: f64,
    /// The carrier's mass, g (none: no energy or power).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub carrier_mass_g: Option<f64>,
    /// Kinetic energy given to the carrier per pick at its mean speed, ½·m·v̄², J.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy_per_pick_j: Option<f64>,
    /// That energy times the picks per second at `speed_rpm`, W.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub drive_power_w: Option<f64>,
}

impl PickBudget {
    /// `reed_width_mm`: 1 ≤ W ≤ 20000 mm.
    pub const REED_WIDTH_MM: Field = Field::new(
        "reed_width_mm",
        Range::closed(1.0, 20_000.0, "mm"),
        "Reed space, the warp's width in the reed: 1 ≤ W ≤ 20000 mm (the widest looms weave about 5.4 m; \
         20 m leaves room for technical looms without admitting nonsense; below a millimetre the highest \
         loom speed of a point carrier would overflow).",
    );
    /// `carrier_length_mm`: 0 ≤ L ≤ 5000 mm.
    pub const CARRIER_LENGTH_MM: Field = Field::new(
        "carrier_length_mm",
        Range::closed(0.0, 5000.0, "mm"),
        "The carrier's length along the weft (a shuttle, a projectile, a rapier head): 0 ≤ L ≤ 5000 mm; it \
         must clear the shed too, so it adds to the path (0: a point carrier, the yarn tip of an air jet).",
    );
    /// `window_deg`: 0.001 ≤ θ < 360°.
    pub const WINDOW_DEG: Field = Field::new(
        "window_deg",
        Range::closed_open(0.001, 360.0, "deg"),
        "The insertion window, main-shaft angle from the carrier's entry to its exit: 0.001 ≤ θ < 360° (the \
         pick must fit in one turn, which also holds the beat-up; a narrower window would need a carrier \
         speed that overflows).",
    );
    /// `speed_m_s`: 0 < v̄ ≤ 1000 m/s.
    pub const SPEED_M_S: Field = Field::new(
        "speed_m_s",
        Range::open_closed(0.0, 1000.0, "m/s"),
        "The carrier's mean speed across the shed: 0 < v̄ ≤ 1000 m/s (shuttles and rapiers fly 10–25 m/s, an \
         air jet's yarn tip up to about 60 m/s; the bound only keeps the arithmetic meaningful).",
    );
    /// `carrier_mass_g`: 0 < m ≤ 10⁵ g.
    pub const CARRIER_MASS_G: Field = Field::new(
        "carrier_mass_g",
        Range::open_closed(0.0, 1e5, "g"),
        "The carrier's moving mass for the energy per pick: 0 < m ≤ 100000 g (a projectile weighs about 40 g, \
         a shuttle about 0.4 kg, a rapier head with its tape a few hundred grams).",
    );

    /// The budget: every input checked against its field, then the formulas of the module's notes.
    pub fn report(&self) -> Result<BudgetReport, RangeError> {
        let w = Self::REED_WIDTH_MM.check(self.reed_width_mm)?;
        let l = Self::CARRIER_LENGTH_MM.check(self.carrier_length_mm)?;
        let theta = Self::WINDOW_DEG.check(self.window_deg)?;
        let v = Self::SPEED_M_S.check(self.speed_m_s)?;
        let mass_g = self.carrier_mass_g.map(|m| Self::CARRIER_MASS_G.check(m)).transpose()?;
        let (w_m, l_m) = (w * 1e-3, l * 1e-3);
        let max_picks_per_min = max_speed_rpm(v, theta, w_m, l_m);
        let speed_rpm = match self.speed_rpm {
            Some(n) => ShaftSpeed::from_rpm(n)?.rpm(),
            None => max_picks_per_min,
        };
        let energy = mass_g.map(|m| 0.5 * (m * 1e-3) * v * v);
        Ok(BudgetReport {
            reed_width_mm: w,
            carrier_length_mm: l,
            window_deg: theta,
            window_source: self.window_source,
            speed_m_s: v,
            max_picks_per_min,
            speed_rpm,
            required_speed_m_s: required_speed_m_s(speed_rpm, theta, w_m, l_m),
            carrier_mass_g: mass_g,
            energy_per_pick_j: energy,
            drive_power_w: energy.map(|e| e * speed_rpm / 60.0),
        })
    }
}

/// The budget's inputs as a front end takes them (the CLI's flags, Python's keywords), each
/// optional: a given one replaces the loom file's (its [`PickBudget`] from
/// `loomkin_loom::insertion::budget_of`), and without a file the reed width, carrier length,
/// window and speed must all be given.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BudgetInputs {
    /// Reed space, mm.
    pub reed_width_mm: Option<f64>,
    /// Carrier length, mm.
    pub carrier_length_mm: Option<f64>,
    /// The insertion window, deg (given: the window's source is [`WindowSource::Given`]).
    pub window_deg: Option<f64>,
    /// The carrier's mean speed, m/s.
    pub speed_m_s: Option<f64>,
    /// The loom's speed, rpm.
    pub speed_rpm: Option<f64>,
    /// The carrier's mass, g.
    pub carrier_mass_g: Option<f64>,
}

/// An input of the budget that neither a loom file nor the caller gave.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MissingInput {
    /// The input's field name (`reed_width_mm`, `carrier_length_mm`, `window_deg`, `speed_m_s`).
    pub field: &'static str,
}

/// The refusal of a pattern without a loom file: the clear-shed window is the loom's.
pub const PATTERN_NEEDS_LOOM: &str = "the clear-shed window needs a loom file";

impl MissingInput {
    /// The message, the input named as the front end names it (`--reed-width-mm`, `reed_width_mm`).
    pub fn message(&self, name: &str) -> String {
        format!("{name}: required without a loom file")
    }
}

impl BudgetInputs {
    /// The budget: `base` (a loom file's) with every given input over it, or the given inputs
    /// alone without a base (the first missing one of reed width, carrier length, window and speed
    /// is the error). Not checked here: [`PickBudget::report`] checks every number.
    pub fn onto(&self, base: Option<PickBudget>) -> Result<PickBudget, MissingInput> {
        let need = |v: Option<f64>, f: &Field| v.ok_or(MissingInput { field: f.name });
        let mut b = match base {
            Some(b) => b,
            None => PickBudget {
                reed_width_mm: need(self.reed_width_mm, &PickBudget::REED_WIDTH_MM)?,
                carrier_length_mm: need(self.carrier_length_mm, &PickBudget::CARRIER_LENGTH_MM)?,
                window_deg: need(self.window_deg, &PickBudget::WINDOW_DEG)?,
                window_source: WindowSource::Given,
                speed_m_s: need(self.speed_m_s, &PickBudget::SPEED_M_S)?,
                speed_rpm: None,
                carrier_mass_g: None,
            },
        };
        b.reed_width_mm = self.reed_width_mm.unwrap_or(b.reed_width_mm);
        b.carrier_length_mm = self.carrier_length_mm.unwrap_or(b.carrier_length_mm);
        if let Some(w) = self.window_deg {
            (b.window_deg, b.window_source) = (w, WindowSource::Given);
        }
        b.speed_m_s = self.speed_m_s.unwrap_or(b.speed_m_s);
        b.speed_rpm = self.speed_rpm.or(b.speed_rpm);
        b.carrier_mass_g = self.carrier_mass_g;
        Ok(b)
    }
}
