//! `loomkin cycle FILE.toml`: a machine cycle in physical units.

use crate::output::{self, Out, outln};
use crate::util::{self, Format};
use anyhow::Result;
use clap::Args;
use loomkin_laws::{Cycle, CyclePoint, SegmentKind};
use loomkin_plot::{Figure, Note, Panel, Series, XBand, sig4};
use loomkin_units::{Cost, ShaftSpeed};
use std::path::PathBuf;

/// `loomkin cycle`.
#[derive(Debug, Args)]
pub struct CycleArgs {
    /// The cycle file (TOML: `unit`, `stroke`, `[[segment]]` tables).
    file: PathBuf,
    #[arg(long, help = util::speed_help("Main-shaft speed in rpm (overrides the file's `speed_rpm`)"))]
    speed_rpm: Option<f64>,
    /// Number of samples over the cycle for CSV, JSON and plots.
    #[arg(long, default_value_t = Cycle::POINTS.default_count())]
    points: usize,
    #[command(flatten)]
    format: Format,
    /// Plot to this file (.svg or .png).
    #[arg(short, long, conflicts_with_all = ["json", "csv"])]
    output: Option<PathBuf>,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
}

/// Runs `loomkin cycle`.
pub fn run(a: CycleArgs) -> Result<()> {
    output::check_outputs([a.output.as_ref().map(|p| Out::plot("--output", p))])?;
    let text = util::read_input(&a.file)?;
    let cycle = Cycle::from_toml(&text).map_err(|e| anyhow::anyhow!("{}: {e}", a.file.display()))?;
    let rpm = cycle.speed_rpm_or(a.speed_rpm);
    let speed = ShaftSpeed::from_rpm_field("--speed-rpm", rpm)?;
    Cycle::POINTS.check_count_as("--points", a.points)?;
    // Tables stream (nothing held per row): their time limits N; a plot holds its points.
    let n = a.points as f64;
    let cost = if a.format.json {
        Cost::cpu_items(n, 0.0, JSON_S_PER_ROW)
    } else if a.format.csv {
        Cost::cpu_items(n, 0.0, CSV_S_PER_ROW)
    } else if a.output.is_some() {
        Cost::cpu_items(n, PLOT_BYTES_PER_POINT, PLOT_S_PER_POINT)
    } else {
        Cost::default()
    };
    crate::util::check_budget("--points", a.points, cost)?;
    if a.format.csv || a.format.json {
        // Checked finite first (evaluating is cheap beside printing), so the streamed output
        // never stops half-way.
        if let Some(p) = cycle
            .samples(a.points, rpm)
            .find(|p| ![p.time_s, p.kin.s, p.kin.v, p.kin.a, p.kin.j].iter().all(|v| v.is_finite()))
        {
            return Err(util::failure(anyhow::anyhow!("internal: the cycle is not finite at {} deg", p.angle_deg)));
        }
        let progress = util::Progress::new(a.points as u64, "samples");
        if a.format.json {
            output::json_streamed(&cycle.report_streamed(speed, a.points, || progress.inc(1)))?;
        } else {
            let columns = cycle.unit.sample_keys();
            let rows = cycle
                .samples(a.points, rpm)
                .inspect(|_| progress.inc(1))
                .map(|p| [p.angle_deg, p.time_s, p.kin.s, p.kin.v, p.kin.a, p.kin.j]);
            output::csv_rows(&columns, true, rows)?;
        }
        progress.finish();
        return Ok(());
    }
    let samples = if a.output.is_some() { cycle.sample(a.points, rpm) } else { Vec::new() };
    if let Some(out) = a.output {
        return output::figure(&cycle_figure(&cycle, &samples, speed, &a.file), &out, &a.plot);
    }
    let [su, vs, as_, _] = cycle.unit.si_units();
    outln!(
        "cycle {} at {rpm} rpm (one cycle {:.6} s)",
        a.file.display(),
        cycle.period_rad / loomkin_units::rad_per_s_from_rpm(rpm)
    )?;
    outln!(
        "{:>3} {:<7} {:>9} {:>9} {:<36} {:>12} {:>14} {:>14}",
        "#",
        "kind",
        "from[deg]",
        "to[deg]",
        "law",
        format!("stroke[{su}]"),
        format!("max|v|[{vs}]"),
        format!("max|a|[{as_}]")
    )?;
    for (i, s) in cycle.segment_peaks(speed).iter().enumerate() {
        outln!(
            "{:>3} {:<7} {:>9.3} {:>9.3} {:<36} {:>12.6} {:>14.6} {:>14.4}",
            i,
            s.kind.name(),
            s.from_deg,
            s.to_deg,
            s.law.as_deref().unwrap_or("-"),
            s.stroke,
            s.peak_velocity,
            s.peak_acceleration,
        )?;
    }
    Ok(())
}

/// CPU seconds per row of `cycle --json` (six keyed numbers, pretty-printed): the `cycle_json_rows`
/// bench of loomkin-laws (release, fastest of 10: 0.92 µs).
const JSON_S_PER_ROW: f64 = 0.92e-6;
/// CPU seconds per row of `cycle --csv`: the `cycle_csv_rows` bench (fastest of 10: 1.75 µs).
const CSV_S_PER_ROW: f64 = 1.75e-6;
/// Bytes held per point of a plot: the sample (48 bytes) and four series of (angle, value) pairs.
const PLOT_BYTES_PER_POINT: f64 = 48.0 + 4.0 * 16.0;
/// Seconds per point of a plot (drawing four polylines): not measured by a bench; taken as four
/// CSV rows.
const PLOT_S_PER_POINT: f64 = 4.0 * CSV_S_PER_ROW;

/// The cycle's position (in the file's unit: mm or deg), velocity, acceleration and jerk over one
/// turn, its dwells, rises and returns shaded, the extremes of velocity and acceleration marked.
/// The cycle's segments as shaded intervals (dwell grey, rise green, return orange), labelled
/// with their law, shifted by `offset_deg`.
pub(crate) fn cycle_bands(cycle: &Cycle, offset_deg: f64) -> Vec<XBand> {
    cycle
        .segments
        .iter()
        .map(|s| {
            let from = s.start_rad.to_degrees() + offset_deg;
            let to = (s.start_rad + s.length_rad).to_degrees() + offset_deg;
            let (color, kind) = match s.kind {
                SegmentKind::Dwell => (XBand::DWELL, "dwell"),
                SegmentKind::Rise => (XBand::RISE, "rise"),
                SegmentKind::Return => (XBand::RETURN, "return"),
            };
            let label = match &s.law {
                Some((spec, _)) => format!("{kind} · {}", spec.label()),
                None => kind.to_string(),
            };
            XBand::new(from, to, label, color)
        })
        .collect()
}

fn cycle_figure(cycle: &Cycle, samples: &[CyclePoint], speed: ShaftSpeed, file: &std::path::Path) -> Figure {
    let [_, vs, as_, js] = cycle.unit.si_units();
    // Positions in the cycle's own unit (mm or deg), from SI.
    let (pos_unit, pos_scale) = (cycle.unit.stroke_range().unit, 1.0 / cycle.unit.to_si());
    let col = |f: &dyn Fn(&loomkin_laws::Kinematics) -> f64| samples.iter().map(|p| (p.angle_deg, f(&p.kin))).collect();
    let bands = cycle_bands(cycle, 0.0);
    let unlabelled = || bands.iter().map(|b| XBand { label: String::new(), ..b.clone() }).collect::<Vec<_>>();
    let mut v_notes = Vec::new();
    let mut a_notes = Vec::new();
    if let Some(e) = cycle.extremes(speed) {
        let (d, v) = e.velocity;
        v_notes.push(Note::new(d, v, format!("|v| max {} {vs} at {d:.1}°", sig4(v.abs()))));
        for ((d, acc), what) in [(e.acceleration_max, "max"), (e.acceleration_min, "min")] {
            a_notes.push(Note::new(d, acc, format!("{what} {} {as_} at {d:.1}°", sig4(acc))));
        }
    }
    let panels = vec![
        Panel::new(format!("position [{pos_unit}]"), vec![Series::line("", col(&|k| k.s * pos_scale))])
            .with_x_bands(bands.clone()),
        Panel::new(format!("velocity [{vs}]"), vec![Series::line("", col(&|k| k.v))])
            .with_x_bands(unlabelled())
            .with_notes(v_notes),
        Panel::new(format!("acceleration [{as_}]"), vec![Series::line("", col(&|k| k.a))])
            .with_x_bands(unlabelled())
            .with_notes(a_notes),
        Panel::new(format!("jerk [{js}]"), vec![Series::line("", col(&|k| k.j))]).with_x_bands(unlabelled()),
    ];
    let title = format!("{} at {} rpm", util::file_name(file), speed.rpm());
    Figure::new(title, "main-shaft angle [deg]", panels)
}
