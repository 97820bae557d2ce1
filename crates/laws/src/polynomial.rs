//! Polynomial-acceleration segments: the law kind that carries any polynomial law (a servo spline
//! law, a constant-acceleration or 3-4-5 law) in a cycle file.

use crate::{AccelPiece, Law, LawError, Result};
use serde::{Deserialize, Serialize};

/// Highest degree of a segment's acceleration polynomial.
pub const MAX_ACCEL_DEGREE: usize = 5;

/// One segment of a polynomial-acceleration law: a relative length and the acceleration as a
/// polynomial in the segment's relative coordinate `u ∈ [0, 1]`,
///
/// $$ a(u) = \sum_{k=0}^{n} c_k\,u^k,\qquad n \le 5. $$
///
/// Levels are relative, as for piecewise shapes: the law is scaled afterwards so that the stroke
/// is 1. Written `LEN:c0:c1:…` (e.g. `0.5:0:6:-6`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PolySegment {
    /// Relative length (fraction of the motion, > 0; all lengths sum to 1).
    pub length: f64,
    /// Acceleration coefficients `c₀…cₙ` in `u`, lowest power first (1 to 6 of them).
    pub accel: Vec<f64>,
}

impl PolySegment {
    /// The acceleration over a segment of the given width as an [`AccelPiece`]
    /// (local `t = u·width`, so the coefficient of `tᵏ` is `cₖ/widthᵏ`).
    pub fn to_piece(&self, width: f64) -> AccelPiece {
        let mut scale = 1.0;
        let poly: Vec<f64> = self
            .accel
            .iter()
            .map(|c| {
                let v = c * scale;
                scale /= width;
                v
            })
            .collect();
        AccelPiece::poly(width, &poly)
    }
}

/// Reads segments written `LEN:c0[:c1…],LEN:c0…`.
pub fn parse_poly_segments(text: &str, field: &str) -> Result<Vec<PolySegment>> {
    text.split(',')
        .enumerate()
        .map(|(i, part)| {
            let f = format!("{field}[{i}]");
            let err = || LawError::Parse {
                field: f.clone(),
                text: part.trim().into(),
                expected: format!("LENGTH:c0[:c1…] with 1 to {} finite coefficients", MAX_ACCEL_DEGREE + 1),
            };
            let nums: Vec<f64> =
                part.split(':').map(|t| t.trim().parse::<f64>().map_err(|_| err())).collect::<Result<_>>()?;
            if nums.len() < 2 || nums.len() > MAX_ACCEL_DEGREE + 2 || nums.iter().any(|v| !v.is_finite()) {
                return Err(err());
            }
            Ok(PolySegment { length: nums[0], accel: nums[1..].to_vec() })
        })
        .collect()
}

/// Writes segments in the form [`parse_poly_segments`] reads (shortest round-trip numbers, so a
/// written law reads back bit for bit).
pub fn format_poly_segments(segs: &[PolySegment]) -> String {
    segs.iter()
        .map(|s| {
            let mut parts = vec![crate::shape::number_text(s.length)];
            parts.extend(s.accel.iter().map(|c| crate::shape::number_text(c + 0.0)));
            parts.join(":")
        })
        .collect::<Vec<_>>()
        .join(",")
}

/// The polynomial segments of a law whose segments are all polynomial (no sinusoid), or `None`.
///
/// The acceleration of a segment with displacement `Σ pₖ tᵏ` on `[x₀, x₁]` is
/// `Σ (k+2)(k+1) p_{k+2} tᵏ`, written in `u = t/(x₁ − x₀)` as `cₖ = (k+2)(k+1) p_{k+2} (x₁ − x₀)ᵏ`.
/// Built again ([`crate::LawSpec::build`]) it gives the same law to rounding.
pub fn poly_segments_of(law: &Law) -> Option<Vec<PolySegment>> {
    law.segments()
        .iter()
        .map(|seg| {
            if seg.sine().is_some() {
                return None;
            }
            let p = seg.displacement_poly();
            let w = seg.width();
            let mut scale = 1.0;
            let mut accel: Vec<f64> = (0..=MAX_ACCEL_DEGREE)
                .map(|k| {
                    let c = ((k + 2) * (k + 1)) as f64 * p[k + 2] * scale;
                    scale *= w;
                    c
                })
                .collect();
            while accel.len() > 1 && accel[accel.len() - 1] == 0.0 {
                accel.pop();
            }
            Some(PolySegment { length: w, accel })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Cycle, CycleSpec, LawSpec, SegmentKind, SegmentSpec, StrokeUnit};

    fn same(a: &Law, b: &Law, tol: f64) {
        for i in 0..=1000 {
            let x = i as f64 / 1000.0;
            let (ka, kb) = (a.eval(x), b.eval(x));
            for k in 0..4 {
                let scale = 1.0 + ka.order(k).abs();
                assert!((ka.order(k) - kb.order(k)).abs() <= tol * scale, "x {x} order {k}: {ka:?} vs {kb:?}");
            }
        }
    }

    #[test]
    fn polynomial_laws_are_carried_through_text_bit_for_bit() {
        for spec in [LawSpec::Poly345, LawSpec::ConstantAcceleration, LawSpec::Poly4567] {
            let law = spec.build().unwrap();
            let segs = poly_segments_of(&law).unwrap();
            let text = format_poly_segments(&segs);
            let back = parse_poly_segments(&text, "segments").unwrap();
            assert_eq!(back, segs, "{text}");
            let rebuilt = LawSpec::parse("polynomial", &[("segments", text.as_str())]).unwrap().build().unwrap();
            same(&law, &rebuilt, 1e-12);
            assert_eq!(rebuilt.segments().len(), law.segments().len());
        }
        assert!(poly_segments_of(&LawSpec::Cycloidal.build().unwrap()).is_none());
    }

    #[test]
    fn a_hand_written_polynomial_law_is_a_rise() {
        // a = 1 − 2u over the whole motion is the constant-jerk (trapezoid-free) rise s = 3x² − 2x³.
        let law = LawSpec::parse("polynomial", &[("segments", "1:6:-12")]).unwrap().build().unwrap();
        for i in 0..=20 {
            let x = i as f64 / 20.0;
            assert!((law.eval(x).s - (3.0 * x * x - 2.0 * x * x * x)).abs() < 1e-14);
        }
    }

    #[test]
    fn bad_polynomial_segments_name_the_field() {
        let e = LawSpec::parse("polynomial", &[("segments", "0.5:1,0.5")]).unwrap_err().to_string();
        assert!(e.contains("segments[1]"), "{e}");
        let e = LawSpec::parse("polynomial", &[("segments", "0.5:1:2:3:4:5:6:7")]).unwrap_err().to_string();
        assert!(e.contains("segments[0]"), "{e}");
        let e = LawSpec::parse("polynomial", &[("segments", "0.4:1,0.4:-1")]).unwrap_err().to_string();
        assert!(e.contains("sum to"), "{e}");
        let e = LawSpec::parse("polynomial", &[("segments", "0.5:1,0.5:1")]).unwrap().build().unwrap_err().to_string();
        assert!(e.contains("velocity does not return to zero"), "{e}");
        assert!(LawSpec::parse::<&str, &str>("polynomial", &[]).is_err());
    }

    #[test]
    fn a_written_cycle_reads_back_to_the_same_motion() {
        let law = LawSpec::parse("polynomial", &[("segments", "0.3:1,0.4:0,0.3:-1")]).unwrap();
        let spec = CycleSpec {
            period_deg: 360.0,
            unit: StrokeUnit::Mm,
            stroke: Some(80.0),
            speed_rpm: Some(600.0),
            segment: vec![
                SegmentSpec::moving(SegmentKind::Rise, 150.0, &law),
                SegmentSpec::dwell(30.0),
                SegmentSpec::moving(SegmentKind::Return, 150.0, &LawSpec::ModifiedTrapezoid { ramp: 0.1 }),
                SegmentSpec::dwell(30.0),
            ],
        };
        let text = spec.to_toml().unwrap();
        let back: CycleSpec = toml::from_str(&text).unwrap();
        assert_eq!(back, spec, "{text}");
        let (a, b) = (Cycle::new(&spec).unwrap(), Cycle::from_toml(&text).unwrap());
        for i in 0..=360 {
            let th = (i as f64).to_radians();
            assert_eq!(a.eval(th, 600.0), b.eval(th, 600.0));
        }
    }
}
