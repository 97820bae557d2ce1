//! A servo design as the editor holds it, and its file form (JSON or TOML) without loss.

use crate::ApiError;
use crate::error::check_count;
use crate::json::{parse_json, parse_toml};
use crate::limits::{MAX_DEF_POINTS, MAX_SPEEDS};
use loomkin_servo::{Drive, ServoError, SplineEnd, SplineLaw, default_points};
use loomkin_units::{FieldError, Range, ShaftSpeed};
use serde::{Deserialize, Serialize};

/// Everything the servo law editor edits: definition points, spline start condition, drive and
/// the main-shaft speeds at which the drive is evaluated.
///
/// The file form is this struct in JSON or TOML (the drive under `[drive]`, as in the servo
/// crate's drive files); `f64` values are written in shortest round-trip form, so save → load
/// gives back exactly the same design.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ServoDesign {
    /// Definition points `[X, Y]`: X from 0 to 0.5 strictly increasing, Y₁ = Y_N = 0, Y ∈ [−1, 1].
    pub points: Vec<[f64; 2]>,
    /// Spline condition at x = 0: `natural` (f″ = 0) or `clamped` (f′ = 0).
    #[serde(default)]
    pub end: SplineEnd,
    /// Main-shaft speeds (rpm), 1 … [`MAX_SPEEDS`] of them.
    pub speeds_rpm: Vec<f64>,
    /// The drive (SI units; see `loomkin_servo::Drive`).
    pub drive: Drive,
}

impl Default for ServoDesign {
    /// The built-in design: the servo crate's default definition points (cycloidal acceleration
    /// sampled at X = j/12) and needle-rack drive, at 600 and 750 1/min (the paper's Table 1).
    fn default() -> Self {
        Self {
            points: default_points(),
            end: SplineEnd::Natural,
            speeds_rpm: vec![600.0, 750.0],
            drive: Drive::needle_rack_default(),
        }
    }
}

/// File formats of a design.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DesignFormat {
    /// JSON.
    #[default]
    Json,
    /// TOML.
    Toml,
    /// Guess from the text (JSON when it starts with `{`), only for reading.
    Auto,
}

impl ServoDesign {
    /// Checks the sizes and ranges the workbench bounds (the servo crate checks the rest).
    pub fn check(&self) -> Result<(), ApiError> {
        check_count("points", self.points.len(), loomkin_servo::MIN_POINTS, MAX_DEF_POINTS)?;
        check_count("speeds_rpm", self.speeds_rpm.len(), 1, MAX_SPEEDS)?;
        for (i, &n) in self.speeds_rpm.iter().enumerate() {
            ShaftSpeed::from_rpm_field(&format!("speeds_rpm[{i}]"), n)?;
        }
        for (i, p) in self.points.iter().enumerate() {
            Range::closed(0.0, 0.5, "").check(&format!("points[{i}][0]"), p[0])?;
            Range::closed(-1.0, 1.0, "").check(&format!("points[{i}][1]"), p[1])?;
        }
        self.drive.validate().map_err(servo_error)?;
        Ok(())
    }

    /// Checks the design and builds its spline law.
    pub fn spline(&self) -> Result<SplineLaw, ApiError> {
        self.check()?;
        SplineLaw::new(&self.points, self.end).map_err(servo_error)
    }

    /// The design as file text.
    pub fn to_text(&self, format: DesignFormat) -> Result<String, ApiError> {
        match format {
            DesignFormat::Json | DesignFormat::Auto => serde_json::to_string_pretty(self)
                .map(|s| s + "\n")
                .map_err(|e| ApiError::Internal(format!("cannot write JSON: {e}"))),
            DesignFormat::Toml => {
                let header = "# loomkin servo design: definition points [X, Y], spline start condition, \
                              speeds (rpm), drive (SI units)\n";
                toml::to_string(self)
                    .map(|s| format!("{header}{s}"))
                    .map_err(|e| ApiError::Internal(format!("cannot write TOML: {e}")))
            }
        }
    }

    /// Reads a design from file text and checks it.
    pub fn from_text(text: &str, format: DesignFormat) -> Result<Self, ApiError> {
        let format = match format {
            DesignFormat::Auto if text.trim_start().starts_with('{') => DesignFormat::Json,
            DesignFormat::Auto => DesignFormat::Toml,
            f => f,
        };
        let d: Self = match format {
            DesignFormat::Toml => parse_toml(text)?,
            _ => parse_json(text.as_bytes()).map_err(|e| match e {
                ApiError::BadJson { field, message } if field == "body" => {
                    ApiError::BadJson { field: "text".into(), message }
                }
                e => e,
            })?,
        };
        d.spline()?;
        Ok(d)
    }
}

/// Maps an error of the servo crate to an API error naming the request field.
pub fn servo_error(e: ServoError) -> ApiError {
    let field = match &e {
        ServoError::Point { index, .. } => format!("points[{}]", index.saturating_sub(1)),
        ServoError::TooFewPoints { .. } | ServoError::NoRise { .. } | ServoError::Law(_) => "points".into(),
        e => e.field().unwrap_or("design").to_string(),
    };
    ApiError::invalid(field, e)
}

#[cfg(test)]
mod tests {
    use super::*;

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
            let text = d.to_text(f).unwrap();
            assert_eq!(ServoDesign::from_text(&text, f).unwrap(), d, "{f:?}:\n{text}");
            assert_eq!(ServoDesign::from_text(&text, DesignFormat::Auto).unwrap(), d);
        }
    }

    #[test]
    fn a_float_serde_json_reads_one_ulp_off_by_default_loads_back_exactly() {
        // Found by the property below: without serde_json's `float_roundtrip` this value came
        // back as -6.5105854551879e268.
        let mut d = ServoDesign::default();
        d.drive.motor_inertia_kg_m2 = -6.510585455187901e268;
        let back: ServoDesign = parse_json(d.to_text(DesignFormat::Json).unwrap().as_bytes()).unwrap();
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
            let json: ServoDesign = parse_json(d.to_text(DesignFormat::Json).unwrap().as_bytes()).unwrap();
            let toml: ServoDesign = parse_toml(&d.to_text(DesignFormat::Toml).unwrap()).unwrap();
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
        let text = d.to_text(DesignFormat::Toml).unwrap().replace("stroke_m = 0.08", "stroke_m = -1.0");
        let e = ServoDesign::from_text(&text, DesignFormat::Toml).unwrap_err();
        assert_eq!(e.field(), "drive.stroke_m", "{e}");
        let e = ServoDesign::from_text("{\"points\": 3}", DesignFormat::Json).unwrap_err();
        assert_eq!(e.field(), "points");
        let e = ServoDesign::from_text("{oops", DesignFormat::Auto).unwrap_err();
        assert_eq!(e.field(), "text");
        let mut d = ServoDesign::default();
        d.points[3][0] = d.points[2][0];
        let e = d.spline().unwrap_err();
        assert_eq!(e.field(), "points[3]", "{e}");
    }
}
