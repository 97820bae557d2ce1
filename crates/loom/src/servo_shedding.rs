//! Electronic shedding on a loom: every frame's servo plan from the pattern, the frames as the
//! servos' loads, the study on the shared bus (loomkin-eshed does the work).

use crate::stagger::{SEARCH_STEP_DEG, STEPS};

/// The servo optimiser's compass steps, deg: 16° and 8° before `loom stagger`'s, as a motion angle
/// may move across most of its range (a search from 280° to 360° in 4° steps takes twenty sweeps).
const SERVO_STEPS: [f64; 7] = [16.0, 8.0, STEPS[0], STEPS[1], STEPS[2], STEPS[3], STEPS[4]];
use crate::{Loom, LoomError, Motion, Objective, Pattern, Result, ShedMotion, StaggerOptions, Timing, TimingReport};
use loomkin_eshed::{ClearShed, FrameInput, FrameLoad, FramePath, FramePlan, FrameSetup, MoveLaws, ServoReport};
use loomkin_units::StopFlag;
use serde::Serialize;

/// The servo frames' plans as the shed's timing reads them ([`ShedMotion`]): every frame's height
/// along its own plan.
#[derive(Debug, Clone)]
pub struct ServoMotion {
    paths: Vec<FramePath>,
    picks: usize,
}

impl ServoMotion {
    /// The frames of `setups` (front first) moving by their laws.
    pub fn new(setups: &[FrameSetup]) -> Self {
        let picks = setups.first().map_or(0, |s| (s.plan.period_deg / 360.0).round() as usize);
        Self { paths: setups.iter().map(|s| FramePath::new(&s.plan, &s.laws)).collect(), picks }
    }
}

impl ShedMotion for ServoMotion {
    fn frame_count(&self) -> usize {
        self.paths.len()
    }

    fn picks(&self) -> usize {
        self.picks
    }

    fn frame_y_m(&self, i: usize, theta_deg: f64) -> f64 {
        self.paths[i].y_m(theta_deg)
    }

    /// A frame in a dwell over the whole span ([`FramePath::rest_m`]).
    fn frame_rest_m(&self, i: usize, from_deg: f64, to_deg: f64) -> Option<f64> {
        self.paths[i].rest_m(from_deg, to_deg)
    }

    /// Every frame's segments over the span ([`FramePath::key_words`]).
    fn turn_key(&self, pick: usize, from_deg: f64, to_deg: f64, key: &mut Vec<u64>) {
        for p in &self.paths {
            p.key_words(360.0 * pick as f64, from_deg, to_deg, key);
            key.push(u64::MAX);
        }
    }
}

/// The timing of the shed (`loom check`'s window and clearance) while the frames of `setups` move
/// by their plans: [`Timing`] over a [`ServoMotion`].
pub fn servo_timing(loom: &Loom, pattern: &Pattern, setups: &[FrameSetup]) -> Result<TimingReport> {
    let motion = ServoMotion::new(setups);
    Timing::new(loom, &motion, pattern)?.report_of(false)
}

/// The report's keys of a timing.
fn clear_shed(t: &TimingReport) -> ClearShed {
    ClearShed {
        min_clearance_mm: t.min_clearance_mm,
        window_deg: t.window_deg,
        window_open_deg: t.open_deg,
        window_close_deg: t.close_deg,
        max_speed_rpm: t.max_speed_rpm,
    }
}

/// The laws of the frames' moves where `[shedding.servo]` gives none: the shedding law's rise and
/// fall (named `shedding` when refused).
pub fn servo_laws(loom: &Loom) -> MoveLaws {
    let law = &loom.shedding.law;
    let mut laws = MoveLaws::new(
        (law.spec(true).clone(), law.law(true).clone()),
        (law.spec(false).clone(), law.law(false).clone()),
    );
    laws.fields = ["shedding".into(), "shedding".into(), "shedding".into()];
    // The shedding law's own name where it is one law both ways (a preset: `dobby preset`).
    if law.spec(true) == law.spec(false) {
        laws.labels = [law.label().into(), law.label().into(), String::new()];
    }
    laws
}

/// Frame `i`'s laws: those `[shedding.servo]` gives for it, else the shedding law's
/// ([`servo_laws`]).
pub fn frame_laws(loom: &Loom, i: usize) -> Result<MoveLaws> {
    let servo = loom.shedding.servo.as_ref().ok_or_else(|| LoomError::field("shedding.drive", "dobby"))?;
    let d = servo_laws(loom);
    let f = servo.frames.get(i).ok_or_else(|| LoomError::field("shedding.servo", format!("no frame {}", i + 1)))?;
    Ok(f.moves.laws(&d))
}

/// Every frame's plan, laws, load and servo (front first) for `loom` weaving `pattern`, the loom's
/// `[shedding.servo]` giving the drives and the laws and motion angles by kind of move;
/// `motion_deg` overrides every frame's motion angle of a move up (a move down's scaled with it,
/// keeping the loom file's ratio of the two, to 12 significant digits) and `centre_deg` every frame's move centre (crossing
/// offset plus stagger) when given (the optimiser's variables). Fails when the loom's shedding
/// drive is the dobby.
pub fn servo_setups(
    loom: &Loom,
    pattern: &Pattern,
    motion_deg: Option<&[f64]>,
    centre_deg: Option<&[f64]>,
) -> Result<Vec<FrameSetup>> {
    let maker = SetupMaker::new(loom, pattern)?;
    (0..loom.frame_count()).map(|i| maker.frame(i, motion_deg.map(|m| m[i]), centre_deg.map(|c| c[i]))).collect()
}

/// What the frames' plans are made from, worked out once for a loom and a pattern: the lifts, the
/// laws and the loom file's motion angles of every frame ([`servo_setups`] frame by frame, for a
/// search that changes one frame at a time).
struct SetupMaker<'a> {
    loom: &'a Loom,
    pass_through: bool,
    motion: Motion,
    laws: Vec<MoveLaws>,
    angles: Vec<(f64, f64)>,
}

impl<'a> SetupMaker<'a> {
    /// Fails when the loom's shedding drive is the dobby.
    fn new(loom: &'a Loom, pattern: &Pattern) -> Result<Self> {
        let servo = loom.shedding.servo.as_ref().ok_or_else(|| {
            LoomError::field(
                "shedding.drive",
                "the loom's shedding drive is the dobby: give drive = \"servo\" and [shedding.servo]",
            )
        })?;
        let motion = Motion::new(loom, pattern)?;
        let n = loom.frame_count();
        Ok(Self {
            loom,
            pass_through: servo.pass_through,
            motion,
            laws: (0..n).map(|i| frame_laws(loom, i)).collect::<Result<_>>()?,
            angles: (0..n).map(|i| file_motion_deg(loom, i)).collect(),
        })
    }

    /// Frame `i`'s plan, laws, load and servo; `motion_deg` and `centre_deg` as [`servo_setups`]'s
    /// for this frame.
    fn frame(&self, i: usize, motion_deg: Option<f64>, centre_deg: Option<f64>) -> Result<FrameSetup> {
        let loom = self.loom;
        let servo = loom.shedding.servo.as_ref().ok_or_else(|| LoomError::field("shedding.drive", "dobby"))?;
        let (rise, fall) = self.angles[i];
        // The move down's angle scaled with the move up's is kept to 12 significant digits
        // (a change of at most 5·10⁻¹² of it, half a unit of the twelfth digit): the plan
        // moves by the number the report prints (`360`, not `359.99999999999994` = 312 ×
        // 300/260), and that number typed back into the loom file gives the same plan bit
        // for bit.
        let (phi, phi_fall) = match motion_deg {
            Some(m) if fall == rise => (m, m),
            Some(m) => (m, loomkin_units::to_12_digits(m * (fall / rise))),
            None => (rise, fall),
        };
        let check = |key: &str, v: f64| {
            loomkin_shed::MOTION_DEG.check(&format!("shedding.servo.frame: frame {} {key}", i + 1), v)
        };
        let input = FrameInput {
            up: self.motion.lifts(i),
            stroke_m: self.motion.stroke_m(i),
            centre_deg: centre_deg.unwrap_or(self.motion.centre0_deg(i)),
            motion_deg: check("motion_deg", phi)?,
            fall_motion_deg: check("fall_motion_deg", phi_fall)?,
        };
        let plan = FramePlan::new(&input, self.pass_through)?;
        let f = &loom.frames[i];
        let load = FrameLoad {
            mass_kg: f.mass_kg,
            spring_n_m: f.spring_n_m,
            preload_n: f.preload_n,
            stroke_m: self.motion.stroke_m(i),
            start_level_m: plan.start_level_m(),
        };
        Ok(FrameSetup { plan, laws: self.laws[i].clone(), load, servo: servo.frames[i].clone() })
    }
}

/// Frame `i`'s motion angles up and down as the loom file gives them, deg: `[shedding.servo]`'s
/// by kind of move, else the frame's `motion_deg`, else the shedding law's.
fn file_motion_deg(loom: &Loom, i: usize) -> (f64, f64) {
    let law = loom.shedding.law.motion_deg();
    match loom.shedding.servo.as_ref().and_then(|s| s.frames.get(i)) {
        Some(f) => {
            let one = f.motion_deg.unwrap_or(law);
            (f.moves.rise_motion_deg.unwrap_or(one), f.moves.fall_motion_deg.unwrap_or(one))
        }
        None => (law, law),
    }
}

/// The servo-shedding study of `loom` weaving `pattern` (`loomkin loom servo`), with the shed the
/// carrier passes ([`servo_timing`]). Fails, as `loom check` does, when the carrier is taller than
/// the shed ever opens.
pub fn servo_study(loom: &Loom, pattern: &Pattern) -> Result<ServoReport> {
    let setups = servo_setups(loom, pattern, None, None)?;
    servo_study_of(loom, pattern, &setups)
}

/// [`servo_study`] of given plans ([`servo_setups`], or the optimiser's).
pub fn servo_study_of(loom: &Loom, pattern: &Pattern, setups: &[FrameSetup]) -> Result<ServoReport> {
    let servo = loom.shedding.servo.as_ref().ok_or_else(|| LoomError::field("shedding.drive", "dobby"))?;
    let mut r = loomkin_eshed::analyse(setups, &servo.bus, loom.speed.rpm(), servo.pass_through)?;
    r.clear_shed = Some(clear_shed(&servo_timing(loom, pattern, setups)?));
    Ok(r)
}

/// Every frame's cam table over the repeat in `formats` (the default set when empty), points
/// placed by `spacing`, and the manifest (`loomkin loom servo --emit-tables`).
pub fn servo_tables(
    loom: &Loom,
    pattern: &Pattern,
    spacing: loomkin_cams::table::Spacing,
    formats: &[loomkin_cams::table::Format],
) -> Result<loomkin_eshed::Tables> {
    servo_tables_of(loom, &servo_setups(loom, pattern, None, None)?, spacing, formats)
}

/// [`servo_tables`] of given plans (`--emit-tables` after `--optimize`: the optimised plans).
pub fn servo_tables_of(
    loom: &Loom,
    setups: &[FrameSetup],
    spacing: loomkin_cams::table::Spacing,
    formats: &[loomkin_cams::table::Format],
) -> Result<loomkin_eshed::Tables> {
    Ok(loomkin_eshed::frame_tables(setups, spacing, formats, loom.speed.rpm())?)
}

/// Curves of the servo-shedding study: `points` samples over the repeat.
pub fn servo_curves(loom: &Loom, pattern: &Pattern, points: usize) -> Result<loomkin_eshed::Curves> {
    servo_curves_of(loom, &servo_setups(loom, pattern, None, None)?, points)
}

/// [`servo_curves`] of given plans.
pub fn servo_curves_of(loom: &Loom, setups: &[FrameSetup], points: usize) -> Result<loomkin_eshed::Curves> {
    let servo = loom.shedding.servo.as_ref().ok_or_else(|| LoomError::field("shedding.drive", "dobby"))?;
    Ok(loomkin_eshed::curves(setups, &servo.bus, loom.speed.rpm(), points)?)
}

/// Points of [`servo_figure`]'s curves: one a degree of the repeat, at most this many.
pub const SERVO_PLOT_POINTS: usize = 20_001;

/// The plot of `loomkin loom servo -o`: every frame's motor torque, and the bus power with its
/// peak, over the repeat.
pub fn servo_figure(loom: &Loom, pattern: &Pattern, report: &ServoReport) -> Result<loomkin_plot::Figure> {
    servo_figure_of(loom, &servo_setups(loom, pattern, None, None)?, report)
}

/// [`servo_figure`] of given plans (after `--optimize`: the optimised plans and their report).
pub fn servo_figure_of(loom: &Loom, setups: &[FrameSetup], report: &ServoReport) -> Result<loomkin_plot::Figure> {
    use loomkin_plot::{Figure, Legend, Note, Panel, Rule, Series, sig4};
    let points = ((report.repeat_deg as usize) + 1).clamp(2, SERVO_PLOT_POINTS);
    let c = servo_curves_of(loom, setups, points)?;
    let line = |ys: &[f64]| c.angle_deg.iter().copied().zip(ys.iter().copied()).collect::<Vec<_>>();
    let torques: Vec<Series> =
        c.torque_n_m.iter().enumerate().map(|(i, t)| Series::line(format!("frame {}", i + 1), line(t))).collect();
    let legend = if torques.len() <= 8 { Legend::Auto } else { Legend::Hidden };
    let peak = report.peak_bus_power_w;
    let mut bus = Panel::new("bus power [W]", vec![Series::line("bus", line(&c.bus_power_w)).with_color([0, 0, 0])])
        .with_notes([Note::new(
            report.peak_bus_power_at_deg,
            peak,
            format!("peak {} W at {}°", sig4(peak), sig4(report.peak_bus_power_at_deg)),
        )]);
    if let Some(m) = report.braking_resistor_max_w {
        bus = bus.with_rule(Rule::y(-m, format!("braking resistor limit −{} W", sig4(m))));
    }
    let title = format!(
        "servo shedding, {} picks at {} rpm: peak bus power {} W, mean {} W, braking {} J per repeat",
        report.picks,
        report.speed_rpm,
        sig4(peak),
        sig4(report.mean_bus_power_w),
        sig4(report.braking_energy_j)
    );
    let panels = vec![Panel::new("motor torque [N·m]", torques).with_legend(legend), bus];
    let mut fig = Figure::new(title, "main-shaft angle [deg] (0 = beat-up of the first pick)", panels);
    fig.size = Some((1100, 800));
    Ok(fig)
}

/// What the servo optimiser minimises and the least clearance it keeps (`loom servo --optimize
/// --objective … --min-clearance-mm …`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ServoOptions {
    /// What to minimise.
    pub objective: Objective,
    /// The least clearance to the carrier every pick must keep from entry to exit, mm: the bound
    /// of `loom stagger`'s ([`StaggerOptions::MIN_CLEARANCE_MM`], 0 … 1000 mm, 0 when left out).
    /// When the loom file's own design keeps less, the search keeps the design's (never worse).
    pub min_clearance_mm: f64,
}

impl ServoOptions {
    /// Minimise `objective` keeping the default least clearance.
    pub fn new(objective: Objective) -> Self {
        Self { objective, min_clearance_mm: StaggerOptions::MIN_CLEARANCE_MM.default_value() }
    }

    /// Checks the least clearance against its range.
    pub fn validate(&self) -> Result<()> {
        StaggerOptions::MIN_CLEARANCE_MM.check(self.min_clearance_mm)?;
        Ok(())
    }
}

/// The servo-shedding optimum (`loomkin loom servo --optimize`): every frame's stagger and motion
/// angle, what it gains against the loom file's design and what it costs in window and clearance,
/// and the study of the optimised plans.
#[derive(Debug, Clone, Serialize)]
pub struct ServoOptimum {
    /// What was minimised: `peak` the peak bus power, `rms` the worst frame's RMS motor torque.
    pub objective: Objective,
    /// Peak bus power of the loom file's design, W.
    pub peak_bus_power_w_before: f64,
    /// Peak bus power of the optimum, W.
    pub peak_bus_power_w_after: f64,
    /// The largest of the frames' RMS motor torques, the loom file's design, N·m.
    pub worst_rms_torque_n_m_before: f64,
    /// The same, the optimum, N·m.
    pub worst_rms_torque_n_m_after: f64,
    /// The clear-shed window common to every pick, the loom file's design, deg.
    pub window_deg_before: f64,
    /// The same, the optimum, deg.
    pub window_deg_after: f64,
    /// The least clearance to the carrier from entry to exit, the loom file's design, mm.
    pub min_clearance_mm_before: f64,
    /// The same, the optimum, mm.
    pub min_clearance_mm_after: f64,
    /// The least clearance the search kept (on its grid), mm: `min_clearance_mm` (0 unless asked),
    /// or the design's own when it is below that (the search never makes it worse).
    pub min_clearance_kept_mm: f64,
    /// Every frame's stagger of the optimum (its move centre less the crossing), front first, deg.
    pub stagger_deg: Vec<f64>,
    /// Every frame's motion angle of the optimum (of a move up where the loom file gives the moves
    /// down another), front first, deg.
    pub motion_deg: Vec<f64>,
    /// Every frame's motion angle of a move down, front first, deg, where the loom file gives some
    /// frame's moves down an angle of their own (the search keeps its ratio to the move up's);
    /// absent otherwise (`motion_deg` both ways).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fall_motion_deg: Option<Vec<f64>>,
    /// Frames the search moved (the others never change place in the pattern: their stagger and
    /// motion angle are left as the loom file gives them).
    pub frames_searched: usize,
    /// Picks whose turns the search evaluated, one for every class of picks that the frames see
    /// alike under any stagger and motion angle (all picks when the classes, each with the picks
    /// around it, would be as many).
    pub picks_searched: usize,
    /// Objective evaluations made by the search.
    pub evaluations: usize,
    /// Clearance checks made by the search.
    pub clearance_checks: usize,
    /// The study of the optimised plans.
    #[serde(flatten)]
    pub report: ServoReport,
    /// The optimised plans (for the controllers' tables).
    #[serde(skip)]
    pub setups: Vec<FrameSetup>,
}

/// The servo optimiser's state: the loom, the objective, the counts.
struct ServoSearch<'a> {
    loom: &'a Loom,
    pattern: &'a Pattern,
    objective: Objective,
    frames: usize,
    /// The crossing taken into `[−180°, 180°)`, deg.
    delta: f64,
    /// The least clearance to keep, m.
    need_m: f64,
    /// The short pattern the search evaluates, and its picks that stand for the repeat's.
    reduced: Reduced,
    /// The frames' plans on the short pattern, remembered from one evaluation to the next.
    plans: SearchFrames<'a>,
    evaluations: usize,
    clearance_checks: usize,
    /// The frames' drive points, remembered from one evaluation to the next (a crank and lever's).
    memo: loomkin_eshed::DriveMemo,
    stop: &'a StopFlag,
    progress: &'a dyn Fn(usize, usize),
    stages: (usize, usize),
}

/// One frame's plan at one move centre and motion angle, and its RMS motor torque once asked for.
struct FrameAt {
    key: [u64; 2],
    setup: FrameSetup,
    rms: Option<f64>,
}

/// The frames' plans as the search meets them. The compass search moves one frame's stagger or
/// motion angle at a time, so every other frame's plan comes again bit for bit: each frame keeps
/// its plans (and RMS torques) at the last [`SearchFrames::RECENT`] points it was asked for, and
/// the plans of the point evaluated last are kept in frame order for the bus and the timing.
struct SearchFrames<'a> {
    maker: SetupMaker<'a>,
    /// Per frame, most recent first.
    recent: Vec<Vec<FrameAt>>,
    /// Per frame, the servo check's values of its moves (a move that the search shifts, or brings
    /// back, is not worked out again).
    checks: Vec<loomkin_eshed::CheckMemo>,
    /// The plans of the point asked for last, and their keys.
    now: Vec<FrameSetup>,
    now_keys: Vec<[u64; 2]>,
}

impl<'a> SearchFrames<'a> {
    /// Points remembered per frame: the current one and the two the search tries about it, and one
    /// more.
    const RECENT: usize = 4;

    fn new(maker: SetupMaker<'a>) -> Self {
        let n = maker.laws.len();
        Self {
            maker,
            recent: (0..n).map(|_| Vec::new()).collect(),
            checks: vec![Default::default(); n],
            now: Vec::new(),
            now_keys: Vec::new(),
        }
    }

    /// Frame `i` with its move centre at `centre_deg` and motion angle `motion_deg`: remembered
    /// (moved to the front), or planned.
    fn at(&mut self, i: usize, centre_deg: f64, motion_deg: f64) -> Result<&mut FrameAt> {
        let key = [centre_deg.to_bits(), motion_deg.to_bits()];
        let recent = &mut self.recent[i];
        match recent.iter().position(|f| f.key == key) {
            Some(k) => recent[..=k].rotate_right(1),
            None => {
                let setup = self.maker.frame(i, Some(motion_deg), Some(centre_deg))?;
                recent.truncate(Self::RECENT - 1);
                recent.insert(0, FrameAt { key, setup, rms: None });
            }
        }
        Ok(&mut recent[0])
    }

    /// Frame `i`'s RMS motor torque at `centre_deg` and `motion_deg`: remembered with its plan, or
    /// worked out by `of` from the plan and the frame's memo of the servo check.
    fn rms(
        &mut self,
        i: usize,
        centre_deg: f64,
        motion_deg: f64,
        of: impl FnOnce(&FrameSetup, &mut loomkin_eshed::CheckMemo) -> Result<f64>,
    ) -> Result<f64> {
        self.at(i, centre_deg, motion_deg)?;
        let f = &mut self.recent[i][0];
        if let Some(rms) = f.rms {
            return Ok(rms);
        }
        let rms = of(&f.setup, &mut self.checks[i])?;
        f.rms = Some(rms);
        Ok(rms)
    }

    /// Every frame's plan at the move centres `centre_deg` and motion angles `motion_deg` (what
    /// [`servo_setups`] makes of them).
    fn setups(&mut self, centre_deg: &[f64], motion_deg: &[f64]) -> Result<&[FrameSetup]> {
        for i in 0..centre_deg.len() {
            let key = [centre_deg[i].to_bits(), motion_deg[i].to_bits()];
            if self.now_keys.get(i) == Some(&key) {
                continue;
            }
            let setup = self.at(i, centre_deg[i], motion_deg[i])?.setup.clone();
            if i < self.now.len() {
                (self.now[i], self.now_keys[i]) = (setup, key);
            } else {
                self.now.push(setup);
                self.now_keys.push(key);
            }
        }
        Ok(&self.now)
    }
}

impl ServoSearch<'_> {
    /// The move centres and motion angles of `x` = every frame's stagger, then every frame's motion
    /// angle.
    fn centres_and_angles(&self, x: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let (stagger, motion) = x.split_at(self.frames);
        (stagger.iter().map(|s| self.delta + s).collect(), motion.to_vec())
    }

    /// The plans of `x` over the loom's pattern.
    fn setups(&self, x: &[f64]) -> Result<Vec<FrameSetup>> {
        let (centre, motion) = self.centres_and_angles(x);
        servo_setups(self.loom, self.pattern, Some(&motion), Some(&centre))
    }

    fn objective(&mut self, x: &[f64]) -> Result<f64> {
        self.stop.check()?;
        self.evaluations += 1;
        let servo = self.loom.shedding.servo.as_ref().ok_or_else(|| LoomError::field("shedding.drive", "dobby"))?;
        let speed = self.loom.speed.rpm();
        let (centre, motion) = self.centres_and_angles(x);
        let r = &self.reduced;
        Ok(match self.objective {
            Objective::Peak => {
                let setups = self.plans.setups(&centre, &motion)?;
                let picks = (!r.whole).then_some(r.picks.as_slice());
                loomkin_eshed::peak_bus_power_w_memo(setups, &servo.bus, speed, picks, &mut self.memo)?
            }
            // The worst frame's: each frame's RMS torque is its own plan's, remembered with it.
            Objective::Rms => {
                let repeat = self.pattern.picks();
                let mut worst = 0.0f64;
                for i in 0..self.frames {
                    worst = worst.max(self.plans.rms(i, centre[i], motion[i], |f, memo| {
                        Ok(if r.whole {
                            loomkin_eshed::rms_torque_n_m(i, f, speed, memo)?
                        } else {
                            loomkin_eshed::rms_torque_n_m_at(i, f, speed, &r.picks, &r.counts, repeat, memo)?
                        })
                    })?);
                }
                worst
            }
        })
    }

    /// The least clearance over the insertion of every pick on the stagger search's grid, m.
    fn clearance(&mut self, x: &[f64]) -> Result<f64> {
        self.stop.check()?;
        self.clearance_checks += 1;
        let (centre, motion) = self.centres_and_angles(x);
        let motion = ServoMotion::new(self.plans.setups(&centre, &motion)?);
        let timing = Timing::new(self.loom, &motion, &self.reduced.pattern)?;
        Ok(if self.reduced.whole {
            timing.min_clearance_coarse(SEARCH_STEP_DEG)
        } else {
            timing.min_clearance_coarse_at(SEARCH_STEP_DEG, &self.reduced.picks)
        })
    }
}

/// A short pattern whose picks `picks` stand for every pick of a loom's pattern in the servo
/// optimiser: what the frames do over a pick's turn (the bus window, the insertion) depends only on
/// the lifts of the picks around it, so picks whose neighbourhoods agree see the same turn (shifted
/// by whole turns) whatever the staggers and motion angles.
#[derive(Debug, Clone)]
pub struct Reduced {
    /// The short pattern: for each class, its neighbourhood of lift rows, the first and the last
    /// row once more around it (so no move between two neighbourhoods runs into either).
    pub pattern: Pattern,
    /// Its picks standing for the classes (increasing).
    pub picks: Vec<usize>,
    /// How many picks of the loom's pattern each stands for (adding up to its picks).
    pub counts: Vec<usize>,
    /// No reduction: the loom's pattern and all its picks.
    pub whole: bool,
}

impl Reduced {
    /// No reduction: `pattern` itself, every pick.
    pub fn whole(pattern: &Pattern) -> Self {
        let n = pattern.picks();
        Self { pattern: pattern.clone(), picks: (0..n).collect(), counts: vec![1; n], whole: true }
    }
}

/// The [`Reduced`] pattern of `loom` weaving `pattern` for staggers within
/// `±shedding.max_stagger_deg` and any motion angle; the pattern itself and all its picks when
/// the neighbourhoods would not be shorter.
///
/// **Why it holds.** A move into pick `q` centred on `360q + c` (c the crossing offset plus the
/// stagger) lies within `[360q + c − 360°, 360q + c + 360°]`: without pass-through it is `φ ≤ 360°`
/// long about the centre; laid end to end in a run of `k + 1` changes, the `j`-th starts
/// `j(360° − φ)/(k + 1) < 360° − φ` before `360q + c − φ/2` and is at most 360° long. So the turn
/// `[360p + s₀, 360p + s₁]` (the bus window `[0, 360°]`, the insertion, the crossing's turn) meets
/// only moves into picks `p + q_lo … p + q_hi`, which the lifts of picks `p + q_lo − 1 … p + q_hi`
/// decide. With pass-through a move's length depends on its whole run, so a neighbourhood grows
/// until no frame's run crosses its ends; when that reaches the whole repeat (a frame changing on
/// every pick) there is no reduction. The first and last rows repeated around a neighbourhood stop
/// the moves between neighbourhoods from joining its runs. The RMS objective sums each frame's
/// `∫T² dt` by per-pick cells, the turn about the pick's move centre (`[360p + c − 180°, 360p + c +
/// 180°]`, [`loomkin_eshed::FramePlan::cell_sums`]): what falls in pick `p`'s cell depends on the
/// lifts of picks `p − 1` and `p` and the run of changes through `p`, all within the
/// neighbourhood, so each class's cell counts once per pick of the class. Tested: the search's
/// objectives and clearance equal the whole pattern's.
pub fn reduced_pattern(loom: &Loom, pattern: &Pattern) -> Result<Reduced> {
    let picks = pattern.picks();
    let whole = || Reduced::whole(pattern);
    let n = loom.frame_count();
    let pass_through = loom.shedding.servo.as_ref().is_some_and(|s| s.pass_through);
    let delta = crate::crossing_offset_deg(loom.shedding.crossing_deg);
    let m = loom.shedding.max_stagger_deg;
    let ins = &loom.insertion;
    let s0 = 0f64.min(ins.entry_deg).min(ins.exit_deg).min(delta);
    let s1 = 360f64.max(ins.entry_deg).max(ins.exit_deg).max(delta + 360.0);
    let q_lo = ((s0 - (delta + m) - 360.0) / 360.0).floor() as i64;
    let q_hi = ((s1 - (delta - m) + 360.0) / 360.0).ceil() as i64;
    let at = |p: i64| p.rem_euclid(picks as i64) as usize;
    let change = |i: usize, p: i64| pattern.is_up(at(p), i) != pattern.is_up(at(p - 1), i);
    // Some frame's run of changes goes on from pick `p` to `p + 1`.
    let straddles = |p: i64| pass_through && (0..n).any(|i| change(i, p) && change(i, p + 1));
    let mut classes: loomkin_numeric::WordMap<Vec<u64>, usize> = Default::default();
    let (mut rows, mut centres, mut counts) = (Vec::new(), Vec::new(), Vec::<usize>::new());
    let mut key = Vec::new();
    for p in 0..picks as i64 {
        let (mut lo, mut hi) = (p + q_lo - 1, p + q_hi);
        while straddles(lo) && hi - lo < picks as i64 {
            lo -= 1;
        }
        while straddles(hi) && hi - lo < picks as i64 {
            hi += 1;
        }
        if hi - lo + 3 > picks as i64 {
            return Ok(whole());
        }
        key.clear();
        key.extend([(lo - p) as u64, (hi - p) as u64]);
        for q in lo..=hi {
            let mut word = 0u64;
            for i in 0..n {
                if i % 64 == 0 && i > 0 {
                    key.push(word);
                    word = 0;
                }
                word |= u64::from(pattern.is_up(at(q), i)) << (i % 64);
            }
            key.push(word);
        }
        if let Some(&c) = classes.get(&key) {
            counts[c] += 1;
        } else {
            classes.insert(key.clone(), counts.len());
            counts.push(1);
            rows.push(pattern.rows()[at(lo)].clone());
            centres.push(rows.len() + (p - lo) as usize);
            rows.extend((lo..=hi).map(|q| pattern.rows()[at(q)].clone()));
            rows.push(pattern.rows()[at(hi)].clone());
            if rows.len() >= picks {
                return Ok(whole());
            }
        }
    }
    Ok(Reduced { pattern: Pattern::new(pattern.shafts(), rows)?, picks: centres, counts, whole: false })
}

/// The per-frame stagger and motion angle of `loom` weaving `pattern` that minimise `objective`
/// (`peak`: the peak bus power; `rms`: the worst frame's RMS motor torque) keeping the insertion
/// the carrier needs clear in every pick: a compass search ([`loomkin_numeric::compass_min`], the
/// steps of `loom stagger`) from the loom file's design over every frame's stagger within
/// `±shedding.max_stagger_deg` and motion angle within [`loomkin_shed::MOTION_DEG`], a move taken
/// when it lowers the objective (exact, on the plans) and keeps the least clearance from entry to
/// exit (on a 2° grid with both ends, as `loom stagger` checks it) at 0 or more — or, when the
/// design itself leaves less, no less than the design's. Ends with [`LoomError::Stopped`] once
/// `stop` is set; calls `progress(done, all)` as it passes its stages.
pub fn optimise_servo(
    loom: &Loom,
    pattern: &Pattern,
    objective: Objective,
    stop: &StopFlag,
    progress: &dyn Fn(usize, usize),
) -> Result<ServoOptimum> {
    optimise_servo_with(loom, pattern, &ServoOptions::new(objective), stop, progress)
}

/// [`optimise_servo`] keeping at least `options.min_clearance_mm` of clearance (or the design's
/// own when it keeps less). The search leaves out the frames that never change place, and
/// evaluates one pick for every class of picks that see the same turn ([`reduced_pattern`]: the
/// peak objective, the clearance, and the RMS objective with each class weighted by its picks,
/// [`loomkin_eshed::worst_rms_torque_n_m_at`]); the optimum is then worked out exactly over the
/// whole repeat.
pub fn optimise_servo_with(
    loom: &Loom,
    pattern: &Pattern,
    options: &ServoOptions,
    stop: &StopFlag,
    progress: &dyn Fn(usize, usize),
) -> Result<ServoOptimum> {
    optimise(loom, pattern, options, true, stop, progress)
}

/// [`optimise_servo_with`]; `reduce`: the search on the [`reduced_pattern`] (otherwise on the
/// whole repeat: what the tests compare it with).
fn optimise(
    loom: &Loom,
    pattern: &Pattern,
    options: &ServoOptions,
    reduce: bool,
    stop: &StopFlag,
    progress: &dyn Fn(usize, usize),
) -> Result<ServoOptimum> {
    options.validate()?;
    let objective = options.objective;
    let before = servo_study(loom, pattern)?;
    loom.shedding.servo.as_ref().ok_or_else(|| LoomError::field("shedding.drive", "dobby"))?;
    let motion = Motion::new(loom, pattern)?;
    let n = loom.frame_count();
    let delta = crate::crossing_offset_deg(loom.shedding.crossing_deg);
    let mut x0: Vec<f64> = (0..n).map(|i| motion.centre0_deg(i) - delta).collect();
    // A frame's motion angle up; down, the loom file's ratio of the two kept ([`servo_setups`]).
    let angles: Vec<(f64, f64)> = (0..n).map(|i| file_motion_deg(loom, i)).collect();
    x0.extend(angles.iter().map(|a| a.0));
    let m = loom.shedding.max_stagger_deg;
    let bound = |b: loomkin_units::Bound, default: f64| match b {
        loomkin_units::Bound::Closed(v) | loomkin_units::Bound::Open(v) => v,
        loomkin_units::Bound::Unbounded => default,
    };
    let (phi_lo, phi_hi) = (bound(loomkin_shed::MOTION_DEG.lo, 1.0), bound(loomkin_shed::MOTION_DEG.hi, 360.0));
    // The variables: the stagger and motion angle of every frame that changes place somewhere.
    let moving: Vec<usize> = (0..n)
        .filter(|&i| (0..pattern.picks()).any(|p| motion.is_up(i, p as i64) != motion.is_up(i, p as i64 - 1)))
        .collect();
    let vars: Vec<usize> = moving.iter().copied().chain(moving.iter().map(|i| n + i)).collect();
    // Both angles of a frame within the motion angle's range.
    let ratio = |j: usize| angles[j - n].1 / angles[j - n].0;
    let lo: Vec<f64> = vars.iter().map(|&j| if j < n { -m } else { phi_lo.max(phi_lo / ratio(j)) }).collect();
    let hi: Vec<f64> = vars.iter().map(|&j| if j < n { m } else { phi_hi.min(phi_hi / ratio(j)) }).collect();
    let full = |x0: &[f64], y: &[f64]| {
        let mut x = x0.to_vec();
        for (k, &j) in vars.iter().enumerate() {
            x[j] = y[k];
        }
        x
    };
    let reduced = if reduce { reduced_pattern(loom, pattern)? } else { Reduced::whole(pattern) };
    let plans = SearchFrames::new(SetupMaker::new(loom, &reduced.pattern)?);
    let mut s = ServoSearch {
        loom,
        pattern,
        objective,
        frames: n,
        delta,
        need_m: 0.0,
        reduced,
        plans,
        evaluations: 0,
        clearance_checks: 0,
        memo: Default::default(),
        stop,
        progress,
        stages: (0, SERVO_STEPS.len()),
    };
    let (design, floor) = (s.clearance(&x0)?, options.min_clearance_mm * 1e-3);
    s.need_m = design.min(floor);
    let kept_mm = if floor <= design { options.min_clearance_mm } else { design * 1e3 };
    let f0 = s.objective(&x0)?;
    let y0: Vec<f64> = vars.iter().map(|&j| x0[j]).collect();
    let (y, _) = loomkin_numeric::compass_min(
        &mut s,
        y0,
        f0,
        &SERVO_STEPS,
        &lo,
        &hi,
        |s, y| s.objective(&full(&x0, y)),
        |s, y| Ok(s.clearance(&full(&x0, y))? >= s.need_m),
        |s| {
            (s.progress)(s.stages.0, s.stages.1);
            s.stages.0 += 1;
        },
    )?;
    let x = full(&x0, &y);
    (s.progress)(s.stages.1, s.stages.1);
    let setups = s.setups(&x)?;
    let report = servo_study_of(loom, pattern, &setups)?;
    let worst = |r: &ServoReport| r.frames.iter().map(|f| f.rms_torque_n_m).fold(0.0, f64::max);
    let shed = |r: &ServoReport| r.clear_shed.map_or((0.0, f64::NAN), |c| (c.window_deg, c.min_clearance_mm));
    let ((wb, cb), (wa, ca)) = (shed(&before), shed(&report));
    Ok(ServoOptimum {
        objective,
        peak_bus_power_w_before: before.peak_bus_power_w,
        peak_bus_power_w_after: report.peak_bus_power_w,
        worst_rms_torque_n_m_before: worst(&before),
        worst_rms_torque_n_m_after: worst(&report),
        window_deg_before: wb,
        window_deg_after: wa,
        min_clearance_mm_before: cb,
        min_clearance_mm_after: ca,
        min_clearance_kept_mm: kept_mm,
        stagger_deg: x[..n].to_vec(),
        motion_deg: x[n..].to_vec(),
        fall_motion_deg: angles
            .iter()
            .any(|a| a.1 != a.0)
            .then(|| setups.iter().map(|s| s.plan.motion_deg[1]).collect()),
        frames_searched: moving.len(),
        picks_searched: s.reduced.picks.len(),
        evaluations: s.evaluations,
        clearance_checks: s.clearance_checks,
        report,
        setups,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_search_on_the_reduced_pattern_finds_the_whole_repeats_optimum() {
        // A 2/2 twill on 4 of the 24 frames, 60 picks: 4 classes of turns, 36 rows of short
        // pattern. Both searches take the same steps: the same optimum, bit for bit after the
        // exact study, with and without pass-through, for both objectives.
        let text = include_str!("../../../examples/servo-shedding-loom.toml");
        let rows: Vec<Vec<bool>> = (0..60).map(|p| (0..4).map(|i| (p + i) % 4 < 2).collect()).collect();
        let pattern = Pattern::new(4, rows).unwrap();
        for pass in [false, true] {
            let loom =
                Loom::from_toml(&text.replace("pass_through = false", &format!("pass_through = {pass}"))).unwrap();
            let reduced = reduced_pattern(&loom, &pattern).unwrap();
            assert!(!reduced.whole && reduced.picks.len() == 4 && reduced.pattern.picks() < 60, "{reduced:?}");
            for objective in [Objective::Peak, Objective::Rms] {
                let options = ServoOptions::new(objective);
                let stop = StopFlag::default();
                let a = optimise(&loom, &pattern, &options, true, &stop, &|_, _| {}).unwrap();
                let b = optimise(&loom, &pattern, &options, false, &stop, &|_, _| {}).unwrap();
                assert_eq!((a.frames_searched, b.frames_searched), (4, 4));
                assert_eq!((&a.stagger_deg, &a.motion_deg), (&b.stagger_deg, &b.motion_deg), "{pass} {objective:?}");
                assert_eq!(a.peak_bus_power_w_after, b.peak_bus_power_w_after);
                assert_eq!(a.min_clearance_mm_after, b.min_clearance_mm_after);
                assert_eq!(a.evaluations, b.evaluations);
                assert!(a.peak_bus_power_w_after <= a.peak_bus_power_w_before);
                // The frames that never move keep the loom file's timing.
                assert!(a.stagger_deg[4..].iter().all(|&s| s == 0.0) && a.motion_deg[4..].iter().all(|&m| m == 280.0));
            }
        }
    }

    #[test]
    fn the_searchs_remembered_plans_give_what_planning_afresh_gives() {
        // A walk like the compass search's (one frame's stagger or motion angle at a time, back
        // and forth) with a jump of every variable now and then: the objective, both ways, and the
        // clearance from the remembered plans equal those of every frame planned afresh, bit for
        // bit; on a linear drive with pass-through and on the crank and lever.
        let linear = include_str!("../../../examples/servo-shedding-loom.toml")
            .replace("pass_through = false", "pass_through = true");
        let crank = include_str!("../../../examples/servo-shedding-crank-loom.toml").to_string();
        // A 2/2 twill on four frames, a 5/7 and a 1/5 on two more, 240 picks.
        let lift = |p: usize, i: usize| match i {
            0..4 => (p + i) % 4 < 2,
            4 => p % 12 < 5,
            _ => p % 6 < 1,
        };
        let rows: Vec<Vec<bool>> = (0..240).map(|p| (0..6).map(|i| lift(p, i)).collect()).collect();
        let pattern = Pattern::new(6, rows).unwrap();
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut unit = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for text in [linear, crank] {
            let loom = Loom::from_toml(&text).unwrap();
            let (n, speed) = (loom.frame_count(), loom.speed.rpm());
            let bus = &loom.shedding.servo.as_ref().unwrap().bus;
            let reduced = reduced_pattern(&loom, &pattern).unwrap();
            assert!(!reduced.whole, "{reduced:?}");
            let (stop, progress) = (StopFlag::default(), |_: usize, _: usize| {});
            for objective in [Objective::Peak, Objective::Rms] {
                let mut s = ServoSearch {
                    loom: &loom,
                    pattern: &pattern,
                    objective,
                    frames: n,
                    delta: crate::crossing_offset_deg(loom.shedding.crossing_deg),
                    need_m: 0.0,
                    plans: SearchFrames::new(SetupMaker::new(&loom, &reduced.pattern).unwrap()),
                    reduced: reduced.clone(),
                    evaluations: 0,
                    clearance_checks: 0,
                    memo: Default::default(),
                    stop: &stop,
                    progress: &progress,
                    stages: (0, 0),
                };
                let mut x: Vec<f64> = (0..n).map(|_| 0.0).chain((0..n).map(|_| 280.0)).collect();
                for step in 0..40 {
                    if step % 13 == 12 {
                        for j in 0..n {
                            x[j] = (unit() - 0.5) * 20.0;
                            x[n + j] = 240.0 + 60.0 * unit();
                        }
                    } else {
                        let j = (unit() * 2.0 * n as f64) as usize;
                        x[j] += if unit() < 0.5 { -4.0 } else { 4.0 };
                    }
                    let (centre, motion) = s.centres_and_angles(&x);
                    let fresh = servo_setups(&loom, &reduced.pattern, Some(&motion), Some(&centre)).unwrap();
                    let want = match objective {
                        Objective::Peak => loomkin_eshed::peak_bus_power_w_at(&fresh, bus, speed, &reduced.picks),
                        Objective::Rms => loomkin_eshed::worst_rms_torque_n_m_at(
                            &fresh,
                            speed,
                            &reduced.picks,
                            &reduced.counts,
                            pattern.picks(),
                        ),
                    }
                    .unwrap();
                    assert_eq!(s.objective(&x).unwrap().to_bits(), want.to_bits(), "{objective:?} step {step}");
                    let paths = ServoMotion::new(&fresh);
                    let timing = Timing::new(&loom, &paths, &reduced.pattern).unwrap();
                    let want = timing.min_clearance_coarse_at(SEARCH_STEP_DEG, &reduced.picks);
                    assert_eq!(s.clearance(&x).unwrap().to_bits(), want.to_bits(), "clearance, step {step}");
                }
            }
        }
    }
}
