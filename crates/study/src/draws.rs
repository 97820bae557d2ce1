//! The per-draw table of a Monte-Carlo study read back and reduced to its report at any size:
//! the rows are streamed from the parts (or one concatenated file) several times, and what is held
//! is a few numbers per reported quantity, whatever the number of draws.
//!
//! The report is the one [`crate::tally`] makes from the draws in memory, bit for bit: the mean
//! and the sum of squares are summed in draw order as there; the minimum, maximum, failing counts
//! and histogram are counts; each percentile is interpolated (type 7) between the same two order
//! statistics, found exactly by narrowing passes — each pass counts the values in 4096 equal
//! slices of the interval of the total order of `f64` that still holds the wanted rank, and once
//! at most 16384 values remain in it, collects and sorts them (at most 7 passes, since each pass
//! divides a 64-bit interval by 4096; 2 to 4 in practice).

use crate::montecarlo::DrawRow;
use crate::parts::{Lines, PartError, Spool};
use crate::stats::{from_order_key as from_key, interpolate, order_key as key, percentile_rank};
use crate::{Histogram, Limit, Named, Percentile, Summary, Tally};
use std::collections::BTreeMap;
use std::path::PathBuf;

type Result<T, E = PartError> = std::result::Result<T, E>;

/// Where the draws are ([`Lines`]: the checked parts of a sharded run — a directory, part files,
/// a merged file with its manifest — or CSV files without manifests, the shards' standard
/// outputs in order), read once per pass of the reduce. Standard input is copied to a temporary
/// file first, since the reduce reads its input more than once.
pub struct DrawSource {
    lines: Lines,
    _spool: Option<Spool>,
}

impl DrawSource {
    /// The draws named by `inputs` (see [`Lines::open`]; `-` is standard input).
    pub fn open(inputs: &[PathBuf]) -> Result<Self> {
        match Lines::open(inputs)? {
            Lines::Stdin => {
                let spool = Spool::from_reader(std::io::stdin().lock())?;
                Ok(Self { lines: Lines::Files(vec![spool.path().to_path_buf()]), _spool: Some(spool) })
            }
            lines => Ok(Self { lines, _spool: None }),
        }
    }

    /// Refuses draws whose manifest names other `facts` than the study's (another seed, other
    /// distributions, another model): the report would mix two studies. Files without a
    /// manifest say nothing and pass.
    pub fn check_facts(&self, facts: &BTreeMap<String, String>) -> Result<()> {
        let Lines::Parts(set) = &self.lines else { return Ok(()) };
        let part = &set.parts()[0];
        for (key, want) in facts {
            match part.manifest.facts.get(key) {
                Some(got) if got == want => {}
                Some(got) => {
                    return Err(PartError::Input(format!(
                        "{}: these draws were made with {key} = {got}, the study has {key} = {want}: they are another study's draws",
                        part.path.display()
                    )));
                }
                None => {
                    return Err(PartError::Input(format!(
                        "{}: its manifest names no {key}: not the per-draw table of this kind of study ({})",
                        part.path.display(),
                        part.manifest.command.join(" ")
                    )));
                }
            }
        }
        Ok(())
    }

    /// Calls `row` with every draw's row, in draw order, after checking the header (`columns`),
    /// that each line is `columns.len()` finite numbers, that the draws are numbered 0, 1, … and
    /// that there are `draws` of them. `command` names the study's command in the messages.
    pub fn for_each(&self, command: &str, columns: &[String], draws: u64, mut row: impl FnMut(&[f64])) -> Result<()> {
        let want = columns.join(",");
        let width = columns.len();
        let mut next = 0u64;
        let mut v = Vec::with_capacity(width);
        let first = match &self.lines {
            Lines::Parts(set) => set.parts()[0].path.clone(),
            Lines::Files(files) => files[0].clone(),
            Lines::Stdin => PathBuf::from("standard input"),
        };
        let header = |text: &str| {
            if text == want {
                Ok(())
            } else {
                Err(PartError::Input(format!(
                    "{}: the first line is not the header of {command} --csv ({want})",
                    first.display()
                )))
            }
        };
        self.lines.for_each(header, |path, n, text| {
            let name = path.display();
            v.clear();
            for x in text.split(',') {
                let x: f64 =
                    x.trim().parse().map_err(|_| PartError::Input(format!("{name}: line {n}: not {width} numbers")))?;
                v.push(x);
            }
            if v.len() != width || v.iter().any(|x| !x.is_finite()) {
                return Err(PartError::Input(format!("{name}: line {n}: not {width} finite numbers")));
            }
            if v[0] != next as f64 {
                return Err(PartError::Input(format!(
                    "{name}: line {n}: draw {} where draw {next} belongs: concatenate every shard, in order",
                    v[0]
                )));
            }
            next += 1;
            row(&v);
            Ok(())
        })?;
        if next != draws {
            let name = match &self.lines {
                Lines::Parts(set) => set.parts()[0].path.parent().map_or_else(String::new, |p| p.display().to_string()),
                _ => first.display().to_string(),
            };
            return Err(PartError::Input(format!(
                "{name}: {next} draws where the study has {draws}: concatenate every shard's --csv output"
            )));
        }
        Ok(())
    }
}

/// The draws of per-draw tables held in memory (a Python caller's shards, each a list of named
/// columns), in order: the tables concatenated are the study's whole per-draw table. Checked as
/// [`DrawSource::for_each`] checks a file: each table's columns are [`DrawRow::columns`] in order,
/// of one length, every value finite, the draws numbered 0, 1, … across the tables, and `draws` of
/// them. [`crate::tally`] of the result is the report of the unsharded run, bit for bit (the same
/// draws in the same order). `command` names the study's command in the messages.
pub fn draws_of_tables<D: DrawRow>(command: &str, tables: &[Vec<(String, Vec<f64>)>], draws: u64) -> Result<Vec<D>> {
    let want = D::columns();
    let mut out = Vec::new();
    let mut next = 0u64;
    for (t, cols) in tables.iter().enumerate() {
        let t = t + 1;
        let names: Vec<&str> = cols.iter().map(|(n, _)| n.as_str()).collect();
        if names != want {
            return Err(PartError::Input(format!(
                "table {t}: its columns ({}) are not those of {command} --csv ({})",
                names.join(","),
                want.join(",")
            )));
        }
        let len = cols.first().map_or(0, |(_, c)| c.len());
        if let Some((name, c)) = cols.iter().find(|(_, c)| c.len() != len) {
            return Err(PartError::Input(format!(
                "table {t}: column {name} has {} rows where column draw has {len}",
                c.len()
            )));
        }
        let mut v = Vec::with_capacity(cols.len());
        for r in 0..len {
            v.clear();
            v.extend(cols.iter().map(|(_, c)| c[r]));
            if let Some(k) = v.iter().position(|x| !x.is_finite()) {
                return Err(PartError::Input(format!("table {t}, row {}: {} is {}", r + 1, want[k], v[k])));
            }
            if v[0] != next as f64 {
                return Err(PartError::Input(format!(
                    "table {t}, row {}: draw {} where draw {next} belongs: give every shard's table, in order",
                    r + 1,
                    v[0]
                )));
            }
            next += 1;
            out.push(D::from_row(&v));
        }
    }
    if next != draws {
        return Err(PartError::Input(format!(
            "{next} draws where the study has {draws}: give every shard's per-draw table, in order"
        )));
    }
    Ok(out)
}

/// Values per slice count before a pass collects them.
const COLLECT: u64 = 1 << 14;
/// Slices of the interval per counting pass.
const SLICES: u128 = 1 << 12;

/// The search for one order statistic.
struct Select {
    rank: u64,
    lo: u64,
    hi: u64,
    below: u64,
    inside: u64,
    counts: Vec<u64>,
    width: u128,
    collected: Vec<f64>,
    value: Option<f64>,
}

impl Select {
    fn new(rank: u64, min: f64, max: f64, n: u64) -> Self {
        let mut s = Self {
            rank,
            lo: key(min),
            hi: key(max),
            below: 0,
            inside: n,
            counts: Vec::new(),
            width: 0,
            collected: Vec::new(),
            value: None,
        };
        s.prepare();
        s
    }

    /// Sets up the next pass: collect when few values remain, else count in slices.
    fn prepare(&mut self) {
        if self.lo == self.hi {
            self.value = Some(from_key(self.lo));
        } else if self.inside <= COLLECT {
            self.counts = Vec::new();
            self.collected = Vec::with_capacity(self.inside as usize);
        } else {
            let span = u128::from(self.hi - self.lo) + 1;
            self.width = span.div_ceil(SLICES);
            self.counts = vec![0; span.div_ceil(self.width) as usize];
        }
    }

    fn see(&mut self, x: f64) {
        if self.value.is_some() {
            return;
        }
        let k = key(x);
        if k < self.lo || k > self.hi {
            return;
        }
        if self.counts.is_empty() {
            self.collected.push(x);
        } else {
            self.counts[(u128::from(k - self.lo) / self.width) as usize] += 1;
        }
    }

    /// After a pass: the value, or a narrower interval for the next pass.
    fn settle(&mut self) {
        if self.value.is_some() {
            return;
        }
        if self.counts.is_empty() {
            let mut v = std::mem::take(&mut self.collected);
            v.sort_unstable_by(f64::total_cmp);
            self.value = Some(v[(self.rank - self.below) as usize]);
            return;
        }
        let mut below = self.below;
        for (j, &c) in self.counts.iter().enumerate() {
            if self.rank < below + c {
                let lo = u128::from(self.lo) + j as u128 * self.width;
                self.hi = (lo + self.width - 1).min(u128::from(self.hi)) as u64;
                self.lo = lo as u64;
                self.below = below;
                self.inside = c;
                break;
            }
            below += c;
        }
        self.prepare();
    }
}

/// One reported quantity: a column of the per-draw rows.
struct Quantity {
    name: String,
    column: usize,
    /// Over the answered draws only (a result), or over every draw (an input).
    answered_only: bool,
    limit: Option<Limit>,
    n: u64,
    first: f64,
    sum: f64,
    ss: f64,
    min: f64,
    max: f64,
    failing: u64,
    histogram: Option<Histogram>,
    selects: BTreeMap<u64, Select>,
}

/// The report of the draws in `source` — the same numbers as [`crate::tally`] of them in
/// memory — with the count of each of `D::FLAGS` over the answered draws. `command` and `draws`
/// as in [`DrawSource::for_each`]; the other arguments as [`crate::tally`]'s.
pub fn tally_stream<D: DrawRow>(
    source: &DrawSource,
    command: &str,
    draws: u64,
    percentiles: &[f64],
    bins: usize,
    inputs: &[(String, bool)],
    results: &[(&str, Option<Limit>)],
) -> Result<(Tally, Vec<u64>)> {
    let columns = D::columns();
    let (n_in, n_res) = (D::input_names().len(), D::result_names().len());
    let answered_at = 1 + n_in;
    let zero: f64 = std::iter::empty::<f64>().sum();
    let quantity = |name: &str, column, answered_only, limit| Quantity {
        name: name.to_string(),
        column,
        answered_only,
        limit,
        n: 0,
        first: 0.0,
        sum: zero,
        ss: zero,
        min: f64::INFINITY,
        max: f64::NEG_INFINITY,
        failing: 0,
        histogram: None,
        selects: BTreeMap::new(),
    };
    let mut qs: Vec<Quantity> = inputs
        .iter()
        .enumerate()
        .filter(|(_, (_, spread))| *spread)
        .map(|(k, (name, _))| quantity(name, 1 + k, false, None))
        .collect();
    let n_inputs = qs.len();
    qs.extend(results.iter().enumerate().map(|(k, (name, limit))| quantity(name, 2 + n_in + k, true, *limit)));
    let flags_at = 2 + n_in + n_res;
    let mut flags = vec![0u64; D::FLAGS.len()];
    let (mut total, mut refused, mut failing) = (0u64, 0u64, 0u64);
    // Pass 1: counts, first values, sums in draw order, extremes, limits.
    source.for_each(command, &columns, draws, |v| {
        total += 1;
        let answered = v[answered_at] == 1.0;
        if !answered {
            refused += 1;
        } else {
            for (j, f) in flags.iter_mut().enumerate() {
                *f += u64::from(v[flags_at + j] == 1.0);
            }
        }
        let mut fails = !answered;
        for q in qs.iter_mut().filter(|q| answered || !q.answered_only) {
            let x = v[q.column];
            if q.n == 0 {
                q.first = x;
            }
            q.n += 1;
            q.sum += x - q.first;
            q.min = q.min.min(x);
            q.max = q.max.max(x);
            if q.limit.is_some_and(|l| l.fails(x)) {
                q.failing += 1;
                fails = true;
            }
        }
        failing += u64::from(fails);
    })?;
    let mean = |q: &Quantity| q.first + q.sum / q.n as f64;
    for q in qs.iter_mut().filter(|q| q.n > 0) {
        q.histogram = Some(Histogram::empty(q.min, q.max, bins));
        for &p in percentiles {
            let (k, frac) = percentile_rank(q.n as usize, p);
            let mut ranks = vec![k as u64];
            if frac != 0.0 && (k as u64) + 1 < q.n {
                ranks.push(k as u64 + 1);
            }
            for r in ranks {
                q.selects.entry(r).or_insert_with(|| Select::new(r, q.min, q.max, q.n));
            }
        }
    }
    let means: Vec<f64> = qs.iter().map(|q| if q.n > 0 { mean(q) } else { 0.0 }).collect();
    // Pass 2 onwards: the sums of squares and the histograms (pass 2), and the order statistics
    // until every one is found.
    let mut pass = 2;
    while pass == 2 || qs.iter().any(|q| q.selects.values().any(|s| s.value.is_none())) {
        let first_pass = pass == 2;
        source.for_each(command, &columns, draws, |v| {
            let answered = v[answered_at] == 1.0;
            for (q, &m) in qs.iter_mut().zip(&means).filter(|(q, _)| answered || !q.answered_only) {
                let x = v[q.column];
                if first_pass {
                    q.ss += (x - m) * (x - m);
                    if let Some(h) = q.histogram.as_mut() {
                        h.add(x);
                    }
                }
                for s in q.selects.values_mut() {
                    s.see(x);
                }
            }
        })?;
        for q in &mut qs {
            for s in q.selects.values_mut() {
                s.settle();
            }
        }
        pass += 1;
    }
    let summary = |q: &Quantity, m: f64| -> Option<Named> {
        let n = q.n as usize;
        let histogram = q.histogram.clone()?;
        let at = |r: usize| q.selects.get(&(r as u64)).and_then(|s| s.value).unwrap_or(m);
        let percentiles = percentiles
            .iter()
            .map(|&p| {
                let (k, frac) = percentile_rank(n, p);
                let value = if frac == 0.0 || k + 1 >= n { at(k) } else { interpolate(at(k), at(k + 1), frac) };
                Percentile { p, value }
            })
            .collect();
        let limit = q.limit.filter(Limit::is_set);
        Some(Named {
            name: q.name.clone(),
            summary: Summary {
                count: n,
                mean: m,
                sd: if n > 1 { (q.ss / (n - 1) as f64).sqrt() } else { 0.0 },
                min: q.min,
                max: q.max,
                percentiles,
                histogram,
                limit,
                failing: if limit.is_some() { q.failing as usize } else { 0 },
            },
        })
    };
    let named: Vec<Option<Named>> = qs.iter().zip(&means).map(|(q, &m)| summary(q, m)).collect();
    let (ins, res) = named.split_at(n_inputs);
    let tally = Tally {
        draws: total,
        refused,
        failing,
        fail_share: if total > 0 { failing as f64 / total as f64 } else { 0.0 },
        inputs: ins.iter().flatten().cloned().collect(),
        results: res.iter().flatten().cloned().collect(),
    };
    Ok((tally, flags))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::{Drawn, tally};
    use proptest::prelude::*;

    #[derive(Debug, Clone)]
    pub(crate) struct D {
        index: u64,
        inputs: Vec<f64>,
        pub(crate) results: Option<Vec<f64>>,
        pub(crate) flag: bool,
    }

    impl Drawn for D {
        fn inputs(&self) -> &[f64] {
            &self.inputs
        }
        fn results(&self) -> Option<&[f64]> {
            self.results.as_deref()
        }
    }

    impl DrawRow for D {
        const ANSWERED: &'static str = "ok";
        const FLAGS: &'static [&'static str] = &["odd"];
        fn input_names() -> Vec<String> {
            vec!["a".into(), "b".into()]
        }
        fn result_names() -> Vec<String> {
            vec!["x".into(), "y".into()]
        }
        fn index(&self) -> u64 {
            self.index
        }
        fn flags(&self) -> Vec<bool> {
            vec![self.flag]
        }
        fn error(&self) -> Option<&str> {
            None
        }
        fn from_parts(index: u64, inputs: &[f64], answered: Option<(&[f64], &[bool])>) -> Self {
            Self {
                index,
                inputs: inputs.to_vec(),
                results: answered.map(|a| a.0.to_vec()),
                flag: answered.is_some_and(|a| a.1[0]),
            }
        }
    }

    fn file_of(draws: &[D], name: &str) -> PathBuf {
        let mut text = D::columns().join(",") + "\n";
        for d in draws {
            let row: Vec<String> = d.row().iter().map(|x| format!("{x}")).collect();
            text += &(row.join(",") + "\n");
        }
        let path = std::env::temp_dir().join(format!("loomkin-draws-{name}-{}.csv", std::process::id()));
        std::fs::write(&path, text).unwrap();
        path
    }

    fn stream_equals_memory(draws: &[D], name: &str) {
        let path = file_of(draws, name);
        let source = DrawSource::open(std::slice::from_ref(&path)).unwrap();
        let ps = [0.0, 1.0, 12.5, 50.0, 99.0, 100.0];
        let inputs = [("a".to_string(), true), ("b".to_string(), false)];
        let limit = Some(Limit { min: Some(-1.0), max: None });
        let results = [("x", limit), ("y", None)];
        let (got, flags) = tally_stream::<D>(&source, "test", draws.len() as u64, &ps, 7, &inputs, &results).unwrap();
        let want = tally(draws, &ps, 7, &inputs, &results);
        assert_eq!(got, want);
        let odd = draws.iter().filter(|d| d.results.is_some() && d.flag).count() as u64;
        assert_eq!(flags, vec![odd]);
        std::fs::remove_file(path).unwrap();
    }

    pub(crate) fn draw(i: u64, a: f64, x: f64, refused: bool) -> D {
        D { index: i, inputs: vec![a, 2.0], results: (!refused).then(|| vec![x, -x]), flag: i % 2 == 1 }
    }

    /// More values than one pass collects, with ties and both signs of zero: the narrowing passes
    /// find the same order statistics as the selection in memory.
    #[test]
    fn large_streams_match_the_tally_in_memory() {
        let n = 3 * COLLECT + 17;
        let draws: Vec<D> = (0..n)
            .map(|i| {
                let u = crate::uniform(7, i, 0);
                let x = if i % 97 == 0 {
                    0.0
                } else if i % 89 == 0 {
                    -0.0
                } else {
                    (u - 0.5) * 1e3
                };
                draw(i, (u * 16.0).floor(), x, i % 13 == 0)
            })
            .collect();
        stream_equals_memory(&draws, "large");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(40))]
        #[test]
        fn small_streams_match_the_tally_in_memory(v in prop::collection::vec((-1e3f64..1e3, any::<bool>()), 1..60)) {
            let draws: Vec<D> = v.iter().enumerate().map(|(i, &(x, r))| draw(i as u64, x.round(), x, r && i > 0)).collect();
            stream_equals_memory(&draws, "prop");
        }
    }

    /// Tables in memory cut anywhere give back the draws bit for bit, so their tally is the
    /// unsharded report; a table missing, out of order, or of other columns is refused by name.
    #[test]
    fn tables_in_memory_are_the_draws() {
        let draws: Vec<D> = (0..11).map(|i| draw(i, i as f64 * 0.5, -(i as f64), i == 4)).collect();
        let table = |ds: &[D]| -> Vec<(String, Vec<f64>)> {
            D::columns().into_iter().enumerate().map(|(k, n)| (n, ds.iter().map(|d| d.row()[k]).collect())).collect()
        };
        let ps = [0.0, 50.0, 90.0];
        let inputs = [("a".to_string(), true), ("b".to_string(), false)];
        let results = [("x", Some(Limit { min: Some(-5.0), max: None })), ("y", None)];
        let want = tally(&draws, &ps, 4, &inputs, &results);
        for n in [1u32, 2, 3, 7, 15] {
            let tables: Vec<_> = (1..=n)
                .map(|i| table(&draws[loomkin_units::Shard { index: i, count: n }.items(draws.len())]))
                .collect();
            let back: Vec<D> = draws_of_tables("test", &tables, 11).unwrap();
            assert_eq!(tally(&back, &ps, 4, &inputs, &results), want, "N = {n}");
            let e = |t: &[Vec<(String, Vec<f64>)>]| draws_of_tables::<D>("test", t, 11).unwrap_err().to_string();
            if n > 1 {
                let k = n as usize;
                let mut swapped = tables.clone();
                swapped.swap(k - 2, k - 1);
                assert!(e(&swapped).contains(" belongs: give every shard's table, in order"), "{}", e(&swapped));
                let first = tables.iter().position(|t| !t[0].1.is_empty()).unwrap();
                let mut lost = tables.clone();
                lost.remove(first);
                assert!(e(&lost).contains("where draw 0 belongs"), "{}", e(&lost));
                assert!(
                    e(&tables[..k - 1])
                        .ends_with("where the study has 11: give every shard's per-draw table, in order")
                );
            }
        }
        let mut renamed = table(&draws);
        renamed[1].0 = "z".into();
        assert!(e_of(&[renamed]).starts_with("table 1: its columns (draw,z,b,ok"));
    }

    fn e_of(t: &[Vec<(String, Vec<f64>)>]) -> String {
        draws_of_tables::<D>("test", t, 11).unwrap_err().to_string()
    }

    #[test]
    fn keys_keep_the_total_order() {
        let xs = [f64::NEG_INFINITY, -1e300, -1.0, -f64::MIN_POSITIVE, -0.0, 0.0, 5e-324, 1.0, f64::MAX];
        for w in xs.windows(2) {
            assert!(key(w[0]) < key(w[1]), "{w:?}");
        }
        for x in xs {
            assert_eq!(from_key(key(x)).to_bits(), x.to_bits());
        }
    }
}
