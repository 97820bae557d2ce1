//! Monte-Carlo tolerance study of the loom settings: speed, strap play and position, shuttle and
//! checking force drawn from stated distributions, the end-of-pick results as distributions.
//!
//! The study is a TOML file (see `examples/pick-montecarlo.toml`):
//!
//! ```toml
//! draws = 1000
//! seed = 1
//! [settings]                     # any of speed_rpm, play_mm, strap_cm, shuttle_g, checking_kgf
//! speed_rpm = { dist = "normal", mean = 200, sd = 3 }
//! play_mm = { dist = "uniform", min = 0, max = 5 }
//! shuttle_g = 420                # a plain number is fixed
//! [limits]                       # any of the results, min and/or max
//! velocity_m_s = { min = 16.5, max = 19 }
//! ```
//!
//! Settings left out keep the mechanism's designed value. Each setting has its own variable of
//! the draw stream ([`loomkin_study::uniform`]`(seed, draw, variable)`, variable = its place in
//! [`INPUTS`]), so draw `i` is the same whether it is computed alone, by a shard or by any thread,
//! and giving one setting a distribution does not change the draws of another. A draw is run by
//! the route asked for ([`Method::Closed`] by default, which answers by numerical integration only
//! where the closed form does not apply).

use crate::{Mechanism, Method, PickEnd, PickError, Result, Setting, Settings, StartRule, simulate};
use loomkin_study::draws::DrawSource;
use loomkin_study::summary::DrawSummary;

/// The study's command, named in summaries and messages.
const COMMAND: &str = "pick montecarlo";
use loomkin_study::{DistSpec, Distribution, DrawRow, Drawn, Limit, Named, Progress, tally, uniform};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The settings drawn, in the order of their stream variables.
pub const INPUTS: [Setting; 5] = [Setting::Speed, Setting::Play, Setting::Strap, Setting::Shuttle, Setting::Checking];

/// The results of a draw, as named in files, tables and limits.
pub const RESULTS: [&str; 6] =
    ["velocity_m_s", "distance_m", "t_end_s", "accel_end_m_s2", "accel_peak_m_s2", "velocity_vs_required_pct"];

/// Most draws a study may ask for.
pub const MAX_DRAWS: u64 = 100_000_000;

/// Default number of histogram bins.
pub const DEFAULT_BINS: usize = loomkin_study::DEFAULT_BINS;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct StudyFile {
    draws: u64,
    seed: u64,
    #[serde(default)]
    method: Option<Method>,
    #[serde(default)]
    start: Option<StartRule>,
    #[serde(default)]
    bins: Option<usize>,
    #[serde(default)]
    percentiles: Option<Vec<f64>>,
    #[serde(default)]
    settings: SettingsFile,
    #[serde(default)]
    limits: LimitsFile,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct SettingsFile {
    speed_rpm: Option<DistSpec>,
    play_mm: Option<DistSpec>,
    strap_cm: Option<DistSpec>,
    shuttle_g: Option<DistSpec>,
    checking_kgf: Option<DistSpec>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct LimitsFile {
    velocity_m_s: Option<Limit>,
    distance_m: Option<Limit>,
    t_end_s: Option<Limit>,
    accel_end_m_s2: Option<Limit>,
    accel_peak_m_s2: Option<Limit>,
    velocity_vs_required_pct: Option<Limit>,
}

/// A Monte-Carlo study of the loom settings, checked.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MonteCarlo {
    /// Number of draws.
    pub draws: u64,
    /// Seed of the draw stream.
    pub seed: u64,
    /// Route of each draw.
    pub method: Method,
    /// Start rule of each draw.
    pub start: StartRule,
    /// Histogram bins per result.
    pub bins: usize,
    /// Percentiles reported (%).
    pub percentiles: Vec<f64>,
    /// Distribution of each setting of [`INPUTS`] (in its [`Setting::unit`]); `None` keeps the
    /// designed value.
    pub inputs: [Option<Distribution>; 5],
    /// Limit of each result of [`RESULTS`].
    pub limits: [Option<Limit>; 6],
}

fn study_err(e: loomkin_study::StudyError) -> PickError {
    use loomkin_units::FieldError;
    PickError::Study { field: e.field().unwrap_or("study").to_string(), reason: e.to_string() }
}

/// Seconds per draw by the closed form: 9.5 µs measured on the reference machine (2 cores, load
/// average 3) as the slope of `loomkin pick montecarlo examples/pick-montecarlo.toml` with
/// `draws = 100000` on one thread (`RAYON_NUM_THREADS=1`, `/usr/bin/time`: 0.93–0.97 s; one draw
/// alone: 0.00 s), taken into estimates by [`loomkin_units::Cost::cpu_items`] as every per-item
/// cost. 10⁶ draws are estimated at 19 s, inside the budget; larger studies shard (`--shard I/N`).
pub const DRAW_S_CLOSED: f64 = 9.5e-6;
/// See [`DRAW_S_CLOSED`]: the draw integrated numerically, 34 µs of CPU per draw measured the same
/// way (`method = "ode"`, `draws = 10000`: 0.34 s user).
pub const DRAW_S_ODE: f64 = 34e-6;

impl MonteCarlo {
    /// What running the draws `items` costs, estimated before they run: each draw's time
    /// ([`DRAW_S_CLOSED`], [`DRAW_S_ODE`], by [`loomkin_units::Cost::cpu_items`]) and the draws held until
    /// the report (a [`Draw`] each, and the text of its CSV or JSON row).
    pub fn cost(&self, items: std::ops::Range<u64>) -> loomkin_units::Cost {
        let n = items.end.min(self.draws).saturating_sub(items.start) as f64;
        let per = if self.method == Method::Ode { DRAW_S_ODE } else { DRAW_S_CLOSED };
        loomkin_units::Cost::cpu_items(n, std::mem::size_of::<Draw>() as f64 + 300.0, per)
    }

    /// Reads and checks a study file.
    pub fn from_toml(text: &str) -> Result<Self> {
        let f: StudyFile = toml::from_str(text)
            .map_err(|e| PickError::Study { field: "study".into(), reason: loomkin_units::toml_reason(text, &e) })?;
        let (bins, percentiles) =
            loomkin_study::check_plan(f.draws, MAX_DRAWS, f.bins, f.percentiles).map_err(study_err)?;
        let s = &f.settings;
        let specs = [&s.speed_rpm, &s.play_mm, &s.strap_cm, &s.shuttle_g, &s.checking_kgf];
        let mut inputs = [None; 5];
        for (k, spec) in specs.into_iter().enumerate() {
            if let Some(spec) = spec {
                inputs[k] = Some(spec.resolve(&format!("settings.{}", INPUTS[k].key())).map_err(study_err)?);
            }
        }
        let l = &f.limits;
        let limits =
            [l.velocity_m_s, l.distance_m, l.t_end_s, l.accel_end_m_s2, l.accel_peak_m_s2, l.velocity_vs_required_pct];
        for (k, lim) in limits.iter().enumerate() {
            if let Some(lim) = lim {
                lim.check(&format!("limits.{}", RESULTS[k])).map_err(study_err)?;
            }
        }
        Ok(Self {
            draws: f.draws,
            seed: f.seed,
            method: f.method.unwrap_or_default(),
            start: f.start.unwrap_or_default(),
            bins,
            percentiles,
            inputs,
            limits,
        })
    }

    /// The settings of draw `index`: the designed ones of `mechanism`, each drawn setting replaced.
    pub fn settings(&self, mechanism: &Mechanism, index: u64) -> Settings {
        let mut st = Settings::designed(mechanism).with_start(self.start);
        for (k, d) in self.inputs.iter().enumerate() {
            if let Some(d) = d {
                st = INPUTS[k].apply(st, d.sample(uniform(self.seed, index, k)));
            }
        }
        st
    }

    /// Runs the draws `items` (all: `0..draws`; a shard: [`loomkin_units::Shard::items`]) in
    /// parallel; the rows come back in draw order and each is independent of the others, of the
    /// shard and of the number of threads. A draw the model refuses (a play beyond the cam's reach,
    /// a speed out of range) is a row with `result: Err(message)`.
    pub fn run(&self, mechanism: &Mechanism, items: std::ops::Range<u64>, progress: Progress) -> Vec<Draw> {
        loomkin_study::run_draws(self.draws, items, progress, |i| self.draw(mechanism, i))
    }

    /// Draw `index` alone.
    pub fn draw(&self, mechanism: &Mechanism, index: u64) -> Draw {
        let st = self.settings(mechanism, index);
        let inputs = INPUTS.map(|s| s.value(&st));
        let result = simulate(mechanism, &st, self.method).map(|o| DrawResult {
            values: [
                o.velocity_m_s,
                o.distance_m,
                o.t_end_s,
                o.accel_end_m_s2,
                o.accel_peak_m_s2,
                o.velocity_vs_required_pct,
            ],
            ode: o.method == Method::Ode,
            separation: o.end == PickEnd::Separation,
        });
        Draw { index, inputs, result: result.map_err(|e| e.to_string()) }
    }

    /// The distributions of the results over `draws` (every draw of the study, in order: the rows
    /// of one run, or the shards' rows concatenated). Sums run in draw order, so the report does
    /// not depend on how the draws were computed.
    pub fn report(&self, draws: &[Draw]) -> Report {
        let (inputs, results) = self.reported();
        let t = tally(draws, &self.percentiles, self.bins, &inputs, &results);
        let ok = || draws.iter().filter_map(|d| d.result.as_ref().ok());
        let flags = [ok().filter(|r| r.ode).count() as u64, ok().filter(|r| r.separation).count() as u64];
        self.report_of(t, &flags)
    }

    /// [`MonteCarlo::report`] of the per-draw table in `source` (the parts of a sharded run, or
    /// their concatenation), streamed: the same report, with memory independent of the number of
    /// draws. The parts' manifests must name this study's facts ([`MonteCarlo::facts`]).
    pub fn report_from(
        &self,
        mechanism: &Mechanism,
        source: &DrawSource,
    ) -> std::result::Result<Report, loomkin_study::parts::PartError> {
        source.check_facts(&self.facts(mechanism))?;
        let (inputs, results) = self.reported();
        let (t, flags) = loomkin_study::draws::tally_stream::<Draw>(
            source,
            COMMAND,
            self.draws,
            &self.percentiles,
            self.bins,
            &inputs,
            &results,
        )?;
        Ok(self.report_of(t, &flags))
    }

    /// The mergeable summary of `draws`, the draws `items` of this study (one shard's, see
    /// [`loomkin_study::summary`]): what its report needs, without the rows.
    pub fn summary(&self, mechanism: &Mechanism, items: std::ops::Range<u64>, draws: &[Draw]) -> DrawSummary {
        let (inputs, results) = self.reported();
        DrawSummary::of(COMMAND, self.facts(mechanism), items, draws, &inputs, &results)
    }

    /// The report of a run from its shards' summaries ([`MonteCarlo::summary`], any order): the
    /// counts, failing counts and share, extremes bit for bit, mean and sd to rounding, no
    /// percentiles or histograms (they need the draws: [`MonteCarlo::report_from`]). Summaries
    /// of another study, or missing or repeating draws, are refused.
    pub fn report_from_summaries(
        &self,
        mechanism: &Mechanism,
        parts: &[DrawSummary],
    ) -> std::result::Result<Report, loomkin_study::parts::PartError> {
        let s = DrawSummary::merge(parts, COMMAND, &self.facts(mechanism), self.draws, &self.reported())?;
        Ok(self.report_of(s.tally(), &s.flags))
    }

    /// What makes the draws of this study what they are, for a part's manifest: the seed, the
    /// number of draws, the drawn settings with the route and start rule, and the model. A reduce
    /// refuses draws whose manifest names others; the limits, bins and percentiles only shape the
    /// report and may change.
    pub fn facts(&self, mechanism: &Mechanism) -> BTreeMap<String, String> {
        use loomkin_study::parts::{fact, fingerprint};
        BTreeMap::from([
            ("seed".to_string(), self.seed.to_string()),
            ("draws".to_string(), self.draws.to_string()),
            ("inputs".to_string(), fact(&(&self.inputs, self.method, self.start))),
            ("model".to_string(), fingerprint(mechanism)),
        ])
    }

    /// The inputs (drawn with a spread or not) and the results with their limits, as reported.
    fn reported(&self) -> loomkin_study::Reported {
        let inputs =
            INPUTS.iter().zip(&self.inputs).map(|(s, d)| (s.key(), d.is_some_and(|d| !d.is_fixed()))).collect();
        (inputs, RESULTS.iter().copied().zip(self.limits).collect())
    }

    fn report_of(&self, t: loomkin_study::Tally, flags: &[u64]) -> Report {
        Report {
            draws: t.draws,
            seed: self.seed,
            method: self.method,
            not_simulated: t.refused,
            ode_draws: flags[0],
            separation_draws: flags[1],
            failing: t.failing,
            fail_share: t.fail_share,
            inputs: t.inputs,
            results: t.results,
        }
    }
}

/// The results of one draw that the model answered.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DrawResult {
    /// The values of [`RESULTS`], in that order.
    pub values: [f64; 6],
    /// Answered by numerical integration (the closed form did not apply).
    pub ode: bool,
    /// The shuttle left the picker before the end of the cam's rise.
    pub separation: bool,
}

/// One draw: its index, its settings (in the units of [`INPUTS`]) and its results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Draw {
    /// Index of the draw in the study, from 0.
    pub index: u64,
    /// The settings drawn, in [`Setting::unit`].
    pub inputs: [f64; 5],
    /// The results, or why the model refused the draw.
    pub result: std::result::Result<DrawResult, String>,
}

/// The distribution of one drawn setting (its name is the setting's key, e.g. `speed_rpm`).
pub type Input = Named;

/// The distribution of one result (its name is one of [`RESULTS`]).
pub type Quantity = Named;

impl Drawn for Draw {
    fn inputs(&self) -> &[f64] {
        &self.inputs
    }
    fn results(&self) -> Option<&[f64]> {
        self.result.as_ref().ok().map(|r| &r.values[..])
    }
}

impl DrawRow for Draw {
    const ANSWERED: &'static str = "simulated";
    const FLAGS: &'static [&'static str] = &["ode", "separation"];
    fn input_names() -> Vec<String> {
        INPUTS.iter().map(Setting::key).collect()
    }
    fn result_names() -> Vec<String> {
        RESULTS.iter().map(|s| s.to_string()).collect()
    }
    fn index(&self) -> u64 {
        self.index
    }
    fn flags(&self) -> Vec<bool> {
        self.result.as_ref().map_or(vec![false; 2], |r| vec![r.ode, r.separation])
    }
    fn error(&self) -> Option<&str> {
        self.result.as_ref().err().map(String::as_str)
    }
    fn from_parts(index: u64, inputs: &[f64], answered: Option<(&[f64], &[bool])>) -> Self {
        let result = match answered {
            Some((v, f)) => Ok(DrawResult {
                values: std::array::from_fn(|k| v[k]),
                ode: f.first() == Some(&true),
                separation: f.get(1) == Some(&true),
            }),
            None => Err("not simulated".to_string()),
        };
        Draw { index, inputs: std::array::from_fn(|k| inputs[k]), result }
    }
}

/// The outcome of a study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Draws.
    pub draws: u64,
    /// Seed.
    pub seed: u64,
    /// Route asked for.
    pub method: Method,
    /// Draws the model refused (counted as failing).
    pub not_simulated: u64,
    /// Draws answered by numerical integration.
    pub ode_draws: u64,
    /// Draws where the shuttle left the picker before the end of the cam's rise.
    pub separation_draws: u64,
    /// Draws failing a limit or refused.
    pub failing: u64,
    /// `failing / draws`.
    pub fail_share: f64,
    /// The drawn settings' distributions (those with a spread).
    pub inputs: Vec<Input>,
    /// The results' distributions.
    pub results: Vec<Quantity>,
}

#[cfg(test)]
mod tests {
    use super::*;

    const PAPER_SETTINGS: &str = "draws = 3\nseed = 5\n[settings]\nspeed_rpm = { dist = \"normal\", mean = 200, sd = 0 }\n\
        play_mm = { dist = \"uniform\", min = 15.5, max = 15.5 }\nshuttle_g = { dist = \"fixed\", value = 440 }\n";

    /// No spread: every draw is the deterministic simulation of the same settings, bit for bit.
    #[test]
    fn zero_spread_is_the_deterministic_design() {
        let m = Mechanism::paper_default();
        let mc = MonteCarlo::from_toml(PAPER_SETTINGS).unwrap();
        let st = Settings::designed(&m).with_speed_rpm(200.0).with_play_mm(15.5).with_shuttle_g(440.0);
        let o = simulate(&m, &st, Method::Closed).unwrap();
        let draws = mc.run(&m, 0..3, Progress::Hidden);
        assert_eq!(draws.len(), 3);
        for d in &draws {
            let r = d.result.as_ref().unwrap();
            assert_eq!(r.values[0], o.velocity_m_s);
            assert_eq!(r.values[1], o.distance_m);
            assert_eq!(r.values[4], o.accel_peak_m_s2);
        }
        let rep = mc.report(&draws);
        let v = &rep.results[0].summary;
        assert_eq!((v.mean, v.sd, v.min, v.max), (o.velocity_m_s, 0.0, o.velocity_m_s, o.velocity_m_s));
        assert!(v.percentiles.iter().all(|p| p.value == o.velocity_m_s));
        assert!(rep.inputs.is_empty(), "no input has a spread");
    }

    /// A study that leaves every setting out runs the designed setting — the shuttle the mechanism
    /// is designed with (419.725 g for the paper's, not the 420 g the paper rounds it to) — so its
    /// statistics are `pick simulate`'s without settings, bit for bit.
    #[test]
    fn settings_left_out_are_the_designed_ones() {
        let m = Mechanism::paper_default();
        let mc = MonteCarlo::from_toml("draws = 2\nseed = 9\n").unwrap();
        let st = mc.settings(&m, 1);
        assert_eq!(st, Settings::designed(&m));
        assert_eq!(Setting::Shuttle.value(&st), Setting::Shuttle.value(&Settings::designed(&m)));
        assert!((Setting::Shuttle.value(&st) - 419.725).abs() < 5e-4, "{}", Setting::Shuttle.value(&st));
        let o = simulate(&m, &Settings::designed(&m), Method::Closed).unwrap();
        let rep = mc.report(&mc.run(&m, 0..2, Progress::Hidden));
        assert_eq!(rep.results[0].summary.mean, o.velocity_m_s);
        assert_eq!(rep.results[1].summary.max, o.distance_m);
    }

    /// Draws are the same computed alone, in a shard or all together; reports the same by thread count.
    #[test]
    fn draws_do_not_depend_on_shards_or_threads() {
        let m = Mechanism::paper_default();
        let text = "draws = 40\nseed = 11\n[settings]\nspeed_rpm = { dist = \"normal\", mean = 200, sd = 5 }\n\
            play_mm = { dist = \"uniform\", min = 0, max = 20 }\n[limits]\nvelocity_m_s = { max = 19 }\n";
        let mc = MonteCarlo::from_toml(text).unwrap();
        let all = mc.run(&m, 0..40, Progress::Hidden);
        let mut pieces = Vec::new();
        for i in 1..=7 {
            let r = loomkin_units::Shard { index: i, count: 7 }.items(40);
            pieces.extend(mc.run(&m, r.start as u64..r.end as u64, Progress::Hidden));
        }
        assert_eq!(all, pieces);
        assert_eq!(all[17], mc.draw(&m, 17));
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let serial = one.install(|| mc.report(&mc.run(&m, 0..40, Progress::Hidden)));
        assert_eq!(serial, mc.report(&all));
        assert!(serial.failing > 0 && serial.failing < 40, "the limit splits the draws: {}", serial.failing);
    }

    #[test]
    fn bad_studies_name_the_field() {
        let e = |t: &str| MonteCarlo::from_toml(t).unwrap_err().to_string();
        assert!(e("draws = 0\nseed = 1\n").contains("draws = 0 is out of range"));
        assert!(e("draws = 5\nseed = 1\n[settings]\nspeed = 3\n").contains("unknown field `speed`"));
        assert!(
            e("draws = 5\nseed = 1\n[settings]\nplay_mm = { dist = \"normal\", mean = 1, sd = -2 }\n")
                .contains("settings.play_mm: sd = -2")
        );
        assert!(e("draws = 5\nseed = 1\n[limits]\ndistance_m = { min = 2, max = 1 }\n").contains("limits.distance_m"));
        assert!(e("draws = 5\nseed = 1\npercentiles = [50, 101]\n").contains("percentiles"));
    }
}
