//! Non-dominated sorting and Pareto fronts.
//!
//! Point `p` dominates `q` when it is at least as good in every objective and strictly better in
//! one. Points with a non-finite objective are never on a front (they rank last).

use crate::{Result, StudyError};
use serde::{Deserialize, Serialize};
use std::cmp::Ordering;

/// Whether an objective is to be made small or large.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Sense {
    /// Smaller is better.
    Minimize,
    /// Larger is better.
    Maximize,
}

impl Sense {
    /// The value as a cost (smaller is better).
    #[inline]
    pub fn cost(self, value: f64) -> f64 {
        match self {
            Sense::Minimize => value,
            Sense::Maximize => -value,
        }
    }
}

/// Whether `a` dominates `b` under `senses` (all three slices of equal length).
pub fn dominates(a: &[f64], b: &[f64], senses: &[Sense]) -> bool {
    let mut strictly = false;
    for ((&x, &y), &s) in a.iter().zip(b).zip(senses) {
        let (x, y) = (s.cost(x), s.cost(y));
        // A NaN compares as neither smaller nor equal: such a point dominates nothing.
        if x.partial_cmp(&y).is_none_or(|o| o == Ordering::Greater) {
            return false;
        }
        strictly |= x < y;
    }
    strictly
}

fn costs<P: AsRef<[f64]>>(points: &[P], senses: &[Sense]) -> Result<Vec<f64>> {
    let m = senses.len();
    let mut c = Vec::with_capacity(points.len() * m);
    for (i, p) in points.iter().enumerate() {
        let p = p.as_ref();
        if p.len() != m {
            return Err(StudyError::Shape { field: format!("points[{i}]"), expected: m, found: p.len() });
        }
        c.extend(p.iter().zip(senses).map(|(&v, &s)| s.cost(v)));
    }
    Ok(c)
}

/// Indices of the non-dominated points (the first Pareto front), in increasing order of the first
/// objective's cost (ties broken by the following objectives).
///
/// Points are sorted lexicographically by cost, so a dominating point always comes first; each
/// point is then compared with the front found so far. Two objectives take an `O(n log n)` sweep.
/// Equal points do not dominate each other: duplicates on the front are all kept.
pub fn pareto_front<P: AsRef<[f64]>>(points: &[P], senses: &[Sense]) -> Result<Vec<usize>> {
    if let [s1, s2] = *senses {
        // Straight to contiguous keys, without a cost matrix.
        let mut keys = Vec::with_capacity(points.len());
        for (i, p) in points.iter().enumerate() {
            match *p.as_ref() {
                [a, b] => keys.push((s1.cost(a), s2.cost(b), i)),
                ref other => {
                    return Err(StudyError::Shape { field: format!("points[{i}]"), expected: 2, found: other.len() });
                }
            }
        }
        return Ok(front_of_keys(keys));
    }
    let all: Vec<usize> = (0..points.len()).collect();
    let c = costs(points, senses)?;
    Ok(front_of(&c, senses.len(), &all))
}

fn front_of(c: &[f64], m: usize, idx: &[usize]) -> Vec<usize> {
    if m == 2 {
        return front_of_two(c, idx);
    }
    let row = |i: usize| &c[i * m..(i + 1) * m];
    let mut order: Vec<usize> = idx.iter().copied().filter(|&i| row(i).iter().all(|v| v.is_finite())).collect();
    order.sort_by(|&a, &b| {
        row(a)
            .iter()
            .zip(row(b))
            .map(|(x, y)| x.total_cmp(y))
            .find(|o| *o != Ordering::Equal)
            .unwrap_or(Ordering::Equal)
    });
    let mut front: Vec<usize> = Vec::new();
    for i in order {
        let dominated = front.iter().any(|&f| {
            let (a, b) = (row(f), row(i));
            a.iter().zip(b).all(|(x, y)| x <= y) && a.iter().zip(b).any(|(x, y)| x < y)
        });
        if !dominated {
            front.push(i);
        }
    }
    front
}

/// The front of two-objective costs `c` (pairs) over the points `idx`, in the order of
/// [`pareto_front`].
///
/// A bucket pre-filter drops most dominated points in two linear passes: the finite points are
/// bucketed by their first cost (a monotone map, so a lower bucket means a strictly smaller first
/// cost), and a point whose second cost is not below the least second cost of all lower buckets is
/// dominated. Only the survivors, kept as contiguous `(c1, c2, index)` keys, are sorted
/// lexicographically (index last, so the order is that of a stable sort) and swept: after the sort
/// a point is dominated iff an earlier one has a smaller second cost, or the same second cost with a
/// smaller first cost; equal points are all kept.
fn front_of_two(c: &[f64], idx: &[usize]) -> Vec<usize> {
    front_of_keys(idx.iter().map(|&i| (c[2 * i], c[2 * i + 1], i)).collect())
}

/// [`front_of_two`] on `(c1, c2, index)` keys.
fn front_of_keys(mut keys: Vec<(f64, f64, usize)>) -> Vec<usize> {
    keys.retain(|(a, b, _)| a.is_finite() && b.is_finite());
    if keys.len() > 256 {
        let (lo, hi) = keys.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), k| (l.min(k.0), h.max(k.0)));
        let buckets = (keys.len() / 16).clamp(1, 1 << 16);
        let scale = buckets as f64 / (hi - lo);
        let scale = if scale.is_finite() { scale } else { 0.0 };
        let bucket = |a: f64| (((a - lo) * scale) as usize).min(buckets - 1);
        let mut least2 = vec![f64::INFINITY; buckets];
        for k in &keys {
            let b = bucket(k.0);
            least2[b] = least2[b].min(k.1);
        }
        // least2[b] becomes the least second cost over the buckets strictly below b.
        let mut running = f64::INFINITY;
        for v in &mut least2 {
            (running, *v) = (running.min(*v), running);
        }
        keys.retain(|k| k.1 < least2[bucket(k.0)]);
    }
    keys.sort_unstable_by(|x, y| x.0.total_cmp(&y.0).then(x.1.total_cmp(&y.1)).then(x.2.cmp(&y.2)));
    let mut front = Vec::new();
    let (mut best2, mut best1) = (f64::INFINITY, f64::INFINITY);
    for (c1, c2, i) in keys {
        if c2 < best2 {
            front.push(i);
            (best2, best1) = (c2, c1);
        } else if c2 == best2 && c1 == best1 {
            front.push(i);
        }
    }
    front
}

/// Non-dominated sorting: the rank of every point (0 = on the Pareto front, 1 = on the front of
/// what remains without rank 0, …). Points with a non-finite objective get the rank after the last
/// front. Fronts are peeled one at a time, so the cost grows with the number of fronts.
pub fn non_dominated_ranks<P: AsRef<[f64]>>(points: &[P], senses: &[Sense]) -> Result<Vec<usize>> {
    let m = senses.len();
    let c = costs(points, senses)?;
    let mut rank = vec![usize::MAX; points.len()];
    let finite = |i: usize| c[i * m..(i + 1) * m].iter().all(|v| v.is_finite());
    let mut left: Vec<usize> = (0..points.len()).filter(|&i| finite(i)).collect();
    let mut r = 0;
    while !left.is_empty() {
        let front = front_of(&c, m, &left);
        for &i in &front {
            rank[i] = r;
        }
        left.retain(|&i| rank[i] == usize::MAX);
        r += 1;
    }
    for v in &mut rank {
        if *v == usize::MAX {
            *v = r;
        }
    }
    Ok(rank)
}

/// The Pareto front of two objectives over a stream of points of any length, kept as the points
/// arrive: memory grows with the front, not with the stream. The same points as [`pareto_front`]
/// of all the points (non-finite points are never on it; equal points are all kept), signed
/// zeros included: like its sweep, the first cost is ordered by [`f64::total_cmp`] and costs are
/// compared as numbers.
///
/// The front is held ordered by the first cost, where the second cost falls; a new point is
/// dominated iff the front point just before it in that order has a lower second cost, or the same
/// second cost and another first cost; the points it dominates are the run after it whose second
/// cost is not below its own (less the points equal to it). Each point costs `O(log f)` besides the
/// points it removes.
///
/// ```
/// use loomkin_study::{Sense, StreamFront};
///
/// let mut f = StreamFront::new([Sense::Maximize, Sense::Minimize]);
/// for (i, p) in [[250.0, 60.0], [195.0, 30.0], [170.0, 26.0], [175.0, 25.0], [140.0, 12.0]].into_iter().enumerate() {
///     f.push(p, i);
/// }
/// assert_eq!(f.into_items(), vec![0, 1, 3, 4]);
/// ```
#[derive(Debug, Clone)]
pub struct StreamFront<T> {
    senses: [Sense; 2],
    /// The first cost's place in the total order → the first and second costs and the points there.
    map: std::collections::BTreeMap<u64, (f64, f64, Vec<T>)>,
    len: usize,
}

impl<T> StreamFront<T> {
    /// An empty front.
    pub fn new(senses: [Sense; 2]) -> Self {
        Self { senses, map: std::collections::BTreeMap::new(), len: 0 }
    }

    /// The point's costs and key; `None` for a point never on a front (non-finite).
    fn costs(&self, point: [f64; 2]) -> Option<(f64, f64, u64)> {
        let (c1, c2) = (self.senses[0].cost(point[0]), self.senses[1].cost(point[1]));
        (c1.is_finite() && c2.is_finite()).then(|| (c1, c2, crate::stats::order_key(c1)))
    }

    /// Whether [`StreamFront::push`] would keep `point` (a caller can skip making the item of a
    /// point that is dominated, most of a large table).
    pub fn admits(&self, point: [f64; 2]) -> bool {
        let Some((c1, c2, k)) = self.costs(point) else { return false };
        match self.map.range(..=k).next_back() {
            Some((_, &(e1, e2, _))) => (e2 == c2 && e1 == c1) || e2 > c2,
            None => true,
        }
    }

    /// Offers a point: whether it is on the front of the points so far.
    pub fn push(&mut self, point: [f64; 2], item: T) -> bool {
        if !self.admits(point) {
            return false;
        }
        let Some((c1, c2, k)) = self.costs(point) else { return false };
        if let Some((e1, e2, items)) = self.map.get_mut(&k)
            && *e2 == c2
        {
            debug_assert!(*e1 == c1);
            items.push(item);
            self.len += 1;
            return true;
        }
        // The points after it (in the first cost's order) with a second cost not below its own are
        // dominated — all but those equal to it (+0 after −0).
        let doomed: Vec<u64> = self
            .map
            .range(k..)
            .take_while(|(_, (_, e2, _))| *e2 >= c2)
            .filter(|(_, (e1, e2, _))| !(*e2 == c2 && *e1 == c1))
            .map(|(&k, _)| k)
            .collect();
        for d in doomed {
            if let Some((_, _, items)) = self.map.remove(&d) {
                self.len -= items.len();
            }
        }
        self.map.insert(k, (c1, c2, vec![item]));
        self.len += 1;
        true
    }

    /// Points on the front.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the front is empty.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The points' items in increasing first cost (equal points in the order they came).
    pub fn into_items(self) -> Vec<T> {
        self.map.into_values().flat_map(|(_, _, items)| items).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Sense::*;

    #[test]
    fn small_front_by_hand() {
        // (window, accel): maximise window, minimise accel.
        let p = [[250.0, 60.0], [195.0, 30.0], [175.0, 25.0], [170.0, 26.0], [140.0, 12.0], [140.0, 13.0]];
        let f = pareto_front(&p, &[Maximize, Minimize]).unwrap();
        let mut f2 = f.clone();
        f2.sort();
        assert_eq!(f2, vec![0, 1, 2, 4]);
        let r = non_dominated_ranks(&p, &[Maximize, Minimize]).unwrap();
        assert_eq!(r, vec![0, 0, 0, 1, 0, 1]);
    }

    #[test]
    fn duplicates_and_nan() {
        let p = [[1.0, 1.0], [1.0, 1.0], [f64::NAN, 0.0], [2.0, 0.5]];
        let mut f = pareto_front(&p, &[Minimize, Minimize]).unwrap();
        f.sort();
        assert_eq!(f, vec![0, 1, 3]);
        assert_eq!(non_dominated_ranks(&p, &[Minimize, Minimize]).unwrap()[2], 1);
        assert!(pareto_front(&[vec![1.0]], &[Minimize, Minimize]).is_err());
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]
        /// The streamed front against the front of all the points at once, in any arrival order,
        /// with ties, duplicates, signed zeros and non-finite values.
        #[test]
        fn the_streamed_front_is_the_front(
            pts in proptest::collection::vec((0u8..12, 0u8..12, 0u8..40), 0..300),
            max1 in proptest::bool::ANY,
        ) {
            let p: Vec<[f64; 2]> = pts
                .iter()
                .map(|&(a, b, z)| match z {
                    0 => [f64::NAN, b as f64],
                    1 => [a as f64, f64::INFINITY],
                    2 => [-0.0, b as f64],
                    3 => [a as f64, -0.0],
                    _ => [a as f64 * 0.5, b as f64],
                })
                .collect();
            let senses = [if max1 { Maximize } else { Minimize }, Minimize];
            let mut s = StreamFront::new(senses);
            for (i, q) in p.iter().enumerate() {
                let admitted = s.admits(*q);
                proptest::prop_assert_eq!(s.push(*q, i), admitted);
            }
            proptest::prop_assert_eq!(s.len(), s.clone().into_items().len());
            let mut got = s.into_items();
            got.sort_unstable();
            let mut want = pareto_front(&p, &senses).unwrap();
            want.sort_unstable();
            proptest::prop_assert_eq!(got, want);
        }

        /// The pre-filtered sweep against the definition of dominance, pair by pair, on clouds with
        /// ties, duplicates and non-finite values (large enough to take the bucket filter).
        #[test]
        fn two_objective_front_matches_brute_force(
            pts in proptest::collection::vec((0u8..40, 0u8..40, 0u8..50), 257..700),
            max1 in proptest::bool::ANY,
        ) {
            let p: Vec<[f64; 2]> = pts
                .iter()
                .map(|&(a, b, z)| [if z == 0 { f64::NAN } else { a as f64 * 0.5 }, if z == 1 { f64::INFINITY } else { b as f64 }])
                .collect();
            let senses = [if max1 { Maximize } else { Minimize }, Minimize];
            let front = pareto_front(&p, &senses).unwrap();
            let finite = |q: &[f64; 2]| q.iter().all(|v| v.is_finite());
            let mut brute: Vec<usize> = (0..p.len())
                .filter(|&i| finite(&p[i]) && !(0..p.len()).any(|j| finite(&p[j]) && dominates(&p[j], &p[i], &senses)))
                .collect();
            let mut got = front.clone();
            got.sort_unstable();
            brute.sort_unstable();
            proptest::prop_assert_eq!(got, brute);
            // Order: increasing first cost, then second, then index.
            let key = |i: usize| (senses[0].cost(p[i][0]), p[i][1], i);
            proptest::prop_assert!(front.windows(2).all(|w| key(w[0]) < key(w[1])));
        }
    }
}
