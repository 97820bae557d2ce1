//! The heald frame's full cycle as a cycle file of the law core: what `cycle`, `cam profile` and
//! `cam table` read.

use crate::{Result, ShedError, ShedLaw};
use loomkin_laws::{CycleSpec, LawSpec, SegmentKind, SegmentSpec, StrokeUnit};
use loomkin_units::{Range, ShaftSpeed};

/// The frame's period in degrees of the main shaft: up over one pick, down over the next (plain
/// weave, two picks).
pub const FRAME_PERIOD_DEG: f64 = 720.0;

/// The allowed frame stroke of [`frame_cycle`] (mm): above 0, at most a metre.
pub const FRAME_STROKE_MM_RANGE: Range = Range::open_closed(0.0, 1000.0, "mm");

/// The full frame cycle over two picks (720° of the main shaft), as [`crate::cycle_curve`] draws it:
/// the rise over `[0, φ_дв]`, a dwell to 360°, the return over `[360°, 360° + φ_дв]` by the same
/// law (`s = H(1 − s°)`), a dwell to 720° (a dwell of zero length, at `φ_дв = 360°`, is left out).
///
/// The law is written as a `piecewise` law of the core with the whole motion's segments
/// ([`ShedLaw::motion_segments`], numbers in shortest round-trip form), so the cycle read back
/// builds exactly the law of [`ShedLaw::build`]. `stroke_mm` is the frame's stroke, `speed_rpm`
/// the main-shaft speed stored in the file (if given).
pub fn frame_cycle(law: &ShedLaw, stroke_mm: f64, speed_rpm: Option<f64>) -> Result<CycleSpec> {
    FRAME_STROKE_MM_RANGE.check("stroke_mm", stroke_mm)?;
    if let Some(n) = speed_rpm {
        ShaftSpeed::from_rpm(n)?;
    }
    let spec = LawSpec::Piecewise { segments: law.motion_segments()? };
    let phi = law.motion_deg();
    let mut segment = Vec::new();
    for kind in [SegmentKind::Rise, SegmentKind::Return] {
        segment.push(SegmentSpec::moving(kind, phi, &spec));
        if phi < 360.0 {
            segment.push(SegmentSpec::dwell(360.0 - phi));
        }
    }
    Ok(CycleSpec { period_deg: FRAME_PERIOD_DEG, unit: StrokeUnit::Mm, stroke: Some(stroke_mm), speed_rpm, segment })
}

/// [`frame_cycle`] as the text of a cycle file, headed by comment lines naming `source` (e.g.
/// the command that chose the law).
pub fn frame_cycle_toml(law: &ShedLaw, stroke_mm: f64, speed_rpm: Option<f64>, source: &str) -> Result<String> {
    let spec = frame_cycle(law, stroke_mm, speed_rpm)?;
    let body = spec.to_toml().map_err(ShedError::from)?;
    Ok(format!(
        "# Heald-frame cycle over two picks (720° of the main shaft): rise, dwell, return, dwell.\n\
         # Law: motion {} deg, positive phase {}, negative phase {}.\n\
         # Source: {source}\n\
         # Read by: loomkin cycle FILE, loomkin cam profile FILE, loomkin cam table FILE.\n{body}",
        law.motion_deg(),
        law.positive_text(),
        law.negative_text()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Conditions, cycle_curve, preset};
    use loomkin_laws::Cycle;

    /// The written cycle read back moves the frame as the shedding law does, to 1e-12.
    #[test]
    fn the_written_frame_cycle_reads_back_to_the_law() {
        let asym = ShedLaw::from_toml(
            "motion_deg = 320\npositive = \"0.5:sine-ramp:0:1,0.5:cosine-ramp:1:0\"\n\
             negative = \"0.2:sine-ramp:0:-1,0.6:constant:-1,0.2:cosine-ramp:-1:0\"\npositive_fraction = 0.4\n",
        )
        .unwrap();
        for law in [preset("dobby").unwrap(), preset("smooth").unwrap(), asym, preset("basic").unwrap()] {
            let text = frame_cycle_toml(&law, 100.0, Some(300.0), "test").unwrap();
            let cycle = Cycle::from_toml(&text).unwrap();
            let cond = Conditions::new(0.95, 0.1, 300.0).unwrap();
            let built = law.build().unwrap();
            let pts = cycle_curve(&law, &cond, 1441).unwrap();
            let phi = law.motion_deg();
            for p in &pts[..pts.len() - 1] {
                let k = cycle.eval(p.angle_deg.to_radians(), 300.0);
                assert!((k.s - p.s_m).abs() < 1e-12 * 0.1, "{} at {}: {} vs {}", phi, p.angle_deg, k.s, p.s_m);
                assert!((k.v - p.v_m_s).abs() < 1e-12 * (1.0 + p.v_m_s.abs()), "v at {}", p.angle_deg);
                assert!((k.a - p.a_m_s2).abs() < 1e-12 * (1.0 + p.a_m_s2.abs()), "a at {}", p.angle_deg);
            }
            // The cycle's rise is the shedding law itself, bit for bit.
            let (_, rise) = cycle.segments[0].law.as_ref().unwrap();
            for i in 0..=400 {
                let x = i as f64 / 400.0;
                assert_eq!(rise.eval(x), built.eval(x));
            }
        }
    }

    #[test]
    fn a_full_motion_angle_leaves_out_the_dwells() {
        let law = preset("dobby").unwrap().with_motion_deg(360.0).unwrap();
        let spec = frame_cycle(&law, 80.0, None).unwrap();
        assert_eq!(spec.segment.len(), 2);
        Cycle::new(&spec).unwrap();
        assert!(frame_cycle(&law, 0.0, None).unwrap_err().to_string().contains("stroke_mm"));
    }
}
