//! Every frame's drive on the shared DC bus over the pattern repeat.
//!
//! Frame `i` draws `P_i(t)` ([`crate::FrameDrive`]); a braking drive (`P_i < 0`) returns
//! `η_r·|P_i|` to the bus, so the bus carries
//!
//! $$ P_{bus}(t) = \sum_i g(P_i(t)), \qquad g(P) = \begin{cases} P & P \ge 0 \\ \eta_r P & P < 0 \end{cases} $$
//!
//! The supply gives `max(P_bus, 0)`; what braking frames return beyond what the others use at the
//! same instant (`max(−P_bus, 0)`) goes to the braking resistor (no storage on the bus is
//! modelled: its capacitors are taken as small).
//!
//! **Exact values.** Every quantity is evaluated on the closed form of the laws: the repeat is cut
//! at every joint of every frame's motion (ends of moves, joints of the laws, the velocity's sign
//! changes when there is Coulomb friction); between cuts each frame's power is smooth, and the
//! maxima of `P_bus`, of `−P_bus` and of each `|P_i|` are the ends and the roots of their
//! derivatives, bracketed on 16 sub-intervals and located by bisection to rounding; the integrals
//! are Gauss–Legendre (8 points, exact for the polynomial laws' powers of degree ≤ 15) between the
//! zeros of `P_bus` and of each `P_i`, located the same way. Each pick's turn is one window; a
//! window whose frames do exactly what an earlier one's did (the same pieces at the same offsets,
//! to 2⁻³⁰°) reuses its values, so a repeat costs as many windows as it has distinct picks.

use crate::drive::{DrivePoint, FrameDrive};
use loomkin_laws::{Cycle, SegmentKind};
use loomkin_servo::Axis;
use std::cell::RefCell;

/// A map keyed by words (the windows' keys).
pub(crate) use loomkin_numeric::WordMap;

/// Sub-intervals on which a derivative's sign changes are bracketed.
const SCAN: usize = 16;
/// Window keys round offsets to 2⁻³⁰ degree.
const KEY_SCALE: f64 = (1u64 << 30) as f64;

/// One smooth piece of a frame's motion within `[0, period)`.
#[derive(Debug, Clone, Copy)]
struct Piece {
    a: f64,
    b: f64,
    seg: usize,
    /// Law segment, `None` for a dwell.
    lseg: Option<usize>,
    /// Angle (deg) where the law segment's local coordinate is 0.
    anchor: f64,
    /// Length of the cycle segment, deg.
    len: f64,
    /// Identity of (cycle segment shape and kind of move, law segment): the shape's interned number
    /// in the high 32 bits, the law segment's index in the low (all ones for a dwell).
    ty: u64,
}

/// A frame's cycle cut into smooth pieces over `[0, period)`.
pub(crate) struct Timeline<'a> {
    cycle: &'a Cycle,
    drive: &'a FrameDrive,
    pieces: Vec<Piece>,
    /// Per cycle segment: a move laid end to end (the plan's, [`crate::FramePlan::parts`]).
    through: Vec<bool>,
    /// The drive's points remembered across studies ([`crate::DriveMemo`]), if any.
    memo: Option<&'a RefCell<FrameMemo>>,
}

impl<'a> Timeline<'a> {
    /// `segments`: the cycle's segments in degrees (`(kind, start, length, laid end to end)`, as
    /// the plan gives them: [`crate::FramePlan::parts`]).
    pub(crate) fn new(
        cycle: &'a Cycle,
        segments: &[(SegmentKind, f64, f64, bool)],
        drive: &'a FrameDrive,
        types: &mut WordMap<[u64; 4], u64>,
        memo: Option<&'a RefCell<FrameMemo>>,
    ) -> Self {
        let period = cycle.period_rad.to_degrees();
        // Into [0, period): shift by whole periods, splitting a piece that straddles a boundary.
        let laid: usize = cycle.segments.iter().map(|s| s.law.as_ref().map_or(1, |(_, l)| l.segments().len())).sum();
        let mut pieces = Vec::with_capacity(laid + 2);
        let place = |p: Piece, pieces: &mut Vec<Piece>| {
            let k = (p.a / period).floor();
            let shift = -k * period;
            let (a, b) = (p.a + shift, p.b + shift);
            if b <= period {
                pieces.push(Piece { a: a.max(0.0), b, anchor: p.anchor + shift, ..p });
            } else {
                pieces.push(Piece { a: a.max(0.0), b: period, anchor: p.anchor + shift, ..p });
                pieces.push(Piece { a: 0.0, b: b - period, anchor: p.anchor + shift - period, ..p });
            }
        };
        let mut cuts: Vec<f64> = Vec::with_capacity(8);
        let friction = drive.axis.load.friction_n > 0.0;
        for (si, (seg, &(kind, s0, len, through))) in cycle.segments.iter().zip(segments).enumerate() {
            // The kind of move and whether it is laid end to end tell its law (a frame's laws by
            // kind of move, `MoveLaws::of`): a move up and a move up laid end to end of the same
            // length and level may move by different laws. The shape and kind interned once per
            // segment; a piece's type is that and its law segment.
            let class = kind as u64 | u64::from(through) << 8;
            let shape = {
                let n = types.len() as u64;
                *types.entry([seg.stroke_si.to_bits(), len.to_bits(), seg.base_si.to_bits(), class]).or_insert(n)
            };
            let intern = |l: u32| shape << 32 | u64::from(l);
            match &seg.law {
                None => place(
                    Piece { a: s0, b: s0 + len, seg: si, lseg: None, anchor: s0, len, ty: intern(u32::MAX) },
                    &mut pieces,
                ),
                Some((_, law)) => {
                    for (li, l) in law.segments().iter().enumerate() {
                        let anchor = s0 + l.x0() * len;
                        let end = if li + 1 == law.segments().len() { s0 + len } else { s0 + l.x1() * len };
                        cuts.clear();
                        cuts.push(anchor);
                        if friction {
                            cuts.extend(
                                l.derivative_roots(1)
                                    .into_iter()
                                    .filter(|&t| t > 0.0 && t < l.width())
                                    .map(|t| anchor + t * len),
                            );
                        }
                        cuts.push(end);
                        let ty = intern(li as u32);
                        for w in cuts.windows(2) {
                            if w[1] > w[0] {
                                place(
                                    Piece { a: w[0], b: w[1], seg: si, lseg: Some(li), anchor, len, ty },
                                    &mut pieces,
                                );
                            }
                        }
                    }
                }
            }
        }
        pieces.retain(|p| p.b > p.a);
        pieces.sort_by(|x, y| x.a.total_cmp(&y.a));
        let through = segments.iter().map(|s| s.3).collect();
        Self { cycle, drive, pieces, through, memo }
    }

    /// The frame's position, velocity, acceleration and jerk at angle `theta` on piece `p`.
    fn state(&self, p: &Piece, theta: f64) -> [f64; 4] {
        let seg = &self.cycle.segments[p.seg];
        match (p.lseg, &seg.law) {
            (Some(li), Some((_, law))) => {
                let t = (theta - p.anchor) / p.len;
                self.drive.state_at_law(seg, &law.segments()[li], t)
            }
            _ => [seg.base_si, 0.0, 0.0, 0.0],
        }
    }

    /// Words that tell piece `p` clipped to `[a, b)` within the window from `w0` exactly: what
    /// the window's values read of it (a dwell: its level alone; a move: its segment's stroke,
    /// length, level, kind, law segment and where the law starts), offsets as their bits.
    fn exact_words(&self, p: &Piece, a: f64, b: f64, w0: f64, key: &mut Vec<u64>) {
        let seg = &self.cycle.segments[p.seg];
        match p.lseg {
            None => key.extend([u64::MAX - 1, seg.base_si.to_bits(), (a - w0).to_bits(), (b - w0).to_bits()]),
            Some(li) => {
                let class = seg.kind as u64 | u64::from(self.through[p.seg]) << 8 | (li as u64) << 16;
                key.extend([
                    class,
                    seg.stroke_si.to_bits(),
                    seg.length_rad.to_bits(),
                    p.len.to_bits(),
                    seg.base_si.to_bits(),
                    (a - w0).to_bits(),
                    (b - w0).to_bits(),
                    (p.anchor - w0).to_bits(),
                ])
            }
        }
    }

    fn eval(&self, p: &Piece, theta: f64) -> DrivePoint {
        let state = self.state(p, theta);
        match self.memo {
            Some(m) => m.borrow_mut().point(self.drive, state),
            None => self.drive.point(state[0], state[1], state[2], state[3]),
        }
    }

    /// [`Timeline::eval`] at every angle of a scan's `grid`, the block remembered as a whole.
    fn eval_grid(&self, p: &Piece, grid: &[f64; SCAN + 1]) -> [DrivePoint; SCAN + 1] {
        let states: [[f64; 4]; SCAN + 1] = std::array::from_fn(|k| self.state(p, grid[k]));
        match self.memo {
            Some(m) => m.borrow_mut().block(self.drive, &states),
            None => states.map(|[s, v, a, j]| self.drive.point(s, v, a, j)),
        }
    }
}

/// Drive points remembered across studies of the same frames' drives: an optimiser's evaluations
/// move the frames' laws in time, not their drives, and the bus's scan meets most of a frame's
/// states (position, velocity, acceleration, jerk at the scan's angles) again bit for bit (the
/// crank-and-lever example's `--optimize`: 13·10⁶ points, 0.68·10⁶ distinct). Only
/// crank-and-lever frames are remembered: their point costs ~1 µs (the inverse, a forward series
/// and a reversion), a linear drive's less than a lookup. A scan's points between two joints are
/// remembered as one block, keyed by all their states (one lookup for 17 points). The values are
/// [`FrameDrive::point`]'s, bit for bit. A frame whose drive differs from the one remembered
/// starts afresh; each frame keeps the blocks of two generations, each up to its share of
/// [`DriveMemo::BLOCKS`], the older dropped when the newer is full (what the search still uses
/// is copied into the newer).
///
/// It also keeps the pick windows of earlier calls by an exact key (the pick and, per frame, every
/// piece's shape, law segment and offsets as bits: what the window's values read), so that a
/// window the search's step left alone is not worked out again; a call's own windows are shared
/// as before (offsets to 2⁻³⁰°), each new one taken from the kept windows when there, so the
/// values are bit for bit those of a call without the memo. The kept windows are dropped when a
/// frame's drive or laws, the regeneration efficiency, the speed or the kind of scan differ from
/// the last call's, and when [`DriveMemo::WINDOWS`] are kept.
#[derive(Debug)]
pub struct DriveMemo {
    frames: Vec<RefCell<FrameMemo>>,
    blocks: usize,
    windows: KeptWindows,
    /// What the kept windows were worked out for: η_r, ω and the kind of scan, and every frame's
    /// laws up, down and laid end to end.
    context: Option<(Vec<u64>, Vec<FrameLaws>)>,
}

impl Default for DriveMemo {
    fn default() -> Self {
        Self::with_blocks(Self::BLOCKS)
    }
}

/// A frame's laws up, down and laid end to end (`None`: none given).
pub(crate) type FrameLaws = [Option<loomkin_laws::Law>; 3];

/// Pick windows by their exact key ([`DriveMemo`]).
pub(crate) type KeptWindows = RefCell<WordMap<Vec<u64>, WindowValues>>;

/// A block of a scan's states (`[s, v, a, j]` bits at each angle) and its points.
type Block = [u64; 4 * (SCAN + 1)];

/// One frame's remembered points.
#[derive(Debug)]
pub(crate) struct FrameMemo {
    axis: Axis,
    loss: u64,
    cap: usize,
    young: WordMap<Block, [DrivePoint; SCAN + 1]>,
    old: WordMap<Block, [DrivePoint; SCAN + 1]>,
    points: WordMap<[u64; 4], DrivePoint>,
}

impl DriveMemo {
    /// Blocks remembered per generation over all frames (about 1.4 kB each).
    pub const BLOCKS: usize = 1 << 13;
    /// Single points (a frame at rest) remembered per frame; forgotten at once beyond.
    const POINTS: usize = 256;

    /// Pick windows kept across calls; all are dropped beyond.
    pub const WINDOWS: usize = 1 << 12;

    /// A memo of `blocks` blocks per generation over all frames (at least one a frame).
    pub fn with_blocks(blocks: usize) -> Self {
        Self { frames: Vec::new(), blocks, windows: RefCell::default(), context: None }
    }

    /// Keeps the windows of earlier calls only if they were worked out for the same `laws` (per
    /// frame: up, down, laid end to end), `eta_r`, `omega` and kind of scan.
    pub(crate) fn windows_for(
        &mut self,
        laws: Vec<[Option<loomkin_laws::Law>; 3]>,
        eta_r: f64,
        omega: f64,
        scan_only: bool,
    ) {
        let words = vec![eta_r.to_bits(), omega.to_bits(), u64::from(scan_only)];
        if self.context.as_ref().is_none_or(|(w, l)| *w != words || *l != laws) {
            self.windows.get_mut().clear();
            self.context = Some((words, laws));
        }
    }

    /// A memo for `drives`, frame by frame (`None`: a linear drive, not remembered): each frame's
    /// points kept when its drive is the one remembered, else forgotten.
    pub(crate) fn frames_for(&mut self, drives: &[FrameDrive]) -> (Vec<Option<&RefCell<FrameMemo>>>, &KeptWindows) {
        let cap = (self.blocks / drives.len().max(1)).max(1);
        if self.frames.len() != drives.len() {
            self.windows.get_mut().clear();
        }
        self.frames.truncate(drives.len());
        for (i, d) in drives.iter().enumerate() {
            let fresh = || FrameMemo {
                axis: d.axis.clone(),
                loss: d.loss.to_bits(),
                cap,
                young: WordMap::default(),
                old: WordMap::default(),
                points: WordMap::default(),
            };
            match self.frames.get_mut(i) {
                None => self.frames.push(RefCell::new(fresh())),
                Some(m) => {
                    let m = m.get_mut();
                    if m.axis != d.axis || m.loss != d.loss.to_bits() || m.cap != cap {
                        *m = fresh();
                        self.windows.get_mut().clear();
                    }
                }
            }
        }
        let frames =
            self.frames.iter().zip(drives).map(|(m, d)| d.axis.load.crank_lever.is_some().then_some(m)).collect();
        (frames, &self.windows)
    }
}

impl FrameMemo {
    /// [`FrameDrive::point`] of `drive` (the drive this memo is for) at `state`, remembered.
    fn point(&mut self, drive: &FrameDrive, [s, v, a, j]: [f64; 4]) -> DrivePoint {
        let key = [s.to_bits(), v.to_bits(), a.to_bits(), j.to_bits()];
        if let Some(p) = self.points.get(&key) {
            return *p;
        }
        if self.points.len() >= DriveMemo::POINTS {
            self.points.clear();
        }
        let p = drive.point(s, v, a, j);
        self.points.insert(key, p);
        p
    }

    /// [`FrameDrive::point`] of `drive` at each of `states`, remembered as a block.
    fn block(&mut self, drive: &FrameDrive, states: &[[f64; 4]; SCAN + 1]) -> [DrivePoint; SCAN + 1] {
        let mut key = [0u64; 4 * (SCAN + 1)];
        for (k, st) in states.iter().enumerate() {
            for (m, x) in st.iter().enumerate() {
                key[4 * k + m] = x.to_bits();
            }
        }
        if let Some(b) = self.young.get(&key) {
            return *b;
        }
        let b = match self.old.get(&key) {
            Some(b) => *b,
            None => states.map(|[s, v, a, j]| drive.point(s, v, a, j)),
        };
        if self.young.len() >= self.cap {
            self.old = std::mem::take(&mut self.young);
        }
        self.young.insert(key, b);
        b
    }
}

/// Values of one window, angles relative to its start.
#[derive(Debug, Clone, Default)]
pub(crate) struct WindowValues {
    peak: (f64, f64),
    trough: (f64, f64),
    supplied_j: f64,
    braking_j: f64,
    regenerated_j: f64,
    /// Per frame: ∫P_i dt, and the largest |P_i| with where.
    frame_energy_j: Vec<f64>,
    frame_peak: Vec<(f64, f64)>,
}

/// The bus over the repeat.
#[derive(Debug, Clone, PartialEq)]
pub struct BusTotals {
    /// Largest bus power, W, and where, deg.
    pub peak_w: (f64, f64),
    /// Least bus power (most negative: braking), W, and where, deg.
    pub trough_w: (f64, f64),
    /// Energy the supply gives per repeat, J.
    pub supplied_j: f64,
    /// Energy the braking resistor takes per repeat, J.
    pub braking_j: f64,
    /// Energy braking frames return to the bus per repeat (after η_r), J.
    pub regenerated_j: f64,
    /// Per frame: the electrical energy drawn over the repeat, J.
    pub frame_energy_j: Vec<f64>,
    /// Per frame: the largest |P_i|, W, and where, deg.
    pub frame_peak_w: Vec<(f64, f64)>,
    /// Distinct windows evaluated (the rest reused).
    pub distinct_windows: usize,
}

fn take_max(best: &mut (f64, f64), v: f64, at: f64) {
    if v > best.0 {
        *best = (v, at);
    }
}

/// The bus of `frames` over a repeat of `picks` turns, braking drives returning `eta_r`. With
/// `scan_only` only the peak of the bus power is worked out, and only on the scan (16 points
/// between every two joints, no root finding): a lower bound of the exact peak, what a search
/// compares (the energies and the frames' peaks are then left at zero).
///
/// `only`: the picks to visit (increasing), every pick of the repeat when `None` (the totals are
/// then those of the listed picks' turns alone: what a search over representative picks compares).
pub(crate) fn bus(
    frames: &[Timeline<'_>],
    picks: usize,
    only: Option<&[usize]>,
    eta_r: f64,
    omega: f64,
    scan_only: bool,
    kept: Option<&KeptWindows>,
) -> BusTotals {
    let n = frames.len();
    let mut exact = Vec::new();
    let mut cursor = vec![0usize; n];
    let mut memo: WordMap<Vec<u64>, WindowValues> = WordMap::default();
    let mut tot = BusTotals {
        peak_w: (f64::NEG_INFINITY, 0.0),
        trough_w: (f64::NEG_INFINITY, 0.0),
        supplied_j: 0.0,
        braking_j: 0.0,
        regenerated_j: 0.0,
        frame_energy_j: vec![0.0; n],
        frame_peak_w: vec![(f64::NEG_INFINITY, 0.0); n],
        distinct_windows: 0,
    };
    // To the nearest 2⁻³⁰° (half away from zero; the cast truncates, without a call to `round`).
    let q = |x: f64| {
        let y = x * KEY_SCALE;
        (y + 0.5f64.copysign(y)) as i64 as u64
    };
    let mut items: Vec<Vec<(Piece, f64, f64)>> = vec![Vec::new(); n];
    let mut key = Vec::new();
    let mut ranges = vec![(0usize, 0usize); n];
    let every: Vec<usize>;
    let order = match only {
        Some(o) => o,
        None => {
            every = (0..picks).collect();
            &every
        }
    };
    for &p in order {
        let (w0, w1) = (360.0 * p as f64, 360.0 * (p + 1) as f64);
        key.clear();
        for (i, f) in frames.iter().enumerate() {
            while cursor[i] < f.pieces.len() && f.pieces[cursor[i]].b <= w0 {
                cursor[i] += 1;
            }
            let mut j = cursor[i];
            while j < f.pieces.len() && f.pieces[j].a < w1 {
                let pc = &f.pieces[j];
                let (a, b) = (pc.a.max(w0), pc.b.min(w1));
                if b > a {
                    key.extend([pc.ty, q(a - w0), q(b - w0), q(pc.anchor - w0)]);
                }
                j += 1;
            }
            ranges[i] = (cursor[i], j);
            key.push(u64::MAX);
        }
        // The key hashed once: a window seen before adds its values, a new one is worked out.
        if let Some(v) = memo.get(&key) {
            add_window(&mut tot, v, w0);
        } else {
            // A new window: its pieces, clipped to it.
            for (i, f) in frames.iter().enumerate() {
                items[i].clear();
                for pc in &f.pieces[ranges[i].0..ranges[i].1] {
                    let (a, b) = (pc.a.max(w0), pc.b.min(w1));
                    if b > a {
                        items[i].push((*pc, a, b));
                    }
                }
            }
            let v = match kept {
                None => window(frames, &items, w0, w1, eta_r, omega, scan_only),
                Some(kept) => {
                    // The window exactly: its pick, and what each frame's pieces are within it.
                    exact.clear();
                    exact.push(p as u64);
                    for (f, it) in frames.iter().zip(&items) {
                        for (pc, a, b) in it {
                            f.exact_words(pc, *a, *b, w0, &mut exact);
                        }
                        exact.push(u64::MAX);
                    }
                    let mut kept = kept.borrow_mut();
                    match kept.get(&exact) {
                        Some(v) => v.clone(),
                        None => {
                            let v = window(frames, &items, w0, w1, eta_r, omega, scan_only);
                            if kept.len() >= DriveMemo::WINDOWS {
                                kept.clear();
                            }
                            kept.insert(exact.clone(), v.clone());
                            v
                        }
                    }
                }
            };
            add_window(&mut tot, &v, w0);
            memo.insert(key.clone(), v);
        }
    }
    tot.trough_w.0 = -tot.trough_w.0;
    tot.distinct_windows = memo.len();
    tot
}

/// Adds the values of the window starting at `w0` to the totals.
fn add_window(tot: &mut BusTotals, v: &WindowValues, w0: f64) {
    take_max(&mut tot.peak_w, v.peak.0, w0 + v.peak.1);
    take_max(&mut tot.trough_w, v.trough.0, w0 + v.trough.1);
    tot.supplied_j += v.supplied_j;
    tot.braking_j += v.braking_j;
    tot.regenerated_j += v.regenerated_j;
    for (i, e) in v.frame_energy_j.iter().enumerate() {
        tot.frame_energy_j[i] += e;
        take_max(&mut tot.frame_peak_w[i], v.frame_peak[i].0, w0 + v.frame_peak[i].1);
    }
}

/// One window `[w0, w1)`: `items[i]` the pieces of frame `i` within it, clipped.
fn window(
    frames: &[Timeline<'_>],
    items: &[Vec<(Piece, f64, f64)>],
    w0: f64,
    w1: f64,
    eta_r: f64,
    omega: f64,
    scan_only: bool,
) -> WindowValues {
    let n = frames.len();
    let mut cuts: Vec<f64> = vec![w0, w1];
    for it in items {
        for &(_, a, b) in it {
            cuts.push(a);
            cuts.push(b);
        }
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|x, y| *x - *y <= 1e-12 * w1.max(1.0));
    let g = |p: f64| if p >= 0.0 { p } else { eta_r * p };
    let dg = |p: f64| if p >= 0.0 { 1.0 } else { eta_r };
    // Seconds per degree of the main shaft.
    let dt = std::f64::consts::PI / 180.0 / omega;
    let mut out = WindowValues {
        peak: (f64::NEG_INFINITY, 0.0),
        trough: (f64::NEG_INFINITY, 0.0),
        frame_energy_j: vec![0.0; n],
        frame_peak: vec![(f64::NEG_INFINITY, 0.0); n],
        ..WindowValues::default()
    };
    let rule = loomkin_laws::gauss_legendre(8);
    let mut active: Vec<Option<Piece>> = vec![None; n];
    let mut vals: Vec<DrivePoint> = vec![DrivePoint::default(); (SCAN + 1) * n];
    let mut scratch: Vec<DrivePoint> = vec![DrivePoint::default(); n];
    let mut zeros: Vec<f64> = Vec::new();
    let mut still: Vec<DrivePoint> = vec![DrivePoint::default(); n];
    let mut movers: Vec<usize> = Vec::with_capacity(n);
    for c in cuts.windows(2) {
        let (u, v) = (c[0], c[1]);
        if v <= u {
            continue;
        }
        let mid = 0.5 * (u + v);
        for i in 0..n {
            active[i] = items[i].iter().find(|(_, a, b)| *a <= mid && mid < *b).map(|x| x.0);
        }
        // A frame at rest (or with no piece here) is the same all over the sub-interval: its point
        // once, the moving frames' at each angle (the same values as evaluating every frame).
        movers.clear();
        for i in 0..n {
            match &active[i] {
                Some(p) if p.lseg.is_some() => movers.push(i),
                Some(p) => still[i] = frames[i].eval(p, u),
                None => still[i] = DrivePoint::default(),
            }
        }
        let eval_all = |theta: f64, pts: &mut [DrivePoint]| {
            pts.copy_from_slice(&still);
            for &i in &movers {
                if let Some(p) = &active[i] {
                    pts[i] = frames[i].eval(p, theta);
                }
            }
        };
        let net = |pts: &[DrivePoint]| -> (f64, f64) {
            pts.iter().fold((0.0, 0.0), |(s, d), q| (s + g(q.power_w), d + dg(q.power_w) * q.power_rate))
        };
        // Scan.
        let h = (v - u) / SCAN as f64;
        let grid: [f64; SCAN + 1] = std::array::from_fn(|k| if k == SCAN { v } else { u + k as f64 * h });
        // `vals[k * n + i]`: frame `i` at grid point `k` (one buffer for the window); the moving
        // frames' points a block at a time (the values of `eval_all` at each grid point).
        for k in 0..=SCAN {
            vals[k * n..(k + 1) * n].copy_from_slice(&still);
        }
        for &i in &movers {
            if let Some(p) = &active[i] {
                for (k, pt) in frames[i].eval_grid(p, &grid).into_iter().enumerate() {
                    vals[k * n + i] = pt;
                }
            }
        }
        let nets: [(f64, f64); SCAN + 1] = std::array::from_fn(|k| net(&vals[k * n..(k + 1) * n]));
        for k in 0..=SCAN {
            take_max(&mut out.peak, nets[k].0, grid[k] - w0);
            take_max(&mut out.trough, -nets[k].0, grid[k] - w0);
            for i in 0..n {
                take_max(&mut out.frame_peak[i], vals[k * n + i].power_w.abs(), grid[k] - w0);
            }
        }
        if scan_only {
            continue;
        }
        zeros.clear();
        zeros.extend([u, v]);
        for k in 0..SCAN {
            let (a, b) = (grid[k], grid[k + 1]);
            // Bus maxima and minima: sign changes of the derivative.
            let (d0, d1) = (nets[k].1, nets[k + 1].1);
            if (d0 > 0.0 && d1 < 0.0) || (d0 < 0.0 && d1 > 0.0) {
                let rising = d0 > 0.0;
                let r = loomkin_numeric::bisect(a, b, |t| {
                    eval_all(t, &mut scratch);
                    (net(&scratch).1 > 0.0) == rising
                });
                eval_all(r, &mut scratch);
                let p = net(&scratch).0;
                take_max(&mut out.peak, p, r - w0);
                take_max(&mut out.trough, -p, r - w0);
            }
            // Zeros of the bus power.
            if (nets[k].0 > 0.0) != (nets[k + 1].0 > 0.0) {
                let pos = nets[k].0 > 0.0;
                zeros.push(loomkin_numeric::bisect(a, b, |t| {
                    eval_all(t, &mut scratch);
                    (net(&scratch).0 > 0.0) == pos
                }));
            }
            for i in 0..n {
                let Some(pc) = &active[i] else { continue };
                if pc.lseg.is_none() {
                    continue;
                }
                let (p0, p1) = (vals[k * n + i], vals[(k + 1) * n + i]);
                // Largest |P_i|: sign changes of d(P²)/dt = 2·P·P'.
                let (s0, s1) = (p0.power_w * p0.power_rate, p1.power_w * p1.power_rate);
                if s0 > 0.0 && s1 < 0.0 {
                    let r = loomkin_numeric::bisect(a, b, |t| {
                        let q = frames[i].eval(pc, t);
                        q.power_w * q.power_rate > 0.0
                    });
                    take_max(&mut out.frame_peak[i], frames[i].eval(pc, r).power_w.abs(), r - w0);
                }
                if (p0.power_w > 0.0) != (p1.power_w > 0.0) {
                    let pos = p0.power_w > 0.0;
                    zeros.push(loomkin_numeric::bisect(a, b, |t| (frames[i].eval(pc, t).power_w > 0.0) == pos));
                }
            }
        }
        zeros.sort_by(f64::total_cmp);
        for z in zeros.windows(2) {
            let (a, b) = (z[0], z[1]);
            if b <= a {
                continue;
            }
            // Two panels of 8-point Gauss–Legendre.
            let half = 0.5 * (b - a);
            for panel in 0..2 {
                let lo = a + panel as f64 * half;
                for &(x, w) in &rule {
                    let th = lo + 0.5 * half * (x + 1.0);
                    let wt = 0.5 * half * w * dt;
                    eval_all(th, &mut scratch);
                    let p = net(&scratch).0;
                    if p >= 0.0 {
                        out.supplied_j += wt * p;
                    } else {
                        out.braking_j -= wt * p;
                    }
                    for i in 0..n {
                        let pi = scratch[i].power_w;
                        out.frame_energy_j[i] += wt * pi;
                        if pi < 0.0 {
                            out.regenerated_j -= wt * eta_r * pi;
                        }
                    }
                }
            }
        }
    }
    out
}
