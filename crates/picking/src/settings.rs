//! Loom settings that differ from the design: speed, strap play and position, shuttle, checking.

use crate::units::{KG_PER_G, M_PER_CM, M_PER_MM, N_PER_KGF};
use crate::{Mechanism, PickError, Result};
use loomkin_units::{Field, Range, ShaftSpeed};
use serde::{Deserialize, Serialize};

/// How the instant the shuttle starts (t = 0) is found on the nominal motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StartRule {
    /// The paper's rule (§2.2): t₀ is read from the designed nominal curve where the cam has
    /// taken up the play, s(u₀) − s(0) = s₀. The checking force's static deflection D' is not
    /// re-read: when D' ≠ D the shuttle starts with ẍ(0) = (D − D')/B' ≠ 0.
    #[default]
    Paper,
    /// The shuttle starts when the picker force first balances the checking force:
    /// s(u₀) − s(0) = s₀ + D' − D (clamped at 0), so ẍ(0) = 0 whenever u₀ > 0.
    Equilibrium,
}

/// The loom settings under which the cam is run (SI inside; `with_*` take the paper's units).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    /// n₂: loom speed, rev/min.
    pub speed_rpm: f64,
    /// s'₀: play of the picking-strap loop, m (referred to the strap; s₀ = s'₀·l/k at the picker).
    pub play_m: f64,
    /// k: height of the strap loop on the picking stick, m (0 < k < l).
    pub strap_m: f64,
    /// m: shuttle mass, kg (a shuttle "weight" Q in grams is its mass in grams).
    pub shuttle_kg: f64,
    /// F₀: checking force, N.
    pub checking_n: f64,
    /// How t = 0 is placed on the nominal motion.
    pub start: StartRule,
}

impl Settings {
    /// `speed_rpm`: the loom speed n₂, the one main-shaft speed range; left out, the speed the cam
    /// is designed for (200 rpm for the paper's mechanism).
    pub const SPEED_RPM: Field = Field::new(
        "speed_rpm",
        ShaftSpeed::RANGE,
        "Loom speed n₂: the main-shaft speed range (0.001 … 100000 rpm keeps every derived quantity \
         finite); left out, the speed the cam is designed for (200 rpm for the paper's mechanism).",
    );
    /// `play_mm`: the play s'₀ of the strap loop; its upper bound is the mechanism's stick length
    /// ([`Setting::range`]), and a play the cam cannot take up is refused when the pick is resolved.
    pub const PLAY_MM: Field = Field::new(
        "play_mm",
        Range::at_least(0.0, "mm"),
        "Play s'₀ of the picking-strap loop: 0 ≤ s'₀ ≤ l, the stick length (740 mm for the paper's \
         mechanism); a play beyond the cam's reach is refused when the pick is resolved. 0 when left out.",
    )
    .with_default(0.0);
    /// `strap_cm`: the height k of the strap loop, 0 < k < l (the stick length, [`Setting::range`]).
    pub const STRAP_CM: Field = Field::new(
        "strap_cm",
        Range::above(0.0, "cm"),
        "Height k of the strap loop on the picking stick: 0 < k < l, the stick length (74 cm for the \
         paper's mechanism; the constants of eq. 4 go as 1/k²); left out, the mechanism's k.",
    );
    /// `shuttle_g`: the shuttle's weight Q in grams (its mass); left out, the mechanism's.
    pub const SHUTTLE_G: Field = Field::new(
        "shuttle_g",
        Range::open_closed(0.0, 1e5, "g"),
        "Shuttle weight Q (its mass in g): 0 < Q ≤ 100 kg, far above any shuttle; left out, the \
         mechanism's (419.725 g for the paper's: 0.428·10⁻³ kgf·s²/cm, which the paper rounds to 420 g).",
    );
    /// `checking_kgf`: the checking force F₀; left out, the mechanism's.
    pub const CHECKING_KGF: Field = Field::new(
        "checking_kgf",
        Range::closed(0.0, 1e3, "kgf"),
        "Checking force F₀: 0 ≤ F₀ ≤ 1000 kgf, far above any shuttle box; left out, the mechanism's \
         (5 kgf for the paper's).",
    );

    /// The designed setting of `mechanism`: designed speed, no play, designed k, m and F₀.
    pub fn designed(mechanism: &Mechanism) -> Self {
        let p = mechanism.params();
        Self {
            speed_rpm: mechanism.design_spec().speed_rpm,
            play_m: 0.0,
            strap_m: p.k_m,
            shuttle_kg: p.shuttle_kg,
            checking_n: p.checking_n,
            start: StartRule::Paper,
        }
    }

    /// Checks the ranges that do not depend on the cam ([`Setting::range`] of each setting):
    /// the shaft-speed range, 0 ≤ play ≤ l, 0 < k < l, 0 < Q ≤ 100 kg, 0 ≤ F₀ ≤ 1000 kgf. (Play
    /// beyond the cam's reach is found when the scenario is resolved.)
    pub fn validate(&self, mechanism: &Mechanism) -> Result<()> {
        for s in [Setting::Speed, Setting::Play, Setting::Strap, Setting::Shuttle, Setting::Checking] {
            s.range(mechanism).check(s.field().name, s.value(self))?;
        }
        Ok(())
    }

    /// Sets the loom speed, rev/min.
    pub fn with_speed_rpm(mut self, v: f64) -> Self {
        self.speed_rpm = v;
        self
    }

    /// Sets the strap-loop play from millimetres.
    pub fn with_play_mm(mut self, v: f64) -> Self {
        self.play_m = v * M_PER_MM;
        self
    }

    /// Sets the strap-loop height k from centimetres.
    pub fn with_strap_cm(mut self, v: f64) -> Self {
        self.strap_m = v * M_PER_CM;
        self
    }

    /// Sets the shuttle from its weight in grams.
    pub fn with_shuttle_g(mut self, v: f64) -> Self {
        self.shuttle_kg = v * KG_PER_G;
        self
    }

    /// Sets the checking force from kilogram-force.
    pub fn with_checking_kgf(mut self, v: f64) -> Self {
        self.checking_n = v * N_PER_KGF;
        self
    }

    /// Sets the start rule.
    pub fn with_start(mut self, start: StartRule) -> Self {
        self.start = start;
        self
    }
}

/// One setting, named as on the command line, valued in the paper's practical unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Setting {
    /// Loom speed, rev/min (the paper's Fig. 5).
    Speed,
    /// Strap-loop play s'₀, mm (Fig. 6).
    Play,
    /// Strap-loop height k, cm (Fig. 10).
    Strap,
    /// Shuttle weight Q, g (Fig. 7).
    Shuttle,
    /// Checking force F₀, kgf (Fig. 8).
    Checking,
}

impl Setting {
    /// All settings, in the paper's order of figures.
    pub const ALL: [Setting; 5] = [Setting::Speed, Setting::Play, Setting::Shuttle, Setting::Checking, Setting::Strap];

    /// Parses `speed`, `play`, `strap`, `shuttle`, `checking` (also with their unit suffix, e.g. `play-mm`).
    pub fn parse(name: &str) -> Result<Self> {
        Ok(match name.trim().to_ascii_lowercase().as_str() {
            "speed" | "speed-rpm" | "speed_rpm" => Setting::Speed,
            "play" | "play-mm" | "play_mm" => Setting::Play,
            "strap" | "strap-cm" | "strap_cm" => Setting::Strap,
            "shuttle" | "shuttle-g" | "shuttle_g" => Setting::Shuttle,
            "checking" | "checking-kgf" | "checking_kgf" => Setting::Checking,
            _ => return Err(PickError::UnknownSetting { name: name.into() }),
        })
    }

    /// The setting's name.
    pub fn name(&self) -> &'static str {
        match self {
            Setting::Speed => "speed",
            Setting::Play => "play",
            Setting::Strap => "strap",
            Setting::Shuttle => "shuttle",
            Setting::Checking => "checking",
        }
    }

    /// A human description, e.g. `strap-loop position k`.
    pub fn description(&self) -> &'static str {
        match self {
            Setting::Speed => "loom speed",
            Setting::Play => "strap-loop play",
            Setting::Strap => "strap-loop position k",
            Setting::Shuttle => "shuttle weight",
            Setting::Checking => "checking force",
        }
    }

    /// The setting's descriptor ([`Settings::SPEED_RPM`], …): its key, unit and static range.
    pub fn field(&self) -> &'static Field {
        match self {
            Setting::Speed => &Settings::SPEED_RPM,
            Setting::Play => &Settings::PLAY_MM,
            Setting::Strap => &Settings::STRAP_CM,
            Setting::Shuttle => &Settings::SHUTTLE_G,
            Setting::Checking => &Settings::CHECKING_KGF,
        }
    }

    /// The allowed values on `mechanism`, in [`Setting::unit`]: the descriptor's range, with the
    /// play at most and the strap below the mechanism's stick length l.
    pub fn range(&self, mechanism: &Mechanism) -> Range {
        let l_m = mechanism.params().l_m;
        match self {
            Setting::Play => Range::closed(0.0, l_m / M_PER_MM, "mm"),
            Setting::Strap => Range::open(0.0, l_m / M_PER_CM, "cm (0 < k < l)"),
            _ => self.field().range,
        }
    }

    /// The practical unit of the setting's values.
    pub fn unit(&self) -> &'static str {
        self.field().unit()
    }

    /// Column name with unit, e.g. `play_mm`.
    pub fn key(&self) -> String {
        format!("{}_{}", self.name(), self.unit())
    }

    /// `settings` with this setting set to `value` (in [`Setting::unit`]).
    pub fn apply(&self, settings: Settings, value: f64) -> Settings {
        match self {
            Setting::Speed => settings.with_speed_rpm(value),
            Setting::Play => settings.with_play_mm(value),
            Setting::Strap => settings.with_strap_cm(value),
            Setting::Shuttle => settings.with_shuttle_g(value),
            Setting::Checking => settings.with_checking_kgf(value),
        }
    }

    /// `settings` with this setting set to `value` (in [`Setting::unit`]), checked first against
    /// [`Setting::range`] on `mechanism` as typed: a value converted to SI first could round into
    /// the range (`-5e-324` mm is `-0` m, `1000.0000000000001` kgf is 1000 kgf again).
    pub fn set(&self, settings: Settings, value: f64, mechanism: &Mechanism) -> Result<Settings> {
        self.range(mechanism).check(self.field().name, value)?;
        Ok(self.apply(settings, value))
    }

    /// The value of this setting in `settings`, in [`Setting::unit`].
    pub fn value(&self, settings: &Settings) -> f64 {
        match self {
            Setting::Speed => settings.speed_rpm,
            Setting::Play => settings.play_m / M_PER_MM,
            Setting::Strap => settings.strap_m / M_PER_CM,
            Setting::Shuttle => settings.shuttle_kg / KG_PER_G,
            Setting::Checking => settings.checking_n / N_PER_KGF,
        }
    }

    /// The paper's range for this setting (Figs. 5–8, 10), in [`Setting::unit`]: what its figures
    /// show (a plot's or a slider's span), not the allowed range ([`Setting::range`]).
    pub fn paper_range(&self) -> (f64, f64) {
        match self {
            Setting::Speed => (160.0, 240.0),
            Setting::Play => (0.0, 60.0),
            Setting::Strap => (13.0, 35.0),
            Setting::Shuttle => (380.0, 520.0),
            Setting::Checking => (0.0, 10.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_round_trip_through_their_practical_units() {
        let m = Mechanism::paper_default();
        let base = Settings::designed(&m);
        for s in Setting::ALL {
            assert_eq!(Setting::parse(s.name()).unwrap(), s);
            assert_eq!(Setting::parse(&s.key()).unwrap(), s);
            let (a, b) = s.paper_range();
            let v = 0.5 * (a + b);
            let applied = s.apply(base, v);
            assert!((s.value(&applied) - v).abs() < 1e-12 * v.abs().max(1.0));
            assert!(applied.validate(&m).is_ok());
        }
        assert!((Setting::Checking.value(&base) - 5.0).abs() < 1e-12, "the paper's F₀ is 5 kgf");
        assert!(Setting::parse("weight").is_err());
    }

    #[test]
    fn each_setting_is_its_descriptor() {
        let m = Mechanism::paper_default();
        for s in Setting::ALL {
            assert_eq!(s.key(), s.field().name);
            assert_eq!(s.unit(), s.field().unit());
            // The paper's spans lie inside the allowed ranges.
            let (a, b) = s.paper_range();
            assert!(s.range(&m).contains(a) && s.range(&m).contains(b), "{s:?}");
        }
        // The play and the strap reach the stick length (74 cm) and no further.
        assert!(Setting::Play.range(&m).contains(740.0) && !Setting::Play.range(&m).contains(740.001));
        assert!(!Setting::Strap.range(&m).contains(74.0));
        // The speed range is the shaft's.
        assert_eq!(Setting::Speed.range(&m), ShaftSpeed::RANGE);
    }

    /// A setting is checked as typed: converted to SI first, `-5e-324` mm of play became `-0` m
    /// and `1000.0000000000001` kgf became 1000 kgf again, and both were taken.
    #[test]
    fn a_setting_is_checked_in_the_unit_it_is_given_in() {
        let m = Mechanism::paper_default();
        let st = Settings::designed(&m);
        assert!(Setting::Play.set(st, -5e-324, &m).is_err());
        assert!(Setting::Checking.set(st, 1000.0_f64.next_up(), &m).is_err());
        assert!(Setting::Strap.set(st, 74.0, &m).is_err());
        let ok = Setting::Checking.set(st, 1000.0, &m).unwrap();
        assert_eq!(ok, Setting::Checking.apply(st, 1000.0));
        assert!(Setting::Play.set(st, 0.0, &m).is_ok());
    }

    #[test]
    fn out_of_range_settings_name_field_range_and_unit() {
        let m = Mechanism::paper_default();
        let e = Settings::designed(&m).with_strap_cm(74.0).validate(&m).unwrap_err().to_string();
        assert!(e.contains("strap_cm = 74") && e.contains("cm"), "{e}");
        let e = Settings::designed(&m).with_shuttle_g(-1.0).validate(&m).unwrap_err().to_string();
        assert!(e.contains("shuttle_g") && e.contains(" g"), "{e}");
    }
}
