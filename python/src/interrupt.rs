//! Long computations that a notebook's interrupt (Ctrl-C, SIGINT) stops.
//!
//! Python handles a signal only when the thread holding the GIL checks for it, and a computation
//! running with the GIL released never does. So the work runs on a worker thread while the calling
//! thread waits with the GIL released in slices of 50 ms, checking Python's signals between them:
//! on an interrupt the call raises `KeyboardInterrupt` at once. [`detached`] leaves a computation
//! without a stop flag to finish on its own thread (its result dropped); [`chunks`] runs work that
//! comes in independent pieces (Monte-Carlo draws) a piece at a time and stops between pieces.

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use std::sync::mpsc::{RecvTimeoutError, channel};
use std::time::Duration;

/// How often the waiting thread checks Python's signals.
const POLL: Duration = Duration::from_millis(50);

/// Runs `work` on its own thread with the GIL released and returns its result; on Ctrl-C raises
/// `KeyboardInterrupt` within 50 ms (the abandoned work finishes on its thread, its result dropped).
pub fn detached<T: Send + 'static>(py: Python<'_>, work: impl FnOnce() -> T + Send + 'static) -> PyResult<T> {
    let (tx, rx) = channel();
    std::thread::Builder::new()
        .name("loomkin-work".into())
        .spawn(move || {
            let _ = tx.send(work());
        })
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start a thread: {e}")))?;
    // The receiver is moved into each wait and back (it is `Send`, not `Sync`).
    let mut rx = rx;
    loop {
        let (got, back) = py.detach(move || (rx.recv_timeout(POLL), rx));
        rx = back;
        match got {
            Ok(v) => return Ok(v),
            Err(RecvTimeoutError::Disconnected) => {
                return Err(PyRuntimeError::new_err("internal: the computation panicked"));
            }
            Err(RecvTimeoutError::Timeout) => py.check_signals()?,
        }
    }
}

/// Runs `work` on the range `items` cut into pieces of `piece` items, each with the GIL released
/// (the work itself may be parallel), checking Python's signals between pieces; the results in
/// order. Work whose items depend on their index only gives the same results as one call on
/// `items`.
pub fn chunks<T: Send>(
    py: Python<'_>,
    items: std::ops::Range<u64>,
    piece: u64,
    work: impl Fn(std::ops::Range<u64>) -> Vec<T> + Sync,
) -> PyResult<Vec<T>> {
    let mut out = Vec::new();
    let (mut lo, n) = (items.start, items.end);
    while lo < n {
        let hi = (lo + piece.max(1)).min(n);
        out.extend(py.detach(|| work(lo..hi)));
        py.check_signals()?;
        lo = hi;
    }
    Ok(out)
}
