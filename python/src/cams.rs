//! From a law to a part: controller cam tables (`loomkin cam table … --json`) and disc cam
//! profiles (`loomkin cam profile … --json`), each the library's report struct converted.

use crate::convert::{columns, to_py};
use crate::cycles::Cycle;
use crate::errors::{Fault, OrRaise, raise};
use loomkin_cams::CamError;
use loomkin_cams::profile::{CamDesign, CamPoint, CamProfile, Closure, DesignInputs, FollowerKind};
use loomkin_cams::table::{CamTable, Format, Motion, Spacing};
use loomkin_laws::{CycleSpec, LawSpec, StrokeUnit};
use loomkin_units::RangeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

impl Fault for CamError {
    fn range(&self) -> Option<&RangeError> {
        match self {
            Self::Range(e) => Some(e),
            _ => None,
        }
    }
    fn accepted(&self) -> Option<String> {
        match self {
            Self::Usage { reason, .. } => Some(reason.clone()),
            _ => None,
        }
    }
}

/// A name that is not one of `allowed` (LoomkinError with `.allowed`).
fn unknown(field: &str, text: &str, allowed: &str) -> PyErr {
    raise(loomkin_laws::LawError::Parse { field: field.into(), text: text.into(), expected: allowed.into() })
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(cam_table, m)?)?;
    m.add_function(wrap_pyfunction!(cam_profile, m)?)?;
    m.add_function(wrap_pyfunction!(rise_return_cycle, m)?)?;
    Ok(())
}

fn usage(field: &str, reason: impl Into<String>) -> PyErr {
    raise(CamError::Usage { field: field.into(), reason: reason.into() })
}

/// A single rise of a catalogue law (the CLI's `--law NAME --param K=V --stroke-mm H
/// --motion-deg B`): the law, the stroke and its unit, the motion angle.
struct Rise {
    law: LawSpec,
    stroke: f64,
    unit: StrokeUnit,
    motion_deg: f64,
}

impl Rise {
    fn new(
        law: &str,
        params: Option<&Bound<'_, PyDict>>,
        stroke_mm: Option<f64>,
        stroke_deg: Option<f64>,
        motion_deg: Option<f64>,
    ) -> PyResult<Self> {
        let law = LawSpec::parse(law, &crate::convert::params(params)?).or_raise()?;
        let (stroke, unit) = match (stroke_mm, stroke_deg) {
            (Some(h), None) => (h, StrokeUnit::Mm),
            (None, Some(h)) => (h, StrokeUnit::Deg),
            (Some(_), Some(_)) => return Err(usage("stroke_mm", "give stroke_mm or stroke_deg, not both")),
            (None, None) => return Err(usage("stroke_mm", "stroke_mm or stroke_deg is needed with a law")),
        };
        let Some(motion_deg) = motion_deg else { return Err(usage("motion_deg", "motion_deg is needed with a law")) };
        Ok(Self { law, stroke, unit, motion_deg })
    }
}

/// rise_return_cycle(law, params=None, stroke_mm=None, stroke_deg=None, motion_deg=None) -> Cycle
/// --
///
/// The cycle `loomkin cam profile --law NAME --stroke-mm H --motion-deg B` makes of a law: the
/// rise over motion_deg, a dwell, the return by the same law and a dwell, over one turn
/// (motion_deg ≤ 180°). The stroke in mm (translating follower) or deg (swinging).
#[pyfunction]
#[pyo3(signature = (law, params=None, stroke_mm=None, stroke_deg=None, motion_deg=None))]
fn rise_return_cycle(
    law: &str,
    params: Option<&Bound<'_, PyDict>>,
    stroke_mm: Option<f64>,
    stroke_deg: Option<f64>,
    motion_deg: Option<f64>,
) -> PyResult<Cycle> {
    let r = Rise::new(law, params, stroke_mm, stroke_deg, motion_deg)?;
    let spec = CycleSpec::rise_return(&r.law, r.unit, r.stroke, r.motion_deg).or_raise()?;
    Cycle::from_spec(spec)
}

/// cam_table(cycle, format, step_deg=None, tolerance=None, source="", law=None, params=None,
/// stroke_mm=None, stroke_deg=None, motion_deg=None) -> dict
/// --
///
/// `loomkin cam table CYCLE --format F --json` (or `--law NAME --stroke-mm H --motion-deg B`
/// for a single rise when cycle is None) and the file it writes: text (the table, byte for byte
/// as `-o` writes it), source, format (xyvaj, poly5, csv, twincat, st, xyva), points, unit (the
/// slave's: mm or deg), spacing, interpolation, the exact re-interpolation errors
/// max_position_error_<unit> (at max_position_error_at_deg), max_velocity_error_<unit>_per_deg,
/// max_accel_error_<unit>_per_deg2 and the decimals written. Points every step_deg (default 1°)
/// or as few as keep the error within tolerance (slave unit). Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (cycle, format, step_deg=None, tolerance=None, source="", law=None, params=None,
    stroke_mm=None, stroke_deg=None, motion_deg=None))]
#[allow(clippy::too_many_arguments)]
fn cam_table<'py>(
    py: Python<'py>,
    cycle: Option<PyRef<'py, Cycle>>,
    format: &str,
    step_deg: Option<f64>,
    tolerance: Option<f64>,
    source: &str,
    law: Option<&str>,
    params: Option<&Bound<'py, PyDict>>,
    stroke_mm: Option<f64>,
    stroke_deg: Option<f64>,
    motion_deg: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let format = Format::ALL
        .into_iter()
        .find(|f| f.name().eq_ignore_ascii_case(format.trim()))
        .ok_or_else(|| unknown("format", format, &Format::ALL.map(|f| f.name()).join(", ")))?;
    if step_deg.is_some() && tolerance.is_some() {
        return Err(usage("tolerance", "give step_deg or tolerance, not both"));
    }
    let spacing = Spacing::of(step_deg, tolerance);
    let motion = match (&cycle, law) {
        (Some(c), None) => Motion::from_cycle(&c.inner),
        (None, Some(name)) => {
            let r = Rise::new(name, params, stroke_mm, stroke_deg, motion_deg)?;
            let law = r.law.build().or_raise()?;
            Motion::rise(&law, r.stroke, r.motion_deg, r.unit).or_raise()?
        }
        (Some(_), Some(_)) => return Err(usage("law", "give a cycle or a law, not both")),
        (None, None) => return Err(usage("cycle", "give a cycle, or a law with its stroke and motion_deg")),
    };
    let (table, out) = py
        .detach(|| -> Result<_, CamError> {
            let table = CamTable::new(motion, spacing)?;
            let out = table.export(format)?;
            Ok((table, out))
        })
        .or_raise()?;
    let r = to_py(py, &table.report(source, format, &out))?.into_bound(py).cast_into::<PyDict>()?;
    r.set_item("text", &out.text)?;
    Ok(r)
}

/// The design of `loomkin cam profile`'s flags, refused as the CLI refuses them (the library's rules).
#[allow(clippy::too_many_arguments)]
fn design(
    follower: &str,
    prime_radius_mm: Option<f64>,
    max_pressure_deg: Option<f64>,
    roller_radius_mm: f64,
    offset_mm: f64,
    arm_mm: Option<f64>,
    pivot_mm: Option<f64>,
    closure: &str,
) -> PyResult<CamDesign> {
    let follower = match follower.trim().to_ascii_lowercase().as_str() {
        "translating" => FollowerKind::Translating,
        "oscillating" => FollowerKind::Oscillating,
        "flat" => FollowerKind::Flat,
        other => return Err(unknown("follower", other, "translating, oscillating, flat")),
    };
    let closure = match closure.trim().to_ascii_lowercase().as_str() {
        "single" => Closure::Single,
        "conjugate" => Closure::Conjugate,
        "groove" => Closure::Groove,
        other => return Err(unknown("closure", other, "single, conjugate, groove")),
    };
    DesignInputs { follower, closure, prime_radius_mm, max_pressure_deg, roller_radius_mm, offset_mm, arm_mm, pivot_mm }
        .design()
        .or_raise()
}

/// The points of a track as arrays: the report's columns (angle_deg, x_mm, y_mm,
/// pressure_angle_deg, curvature_pitch_per_mm, profile_x_mm, profile_y_mm) and
/// curvature_profile_per_mm (the CSV's).
fn point_columns<'py>(py: Python<'py>, pts: &[CamPoint]) -> PyResult<Bound<'py, PyDict>> {
    let col = |f: fn(&CamPoint) -> f64| pts.iter().map(f).collect::<Vec<f64>>();
    columns(
        py,
        vec![
            ("angle_deg", col(|p| p.angle_deg)),
            ("x_mm", col(|p| p.pitch_mm[0])),
            ("y_mm", col(|p| p.pitch_mm[1])),
            ("pressure_angle_deg", col(|p| p.pressure_angle_deg)),
            ("curvature_pitch_per_mm", col(|p| p.curvature_pitch_per_mm)),
            ("profile_x_mm", col(|p| p.profile_mm[0])),
            ("profile_y_mm", col(|p| p.profile_mm[1])),
            ("curvature_profile_per_mm", col(|p| p.curvature_profile_per_mm)),
        ],
    )
}

/// cam_profile(cycle, follower, prime_radius_mm=None, max_pressure_deg=None, roller_radius_mm=...,
/// offset_mm=..., arm_mm=None, pivot_mm=None, closure="single", step_deg=..., source="", dxf=False,
/// chord_tol_mm=..., bore_mm=None) -> dict
/// --
///
/// `loomkin cam profile CYCLE --follower F … --json`: a disc cam for the cycle and a translating
/// (radial or offset offset_mm), oscillating (arm_mm, pivot_mm) or flat-faced follower; single,
/// conjugate or groove closure; the prime radius given (mm) or the least whose pressure angle is at
/// most max_pressure_deg (default 30° for a roller). The report (source, follower, closure,
/// prime_radius_mm, base_radius_mm, roller_radius_mm, max_pressure_angle_deg and where,
/// min_convex_radius_pitch_mm and where, undercut, and the keys of the follower kind) with
/// `points` (and `counter_points` of a conjugate pair) as dicts of arrays every step_deg:
/// angle_deg, x_mm, y_mm (pitch curve), pressure_angle_deg, curvature_pitch_per_mm (1/mm, convex
/// > 0), profile_x_mm, profile_y_mm, curvature_profile_per_mm. With dxf=True, `dxf` holds the
/// drawing `--dxf` writes (mm; polylines within chord_tol_mm; bore diameter bore_mm, default
/// 0.4 × base radius); an undercut cam is never drawn (LoomkinError naming the roller).
/// Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (cycle, follower, prime_radius_mm=None, max_pressure_deg=None,
    roller_radius_mm=CamDesign::ROLLER_RADIUS_MM.default_value(), offset_mm=CamDesign::OFFSET_MM.default_value(),
    arm_mm=None, pivot_mm=None, closure="single", step_deg=CamProfile::STEP_DEG.default_value(), source="", dxf=false,
    chord_tol_mm=CamProfile::CHORD_TOL_MM.default_value(), bore_mm=None))]
#[allow(clippy::too_many_arguments)]
fn cam_profile<'py>(
    py: Python<'py>,
    cycle: PyRef<'py, Cycle>,
    follower: &str,
    prime_radius_mm: Option<f64>,
    max_pressure_deg: Option<f64>,
    roller_radius_mm: f64,
    offset_mm: f64,
    arm_mm: Option<f64>,
    pivot_mm: Option<f64>,
    closure: &str,
    step_deg: f64,
    source: &str,
    dxf: bool,
    chord_tol_mm: f64,
    bore_mm: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    CamProfile::STEP_DEG.check(step_deg).or_raise()?;
    let design =
        design(follower, prime_radius_mm, max_pressure_deg, roller_radius_mm, offset_mm, arm_mm, pivot_mm, closure)?;
    let motion = Motion::from_cycle(&cycle.inner);
    let (report, points, counter, drawing) = py
        .detach(|| -> Result<_, CamError> {
            let cam = CamProfile::new(&motion, &design)?;
            let report = cam.report(source, step_deg);
            let points = cam.sample(0, step_deg);
            let counter = (cam.track_count() == 2).then(|| cam.sample(1, step_deg));
            let drawing = match (dxf, cam.undercut()) {
                (false, _) => None,
                (true, Some(u)) => {
                    let field = u.field_name();
                    let text = u.to_string();
                    let reason = text.strip_prefix(&format!("{field}: ")).unwrap_or(&text);
                    return Err(CamError::Usage { field: field.into(), reason: format!("{reason}: no DXF written") });
                }
                (true, None) => Some(cam.dxf(chord_tol_mm, cam.bore_mm_or(bore_mm))?),
            };
            Ok((report, points, counter, drawing))
        })
        .or_raise()?;
    let out = to_py(py, &report)?.into_bound(py).cast_into::<PyDict>()?;
    out.set_item("points", point_columns(py, &points)?)?;
    if let Some(c) = &counter {
        out.set_item("counter_points", point_columns(py, c)?)?;
    }
    if let Some(text) = drawing {
        out.set_item("dxf", text)?;
    }
    Ok(out)
}
