//! Exact characteristic values of a law, found from the closed form.

use crate::extrema::{brackets, roots};
use crate::quadrature::integrate;
use crate::{Law, Segment};
use serde::Serialize;
use std::f64::consts::PI;

/// Characteristic values of a law (dimensionless, per unit stroke and unit motion angle).
///
/// Extrema are located per segment from the closed form: the derivative's sign changes are
/// bracketed on a grid sized to the segment's degree and frequency and refined by Newton's method,
/// and both one-sided limits at every joint are included. `ca_rms` is integrated by 16-point
/// Gauss–Legendre panels (one per half-period of the segment's sinusoid), exact for the polynomial
/// part and accurate to rounding for the sinusoid.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Metrics {
    /// Cv = max v.
    pub cv: f64,
    /// Where Cv occurs.
    pub x_cv: f64,
    /// Ca = max |a|.
    pub ca: f64,
    /// Largest positive acceleration, max a.
    pub ca_pos: f64,
    /// Where `ca_pos` occurs.
    pub x_ca_pos: f64,
    /// Largest negative acceleration, min a (a signed, usually negative number).
    pub ca_neg: f64,
    /// Where `ca_neg` occurs.
    pub x_ca_neg: f64,
    /// Cj = max |j| inside segments (jumps at joints excluded).
    pub cj: f64,
    /// Where Cj occurs.
    pub x_cj: f64,
    /// Cm = max (v·a).
    pub cm: f64,
    /// Where Cm occurs.
    pub x_cm: f64,
    /// RMS acceleration over the rise, √(∫₀¹ a² dx).
    pub ca_rms: f64,
}

#[derive(Clone, Copy)]
struct Peak {
    value: f64,
    x: f64,
}

impl Peak {
    fn max() -> Self {
        Self { value: f64::NEG_INFINITY, x: 0.0 }
    }
    fn min() -> Self {
        Self { value: f64::INFINITY, x: 0.0 }
    }
    fn take_max(&mut self, value: f64, x: f64) {
        if value > self.value {
            *self = Self { value, x };
        }
    }
    fn take_min(&mut self, value: f64, x: f64) {
        if value < self.value {
            *self = Self { value, x };
        }
    }
}

impl Law {
    /// The exact characteristic values of the law.
    pub fn metrics(&self) -> Metrics {
        let (mut cv, mut apos, mut aneg, mut jabs, mut cm) =
            (Peak::max(), Peak::max(), Peak::min(), Peak::max(), Peak::max());
        let mut a2 = 0.0;
        for seg in self.segments() {
            let w = seg.width();
            let x0 = seg.x0();
            let deg = seg.degree();
            let mut visit = |t: f64| {
                let k = seg.eval_local(t);
                let x = x0 + t;
                cv.take_max(k.v, x);
                apos.take_max(k.a, x);
                aneg.take_min(k.a, x);
                jabs.take_max(k.j.abs(), x);
                cm.take_max(k.v * k.a, x);
            };
            visit(0.0);
            visit(w);
            // v extrema: roots of a; a extrema: roots of j; j extrema: roots of snap.
            for k in 2..=4 {
                let n = brackets(seg, deg.saturating_sub(k));
                roots(
                    w,
                    n,
                    |t| {
                        let d = seg.derivs_local(t);
                        (d[k], d[k + 1])
                    },
                    &mut visit,
                );
            }
            // (v·a)' = a² + v·j, whose derivative is 3·a·j + v·snap.
            let n = brackets(seg, 2 * deg.saturating_sub(2));
            roots(
                w,
                n,
                |t| {
                    let d = seg.derivs_local(t);
                    (d[2] * d[2] + d[1] * d[3], 3.0 * d[2] * d[3] + d[1] * d[4])
                },
                &mut visit,
            );
            a2 += integrate(0.0, w, panels(seg), |t| seg.deriv_local(2, t).powi(2));
        }
        Metrics {
            cv: cv.value,
            x_cv: cv.x,
            ca: apos.value.max(-aneg.value),
            ca_pos: apos.value,
            x_ca_pos: apos.x,
            ca_neg: aneg.value,
            x_ca_neg: aneg.x,
            cj: jabs.value,
            x_cj: jabs.x,
            cm: cm.value,
            x_cm: cm.x,
            ca_rms: a2.sqrt(),
        }
    }
}

fn panels(seg: &Segment) -> usize {
    1 + seg.sine().map_or(0.0, |s| (s.omega.abs() * seg.width() / PI).ceil()) as usize
}
