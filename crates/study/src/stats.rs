//! The distribution of a result over many draws: mean, standard deviation, percentiles,
//! histogram and the share outside a stated limit.

use crate::{Result, StudyError};
use serde::{Deserialize, Serialize};

/// Percentiles reported by default (%).
pub const DEFAULT_PERCENTILES: [f64; 9] = [0.0, 1.0, 5.0, 25.0, 50.0, 75.0, 95.0, 99.0, 100.0];

/// The `p`-th percentile (0 ≤ p ≤ 100) of `values` by linear interpolation between order
/// statistics (Hyndman & Fan's type 7, numpy's default): with `h = (n − 1)·p/100`,
/// `x₍⌊h⌋₎ + (h − ⌊h⌋)·(x₍⌊h⌋+1₎ − x₍⌊h⌋₎)`. `values` is reordered (selection, O(n)); `None` when empty.
pub fn percentile(values: &mut [f64], p: f64) -> Option<f64> {
    let n = values.len();
    if n == 0 {
        return None;
    }
    let (k, frac) = percentile_rank(n, p);
    let (_, &mut lo, right) = values.select_nth_unstable_by(k, f64::total_cmp);
    if frac == 0.0 || right.is_empty() {
        return Some(lo);
    }
    let hi = right.iter().copied().min_by(f64::total_cmp).unwrap_or(lo);
    Some(interpolate(lo, hi, frac))
}

/// Where the `p`-th percentile of `n ≥ 1` values lies (type 7): the 0-based rank `k` of the order
/// statistic below it and the fraction `frac` of the way to the next (none is needed when
/// `frac = 0` or `k = n − 1`). [`percentile`] and the streamed reduce
/// ([`crate::draws::tally_stream`]) both place percentiles by it.
pub fn percentile_rank(n: usize, p: f64) -> (usize, f64) {
    let h = (n - 1) as f64 * p.clamp(0.0, 100.0) / 100.0;
    let k = (h.floor() as usize).min(n - 1);
    (k, h - k as f64)
}

/// The value `frac` of the way from the order statistic `lo` to the next one, `hi`.
pub fn interpolate(lo: f64, hi: f64, frac: f64) -> f64 {
    lo + frac * (hi - lo)
}

/// `x`'s place in the total order of `f64` ([`f64::total_cmp`]) as an unsigned key.
pub(crate) fn order_key(x: f64) -> u64 {
    let b = x.to_bits();
    if b >> 63 == 1 { !b } else { b | 1 << 63 }
}

/// The `f64` of an [`order_key`].
pub(crate) fn from_order_key(k: u64) -> f64 {
    f64::from_bits(if k >> 63 == 1 { k & !(1 << 63) } else { !k })
}

/// Equal-width bins from the smallest to the largest value.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Histogram {
    /// Bin edges, `bins + 1` of them: `edges[i] = min + i·(max − min)/bins`.
    pub edges: Vec<f64>,
    /// Values in each bin `[edges[i], edges[i+1])`, the last bin closed (with no spread every
    /// edge is the one value, and every value is in the last bin).
    pub counts: Vec<u64>,
}

impl Histogram {
    /// No histogram (a report merged from per-shard summaries, where the bins cannot be known).
    pub const NONE: Histogram = Histogram { edges: Vec::new(), counts: Vec::new() };

    /// Whether this is [`Histogram::NONE`].
    pub fn is_none(&self) -> bool {
        self.counts.is_empty()
    }

    /// The histogram of `values` in `bins ≥ 1` bins; each value lies between its bin's edges.
    pub fn of(values: &[f64], bins: usize) -> Self {
        if values.is_empty() {
            return Self { edges: vec![0.0; bins.max(1) + 1], counts: vec![0; bins.max(1)] };
        }
        let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let mut h = Self::empty(lo, hi, bins);
        for &x in values {
            h.add(x);
        }
        h
    }

    /// `bins ≥ 1` empty bins from `lo` to `hi` (the smallest and largest value to come).
    pub fn empty(lo: f64, hi: f64, bins: usize) -> Self {
        let bins = bins.max(1);
        let edge = |i: usize| if i == bins { hi } else { lo + (hi - lo) * i as f64 / bins as f64 };
        Self { edges: (0..=bins).map(edge).collect(), counts: vec![0u64; bins] }
    }

    /// Counts `x` (between the first and last edge) in its bin.
    pub fn add(&mut self, x: f64) {
        let bins = self.counts.len();
        let (lo, hi) = (self.edges[0], self.edges[bins]);
        let width = hi - lo;
        let mut i = if width > 0.0 { (((x - lo) / width) * bins as f64) as usize } else { 0 };
        i = i.min(bins - 1);
        // The scaled index may be one off where x is at an edge: settle it on the edges themselves.
        while i > 0 && x < self.edges[i] {
            i -= 1;
        }
        while i + 1 < bins && x >= self.edges[i + 1] {
            i += 1;
        }
        self.counts[i] += 1;
    }
}

/// A stated limit on a result: a draw fails below `min` or above `max`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Limit {
    /// Least acceptable value.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min: Option<f64>,
    /// Largest acceptable value.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max: Option<f64>,
}

impl Limit {
    /// Checks the bounds are finite and `min ≤ max`, naming `field`.
    pub fn check(&self, field: &str) -> Result<()> {
        for (k, v) in [("min", self.min), ("max", self.max)] {
            if let Some(x) = v
                && !x.is_finite()
            {
                return Err(StudyError::Distribution {
                    field: field.into(),
                    reason: format!("limit {k} = {x} is not a finite number"),
                });
            }
        }
        if let (Some(lo), Some(hi)) = (self.min, self.max)
            && hi < lo
        {
            return Err(StudyError::Distribution {
                field: field.into(),
                reason: format!("limit max = {hi} is below min = {lo}"),
            });
        }
        Ok(())
    }

    /// Whether `x` fails the limit.
    pub fn fails(&self, x: f64) -> bool {
        self.min.is_some_and(|m| x < m) || self.max.is_some_and(|m| x > m)
    }

    /// Whether any bound is set.
    pub fn is_set(&self) -> bool {
        self.min.is_some() || self.max.is_some()
    }
}

/// One percentile.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Percentile {
    /// Percent, 0–100.
    pub p: f64,
    /// Value.
    pub value: f64,
}

/// The distribution of one result over the draws that gave it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Draws that gave a value.
    pub count: usize,
    /// Mean `x₀ + Σ(xᵢ − x₀)/n`, summed in draw order (so independent of threads).
    pub mean: f64,
    /// Sample standard deviation (n − 1), 0 for one value.
    pub sd: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// The percentiles asked for (none in a report merged from summaries: left out of the JSON).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub percentiles: Vec<Percentile>,
    /// Equal-width histogram ([`Histogram::NONE`] in a report merged from summaries: left out).
    #[serde(skip_serializing_if = "Histogram::is_none")]
    pub histogram: Histogram,
    /// The limit, if one was stated.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limit: Option<Limit>,
    /// Values failing the limit (0 without one).
    pub failing: usize,
}

impl Summary {
    /// The summary of `values` (in draw order); `None` when there are none.
    pub fn of(values: &[f64], percentiles: &[f64], bins: usize, limit: Option<Limit>) -> Option<Self> {
        let n = values.len();
        if n == 0 {
            return None;
        }
        // Shifted by the first value: the sum of small differences loses less, and values with no
        // spread give their value exactly.
        let x0 = values[0];
        let mean = x0 + values.iter().map(|x| x - x0).sum::<f64>() / n as f64;
        let ss: f64 = values.iter().map(|x| (x - mean) * (x - mean)).sum();
        let sd = if n > 1 { (ss / (n - 1) as f64).sqrt() } else { 0.0 };
        let mut work = values.to_vec();
        let percentiles =
            percentiles.iter().map(|&p| Percentile { p, value: percentile(&mut work, p).unwrap_or(mean) }).collect();
        let limit = limit.filter(Limit::is_set);
        Some(Self {
            count: n,
            mean,
            sd,
            min: values.iter().copied().fold(f64::INFINITY, f64::min),
            max: values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            percentiles,
            histogram: Histogram::of(values, bins),
            limit,
            failing: limit.map_or(0, |l| values.iter().filter(|&&x| l.fails(x)).count()),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Brute force: sort a copy and interpolate between neighbours.
    fn sorted_percentile(values: &[f64], p: f64) -> f64 {
        let mut s = values.to_vec();
        s.sort_by(f64::total_cmp);
        let h = (s.len() - 1) as f64 * p / 100.0;
        let k = h.floor() as usize;
        if k + 1 >= s.len() { s[k] } else { s[k] + (h - k as f64) * (s[k + 1] - s[k]) }
    }

    #[test]
    fn known_percentiles() {
        // numpy.percentile([1, 2, 3, 4], [0, 25, 50, 100]) = [1, 1.75, 2.5, 4].
        let v = [4.0, 1.0, 3.0, 2.0];
        let got: Vec<f64> = [0.0, 25.0, 50.0, 100.0].iter().map(|&p| percentile(&mut v.clone(), p).unwrap()).collect();
        assert_eq!(got, vec![1.0, 1.75, 2.5, 4.0]);
        assert_eq!(percentile(&mut [], 50.0), None);
        let s =
            Summary::of(&[2.0, 2.0, 2.0], &DEFAULT_PERCENTILES, 4, Some(Limit { min: Some(2.5), max: None })).unwrap();
        assert_eq!((s.mean, s.sd, s.failing), (2.0, 0.0, 3));
        // No spread: every edge is the value, and every value is in the last (closed) bin.
        assert_eq!(s.histogram.counts, vec![0, 0, 0, 3]);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        #[test]
        fn percentiles_match_a_sorted_brute_force(v in prop::collection::vec(-1e6f64..1e6, 1..300), p in 0f64..=100.0) {
            let fast = percentile(&mut v.clone(), p).unwrap();
            prop_assert_eq!(fast, sorted_percentile(&v, p));
        }

        #[test]
        fn histogram_counts_every_value_in_its_bin(v in prop::collection::vec(-1e3f64..1e3, 1..300), bins in 1usize..40) {
            let h = Histogram::of(&v, bins);
            prop_assert_eq!(h.counts.iter().sum::<u64>() as usize, v.len());
            prop_assert_eq!(h.edges.len(), bins + 1);
            // Brute force: a value's bin is the first whose upper edge lies above it (else the last).
            let mut want = vec![0u64; bins];
            for &x in &v {
                want[(0..bins).find(|&i| x < h.edges[i + 1]).unwrap_or(bins - 1)] += 1;
            }
            prop_assert_eq!(&h.counts, &want);
            prop_assert_eq!(h.edges[0], v.iter().copied().fold(f64::INFINITY, f64::min));
            prop_assert_eq!(h.edges[bins], v.iter().copied().fold(f64::NEG_INFINITY, f64::max));
        }
    }
}
