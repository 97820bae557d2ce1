//! The whole loom on its main shaft: the reduced moment of inertia `J(φ)` of every mechanism over
//! the pattern repeat, and the load torque `M_load(φ)` of their non-inertial forces — what the
//! speed-ripple solver of loomkin-drive takes ([`LoomShaft`] is its [`Shaft`]).
//!
//! The kinetic energy of the mechanisms at shaft speed ω is `½·J(φ)·ω²` with
//!
//! $$ J(\varphi) = \sum_i m_i\,y_i'(\varphi)^2 + J_Q\,\theta'(\varphi)^2 + J_\mathrm{rot}, \qquad
//!    \frac{dJ}{d\varphi} = \sum_i 2 m_i\,y_i' y_i'' + 2 J_Q\,\theta'\theta'' $$
//!
//! (frame `i` of mass `m_i` at height `y_i`, the sley of inertia `J_Q` about its rocking shaft at
//! angle `θ`, the rotating parts' constant `J_rot`; primes are derivatives in the main-shaft angle,
//! exact in closed form). The load is what [`Drive::torque_at`] gives less its inertial part — the
//! frames' weight, springs and warp by power balance over the shedding drive's efficiency — plus the
//! sley's beat-up resistance and weight (`FourBarSley::load_torque_n_m`) and a constant friction
//! torque on the shaft. At constant speed,
//! `M_load + ½ω²·dJ/dφ` is `loom torque`'s torque (at efficiency 1; the efficiency divides the
//! shedding's inertial part there, while the kinetic energy here is exchanged without loss).

use crate::{CorrectedFrames, Drive, FrameKin, Loom, LoomError, Motion, Pattern, Result};
use loomkin_drive::{MotorSpec, Shaft, Sley};
use loomkin_laws::gauss_legendre;
use loomkin_numeric::PeriodicScan;
use loomkin_units::{Field, Range};
use serde::Serialize;
use std::f64::consts::TAU;

/// The `[drive]` table of a loom file: the rotating parts, friction, flywheel and motor.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct DriveSpec {
    /// Inertia of the rotating parts referred to the main shaft (shaft, cams, gears, the motor's
    /// rotor times the gear ratio squared), kg·m².
    pub rotating_inertia_kg_m2: f64,
    /// Constant friction torque on the main shaft, N·m.
    pub friction_torque_n_m: f64,
    /// Flywheel on the main shaft, kg·m².
    pub flywheel_kg_m2: f64,
    /// The motor.
    pub motor: MotorSpec,
}

impl DriveSpec {
    /// `rotating_inertia_kg_m2`.
    pub const ROTATING_INERTIA_KG_M2: Field = Field::new(
        "rotating_inertia_kg_m2",
        Range::closed(0.0, 1e6, "kg·m²"),
        "Inertia of the loom's rotating parts referred to the main shaft (shafts, cams, gears, pulleys, \
         the motor's rotor times the gear ratio squared), kg·m²: 0 … 10⁶. The speed ripple needs it \
         above 0 (the frames' and sley's inertia vanishes where they stand still).",
    )
    .with_default(0.0);
    /// `friction_torque_n_m`.
    pub const FRICTION_TORQUE_N_M: Field = Field::new(
        "friction_torque_n_m",
        Range::closed(0.0, 1e7, "N·m"),
        "Constant friction torque on the main shaft (bearings, seals), N·m: 0 … 10⁷; the shaft turns \
         one way, so it always takes power.",
    )
    .with_default(0.0);
}

/// One mechanism's reduced inertia over the repeat.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MechanismInertia {
    /// `frame 1` … (front first), `sley`, `rotating parts`.
    pub name: String,
    /// Least J, kg·m² (located between the grid points).
    pub j_min_kg_m2: f64,
    /// Largest J, kg·m².
    pub j_max_kg_m2: f64,
    /// Mean J over the repeat, kg·m² (exact quadrature).
    pub j_mean_kg_m2: f64,
}

/// The extremes and mean of a J(φ).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct InertiaStats {
    /// Least J, kg·m².
    pub j_min_kg_m2: f64,
    /// Where, deg within the repeat.
    pub j_min_angle_deg: f64,
    /// Largest J, kg·m².
    pub j_max_kg_m2: f64,
    /// Where, deg within the repeat.
    pub j_max_angle_deg: f64,
    /// Mean J over the repeat, kg·m².
    pub j_mean_kg_m2: f64,
}

/// `loomkin drive inertia --json`: the total's extremes and mean at the top, the total again under
/// `total`, and each mechanism under `mechanisms`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InertiaReport {
    /// Picks in the repeat.
    pub picks: usize,
    /// The repeat, deg.
    pub repeat_deg: f64,
    /// Least total J, kg·m².
    pub j_min_kg_m2: f64,
    /// Largest total J, kg·m².
    pub j_max_kg_m2: f64,
    /// Mean total J, kg·m².
    pub j_mean_kg_m2: f64,
    /// The total with where its extremes are.
    pub total: InertiaStats,
    /// Each mechanism.
    pub mechanisms: Vec<MechanismInertia>,
}

/// The sley seen from the side ([`LoomShaft::side_view`]): its joints, mm behind and over the fell.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SleySide {
    /// The crank centre (the main shaft).
    pub crank_centre: [f64; 2],
    /// The crank pin.
    pub crank_pin: [f64; 2],
    /// The sword's pin (the rod's other end).
    pub sword_pin: [f64; 2],
    /// The rocking shaft.
    pub rocking_shaft: [f64; 2],
    /// The reed's beating point (at the fell, `[0, 0]`, at its front dead centre).
    pub reed: [f64; 2],
}

/// The loom seen from the side at one main-shaft angle, mm: x behind the fell toward the back rest,
/// y over the fell.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SideView {
    /// The main-shaft angle, deg.
    pub angle_deg: f64,
    /// The sley, when the loom file has one.
    pub sley: Option<SleySide>,
    /// Each frame's heald eye (front first): distance behind the fell and height over it.
    pub heald_eyes_mm: Vec<[f64; 2]>,
    /// The back rest: distance behind the fell and height over it (the warp's other end).
    pub back_rest_mm: [f64; 2],
}

/// The loom's main shaft weaving a pattern: J(φ), dJ/dφ and M_load(φ) over the repeat.
#[derive(Debug, Clone)]
pub struct LoomShaft<'a> {
    loom: &'a Loom,
    drive: Drive<'a>,
    sley: Option<&'a Sley>,
    corrected: Option<&'a CorrectedFrames>,
}

impl<'a> LoomShaft<'a> {
    /// The shaft of `loom` moving `motion` (its frames weaving `pattern`), with the loom's sley if
    /// it has one.
    pub fn new(loom: &'a Loom, motion: &'a Motion, pattern: &Pattern) -> Self {
        Self { loom, drive: Drive::new(loom, motion, pattern), sley: loom.sley.as_ref(), corrected: None }
    }

    /// The same shaft with the frames driven by time-true cams (`loomkin drive correct`) instead
    /// of the design law; [`LoomShaft::report`] still describes the design law.
    pub fn with_corrected(mut self, frames: &'a CorrectedFrames) -> Self {
        self.corrected = Some(frames);
        self
    }

    /// Frame `i` at `theta_deg`: the design law's motion, or the time-true cam's.
    pub fn frame_kin(&self, i: usize, theta_deg: f64) -> FrameKin {
        match self.corrected {
            Some(c) => c.frame(i, theta_deg),
            None => self.motion().frame(i, theta_deg),
        }
    }

    /// The frames' motion.
    pub fn motion(&self) -> &Motion {
        self.drive.motion()
    }

    /// The sley, if any.
    pub fn sley(&self) -> Option<&Sley> {
        self.sley
    }

    /// Frame `i`'s reduced inertia `m·y'²` and its rate `2m·y'·y''` at `theta_deg`.
    pub fn frame_inertia(&self, i: usize, theta_deg: f64) -> (f64, f64) {
        let k = self.frame_kin(i, theta_deg);
        let m = self.loom.frames[i].mass_kg;
        (m * k.dy * k.dy, 2.0 * m * k.dy * k.d2y)
    }

    /// The sley's mean J over a turn, kg·m²: 16-point Gauss–Legendre (`rule`) on panels of 10°,
    /// split at the joints of a cam law (where J is not smooth; a joint within 1e-9° of a panel's
    /// end is that end).
    fn sley_mean(&self, rule: &[(f64, f64)]) -> f64 {
        let mut cuts: Vec<f64> = (0..=36).map(|p| 10.0 * p as f64).collect();
        if let Some(s) = self.sley {
            let off_panel = |d: &f64| (d - 10.0 * (d / 10.0).round()).abs() > 1e-9;
            cuts.extend(s.inertia_joints_rad().into_iter().map(f64::to_degrees).filter(off_panel));
        }
        cuts.sort_by(f64::total_cmp);
        cuts.dedup_by(|later, earlier| *later - *earlier <= 1e-9);
        cuts.windows(2)
            .map(|w| {
                let half = 0.5 * (w[1] - w[0]);
                rule.iter().map(|&(x, wt)| half * wt * self.sley_inertia(w[0] + half + half * x).0).sum::<f64>()
            })
            .sum::<f64>()
            / 360.0
    }

    /// The sley's reduced inertia and rate at `theta_deg` (0 without a sley).
    pub fn sley_inertia(&self, theta_deg: f64) -> (f64, f64) {
        self.sley.map_or((0.0, 0.0), |s| s.reduced_inertia_kg_m2(theta_deg.to_radians().rem_euclid(TAU)))
    }

    /// The mechanisms' names, in the order of [`LoomShaft::mechanism_inertia`]: the frames, the
    /// sley (when there is one), the rotating parts.
    pub fn mechanism_names(&self) -> Vec<String> {
        let mut out: Vec<String> = (1..=self.loom.frame_count()).map(|i| format!("frame {i}")).collect();
        if self.sley.is_some() {
            out.push("sley".into());
        }
        out.push("rotating parts".into());
        out
    }

    /// Every mechanism's `(J, dJ/dφ)` at `theta_deg`, in the order of [`LoomShaft::mechanism_names`].
    pub fn mechanism_inertia(&self, theta_deg: f64) -> Vec<(f64, f64)> {
        let mut out: Vec<(f64, f64)> = (0..self.loom.frame_count()).map(|i| self.frame_inertia(i, theta_deg)).collect();
        if self.sley.is_some() {
            out.push(self.sley_inertia(theta_deg));
        }
        out.push((self.loom.drive.rotating_inertia_kg_m2, 0.0));
        out
    }

    /// The total `(J, dJ/dφ)` at `theta_deg`, kg·m² and kg·m²/rad.
    pub fn inertia_at(&self, theta_deg: f64) -> (f64, f64) {
        let (mut j, mut dj) = self.sley_inertia(theta_deg);
        j += self.loom.drive.rotating_inertia_kg_m2;
        for i in 0..self.loom.frame_count() {
            let (a, b) = self.frame_inertia(i, theta_deg);
            j += a;
            dj += b;
        }
        (j, dj)
    }

    /// The loom seen from the side at main-shaft angle `theta_deg` (the workbench's animation), in
    /// mm with x behind the fell (toward the back rest) and y over it: the sley's joints placed so that
    /// the reed's beating point meets the fell at its front dead centre, and every frame's heald eye on
    /// its way through the shed (its lift over the level warp line from the fell to the back rest).
    pub fn side_view(&self, theta_deg: f64) -> SideView {
        let g = &self.loom.geometry;
        let mm = 1e3;
        let sley = self.sley.map(|s| {
            let fell = s.joints_m(s.front_dead_centre_rad()).reed;
            let j = s.joints_m(theta_deg.to_radians().rem_euclid(TAU));
            let place = |p: [f64; 2]| [-(p[0] - fell[0]) * mm, (p[1] - fell[1]) * mm];
            SleySide {
                crank_centre: place([0.0, 0.0]),
                crank_pin: place(j.crank_pin),
                sword_pin: place(j.sword_pin),
                rocking_shaft: place(j.rocking_shaft),
                reed: place(j.reed),
            }
        });
        let heald_eyes_mm = (0..self.loom.frame_count())
            .map(|i| {
                let d = g.frame_m[i];
                [d * mm, (g.warp_line_m * d / g.back_rest_m + self.frame_kin(i, theta_deg).y_m) * mm]
            })
            .collect();
        SideView { angle_deg: theta_deg, sley, heald_eyes_mm, back_rest_mm: [g.back_rest_m * mm, g.warp_line_m * mm] }
    }

    /// `loomkin drive inertia --csv`'s column names: `angle_deg`, then `j_NAME_kg_m2` and
    /// `dj_NAME_kg_m2_per_rad` for every mechanism (NAME as [`LoomShaft::mechanism_names`] in one
    /// word: `frame3`, `sley`, `rotating`) and for the `total`.
    pub fn inertia_header(&self) -> Vec<String> {
        let mut out = vec!["angle_deg".to_string()];
        for name in self.mechanism_names().iter().map(|n| column_word(n)).chain(std::iter::once("total".to_string())) {
            out.push(format!("j_{name}_kg_m2"));
            out.push(format!("dj_{name}_kg_m2_per_rad"));
        }
        out
    }

    /// `loomkin drive inertia --csv`'s rows over the repeat on a grid of about `step_deg`
    /// ([`Drive::STEP_DEG`]), made one at a time (a long repeat's table is never held whole), in
    /// the order of [`LoomShaft::inertia_header`]; every value exact at its grid point.
    pub fn inertia_rows(&self, step_deg: f64) -> Result<impl Iterator<Item = Vec<f64>> + '_> {
        Drive::STEP_DEG.check(step_deg)?;
        let period = self.motion().repeat_deg();
        let n = (period / step_deg).round().max(1.0) as usize;
        let h = period / n as f64;
        Ok((0..n).map(move |k| {
            let th = k as f64 * h;
            let mut row = vec![th];
            for (j, dj) in self.mechanism_inertia(th).into_iter().chain(std::iter::once(self.inertia_at(th))) {
                row.push(j);
                row.push(dj);
            }
            row
        }))
    }

    /// [`LoomShaft::inertia_header`] and [`LoomShaft::inertia_rows`] as columns (for numpy).
    pub fn inertia_columns(&self, step_deg: f64) -> Result<Vec<(String, Vec<f64>)>> {
        let mut cols: Vec<(String, Vec<f64>)> = self.inertia_header().into_iter().map(|c| (c, Vec::new())).collect();
        for row in self.inertia_rows(step_deg)? {
            cols.iter_mut().zip(row).for_each(|(c, v)| c.1.push(v));
        }
        Ok(cols)
    }

    /// The load torque at `theta_deg`, N·m: the frames' weight, springs and warp over the shedding
    /// drive's efficiency, the sley's beat-up resistance and weight, the friction.
    pub fn load_at(&self, theta_deg: f64) -> f64 {
        let mut sum = 0.0;
        for i in 0..self.loom.frame_count() {
            let k = self.frame_kin(i, theta_deg);
            if k.dy != 0.0 {
                let f = self.drive.force(i, &k);
                sum += (f.weight_n + f.spring_n + f.warp_n) * k.dy;
            }
        }
        let sley = self.sley.map_or(0.0, |s| s.load_torque_n_m(theta_deg.to_radians().rem_euclid(TAU)));
        sum / self.loom.efficiency + sley + self.loom.drive.friction_torque_n_m
    }

    /// The statistics of J over the repeat, per mechanism and in total. A grid of `step_deg`
    /// ([`Drive::STEP_DEG`]) finds the extremes' neighbourhoods and golden-section search locates
    /// them on the exact J; the means are exact quadratures (Gauss–Legendre between the laws'
    /// joints). When the step divides 360°, every move of a frame in one direction meets the grid
    /// at the same fractions of its motion, so each frame's J over a rise and over a fall is
    /// computed once and added at every move (the cost of a long repeat is additions). The total's
    /// grid is made a turn at a time and scanned as it is made ([`loomkin_numeric::PeriodicScan`]):
    /// a long repeat is never held whole (docs/performance.md).
    pub fn report(&self, step_deg: f64) -> Result<InertiaReport> {
        let (grid, mechanisms, mean_total) = self.grid_of(step_deg)?;
        let motion = self.motion();
        let total = grid.stats(self, motion.repeat_deg(), mean_total);
        Ok(InertiaReport {
            picks: motion.picks(),
            repeat_deg: motion.repeat_deg(),
            j_min_kg_m2: total.j_min_kg_m2,
            j_max_kg_m2: total.j_max_kg_m2,
            j_mean_kg_m2: total.j_mean_kg_m2,
            total,
            mechanisms,
        })
    }

    /// The total's grid (to be made a stretch at a time), every mechanism's statistics and the
    /// total's mean.
    fn grid_of(&self, step_deg: f64) -> Result<(TotalGrid, Vec<MechanismInertia>, f64)> {
        Drive::STEP_DEG.check(step_deg)?;
        let motion = self.motion();
        let period = motion.repeat_deg();
        let n = (period / step_deg).round().max(1.0) as usize;
        let h = period / n as f64;
        let per_turn = 360.0 / h;
        let aligned = (per_turn - per_turn.round()).abs() <= 1e-9 * per_turn;
        let rule = gauss_legendre(16);
        let rot = self.loom.drive.rotating_inertia_kg_m2;
        let mut grid = TotalGrid {
            n,
            h,
            rot,
            aligned,
            tables: Vec::new(),
            adds: Vec::new(),
            moving: Vec::new(),
            turn: Vec::new(),
        };
        let mut mechanisms = Vec::new();
        let mut mean_total = 0.0;
        for i in 0..self.loom.frame_count() {
            let (mech, mean) = self.frame_stats(i, &rule, &mut grid, per_turn);
            mean_total += mean;
            mechanisms.push(mech);
        }
        // In order of (start, table): the moves bucketed by the turn they start in (each frame's are
        // already in order of start), each turn's few sorted.
        let turns = n.div_ceil(per_turn.round().max(1.0) as usize);
        let bucket = |a: &(usize, usize)| a.0 * turns / n;
        let mut count = vec![0usize; turns + 1];
        grid.adds.iter().for_each(|a| count[bucket(a) + 1] += 1);
        (0..turns).for_each(|b| count[b + 1] += count[b]);
        let mut sorted = vec![(0, 0); grid.adds.len()];
        for a in &grid.adds {
            let b = bucket(a);
            sorted[count[b]] = *a;
            count[b] += 1;
        }
        let mut at = 0;
        for b in 0..turns {
            sorted[at..count[b]].sort_unstable();
            at = count[b];
        }
        grid.adds = sorted;
        if self.sley.is_some() {
            // The sley repeats every turn: one turn's J on the grid, tiled when the step divides 360°.
            if aligned {
                let m = per_turn.round() as usize;
                grid.turn = (0..m).map(|k| self.sley_inertia(k as f64 * h).0).collect();
            }
            let f = |x: f64| self.sley_inertia(x).0;
            let sley_grid: Vec<f64> = (0..3600).map(|k| f(k as f64 * 0.1)).collect();
            let mut st = stats(&sley_grid, 0.1, 360.0, &f, 0.0);
            st.j_mean_kg_m2 = self.sley_mean(&rule);
            mean_total += st.j_mean_kg_m2;
            mechanisms.push(MechanismInertia {
                name: "sley".into(),
                j_min_kg_m2: st.j_min_kg_m2,
                j_max_kg_m2: st.j_max_kg_m2,
                j_mean_kg_m2: st.j_mean_kg_m2,
            });
        }
        mean_total += rot;
        mechanisms.push(MechanismInertia {
            name: "rotating parts".into(),
            j_min_kg_m2: rot,
            j_max_kg_m2: rot,
            j_mean_kg_m2: rot,
        });
        Ok((grid, mechanisms, mean_total))
    }

    /// Frame `i`'s extremes and mean (returned) and its part of the total's grid (put in `grid`).
    fn frame_stats(
        &self,
        i: usize,
        rule: &[(f64, f64)],
        grid: &mut TotalGrid,
        per_turn: f64,
    ) -> (MechanismInertia, f64) {
        let motion = self.motion();
        let period = motion.repeat_deg();
        let phi = motion.motion_deg();
        let h = grid.h;
        let moves = motion.moves(i);
        let mass = self.loom.frames[i].mass_kg;
        let j_of = |rising: bool, x: f64| {
            let k = motion.moving(i, rising, x);
            mass * k.dy * k.dy
        };
        // ∫ J over one move, by direction: Gauss–Legendre on the law's panels.
        let move_integral = |rising: bool| -> f64 {
            let law = motion.law().law(rising);
            let xs: Vec<f64> = std::iter::once(0.0).chain(law.joints()).chain(std::iter::once(1.0)).collect();
            xs.windows(2)
                .map(|w| {
                    let (mid, half) = (0.5 * (w[0] + w[1]), 0.5 * (w[1] - w[0]));
                    rule.iter().map(|&(x, wt)| half * wt * j_of(rising, mid + half * x)).sum::<f64>()
                })
                .sum::<f64>()
                * phi
        };
        let rises = moves.iter().filter(|m| m.rising).count();
        let falls = moves.len() - rises;
        let mean = (rises as f64 * if rises > 0 { move_integral(true) } else { 0.0 }
            + falls as f64 * if falls > 0 { move_integral(false) } else { 0.0 })
            / period;
        // Extremes over the move(s): the grid on x, refined.
        let extreme = |sign: f64| -> f64 {
            let mut best = f64::NEG_INFINITY;
            for rising in [true, false] {
                if (rising && rises == 0) || (!rising && falls == 0) {
                    continue;
                }
                let m = 720;
                let vals: Vec<f64> = (0..=m).map(|k| sign * j_of(rising, k as f64 / m as f64)).collect();
                let (k, _) = vals
                    .iter()
                    .enumerate()
                    .fold((0, f64::NEG_INFINITY), |b, (k, v)| if *v > b.1 { (k, *v) } else { b });
                let a = (k as f64 - 1.0).max(0.0) / m as f64;
                let b = (k as f64 + 1.0).min(m as f64) / m as f64;
                let r = loomkin_numeric::golden_max(|x| sign * j_of(rising, x), a, b);
                best = best.max(r.value).max(vals[k]);
            }
            sign * best
        };
        let dwells = moves.len() as f64 * phi < period - 1e-9 * period;
        let j_max = if moves.is_empty() { 0.0 } else { extreme(1.0) };
        let j_min = if dwells || moves.is_empty() { 0.0 } else { extreme(-1.0) };
        let mech = MechanismInertia {
            name: format!("frame {}", i + 1),
            j_min_kg_m2: j_min,
            j_max_kg_m2: j_max,
            j_mean_kg_m2: mean,
        };
        // Onto the total's grid.
        let Some(first) = moves.first() else { return (mech, mean) };
        if grid.aligned {
            let per_turn = per_turn.round() as i64;
            let w0 = first.start_deg - 360.0 * first.pick as f64;
            let k0 = (w0 / h - 1e-12).ceil() as i64;
            let x0 = (k0 as f64 * h - w0) / phi;
            let dx = h / phi;
            let cnt = ((1.0 - x0) / dx).ceil().max(0.0) as usize;
            let t = grid.tables.len();
            grid.tables.push((0..cnt).map(|j| j_of(true, x0 + j as f64 * dx)).collect());
            grid.tables.push((0..cnt).map(|j| j_of(false, x0 + j as f64 * dx)).collect());
            let n = grid.n as i64;
            for m in &moves {
                let start = (k0 + per_turn * m.pick as i64).rem_euclid(n) as usize;
                grid.adds.push((start, t + usize::from(!m.rising)));
            }
        } else {
            grid.moving.push(i);
        }
        (mech, mean)
    }
}

/// The total J on the report's grid, made a stretch at a time: the rotating parts' constant, the
/// frames' moves (their tables added where each move starts, in the order of `(start, table)`, a
/// move across the repeat's end wrapping to its start), the sley last — for every point the
/// additions of a whole grid swept move by move, in the same order, so the same sums bit for bit.
struct TotalGrid {
    /// Points over the repeat, and their spacing, deg.
    n: usize,
    h: f64,
    rot: f64,
    /// Whether the step divides 360° (the tables and the sley's turn are used).
    aligned: bool,
    /// Each moving frame's J over a rise and over a fall on the grid.
    tables: Vec<Vec<f64>>,
    /// Where each move adds its table: (first point, table), sorted.
    adds: Vec<(usize, usize)>,
    /// Without tables (the step does not divide 360°): the frames that move, evaluated pointwise.
    moving: Vec<usize>,
    /// The sley's J over one turn (aligned), else empty.
    turn: Vec<f64>,
}

impl TotalGrid {
    /// Points `lo..lo + out.len()` of the total J into `out`; `from` is the first add that may reach
    /// `lo` (adds before it end before `lo`, unless they wrap), advanced for the next stretch.
    fn fill(&self, shaft: &LoomShaft<'_>, lo: usize, out: &mut [f64], from: &mut usize, wrapping: &[usize]) {
        let hi = lo + out.len();
        out.fill(self.rot);
        if self.aligned {
            // Adds that cannot reach `lo` (nor anything after it) are passed for good.
            let longest = self.tables.iter().map(Vec::len).max().unwrap_or(0);
            while *from < self.adds.len() && self.adds[*from].0 + longest <= lo {
                *from += 1;
            }
            let end = *from + self.adds[*from..].partition_point(|a| a.0 < hi);
            let n = self.n;
            let mut add = |i: usize| {
                let (start, t) = self.adds[i];
                let tab = &self.tables[t];
                // Lap `l` puts entry j at point start + j − l·n.
                let mut lap = 0;
                while lap * n < start + tab.len() {
                    let base = start as i64 - (lap * n) as i64;
                    let j0 = (lo as i64 - base).max(0) as usize;
                    let j1 = ((hi as i64 - base).max(0) as usize).min(tab.len());
                    if j0 < j1 {
                        let at = (base + j0 as i64) as usize - lo;
                        out[at..at + (j1 - j0)].iter_mut().zip(&tab[j0..j1]).for_each(|(o, v)| *o += v);
                    }
                    lap += 1;
                }
            };
            // In the sorted order: the adds starting up to `hi`, then those wrapping past the end.
            (*from..end).for_each(&mut add);
            wrapping.iter().filter(|&&i| i >= end).for_each(|&i| add(i));
            if !self.turn.is_empty() {
                // The turn's values from the stretch's place in it on, again from its start.
                let mut rest = &mut out[..];
                let mut at = lo % self.turn.len();
                while !rest.is_empty() {
                    let len = rest.len().min(self.turn.len() - at);
                    let (now, later) = rest.split_at_mut(len);
                    now.iter_mut().zip(&self.turn[at..at + len]).for_each(|(o, v)| *o += v);
                    rest = later;
                    at = 0;
                }
            }
        } else {
            for (k, o) in (lo..hi).zip(out.iter_mut()) {
                let th = k as f64 * self.h;
                for &i in &self.moving {
                    *o += shaft.frame_inertia(i, th).0;
                }
                if shaft.sley.is_some() {
                    *o += shaft.sley_inertia(th).0;
                }
            }
        }
    }

    /// The adds that wrap past the repeat's end (their indices, in order).
    fn wrapping(&self) -> Vec<usize> {
        (0..self.adds.len()).filter(|&i| self.adds[i].0 + self.tables[self.adds[i].1].len() > self.n).collect()
    }

    /// The total's extremes (located on the exact J, [`loomkin_numeric::PeriodicScan`] on J and on
    /// −J) and the mean given, the grid made a stretch at a time.
    fn stats(&self, shaft: &LoomShaft<'_>, period: f64, mean: f64) -> InertiaStats {
        let n = self.n;
        let stretch = if self.aligned { self.turn.len().max((360.0 / self.h).round() as usize) } else { 4096 }.min(n);
        let wrapping = self.wrapping();
        let mut buf = vec![0.0; stretch];
        let mut from = 0;
        // The last point first (the scan starts from its neighbours across the end).
        let last_lo = n - (n - 1) % stretch - 1;
        let mut tail_from = 0;
        self.fill(shaft, last_lo, &mut buf[..n - last_lo], &mut tail_from, &wrapping);
        let last = buf[n - last_lo - 1];
        self.fill(shaft, 0, &mut buf[..stretch], &mut from, &wrapping);
        let mut hi_scan = PeriodicScan::new(last, buf[0]);
        let mut lo_scan = PeriodicScan::new(-last, -buf[0]);
        let mut neg = vec![0.0; stretch];
        let mut scan = |buf: &[f64]| {
            neg.iter_mut().zip(buf).for_each(|(m, v)| *m = -v);
            hi_scan.extend_from_slice(buf);
            lo_scan.extend_from_slice(&neg[..buf.len()]);
        };
        scan(&buf[1..stretch]);
        let mut lo = stretch;
        while lo < n {
            let len = stretch.min(n - lo);
            self.fill(shaft, lo, &mut buf[..len], &mut from, &wrapping);
            scan(&buf[..len]);
            lo += len;
        }
        let node = |k: usize| if k == n { period } else { k as f64 * self.h };
        let max = hi_scan.finish(n, node, |t| shaft.inertia_at(t).0);
        let min = lo_scan.finish(n, node, |t| -shaft.inertia_at(t).0);
        InertiaStats {
            j_min_kg_m2: -min.value,
            j_min_angle_deg: min.at,
            j_max_kg_m2: max.value,
            j_max_angle_deg: max.at,
            j_mean_kg_m2: mean,
        }
    }
}

/// Extremes of `f` near the grid's ([`loomkin_numeric::periodic_scan_max`] on `f` and on `−f`; the
/// grid's values are `f` every `h` over the period) and the mean given.
fn stats(grid: &[f64], h: f64, period: f64, f: &dyn Fn(f64) -> f64, mean: f64) -> InertiaStats {
    let n = grid.len();
    let node = |k: usize| if k == n { period } else { k as f64 * h };
    let find = |sign: f64| -> (f64, f64) {
        let m = loomkin_numeric::periodic_scan_max(n, node, |k| sign * grid[k], |t| sign * f(t));
        (sign * m.value, m.at)
    };
    let (max, at_max) = find(1.0);
    let (min, at_min) = find(-1.0);
    InertiaStats {
        j_min_kg_m2: min,
        j_min_angle_deg: at_min,
        j_max_kg_m2: max,
        j_max_angle_deg: at_max,
        j_mean_kg_m2: mean,
    }
}

/// A mechanism's name as one word of a column name (`frame 3` → `frame3`, `rotating parts` →
/// `rotating`).
fn column_word(name: &str) -> String {
    name.split_whitespace().take(if name.starts_with("frame") { 2 } else { 1 }).collect::<Vec<_>>().concat()
}

impl Shaft for LoomShaft<'_> {
    fn key_prefix(&self) -> &str {
        "drive."
    }

    fn period_rad(&self) -> f64 {
        self.motion().repeat_deg().to_radians()
    }

    fn inertia(&self, phi_rad: f64) -> (f64, f64) {
        self.inertia_at(phi_rad.to_degrees())
    }

    fn load_torque(&self, phi_rad: f64) -> f64 {
        self.load_at(phi_rad.to_degrees())
    }

    fn breaks_rad(&self) -> Vec<f64> {
        let joints = match self.corrected {
            Some(c) => c.joints(),
            None => self.motion().joints(),
        };
        let mut out: Vec<f64> = joints.into_iter().map(f64::to_radians).collect();
        match self.sley {
            Some(Sley::FourBar(s)) => {
                let range = s.table().beat_up_range_deg.to_radians();
                if s.table().beat_up_force_n > 0.0 && range > 0.0 {
                    for p in 0..self.motion().picks() {
                        let front = s.front_dead_centre_rad() + TAU * p as f64;
                        out.push(front);
                        out.push(front - range);
                    }
                }
            }
            Some(s @ Sley::Cam(_)) => {
                let turn = s.breaks_rad();
                for p in 0..self.motion().picks() {
                    out.extend(turn.iter().map(|b| b + TAU * p as f64));
                }
            }
            None => {}
        }
        let period = self.period_rad();
        out.iter_mut().for_each(|x| *x = x.rem_euclid(period));
        out
    }
}

/// Reads the `[drive]` table's values (all optional) into a [`DriveSpec`], each checked against
/// its descriptor and named `drive.KEY`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn drive_spec(
    rotating: Option<f64>,
    friction: Option<f64>,
    flywheel: Option<f64>,
    motor: MotorSpec,
) -> Result<DriveSpec> {
    let check = |f: &Field, v: Option<f64>| -> Result<f64> {
        Ok(f.check_as(&format!("drive.{}", f.name), v.unwrap_or_else(|| f.default_value()))?)
    };
    Ok(DriveSpec {
        rotating_inertia_kg_m2: check(&DriveSpec::ROTATING_INERTIA_KG_M2, rotating)?,
        friction_torque_n_m: check(&DriveSpec::FRICTION_TORQUE_N_M, friction)?,
        flywheel_kg_m2: check(&loomkin_drive::ripple::FLYWHEEL_KG_M2, flywheel)?,
        motor,
    })
}

impl From<loomkin_drive::RippleError> for LoomError {
    fn from(e: loomkin_drive::RippleError) -> Self {
        match e {
            loomkin_drive::RippleError::Range(r) => LoomError::Range(r),
            loomkin_drive::RippleError::Field { field, reason } => LoomError::Field { field, reason },
            loomkin_drive::RippleError::Infeasible { field, reason } => LoomError::Infeasible { field, reason },
            other => LoomError::Field { field: "drive".into(), reason: other.to_string() },
        }
    }
}

/// The speed ripple plotted: the shaft speed ω(φ) with its mean and extremes, and the motor and
/// load torques, over the repeat (`loomkin drive ripple -o`).
pub fn ripple_figure<S: Shaft + ?Sized>(sol: &loomkin_drive::Solution<'_, '_, S>, title: &str) -> loomkin_plot::Figure {
    use loomkin_plot::{Note, Panel, Rule, Series, sig4};
    let r = &sol.report;
    let deg: Vec<f64> = sol.angles_rad().iter().map(|a| a.to_degrees()).collect();
    let rpm: Vec<(f64, f64)> =
        deg.iter().zip(sol.omega()).map(|(a, w)| (*a, loomkin_units::rpm_from_rad_per_s(w))).collect();
    let motor: Vec<(f64, f64)> = deg.iter().copied().zip(sol.motor_torque()).collect();
    let load: Vec<(f64, f64)> = deg.iter().copied().zip(sol.load_torque()).collect();
    let speed = Panel::new("speed [rpm]", vec![Series::line("ω", rpm)])
        .with_rule(Rule::y(r.mean_speed_rpm, format!("mean {} rpm", sig4(r.mean_speed_rpm))))
        .with_notes([
            Note::new(r.max_speed_angle_deg, r.max_speed_rpm, format!("max {} rpm", sig4(r.max_speed_rpm))),
            Note::new(r.min_speed_angle_deg, r.min_speed_rpm, format!("min {} rpm", sig4(r.min_speed_rpm))),
        ]);
    let torque = Panel::new("torque [N·m]", vec![Series::line("motor", motor), Series::line("load", load)]);
    let full = format!(
        "{title}: {} motor, ripple {} %, ΔE {} J, flywheel {} kg·m²",
        r.motor,
        sig4(r.speed_ripple_pct),
        sig4(r.energy_swing_j),
        sig4(r.flywheel_kg_m2)
    );
    let picks = deg.last().map_or(0.0, |d| (d / 360.0).round());
    crate::diagram::repeat_figure(full, vec![speed, torque], picks > crate::diagram::TURNS_AXIS_FROM_PICKS as f64)
}

#[cfg(test)]
impl LoomShaft<'_> {
    /// The report as it was made before the total's grid was streamed (the whole grid held, then
    /// scanned): the reference the streamed report must meet bit for bit.
    pub(crate) fn report_materialised(&self, step_deg: f64) -> Result<(InertiaReport, Vec<f64>)> {
        Drive::STEP_DEG.check(step_deg)?;
        let motion = self.motion();
        let period = motion.repeat_deg();
        let n = (period / step_deg).round().max(1.0) as usize;
        let h = period / n as f64;
        let per_turn = 360.0 / h;
        let aligned = (per_turn - per_turn.round()).abs() <= 1e-9 * per_turn;
        let phi = motion.motion_deg();
        let rule = gauss_legendre(16);
        let mut total = vec![self.loom.drive.rotating_inertia_kg_m2; n];
        // Each frame's J over a rise and a fall on the grid, and where every move adds one: added in
        // the order of the repeat at the end, so the grid is swept once (not once per frame).
        let mut tables: Vec<Vec<f64>> = Vec::new();
        let mut adds: Vec<(usize, usize)> = Vec::new();
        let mut mechanisms = Vec::new();
        let mut mean_total = 0.0;
        for i in 0..self.loom.frame_count() {
            let moves = motion.moves(i);
            let mass = self.loom.frames[i].mass_kg;
            let j_of = |rising: bool, x: f64| {
                let k = motion.moving(i, rising, x);
                mass * k.dy * k.dy
            };
            // ∫ J over one move, by direction: Gauss–Legendre on the law's panels.
            let move_integral = |rising: bool| -> f64 {
                let law = motion.law().law(rising);
                let xs: Vec<f64> = std::iter::once(0.0).chain(law.joints()).chain(std::iter::once(1.0)).collect();
                xs.windows(2)
                    .map(|w| {
                        let (mid, half) = (0.5 * (w[0] + w[1]), 0.5 * (w[1] - w[0]));
                        rule.iter().map(|&(x, wt)| half * wt * j_of(rising, mid + half * x)).sum::<f64>()
                    })
                    .sum::<f64>()
                    * phi
            };
            let rises = moves.iter().filter(|m| m.rising).count();
            let falls = moves.len() - rises;
            let mean = (rises as f64 * if rises > 0 { move_integral(true) } else { 0.0 }
                + falls as f64 * if falls > 0 { move_integral(false) } else { 0.0 })
                / period;
            mean_total += mean;
            // Extremes over the move(s): the grid on x, refined.
            let extreme = |sign: f64| -> f64 {
                let mut best = f64::NEG_INFINITY;
                for rising in [true, false] {
                    if (rising && rises == 0) || (!rising && falls == 0) {
                        continue;
                    }
                    let m = 720;
                    let vals: Vec<f64> = (0..=m).map(|k| sign * j_of(rising, k as f64 / m as f64)).collect();
                    let (k, _) = vals
                        .iter()
                        .enumerate()
                        .fold((0, f64::NEG_INFINITY), |b, (k, v)| if *v > b.1 { (k, *v) } else { b });
                    let a = (k as f64 - 1.0).max(0.0) / m as f64;
                    let b = (k as f64 + 1.0).min(m as f64) / m as f64;
                    let r = loomkin_numeric::golden_max(|x| sign * j_of(rising, x), a, b);
                    best = best.max(r.value).max(vals[k]);
                }
                sign * best
            };
            let dwells = moves.len() as f64 * phi < period - 1e-9 * period;
            let j_max = if moves.is_empty() { 0.0 } else { extreme(1.0) };
            let j_min = if dwells || moves.is_empty() { 0.0 } else { extreme(-1.0) };
            mechanisms.push(MechanismInertia {
                name: format!("frame {}", i + 1),
                j_min_kg_m2: j_min,
                j_max_kg_m2: j_max,
                j_mean_kg_m2: mean,
            });
            // Onto the total's grid.
            let Some(first) = moves.first() else { continue };
            if aligned {
                let per_turn = per_turn.round() as i64;
                let w0 = first.start_deg - 360.0 * first.pick as f64;
                let k0 = (w0 / h - 1e-12).ceil() as i64;
                let x0 = (k0 as f64 * h - w0) / phi;
                let dx = h / phi;
                let cnt = ((1.0 - x0) / dx).ceil().max(0.0) as usize;
                let t = tables.len();
                tables.push((0..cnt).map(|j| j_of(true, x0 + j as f64 * dx)).collect());
                tables.push((0..cnt).map(|j| j_of(false, x0 + j as f64 * dx)).collect());
                for m in &moves {
                    let start = (k0 + per_turn * m.pick as i64).rem_euclid(n as i64) as usize;
                    adds.push((start, t + usize::from(!m.rising)));
                }
            } else {
                for (k, t) in total.iter_mut().enumerate() {
                    *t += self.frame_inertia(i, k as f64 * h).0;
                }
            }
        }
        adds.sort_unstable();
        for (start, t) in adds {
            add_wrapped(&mut total, start, &tables[t]);
        }
        if self.sley.is_some() {
            // The sley repeats every turn: one turn's J on the grid, tiled when the step divides 360°.
            if aligned {
                let m = per_turn.round() as usize;
                let turn: Vec<f64> = (0..m).map(|k| self.sley_inertia(k as f64 * h).0).collect();
                for chunk in total.chunks_mut(m) {
                    chunk.iter_mut().zip(&turn).for_each(|(t, v)| *t += v);
                }
            } else {
                for (k, t) in total.iter_mut().enumerate() {
                    *t += self.sley_inertia(k as f64 * h).0;
                }
            }
            let f = |x: f64| self.sley_inertia(x).0;
            let grid: Vec<f64> = (0..3600).map(|k| f(k as f64 * 0.1)).collect();
            let mut st = stats(&grid, 0.1, 360.0, &f, 0.0);
            st.j_mean_kg_m2 = self.sley_mean(&rule);
            mean_total += st.j_mean_kg_m2;
            mechanisms.push(MechanismInertia {
                name: "sley".into(),
                j_min_kg_m2: st.j_min_kg_m2,
                j_max_kg_m2: st.j_max_kg_m2,
                j_mean_kg_m2: st.j_mean_kg_m2,
            });
        }
        let rot = self.loom.drive.rotating_inertia_kg_m2;
        mean_total += rot;
        mechanisms.push(MechanismInertia {
            name: "rotating parts".into(),
            j_min_kg_m2: rot,
            j_max_kg_m2: rot,
            j_mean_kg_m2: rot,
        });
        let grid = total;
        let total = stats(&grid, h, period, &|x| self.inertia_at(x).0, mean_total);
        Ok((
            InertiaReport {
                picks: motion.picks(),
                repeat_deg: period,
                j_min_kg_m2: total.j_min_kg_m2,
                j_max_kg_m2: total.j_max_kg_m2,
                j_mean_kg_m2: total.j_mean_kg_m2,
                total,
                mechanisms,
            },
            grid,
        ))
    }
}

#[cfg(test)]
/// `tab` added to `total` from index `start` on, wrapping past the end (a move across the repeat's end).
fn add_wrapped(total: &mut [f64], start: usize, tab: &[f64]) {
    let n = total.len();
    let mut at = start;
    let mut rest = tab;
    while !rest.is_empty() {
        let len = rest.len().min(n - at);
        total[at..at + len].iter_mut().zip(&rest[..len]).for_each(|(t, v)| *t += v);
        rest = &rest[len..];
        at = 0;
    }
}

#[cfg(test)]
mod streamed {
    use super::*;

    /// A lift plan of `picks` picks on `shafts` shafts, each up or down at random (a fixed LCG).
    fn random_plan(picks: usize, shafts: usize, seed: u64) -> Pattern {
        let mut state = seed;
        let mut text = String::new();
        for _ in 0..picks {
            let mut up = Vec::new();
            for s in 1..=shafts {
                state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
                if state >> 63 == 1 {
                    up.push(s.to_string());
                }
            }
            if up.is_empty() {
                up.push("1".into());
            }
            text += &(up.join(" ") + "\n");
        }
        Pattern::from_lift_plan(&text).unwrap()
    }

    fn bits(r: &InertiaReport) -> Vec<u64> {
        let t = &r.total;
        let mut out = vec![t.j_min_kg_m2, t.j_min_angle_deg, t.j_max_kg_m2, t.j_max_angle_deg, t.j_mean_kg_m2];
        for m in &r.mechanisms {
            out.extend([m.j_min_kg_m2, m.j_max_kg_m2, m.j_mean_kg_m2]);
        }
        out.into_iter().map(f64::to_bits).collect()
    }

    /// The streamed report is the materialised one bit for bit: the examples' looms (four-bar and
    /// cam sleys, with and without rotating parts) on random plans of 1 to 37 picks, on steps that
    /// divide 360° (tables, moves across the repeat's end) and steps that do not (pointwise).
    #[test]
    fn the_streamed_report_is_the_whole_grids() {
        let looms = [
            include_str!("../../../examples/rapier-loom.toml"),
            include_str!("../../../examples/shuttle-loom.toml"),
            include_str!("../../../examples/projectile-loom.toml"),
        ];
        let mut checked = 0;
        for (l, text) in looms.iter().enumerate() {
            let loom = Loom::from_toml(text).unwrap();
            for (p, picks) in [1usize, 2, 3, 8, 37].into_iter().enumerate() {
                let shafts = loom.frame_count().min(24);
                let pattern = random_plan(picks, shafts, 0x9e37_79b9 + (l * 10 + p) as u64);
                let Ok(motion) = Motion::new(&loom, &pattern) else { continue };
                let shaft = LoomShaft::new(&loom, &motion, &pattern);
                for step in [0.5, 1.0, 0.7, 3.3, 10.0] {
                    let a = shaft.report(step).unwrap();
                    let (b, whole) = shaft.report_materialised(step).unwrap();
                    assert_eq!(bits(&a), bits(&b), "loom {l}, {picks} picks, step {step}: {a:?} vs {b:?}");
                    // The grid itself, made in stretches of every length from one point up.
                    let (grid, _, _) = shaft.grid_of(step).unwrap();
                    let wrapping = grid.wrapping();
                    for stretch in [1, 7, 720, whole.len()] {
                        let mut made = vec![0.0; whole.len()];
                        let mut from = 0;
                        for (c, out) in made.chunks_mut(stretch).enumerate() {
                            grid.fill(&shaft, c * stretch, out, &mut from, &wrapping);
                        }
                        let same = made.iter().zip(&whole).all(|(x, y)| x.to_bits() == y.to_bits());
                        assert!(same, "loom {l}, {picks} picks, step {step}, stretch {stretch}");
                    }
                    checked += 1;
                }
            }
        }
        assert!(checked >= 60, "{checked}");
    }
}
