//! Integration of the velocity equations along the input (the paper's Simulink route).
//!
//! The loops are differentiated once, `J_q q′ = −J_x`, and `q′(x)` is integrated by the classical
//! fourth-order Runge–Kutta method with a fixed step. This is an independent check of the Newton
//! positions: it never solves `F(x, q) = 0`, so its drift `|F|` measures its own error.

use crate::linalg::Lu;
use crate::vloop::LoopSystem;
use crate::{MechError, Result};
use nalgebra::SVector;

impl<const N: usize> LoopSystem<N> {
    /// `dq/dx` at `(x, q)` from `J_q q′ = −J_x`.
    pub fn velocity_field(&self, x: f64, q: &SVector<f64, N>) -> Result<SVector<f64, N>> {
        let lin = self.linearize(x, q);
        let lu = Lu::new(&lin.jq);
        lu.solve(&(-lin.jx)).ok_or(MechError::Singular { input: x, det: lu.det() })
    }

    /// Integrates `q′ = −J_q⁻¹ J_x` from `(x0, q0)` to `x1` in `steps` RK4 steps; returns the
    /// `steps + 1` states `(x, q)`.
    pub fn integrate_velocity(
        &self,
        x0: f64,
        q0: SVector<f64, N>,
        x1: f64,
        steps: usize,
    ) -> Result<Vec<(f64, SVector<f64, N>)>> {
        let steps = steps.max(1);
        let h = (x1 - x0) / steps as f64;
        let mut out = Vec::with_capacity(steps + 1);
        let mut q = q0;
        out.push((x0, q));
        for k in 0..steps {
            let x = x0 + k as f64 * h;
            let k1 = self.velocity_field(x, &q)?;
            let k2 = self.velocity_field(x + h / 2.0, &(q + k1 * (h / 2.0)))?;
            let k3 = self.velocity_field(x + h / 2.0, &(q + k2 * (h / 2.0)))?;
            let k4 = self.velocity_field(x + h, &(q + k3 * h))?;
            q += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0);
            out.push((x0 + (k + 1) as f64 * h, q));
        }
        Ok(out)
    }
}
