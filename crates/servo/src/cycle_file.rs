//! The spline law on the drive's machine cycle as a cycle file of the law core.

use crate::{Drive, Result, ServoError, SplineLaw};
use loomkin_laws::{CycleSpec, LawSpec, SegmentKind, SegmentSpec, StrokeUnit, poly_segments_of};

/// The drive's turn (rise over `φ`, dwell, return over `φ_r`, dwell; see [`Drive::layout`]) with
/// the spline law as a `polynomial` law of the core (its cubic-spline acceleration, segment by
/// segment), in mm, so `loomkin cycle`, `cam profile` and `cam table` read the servo law as it is.
/// Zero-length dwells are left out.
pub fn spline_cycle(law: &SplineLaw, drive: &Drive, speed_rpm: Option<f64>) -> Result<CycleSpec> {
    drive.validate()?;
    let lay = drive.layout()?;
    let segments = poly_segments_of(law.law()).ok_or_else(|| ServoError::Cycle {
        field: "law".into(),
        reason: "the spline law has a non-polynomial segment".into(),
    })?;
    let spec = LawSpec::Polynomial { segments };
    let mut segment = vec![SegmentSpec::moving(SegmentKind::Rise, lay.rise_deg, &spec)];
    if lay.dwell_after_rise_deg > 0.0 {
        segment.push(SegmentSpec::dwell(lay.dwell_after_rise_deg));
    }
    segment.push(SegmentSpec::moving(SegmentKind::Return, lay.return_deg, &spec));
    if lay.dwell_after_return_deg > 0.0 {
        segment.push(SegmentSpec::dwell(lay.dwell_after_return_deg));
    }
    Ok(CycleSpec {
        period_deg: crate::CYCLE_DEG,
        unit: StrokeUnit::Mm,
        stroke: Some(drive.stroke_m * 1e3),
        speed_rpm,
        segment,
    })
}
