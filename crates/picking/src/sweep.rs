//! Sweeps of one setting over a range, evaluated in parallel (the paper's Figs. 5–8 and 10).

use crate::{Mechanism, Method, Outcome, Result, Setting, Settings, simulate};
use loomkin_units::Range;
use rayon::prelude::*;
use serde::Serialize;

/// One point of a sweep.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepRow {
    /// Value of the swept setting, in [`Setting::unit`].
    pub value: f64,
    /// The end-of-pick values there.
    pub outcome: Outcome,
}

/// A setting swept over a range.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sweep {
    /// The swept setting.
    pub setting: Setting,
    /// The rows, in order of value.
    pub rows: Vec<SweepRow>,
}

impl Sweep {
    /// Rows where the closed form could not answer and the numerical route did.
    pub fn fallbacks(&self) -> impl Iterator<Item = &SweepRow> {
        self.rows.iter().filter(|r| r.outcome.note.is_some())
    }
}

/// Runs `setting` from `from` to `to` (its practical unit, both ends included) in `steps ≥ 1`
/// evenly spaced points over `base`, in parallel. Fails on the first invalid point, naming it.
pub fn sweep(
    mechanism: &Mechanism,
    base: &Settings,
    setting: Setting,
    from: f64,
    to: f64,
    steps: usize,
    method: Method,
) -> Result<Sweep> {
    sweep_items(mechanism, base, setting, from, to, steps, method, 0..steps)
}

/// The points `items` (indices into `0..steps`, e.g. one shard's share,
/// [`loomkin_units::Shard::items`]) of the sweep [`sweep`] would run: each point's value and
/// outcome are those of the whole sweep, bit for bit. Indices past `steps` are left out.
#[allow(clippy::too_many_arguments)]
pub fn sweep_items(
    mechanism: &Mechanism,
    base: &Settings,
    setting: Setting,
    from: f64,
    to: f64,
    steps: usize,
    method: Method,
    items: std::ops::Range<usize>,
) -> Result<Sweep> {
    sweep_observed(mechanism, base, setting, from, to, steps, method, items, &|| {})
}

/// [`sweep_items`], calling `on_point` as each point is done (from the worker threads: a
/// progress bar).
#[allow(clippy::too_many_arguments)]
pub fn sweep_observed(
    mechanism: &Mechanism,
    base: &Settings,
    setting: Setting,
    from: f64,
    to: f64,
    steps: usize,
    method: Method,
    items: std::ops::Range<usize>,
    on_point: &(dyn Fn() + Sync),
) -> Result<Sweep> {
    Range::finite(setting.unit()).check("from", from)?;
    Range::finite(setting.unit()).check("to", to)?;
    // No upper bound here: a front end estimates the time of its points against its budget.
    Range::at_least(1.0, "").check("steps", steps as f64)?;
    let value = |i: usize| if steps == 1 { from } else { from + (to - from) * i as f64 / (steps - 1) as f64 };
    let rows = (items.start.min(steps)..items.end.min(steps))
        .into_par_iter()
        .map(|i| {
            let v = value(i);
            let row =
                simulate(mechanism, &setting.apply(*base, v), method).map(|outcome| SweepRow { value: v, outcome });
            on_point();
            row
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(Sweep { setting, rows })
}
