//! The fast closed-form criteria of a symmetric law whose positive phase has non-negative
//! acceleration. Each segment is kept as its displacement polynomial and one sinusoid, and every
//! evaluation costs one `sin_cos`; no allocation.

use crate::template::MAX_PARTS;
use crate::{Dimensionless, Result, ShedError};
use loomkin_laws::Shape;
use loomkin_numeric::refine_root;
use std::f64::consts::{FRAC_PI_2, PI};

/// The two levels a shape spans (`[0, peak]` for a sine arc).
pub(crate) fn levels(shape: &Shape) -> [f64; 2] {
    match *shape {
        Shape::SineArc { peak } => [0.0, peak],
        other => {
            let (a, b) = other.end_levels();
            [a, b]
        }
    }
}

/// `sup |j|` of a shape over a segment of width `w`, in closed form.
#[inline]
fn jerk_peak(shape: &Shape, w: f64) -> f64 {
    match *shape {
        Shape::Zero | Shape::Constant { .. } => 0.0,
        Shape::Linear { from, to } => (to - from).abs() / w,
        Shape::SineRamp { from, to } | Shape::CosineRamp { from, to } | Shape::HalfCosine { from, to } => {
            (to - from).abs() * FRAC_PI_2 / w
        }
        Shape::SineArc { peak } => peak.abs() * PI / w,
    }
}

/// `∫₀¹ a(u)² du` of a shape in its relative coordinate, in closed form.
#[inline]
fn square_mean(shape: &Shape) -> f64 {
    match *shape {
        Shape::Zero => 0.0,
        Shape::Constant { level } => level * level,
        Shape::Linear { from, to } => (from * from + from * to + to * to) / 3.0,
        // (f + d sin(πu/2))²: f² + 2fd·(2/π) + d²/2.
        Shape::SineRamp { from, to } => {
            let d = to - from;
            from * from + 4.0 * from * d / PI + d * d / 2.0
        }
        // to − d cos(πu/2): to² − 2·to·d·(2/π) + d²/2.
        Shape::CosineRamp { from, to } => {
            let d = to - from;
            to * to - 4.0 * to * d / PI + d * d / 2.0
        }
        // m − (d/2) cos(πu): m² + d²/8.
        Shape::HalfCosine { from, to } => {
            let (m, d) = ((from + to) / 2.0, to - from);
            m * m + d * d / 8.0
        }
        Shape::SineArc { peak } => peak * peak / 2.0,
    }
}

/// Whether `a` never decreases over the shape (then `v·a` peaks at the segment's end).
fn non_decreasing(shape: &Shape) -> bool {
    match *shape {
        Shape::SineArc { peak } => peak == 0.0,
        other => {
            let (a, b) = other.end_levels();
            b >= a
        }
    }
}

/// One segment: `a(t) = c0 + c1·t + A·sin(ωt + φ)` with `φ ∈ {0, π/2}` (so `sin φ`, `cos φ` are
/// exact), `s(0) = s0`, `v(0) = v0`, integrated in closed form.
#[derive(Clone, Copy, Default)]
struct Local {
    x0: f64,
    w: f64,
    /// s(t) = p0 + p1 t + p2 t² + p3 t³ − (A/ω²)·sin(ωt + φ).
    p: [f64; 4],
    amp: f64,
    omega: f64,
    /// (sin φ, cos φ).
    rot: (f64, f64),
}

/// (s, v, a, j, snap) at local t.
type Derivs = [f64; 5];

impl Local {
    fn new(shape: &Shape, x0: f64, w: f64, s0: f64, v0: f64) -> Self {
        // c0, c1, A, ω, (sin φ, cos φ): the same acceleration as `Shape::to_piece`.
        let (c0, c1, amp, omega, rot) = match *shape {
            Shape::Zero => (0.0, 0.0, 0.0, 1.0, (0.0, 1.0)),
            Shape::Constant { level } => (level, 0.0, 0.0, 1.0, (0.0, 1.0)),
            Shape::Linear { from, to } => (from, (to - from) / w, 0.0, 1.0, (0.0, 1.0)),
            Shape::SineRamp { from, to } => (from, 0.0, to - from, FRAC_PI_2 / w, (0.0, 1.0)),
            Shape::CosineRamp { from, to } => (to, 0.0, -(to - from), FRAC_PI_2 / w, (1.0, 0.0)),
            Shape::HalfCosine { from, to } => ((from + to) / 2.0, 0.0, -(to - from) / 2.0, PI / w, (1.0, 0.0)),
            Shape::SineArc { peak } => (0.0, 0.0, peak, PI / w, (0.0, 1.0)),
        };
        let p = [s0 + amp / (omega * omega) * rot.0, v0 + amp / omega * rot.1, c0 / 2.0, c1 / 6.0];
        Self { x0, w, p, amp, omega, rot }
    }

    #[inline]
    fn at(&self, t: f64) -> Derivs {
        let p = &self.p;
        let mut d = [
            p[0] + t * (p[1] + t * (p[2] + t * p[3])),
            p[1] + t * (2.0 * p[2] + 3.0 * t * p[3]),
            2.0 * p[2] + 6.0 * t * p[3],
            6.0 * p[3],
            0.0,
        ];
        if self.amp != 0.0 {
            let (st, ct) = (self.omega * t).sin_cos();
            let (sp, cp) = self.rot;
            let sin = st * cp + ct * sp;
            let cos = ct * cp - st * sp;
            let (a, w) = (self.amp, self.omega);
            d[0] -= a / (w * w) * sin;
            d[1] -= a / w * cos;
            d[2] += a * sin;
            d[3] += a * w * cos;
            d[4] -= a * w * w * sin;
        }
        d
    }
}

/// The fast path (see [`crate::Template::evaluate_fast`]); the template has been checked.
pub(crate) fn evaluate(shapes: &[Shape], lengths: &[f64], threshold: f64) -> Result<Dimensionless> {
    let mut sum = 0.0;
    for (i, &k) in lengths.iter().enumerate() {
        crate::GridSpec::K_RANGE.check(&format!("positive[{i}].length"), k)?;
        sum += k;
    }
    if (sum - 1.0).abs() > 1e-9 {
        return Err(ShedError::LengthsDoNotSumToOne { field: "positive".into(), sum });
    }
    let mut segs = [(Local::default(), Shape::Zero); MAX_PARTS];
    let mut n = 0;
    let (mut x, mut s, mut v) = (0.0, 0.0, 0.0);
    let (mut amax, mut jmax, mut a2, mut lead) = (0.0f64, 0.0f64, 0.0, 0.0);
    let mut leading = true;
    // Jumps of a: at x = 0 against the dwell, between segments, and 2·|a(½)| at mid-motion where
    // the mirror flips the sign (the end x = 1 mirrors x = 0).
    let (mut jump, mut a_prev) = (0.0f64, 0.0);
    for (shape, &k) in shapes.iter().zip(lengths) {
        if k <= 0.0 {
            continue;
        }
        let w = 0.5 * k / sum;
        let seg = Local::new(shape, x, w, s, v);
        let lv = levels(shape);
        if leading && lv == [0.0, 0.0] {
            lead = x + w;
        } else {
            leading = false;
        }
        amax = amax.max(lv[0]).max(lv[1]);
        let (a_in, a_out) = shape.end_levels();
        jump = jump.max((a_in - a_prev).abs());
        a_prev = a_out;
        jmax = jmax.max(jerk_peak(shape, w));
        a2 += w * square_mean(shape);
        let e = seg.at(w);
        (x, s, v) = (x + w, e[0], e[1]);
        segs[n] = (seg, *shape);
        n += 1;
    }
    if !(s > 0.0 && s.is_finite()) {
        return Err(ShedError::NotARise {
            field: "positive".into(),
            reason: "the positive phase makes no displacement".into(),
        });
    }
    jump = jump.max(2.0 * a_prev.abs());
    let segs = &segs[..n];
    let kn = 0.5 / s;
    // Peak of v·a on the positive phase (unscaled): at a segment's end where a does not fall,
    // else also at its start and at sign changes (+ → −) of (v·a)' = a² + v·j.
    let mut cm = 0.0f64;
    for (seg, shape) in segs {
        let w = seg.w;
        let e = seg.at(w);
        cm = cm.max(e[1] * e[2]);
        if non_decreasing(shape) {
            continue;
        }
        let gd = |t: f64| {
            let d = seg.at(t);
            (d[2] * d[2] + d[1] * d[3], 3.0 * d[2] * d[3] + d[1] * d[4], d[1] * d[2])
        };
        const N: usize = 4;
        let (mut t0, (mut g0, _, va0)) = (0.0, gd(0.0));
        cm = cm.max(va0);
        for m in 1..=N {
            let t1 = if m == N { w } else { w * m as f64 / N as f64 };
            let (g1, _, _) = gd(t1);
            if g0 > 0.0 && g1 < 0.0 {
                let r = refine_root(t0, t1, false, |t| {
                    let (g, dg, _) = gd(t);
                    (g, dg)
                });
                cm = cm.max(gd(r).2);
            }
            (t0, g0) = (t1, g1);
        }
    }
    // x_depart: s(x) = (1 − T)/kn on the convex first half, in the one segment that brackets it.
    let target = (1.0 - threshold) / kn;
    let mut x_depart = 0.5;
    let mut s_start = 0.0;
    for (seg, _) in segs {
        let e = seg.at(seg.w);
        if e[0] >= target {
            let t = refine_root(0.0, seg.w, s_start < target, |t| {
                let d = seg.at(t);
                (d[0] - target, d[1])
            });
            x_depart = seg.x0 + t;
            break;
        }
        s_start = e[0];
    }
    Ok(Dimensionless {
        threshold,
        cv: kn * v,
        ca: kn * amax,
        cj: kn * jmax,
        cm: kn * kn * cm,
        ca_rms: kn * (2.0 * a2).sqrt(),
        a_jump: kn * jump,
        lead,
        tail: 1.0 - lead,
        x_depart,
        x_arrive: 1.0 - x_depart,
    })
}
