//! Simulating a scenario by either route and reading the end-of-pick values.

use crate::closed::{CANCELLATION_LIMIT, PaperConstants};
use crate::ode::OdeTrajectory;
use crate::scenario::Scenario;
use crate::{Mechanism, Nominal, PickError, Result, Settings, State};
use loomkin_units::{Field, Range};
use serde::{Deserialize, Serialize};

/// Which route computes the actual motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// The paper's closed form (eqs. 29–47, corrected). Falls back to [`Method::Ode`] with a
    /// note when it cannot answer (resonance, or a cam law other than the compound one).
    #[default]
    Closed,
    /// Numerical integration of eq. 28 (DOP853, rtol 1e-13).
    Ode,
}

impl Method {
    /// `closed` or `ode`.
    pub fn name(&self) -> &'static str {
        match self {
            Method::Closed => "closed",
            Method::Ode => "ode",
        }
    }
}

/// What ended the pick.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PickEnd {
    /// The cam reached the end of its rise, u = T' (the paper's eq. 47).
    CamEnd,
    /// The shuttle left the picker earlier: the contact force m·ẍ + F₀ fell to zero.
    Separation,
}

/// End-of-pick values of one scenario (SI; names carry units).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Outcome {
    /// Duration of the pick in real time, from the shuttle's start, s.
    pub t_end_s: f64,
    /// Delay t₀ = u₀/q between the designed start and the shuttle's start (the play), s.
    pub t0_s: f64,
    /// Distance travelled by the shuttle during the pick, x(T), m.
    pub distance_m: f64,
    /// Shuttle velocity at the end of the pick, ẋ(T), m/s.
    pub velocity_m_s: f64,
    /// Shuttle acceleration at the end of the pick, ẍ(T), m/s².
    pub accel_end_m_s2: f64,
    /// Largest shuttle acceleration during the pick, m/s².
    pub accel_peak_m_s2: f64,
    /// Time of the largest acceleration, s.
    pub t_peak_s: f64,
    /// What ended the pick.
    pub end: PickEnd,
    /// Required velocity V_r at this loom speed, m/s.
    pub required_velocity_m_s: f64,
    /// (ẋ(T)/V_r − 1)·100, percent.
    pub velocity_vs_required_pct: f64,
    /// The route that answered.
    pub method: Method,
    /// Why the closed form did not answer, when it was asked and could not (left out of the JSON
    /// when it did).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
    /// B' at the setting, s².
    pub b_s2: f64,
    /// C' at the setting.
    pub c: f64,
    /// D' at the setting, m.
    pub d_m: f64,
    /// ψ = √((C'+1)/B'), 1/s.
    pub natural_1_s: f64,
    /// Play referred to the picker, s₀ = s'₀·l/k, m.
    pub play_picker_m: f64,
}

/// One row of a time history: the picker's nominal and the shuttle's actual motion.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Sample {
    /// Real time from the shuttle's start, s.
    pub t_s: f64,
    /// Nominal motion (picker, cam side).
    pub nominal: Nominal,
    /// Actual motion (shuttle).
    pub actual: State,
}

/// A simulated pick with its time history.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct History {
    /// End-of-pick values.
    pub outcome: Outcome,
    /// Evenly spaced samples from 0 to `outcome.t_end_s`.
    pub samples: Vec<Sample>,
}

impl History {
    /// `points`: samples of a pick's history, both ends included. Two are the least that span the
    /// pick; 10⁶ (some 100 MB of samples) the most; 201 draw a smooth curve for a table.
    pub const POINTS: Field = Field::count(
        "points",
        Range::closed(2.0, 1e6, ""),
        "Samples of the pick's history, both ends included: 2 span the pick, 10⁶ (about 100 MB) is the \
         most; 201 when left out (601 for a plot).",
    )
    .with_default(201.0);
    /// [`History::POINTS`] for a plot: 601 samples, a smooth curve at a plot's resolution.
    pub const PLOT_POINTS: Field = Self::POINTS.with_default(601.0);
}

/// A route made ready: either the closed form's constants or the stored integration.
enum Route<'a> {
    Closed(PaperConstants),
    Ode(OdeTrajectory<'a>),
}

impl Route<'_> {
    fn state(&self, t: f64) -> Result<State> {
        match self {
            Route::Closed(p) => Ok(p.state(t)),
            Route::Ode(o) => o.state(t),
        }
    }

    /// ȧ and ä at `t`.
    fn jerk(&self, t: f64) -> Result<[f64; 2]> {
        match self {
            Route::Closed(p) => Ok(p.jerk(t)),
            Route::Ode(o) => o.jerk(t),
        }
    }
}

/// Least number of uniform scan intervals for the closed form's extrema and events.
const SCAN: usize = 512;

/// Scan intervals per natural oscillation: a dip of the contact force below zero or a peak of
/// the acceleration lies within (1 − cos(π/32)) ≈ 0.5 % of the oscillation's amplitude of a scan
/// point, so no event or peak of the free oscillation is stepped over.
const SCAN_PER_CYCLE: f64 = 32.0;

fn prepare<'a>(sc: &'a Scenario, method: Method) -> Result<(Route<'a>, Method, Option<String>)> {
    if method == Method::Closed {
        match PaperConstants::new(sc) {
            Ok(p) => {
                // A pick far shorter than a natural period: the closed form's terms cancel.
                let loss = p.cancellation(sc.t_cam_end);
                if loss <= CANCELLATION_LIMIT {
                    return Ok((Route::Closed(p), Method::Closed, None));
                }
                let note = format!(
                    "the pick lasts {:.3e} s, {:.2e} of a natural period: the closed form's terms cancel \
                     (estimated relative rounding error {loss:.1e}, above {CANCELLATION_LIMIT:.0e}); \
                     answered by numerical integration",
                    sc.t_cam_end,
                    sc.psi() * sc.t_cam_end / (2.0 * std::f64::consts::PI)
                );
                return Ok((Route::Ode(OdeTrajectory::new(sc)?), Method::Ode, Some(note)));
            }
            Err(e @ (PickError::Resonance { .. } | PickError::NoClosedForm { .. })) => {
                let note = format!("{e}; answered by numerical integration");
                return Ok((Route::Ode(OdeTrajectory::new(sc)?), Method::Ode, Some(note)));
            }
            Err(e) => return Err(e),
        }
    }
    Ok((Route::Ode(OdeTrajectory::new(sc)?), Method::Ode, None))
}

/// The scan: times and states at which events and peaks are bracketed. The closed form uses a
/// uniform grid of at least [`SCAN`] intervals ([`SCAN_PER_CYCLE`] per natural oscillation) plus
/// the cam's joints, its states by angle recurrences; the numerical route its own steps (with the
/// uniform grid added when it took few).
fn scan(sc: &Scenario, route: &Route<'_>) -> Result<(Vec<f64>, Vec<State>)> {
    let cycles = sc.psi() * sc.t_cam_end / (2.0 * std::f64::consts::PI);
    // cycles ≤ MAX_CYCLES (checked when the scenario is built), so n stays ≤ 32 000.
    let n = SCAN.max((SCAN_PER_CYCLE * cycles).ceil() as usize);
    let uniform = |i: usize| sc.t_cam_end * i as f64 / n as f64;
    match route {
        Route::Closed(p) => {
            let mut joints = sc.joints.clone();
            joints.sort_by(f64::total_cmp);
            let mut ts = Vec::with_capacity(n + 1 + joints.len());
            let mut states = Vec::with_capacity(n + 1 + joints.len());
            p.scan_uniform(sc.t_cam_end, n, &joints, &mut ts, &mut states);
            Ok((ts, states))
        }
        Route::Ode(o) => {
            let ts: Vec<f64> = if o.len() >= SCAN / 4 {
                o.knots().to_vec()
            } else {
                let mut k: Vec<f64> = (0..=n).map(uniform).collect();
                k.extend(sc.joints.iter().copied());
                k.extend(o.knots());
                k.sort_by(f64::total_cmp);
                k.dedup();
                k
            };
            let states = ts.iter().map(|&t| o.state(t)).collect::<Result<Vec<_>>>()?;
            Ok((ts, states))
        }
    }
}

/// Bisection for the first downward zero of the contact force between `lo` (positive) and `hi`,
/// to adjacent doubles: the first instant found without contact.
fn bisect_contact(sc: &Scenario, route: &Route<'_>, lo: f64, hi: f64) -> Result<f64> {
    let contact = |t: f64| -> Result<f64> { Ok(sc.shuttle_kg * route.state(t)?.a_m_s2 + sc.checking_n) };
    Ok(loomkin_numeric::try_bisect_bracket(lo, hi, |mid| -> Result<bool> { Ok(contact(mid)? > 0.0) })?.1)
}

/// Golden-section search for the largest acceleration in [lo, hi] (when the jerk does not change
/// sign across the bracket).
fn golden_peak(route: &Route<'_>, lo: f64, hi: f64) -> Result<(f64, f64)> {
    let m = loomkin_numeric::try_golden_max(|t| -> Result<f64> { Ok(route.state(t)?.a_m_s2) }, lo, hi, None)?;
    Ok((m.at, m.value))
}

/// The largest acceleration in [lo, hi]: the zero of the jerk ȧ where it falls through zero across
/// the bracket, by Newton's method on ȧ with ä kept inside the shrinking bracket
/// ([`loomkin_numeric::try_refine_root_from`], from the secant point of the bracket's jerks), to the
/// last bits of t; golden-section search otherwise.
fn refine_peak(route: &Route<'_>, lo: f64, hi: f64) -> Result<(f64, f64)> {
    let (j_lo, j_hi) = (route.jerk(lo)?[0], route.jerk(hi)?[0]);
    if !(j_lo > 0.0 && j_hi < 0.0) {
        return golden_peak(route, lo, hi);
    }
    let start = (lo * j_hi - hi * j_lo) / (j_hi - j_lo);
    let t = loomkin_numeric::try_refine_root_from(lo, hi, start, false, |t| {
        let [j, dj] = route.jerk(t)?;
        Ok::<_, PickError>((j, dj))
    })?;
    Ok((t, route.state(t)?.a_m_s2))
}

fn evaluate(
    m: &Mechanism,
    st: &Settings,
    sc: &Scenario,
    route: &Route<'_>,
    method: Method,
    note: Option<String>,
) -> Result<Outcome> {
    let (ts, states) = scan(sc, route)?;
    // End of the pick: the cam's end, or the first downward crossing of the contact force.
    let contact = |s: &State| sc.shuttle_kg * s.a_m_s2 + sc.checking_n;
    let (mut t_end, mut end, mut n_used) = (sc.t_cam_end, PickEnd::CamEnd, ts.len());
    // One pass over the scan up to the end of the pick: the crossing, and the extremes of the
    // acceleration at the scan points before it (with the widest step between them).
    let mut armed = false;
    let (mut a_min, mut a_max, mut h_max) = (f64::INFINITY, f64::NEG_INFINITY, 0.0f64);
    let mut scan_best = (t_end, f64::NEG_INFINITY);
    for i in 0..ts.len() {
        let f = contact(&states[i]);
        if armed && f <= 0.0 {
            t_end = bisect_contact(sc, route, ts[i - 1], ts[i])?;
            end = PickEnd::Separation;
            n_used = i;
            break;
        }
        armed |= f > 0.0;
        let a = states[i].a_m_s2;
        (a_min, a_max) = (a_min.min(a), a_max.max(a));
        if a > scan_best.1 {
            scan_best = (ts[i], a);
        }
        if i > 0 {
            h_max = h_max.max(ts[i] - ts[i - 1]);
        }
    }
    let last = route.state(t_end)?;
    if n_used > 0 {
        h_max = h_max.max(t_end - ts[n_used - 1]);
    }
    (a_min, a_max) = (a_min.min(last.a_m_s2), a_max.max(last.a_m_s2));
    // Peak acceleration over [0, t_end]: every local maximum of the scan that may hide the
    // global one is refined. Between scan points h apart, an oscillation of amplitude a_osc at
    // ψ rises at most a_osc·(1 − cos(ψh/2)) above the nearer point, so any local maximum within
    // twice that of the best scan value is a candidate (many nearly equal peaks when the pick
    // lasts many natural periods). The best point so far: the first largest scan value, or the
    // end of the pick if no scan value exceeds it.
    let mut best = if scan_best.1 > last.a_m_s2 { scan_best } else { (t_end, last.a_m_s2) };
    let half_phase = (0.5 * sc.psi() * h_max).min(std::f64::consts::PI);
    let slack = (1.0 - half_phase.cos()) * (a_max - a_min) + 1e-12 * best.1.abs();
    let grid_best = best.1;
    // A plateau (the designed constant-acceleration stage) is not a peak: a candidate must stand
    // above a neighbour by more than rounding noise, or be the best scan point itself.
    let noise = 1e-9 * a_max.abs().max(a_min.abs());
    let a_at = |i: usize| if i < n_used { states[i].a_m_s2 } else { last.a_m_s2 };
    for i in 0..n_used {
        let a = states[i].a_m_s2;
        let before = if i == 0 { f64::NEG_INFINITY } else { states[i - 1].a_m_s2 };
        let local_max = a >= before && a >= a_at(i + 1) && a - before.min(a_at(i + 1)) > noise;
        if !(local_max && a >= grid_best - slack || ts[i] == best.0) {
            continue;
        }
        let lo = ts[i.saturating_sub(1)];
        let hi = if i + 1 < n_used { ts[i + 1] } else { t_end };
        if hi > lo {
            let r = refine_peak(route, lo, hi)?;
            if r.1 > best.1 {
                best = r;
            }
        }
    }
    let vr = m.required().at(st.speed_rpm);
    // The required velocity is the divisor of the percentage: a free-shed angle so small that it
    // overflows (free_shed_deg = 5e-324) leaves no finite comparison (path_m's range keeps V_r
    // from underflowing).
    let pct = (last.v_m_s / vr - 1.0) * 100.0;
    if !(vr >= f64::MIN_POSITIVE && vr.is_finite() && pct.is_finite()) {
        let r = m.required();
        let (field, value) = if vr.is_finite() { ("path_m", r.path_m) } else { ("free_shed_deg", r.free_shed_deg) };
        return Err(PickError::NonFiniteResult {
            field: field.into(),
            value,
            quantity: "the required velocity (path over the free-shed time) and the comparison with it".into(),
        });
    }
    let values = [t_end, last.x_m, last.v_m_s, last.a_m_s2, best.0, best.1, vr];
    if values.iter().any(|v| !v.is_finite()) {
        return Err(PickError::Solver { reason: "the end-of-pick values are not finite numbers".into() });
    }
    Ok(Outcome {
        t_end_s: t_end,
        t0_s: sc.t0(),
        distance_m: last.x_m,
        velocity_m_s: last.v_m_s,
        accel_end_m_s2: last.a_m_s2,
        accel_peak_m_s2: best.1,
        t_peak_s: best.0,
        end,
        required_velocity_m_s: vr,
        velocity_vs_required_pct: pct,
        method,
        note,
        b_s2: sc.k.b_s2,
        c: sc.k.c,
        d_m: sc.k.d_m,
        natural_1_s: sc.psi(),
        play_picker_m: sc.s0,
    })
}

/// Simulates the pick of `mechanism` under `settings` by `method` and returns the end-of-pick values.
///
/// Errors: settings out of range (naming the field, value, range and unit), play beyond the
/// cam's reach, or a solver failure. A resonance never fails: the closed form hands over to the
/// numerical route and says so in [`Outcome::note`].
pub fn simulate(mechanism: &Mechanism, settings: &Settings, method: Method) -> Result<Outcome> {
    let sc = Scenario::new(mechanism, settings)?;
    let (route, used, note) = prepare(&sc, method)?;
    evaluate(mechanism, settings, &sc, &route, used, note)
}

/// Simulates and samples the nominal and actual motion at `n ≥ 2` evenly spaced instants of the pick.
pub fn history(mechanism: &Mechanism, settings: &Settings, method: Method, n: usize) -> Result<History> {
    let sc = Scenario::new(mechanism, settings)?;
    let (route, used, note) = prepare(&sc, method)?;
    let outcome = evaluate(mechanism, settings, &sc, &route, used, note)?;
    let n = n.max(2);
    let mut samples = Vec::with_capacity(n);
    for i in 0..n {
        let t = if i + 1 == n { outcome.t_end_s } else { outcome.t_end_s * i as f64 / (n - 1) as f64 };
        samples.push(Sample { t_s: t, nominal: sc.nominal(t), actual: route.state(t)? });
    }
    Ok(History { outcome, samples })
}

/// The paper's closed-form constants for a scenario (compound cam only); exposed so the
/// printed and corrected forms of eqs. 33–46 can be compared.
pub fn closed_form_constants(mechanism: &Mechanism, settings: &Settings) -> Result<PaperConstants> {
    let sc = Scenario::new(mechanism, settings)?;
    if !matches!(mechanism.cam(), crate::Cam::Compound) {
        return Err(PickError::NoClosedForm { law: mechanism.cam().label() });
    }
    PaperConstants::new(&sc)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// x, ẋ at the end of the cam's rise by classical fixed-step RK4 on eq. 5 (an integrator of
    /// its own, not the crate's DOP853), from rest at t = 0.
    fn rk4_end(sc: &Scenario, steps: usize) -> (f64, f64) {
        let h = sc.t_cam_end / steps as f64;
        let f = |t: f64, x: f64, v: f64| (v, sc.accel(t, x));
        let (mut x, mut v) = (0.0, 0.0);
        for i in 0..steps {
            let t = h * i as f64;
            let (k1x, k1v) = f(t, x, v);
            let (k2x, k2v) = f(t + h / 2.0, x + h / 2.0 * k1x, v + h / 2.0 * k1v);
            let (k3x, k3v) = f(t + h / 2.0, x + h / 2.0 * k2x, v + h / 2.0 * k2v);
            let (k4x, k4v) = f(t + h, x + h * k3x, v + h * k3v);
            x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
            v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        }
        (x, v)
    }

    /// Picks far shorter than a natural period (the play at the edge of the cam's reach, a loom
    /// speed of 10⁵ rev/min): the closed form's terms cancel — its distance was 8.8e-4 off at a
    /// play of 76.52 mm — so the closed route hands over to integration, says so, and the answer
    /// meets an RK4 integration of eq. 5 (ψ·T ≤ 0.01 there, so 2000 steps are exact to rounding).
    /// At the paper's settings the closed form keeps its digits and answers itself.
    #[test]
    fn short_picks_leave_the_cancelling_closed_form() {
        let m = Mechanism::paper_default();
        let d = Settings::designed(&m);
        for st in [
            d.with_play_mm(76.52),
            d.with_play_mm(76.5),
            d.with_speed_rpm(1e5),
            d.with_speed_rpm(1e5).with_play_mm(10.0),
        ] {
            let sc = Scenario::new(&m, &st).unwrap();
            let p = PaperConstants::new(&sc).unwrap();
            assert!(p.cancellation(sc.t_cam_end) > CANCELLATION_LIMIT, "{st:?}");
            let (x, v) = rk4_end(&sc, 2000);
            let o = simulate(&m, &st, Method::Closed).unwrap();
            assert_eq!(o.method, Method::Ode, "{st:?}");
            assert!(o.note.as_deref().is_some_and(|n| n.contains("terms cancel")), "{:?}", o.note);
            assert!((o.distance_m - x).abs() <= 1e-9 * x, "{st:?}: {} vs RK4 {x}", o.distance_m);
            assert!((o.velocity_m_s - v).abs() <= 1e-9 * v, "{st:?}: {} vs RK4 {v}", o.velocity_m_s);
        }
        // The cancellation the estimate guards against is real: the closed form itself, at the
        // edge of the reach, misses the RK4 distance by far more than the limit.
        let st = d.with_play_mm(76.52);
        let sc = Scenario::new(&m, &st).unwrap();
        let closed = PaperConstants::new(&sc).unwrap().state(sc.t_cam_end);
        let (x, _) = rk4_end(&sc, 2000);
        assert!((closed.x_m - x).abs() > 1e-6 * x, "{} vs {x}", closed.x_m);
        for st in [d, d.with_play_mm(15.5), d.with_play_mm(60.0), d.with_speed_rpm(240.0), d.with_strap_cm(13.0)] {
            let o = simulate(&m, &st, Method::Closed).unwrap();
            assert_eq!((o.method, o.note.is_none()), (Method::Closed, true), "{st:?}: {:?}", o.note);
        }
    }
}
