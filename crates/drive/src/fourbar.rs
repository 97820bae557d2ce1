//! The crank-rocker four-bar loop, solved in closed form with analytic rates: the one loop the
//! sley ([`crate::FourBarSley`]) and the rapier's crank drive (loomkin-insertion) both ride on.
//!
//! **Frame.** The crank centre O is the origin. The crank pin is `A = r·e(α)`, the rocker's pivot
//! `Q = (qx, qy)`, the rocker's pin (where the rod meets the rocker) `B = Q + c·e(θ)` and the rod
//! `B − A = b·e(β)`; `e(x) = (cos x, sin x)`.
//!
//! **Loop.** With `d = A − Q`, `s = |d|`, the triangle Q-A-B has sides `s`, `c`, `b`; its angle at Q
//! is `γ = atan2(√((s+b+c)(−s+b+c)(s−b+c)(s+b−c)), s² + c² − b²)` and `θ = atan2(d) + κ·γ`, where
//! κ = ±1 is the assembly branch (B to the left of Q→A for +1). For a crank-rocker
//! ([`CrankRocker::check`]) `0 < γ < π` at every crank angle, so the branch never changes and every
//! rate is finite.
//!
//! **Rates** (per radian of crank) from the loop `A + b·e(β) = Q + c·e(θ)` differentiated once,
//! twice and three times and projected on `e(β)` (which removes the rod's unknown rates) and on
//! `e(θ)`:
//! `θ' = r·sin(β−α) / (c·sin(β−θ))`, `β' = r·sin(α−θ) / (b·sin(θ−β))`,
//! `θ'' = (c·θ'²·cos(θ−β) − r·cos(α−β) − b·β'²) / (c·sin(β−θ))`,
//! `β'' = (r·cos(α−θ) + b·β'²·cos(β−θ) − c·θ'²) / (b·sin(θ−β))`,
//! `θ''' = θ'³ + (3c·θ'·θ''·cos(θ−β) − r·sin(β−α) − 3b·β'·β'') / (c·sin(β−θ))`.
//!
//! **Dead centres** are where crank and rod are collinear (`θ' = 0`): the rocker's pin at distance
//! `b + r` (extended) or `b − r` (folded) from O, each on the circle of radius `c` about Q — a circle
//! intersection in closed form, the candidate on the linkage's branch.

use std::f64::consts::PI;

/// The angle at the vertex between sides `p` and `q` of a triangle whose third side is `o`:
/// `atan2(√((p+q+o)(−p+q+o)(p−q+o)(p+q−o)), p² + q² − o²)`, exact at every shape (no `acos`).
pub fn triangle_angle(p: f64, q: f64, o: f64) -> f64 {
    let area16 = ((p + q + o) * (-p + q + o) * (p - q + o) * (p + q - o)).max(0.0);
    area16.sqrt().atan2(p * p + q * q - o * o)
}

/// Which of Grashof's crank-rocker conditions a set of lengths breaks ([`CrankRocker::check`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Breaks {
    /// `r ≥ d`: the crank reaches the rocker's pivot.
    CrankReachesPivot,
    /// `d + r ≥ b + c`: the loop does not close with the crank pointing away from the pivot.
    OpensAway,
    /// `d − r ≤ |b − c|`: the loop does not close with the crank pointing toward the pivot.
    OpensToward,
}

/// A crank-rocker four-bar: crank `r`, rod `b`, rocker `c`, the rocker's pivot at `(qx, qy)` from
/// the crank centre, on branch `kappa` (±1). Lengths in any one unit (loomkin passes metres).
///
/// ```
/// use loomkin_drive::fourbar::CrankRocker;
///
/// let l = CrankRocker::new(0.04, 0.12, 0.2, 0.12, -0.2, 1.0).unwrap();
/// let (alpha, theta) = l.dead_centre(true);
/// let s = l.at_crank(alpha);
/// assert!((s.rocker_rad - theta).abs() < 1e-12 && s.rocker_d1.abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrankRocker {
    /// Crank radius.
    pub r: f64,
    /// Rod, crank pin to the rocker's pin.
    pub b: f64,
    /// Rocker, pivot to the rod's pin.
    pub c: f64,
    /// The rocker's pivot, x from the crank centre.
    pub qx: f64,
    /// The rocker's pivot, y from the crank centre.
    pub qy: f64,
    /// The assembly branch: +1 with the rocker's pin to the left of Q→A, −1 to its right.
    pub kappa: f64,
}

/// The loop at one crank angle: positions and rates per radian of crank.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoopState {
    /// Crank angle α from +x, rad.
    pub crank_rad: f64,
    /// Rocker angle θ from +x, rad.
    pub rocker_rad: f64,
    /// dθ/dα.
    pub rocker_d1: f64,
    /// d²θ/dα², per rad².
    pub rocker_d2: f64,
    /// d³θ/dα³, per rad³.
    pub rocker_d3: f64,
    /// Rod angle β from +x (direction from crank pin to rocker's pin), rad.
    pub rod_rad: f64,
    /// dβ/dα.
    pub rod_d1: f64,
    /// d²β/dα².
    pub rod_d2: f64,
}

impl CrankRocker {
    /// Which crank-rocker condition the lengths break, if any, with `d = |Q|`: `r < d`,
    /// `d + r < b + c` and `d − r > |b − c|`, all strict (so rod and rocker are never collinear and
    /// every rate is finite). Together they are Grashof's condition with the crank the shortest link.
    pub fn check(r: f64, b: f64, c: f64, qx: f64, qy: f64) -> Option<Breaks> {
        let d = qx.hypot(qy);
        if r >= d {
            Some(Breaks::CrankReachesPivot)
        } else if d + r >= b + c {
            Some(Breaks::OpensAway)
        } else if d - r <= (b - c).abs() {
            Some(Breaks::OpensToward)
        } else {
            None
        }
    }

    /// A crank-rocker, checked ([`CrankRocker::check`]); `kappa` is taken by its sign.
    pub fn new(r: f64, b: f64, c: f64, qx: f64, qy: f64, kappa: f64) -> Result<Self, Breaks> {
        match Self::check(r, b, c, qx, qy) {
            Some(e) => Err(e),
            None => Ok(Self { r, b, c, qx, qy, kappa: if kappa < 0.0 { -1.0 } else { 1.0 } }),
        }
    }

    /// Distance of the rocker's pivot from the crank centre.
    pub fn pivot_distance(&self) -> f64 {
        self.qx.hypot(self.qy)
    }

    /// The rocker angle θ at crank angle α, closed form (the position only, no rates).
    pub fn rocker_at_crank(&self, alpha: f64) -> f64 {
        let (dx, dy) = (self.r * alpha.cos() - self.qx, self.r * alpha.sin() - self.qy);
        let s = (dx * dx + dy * dy).sqrt();
        dy.atan2(dx) + self.kappa * triangle_angle(s, self.c, self.b)
    }

    /// The loop at crank angle α: positions in closed form and the rocker's first three and the
    /// rod's first two rates per radian of crank (the formulas of the module's notes).
    pub fn at_crank(&self, alpha: f64) -> LoopState {
        let theta = self.rocker_at_crank(alpha);
        let (r, b, c) = (self.r, self.b, self.c);
        // Unit vectors of crank, rocker and rod; the sines and cosines of the angles between them
        // are their cross and dot products (sin(y − x) = e(x) × e(y), cos(y − x) = e(x)·e(y)).
        let (sa, ca) = alpha.sin_cos();
        let (st, ct) = theta.sin_cos();
        let (rx, ry) = (self.qx + c * ct - r * ca, self.qy + c * st - r * sa);
        let beta = ry.atan2(rx);
        let (cb, sb) = (rx / b, ry / b);
        let sin = |(x1, y1): (f64, f64), (x2, y2): (f64, f64)| x1 * y2 - y1 * x2;
        let cos = |(x1, y1): (f64, f64), (x2, y2): (f64, f64)| x1 * x2 + y1 * y2;
        let (ea, et, eb) = ((ca, sa), (ct, st), (cb, sb));
        let sbt = sin(et, eb);
        let cbt = cos(et, eb);
        let sba = sin(ea, eb);
        let cab = cos(ea, eb);
        let sat = sin(et, ea);
        let cat = cos(et, ea);
        let d1 = r * sba / (c * sbt);
        let b1 = -r * sat / (b * sbt);
        let d2 = (c * d1 * d1 * cbt - r * cab - b * b1 * b1) / (c * sbt);
        let b2 = -(r * cat + b * b1 * b1 * cbt - c * d1 * d1) / (b * sbt);
        let d3 = d1 * d1 * d1 + (3.0 * c * d1 * d2 * cbt - r * sba - 3.0 * b * b1 * b2) / (c * sbt);
        LoopState {
            crank_rad: alpha,
            rocker_rad: theta,
            rocker_d1: d1,
            rocker_d2: d2,
            rocker_d3: d3,
            rod_rad: beta,
            rod_d1: b1,
            rod_d2: b2,
        }
    }

    /// The crank angle α and the rocker angle θ of a dead centre: the rocker's pin at `b + r`
    /// (`extended`) or `b − r` from O, on the circle of radius c about Q, on this linkage's branch.
    pub fn dead_centre(&self, extended: bool) -> (f64, f64) {
        let l = if extended { self.b + self.r } else { self.b - self.r };
        let d = self.qx.hypot(self.qy);
        // In the triangle O-Q-B: the angle at Q between Q→O and Q→B.
        let at_q = triangle_angle(d, self.c, l);
        let to_o = (-self.qy).atan2(-self.qx);
        let mut best = (0.0, 0.0);
        for sign in [1.0, -1.0] {
            let theta = to_o + sign * at_q;
            let (bx, by) = (self.qx + self.c * theta.cos(), self.qy + self.c * theta.sin());
            let toward_b = by.atan2(bx);
            let alpha = if extended { toward_b } else { toward_b + PI };
            let (ax, ay) = (self.r * alpha.cos(), self.r * alpha.sin());
            let cross = (ax - self.qx) * (by - self.qy) - (ay - self.qy) * (bx - self.qx);
            if cross * self.kappa > 0.0 {
                best = (alpha, theta);
            }
        }
        best
    }

    /// The least transmission angle over a revolution, rad, in closed form: the angle between rod
    /// and rocker is extreme where the crank lies on the line O–Q (`|A − Q| = d ∓ r`), so the least
    /// is the smaller of those two positions' acute angles.
    pub fn min_transmission_rad(&self) -> f64 {
        let d = self.qx.hypot(self.qy);
        [d - self.r, d + self.r]
            .into_iter()
            .map(|s| {
                let mu = triangle_angle(self.b, self.c, s);
                mu.min(PI - mu)
            })
            .fold(f64::INFINITY, f64::min)
    }
}
