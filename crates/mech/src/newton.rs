//! Position by Newton's method, rates from the differentiated loops, and continuation along the
//! input.

use crate::linalg::Lu;
use crate::vloop::LoopSystem;
use crate::{MechError, Result};
use nalgebra::{SMatrix, SVector};

/// Settings of the Newton iteration and of the continuation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonOptions {
    /// Converged when the residual's largest component is below this (m).
    pub residual_tol: f64,
    /// Iterations allowed per solve.
    pub max_iterations: usize,
    /// Continuation: a step is halved at most this many times before the branch is declared lost.
    pub max_halvings: u32,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        Self { residual_tol: 1e-12, max_iterations: 30, max_halvings: 12 }
    }
}

/// A solved position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Position<const N: usize> {
    /// The unknowns.
    pub q: SVector<f64, N>,
    /// Newton iterations used.
    pub iterations: usize,
    /// Largest residual component left (m).
    pub residual: f64,
}

/// A solved position with its rates with respect to the input `x`.
///
/// Time rates follow by the chain rule: `q̇ = q′ẋ`, `q̈ = q″ẋ² + q′ẍ`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoopState<const N: usize> {
    /// Input coordinate x.
    pub input: f64,
    /// Unknowns q.
    pub q: SVector<f64, N>,
    /// `q′ = dq/dx`.
    pub dq: SVector<f64, N>,
    /// `q″ = d²q/dx²`.
    pub ddq: SVector<f64, N>,
    /// `det J_q` (its sign changes through a fold).
    pub det: f64,
}

fn lu_solve<const N: usize>(m: &SMatrix<f64, N, N>, b: &SVector<f64, N>, input: f64) -> Result<SVector<f64, N>> {
    let scale = m.amax().max(1e-300);
    let lu = Lu::new(m);
    let det = lu.det();
    // Relative singularity test: |det| against the scale of the matrix.
    if !det.is_finite() || det.abs() < 1e-13 * scale.powi(N as i32) {
        return Err(MechError::Singular { input, det });
    }
    lu.solve(b).ok_or(MechError::Singular { input, det })
}

impl<const N: usize> LoopSystem<N> {
    /// Newton's method `q ← q − J_q⁻¹ F` from `guess` at input `x`.
    pub fn solve_position(&self, x: f64, guess: SVector<f64, N>, opts: &NewtonOptions) -> Result<Position<N>> {
        let mut q = guess;
        let mut residual = f64::INFINITY;
        for it in 0..=opts.max_iterations {
            let lin = self.linearize(x, &q);
            residual = lin.f.amax();
            if !residual.is_finite() {
                break;
            }
            if residual <= opts.residual_tol {
                return Ok(Position { q, iterations: it, residual });
            }
            if it == opts.max_iterations {
                break;
            }
            q -= lu_solve(&lin.jq, &lin.f, x)?;
        }
        Err(MechError::NoConvergence { input: x, iterations: opts.max_iterations, residual })
    }

    /// Rates with respect to the input at a solved position: `J_q q′ = −J_x`,
    /// `J_q q″ = −γ(q′, 1)` (the input is the independent variable, so `x″ = 0`).
    pub fn rates(&self, x: f64, q: SVector<f64, N>) -> Result<LoopState<N>> {
        let lin = self.linearize(x, &q);
        let det = Lu::new(&lin.jq).det();
        let dq = lu_solve(&lin.jq, &(-lin.jx), x)?;
        let ddq = lu_solve(&lin.jq, &(-self.gamma(x, &q, &dq, 1.0)), x)?;
        Ok(LoopState { input: x, q, dq, ddq, det })
    }

    /// Follows the branch through `guess` over the increasing or decreasing `inputs`.
    ///
    /// Each step predicts `q + q′h + q″h²/2`, corrects by Newton and accepts the result only if the
    /// correction is small against the predicted change and `det J_q` keeps its sign; otherwise the
    /// step is halved (up to [`NewtonOptions::max_halvings`] times). A sign change of `det J_q` or a
    /// failure to converge ends the branch with [`MechError::BranchLost`].
    pub fn trace(&self, inputs: &[f64], guess: SVector<f64, N>, opts: &NewtonOptions) -> Result<Vec<LoopState<N>>> {
        let mut out = Vec::with_capacity(inputs.len());
        let Some(&x0) = inputs.first() else { return Ok(out) };
        let p = self.solve_position(x0, guess, opts)?;
        let mut st = self.rates(x0, p.q)?;
        out.push(st);
        for &x1 in &inputs[1..] {
            st = self.advance(&st, x1, opts)?;
            out.push(st);
        }
        Ok(out)
    }

    /// One continuation step from a solved state to input `x1`, with step halving.
    pub fn advance(&self, from: &LoopState<N>, x1: f64, opts: &NewtonOptions) -> Result<LoopState<N>> {
        let mut cur = *from;
        let mut target_h = x1 - cur.input;
        let mut halvings = 0;
        while (x1 - cur.input).abs() > 0.0 {
            let h = if (x1 - cur.input).abs() <= target_h.abs() { x1 - cur.input } else { target_h };
            let x = if h == x1 - cur.input { x1 } else { cur.input + h };
            match self.try_step(&cur, x, h, opts) {
                Ok(next) => cur = next,
                Err(reason) => {
                    halvings += 1;
                    if halvings > opts.max_halvings {
                        return Err(MechError::BranchLost { from: from.input, to: x1, reason });
                    }
                    target_h = h / 2.0;
                }
            }
        }
        Ok(cur)
    }

    fn try_step(&self, cur: &LoopState<N>, x: f64, h: f64, opts: &NewtonOptions) -> Result<LoopState<N>, String> {
        let pred = cur.q + cur.dq * h + cur.ddq * (h * h / 2.0);
        let pos = self.solve_position(x, pred, opts).map_err(|e| e.to_string())?;
        let change = (cur.dq * h).amax() + (cur.ddq * (h * h / 2.0)).amax();
        let correction = (pos.q - pred).amax();
        if correction > 1e-6 + 0.2 * change {
            return Err(format!(
                "Newton moved {correction:.3e} away from the predicted position (predicted change {change:.3e}): \
                 a jump to another branch"
            ));
        }
        let st = self.rates(x, pos.q).map_err(|e| e.to_string())?;
        if st.det.signum() != cur.det.signum() {
            return Err("det J_q changes sign: a fold (dead point) lies in between".into());
        }
        Ok(st)
    }
}

#[cfg(test)]
mod tests {
    use crate::planar::{Vec2, e};
    use crate::vloop::{LoopSystem, Scalar, VectorLoop};
    use nalgebra::SVector;

    use super::NewtonOptions;

    fn four_bar() -> LoopSystem<2> {
        let l = VectorLoop::new()
            .plus_polar(Scalar::constant(0.1), Scalar::input_plus(0.0))
            .plus_polar(Scalar::constant(0.35), Scalar::unknown(0))
            .minus_polar(Scalar::constant(0.3), Scalar::unknown(1))
            .plus_fixed(Vec2::new(-0.4, 0.0));
        LoopSystem::new(vec![l]).unwrap()
    }

    /// The four-bar's closed form: B = a e(x), C on the circle (D, c) at distance b from B.
    fn four_bar_closed(x: f64) -> (f64, f64) {
        let b = 0.1 * e(x);
        let d = Vec2::new(0.4, 0.0);
        let c = crate::dyad::circle_circle(b, 0.35, d, 0.3, "four-bar").unwrap()[0];
        ((c - b).y.atan2((c - b).x), (c - d).y.atan2((c - d).x))
    }

    #[test]
    fn newton_matches_the_closed_form_dyad_over_a_revolution() {
        let sys = four_bar();
        let xs: Vec<f64> = (0..=360).map(|i| (i as f64).to_radians()).collect();
        let (g0, g1) = four_bar_closed(0.0);
        let states = sys.trace(&xs, SVector::<f64, 2>::new(g0 + 0.05, g1 - 0.05), &NewtonOptions::default()).unwrap();
        for s in &states {
            let (t3, t4) = four_bar_closed(s.input);
            assert!(crate::planar::wrap_pi(s.q[0] - t3).abs() < 1e-10);
            assert!(crate::planar::wrap_pi(s.q[1] - t4).abs() < 1e-10);
        }
        // Rates against central differences of the closed form.
        let h = 1e-5;
        for s in states.iter().step_by(17) {
            let (p, m) = (four_bar_closed(s.input + h), four_bar_closed(s.input - h));
            let (c0, _) = four_bar_closed(s.input);
            let d1 = crate::planar::wrap_pi(p.0 - m.0) / (2.0 * h);
            let d2 = (crate::planar::wrap_pi(p.0 - c0) - crate::planar::wrap_pi(c0 - m.0)) / (h * h);
            assert!((d1 - s.dq[0]).abs() < 1e-8, "q0' {d1} vs {}", s.dq[0]);
            assert!((d2 - s.ddq[0]).abs() < 1e-4, "q0'' {d2} vs {}", s.ddq[0]);
        }
    }

    #[test]
    fn a_fold_ends_the_branch_with_an_error() {
        // A crank longer than the coupler can follow: a = 0.3 with b = 0.2, c = 0.3, d = 0.4 folds.
        let l = VectorLoop::new()
            .plus_polar(Scalar::constant(0.3), Scalar::input_plus(0.0))
            .plus_polar(Scalar::constant(0.2), Scalar::unknown(0))
            .minus_polar(Scalar::constant(0.3), Scalar::unknown(1))
            .plus_fixed(Vec2::new(-0.4, 0.0));
        let sys = LoopSystem::<2>::new(vec![l]).unwrap();
        let xs: Vec<f64> = (0..=360).map(|i| (i as f64).to_radians()).collect();
        // At x = 0, B = (0.3, 0), D = (0.4, 0): |BD| = 0.1, reachable. Guess the elbow-up branch.
        let err = sys.trace(&xs, SVector::<f64, 2>::new(1.2, 2.0), &NewtonOptions::default()).unwrap_err();
        assert!(matches!(err, crate::MechError::BranchLost { .. }), "{err}");
        assert!(!err.to_string().contains("NaN"));
    }
}
