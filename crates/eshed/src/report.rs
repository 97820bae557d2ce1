//! The servo-shedding study of a loom weaving a pattern: per frame and on the bus.

use crate::bus::{DriveMemo, Timeline, bus};
use crate::continuity::{JointClass, joint_class};
use crate::drive::{FrameDrive, FrameLoad, axis};
use crate::{Bus, EshedError, FramePlan, FrameServo, MoveLaws, Result};
use loomkin_servo::{Check, CheckMemo, check_axis, check_axis_memo};
use serde::Serialize;

/// One frame: its plan and the laws of its moves, the frame as a load, its servo.
#[derive(Debug, Clone)]
pub struct FrameSetup {
    /// The moves over the repeat.
    pub plan: FramePlan,
    /// The laws the moves follow.
    pub laws: MoveLaws,
    /// The frame as a load.
    pub load: FrameLoad,
    /// The servo drive.
    pub servo: FrameServo,
}

/// One frame's drive over the repeat (`frames` of `loomkin loom servo --json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrameReport {
    /// The frame (1 = front).
    pub frame: usize,
    /// Moves over the repeat.
    pub moves: usize,
    /// Its motion angle, deg (before pass-through lengthens moves; the rise's when the fall's differs).
    pub motion_deg: f64,
    /// The motion angle of its moves down, deg, where it differs from the rise's (absent otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fall_motion_deg: Option<f64>,
    /// The law of its moves up, as the loom file names it ([`MoveLaws::labels`]): a catalogue law
    /// with its parameters (`cycloidal`, `modified-trapezoid (ramp=0.125)`), a shedding preset
    /// (`dobby preset`), a spline law (`spline (5 points, clamped)`); the shedding law's where
    /// `[shedding.servo]` gives none.
    pub rise_law: String,
    /// The law of its moves down, named alike.
    pub fall_law: String,
    /// The law of the moves laid end to end by pass-through, named alike, where one is given
    /// (absent otherwise: those moves follow the rise and fall laws).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub through_law: Option<String>,
    /// Largest |motor torque|, N·m (located exactly by the servo check).
    pub peak_torque_n_m: f64,
    /// Where, deg of the repeat.
    pub peak_torque_at_deg: f64,
    /// RMS motor torque over the repeat, N·m.
    pub rms_torque_n_m: f64,
    /// Largest |motor speed|, rpm.
    pub peak_speed_rpm: f64,
    /// Largest |electrical power| (drawn or returned), W.
    pub peak_power_w: f64,
    /// Where, deg of the repeat (within `[0, repeat)`).
    pub peak_power_at_deg: f64,
    /// Electrical energy drawn over the repeat (losses, as the motion is periodic), J.
    pub energy_j: f64,
    /// Load inertia reflected to the motor over the rotor's.
    pub inertia_ratio: f64,
    /// Every check of `loomkin servo check` passes.
    pub motor_ok: bool,
    /// The checks (peak torque, RMS torque, peak speed, torque–speed envelope, inertia ratio) with
    /// their margins `(limit − value)/limit`.
    pub checks: Vec<Check>,
    /// Highest derivative continuous at every rest transition (2: C², acceleration continuous).
    pub rest_continuity: i32,
    /// Where the least smooth rest transition is, deg (absent without joints).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rest_continuity_at_deg: Option<f64>,
}

/// The study (`loomkin loom servo --json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ServoReport {
    /// Main-shaft speed, rpm.
    pub speed_rpm: f64,
    /// Picks in the repeat.
    pub picks: usize,
    /// The repeat, deg.
    pub repeat_deg: f64,
    /// Its duration, s.
    pub repeat_s: f64,
    /// Consecutive changes laid end to end without a stop.
    pub pass_through: bool,
    /// Largest power the bus draws from the supply, W.
    pub peak_bus_power_w: f64,
    /// Where, deg of the repeat.
    pub peak_bus_power_at_deg: f64,
    /// `peak_bus_power_w` over the bus voltage, A.
    pub peak_bus_current_a: f64,
    /// Mean power drawn from the supply over the repeat, W.
    pub mean_bus_power_w: f64,
    /// Energy braking frames return to the bus per repeat (after the regeneration efficiency), J.
    pub regenerated_energy_j: f64,
    /// What the braking resistor must take per repeat: the returned energy no other frame uses at
    /// the same instant, J.
    pub braking_energy_j: f64,
    /// Largest power into the braking resistor, W.
    pub peak_braking_power_w: f64,
    /// What the braking resistor can take at the bus voltage, `V²/R`, W (absent without a resistor).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub braking_resistor_max_w: Option<f64>,
    /// `peak_braking_power_w ≤ braking_resistor_max_w` (absent without a resistor).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub braking_resistor_ok: Option<bool>,
    /// Energy the supply gives per repeat, J.
    pub supplied_energy_j: f64,
    /// Every frame's motor passes.
    pub motors_ok: bool,
    /// Distinct pick windows evaluated (the others reuse one of them).
    pub distinct_windows: usize,
    /// The shed the weft carrier passes, over the frames' plans (absent where the caller has no
    /// carrier: [`analyse`] leaves it out, the loom's study fills it in).
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub clear_shed: Option<ClearShed>,
    /// The frames, in shaft order (front first).
    pub frames: Vec<FrameReport>,
}

/// The shed the weft carrier passes while the frames move by their plans: the keys of `loomkin
/// loom check`, worked out the same way (the loom's timing) over the servo frames' plans.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ClearShed {
    /// Least clearance to the carrier from entry to exit over every pick, mm (negative: it touches).
    pub min_clearance_mm: f64,
    /// The window common to every pick in which the shed clears the carrier, deg.
    pub window_deg: f64,
    /// Its start in the turn, deg.
    pub window_open_deg: f64,
    /// Its end in the turn, deg.
    pub window_close_deg: f64,
    /// The highest loom speed at which the carrier passes in the window, rpm.
    pub max_speed_rpm: f64,
}

/// The frames' drives and cycles, built once.
pub struct Study {
    /// Per frame: the cycle of the law core.
    pub cycles: Vec<loomkin_laws::Cycle>,
    /// Per frame: the drive.
    pub drives: Vec<FrameDrive>,
    /// Per frame: the plan's segments in degrees, each with whether it is a move laid end to end
    /// ([`FramePlan::parts`]).
    pub segments: Vec<Vec<(loomkin_laws::SegmentKind, f64, f64, bool)>>,
}

impl Study {
    /// The drives of `frames` moving by their laws at `speed_rpm`.
    pub fn new(frames: &[FrameSetup], speed_rpm: f64) -> Result<Self> {
        let omega = loomkin_units::ShaftSpeed::from_rpm(speed_rpm)?.rad_per_s();
        let mut cycles = Vec::with_capacity(frames.len());
        let mut drives = Vec::with_capacity(frames.len());
        let mut segments = Vec::with_capacity(frames.len());
        check_strokes(frames)?;
        for f in frames {
            cycles.push(f.plan.cycle(&f.laws));
            segments.push(f.plan.parts());
            drives.push(FrameDrive::new(
                axis(&f.servo.motor, &f.servo.transmission, &f.load),
                f.load,
                f.servo.winding.loss_w_per_n_m2(),
                omega,
            ));
        }
        Ok(Self { cycles, drives, segments })
    }

    /// The bus over the repeat (`scan_only`: see [`peak_bus_power_w`]).
    fn bus(&self, bus_spec: &Bus, scan_only: bool) -> crate::BusTotals {
        self.bus_at(bus_spec, None, scan_only, None)
    }

    /// The bus over the turns of the picks `only` (increasing), or of every pick; the drives'
    /// points remembered in `memo` when given.
    fn bus_at(
        &self,
        bus_spec: &Bus,
        only: Option<&[usize]>,
        scan_only: bool,
        memo: Option<&mut DriveMemo>,
    ) -> crate::BusTotals {
        let mut types = crate::bus::WordMap::default();
        let (memos, kept) = match memo {
            Some(m) => {
                let (memos, kept) = m.frames_for(&self.drives);
                (memos, Some(kept))
            }
            None => (vec![None; self.drives.len()], None),
        };
        let lines: Vec<Timeline<'_>> = (0..self.cycles.len())
            .map(|i| Timeline::new(&self.cycles[i], &self.segments[i], &self.drives[i], &mut types, memos[i]))
            .collect();
        let picks = (self.cycles[0].period_rad.to_degrees() / 360.0).round() as usize;
        bus(&lines, picks, only, bus_spec.regeneration_efficiency, self.drives[0].omega, scan_only, kept)
    }
}

/// A crank and lever must make each frame's stroke without a dead centre (checked once per distinct
/// transmission and stroke), the error naming the frame.
pub(crate) fn check_strokes(frames: &[FrameSetup]) -> Result<()> {
    let mut checked: Vec<(loomkin_servo::CrankLever, u64, u64)> = Vec::new();
    for (i, f) in frames.iter().enumerate() {
        let Some(cl) = f.servo.transmission.crank_lever else { continue };
        let key = (cl, f.load.stroke_m.to_bits(), f.load.start_level_m.to_bits());
        if checked.contains(&key) {
            continue;
        }
        check_stroke(i, f)?;
        checked.push(key);
    }
    Ok(())
}

/// Frame `i`'s crank and lever, if it has one, makes its stroke without a dead centre; the error
/// names the frame.
fn check_stroke(i: usize, f: &FrameSetup) -> Result<()> {
    let Some(cl) = f.servo.transmission.crank_lever else { return Ok(()) };
    let lo = -f.load.stroke_m / 2.0 - f.load.start_level_m;
    let cl = loomkin_servo::CrankLever { mid_stroke_mm: -f.load.start_level_m * 1e3, ..cl };
    cl.check_stroke(lo, lo + f.load.stroke_m, "shedding.servo.transmission").map_err(|e| {
        let field = loomkin_units::FieldError::field(&e).unwrap_or("shedding.servo.transmission");
        let text = e.to_string();
        let reason = text.strip_prefix(&format!("{field}: ")).unwrap_or(&text).to_string();
        EshedError::field(field, format!("frame {}: {reason}", i + 1))
    })
}

/// The study of `frames` (front first) moving by their laws at `speed_rpm` on `bus` (`pass_through`:
/// how the plans were made, for the report). Fails when a rest transition of some frame is less
/// smooth than C² (a law's acceleration must start and end at zero where the frame rests, and two
/// moves laid end to end must meet with equal accelerations), naming the law's field
/// ([`MoveLaws::fields`]).
pub fn analyse(frames: &[FrameSetup], bus_spec: &Bus, speed_rpm: f64, pass_through: bool) -> Result<ServoReport> {
    let first = frames.first().ok_or_else(|| EshedError::field("frames", "no frames"))?;
    let picks = (first.plan.period_deg / 360.0).round() as usize;
    let study = Study::new(frames, speed_rpm)?;
    let omega = study.drives[0].omega;
    let tot = study.bus(bus_spec, false);
    let repeat_deg = first.plan.period_deg;
    let repeat_s = repeat_deg.to_radians() / omega;
    let mut reports = Vec::with_capacity(frames.len());
    for (i, f) in frames.iter().enumerate() {
        let check = check_axis(&study.drives[i].axis, &study.cycles[i], speed_rpm)?;
        let class = joint_class(&study.cycles[i], &f.laws, omega);
        if class.rest < 2 {
            return Err(rest_refusal(i, f, &study.cycles[i], &class, omega));
        }
        reports.push(FrameReport {
            frame: i + 1,
            moves: f.plan.moves.len(),
            motion_deg: match f.plan.motion_deg {
                [r, fall] if r != fall => r,
                _ => f.plan.moves.first().map_or(0.0, |m| m.length_deg),
            },
            fall_motion_deg: Some(f.plan.motion_deg[1]).filter(|&fall| fall != f.plan.motion_deg[0]),
            rise_law: f.laws.labels[0].clone(),
            fall_law: f.laws.labels[1].clone(),
            through_law: f.laws.through.as_ref().map(|_| f.laws.labels[2].clone()),
            peak_torque_n_m: check.peak_torque_nm,
            peak_torque_at_deg: check.peak_torque_at_deg.rem_euclid(repeat_deg),
            rms_torque_n_m: check.rms_torque_nm,
            peak_speed_rpm: check.peak_motor_speed_rpm,
            peak_power_w: tot.frame_peak_w[i].0,
            peak_power_at_deg: tot.frame_peak_w[i].1,
            energy_j: tot.frame_energy_j[i],
            inertia_ratio: check.inertia_ratio,
            motor_ok: check.pass,
            checks: check.checks,
            rest_continuity: class.rest,
            rest_continuity_at_deg: class.rest_at_deg.map(|a| a.rem_euclid(repeat_deg)),
        });
    }
    let peak_braking_power_w = (-tot.trough_w.0).max(0.0);
    let resistor = bus_spec.braking_resistor_ohm.map(|r| bus_spec.voltage_v * bus_spec.voltage_v / r);
    Ok(ServoReport {
        speed_rpm,
        picks,
        repeat_deg,
        repeat_s,
        pass_through,
        peak_bus_power_w: tot.peak_w.0,
        peak_bus_power_at_deg: tot.peak_w.1,
        peak_bus_current_a: tot.peak_w.0.max(0.0) / bus_spec.voltage_v,
        mean_bus_power_w: tot.supplied_j / repeat_s,
        regenerated_energy_j: tot.regenerated_j,
        braking_energy_j: tot.braking_j,
        peak_braking_power_w,
        braking_resistor_max_w: resistor,
        braking_resistor_ok: resistor.map(|m| peak_braking_power_w <= m),
        supplied_energy_j: tot.supplied_j,
        motors_ok: reports.iter().all(|r| r.motor_ok),
        distinct_windows: tot.distinct_windows,
        clear_shed: None,
        frames: reports,
    })
}

/// The peak bus power of `frames` moving by their laws at `speed_rpm` on `bus_spec`, W: [`analyse`]'s
/// `peak_bus_power_w` (the same bus, bit for bit) without the frames' checks; with `scan_only`,
/// the largest of the bus's scan (16 points between every two joints of every frame, no root
/// finding, no energies: a lower bound, a few times cheaper, what the optimiser's search compares).
pub fn peak_bus_power_w(frames: &[FrameSetup], bus_spec: &Bus, speed_rpm: f64, scan_only: bool) -> Result<f64> {
    if frames.is_empty() {
        return Err(EshedError::field("frames", "no frames"));
    }
    Ok(Study::new(frames, speed_rpm)?.bus(bus_spec, scan_only).peak_w.0)
}

/// The largest bus power of the scan ([`peak_bus_power_w`] with `scan_only`) over the turns of the
/// picks `picks` alone (increasing, each in `0..picks of the repeat`), W: what a search compares
/// when one pick stands for every pick whose turn is the same.
pub fn peak_bus_power_w_at(frames: &[FrameSetup], bus_spec: &Bus, speed_rpm: f64, picks: &[usize]) -> Result<f64> {
    scanned_peak(frames, bus_spec, speed_rpm, Some(picks), None)
}

/// The largest bus power of the scan over every pick (`picks` = `None`: [`peak_bus_power_w`] with
/// `scan_only`) or over the turns of `picks` ([`peak_bus_power_w_at`]), the same value bit for
/// bit, the drives' points remembered in `memo` from one call to the next: a search evaluating
/// the same frames again and again ([`DriveMemo`]).
pub fn peak_bus_power_w_memo(
    frames: &[FrameSetup],
    bus_spec: &Bus,
    speed_rpm: f64,
    picks: Option<&[usize]>,
    memo: &mut DriveMemo,
) -> Result<f64> {
    scanned_peak(frames, bus_spec, speed_rpm, picks, Some(memo))
}

fn scanned_peak(
    frames: &[FrameSetup],
    bus_spec: &Bus,
    speed_rpm: f64,
    picks: Option<&[usize]>,
    memo: Option<&mut DriveMemo>,
) -> Result<f64> {
    let first = frames.first().ok_or_else(|| EshedError::field("frames", "no frames"))?;
    let repeat = (first.plan.period_deg / 360.0).round() as usize;
    if let Some(picks) = picks
        && (picks.windows(2).any(|w| w[1] <= w[0]) || picks.last().is_some_and(|&p| p >= repeat))
    {
        return Err(EshedError::field("picks", format!("picks must increase within the repeat of {repeat}")));
    }
    let study = Study::new(frames, speed_rpm)?;
    let mut memo = memo;
    if let Some(m) = memo.as_deref_mut() {
        let laws = frames.iter().map(|f| f.laws.law_values()).collect();
        m.windows_for(laws, bus_spec.regeneration_efficiency, study.drives[0].omega, true);
    }
    Ok(study.bus_at(bus_spec, picks, true, memo).peak_w.0)
}

/// The largest of the frames' RMS motor torques, N·m: [`analyse`]'s largest `rms_torque_n_m` (the
/// servo check of each frame, bit for bit) without the bus (what the optimiser minimises).
pub fn worst_rms_torque_n_m(frames: &[FrameSetup], speed_rpm: f64) -> Result<f64> {
    loomkin_units::ShaftSpeed::from_rpm(speed_rpm)?;
    check_strokes(frames)?;
    let memo = &mut CheckMemo::default();
    frames.iter().enumerate().try_fold(0.0f64, |worst, (i, f)| Ok(worst.max(rms_torque_n_m(i, f, speed_rpm, memo)?)))
}

/// Frame `frame`'s RMS motor torque, N·m: [`worst_rms_torque_n_m`]'s term for the frame, `i` (front
/// first, from 0) naming it in errors, the check's values of its moves remembered in `memo` (the
/// frame's own: a search that changes one frame at a time keeps one per frame).
pub fn rms_torque_n_m(i: usize, frame: &FrameSetup, speed_rpm: f64, memo: &mut CheckMemo) -> Result<f64> {
    let (drive, cycle, _) = frame_drive(i, frame, speed_rpm)?;
    Ok(check_axis_memo(&drive, &cycle, speed_rpm, memo)?.rms_torque_nm)
}

/// Frame `i`'s axis and cycle (as [`Study::new`] makes them), its stroke checked, and the main
/// shaft's speed `speed_rpm` in rad/s.
fn frame_drive(i: usize, f: &FrameSetup, speed_rpm: f64) -> Result<(loomkin_servo::Axis, loomkin_laws::Cycle, f64)> {
    let omega = loomkin_units::ShaftSpeed::from_rpm(speed_rpm)?.rad_per_s();
    check_stroke(i, f)?;
    Ok((axis(&f.servo.motor, &f.servo.transmission, &f.load), f.plan.cycle(&f.laws), omega))
}

/// The largest of the frames' RMS motor torques over a repeat of `repeat_picks` picks, N·m, from
/// the turns of the picks `picks` (increasing) of `frames`' plans alone, pick `picks[k]` standing
/// for `counts[k]` picks of the repeat: each frame's `∫T² dt` per segment (the servo check's own
/// terms, [`loomkin_servo::torque_squared_by_segment`]) cut into per-pick cells
/// ([`FramePlan::cell_sums`]), weighted by the counts, over the repeat's duration. When every pick
/// of the repeat is one of a class whose picks do the same in their cells (the servo optimiser's
/// short pattern), this is [`worst_rms_torque_n_m`] of the whole repeat to rounding.
pub fn worst_rms_torque_n_m_at(
    frames: &[FrameSetup],
    speed_rpm: f64,
    picks: &[usize],
    counts: &[usize],
    repeat_picks: usize,
) -> Result<f64> {
    frames.first().ok_or_else(|| EshedError::field("frames", "no frames"))?;
    loomkin_units::ShaftSpeed::from_rpm(speed_rpm)?;
    check_strokes(frames)?;
    let memo = &mut CheckMemo::default();
    frames.iter().enumerate().try_fold(0.0f64, |worst, (i, f)| {
        Ok(worst.max(rms_torque_n_m_at(i, f, speed_rpm, picks, counts, repeat_picks, memo)?))
    })
}

/// Frame `frame`'s RMS motor torque over a repeat of `repeat_picks` picks, N·m, from the turns of
/// the picks `picks` alone: [`worst_rms_torque_n_m_at`]'s term for the frame, `i` (front first,
/// from 0) naming it in errors, the terms of its moves remembered in `memo` (as
/// [`rms_torque_n_m`]'s).
pub fn rms_torque_n_m_at(
    i: usize,
    frame: &FrameSetup,
    speed_rpm: f64,
    picks: &[usize],
    counts: &[usize],
    repeat_picks: usize,
    memo: &mut CheckMemo,
) -> Result<f64> {
    let short = (frame.plan.period_deg / 360.0).round() as usize;
    if picks.windows(2).any(|w| w[1] <= w[0]) || picks.last().is_some_and(|&p| p >= short) {
        return Err(EshedError::field("picks", format!("picks must increase within the repeat of {short}")));
    }
    if counts.len() != picks.len() || counts.iter().sum::<usize>() != repeat_picks {
        return Err(EshedError::field(
            "counts",
            format!("one count for each pick, adding up to the repeat's {repeat_picks} picks"),
        ));
    }
    let (drive, cycle, omega) = frame_drive(i, frame, speed_rpm)?;
    let repeat_s = (360.0 * repeat_picks as f64).to_radians() / omega;
    let t2 = loomkin_servo::torque_squared_by_segment_memo(&drive, &cycle, speed_rpm, memo)?;
    let cells = frame.plan.cell_sums(&t2, picks);
    let total: f64 = cells.iter().zip(counts).map(|(v, &n)| v * n as f64).sum();
    Ok((total / repeat_s).sqrt())
}

/// Curves of the study at evenly spaced angles over the repeat (for plots and arrays).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Curves {
    /// Main-shaft angle, deg, from 0 to the repeat (both ends).
    pub angle_deg: Vec<f64>,
    /// Per frame (front first): the frame's height over mid-stroke, m.
    pub position_m: Vec<Vec<f64>>,
    /// Per frame: motor speed, rpm.
    pub speed_rpm: Vec<Vec<f64>>,
    /// Per frame: motor torque, N·m.
    pub torque_n_m: Vec<Vec<f64>>,
    /// Per frame: electrical power, W.
    pub power_w: Vec<Vec<f64>>,
    /// The bus power (braking drives' power times the regeneration efficiency), W.
    pub bus_power_w: Vec<f64>,
}

/// `points` (≥ 2) samples of every frame and the bus over the repeat, from 0° to its end.
pub fn curves(frames: &[FrameSetup], bus_spec: &Bus, speed_rpm: f64, points: usize) -> Result<Curves> {
    let first = frames.first().ok_or_else(|| EshedError::field("frames", "no frames"))?;
    let study = Study::new(frames, speed_rpm)?;
    let period = first.plan.period_deg;
    let n = points.max(2);
    let angle_deg: Vec<f64> = (0..n).map(|k| period * k as f64 / (n - 1) as f64).collect();
    let mut out = Curves {
        angle_deg: angle_deg.clone(),
        position_m: Vec::new(),
        speed_rpm: Vec::new(),
        torque_n_m: Vec::new(),
        power_w: Vec::new(),
        bus_power_w: vec![0.0; n],
    };
    let eta_r = bus_spec.regeneration_efficiency;
    for (i, f) in frames.iter().enumerate() {
        let cycle = &study.cycles[i];
        let segs = &study.segments[i];
        let d = &study.drives[i];
        let (mut y, mut sp, mut tq, mut pw) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        // Angles from the cycle's start, in order: a cursor over the segments.
        let start = f.plan.start_deg;
        let mut order: Vec<(f64, usize)> =
            angle_deg.iter().enumerate().map(|(k, &a)| ((a - start).rem_euclid(period), k)).collect();
        order.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut j = 0;
        for (rel, k) in order {
            let th = start + rel;
            while j + 1 < segs.len() && th >= segs[j + 1].1 {
                j += 1;
            }
            let (seg, (_, s0, len, _)) = (&cycle.segments[j], segs[j]);
            let kin = crate::continuity::kin(seg, ((th - s0) / len).clamp(0.0, 1.0), d.omega);
            let p = d.point(kin[0], kin[1], kin[2], kin[3]);
            y[k] = f.plan.start_level_m() + kin[0];
            sp[k] = loomkin_units::rpm_from_rad_per_s(p.motor_rad_s);
            tq[k] = p.torque_n_m;
            pw[k] = p.power_w;
            out.bus_power_w[k] += if p.power_w >= 0.0 { p.power_w } else { eta_r * p.power_w };
        }
        out.position_m.push(y);
        out.speed_rpm.push(sp);
        out.torque_n_m.push(tq);
        out.power_w.push(pw);
    }
    Ok(out)
}

/// The refusal of a frame whose motion is less smooth than C² at a joint ([`JointClass`] of its
/// cycle): the law at fault, by its field — a move's law whose acceleration (or velocity) is not
/// zero where the frame rests, or two moves laid end to end whose accelerations differ.
fn rest_refusal(i: usize, f: &FrameSetup, cycle: &loomkin_laws::Cycle, class: &JointClass, omega: f64) -> EshedError {
    use loomkin_laws::SegmentKind;
    // Four digits; a value at rounding level is 0.
    let sig4 = |x: f64| loomkin_units::sig4(if x.abs() < 1e-12 { 0.0 } else { x });
    let segs = &cycle.segments;
    let levels = f.plan.levels();
    let n = segs.len();
    let j = class.rest_at_segment.unwrap_or(0) % n.max(1);
    let h = (j + n - 1) % n;
    let at = class.rest_at_deg.unwrap_or(0.0).rem_euclid(f.plan.period_deg);
    // A move's field, law and its normalised velocity and acceleration at `x`.
    let side = |k: usize, x: f64| {
        let l = &levels[k];
        let rising = l.kind == SegmentKind::Rise;
        let (spec, law) = f.laws.of(rising, l.through);
        let e = law.eval(x);
        (f.laws.field_of(rising, l.through).to_string(), spec.label(), e.v, e.a)
    };
    let ends = |v: f64, a: f64, end: &str| {
        if v.abs() > 1e-9 {
            format!("velocity {} and acceleration {} at its {end}", sig4(v), sig4(a))
        } else {
            format!("acceleration {} at its {end}", sig4(a))
        }
    };
    let frame = i + 1;
    match (levels[h].kind, levels[j].kind) {
        (_, SegmentKind::Dwell) => {
            let (field, label, v, a) = side(h, 1.0);
            EshedError::field(
                field,
                format!(
                    "{label} has {} where frame {frame} comes to rest ({}° of the repeat): a rest transition must be \
                     C² (acceleration zero where the frame starts or stops; velocity and acceleration per unit \
                     stroke and unit motion angle)",
                    ends(v, a, "end"),
                    sig4(at)
                ),
            )
        }
        (SegmentKind::Dwell, _) => {
            let (field, label, v, a) = side(j, 0.0);
            EshedError::field(
                field,
                format!(
                    "{label} has {} where frame {frame} starts from rest ({}° of the repeat): a rest transition \
                     must be C² (acceleration zero where the frame starts or stops; velocity and acceleration per \
                     unit stroke and unit motion angle)",
                    ends(v, a, "start"),
                    sig4(at)
                ),
            )
        }
        _ => {
            let (field_a, label_a, ..) = side(h, 1.0);
            let (field_b, label_b, ..) = side(j, 0.0);
            let ka = crate::continuity::kin(&segs[h], 1.0, omega);
            let kb = crate::continuity::kin(&segs[j], 0.0, omega);
            EshedError::field(
                field_b,
                format!(
                    "{label_b} starts with velocity {} m/s and acceleration {} m/s² where the move before it \
                     ({field_a}: {label_a}) ends with {} m/s and {} m/s² (frame {frame} at {}° of the repeat, \
                     moves laid end to end): a pass-through joint must match velocity and acceleration (C²)",
                    sig4(kb[1]),
                    sig4(kb[2]),
                    sig4(ka[1]),
                    sig4(ka[2]),
                    sig4(at)
                ),
            )
        }
    }
}
