//! Sweeps of one setting over a range, evaluated in parallel (the paper's Figs. 5–8 and 10).

use crate::{Mechanism, Method, Outcome, Result, Setting, Settings, simulate};
use loomkin_units::{Field, Range};
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
    /// `points`: the evenly spaced values of a sweep, both ends included (required): at least one
    /// (a single simulation); the time budget ([`loomkin_units::Budget`]) bounds how many.
    pub const POINTS: Field = Field::count(
        "points",
        Range::at_least(1.0, ""),
        "Values of the swept setting, both ends included: at least 1; the time budget bounds how many (10⁶ \
         when the rows are held as arrays).",
    );
    /// [`Sweep::POINTS`] held as arrays (Python): 1 … 10⁶.
    pub const HELD_POINTS: Field = Self::POINTS
        .within(Range::closed(1.0, 1e6, ""), "Values of the swept setting when the rows are held as arrays: 1 … 10⁶.");

    /// CPU seconds per point by the closed form (one `simulate`, the ODE fallback at a few points):
    /// 40 µs, measured on the reference machine (release, one core).
    pub const CPU_S_PER_POINT_CLOSED: f64 = 40e-6;
    /// CPU seconds per point integrated numerically, measured as [`Sweep::CPU_S_PER_POINT_CLOSED`]: 400 µs.
    pub const CPU_S_PER_POINT_ODE: f64 = 400e-6;
    /// Bytes held per point: the row (value and outcome, with its note's text at a fallback).
    pub const BYTES_PER_POINT: f64 = 200.0;

    /// What sweeping `points` values by `method` on `threads` threads costs, estimated before it
    /// runs ([`loomkin_units::Cost::cpu_items`]), each point holding its row and `row_bytes` more
    /// (the text a front end keeps for it).
    pub fn cost(points: f64, method: Method, threads: f64, row_bytes: f64) -> loomkin_units::Cost {
        let per = if method == Method::Ode { Self::CPU_S_PER_POINT_ODE } else { Self::CPU_S_PER_POINT_CLOSED };
        loomkin_units::Cost::cpu_items(points, Self::BYTES_PER_POINT + row_bytes, per / threads.max(1.0))
    }

    /// Rows where the closed form could not answer and the numerical route did.
    pub fn fallbacks(&self) -> impl Iterator<Item = &SweepRow> {
        self.rows.iter().filter(|r| r.outcome.note.is_some())
    }
}

/// A sweep as users read it (`loomkin pick sweep --json`): the setting's name and unit, the route
/// asked for, the values where the closed form fell back to integration, and the rows.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepReport<'a> {
    /// The swept setting's name ([`Setting::name`]).
    pub setting: &'static str,
    /// Its unit.
    pub unit: &'static str,
    /// The route asked for.
    pub method: Method,
    /// Values where the closed form could not answer.
    pub fallback_values: Vec<f64>,
    /// The rows.
    pub rows: Vec<RowReport<'a>>,
}

/// A sweep row as users read it: the outcome's keys and the swept value under the setting's key
/// (e.g. `play_mm`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RowReport<'a> {
    /// The end-of-pick values.
    #[serde(flatten)]
    pub outcome: &'a Outcome,
    /// The swept value, keyed by [`Setting::key`].
    #[serde(flatten)]
    pub value: SettingValue,
}

/// A setting's value under its key ([`Setting::key`]): one entry of a JSON object.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SettingValue {
    /// The setting.
    pub setting: Setting,
    /// Its value, in [`Setting::unit`].
    pub value: f64,
}

impl Serialize for SettingValue {
    fn serialize<S: serde::Serializer>(&self, ser: S) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut m = ser.serialize_map(Some(1))?;
        m.serialize_entry(&self.setting.key(), &self.value)?;
        m.end()
    }
}

impl SweepRow {
    /// This row as users read it, the value keyed by `setting`.
    pub fn report(&self, setting: Setting) -> RowReport<'_> {
        RowReport { outcome: &self.outcome, value: SettingValue { setting, value: self.value } }
    }
}

impl Sweep {
    /// The sweep as users read it, run by `method`.
    pub fn report(&self, method: Method) -> SweepReport<'_> {
        SweepReport {
            setting: self.setting.name(),
            unit: self.setting.unit(),
            method,
            fallback_values: self.fallbacks().map(|r| r.value).collect(),
            rows: self.rows.iter().map(|r| r.report(self.setting)).collect(),
        }
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
    Sweep::POINTS.check_count(steps)?;
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

/// Values of the swept setting where the shuttle's velocity at the end of the pick equals the
/// required velocity V_r, in order: each one between two rows of the sweep whose margin
/// `V − V_r` changes sign, located by bisection on the model itself (not interpolated between
/// rows) until the bracket is 1e-12 of the value wide ([`loomkin_numeric::try_bisect_bracket_within`]). `base` and `method` must be those the
/// sweep was run with.
pub fn required_velocity_crossings(
    mechanism: &Mechanism,
    base: &Settings,
    sweep: &Sweep,
    method: Method,
) -> Result<Vec<f64>> {
    // A margin within 1e-12 of V_r is an equality (the designed setting meets V_r exactly, and
    // its closed form leaves a rounding residue of either sign).
    let margin = |o: &Outcome| {
        let m = o.velocity_m_s - o.required_velocity_m_s;
        if m.abs() <= 1e-12 * o.required_velocity_m_s.abs() { 0.0 } else { m }
    };
    let mut out = Vec::new();
    for w in sweep.rows.windows(2) {
        let (fa, fb) = (margin(&w[0].outcome), margin(&w[1].outcome));
        if fa == 0.0 {
            if out.last() != Some(&w[0].value) {
                out.push(w[0].value);
            }
            continue;
        }
        if fb == 0.0 || fa.signum() == fb.signum() || !(fa.is_finite() && fb.is_finite()) {
            continue;
        }
        // A margin of exactly zero at a midpoint is the crossing itself: it ends the search.
        enum Stop {
            Exact(f64),
            Failed(crate::PickError),
        }
        let bracket = loomkin_numeric::try_bisect_bracket_within(w[0].value, w[1].value, 1e-12, |mid| {
            let fm = margin(&simulate(mechanism, &sweep.setting.apply(*base, mid), method).map_err(Stop::Failed)?);
            if fm == 0.0 { Err(Stop::Exact(mid)) } else { Ok(fm.signum() == fa.signum()) }
        });
        out.push(match bracket {
            Ok((lo, hi)) => 0.5 * (lo + hi),
            Err(Stop::Exact(mid)) => mid,
            Err(Stop::Failed(e)) => return Err(e),
        });
    }
    if let Some(last) = sweep.rows.last().filter(|r| margin(&r.outcome) == 0.0) {
        out.push(last.value);
    }
    Ok(out)
}
