//! The maximum of a function known by its values only: a grid's local maxima, each refined.

use crate::{Max, golden_max, golden_max_from};

/// The largest value of `f` on `[lo, hi]` and where it is: `f` on a grid of `n` intervals (at
/// least 2), then every local maximum of the grid (the ends included) refined by golden-section
/// search ([`golden_max_from`]) in its two neighbouring intervals. So the result is the
/// function's maximum, not the grid's, whenever each peak is resolved by the grid (one peak per
/// bracket); a finer grid only finds the same peaks.
///
/// A plateau of equal grid values is refined once, from its first point: on a flat stretch (a
/// narrow band, where neighbouring values round to the same number) every point is a local
/// maximum, and each search costs dozens of evaluations.
pub fn scan_max(lo: f64, hi: f64, n: usize, f: impl Fn(f64) -> f64) -> Max {
    let n = n.max(2);
    let x = |j: usize| grid_node(lo, hi, n, j);
    let v: Vec<f64> = (0..=n).map(|j| f(x(j))).collect();
    let mut best = Max { at: lo, value: f64::NEG_INFINITY };
    for peak in grid_peaks(&v) {
        let j = peak.index;
        let (a, b) = (x(j.saturating_sub(1)), x((j + 1).min(n)));
        let m = golden_max_from(&f, a, b, (x(j), v[j]));
        if m.value > best.value {
            best = m;
        }
    }
    best
}

/// Node `j` of the grid of `n` equal intervals on `[lo, hi]` that [`scan_max`] samples: the last
/// node is `hi` itself.
pub fn grid_node(lo: f64, hi: f64, n: usize, j: usize) -> f64 {
    if j == n { hi } else { lo + (hi - lo) * j as f64 / n as f64 }
}

/// A local maximum of a grid's values ([`grid_peaks`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridPeak {
    /// Its node.
    pub index: usize,
    /// How high the function may rise between its neighbours: through three points a parabola's
    /// vertex exceeds the middle value `b` by at most `(b − min(a, c))/8`; the reach allows four
    /// times that, `b + (b − min(a, c))/2`, for functions that are not parabolas at the grid's
    /// scale (at an end, the one neighbour stands for both). A peak whose reach is below a value
    /// already found need not be refined.
    pub reach: f64,
}

/// The local maxima of a grid's values (the ends included, against their one neighbour) that
/// [`scan_max`] refines, in order: a plateau of equal values counts once, at its first node.
pub fn grid_peaks(v: &[f64]) -> impl Iterator<Item = GridPeak> + '_ {
    (0..v.len()).filter_map(move |j| {
        let left = if j > 0 { v[j - 1] } else { f64::NEG_INFINITY };
        let right = v.get(j + 1).copied().unwrap_or(f64::NEG_INFINITY);
        let on_plateau = j > 0 && v[j] == left;
        (v[j] >= left && v[j] >= right && !on_plateau).then(|| {
            let low = match (j > 0, j + 1 < v.len()) {
                (true, true) => left.min(right),
                (true, false) => left,
                (false, true) => right,
                (false, false) => v[j],
            };
            GridPeak { index: j, reach: v[j] + 0.5 * (v[j] - low) }
        })
    })
}

/// The block [`PeriodicScan::extend_from_slice`] passes over at once when it cannot hold a candidate.
const SKIP_BLOCK: usize = 32;

/// How many of a periodic grid's local maxima [`periodic_scan_max`] refines at most.
const PERIODIC_CANDIDATES: usize = 4;

/// The largest value of a periodic `f`, known on `n` intervals of one period, and where it is (in
/// `[node(0), period)`): `node(k)` rises from 0 to the period (`node(n)` is the period, the nodes
/// need not be evenly spaced), `value(k) = f(node(k))` for `k < n` (functions of the index, so a
/// long grid is read where it lies, not copied).
///
/// The grid's local maxima (neighbours taken across the period's end) that could reach the grid's
/// best are each refined by golden-section search on the two intervals beside them. Whether a
/// grid maximum `b` between `a` and `c` could: through three points a parabola's vertex exceeds
/// `b` by at most `(b − min(a, c))/8`; a margin of four times that, `(b − min(a, c))/2`, is allowed
/// for functions that are not parabolas at the grid's scale. Of those, the
/// four highest are refined (a flat stretch makes every point a local maximum:
/// the first few suffice). The result is the best of the grid and the refinements, so never below
/// the grid's best.
///
/// # Panics
/// When `n < 2`.
pub fn periodic_scan_max(
    n: usize,
    node: impl Fn(usize) -> f64,
    value: impl Fn(usize) -> f64,
    f: impl Fn(f64) -> f64,
) -> Max {
    assert!(n >= 2, "a periodic grid needs two intervals");
    let mut scan = PeriodicScan::new(value(n - 1), value(0));
    scan.extend((1..n).map(&value));
    scan.finish(n, node, f)
}

/// [`periodic_scan_max`] fed its grid's values in order, a stretch at a time, so that a long grid
/// need never be held whole (`loomkin drive inertia` over a 10⁴-pick repeat): give the last and
/// the first value to [`PeriodicScan::new`], then `value(1)`, `value(2)`, … `value(n − 1)` to
/// [`PeriodicScan::extend`] (in as many calls as suits), then [`PeriodicScan::finish`]. The
/// result is [`periodic_scan_max`]'s, bit for bit (that function is this one).
#[derive(Debug, Clone)]
pub struct PeriodicScan {
    /// The running best local maximum.
    top: f64,
    /// `(index, value, reach)` of the local maxima that may yet be refined, highest value first.
    cands: Vec<(usize, f64, f64)>,
    /// The two latest values, `b` at index `k`.
    a: f64,
    b: f64,
    k: usize,
    first: f64,
}

impl PeriodicScan {
    /// A scan of a periodic grid whose last value (index `n − 1`) is `last` and first (index 0) is
    /// `first`.
    pub fn new(last: f64, first: f64) -> Self {
        Self { top: f64::NEG_INFINITY, cands: Vec::new(), a: last, b: first, k: 0, first }
    }

    /// The grid's next values, in order from index 1.
    #[inline]
    pub fn extend(&mut self, values: impl IntoIterator<Item = f64>) {
        // One pass over the grid (a long grid is read once): the running best local maximum `top`
        // and the local maxima that may yet be refined, in the order of a stable sort by value
        // (highest first, ties by index). A peak whose reach falls below the running top never could
        // (the top only rises); one with PERIODIC_CANDIDATES peaks ranked above it that reach at least
        // as far never will be among the first PERIODIC_CANDIDATES (whenever it reaches the final top,
        // so do they). So the list stays short even where a flat stretch makes every point a peak, and the
        // candidates are those of collecting every peak, sorting, keeping those that reach the top and
        // taking the first PERIODIC_CANDIDATES.
        let (mut a, mut b, mut k) = (self.a, self.b, self.k);
        for c in values {
            if b >= a && b >= c {
                self.peak(k, a, b, c);
            }
            (a, b) = (b, c);
            k += 1;
        }
        (self.a, self.b, self.k) = (a, b, k);
    }

    /// [`PeriodicScan::extend`] from a slice, passing over a block of it at once where no point of
    /// the block could be a candidate: every reach `b + (b − min(a, c))/2` is at most
    /// `M + (M − m)/2` (`M`, `m` the block's extremes with its two neighbours before; rounding is
    /// monotone), and one below the running top changes nothing. The scan's result is
    /// [`PeriodicScan::extend`]'s.
    pub fn extend_from_slice(&mut self, values: &[f64]) {
        for block in values.chunks(SKIP_BLOCK) {
            // Extremes in four independent lanes (a chain of comparisons is the loop's latency).
            let (mut hi, mut lo) = ([self.a.max(self.b); 4], [self.a.min(self.b); 4]);
            let quads = block.chunks_exact(4);
            for &v in quads.remainder() {
                hi[0] = if v > hi[0] { v } else { hi[0] };
                lo[0] = if v < lo[0] { v } else { lo[0] };
            }
            for q in quads {
                for l in 0..4 {
                    hi[l] = if q[l] > hi[l] { q[l] } else { hi[l] };
                    lo[l] = if q[l] < lo[l] { q[l] } else { lo[l] };
                }
            }
            let big = hi.iter().fold(hi[0], |m, &v| if v > m { v } else { m });
            let small = lo.iter().fold(lo[0], |m, &v| if v < m { v } else { m });
            if big + 0.5 * (big - small) < self.top {
                self.a = if block.len() >= 2 { block[block.len() - 2] } else { self.b };
                self.b = block[block.len() - 1];
                self.k += block.len();
            } else {
                self.extend(block.iter().copied());
            }
        }
    }

    /// Grid point `k` of value `b` between `a` and `c` is a local maximum.
    #[cold]
    fn peak(&mut self, k: usize, a: f64, b: f64, c: f64) {
        let cands = &mut self.cands;
        if b.total_cmp(&self.top).is_gt() {
            self.top = b;
            cands.retain(|e| e.2 >= b);
        }
        let top = self.top;
        let reach = b + 0.5 * (b - a.min(c)); // as GridPeak::reach, across the period's end
        let outranked = cands.iter().filter(|e| e.1.total_cmp(&b).is_ge() && e.2 >= reach).count();
        if reach >= top && outranked < PERIODIC_CANDIDATES {
            let at = cands.iter().position(|e| e.1.total_cmp(&b).is_lt()).unwrap_or(cands.len());
            cands.insert(at, (k, b, reach));
            if cands.len() > 4 * PERIODIC_CANDIDATES {
                let keep: Vec<bool> = (0..cands.len())
                    .map(|i| cands[..i].iter().filter(|e| e.2 >= cands[i].2).count() < PERIODIC_CANDIDATES)
                    .collect();
                let mut i = 0;
                cands.retain(|_| {
                    i += 1;
                    keep[i - 1]
                });
            }
        }
    }

    /// The maximum of `f` over the period: the candidates refined by golden-section search on the
    /// grid of `n` intervals (`n − 1` values were given after the first; `node` as
    /// [`periodic_scan_max`]'s).
    ///
    /// # Panics
    /// When `n < 2` or the values given do not number `n − 1`.
    pub fn finish(mut self, n: usize, node: impl Fn(usize) -> f64, f: impl Fn(f64) -> f64) -> Max {
        assert!(n >= 2, "a periodic grid needs two intervals");
        assert_eq!(self.k + 1, n, "a periodic scan of {n} intervals takes {} values after the first", n - 1);
        let first = self.first;
        self.extend(std::iter::once(first));
        let top = self.top;
        let period = node(n);
        let mut best = Max { at: node(0), value: f64::NEG_INFINITY };
        for &(k, v, _) in self.cands.iter().filter(|e| e.2 >= top).take(PERIODIC_CANDIDATES) {
            if v > best.value {
                best = Max { at: node(k), value: v };
            }
            let a = if k == 0 { node(n - 1) - period } else { node(k - 1) };
            let m = golden_max(&f, a, node(k + 1));
            if m.value > best.value {
                best = Max { at: m.at.rem_euclid(period), value: m.value };
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_narrow_band_far_from_zero_ends() {
        // ±0.2 % around 300: the grid's intervals are 3e-2 wide, 1e-12 of that is below an ulp of 300.
        let m = scan_max(299.4, 300.6, 40, |x| -(x - 300.1).powi(2));
        assert!((m.at - 300.1).abs() < 1e-6 && m.value <= 0.0, "{m:?}");
    }

    #[test]
    fn a_flat_band_is_refined_once() {
        // Every grid point of a constant is a local maximum; one search, not 41.
        let calls = std::cell::Cell::new(0);
        let m = scan_max(1.0, 2.0, 40, |_| {
            calls.set(calls.get() + 1);
            3.0
        });
        assert_eq!((m.value, m.at), (3.0, 1.0));
        assert!(calls.get() < 41 + 80, "{} evaluations", calls.get());
    }

    #[test]
    fn the_higher_of_two_peaks_between_grid_points() {
        let f = |x: f64| (-(x - 1.0).powi(2) * 50.0).exp() + 2.0 * (-(x - 2.37).powi(2) * 50.0).exp();
        for n in [7usize, 13, 40, 1000] {
            let m = scan_max(0.0, 3.0, n, f);
            assert!((m.value - 2.0).abs() < 1e-12 && (m.at - 2.37).abs() < 1e-6, "n = {n}: {m:?}");
        }
    }

    #[test]
    fn a_periodic_peak_across_the_end_and_between_uneven_nodes() {
        // cos(x − c) on [0, 2π): the peak at c, also just before the period's end (found from
        // the grid's wrap), on uneven nodes.
        let period = std::f64::consts::TAU;
        for c in [0.3, 2.0, period - 1e-3, 1e-3] {
            let f = |x: f64| (x - c).cos();
            let mut nodes: Vec<f64> = (0..=24).map(|k| period * k as f64 / 24.0).collect();
            nodes.insert(5, 0.5 * (nodes[4] + nodes[5]));
            let values: Vec<f64> = nodes.iter().map(|&x| f(x)).collect();
            let m = periodic_scan_max(nodes.len() - 1, |k| nodes[k], |k| values[k], f);
            let d = (m.at - c).rem_euclid(period);
            assert!(d.min(period - d) < 1e-7 && (m.value - 1.0).abs() < 1e-14, "c = {c}: {m:?}");
        }
    }

    #[test]
    fn a_periodic_scan_is_never_below_the_grid_and_finds_the_higher_of_two_peaks() {
        let period = 360.0;
        let f = |x: f64| (-(x - 100.3_f64).powi(2) / 8.0).exp() + 1.5 * (-(x - 271.7_f64).powi(2) / 8.0).exp();
        for n in [90usize, 360, 3600] {
            let nodes: Vec<f64> = (0..=n).map(|k| period * k as f64 / n as f64).collect();
            let values: Vec<f64> = nodes.iter().map(|&x| f(x)).collect();
            let m = periodic_scan_max(nodes.len() - 1, |k| nodes[k], |k| values[k], f);
            let grid_best = values[..n].iter().copied().fold(f64::NEG_INFINITY, f64::max);
            assert!(m.value >= grid_best, "n = {n}");
            assert!((m.at - 271.7).abs() < 1e-5 && (m.value - 1.5).abs() < 1e-12, "n = {n}: {m:?}");
        }
    }
}

#[cfg(test)]
mod one_pass {
    use super::*;
    use proptest::prelude::*;

    /// The candidates as they were chosen before the one-pass scan: every local maximum collected,
    /// stably sorted by value (highest first), those that can reach the top kept, the first few.
    fn candidates_by_sorting(v: &[f64]) -> Vec<usize> {
        let n = v.len();
        let prev = |k: usize| if k == 0 { n - 1 } else { k - 1 };
        let next = |k: usize| if k + 1 == n { 0 } else { k + 1 };
        let reach = |k: usize| v[k] + 0.5 * (v[k] - v[prev(k)].min(v[next(k)]));
        let mut idx: Vec<usize> = (0..n).filter(|&k| v[k] >= v[prev(k)] && v[k] >= v[next(k)]).collect();
        idx.sort_by(|a, b| v[*b].total_cmp(&v[*a]));
        let top = idx.first().map_or(f64::NEG_INFINITY, |&k| v[k]);
        idx.retain(|&k| reach(k) >= top);
        idx.truncate(PERIODIC_CANDIDATES);
        idx
    }

    /// The grid points the one-pass scan refines: the ends of its golden-section brackets.
    fn candidates_one_pass(v: &[f64]) -> Vec<usize> {
        let n = v.len();
        let seen = std::cell::RefCell::new(Vec::new());
        periodic_scan_max(
            n,
            |k| k as f64,
            |k| v[k],
            |x| {
                seen.borrow_mut().push(x);
                0.0
            },
        );
        // Each golden search starts from its bracket [k − 1, k + 1]; its first two probes lie
        // inside it, symmetric about k: k is their mean.
        let s = seen.into_inner();
        let mut out = Vec::new();
        let mut i = 0;
        while i + 1 < s.len() {
            let k = (0.5 * (s[i] + s[i + 1])).round().rem_euclid(n as f64) as usize;
            out.push(k);
            // Skip the rest of this search: until a probe jumps to another bracket.
            let mut j = i + 2;
            while j < s.len() && (s[j] - k as f64).abs() <= 1.0 + 1e-9 {
                j += 1;
            }
            i = j;
        }
        out
    }

    proptest! {
        /// Grids of a few levels (flat stretches, ties, plateaus) and of random values: the same
        /// candidates, in the same order, as collecting and sorting every peak.
        #[test]
        fn the_same_candidates_as_sorting(v in prop::collection::vec(0u8..4, 3..200), w in prop::collection::vec(-1e3f64..1e3, 3..200)) {
            for grid in [v.iter().map(|x| f64::from(*x)).collect::<Vec<f64>>(), w] {
                prop_assert_eq!(candidates_one_pass(&grid), candidates_by_sorting(&grid), "{:?}", grid);
            }
        }

        /// The scan fed its grid in pieces (as a long grid is streamed) is the scan fed it whole.
        #[test]
        fn pieces_give_the_whole_grids_maximum(v in prop::collection::vec(0u8..4, 3..200), cuts in prop::collection::vec(1usize..40, 1..20), wave in 0.0f64..20.0) {
            // Levels on a wave: with a wave, whole stretches lie below the top and are passed over.
            let grid: Vec<f64> = v.iter().enumerate().map(|(k, x)| f64::from(*x) + wave * (k as f64 * 0.2).sin()).collect();
            let n = grid.len();
            // Every probe of the refinements recorded: the same candidates, searched in the same order.
            let probes = std::cell::RefCell::new(Vec::new());
            let f = |x: f64| {
                probes.borrow_mut().push(x.to_bits());
                grid[(x.round() as usize) % n] + 0.01 * (x - x.round())
            };
            let whole = periodic_scan_max(n, |k| k as f64, |k| grid[k], f);
            let whole_probes = probes.replace(Vec::new());
            let mut scan = PeriodicScan::new(grid[n - 1], grid[0]);
            let mut at = 1;
            for (i, c) in cuts.iter().cycle().enumerate() {
                let to = (at + c).min(n);
                if i % 2 == 0 {
                    scan.extend_from_slice(&grid[at..to]);
                } else {
                    scan.extend(grid[at..to].iter().copied());
                }
                at = to;
                if at == n {
                    break;
                }
            }
            let pieces = scan.finish(n, |k| k as f64, f);
            prop_assert_eq!(whole_probes, probes.into_inner());
            prop_assert_eq!((whole.at.to_bits(), whole.value.to_bits()), (pieces.at.to_bits(), pieces.value.to_bits()));
        }
    }
}
