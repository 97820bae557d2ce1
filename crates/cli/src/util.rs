//! Shared plumbing of the subcommands: output format flags, exit codes, `KEY=VALUE` params, input files.

use anyhow::Context;
use clap::Args;
use loomkin_laws::{Cycle, CycleSpec, LawSpec, StrokeUnit};

/// An error that is a failure of the run (exit 1), not of the user's input (exit 2).
#[derive(Debug)]
pub struct Failure(String);

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Failure {}

/// Exit code for an error: 1 if it is a [`Failure`], else 2 (bad input or usage).
pub fn exit_code(e: &anyhow::Error) -> u8 {
    if e.chain().any(|c| c.is::<Failure>() || c.is::<crate::output::WriteError>()) { 1 } else { 2 }
}

/// Wraps an output error (writing a file or stdout) as a run failure, exit code 1.
pub fn failure(e: impl Into<anyhow::Error>) -> anyhow::Error {
    let e: anyhow::Error = e.into();
    anyhow::Error::new(Failure(format!("{e:#}")))
}

/// An error of the parts of a sharded run: the user's input (no manifest, another study's draws)
/// exits with 2, a failed check or I/O with 1.
pub fn part_error(e: loomkin_study::parts::PartError) -> anyhow::Error {
    if e.is_input() { anyhow::Error::new(e) } else { failure(e) }
}

/// `--json` / `--csv` choice shared by the subcommands.
#[derive(Debug, Clone, Copy, Args, Default)]
pub struct Format {
    /// Print machine-readable JSON.
    #[arg(long, conflicts_with = "csv")]
    pub json: bool,
    /// Print CSV (header with units, one row per sample).
    #[arg(long)]
    pub csv: bool,
}

/// A catalogue law for a rise (and, where the command makes a whole cycle, the return) instead of
/// a cycle file: `cam table`, `cam profile` and `servo check` take the same flags.
#[derive(Debug, Args)]
pub struct RiseArgs {
    /// A catalogue law for the rise (see `loomkin law list`), instead of a cycle file.
    #[arg(long)]
    pub law: Option<String>,
    /// A law parameter KEY=VALUE (repeatable).
    #[arg(long = "param", value_parser = parse_key_value, requires = "law")]
    pub params: Vec<(String, String)>,
    /// Stroke of the rise in mm (translating follower or slave).
    #[arg(long, requires = "law", conflicts_with = "stroke_deg", allow_hyphen_values = true)]
    pub stroke_mm: Option<f64>,
    /// Swing of the rise in deg (oscillating follower, swinging slave).
    #[arg(long, requires = "law", allow_hyphen_values = true)]
    pub stroke_deg: Option<f64>,
    /// Master angle of the rise (and of the return, where there is one), deg.
    #[arg(long, requires = "law", allow_hyphen_values = true)]
    pub motion_deg: Option<f64>,
}

impl RiseArgs {
    /// The law (default `cycloidal`), the stroke and its unit, the motion angle (deg).
    pub fn rise(&self) -> anyhow::Result<(LawSpec, f64, StrokeUnit, f64)> {
        let law = LawSpec::parse(self.name(), &self.params)?;
        let (stroke, unit) = match (self.stroke_mm, self.stroke_deg) {
            (Some(h), None) => (h, StrokeUnit::Mm),
            (None, Some(h)) => (h, StrokeUnit::Deg),
            _ => anyhow::bail!("stroke_mm: --stroke-mm or --stroke-deg is needed with --law"),
        };
        let Some(b) = self.motion_deg else { anyhow::bail!("motion_deg: --motion-deg is needed with --law") };
        Ok((law, stroke, unit, b))
    }

    /// With a cycle file the rise flags have nothing to act on: refused, not silently ignored
    /// (`cam table CYCLE --stroke-mm 50` does not scale the file's strokes).
    pub fn none_with_file(&self) -> anyhow::Result<()> {
        let given = [
            ("--law", self.law.is_some()),
            ("--param", !self.params.is_empty()),
            ("--stroke-mm", self.stroke_mm.is_some()),
            ("--stroke-deg", self.stroke_deg.is_some()),
            ("--motion-deg", self.motion_deg.is_some()),
        ];
        if let Some((flag, _)) = given.iter().find(|(_, g)| *g) {
            anyhow::bail!(
                "{}: {flag} describes a single rise and cannot be combined with a cycle file (the file sets the laws, strokes and angles)",
                flag.trim_start_matches("--").replace('-', "_")
            );
        }
        Ok(())
    }

    /// The law's name (`cycloidal` when none is given).
    pub fn name(&self) -> &str {
        self.law.as_deref().unwrap_or("cycloidal")
    }

    /// The cycle of `file`, or of this rise with a dwell, the return and a dwell over one turn;
    /// with where it came from (the file's name, or `law NAME (rise, dwell, return, dwell)`).
    pub fn cycle(&self, file: Option<&std::path::Path>) -> anyhow::Result<(Cycle, String)> {
        if let Some(path) = file {
            self.none_with_file()?;
            let cycle = read_cycle(path)?;
            return Ok((cycle, path.display().to_string()));
        }
        let (law, stroke, unit, b) = self.rise()?;
        let cycle = Cycle::new(&CycleSpec::rise_return(&law, unit, stroke, b)?)?;
        Ok((cycle, format!("law {} (rise, dwell, return, dwell)", self.name())))
    }
}

/// Reads a cycle file (TOML), naming the file in the error.
pub fn read_cycle(path: &std::path::Path) -> anyhow::Result<Cycle> {
    let text = read_input(path)?;
    Cycle::from_toml(&text).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))
}

/// Splits `KEY=VALUE`.
pub fn parse_key_value(s: &str) -> Result<(String, String), String> {
    let (k, v) = s.split_once('=').ok_or_else(|| format!("'{s}' is not KEY=VALUE"))?;
    Ok((k.trim().to_string(), v.trim().to_string()))
}

/// Largest input file read (16 MiB): every input of loomkin (a cycle, a drive, a mechanism, a
/// point table, a shedding spec) is a few KiB; a larger one (or `/dev/zero`) is refused before it
/// fills the memory.
pub const MAX_INPUT_BYTES: u64 = 16 * 1024 * 1024;

/// Reads a whole input file of at most [`MAX_INPUT_BYTES`], naming it in the error (a missing,
/// unreadable, oversized or non-UTF-8 input is a usage error: exit 2).
pub fn read_input(path: &std::path::Path) -> anyhow::Result<String> {
    String::from_utf8(read_input_bytes(path)?).map_err(|e| {
        anyhow::anyhow!("cannot read {}: not UTF-8 text (byte {})", path.display(), e.utf8_error().valid_up_to())
    })
}

/// As [`read_input`], the bytes as they are (a WIF, whose encoding the library decides).
pub fn read_input_bytes(path: &std::path::Path) -> anyhow::Result<Vec<u8>> {
    use std::io::Read;
    let name = path.display();
    let file = std::fs::File::open(path).with_context(|| format!("cannot read {name}"))?;
    let mut bytes = Vec::new();
    file.take(MAX_INPUT_BYTES + 1).read_to_end(&mut bytes).with_context(|| format!("cannot read {name}"))?;
    if bytes.len() as u64 > MAX_INPUT_BYTES {
        anyhow::bail!("cannot read {name}: larger than the input limit of 16 MiB");
    }
    Ok(bytes)
}

/// A progress bar on standard error for a run that may take long: drawn only when standard error
/// is a terminal, and only once the run has lasted a second (so a quick run shows nothing).
/// Counts are gathered locally and passed to the bar every few thousand items, so counting every
/// row of a 10⁷-row table costs nothing measurable. The bar is cleared when dropped (an error line
/// is not printed across it).
///
/// Two kinds: [`Progress::new`] for a count known before the run (or, through
/// [`Progress::set_length`], as soon as it starts), drawn as a bar with an ETA; and
/// [`Progress::open_ended`] for a search whose count the library can only estimate (`dyn
/// optimize`'s band responses, the stagger search's stages), drawn as a spinner with the count so
/// far and the time spent — a bar of an estimated length stops short of its end or runs past it,
/// and its ETA is wrong from the first frame (`dyn optimize` read 4/176, ETA 47 s, for a 4 s run
/// that ended at 141).
pub struct Progress {
    bar: Option<indicatif::ProgressBar>,
    start: std::time::Instant,
    pending: std::sync::atomic::AtomicU64,
    shown: std::sync::atomic::AtomicBool,
}

impl Progress {
    /// Items passed to the bar at once.
    const BATCH: u64 = 4096;

    /// The bar's line for a known count.
    const COUNTED: &str = "{msg} {wide_bar} {pos}/{len} (eta {eta})";
    /// The line for a count not known ahead: no length, no ETA.
    const OPEN_ENDED: &str = "{msg} {spinner} {pos} so far ({elapsed})";
    /// How often an open-ended line redraws by itself (its spinner and time move during a long
    /// step).
    const TICK: std::time::Duration = std::time::Duration::from_millis(200);

    /// A bar for `len` items named `label` (hidden unless standard error is a terminal).
    pub fn new(len: u64, label: &str) -> Self {
        Self::on_a_terminal(Some(len), label)
    }

    /// A line for work whose count is not known ahead (see [`Progress`]): `label`, a spinner,
    /// the items done so far and the time spent; [`Progress::set`] moves it.
    pub fn open_ended(label: &str) -> Self {
        Self::on_a_terminal(None, label)
    }

    fn on_a_terminal(len: Option<u64>, label: &str) -> Self {
        use std::io::IsTerminal;
        let bar =
            std::io::stderr().is_terminal().then(|| Self::styled(len, label, indicatif::ProgressDrawTarget::hidden()));
        Self { bar, start: std::time::Instant::now(), pending: 0.into(), shown: false.into() }
    }

    /// The bar of [`Progress::new`] (`len` given) or [`Progress::open_ended`] drawing to `target`.
    fn styled(len: Option<u64>, label: &str, target: indicatif::ProgressDrawTarget) -> indicatif::ProgressBar {
        let bar = indicatif::ProgressBar::with_draw_target(len, target);
        let template = if len.is_some() { Self::COUNTED } else { Self::OPEN_ENDED };
        if let Ok(style) = indicatif::ProgressStyle::with_template(template) {
            bar.set_style(style);
        }
        bar.set_message(label.to_string());
        bar
    }

    /// `n` more items done.
    pub fn inc(&self, n: u64) {
        use std::sync::atomic::Ordering::Relaxed;
        let Some(bar) = &self.bar else { return };
        let pending = self.pending.fetch_add(n, Relaxed) + n;
        if pending < Self::BATCH {
            return;
        }
        bar.inc(self.pending.swap(0, Relaxed));
        self.show_after_a_second();
    }

    /// The items in all (a length known once the work has started).
    pub fn set_length(&self, len: u64) {
        if let Some(bar) = &self.bar {
            bar.set_length(len);
        }
    }

    /// `n` items done in all (for a count kept elsewhere, read now and then).
    pub fn set(&self, n: u64) {
        let Some(bar) = &self.bar else { return };
        bar.set_position(n);
        self.show_after_a_second();
    }

    fn show_after_a_second(&self) {
        use std::sync::atomic::Ordering::Relaxed;
        if let Some(bar) = &self.bar
            && !self.shown.load(Relaxed)
            && self.start.elapsed().as_secs_f64() > 1.0
        {
            self.shown.store(true, Relaxed);
            bar.set_draw_target(indicatif::ProgressDrawTarget::stderr());
            if bar.length().is_none() {
                bar.enable_steady_tick(Self::TICK);
            }
        }
    }

    /// Clears the bar (also done when dropped).
    pub fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.finish();
    }
}

/// The help of an option that takes a library quantity: `text`, then the quantity's range and
/// default in words, read from its descriptor (so `--help` never states a bound or default of
/// its own).
pub fn field_help(text: &str, field: &loomkin_units::Field) -> String {
    match field.default {
        Some(d) => format!("{text}: {}, default {}", field.describe(), loomkin_units::compact(d)),
        None => format!("{text}: {}", field.describe()),
    }
}

/// The help of an option whose default clap shows (`[default: …]`): `text`, then the quantity's
/// range in words, read from its descriptor.
pub fn range_help(text: &str, field: &loomkin_units::Field) -> String {
    format!("{text}: {}", field.describe())
}

/// `--speed-rpm`'s help where the file may set the speed: the main-shaft speed's range and default.
pub fn speed_help(text: &str) -> String {
    field_help(text, &loomkin_units::ShaftSpeed::SPEED)
}

/// Cores the parallel parts of a run share (at least 1), for time estimates: `RAYON_NUM_THREADS`
/// when set (a batch task's CPUs: scripts/slurm-shards.sbatch sets it), else the machine's. So what
/// a shard may do depends on the CPUs it was given, not on the node it lands on.
pub fn cores() -> f64 {
    let given = std::env::var("RAYON_NUM_THREADS").ok().and_then(|t| t.trim().parse::<usize>().ok()).filter(|&n| n > 0);
    given.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get())) as f64
}

/// The limit of this run: [`loomkin_units::Budget::DEFAULT`], or `--budget` / `LOOMKIN_BUDGET`.
static BUDGET: std::sync::OnceLock<loomkin_units::Budget> = std::sync::OnceLock::new();

/// Sets the limit of this run (once, at the start).
pub fn set_budget(budget: loomkin_units::Budget) {
    let _ = BUDGET.set(budget);
}

/// The limit every estimate of this run is checked against.
pub fn budget() -> loomkin_units::Budget {
    BUDGET.get().copied().unwrap_or(loomkin_units::Budget::DEFAULT)
}

/// [`budget`]'s check of `flag = value` (a run's size, estimated as `cost`), its refusal naming the
/// flag the user typed (or the study file's key, `draws`) and `--budget`, the flag that lifts the
/// limit.
pub fn check_budget(
    flag: &str,
    value: impl std::fmt::Display,
    cost: loomkin_units::Cost,
) -> Result<(), loomkin_units::BudgetError> {
    budget().check(flag, value, cost).map_err(|e| e.in_front_end(flag, "--budget MEMORY,TIME"))
}

/// Size, resolution and title of a plot file, shared by every command that plots.
#[derive(Debug, Clone, Args, Default)]
pub struct PlotOpts {
    /// Plot width in pixels at 96 dpi.
    #[arg(long, value_name = "PX", help_heading = "Plot", value_parser = page_width, allow_hyphen_values = true,
          help = field_help("Plot width in pixels at 96 dpi (a figure names the least width its texts need)", &loomkin_plot::Page::WIDTH))]
    pub width: Option<f64>,
    /// Plot height in pixels at 96 dpi.
    #[arg(long, value_name = "PX", help_heading = "Plot", value_parser = page_height, allow_hyphen_values = true,
          help = field_help("Plot height in pixels at 96 dpi (left out: from the number of panels; a figure names the least height its panels need)", &loomkin_plot::Page::HEIGHT))]
    pub height: Option<f64>,
    /// PNG resolution in dots per inch.
    #[arg(long, help_heading = "Plot", value_parser = page_dpi, allow_hyphen_values = true,
          help = field_help("PNG resolution in dots per inch (96 draws one pixel per SVG pixel)", &loomkin_plot::Page::DPI))]
    pub dpi: Option<f64>,
    /// Plot title (default: the input's file name and the run's settings).
    #[arg(long, help_heading = "Plot")]
    pub title: Option<String>,
}

// The page settings are checked while the command line is read: before any computation (so a
// bad `--dpi` is the one line on stderr, not a line after a run's warnings) and whether or not a
// plot is written (a `--width nan` given without `-o` is refused, not ignored).
fn page_value(text: &str, page: impl Fn(f64) -> loomkin_plot::Page) -> Result<f64, String> {
    let v: f64 = text.trim().parse().map_err(|_| format!("'{text}' is not a number"))?;
    page(v).check().map_err(|e| page_error(e).to_string())?;
    Ok(v)
}

fn page_width(text: &str) -> Result<f64, String> {
    page_value(text, |v| loomkin_plot::Page { width: Some(v), ..Default::default() })
}

fn page_height(text: &str) -> Result<f64, String> {
    page_value(text, |v| loomkin_plot::Page { height: Some(v), ..Default::default() })
}

fn page_dpi(text: &str) -> Result<f64, String> {
    page_value(text, |v| loomkin_plot::Page { dpi: Some(v), ..Default::default() })
}

impl PlotOpts {
    /// The settings as the plotting library takes them, checked (one-line error naming the flag).
    pub fn page(&self) -> anyhow::Result<loomkin_plot::Page> {
        let page =
            loomkin_plot::Page { width: self.width, height: self.height, dpi: self.dpi, title: self.title.clone() };
        page.check().map_err(page_error)?;
        Ok(page)
    }
}

/// A page setting's error named as its flag (`--dpi = 0 is out of range: allowed 24 ≤ --dpi ≤ 1200 dpi`).
pub fn page_error(e: loomkin_io::IoError) -> anyhow::Error {
    match e {
        loomkin_io::IoError::Range(r) => {
            let flag = format!("--{}", r.field);
            anyhow::Error::new(r.renamed(flag))
        }
        // One flag too small: the flag named, and what does not fit at its size.
        loomkin_io::IoError::TooSmall { range, reason } => {
            let flag = format!("--{}", range.field);
            anyhow::Error::new(loomkin_io::IoError::TooSmall { range: range.renamed(flag), reason })
        }
        // A size no single flag fixes: `width = 200 and height = 200 px are too small …`, each
        // page setting named as its flag.
        other => {
            let text = other.to_string();
            let text = text.trim_start_matches("plot: ");
            let named = ["width", "height", "dpi"]
                .iter()
                .fold(text.to_string(), |t, k| t.replace(&format!("{k} = "), &format!("--{k} = ")));
            anyhow::anyhow!("{named}")
        }
    }
}

/// A file's name without its folders, for a plot title (`examples/x.toml` → `x.toml`).
pub fn file_name(path: &std::path::Path) -> String {
    path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned())
}

#[cfg(test)]
mod tests {
    use super::Progress;
    use std::sync::{Arc, Mutex};

    /// A terminal that keeps the lines drawn on it.
    #[derive(Debug, Clone, Default)]
    struct Screen(Arc<Mutex<Vec<String>>>);

    impl indicatif::TermLike for Screen {
        fn width(&self) -> u16 {
            100
        }
        fn move_cursor_up(&self, _: usize) -> std::io::Result<()> {
            Ok(())
        }
        fn move_cursor_down(&self, _: usize) -> std::io::Result<()> {
            Ok(())
        }
        fn move_cursor_right(&self, _: usize) -> std::io::Result<()> {
            Ok(())
        }
        fn move_cursor_left(&self, _: usize) -> std::io::Result<()> {
            Ok(())
        }
        fn write_line(&self, s: &str) -> std::io::Result<()> {
            self.write_str(s)
        }
        fn write_str(&self, s: &str) -> std::io::Result<()> {
            if !s.is_empty() {
                self.0.lock().expect("the screen").push(s.to_string());
            }
            Ok(())
        }
        fn clear_line(&self) -> std::io::Result<()> {
            Ok(())
        }
        fn flush(&self) -> std::io::Result<()> {
            Ok(())
        }
    }

    /// The last line `len` (or an open-ended count) shows at `pos` done.
    fn drawn(len: Option<u64>, pos: u64) -> String {
        let screen = Screen::default();
        let target = indicatif::ProgressDrawTarget::term_like(Box::new(screen.clone()));
        let bar = Progress::styled(len, "dyn optimize: responses", target);
        bar.set_position(pos);
        bar.tick();
        let lines = screen.0.lock().expect("the screen");
        lines.iter().rev().find(|l| l.contains("dyn optimize")).cloned().unwrap_or_default()
    }

    /// A known count draws a bar with its length and an ETA; a count not known ahead (issue 27:
    /// `dyn optimize` stopped at 141/176 with an ETA of 47 s for a 4 s run) draws the count so far
    /// and the time spent, with no length that could stop short and no ETA.
    #[test]
    fn a_count_not_known_ahead_shows_no_length_and_no_eta() {
        let counted = drawn(Some(176), 141);
        assert!(counted.contains("141/176") && counted.contains("eta"), "{counted}");
        let open = drawn(None, 141);
        assert!(open.starts_with("dyn optimize: responses "), "{open}");
        assert!(open.contains(" 141 so far (") && !open.contains("eta") && !open.contains('/'), "{open}");
    }
}
