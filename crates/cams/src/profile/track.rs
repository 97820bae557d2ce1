//! One roller path (or the flat face) of a cam: where the follower's trace point is at each cam
//! angle, in the fixed frame and in the frame of the cam.
//!
//! Frames: the cam centre is the origin; the fixed frame has `y` along a translating follower's
//! line of motion; the cam turns counter-clockwise, so a point fixed in the fixed frame at `q` sits
//! at `P = R(−ψ) q` in the cam's own frame (`R(α)` the rotation by `α`), and the pitch curve is
//! traced clockwise as ψ grows. With `J(x, y) = (−y, x)` the rotation by +90°,
//!
//! $$ P' = R(-ψ)\,t,\qquad t = q' - J q, $$
//!
//! so the pitch curve's tangent in the fixed frame is `t`, and the pressure angle — between the
//! contact normal and the direction `e` in which the trace point moves as the lift grows — is
//! `φ = atan((t·e)/(t·a))` with `a = −J e`.

use super::jet::Jet;

/// The trace-point path of one follower roller (or face).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Track {
    /// Translating trace point at `q = (ε, y₀ + s)`, moving along `e = (0, 1)`.
    Translating {
        /// Offset ε of the line of motion (mm).
        eps: f64,
        /// `y` of the trace point at zero lift (mm); negative for the conjugate roller below the centre.
        y0: f64,
    },
    /// Swinging arm of length `L` about the pivot `(d, 0)`: `γ = γ₀ + σ s` is the angle at the pivot
    /// between the line to the cam centre and the arm, and `q = (d − L cos γ, σ L sin γ)`.
    Oscillating {
        /// Pivot distance d (mm).
        d: f64,
        /// Arm length L (mm).
        l: f64,
        /// γ at zero lift (rad).
        g0: f64,
        /// +1: arm above the line of centres, moving away from the cam centre as the lift grows;
        /// −1: the conjugate arm below it, moving towards the cam centre.
        sigma: f64,
    },
    /// Flat face perpendicular to `y` at `y = r_b + s`; the trace point is `(0, r_b + s)`, the
    /// contact point `(ds/dψ, r_b + s)`.
    Flat {
        /// Base circle radius r_b (mm).
        rb: f64,
    },
}

/// The geometry of a track at one cam angle, as jets in ψ.
#[derive(Debug, Clone, Copy)]
pub struct TrackJets {
    /// Pitch point in the cam frame (mm).
    pub p: [Jet; 2],
    /// Pressure angle φ (rad).
    pub phi: Jet,
    /// Contact point of the flat face in the cam frame (flat follower only; else the pitch point).
    pub contact: [Jet; 2],
}

fn rot_minus(psi: f64, q: [Jet; 2]) -> [Jet; 2] {
    let (s, c) = Jet::var(psi).sin_cos();
    [c * q[0] + s * q[1], c * q[1] - s * q[0]]
}

impl Track {
    /// The trace point `q` and its motion direction `e` in the fixed frame, from the lift jet (mm or rad).
    pub fn q_e(&self, s: Jet) -> ([Jet; 2], [Jet; 2]) {
        match *self {
            Track::Translating { eps, y0 } => ([Jet::cst(eps), Jet::cst(y0) + s], [Jet::cst(0.0), Jet::cst(1.0)]),
            Track::Oscillating { d, l, g0, sigma } => {
                let g = Jet::cst(g0) + s.scale(sigma);
                let (sn, cs) = g.sin_cos();
                ([Jet::cst(d) - cs.scale(l), sn.scale(sigma * l)], [sn.scale(sigma), cs])
            }
            Track::Flat { rb } => ([Jet::cst(0.0), Jet::cst(rb) + s], [Jet::cst(0.0), Jet::cst(1.0)]),
        }
    }

    /// The pitch point, pressure angle and contact point as jets at cam angle `psi` for lift `s`.
    pub fn jets(&self, psi: f64, s: Jet) -> TrackJets {
        let (q, e) = self.q_e(s);
        let p = rot_minus(psi, q);
        if let Track::Flat { rb } = *self {
            let contact = rot_minus(psi, [s.deriv(), Jet::cst(rb) + s]);
            return TrackJets { p, phi: Jet::cst(0.0), contact };
        }
        let dq = [q[0].deriv(), q[1].deriv()];
        let t = [dq[0] + q[1], dq[1] - q[0]];
        let a = [e[1], -e[0]];
        let f = Jet::dot(t, e);
        let h = Jet::dot(t, a);
        let phi = if h.v() != 0.0 { f.div(&h).atan() } else { Jet::cst(std::f64::consts::FRAC_PI_2.copysign(f.v())) };
        TrackJets { p, phi, contact: p }
    }
}

/// Signed curvature of a curve traced clockwise, positive where it is convex (bulges away from
/// the cam centre): `κ = −(C′ × C″)/|C′|³`, as a jet (two orders fewer than `c`).
pub fn curvature(c: [Jet; 2]) -> Jet {
    let d1 = [c[0].deriv(), c[1].deriv()];
    let d2 = [d1[0].deriv(), d1[1].deriv()];
    let n2 = Jet::dot(d1, d1);
    let n3 = n2 * n2.sqrt();
    (-Jet::cross(d1, d2)).div(&n3)
}

/// The curve offset by `dist` along the outward normal `J C′/|C′|` of a clockwise curve (a roller
/// outside the cam: `dist = −r`; the outer wall of a groove: `dist = +r`), as a jet (one order fewer).
pub fn offset(c: [Jet; 2], dist: f64) -> [Jet; 2] {
    let d1 = [c[0].deriv(), c[1].deriv()];
    let n = Jet::dot(d1, d1).sqrt();
    [c[0] - d1[1].div(&n).scale(dist), c[1] + d1[0].div(&n).scale(dist)]
}
