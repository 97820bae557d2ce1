//! Moving the free definition points to minimise the motor torque: multi-start Nelder–Mead.

use crate::drive::CYCLE_DEG;
use crate::torque::{PhaseModel, models, stats_above};
use crate::{Drive, Result, ServoError, SplineLaw, TorqueSummary, summaries};
use loomkin_units::Range;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// What the optimiser minimises; with several speeds, the worst (largest) value over the speeds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Objective {
    /// Peak |motor torque| over the turn (N·m).
    #[default]
    Peak,
    /// RMS motor torque over the turn (N·m).
    Rms,
}

impl Objective {
    /// Reads `peak` or `rms`.
    pub fn parse(text: &str) -> Result<Self> {
        match text.trim().to_ascii_lowercase().as_str() {
            "peak" => Ok(Self::Peak),
            "rms" => Ok(Self::Rms),
            _ => {
                Err(ServoError::Parse { field: "objective".into(), text: text.into(), expected: "peak or rms".into() })
            }
        }
    }

    /// `peak` or `rms`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Peak => "peak",
            Self::Rms => "rms",
        }
    }
}

/// Settings of [`optimize`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OptimizeOptions {
    /// Quantity to minimise.
    pub objective: Objective,
    /// Main-shaft speeds (1/min); the worst value over them is minimised.
    pub speeds_rpm: Vec<f64>,
    /// Number of Nelder–Mead starts: the given points, then pseudo-random points in the bounds.
    pub starts: usize,
    /// Objective evaluations allowed per start.
    pub max_evals_per_start: usize,
    /// Move the X of the free points too (else only their Y).
    pub move_x: bool,
    /// Bounds of the free Y (the paper uses `[0, 1]`); widened to include the starting points.
    pub y_bounds: [f64; 2],
    /// Largest factor by which an X gap may grow or shrink from its starting width.
    pub max_gap_factor: f64,
    /// Seed of the pseudo-random starts (the result is deterministic).
    pub seed: u64,
    /// Set from another thread to stop early (a client gone, a time budget spent): every later
    /// evaluation counts as +∞, so each start ends at once. The caller checks
    /// [`StopFlag::is_set`] to know that the result is not a finished optimisation.
    #[serde(skip)]
    pub stop: StopFlag,
    /// Counts the objective evaluations as they are made, for another thread to read (a
    /// progress bar over `starts × max_evals_per_start`).
    #[serde(skip)]
    pub evaluated: Counter,
}

/// A count shared between an optimisation and whoever watches it.
#[derive(Debug, Clone, Default)]
pub struct Counter(std::sync::Arc<std::sync::atomic::AtomicUsize>);

impl Counter {
    /// The count so far.
    pub fn get(&self) -> usize {
        self.0.load(std::sync::atomic::Ordering::Relaxed)
    }

    fn add(&self, n: usize) {
        self.0.fetch_add(n, std::sync::atomic::Ordering::Relaxed);
    }
}

impl PartialEq for Counter {
    /// Two counters are equal when they are the same counter.
    fn eq(&self, other: &Self) -> bool {
        std::sync::Arc::ptr_eq(&self.0, &other.0)
    }
}

/// A flag shared between an optimisation and whoever may stop it: the one of every long
/// computation, [`loomkin_units::StopFlag`].
pub use loomkin_units::StopFlag;

impl Default for OptimizeOptions {
    fn default() -> Self {
        Self {
            objective: Objective::Peak,
            speeds_rpm: vec![600.0],
            starts: 6,
            max_evals_per_start: 1200,
            move_x: true,
            y_bounds: [0.0, 1.0],
            max_gap_factor: 3.0,
            seed: 0x5eed_1e55,
            stop: StopFlag::default(),
            evaluated: Counter::default(),
        }
    }
}

/// Seconds per objective evaluation, per definition point and per speed: the spline through the
/// points, then the exact torque extremes (or the RMS) at each speed. From the `optimize_eval`
/// bench (release, fastest of 5, 200 evaluations): 1.04 µs at 7 points × 1 speed, 0.69 µs at
/// 7 × 6, 1.12 µs at 33 × 1, 2.09 µs at 33 × 6 (the Nelder–Mead bookkeeping grows with the
/// points); the largest, taken into estimates by [`loomkin_units::Cost::cpu_items`].
pub const EVAL_S_PER_POINT_SPEED: f64 = 2.1e-6;

impl OptimizeOptions {
    /// The cost of [`optimize`] with these options from `points` definition points, estimated
    /// before it runs (the most evaluations it may make, each timed by
    /// [`EVAL_S_PER_POINT_SPEED`]), with the starts shared by `cores` threads. Memory is a few
    /// vectors per start: not counted.
    pub fn cost(&self, points: usize, cores: usize) -> loomkin_units::Cost {
        let starts = self.starts.max(1);
        let evals = (starts * self.max_evals_per_start) as f64;
        let per_eval = EVAL_S_PER_POINT_SPEED * points.max(1) as f64 * self.speeds_rpm.len().max(1) as f64;
        let threads = cores.clamp(1, starts) as f64;
        loomkin_units::Cost::cpu_items(evals, 0.0, per_eval / threads)
    }
}

/// Before / after of an optimisation.
#[derive(Debug, Clone, PartialEq)]
pub struct OptimizeReport {
    /// The options used.
    pub objective: Objective,
    /// Summaries of the starting law at every speed.
    pub before: Vec<TorqueSummary>,
    /// Summaries of the optimised law at every speed.
    pub after: Vec<TorqueSummary>,
    /// The optimised law (its points: [`SplineLaw::points`]).
    pub law: SplineLaw,
    /// Objective of the start (N·m).
    pub objective_before_nm: f64,
    /// Objective of the result (N·m).
    pub objective_after_nm: f64,
    /// Objective evaluations spent.
    pub evaluations: usize,
}

/// Maps a point of the unit box `z ∈ [0, 1]^d` to definition points.
struct Mapping {
    base: Vec<[f64; 2]>,
    gaps0: Vec<f64>,
    y_lo: f64,
    y_hi: f64,
    log_f: f64,
    move_x: bool,
}

impl Mapping {
    fn dim(&self) -> usize {
        let free = self.base.len() - 2;
        free + if self.move_x { self.gaps0.len() } else { 0 }
    }

    fn start(&self) -> Vec<f64> {
        let mut z: Vec<f64> = self.base[1..self.base.len() - 1]
            .iter()
            .map(|p| if self.y_hi > self.y_lo { (p[1] - self.y_lo) / (self.y_hi - self.y_lo) } else { 0.5 })
            .collect();
        if self.move_x {
            z.extend(std::iter::repeat_n(0.5, self.gaps0.len()));
        }
        z
    }

    fn points(&self, z: &[f64]) -> Vec<[f64; 2]> {
        let n = self.base.len();
        let mut pts = self.base.clone();
        for j in 1..n - 1 {
            pts[j][1] = self.y_lo + z[j - 1] * (self.y_hi - self.y_lo);
        }
        if self.move_x {
            let g: Vec<f64> =
                self.gaps0.iter().zip(&z[n - 2..]).map(|(g, zz)| g * (self.log_f * (2.0 * zz - 1.0)).exp()).collect();
            let total: f64 = g.iter().sum();
            let mut x = 0.0;
            for j in 1..n - 1 {
                x += 0.5 * g[j - 1] / total;
                pts[j][0] = x;
            }
        }
        pts
    }
}

/// The objective at every speed: worst peak or RMS torque (N·m); `+∞` for invalid points.
///
/// Only the worst value counts, so each speed's peak search is told the worst so far (a segment
/// whose torque bound is below it is not searched), and the RMS objective searches no peak at all;
/// the value is the same, bit for bit, as the maximum of the full [`crate::summary`] figures.
fn objective_value(law: &SplineLaw, ms: &[([PhaseModel; 4], f64)], obj: Objective) -> f64 {
    let mut worst = 0.0f64;
    for (m, cycle_s) in ms {
        worst = worst.max(match obj {
            Objective::Peak => stats_above(law.law(), m, *cycle_s, false, false, worst).peak_torque_nm,
            Objective::Rms => stats_above(law.law(), m, *cycle_s, false, true, f64::INFINITY).rms_torque_nm,
        });
    }
    worst
}

/// Minimises the peak (or RMS) motor torque of `drive` over the free definition points of `start`.
///
/// The first and last points stay at `[0, 0]` and `[0.5, 0]`. The free Y move within
/// `y_bounds`; with `move_x`, the X gaps may each grow or shrink by up to `max_gap_factor` (and
/// are renormalised to end at 0.5), so the points stay in order. Each start runs a bounded
/// Nelder–Mead (vertices projected onto the box) and is restarted once from its result; the best
/// of all starts is returned, its Y scaled to a largest |Y| of 1 (the same law). Deterministic
/// for a given `seed`.
pub fn optimize(start: &SplineLaw, drive: &Drive, opts: &OptimizeOptions) -> Result<OptimizeReport> {
    drive.validate()?;
    if opts.speeds_rpm.is_empty() {
        return Err(ServoError::Parse {
            field: "speed_rpm".into(),
            text: String::new(),
            expected: "at least one speed".into(),
        });
    }
    let ms: Vec<([PhaseModel; 4], f64)> =
        opts.speeds_rpm.iter().map(|&n| Ok((models(drive, n)?, CYCLE_DEG / (n * 6.0)))).collect::<Result<_>>()?;
    Range::closed(-1.0, 1.0, "").check("y_bounds[0]", opts.y_bounds[0])?;
    Range::closed(opts.y_bounds[0], 1.0, "").check("y_bounds[1]", opts.y_bounds[1])?;
    Range::closed(1.0, 100.0, "").check("max_gap_factor", opts.max_gap_factor)?;
    let base = start.points().to_vec();
    let free_y = base[1..base.len() - 1].iter().map(|p| p[1]);
    let map = Mapping {
        gaps0: base.windows(2).map(|w| w[1][0] - w[0][0]).collect(),
        y_lo: free_y.clone().fold(opts.y_bounds[0], f64::min),
        y_hi: free_y.fold(opts.y_bounds[1], f64::max),
        log_f: opts.max_gap_factor.ln(),
        move_x: opts.move_x,
        base,
    };
    let end = start.end();
    let value = |z: &[f64]| match SplineLaw::new(&map.points(z), end) {
        Ok(l) => objective_value(&l, &ms, opts.objective),
        Err(_) => f64::INFINITY,
    };
    let f = |z: &[f64]| if opts.stop.is_set() { f64::INFINITY } else { value(z) };
    let z0 = map.start();
    let f0 = value(&z0);
    // The starts are independent: they run in parallel, each with its own evaluation count, and
    // are reduced in start order afterwards, so the result is the same as a serial run's.
    let starts: Vec<Vec<f64>> = {
        let mut rng = opts.seed | 1;
        (0..opts.starts.max(1))
            .map(|s| if s == 0 { z0.clone() } else { (0..map.dim()).map(|_| next_unit(&mut rng)).collect() })
            .collect()
    };
    let runs: Vec<(Vec<f64>, f64, usize)> = starts
        .par_iter()
        .map(|zs| {
            let mut evals = 0usize;
            let mut counted = |z: &[f64]| {
                evals += 1;
                opts.evaluated.add(1);
                f(z)
            };
            let (z1, _) = nelder_mead(&mut counted, zs, 0.2, opts.max_evals_per_start / 2);
            let (z2, f2) = nelder_mead(&mut counted, &z1, 0.05, opts.max_evals_per_start / 2);
            (z2, f2, evals)
        })
        .collect();
    let evals = 1 + runs.iter().map(|r| r.2).sum::<usize>();
    let mut best = (z0, f0);
    for (z2, f2, _) in runs {
        if f2 < best.1 {
            best = (z2, f2);
        }
    }
    // The law does not change when every Y is multiplied by the same positive factor (it is
    // normalised to a unit stroke), so the optimiser may end anywhere along that ray: report the
    // points scaled to a largest |Y| of 1, as the paper draws them.
    let mut pts = map.points(&best.0);
    let y_max = pts.iter().map(|p| p[1].abs()).fold(0.0, f64::max);
    if y_max > 0.0 {
        pts.iter_mut().for_each(|p| p[1] /= y_max);
    }
    let law = SplineLaw::new(&pts, end)?;
    let objective_after_nm = objective_value(&law, &ms, opts.objective);
    Ok(OptimizeReport {
        objective: opts.objective,
        before: summaries(start.law(), drive, &opts.speeds_rpm)?,
        after: summaries(law.law(), drive, &opts.speeds_rpm)?,
        law,
        objective_before_nm: f0,
        objective_after_nm,
        evaluations: evals,
    })
}

/// xorshift64*: a uniform number in `[0, 1)`.
fn next_unit(state: &mut u64) -> f64 {
    let mut x = *state;
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    *state = x;
    (x.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
}

/// Nelder–Mead in the unit box (every trial point clamped into `[0, 1]^d`), starting from a
/// simplex of `x0` and `x0 ± step` along each axis. Stops after `max_evals` evaluations or when
/// the simplex has collapsed (spread of values ≤ 1e-10 relative and size ≤ 1e-7).
pub(crate) fn nelder_mead(
    f: &mut impl FnMut(&[f64]) -> f64,
    x0: &[f64],
    step: f64,
    max_evals: usize,
) -> (Vec<f64>, f64) {
    let d = x0.len();
    let clamp = |v: Vec<f64>| v.into_iter().map(|c| c.clamp(0.0, 1.0)).collect::<Vec<_>>();
    let mut simplex: Vec<(Vec<f64>, f64)> = Vec::with_capacity(d + 1);
    let x0 = clamp(x0.to_vec());
    let f0 = f(&x0);
    simplex.push((x0.clone(), f0));
    for i in 0..d {
        let mut x = x0.clone();
        x[i] = if x[i] + step <= 1.0 { x[i] + step } else { x[i] - step };
        let fx = f(&x);
        simplex.push((x, fx));
    }
    let mut used = d + 1;
    while used < max_evals {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        let (fb, fw) = (simplex[0].1, simplex[d].1);
        let size = simplex.iter().skip(1).map(|(x, _)| dist(x, &simplex[0].0)).fold(0.0, f64::max);
        if (fw - fb).abs() <= 1e-10 * fb.abs().max(1e-300) && size <= 1e-7 {
            break;
        }
        let centroid: Vec<f64> =
            (0..d).map(|k| simplex[..d].iter().map(|(x, _)| x[k]).sum::<f64>() / d as f64).collect();
        let along = |t: f64| clamp(centroid.iter().zip(&simplex[d].0).map(|(c, w)| c + t * (c - w)).collect());
        let xr = along(1.0);
        let fr = f(&xr);
        used += 1;
        if fr < simplex[0].1 {
            let xe = along(2.0);
            let fe = f(&xe);
            used += 1;
            simplex[d] = if fe < fr { (xe, fe) } else { (xr, fr) };
        } else if fr < simplex[d - 1].1 {
            simplex[d] = (xr, fr);
        } else {
            let (xc, fc) = if fr < fw {
                let x = along(0.5);
                let fx = f(&x);
                (x, fx)
            } else {
                let x = along(-0.5);
                let fx = f(&x);
                (x, fx)
            };
            used += 1;
            if fc < fw.min(fr) {
                simplex[d] = (xc, fc);
            } else {
                let best = simplex[0].0.clone();
                for (x, fx) in simplex.iter_mut().skip(1) {
                    *x = x.iter().zip(&best).map(|(a, b)| b + 0.5 * (a - b)).collect();
                    *fx = f(x);
                }
                used += d;
            }
        }
    }
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    simplex.swap_remove(0)
}

fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nelder_mead_finds_a_boxed_quadratic_minimum() {
        let mut f = |z: &[f64]| (z[0] - 0.3).powi(2) + 2.0 * (z[1] - 0.7).powi(2) + (z[2] + 0.5).powi(2);
        let (z, fz) = nelder_mead(&mut f, &[0.9, 0.1, 0.5], 0.2, 3000);
        assert!((z[0] - 0.3).abs() < 1e-4 && (z[1] - 0.7).abs() < 1e-4, "{z:?}");
        assert!(z[2].abs() < 1e-6, "the bound z ≥ 0 is active: {z:?}");
        assert!((fz - 0.25).abs() < 1e-7);
    }
}
