//! The loom's requirement: the window the weft carrier needs, and the threshold that the shed's
//! height reserve allows.

use crate::Result;
use loomkin_units::{Field, Range, ShaftSpeed};
use serde::Serialize;

/// Loom data that fix the weft-insertion window a law must give.
///
/// **Window.** The carrier (projectile, rapier head, shuttle) of length `l` crosses the warp of
/// the cloth width `L_т` at the mean speed `v_п`; the shed must be open from the moment its nose
/// enters the warp until its tail leaves it, a path of `L_т + l` and a time `(L_т + l)/v_п`. The
/// main shaft turns at `6n` degrees per second (`n` in rpm), so the flight takes
/// `φ_flight = 6n·(L_т + l)/v_п` degrees. The crossing point (заступ) — and the window with it —
/// may be set anywhere in a range `D_заст` of main-shaft angle while the carrier's timing stays
/// fixed, so the window must cover the flight for every setting:
///
/// `φ_req = 6·n·(L_т + l)/v_п + D_заст`   (degrees).
///
/// The reed width `L_з` (the loom's working width) bounds the cloth, `L_т ≤ L_з`. Where the cloth
/// sits in the reed does not change the time spent in the warp at a mean speed; a loom set up for
/// any cloth up to its full width must meet `L_т = L_з`, which is the default.
///
/// **Threshold.** The shed is `ΔA_S` (a fraction, the paper's 5…7 %) higher than necessary. If the
/// opening at the carrier is taken proportional to the frame's displacement from its other
/// extreme — the paper's own measure of the conditional dwell — the frame may fall back to
/// `T = 1/(1 + ΔA_S)` of its stroke before the carrier is touched. With `ΔA_S = 5 %` that is
/// `T = 0.952`, the threshold that reproduces Table 3. If instead both warp sheets move
/// symmetrically and only the half reserve of each sheet counts, `T = 1 − ΔA_S/(2(1 + ΔA_S))`
/// ([`LoomRequirement::threshold_both_sheets`]), a stricter value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LoomRequirement {
    /// Mean carrier speed `v_п`, m/s (0 < v ≤ 200).
    pub carrier_speed_m_s: f64,
    /// Reed (working) width `L_з`, m (0 < L ≤ 20).
    pub reed_width_m: f64,
    /// Cloth width in the reed `L_т`, m (0 < L_т ≤ L_з).
    pub cloth_width_m: f64,
    /// Carrier length `l`, m (0 ≤ l ≤ 2).
    pub carrier_length_m: f64,
    /// Range of the crossing-point setting `D_заст`, deg (0 ≤ D < 360).
    pub crossing_range_deg: f64,
    /// Shed-height excess `ΔA_S`, fraction (e.g. 0.05 for 5 %).
    pub shed_excess: f64,
    /// Main-shaft speed `n`, rpm (0 < n ≤ 5000).
    pub speed_rpm: f64,
}

impl LoomRequirement {
    /// `carrier_speed_m_s`: v_п, 0 < v ≤ 200 m/s (above any projectile).
    pub const CARRIER_SPEED_M_S: Field = Field::new(
        "carrier_speed_m_s",
        Range::open_closed(0.0, 200.0, "m/s"),
        "Mean speed of the weft carrier: 0 < v ≤ 200 m/s (above any projectile or air jet).",
    );
    /// `reed_width_m`: L_з, 0 < L ≤ 20 m.
    pub const REED_WIDTH_M: Field = Field::new(
        "reed_width_m",
        Range::open_closed(0.0, 20.0, "m"),
        "Reed (working) width of the loom: 0 < L ≤ 20 m.",
    );
    /// `cloth_width_m`: L_т, 0 < L_т ≤ L_з; left out, the reed width.
    pub const CLOTH_WIDTH_M: Field = Field::new(
        "cloth_width_m",
        Range::above(0.0, "m"),
        "Cloth width in the reed: 0 < L_т ≤ the reed width; left out, the reed width (a loom set up for \
         any cloth).",
    );
    /// `carrier_length_m`: l, 0 … 2 m; 0.
    pub const CARRIER_LENGTH_M: Field =
        Field::new("carrier_length_m", Range::closed(0.0, 2.0, "m"), "Carrier length: 0 … 2 m; 0 when left out.")
            .with_default(0.0);
    /// `crossing_range_deg`: D_заст, 0 … 359°; 0.
    pub const CROSSING_RANGE_DEG: Field = Field::new(
        "crossing_range_deg",
        Range::closed(0.0, 359.0, "deg"),
        "Range of the crossing-point (заступ) setting: 0 … 359° (the window must stay below a turn); 0 \
         when left out.",
    )
    .with_default(0.0);
    /// The ends of `shed_excess`: T = 1/(1 + ΔA_S) must lie in the threshold range
    /// ([`crate::THRESHOLD_RANGE`], 0.75 … 0.99), so ΔA_S in 1/0.99 − 1 = 0.010101… … 1/0.75 − 1 = 0.3333…;
    /// taken inward to three significant digits, numbers a user types back as they are printed
    /// (T = 0.98990 … 0.75019; the next three-digit numbers out, 0.0101 and 0.334, give T outside
    /// the range: tested).
    pub const SHED_EXCESS_RANGE: (f64, f64) = (0.0102, 0.333);
    /// `shed_excess`: ΔA_S, a fraction; T = 1/(1 + ΔA_S) must lie in the threshold range
    /// ([`Self::SHED_EXCESS_RANGE`], 0.0102 … 0.333); 0.05, the paper's 5 %.
    pub const SHED_EXCESS: Field = Field::new(
        "shed_excess",
        Range::closed(Self::SHED_EXCESS_RANGE.0, Self::SHED_EXCESS_RANGE.1, "(fraction)"),
        "Shed-height excess over the necessary opening, a fraction; sets T = 1/(1 + excess), which must \
         lie in 0.75 … 0.99 (0.0102 … 0.333: that range's ends to three digits, inward); 0.05 (the \
         paper's 5 %) when left out.",
    )
    .with_default(0.05);

    /// The requirement of a front end's loom data, the options left out taking their defaults
    /// (the cloth the reed's width, no carrier length, no crossing range, 5 % excess).
    pub fn from_inputs(
        carrier_speed_m_s: f64,
        reed_width_m: f64,
        cloth_width_m: Option<f64>,
        carrier_length_m: Option<f64>,
        crossing_range_deg: Option<f64>,
        shed_excess: Option<f64>,
        speed_rpm: f64,
    ) -> Self {
        Self {
            carrier_speed_m_s,
            reed_width_m,
            cloth_width_m: cloth_width_m.unwrap_or(reed_width_m),
            carrier_length_m: carrier_length_m.unwrap_or(Self::CARRIER_LENGTH_M.default_value()),
            crossing_range_deg: crossing_range_deg.unwrap_or(Self::CROSSING_RANGE_DEG.default_value()),
            shed_excess: shed_excess.unwrap_or(Self::SHED_EXCESS.default_value()),
            speed_rpm,
        }
    }

    /// Checks every field's range.
    pub fn validate(&self) -> Result<()> {
        Self::CARRIER_SPEED_M_S.check(self.carrier_speed_m_s)?;
        Self::REED_WIDTH_M.check(self.reed_width_m)?;
        Range::open_closed(0.0, self.reed_width_m, "m").check(Self::CLOTH_WIDTH_M.name, self.cloth_width_m)?;
        Self::CARRIER_LENGTH_M.check(self.carrier_length_m)?;
        Self::CROSSING_RANGE_DEG.check(self.crossing_range_deg)?;
        ShaftSpeed::from_rpm(self.speed_rpm)?;
        // T = 1/(1 + e) must lie in the threshold range.
        Self::SHED_EXCESS.check(self.shed_excess)?;
        Ok(())
    }

    /// Flight angle `φ_flight = 6n·(L_т + l)/v_п`, deg.
    pub fn flight_deg(&self) -> f64 {
        6.0 * self.speed_rpm * (self.cloth_width_m + self.carrier_length_m) / self.carrier_speed_m_s
    }

    /// Required window `φ_req = φ_flight + D_заст`, deg (validated; must be below 360°).
    pub fn required_window_deg(&self) -> Result<f64> {
        self.validate()?;
        let w = self.flight_deg() + self.crossing_range_deg;
        Ok(Range::open_closed(0.0, 359.0, "deg (the carrier cannot cross in time)").check("required_window_deg", w)?)
    }

    /// Threshold `T = 1/(1 + ΔA_S)` (opening proportional to the frame's displacement).
    pub fn threshold(&self) -> f64 {
        1.0 / (1.0 + self.shed_excess)
    }

    /// Threshold `T = 1 − ΔA_S/(2(1 + ΔA_S))` (two sheets moving symmetrically).
    pub fn threshold_both_sheets(&self) -> f64 {
        1.0 - self.shed_excess / (2.0 * (1.0 + self.shed_excess))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stb() -> LoomRequirement {
        LoomRequirement {
            carrier_speed_m_s: 24.0,
            reed_width_m: 1.8,
            cloth_width_m: 1.8,
            carrier_length_m: 0.09,
            crossing_range_deg: 15.0,
            shed_excess: 0.05,
            speed_rpm: 250.0,
        }
    }

    #[test]
    fn window_by_an_independent_route() {
        let r = stb();
        // Time in the warp, then degrees turned by the shaft in that time.
        let t_s = (1.8 + 0.09) / 24.0;
        let deg_per_s = 250.0 / 60.0 * 360.0;
        assert!((r.required_window_deg().unwrap() - (t_s * deg_per_s + 15.0)).abs() < 1e-12);
        assert!((r.threshold() - 0.952_380_952_380_952_4).abs() < 1e-15);
        assert!(r.threshold_both_sheets() > r.threshold());
    }

    #[test]
    fn rejects_impossible_looms() {
        let mut r = stb();
        r.cloth_width_m = 2.0;
        assert!(r.required_window_deg().is_err());
        let mut r = stb();
        r.carrier_speed_m_s = 5.0; // 6·250·1.89/5 = 567° > 360°
        assert!(r.required_window_deg().is_err());
        let mut r = stb();
        r.shed_excess = 0.5;
        assert!(r.validate().is_err());
    }

    /// The excess's ends give thresholds inside the threshold range, and the next numbers of three
    /// significant digits beyond them thresholds outside it: the tightest such bounds.
    #[test]
    fn the_excess_range_is_the_threshold_range_to_three_digits() {
        let (lo, hi) = LoomRequirement::SHED_EXCESS_RANGE;
        let t = |e: f64| LoomRequirement { shed_excess: e, ..stb() }.threshold();
        let inside = |e: f64| crate::Conditions::THRESHOLD.contains(t(e));
        assert!(inside(lo) && inside(hi), "{} {}", t(lo), t(hi));
        assert!(!inside(0.0101) && !inside(0.334), "{} {}", t(0.0101), t(0.334));
        for e in [lo, hi] {
            let mut r = stb();
            r.shed_excess = e;
            r.validate().unwrap();
            assert_eq!(loomkin_units::compact(e).parse::<f64>(), Ok(e));
        }
        let mut r = stb();
        r.shed_excess = 0.0101;
        let e = r.validate().unwrap_err().to_string();
        assert_eq!(e, "shed_excess = 0.0101 is out of range: allowed 0.0102 ≤ shed_excess ≤ 0.333 (fraction)");
    }
}
