//! `loomkin`: design and check the motion of a loom's mechanisms from the command line.
//!
//! The binary only parses arguments, calls the libraries and prints. Bad input and usage errors
//! exit with code 2 and one line on stderr; other failures (an unwritable file) exit with 1.

mod cam;
mod cycle;
mod dobby;
mod dobby_tolerance;
mod draws;
mod drive;
mod dynamics;
#[cfg(test)]
mod fields_doc;
#[cfg(test)]
mod flag_fields;
#[cfg(test)]
mod front_end_literals;
mod insert;
mod insert_air;
mod law;
mod loom;
mod loom_servo;
mod merge;
mod output;
mod pick;
mod pick_montecarlo;
#[cfg(test)]
mod python_fields;
#[cfg(test)]
mod range_ends;
mod serve;
mod servo;
mod servo_check;
mod shard;
mod shed;
mod sley;
mod util;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use std::process::ExitCode;

/// loomkin — motion design for weaving machines (laws, servo drives, picking, dobby, shedding).
#[derive(Debug, Parser)]
#[command(name = "loomkin", version, about, long_about = None, max_term_width = 110)]
struct Cli {
    /// Lift the per-run limit (about 1 GB and 1 min, estimated before a run starts) for a batch task:
    /// MEMORY,TIME such as 64GB,2h; also the variable LOOMKIN_BUDGET. Goes before the command.
    #[arg(long, value_name = "MEMORY,TIME", value_parser = parse_budget)]
    budget: Option<loomkin_units::Budget>,
    #[command(subcommand)]
    command: Command,
}

fn parse_budget(text: &str) -> Result<loomkin_units::Budget, String> {
    loomkin_units::Budget::parse("budget", text).map_err(|e| e.to_string())
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Normalised motion laws: catalogue, metrics, samples, plots.
    #[command(subcommand)]
    Law(law::LawCommand),
    /// A machine cycle (dwell / rise / dwell / return) from a TOML file, in physical units.
    Cycle(cycle::CycleArgs),
    /// Shuttle picking dynamics: compound law design, actual motion under loom settings, sweeps.
    #[command(subcommand)]
    Pick(pick::PickCommand),
    /// Servo motion laws from definition points: spline law, drive torque, controller export, optimisation.
    #[command(subcommand)]
    Servo(servo::ServoCommand),
    /// Shedding (heald-frame) laws: dwell criteria, experiment tables, Pareto choice of a law.
    #[command(subcommand)]
    Shed(shed::ShedCommand),
    /// Rotary-dobby modulator: cam analysis, conjugate-cam synthesis, plots, α sweep.
    #[command(subcommand)]
    Dobby(dobby::DobbyCommand),
    /// From a law to a part: controller cam tables.
    #[command(subcommand)]
    Cam(cam::CamCommand),
    /// Elastic follower dynamics: response at speed, residual vibration, sweeps, spectra, quiet laws.
    #[command(subcommand, name = "dyn")]
    Dyn(dynamics::DynCommand),
    /// The whole loom: weave pattern (WIF, lift plan), shed geometry, shedding torque, stagger, timing diagram.
    #[command(subcommand)]
    Loom(loom::LoomCommand),
    /// The sley (batten) linkage: reed motion, back dwell, forces and crank torque; a four-bar for a stroke and dwell.
    #[command(subcommand)]
    Sley(sley::SleyCommand),
    /// The main shaft: reduced inertia of the mechanisms, speed ripple under a motor, flywheel.
    #[command(subcommand)]
    Drive(drive::DriveCommand),
    /// Weft insertion: the time budget of any carrier; rapier drives and their clearance in the shed.
    #[command(subcommand)]
    Insert(insert::InsertCommand),
    /// The parts of a sharded run (--parts DIR) checked and joined into the one-machine output.
    Merge(merge::MergeArgs),
    /// The workbench: a local web page with live plots and draggable definition points (127.0.0.1 only).
    Serve(serve::ServeArgs),
}

fn run(cli: Cli) -> anyhow::Result<()> {
    let budget = match (cli.budget, std::env::var("LOOMKIN_BUDGET")) {
        (Some(b), _) => b,
        (None, Ok(text)) if !text.is_empty() => loomkin_units::Budget::parse("LOOMKIN_BUDGET", &text)?,
        _ => loomkin_units::Budget::DEFAULT,
    };
    util::set_budget(budget);
    match cli.command {
        Command::Law(cmd) => law::run(cmd),
        Command::Cycle(args) => cycle::run(args),
        Command::Pick(cmd) => pick::run(cmd),
        Command::Servo(cmd) => servo::run(cmd),
        Command::Shed(cmd) => shed::run(cmd),
        Command::Dobby(cmd) => dobby::run(cmd),
        Command::Cam(cmd) => cam::run(cmd),
        Command::Dyn(cmd) => dynamics::run(cmd),
        Command::Loom(cmd) => loom::run(cmd),
        Command::Sley(cmd) => sley::run(cmd),
        Command::Drive(cmd) => drive::run(cmd),
        Command::Insert(cmd) => insert::run(cmd),
        Command::Merge(args) => merge::run(args),
        Command::Serve(args) => serve::run(args),
    }
}

/// Longest error message printed (characters): a message that quotes a huge input (a TOML key of
/// a megabyte, an argument of the same size) is cut in the middle, so the line stays readable.
const MAX_MESSAGE_CHARS: usize = 600;

/// `text` cut to [`MAX_MESSAGE_CHARS`], keeping its start and end around `…`.
fn cut(text: &str) -> String {
    let n = text.chars().count();
    if n <= MAX_MESSAGE_CHARS {
        return text.to_string();
    }
    let head: String = text.chars().take(MAX_MESSAGE_CHARS / 2).collect();
    let tail: String = text.chars().skip(n - MAX_MESSAGE_CHARS / 2 + 40).collect();
    format!("{head} … ({} characters cut) … {tail}", n - MAX_MESSAGE_CHARS + 40)
}

/// Every subcommand takes `--speed-rpm -5` as a value (and refuses it with its range) rather than
/// as an unknown flag `-5`.
fn negatives_allowed(cmd: clap::Command) -> clap::Command {
    let names: Vec<String> = cmd.get_subcommands().map(|s| s.get_name().to_string()).collect();
    names.into_iter().fold(cmd.allow_negative_numbers(true), |c, n| c.mut_subcommand(n, negatives_allowed))
}

/// A negative number with a negative exponent (`--speed-rpm -1e-300`) joined to the long option
/// before it (`--speed-rpm=-1e-300`): clap takes `-1e-3` as a number but `-1e-300`'s second `-`
/// makes it read as short flags (`unexpected argument '-1'`), so the value would not reach its
/// range check.
fn glue_negative_values(args: impl IntoIterator<Item = std::ffi::OsString>) -> Vec<std::ffi::OsString> {
    let mut out: Vec<std::ffi::OsString> = Vec::new();
    for arg in args {
        let glue = match (out.last().and_then(|p| p.to_str()), arg.to_str()) {
            (Some(prev), Some(a)) => {
                out.len() > 1
                    && prev.starts_with("--")
                    && prev.len() > 2
                    && !prev.contains('=')
                    && a.starts_with('-')
                    && a[1..].contains('-')
                    && a.parse::<f64>().is_ok()
            }
            _ => false,
        };
        if glue {
            let prev = out.pop().unwrap_or_default();
            let mut joined = prev;
            joined.push("=");
            joined.push(&arg);
            out.push(joined);
        } else {
            out.push(arg);
        }
    }
    out
}

/// One line for a command group given without its subcommand, from clap's help text: the
/// group's path (its `Usage:` line) and the subcommands it takes.
fn missing_subcommand(help: &str) -> String {
    let path: Vec<&str> = help
        .lines()
        .find_map(|l| l.trim().strip_prefix("Usage: "))
        .map(|u| u.split_whitespace().take_while(|w| !w.starts_with(['<', '['])).collect())
        .unwrap_or_default();
    let mut cmd = Cli::command();
    for name in path.iter().skip(1) {
        match cmd.find_subcommand(name) {
            Some(c) => cmd = c.clone(),
            None => break,
        }
    }
    let subs: Vec<&str> = cmd.get_subcommands().map(|c| c.get_name()).filter(|n| *n != "help").collect();
    format!("`{}` needs a subcommand: one of {} (see --help)", path.join(" "), subs.join(", "))
}

fn main() -> ExitCode {
    ExitCode::from(cli_main(std::env::args_os()))
}

/// The whole program for these arguments (the first is the program's name): parse, run, print,
/// and the exit code (0, 1 or 2). `main` calls it with the process's arguments; the range-end tests run it
/// in a child process of the test binary.
fn cli_main(args: impl IntoIterator<Item = std::ffi::OsString>) -> u8 {
    let args = glue_negative_values(args);
    let cli = match negatives_allowed(Cli::command()).try_get_matches_from(args).and_then(|m| Cli::from_arg_matches(&m))
    {
        Ok(cli) => cli,
        Err(e) if e.kind() == clap::error::ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            // `loomkin law` without a subcommand: name the subcommands, not the group's description.
            output::note(format_args!("loomkin: error: {}", missing_subcommand(&e.render().to_string())));
            return 2;
        }
        Err(e) if e.use_stderr() => {
            // One line: clap's first line (the error itself), without its usage block and tips.
            let text = e.render().to_string();
            let message: Vec<&str> = text
                .lines()
                .map(str::trim)
                .take_while(|l| {
                    !l.starts_with("Usage:") && !l.starts_with("For more information") && !l.starts_with("tip:")
                })
                .filter(|l| !l.is_empty())
                .collect();
            let line = message.join(" ");
            output::note(format_args!("loomkin: error: {} (see --help)", cut(line.trim_start_matches("error: "))));
            return 2;
        }
        Err(e) => {
            // --help and --version.
            let _ = e.print();
            return 0;
        }
    };
    match run(cli).and_then(|()| output::finish()) {
        Ok(()) => 0,
        // The reader of our output went away (`loomkin law list | head -1`): stop quietly.
        Err(e) if output::is_broken_pipe(&e) => 0,
        Err(e) => {
            // A part being written is dropped: a failed shard leaves no part behind.
            output::abandon_part();
            // One line: the error and its causes joined by ": ".
            output::note(format_args!("loomkin: error: {}", cut(&format!("{e:#}").replace('\n', " "))));
            util::exit_code(&e)
        }
    }
}
