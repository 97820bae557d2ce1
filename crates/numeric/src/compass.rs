//! Compass search: a derivative-free local minimisation over a box, one coordinate at a time.

/// The sweeps over the coordinates at one step length before the step is halved regardless.
pub const COMPASS_SWEEPS: usize = 50;

/// Minimises `f` from `x` (where `f` is `fx`) by compass search: for each step length of `steps`
/// in turn (longest first), sweep the coordinates in order, trying `x[j] + step` then
/// `x[j] − step`, each clamped into `[lo[j], hi[j]]`; a trial is taken when it lowers `f` by more
/// than `10⁻¹²` of `|f|` and `ok` accepts it (`ok` is asked only for trials that improve, so an
/// expensive constraint is evaluated as little as possible); after a taken trial the sweep goes on
/// with the next coordinate. The sweeps repeat until one takes nothing (at most
/// [`COMPASS_SWEEPS`] times), then the next step length starts. Returns the best point and its
/// value. `state` is handed to `f`, `ok` and `stage` (called before each step length), so the
/// three can share a cache; the first error of `f` or `ok` ends the search.
///
/// The result is a point from which no single-coordinate move of the last step improves: a local
/// minimum on that grid within the box and the constraint.
///
/// ```
/// // (x − 1.3)² + 2(y + 0.6)² on [−2, 2]², keeping x + y ≥ 0.8.
/// let f = |_: &mut (), p: &[f64]| Ok::<_, ()>((p[0] - 1.3).powi(2) + 2.0 * (p[1] + 0.6).powi(2));
/// let ok = |_: &mut (), p: &[f64]| Ok(p[0] + p[1] >= 0.8);
/// let steps = [0.5, 0.25, 0.125, 0.0625];
/// let x0 = vec![1.0, 1.0];
/// let f0 = f(&mut (), &x0)?;
/// let (x, fx) =
///     loomkin_numeric::compass_min(&mut (), x0, f0, &steps, &[-2.0; 2], &[2.0; 2], f, ok, |_| {})?;
/// assert!(x[0] + x[1] >= 0.8 && fx < f0);
/// # Ok::<(), ()>(())
/// ```
pub fn compass_min<S, E>(
    state: &mut S,
    mut x: Vec<f64>,
    mut fx: f64,
    steps: &[f64],
    lo: &[f64],
    hi: &[f64],
    mut f: impl FnMut(&mut S, &[f64]) -> Result<f64, E>,
    mut ok: impl FnMut(&mut S, &[f64]) -> Result<bool, E>,
    mut stage: impl FnMut(&mut S),
) -> Result<(Vec<f64>, f64), E> {
    for &step in steps {
        stage(state);
        for _sweep in 0..COMPASS_SWEEPS {
            let mut improved = false;
            for j in 0..x.len() {
                for dir in [1.0, -1.0] {
                    let mut y = x.clone();
                    y[j] = (x[j] + dir * step).clamp(lo[j], hi[j]);
                    if y[j] == x[j] {
                        continue;
                    }
                    let fy = f(state, &y)?;
                    if fy < fx - 1e-12 * fx.abs().max(1e-300) && ok(state, &y)? {
                        (x, fx) = (y, fy);
                        improved = true;
                        break;
                    }
                }
            }
            if !improved {
                break;
            }
        }
    }
    Ok((x, fx))
}
