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

/// The numerical actual motion of a scenario on [0, t_cam_end], stored at the solver's steps with
/// an exact interpolant between them.
///
/// Between two accepted steps the motion is the septic Hermite polynomial that matches x, ẋ, ẍ
/// and x⃛ at both ends, the two higher derivatives taken from the equation itself
/// (ẍ = (f − κx)/B, x⃛ = (f′ − κẋ)/B), so no state is integrated twice. Its error,
/// h⁸·max|x⁽⁸⁾|/(8!·2⁸) ≈ (ψh)⁸/10⁷ of the oscillation's amplitude, lies far below the solver's
/// tolerance at the steps DOP853 takes at 1e-13 (ψh ≲ 0.1). At the cam's joints and the ends of
/// the rise f′ is taken one-sided, from inside the step.
#[derive(Debug, Clone)]
pub(crate) struct OdeTrajectory<'a> {
    sc: &'a Scenario,
    /// Accepted step times; joints of the forcing are step points.
    ts: Vec<f64>,
    /// States (x, ẋ) at the step times.
    ys: Vec<[f64; 2]>,
    /// Coefficients of x on each interval [ts[k], ts[k+1]] in powers of s = (t − ts[k])/h.
    polys: Vec<[f64; 8]>,
}

/// Coefficients in s ∈ [0, 1] of the septic matching value and first three derivatives
/// (already scaled by powers of h) at both ends.
fn septic(d0: [f64; 4], d1: [f64; 4]) -> [f64; 8] {
    let c = [d0[0], d0[1], d0[2] / 2.0, d0[3] / 6.0];
    let r0 = d1[0] - (c[0] + c[1] + c[2] + c[3]);
    let r1 = d1[1] - (c[1] + 2.0 * c[2] + 3.0 * c[3]);
    let r2 = d1[2] - (2.0 * c[2] + 6.0 * c[3]);
    let r3 = d1[3] - 6.0 * c[3];
    // The inverse of the 4×4 system for the s⁴…s⁷ terms at s = 1.
    [
        c[0],
        c[1],
        c[2],
        c[3],
        35.0 * r0 - 15.0 * r1 + 2.5 * r2 - r3 / 6.0,
        -84.0 * r0 + 39.0 * r1 - 7.0 * r2 + r3 / 2.0,
        70.0 * r0 - 34.0 * r1 + 6.5 * r2 - r3 / 2.0,
        -20.0 * r0 + 10.0 * r1 - 2.0 * r2 + r3 / 6.0,
    ]
}

impl<'a> OdeTrajectory<'a> {
    pub(crate) fn new(sc: &'a Scenario) -> Result<Self> {
        let mut knots = vec![0.0];
        knots.extend(sc.joints.iter().copied());
        knots.push(sc.t_cam_end);
        let f = |t: f64| sc.forcing(t);
        let (b, kappa) = (sc.k.b_s2, sc.k.c + 1.0);
        let mut ts: Vec<f64> = Vec::new();
        let mut ys: Vec<[f64; 2]> = Vec::new();
        let mut polys: Vec<[f64; 8]> = Vec::new();
        let mut y = [0.0, 0.0];
        for w in knots.windows(2) {
            let part = integrate(&f, b, kappa, w[0], w[1], y)?;
            y = part.last().map(|p| p.1).unwrap_or(y);
            // x, ẋ, ẍ, x⃛ at t with f′ read at `t_in`, a point inside the step next to t.
            let derivs = |t: f64, t_in: f64, y: [f64; 2], h: f64| {
                let a = (f(t) - kappa * y[0]) / b;
                let j = (sc.q * sc.cam.eval(sc.q * t_in + sc.u0).v_m_s - kappa * y[1]) / b;
                [y[0], h * y[1], h * h * a, h * h * h * j]
            };
            let last = part.len().saturating_sub(1);
            for (i, p) in part.windows(2).enumerate() {
                let ((t0, y0), (t1, y1)) = (p[0], p[1]);
                let h = t1 - t0;
                // One-sided at the ends of the smooth piece (the joints), exact inside it.
                let in0 = if i == 0 { t0 + 1e-9 * h } else { t0 };
                let in1 = if i + 1 == last { t1 - 1e-9 * h } else { t1 };
                polys.push(septic(derivs(t0, in0, y0, h), derivs(t1, in1, y1, h)));
                ts.push(t0);
                ys.push(y0);
            }
        }
        ts.push(sc.t_cam_end);
        ys.push(y);
        Ok(Self { sc, ts, ys, polys })
    }

    /// The step times (scan points for extrema and events).
    pub(crate) fn knots(&self) -> &[f64] {
        &self.ts
    }

    /// Number of accepted steps.
    pub(crate) fn len(&self) -> usize {
        self.ts.len()
    }

    /// (x, ẋ) at `t` from the interpolant (the stored values at a step time).
    fn xv(&self, t: f64) -> [f64; 2] {
        let n = self.polys.len();
        let k = self.ts.partition_point(|&s| s <= t).saturating_sub(1);
        if n == 0 || k >= n || t <= self.ts[0] {
            return self.ys[k.min(self.ys.len() - 1)];
        }
        if t == self.ts[k] {
            return self.ys[k];
        }
        let c = &self.polys[k];
        let h = self.ts[k + 1] - self.ts[k];
        let s = (t - self.ts[k]) / h;
        let x = c[0] + s * (c[1] + s * (c[2] + s * (c[3] + s * (c[4] + s * (c[5] + s * (c[6] + s * c[7]))))));
        let dx = c[1]
            + s * (2.0 * c[2]
                + s * (3.0 * c[3] + s * (4.0 * c[4] + s * (5.0 * c[5] + s * (6.0 * c[6] + s * 7.0 * c[7])))));
        [x, dx / h]
    }

    /// State at `t` from the interpolant (the stored step itself at a step time).
    pub(crate) fn state(&self, t: f64) -> Result<State> {
        let [x, v] = self.xv(t);
        Ok(State { x_m: x, v_m_s: v, a_m_s2: self.sc.accel(t, x) })
    }

    /// Jerk and its rate, ȧ and ä at `t`, from the equation: B·x⃛ = f′ − κẋ, B·x⁗ = f″ − κẍ.
    pub(crate) fn jerk(&self, t: f64) -> Result<[f64; 2]> {
        let [x, v] = self.xv(t);
        let sc = self.sc;
        let (b, kappa) = (sc.k.b_s2, sc.k.c + 1.0);
        let n = sc.cam.eval(sc.q * t + sc.u0);
        let a = (n.s_m - sc.s0 - sc.k.d_m - kappa * x) / b;
        Ok([(sc.q * n.v_m_s - kappa * v) / b, (sc.q * sc.q * n.a_m_s2 - kappa * a) / b])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Mechanism, Settings};

    /// Independent route: the interpolated state between steps against DOP853 restarted from the
    /// last step before it (what the trajectory did before it had an interpolant).
    #[test]
    fn interpolant_matches_reintegration() {
        let m = Mechanism::paper_default();
        for st in [Settings::designed(&m).with_play_mm(15.5), Settings::designed(&m).with_speed_rpm(230.0)] {
            let sc = Scenario::new(&m, &st).unwrap();
            let o = OdeTrajectory::new(&sc).unwrap();
            let f = |s: f64| sc.forcing(s);
            let (mut worst_x, mut worst_v) = (0.0f64, 0.0f64);
            for k in 0..o.polys.len() {
                for frac in [0.13, 0.5, 0.87] {
                    let t = o.ts[k] + frac * (o.ts[k + 1] - o.ts[k]);
                    let part = integrate(&f, sc.k.b_s2, sc.k.c + 1.0, o.ts[k], t, o.ys[k]).unwrap();
                    let y = part.last().unwrap().1;
                    let s = o.state(t).unwrap();
                    worst_x = worst_x.max((s.x_m - y[0]).abs());
                    worst_v = worst_v.max((s.v_m_s - y[1]).abs());
                }
            }
            // x is about 0.1 m and ẋ about 20 m/s: agreement at the solver's own 1e-13.
            assert!(worst_x < 1e-14 && worst_v < 1e-11, "x {worst_x:e} m, v {worst_v:e} m/s");
        }
    }

    /// The jerk and its rate against central differences of the acceleration.
    #[test]
    fn jerk_matches_finite_differences() {
        let m = Mechanism::paper_default();
        let sc = Scenario::new(&m, &Settings::designed(&m).with_play_mm(15.5)).unwrap();
        let o = OdeTrajectory::new(&sc).unwrap();
        let h = 1e-7;
        for t in [0.002, 0.0071, 0.0123, 0.016] {
            let a = |t: f64| o.state(t).unwrap().a_m_s2;
            let fd = (a(t + h) - a(t - h)) / (2.0 * h);
            let [j, snap] = o.jerk(t).unwrap();
            assert!((fd - j).abs() < 1e-5 * j.abs().max(1e3), "t = {t}: jerk {j} vs {fd}");
            let jf = |t: f64| o.jerk(t).unwrap()[0];
            let fs = (jf(t + h) - jf(t - h)) / (2.0 * h);
            assert!((fs - snap).abs() < 1e-5 * snap.abs().max(1e6), "t = {t}: snap {snap} vs {fs}");
        }
    }
}
