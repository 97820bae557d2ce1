//! The timing of the shed and the weft carrier: clear shed height, clearance, the window in which
//! the carrier passes, and the highest loom speed.
//!
//! At main-shaft angle θ in the turn of pick `p`, the clear shed at distance `x` from the fell is
//! the gap from the lowest end of the upper sheet (the frames up at pick `p`) down to the highest
//! end of the lower sheet, `x·(min_up y_i/d_i − max_down y_j/d_j)`. The carrier (height `h_c`,
//! width `w_c` along the warp, pressed against the reed at `x_r`) sees the narrowest gap at its
//! front edge `x_c = x_r − w_c`; its clearance is the gap there less `h_c`.
//!
//! The carrier flies the reed space `W` plus its own length `L_s` at a mean speed `v̄` while the
//! main shaft turns through the window `θ_w` in which the shed clears it, so the highest speed is
//!
//! $$ n_{max} = \frac{\bar v\,\theta_w}{6\,(W + L_s)} \quad [\mathrm{rpm}], $$
//!
//! (θ_w in degrees, v̄ in m/s, lengths in m): 213 picks/min for 13.75 m/s, 135°, 1.15 m and 0.30 m.

use crate::geometry::Sheets;
use crate::turn_rows::{FrameStates, MAX_WHOLE_TURNS, SlopeRows};
use crate::turns::{Turns, lift_key};
use crate::{Loom, LoomError, Motion, Pattern, Result, crossing_offset_deg};
use serde::Serialize;

/// What the timing of the shed reads of the frames: each frame's height at any angle of the main
/// shaft, and which picks see the same motion. The dobby's [`Motion`] (one law, one motion angle,
/// a stagger per frame) and the servo frames' plans ([`crate::ServoMotion`]: a motion angle and a
/// centre per frame, moves laid end to end) both give it, so the clear shed, its window and the
/// clearance to the carrier are worked out by one code path ([`Timing`]).
pub trait ShedMotion {
    /// Frames, front first.
    fn frame_count(&self) -> usize;
    /// Picks in the repeat.
    fn picks(&self) -> usize;
    /// Frame `i`'s height over mid-stroke at main-shaft angle `theta_deg` (any angle: the motion
    /// repeats), m.
    fn frame_y_m(&self, i: usize, theta_deg: f64) -> f64;
    /// Frame `i`'s height over mid-stroke where it rests over all of `[from_deg, to_deg]`
    /// (main-shaft angles), m: [`ShedMotion::frame_y_m`] at every angle of the span, bit for bit.
    /// `None` when it moves there, or when the motion does not tell (the default: every height is
    /// then evaluated).
    fn frame_rest_m(&self, _i: usize, _from_deg: f64, _to_deg: f64) -> Option<f64> {
        None
    }
    /// Appends to `key` words naming what every frame does over `[360p + from_deg, 360p +
    /// to_deg]` (`p = pick`): two picks with equal words see the same heights over their spans.
    fn turn_key(&self, pick: usize, from_deg: f64, to_deg: f64, key: &mut Vec<u64>);
}

impl ShedMotion for Motion {
    fn frame_count(&self) -> usize {
        self.frames()
    }

    fn picks(&self) -> usize {
        Motion::picks(self)
    }

    fn frame_y_m(&self, i: usize, theta_deg: f64) -> f64 {
        self.frame(i, theta_deg).y_m
    }

    /// The lifts of the picks the span reads (see `crate::turns`).
    fn turn_key(&self, pick: usize, from_deg: f64, to_deg: f64, key: &mut Vec<u64>) {
        let (cmin, cmax) = (0..self.frames())
            .map(|i| self.centre0_deg(i))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), c| (a.min(c), b.max(c)));
        lift_key(self, pick, from_deg, to_deg, cmin, cmax, key);
    }
}

pub use loomkin_insertion::max_speed_rpm;

/// The window of one pick in which the shed clears the carrier.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PickWindow {
    /// The pick (1 = first).
    pub pick: usize,
    /// Angle in the pick's turn at which the clearance becomes positive, deg.
    pub open_deg: f64,
    /// Angle at which it ends, deg.
    pub close_deg: f64,
    /// The least clearance over the required insertion (entry to exit), mm (negative: the carrier touches).
    pub min_clearance_mm: f64,
}

/// The timing of a loom weaving a pattern.
#[derive(Debug, Clone, Serialize)]
pub struct TimingReport {
    /// Per pick.
    pub picks: Vec<PickWindow>,
    /// The window common to every pick: from the latest opening to the earliest closing, deg.
    pub open_deg: f64,
    /// See `open_deg`.
    pub close_deg: f64,
    /// Its length, deg.
    pub window_deg: f64,
    /// The least clearance over the required insertion of every pick, mm.
    pub min_clearance_mm: f64,
    /// The carrier's mean speed across the shed, m/s.
    pub mean_speed_m_s: f64,
    /// The highest loom speed at which the carrier passes in the common window, rpm.
    pub max_speed_rpm: f64,
    /// Largest clear height at the carrier's front edge over the repeat, mm.
    pub max_clear_mm: f64,
}

/// The shed seen by the carrier of a loom weaving a pattern, the frames moving by `M` (the
/// dobby's [`Motion`], or the servo frames' plans).
#[derive(Debug, Clone)]
pub struct Timing<'a, M: ShedMotion + ?Sized = Motion> {
    loom: &'a Loom,
    motion: &'a M,
    /// `upper[p·n + i]`: frame `i` in the upper sheet at pick `p` (`n` frames; one allocation
    /// however long the repeat).
    upper: Vec<bool>,
    delta: f64,
    x_c: f64,
}

impl<'a, M: ShedMotion + ?Sized> Timing<'a, M> {
    /// The timing of `loom` moving `motion` (weaving `pattern`). The pattern must be weavable on
    /// the loom ([`crate::check_weavable`], as [`Motion::new`] checks it).
    pub fn new(loom: &'a Loom, motion: &'a M, pattern: &Pattern) -> Result<Self> {
        let n = loom.frame_count();
        crate::pattern::check_weavable(pattern, n)?;
        if motion.frame_count() != n {
            return Err(LoomError::field(
                "geometry.frames",
                format!("the motion moves {} frames, the loom has {n}", motion.frame_count()),
            ));
        }
        // Row by row, the frames beyond the pattern's shafts down ([`Pattern::is_up`]).
        let mut upper: Vec<bool> = Vec::with_capacity(pattern.picks() * n);
        for row in pattern.rows() {
            upper.extend((0..n).map(|i| row.get(i).copied().unwrap_or(false)));
        }
        let x_c = loom.geometry.reed_m - loom.insertion.carrier_width_m;
        Ok(Self { loom, motion, upper, delta: crossing_offset_deg(loom.shedding.crossing_deg), x_c })
    }

    /// Distance of the carrier's front edge from the fell, m.
    pub fn carrier_edge_m(&self) -> f64 {
        self.x_c
    }

    /// The clear shed height at distance `x` from the fell at absolute angle `theta_deg`, for pick
    /// `pick`'s sheets, m.
    pub fn clear_m(&self, pick: usize, x: f64, theta_deg: f64) -> f64 {
        self.clear_with(pick, x, |i| self.motion.frame_y_m(i, theta_deg))
    }

    /// [`Timing::clear_m`] of the frames' heights `y(i)`, m.
    fn clear_with(&self, pick: usize, x: f64, y_of: impl Fn(usize) -> f64) -> f64 {
        let n = self.loom.frame_count();
        // The frames' positions on the stack up to 64 frames (this runs at every angle of every
        // scan: an allocation per call was a tenth of the clearance's time).
        let mut stack = [0.0; 64];
        let mut heap = Vec::new();
        let y: &mut [f64] = if n <= stack.len() {
            &mut stack[..n]
        } else {
            heap.resize(n, 0.0);
            &mut heap
        };
        for (i, yi) in y.iter_mut().enumerate() {
            *yi = y_of(i);
        }
        let row = pick % (self.upper.len() / n) * n;
        self.loom.geometry.clear_height(x, y, &self.upper[row..row + n]).unwrap_or(0.0)
    }

    /// The clearance to the carrier at angle `angle_deg` of pick `pick`'s turn, m.
    pub fn clearance_m(&self, pick: usize, angle_deg: f64) -> f64 {
        self.clear_m(pick, self.x_c, 360.0 * pick as f64 + angle_deg) - self.loom.insertion.carrier_height_m
    }

    /// The frames of pick `pick`'s sheets resting over all of `[from_deg, to_deg]` of its turn
    /// ([`ShedMotion::frame_rest_m`]) added once, and the others: a pick's scans evaluate only
    /// the moving frames at each angle.
    fn resting(&self, pick: usize, from_deg: f64, to_deg: f64) -> Resting {
        let origin = 360.0 * pick as f64;
        let mut out = Resting { sheets: Sheets::EMPTY, moving: Vec::new() };
        for (i, &up) in self.upper_row(pick).iter().enumerate() {
            match self.motion.frame_rest_m(i, origin + from_deg, origin + to_deg) {
                Some(y) => out.sheets.add(y, self.loom.geometry.frame_m[i], up),
                None => out.moving.push(i),
            }
        }
        out
    }

    /// Pick `pick`'s row of [`Timing::upper`].
    fn upper_row(&self, pick: usize) -> &[bool] {
        let n = self.loom.frame_count();
        let row = pick % (self.upper.len() / n) * n;
        &self.upper[row..row + n]
    }

    /// [`Timing::clear_m`] at angle `angle_deg` of pick `pick`'s turn, the frames resting there
    /// taken from `rest` ([`Timing::resting`] over a span holding the angle): the same value bit
    /// for bit (the sheets' extreme slopes do not depend on the order of the frames).
    fn clear_resting(&self, pick: usize, x: f64, rest: &Resting, angle_deg: f64) -> f64 {
        let theta_deg = 360.0 * pick as f64 + angle_deg;
        let (upper, d) = (self.upper_row(pick), &self.loom.geometry.frame_m);
        let mut sheets = rest.sheets;
        for &i in &rest.moving {
            sheets.add(self.motion.frame_y_m(i, theta_deg), d[i], upper[i]);
        }
        sheets.clear_height(x).unwrap_or(0.0)
    }

    /// [`Timing::clearance_m`] with the frames resting as `rest` gives them.
    fn clearance_resting(&self, pick: usize, rest: &Resting, angle_deg: f64) -> f64 {
        self.clear_resting(pick, self.x_c, rest, angle_deg) - self.loom.insertion.carrier_height_m
    }

    /// The turn of pick `p`, in angles of its own turn: from its crossing to the next.
    fn turn(&self) -> (f64, f64) {
        (self.delta, self.delta + 360.0)
    }

    /// Pick `p`'s window (angles in its turn), the least clearance over the required insertion.
    pub fn pick_window(&self, p: usize) -> PickWindow {
        let (a, b) = self.turn();
        let (from, to) = self.span();
        let rest = self.resting(p, from, to);
        let c = |t: f64| self.clearance_resting(p, &rest, t);
        let step = 1.0;
        let n = ((b - a) / step).ceil() as usize;
        let grid: Vec<(f64, f64)> =
            (0..=n).map(|k| (a + k as f64 * (b - a) / n as f64, 0.0)).map(|(t, _)| (t, c(t))).collect();
        // The longest run of positive clearance.
        let (mut best, mut run_start) = (None::<(usize, usize)>, None::<usize>);
        for k in 0..grid.len() {
            if grid[k].1 >= 0.0 {
                run_start.get_or_insert(k);
            }
            if (grid[k].1 < 0.0 || k + 1 == grid.len())
                && let Some(s) = run_start.take()
            {
                let e = if grid[k].1 < 0.0 { k - 1 } else { k };
                if best.is_none_or(|(bs, be)| e - s > be - bs) {
                    best = Some((s, e));
                }
            }
        }
        let (open_deg, close_deg) = match best {
            None => (f64::NAN, f64::NAN),
            Some((s, e)) => {
                let open = if s == 0 { grid[0].0 } else { crossing(&c, grid[s - 1].0, grid[s].0) };
                let close = if e + 1 == grid.len() { grid[e].0 } else { crossing(&c, grid[e].0, grid[e + 1].0) };
                (open, close)
            }
        };
        let ins = &self.loom.insertion;
        PickWindow {
            pick: p + 1,
            open_deg,
            close_deg,
            min_clearance_mm: 1e3 * self.min_over_resting(p, &rest, ins.entry_deg, ins.exit_deg),
        }
    }

    /// The least clearance of pick `p` over `[from, to]` (angles of its turn), m: the grid's
    /// smallest values (1° apart) refined by golden-section search, and both ends.
    pub fn min_over(&self, p: usize, from: f64, to: f64) -> f64 {
        self.min_over_resting(p, &self.resting(p, from.min(to), to.max(from)), from, to)
    }

    /// [`Timing::min_over`] with the frames resting over `[from, to]` at their heights in `rest`.
    fn min_over_resting(&self, p: usize, rest: &Resting, from: f64, to: f64) -> f64 {
        let c = |t: f64| self.clearance_resting(p, rest, t);
        let n = ((to - from) / 1.0).ceil().max(1.0) as usize;
        let h = (to - from) / n as f64;
        let vals: Vec<f64> = (0..=n).map(|k| c(from + k as f64 * h)).collect();
        let mut best = vals.iter().copied().fold(f64::INFINITY, f64::min);
        // Strict local minima of the grid only (a dwell's flat clearance is not refined point by point).
        for k in 1..n {
            let strict = vals[k] < vals[k - 1] || vals[k] < vals[k + 1];
            if strict && vals[k] <= vals[k - 1] && vals[k] <= vals[k + 1] {
                let m = loomkin_numeric::golden_max(|t| -c(t), from + (k - 1) as f64 * h, from + (k + 1) as f64 * h);
                best = best.min(-m.value);
            }
        }
        best
    }

    /// The picks grouped by what the frames do over the span a pick's timing reads (its turn,
    /// from the crossing, and the insertion): each group's numbers are those of its first pick.
    fn turns(&self) -> Turns {
        let (from, to) = self.span();
        Turns::of(self.motion, from, to)
    }

    /// The span of a pick's turn its timing reads, in angles of the turn: the turn, from the
    /// crossing, and the insertion.
    fn span(&self) -> (f64, f64) {
        let ins = &self.loom.insertion;
        let (a, b) = self.turn();
        (a.min(ins.entry_deg).min(ins.exit_deg), b.max(ins.exit_deg).max(ins.entry_deg))
    }

    /// [`Timing::turns`], or `None` once more than `cap` distinct turns are found.
    fn turns_within(&self, cap: usize) -> Option<Turns> {
        let (from, to) = self.span();
        Turns::of_within(self.motion, from, to, cap)
    }

    /// The least clearance over the required insertion of every pick, m (a cheap form for the
    /// stagger search: on a grid of `step_deg` and the ends, not refined), once per distinct turn.
    pub fn min_clearance_coarse(&self, step_deg: f64) -> f64 {
        self.min_clearance_coarse_at(step_deg, &self.turns().first)
    }

    /// [`Timing::min_clearance_coarse`] over the picks `picks` alone, m (what a search compares
    /// when one pick stands for every pick whose turn is the same).
    pub fn min_clearance_coarse_at(&self, step_deg: f64, picks: &[usize]) -> f64 {
        let ins = &self.loom.insertion;
        let n = ((ins.exit_deg - ins.entry_deg) / step_deg).ceil().max(1.0) as usize;
        let h = (ins.exit_deg - ins.entry_deg) / n as f64;
        picks
            .iter()
            .flat_map(|&p| (0..=n).map(move |k| (p, ins.entry_deg + k as f64 * h)))
            .map(|(p, t)| self.clearance_m(p, t))
            .fold(f64::INFINITY, f64::min)
    }

    /// The least clearance over the required insertion of every pick, m ([`Timing::min_over`]
    /// from entry to exit), once per distinct turn.
    pub fn min_clearance_m(&self) -> f64 {
        let ins = &self.loom.insertion;
        self.turns().first.iter().map(|&p| self.min_over(p, ins.entry_deg, ins.exit_deg)).fold(f64::INFINITY, f64::min)
    }

    /// The report: every pick's window, the common window and its length, the least clearance,
    /// and the highest speed. Fails when the carrier is taller than the shed ever opens. Each
    /// distinct turn is computed once (picks that repeat one get its numbers).
    pub fn report(&self) -> Result<TimingReport> {
        self.report_of(true)
    }

    /// [`Timing::report`] with no per-pick list when `picks` is false (what `loom check` prints:
    /// memory that does not grow with the repeat).
    pub fn report_of(&self, picks: bool) -> Result<TimingReport> {
        let turns = self.turns();
        let windows: Vec<PickWindow> = turns.first.iter().map(|&p| self.pick_window(p)).collect();
        let ins = &self.loom.insertion;
        if windows.iter().any(|w| w.open_deg.is_nan()) {
            return Err(self.too_tall(self.max_clear_of(&turns)));
        }
        let open_deg = windows.iter().map(|w| w.open_deg).fold(f64::NEG_INFINITY, f64::max);
        let close_deg = windows.iter().map(|w| w.close_deg).fold(f64::INFINITY, f64::min);
        let window_deg = (close_deg - open_deg).max(0.0);
        let min_clearance_mm = windows.iter().map(|w| w.min_clearance_mm).fold(f64::INFINITY, f64::min);
        let v = ins.mean_speed_m_s(self.loom.speed.rpm());
        let picks = if picks {
            turns.of.iter().enumerate().map(|(p, &c)| PickWindow { pick: p + 1, ..windows[c as usize] }).collect()
        } else {
            Vec::new()
        };
        Ok(TimingReport {
            picks,
            open_deg,
            close_deg,
            window_deg,
            min_clearance_mm,
            mean_speed_m_s: v,
            max_speed_rpm: max_speed_rpm(v, window_deg, ins.reed_width_m, ins.carrier_length_m),
            max_clear_mm: self.max_clear_of(&turns) * 1e3,
        })
    }

    /// The error of a carrier taller than the shed ever opens (`max_clear` m).
    fn too_tall(&self, max_clear: f64) -> LoomError {
        let ins = &self.loom.insertion;
        LoomError::Infeasible {
            field: "insertion.carrier_height_mm".into(),
            reason: format!(
                "the carrier ({:.1} mm) is taller than the shed: it opens at most {:.1} mm at the carrier's front edge, {:.1} mm from the fell",
                ins.carrier_height_m * 1e3,
                max_clear * 1e3,
                self.x_c * 1e3
            ),
        }
    }

    /// The largest clear height at the carrier's front edge over the repeat, m: per pick the
    /// largest of a 5° grid, refined by golden-section search between its neighbours.
    pub fn max_clear_m(&self) -> f64 {
        self.max_clear_of(&self.turns())
    }

    fn max_clear_of(&self, turns: &Turns) -> f64 {
        let (a, b) = self.turn();
        let h = (b - a) / 72.0;
        turns
            .first
            .iter()
            .map(|&p| {
                let rest = self.resting(p, a, b);
                let f = |t: f64| self.clear_resting(p, self.x_c, &rest, t);
                let (k, v) = (0..=72)
                    .map(|k| (k, f(a + h * k as f64)))
                    .fold((0, f64::NEG_INFINITY), |best, kv| if kv.1 > best.1 { kv } else { best });
                let t = a + h * k as f64;
                loomkin_numeric::golden_max(f, (t - h).max(a), (t + h).min(b)).value.max(v)
            })
            .fold(f64::NEG_INFINITY, f64::max)
    }
}

impl Timing<'_, Motion> {
    /// [`Timing::report_of`] without the per-pick list (what `loom check` prints): each distinct
    /// turn worked out whole when there are at most 256, else from rows made once per frame
    /// and run of its lifts (every pick scanned from them, what the report keeps refined on the
    /// exact laws of the picks that can set it) — a repeat of 10⁵ random picks in seconds, the
    /// same numbers to rounding (the tests hold them to 1e-12).
    pub fn summary(&self) -> Result<TimingReport> {
        if self.turns_within(MAX_WHOLE_TURNS).is_some() {
            return self.report_of(false);
        }
        self.summary_from_rows().unwrap_or_else(|| self.report_of(false))
    }

    /// [`Timing::summary`] from rows (`None` when the turn's span reads more than 64 picks).
    ///
    /// Every pick is scanned on the grids [`Timing::pick_window`], [`Timing::min_over`] and
    /// [`Timing::max_clear_m`] lay over its turn, a frame's slope `y/d` there made once per run
    /// of its lifts (`crate::turn_rows`), the pick's clearance the min/max of its frames'
    /// rows. What the report keeps is then refined on the exact laws of the picks that can set
    /// it: the latest opening among the picks whose grid opens in the latest interval and the
    /// earliest closing likewise, by bisection of all of them at once (at each halving the picks
    /// on the far side are the answer's; the others are dropped: the same root as each bisected
    /// alone, the extreme kept); the least clearance and the largest clear height at the grid's
    /// local extremes whose reach ([`loomkin_numeric::GridPeak`]) comes within 1e-12 m of the
    /// best found, by golden section, once per bracket of equal grid values.
    pub(crate) fn summary_from_rows(&self) -> Option<Result<TimingReport>> {
        let motion = self.motion;
        let n = self.loom.frame_count();
        let ins = &self.loom.insertion;
        let (a, b) = self.turn();
        let (from, to) = (a.min(ins.entry_deg).min(ins.exit_deg), b.max(ins.exit_deg).max(ins.entry_deg));
        let mut states = FrameStates::new(motion, from, to)?;
        // The three grids, laid as pick_window, min_over and max_clear_of lay them.
        let wn = (b - a).ceil() as usize;
        let (e0, e1) = (ins.entry_deg, ins.exit_deg);
        let en = (e1 - e0).ceil().max(1.0) as usize;
        let eh = (e1 - e0) / en as f64;
        let mh = (b - a) / 72.0;
        let mut nodes: Vec<f64> = (0..=wn).map(|k| a + k as f64 * (b - a) / wn as f64).collect();
        nodes.extend((0..=en).map(|k| e0 + k as f64 * eh));
        nodes.extend((0..=72).map(|k| a + mh * k as f64));
        let (w_at, e_at, m_at) = (0, wn + 1, wn + en + 2);
        let m = nodes.len();
        let mut rows: Vec<f64> = Vec::new();
        let mut ids = vec![0u32; n];
        let (mut lo_up, mut hi_down, mut clear) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
        let h = ins.carrier_height_m;
        let picks = motion.picks();
        // The latest opening's interval (0: at the turn's start) and its picks; the earliest
        // closing's (wn: at its end) and its picks.
        let (mut open_k, mut open_picks, mut close_k, mut close_picks) = (0usize, Vec::new(), wn, Vec::new());
        let mut shut = false;
        let mut least = f64::INFINITY;
        let mut most = f64::NEG_INFINITY;
        // Local minima of the clearance (pick, node) and local maxima of the clear height to refine.
        // Per bracket (the node and the bits of the grid's three values around it): the first
        // pick met with it and its reach. Brackets of equal values are searched once.
        let (mut minima, mut maxima) = (Brackets::default(), Brackets::default());
        for p in 0..picks {
            for (i, id) in ids.iter_mut().enumerate() {
                let (r, new) = states.row(motion, i, p);
                if new {
                    let d = self.loom.geometry.frame_m[i];
                    rows.extend(nodes.iter().map(|&t| motion.frame_in_turn(i, p, t).y_m / d));
                }
                *id = r;
            }
            lo_up.fill(f64::INFINITY);
            hi_down.fill(f64::NEG_INFINITY);
            let upper = &self.upper[p * n..][..n];
            for (&id, &up) in ids.iter().zip(upper) {
                let row = &rows[id as usize * m..][..m];
                if up {
                    lo_up.iter_mut().zip(row).for_each(|(v, &y)| *v = v.min(y));
                } else {
                    hi_down.iter_mut().zip(row).for_each(|(v, &y)| *v = v.max(y));
                }
            }
            for j in 0..m {
                // As `clear_height`: the opening, or none when one sheet is empty.
                clear[j] = if lo_up[j].is_finite() && hi_down[j].is_finite() {
                    self.x_c * (lo_up[j] - hi_down[j])
                } else {
                    0.0
                };
            }
            // The window: the longest run of clearance ≥ 0 on the 1° grid (as pick_window).
            let c = |j: usize| clear[w_at + j] - h;
            let (mut best, mut run_start) = (None::<(usize, usize)>, None::<usize>);
            for k in 0..=wn {
                if c(k) >= 0.0 {
                    run_start.get_or_insert(k);
                }
                if (c(k) < 0.0 || k == wn)
                    && let Some(s) = run_start.take()
                {
                    let e = if c(k) < 0.0 { k - 1 } else { k };
                    if best.is_none_or(|(bs, be)| e - s > be - bs) {
                        best = Some((s, e));
                    }
                }
            }
            match best {
                None => shut = true,
                Some((s, e)) => {
                    if s > open_k {
                        (open_k, open_picks) = (s, Vec::new());
                    }
                    if s == open_k && s > 0 {
                        open_picks.push(p as u32);
                    }
                    if e < close_k {
                        (close_k, close_picks) = (e, Vec::new());
                    }
                    if e == close_k && e < wn {
                        close_picks.push(p as u32);
                    }
                }
            }
            // The least clearance over the insertion (as min_over): the grid, and its strict
            // local minima that could go below the least found.
            let v = &clear[e_at..e_at + en + 1];
            least = v.iter().map(|x| x - h).fold(least, f64::min);
            for k in 1..en {
                let (l, x, r) = (v[k - 1] - h, v[k] - h, v[k + 1] - h);
                if (x < l || x < r) && x <= l && x <= r && x - 0.5 * (l.max(r) - x) <= least + TIE_M {
                    let key = [k as u64, l.to_bits(), x.to_bits(), r.to_bits()];
                    minima.entry(key).or_insert((p, x - 0.5 * (l.max(r) - x)));
                }
            }
            // The largest clear height (as max_clear_of): the grid's first largest node, refined
            // between its neighbours when its reach could pass the largest found.
            let v = &clear[m_at..m_at + 73];
            let (k, top) =
                (0..=72).map(|k| (k, v[k])).fold((0, f64::NEG_INFINITY), |bt, kv| if kv.1 > bt.1 { kv } else { bt });
            let low = match k {
                0 => v[1],
                72 => v[71],
                _ => v[k - 1].min(v[k + 1]),
            };
            let reach = top + 0.5 * (top - low);
            if reach >= most - TIE_M {
                let (l, r) = (v[k.saturating_sub(1)], v[(k + 1).min(72)]);
                maxima.entry([k as u64, l.to_bits(), top.to_bits(), r.to_bits()]).or_insert((p, reach));
            }
            most = most.max(top);
        }
        // The bisection holds its picks' rows in two bytes each.
        if states.rows.len() > usize::from(u16::MAX) {
            return None;
        }
        let max_clear = {
            for (key, &(p, reach)) in maxima.iter() {
                if reach < most - TIE_M {
                    continue;
                }
                let f = |t: f64| self.clear_in_turn(p, t);
                let t = a + mh * key[0] as f64;
                let v =
                    loomkin_numeric::golden_max(f, (t - mh).max(a), (t + mh).min(b)).value.max(f64::from_bits(key[2]));
                most = most.max(v);
            }
            most
        };
        if shut {
            return Some(Err(self.too_tall(max_clear)));
        }
        for (key, &(p, reach)) in minima.iter() {
            if reach > least + TIE_M {
                continue;
            }
            let c = |t: f64| self.clear_in_turn(p, t) - h;
            let k = key[0] as usize;
            let (l, r) = (e0 + (k - 1) as f64 * eh, e0 + (k + 1) as f64 * eh);
            least = least.min(-loomkin_numeric::golden_max(|t| -c(t), l, r).value);
        }
        let node = |k: usize| nodes[w_at + k];
        let open_deg = if open_k == 0 {
            node(0)
        } else {
            self.extreme_root(&states, &mut open_picks, node(open_k - 1), node(open_k), true)
        };
        let close_deg = if close_k == wn {
            node(wn)
        } else {
            self.extreme_root(&states, &mut close_picks, node(close_k), node(close_k + 1), false)
        };
        let window_deg = (close_deg - open_deg).max(0.0);
        let v = ins.mean_speed_m_s(self.loom.speed.rpm());
        Some(Ok(TimingReport {
            picks: Vec::new(),
            open_deg,
            close_deg,
            window_deg,
            min_clearance_mm: 1e3 * least,
            mean_speed_m_s: v,
            max_speed_rpm: max_speed_rpm(v, window_deg, ins.reed_width_m, ins.carrier_length_m),
            max_clear_mm: max_clear * 1e3,
        }))
    }

    /// [`Timing::min_clearance_coarse`] from rows (what the stagger search checks on a repeat
    /// with many distinct turns): every pick's grid the min/max of its frames' slope rows, the
    /// rows kept in `rows` across the motions of the search (a frame's row depends on its own
    /// centre and lifts alone); the same values at the same nodes, each pick's from its own turn.
    pub(crate) fn min_clearance_coarse_rows(&self, step_deg: f64, rows: &mut SlopeRows) -> f64 {
        let motion = self.motion;
        let ins = &self.loom.insertion;
        let n = self.loom.frame_count();
        let k = ((ins.exit_deg - ins.entry_deg) / step_deg).ceil().max(1.0) as usize;
        let h = (ins.exit_deg - ins.entry_deg) / k as f64;
        let nodes: Vec<f64> = (0..=k).map(|j| ins.entry_deg + j as f64 * h).collect();
        let Some(states) = FrameStates::new(motion, ins.entry_deg.min(ins.exit_deg), ins.exit_deg.max(ins.entry_deg))
        else {
            return self.min_clearance_coarse(step_deg);
        };
        let (mut lo_up, mut hi_down) = (vec![0.0; nodes.len()], vec![0.0; nodes.len()]);
        let mut ids = vec![0usize; n];
        let mut least = f64::INFINITY;
        let height = ins.carrier_height_m;
        for p in 0..motion.picks() {
            for (i, id) in ids.iter_mut().enumerate() {
                let key = [i as u64, motion.centre0_deg(i).to_bits(), states.lo as u64, states.run(motion, i, p)];
                let d = self.loom.geometry.frame_m[i];
                *id = rows.get(key, || nodes.iter().map(|&t| motion.frame_in_turn(i, p, t).y_m / d).collect());
            }
            lo_up.fill(f64::INFINITY);
            hi_down.fill(f64::NEG_INFINITY);
            for (&id, &up) in ids.iter().zip(&self.upper[p * n..][..n]) {
                let row = rows.row(id);
                if up {
                    lo_up.iter_mut().zip(row).for_each(|(v, &y)| *v = v.min(y));
                } else {
                    hi_down.iter_mut().zip(row).for_each(|(v, &y)| *v = v.max(y));
                }
            }
            for (lu, hd) in lo_up.iter().zip(&hi_down) {
                let clear = if lu.is_finite() && hd.is_finite() { self.x_c * (lu - hd) } else { 0.0 };
                least = least.min(clear - height);
            }
        }
        least
    }

    /// The clear height of pick `p` at angle `t_deg` of its turn, at the carrier's front edge,
    /// from the exact laws ([`Motion::frame_in_turn`]), m.
    fn clear_in_turn(&self, p: usize, t_deg: f64) -> f64 {
        self.clear_with(p, self.x_c, |i| self.motion.frame_in_turn(i, p, t_deg).y_m)
    }

    /// The latest opening (`open`) or the earliest closing of the picks `picks`, whose clearance
    /// changes sign between `lo` and `hi` (closed at `lo` when opening, open at `lo` when
    /// closing): one bisection of them all to adjacent doubles, the picks on the answer's side
    /// kept at each halving (each pick's own bisection would end there or short of it).
    fn extreme_root(&self, states: &FrameStates, picks: &mut Vec<u32>, lo: f64, hi: f64, open: bool) -> f64 {
        let h = self.loom.insertion.carrier_height_m;
        let motion = self.motion;
        let n = self.loom.frame_count();
        let g = &self.loom.geometry;
        // Each row's slope at the probe, made once per probe: a pick's clearance is the min/max
        // of its frames' (the same bits as `clear_in_turn`: min and max do not round). The
        // candidates' rows are held (two bytes a frame) while they are bisected.
        let rows = states.rows.len();
        let mut slope = vec![f64::NAN; rows];
        let mut done = vec![false; rows];
        let mut ids: Vec<u16> = Vec::with_capacity(picks.len() * n);
        for &p in picks.iter() {
            ids.extend((0..n).map(|i| states.known(motion, i, p as usize) as u16));
        }
        loomkin_numeric::bisect(lo, hi, |t| {
            done.fill(false);
            let mut clearance = |p: usize, row_ids: &[u16]| -> f64 {
                let (mut lo_up, mut hi_down) = (f64::INFINITY, f64::NEG_INFINITY);
                for (i, &r) in row_ids.iter().enumerate() {
                    let r = r as usize;
                    if !done[r] {
                        let (fi, fp) = states.rows[r];
                        slope[r] = motion.frame_in_turn(fi, fp, t).y_m / g.frame_m[fi];
                        done[r] = true;
                    }
                    if self.upper[p * n + i] { lo_up = lo_up.min(slope[r]) } else { hi_down = hi_down.max(slope[r]) }
                }
                let clear = if lo_up.is_finite() && hi_down.is_finite() { self.x_c * (lo_up - hi_down) } else { 0.0 };
                clear - h
            };
            // The picks closed at t (the opening lies beyond t) moved to the front.
            let mut closed = 0;
            for c in 0..picks.len() {
                let p = picks[c] as usize;
                if clearance(p, &ids[c * n..][..n]) < 0.0 {
                    picks.swap(closed, c);
                    for i in 0..n {
                        ids.swap(closed * n + i, c * n + i);
                    }
                    closed += 1;
                }
            }
            let keep_closed = |picks: &mut Vec<u32>, ids: &mut Vec<u16>| {
                picks.truncate(closed);
                ids.truncate(closed * n);
            };
            match (open, closed == 0) {
                (true, false) => {
                    keep_closed(picks, &mut ids);
                    true
                }
                (true, true) => false,
                (false, false) => {
                    keep_closed(picks, &mut ids);
                    false
                }
                (false, true) => true,
            }
        })
    }
}

/// A pick's frames over a span of its turn: the sheets of those resting throughout, and the others.
struct Resting {
    sheets: Sheets,
    moving: Vec<usize>,
}

/// Grid extremes to refine, by bracket (the node and the bits of the grid's values there and at
/// its neighbours: equal bits, one search): the first pick met with it and its reach.
type Brackets = loomkin_numeric::WordMap<[u64; 4], (usize, f64)>;

/// Clearances (m) closer than this are the same: the rounding of a pick's angles moves them by
/// ~10⁻¹⁶ m.
const TIE_M: f64 = 1e-12;

/// The root of `f` between `a` (one sign) and `b` (the other), by bisection to adjacent doubles.
fn crossing(f: &impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let fa_neg = f(a) < 0.0;
    loomkin_numeric::bisect(a, b, |m| (f(m) < 0.0) == fa_neg)
}
