//! Stopping a long computation from outside: one flag every long loop of the libraries checks.
//!
//! A front end that may abandon a computation (the workbench when its client hangs up or the
//! request's time budget is spent, Python on Ctrl-C) makes a [`StopFlag`], hands a clone to the
//! computation and sets it from another thread. The computation checks it between its units of
//! work (an objective evaluation, a search step) with [`StopFlag::check`] and returns
//! [`Stopped`] at the next check, so it ends within one unit of work of the request.
//!
//! ```
//! use loomkin_units::{StopFlag, Stopped};
//!
//! fn count_up(n: u64, stop: &StopFlag) -> Result<u64, Stopped> {
//!     let mut sum = 0;
//!     for i in 0..n {
//!         stop.check()?; // one unit of work between checks
//!         sum += i;
//!     }
//!     Ok(sum)
//! }
//!
//! let stop = StopFlag::default();
//! assert_eq!(count_up(10, &stop), Ok(45));
//! stop.clone().stop(); // from another thread, through a clone
//! assert_eq!(count_up(10, &stop), Err(Stopped));
//! ```

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// A flag shared between a long computation and whoever may stop it; clones share the flag.
#[derive(Debug, Clone, Default)]
pub struct StopFlag(Arc<AtomicBool>);

impl StopFlag {
    /// Asks the computation to stop (it ends at its next check).
    pub fn stop(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Whether a stop was asked for.
    pub fn is_set(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    /// `Err(Stopped)` once a stop was asked for: the check a long loop makes between its units of
    /// work.
    pub fn check(&self) -> Result<(), Stopped> {
        if self.is_set() { Err(Stopped) } else { Ok(()) }
    }
}

/// Runs a stoppable computation to its end: `f` gets a flag no one else holds, so it is never set
/// and `f` cannot end with [`Stopped`]. The plain form of a `…_until` function is this call.
pub fn to_the_end<T>(f: impl FnOnce(&StopFlag) -> Result<T, Stopped>) -> T {
    match f(&StopFlag::default()) {
        Ok(out) => out,
        Err(_) => unreachable!("a stop flag no one else holds was set"),
    }
}

impl PartialEq for StopFlag {
    /// Two flags are equal when they are the same flag.
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// A computation ended early because its [`StopFlag`] was set: the caller that set it knows why
/// (a client gone, a time budget spent) and words the refusal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("stopped before it finished (asked to stop)")]
pub struct Stopped;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_clone_set_on_another_thread_stops_the_loop() {
        let stop = StopFlag::default();
        assert!(stop.check().is_ok() && !stop.is_set());
        let other = stop.clone();
        assert_eq!(other, stop);
        assert_ne!(StopFlag::default(), stop, "a new flag is another flag");
        std::thread::spawn(move || other.stop()).join().unwrap();
        assert!(stop.is_set());
        assert_eq!(stop.check(), Err(Stopped));
    }

    /// The flag handed in is a fresh one: a loop that checks it runs to its end.
    #[test]
    fn to_the_end_hands_in_an_unset_flag() {
        let n = to_the_end(|stop| {
            let mut n = 0;
            while n < 1000 {
                stop.check()?;
                n += 1;
            }
            Ok(n)
        });
        assert_eq!(n, 1000);
    }
}
