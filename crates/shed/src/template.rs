//! A family of symmetric laws: fixed shapes of the positive phase, free relative lengths
//! `k_T1 … k_Tn`. Its criteria have a fast closed-form path used for large experiment tables.

use crate::dwell::refine;
use crate::{Dimensionless, Result, ShedError, ShedLaw, check_threshold};
use loomkin_laws::{Segment, Shape, ShapeSegment, Sine};
use serde::Serialize;
use std::f64::consts::{FRAC_PI_2, PI};

/// Most parts a template may have.
pub const MAX_PARTS: usize = 12;

/// Shapes of the positive phase of a symmetric law; the lengths are given per evaluation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Template {
    name: String,
    shapes: Vec<Shape>,
    /// All levels ≥ 0: the acceleration is non-negative over the positive phase, which the fast
    /// path needs (v then peaks at mid-motion and s is convex on the first half).
    fast: bool,
}

fn levels(shape: &Shape) -> [f64; 2] {
    match *shape {
        Shape::SineArc { peak } => [0.0, peak],
        other => {
            let (a, b) = other.end_levels();
            [a, b]
        }
    }
}

/// The acceleration of a shape as the polynomial `c0 + c1·t` and an optional sinusoid, over a
/// width `w` (the same as `Shape::to_piece`, without allocating).
#[inline]
fn piece(shape: &Shape, w: f64) -> ([f64; 2], Option<Sine>) {
    match *shape {
        Shape::Zero => ([0.0, 0.0], None),
        Shape::Constant { level } => ([level, 0.0], None),
        Shape::Linear { from, to } => ([from, (to - from) / w], None),
        Shape::SineRamp { from, to } => ([from, 0.0], Some(Sine { amp: to - from, omega: FRAC_PI_2 / w, phase: 0.0 })),
        Shape::CosineRamp { from, to } => {
            ([to, 0.0], Some(Sine { amp: -(to - from), omega: FRAC_PI_2 / w, phase: FRAC_PI_2 }))
        }
        Shape::HalfCosine { from, to } => {
            ([(from + to) / 2.0, 0.0], Some(Sine { amp: -(to - from) / 2.0, omega: PI / w, phase: FRAC_PI_2 }))
        }
        Shape::SineArc { peak } => ([0.0, 0.0], Some(Sine { amp: peak, omega: PI / w, phase: 0.0 })),
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

impl Template {
    /// A template from the shapes of the positive phase (1 … 12 of them).
    pub fn new(name: impl Into<String>, shapes: Vec<Shape>) -> Result<Self> {
        ShedError::check_range("parts", shapes.len() as f64, 1.0, MAX_PARTS as f64, "")?;
        let fast = shapes.iter().all(|s| levels(s).iter().all(|&l| l >= 0.0));
        Ok(Self { name: name.into(), shapes, fast })
    }

    /// Reads the shapes written `SHAPE[:LEVEL…],…`, e.g. `zero,sine-ramp:0:1,constant:1,cosine-ramp:1:0`.
    pub fn parse(name: impl Into<String>, text: &str) -> Result<Self> {
        let shapes = text
            .split(',')
            .enumerate()
            .map(|(i, t)| Shape::parse(t.trim(), &format!("shapes[{i}]")))
            .collect::<std::result::Result<Vec<_>, _>>()?;
        Self::new(name, shapes)
    }

    /// The three-part family of Table 1: quarter-sine rise, constant plateau, quarter-cosine fall
    /// (`k1 = k3 = k_r` gives the modified trapezoid, `k1 = k3 = 0.5` the cycloidal law).
    pub fn trapezoid() -> Self {
        Self::parse("trapezoid", "sine-ramp:0:1,constant:1,cosine-ramp:1:0").expect("valid shapes")
    }

    /// The four-part family of the paper's Fig. 1: a stretch of zero acceleration (extra dwell),
    /// then the three parts of [`Template::trapezoid`].
    pub fn lead_trapezoid() -> Self {
        Self::parse("lead-trapezoid", "zero,sine-ramp:0:1,constant:1,cosine-ramp:1:0").expect("valid shapes")
    }

    /// The simplest three-part family: linear rise, constant, linear fall.
    pub fn linear_trapezoid() -> Self {
        Self::parse("linear-trapezoid", "linear:0:1,constant:1,linear:1:0").expect("valid shapes")
    }

    /// The named families: `trapezoid`, `lead-trapezoid`, `linear-trapezoid`.
    pub fn named(name: &str) -> Result<Self> {
        match name.trim() {
            "trapezoid" => Ok(Self::trapezoid()),
            "lead-trapezoid" => Ok(Self::lead_trapezoid()),
            "linear-trapezoid" => Ok(Self::linear_trapezoid()),
            other => Err(ShedError::Parse {
                field: "family".into(),
                reason: format!("unknown family '{other}': known are trapezoid, lead-trapezoid, linear-trapezoid"),
            }),
        }
    }

    /// The family's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Number of parts `n`.
    pub fn parts(&self) -> usize {
        self.shapes.len()
    }

    /// The shapes.
    pub fn shapes(&self) -> &[Shape] {
        &self.shapes
    }

    /// Whether the fast closed-form path applies (every level ≥ 0).
    pub fn is_fast(&self) -> bool {
        self.fast
    }

    fn segments(&self, lengths: &[f64]) -> Result<Vec<ShapeSegment>> {
        if lengths.len() != self.parts() {
            return Err(ShedError::Parse {
                field: "lengths".into(),
                reason: format!("the family has {} parts, {} lengths given", self.parts(), lengths.len()),
            });
        }
        Ok(lengths.iter().zip(&self.shapes).map(|(&length, &shape)| ShapeSegment { length, shape }).collect())
    }

    /// The law with these lengths at a motion angle.
    pub fn law(&self, motion_deg: f64, lengths: &[f64]) -> Result<ShedLaw> {
        ShedLaw::symmetric(motion_deg, self.segments(lengths)?)
    }

    /// Dimensionless criteria of the law with these lengths: the fast closed-form path when the
    /// template allows it, else the generic path through the law core.
    pub fn evaluate(&self, lengths: &[f64], threshold: f64) -> Result<Dimensionless> {
        if self.fast {
            self.evaluate_fast(lengths, threshold)
        } else {
            let law = self.law(360.0, lengths)?.build()?;
            Dimensionless::of_law(&law, threshold)
        }
    }

    /// The generic path (through [`ShedLaw::build`] and [`loomkin_laws::Law::metrics`]), for checks.
    pub fn evaluate_generic(&self, lengths: &[f64], threshold: f64) -> Result<Dimensionless> {
        let law = self.law(360.0, lengths)?.build()?;
        Dimensionless::of_law(&law, threshold)
    }

    /// The fast path. On the positive phase (`x ∈ [0, ½]`) `a ≥ 0`, so `v` rises to its peak at
    /// `x = ½` and `s` is convex there; the negative phase is the mirror. Hence, with `k` the
    /// stroke normalisation `½/s(½)`:
    /// `Cv = k·v(½)`; `Ca = k·max level`; `Cj = k·max` of the closed-form per-shape jerk peaks;
    /// `∫a² = 2k²·Σ wᵢ·∫₀¹aᵢ²`; `Cm = k²·max v·a`, at a segment's end where `a` does not fall and
    /// at the root of `(v·a)' = a² + v·j` where it does; and `x_depart` solves `s(x) = (1 − T)/k`
    /// by Newton's method in the one segment that brackets it (`x_arrive = 1 − x_depart`).
    pub fn evaluate_fast(&self, lengths: &[f64], threshold: f64) -> Result<Dimensionless> {
        check_threshold(threshold)?;
        if !self.fast {
            return Err(ShedError::Parse {
                field: "template".into(),
                reason: "the fast path needs non-negative levels in the positive phase".into(),
            });
        }
        if lengths.len() != self.parts() {
            return Err(ShedError::Parse {
                field: "lengths".into(),
                reason: format!("the family has {} parts, {} lengths given", self.parts(), lengths.len()),
            });
        }
        let mut sum = 0.0;
        for (i, &k) in lengths.iter().enumerate() {
            if !(k.is_finite() && (0.0..=1.0).contains(&k)) {
                return Err(ShedError::out_of_range(format!("positive[{i}].length"), k, 0.0, 1.0, ""));
            }
            sum += k;
        }
        if (sum - 1.0).abs() > 1e-9 {
            return Err(ShedError::LengthsDoNotSumToOne { field: "positive".into(), sum });
        }
        let mut segs = [None::<(Segment, &Shape)>; MAX_PARTS];
        let (mut x, mut s, mut v) = (0.0, 0.0, 0.0);
        let (mut amax, mut jmax, mut a2, mut lead) = (0.0f64, 0.0f64, 0.0, 0.0);
        let mut leading = true;
        for (i, (shape, &k)) in self.shapes.iter().zip(lengths).enumerate() {
            if k <= 0.0 {
                continue;
            }
            let w = 0.5 * k / sum;
            let (poly, sine) = piece(shape, w);
            let seg = Segment::from_accel(x, x + w, &poly, sine, s, v)
                .ok_or_else(|| ShedError::NotARise { field: format!("positive[{i}]"), reason: "bad segment".into() })?;
            let lv = levels(shape);
            let zero = lv[0] == 0.0 && lv[1] == 0.0;
            if leading && zero {
                lead = x + w;
            } else {
                leading = false;
            }
            amax = amax.max(lv[0]).max(lv[1]);
            jmax = jmax.max(jerk_peak(shape, w));
            a2 += w * square_mean(shape);
            let e = seg.end();
            (x, s, v) = (x + w, e.s, e.v);
            segs[i] = Some((seg, shape));
        }
        if !(s > 0.0 && s.is_finite()) {
            return Err(ShedError::NotARise {
                field: "positive".into(),
                reason: "the positive phase makes no displacement".into(),
            });
        }
        let kn = 0.5 / s;
        // v·a on the positive phase (unscaled).
        let mut cm = 0.0f64;
        for (seg, shape) in segs.iter().flatten() {
            let w = seg.width();
            let e = seg.end();
            cm = cm.max(e.v * e.a);
            if !non_decreasing(shape) {
                let st = seg.start();
                cm = cm.max(st.v * st.a);
                let g = |t: f64| {
                    let k = seg.eval_local(t);
                    k.a * k.a + k.v * k.j
                };
                let dg = |t: f64| {
                    let k = seg.eval_local(t);
                    3.0 * k.a * k.j + k.v * seg.deriv_local(4, t)
                };
                const N: usize = 4;
                let mut t0 = 0.0;
                let mut g0 = g(0.0);
                for m in 1..=N {
                    let t1 = if m == N { w } else { w * m as f64 / N as f64 };
                    let g1 = g(t1);
                    if g0 > 0.0 && g1 < 0.0 {
                        let r = refine(t0, t1, g, dg);
                        let k = seg.eval_local(r);
                        cm = cm.max(k.v * k.a);
                    }
                    (t0, g0) = (t1, g1);
                }
            }
        }
        // x_depart: s(x) = (1 − T)/kn on the convex first half.
        let target = (1.0 - threshold) / kn;
        let mut x_depart = 0.5;
        for (seg, _) in segs.iter().flatten() {
            if seg.end().s >= target {
                let g = |t: f64| seg.deriv_local(0, t) - target;
                x_depart = seg.x0() + refine(0.0, seg.width(), g, |t| seg.deriv_local(1, t));
                break;
            }
        }
        Ok(Dimensionless {
            threshold,
            cv: kn * v,
            ca: kn * amax,
            cj: kn * jmax,
            cm: kn * kn * cm,
            ca_rms: kn * (2.0 * a2).sqrt(),
            lead,
            tail: 1.0 - lead,
            x_depart,
            x_arrive: 1.0 - x_depart,
        })
    }
}
