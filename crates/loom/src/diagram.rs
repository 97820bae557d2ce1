//! Figures: the classic loom timing diagram and the torque over the repeat.

use crate::{Drive, Loom, Motion, Pattern, Result, Timing, crossing_offset_deg};
use loomkin_io::plot::{Figure, Legend, Panel, Series};

/// The classic timing diagram over the first two picks (0° to 720°, 0° = beat-up): every frame's
/// lift; the clear shed at the carrier's front edge against the carrier's height, with the shed
/// open (clear of the carrier) or closed; the insertion window; the carrier's path across the
/// reed; the beat-ups.
pub fn timing_diagram(loom: &Loom, pattern: &Pattern) -> Result<Figure> {
    let motion = Motion::new(loom, pattern)?;
    let timing = Timing::new(loom, &motion, pattern)?;
    let report = timing.report()?;
    let turns = pattern.picks().min(2);
    let end = 360.0 * turns as f64;
    let step = 0.5;
    let n = (end / step) as usize;
    let angles: Vec<f64> = (0..=n).map(|k| k as f64 * step).collect();
    let frames = loom.frame_count();
    // The frames that move (at most 12 of them), else the first ones.
    let moving: Vec<usize> = (0..frames).filter(|&i| !motion.moves(i).is_empty()).collect();
    let pool = if moving.is_empty() { (0..frames).collect() } else { moving };
    let shown: Vec<usize> =
        if pool.len() <= 12 { pool } else { pool.iter().copied().step_by(pool.len().div_ceil(12)).collect() };
    let lifts: Vec<Series> = shown
        .iter()
        .map(|&i| {
            let pts = angles.iter().map(|&t| (t, 1e3 * motion.frame(i, t).y_m)).collect();
            Series::line(format!("frame {}", i + 1), pts)
        })
        .collect();
    let delta = crossing_offset_deg(loom.shedding.crossing_deg);
    let pick_at = |t: f64| ((t - delta) / 360.0).floor().max(0.0) as usize;
    let x_c = timing.carrier_edge_m();
    let clear: Vec<(f64, f64)> =
        angles.iter().map(|&t| (t, 1e3 * timing.clear_m(pick_at(t), x_c, t).max(0.0))).collect();
    let h_c = loom.insertion.carrier_height_m * 1e3;
    let open: Vec<(f64, f64)> = clear.iter().map(|&(t, c)| (t, if c >= h_c { h_c } else { 0.0 })).collect();
    let ins = &loom.insertion;
    // One series per pick (a line through a gap would join the picks); the first carries the label.
    let per_pick = |label: &str, color: [u8; 3], pts: &dyn Fn(f64) -> Vec<(f64, f64)>| -> Vec<Series> {
        (0..turns)
            .map(|p| {
                let l = if p == 0 { label } else { "" };
                Series::line(l, pts(360.0 * p as f64)).with_color(color)
            })
            .collect()
    };
    let beat: Vec<(f64, f64)> = (0..=turns).map(|p| (360.0 * p as f64 + loom.beat_up_deg, 0.0)).collect();
    let mut shed = vec![
        Series::line("clear shed", clear).with_color([0, 114, 178]),
        Series::line("carrier height", angles.iter().map(|&t| (t, h_c)).collect())
            .with_color([213, 94, 0])
            .with_dashes(),
        Series::line("shed open to the carrier", open).with_color([0, 158, 115]),
    ];
    shed.extend(per_pick("insertion (entry to exit)", [0, 0, 0], &|b| {
        vec![(b + ins.entry_deg, -2.0), (b + ins.exit_deg, -2.0)]
    }));
    shed.extend(per_pick("clear window (all picks)", [204, 121, 167], &|b| {
        vec![(b + report.open_deg, -4.0), (b + report.close_deg, -4.0)]
    }));
    let mut carrier = per_pick("carrier path", [0, 114, 178], &|b| {
        vec![(b + ins.entry_deg, 0.0), (b + ins.exit_deg, ins.reed_width_m)]
    });
    carrier.push(Series::markers("beat-up", beat).with_color([213, 94, 0]));
    let panels = vec![
        Panel::new("frame lift [mm]", lifts).with_legend(if shown.len() <= 8 {
            Legend::UpperRight
        } else {
            Legend::Hidden
        }),
        Panel::new("shed at the carrier [mm]", shed).with_legend(Legend::UpperRight),
        Panel::new("carrier across the reed [m]", carrier).with_legend(Legend::UpperLeft),
    ];
    let title = format!(
        "{} — {} picks, window {:.1}° ({:.1}° to {:.1}°), max {:.0} rpm",
        if loom.name.is_empty() { "loom" } else { &loom.name },
        pattern.picks(),
        report.window_deg,
        report.open_deg,
        report.close_deg,
        report.max_speed_rpm
    );
    let mut fig = Figure::new(title, "main-shaft angle [deg] (0 = beat-up)", panels);
    fig.size = Some((1100, 900));
    Ok(fig)
}

/// The shedding torque over the repeat at `step_deg`, with its peak and RMS in the title.
pub fn torque_figure(loom: &Loom, pattern: &Pattern, step_deg: f64) -> Result<Figure> {
    let motion = Motion::new(loom, pattern)?;
    let drive = Drive::new(loom, &motion, pattern);
    let curve = drive.torque_curve(step_deg);
    let peak = drive.peak_of(&curve);
    let rms = drive.rms();
    let mut pts = curve.clone();
    pts.push((motion.repeat_deg(), curve.first().map_or(0.0, |c| c.1)));
    let title = format!(
        "shedding torque at {} rpm, {} picks: peak {:.2} N·m at {:.1}°, RMS {:.2} N·m",
        loom.speed.rpm(),
        pattern.picks(),
        peak.torque_n_m,
        peak.angle_deg,
        rms
    );
    let panels = vec![Panel::new(
        "torque [N·m]",
        vec![Series::line("torque", pts), Series::markers("peak", vec![(peak.angle_deg, peak.torque_n_m)])],
    )];
    Ok(Figure::new(title, "main-shaft angle [deg]", panels))
}
