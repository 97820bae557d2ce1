//! The output law φ6(φ2) of task 2: dwells and rises built from a law of the core.

use crate::Result;
use loomkin_laws::{Law, LawSpec};
use loomkin_units::{Field, Range};
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// An output law with `cycles` identical cycles per input revolution, each a dwell of `dwell_deg`
/// centred at `dwell_centre_deg + k·360°/cycles` that holds `φ6 = dwell_centre_deg + k·360°/cycles`,
/// then a rise of `360°/cycles` of the output over the remaining `360°/cycles − dwell_deg` of input,
/// shaped by the normalised law `rise`.
///
/// The default is the Stäubli-type law: two cycles, 40° dwells centred at φ2 = 90° and 270°, 180°
/// cycloidal rises over 140°. Because the output turns exactly once per input revolution, the cam
/// curves close.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OutputLawSpec {
    /// Cycles per input revolution, 1…6.
    pub cycles: u32,
    /// Dwell of the output per cycle (deg of input), 0 ≤ dwell < 360/cycles − 1.
    pub dwell_deg: f64,
    /// Input angle at the centre of the first dwell, also the output angle held there (deg).
    pub dwell_centre_deg: f64,
    /// Shape of each rise (any law of the core).
    pub rise: LawSpec,
}

impl Default for OutputLawSpec {
    fn default() -> Self {
        Self { cycles: 2, dwell_deg: 40.0, dwell_centre_deg: 90.0, rise: LawSpec::Cycloidal }
    }
}

/// Output angle and its derivatives with respect to the input angle.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct OutputState {
    /// φ6 (rad), continuous (it grows by 2π per input revolution).
    pub phi6: f64,
    /// dφ6/dφ2.
    pub d1: f64,
    /// d²φ6/dφ2² (1/rad).
    pub d2: f64,
    /// d³φ6/dφ2³ (1/rad²).
    pub d3: f64,
}

/// A built output law, ready to evaluate.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputLaw {
    spec: OutputLawSpec,
    law: Law,
    period: f64,
    dwell: f64,
    start: f64,
    centre: f64,
}

impl OutputLawSpec {
    /// The allowed output cycles per input revolution.
    pub const CYCLES_RANGE: Range = Range::closed(1.0, 6.0, "");

    /// `cycles`: dwell-and-rise cycles per input turn, 1 … 6 (a rise of 60° at six); 2 (a plain weave).
    pub const CYCLES: Field = Field::count(
        "cycles",
        Self::CYCLES_RANGE,
        "Cycles (a dwell and a rise of 360°/cycles) per input turn: 1 … 6; 2 when left out.",
    )
    .with_default(2.0);
    /// `dwell_deg`: the output's dwell per cycle, 0 ≤ dwell ≤ 360°/cycles − 1° (a rise of at least
    /// 1°); 40°.
    pub const DWELL_DEG: Field = Field::new(
        "dwell_deg",
        Range::closed(0.0, 359.0, "°"),
        "Dwell of the output per cycle, deg of input: 0 ≤ dwell ≤ 360°/cycles − 1 (the rise keeps a degree); \
         40° when left out.",
    )
    .with_default(40.0);
    /// `dwell_centre_deg`: the input angle at the first dwell's centre, ±360°; 90°.
    pub const DWELL_CENTRE_DEG: Field = Field::new(
        "dwell_centre_deg",
        Range::closed(-360.0, 360.0, "°"),
        "Input angle at the centre of the first dwell (the output angle held there): ±360°; 90° when left out.",
    )
    .with_default(90.0);
    /// The law of each rise when none is given: the cycloidal (continuous acceleration, the
    /// paper's choice).
    pub const DEFAULT_LAW: &'static str = "cycloidal";

    /// Checks the fields: cycles in 1…6, dwell in [0, 360/cycles − 1]°, centre in [−360, 360]°.
    pub fn validate(&self) -> Result<()> {
        Self::CYCLES.check(f64::from(self.cycles))?;
        // The descriptor's range first (one message for every cycle count), then the bound the
        // cycles put on it.
        Self::DWELL_DEG.check(self.dwell_deg)?;
        let max_dwell = 360.0 / f64::from(self.cycles) - 1.0;
        Self::DWELL_DEG.at_most(max_dwell).check(self.dwell_deg)?;
        Self::DWELL_CENTRE_DEG.check(self.dwell_centre_deg)?;
        self.rise.validate()?;
        Ok(())
    }

    /// Builds the law.
    pub fn build(&self) -> Result<OutputLaw> {
        self.validate()?;
        let law = self.rise.build()?;
        let period = TAU / f64::from(self.cycles);
        let dwell = self.dwell_deg.to_radians();
        let centre = self.dwell_centre_deg.to_radians();
        Ok(OutputLaw { spec: self.clone(), law, period, dwell, start: centre - dwell / 2.0, centre })
    }
}

impl OutputLaw {
    /// The specification.
    pub fn spec(&self) -> &OutputLawSpec {
        &self.spec
    }

    /// `φ6(φ2)` and its derivatives: with `P = 2π/cycles`, `w` the input angle since the start of the
    /// current dwell, `k` the cycle index and `x = (w − dwell)/(P − dwell)`,
    /// `φ6 = centre + kP + P·s(x)` (and `s = 0` inside the dwell), `dφ6/dφ2 = P·v(x)/(P − dwell)`, …
    pub fn eval(&self, phi2_rad: f64) -> OutputState {
        let u = phi2_rad - self.start;
        let k = crate::planar::floor(u / self.period);
        let w = u - k * self.period;
        let base = self.centre + k * self.period;
        if w < self.dwell || !w.is_finite() {
            return OutputState { phi6: base, ..OutputState::default() };
        }
        let rise = self.period - self.dwell;
        let kin = self.law.eval((w - self.dwell) / rise);
        let p = self.period;
        OutputState {
            phi6: base + p * kin.s,
            d1: p * kin.v / rise,
            d2: p * kin.a / (rise * rise),
            d3: p * kin.j / (rise * rise * rise),
        }
    }

    /// Largest `|φ6 − φ2|` (deg) over one revolution, refined between the points of a 0.25° grid,
    /// and the input angle (deg) where it occurs.
    pub fn max_lag_deg(&self) -> (f64, f64) {
        let xs = super::refine::check_grid(0.0);
        let lag = |x: f64| crate::planar::wrap_pi(self.eval(x).phi6 - x).abs();
        let vals: Vec<f64> = xs.iter().map(|&x| lag(x)).collect();
        let e = super::refine::refined_max(&xs, &vals, &lag);
        (e.value.to_degrees(), e.at_deg().rem_euclid(360.0))
    }
}

/// The largest dwell (deg) for which the output law keeps `max |φ6 − φ2|` below `max_lag_deg`, with
/// the other fields of `spec`; `None` if even a zero dwell exceeds it.
pub fn max_dwell_deg(spec: &OutputLawSpec, max_lag_deg: f64) -> Result<Option<f64>> {
    let lag_at =
        |d: f64| -> Result<f64> { Ok(OutputLawSpec { dwell_deg: d, ..spec.clone() }.build()?.max_lag_deg().0) };
    let hi_limit = 360.0 / f64::from(spec.cycles.max(1)) - 1.0;
    if lag_at(0.0)? >= max_lag_deg {
        return Ok(None);
    }
    if lag_at(hi_limit)? < max_lag_deg {
        return Ok(Some(hi_limit));
    }
    // To 1e-11 of the dwell (each step builds a law and finds its largest lag).
    let (lo, _) = loomkin_numeric::try_bisect_bracket_within(0.0, hi_limit, 1e-11, |mid| -> Result<bool> {
        Ok(lag_at(mid)? < max_lag_deg)
    })?;
    Ok(Some(lo))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_law_has_the_issue_s_shape() {
        let law = OutputLawSpec::default().build().unwrap();
        let d = |x: f64| x.to_radians();
        // Dwell 70°…110° at 90°, 90° at φ2 = 90°, rise to 270° by 250°, 450° at 430°.
        for phi2 in [70.0, 90.0, 109.9] {
            let s = law.eval(d(phi2));
            assert!((s.phi6 - d(90.0)).abs() < 1e-12 && s.d1 == 0.0);
        }
        assert!((law.eval(d(180.0)).phi6 - d(180.0)).abs() < 1e-12); // cycloidal mid-rise
        assert!((law.eval(d(250.0)).phi6 - d(270.0)).abs() < 1e-12);
        assert!((law.eval(d(430.0)).phi6 - d(450.0)).abs() < 1e-12);
        // Peak rate of a cycloidal rise: 2 × 180/140.
        assert!((law.eval(d(180.0)).d1 - 2.0 * 180.0 / 140.0).abs() < 1e-12);
        // One output turn per input turn.
        assert!((law.eval(d(400.0)).phi6 - law.eval(d(40.0)).phi6 - d(360.0)).abs() < 1e-12);
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let law = OutputLawSpec { rise: LawSpec::Poly345, ..OutputLawSpec::default() }.build().unwrap();
        let h = 1e-5;
        for phi2 in [0.3, 1.0, 2.5, 3.3, 4.0, 5.9] {
            let s = law.eval(phi2);
            let (p, m) = (law.eval(phi2 + h), law.eval(phi2 - h));
            assert!(((p.phi6 - m.phi6) / (2.0 * h) - s.d1).abs() < 1e-7);
            assert!(((p.d1 - m.d1) / (2.0 * h) - s.d2).abs() < 1e-6);
            assert!(((p.d2 - m.d2) / (2.0 * h) - s.d3).abs() < 1e-4);
        }
    }

    #[test]
    fn dwell_limit_is_found_by_bisection() {
        let spec = OutputLawSpec::default();
        let dmax = max_dwell_deg(&spec, 52.7).unwrap().unwrap();
        assert!(dmax > 40.0 && dmax < 179.0, "{dmax}");
        let at = OutputLawSpec { dwell_deg: dmax, ..spec.clone() }.build().unwrap().max_lag_deg().0;
        assert!((at - 52.7).abs() < 0.05, "{at}");
        assert!(OutputLawSpec { dwell_deg: 200.0, ..spec }.validate().is_err());
    }
}
