//! Where the computations run: light ones (drag updates) and heavy ones (optimisation, Pareto
//! fronts, large exports) in separate bounded pools, so that a drag never waits behind an
//! optimisation.
//!
//! * Heavy: at most [`heavy_slots`] at once (the cores less one, at least one, so a core stays free
//!   for the light routes), on a thread pool of that many threads (parallel work inside a heavy
//!   computation stays there); beyond that the answer is at once `503` with `Retry-After`. Each heavy
//!   computation carries a [`StopFlag`] that is set when its client goes away (the request future
//!   is dropped) or when its time budget [`HEAVY_BUDGET`] is spent; the optimiser checks it.
//! * Light: at most four per core run at once; more wait their turn (they are short), so the
//!   blocking threads cannot pile up.

use crate::ApiError;
use loomkin_servo::StopFlag;
use std::sync::{Arc, LazyLock};
use std::time::Duration;
use tokio::sync::Semaphore;

/// Time budget of one heavy computation; past it the computation is stopped and refused.
pub const HEAVY_BUDGET: Duration = Duration::from_secs(30);

/// Seconds a client is asked to wait before it tries a refused heavy request again.
pub const RETRY_AFTER_S: u64 = 2;

fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Heavy computations allowed at once: the cores less one, at least one.
pub fn heavy_slots() -> usize {
    cores().saturating_sub(1).max(1)
}

static HEAVY: LazyLock<Arc<Semaphore>> = LazyLock::new(|| Arc::new(Semaphore::new(heavy_slots())));
/// The threads heavy computations run on (the optimiser's parallel starts included): as many as
/// the heavy slots, so heavy work never takes the core kept for the light routes.
static HEAVY_THREADS: LazyLock<Option<rayon::ThreadPool>> =
    LazyLock::new(|| rayon::ThreadPoolBuilder::new().num_threads(heavy_slots()).build().ok());
static LIGHT: LazyLock<Arc<Semaphore>> = LazyLock::new(|| Arc::new(Semaphore::new(4 * cores())));

/// Sets the flag when dropped: the request future is dropped when its client hangs up.
struct StopOnDrop(StopFlag);

impl Drop for StopOnDrop {
    fn drop(&mut self) {
        self.0.stop();
    }
}

/// Runs a short computation on the blocking pool (at most four per core at once; the others wait):
/// CPU work does not stall the listener, and a panic (a bug, never expected) becomes a 500 answer
/// instead of a dropped connection.
pub(crate) async fn light<T: Send + 'static>(
    f: impl FnOnce() -> Result<T, ApiError> + Send + 'static,
) -> Result<T, ApiError> {
    let permit = LIGHT.clone().acquire_owned().await.map_err(|e| ApiError::Internal(e.to_string()))?;
    tokio::task::spawn_blocking(move || {
        let _permit = permit;
        f()
    })
    .await
    .map_err(|e| ApiError::Internal(format!("the computation failed: {e}")))?
}

/// Runs a heavy computation in the bounded heavy pool, or refuses it with 503 and `Retry-After`
/// when every slot is taken. The computation gets a [`StopFlag`] to check between its units of work
/// (the libraries' long loops take it); it is set when the client goes away or after
/// [`HEAVY_BUDGET`], and a computation stopped by the budget is refused (422) with the budget named,
/// whatever it returned.
pub(crate) async fn heavy<T: Send + 'static>(
    f: impl FnOnce(&StopFlag) -> Result<T, ApiError> + Send + 'static,
) -> Result<T, ApiError> {
    heavy_within(HEAVY_BUDGET, f).await
}

/// [`heavy`] with another time budget.
async fn heavy_within<T: Send + 'static>(
    budget: Duration,
    f: impl FnOnce(&StopFlag) -> Result<T, ApiError> + Send + 'static,
) -> Result<T, ApiError> {
    let permit = HEAVY.clone().try_acquire_owned().map_err(|_| ApiError::Busy { retry_after_s: RETRY_AFTER_S })?;
    let stop = StopFlag::default();
    let _on_drop = StopOnDrop(stop.clone());
    let watchdog = {
        let stop = stop.clone();
        tokio::spawn(async move {
            tokio::time::sleep(budget).await;
            stop.stop();
        })
    };
    let flag = stop.clone();
    let out = tokio::task::spawn_blocking(move || {
        let _permit = permit;
        match HEAVY_THREADS.as_ref() {
            Some(pool) => pool.install(|| f(&flag)),
            None => f(&flag),
        }
    })
    .await;
    watchdog.abort();
    // Stopped (here only by the budget: a client gone no longer awaits this): the computation's
    // answer, a `Stopped` error or a partial result, is not the answer asked for.
    if stop.is_set() {
        return Err(over_budget(budget));
    }
    out.map_err(|e| ApiError::Internal(format!("the computation failed: {e}")))?
}

/// The refusal of a computation stopped by its time budget.
fn over_budget(budget: Duration) -> ApiError {
    ApiError::Invalid {
        field: "body".into(),
        message: format!(
            "body: the computation took longer than its budget of {} s and was stopped; ask for less (fewer speeds, \
             points or picks)",
            loomkin_units::compact(budget.as_secs_f64())
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A computation that runs until it is stopped ends at the budget with the budget's refusal,
    /// not with its own answer.
    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn the_budget_stops_the_computation_inside() {
        let checks = Arc::new(std::sync::atomic::AtomicUsize::new(0));
        let seen = checks.clone();
        let budget = Duration::from_millis(150);
        let out = heavy_within(budget, move |stop| {
            // One unit of work between checks, as a library loop does.
            while stop.check().is_ok() {
                seen.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                std::thread::sleep(Duration::from_millis(1));
            }
            Ok("finished")
        })
        .await;
        assert_eq!(out, Err(over_budget(budget)));
        assert!(checks.load(std::sync::atomic::Ordering::Relaxed) > 0);
        assert_eq!(
            over_budget(HEAVY_BUDGET).to_string(),
            "body: the computation took longer than its budget of 30 s and was stopped; ask for less (fewer speeds, \
             points or picks)"
        );
        // Within the budget, the answer is the computation's.
        assert_eq!(heavy_within(Duration::from_secs(60), |_| Ok(7)).await, Ok(7));
    }
}
