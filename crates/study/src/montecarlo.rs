//! What every Monte-Carlo study shares, whatever it draws: the checked size of the study
//! ([`check_plan`]), the parallel run of any shard of its draws ([`run_draws`]) and the report of
//! the draws ([`tally`]: the distribution of each drawn input and each result, the draws the model
//! refused and the share failing a limit). The pick study (`loomkin_picking::montecarlo`) and the
//! dobby tolerance study (`loomkin_mech::tolerance`) are this runner with their own model.

use crate::{Limit, Progress, Result, StudyError, Summary, evaluate_indexed};
use serde::Serialize;

/// Most histogram bins a study may ask for.
pub const MAX_BINS: usize = 1000;

/// Histogram bins when the study file gives none.
pub const DEFAULT_BINS: usize = 20;

/// One draw as the report reads it.
pub trait Drawn {
    /// The drawn inputs, in the study's order of inputs.
    fn inputs(&self) -> &[f64];
    /// The results in the study's order of results, or `None` when the model refused the draw.
    fn results(&self) -> Option<&[f64]>;
}

/// A draw as one row of the per-draw table (`--csv` of a study, read back to report a run made
/// in shards): `draw`, the inputs, a 1/0 column [`DrawRow::ANSWERED`], the results, then the
/// [`DrawRow::FLAGS`] as 1/0; a refused draw has 0 in every column after its inputs.
pub trait DrawRow: Drawn + Sized {
    /// Name of the column that says whether the model answered (`simulated`, `assembled`).
    const ANSWERED: &'static str;
    /// Names of the yes/no columns after the results.
    const FLAGS: &'static [&'static str];
    /// Names of the inputs, with units.
    fn input_names() -> Vec<String>;
    /// Names of the results, with units.
    fn result_names() -> Vec<String>;
    /// Index of the draw in the study, from 0.
    fn index(&self) -> u64;
    /// The yes/no values of [`DrawRow::FLAGS`] (an answered draw).
    fn flags(&self) -> Vec<bool>;
    /// Why the model refused the draw.
    fn error(&self) -> Option<&str>;
    /// The draw of a row: `answered` holds the results and flags, `None` for a refused draw.
    fn from_parts(index: u64, inputs: &[f64], answered: Option<(&[f64], &[bool])>) -> Self;

    /// The columns of the per-draw table.
    fn columns() -> Vec<String> {
        let mut c = vec!["draw".to_string()];
        c.extend(Self::input_names());
        c.push(Self::ANSWERED.into());
        c.extend(Self::result_names());
        c.extend(Self::FLAGS.iter().map(|s| s.to_string()));
        c
    }

    /// This draw as a row of [`DrawRow::columns`].
    fn row(&self) -> Vec<f64> {
        let flag = |b: bool| if b { 1.0 } else { 0.0 };
        let mut r = vec![self.index() as f64];
        r.extend(self.inputs());
        match self.results() {
            Some(x) => {
                r.push(1.0);
                r.extend(x);
                r.extend(self.flags().into_iter().map(flag));
            }
            None => r.extend(std::iter::repeat_n(0.0, 1 + Self::result_names().len() + Self::FLAGS.len())),
        }
        r
    }

    /// The draw of a row of [`DrawRow::columns`] (as wide as they are).
    fn from_row(v: &[f64]) -> Self {
        let (n_in, n_res) = (Self::input_names().len(), Self::result_names().len());
        let inputs = &v[1..1 + n_in];
        let at = 2 + n_in;
        let flags: Vec<bool> = v[at + n_res..].iter().map(|&f| f == 1.0).collect();
        let answered = (v[1 + n_in] == 1.0).then_some((&v[at..at + n_res], &flags[..]));
        Self::from_parts(v[0] as u64, inputs, answered)
    }
}

/// A draw as a JSON object (one line of a sharded `--json` run): `draw`, each input and result by
/// name and each flag as a boolean, or `error` for a refused draw.
#[derive(Debug, Clone, Copy)]
pub struct DrawEntry<'a, D>(pub &'a D);

impl<D: DrawRow> Serialize for DrawEntry<'_, D> {
    fn serialize<S: serde::Serializer>(&self, ser: S) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let d = self.0;
        let mut m = ser.serialize_map(None)?;
        m.serialize_entry("draw", &d.index())?;
        for (k, x) in D::input_names().iter().zip(d.inputs()) {
            m.serialize_entry(k, x)?;
        }
        match (d.results(), d.error()) {
            (Some(r), _) => {
                for (k, y) in D::result_names().iter().zip(r) {
                    m.serialize_entry(k, y)?;
                }
                for (k, f) in D::FLAGS.iter().zip(d.flags()) {
                    m.serialize_entry(k, &f)?;
                }
            }
            (None, e) => m.serialize_entry("error", e.unwrap_or(""))?,
        }
        m.end()
    }
}

/// What a study reports, as [`tally`] takes it: each input named with whether it is drawn with a
/// spread (only those are reported), and each result named with its limit.
pub type Reported = (Vec<(String, bool)>, Vec<(&'static str, Option<Limit>)>);

/// The distribution of one quantity (a drawn input or a result), named with its unit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Named {
    /// Name with unit, e.g. `speed_rpm`.
    pub name: String,
    /// Its distribution.
    #[serde(flatten)]
    pub summary: Summary,
}

/// The report of a run's draws.
#[derive(Debug, Clone, PartialEq)]
pub struct Tally {
    /// Draws.
    pub draws: u64,
    /// Draws the model refused (counted as failing).
    pub refused: u64,
    /// Draws failing a limit or refused.
    pub failing: u64,
    /// `failing / draws` (0 without draws).
    pub fail_share: f64,
    /// The distributions of the inputs drawn with a spread, over every draw.
    pub inputs: Vec<Named>,
    /// The distributions of the results, over the draws the model answered.
    pub results: Vec<Named>,
}

/// Checks a study's size and what its report shows: `1 ≤ draws ≤ max_draws`,
/// `1 ≤ bins ≤` [`MAX_BINS`] (default [`DEFAULT_BINS`]), 1 to 101 percentiles each in `[0, 100]`
/// (default [`crate::DEFAULT_PERCENTILES`]). Gives the bins and the percentiles.
pub fn check_plan(
    draws: u64,
    max_draws: u64,
    bins: Option<usize>,
    percentiles: Option<Vec<f64>>,
) -> Result<(usize, Vec<f64>)> {
    let invalid = |field: &str, reason: String| StudyError::Distribution { field: field.into(), reason };
    if draws == 0 || draws > max_draws {
        return Err(invalid("draws", format!("draws = {draws} is out of range: allowed 1 ≤ draws ≤ {max_draws}")));
    }
    let bins = bins.unwrap_or(DEFAULT_BINS);
    if !(1..=MAX_BINS).contains(&bins) {
        return Err(invalid("bins", format!("bins = {bins} is out of range: allowed 1 ≤ bins ≤ {MAX_BINS}")));
    }
    let percentiles = percentiles.unwrap_or_else(|| crate::DEFAULT_PERCENTILES.to_vec());
    if percentiles.is_empty() || percentiles.len() > 101 || percentiles.iter().any(|p| !(0.0..=100.0).contains(p)) {
        return Err(invalid("percentiles", "give 1 to 101 values, each 0 ≤ p ≤ 100 (%)".into()));
    }
    Ok((bins, percentiles))
}

/// Runs `draw` on the indices `items` of a study of `draws` draws (all: `0..draws`; a shard:
/// `loomkin_units::Shard::items`), clipped to the study, in parallel. The draws come back in
/// index order; each depends on its index only, not on the shard or the number of threads.
pub fn run_draws<T, F>(draws: u64, items: std::ops::Range<u64>, progress: Progress, draw: F) -> Vec<T>
where
    T: Send,
    F: Fn(u64) -> T + Sync,
{
    let lo = items.start.min(draws);
    let hi = items.end.min(draws).max(lo);
    evaluate_indexed((hi - lo) as usize, progress, "draws", |i| draw(lo + i as u64))
}

/// The report of `draws` (every draw of the study, in order: one run's, or the shards'
/// concatenated; sums run in draw order, so it does not depend on how they were computed).
/// `inputs` names each input and says whether it was drawn with a spread (only those are
/// reported); `results` names each result with its limit.
pub fn tally<D: Drawn>(
    draws: &[D],
    percentiles: &[f64],
    bins: usize,
    inputs: &[(String, bool)],
    results: &[(&str, Option<Limit>)],
) -> Tally {
    let ok: Vec<&[f64]> = draws.iter().filter_map(Drawn::results).collect();
    let named = |name: &str, v: &[f64], limit| {
        Summary::of(v, percentiles, bins, limit).map(|summary| Named { name: name.to_string(), summary })
    };
    let result_summaries = results
        .iter()
        .enumerate()
        .filter_map(|(k, (name, limit))| named(name, &ok.iter().map(|r| r[k]).collect::<Vec<_>>(), *limit))
        .collect();
    let input_summaries = inputs
        .iter()
        .enumerate()
        .filter(|(_, (_, spread))| *spread)
        .filter_map(|(k, (name, _))| named(name, &draws.iter().map(|d| d.inputs()[k]).collect::<Vec<_>>(), None))
        .collect();
    let failing = draws
        .iter()
        .filter(|d| match d.results() {
            None => true,
            Some(r) => results.iter().enumerate().any(|(k, (_, l))| l.is_some_and(|l| l.fails(r[k]))),
        })
        .count() as u64;
    let n = draws.len() as u64;
    Tally {
        draws: n,
        refused: n - ok.len() as u64,
        failing,
        fail_share: if n > 0 { failing as f64 / n as f64 } else { 0.0 },
        inputs: input_summaries,
        results: result_summaries,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct D(Vec<f64>, Option<Vec<f64>>);

    impl Drawn for D {
        fn inputs(&self) -> &[f64] {
            &self.0
        }
        fn results(&self) -> Option<&[f64]> {
            self.1.as_deref()
        }
    }

    /// Counted by hand: 4 draws, one refused, one over the limit of the first result.
    #[test]
    fn tally_counts_by_hand() {
        let draws = [
            D(vec![1.0, 5.0], Some(vec![0.5, 2.0])),
            D(vec![2.0, 5.0], None),
            D(vec![3.0, 5.0], Some(vec![1.5, 2.0])),
            D(vec![4.0, 5.0], Some(vec![0.7, 2.0])),
        ];
        let limit = Limit { min: None, max: Some(1.0) };
        let t = tally(
            &draws,
            &[0.0, 50.0, 100.0],
            4,
            &[("a_m".into(), true), ("b_m".into(), false)],
            &[("x_s", Some(limit)), ("y_s", None)],
        );
        assert_eq!((t.draws, t.refused, t.failing), (4, 1, 2));
        assert_eq!(t.fail_share, 0.5);
        assert_eq!(t.inputs.len(), 1);
        assert_eq!(t.inputs[0].name, "a_m");
        assert_eq!(t.inputs[0].summary.mean, 2.5);
        assert_eq!(t.results[0].summary.max, 1.5);
        assert_eq!(t.results[0].summary.failing, 1);
        assert_eq!(t.results[1].summary.sd, 0.0);
    }

    #[test]
    fn plans_are_checked_naming_the_key() {
        assert_eq!(check_plan(5, 10, None, None).unwrap(), (DEFAULT_BINS, crate::DEFAULT_PERCENTILES.to_vec()));
        let e = |r: Result<(usize, Vec<f64>)>| r.unwrap_err().to_string();
        assert_eq!(e(check_plan(0, 10, None, None)), "draws: draws = 0 is out of range: allowed 1 ≤ draws ≤ 10");
        assert!(e(check_plan(5, 10, Some(0), None)).starts_with("bins: bins = 0"));
        assert!(e(check_plan(5, 10, None, Some(vec![101.0]))).starts_with("percentiles: "));
        let items: Vec<u64> = run_draws(10, 7..20, Progress::Hidden, |i| i);
        assert_eq!(items, [7, 8, 9]);
    }
}
