//! Exact characteristic values of a law, found from the closed form.

use crate::extrema::brackets;
use crate::quadrature::integrate;
use crate::{Law, Segment};
use loomkin_numeric::scan_roots as scan;
use serde::Serialize;
use std::f64::consts::PI;

/// Characteristic values of a law (dimensionless, per unit stroke and unit motion angle).
///
/// Extrema are located per segment from the closed form: the derivative's sign changes are
/// bracketed on a grid sized to the segment's degree and frequency and refined by Newton's method,
/// and both one-sided limits at every joint are included. `ca_rms` is integrated in closed form
/// per segment (see `accel_square_integral`).
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
        let mut grid: Vec<(f64, [f64; 6])> = Vec::new();
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
            // One grid, fine enough for every search below, with all derivatives evaluated once per point.
            let n = [deg.saturating_sub(2), deg.saturating_sub(3), 2 * deg.saturating_sub(2)]
                .into_iter()
                .map(|d| brackets(seg, d))
                .max()
                .unwrap_or(1);
            let h = w / n as f64;
            grid.clear();
            grid.extend((0..=n).map(|i| {
                let t = if i == n { w } else { i as f64 * h };
                (t, seg.derivs_local(t))
            }));
            // v extrema: roots of a; a extrema: roots of j; j extrema: roots of snap.
            for k in 2..=4 {
                let gd = |t: f64| {
                    let d = seg.derivs_local(t);
                    (d[k], d[k + 1])
                };
                scan(grid.iter().map(|(t, d)| (*t, d[k], d[k + 1])), &gd, &mut visit);
            }
            // (v·a)' = a² + v·j, whose derivative is 3·a·j + v·snap.
            let cm_gd = |d: &[f64; 6]| (d[2] * d[2] + d[1] * d[3], 3.0 * d[2] * d[3] + d[1] * d[4]);
            scan(grid.iter().map(|(t, d)| (*t, cm_gd(d).0, cm_gd(d).1)), &|t| cm_gd(&seg.derivs_local(t)), &mut visit);
            a2 += accel_square_integral(seg);
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

/// `∫₀ʷ a(t)² dt` of one segment in closed form, with `a(t) = q(t) + A·sin(ωt + φ)`:
///
/// $$ \int_0^w a^2 = \int_0^w q^2 + 2A \int_0^w q \sin\theta + A^2 \Big[\tfrac{t}{2} - \tfrac{\sin 2\theta}{4\omega}\Big]_0^w, $$
///
/// the middle term by repeated integration by parts, `∫ q sin θ = Σₙ (−1)ⁿ q⁽ⁿ⁾ sin(θ − (n+1)π/2) / ωⁿ⁺¹`.
/// That series cancels badly when `ω·w` is small (a long-period sinusoid on a short segment); there
/// the segment is integrated by Gauss–Legendre panels instead, exact for the polynomial part.
fn accel_square_integral(seg: &Segment) -> f64 {
    let w = seg.width();
    let p = seg.displacement_poly();
    // Acceleration polynomial q_k = (k+2)(k+1)·p_{k+2}.
    let mut q = [0.0; 6];
    for (k, qk) in q.iter_mut().enumerate() {
        *qk = ((k + 2) * (k + 1)) as f64 * p[k + 2];
    }
    let qdeg = seg.degree().saturating_sub(2);
    let mut poly = 0.0;
    for i in 0..=qdeg {
        for j in 0..=qdeg {
            poly += q[i] * q[j] * w.powi((i + j + 1) as i32) / (i + j + 1) as f64;
        }
    }
    let Some(sn) = seg.sine() else { return poly };
    if (sn.omega * w).abs() < 1.0 {
        return integrate(0.0, w, panels(seg), |t| seg.deriv_local(2, t).powi(2));
    }
    let (a, om, ph) = (sn.amp, sn.omega, sn.phase);
    // Σₙ (−1)ⁿ q⁽ⁿ⁾(t) sin(θ − (n+1)π/2) / ωⁿ⁺¹ at t; q⁽ⁿ⁾ by differentiating the coefficients.
    let cross_at = |t: f64| {
        let mut d = q;
        let mut sum = 0.0;
        let mut scale = 1.0 / om;
        for n in 0..=qdeg {
            let val = d.iter().rev().fold(0.0, |acc, c| acc * t + c);
            let arg = om * t + ph - (n + 1) as f64 * std::f64::consts::FRAC_PI_2;
            sum += if n % 2 == 0 { 1.0 } else { -1.0 } * val * scale * arg.sin();
            for k in 0..5 {
                d[k] = (k + 1) as f64 * d[k + 1];
            }
            d[5] = 0.0;
            scale /= om;
        }
        sum
    };
    let cross = cross_at(w) - cross_at(0.0);
    let sq = w / 2.0 - ((2.0 * (om * w + ph)).sin() - (2.0 * ph).sin()) / (4.0 * om);
    poly + 2.0 * a * cross + a * a * sq
}

fn panels(seg: &Segment) -> usize {
    1 + seg.sine().map_or(0.0, |s| (s.omega.abs() * seg.width() / PI).ceil()) as usize
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Sine;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]
        /// The closed-form ∫a² against Gauss–Legendre quadrature on many panels (an independent route:
        /// exact for the polynomial part, converged for the sinusoid).
        #[test]
        fn closed_form_square_integral_matches_quadrature(
            coeffs in proptest::collection::vec(-5.0f64..5.0, 0..=6),
            amp in -3.0f64..3.0,
            omega in prop_oneof![0.05f64..1.0, 1.0f64..60.0, -60.0f64..-1.0],
            phase in -3.2f64..3.2,
            width in 0.01f64..1.5,
        ) {
            let seg = Segment::from_accel(0.2, 0.2 + width, &coeffs, Some(Sine { amp, omega, phase }), 0.1, 0.3).unwrap();
            let exact = accel_square_integral(&seg);
            let panels = 64 + (omega.abs() * width) as usize * 4;
            let quad = integrate(0.0, seg.width(), panels, |t| seg.deriv_local(2, t).powi(2));
            prop_assert!((exact - quad).abs() <= 1e-11 * quad.abs().max(1e-300) + 1e-14, "{exact} vs {quad}");
        }
    }
}
