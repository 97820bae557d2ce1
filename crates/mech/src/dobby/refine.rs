//! Extremes and boundaries located between grid points, so that every verdict and every printed
//! extreme of the modulator is independent of the output step.
//!
//! The checks read a fixed check grid of [`CHECK_STEP_DEG`] (not the output grid): the largest
//! values on it bracket each candidate extremum between its two neighbours, and a golden-section
//! search on the continuous solution (closed form for synthesis, Newton from the neighbouring traced
//! state for analysis) refines it to ~1e-13 rad. A boundary (the first input angle where a condition
//! fails) is bracketed on the grid and refined by bisection.

use super::analysis::input_grid;
use super::geometry::ModulatorGeometry;
use super::kinematics::ModulatorState;
use crate::planar::Vec2;

/// Step of the check grid (deg): 1440 points per revolution, whatever the output step.
pub(crate) const CHECK_STEP_DEG: f64 = 0.25;

/// Candidate local maxima refined per quantity (the best grid maxima).
const CANDIDATES: usize = 4;

/// The check grid (rad) over one revolution from `start_deg`, both ends included.
pub(crate) fn check_grid(start_deg: f64) -> Vec<f64> {
    input_grid(start_deg, CHECK_STEP_DEG).0
}

/// A maximum with the input angle where it occurs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Extreme {
    /// The largest value (−∞ if no value was finite).
    pub value: f64,
    /// Its input angle (rad).
    pub at: f64,
}

impl Extreme {
    /// The input angle in degrees.
    pub fn at_deg(&self) -> f64 {
        self.at.to_degrees()
    }

    /// The value, or `d` if none was finite.
    pub fn value_or(&self, d: f64) -> f64 {
        if self.value.is_finite() { self.value } else { d }
    }
}

fn finite_or_neg_inf(v: f64) -> f64 {
    if v.is_nan() { f64::NEG_INFINITY } else { v }
}

/// The search's tolerance: the check grid's brackets (0.5°, 8.7e-3 rad) are closed to ~1e-13 rad.
const TOL: f64 = 2.5e-14;

/// The largest value of `f` on the bracket `[a, b]` whose end values are known (the grid's, not
/// evaluated again), by Brent's method to [`TOL`] ([`loomkin_numeric::brent_max_from`]: parabolic
/// steps, golden-section where they fail, an early end where the fall-off is quadratic, a flat
/// bracket in two evaluations).
pub(crate) fn brent_max_from(f: &dyn Fn(f64) -> f64, a: (f64, f64), b: (f64, f64)) -> Extreme {
    let m = loomkin_numeric::brent_max_from(f, a, b, TOL);
    Extreme { value: m.value, at: m.at }
}

/// The best local maxima of a grid's values `vals`: the local maxima (`≥` both neighbours; a plateau counts at every point) in decreasing
/// order of value, equal values in grid order, each dropped when it neighbours the last one kept;
/// the first [`CANDIDATES`] of them. Only the best `3·CANDIDATES` maxima are ordered: a kept
/// maximum drops at most its two neighbours, so the first [`CANDIDATES`] kept are among them (a
/// plateau, e.g. a dwell, has hundreds of local maxima, and sorting them all cost more than the
/// refinement).
///
/// `periodic`: the grid is a whole turn whose last point repeats the first
/// (n ≥ 3), so the last point is not a candidate of its own and the first one's neighbours are the
/// second and the last but one.
fn local_maxima(vals: &[f64], periodic: bool) -> Vec<usize> {
    let n = vals.len();
    let periodic = periodic && n >= 3;
    let v = |k: usize| finite_or_neg_inf(vals[k]);
    let order = |i: &usize, j: &usize| v(*j).total_cmp(&v(*i)).then(i.cmp(j));
    let before = |k: usize| if k == 0 { periodic.then(|| n - 2) } else { Some(k - 1) };
    let after = |k: usize| if k + 1 == n { None } else { Some(k + 1) };
    let points = if periodic { n - 1 } else { n };
    let mut cands: Vec<usize> = (0..points)
        .filter(|&k| before(k).is_none_or(|j| v(k) >= v(j)) && after(k).is_none_or(|j| v(k) >= v(j)))
        .collect();
    let keep = 3 * CANDIDATES;
    if cands.len() > keep {
        cands.select_nth_unstable_by(keep - 1, order);
        cands.truncate(keep);
    }
    cands.sort_by(order);
    let neighbours = |a: usize, b: usize| a.abs_diff(b) <= 1 || (periodic && a.min(b) == 0 && a.max(b) == n - 2);
    cands.dedup_by(|a, b| neighbours(*a, *b));
    cands.truncate(CANDIDATES);
    cands
}

/// Largest value of a quantity given on the grid `xs` (values `vals`) and continuously by `f`:
/// the [`CANDIDATES`] best local maxima of the grid are each refined on their two neighbouring
/// intervals. Of maxima equal to rounding (1e-12 relative), the first over the grid is reported.
pub(crate) fn refined_max(xs: &[f64], vals: &[f64], f: &dyn Fn(f64) -> f64) -> Extreme {
    refined_max_in(xs, vals, f, false)
}

/// [`refined_max`] of a quantity periodic over the grid, a whole turn whose last point repeats the
/// first: the joint of the turn (both ends) is one grid point, a local maximum when it is not below
/// the second point and the last but one, and it is refined once, on the bracket from the last
/// but one point (a turn early: `f` is evaluated before the start) to the second, as an interior
/// maximum; its location is reported within `[xs₀, xs₀ + turn)`. On the grid as an interval each
/// end was a candidate whenever it was not below its one neighbour, refined on its one-sided
/// bracket by golden steps into the end (~50 evaluations each, twice for one maximum).
pub(crate) fn refined_turn_max(xs: &[f64], vals: &[f64], f: &dyn Fn(f64) -> f64) -> Extreme {
    refined_max_in(xs, vals, f, true)
}

fn refined_max_in(xs: &[f64], vals: &[f64], f: &dyn Fn(f64) -> f64, periodic: bool) -> Extreme {
    refined_max_ordered(xs, vals, &|k| vals[k], f, periodic)
}

/// [`refined_max_in`] with the grid's candidates chosen by `order`, values in the same order as
/// the quantity's own (a strictly increasing function of them, cheaper to form), whose own values
/// `value(k)` are formed only where the search reads them: at the candidates and the ends of their
/// brackets.
fn refined_max_ordered(
    xs: &[f64],
    order: &[f64],
    value: &dyn Fn(usize) -> f64,
    f: &dyn Fn(f64) -> f64,
    periodic: bool,
) -> Extreme {
    let n = xs.len().min(order.len());
    if n == 0 {
        return Extreme { value: f64::NEG_INFINITY, at: 0.0 };
    }
    let cands = local_maxima(&order[..n], periodic);
    // Equal maxima (a law repeated over the turn gives several) are told apart by rounding alone:
    // values within 1e-12 (relative) of the best count as equal, and the first over the turn wins.
    let better = |e: &Extreme, best: &Extreme| {
        let tie = best.value.is_finite() && (e.value - best.value).abs() <= 1e-12 * best.value.abs();
        if tie { e.at < best.at } else { e.value > best.value }
    };
    let mut best = Extreme { value: f64::NEG_INFINITY, at: xs[0] };
    let last = n - 1;
    for &k in cands.iter().take(CANDIDATES) {
        let grid = Extreme { value: finite_or_neg_inf(value(k)), at: xs[k] };
        if better(&grid, &best) {
            best = grid;
        }
        if periodic && n >= 3 && k == 0 {
            // The joint of the turn: from the point before the end, a turn early, to the point
            // after the start.
            let turn = xs[last] - xs[0];
            let before = xs[last - 1] - turn;
            let mut e = brent_max_from(f, (before, value(last - 1)), (xs[1], value(1)));
            if e.at == before {
                e.at = xs[last - 1];
            } else if e.at < xs[0] {
                e.at += turn;
            }
            if better(&e, &best) {
                best = e;
            }
            continue;
        }
        let (lo, hi) = (k.saturating_sub(1), (k + 1).min(n - 1));
        if xs[hi] > xs[lo] {
            let e = brent_max_from(f, (xs[lo], value(lo)), (xs[hi], value(hi)));
            if better(&e, &best) {
                best = e;
            }
        }
    }
    best
}

/// The first input angle (rad) where `ok(x) > 0` stops holding, refined by bisection between the
/// last grid point where it holds and the first where it fails; `None` if it holds at every grid
/// point.
pub(crate) fn first_failure(xs: &[f64], ok: &dyn Fn(f64) -> f64) -> Option<f64> {
    let holds = |x: f64| ok(x) > 0.0;
    let k = xs.iter().position(|&x| !holds(x))?;
    if k == 0 {
        return Some(xs[0]);
    }
    Some(loomkin_numeric::bisect_bracket(xs[k - 1], xs[k], holds).1)
}

/// The states of one revolution on the check grid and a way to evaluate the state between them.
pub(crate) struct Revolution<'a> {
    /// Check-grid input angles (rad).
    pub xs: Vec<f64>,
    /// States on the check grid.
    pub states: Vec<ModulatorState>,
    /// Crank pin A of each state on the check grid (m), [`ModulatorState::a`].
    pub pins: Vec<Vec2>,
    /// The state at any input angle within the revolution (`None` where it cannot be solved).
    pub eval: Box<dyn Fn(f64) -> Option<ModulatorState> + 'a>,
    /// φ6 and its first two derivatives at any input angle, where they come cheaper than the
    /// whole state (synthesis: the output law itself); `None`: from [`Self::eval`].
    pub output: Option<Box<dyn Fn(f64) -> [f64; 3] + 'a>>,
}

impl Revolution<'_> {
    /// Index of the check-grid point nearest to `x` (rad).
    pub fn nearest(xs: &[f64], x: f64) -> usize {
        let n = xs.len();
        if n < 2 {
            return 0;
        }
        let h = (xs[n - 1] - xs[0]) / (n - 1) as f64;
        let k = crate::planar::round((x - xs[0]) / h);
        if k.is_finite() { (k.max(0.0) as usize).min(n - 1) } else { 0 }
    }

    /// Largest value of the quantity `q` over the revolution, refined between grid points.
    pub fn max(&self, q: &dyn Fn(&ModulatorState) -> f64) -> Extreme {
        let vals: Vec<f64> = self.states.iter().map(q).collect();
        refined_turn_max(&self.xs, &vals, &|x| (self.eval)(x).map_or(f64::NEG_INFINITY, |s| q(&s)))
    }

    /// [`Self::max`] of a quantity that also reads the crank pin A: on the grid from
    /// [`Self::pins`], between grid points from the state ([`ModulatorState::a`], the same value).
    /// The grid's candidates are chosen by `order` (the same arguments), a strictly increasing
    /// function of `q` that is cheaper to form; `q` itself is formed on the grid only where the
    /// search reads it (the candidates and their neighbours).
    pub fn max_with_pin_ordered(
        &self,
        g: &ModulatorGeometry,
        order: &dyn Fn(&ModulatorState, Vec2) -> f64,
        q: &dyn Fn(&ModulatorState, Vec2) -> f64,
    ) -> Extreme {
        let ord: Vec<f64> = self.states.iter().zip(&self.pins).map(|(s, &a)| order(s, a)).collect();
        refined_max_ordered(
            &self.xs,
            &ord,
            &|k| q(&self.states[k], self.pins[k]),
            &|x| (self.eval)(x).map_or(f64::NEG_INFINITY, |s| q(&s, s.a(g))),
            true,
        )
    }

    /// Smallest value of `q` (as an [`Extreme`] whose value is the minimum).
    pub fn min(&self, q: &dyn Fn(&ModulatorState) -> f64) -> Extreme {
        let e = self.max(&|s| -q(s));
        Extreme { value: -e.value, at: e.at }
    }

    /// [`Self::max`] of a quantity of φ6 and its derivatives alone, between grid points from
    /// [`Self::output`] where given (the same values as the states' `phi6`).
    pub fn max_output(&self, q: &dyn Fn([f64; 3]) -> f64) -> Extreme {
        let vals: Vec<f64> = self.states.iter().map(|s| q(s.phi6)).collect();
        match &self.output {
            Some(out) => refined_turn_max(&self.xs, &vals, &|x| q(out(x))),
            None => refined_turn_max(&self.xs, &vals, &|x| (self.eval)(x).map_or(f64::NEG_INFINITY, |s| q(s.phi6))),
        }
    }

    /// Smallest value of a quantity of φ6 ([`Self::max_output`]).
    pub fn min_output(&self, q: &dyn Fn([f64; 3]) -> f64) -> Extreme {
        let e = self.max_output(&|p| -q(p));
        Extreme { value: -e.value, at: e.at }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A peak narrower than the grid is found by refining its bracket: sin²-shaped bumps of height
    /// 1 and 2, the higher one between grid points.
    #[test]
    fn refined_max_does_not_depend_on_the_grid() {
        let f = |x: f64| (-(x - 1.0).powi(2) * 50.0).exp() + 2.0 * (-(x - 2.37).powi(2) * 50.0).exp();
        for n in [7usize, 13, 40, 1000] {
            let xs: Vec<f64> = (0..=n).map(|i| 3.0 * i as f64 / n as f64).collect();
            let vals: Vec<f64> = xs.iter().map(|&x| f(x)).collect();
            let e = refined_max(&xs, &vals, &f);
            assert!((e.value - 2.0).abs() < 1e-9 && (e.at - 2.37).abs() < 1e-4, "n = {n}: {e:?}");
        }
    }

    /// Two equal peaks (a law repeated twice over the turn): the first is reported, whatever
    /// rounding says. (The search's own cost and its flat and kinked brackets are tested with
    /// `loomkin_numeric::brent_max_from`.)
    #[test]
    fn equal_peaks_report_the_first() {
        let f = |x: f64| (2.0 * x).cos().powi(2) * 3.0 + 1.0;
        let xs: Vec<f64> = (0..=1440).map(|i| std::f64::consts::TAU * f64::from(i) / 1440.0 + 0.3).collect();
        let vals: Vec<f64> = xs.iter().map(|&x| f(x)).collect();
        let e = refined_max(&xs, &vals, &f);
        assert!((e.value - 4.0).abs() < 1e-14, "{e:?}");
        assert!((e.at - std::f64::consts::FRAC_PI_2).abs() < 1e-7, "the first peak after 0.3 rad: {e:?}");
    }

    /// A maximum at the joint of a turn is refined once, across the joint: at the joint itself
    /// it is reported there (its grid point ties with the refined one and comes first), just
    /// before the joint at its place near the end of the turn, in few evaluations either way;
    /// a slope falling from the last but one point through the joint is no candidate.
    #[test]
    fn maxima_at_the_joint_of_a_turn_are_refined_across_it() {
        let xs: Vec<f64> = (0..=1440).map(|i| std::f64::consts::TAU * f64::from(i) / 1440.0).collect();
        let calls = std::cell::Cell::new(0);
        for (shift, at) in [(0.0, 0.0), (-1e-3, std::f64::consts::TAU - 1e-3), (1e-3, 1e-3)] {
            let f = |x: f64| {
                calls.set(calls.get() + 1);
                2.0 * (x - shift).cos() + 0.5 * (3.0 * (x - shift)).cos()
            };
            let vals: Vec<f64> = xs.iter().map(|&x| f(x)).collect();
            calls.set(0);
            let e = refined_turn_max(&xs, &vals, &f);
            assert!((e.value - 2.5).abs() < 1e-15 && (e.at - at).abs() < 1e-7, "shift {shift}: {e:?}");
            assert!((0.0..std::f64::consts::TAU).contains(&e.at));
            if shift == 0.0 {
                assert_eq!(e.at, 0.0);
            }
            // Two candidates (the other maximum, of value 1.5, at π) of ≤ 16 evaluations each.
            assert!(calls.get() <= 32, "shift {shift}: {} evaluations", calls.get());
        }
        // Rising towards 350° through the joint: the joint is no candidate of its own.
        let f = |x: f64| (x - 350f64.to_radians()).cos();
        let vals: Vec<f64> = xs.iter().map(|&x| f(x)).collect();
        assert_eq!(local_maxima(&vals, true), vec![1400]);
        let e = refined_turn_max(&xs, &vals, &f);
        assert!((e.value - 1.0).abs() < 1e-15 && (e.at - 350f64.to_radians()).abs() < 1e-7, "{e:?}");
    }

    /// Candidates chosen by a strictly increasing function of the values (here `exp`) give the
    /// same refined maxima as the values themselves, on a grid as an interval and as a turn.
    #[test]
    fn candidates_by_an_order_match_candidates_by_value() {
        let f = |x: f64| (3.0 * x).sin() + 0.7 * (5.0 * x + 0.4).cos() + 0.2 * (11.0 * x).sin();
        for n in [40usize, 360, 1440] {
            let xs: Vec<f64> = (0..=n).map(|i| std::f64::consts::TAU * i as f64 / n as f64).collect();
            let vals: Vec<f64> = xs.iter().map(|&x| f(x)).collect();
            let ord: Vec<f64> = vals.iter().map(|v| v.exp()).collect();
            for periodic in [false, true] {
                let plain = refined_max_in(&xs, &vals, &f, periodic);
                let ordered = refined_max_ordered(&xs, &ord, &|k| vals[k], &f, periodic);
                assert_eq!(plain, ordered, "n = {n}, periodic {periodic}");
            }
        }
    }

    /// Independent route for the candidates of a turn: the candidates of the same values as an
    /// interval, the last point dropped and the first one's neighbours taken from both sides.
    #[test]
    fn local_maxima_of_a_turn_match_a_full_sort() {
        use proptest::prelude::*;
        use proptest::test_runner::{Config, TestRunner};
        let full = |vals: &[f64]| {
            let v = |k: usize| finite_or_neg_inf(vals[k]);
            let m = vals.len() - 1;
            let (prev, next) = (|k: usize| (k + m - 1) % m, |k: usize| (k + 1) % m);
            let mut c: Vec<usize> = (0..m).filter(|&k| v(k) >= v(prev(k)) && v(k) >= v(next(k))).collect();
            c.sort_by(|&i, &j| v(j).total_cmp(&v(i)).then(i.cmp(&j)));
            c.dedup_by(|a, b| next(*a) == *b || next(*b) == *a);
            c.truncate(CANDIDATES);
            c
        };
        let grid = prop::collection::vec(prop_oneof![0u8..4, Just(9)], 3..300);
        TestRunner::new(Config { cases: 500, ..Config::default() })
            .run(&grid, |g| {
                // A turn: the last point repeats the first.
                let mut vals: Vec<f64> = g.iter().map(|&k| if k == 9 { f64::NAN } else { f64::from(k) }).collect();
                vals.push(vals[0]);
                prop_assert_eq!(local_maxima(&vals, true), full(&vals));
                Ok(())
            })
            .unwrap();
    }

    /// Independent route for the partial ordering of candidates: every local maximum sorted,
    /// then the neighbours of kept ones dropped, on grids with plateaus and repeated values.
    #[test]
    fn best_local_maxima_match_a_full_sort() {
        use proptest::prelude::*;
        use proptest::test_runner::{Config, TestRunner};
        let full = |vals: &[f64]| {
            let v = |k: usize| finite_or_neg_inf(vals[k]);
            let n = vals.len();
            let mut c: Vec<usize> =
                (0..n).filter(|&k| (k == 0 || v(k) >= v(k - 1)) && (k + 1 == n || v(k) >= v(k + 1))).collect();
            c.sort_by(|&i, &j| v(j).total_cmp(&v(i)).then(i.cmp(&j)));
            c.dedup_by(|a, b| a.abs_diff(*b) <= 1);
            c.truncate(CANDIDATES);
            c
        };
        // Few distinct levels make long plateaus and many equal maxima; NaN counts as −∞.
        let grid = prop::collection::vec(prop_oneof![0u8..4, Just(9)], 1..300);
        TestRunner::new(Config { cases: 500, ..Config::default() })
            .run(&grid, |g| {
                let vals: Vec<f64> = g.iter().map(|&k| if k == 9 { f64::NAN } else { f64::from(k) }).collect();
                prop_assert_eq!(local_maxima(&vals, false), full(&vals));
                Ok(())
            })
            .unwrap();
    }

    #[test]
    fn first_failure_is_the_boundary() {
        let xs: Vec<f64> = (0..=10).map(f64::from).collect();
        let x = first_failure(&xs, &|x| 3.3 - x).unwrap();
        assert!((x - 3.3).abs() < 1e-12, "{x}");
        assert_eq!(first_failure(&xs, &|_| 1.0), None);
    }

    /// Independent route for the refined extremes of a synthesis: a scan at 1e-4° over ±0.05°
    /// around each reported location, from the closed form, agrees with the refined value to 1e-9.
    #[test]
    fn refined_synthesis_extremes_match_a_1e_4_degree_scan() {
        use crate::dobby::kinematics::{ArmAngles, state_from_phi6};
        use crate::{ModulatorGeometry, OutputLawSpec, SynthesisOptions, synthesize};
        let g = ModulatorGeometry::PAPER;
        let law = OutputLawSpec::default();
        let s = synthesize(&g, &law, &SynthesisOptions { step_deg: 30.0, ..Default::default() }).unwrap();
        let out = law.build().unwrap();
        let c = &s.summary.checks;
        let scan = |at_deg: f64, q: &dyn Fn(&ModulatorState) -> f64| {
            (-500..=500)
                .map(|i| {
                    let x = (at_deg + f64::from(i) * 1e-4).to_radians();
                    let o = out.eval(x);
                    q(&state_from_phi6(
                        &g,
                        &ArmAngles::new(&g),
                        x,
                        crate::planar::e(x),
                        [o.phi6, o.d1, o.d2],
                        (x, None),
                    )
                    .0)
                })
                .fold(f64::NEG_INFINITY, f64::max)
        };
        type Quantity<'q> = &'q dyn Fn(&ModulatorState) -> f64;
        let cases: [(f64, f64, Quantity); 4] = [
            (c.mu_b_max_deg, c.mu_b_max_at_phi2_deg, &|s| s.mu_b_deg(&g)),
            (c.mu_out_max_deg, c.mu_out_max_at_phi2_deg, &|s| s.mu_out_deg()),
            (1.0 / c.rho_b_min_m.unwrap(), c.rho_b_min_at_phi2_deg, &|s| s.kappa_b().abs()),
            (1.0 / c.rho_c_min_m.unwrap(), c.rho_c_min_at_phi2_deg, &|s| s.kappa_c().abs()),
        ];
        for (refined, at, q) in cases {
            let dense = scan(at, q);
            assert!(dense <= refined + 1e-12 * refined.abs());
            assert!((refined - dense).abs() < 1e-9 * refined.abs().max(1.0), "{refined} vs scan {dense} at {at}°");
        }
    }
}
