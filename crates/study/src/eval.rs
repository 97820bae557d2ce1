//! Parallel evaluation of experiment tables with an optional progress bar.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use loomkin_units::{StopFlag, Stopped};
use rayon::prelude::*;
use std::io::IsTerminal;

/// Rows evaluated per parallel task (and per progress-bar update), at most: a table of fewer
/// than 64 such chunks is cut into 64 (a few thousand heavy draws still move the bar).
const CHUNK: usize = 2048;

/// Whether and how to show progress while a table is evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Progress {
    /// A bar on standard error, but only when standard error is a terminal.
    #[default]
    Auto,
    /// No bar.
    Hidden,
}

impl Progress {
    /// The bar: hidden unless `Auto` and standard error is a terminal, and drawn only once the
    /// run has lasted a second ([`Bar::inc`]), so a quick table shows nothing.
    fn bar(self, len: usize, label: &str) -> Bar {
        let bar = ProgressBar::with_draw_target(Some(len as u64), ProgressDrawTarget::hidden());
        let live = self == Progress::Auto && std::io::stderr().is_terminal();
        if live {
            if let Ok(style) = ProgressStyle::with_template("{msg} {wide_bar} {pos}/{len} ({rate}/s, eta {eta})") {
                bar.set_style(style.with_key("rate", |s: &indicatif::ProgressState, w: &mut dyn std::fmt::Write| {
                    let _ = w.write_str(&rate(s.per_sec()));
                }));
            }
            bar.set_message(label.to_string());
        }
        Bar { bar, live, start: std::time::Instant::now(), shown: std::sync::Once::new() }
    }
}

/// Rows per second as the bar shows them: whole numbers (`491`, where indicatif's `{per_sec}`
/// wrote `491.0946`), and four significant digits below one a second (`0.25`).
fn rate(per_sec: f64) -> String {
    if per_sec.is_finite() && per_sec >= 1.0 { format!("{per_sec:.0}") } else { loomkin_units::sig4(per_sec) }
}

/// A progress bar that appears after a second (see [`Progress::bar`]).
struct Bar {
    bar: ProgressBar,
    live: bool,
    start: std::time::Instant,
    shown: std::sync::Once,
}

impl Bar {
    fn inc(&self, n: u64) {
        self.bar.inc(n);
        if self.live && self.start.elapsed().as_secs_f64() > 1.0 {
            self.shown.call_once(|| self.bar.set_draw_target(ProgressDrawTarget::stderr()));
        }
    }
}

/// Evaluates `f(i)` for `i = 0 … n − 1` in parallel (rayon) and returns the results in order.
///
/// Work is split into chunks of rows; the progress bar (see [`Progress`]) advances once per
/// chunk, so its cost is negligible even for millions of cheap rows.
pub fn evaluate_indexed<R, F>(n: usize, progress: Progress, label: &str, f: F) -> Vec<R>
where
    R: Send,
    F: Fn(usize) -> R + Sync,
{
    loomkin_units::to_the_end(|stop| evaluate_indexed_until(n, progress, label, stop, f))
}

/// [`evaluate_indexed`] that looks at `stop` before each chunk of rows and ends with [`Stopped`]
/// once it is set (a client gone, a time budget spent, Ctrl-C), so a long table stops within a
/// chunk's work. Run to its end it gives [`evaluate_indexed`]'s results bit for bit.
pub fn evaluate_indexed_until<R, F>(
    n: usize,
    progress: Progress,
    label: &str,
    stop: &StopFlag,
    f: F,
) -> Result<Vec<R>, Stopped>
where
    R: Send,
    F: Fn(usize) -> R + Sync,
{
    let bar = progress.bar(n, label);
    let chunk = (n / 64).clamp(1, CHUNK);
    let chunks: Result<Vec<Vec<R>>, Stopped> = (0..n.div_ceil(chunk))
        .into_par_iter()
        .map(|c| {
            stop.check()?;
            let lo = c * chunk;
            let hi = (lo + chunk).min(n);
            let out: Vec<R> = (lo..hi).map(&f).collect();
            bar.inc((hi - lo) as u64);
            Ok(out)
        })
        .collect();
    bar.bar.finish_and_clear();
    let chunks = chunks?;
    let mut out = Vec::with_capacity(n);
    for c in chunks {
        out.extend(c);
    }
    Ok(out)
}

/// Evaluates `f` on every item in parallel, in order (see [`evaluate_indexed`]).
pub fn evaluate<T, R, F>(items: &[T], progress: Progress, label: &str, f: F) -> Vec<R>
where
    T: Sync,
    R: Send,
    F: Fn(&T) -> R + Sync,
{
    evaluate_indexed(items.len(), progress, label, |i| f(&items[i]))
}

/// Evaluates `f` on every row of a [`crate::Design`] in parallel, in order.
pub fn evaluate_design<R, F>(design: &crate::Design, progress: Progress, label: &str, f: F) -> Vec<R>
where
    R: Send,
    F: Fn(&[f64]) -> R + Sync,
{
    evaluate_indexed(design.len(), progress, label, |i| f(design.row(i)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rate reads as a whole number of rows a second (issue 27: `491.0946/s`), a slow one
    /// with its significant digits.
    #[test]
    fn the_rate_is_a_whole_number_of_rows_a_second() {
        assert_eq!(rate(491.0946), "491");
        assert_eq!(rate(1.5), "2");
        assert_eq!(rate(0.25), "0.25");
        assert_eq!(rate(0.0), "0");
    }

    #[test]
    fn keeps_order_across_chunks() {
        let n = 3 * CHUNK + 17;
        let out = evaluate_indexed(n, Progress::Hidden, "t", |i| i * i);
        assert_eq!(out.len(), n);
        assert!(out.iter().enumerate().all(|(i, &v)| v == i * i));
        let items: Vec<f64> = (0..100).map(f64::from).collect();
        let twice = evaluate(&items, Progress::Auto, "t", |x| 2.0 * x);
        assert_eq!(twice[37], 74.0);
        assert!(evaluate_indexed(0, Progress::Hidden, "t", |i| i).is_empty());
    }

    /// A set flag ends the evaluation before the chunk it is seen at; one set mid-way ends it
    /// without evaluating every row; an unset one gives the plain evaluation's rows.
    #[test]
    fn a_set_flag_stops_the_evaluation() {
        // Hundreds of chunks: far more than threads in flight when the flag is set.
        let n = 300 * CHUNK + 3;
        let stop = StopFlag::default();
        let all = evaluate_indexed_until(n, Progress::Hidden, "t", &stop, |i| i as f64 * 0.5).unwrap();
        assert_eq!(all, evaluate_indexed(n, Progress::Hidden, "t", |i| i as f64 * 0.5));
        let done = std::sync::atomic::AtomicUsize::new(0);
        let out = evaluate_indexed_until(n, Progress::Hidden, "t", &stop, |i| {
            if done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) == 10 {
                stop.stop();
            }
            i
        });
        assert_eq!(out, Err(Stopped));
        let evaluated = done.into_inner();
        assert!(evaluated < n, "{evaluated} of {n} rows evaluated after the flag was set");
        assert_eq!(evaluate_indexed_until(n, Progress::Hidden, "t", &stop, |i| i), Err(Stopped));
    }
}
