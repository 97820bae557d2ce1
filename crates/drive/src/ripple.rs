//! The periodic motion of the main shaft: speed ripple and flywheel.
//!
//! A shaft of reduced moment of inertia `J(φ)` (the kinetic energy of every mechanism it drives is
//! `½·J(φ)·ω²`), loaded by the torque `M_load(φ)` of the mechanisms' non-inertial forces and
//! turned by a motor of torque `M_motor(ω)`, obeys the energy balance
//!
//! $$ \frac{dE}{d\varphi} = M_\mathrm{motor}(\omega) - M_\mathrm{load}(\varphi), \qquad E = \tfrac12 J(\varphi)\,\omega^2, $$
//!
//! whose solution over the repeat `P` with `E(P) = E(0)` (and the servo's integrator periodic too)
//! is the steady running of the loom. [`Table`] tabulates `J`, `dJ/dφ` and `M_load` once on a grid
//! (uniform, split at the shaft's [`Shaft::breaks_rad`]); [`solve`] integrates `E` (and the
//! servo's integrator) over the grid by the classical fourth-order Runge–Kutta rule and finds the
//! periodic start by shooting:
//!
//! * constant torque — the torque is the load's mean (Simpson's rule on the grid, which is what
//!   the Runge–Kutta rule reduces to when `M_motor` does not depend on `E`), so every start is
//!   periodic; the start is the one whose repeat takes `P/ω_mean` (a monotone root in `E₀`);
//! * induction motor — `E(P) − E₀` falls monotonically with `E₀` on the motor's stable side (a
//!   faster shaft gets less torque); its root by regula falsi (Illinois);
//! * servo — two unknowns (`E₀` and the integrator), Newton's method with a finite-difference
//!   Jacobian of the periodic map.
//!
//! Newton's method (on the exact derivative of the discrete map, each pass carrying the variational
//! equations) is run first on a coarse grid ([`PRESOLVE_STEP_DEG`], the same joints), then on the
//! grid itself from the coarse grid's periodic start, which then takes two passes instead of four
//! or five; the bracketing searches above are the fallback when Newton fails.
//!
//! The speeds' and torques' extremes are located between the grid points, on the cubic Hermite
//! interpolant of `E` (values and slopes `dE/dφ` at the grid points, fourth order like the rule)
//! with `J` evaluated exactly, by golden-section search around the grid's extremes.

use crate::motor::{Induction, Motor, MotorCurve, Servo};
use loomkin_units::{Field, FieldError, Range, RangeError, rpm_from_rad_per_s};
use serde::Serialize;
use thiserror::Error;

/// What can be wrong with a speed-ripple study.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum RippleError {
    /// A number outside its allowed range.
    #[error(transparent)]
    Range(#[from] RangeError),
    /// A field that is missing or contradicts another.
    #[error("{field}: {reason}")]
    Field {
        /// The field.
        field: String,
        /// Why.
        reason: String,
    },
    /// A drive that cannot keep the shaft turning, or a flywheel no size of which meets a target.
    #[error("{field}: {reason}")]
    Infeasible {
        /// The field whose requirement cannot be met.
        field: String,
        /// Why.
        reason: String,
    },
}

impl RippleError {
    /// A field error.
    pub fn field(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Self::Field { field: field.into(), reason: reason.into() }
    }

    fn infeasible(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Self::Infeasible { field: field.into(), reason: reason.into() }
    }
}

impl FieldError for RippleError {
    fn field(&self) -> Option<&str> {
        match self {
            Self::Range(e) => Some(&e.field),
            Self::Field { field, .. } | Self::Infeasible { field, .. } => Some(field),
        }
    }
}

/// A main shaft: its period, its reduced inertia and its load, as functions of its angle.
pub trait Shaft {
    /// The period (the pattern repeat), rad.
    fn period_rad(&self) -> f64;
    /// `J(φ)` in kg·m² and `dJ/dφ` in kg·m²/rad.
    fn inertia(&self, phi_rad: f64) -> (f64, f64);
    /// `M_load(φ)`, N·m: what the non-inertial forces of the mechanisms take from the shaft.
    fn load_torque(&self, phi_rad: f64) -> f64;
    /// Angles in `[0, period)` where `J` or `M_load` is not smooth (the grid is split there).
    fn breaks_rad(&self) -> Vec<f64> {
        Vec::new()
    }
    /// The prefix of the shaft's keys in its input (`drive.` for a loom file's `[drive]` table):
    /// refusals name `PREFIXrotating_inertia_kg_m2`, `PREFIXmotor`.
    fn key_prefix(&self) -> &str {
        ""
    }
}

/// `J`, `dJ/dφ` and `M_load` on the integration grid: at every grid point and every midpoint.
#[derive(Debug, Clone)]
pub struct Table<'a, S: Shaft + ?Sized> {
    shaft: &'a S,
    period: f64,
    /// Grid points, 0 to the period.
    nodes: Vec<f64>,
    /// Values at grid point `k` (index `2k`) and at the midpoint after it (`2k + 1`).
    j: Vec<f64>,
    ml: Vec<f64>,
    /// The presolve's coarse grid: indices into `nodes`, 0 to the last, every interval a run of
    /// equal fine intervals (so its midpoint is a fine point or midpoint); empty when the grid is
    /// already about as coarse ([`PRESOLVE_STEP_DEG`]).
    coarse: Vec<usize>,
}

/// The step of the presolve's grid, deg: the periodic start is found first on a grid of about this
/// step (a tenth of the default's points), then refined on the grid itself by Newton's method from
/// there, which then needs two passes instead of four or five (the two grids' periodic starts agree
/// to the rule's error on the coarse grid, ~10⁻⁹ relative on smooth loads). A grid is presolved
/// when this step holds two or more of its steps (0.66° and finer).
pub const PRESOLVE_STEP_DEG: f64 = 1.0;

/// The coarse grid of [`Table`]'s presolve over `nodes` of regular step `h`: runs of at most
/// `stride` equal intervals; an interval of another width (at a break) is a run of its own.
fn coarse_grid(nodes: &[f64], h: f64, stride: usize) -> Vec<usize> {
    let m = nodes.len() - 1;
    if stride < 2 {
        return Vec::new();
    }
    let regular = |k: usize| k < m && ((nodes[k + 1] - nodes[k]) - h).abs() <= 1e-9 * h;
    let mut out = vec![0];
    let mut run = 0;
    for k in 0..m {
        run += 1;
        if k + 1 == m || run == stride || !regular(k) || !regular(k + 1) {
            out.push(k + 1);
            run = 0;
        }
    }
    out
}

/// `step_deg` of the speed-ripple grid.
pub const STEP_DEG: Field = Field::new(
    "step_deg",
    Range::closed(0.001, 10.0, "deg"),
    "Step of the speed-ripple grid (fourth-order Runge–Kutta in the shaft angle), split at the \
     mechanisms' joints: 0.001 … 10°. 0.1° (3600 steps a turn) puts the rule's error near 1e-12 \
     of the speed on smooth loads.",
)
.with_default(0.1);

impl<'a, S: Shaft + ?Sized> Table<'a, S> {
    /// The table of `shaft` on a grid of about `step_deg`.
    pub fn new(shaft: &'a S, step_deg: f64) -> Result<Self, RippleError> {
        let step = STEP_DEG.check(step_deg)?.to_radians();
        let period = shaft.period_rad();
        if !(period.is_finite() && period > 0.0) {
            return Err(RippleError::field("period", format!("{period} rad: a repeat must be a positive angle")));
        }
        let n = (period / step).ceil().max(1.0) as usize;
        let h = period / n as f64;
        let mut nodes: Vec<f64> = (0..=n).map(|k| if k == n { period } else { k as f64 * h }).collect();
        let mut breaks: Vec<f64> = shaft.breaks_rad().into_iter().filter(|b| *b > 0.0 && *b < period).collect();
        if !breaks.is_empty() {
            breaks.sort_by(f64::total_cmp);
            nodes.extend(breaks);
            nodes.sort_by(f64::total_cmp);
            let tiny = 1e-9 * h;
            let mut kept: Vec<f64> = Vec::with_capacity(nodes.len());
            for x in nodes {
                if kept.last().is_none_or(|l| x - l > tiny) {
                    kept.push(x);
                } else if x == period {
                    *kept.last_mut().unwrap_or(&mut 0.0) = period;
                }
            }
            nodes = kept;
        }
        let m = nodes.len() - 1;
        let mut j = Vec::with_capacity(2 * m + 1);
        let mut ml = Vec::with_capacity(2 * m + 1);
        for k in 0..=m {
            for phi in std::iter::once(nodes[k]).chain((k < m).then(|| 0.5 * (nodes[k] + nodes[k + 1]))) {
                let (jj, _) = shaft.inertia(phi);
                j.push(jj);
                ml.push(shaft.load_torque(phi));
            }
        }
        let stride = (PRESOLVE_STEP_DEG.to_radians() / h).round() as usize;
        let coarse = coarse_grid(&nodes, h, stride);
        Ok(Self { shaft, period, nodes, j, ml, coarse })
    }

    /// The same table without the presolve: Newton's method on the grid itself from the first
    /// guess (the algorithm before the presolve; what tests compare it with).
    pub fn without_presolve(mut self) -> Self {
        self.coarse.clear();
        self
    }

    /// The grid points, rad (the first 0, the last the period).
    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    /// The shaft.
    pub fn shaft(&self) -> &S {
        self.shaft
    }

    /// The load's mean over the repeat, N·m (Simpson's rule on every interval).
    pub fn mean_load_n_m(&self) -> f64 {
        self.load_work_j() / self.period
    }

    /// The work the load takes over the repeat, J (Simpson's rule on every interval).
    pub fn load_work_j(&self) -> f64 {
        (0..self.nodes.len() - 1)
            .map(|k| {
                (self.nodes[k + 1] - self.nodes[k]) / 6.0
                    * (self.ml[2 * k] + 4.0 * self.ml[2 * k + 1] + self.ml[2 * k + 2])
            })
            .sum()
    }

    /// The smallest `J` on the grid (points and midpoints), kg·m².
    pub fn min_inertia(&self) -> f64 {
        self.j.iter().copied().fold(f64::INFINITY, f64::min)
    }
}

/// The motor as the integrator sees it: its constants computed once.
#[derive(Debug, Clone, Copy)]
enum Drive {
    Constant(f64),
    /// Gear ratio `i`, `i/ω_s`, and `M(s)` as `a·s/(s² + s_b²)` (Kloss) or `a·s` (line, `kloss` false).
    Induction {
        ratio_over_sync: f64,
        a: f64,
        sb2: f64,
        kloss: bool,
    },
    Servo(Servo),
}

/// A motor's torque and integrator rate with their partial derivatives in ω and z.
#[derive(Debug, Clone, Copy)]
struct Eval {
    m: f64,
    dz: f64,
    m_w: f64,
    m_z: f64,
    dz_w: f64,
}

impl Drive {
    fn induction(ind: &Induction) -> Self {
        let i = ind.gear_ratio;
        let (a, sb2, kloss) = match ind.curve {
            MotorCurve::Linear => (i * ind.rated_torque_n_m / ind.rated_slip(), 0.0, false),
            MotorCurve::Kloss => {
                let sb = ind.breakdown_slip();
                (2.0 * i * ind.breakdown_ratio * ind.rated_torque_n_m * sb, sb * sb, true)
            }
        };
        Self::Induction { ratio_over_sync: i / ind.synchronous_rad_s, a, sb2, kloss }
    }

    /// Torque and `dz/dφ` at speed `w`, integrator `z`, with their partials.
    #[inline(always)]
    fn eval(&self, w: f64, z: f64) -> Eval {
        match *self {
            Self::Constant(m) => Eval { m, dz: 0.0, m_w: 0.0, m_z: 0.0, dz_w: 0.0 },
            Self::Induction { ratio_over_sync: r, a, sb2, kloss } => {
                let s = 1.0 - r * w;
                if kloss {
                    let den = s * s + sb2;
                    let m = a * s / den;
                    Eval { m, dz: 0.0, m_w: -r * a * (sb2 - s * s) / (den * den), m_z: 0.0, dz_w: 0.0 }
                } else {
                    Eval { m: a * s, dz: 0.0, m_w: -r * a, m_z: 0.0, dz_w: 0.0 }
                }
            }
            Self::Servo(sv) => {
                let e = sv.speed_rad_s - w;
                let raw = z + sv.gain_n_m_s * e;
                let l = sv.torque_limit_n_m;
                let (m, limited) = if raw > l {
                    (l, true)
                } else if raw < -l {
                    (-l, true)
                } else {
                    (raw, false)
                };
                let (m_w, m_z) = if limited { (0.0, 0.0) } else { (-sv.gain_n_m_s, 1.0) };
                let ki = sv.gain_n_m_s / sv.integral_s;
                let (dz, dz_w) = if limited && (m > 0.0) == (e > 0.0) {
                    (0.0, 0.0)
                } else {
                    (ki * e / w, -ki * sv.speed_rad_s / (w * w))
                };
                Eval { m, dz, m_w, m_z, dz_w }
            }
        }
    }
}

/// The state at the end of one pass over the repeat, and its derivatives in the start.
#[derive(Debug, Clone, Copy)]
struct End {
    e: f64,
    z: f64,
    /// Time of the repeat, s.
    t: f64,
    /// `∫M_motor² dt`.
    q: f64,
    /// `∫M_motor dφ`.
    w: f64,
    /// `∂(E, z)(P)/∂(E₀, z₀)` (rows E, z).
    jac: [[f64; 2]; 2],
    /// `∂t(P)/∂(E₀, z₀)`.
    dt: [f64; 2],
}

/// Values at the grid points of a recorded pass.
#[derive(Debug, Clone, Default)]
struct Record {
    e: Vec<f64>,
    de: Vec<f64>,
    z: Vec<f64>,
    dz: Vec<f64>,
    /// Time from the repeat's start, s.
    t: Vec<f64>,
}

impl Record {
    fn clear(&mut self) {
        self.e.clear();
        self.de.clear();
        self.z.clear();
        self.dz.clear();
        self.t.clear();
    }

    fn push(&mut self, e: f64, z: f64, de: f64, dz: f64, t: f64) {
        self.e.push(e);
        self.de.push(de);
        self.z.push(z);
        self.dz.push(dz);
        self.t.push(t);
    }
}

/// One stage of the rule: the rates of `(E, z, t, ∫M²dt, ∫M dφ)`, the Jacobian of `(E′, z′)` in
/// `(E, z)` and the derivative of `t′ = 1/ω` in `E`.
struct Stage {
    f: [f64; 5],
    a: [[f64; 2]; 2],
    t_e: f64,
}

impl<S: Shaft + ?Sized> Table<'_, S> {
    #[inline(always)]
    fn stage(&self, inv_j: &[f64], drive: &Drive, i: usize, e: f64, z: f64) -> Option<Stage> {
        if e.is_nan() || e <= 0.0 {
            return None;
        }
        let ij = inv_j[i];
        // ω on the critical path first (the next stage waits for it); 1/ω beside it.
        let om = (2.0 * e * ij).sqrt();
        let ev = drive.eval(om, z);
        let inv = 1.0 / om;
        // dω/dE = 1/(J·ω).
        let g = ij * inv;
        Some(Stage {
            f: [ev.m - self.ml[i], ev.dz, inv, ev.m * ev.m * inv, ev.m],
            a: [[ev.m_w * g, ev.m_z], [ev.dz_w * g, 0.0]],
            t_e: -g * inv * inv,
        })
    }

    /// One fourth-order Runge–Kutta pass over the repeat from `(e0, z0)`, with the derivatives
    /// of the end in the start (the rule applied to the variational equations: the exact
    /// derivative of the discrete map); `None` when the shaft stops (`E ≤ 0` at a stage).
    ///
    /// `COARSE`: over the presolve's coarse grid (each interval a run of equal fine ones, its
    /// midpoint a fine point or midpoint); never recorded.
    fn pass<const COARSE: bool>(
        &self,
        inv_j: &[f64],
        drive: &Drive,
        e0: f64,
        z0: f64,
        mut rec: Option<&mut Record>,
    ) -> Option<End> {
        let two = matches!(drive, Drive::Servo(_));
        let (mut e, mut z) = (e0, z0);
        let (mut t, mut q, mut w) = (0.0, 0.0, 0.0);
        let mut p = [[1.0, 0.0], [0.0, 1.0]];
        let mut dt = [0.0, 0.0];
        let mul = |a: &[[f64; 2]; 2], x: &[[f64; 2]; 2]| {
            [
                [a[0][0] * x[0][0] + a[0][1] * x[1][0], a[0][0] * x[0][1] + a[0][1] * x[1][1]],
                [a[1][0] * x[0][0] + a[1][1] * x[1][0], a[1][0] * x[0][1] + a[1][1] * x[1][1]],
            ]
        };
        let axpy = |x: &[[f64; 2]; 2], c: f64, y: &[[f64; 2]; 2]| {
            [[x[0][0] + c * y[0][0], x[0][1] + c * y[0][1]], [x[1][0] + c * y[1][0], x[1][1] + c * y[1][1]]]
        };
        let m = if COARSE { self.coarse.len() - 1 } else { self.nodes.len() - 1 };
        for k in 0..m {
            let (a, b) = if COARSE { (self.coarse[k], self.coarse[k + 1]) } else { (k, k + 1) };
            let h = self.nodes[b] - self.nodes[a];
            let s1 = self.stage(inv_j, drive, 2 * a, e, z)?;
            if let Some(r) = rec.as_deref_mut() {
                r.push(e, z, s1.f[0], s1.f[1], t);
            }
            let s2 = self.stage(inv_j, drive, a + b, e + 0.5 * h * s1.f[0], z + 0.5 * h * s1.f[1])?;
            let s3 = self.stage(inv_j, drive, a + b, e + 0.5 * h * s2.f[0], z + 0.5 * h * s2.f[1])?;
            let s4 = self.stage(inv_j, drive, 2 * b, e + h * s3.f[0], z + h * s3.f[1])?;
            // The variational equations through the same stages (E alone for a motor without state).
            if !two {
                let k1 = s1.a[0][0] * p[0][0];
                let p2 = p[0][0] + 0.5 * h * k1;
                let k2 = s2.a[0][0] * p2;
                let p3 = p[0][0] + 0.5 * h * k2;
                let k3 = s3.a[0][0] * p3;
                let p4 = p[0][0] + h * k3;
                let k4 = s4.a[0][0] * p4;
                dt[0] += h / 6.0 * (s1.t_e * p[0][0] + 2.0 * (s2.t_e * p2 + s3.t_e * p3) + s4.t_e * p4);
                p[0][0] += h / 6.0 * (k1 + 2.0 * (k2 + k3) + k4);
                let s = |c: usize| h / 6.0 * (s1.f[c] + 2.0 * (s2.f[c] + s3.f[c]) + s4.f[c]);
                e += s(0);
                t += s(2);
                q += s(3);
                w += s(4);
                continue;
            }
            let k1 = mul(&s1.a, &p);
            let p2 = axpy(&p, 0.5 * h, &k1);
            let k2 = mul(&s2.a, &p2);
            let p3 = axpy(&p, 0.5 * h, &k2);
            let k3 = mul(&s3.a, &p3);
            let p4 = axpy(&p, h, &k3);
            let k4 = mul(&s4.a, &p4);
            for c in 0..2 {
                dt[c] +=
                    h / 6.0 * (s1.t_e * p[0][c] + 2.0 * (s2.t_e * p2[0][c] + s3.t_e * p3[0][c]) + s4.t_e * p4[0][c]);
                for r in 0..2 {
                    p[r][c] += h / 6.0 * (k1[r][c] + 2.0 * (k2[r][c] + k3[r][c]) + k4[r][c]);
                }
            }
            let s = |c: usize| h / 6.0 * (s1.f[c] + 2.0 * (s2.f[c] + s3.f[c]) + s4.f[c]);
            e += s(0);
            z += s(1);
            t += s(2);
            q += s(3);
            w += s(4);
        }
        if let Some(r) = rec {
            let s1 = self.stage(inv_j, drive, 2 * (self.nodes.len() - 1), e, z)?;
            r.push(e, z, s1.f[0], s1.f[1], t);
        }
        Some(End { e, z, t, q, w, jac: p, dt })
    }

    /// The periodic start by Newton's method ([`Table::newton`]) on the grid, from the periodic
    /// start of the coarse grid when there is one (found from `guess`); from `guess` itself when
    /// there is none or when Newton fails from it.
    #[allow(clippy::too_many_arguments)]
    fn periodic(
        &self,
        inv_j: &[f64],
        drive: &Drive,
        guess: [f64; 2],
        scale: [f64; 2],
        two: bool,
        residual: &Residual<'_>,
        rec: &mut Record,
    ) -> Option<([f64; 2], End)> {
        if !self.coarse.is_empty()
            && let Some((x, _)) = self.newton::<true>(inv_j, drive, guess, scale, two, residual, None)
            && let Some(found) = self.newton::<false>(inv_j, drive, x, scale, two, residual, Some(&mut *rec))
        {
            return Some(found);
        }
        self.newton::<false>(inv_j, drive, guess, scale, two, residual, Some(rec))
    }

    /// Newton's method on `residual(start, end)` (one or two unknowns; `two`: the servo's z too),
    /// its Jacobian from the pass's derivatives, each step halved while it stalls the shaft or
    /// raises the scaled residual. Returns the start and the end of the pass from it, which has
    /// been recorded in `rec`; `None` when it does not converge (the caller falls back on a bracketing search).
    ///
    /// On the grid it stops when the next step would move the start by rounding only (10⁻¹³ of
    /// `scale`). On the coarse grid (`COARSE`, no record) it stops sooner, when the step is below
    /// [`PRESOLVE_TOL`] (Newton's next error is of its square), and returns the start after that
    /// step with the end of the pass before it.
    #[allow(clippy::too_many_arguments)]
    fn newton<const COARSE: bool>(
        &self,
        inv_j: &[f64],
        drive: &Drive,
        start: [f64; 2],
        scale: [f64; 2],
        two: bool,
        residual: &Residual<'_>,
        mut rec: Option<&mut Record>,
    ) -> Option<([f64; 2], End)> {
        let norm = |r: [f64; 2]| (r[0] / scale[0]).abs().max(if two { (r[1] / scale[1]).abs() } else { 0.0 });
        let mut run = |x: [f64; 2]| {
            if let Some(r) = rec.as_deref_mut() {
                r.clear();
            }
            self.pass::<COARSE>(inv_j, drive, x[0], x[1], rec.as_deref_mut())
        };
        let tol = if COARSE { PRESOLVE_TOL } else { 1e-13 };
        let mut x = start;
        let mut end = run(x)?;
        let (mut r, mut d) = residual(x, &end);
        for _ in 0..50 {
            let step = if two {
                let det = d[0][0] * d[1][1] - d[0][1] * d[1][0];
                if !(det.is_finite() && det != 0.0) {
                    return None;
                }
                [(d[1][1] * r[0] - d[0][1] * r[1]) / det, (d[0][0] * r[1] - d[1][0] * r[0]) / det]
            } else {
                if !(d[0][0].is_finite() && d[0][0] != 0.0) {
                    return None;
                }
                [r[0] / d[0][0], 0.0]
            };
            // Converged: the next step would move the start by rounding only (on the coarse grid:
            // by less than its error on the grid itself).
            if norm(step) <= tol {
                if COARSE {
                    x = [x[0] - step[0], x[1] - step[1]];
                }
                return Some((x, end));
            }
            let mut lambda = 1.0;
            let mut accepted = false;
            for _ in 0..30 {
                let y = [x[0] - lambda * step[0], x[1] - lambda * step[1]];
                if let Some(ey) = run(y) {
                    let (ry, dy) = residual(y, &ey);
                    if norm(ry) < norm(r) || norm(step) * lambda <= 1e-9 {
                        (x, end, r, d) = (y, ey, ry, dy);
                        accepted = true;
                        break;
                    }
                }
                lambda *= 0.5;
            }
            if !accepted {
                return None;
            }
        }
        None
    }
}

/// A periodicity residual and its Jacobian from a start and the end of the pass from it.
type Residual<'r> = dyn Fn([f64; 2], &End) -> ([f64; 2], [[f64; 2]; 2]) + 'r;

/// Where the presolve on the coarse grid stops: a Newton step below this (relative to the start's
/// scale) leaves an error of about its square, below the two grids' difference.
const PRESOLVE_TOL: f64 = 1e-6;

/// The root of a decreasing function from a positive guess; `None` from `f` means the shot
/// stalled, which happens only below the root (a slower start stays slower everywhere).
fn decreasing_root(
    f: impl Fn(f64) -> Option<f64>,
    guess: f64,
    fail: impl Fn(&str) -> RippleError,
) -> Result<f64, RippleError> {
    let mut lo: Option<(f64, f64)> = None;
    let mut hi: Option<(f64, f64)> = None;
    let mut x = guess;
    // Upward until a negative value.
    for _ in 0..200 {
        match f(x) {
            Some(0.0) => return Ok(x),
            Some(v) if v < 0.0 => {
                hi = Some((x, v));
                break;
            }
            Some(v) => lo = Some((x, v)),
            None => {}
        }
        x *= 2.0;
    }
    let Some((mut xh, mut vh)) = hi else {
        return Err(fail("the motor accelerates the shaft without bound"));
    };
    let (xl, vl) = match lo {
        Some(p) => p,
        None => {
            let mut x = xh;
            let mut found = None;
            for _ in 0..200 {
                x *= 0.5;
                match f(x) {
                    Some(0.0) => return Ok(x),
                    Some(v) if v > 0.0 => {
                        found = Some((x, v));
                        break;
                    }
                    Some(v) => (xh, vh) = (x, v),
                    None => {
                        let (l, _) = loomkin_numeric::bisect_bracket(x, xh, |t| f(t).is_none_or(|v| v > 0.0));
                        match f(l) {
                            Some(v) if v > 0.0 => found = Some((l, v)),
                            _ => return Err(fail("the motor cannot keep the shaft turning: it stops")),
                        }
                        break;
                    }
                }
            }
            found.ok_or_else(|| fail("no start keeps the shaft turning"))?
        }
    };
    let big = vl.abs() * 1e6 + 1.0;
    Ok(loomkin_numeric::illinois_root(xl, xh, vl, vh, |t| f(t).unwrap_or(big)))
}

/// The steady running of the shaft over one repeat.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RippleReport {
    /// The motor model.
    pub motor: &'static str,
    /// Mean speed, rpm: the repeat's angle over its time.
    pub mean_speed_rpm: f64,
    /// Lowest speed, rpm (located between the grid points).
    pub min_speed_rpm: f64,
    /// Where, deg within the repeat.
    pub min_speed_angle_deg: f64,
    /// Highest speed, rpm.
    pub max_speed_rpm: f64,
    /// Where, deg within the repeat.
    pub max_speed_angle_deg: f64,
    /// `(ω_max − ω_min)/ω_mean · 100`.
    pub speed_ripple_pct: f64,
    /// Largest less smallest kinetic energy `½Jω²` over the repeat, J (the work the motor and
    /// the load exchange with the moving masses).
    pub energy_swing_j: f64,
    /// Largest |motor torque| at the main shaft, N·m.
    pub peak_motor_torque_n_m: f64,
    /// RMS motor torque over time (what heats the motor), N·m.
    pub rms_motor_torque_n_m: f64,
    /// Mean load torque over the repeat's angle, N·m.
    pub mean_load_torque_n_m: f64,
    /// Work the motor gives over the repeat, J.
    pub motor_work_j: f64,
    /// Work the load takes over the repeat, J (equal to the motor's in steady running).
    pub load_work_j: f64,
    /// The added inertia (flywheel) of this solution, kg·m².
    pub flywheel_kg_m2: f64,
    /// Points of the integration grid over the repeat (both its ends counted).
    pub points: usize,
}

/// The periodic solution: the report and the curves at the grid points.
#[derive(Debug, Clone)]
pub struct Solution<'t, 'a, S: Shaft + ?Sized> {
    table: &'t Table<'a, S>,
    drive: Drive,
    extra: f64,
    rec: Record,
    /// The report.
    pub report: RippleReport,
}

impl<S: Shaft + ?Sized> Solution<'_, '_, S> {
    /// Grid points, rad.
    pub fn angles_rad(&self) -> &[f64] {
        &self.table.nodes
    }

    /// Kinetic energy at the grid points, J.
    pub fn energy_j(&self) -> &[f64] {
        &self.rec.e
    }

    /// `E` and `z` between the grid points (cubic Hermite), and the interval.
    fn interpolate(&self, phi: f64) -> (f64, f64) {
        let p = self.table.period;
        let phi = phi.rem_euclid(p);
        let nodes = &self.table.nodes;
        let k = nodes.partition_point(|x| *x <= phi).clamp(1, nodes.len() - 1) - 1;
        let h = nodes[k + 1] - nodes[k];
        let s = (phi - nodes[k]) / h;
        let (h00, h10, h01, h11) =
            ((1.0 + 2.0 * s) * (1.0 - s).powi(2), s * (1.0 - s).powi(2), s * s * (3.0 - 2.0 * s), s * s * (s - 1.0));
        let r = &self.rec;
        let e = h00 * r.e[k] + h10 * h * r.de[k] + h01 * r.e[k + 1] + h11 * h * r.de[k + 1];
        let z = h00 * r.z[k] + h10 * h * r.dz[k] + h01 * r.z[k + 1] + h11 * h * r.dz[k + 1];
        (e, z)
    }

    /// Kinetic energy at any angle, J.
    pub fn energy_at(&self, phi_rad: f64) -> f64 {
        self.interpolate(phi_rad).0
    }

    /// Shaft speed at any angle, rad/s.
    pub fn omega_at(&self, phi_rad: f64) -> f64 {
        let (e, _) = self.interpolate(phi_rad);
        let j = self.table.shaft.inertia(phi_rad.rem_euclid(self.table.period)).0 + self.extra;
        (2.0 * e / j).sqrt()
    }

    /// Motor torque at any angle, N·m.
    pub fn motor_torque_at(&self, phi_rad: f64) -> f64 {
        let (_, z) = self.interpolate(phi_rad);
        self.drive.eval(self.omega_at(phi_rad), z).m
    }

    /// Speed at the grid points, rad/s.
    pub fn omega(&self) -> Vec<f64> {
        (0..self.table.nodes.len()).map(|k| (2.0 * self.rec.e[k] / (self.table.j[2 * k] + self.extra)).sqrt()).collect()
    }

    /// Motor torque at the grid points, N·m.
    pub fn motor_torque(&self) -> Vec<f64> {
        let w = self.omega();
        (0..w.len()).map(|k| self.drive.eval(w[k], self.rec.z[k]).m).collect()
    }

    /// Load torque at the grid points, N·m.
    pub fn load_torque(&self) -> Vec<f64> {
        (0..self.table.nodes.len()).map(|k| self.table.ml[2 * k]).collect()
    }

    /// `loomkin drive ripple --csv`'s columns at the grid points: `angle_deg`, `speed_rpm`,
    /// `motor_torque_n_m`, `load_torque_n_m`, `energy_j`.
    pub fn columns(&self) -> Vec<(&'static str, Vec<f64>)> {
        let w = self.omega();
        vec![
            ("angle_deg", self.table.nodes.iter().map(|phi| phi.to_degrees()).collect()),
            ("speed_rpm", w.iter().map(|w| rpm_from_rad_per_s(*w)).collect()),
            ("motor_torque_n_m", self.motor_torque()),
            ("load_torque_n_m", self.load_torque()),
            ("energy_j", self.rec.e.clone()),
        ]
    }

    /// Time from the repeat's start at the grid points, s (the rule's own integral of `dφ/ω`,
    /// whose last value is the repeat's time).
    pub fn time_s(&self) -> &[f64] {
        &self.rec.t
    }

    /// The shaft's time as a function of its angle ([`crate::timetrue::TimeMap`]): at the grid
    /// points the time, `1/ω` and `−ω′/ω²` (with `ω′ = ω/2·(E′/E − J′/J)`, `E′` the balance's
    /// `M_motor − M_load`), a quintic Hermite interpolant between them.
    pub fn time_map(&self) -> crate::timetrue::TimeMap {
        let w = self.omega();
        let dw: Vec<f64> = (0..w.len())
            .map(|k| {
                let phi = self.table.nodes[k];
                let (_, dj) = self.table.shaft.inertia(phi.rem_euclid(self.table.period));
                let j = self.table.j[2 * k] + self.extra;
                0.5 * w[k] * (self.rec.de[k] / self.rec.e[k] - dj / j)
            })
            .collect();
        crate::timetrue::TimeMap::new(self.table.nodes.clone(), self.rec.t.clone(), w, dw)
    }
}

/// The largest value of `f` over the repeat, (value, angle): the grid's `values` on `nodes` refined
/// ([`loomkin_numeric::periodic_scan_max`]).
fn refined_max(nodes: &[f64], values: &[f64], f: impl Fn(f64) -> f64) -> (f64, f64) {
    let m = loomkin_numeric::periodic_scan_max(nodes.len() - 1, |k| nodes[k], |k| values[k], f);
    (m.value, m.at)
}

/// The steady running of the shaft of `table` turned by `motor`, with `flywheel_kg_m2` added to
/// its inertia.
pub fn solve<'t, 'a, S: Shaft + ?Sized>(
    table: &'t Table<'a, S>,
    motor: &Motor,
    flywheel_kg_m2: f64,
) -> Result<Solution<'t, 'a, S>, RippleError> {
    let extra = FLYWHEEL_KG_M2.check(flywheel_kg_m2)?;
    let jmin = table.min_inertia() + extra;
    let jmax = table.j.iter().copied().fold(f64::NEG_INFINITY, f64::max) + extra;
    // A shaft whose inertia all but vanishes somewhere (the frames dwelling, the sley at a dead
    // centre, nothing rotating) would spin up without bound there: ω = √(2E/J).
    let prefix = table.shaft.key_prefix();
    if jmin.is_nan() || jmin <= MIN_INERTIA_RATIO * jmax {
        return Err(RippleError::field(
            format!("{prefix}rotating_inertia_kg_m2"),
            format!(
                "the shaft's inertia falls to {} kg·m² (largest {} kg·m²) where the mechanisms stand still: give the rotating parts' inertia (> 0 kg·m²)",
                loomkin_units::compact(jmin),
                loomkin_units::compact(jmax)
            ),
        ));
    }
    let p = table.period;
    let j0 = table.j[0] + extra;
    let mean_load = table.mean_load_n_m();
    let inv_j: Vec<f64> = table.j.iter().map(|j| 1.0 / (j + extra)).collect();
    let motor_field = |what: &str| RippleError::infeasible(format!("{prefix}motor"), what.to_string());
    let stops = || motor_field("the motor cannot keep the shaft turning: it stops");
    let mut rec = Record::default();
    let (drive, (start, found)) = match *motor {
        Motor::Constant { speed_rad_s } => {
            let drive = Drive::Constant(mean_load);
            let time = p / speed_rad_s;
            let guess = 0.5 * j0 * speed_rad_s * speed_rad_s;
            let residual = |_: [f64; 2], end: &End| ([end.t - time, 0.0], [[end.dt[0], 0.0], [0.0, 1.0]]);
            let x = match table.periodic(&inv_j, &drive, [guess, 0.0], [guess, 1.0], false, &residual, &mut rec) {
                Some((x, end)) => (x, Some(end)),
                None => {
                    let e0 = decreasing_root(
                        |e0| table.pass::<false>(&inv_j, &drive, e0, 0.0, None).map(|end| end.t - time),
                        guess,
                        motor_field,
                    )?;
                    ([e0, 0.0], None)
                }
            };
            (drive, x)
        }
        Motor::Induction(ind) => {
            let drive = Drive::induction(&ind);
            let top = ind.synchronous_rad_s / ind.gear_ratio;
            if mean_load >= ind.max_torque_n_m() {
                return Err(motor_field(&format!(
                    "the load's mean torque {mean_load:.6} N·m reaches the motor's breakdown torque {:.6} N·m at the main shaft",
                    ind.max_torque_n_m()
                )));
            }
            // The speed where the motor meets the mean load on its stable side: the first guess.
            let lo = ind.breakdown_speed_rad_s();
            let w = loomkin_numeric::bisect(lo, top, |w| ind.torque(w).0 > mean_load);
            let w = if w > 0.0 { w } else { 0.5 * top };
            let guess = 0.5 * j0 * w * w;
            let residual = |x: [f64; 2], end: &End| ([end.e - x[0], 0.0], [[end.jac[0][0] - 1.0, 0.0], [0.0, 1.0]]);
            let x = match table.periodic(&inv_j, &drive, [guess, 0.0], [guess, 1.0], false, &residual, &mut rec) {
                Some((x, end)) => (x, Some(end)),
                None => {
                    let e0 = decreasing_root(
                        |e0| table.pass::<false>(&inv_j, &drive, e0, 0.0, None).map(|end| end.e - e0),
                        guess,
                        motor_field,
                    )?;
                    ([e0, 0.0], None)
                }
            };
            (drive, x)
        }
        Motor::Servo(sv) => {
            let drive = Drive::Servo(sv);
            let guess = [
                0.5 * j0 * sv.speed_rad_s * sv.speed_rad_s,
                mean_load.clamp(-sv.torque_limit_n_m, sv.torque_limit_n_m),
            ];
            let residual = |x: [f64; 2], end: &End| {
                let j = end.jac;
                ([end.e - x[0], end.z - x[1]], [[j[0][0] - 1.0, j[0][1]], [j[1][0], j[1][1] - 1.0]])
            };
            let scale = [guess[0], sv.torque_limit_n_m];
            let (x, end) = table.periodic(&inv_j, &drive, guess, scale, true, &residual, &mut rec).ok_or_else(|| {
                RippleError::infeasible(
                    format!("{prefix}motor"),
                    format!(
                        "the servo finds no periodic running from its set-point: raise {prefix}servo_torque_limit_n_m or {prefix}servo_gain_n_m_s"
                    ),
                )
            })?;
            (drive, (x, Some(end)))
        }
    };
    let end = match found {
        Some(end) => end,
        None => {
            rec.clear();
            table.pass::<false>(&inv_j, &drive, start[0], start[1], Some(&mut rec)).ok_or_else(stops)?
        }
    };
    let mut sol = Solution { table, drive, extra, rec, report: empty_report(motor.name()) };
    let nodes = &table.nodes;
    let w = sol.omega();
    let (wmax, at_max) = refined_max(nodes, &w, |x| sol.omega_at(x));
    let neg: Vec<f64> = w.iter().map(|v| -v).collect();
    let (wmin, at_min) = refined_max(nodes, &neg, |x| -sol.omega_at(x));
    let wmin = -wmin;
    let e = &sol.rec.e;
    let (emax, _) = refined_max(nodes, e, |x| sol.energy_at(x));
    let eneg: Vec<f64> = e.iter().map(|v| -v).collect();
    let (neg_emin, _) = refined_max(nodes, &eneg, |x| -sol.energy_at(x));
    let mt: Vec<f64> = sol.motor_torque().iter().map(|m| m.abs()).collect();
    let (peak, _) = refined_max(nodes, &mt, |x| sol.motor_torque_at(x).abs());
    let mean = p / end.t;
    sol.report = RippleReport {
        motor: motor.name(),
        mean_speed_rpm: rpm_from_rad_per_s(mean),
        min_speed_rpm: rpm_from_rad_per_s(wmin),
        min_speed_angle_deg: at_min.to_degrees(),
        max_speed_rpm: rpm_from_rad_per_s(wmax),
        max_speed_angle_deg: at_max.to_degrees(),
        speed_ripple_pct: (wmax - wmin) / mean * 100.0,
        energy_swing_j: emax + neg_emin,
        peak_motor_torque_n_m: peak,
        rms_motor_torque_n_m: (end.q / end.t).sqrt(),
        mean_load_torque_n_m: mean_load,
        motor_work_j: end.w,
        load_work_j: table.load_work_j(),
        flywheel_kg_m2: extra,
        points: nodes.len(),
    };
    Ok(sol)
}

fn empty_report(motor: &'static str) -> RippleReport {
    RippleReport {
        motor,
        mean_speed_rpm: 0.0,
        min_speed_rpm: 0.0,
        min_speed_angle_deg: 0.0,
        max_speed_rpm: 0.0,
        max_speed_angle_deg: 0.0,
        speed_ripple_pct: 0.0,
        energy_swing_j: 0.0,
        peak_motor_torque_n_m: 0.0,
        rms_motor_torque_n_m: 0.0,
        mean_load_torque_n_m: 0.0,
        motor_work_j: 0.0,
        load_work_j: 0.0,
        flywheel_kg_m2: 0.0,
        points: 0,
    }
}

/// The least inertia of a shaft the solver takes, relative to its largest: below it the shaft is
/// all but free somewhere and its speed there unbounded.
const MIN_INERTIA_RATIO: f64 = 1e-6;

/// The largest flywheel, kg·m².
const MAX_FLYWHEEL_KG_M2: f64 = 1e6;

/// `flywheel_kg_m2`: inertia added to the main shaft.
pub const FLYWHEEL_KG_M2: Field = Field::new(
    "flywheel_kg_m2",
    Range::closed(0.0, MAX_FLYWHEEL_KG_M2, "kg·m²"),
    "Inertia added to the main shaft (a flywheel), kg·m²: 0 … 10⁶.",
)
.with_default(0.0);

/// The loom speeds of a ripple-against-speed sweep (the workbench's), relative to the loom's own
/// speed: from half to one and a half times it (the motor's model built for each speed).
pub const SWEEP_SPEED_RATIO: [f64; 2] = [0.5, 1.5];

/// The grid step of a ripple-against-speed sweep, deg: ten times [`STEP_DEG`]'s default, for a tenth
/// of the time; on the examples' looms its ripple lies within 2·10⁻⁸ (relative) of the default
/// grid's (the rule is fourth order and the loads are smooth between the grid's breaks; the rapier's
/// cam sley, 70° moves at 500 rpm, is the farthest: 1.4·10⁻⁸).
pub const SWEEP_STEP_DEG: f64 = 1.0;

/// `target_ripple_pct`: the speed ripple a flywheel is sized for.
pub const TARGET_RIPPLE_PCT: Field = Field::new(
    "target_ripple_pct",
    Range::open(0.0, 200.0, "%"),
    "The speed ripple (ω_max − ω_min)/ω_mean·100 a flywheel is sized to hold: above 0, below 200 %.",
);

/// The least flywheel that holds the speed ripple at `target_pct` (a root of the ripple, which
/// falls as the inertia grows, by regula falsi on `1/ripple`, nearly linear in the inertia), with
/// its solution; no flywheel (0) when the shaft already holds it.
pub fn flywheel_for<'t, 'a, S: Shaft + ?Sized>(
    table: &'t Table<'a, S>,
    motor: &Motor,
    target_pct: f64,
) -> Result<(f64, Solution<'t, 'a, S>), RippleError> {
    let target = TARGET_RIPPLE_PCT.check(target_pct)?;
    let bare = solve(table, motor, 0.0)?;
    if bare.report.speed_ripple_pct <= target {
        return Ok((0.0, bare));
    }
    let g = |jf: f64| -> Result<f64, RippleError> {
        let r = solve(table, motor, jf)?.report.speed_ripple_pct;
        Ok(1.0 / r - 1.0 / target)
    };
    // First guess from flywheel practice: I = ΔE/(δ·ω²).
    let w = loomkin_units::rad_per_s_from_rpm(bare.report.mean_speed_rpm);
    let mut hi = (bare.report.energy_swing_j / (target / 100.0 * w * w)).max(1e-9);
    let mut ghi = g(hi)?;
    let mut tries = 0;
    while ghi < 0.0 {
        hi *= 4.0;
        tries += 1;
        if tries > 40 || hi > MAX_FLYWHEEL_KG_M2 {
            return Err(RippleError::infeasible(
                "target_ripple_pct",
                format!("no flywheel up to 10⁶ kg·m² holds the ripple at {target} %"),
            ));
        }
        ghi = g(hi)?;
    }
    let glo = 1.0 / bare.report.speed_ripple_pct - 1.0 / target;
    let err = std::cell::RefCell::new(None);
    let root = loomkin_numeric::illinois_root(0.0, hi, glo, ghi, |jf| match g(jf) {
        Ok(v) => v,
        Err(e) => {
            err.borrow_mut().get_or_insert(e);
            0.0
        }
    });
    if let Some(e) = err.into_inner() {
        return Err(e);
    }
    Ok((root, solve(table, motor, root)?))
}
