//! The numerical route: the equation of motion integrated by DOP853 (differential-equations),
//! wrapped behind one function, [`integrate`].

use crate::scenario::Scenario;
use crate::{PickError, Result, State};
use differential_equations::prelude::{ExplicitRungeKutta, IVP, ODE};

/// Relative tolerance of the integrator.
pub const ODE_RTOL: f64 = 1e-13;
/// Absolute tolerance of the integrator (m for x, m/s for ẋ).
pub const ODE_ATOL: f64 = 1e-15;

/// B·ẍ + κ·x = forcing(t) as a first-order system y = (x, ẋ).
struct Equation<'a, F: Fn(f64) -> f64> {
    forcing: &'a F,
    b: f64,
    kappa: f64,
}

impl<F: Fn(f64) -> f64> ODE<f64, [f64; 2]> for Equation<'_, F> {
    fn diff(&self, t: f64, y: &[f64; 2], dydt: &mut [f64; 2]) {
        dydt[0] = y[1];
        dydt[1] = ((self.forcing)(t) - self.kappa * y[0]) / self.b;
    }
}

/// Integrates B·ẍ + κ·x = forcing(t) from `(t0, y0 = [x, ẋ])` to `t1` with DOP853 at
/// [`ODE_RTOL`]/[`ODE_ATOL`]; returns every accepted step, the first at `t0`, the last at `t1`.
///
/// The forcing must be smooth on (t0, t1): callers split the interval at the cam's joints.
pub fn integrate<F: Fn(f64) -> f64>(
    forcing: &F,
    b: f64,
    kappa: f64,
    t0: f64,
    t1: f64,
    y0: [f64; 2],
) -> Result<Vec<(f64, [f64; 2])>> {
    if t1 <= t0 {
        return Ok(vec![(t0, y0)]);
    }
    let eq = Equation { forcing, b, kappa };
    let method = ExplicitRungeKutta::dop853().rtol(ODE_RTOL).atol(ODE_ATOL).max_steps(1_000_000);
    let sol =
        IVP::ode(&eq, t0, t1, y0).method(method).solve().map_err(|e| PickError::Solver { reason: format!("{e:?}") })?;
    let (t, y) = sol.into_tuple();
    let mut out: Vec<(f64, [f64; 2])> = t.into_iter().zip(y).collect();
    if out.first().is_none_or(|p| p.0 != t0) {
        out.insert(0, (t0, y0));
    }
    match out.last() {
        Some(p) if (p.0 - t1).abs() <= 1e-15 * t1.abs().max(1.0) => {}
        _ => return Err(PickError::Solver { reason: format!("the solver stopped before t = {t1} s") }),
    }
    Ok(out)
}

/// The numerical actual motion of a scenario on [0, t_cam_end], stored at the solver's steps.
#[derive(Debug, Clone)]
pub(crate) struct OdeTrajectory<'a> {
    sc: &'a Scenario,
    /// Accepted steps (t, [x, ẋ]); joints of the forcing are step points.
    steps: Vec<(f64, [f64; 2])>,
}

impl<'a> OdeTrajectory<'a> {
    pub(crate) fn new(sc: &'a Scenario) -> Result<Self> {
        let mut knots = vec![0.0];
        knots.extend(sc.joints.iter().copied());
        knots.push(sc.t_cam_end);
        let f = |t: f64| sc.forcing(t);
        let mut steps: Vec<(f64, [f64; 2])> = Vec::new();
        let mut y = [0.0, 0.0];
        for w in knots.windows(2) {
            let mut part = integrate(&f, sc.k.b_s2, sc.k.c + 1.0, w[0], w[1], y)?;
            if !steps.is_empty() {
                part.remove(0);
            }
            y = part.last().map(|p| p.1).unwrap_or(y);
            steps.extend(part);
        }
        Ok(Self { sc, steps })
    }

    /// The step times (scan points for extrema and events).
    pub(crate) fn knots(&self) -> Vec<f64> {
        self.steps.iter().map(|p| p.0).collect()
    }

    /// Number of accepted steps.
    pub(crate) fn len(&self) -> usize {
        self.steps.len()
    }

    /// State at `t`: from the last stored step at or before `t`, integrated on to `t`.
    pub(crate) fn state(&self, t: f64) -> Result<State> {
        let i = self.steps.partition_point(|p| p.0 <= t).saturating_sub(1);
        let (ti, yi) = self.steps[i];
        let y = if t > ti {
            let f = |s: f64| self.sc.forcing(s);
            let part = integrate(&f, self.sc.k.b_s2, self.sc.k.c + 1.0, ti, t, yi)?;
            part.last().map(|p| p.1).unwrap_or(yi)
        } else {
            yi
        };
        Ok(State { x_m: y[0], v_m_s: y[1], a_m_s2: self.sc.accel(t, y[0]) })
    }
}
