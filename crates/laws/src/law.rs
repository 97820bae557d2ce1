//! A law: a sequence of closed-form segments covering `[0, 1]`.

use crate::{Kinematics, LawError, MotionLaw, Result, Segment, Sine};
use loomkin_units::{Field, Range};
use serde::Serialize;
use std::sync::Arc;

/// One piece of acceleration handed to [`Law::from_accel_pieces`]: a width on the `x` axis and the
/// acceleration `poly(t) + sine(t)` in the piece's local coordinate `t ∈ [0, width]`.
#[derive(Debug, Clone, PartialEq)]
pub struct AccelPiece {
    /// Width of the piece on the x axis (> 0).
    pub width: f64,
    /// Acceleration polynomial in the local coordinate, lowest power first (degree ≤ 5).
    pub poly: Vec<f64>,
    /// Optional sinusoidal term.
    pub sine: Option<Sine>,
}

impl AccelPiece {
    /// A piece of polynomial acceleration only.
    pub fn poly(width: f64, poly: &[f64]) -> Self {
        Self { width, poly: poly.to_vec(), sine: None }
    }

    /// A piece of polynomial plus sinusoid acceleration.
    pub fn with_sine(width: f64, poly: &[f64], sine: Sine) -> Self {
        Self { width, poly: poly.to_vec(), sine: Some(sine) }
    }
}

/// The pieces with their acceleration multiplied by a power of two (exact) that brings its
/// largest coefficient near 1, when that coefficient is beyond 2^±500; otherwise unchanged.
fn rescaled(pieces: &[AccelPiece]) -> std::borrow::Cow<'_, [AccelPiece]> {
    let peak = pieces
        .iter()
        .flat_map(|p| p.poly.iter().copied().chain(p.sine.map(|s| s.amp)))
        .map(f64::abs)
        .filter(|c| c.is_finite())
        .fold(0.0, f64::max);
    let e = if peak > 0.0 { peak.log2().round() as i32 } else { 0 };
    if e.abs() <= 500 {
        return std::borrow::Cow::Borrowed(pieces);
    }
    // Two factors, each representable (2^1074 is not, for a peak of 5e-324).
    let (f1, f2) = (2f64.powi(-e / 2), 2f64.powi(-e + e / 2));
    pieces
        .iter()
        .map(|p| AccelPiece {
            width: p.width,
            poly: p.poly.iter().map(|c| c * f1 * f2).collect(),
            sine: p.sine.map(|s| Sine { amp: s.amp * f1 * f2, ..s }),
        })
        .collect::<Vec<_>>()
        .into()
}

/// How [`Law::from_accel_pieces`] treats the end of the integrated motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EndCondition {
    /// A rise between dwells: the velocity must return to zero at `x = 1`
    /// (to 1e-9 of the peak velocity), else the build fails.
    Rest,
    /// The end velocity is free (e.g. a picking law that releases the shuttle at speed).
    Free,
}

/// A motion law on `x ∈ [0, 1]`: contiguous [`Segment`]s, `s` and `v` continuous at every joint.
///
/// Normalised laws have `s(0) = 0` and `s(1) = 1`. Outside `[0, 1]` the law is held at its
/// end values (`x` is clamped).
///
/// The segments are shared: a clone is a reference (a long machine cycle holds a law per move, e.g.
/// a servo-driven heald frame's ~800 moves over a 10⁴-pick repeat), and two laws holding the same
/// segments compare equal without comparing them.
#[derive(Debug, Clone)]
pub struct Law {
    segments: Arc<[Segment]>,
}

impl PartialEq for Law {
    /// Equal segments (the same shared segments are equal at once).
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.segments, &other.segments) || self.segments == other.segments
    }
}

impl Serialize for Law {
    /// As a struct of its segments: `{"segments": [...]}`.
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut s = serializer.serialize_struct("Law", 1)?;
        s.serialize_field("segments", &*self.segments)?;
        s.end()
    }
}

impl Law {
    /// `points` of a law's samples, both ends included: at least 2 (the ends). A table streams
    /// them, so the time budget ([`loomkin_units::Budget`]) bounds how many; held as arrays (Python)
    /// they are bounded by [`Law::HELD_POINTS`].
    pub const SAMPLE_POINTS: Field = Field::count(
        "points",
        Range::at_least(2.0, ""),
        "Samples of the law from x = 0 to 1, both ends included: at least 2; a streamed table is bounded \
         by the time budget, samples held as arrays by 10⁸.",
    );
    /// [`Law::SAMPLE_POINTS`] held in memory as five float64 columns (Python's arrays): 2 … 10⁸ (4 GB).
    pub const HELD_POINTS: Field = Self::SAMPLE_POINTS.within(
        Range::closed(2.0, 1e8, ""),
        "Samples of the law held as arrays (five float64 columns): 2 … 10⁸ (4 GB at the top).",
    );
    /// [`Law::SAMPLE_POINTS`] of a plot: 2 … 10⁵ points a curve (a plot holds them all, several
    /// curves at once), 801 when left out.
    pub const PLOT_POINTS: Field = Field::count(
        "points",
        Range::closed(2.0, 1e5, ""),
        "Points per plotted curve: 2 … 10⁵ (a plot holds every curve's points); 801 when left out.",
    )
    .with_default(801.0);

    /// Builds a law from contiguous segments. The first must start at 0, the last end at 1, each
    /// start where the previous ended (within 1e-12), and `s`, `v` be continuous at the joints (as
    /// [`crate::DerivativeScale`] judges it: within 1e-9 of their peaks over the segments).
    pub fn from_segments(segments: Vec<Segment>) -> Result<Self> {
        let field = "segments";
        let (Some(first), Some(last)) = (segments.first(), segments.last()) else {
            return Err(LawError::NotARise { field: field.into(), reason: "a law needs at least one segment".into() });
        };
        if first.x0().abs() > 1e-12 || (last.x1() - 1.0).abs() > 1e-12 {
            return Err(LawError::Cycle {
                field: field.into(),
                reason: format!("segments cover [{}, {}], they must cover [0, 1]", first.x0(), last.x1()),
            });
        }
        let scale = crate::continuity::segments_scale(&segments);
        for (i, w) in segments.windows(2).enumerate() {
            let (l, r) = (w[0].end(), w[1].start());
            if (w[0].x1() - w[1].x0()).abs() > 1e-12 {
                return Err(LawError::Cycle {
                    field: format!("segments[{}].x0", i + 1),
                    reason: format!("starts at {} but segment {} ends at {}", w[1].x0(), i, w[0].x1()),
                });
            }
            let (tl, tr) = (w[0].term_magnitudes(w[0].width()), w[1].term_magnitudes(0.0));
            let terms = std::array::from_fn(|k| tl[k].max(tr[k]));
            let round = |k| crate::continuity::joint_rounding(w[1].x0(), &terms, k);
            if scale.jumps(0, l.s, r.s, round(0)) || scale.jumps(1, l.v, r.v, round(1)) {
                return Err(LawError::NotARise {
                    field: format!("segments[{}]", i + 1),
                    reason: "displacement and velocity must be continuous at every joint".into(),
                });
            }
        }
        Ok(Self { segments: segments.into() })
    }

    /// Integrates acceleration pieces twice from `s(0) = 0`, `v(0) = 0` in closed form and scales
    /// the result so that `s(1) = 1`.
    ///
    /// The widths must be positive and sum to 1 (±1e-9); `field` names the input in errors.
    pub fn from_accel_pieces(pieces: &[AccelPiece], end: EndCondition, field: &str) -> Result<Self> {
        if pieces.is_empty() {
            return Err(LawError::NotARise { field: field.into(), reason: "no acceleration segments given".into() });
        }
        let mut sum = 0.0;
        let widths = Range::open_closed(0.0, 1.0, "");
        for (i, p) in pieces.iter().enumerate() {
            // The field name is formatted only for the error (the optimisers build laws in a loop).
            if !widths.contains(p.width) {
                widths.check(&format!("{field}[{i}].length"), p.width)?;
            }
            sum += p.width;
        }
        if (sum - 1.0).abs() > 1e-9 {
            return Err(LawError::LengthsDoNotSumToOne { field: field.into(), sum });
        }
        // The law is normalised to s(1) = 1, so the scale of the acceleration does not matter:
        // levels far from 1 (1e-308, 1e300) are first brought near 1 by a power of two, which is
        // exact, so that s(1) cannot underflow and 1/s(1) overflow (levels of ±1e-308 gave Cv = −∞).
        let pieces = &rescaled(pieces);
        let mut segs = Vec::with_capacity(pieces.len());
        let (mut x, mut s, mut v) = (0.0, 0.0, 0.0);
        for (i, p) in pieces.iter().enumerate() {
            // Snap the last end onto 1 exactly so the law covers [0, 1].
            let x1 = if i + 1 == pieces.len() { 1.0 } else { x + p.width / sum };
            if x1 <= x {
                return Err(LawError::NotARise {
                    field: format!("{field}[{i}]"),
                    reason: format!(
                        "a length of {} is too narrow to have a place of its own at x = {x} (positions are resolved \
                         to {:e} there)",
                        loomkin_units::compact(p.width),
                        if x > 0.0 { f64::EPSILON * x } else { f64::MIN_POSITIVE }
                    ),
                });
            }
            // Places are the widths divided by their total, which may differ from 1 by up to 1e-9: the
            // shapes are scaled with them (t → t·sum), so that their end values (a sine arc's zero, a
            // ramp's level) fall on the joints. Left at their nominal widths, lengths summing to
            // 1 + 9e-10 left a jump of 1.8e-8 in a at the joint of two sine arcs. (A place's own
            // rounding is left alone: a shape keeps its exact width, and the continuity report allows
            // for the rounding of the joint's position; so is a total off 1 by its own rounding.)
            let scaled;
            let p = if (sum - 1.0).abs() <= 4.0 * f64::EPSILON * pieces.len() as f64 {
                p
            } else {
                let mut qk = 1.0;
                let poly = p.poly.iter().map(|c| {
                    let v = c * qk;
                    qk *= sum;
                    v
                });
                scaled = AccelPiece {
                    width: p.width / sum,
                    poly: poly.collect(),
                    sine: p.sine.map(|sn| Sine { omega: sn.omega * sum, ..sn }),
                };
                &scaled
            };
            let seg = Segment::from_accel(x, x1, &p.poly, p.sine, s, v).ok_or_else(|| LawError::NotARise {
                field: format!("{field}[{i}]"),
                reason: "acceleration must be finite, of polynomial degree ≤ 5, with a non-zero sine frequency".into(),
            })?;
            let e = seg.end();
            (x, s, v) = (x1, e.s, e.v);
            segs.push(seg);
        }
        if !(s.is_finite() && s > 0.0) {
            return Err(LawError::NotARise {
                field: field.into(),
                reason: format!(
                    "the acceleration gives a net displacement of {s:e}; it must be positive to make a rise"
                ),
            });
        }
        let k = 1.0 / s;
        segs.iter_mut().for_each(|g| *g = g.scaled(k));
        // Every metric must be finite: max |s|, |v|, |a|, |j| (and the two derivatives used to
        // locate them) are bounded by the coefficient sums, and Cm = max v·a and Ca,rms = √∫a² by
        // the products of those bounds. A net displacement tiny against the acceleration (its
        // areas nearly cancelling) scales them past the largest double.
        let bounds = segs
            .iter()
            .map(Segment::derivative_bounds)
            .fold([0.0f64; 6], |acc, b| std::array::from_fn(|i| acc[i].max(b[i])));
        let peak = bounds[..4].iter().copied().fold(0.0, f64::max);
        if !(k.is_finite() && bounds.iter().all(|b| b.is_finite()) && (peak * peak).is_finite()) {
            return Err(LawError::NotARise {
                field: field.into(),
                reason: format!(
                    "the acceleration gives a net displacement of only {s:e} of its own scale: normalised to a unit \
                     stroke its values would pass {:e}, and v·a and a² would not be finite numbers",
                    f64::MAX.sqrt()
                ),
            });
        }
        if end == EndCondition::Rest {
            // v must not jump against the dwell after the rise, as the law's continuity report judges
            // it (against the peak velocity, sampled only where the ends' values do not settle it:
            // the peak is at least the largest of them).
            let vmax = segs.iter().map(|g| g.start().v.abs().max(g.end().v.abs())).fold(0.0, f64::max);
            let v1 = v * k;
            let last = &segs[segs.len() - 1];
            let rounding = crate::continuity::joint_rounding(1.0, &last.term_magnitudes(last.width()), 1);
            let jumps = |scale: f64| v1.abs() > crate::CONTINUITY_TOL * scale + rounding;
            if jumps(vmax) && crate::continuity::segments_scale(&segs).jumps(1, v1, 0.0, rounding) {
                return Err(LawError::NotARise {
                    field: field.into(),
                    reason: format!(
                        "the velocity does not return to zero at the end (v(1) = {v1:.6}): the positive and negative \
                         acceleration areas must balance"
                    ),
                });
            }
        }
        Ok(Self { segments: segs.into() })
    }

    /// The segments, in order.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// The joints between segments (excluding 0 and 1).
    pub fn joints(&self) -> impl Iterator<Item = f64> + '_ {
        self.segments.iter().skip(1).map(|g| g.x0())
    }

    /// Index of the segment containing `x` (the right one at a joint).
    #[inline]
    pub fn segment_index(&self, x: f64) -> usize {
        let n = self.segments.len();
        if n <= 8 {
            let mut i = 0;
            while i + 1 < n && x >= self.segments[i + 1].x0() {
                i += 1;
            }
            i
        } else {
            self.segments.partition_point(|g| g.x0() <= x).saturating_sub(1)
        }
    }

    /// Kinematics at `x`. Outside `[0, 1]` the follower dwells where the law starts (`x < 0`) or
    /// ends (`x > 1`): `s` is the law's value there, `v`, `a` and `j` are 0 (the derivatives of a
    /// dwell), whatever the law's own derivatives at its ends. A NaN is taken as 0.
    #[inline]
    pub fn eval(&self, x: f64) -> Kinematics {
        let inside = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
        let seg = &self.segments[self.segment_index(inside)];
        let k = seg.eval(inside);
        if inside == x || x.is_nan() { k } else { Kinematics { s: k.s, ..Kinematics::default() } }
    }

    /// Fills `out` with the kinematics at `n = out.len()` evenly spaced points from 0 to 1, both ends
    /// included. Walks the segments in order and uses an exact angle-addition recurrence for the
    /// sinusoids, so it is several times faster than calling [`Law::eval`] per point.
    pub fn sample_into(&self, out: &mut [Kinematics]) {
        let n = out.len();
        if n == 0 {
            return;
        }
        if n == 1 {
            out[0] = self.eval(0.0);
            return;
        }
        let h = 1.0 / (n - 1) as f64;
        // Tables far larger than the caches bypass them (non-temporal stores; same values).
        let nontemporal = crate::nontemporal::worth_it(out);
        let mut i = 0;
        for (si, seg) in self.segments.iter().enumerate() {
            let last = si + 1 == self.segments.len();
            // Points i.. with x = i·h < x1 (all remaining for the last segment), decided with the
            // same arithmetic as `eval` so that a point on a joint goes to the right-hand segment.
            let mut end = if last { n } else { ((seg.x1() / h).ceil() as usize).clamp(i, n) };
            if !last {
                while end > i && (end - 1) as f64 * h >= seg.x1() {
                    end -= 1;
                }
                while end < n && (end as f64) * h < seg.x1() {
                    end += 1;
                }
            }
            if end > i {
                let t0 = i as f64 * h - seg.x0();
                if nontemporal {
                    seg.eval_run_nontemporal(t0, h, &mut out[i..end]);
                } else {
                    seg.eval_run(t0, h, &mut out[i..end]);
                }
            }
            i = end;
        }
        if nontemporal {
            crate::nontemporal::fence();
        }
        // Make the last point land exactly on x = 1.
        out[n - 1] = self.eval(1.0);
    }

    /// `n ≥ 2` evenly spaced samples including both ends, as `(x, kinematics)`.
    pub fn sample(&self, n: usize) -> Vec<(f64, Kinematics)> {
        let n = n.max(2);
        let mut k = vec![Kinematics::default(); n];
        self.sample_into(&mut k);
        let h = 1.0 / (n - 1) as f64;
        k.into_iter().enumerate().map(|(i, k)| (if i + 1 == n { 1.0 } else { i as f64 * h }, k)).collect()
    }
}

impl Law {
    /// The same samples as [`Law::sample`], produced a block at a time: the memory held is one
    /// block (a few hundred KB) whatever `n`, and the values are bit-identical to [`Law::sample`]'s.
    pub fn samples(&self, n: usize) -> Samples<'_> {
        let n = n.max(2);
        let h = 1.0 / (n - 1) as f64;
        // The runs of points per segment, decided exactly as in `sample_into`.
        let mut runs = Vec::with_capacity(self.segments.len());
        let mut i = 0;
        for (si, seg) in self.segments.iter().enumerate() {
            let last = si + 1 == self.segments.len();
            let mut end = if last { n } else { ((seg.x1() / h).ceil() as usize).clamp(i, n) };
            if !last {
                while end > i && (end - 1) as f64 * h >= seg.x1() {
                    end -= 1;
                }
                while end < n && (end as f64) * h < seg.x1() {
                    end += 1;
                }
            }
            if end > i {
                runs.push((si, i, end));
            }
            i = end;
        }
        Samples { law: self, n, h, runs, run: 0, next: 0, block: Vec::new(), block_start: 0, pos: 0 }
    }
}

impl Law {
    /// The samples of [`Law::samples`] written as five columns `[x, s, v, a, j]` — the layout of a
    /// data frame or of numpy arrays — a block at a time: the same bits as `samples(n)` with `n` the
    /// columns' length, and no table of records beside the columns. Columns of different lengths
    /// are filled to the shortest one's length `n` (the points evenly spaced for that `n`); fewer
    /// than two points write nothing. Returns `n` (0 when nothing was written).
    pub fn sample_columns(&self, columns: [&mut [f64]; 5]) -> usize {
        let n = columns.iter().map(|c| c.len()).min().unwrap_or(0);
        if n < 2 {
            return 0;
        }
        let [xs, ss, vs, as_, js] = columns;
        let mut it = self.samples(n);
        while it.refill() {
            let (from, block) = (it.block_start, &it.block);
            let to = from + block.len();
            let rows = xs[from..to].iter_mut().zip(&mut ss[from..to]).zip(&mut vs[from..to]);
            let rows = rows.zip(&mut as_[from..to]).zip(&mut js[from..to]).zip(block);
            for (i, (((((x, s), v), a), j), k)) in (from..).zip(rows) {
                // x as the iterator gives it: i·h, and exactly 1 at the last point.
                *x = if i + 1 == n { 1.0 } else { i as f64 * it.h };
                (*s, *v, *a, *j) = (k.s, k.v, k.a, k.j);
            }
        }
        n
    }
}

/// Points per block of [`Samples`] (a multiple of the segment recurrence's re-seed interval).
const SAMPLE_BLOCK: usize = 64 * crate::segment::RUN_CHUNK;

/// Evenly spaced samples `(x, kinematics)` of a law, made a block at a time ([`Law::samples`]).
#[derive(Debug, Clone)]
pub struct Samples<'a> {
    law: &'a Law,
    n: usize,
    h: f64,
    /// `(segment, first point, end point)` of each run of points in one segment.
    runs: Vec<(usize, usize, usize)>,
    /// The run the next block comes from.
    run: usize,
    /// The first point of the next block.
    next: usize,
    block: Vec<Kinematics>,
    /// Index of `block[0]`.
    block_start: usize,
    /// Next point to hand out.
    pos: usize,
}

impl Samples<'_> {
    /// Fills the block with the next points (never across a segment's run, so each block starts
    /// a multiple of the re-seed interval after its run's start).
    fn refill(&mut self) -> bool {
        while let Some(&(si, start, end)) = self.runs.get(self.run) {
            let from = self.next.max(start);
            if from >= end {
                self.run += 1;
                continue;
            }
            let to = (from + SAMPLE_BLOCK).min(end);
            let seg = &self.law.segments[si];
            self.block.clear();
            self.block.resize(to - from, Kinematics::default());
            seg.eval_run_from(start as f64 * self.h - seg.x0(), self.h, from - start, &mut self.block);
            if to == self.n {
                // The last point lands exactly on x = 1, as in `sample_into`.
                *self.block.last_mut().expect("a block holds a point") = self.law.eval(1.0);
            }
            self.block_start = from;
            self.next = to;
            return true;
        }
        false
    }
}

impl Iterator for Samples<'_> {
    type Item = (f64, Kinematics);

    fn next(&mut self) -> Option<Self::Item> {
        if self.pos >= self.n {
            return None;
        }
        if self.pos >= self.block_start + self.block.len() && !self.refill() {
            return None;
        }
        let i = self.pos;
        self.pos += 1;
        let x = if i + 1 == self.n { 1.0 } else { i as f64 * self.h };
        Some((x, self.block[i - self.block_start]))
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.n - self.pos;
        (left, Some(left))
    }
}

impl ExactSizeIterator for Samples<'_> {}

impl MotionLaw for Law {
    fn eval(&self, x: f64) -> Kinematics {
        Law::eval(self, x)
    }

    fn sample_uniform(&self, n: usize) -> Vec<(f64, Kinematics)> {
        self.sample(n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::LawSpec;

    #[test]
    fn a_clone_shares_its_segments_and_compares_and_serialises_as_the_law() {
        let law = LawSpec::ModifiedSine.build().unwrap();
        let copy = law.clone();
        assert!(Arc::ptr_eq(&law.segments, &copy.segments));
        assert_eq!(copy, law);
        // Built again: other segments, equal values — equal; another law is not.
        let again = LawSpec::ModifiedSine.build().unwrap();
        assert!(!Arc::ptr_eq(&law.segments, &again.segments) && again == law);
        assert_ne!(LawSpec::Cycloidal.build().unwrap(), law);
        // The JSON is the struct of its segments, `{"segments": [...]}`, as a list of them.
        let json = serde_json::to_value(&law).unwrap();
        let list = serde_json::to_value(law.segments().to_vec()).unwrap();
        assert_eq!(json, serde_json::json!({ "segments": list }));
    }
}
