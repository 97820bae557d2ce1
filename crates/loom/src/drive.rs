//! The shedding drive: the force on every frame and the torque the main shaft delivers.
//!
//! Frame `i` at height `y` over mid-stroke (θ the main-shaft angle, ω its speed) needs
//!
//! $$ F_i = m_i(\omega^2 y'' + g) + F_{0,i} + k_i\,(y + H_i/2) + N_i\,T(\varepsilon_i)\,\frac{\partial L_i}{\partial y}, \qquad T(\varepsilon) = T_0 + K\varepsilon, $$
//!
//! (inertia and weight, the return spring from its preload at the bottom of the stroke, and the
//! `N_i` warp ends through the frame's eyes, whose tension grows with the strain `ε_i` and whose
//! length `L_i` the lift stretches). By power balance `T·ω = Σ F_i·v_i / η` with `v_i = ω·y'_i`,
//!
//! $$ T(\theta) = \frac{1}{\eta} \sum_i F_i\, y'_i(\theta) \quad [\mathrm{N\,m}], $$
//!
//! and the same torque is `dE/dθ / η` of the energy stored in the frames, springs and warp
//! ([`Drive::energy_j`]) — the independent route the tests take.

use crate::geometry::{straight_length, thread_length};
use crate::turn_rows::{MAX_WHOLE_TURNS, rms_from_rows};
use crate::turns::Turns;
use crate::{FrameKin, G_M_S2, Loom, Motion, Pattern};
use loomkin_laws::gauss_legendre;
use serde::Serialize;

/// The forces on one frame at one angle, N (positive up: what the drive must push with).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FrameForce {
    /// `m·a`.
    pub inertia_n: f64,
    /// `m·g`.
    pub weight_n: f64,
    /// The return spring.
    pub spring_n: f64,
    /// The warp ends pulling the eyes back to the straight line.
    pub warp_n: f64,
    /// The sum.
    pub total_n: f64,
}

/// Power tables of frames over one move, by frame and grid offset (see [`Drive::torque_curve_cached`]).
#[derive(Debug, Clone, Default)]
#[allow(clippy::type_complexity)]
pub struct TableCache(std::collections::HashMap<(usize, u64, usize), (Vec<f64>, Vec<f64>)>);

/// The largest torque over the repeat.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Peak {
    /// The torque there (signed), N·m.
    pub torque_n_m: f64,
    /// The main-shaft angle, deg (within the repeat).
    pub angle_deg: f64,
}

/// One point of the torque curve.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TorquePoint {
    /// Main-shaft angle, deg (within the repeat).
    pub angle_deg: f64,
    /// Torque the main shaft delivers, N·m.
    pub torque_n_m: f64,
}

/// The shedding torque over the repeat (`loomkin loom torque --json`). The points are a
/// `Vec<TorquePoint>`, or anything serialised as their list (a stream of them, see
/// [`Drive::torque_summary`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TorqueReport<P = Vec<TorquePoint>> {
    /// Main-shaft speed, rpm.
    pub speed_rpm: f64,
    /// Picks in the repeat.
    pub picks: usize,
    /// The repeat, deg.
    pub repeat_deg: f64,
    /// Largest |torque|, N·m (located exactly, see [`Drive::peak_of`]).
    pub peak_torque_n_m: f64,
    /// Where, deg.
    pub peak_angle_deg: f64,
    /// RMS torque over the repeat, N·m.
    pub rms_torque_n_m: f64,
    /// Step of the points, deg (the repeat divided into a whole number of steps).
    pub step_deg: f64,
    /// The curve.
    pub points: P,
}

/// The shedding drive of a loom weaving a pattern.
#[derive(Debug, Clone)]
pub struct Drive<'a> {
    loom: &'a Loom,
    motion: &'a Motion,
    /// Warp ends through each frame.
    ends: Vec<f64>,
    omega: f64,
    l0: f64,
}

impl Drive<'_> {
    /// `step_deg` of a torque curve: 0.01 … 10° (finer is rounding noise between samples; coarser
    /// misses a frame's move of 60°); 0.5° when left out (720 samples a turn).
    pub const STEP_DEG: loomkin_units::Field = loomkin_units::Field::new(
        "step_deg",
        loomkin_units::Range::closed(0.01, 10.0, "deg"),
        "Angle step of the torque curve: 0.01 … 10° (coarser would step over a frame's move); 0.5° \
         (720 samples a turn) when left out.",
    )
    .with_default(0.5);

    /// CPU seconds per point of a torque curve made a turn at a time and written as a CSV row
    /// or a JSON object (`loom torque --csv`/`--json`): 0.6 µs, measured on the reference
    /// machine (release) as the CLI's user time over 1.7·10⁷ points (4,800 picks of 24 frames at
    /// 0.1°: 5.6 s for CSV, 10.4 s for JSON); the `torque_points_24_frames_480_picks` bench
    /// times the points alone.
    pub const CPU_S_PER_POINT: f64 = 0.6e-6;
    /// Bytes held per point of a drawn torque curve ([`crate::torque_figure`]): the curve, the
    /// series and the figure's copies of it, and the drawing's path: 130 bytes, measured as the
    /// CLI's peak memory over 1.7·10⁶ points (480 picks at 0.1°: 229 MB).
    pub const PLOT_BYTES_PER_POINT: f64 = 130.0;
    /// CPU seconds per drawn point, measured as [`Drive::PLOT_BYTES_PER_POINT`] (user time: 2.1 s
    /// over 1.7·10⁶ points to PNG, 10.4 s over 6.9·10⁶ to SVG).
    pub const PLOT_CPU_S_PER_POINT: f64 = 1.5e-6;
}

impl<'a> Drive<'a> {
    /// The drive of `loom` moving `motion` (the frames weaving `pattern`). The loom's warp ends
    /// are shared among the frames by the pattern's threading if it has one, else equally.
    pub fn new(loom: &'a Loom, motion: &'a Motion, pattern: &Pattern) -> Self {
        let n = loom.frame_count();
        let ends = match pattern.ends_per_shaft() {
            Some(e) if e.iter().sum::<usize>() > 0 => {
                let total: usize = e.iter().sum();
                (0..n).map(|i| loom.warp.ends * e.get(i).copied().unwrap_or(0) as f64 / total as f64).collect()
            }
            _ => vec![loom.warp.ends / n as f64; n],
        };
        let g = &loom.geometry;
        Self { loom, motion, ends, omega: loom.speed.rad_per_s(), l0: straight_length(g.back_rest_m, g.warp_line_m) }
    }

    /// Warp ends through each frame.
    pub fn ends(&self) -> &[f64] {
        &self.ends
    }

    /// The motion driven.
    pub fn motion(&self) -> &Motion {
        self.motion
    }

    /// The forces on frame `i` in state `k`.
    pub fn force(&self, i: usize, k: &FrameKin) -> FrameForce {
        let f = &self.loom.frames[i];
        let g = &self.loom.geometry;
        let w = &self.loom.warp;
        let inertia_n = f.mass_kg * self.omega * self.omega * k.d2y;
        let weight_n = f.mass_kg * G_M_S2;
        let spring_n = f.preload_n + f.spring_n_m * (k.y_m + g.stroke_m[i] / 2.0);
        let warp_n = if self.ends[i] > 0.0 {
            let (l, dl, _) = thread_length(g.frame_m[i], g.back_rest_m, g.warp_line_m, k.y_m);
            let strain = l / self.l0 - 1.0;
            self.ends[i] * (w.tension_per_end_n + w.stiffness_per_end_n * strain) * dl
        } else {
            0.0
        };
        FrameForce { inertia_n, weight_n, spring_n, warp_n, total_n: inertia_n + weight_n + spring_n + warp_n }
    }

    /// The main-shaft shedding torque at `theta_deg`, N·m.
    pub fn torque_at(&self, theta_deg: f64) -> f64 {
        let mut sum = 0.0;
        for i in 0..self.loom.frame_count() {
            let k = self.motion.frame(i, theta_deg);
            if k.dy != 0.0 {
                sum += self.force(i, &k).total_n * k.dy;
            }
        }
        sum / self.loom.efficiency
    }

    /// Frame `i`'s share of the torque in state `k`, N·m: its force times `y'` over the
    /// efficiency (0 while it dwells).
    pub(crate) fn power(&self, i: usize, k: &FrameKin) -> f64 {
        if k.dy != 0.0 { self.force(i, k).total_n * k.dy / self.loom.efficiency } else { 0.0 }
    }

    /// The energy stored at `theta_deg`, J: kinetic `½mω²y'²`, potential `m·g·y`, the springs
    /// `F₀(y + H/2) + ½k(y + H/2)²` and the warp `N(T₀ΔL + K·ΔL²/(2L₀))`. At η = 1 the torque
    /// is its derivative `dE/dθ`.
    pub fn energy_j(&self, theta_deg: f64) -> f64 {
        let g = &self.loom.geometry;
        let w = &self.loom.warp;
        (0..self.loom.frame_count())
            .map(|i| {
                let k = self.motion.frame(i, theta_deg);
                let f = &self.loom.frames[i];
                let ext = k.y_m + g.stroke_m[i] / 2.0;
                let (l, _, _) = thread_length(g.frame_m[i], g.back_rest_m, g.warp_line_m, k.y_m);
                let dl = l - self.l0;
                0.5 * f.mass_kg * (self.omega * k.dy).powi(2)
                    + f.mass_kg * G_M_S2 * k.y_m
                    + f.preload_n * ext
                    + 0.5 * f.spring_n_m * ext * ext
                    + self.ends[i] * (w.tension_per_end_n * dl + w.stiffness_per_end_n * dl * dl / (2.0 * self.l0))
            })
            .sum()
    }

    /// The torque at every `step_deg` over the repeat, from 0 (inclusive) to the repeat's end
    /// (exclusive), as `(angle_deg, torque_n_m)`.
    ///
    /// When `step_deg` divides 360°, every move of a frame in one direction meets the grid at the
    /// same fractions of its motion, so each frame's power over a rise and over a fall is
    /// computed once and added at every move (exact, and independent of the number of picks);
    /// otherwise every point is evaluated directly.
    pub fn torque_curve(&self, step_deg: f64) -> Vec<(f64, f64)> {
        self.torque_curve_cached(step_deg, &mut TableCache::default())
    }

    /// [`Drive::torque_curve`] keeping each frame's power tables in `cache`, keyed by the frame and
    /// where its moves meet the grid: a search that shifts frames by multiples of the step's
    /// divisors (the stagger search) reuses them. Use one cache per loom, pattern and step.
    pub fn torque_curve_cached(&self, step_deg: f64, cache: &mut TableCache) -> Vec<(f64, f64)> {
        let (h, t) = self.torque_values_cached(step_deg, cache);
        t.into_iter().enumerate().map(|(k, v)| (k as f64 * h, v)).collect()
    }

    /// The points of [`Drive::torque_curve`] (the same values, in order) made a turn at a time as
    /// they are read: what is held does not grow with the number of picks (a table of 10⁵ picks
    /// at 0.1° is 3.6·10⁸ points).
    pub fn torque_points(&self, step_deg: f64) -> TorquePoints<'_, 'a> {
        let mut cache = TableCache::default();
        let grid = self.grid(step_deg, &mut cache);
        TorquePoints { drive: self, buf: vec![0.0; grid.per_turn], grid, cache, k: 0 }
    }

    /// The number of points of the torque curve at `step_deg` (the repeat divided into a whole
    /// number of steps), known before any is made.
    pub fn curve_len(&self, step_deg: f64) -> usize {
        Self::curve_len_of(self.motion.repeat_deg(), step_deg)
    }

    fn curve_len_of(period: f64, step_deg: f64) -> usize {
        (period / step_deg).round().max(1.0) as usize
    }

    /// What the torque curve at `step_deg` costs, estimated before it is made: streamed as a
    /// table (`plot` false: a turn held, [`Drive::CPU_S_PER_POINT`] each) or drawn (every point
    /// held, [`Drive::PLOT_BYTES_PER_POINT`] each).
    pub fn curve_cost(&self, step_deg: f64, plot: bool) -> loomkin_units::Cost {
        let n = self.motion.repeat_deg() / step_deg;
        if plot {
            loomkin_units::Cost::cpu_items(n, Self::PLOT_BYTES_PER_POINT, Self::PLOT_CPU_S_PER_POINT)
        } else {
            loomkin_units::Cost::cpu_items(n, 0.0, Self::CPU_S_PER_POINT)
        }
    }

    /// The torque report at `step_deg` with `points` for its curve (a list, or a stream of
    /// [`Drive::torque_points`] serialised as it is read): the peak found a turn at a time
    /// ([`Drive::peak`], equal to [`Drive::peak_of`] of the whole curve), so the same report as
    /// [`Drive::torque_report`] of [`Drive::torque_curve`] without the curve held.
    pub fn torque_summary<P>(&self, step_deg: f64, points: P) -> TorqueReport<P> {
        self.report_with(self.peak(step_deg), self.curve_len(step_deg), points)
    }

    /// The torque report of a curve of `n` points whose peak is `peak`.
    fn report_with<P>(&self, peak: Peak, n: usize, points: P) -> TorqueReport<P> {
        TorqueReport {
            speed_rpm: self.loom.speed.rpm(),
            picks: self.motion.picks(),
            repeat_deg: self.motion.repeat_deg(),
            peak_torque_n_m: peak.torque_n_m.abs(),
            peak_angle_deg: peak.angle_deg,
            rms_torque_n_m: self.rms(),
            step_deg: self.motion.repeat_deg() / n as f64,
            points,
        }
    }

    /// The torques of [`Drive::torque_curve_cached`] without their angles, and the step `h`
    /// between them (the k-th at `k·h`).
    fn torque_values_cached(&self, step_deg: f64, cache: &mut TableCache) -> (f64, Vec<f64>) {
        let g = self.grid(step_deg, cache);
        let mut t = Vec::with_capacity(g.n);
        self.for_each_value(&g, cache, &|_| {}, |v| t.push(v));
        (g.h, t)
    }

    /// The grid of a torque curve at `step_deg`, with every frame's power tables put in `cache`.
    fn grid(&self, step_deg: f64, cache: &mut TableCache) -> Grid {
        let period = self.motion.repeat_deg();
        let n = Self::curve_len_of(period, step_deg);
        let h = period / n as f64;
        let per_turn = 360.0 / h;
        if (per_turn - per_turn.round()).abs() > 1e-9 * per_turn {
            return Grid { h, n, per_turn: 0, frames: Vec::new() };
        }
        let phi = self.motion.motion_deg();
        let frames = (0..self.loom.frame_count())
            .map(|i| {
                if self.motion.move_count(i) == 0 {
                    return None;
                }
                // Grid index of the first point at or after the start of a move into pick 0.
                let w0 = self.motion.centre0_deg(i) - phi / 2.0;
                let k0 = (w0 / h - 1e-12).ceil() as i64;
                let x0 = (k0 as f64 * h - w0) / phi;
                let dx = h / phi;
                let count = ((1.0 - x0) / dx).ceil().max(0.0) as usize;
                let table = |rising: bool| -> Vec<f64> {
                    (0..count)
                        .map(|j| {
                            let k = self.motion.moving(i, rising, x0 + j as f64 * dx);
                            self.force(i, &k).total_n * k.dy / self.loom.efficiency
                        })
                        .collect()
                };
                let key = (i, x0.to_bits(), count);
                cache.0.entry(key).or_insert_with(|| (table(true), table(false)));
                Some((k0, key))
            })
            .collect();
        Grid { h, n, per_turn: per_turn.round() as usize, frames }
    }

    /// Calls `f` with the torque at every point of grid `g`, in order (`k·h`, k = 0 … n − 1),
    /// holding one turn of points at a time.
    ///
    /// When `h` divides 360°, every move of a frame in one direction meets the grid at the same
    /// fractions of its motion, so its power tables (computed once, in `cache`) are added at
    /// every move: the points of turn `p` get, frame by frame in order, the tables of the moves
    /// into the picks around `p` (the move into pick `q` meets the grid from index
    /// `k0 + q·per_turn`). Otherwise every point is evaluated directly.
    /// `turn_done(p)` is called once the first `p` turns are read (at the end only when every
    /// point is evaluated directly).
    fn for_each_value(&self, g: &Grid, cache: &TableCache, turn_done: &dyn Fn(usize), mut f: impl FnMut(f64)) {
        if g.per_turn == 0 {
            (0..g.n).for_each(|k| f(self.torque_at(k as f64 * g.h)));
            turn_done(self.motion.picks());
            return;
        }
        let mut buf = vec![0.0; g.per_turn];
        let tables = Self::tables(g, cache);
        for p in 0..self.motion.picks() {
            self.fill_turn_from(g, &tables, p, &mut buf);
            buf.iter().for_each(|&v| f(v));
            turn_done(p + 1);
        }
    }

    /// The largest |T| (or, with `rms`, the RMS) of the torque at every `step_deg` over the
    /// repeat (the values of [`Drive::torque_curve_cached`]), each distinct turn of `turns` (a
    /// grouping that holds for this motion) read once: what the stagger search minimises.
    pub(crate) fn grid_objective(&self, step_deg: f64, cache: &mut TableCache, turns: &Turns, rms: bool) -> f64 {
        let g = self.grid(step_deg, cache);
        if g.per_turn == 0 {
            let (_, t) = self.torque_values_cached(step_deg, cache);
            return if rms {
                (t.iter().map(|t| t * t).sum::<f64>() / t.len() as f64).sqrt()
            } else {
                t.iter().map(|t| t.abs()).fold(0.0, f64::max)
            };
        }
        let mut buf = vec![0.0; g.per_turn];
        let (mut max, mut squares) = (0.0, 0.0);
        let tables = Self::tables(&g, cache);
        for (&p, &count) in turns.first.iter().zip(&turns.count) {
            self.fill_turn_from(&g, &tables, p, &mut buf);
            if rms {
                squares += count as f64 * buf.iter().map(|t| t * t).sum::<f64>();
            } else {
                max = buf.iter().map(|t| t.abs()).fold(max, f64::max);
            }
        }
        if rms { (squares / g.n as f64).sqrt() } else { max }
    }

    /// The torques of turn `p`'s points of grid `g` (one whose step divides 360°) into `buf`.
    fn fill_turn(&self, g: &Grid, cache: &TableCache, p: usize, buf: &mut [f64]) {
        self.fill_turn_from(g, &Self::tables(g, cache), p, buf);
    }

    /// Every frame's grid index and power tables of grid `g` (`None`: the frame never moves),
    /// looked up in `cache` once for all the turns read.
    fn tables<'c>(g: &Grid, cache: &'c TableCache) -> Vec<Option<FrameTables<'c>>> {
        g.frames
            .iter()
            .map(|f| f.as_ref().and_then(|(k0, key)| cache.0.get(key).map(|(u, d)| (*k0, &u[..], &d[..]))))
            .collect()
    }

    /// [`Drive::fill_turn`] with the tables looked up ([`Drive::tables`]).
    fn fill_turn_from(&self, g: &Grid, tables: &[Option<FrameTables<'_>>], p: usize, buf: &mut [f64]) {
        buf.fill(0.0);
        let pt = g.per_turn as i64;
        for (i, frame) in tables.iter().enumerate() {
            let Some((k0, up, down)) = *frame else { continue };
            let count = up.len() as i64;
            // Moves into picks p + dq with a point in the turn: 0 ≤ k0 + dq·pt + j < pt, j < count.
            let lo = -(k0 + count - 1).div_euclid(pt);
            let hi = (pt - 1 - k0).div_euclid(pt);
            for dq in lo..=hi {
                let q = p as i64 + dq;
                let rising = self.motion.is_up(i, q);
                if rising == self.motion.is_up(i, q - 1) {
                    continue;
                }
                let tab = if rising { up } else { down };
                let off = k0 + dq * pt;
                let (from, to) = ((-off).max(0), count.min(pt - off));
                for j in from..to {
                    buf[(off + j) as usize] += tab[j as usize];
                }
            }
        }
    }

    /// The torque report of a curve already computed ([`Drive::torque_curve`]).
    pub fn torque_report(&self, curve: &[(f64, f64)]) -> TorqueReport {
        let points = curve.iter().map(|&(angle_deg, torque_n_m)| TorquePoint { angle_deg, torque_n_m }).collect();
        self.report_with(self.peak_of(curve), curve.len(), points)
    }

    /// The largest |torque| over the repeat: the grid's largest local maxima of |T| (at
    /// `step_deg`) refined by golden-section search between their neighbours. The grid is read
    /// one turn at a time (see [`Drive::torque_curve`]): what it holds does not grow with the
    /// number of picks.
    pub fn peak(&self, step_deg: f64) -> Peak {
        self.peak_with(step_deg, &|_| {})
    }

    /// [`Drive::peak`], calling `turn_done(p)` once the grid's first `p` turns are read.
    pub(crate) fn peak_with(&self, step_deg: f64, turn_done: &dyn Fn(usize)) -> Peak {
        let mut cache = TableCache::default();
        let g = self.grid(step_deg, &mut cache);
        let last = if g.per_turn == 0 {
            self.torque_at((g.n - 1) as f64 * g.h)
        } else {
            let mut buf = vec![0.0; g.per_turn];
            self.fill_turn(&g, &cache, self.motion.picks() - 1, &mut buf);
            buf[g.per_turn - 1]
        };
        let mut top = TopPeaks::new(g.n, last);
        self.for_each_value(&g, &cache, turn_done, |v| top.push(v));
        self.refine_peaks(g.h, |k| k as f64 * g.h, top.finish())
    }

    /// [`Drive::peak`] from a torque curve already computed.
    pub fn peak_of(&self, curve: &[(f64, f64)]) -> Peak {
        let n = curve.len();
        if n == 0 {
            return Peak { torque_n_m: 0.0, angle_deg: 0.0 };
        }
        let h = if n > 1 { curve[1].0 - curve[0].0 } else { self.motion.repeat_deg() };
        let mut top = TopPeaks::new(n, curve[n - 1].1);
        curve.iter().for_each(|&(_, t)| top.push(t));
        self.refine_peaks(h, |k| curve[k].0, top.finish())
    }

    /// The peak among the candidates of a grid `h` apart (the k-th at `angle(k)`, see
    /// [`TopPeaks`]): each refined on its two neighbouring intervals
    /// ([`loomkin_numeric::golden_max`]); of peaks within 1e-13 of the highest, the earliest in
    /// the repeat.
    fn refine_peaks(&self, h: f64, angle: impl Fn(usize) -> f64, top: Vec<(f64, usize, f64)>) -> Peak {
        let Some(&(a0, k0, t0)) = top.first() else {
            return Peak { torque_n_m: 0.0, angle_deg: 0.0 };
        };
        let repeat = self.motion.repeat_deg();
        // (|T|, angle within the repeat, T) of the grid's best point and of every refined candidate.
        let mut found = vec![(a0, angle(k0), t0)];
        for &(_, k, _) in &top {
            let m = loomkin_numeric::golden_max(|x| self.torque_at(x).abs(), angle(k) - h, angle(k) + h);
            found.push((m.value, m.at.rem_euclid(repeat), self.torque_at(m.at)));
        }
        // Peaks equal to rounding (within 1e-13: a symmetric pattern's mirror images) are told
        // apart by their last bits alone; the earliest in the repeat is reported.
        let top_value = found.iter().map(|f| f.0).fold(f64::NEG_INFINITY, f64::max);
        let (_, angle_deg, torque_n_m) = found
            .into_iter()
            .filter(|f| f.0 >= top_value * (1.0 - 1e-13))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((0.0, 0.0, 0.0));
        Peak { torque_n_m, angle_deg }
    }

    /// The RMS torque over the repeat, N·m: `√(∫T²dθ / repeat)` by 16-point Gauss–Legendre on
    /// panels between the joints of every frame's motion (where T is smooth), each at most 20° wide,
    /// halved where the rule on a panel and on its two halves disagree.
    ///
    /// T is smooth between the joints, but not always on the scale of a panel: a frame whose eye
    /// passes within a fraction of a millimetre of the fell or of the back rest level (a back frame
    /// 0.1 mm before the back rest) turns its warp pull `∂L/∂y` from −1 to +1 over that fraction,
    /// and one 16-point rule over 20° then missed the RMS by 1.4e-4 (against 0.02° panels). A panel
    /// is accepted when its two halves change its integral by at most 1e-13 of the first pass's
    /// whole integral scaled to the panel's share of the repeat, or by 1e-13 of its own integral
    /// (rounding), or after 30 halvings (2e-8° for a 20° panel); [`MAX_RMS_SPLITS`] halvings in all.
    ///
    /// A tiny efficiency (η below ~1e-150, inside its range) makes T² overflow while T itself is
    /// finite: the integral is then taken of `(T·2^e)²`, 2^e the power of two at or below η (at
    /// least 2^-1022; an exact scaling), and the root divided by 2^e, so the RMS is finite wherever the torque is.
    pub fn rms(&self) -> f64 {
        let rms = self.rms_scaled(1.0);
        let eta = self.loom.efficiency;
        if rms.is_finite() || !(eta > 0.0 && eta < 1.0) {
            return rms;
        }
        // At least 2^-1022: `powi` of a smaller power underflows to 0 (and T·0 would be NaN).
        let k = 2f64.powi((eta.log2().floor() as i32).max(-1022));
        self.rms_scaled(k) / k
    }

    /// [`Drive::rms`] of the torque times `k` (a power of two: exact): the integral of `(kT)²`
    /// turn by turn, once per distinct turn (turns whose frames move alike, see
    /// [`crate::turns`]) times the picks that repeat it.
    fn rms_scaled(&self, k: f64) -> f64 {
        match Turns::new_within(self.motion, 0.0, 360.0, MAX_WHOLE_TURNS) {
            Some(turns) => self.rms_of_turns(&turns, k),
            None => rms_from_rows(self, k, MAX_RMS_SPLITS)
                .unwrap_or_else(|| self.rms_of_turns(&Turns::new(self.motion, 0.0, 360.0), k)),
        }
    }

    /// [`Drive::rms_scaled`] turn by turn, once per distinct turn of `turns`.
    pub(crate) fn rms_of_turns(&self, turns: &Turns, k: f64) -> f64 {
        let rule = gauss_legendre(16);
        let mut splits = 0usize;
        let mut sum = 0.0;
        for (&p, &count) in turns.first.iter().zip(&turns.count) {
            let a = 360.0 * p as f64;
            sum += count as f64 * self.square_integral(a, a + 360.0, k, &rule, &mut splits);
        }
        (sum / self.motion.repeat_deg()).sqrt()
    }

    /// `∫(kT)²dθ` over `[from, to]` (one turn): 16-point Gauss–Legendre on panels between the
    /// joints (at most 20° wide), halved where a panel and its two halves disagree (see
    /// [`Drive::rms`]); `splits` counts the halvings, [`MAX_RMS_SPLITS`] in all.
    fn square_integral(&self, from: f64, to: f64, k: f64, rule: &[(f64, f64)], splits: &mut usize) -> f64 {
        let gl = |a: f64, b: f64| -> f64 {
            let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
            rule.iter()
                .map(|&(x, wt)| {
                    let t = self.torque_at(mid + half * x) * k;
                    half * wt * t * t
                })
                .sum()
        };
        let mut panels = Vec::new();
        for w in self.motion.joints_between(from, to).windows(2) {
            let (a, b) = (w[0], w[1]);
            let parts = ((b - a) / 20.0).ceil().max(1.0) as usize;
            let hp = (b - a) / parts as f64;
            for p in 0..parts {
                let (pa, pb) = (a + p as f64 * hp, if p + 1 == parts { b } else { a + (p + 1) as f64 * hp });
                panels.push((pa, pb, gl(pa, pb)));
            }
        }
        let first: f64 = panels.iter().map(|p| p.2).sum();
        let span = to - from;
        let mut sum = 0.0;
        let mut stack: Vec<(f64, f64, f64, u32)> = panels.into_iter().map(|(a, b, i)| (a, b, i, 0)).collect();
        while let Some((a, b, whole, depth)) = stack.pop() {
            let m = 0.5 * (a + b);
            let (left, right) = (gl(a, m), gl(m, b));
            let tol = (1e-13 * first * (b - a) / span).max(1e-13 * (left + right));
            // A sum that is not finite (a torque that overflows) is not refined further, and the
            // halvings are bounded in all: a torque whose rounding noise stays above the
            // tolerance (a loom of micrometres with a million ends) would halve every panel to
            // the depth limit.
            let settled = (left + right - whole).abs() <= tol || !(left + right).is_finite();
            if settled || depth >= 30 || *splits >= MAX_RMS_SPLITS {
                sum += left + right;
            } else {
                *splits += 1;
                stack.push((a, m, left, depth + 1));
                stack.push((m, b, right, depth + 1));
            }
        }
        sum
    }
}

/// The grid of a torque curve: `n` points `h` apart over the repeat; when `h` divides 360°
/// (`per_turn` points a turn, else 0), per moving frame the grid index `k0` at which its moves
/// into pick 0 meet the grid and the key of its power tables in the [`TableCache`].
/// The points of a torque curve made a turn at a time ([`Drive::torque_points`]):
/// `(angle_deg, torque_n_m)`.
#[derive(Debug)]
pub struct TorquePoints<'d, 'a> {
    drive: &'d Drive<'a>,
    grid: Grid,
    cache: TableCache,
    /// The turn being read (empty when every point is evaluated directly).
    buf: Vec<f64>,
    /// The next point.
    k: usize,
}

impl Iterator for TorquePoints<'_, '_> {
    type Item = (f64, f64);

    fn next(&mut self) -> Option<(f64, f64)> {
        let Self { drive, grid, cache, buf, k } = self;
        if *k >= grid.n {
            return None;
        }
        let at = *k as f64 * grid.h;
        let v = if grid.per_turn == 0 {
            drive.torque_at(at)
        } else {
            let j = *k % grid.per_turn;
            if j == 0 {
                drive.fill_turn(grid, cache, *k / grid.per_turn, buf);
            }
            buf[j]
        };
        *k += 1;
        Some((at, v))
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.grid.n - self.k;
        (left, Some(left))
    }
}

impl ExactSizeIterator for TorquePoints<'_, '_> {}

#[derive(Debug)]
struct Grid {
    h: f64,
    n: usize,
    per_turn: usize,
    frames: Vec<Option<(i64, TableKey)>>,
}

/// A frame's grid index of its moves into pick 0 and its power tables up and down.
type FrameTables<'c> = (i64, &'c [f64], &'c [f64]);

/// A frame's power tables in the [`TableCache`]: the frame, the grid's phase in its move (bits), the points.
type TableKey = (usize, u64, usize);

/// The six largest local maxima of |T| of a periodic grid read in order, kept as it is read (a
/// dwell's flat torque makes every point a local maximum): `(|T|, k, T)`, largest first, a tie
/// to the earlier point.
struct TopPeaks {
    n: usize,
    /// The two latest values (the point before the one under test, and it).
    prev: f64,
    cur: f64,
    /// Values read so far.
    read: usize,
    first: f64,
    top: Vec<(f64, usize, f64)>,
}

impl TopPeaks {
    const CANDIDATES: usize = 6;

    /// For a grid of `n` points whose last value is `last` (the first point's neighbour).
    fn new(n: usize, last: f64) -> Self {
        Self { n, prev: f64::NAN, cur: last, read: 0, first: 0.0, top: Vec::with_capacity(Self::CANDIDATES + 1) }
    }

    /// The next value of the grid.
    fn push(&mut self, v: f64) {
        if self.read == 0 {
            self.first = v;
        } else {
            self.test(self.read - 1, v);
        }
        (self.prev, self.cur) = (self.cur, v);
        self.read += 1;
    }

    /// Whether point `k` (value `cur`, neighbours `prev` and `next`) is a candidate.
    fn test(&mut self, k: usize, next: f64) {
        let a = self.cur.abs();
        if a >= self.prev.abs() && a >= next.abs() {
            let at = self.top.partition_point(|&(v, _, _)| v >= a);
            if at < Self::CANDIDATES {
                self.top.insert(at, (a, k, self.cur));
                self.top.truncate(Self::CANDIDATES);
            }
        }
    }

    /// The candidates, once all `n` values are read.
    fn finish(mut self) -> Vec<(f64, usize, f64)> {
        if self.read == self.n && self.n > 0 {
            self.test(self.n - 1, self.first);
        }
        self.top
    }
}

/// Most panel halvings of [`Drive::rms`] (each 32 torque evaluations): the back frame 0.1 mm
/// before the back rest takes 19, the examples none.
pub const MAX_RMS_SPLITS: usize = 4096;
