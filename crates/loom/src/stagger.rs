//! Heald staggering: crossing-angle offsets per frame (or per group) that lower the peak (or RMS)
//! shedding torque while every pick keeps the insertion window its carrier needs.
//!
//! A compass search on the offsets (steps 4°, 2°, 1°, 0.5°, 0.25°, each within
//! `±max_stagger_deg`): a move is taken when it lowers the objective (the largest |T| on a 2°
//! grid, or the RMS of that grid) and keeps the clearance to the carrier non-negative from entry
//! to exit in every pick (checked on a 2° grid with both ends). It starts from no stagger and from
//! the two-group baseline (odd frames 0°, even frames 7.5°) and keeps the better; the result is
//! then evaluated exactly (refined peak, quadrature RMS, refined clearance). When no start keeps
//! the window, the search first maximises the least clearance; if that stays negative, no stagger
//! in range gives the window, and the error says how short it falls.
//!
//! The optimum spends clearance, clear-shed window and top speed for its torque: each case
//! reports all three, and [`StaggerOptions::min_clearance_mm`] keeps a least clearance (the
//! window check above asks for that much instead of none). The objective and the clearance are
//! computed once per distinct turn of the repeat (see `crate::turns`): a 1,000-pick repeat of a
//! 48-pick draft costs what the draft does. Beyond 256 distinct turns (random picks) the window
//! checks are made from each frame's slope rows, kept across the search (`crate::turn_rows`).

use crate::turn_rows::{MAX_WHOLE_TURNS, SlopeRows};
use crate::turns::Turns;
use crate::{Drive, Loom, LoomError, Motion, Pattern, Result, TableCache, Timing};
use loomkin_units::{Field, Range, StopFlag};
use serde::Serialize;

/// What the stagger search minimises and what it keeps.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StaggerOptions {
    /// What to minimise.
    pub objective: Objective,
    /// The least clearance to the carrier every pick must keep from entry to exit, mm
    /// ([`StaggerOptions::MIN_CLEARANCE_MM`]).
    pub min_clearance_mm: f64,
}

impl StaggerOptions {
    /// `min_clearance_mm`: 0 … 1000 mm; 0 (the window just kept: the carrier may graze the warp)
    /// when left out.
    pub const MIN_CLEARANCE_MM: Field = Field::new(
        "min_clearance_mm",
        Range::closed(0.0, 1000.0, "mm"),
        "Least clearance to the carrier that the stagger must keep in every pick from entry to exit: \
         0 … 1000 mm; 0 (the window just kept, the carrier may graze the warp) when left out.",
    )
    .with_default(0.0);

    /// Minimise `objective` keeping the default least clearance.
    pub fn new(objective: Objective) -> Self {
        Self { objective, min_clearance_mm: Self::MIN_CLEARANCE_MM.default_value() }
    }

    /// Checks the least clearance against its range.
    pub fn validate(&self) -> Result<()> {
        Self::MIN_CLEARANCE_MM.check(self.min_clearance_mm)?;
        Ok(())
    }
}

/// What the stagger minimises.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Objective {
    /// The largest |torque| over the repeat.
    Peak,
    /// The RMS torque over the repeat.
    Rms,
}

/// One stagger and what it gives.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StaggerCase {
    /// What it is.
    pub label: String,
    /// Stagger of every frame, front first, deg.
    pub stagger_deg: Vec<f64>,
    /// Peak |torque| (refined), N·m.
    pub peak_torque_n_m: f64,
    /// RMS torque, N·m.
    pub rms_torque_n_m: f64,
    /// Least clearance to the carrier from entry to exit over every pick, mm.
    pub min_clearance_mm: f64,
    /// Whether every pick keeps its insertion window (clearance ≥ 0 throughout).
    pub window_kept: bool,
    /// The window common to every pick in which the shed clears the carrier, deg (0: none).
    pub window_deg: f64,
    /// The highest loom speed at which the carrier passes in that window, rpm.
    pub max_speed_rpm: f64,
}

/// The optimised stagger beside the two baselines.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StaggerResult {
    /// The objective.
    pub objective: Objective,
    /// The groups searched (0-based frames), or none when every frame has its own offset.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub groups: Option<Vec<Vec<usize>>>,
    /// No stagger.
    pub none: StaggerCase,
    /// Odd frames 0°, even frames 7.5°.
    pub two_groups: StaggerCase,
    /// The optimum found.
    pub best: StaggerCase,
    /// Peak torque reduction of the optimum against no stagger, %.
    pub peak_reduction_pct: f64,
    /// Peak torque reduction of the two-group baseline against no stagger, %.
    pub two_groups_peak_reduction_pct: f64,
    /// Objective evaluations made by the search.
    pub evaluations: usize,
    /// Window (clearance) checks made by the search.
    pub clearance_checks: usize,
    /// The least clearance the search kept, mm ([`StaggerOptions::min_clearance_mm`]).
    pub min_clearance_kept_mm: f64,
}

/// Grid of the search, deg.
pub(crate) const SEARCH_STEP_DEG: f64 = 2.0;
/// Compass steps, deg.
pub(crate) const STEPS: [f64; 5] = [4.0, 2.0, 1.0, 0.5, 0.25];

struct Search<'a> {
    loom: &'a Loom,
    pattern: &'a Pattern,
    objective: Objective,
    /// The least clearance to keep, m.
    need_m: f64,
    groups: Option<Vec<Vec<usize>>>,
    evaluations: usize,
    clearance_checks: usize,
    cache: TableCache,
    /// The picks grouped by their turn's lifts, for every stagger within range.
    turns: Turns,
    /// Whether the repeat has so many distinct turns that the window checks are made from rows
    /// (`crate::turn_rows`), and the rows made so far.
    rows: Option<SlopeRows>,
    /// Called with (compass stages done, stages in all).
    progress: &'a dyn Fn(usize, usize),
    stop: &'a StopFlag,
    stages: (usize, usize),
}

impl Search<'_> {
    fn per_frame(&self, x: &[f64]) -> Vec<f64> {
        match &self.groups {
            None => x.to_vec(),
            Some(gs) => {
                let mut out = vec![0.0; self.loom.frame_count()];
                for (g, v) in gs.iter().zip(x) {
                    for &i in g {
                        out[i] = *v;
                    }
                }
                out
            }
        }
    }

    fn setup(&self, x: &[f64]) -> Result<(Loom, Motion)> {
        let loom = self.loom.with_stagger(&self.per_frame(x))?;
        let motion = Motion::new(&loom, self.pattern)?;
        Ok((loom, motion))
    }

    fn objective(&mut self, x: &[f64]) -> Result<f64> {
        self.stop.check()?;
        self.evaluations += 1;
        let (loom, motion) = self.setup(x)?;
        let drive = Drive::new(&loom, &motion, self.pattern);
        Ok(drive.grid_objective(SEARCH_STEP_DEG, &mut self.cache, &self.turns, self.objective == Objective::Rms))
    }

    fn clearance(&mut self, x: &[f64]) -> Result<f64> {
        self.stop.check()?;
        self.clearance_checks += 1;
        let (loom, motion) = self.setup(x)?;
        let timing = Timing::new(&loom, &motion, self.pattern)?;
        Ok(match &mut self.rows {
            Some(rows) => timing.min_clearance_coarse_rows(SEARCH_STEP_DEG, rows),
            None => timing.min_clearance_coarse(SEARCH_STEP_DEG),
        })
    }

    /// Compass search ([`loomkin_numeric::compass_min`]) minimising `f` from `x` over the steps
    /// [`STEPS`] within `±max_stagger_deg`, taking only moves that `ok` accepts (asked only for
    /// moves that improve `f`).
    fn compass(
        &mut self,
        x: Vec<f64>,
        fx: f64,
        f: &dyn Fn(&mut Self, &[f64]) -> Result<f64>,
        ok: &dyn Fn(&mut Self, &[f64]) -> Result<bool>,
    ) -> Result<(Vec<f64>, f64)> {
        let m = self.loom.shedding.max_stagger_deg;
        let (lo, hi) = (vec![-m; x.len()], vec![m; x.len()]);
        loomkin_numeric::compass_min(self, x, fx, &STEPS, &lo, &hi, f, ok, |s| {
            s.stages.0 += 1;
            (s.progress)(s.stages.0.min(s.stages.1), s.stages.1);
        })
    }

    fn case(&self, label: &str, x: &[f64]) -> Result<StaggerCase> {
        self.stop.check()?;
        let (loom, motion) = self.setup(x)?;
        let drive = Drive::new(&loom, &motion, self.pattern);
        let timing = Timing::new(&loom, &motion, self.pattern)?;
        // The least clearance is the report's (the same minimum over the same picks); with no
        // pick whose shed clears the carrier, no window, no speed.
        let (min_clearance_mm, window_deg, max_speed_rpm) = match timing.summary() {
            Ok(r) => (r.min_clearance_mm, r.window_deg, r.max_speed_rpm),
            Err(_) => (timing.min_clearance_m() * 1e3, 0.0, 0.0),
        };
        Ok(StaggerCase {
            label: label.into(),
            stagger_deg: self.per_frame(x),
            peak_torque_n_m: drive.peak(0.5).torque_n_m.abs(),
            rms_torque_n_m: drive.rms(),
            min_clearance_mm,
            window_kept: min_clearance_mm >= 0.0,
            window_deg,
            max_speed_rpm,
        })
    }
}

/// The stagger of `loom` weaving `pattern` that minimises `objective` with every window kept,
/// beside no stagger and the two-group baseline. Searches per group when the loom file gives
/// groups, else per frame.
pub fn optimise_stagger(loom: &Loom, pattern: &Pattern, objective: Objective) -> Result<StaggerResult> {
    optimise_stagger_until(loom, pattern, objective, &StopFlag::default())
}

/// [`optimise_stagger`] that ends with [`LoomError::Stopped`] once `stop` is set: the flag is
/// checked before every objective evaluation and window check, so it ends within one of them (one
/// torque curve over the repeat) of the request.
pub fn optimise_stagger_until(
    loom: &Loom,
    pattern: &Pattern,
    objective: Objective,
    stop: &StopFlag,
) -> Result<StaggerResult> {
    optimise_stagger_with(loom, pattern, &StaggerOptions::new(objective), stop, &|_, _| {})
}

/// [`optimise_stagger_until`] with a least clearance to keep ([`StaggerOptions`]), calling
/// `progress(done, all)` as the search passes its stages (for a progress bar).
pub fn optimise_stagger_with(
    loom: &Loom,
    pattern: &Pattern,
    options: &StaggerOptions,
    stop: &StopFlag,
    progress: &dyn Fn(usize, usize),
) -> Result<StaggerResult> {
    optimise(loom, pattern, options, stop, progress, None)
}

/// [`optimise_stagger_with`], the window checks made from rows (`Some(true)`), turn by turn
/// (`Some(false)`), or as the number of distinct turns decides (`None`: rows beyond
/// [`MAX_WHOLE_TURNS`]).
pub(crate) fn optimise(
    loom: &Loom,
    pattern: &Pattern,
    options: &StaggerOptions,
    stop: &StopFlag,
    progress: &dyn Fn(usize, usize),
    rows: Option<bool>,
) -> Result<StaggerResult> {
    options.validate()?;
    let objective = options.objective;
    let n = loom.frame_count();
    let groups = loom.shedding.groups.clone();
    let dims = groups.as_ref().map_or(n, Vec::len);
    let motion = Motion::new(loom, pattern)?;
    // Every centre the search may move a frame to: the crossing plus any stagger in range.
    let delta = crate::crossing_offset_deg(loom.shedding.crossing_deg);
    let m = loom.shedding.max_stagger_deg;
    let turns = Turns::spanning(&motion, 0.0, 360.0, delta - m, delta + m);
    let mut s = Search {
        loom,
        pattern,
        objective,
        need_m: options.min_clearance_mm * 1e-3,
        groups,
        evaluations: 0,
        clearance_checks: 0,
        cache: TableCache::default(),
        rows: rows.unwrap_or(turns.first.len() > MAX_WHOLE_TURNS).then(SlopeRows::default),
        turns,
        progress,
        stop,
        stages: (0, 2 * STEPS.len()),
    };
    let need = s.need_m;
    let zero = vec![0.0; dims];
    let two: Vec<f64> = match &s.groups {
        None => (0..n).map(|i| if i % 2 == 1 { 7.5f64.min(loom.shedding.max_stagger_deg) } else { 0.0 }).collect(),
        Some(gs) => {
            (0..gs.len()).map(|g| if g % 2 == 1 { 7.5f64.min(loom.shedding.max_stagger_deg) } else { 0.0 }).collect()
        }
    };
    let two_frames: Vec<f64> = (0..n).map(|i| if i % 2 == 1 { 7.5 } else { 0.0 }).collect();
    let none = s.case("no stagger", &zero)?;
    let two_case = {
        let saved = s.groups.take();
        let c = if loom.shedding.max_stagger_deg >= 7.5 {
            s.case("two groups 7.5°", &two_frames)?
        } else {
            let mut c = s.case("two groups 7.5°", &zero)?;
            c.label = "two groups 7.5° (beyond max_stagger_deg: not evaluated)".into();
            c
        };
        s.groups = saved;
        c
    };
    let mut starts = Vec::new();
    for x0 in [zero.clone(), two] {
        if s.clearance(&x0)? >= need {
            starts.push(x0);
        }
    }
    if starts.is_empty() {
        // Phase 1: the stagger that opens the shed most over the insertion.
        s.stages.1 += STEPS.len();
        let g0 = s.clearance(&zero)?;
        let (x1, neg) = s.compass(zero.clone(), -g0, &|s, y| Ok(-s.clearance(y)?), &|_, _| Ok(true))?;
        if -neg < need {
            let ins = &loom.insertion;
            let (field, reason) = if need > 0.0 {
                (
                    "min_clearance_mm",
                    format!(
                        "no stagger within ±{}° (shedding.max_stagger_deg) keeps {} mm of clearance to the carrier from {}° to {}°: the best keeps {:.2} mm",
                        loom.shedding.max_stagger_deg,
                        options.min_clearance_mm,
                        ins.entry_deg,
                        ins.exit_deg,
                        -neg * 1e3
                    ),
                )
            } else {
                (
                    "insertion.entry_deg",
                    format!(
                        "no stagger within ±{}° (shedding.max_stagger_deg) keeps the carrier clear from {}° to {}°: the best still leaves {:.2} mm of interference",
                        loom.shedding.max_stagger_deg,
                        ins.entry_deg,
                        ins.exit_deg,
                        neg * 1e3
                    ),
                )
            };
            return Err(LoomError::Infeasible { field: field.into(), reason });
        }
        starts.push(x1);
    }
    s.stages.1 = s.stages.0 + starts.len() * STEPS.len();
    let mut best: Option<(Vec<f64>, f64)> = None;
    for x0 in starts {
        let f0 = s.objective(&x0)?;
        let (x, fx) = s.compass(x0, f0, &|s, y| s.objective(y), &|s, y| Ok(s.clearance(y)? >= s.need_m))?;
        if best.as_ref().is_none_or(|(_, fb)| fx < *fb) {
            best = Some((x, fx));
        }
    }
    let (bx, _) = best.unwrap_or((zero, 0.0));
    let best_case = s.case("optimised", &bx)?;
    let pct = |c: &StaggerCase| 100.0 * (1.0 - c.peak_torque_n_m / none.peak_torque_n_m);
    Ok(StaggerResult {
        objective,
        groups: s.groups.clone(),
        peak_reduction_pct: pct(&best_case),
        two_groups_peak_reduction_pct: pct(&two_case),
        none,
        two_groups: two_case,
        best: best_case,
        evaluations: s.evaluations,
        clearance_checks: s.clearance_checks,
        min_clearance_kept_mm: options.min_clearance_mm,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The search with its window checks made from rows takes the same steps to the same optimum
    /// as with every distinct turn worked out whole (100 random picks of 24 frames), and the
    /// checks agree to 1e-12 m at every stagger it met.
    #[test]
    fn the_search_from_rows_is_the_search_by_turns() {
        let loom = Loom::from_toml(include_str!("../../../examples/rapier-loom.toml")).unwrap();
        let pattern = crate::turn_rows::random(0x2545_f491_4f6c_dd1d, 100, 24);
        let options = StaggerOptions::new(Objective::Peak);
        let stop = StopFlag::default();
        let turns = optimise(&loom, &pattern, &options, &stop, &|_, _| {}, Some(false)).unwrap();
        let rows = optimise(&loom, &pattern, &options, &stop, &|_, _| {}, Some(true)).unwrap();
        assert_eq!(format!("{turns:?}"), format!("{rows:?}"));
        assert!(turns.best.peak_torque_n_m < turns.none.peak_torque_n_m, "{turns:?}");
        let mut cache = SlopeRows::default();
        for case in [&turns.none, &turns.two_groups, &turns.best] {
            let l = loom.with_stagger(&case.stagger_deg).unwrap();
            let motion = Motion::new(&l, &pattern).unwrap();
            let timing = Timing::new(&l, &motion, &pattern).unwrap();
            let (a, b) = (
                timing.min_clearance_coarse(SEARCH_STEP_DEG),
                timing.min_clearance_coarse_rows(SEARCH_STEP_DEG, &mut cache),
            );
            assert!((a - b).abs() <= 1e-12, "{}: {a} vs {b}", case.label);
        }
    }
}
