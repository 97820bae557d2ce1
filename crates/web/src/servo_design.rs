//! The servo design (`loomkin_servo::ServoDesign`) as requests carry it: reading its file text with
//! errors at the request's JSON paths, and servo errors mapped to request fields.

use crate::ApiError;
use crate::json::{parse_json, parse_toml};
pub use loomkin_servo::{DesignFormat, ServoDesign};
use loomkin_servo::{ServoError, SplineLaw};
use loomkin_units::FieldError;

/// Checks a design and builds its spline law, errors placed at the design's fields.
pub fn design_spline(design: &ServoDesign) -> Result<SplineLaw, ApiError> {
    design.spline().map_err(servo_error)
}

/// The design as file text.
pub fn design_text(design: &ServoDesign, format: DesignFormat) -> Result<String, ApiError> {
    design.to_text(format).map_err(|e| ApiError::Internal(e.to_string()))
}

/// Reads a design from file text (a request field named `text`) and checks it.
pub fn design_from_text(text: &str, format: DesignFormat) -> Result<ServoDesign, ApiError> {
    let d: ServoDesign = match format.of(text) {
        DesignFormat::Toml => parse_toml(text)?,
        _ => parse_json(text.as_bytes()).map_err(|e| match e {
            ApiError::BadJson { field, message } if field == "body" => {
                ApiError::BadJson { field: "text".into(), message }
            }
            e => e,
        })?,
    };
    design_spline(&d)?;
    Ok(d)
}

/// Maps an error of the servo crate to an API error naming the request field.
pub fn servo_error(e: ServoError) -> ApiError {
    let field = match &e {
        ServoError::Range(r) => return ApiError::Range(r.clone()),
        ServoError::Point { index, .. } => format!("points[{}]", index.saturating_sub(1)),
        ServoError::TooFewPoints { .. } | ServoError::NoRise { .. } | ServoError::Law(_) => "points".into(),
        e => e.field().unwrap_or("design").to_string(),
    };
    ApiError::invalid(field, e)
}

#[cfg(test)]
mod tests {
    use super::*;
    use loomkin_servo::SplineEnd;

    fn odd_design() -> ServoDesign {
        let mut d = ServoDesign::default();
        d.points[2] = [0.1 + 1.0 / 3.0 * 1e-3, 0.123_456_789_012_345_67];
        d.end = SplineEnd::Clamped;
        d.drive.return_angle_deg = Some(140.0);
        d.drive.spring_n_m = 1234.5e-7;
        d.speeds_rpm = vec![600.0, 712.345_678_9];
        d
    }

    #[test]
    fn json_and_toml_round_trip_exactly() {
        let d = odd_design();
        for f in [DesignFormat::Json, DesignFormat::Toml] {
            let text = design_text(&d, f).unwrap();
            assert_eq!(design_from_text(&text, f).unwrap(), d, "{f:?}:\n{text}");
            assert_eq!(design_from_text(&text, DesignFormat::Auto).unwrap(), d);
        }
    }

    #[test]
    fn a_float_serde_json_reads_one_ulp_off_by_default_loads_back_exactly() {
        // Found by the property below: without serde_json's `float_roundtrip` this value came
        // back as -6.5105854551879e268.
        let mut d = ServoDesign::default();
        d.drive.motor_inertia_kg_m2 = -6.510585455187901e268;
        let back: ServoDesign = parse_json(design_text(&d, DesignFormat::Json).unwrap().as_bytes()).unwrap();
        assert_eq!(back.drive.motor_inertia_kg_m2.to_bits(), d.drive.motor_inertia_kg_m2.to_bits());
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]

        /// Any finite `f64` in any field (subnormal, huge, negative zero, many digits) comes back
        /// bit for bit from both file forms; the checks are not involved.
        #[test]
        fn every_finite_value_survives_both_file_forms(
            bits in proptest::collection::vec(proptest::num::f64::NORMAL | proptest::num::f64::SUBNORMAL
                | proptest::num::f64::ZERO | proptest::num::f64::NEGATIVE | proptest::num::f64::POSITIVE, 20),
            clamped: bool,
            with_return: bool,
        ) {
            let v = |i: usize| bits[i];
            let mut d = ServoDesign {
                points: vec![[v(0), v(1)], [v(2), v(3)], [v(4), v(5)], [v(6), v(7)]],
                end: if clamped { SplineEnd::Clamped } else { SplineEnd::Natural },
                speeds_rpm: vec![v(8), v(9)],
                ..Default::default()
            };
            let dr = &mut d.drive;
            (dr.stroke_m, dr.motion_angle_deg, dr.moving_mass_kg, dr.pinion_radius_m) = (v(10), v(11), v(12), v(13));
            (dr.gear_ratio, dr.motor_inertia_kg_m2, dr.spring_n_m, dr.spring_preload_n) = (v(14), v(15), v(16), v(17));
            (dr.damping_n_s_m, dr.constant_force_n, dr.efficiency) = (v(18), v(19), v(0));
            dr.return_angle_deg = with_return.then_some(v(1));
            dr.dwell_after_rise_deg = with_return.then_some(v(2));
            let json: ServoDesign = parse_json(design_text(&d, DesignFormat::Json).unwrap().as_bytes()).unwrap();
            let toml: ServoDesign = parse_toml(&design_text(&d, DesignFormat::Toml).unwrap()).unwrap();
            let bits_of = |d: &ServoDesign| serde_json::to_value(d).unwrap().to_string();
            for back in [&json, &toml] {
                proptest::prop_assert_eq!(back, &d);
                // PartialEq treats −0 and 0 alike: compare the shortest forms too.
                proptest::prop_assert_eq!(bits_of(back), bits_of(&d));
            }
        }
    }

    #[test]
    fn bad_files_name_the_field() {
        let d = ServoDesign::default();
        let text = design_text(&d, DesignFormat::Toml).unwrap().replace("stroke_m = 0.08", "stroke_m = -1.0");
        let e = design_from_text(&text, DesignFormat::Toml).unwrap_err();
        assert_eq!(e.field(), "drive.stroke_m", "{e}");
        let e = design_from_text("{\"points\": 3}", DesignFormat::Json).unwrap_err();
        assert_eq!(e.field(), "points");
        let e = design_from_text("{oops", DesignFormat::Auto).unwrap_err();
        assert_eq!(e.field(), "text");
        let mut d = ServoDesign::default();
        d.points[3][0] = d.points[2][0];
        let e = design_spline(&d).unwrap_err();
        assert_eq!(e.field(), "points[3]", "{e}");
    }
}
