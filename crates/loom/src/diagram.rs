//! Figures: the classic loom timing diagram and the torque over the repeat.

use crate::insertion_timing::{CarrierTiming, carrier_timing};
use crate::{Drive, Loom, Motion, Pattern, Result, Timing, TimingReport, crossing_offset_deg};
use loomkin_plot::{Figure, Legend, Note, Panel, Rule, Series, XBand, sig4};
use loomkin_units::Range;
use serde::Serialize;

/// The numbers behind the timing diagram over picks `from_pick … from_pick + picks` of the repeat
/// (angles absolute, 0° = the first pick's beat-up): what [`timing_diagram`] draws and the
/// workbench's loom view shows.
#[derive(Debug, Clone, Serialize)]
pub struct TimingCurves {
    /// Main-shaft angles, every `step_deg` from `360·from_pick` to `360·(from_pick + picks)`.
    pub angle_deg: Vec<f64>,
    /// Every frame's position from the level shed (mid-stroke), mm, up positive (`lift_mm[i][k]`:
    /// frame `i`, front first).
    pub lift_mm: Vec<Vec<f64>>,
    /// Frames that move at least once in the repeat (0-based).
    pub moving_frames: Vec<usize>,
    /// Clear height of the shed at the carrier's front edge, mm (0 where closed).
    pub clear_mm: Vec<f64>,
    /// The shed open to the carrier (clear height ≥ carrier height).
    pub open: Vec<bool>,
    /// Carrier height, mm.
    pub carrier_height_mm: f64,
    /// Reed width the carrier crosses, m.
    pub reed_width_m: f64,
    /// The carrier's entry and exit in each pick shown (absolute deg).
    pub insertion_deg: Vec<[f64; 2]>,
    /// The window common to every pick, in each pick shown (absolute deg).
    pub clear_window_deg: Vec<[f64; 2]>,
    /// Each pick's own window where the shed clears the carrier (absolute deg).
    pub pick_window_deg: Vec<[f64; 2]>,
    /// Beat-ups (absolute deg).
    pub beat_up_deg: Vec<f64>,
    /// The whole repeat's timing figures.
    pub report: TimingReport,
}

/// The allowed angle step of [`timing_curves`] (deg): at least a tenth of a degree (3 600 points a
/// pick per frame), at most 10° (the shed's opening still drawn within a step).
pub const TIMING_STEP_RANGE: Range = Range::closed(0.1, 10.0, "deg");
/// The angle step of [`timing_curves`] when none is given (deg).
pub const DEFAULT_TIMING_STEP_DEG: f64 = 1.0;
/// The picks a timing diagram shows when not told: two, so that the beat-up between them shows.
pub const DEFAULT_TIMING_PICKS: usize = 2;

/// [`TimingCurves`] of `picks` picks from `from_pick` (0-based, taken within the repeat) at
/// `step_deg` (within [`TIMING_STEP_RANGE`], under the field name `step_deg`).
pub fn timing_curves(
    loom: &Loom,
    pattern: &Pattern,
    from_pick: usize,
    picks: usize,
    step_deg: f64,
) -> Result<TimingCurves> {
    TIMING_STEP_RANGE.check("step_deg", step_deg)?;
    let motion = Motion::new(loom, pattern)?;
    let timing = Timing::new(loom, &motion, pattern)?;
    let report = timing.report()?;
    let from = from_pick % pattern.picks();
    let picks = picks.clamp(1, pattern.picks());
    let (a, b) = (360.0 * from as f64, 360.0 * (from + picks) as f64);
    let n = ((b - a) / step_deg).ceil().max(1.0) as usize;
    let angle_deg: Vec<f64> = (0..=n).map(|k| if k == n { b } else { a + k as f64 * step_deg }).collect();
    let frames = loom.frame_count();
    let lift_mm = (0..frames).map(|i| angle_deg.iter().map(|&t| 1e3 * motion.frame(i, t).y_m).collect()).collect();
    let moving_frames = (0..frames).filter(|&i| !motion.moves(i).is_empty()).collect();
    let delta = crossing_offset_deg(loom.shedding.crossing_deg);
    let pick_at = |t: f64| ((t - delta) / 360.0).floor().max(0.0) as usize;
    let x_c = timing.carrier_edge_m();
    let clear_mm: Vec<f64> = angle_deg.iter().map(|&t| 1e3 * timing.clear_m(pick_at(t), x_c, t).max(0.0)).collect();
    let h_c = loom.insertion.carrier_height_m * 1e3;
    let open = clear_mm.iter().map(|&c| c >= h_c).collect();
    let ins = &loom.insertion;
    let base = |p: usize| 360.0 * (from + p) as f64;
    let insertion_deg = (0..picks).map(|p| [base(p) + ins.entry_deg, base(p) + ins.exit_deg]).collect();
    let clear_window_deg = (0..picks).map(|p| [base(p) + report.open_deg, base(p) + report.close_deg]).collect();
    let pick_window_deg = (0..picks)
        .map(|p| {
            let w = &report.picks[(from + p) % report.picks.len()];
            [base(p) + w.open_deg, base(p) + w.close_deg]
        })
        .collect();
    let beat_up_deg = (0..=picks).map(|p| base(p) + loom.beat_up_deg).filter(|&t| t <= b).collect();
    Ok(TimingCurves {
        angle_deg,
        lift_mm,
        moving_frames,
        clear_mm,
        open,
        carrier_height_mm: h_c,
        reed_width_m: ins.reed_width_m,
        insertion_deg,
        clear_window_deg,
        pick_window_deg,
        beat_up_deg,
        report,
    })
}

/// The classic timing diagram over the first two picks (0° to 720°, 0° = beat-up): every frame's
/// lift; the clear shed at the carrier's front edge against the carrier's height, with the shed
/// open (clear of the carrier) or closed; the insertion window; the carrier's path across the
/// reed; the beat-ups.
pub fn timing_diagram(loom: &Loom, pattern: &Pattern) -> Result<Figure> {
    let turns = pattern.picks().min(2);
    let c = timing_curves(loom, pattern, 0, turns, 0.5)?;
    let report = &c.report;
    let angles = &c.angle_deg;
    let frames = loom.frame_count();
    // The frames that move (at most 12 of them), else the first ones.
    let pool = if c.moving_frames.is_empty() { (0..frames).collect() } else { c.moving_frames.clone() };
    let shown: Vec<usize> =
        if pool.len() <= 12 { pool } else { pool.iter().copied().step_by(pool.len().div_ceil(12)).collect() };
    let lifts: Vec<Series> = shown
        .iter()
        .map(|&i| {
            let pts = angles.iter().zip(&c.lift_mm[i]).map(|(&t, &y)| (t, y)).collect();
            Series::line(format!("frame {}", i + 1), pts)
        })
        .collect();
    let clear: Vec<(f64, f64)> = angles.iter().zip(&c.clear_mm).map(|(&t, &y)| (t, y)).collect();
    let h_c = c.carrier_height_mm;
    let open: Vec<(f64, f64)> = angles.iter().zip(&c.open).map(|(&t, &o)| (t, if o { h_c } else { 0.0 })).collect();
    // One series per pick (a line through a gap would join the picks); the first carries the label.
    let per_pick = |label: &str, color: [u8; 3], spans: &[[f64; 2]], y: [f64; 2]| -> Vec<Series> {
        spans
            .iter()
            .enumerate()
            .map(|(p, s)| {
                let l = if p == 0 { label } else { "" };
                Series::line(l, vec![(s[0], y[0]), (s[1], y[1])]).with_color(color)
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
    shed.extend(per_pick("insertion (entry to exit)", [0, 0, 0], &c.insertion_deg, [-2.0, -2.0]));
    shed.extend(per_pick("clear window (all picks)", [204, 121, 167], &c.clear_window_deg, [-4.0, -4.0]));
    let ct = carrier_timing(loom)?;
    let end = 360.0 * turns as f64;
    if let Some(d) = ct.sley_back_dwell_deg {
        let spans: Vec<[f64; 2]> = per_turn(d, turns, end).collect();
        shed.extend(per_pick("sley back dwell", [120, 120, 120], &spans, [-6.0, -6.0]));
    }
    let mut carrier = match ct.kind {
        "shuttle" => per_pick("carrier path", [0, 114, 178], &c.insertion_deg, [0.0, c.reed_width_m]),
        _ => carrier_series(&ct, turns),
    };
    let beat_up = Series::markers("beat-up", beat).with_color([213, 94, 0]);
    carrier.push(beat_up.clone());
    let bands: Vec<XBand> = match ct.kind {
        "shuttle" => Vec::new(),
        _ => {
            per_turn(ct.in_shed_deg, turns, end).map(|s| XBand::new(s[0], s[1], "in the shed", XBand::WINDOW)).collect()
        }
    };
    let mut panels = vec![
        Panel::new("frame lift [mm]", lifts).with_legend(if shown.len() <= 8 { Legend::Auto } else { Legend::Hidden }),
        Panel::new("shed at the carrier [mm]", shed).with_legend(Legend::Auto),
        Panel::new(format!("{} across the reed [m]", carrier_noun(ct.kind)), carrier)
            .with_legend(Legend::Auto)
            .with_x_bands(bands),
    ];
    if !ct.relay_plan.is_empty() {
        panels.push(relay_panel(&ct, turns, beat_up));
    }
    let title = format!(
        "{} — {} picks, window {:.1}° ({:.1}° to {:.1}°), max {:.0} rpm",
        if loom.name.is_empty() { "loom" } else { &loom.name },
        pattern.picks(),
        report.window_deg,
        report.open_deg,
        report.close_deg,
        report.max_speed_rpm
    );
    let tall = panels.len() > 3;
    let mut fig = Figure::new(title, "main-shaft angle [deg] (0 = beat-up)", panels);
    fig.size = Some((1100, if tall { 1150 } else { 900 }));
    Ok(fig)
}

/// What the carrier panel's axis names: the shuttle's panel keeps its "carrier".
fn carrier_noun(kind: &str) -> &'static str {
    match kind {
        "rapier" => "rapier heads",
        "projectile" => "projectile",
        "airjet" => "yarn tip",
        _ => "carrier",
    }
}

/// The turns' copies of a span of one turn (deg) that meet the diagram's axis `[0, end]`, cut to it.
fn per_turn(span: [f64; 2], turns: usize, end: f64) -> impl Iterator<Item = [f64; 2]> {
    (-1..=turns as i64).filter_map(move |k| {
        let (a, b) = (span[0] + 360.0 * k as f64, span[1] + 360.0 * k as f64);
        (b > 0.0 && a < end).then(|| [a.max(0.0), b.min(end)])
    })
}

/// The colours of the carriers' tracks (the shuttle's path colour first).
const TRACK_COLORS: [[u8; 3]; 2] = [[0, 114, 178], [230, 159, 0]];

/// Each track of `ct` in each of `turns` turns (one series per turn, the first labelled), and the
/// rapier's transfer in each turn.
fn carrier_series(ct: &CarrierTiming, turns: usize) -> Vec<Series> {
    let mut out = Vec::new();
    for (i, t) in ct.tracks.iter().enumerate() {
        for p in 0..turns {
            let shift = 360.0 * p as f64;
            let pts = t.angle_deg.iter().zip(&t.position_m).map(|(&a, &x)| (a + shift, x)).collect();
            let label = if p == 0 { t.label } else { "" };
            out.push(Series::line(label, pts).with_color(TRACK_COLORS[i % TRACK_COLORS.len()]));
        }
    }
    if let Some(tr) = ct.transfer {
        let pts = (0..turns).map(|p| (tr.angle_deg + 360.0 * p as f64, tr.position_m)).collect();
        out.push(Series::markers("transfer", pts).with_color([0, 0, 0]));
    }
    out
}

/// The air jet's relay groups as bars: group `g` at height `g`, from its opening to its closing in
/// each turn; with the beat-ups (which also span the angle axis as the other panels do).
fn relay_panel(ct: &CarrierTiming, turns: usize, beat_up: Series) -> Panel {
    let mut bars = Vec::new();
    for p in 0..turns {
        let shift = 360.0 * p as f64;
        for (k, o) in ct.relay_plan.iter().enumerate() {
            let g = o.group as f64;
            let label = if p == 0 && k == 0 { "relay group open" } else { "" };
            bars.push(
                Series::line(label, vec![(o.open_deg + shift, g), (o.close_deg + shift, g)]).with_color([0, 158, 115]),
            );
        }
    }
    bars.push(beat_up);
    Panel::new("relay group", bars).with_legend(Legend::Auto)
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
    let many = pattern.picks() > TURNS_AXIS_FROM_PICKS;
    let at = if many { in_pick(peak.angle_deg) } else { format!("{}°", sig4(peak.angle_deg)) };
    let title = format!(
        "shedding torque at {} rpm, {} picks: peak {:.2} N·m at {}, RMS {:.2} N·m",
        loom.speed.rpm(),
        pattern.picks(),
        peak.torque_n_m,
        if many { in_pick(peak.angle_deg) } else { format!("{:.1}°", peak.angle_deg) },
        rms
    );
    let mut panel = Panel::new("torque [N·m]", vec![Series::line("torque", pts)]).with_notes([Note::new(
        peak.angle_deg,
        peak.torque_n_m,
        format!("peak {} N·m at {at}", sig4(peak.torque_n_m)),
    )]);
    // The motor's limit both ways (the drive brakes the frames as well as lifting them).
    if let Some(limit) = loom.motor_torque_n_m {
        let over = if peak.torque_n_m.abs() > limit { ": exceeded" } else { "" };
        panel = panel
            .with_rule(Rule::y(limit, format!("motor torque limit ±{} N·m{over}", sig4(limit))))
            .with_rule(Rule::y(-limit, ""));
    }
    Ok(repeat_figure(title, vec![panel], many))
}

/// Repeats of more picks than this are drawn against picks (main-shaft turns), fewer in degrees.
pub(crate) const TURNS_AXIS_FROM_PICKS: usize = 2;

/// A figure over a repeat: in main-shaft degrees, or against picks with the degrees within a pick
/// as minor ticks (`many`), so a repeat of 48 picks does not read "17280°".
pub(crate) fn repeat_figure(title: String, panels: Vec<Panel>, many: bool) -> Figure {
    if many {
        Figure::new(title, "picks from the repeat's start (one main-shaft turn each)", panels).with_turns_axis()
    } else {
        Figure::new(title, "main-shaft angle [deg]", panels)
    }
}

/// An angle over the repeat as its pick (counted from 1) and the angle within it: `pick 18 at 350.3°`.
pub(crate) fn in_pick(angle_deg: f64) -> String {
    let turn = (angle_deg / 360.0).floor();
    format!("pick {} at {}°", turn as i64 + 1, sig4(angle_deg - 360.0 * turn))
}
