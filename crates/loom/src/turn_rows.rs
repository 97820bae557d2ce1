//! Rows of a long repeat whose picks do not repeat: each frame's contribution over a pick's turn
//! made once per distinct state of that frame, and every pick's numbers summed from them.
//!
//! [`Motion::frame_in_turn`] gives frame `i` at angle `t` of pick `p`'s turn from `t` and the
//! frame's lifts at picks `p + q − 1` and `p + q` alone, `q` the move nearest `t`
//! ([`Motion::move_in_turn`], non-decreasing in `t`). Over a span `[from, to]` of the turn a
//! frame therefore reads the picks `p + q(from) − 1 … p + q(to)`: its *run* of lifts there (three
//! picks for a turn of 360°) names what it does, bit for bit, so a frame has at most `2^span`
//! distinct rows whatever the length of the repeat (8 for 24 frames over a turn: 192 rows for
//! 10⁵ random picks). A pick's values at any angle of the span are its frames' rows combined (a
//! sum for the torque, min/max for the clear shed): exact at every angle the rows hold, and the
//! refinements (roots, extremes) are made on the exact laws of the pick itself.
//!
//! These rows serve repeats with many distinct turns (more than [`MAX_WHOLE_TURNS`]); up to that,
//! each distinct turn is worked out whole, once (`crate::turns`), the path whose numbers the
//! examples print. Both agree to rounding (the tests hold them to 1e-12).

use crate::{Drive, Motion};
use loomkin_laws::gauss_legendre;

/// Distinct turns up to which a repeat is worked out turn by turn, each distinct turn whole (the
/// numbers the examples print; at most ~0.3 s for 24 frames); beyond it, from rows (a constant
/// cost plus a sum per pick).
pub(crate) const MAX_WHOLE_TURNS: usize = 256;

/// Every frame's run of lifts over a span of a pick's turn, and the rows met so far.
#[derive(Debug, Clone)]
pub(crate) struct FrameStates {
    /// The first pick read, relative to the pick.
    pub lo: i64,
    /// Picks read.
    span: usize,
    /// Per frame, the runs met so far and their row numbers.
    runs: Vec<Vec<(u64, u32)>>,
    /// Per row: its frame and the first pick met with it.
    pub rows: Vec<(usize, usize)>,
}

impl FrameStates {
    /// The runs of `motion`'s frames over `[from_deg, to_deg]` of a pick's turn; `None` when the
    /// span reads more than 64 picks.
    pub fn new(motion: &Motion, from_deg: f64, to_deg: f64) -> Option<Self> {
        let n = motion.frames();
        let lo = (0..n).map(|i| motion.move_in_turn(i, from_deg)).min().unwrap_or(0) - 1;
        let hi = (0..n).map(|i| motion.move_in_turn(i, to_deg)).max().unwrap_or(0);
        let span = usize::try_from(hi - lo + 1).ok().filter(|&s| s <= 64)?;
        Some(Self { lo, span, runs: vec![Vec::new(); n], rows: Vec::new() })
    }

    /// The run of frame `i`'s lifts read by pick `p`'s span (bit `k`: up at pick `p + lo + k`).
    pub fn run(&self, motion: &Motion, i: usize, p: usize) -> u64 {
        (0..self.span).filter(|&k| motion.is_up(i, p as i64 + self.lo + k as i64)).fold(0, |b, k| b | 1 << k)
    }

    /// The row of frame `i` at pick `p` and whether it is new (recorded with `p` as its first pick).
    pub fn row(&mut self, motion: &Motion, i: usize, p: usize) -> (u32, bool) {
        let run = self.run(motion, i, p);
        if let Some(&(_, id)) = self.runs[i].iter().find(|r| r.0 == run) {
            return (id, false);
        }
        let id = self.rows.len() as u32;
        self.runs[i].push((run, id));
        self.rows.push((i, p));
        (id, true)
    }

    /// The row of frame `i` at pick `p`, which must have been met.
    pub fn known(&self, motion: &Motion, i: usize, p: usize) -> u32 {
        let run = self.run(motion, i, p);
        self.runs[i].iter().find(|r| r.0 == run).map_or(u32::MAX, |r| r.1)
    }
}

/// Frames' slope rows `y/d` on a grid of the insertion, kept across the motions of a search
/// that moves the frames' centres (the stagger search): a row is named by its frame, the frame's
/// move centre (bits), the span's first pick and the run of lifts, and is the same for every
/// motion that shares them.
#[derive(Debug, Clone, Default)]
pub(crate) struct SlopeRows {
    index: loomkin_numeric::WordMap<[u64; 4], usize>,
    rows: Vec<Vec<f64>>,
}

impl SlopeRows {
    /// The number of the row named `key` (frame, centre bits, the span's first pick, run),
    /// made by `make` when it is not held yet.
    pub(crate) fn get(&mut self, key: [u64; 4], make: impl FnOnce() -> Vec<f64>) -> usize {
        if let Some(&r) = self.index.get(&key) {
            return r;
        }
        self.rows.push(make());
        self.index.insert(key, self.rows.len() - 1);
        self.rows.len() - 1
    }

    /// Row `r`.
    pub(crate) fn row(&self, r: usize) -> &[f64] {
        &self.rows[r]
    }
}

/// The nodes and weights of the RMS's quadrature over a turn `[0°, 360°]` shared by every pick:
/// 16-point Gauss–Legendre on the two halves of panels cut at every joint any frame's move may
/// put in the turn (each at most 20° wide), a panel halved while some row's square changes by
/// more than [`Drive::rms`]'s tolerance; and every row's `k`-scaled power at the nodes.
struct RmsNodes {
    at: Vec<f64>,
    weight: Vec<f64>,
    /// `values[r·n + j]`: row `r` at node `j` (`n` nodes).
    values: Vec<f64>,
}

/// The RMS torque of `drive` from rows ([`Drive::rms`] of a repeat with many distinct turns):
/// `∫(kT)²` over a pick's turn is `Σ_i Σ_j ∫ P_i P_j`, `P_i` frame `i`'s row there (its power
/// times `k/η`), and the integrals of every pair of rows are made once on nodes shared by every
/// pick (the Gram matrix of the rows); a pick adds up those of its frames' rows.
pub(crate) fn rms_from_rows(drive: &Drive, k: f64, max_splits: usize) -> Option<f64> {
    let motion = drive.motion();
    let mut states = FrameStates::new(motion, 0.0, 360.0)?;
    let n = motion.frames();
    for p in 0..motion.picks() {
        (0..n).for_each(|i| _ = states.row(motion, i, p));
    }
    let power = |r: usize, t: f64| -> f64 {
        let (i, p) = states.rows[r];
        drive.power(i, &motion.frame_in_turn(i, p, t)) * k
    };
    let nodes = rms_nodes(motion, &states, max_splits, &power);
    let rows = states.rows.len();
    let m = nodes.at.len();
    // Each row's nodes where it is not zero (a frame dwelling contributes nothing).
    let support: Vec<(usize, usize)> = (0..rows)
        .map(|r| {
            let v = &nodes.values[r * m..][..m];
            let first = v.iter().position(|&x| x != 0.0).unwrap_or(m);
            let last = v.iter().rposition(|&x| x != 0.0).map_or(first, |j| j + 1);
            (first, last)
        })
        .collect();
    let mut gram = vec![0.0; rows * rows];
    for r in 0..rows {
        for s in r..rows {
            let (a, b) = (support[r].0.max(support[s].0), support[r].1.min(support[s].1));
            let (vr, vs) = (&nodes.values[r * m..][..m], &nodes.values[s * m..][..m]);
            let g: f64 = (a..b.max(a)).map(|j| nodes.weight[j] * vr[j] * vs[j]).sum();
            gram[r * rows + s] = g;
            gram[s * rows + r] = g;
        }
    }
    let mut ids = vec![0usize; n];
    let mut sum = 0.0;
    for p in 0..motion.picks() {
        let mut live = 0;
        for i in 0..n {
            let r = states.known(motion, i, p) as usize;
            if support[r].0 < support[r].1 {
                ids[live] = r;
                live += 1;
            }
        }
        let ids = &ids[..live];
        let mut turn = 0.0;
        for (a, &r) in ids.iter().enumerate() {
            let row = &gram[r * rows..][..rows];
            turn += row[r] + 2.0 * ids[a + 1..].iter().map(|&s| row[s]).sum::<f64>();
        }
        sum += turn;
    }
    Some((sum / motion.repeat_deg()).sqrt())
}

/// The nodes of [`rms_from_rows`] (see [`RmsNodes`]).
fn rms_nodes(motion: &Motion, states: &FrameStates, max_splits: usize, power: &dyn Fn(usize, f64) -> f64) -> RmsNodes {
    let phi = motion.motion_deg();
    let mut cuts = vec![0.0, 360.0];
    for i in 0..motion.frames() {
        let c = motion.centre0_deg(i);
        for q in states.lo..states.lo + states.span as i64 {
            let start = 360.0 * q as f64 + c - phi / 2.0;
            for rising in [true, false] {
                let law = motion.law().law(rising);
                let xs = std::iter::once(0.0).chain(law.joints()).chain(std::iter::once(1.0));
                cuts.extend(xs.map(|x| start + x * phi).filter(|&t| t > 1e-9 && t < 360.0 - 1e-9));
            }
        }
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|a, b| (*a - *b).abs() <= 1e-9);
    let rule = gauss_legendre(16);
    let rows = states.rows.len();
    // Every row's 16 values on [a, b] and the integral of its square there.
    let panel = |a: f64, b: f64| -> (Vec<f64>, Vec<f64>) {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        let mut vals = Vec::with_capacity(rows * rule.len());
        let mut sq = Vec::with_capacity(rows);
        for r in 0..rows {
            let at = vals.len();
            vals.extend(rule.iter().map(|&(x, _)| power(r, mid + half * x)));
            sq.push(rule.iter().zip(&vals[at..]).map(|(&(_, w), v)| half * w * v * v).sum());
        }
        (vals, sq)
    };
    let mut first = vec![0.0; rows];
    let mut stack = Vec::new();
    for w in cuts.windows(2) {
        let (a, b) = (w[0], w[1]);
        let parts = ((b - a) / 20.0).ceil().max(1.0) as usize;
        let hp = (b - a) / parts as f64;
        for j in 0..parts {
            let (pa, pb) = (a + j as f64 * hp, if j + 1 == parts { b } else { a + (j + 1) as f64 * hp });
            let (_, sq) = panel(pa, pb);
            first.iter_mut().zip(&sq).for_each(|(f, s)| *f += s);
            stack.push((pa, pb, sq, 0u32));
        }
    }
    stack.reverse();
    let mut out = RmsNodes { at: Vec::new(), weight: Vec::new(), values: Vec::new() };
    // Accepted halves: (a, b, every row's 16 values).
    let mut accepted: Vec<(f64, f64, Vec<f64>)> = Vec::new();
    let mut splits = 0usize;
    while let Some((a, b, whole, depth)) = stack.pop() {
        let m = 0.5 * (a + b);
        let ((lv, ls), (rv, rs)) = (panel(a, m), panel(m, b));
        let settled = (0..rows).all(|r| {
            let sum = ls[r] + rs[r];
            let tol = (1e-13 * first[r] * (b - a) / 360.0).max(1e-13 * sum);
            (sum - whole[r]).abs() <= tol || !sum.is_finite()
        });
        if settled || depth >= 30 || splits >= max_splits {
            accepted.push((a, m, lv));
            accepted.push((m, b, rv));
        } else {
            splits += 1;
            stack.push((m, b, rs, depth + 1));
            stack.push((a, m, ls, depth + 1));
        }
    }
    accepted.sort_by(|x, y| x.0.total_cmp(&y.0));
    let per = rule.len();
    for (a, b, _) in &accepted {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        out.at.extend(rule.iter().map(|&(x, _)| mid + half * x));
        out.weight.extend(rule.iter().map(|&(_, w)| half * w));
    }
    let m = out.at.len();
    out.values = vec![0.0; rows * m];
    for (h, (_, _, vals)) in accepted.iter().enumerate() {
        for r in 0..rows {
            out.values[r * m + h * per..][..per].copy_from_slice(&vals[r * per..][..per]);
        }
    }
    out
}

/// `picks` random picks on `shafts` shafts for the tests (an LCG from `seed`; each lift up with p = ½, a
/// pick with every frame up or every frame down drawn again).
#[cfg(test)]
pub(crate) fn random(seed: u64, picks: usize, shafts: usize) -> crate::Pattern {
    let mut state = seed;
    let mut lifts = Vec::new();
    while lifts.len() < picks {
        let pick: Vec<bool> = (0..shafts)
            .map(|_| {
                state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
                state >> 63 == 1
            })
            .collect();
        if pick.contains(&true) && pick.contains(&false) {
            lifts.push(pick);
        }
    }
    crate::Pattern::new(shafts, lifts).unwrap()
}

#[cfg(test)]
mod tests {
    //! The rows against the old evaluation, each distinct turn worked out whole (every pick of a
    //! random draft is one): the RMS and the timing summary to 1e-12, on a few hundred random
    //! picks, with the frames staggered to the ends of their range and the crossing at both ends
    //! of its own.
    use super::*;
    use crate::turns::Turns;
    use crate::{Loom, MAX_RMS_SPLITS, Timing};

    fn looms() -> Vec<(String, Loom)> {
        let text = include_str!("../../../examples/rapier-loom.toml");
        let stagger: Vec<String> = (0..24).map(|i| ["15", "-15", "0", "7.3"][i % 4].to_string()).collect();
        let staggered = text.replacen(
            "max_stagger_deg = 15",
            &format!("max_stagger_deg = 15\nstagger_deg = [{}]", stagger.join(", ")),
            1,
        );
        let mut out = vec![("rapier".to_string(), Loom::from_toml(text).unwrap())];
        for crossing in ["crossing_deg = 350", "crossing_deg = 180", "crossing_deg = 179.9", "crossing_deg = 0"] {
            let t = staggered.replacen("crossing_deg = 350", crossing, 1);
            out.push((format!("staggered, {crossing}"), Loom::from_toml(&t).unwrap()));
        }
        out.push(("shuttle".into(), Loom::from_toml(include_str!("../../../examples/shuttle-loom.toml")).unwrap()));
        out
    }

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * a.abs().max(b.abs())
    }

    /// A frame in its pick's turn is the frame at the absolute angle: bit for bit in the first
    /// pick, to the absolute angle's rounding in later ones.
    #[test]
    fn a_frame_in_its_turn_is_the_frame() {
        for (name, loom) in looms() {
            let pattern = random(7, 40, loom.frame_count());
            let motion = Motion::new(&loom, &pattern).unwrap();
            for i in 0..loom.frame_count() {
                for k in 0..=96 {
                    let t = -30.0 + 4.1 * k as f64;
                    assert_eq!(motion.frame_in_turn(i, 0, t), motion.frame(i, t), "{name}: frame {i} at {t}");
                    for p in [1, 17, 39] {
                        let (a, b) = (motion.frame_in_turn(i, p, t), motion.frame(i, 360.0 * p as f64 + t));
                        assert!(
                            (a.y_m - b.y_m).abs() <= 1e-12 && (a.dy - b.dy).abs() <= 1e-11,
                            "{name}: {a:?} vs {b:?}"
                        );
                    }
                }
            }
        }
    }

    /// The RMS from rows is the old turn-by-turn RMS (16-point Gauss–Legendre per distinct turn
    /// on its own joints) to 1e-12, on 300 random picks of every loom.
    #[test]
    fn the_rms_from_rows_is_the_turns() {
        for (name, loom) in looms() {
            let pattern = random(11, 300, loom.frame_count());
            let motion = Motion::new(&loom, &pattern).unwrap();
            let drive = Drive::new(&loom, &motion, &pattern);
            let turns = Turns::new(&motion, 0.0, 360.0);
            assert!(turns.first.len() > MAX_WHOLE_TURNS || name == "shuttle", "{name}: {} turns", turns.first.len());
            let old = drive.rms_of_turns(&turns, 1.0);
            let new = rms_from_rows(&drive, 1.0, MAX_RMS_SPLITS).unwrap();
            assert!(close(old, new, 1e-12), "{name}: {old} vs {new}");
            if turns.first.len() > MAX_WHOLE_TURNS {
                assert_eq!(drive.rms(), new, "{name}: rms() takes the rows");
            }
        }
    }

    /// The timing summary from rows is the old one (every pick's window and least clearance
    /// refined on its own) to 1e-12, on 300 random picks of every loom.
    #[test]
    fn the_timing_from_rows_is_the_turns() {
        let mut compared = 0;
        for (name, loom) in looms() {
            let pattern = random(13, 300, loom.frame_count());
            let motion = Motion::new(&loom, &pattern).unwrap();
            let timing = Timing::new(&loom, &motion, &pattern).unwrap();
            let new = timing.summary_from_rows().unwrap();
            let (old, new) = match (timing.report_of(false), new) {
                (Ok(o), Ok(n)) => (o, n),
                (Err(o), Err(n)) => {
                    assert_eq!(o.to_string(), n.to_string(), "{name}");
                    continue;
                }
                (o, n) => panic!("{name}: {o:?} vs {n:?}"),
            };
            compared += 1;
            for (what, a, b) in [
                ("open", old.open_deg, new.open_deg),
                ("close", old.close_deg, new.close_deg),
                ("window", old.window_deg, new.window_deg),
                ("least clearance", old.min_clearance_mm, new.min_clearance_mm),
                ("most clear", old.max_clear_mm, new.max_clear_mm),
                ("speed", old.max_speed_rpm, new.max_speed_rpm),
            ] {
                assert!(close(a, b, 1e-12), "{name}, {what}: {a} vs {b}");
            }
            assert!(new.picks.is_empty());
            if name != "shuttle" {
                assert_eq!(
                    format!("{:?}", timing.summary().unwrap()),
                    format!("{new:?}"),
                    "{name}: summary() takes the rows"
                );
            }
        }
        assert!(compared >= 4, "{compared} looms compared");
    }
}
