//! Electronic shedding on a loom: every frame's servo plan from the pattern, the frames as the
//! servos' loads, the study on the shared bus (loomkin-eshed does the work).

use crate::stagger::{SEARCH_STEP_DEG, STEPS};

/// The servo optimiser's compass steps, deg: 16° and 8° before `loom stagger`'s, as a motion angle
/// may move across most of its range (a search from 280° to 360° in 4° steps takes twenty sweeps).
const SERVO_STEPS: [f64; 7] = [16.0, 8.0, STEPS[0], STEPS[1], STEPS[2], STEPS[3], STEPS[4]];
use crate::{Loom, LoomError, Motion, Objective, Pattern, Result, ShedMotion, Timing, TimingReport};
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
    /// The frames of `setups` (front first) moving by `laws`.
    pub fn new(setups: &[FrameSetup], laws: &MoveLaws) -> Self {
        let picks = setups.first().map_or(0, |s| (s.plan.period_deg / 360.0).round() as usize);
        Self { paths: setups.iter().map(|s| FramePath::new(&s.plan, laws)).collect(), picks }
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
    let motion = ServoMotion::new(setups, &servo_laws(loom));
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

/// The laws of the frames' moves: the shedding law's rise and fall.
pub fn servo_laws(loom: &Loom) -> MoveLaws {
    let law = &loom.shedding.law;
    MoveLaws {
        rise: (law.spec(true).clone(), law.law(true).clone()),
        fall: (law.spec(false).clone(), law.law(false).clone()),
    }
}

/// Every frame's plan, load and servo (front first) for `loom` weaving `pattern`, the loom's
/// `[shedding.servo]` giving the drives; `motion_deg` overrides every frame's motion angle and
/// `centre_deg` every frame's move centre (crossing offset plus stagger) when given (the optimiser's
/// variables). Fails when the loom's shedding drive is the dobby.
pub fn servo_setups(
    loom: &Loom,
    pattern: &Pattern,
    motion_deg: Option<&[f64]>,
    centre_deg: Option<&[f64]>,
) -> Result<Vec<FrameSetup>> {
    let servo = loom.shedding.servo.as_ref().ok_or_else(|| {
        LoomError::field(
            "shedding.drive",
            "the loom's shedding drive is the dobby: give drive = \"servo\" and [shedding.servo]",
        )
    })?;
    let motion = Motion::new(loom, pattern)?;
    let picks = motion.picks();
    (0..loom.frame_count())
        .map(|i| {
            let up: Vec<bool> = (0..picks).map(|p| motion.is_up(i, p as i64)).collect();
            let s = &servo.frames[i];
            let phi = match (motion_deg, s.motion_deg) {
                (Some(m), _) => m[i],
                (None, Some(m)) => m,
                (None, None) => motion.motion_deg(),
            };
            let phi =
                loomkin_shed::MOTION_DEG.check(&format!("shedding.servo.frame: frame {} motion_deg", i + 1), phi)?;
            let input = FrameInput {
                up: &up,
                stroke_m: motion.stroke_m(i),
                centre_deg: centre_deg.map_or(motion.centre0_deg(i), |c| c[i]),
                motion_deg: phi,
            };
            let plan = FramePlan::new(&input, servo.pass_through)?;
            let f = &loom.frames[i];
            let load = FrameLoad {
                mass_kg: f.mass_kg,
                spring_n_m: f.spring_n_m,
                preload_n: f.preload_n,
                stroke_m: motion.stroke_m(i),
                start_level_m: plan.start_level_m(),
            };
            Ok(FrameSetup { plan, load, servo: s.clone() })
        })
        .collect()
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
    let mut r = loomkin_eshed::analyse(setups, &servo_laws(loom), &servo.bus, loom.speed.rpm(), servo.pass_through)?;
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
    Ok(loomkin_eshed::frame_tables(setups, &servo_laws(loom), spacing, formats, loom.speed.rpm())?)
}

/// Curves of the servo-shedding study: `points` samples over the repeat.
pub fn servo_curves(loom: &Loom, pattern: &Pattern, points: usize) -> Result<loomkin_eshed::Curves> {
    servo_curves_of(loom, &servo_setups(loom, pattern, None, None)?, points)
}

/// [`servo_curves`] of given plans.
pub fn servo_curves_of(loom: &Loom, setups: &[FrameSetup], points: usize) -> Result<loomkin_eshed::Curves> {
    let servo = loom.shedding.servo.as_ref().ok_or_else(|| LoomError::field("shedding.drive", "dobby"))?;
    Ok(loomkin_eshed::curves(setups, &servo_laws(loom), &servo.bus, loom.speed.rpm(), points)?)
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
    /// The least clearance the search kept (on its grid), mm: 0, or the design's own when it is
    /// below 0 (the search never makes it worse).
    pub min_clearance_kept_mm: f64,
    /// Every frame's stagger of the optimum (its move centre less the crossing), front first, deg.
    pub stagger_deg: Vec<f64>,
    /// Every frame's motion angle of the optimum, front first, deg.
    pub motion_deg: Vec<f64>,
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
    evaluations: usize,
    clearance_checks: usize,
    stop: &'a StopFlag,
    progress: &'a dyn Fn(usize, usize),
    stages: (usize, usize),
}

impl ServoSearch<'_> {
    /// The plans of `x` = every frame's stagger, then every frame's motion angle.
    fn setups(&self, x: &[f64]) -> Result<Vec<FrameSetup>> {
        let (stagger, motion) = x.split_at(self.frames);
        let centre: Vec<f64> = stagger.iter().map(|s| self.delta + s).collect();
        servo_setups(self.loom, self.pattern, Some(motion), Some(&centre))
    }

    fn objective(&mut self, x: &[f64]) -> Result<f64> {
        self.stop.check()?;
        self.evaluations += 1;
        let setups = self.setups(x)?;
        let laws = servo_laws(self.loom);
        let servo = self.loom.shedding.servo.as_ref().ok_or_else(|| LoomError::field("shedding.drive", "dobby"))?;
        let speed = self.loom.speed.rpm();
        Ok(match self.objective {
            Objective::Peak => loomkin_eshed::peak_bus_power_w(&setups, &laws, &servo.bus, speed, true)?,
            Objective::Rms => loomkin_eshed::worst_rms_torque_n_m(&setups, &laws, speed)?,
        })
    }

    /// The least clearance over the insertion of every pick on the stagger search's grid, m.
    fn clearance(&mut self, x: &[f64]) -> Result<f64> {
        self.stop.check()?;
        self.clearance_checks += 1;
        let setups = self.setups(x)?;
        let motion = ServoMotion::new(&setups, &servo_laws(self.loom));
        Ok(Timing::new(self.loom, &motion, self.pattern)?.min_clearance_coarse(SEARCH_STEP_DEG))
    }
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
    let before = servo_study(loom, pattern)?;
    let servo = loom.shedding.servo.as_ref().ok_or_else(|| LoomError::field("shedding.drive", "dobby"))?;
    let motion = Motion::new(loom, pattern)?;
    let n = loom.frame_count();
    let delta = crate::crossing_offset_deg(loom.shedding.crossing_deg);
    let mut x0: Vec<f64> = (0..n).map(|i| motion.centre0_deg(i) - delta).collect();
    x0.extend(servo.frames.iter().map(|f| f.motion_deg.unwrap_or(motion.motion_deg())));
    let m = loom.shedding.max_stagger_deg;
    let bound = |b: loomkin_units::Bound, default: f64| match b {
        loomkin_units::Bound::Closed(v) | loomkin_units::Bound::Open(v) => v,
        loomkin_units::Bound::Unbounded => default,
    };
    let (phi_lo, phi_hi) = (bound(loomkin_shed::MOTION_DEG.lo, 1.0), bound(loomkin_shed::MOTION_DEG.hi, 360.0));
    let lo: Vec<f64> = (0..2 * n).map(|j| if j < n { -m } else { phi_lo }).collect();
    let hi: Vec<f64> = (0..2 * n).map(|j| if j < n { m } else { phi_hi }).collect();
    let mut s = ServoSearch {
        loom,
        pattern,
        objective,
        frames: n,
        delta,
        need_m: 0.0,
        evaluations: 0,
        clearance_checks: 0,
        stop,
        progress,
        stages: (0, SERVO_STEPS.len()),
    };
    s.need_m = s.clearance(&x0)?.min(0.0);
    let f0 = s.objective(&x0)?;
    let (x, _) = loomkin_numeric::compass_min(
        &mut s,
        x0,
        f0,
        &SERVO_STEPS,
        &lo,
        &hi,
        |s, y| s.objective(y),
        |s, y| Ok(s.clearance(y)? >= s.need_m),
        |s| {
            (s.progress)(s.stages.0, s.stages.1);
            s.stages.0 += 1;
        },
    )?;
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
        min_clearance_kept_mm: s.need_m * 1e3,
        stagger_deg: x[..n].to_vec(),
        motion_deg: x[n..].to_vec(),
        evaluations: s.evaluations,
        clearance_checks: s.clearance_checks,
        report,
        setups,
    })
}
