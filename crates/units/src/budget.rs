//! What a run may cost: an estimate of its memory and time made before it starts, and the one
//! limit every front end refuses beyond (about 1 GB and one minute).
//!
//! A command that grows with an input (`--points`, a sweep's step, a number of starts) knows
//! what one item costs — the bytes it holds per item and the seconds per item, measured by the
//! crate's benchmarks on the reference machine (2 cores) — and checks `items × cost` against
//! [`Budget::DEFAULT`] before allocating anything. The largest allowed count is derived from
//! the same figures, so the limit moves when the code gets faster or leaner, not by editing a
//! constant.
//!
//! ```
//! use loomkin_units::{Budget, Cost};
//!
//! // 10⁷ rows streamed (a block in memory) at 0.4 µs each: allowed.
//! let ok = Cost::items(1e7, 0.0, 0.4e-6);
//! assert!(Budget::DEFAULT.check("points", 10_000_000, ok).is_ok());
//! // 10⁹ rows of 600 bytes held at once: 600 GB, refused up front, naming both.
//! let e = Budget::DEFAULT.check("points", 1_000_000_000, Cost::items(1e9, 600.0, 1e-6)).unwrap_err();
//! assert_eq!(
//!     e.to_string(),
//!     "points = 1000000000 needs about 600 GB of memory and 17 min (estimate); the limit is 1 GB and 1 min"
//! );
//! ```

use std::fmt;

use serde::Serialize;

use crate::format::compact;

/// An estimate of what a run needs: peak memory in bytes and wall time in seconds.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Cost {
    /// Memory held at the peak (bytes).
    pub bytes: f64,
    /// Wall time (seconds).
    pub seconds: f64,
}

impl Cost {
    /// `n` items, each holding `bytes_each` until the end and taking `seconds_each`.
    pub fn items(n: f64, bytes_each: f64, seconds_each: f64) -> Self {
        Self { bytes: n * bytes_each, seconds: n * seconds_each }
    }

    /// `n` items, each holding `bytes_each` until the end and taking `cpu_seconds_each` of one
    /// core as a benchmark measures it on an idle reference machine: the time is taken as
    /// [`Cost::SHARED`] times that, the machine shared with one other job. Every per-item time
    /// measured by a bench enters an estimate through this one rule.
    pub fn cpu_items(n: f64, bytes_each: f64, cpu_seconds_each: f64) -> Self {
        Self::items(n, bytes_each, Self::SHARED * cpu_seconds_each)
    }

    /// How much longer than a benchmark's single-core figure an item is estimated to take: 2, the
    /// reference machine (2 cores) shared with one other job. An estimate is a guard against runs
    /// far beyond the budget, so it errs long by this factor and no more.
    pub const SHARED: f64 = 2.0;

    /// Both costs added (two phases, or a fixed part and a part per item).
    pub fn plus(self, other: Cost) -> Self {
        Self { bytes: self.bytes + other.bytes, seconds: self.seconds + other.seconds }
    }

    /// The cost repeated `n` times (an outer loop around a measured inner cost; memory is
    /// assumed held by every repetition).
    pub fn times(self, n: f64) -> Self {
        Self { bytes: self.bytes * n, seconds: self.seconds * n }
    }
}

/// The most a run may take: a request estimated beyond it is refused before it starts.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Budget {
    /// Peak memory (bytes).
    pub bytes: f64,
    /// Wall time (seconds).
    pub seconds: f64,
}

impl Budget {
    /// About 1 GB and one minute: a command-line run or a workbench request.
    pub const DEFAULT: Budget = Budget { bytes: 1e9, seconds: 60.0 };

    /// Reads a budget for a batch task, `MEMORY,TIME` (`--budget 64GB,2h`): memory in bytes with
    /// a decimal prefix (`500MB`, `64GB`, `1.5TB`; `kB`, `MB`, `GB`, `TB`, `PB`, case-insensitive,
    /// `B` optional), time in `s`, `min`, `h` or `d` (`90s`, `30min`, `2h`, `1.5d`). Each must be
    /// at least the interactive [`Budget::DEFAULT`]'s (a budget lifts the guard, never tightens
    /// it) and finite.
    pub fn parse(field: &str, text: &str) -> Result<Self, BudgetParseError> {
        let bad = |what: &str| BudgetParseError {
            field: field.into(),
            text: text.chars().take(80).collect(),
            reason: what.to_string(),
        };
        let (mem, time) = text.split_once(',').ok_or_else(|| bad("no comma"))?;
        let number = |t: &str, units: &[(&str, f64)], what: &str| -> Result<f64, BudgetParseError> {
            let t = t.trim().to_ascii_lowercase();
            let (unit, scale) = units
                .iter()
                .filter(|(u, _)| t.ends_with(u))
                .max_by_key(|(u, _)| u.len())
                .ok_or_else(|| bad(&format!("{what} has no unit")))?;
            let v: f64 =
                t[..t.len() - unit.len()].trim().parse().map_err(|_| bad(&format!("{what} is not a number")))?;
            let v = v * scale;
            if v.is_finite() { Ok(v) } else { Err(bad(&format!("{what} is not finite"))) }
        };
        let bytes = number(
            mem,
            &[
                ("kb", 1e3),
                ("mb", 1e6),
                ("gb", 1e9),
                ("tb", 1e12),
                ("pb", 1e15),
                ("k", 1e3),
                ("m", 1e6),
                ("g", 1e9),
                ("t", 1e12),
            ],
            "memory",
        )?;
        let seconds = number(time, &[("s", 1.0), ("min", 60.0), ("h", 3600.0), ("d", 86_400.0)], "time")?;
        if bytes < Self::DEFAULT.bytes || seconds < Self::DEFAULT.seconds {
            return Err(bad("below the interactive limit"));
        }
        Ok(Self { bytes, seconds })
    }

    /// Whether `cost` fits.
    pub fn allows(&self, cost: Cost) -> bool {
        // `!(a > b)` so that a NaN estimate (a corrupt input) is refused too.
        cost.bytes <= self.bytes && cost.seconds <= self.seconds
    }

    /// `Ok` if `cost`, the estimate for `field = value`, fits; else the error naming both.
    /// `value` is printed as given (`10000000`, `1:360:0.001`).
    pub fn check(&self, field: &str, value: impl fmt::Display, cost: Cost) -> Result<(), BudgetError> {
        if self.allows(cost) {
            Ok(())
        } else {
            Err(BudgetError { field: field.into(), value: value.to_string(), cost, budget: *self, lifted_by: None })
        }
    }
}

/// A `--budget` that cannot be read, or that is below the interactive limit.
#[derive(Debug, Clone, PartialEq)]
pub struct BudgetParseError {
    /// The flag or key.
    pub field: String,
    /// The text given (cut to 80 characters).
    pub text: String,
    /// What is wrong.
    pub reason: String,
}

impl fmt::Display for BudgetParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}: cannot read '{}' ({}): expected MEMORY,TIME such as 64GB,2h, memory ≥ {} and time ≥ {}",
            self.field,
            self.text,
            self.reason,
            bytes_text(Budget::DEFAULT.bytes),
            seconds_text(Budget::DEFAULT.seconds)
        )
    }
}

impl std::error::Error for BudgetParseError {}

impl crate::range::FieldError for BudgetParseError {
    fn field(&self) -> Option<&str> {
        Some(&self.field)
    }
}

/// A run estimated to need more memory or time than the [`Budget`] allows.
///
/// One line: `points = 1000000000 needs about 600 GB of memory and 17 min (estimate); the limit
/// is 1 GB and 1 min`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BudgetError {
    /// The input that makes the run large (`points`, `step_deg`, `starts`).
    pub field: String,
    /// Its value, as given.
    pub value: String,
    /// The estimate.
    pub cost: Cost,
    /// The limit.
    pub budget: Budget,
    /// How the user lifts the limit, in the front end's words (`--budget MEMORY,TIME` on the
    /// command line); `None` where nothing lifts it (a workbench request).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lifted_by: Option<String>,
}

impl BudgetError {
    /// The same error under a front end's name for the input (`--points` for `points`) and with
    /// the setting that lifts the limit (`--budget MEMORY,TIME`), as a front end maps its flags.
    pub fn in_front_end(mut self, field: impl Into<String>, lifted_by: impl Into<String>) -> Self {
        self.field = field.into();
        self.lifted_by = Some(lifted_by.into());
        self
    }
}

impl fmt::Display for BudgetError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // What passes the limit is said; an amount within it is left out (a streamed table
        // holds a buffer: `needs about 0 bytes of memory and 4.4 h` read as an overflow).
        let memory = format!("{} of memory", bytes_text(self.cost.bytes));
        let time = seconds_text(self.cost.seconds);
        let needs = match (self.cost.bytes <= self.budget.bytes, self.cost.seconds <= self.budget.seconds) {
            (true, false) => time,
            (false, true) => memory,
            _ => format!("{memory} and {time}"),
        };
        write!(
            f,
            "{} = {} needs about {needs} (estimate); the limit is {} and {}",
            self.field,
            self.value,
            bytes_text(self.budget.bytes),
            seconds_text(self.budget.seconds)
        )?;
        match &self.lifted_by {
            Some(how) => write!(f, " ({how} lifts it)"),
            None => Ok(()),
        }
    }
}

impl std::error::Error for BudgetError {}

impl crate::range::FieldError for BudgetError {
    fn field(&self) -> Option<&str> {
        Some(&self.field)
    }
}

/// `600 GB`, `48 MB`, `2 kB`: two significant digits at most, decimal prefixes.
pub fn bytes_text(b: f64) -> String {
    if !b.is_finite() {
        return "more than can be counted".into();
    }
    let units = [(1e15, "PB"), (1e12, "TB"), (1e9, "GB"), (1e6, "MB"), (1e3, "kB")];
    match units.iter().find(|(u, _)| b >= *u) {
        Some((u, name)) => format!("{} {name}", two_digits(b / u)),
        None => format!("{} bytes", b.round()),
    }
}

/// `17 min`, `1 min`, `45 s`, `0.2 s`, `3.2 h`, `2 days`.
pub fn seconds_text(s: f64) -> String {
    if !s.is_finite() {
        return "longer than can be counted".into();
    }
    match s {
        s if s >= 86_400.0 * 2.0 => format!("{} days", two_digits(s / 86_400.0)),
        s if s >= 3600.0 => format!("{} h", two_digits(s / 3600.0)),
        s if s >= 60.0 => format!("{} min", two_digits(s / 60.0)),
        s => format!("{} s", two_digits(s)),
    }
}

/// Two significant digits, no trailing zeros (`17`, `1.5`, `0.25`, `600`).
fn two_digits(v: f64) -> String {
    let r: f64 = format!("{v:.1e}").parse().unwrap_or(v);
    compact(r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texts_are_short() {
        assert_eq!(bytes_text(6e11), "600 GB");
        assert_eq!(bytes_text(4.8e7), "48 MB");
        assert_eq!(bytes_text(1e9), "1 GB");
        assert_eq!(bytes_text(12.0), "12 bytes");
        assert_eq!(seconds_text(1000.0), "17 min");
        assert_eq!(seconds_text(0.25), "0.25 s");
        assert_eq!(seconds_text(60.0), "1 min");
        assert_eq!(seconds_text(3.0 * 86_400.0), "3 days");
        assert_eq!(seconds_text(f64::INFINITY), "longer than can be counted");
    }

    #[test]
    fn budgets_parse_and_only_lift_the_limit() {
        assert_eq!(Budget::parse("budget", "64GB,2h").unwrap(), Budget { bytes: 64e9, seconds: 7200.0 });
        assert_eq!(Budget::parse("budget", "1.5tb, 30min").unwrap(), Budget { bytes: 1.5e12, seconds: 1800.0 });
        assert_eq!(Budget::parse("budget", "2G,1d").unwrap(), Budget { bytes: 2e9, seconds: 86_400.0 });
        assert_eq!(Budget::parse("budget", "1GB,60s").unwrap(), Budget::DEFAULT);
        for bad in ["64GB", "64,2h", "64GB,2", "x GB,2h", "500MB,2h", "64GB,30s", "1e400GB,1h"] {
            let e = Budget::parse("budget", bad).unwrap_err().to_string();
            assert!(e.starts_with("budget"), "{bad}: {e}");
        }
    }

    #[test]
    fn the_limit_is_inclusive_and_nan_is_refused() {
        let b = Budget::DEFAULT;
        assert!(b.allows(Cost { bytes: 1e9, seconds: 60.0 }));
        assert!(!b.allows(Cost { bytes: 1.0001e9, seconds: 1.0 }));
        assert!(!b.allows(Cost { bytes: 1.0, seconds: 61.0 }));
        assert!(!b.allows(Cost { bytes: f64::NAN, seconds: 1.0 }));
        let e = b.check("step_deg", compact(1e-7), Cost::items(3.6e9, 8.0, 1e-7)).unwrap_err();
        assert_eq!(
            e.to_string(),
            "step_deg = 1e-7 needs about 29 GB of memory and 6 min (estimate); the limit is 1 GB and 1 min"
        );
        use crate::FieldError;
        assert_eq!(e.field(), Some("step_deg"));
        // Only what passes the limit is named: a streamed table's few bytes are not "0 bytes".
        let e = b.check("points", 4_294_967_297u64, Cost::items(4_294_967_297.0, 0.0, 3.66e-6)).unwrap_err();
        assert_eq!(e.to_string(), "points = 4294967297 needs about 4.4 h (estimate); the limit is 1 GB and 1 min");
        let e = b.check("points", 7, Cost { bytes: 2e9, seconds: 1.0 }).unwrap_err();
        assert_eq!(e.to_string(), "points = 7 needs about 2 GB of memory (estimate); the limit is 1 GB and 1 min");
        let e = b.check("points", 7, Cost { bytes: f64::NAN, seconds: 1.0 }).unwrap_err();
        assert!(e.to_string().contains("needs about more than can be counted of memory (estimate)"), "{e}");
        // A front end names its flag and what lifts the limit; the key stays the library's
        // until then.
        let e = b.check("points", 7, Cost { bytes: 2e9, seconds: 1.0 }).unwrap_err();
        assert_eq!(e.lifted_by, None);
        let e = e.in_front_end("--points", "--budget MEMORY,TIME");
        assert_eq!(
            e.to_string(),
            "--points = 7 needs about 2 GB of memory (estimate); the limit is 1 GB and 1 min (--budget MEMORY,TIME lifts it)"
        );
        assert_eq!(e.field(), Some("--points"));
    }
}
