//! Planar vector loops: a declarative description of closed vector contours and their exact
//! first and second derivatives.
//!
//! A loop is a sum of vectors that must vanish, `Σₖ vₖ = 0`, each vector being
//!
//! * a polar vector `± ρ·e(θ)` whose length `ρ` and angle `θ` are affine in one variable
//!   (a constant, the input `x`, or an unknown `qᵢ`) — links, sliders, cranks;
//! * a point `± r(p)` of a closed [`PlaneCurve`] at an affine parameter `p` — a roller centre on a cam;
//! * a fixed vector — a frame offset.
//!
//! `L` loops give `2L` scalar equations `F(x, q) = 0` in `N = 2L` unknowns. Differentiating once
//! and twice in time gives the velocity and acceleration equations, linear in the rates:
//!
//! `J_q q̇ + J_x ẋ = 0`,  `J_q q̈ + J_x ẍ + γ(q̇, ẋ) = 0`,
//!
//! where `γ` gathers the velocity-quadratic terms, for a polar vector `2ρ̇θ̇ e⊥(θ) − ρθ̇² e(θ)`
//! and for a curve point `r″(p) ṗ²`. [`LoopSystem`] evaluates `F`, `J_q`, `J_x` and `γ` exactly.

use crate::curve::PlaneCurve;
use crate::planar::{Vec2, e, e_perp};
use crate::{MechError, Result};
use loomkin_units::Range;
use nalgebra::{SMatrix, SVector};
use std::sync::Arc;

/// What a loop scalar depends on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Var {
    /// Nothing: a constant.
    Const,
    /// The input coordinate `x` (e.g. the crank angle φ2, rad).
    Input,
    /// The unknown `q[i]`.
    Unknown(usize),
}

/// An affine scalar `offset + gain·var` (a length in m or an angle in rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scalar {
    /// The variable.
    pub var: Var,
    /// Gain on the variable.
    pub gain: f64,
    /// Constant offset.
    pub offset: f64,
}

impl Scalar {
    /// A constant `c`.
    pub const fn constant(c: f64) -> Self {
        Self { var: Var::Const, gain: 0.0, offset: c }
    }
    /// The input `x` plus a constant offset.
    pub const fn input_plus(offset: f64) -> Self {
        Self { var: Var::Input, gain: 1.0, offset }
    }
    /// The unknown `q[i]` plus a constant offset.
    pub const fn unknown_plus(i: usize, offset: f64) -> Self {
        Self { var: Var::Unknown(i), gain: 1.0, offset }
    }
    /// The unknown `q[i]`.
    pub const fn unknown(i: usize) -> Self {
        Self::unknown_plus(i, 0.0)
    }

    #[inline]
    fn value<const N: usize>(&self, x: f64, q: &SVector<f64, N>) -> f64 {
        match self.var {
            Var::Const => self.offset,
            Var::Input => self.offset + self.gain * x,
            Var::Unknown(i) => self.offset + self.gain * q[i],
        }
    }

    #[inline]
    fn rate<const N: usize>(&self, xd: f64, qd: &SVector<f64, N>) -> f64 {
        match self.var {
            Var::Const => 0.0,
            Var::Input => self.gain * xd,
            Var::Unknown(i) => self.gain * qd[i],
        }
    }
}

/// One vector of a loop.
#[derive(Debug, Clone)]
pub enum Term {
    /// `sign · length · e(angle)`.
    Polar {
        /// +1 or −1.
        sign: f64,
        /// Length ρ (m).
        length: Scalar,
        /// Angle θ (rad).
        angle: Scalar,
    },
    /// `sign · r(param)` on a closed curve.
    Curve {
        /// +1 or −1.
        sign: f64,
        /// The curve.
        curve: Arc<dyn PlaneCurve>,
        /// Curve parameter p.
        param: Scalar,
    },
    /// A constant vector (m).
    Fixed(Vec2),
}

/// A closed vector contour `Σ terms = 0` (two scalar equations).
#[derive(Debug, Clone, Default)]
pub struct VectorLoop {
    terms: Vec<Term>,
}

impl VectorLoop {
    /// An empty loop.
    pub fn new() -> Self {
        Self::default()
    }
    /// Adds `+ρ e(θ)`.
    pub fn plus_polar(mut self, length: Scalar, angle: Scalar) -> Self {
        self.terms.push(Term::Polar { sign: 1.0, length, angle });
        self
    }
    /// Adds `−ρ e(θ)`.
    pub fn minus_polar(mut self, length: Scalar, angle: Scalar) -> Self {
        self.terms.push(Term::Polar { sign: -1.0, length, angle });
        self
    }
    /// Adds `+r(p)` of a curve.
    pub fn plus_curve(mut self, curve: Arc<dyn PlaneCurve>, param: Scalar) -> Self {
        self.terms.push(Term::Curve { sign: 1.0, curve, param });
        self
    }
    /// Adds `−r(p)` of a curve.
    pub fn minus_curve(mut self, curve: Arc<dyn PlaneCurve>, param: Scalar) -> Self {
        self.terms.push(Term::Curve { sign: -1.0, curve, param });
        self
    }
    /// Adds a constant vector.
    pub fn plus_fixed(mut self, v: Vec2) -> Self {
        self.terms.push(Term::Fixed(v));
        self
    }
    /// The terms.
    pub fn terms(&self) -> &[Term] {
        &self.terms
    }
}

/// The residual and its Jacobians at one point: `F`, `J_q = ∂F/∂q`, `J_x = ∂F/∂x`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Linearization<const N: usize> {
    /// Residual `F(x, q)` (m).
    pub f: SVector<f64, N>,
    /// `∂F/∂q`.
    pub jq: SMatrix<f64, N, N>,
    /// `∂F/∂x`.
    pub jx: SVector<f64, N>,
}

/// `L = N/2` vector loops in `N` unknowns and one input.
#[derive(Debug, Clone)]
pub struct LoopSystem<const N: usize> {
    loops: Vec<VectorLoop>,
}

fn check_scalar<const N: usize>(s: &Scalar, field: &str) -> Result<()> {
    Range::finite("").check(&format!("{field}.gain"), s.gain)?;
    Range::finite("").check(&format!("{field}.offset"), s.offset)?;
    if let Var::Unknown(i) = s.var
        && i >= N
    {
        return Err(MechError::Invalid { field: field.into(), reason: format!("unknown index {i} ≥ N = {N}") });
    }
    Ok(())
}

impl<const N: usize> LoopSystem<N> {
    /// A system of loops; `2 · loops.len()` must equal `N` and every unknown index be `< N`.
    pub fn new(loops: Vec<VectorLoop>) -> Result<Self> {
        if 2 * loops.len() != N {
            return Err(MechError::Invalid {
                field: "loops".into(),
                reason: format!("{} loops give {} equations for N = {N} unknowns", loops.len(), 2 * loops.len()),
            });
        }
        for (li, l) in loops.iter().enumerate() {
            for (ti, t) in l.terms.iter().enumerate() {
                let f = format!("loops[{li}].terms[{ti}]");
                match t {
                    Term::Polar { sign, length, angle } => {
                        check_scalar::<N>(length, &f)?;
                        check_scalar::<N>(angle, &f)?;
                        Range::finite("").check(&format!("{f}.sign"), *sign)?;
                    }
                    Term::Curve { param, .. } => check_scalar::<N>(param, &f)?,
                    Term::Fixed(v) => {
                        Range::finite("m").check(&format!("{f}.x"), v.x)?;
                        Range::finite("m").check(&format!("{f}.y"), v.y)?;
                    }
                }
            }
        }
        Ok(Self { loops })
    }

    /// The loops.
    pub fn loops(&self) -> &[VectorLoop] {
        &self.loops
    }

    /// Residual `F(x, q)` (m).
    pub fn residual(&self, x: f64, q: &SVector<f64, N>) -> SVector<f64, N> {
        self.linearize(x, q).f
    }

    /// Residual and Jacobians at `(x, q)`.
    pub fn linearize(&self, x: f64, q: &SVector<f64, N>) -> Linearization<N> {
        let mut f = SVector::<f64, N>::zeros();
        let mut jq = SMatrix::<f64, N, N>::zeros();
        let mut jx = SVector::<f64, N>::zeros();
        let mut add_col = |row: usize, s: &Scalar, d: Vec2, jq: &mut SMatrix<f64, N, N>| match s.var {
            Var::Const => {}
            Var::Input => {
                jx[row] += s.gain * d.x;
                jx[row + 1] += s.gain * d.y;
            }
            Var::Unknown(i) => {
                jq[(row, i)] += s.gain * d.x;
                jq[(row + 1, i)] += s.gain * d.y;
            }
        };
        for (li, l) in self.loops.iter().enumerate() {
            let row = 2 * li;
            for t in &l.terms {
                match t {
                    Term::Polar { sign, length, angle } => {
                        let (rho, th) = (length.value(x, q), angle.value(x, q));
                        let v = *sign * rho * e(th);
                        f[row] += v.x;
                        f[row + 1] += v.y;
                        add_col(row, length, *sign * e(th), &mut jq);
                        add_col(row, angle, *sign * rho * e_perp(th), &mut jq);
                    }
                    Term::Curve { sign, curve, param } => {
                        let c = curve.eval(param.value(x, q));
                        f[row] += sign * c.r.x;
                        f[row + 1] += sign * c.r.y;
                        add_col(row, param, *sign * c.d1, &mut jq);
                    }
                    Term::Fixed(v) => {
                        f[row] += v.x;
                        f[row + 1] += v.y;
                    }
                }
            }
        }
        Linearization { f, jq, jx }
    }

    /// The velocity-quadratic part `γ(q̇, ẋ)` of the second time derivative of the loops,
    /// so that `J_q q̈ + J_x ẍ + γ = 0`.
    pub fn gamma(&self, x: f64, q: &SVector<f64, N>, qd: &SVector<f64, N>, xd: f64) -> SVector<f64, N> {
        let mut g = SVector::<f64, N>::zeros();
        for (li, l) in self.loops.iter().enumerate() {
            let row = 2 * li;
            let mut acc = Vec2::zeros();
            for t in &l.terms {
                match t {
                    Term::Polar { sign, length, angle } => {
                        let (rho, th) = (length.value(x, q), angle.value(x, q));
                        let (rhod, thd) = (length.rate(xd, qd), angle.rate(xd, qd));
                        acc += *sign * (2.0 * rhod * thd * e_perp(th) - rho * thd * thd * e(th));
                    }
                    Term::Curve { sign, curve, param } => {
                        let pd = param.rate(xd, qd);
                        acc += *sign * curve.eval(param.value(x, q)).d2 * (pd * pd);
                    }
                    Term::Fixed(_) => {}
                }
            }
            g[row] = acc.x;
            g[row + 1] = acc.y;
        }
        g
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::Ellipse;

    /// Four-bar: crank a·e(x) + coupler b·e(q0) − rocker c·e(q1) − ground d·e(0) = 0.
    pub(crate) fn four_bar() -> LoopSystem<2> {
        let l = VectorLoop::new()
            .plus_polar(Scalar::constant(0.1), Scalar::input_plus(0.0))
            .plus_polar(Scalar::constant(0.35), Scalar::unknown(0))
            .minus_polar(Scalar::constant(0.3), Scalar::unknown(1))
            .plus_fixed(Vec2::new(-0.4, 0.0));
        LoopSystem::new(vec![l]).unwrap()
    }

    #[test]
    fn jacobians_match_finite_differences() {
        let el: Arc<dyn PlaneCurve> = Arc::new(Ellipse::PAPER);
        let l1 = VectorLoop::new()
            .plus_curve(el, Scalar::unknown(0))
            .plus_polar(Scalar::constant(0.36), Scalar::unknown_plus(1, 0.8))
            .minus_polar(Scalar::constant(0.66), Scalar::input_plus(0.0));
        let l2 = VectorLoop::new()
            .plus_polar(Scalar::constant(0.4), Scalar::unknown(3))
            .plus_polar(Scalar::unknown(2), Scalar::unknown(1))
            .minus_polar(Scalar::constant(0.66), Scalar::input_plus(0.0));
        let sys = LoopSystem::<4>::new(vec![l1, l2]).unwrap();
        let (x, q) = (0.4, SVector::<f64, 4>::new(0.2, -0.1, 0.3, 0.5));
        let lin = sys.linearize(x, &q);
        let h = 1e-6;
        for j in 0..4 {
            let mut dq = SVector::<f64, 4>::zeros();
            dq[j] = h;
            let col = (sys.residual(x, &(q + dq)) - sys.residual(x, &(q - dq))) / (2.0 * h);
            assert!((col - lin.jq.column(j)).norm() < 1e-9, "column {j}");
        }
        let colx = (sys.residual(x + h, &q) - sys.residual(x - h, &q)) / (2.0 * h);
        assert!((colx - lin.jx).norm() < 1e-9);
        // γ: the second derivative along a straight path q(t) = q + qd t, x(t) = x + xd t.
        let (qd, xd) = (SVector::<f64, 4>::new(0.3, -0.7, 0.2, 1.1), 0.9);
        let f = |t: f64| sys.residual(x + xd * t, &(q + qd * t));
        let second = (f(h * 10.0) - 2.0 * f(0.0) + f(-h * 10.0)) / (100.0 * h * h);
        assert!((second - sys.gamma(x, &q, &qd, xd)).norm() < 1e-5);
    }

    #[test]
    fn bad_systems_are_rejected() {
        let l = VectorLoop::new().plus_polar(Scalar::constant(1.0), Scalar::unknown(5));
        assert!(matches!(LoopSystem::<2>::new(vec![l.clone()]), Err(MechError::Invalid { .. })));
        assert!(matches!(LoopSystem::<4>::new(vec![l]), Err(MechError::Invalid { .. })));
        let _ = four_bar();
    }
}
