//! The whole-loom check: geometry per frame, torque, timing — what `loomkin loom check` prints.

use crate::geometry::{equal_strain_strokes, full_shed_strain};
use crate::{Drive, Loom, Motion, Pattern, Result, Timing, TimingReport};
use serde::Serialize;

/// One frame of the check.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrameCheck {
    /// Frame number, 1 = front.
    pub frame: usize,
    /// Distance from the fell (front shed depth), mm.
    pub distance_mm: f64,
    /// Back shed depth (to the back rest), mm.
    pub back_depth_mm: f64,
    /// Full stroke, mm.
    pub stroke_mm: f64,
    /// Angle between the frame's sheets at the fell, deg.
    pub shed_angle_deg: f64,
    /// Largest warp strain over the repeat (at the frame's extreme positions the pattern uses).
    pub max_strain: f64,
    /// The stroke that would give the front frame's full-shed strain, mm (to 12 significant digits).
    pub equal_strain_stroke_mm: f64,
    /// Warp ends through the frame.
    pub ends: f64,
    /// Moves over the repeat.
    pub moves: usize,
}

/// The check of a loom weaving a pattern.
#[derive(Debug, Clone, Serialize)]
pub struct CheckReport {
    /// The loom's name.
    pub loom: String,
    /// Main-shaft speed, rpm.
    pub speed_rpm: f64,
    /// The shedding law.
    pub law: String,
    /// Motion angle, deg.
    pub motion_deg: f64,
    /// The frames, front first.
    pub frames: Vec<FrameCheck>,
    /// The frame (1 = front) with the largest strain.
    pub max_strain_frame: usize,
    /// Picks in the pattern repeat.
    pub picks: usize,
    /// Largest |shedding torque| over the repeat (refined), N·m.
    pub peak_torque_n_m: f64,
    /// Where, deg of the repeat.
    pub peak_angle_deg: f64,
    /// RMS shedding torque over the repeat, N·m.
    pub rms_torque_n_m: f64,
    /// Least clearance to the carrier from entry to exit over every pick, mm.
    pub min_clearance_mm: f64,
    /// The window common to every pick in which the shed clears the carrier, deg.
    pub window_deg: f64,
    /// Its start in the turn, deg.
    pub window_open_deg: f64,
    /// Its end in the turn, deg.
    pub window_close_deg: f64,
    /// The insertion the carrier needs: entry and exit, deg.
    pub insertion_deg: [f64; 2],
    /// The carrier's mean speed across the shed, m/s.
    pub mean_speed_m_s: f64,
    /// The highest loom speed at which the carrier passes in the window, rpm.
    pub max_speed_rpm: f64,
}

/// Checks `loom` weaving `pattern`.
pub fn check(loom: &Loom, pattern: &Pattern) -> Result<CheckReport> {
    check_with(loom, pattern, &|_, _| {})
}

/// [`check`], calling `progress(done, all)` as it goes (`all` is the number of picks and 2: the
/// windows, each pick's turn of the torque grid, the RMS), for a progress bar on a long repeat.
pub fn check_with(loom: &Loom, pattern: &Pattern, progress: &dyn Fn(usize, usize)) -> Result<CheckReport> {
    let all = pattern.picks() + 2;
    let motion = Motion::new(loom, pattern)?;
    let drive = Drive::new(loom, &motion, pattern);
    let timing: TimingReport = Timing::new(loom, &motion, pattern)?.summary()?;
    progress(1, all);
    let g = &loom.geometry;
    let equal = equal_strain_strokes(&g.frame_m, g.back_rest_m, g.warp_line_m, g.stroke_m[0]);
    let frames: Vec<FrameCheck> = (0..loom.frame_count())
        .map(|i| {
            let shed = g.frame_shed(i);
            let (mut up, mut down) = (false, false);
            for p in 0..pattern.picks() {
                if pattern.is_up(p, i) { up = true } else { down = true }
            }
            let max_strain = match (up, down) {
                (true, true) => full_shed_strain(g.frame_m[i], g.back_rest_m, g.warp_line_m, g.stroke_m[i]),
                (true, false) => shed.strain_top,
                _ => shed.strain_bottom,
            };
            FrameCheck {
                frame: i + 1,
                distance_mm: shed.distance_mm,
                back_depth_mm: shed.back_depth_mm,
                stroke_mm: shed.stroke_mm,
                shed_angle_deg: shed.shed_angle_deg,
                max_strain,
                equal_strain_stroke_mm: loomkin_units::to_12_digits(equal[i] * 1e3),
                ends: drive.ends()[i],
                moves: motion.move_count(i),
            }
        })
        .collect();
    let max_strain_frame = frames.iter().max_by(|a, b| a.max_strain.total_cmp(&b.max_strain)).map_or(1, |f| f.frame);
    let peak = drive.peak_with(0.5, &|p| progress(1 + p, all));
    let rms_torque_n_m = drive.rms();
    progress(all, all);
    Ok(CheckReport {
        loom: loom.name.clone(),
        speed_rpm: loom.speed.rpm(),
        law: loom.shedding.law.label().to_string(),
        motion_deg: motion.motion_deg(),
        frames,
        max_strain_frame,
        picks: pattern.picks(),
        peak_torque_n_m: peak.torque_n_m.abs(),
        peak_angle_deg: peak.angle_deg,
        rms_torque_n_m,
        min_clearance_mm: timing.min_clearance_mm,
        window_deg: timing.window_deg,
        window_open_deg: timing.open_deg,
        window_close_deg: timing.close_deg,
        insertion_deg: [loom.insertion.entry_deg, loom.insertion.exit_deg],
        mean_speed_m_s: timing.mean_speed_m_s,
        max_speed_rpm: timing.max_speed_rpm,
    })
}
