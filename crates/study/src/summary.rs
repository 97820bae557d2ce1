//! Per-shard summaries of a Monte-Carlo run: what each shard's draws contribute to the report,
//! small and mergeable, so a cluster need not move the per-draw rows to report a run.
//!
//! A [`DrawSummary`] holds, for the draws of one shard (or of several merged), the counts (draws,
//! refused, failing, each yes/no flag), and per reported quantity its count, mean and sum of
//! squared deviations from the mean (merged by Chan, Golub & LeVeque's pairwise update), least and
//! largest value and the count failing its limit. [`DrawSummary::merge`] joins the shards'
//! summaries in any order, checking they are one study's and cover its draws once;
//! [`DrawSummary::tally`] gives the report.
//!
//! Against the report of the rows ([`crate::tally`]): the counts, the failing counts and share, the
//! least and largest values are the same numbers bit for bit (counts and comparisons); the mean and
//! the standard deviation agree to rounding (the unsharded report sums the draws in order, the
//! merge adds per-shard moments; tested to 1e-12 relative). Percentiles and the histogram do not
//! merge: an order statistic of the union is not a function of the shards' order statistics, and
//! the histogram's bins span the whole run's range, unknown to a shard. The reduced report leaves
//! them out; `--from-draws` (the rows, streamed) gives them exactly.

use crate::parts::PartError;
use crate::{DrawRow, Histogram, Limit, Named, Summary, Tally};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The `format` of every summary this version writes.
pub const SUMMARY_FORMAT: &str = "loomkin-summary/1";

/// Count, mean, sum of squared deviations, extremes and failing count of one quantity.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Moments {
    /// Values.
    pub count: u64,
    /// Their mean (0 without values).
    pub mean: f64,
    /// Σ(x − mean)² (0 without values).
    pub m2: f64,
    /// Least value (`None` without values).
    pub min: Option<f64>,
    /// Largest value.
    pub max: Option<f64>,
    /// Values failing the quantity's limit.
    pub failing: u64,
}

impl Moments {
    /// No values.
    pub const EMPTY: Self = Self { count: 0, mean: 0.0, m2: 0.0, min: None, max: None, failing: 0 };

    /// Adds one value (Welford's update), failing its limit or not.
    pub fn add(&mut self, x: f64, fails: bool) {
        self.count += 1;
        let d = x - self.mean;
        self.mean += d / self.count as f64;
        self.m2 += d * (x - self.mean);
        self.min = Some(self.min.map_or(x, |m| m.min(x)));
        self.max = Some(self.max.map_or(x, |m| m.max(x)));
        self.failing += u64::from(fails);
    }

    /// The moments of both sets of values together (Chan, Golub & LeVeque 1979): with
    /// `δ = mean_b − mean_a`, `mean = mean_a + δ·n_b/n` and `M2 = M2_a + M2_b + δ²·n_a·n_b/n`.
    pub fn merge(&self, b: &Self) -> Self {
        if b.count == 0 {
            return *self;
        }
        if self.count == 0 {
            return *b;
        }
        let (na, nb) = (self.count as f64, b.count as f64);
        let n = na + nb;
        let delta = b.mean - self.mean;
        let pick = |x: Option<f64>, y: Option<f64>, f: fn(f64, f64) -> f64| match (x, y) {
            (Some(x), Some(y)) => Some(f(x, y)),
            (x, None) => x,
            (None, y) => y,
        };
        Self {
            count: self.count + b.count,
            mean: self.mean + delta * (nb / n),
            m2: self.m2 + b.m2 + delta * delta * (na * nb / n),
            min: pick(self.min, b.min, f64::min),
            max: pick(self.max, b.max, f64::max),
            failing: self.failing + b.failing,
        }
    }

    /// Sample standard deviation (n − 1), 0 for one value, as [`Summary::sd`].
    pub fn sd(&self) -> f64 {
        if self.count > 1 { (self.m2.max(0.0) / (self.count - 1) as f64).sqrt() } else { 0.0 }
    }
}

/// One reported quantity of a summary: its name (with unit), its limit and its moments.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QuantityMoments {
    /// Name with unit, e.g. `velocity_m_s`.
    pub name: String,
    /// The limit the failing count was taken against.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub limit: Option<Limit>,
    /// The moments.
    #[serde(flatten)]
    pub moments: Moments,
}

/// The mergeable summary of some draws of a Monte-Carlo study (see the module's documentation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DrawSummary {
    /// [`SUMMARY_FORMAT`].
    pub format: String,
    /// The study's command (`pick montecarlo`).
    pub command: String,
    /// What makes the draws what they are (seed, draws, inputs, model): equal in every summary
    /// merged.
    pub facts: BTreeMap<String, String>,
    /// The ranges of draw indices summarised, `[start, end)`, in order.
    pub covers: Vec<[u64; 2]>,
    /// Draws.
    pub draws: u64,
    /// Draws the model refused.
    pub refused: u64,
    /// Draws refused or failing a limit.
    pub failing: u64,
    /// Answered draws with each yes/no flag of the per-draw table.
    pub flags: Vec<u64>,
    /// The inputs drawn with a spread (over every draw).
    pub inputs: Vec<QuantityMoments>,
    /// The results (over the answered draws).
    pub results: Vec<QuantityMoments>,
}

impl DrawSummary {
    /// The summary of `draws`, the draws `items` of a study: `inputs` and `results` name what the
    /// report shows, as [`crate::tally`] takes them.
    pub fn of<D: DrawRow>(
        command: &str,
        facts: BTreeMap<String, String>,
        items: std::ops::Range<u64>,
        draws: &[D],
        inputs: &[(String, bool)],
        results: &[(&str, Option<Limit>)],
    ) -> Self {
        let spread: Vec<usize> = inputs.iter().enumerate().filter(|(_, (_, s))| *s).map(|(k, _)| k).collect();
        let mut ins: Vec<QuantityMoments> = spread
            .iter()
            .map(|&k| QuantityMoments { name: inputs[k].0.clone(), limit: None, moments: Moments::EMPTY })
            .collect();
        let limits: Vec<Option<Limit>> = results.iter().map(|(_, l)| l.filter(Limit::is_set)).collect();
        let mut res: Vec<QuantityMoments> = results
            .iter()
            .zip(&limits)
            .map(|((name, _), l)| QuantityMoments { name: name.to_string(), limit: *l, moments: Moments::EMPTY })
            .collect();
        let mut flags = vec![0u64; D::FLAGS.len()];
        let (mut refused, mut failing) = (0u64, 0u64);
        for d in draws {
            for (q, &k) in ins.iter_mut().zip(&spread) {
                q.moments.add(d.inputs()[k], false);
            }
            match d.results() {
                None => {
                    refused += 1;
                    failing += 1;
                }
                Some(r) => {
                    let mut fails = false;
                    for ((q, l), &x) in res.iter_mut().zip(&limits).zip(r) {
                        let f = l.is_some_and(|l| l.fails(x));
                        fails |= f;
                        q.moments.add(x, f);
                    }
                    failing += u64::from(fails);
                    for (c, f) in flags.iter_mut().zip(d.flags()) {
                        *c += u64::from(f);
                    }
                }
            }
        }
        Self {
            format: SUMMARY_FORMAT.into(),
            command: command.into(),
            facts,
            covers: if items.is_empty() { Vec::new() } else { vec![[items.start, items.end]] },
            draws: draws.len() as u64,
            refused,
            failing,
            flags,
            inputs: ins,
            results: res,
        }
    }

    /// Joins the summaries of a study's shards (any order) into the summary of its `draws` draws,
    /// after checking that they are summaries of this version, of this study — its `command`, its
    /// `facts` (another seed, other distributions or another model is refused) and the quantities
    /// and limits its report shows (`inputs`, `results` as [`crate::tally`] takes them: the
    /// failing counts were taken against the limits of the run) — and that together they cover
    /// the draws `0..draws` once.
    pub fn merge(
        parts: &[DrawSummary],
        command: &str,
        facts: &BTreeMap<String, String>,
        draws: u64,
        (inputs, results): &crate::Reported,
    ) -> Result<DrawSummary, PartError> {
        let want_inputs: Vec<(String, Option<Limit>)> =
            inputs.iter().filter(|(_, s)| *s).map(|(n, _)| (n.clone(), None)).collect();
        let want_results: Vec<(String, Option<Limit>)> =
            results.iter().map(|(n, l)| (n.to_string(), l.filter(Limit::is_set))).collect();
        let bad = |m: String| Err(PartError::Input(m));
        if parts.is_empty() {
            return bad("no summaries given".into());
        }
        for (i, p) in parts.iter().enumerate() {
            let i = i + 1;
            if p.format != SUMMARY_FORMAT {
                return bad(format!("summary {i}: format '{}', this loomkin reads '{SUMMARY_FORMAT}'", p.format));
            }
            if p.command != command {
                return bad(format!("summary {i}: a summary of {}, not of {command}", p.command));
            }
            for (key, want) in facts {
                match p.facts.get(key) {
                    Some(got) if got == want => {}
                    got => {
                        return bad(format!(
                            "summary {i}: made with {key} = {}, the study has {key} = {want}: another study's summary",
                            got.map_or("(none)", String::as_str)
                        ));
                    }
                }
            }
            let names = |q: &[QuantityMoments]| q.iter().map(|q| (q.name.clone(), q.limit)).collect::<Vec<_>>();
            if names(&p.inputs) != want_inputs || names(&p.results) != want_results {
                return bad(format!(
                    "summary {i}: its quantities or limits are not the study's ([limits] changed since the shards ran?): \
                     run the shards again with this study file, or report from the draws (--from-draws)"
                ));
            }
        }
        let mut covers: Vec<[u64; 2]> = parts.iter().flat_map(|p| p.covers.iter().copied()).collect();
        covers.sort_unstable();
        let mut next = 0u64;
        for [a, b] in &covers {
            if *a > next {
                return bad(format!("draws {next}..{a} are in no summary: give every shard's summary"));
            }
            if *a < next {
                return bad(format!(
                    "draws {a}..{} are in two summaries: give each shard's summary once",
                    next.min(*b)
                ));
            }
            next = *b;
        }
        if next != draws {
            return bad(format!(
                "the summaries cover draws 0..{next}, the study has {draws}: give every shard's summary"
            ));
        }
        let join = |a: &[QuantityMoments], b: &[QuantityMoments]| -> Vec<QuantityMoments> {
            a.iter()
                .zip(b)
                .map(|(x, y)| QuantityMoments { moments: x.moments.merge(&y.moments), ..x.clone() })
                .collect()
        };
        // Joined in draw order, so the result does not depend on the order the summaries came in.
        let mut order: Vec<&DrawSummary> = parts.iter().collect();
        order.sort_by_key(|p| p.covers.first().map_or(0, |c| c[0]));
        let mut out = order[0].clone();
        for p in &order[1..] {
            out.draws += p.draws;
            out.refused += p.refused;
            out.failing += p.failing;
            for (c, f) in out.flags.iter_mut().zip(&p.flags) {
                *c += f;
            }
            out.inputs = join(&out.inputs, &p.inputs);
            out.results = join(&out.results, &p.results);
        }
        out.covers = vec![[0, draws]];
        out.facts = facts.clone();
        Ok(out)
    }

    /// The report of these draws as [`crate::tally`] makes it of the rows, without what does not
    /// merge: each quantity's `percentiles` are empty and its `histogram` has no bins (both left
    /// out of the report's JSON). A quantity without values is left out, as there.
    pub fn tally(&self) -> Tally {
        let named = |q: &QuantityMoments| {
            let m = &q.moments;
            let (Some(min), Some(max)) = (m.min, m.max) else { return None };
            Some(Named {
                name: q.name.clone(),
                summary: Summary {
                    count: m.count as usize,
                    mean: m.mean,
                    sd: m.sd(),
                    min,
                    max,
                    percentiles: Vec::new(),
                    histogram: Histogram::NONE,
                    limit: q.limit,
                    failing: m.failing as usize,
                },
            })
        };
        Tally {
            draws: self.draws,
            refused: self.refused,
            failing: self.failing,
            fail_share: if self.draws > 0 { self.failing as f64 / self.draws as f64 } else { 0.0 },
            inputs: self.inputs.iter().filter_map(named).collect(),
            results: self.results.iter().filter_map(named).collect(),
        }
    }
}

/// Reads the summaries in `inputs` (files holding one or more, one after another, as
/// `--summary` writes them and `cat` joins them; `-` is standard input).
pub fn read_summaries(inputs: &[std::path::PathBuf]) -> Result<Vec<DrawSummary>, PartError> {
    let mut out = Vec::new();
    for path in inputs {
        let text = if path.as_os_str() == "-" {
            let mut t = String::new();
            std::io::Read::read_to_string(&mut std::io::stdin().lock(), &mut t)
                .map_err(|e| PartError::Io { path: "standard input".into(), source: e })?;
            t
        } else {
            std::fs::read_to_string(path).map_err(|e| PartError::Io { path: path.display().to_string(), source: e })?
        };
        out.extend(parse_summaries(&path.display().to_string(), &text)?);
    }
    Ok(out)
}

/// The summaries in `text` (one or more JSON objects, one after another), named `name` in the
/// messages.
pub fn parse_summaries(name: &str, text: &str) -> Result<Vec<DrawSummary>, PartError> {
    let out = serde_json::Deserializer::from_str(text)
        .into_iter::<DrawSummary>()
        .enumerate()
        .map(|(k, v)| {
            v.map_err(|e| PartError::Input(format!("{name}: summary {}: not a loomkin summary ({e})", k + 1)))
        })
        .collect::<Result<Vec<_>, _>>()?;
    if out.is_empty() {
        return Err(PartError::Input(format!("{name}: no summary in it")));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::draws::tests::{D, draw};
    use crate::tally;
    use loomkin_units::Shard;
    use proptest::prelude::*;

    fn rel(a: f64, b: f64) -> f64 {
        if a == b { 0.0 } else { (a - b).abs() / a.abs().max(b.abs()) }
    }

    const PS: [f64; 3] = [0.0, 50.0, 100.0];

    fn plan() -> crate::Reported {
        (
            vec![("a".to_string(), true), ("b".to_string(), false)],
            vec![("x", Some(Limit { min: Some(-150.0), max: Some(400.0) })), ("y", None)],
        )
    }

    fn facts() -> BTreeMap<String, String> {
        BTreeMap::from([("seed".to_string(), "7".to_string())])
    }

    fn summaries(draws: &[D], n: u32) -> Vec<DrawSummary> {
        let (inputs, results) = plan();
        (1..=n)
            .map(|i| {
                let r = Shard { index: i, count: n }.items(draws.len());
                DrawSummary::of("test", facts(), r.start as u64..r.end as u64, &draws[r], &inputs, &results)
            })
            .collect()
    }

    /// The reduced report against the report of the rows: counts, failing, extremes and limits
    /// bit for bit, mean and sd to 1e-12 relative, no percentiles or histogram.
    fn reduced_equals_rows(draws: &[D], n: u32) -> std::result::Result<(), TestCaseError> {
        let (inputs, results) = plan();
        let mut parts = summaries(draws, n);
        let reported = (inputs.clone(), results.clone());
        let in_order = DrawSummary::merge(&parts, "test", &facts(), draws.len() as u64, &reported).unwrap();
        parts.reverse(); // any order gives the same numbers
        let merged = DrawSummary::merge(&parts, "test", &facts(), draws.len() as u64, &reported).unwrap();
        prop_assert_eq!(&merged, &in_order);
        let got = merged.tally();
        let want = tally(draws, &PS, 4, &inputs, &results);
        prop_assert_eq!((got.draws, got.refused, got.failing), (want.draws, want.refused, want.failing));
        prop_assert_eq!(got.fail_share.to_bits(), want.fail_share.to_bits());
        for (g, w) in got.inputs.iter().chain(&got.results).zip(want.inputs.iter().chain(&want.results)) {
            let (g, w) = (&g.summary, &w.summary);
            prop_assert_eq!(
                (g.count, g.min.to_bits(), g.max.to_bits(), g.failing),
                (w.count, w.min.to_bits(), w.max.to_bits(), w.failing)
            );
            prop_assert_eq!(g.limit, w.limit);
            prop_assert!(rel(g.mean, w.mean) <= 1e-12, "mean {} vs {}", g.mean, w.mean);
            prop_assert!(rel(g.sd, w.sd) <= 1e-12, "sd {} vs {}", g.sd, w.sd);
            prop_assert!(g.percentiles.is_empty() && g.histogram.counts.is_empty());
        }
        prop_assert_eq!(got.inputs.len() + got.results.len(), want.inputs.len() + want.results.len());
        let odd = draws.iter().filter(|d| d.results.is_some() && d.flag).count() as u64;
        prop_assert_eq!(merged.flags, vec![odd]);
        Ok(())
    }

    #[test]
    fn shards_reduce_to_the_report_of_the_rows() {
        // Values of magnitude 1e3 around an offset of 1e6: the sums of squares are where the
        // order of additions shows.
        let draws: Vec<D> =
            (0..11).map(|i| draw(i, 1e6 + crate::uniform(3, i, 0) * 1e3, (i as f64 - 5.0) * 37.5, i == 4)).collect();
        for n in [1, 2, 3, 7, 15] {
            reduced_equals_rows(&draws, n).unwrap();
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(60))]
        #[test]
        fn any_cut_reduces_to_the_report_of_the_rows(
            v in prop::collection::vec((-1e3f64..1e3, any::<bool>()), 1..80),
            offset in prop_oneof![Just(0.0), Just(1e4), Just(-3e5)],
            n in 1u32..12,
        ) {
            let draws: Vec<D> =
                v.iter().enumerate().map(|(i, &(x, r))| draw(i as u64, offset + x.round(), offset + x, r && i > 0)).collect();
            reduced_equals_rows(&draws, n)?;
        }

        /// Chan's merge against Welford over the whole, and both against the two-pass moments.
        #[test]
        fn moments_merge_as_one_pass(v in prop::collection::vec(-1e6f64..1e6, 2..200), cut in 0usize..200) {
            let cut = cut.min(v.len());
            let one = |xs: &[f64]| {
                let mut m = Moments::EMPTY;
                for &x in xs {
                    m.add(x, x > 0.0);
                }
                m
            };
            let (all, merged) = (one(&v), one(&v[..cut]).merge(&one(&v[cut..])));
            prop_assert_eq!((merged.count, merged.min, merged.max, merged.failing), (all.count, all.min, all.max, all.failing));
            let mean = v.iter().sum::<f64>() / v.len() as f64;
            let m2: f64 = v.iter().map(|x| (x - mean) * (x - mean)).sum();
            let scale = v.iter().map(|x| x.abs()).fold(0.0, f64::max);
            prop_assert!((merged.mean - mean).abs() <= 1e-12 * scale);
            prop_assert!((merged.m2 - m2).abs() <= 1e-10 * m2.max(scale * scale * 1e-6));
        }
    }

    #[test]
    fn merges_refuse_what_is_not_one_run_of_this_study() {
        let (inputs, results) = plan();
        let draws: Vec<D> = (0..11).map(|i| draw(i, i as f64, i as f64, false)).collect();
        let parts = summaries(&draws, 3);
        let e = |p: &[DrawSummary], f: &BTreeMap<String, String>, r: &[(&'static str, Option<Limit>)]| {
            DrawSummary::merge(p, "test", f, 11, &(inputs.clone(), r.to_vec())).unwrap_err().to_string()
        };
        assert_eq!(e(&parts[1..], &facts(), &results), "draws 0..3 are in no summary: give every shard's summary");
        let twice = [parts.clone(), vec![parts[1].clone()]].concat();
        assert_eq!(e(&twice, &facts(), &results), "draws 3..7 are in two summaries: give each shard's summary once");
        assert!(e(&parts[..2], &facts(), &results).starts_with("the summaries cover draws 0..7, the study has 11"));
        let other = BTreeMap::from([("seed".to_string(), "8".to_string())]);
        assert!(e(&parts, &other, &results).contains("made with seed = 7, the study has seed = 8"));
        let looser = [("x", Some(Limit { min: None, max: Some(400.0) })), ("y", None)];
        assert!(e(&parts, &facts(), &looser).contains("[limits] changed since the shards ran?"));
        assert_eq!(
            DrawSummary::merge(&[], "test", &facts(), 11, &(inputs.clone(), results.clone())).unwrap_err().to_string(),
            "no summaries given"
        );
        // A summary survives its JSON (what the CLI writes and reads back) bit for bit.
        let text: String = parts.iter().map(|p| serde_json::to_string(p).unwrap() + "\n").collect();
        let back: Vec<DrawSummary> =
            serde_json::Deserializer::from_str(&text).into_iter().collect::<std::result::Result<_, _>>().unwrap();
        assert_eq!(back, parts);
    }
}
