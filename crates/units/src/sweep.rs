//! One syntax for stepped sweeps (`FROM:TO:STEP`) and for a share of one (`--shard I/N`).

use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::format::compact;
use crate::range::{Range, RangeError};

/// Why a sweep could not be read.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SweepError {
    /// Text that is not `FROM:TO:STEP` (or `I/N` for a shard).
    #[error("{field}: cannot read '{text}': expected {expected}")]
    Parse {
        /// Field (flag or key) it was given for.
        field: String,
        /// Text given (cut to 80 characters).
        text: String,
        /// What was expected.
        expected: &'static str,
    },
    /// A bound or step out of range.
    #[error(transparent)]
    Range(#[from] RangeError),
    /// A step so small the sweep would have more points than allowed.
    #[error("{field}: {} points from {} to {} by {} is more than the {max} allowed; take a larger step", compact(*.count), compact(*.from), compact(*.to), compact(*.step))]
    TooMany {
        /// Field.
        field: String,
        /// Points the sweep would have.
        count: f64,
        /// First value.
        from: f64,
        /// Last value.
        to: f64,
        /// Step.
        step: f64,
        /// Largest count allowed.
        max: u64,
    },
}

impl crate::range::FieldError for SweepError {
    fn field(&self) -> Option<&str> {
        match self {
            Self::Parse { field, .. } | Self::TooMany { field, .. } => Some(field),
            Self::Range(e) => Some(&e.field),
        }
    }
}

fn cut(text: &str) -> String {
    text.chars().take(80).collect()
}

/// The values `from, from + step, …, to`: a stepped sweep. The last value is `to` exactly when the
/// step divides the span (to 1e-9 of a step); otherwise the sweep stops at the last value before `to`.
/// Values are computed as `from + i·step` (no accumulated rounding).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Span {
    /// First value.
    pub from: f64,
    /// Last value asked for.
    pub to: f64,
    /// Step, > 0.
    pub step: f64,
}

impl Span {
    /// Most values a sweep may hold (a larger one is refused before anything is allocated).
    pub const MAX_POINTS: u64 = 100_000_000;

    /// Reads `FROM:TO:STEP` for `field`, every value checked against `range`.
    pub fn parse(field: &str, text: &str, range: Range) -> Result<Self, SweepError> {
        let bad = || SweepError::Parse { field: field.into(), text: cut(text), expected: "FROM:TO:STEP" };
        let parts: Vec<&str> = text.split(':').collect();
        let [a, b, c] = parts.as_slice() else { return Err(bad()) };
        let num = |t: &str| t.trim().parse::<f64>().map_err(|_| bad());
        Self::new(field, num(a)?, num(b)?, num(c)?, range)
    }

    /// A checked sweep: `from ≤ to`, both in `range`, `step > 0`, at most [`Span::MAX_POINTS`] values.
    pub fn new(field: &str, from: f64, to: f64, step: f64, range: Range) -> Result<Self, SweepError> {
        range.check(&format!("{field} (from)"), from)?;
        range.check(&format!("{field} (to)"), to)?;
        Range::at_least(from, range.unit).check(&format!("{field} (to)"), to)?;
        Range::above(0.0, range.unit).check(&format!("{field} (step)"), step)?;
        let count = ((to - from) / step + 1e-9).floor() + 1.0;
        if count.is_nan() || count > Self::MAX_POINTS as f64 {
            return Err(SweepError::TooMany { field: field.into(), count, from, to, step, max: Self::MAX_POINTS });
        }
        Ok(Self { from, to, step })
    }

    /// Number of values.
    pub fn count(&self) -> usize {
        (((self.to - self.from) / self.step + 1e-9).floor() as usize) + 1
    }

    /// The `i`-th value (`to` itself for the last one when the step divides the span).
    pub fn value(&self, i: usize) -> f64 {
        let v = self.from + i as f64 * self.step;
        if (v - self.to).abs() <= 1e-9 * self.step { self.to } else { v.min(self.to) }
    }

    /// All values in order.
    pub fn values(&self) -> impl ExactSizeIterator<Item = f64> + '_ {
        (0..self.count()).map(|i| self.value(i))
    }
}

/// A share of a sweep for one machine of a cluster: shard `index` (1-based) of `count`.
///
/// Shard `i` of `n` takes the contiguous block of items `⌊(i−1)·len/n⌋ .. ⌊i·len/n⌋`, so the `n`
/// outputs concatenated in order are the whole sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// 1-based index of this shard.
    pub index: u32,
    /// Number of shards.
    pub count: u32,
}

impl Shard {
    /// The whole sweep (shard 1 of 1).
    pub const WHOLE: Shard = Shard { index: 1, count: 1 };

    /// Reads `I/N` with 1 ≤ I ≤ N.
    pub fn parse(field: &str, text: &str) -> Result<Self, SweepError> {
        let bad =
            || SweepError::Parse { field: field.into(), text: cut(text), expected: "I/N with 1 ≤ I ≤ N, e.g. 3/8" };
        let (i, n) = text.split_once('/').ok_or_else(bad)?;
        let (index, count): (u32, u32) = (i.trim().parse().map_err(|_| bad())?, n.trim().parse().map_err(|_| bad())?);
        if count == 0 || index == 0 || index > count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }

    /// The items of `0..len` this shard takes.
    pub fn items(&self, len: usize) -> std::ops::Range<usize> {
        let at = |k: u32| ((k as u128 * len as u128) / self.count as u128) as usize;
        at(self.index - 1)..at(self.index)
    }

    /// Whether this is the first shard (the one that writes a table's header).
    pub fn is_first(&self) -> bool {
        self.index == 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn stepped_sweeps() {
        let r = Range::closed(0.0, 360.0, "deg");
        let s = Span::parse("motion_deg", "180:360:10", r).unwrap();
        assert_eq!(s.count(), 19);
        assert_eq!(s.values().last(), Some(360.0));
        let s = Span::parse("motion_deg", "0:1:0.1", r).unwrap();
        assert_eq!(s.count(), 11);
        assert_eq!(s.value(10), 1.0);
        assert_eq!(s.value(3), 0.30000000000000004);
        let s = Span::parse("x", "0:10:3", r).unwrap();
        assert_eq!(s.values().collect::<Vec<_>>(), vec![0.0, 3.0, 6.0, 9.0]);
        assert_eq!(Span::parse("x", "5:5:1", r).unwrap().count(), 1);
    }

    #[test]
    fn bad_sweeps_name_the_field() {
        let r = Range::closed(1.0, 360.0, "deg");
        let e = |t: &str| Span::parse("motion_deg", t, r).unwrap_err().to_string();
        assert_eq!(e("1:360"), "motion_deg: cannot read '1:360': expected FROM:TO:STEP");
        assert_eq!(e("10:5:1"), "motion_deg (to) = 5 is out of range: allowed motion_deg (to) ≥ 10 deg");
        assert_eq!(e("1:360:0"), "motion_deg (step) = 0 is out of range: allowed motion_deg (step) > 0 deg");
        assert!(e("1:360:1e-9").starts_with("motion_deg: 3.59000000001e11 points from 1 to 360 by 1e-9 is more than"));
        assert!(e("0:360:1").starts_with("motion_deg (from) = 0 is out of range"));
    }

    #[test]
    fn shards() {
        assert_eq!(Shard::parse("shard", "3/8").unwrap(), Shard { index: 3, count: 8 });
        for t in ["0/3", "4/3", "1/0", "x", "1/2/3"] {
            assert!(Shard::parse("shard", t).is_err(), "{t}");
        }
    }

    proptest! {
        #[test]
        fn shards_tile_the_sweep(len in 0usize..10_000, n in 1u32..64) {
            let mut next = 0;
            for i in 1..=n {
                let r = Shard { index: i, count: n }.items(len);
                prop_assert_eq!(r.start, next);
                next = r.end;
            }
            prop_assert_eq!(next, len);
        }

        #[test]
        fn span_values_stay_inside(from in -1e3f64..1e3, width in 0f64..1e3, step in 1e-3f64..1e2) {
            let s = Span::new("x", from, from + width, step, Range::finite("")).unwrap();
            let v: Vec<f64> = s.values().collect();
            prop_assert_eq!(v.len(), s.count());
            prop_assert_eq!(v[0], from);
            prop_assert!(v.iter().all(|&x| x >= from && x <= from + width));
            prop_assert!(v.windows(2).all(|w| w[1] > w[0]));
            prop_assert!(from + width - v[v.len() - 1] < step * (1.0 + 1e-9));
        }
    }
}
