//! A servo design — definition points, spline start condition, main-shaft speeds and drive — and
//! its file form (JSON or TOML) without loss.

use crate::{Drive, Result, ServoError, SplineEnd, SplineLaw, default_points};
use loomkin_units::{Range, ShaftSpeed};
use serde::{Deserialize, Serialize};

/// Most definition points of a design.
pub const MAX_DEF_POINTS: usize = 64;

/// Most main-shaft speeds of a design.
pub const MAX_SPEEDS: usize = 6;

/// Everything the servo law editor edits: definition points, spline start condition, drive and
/// the main-shaft speeds at which the drive is evaluated.
///
/// The file form is this struct in JSON or TOML (the drive under `[drive]`, as in drive files);
/// `f64` values are written in shortest round-trip form, so save → load gives back exactly the
/// same design. Its top-level keys besides `drive` are [`crate::DESIGN_KEYS`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ServoDesign {
    /// Definition points `[X, Y]`: X from 0 to 0.5 strictly increasing, Y₁ = Y_N = 0, Y ∈ [−1, 1].
    pub points: Vec<[f64; 2]>,
    /// Spline condition at x = 0: `natural` (f″ = 0) or `clamped` (f′ = 0).
    #[serde(default)]
    pub end: SplineEnd,
    /// Main-shaft speeds (rpm), 1 … [`MAX_SPEEDS`] of them.
    #[schemars(transform = loomkin_units::schema::item_bounds(ShaftSpeed::RANGE))]
    pub speeds_rpm: Vec<f64>,
    /// The drive (SI units; see [`Drive`]).
    pub drive: Drive,
}

impl Default for ServoDesign {
    /// The built-in design: the default definition points (cycloidal acceleration sampled at
    /// X = j/12) and needle-rack drive, at 600 and 750 rpm (the paper's Table 1).
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
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema)]
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

impl DesignFormat {
    /// The format of `text`: `self`, or for [`DesignFormat::Auto`] JSON when the text starts
    /// with `{`, else TOML.
    pub fn of(self, text: &str) -> Self {
        match self {
            Self::Auto if text.trim_start().starts_with('{') => Self::Json,
            Self::Auto => Self::Toml,
            f => f,
        }
    }

    /// Suggested file name and media type of a design file in this format.
    pub fn file(self) -> (&'static str, &'static str) {
        match self {
            Self::Toml => ("servo-design.toml", "application/toml"),
            _ => ("servo-design.json", "application/json"),
        }
    }
}

fn count(field: &str, n: usize, min: usize, max: usize) -> Result<()> {
    Range::closed(min as f64, max as f64, "").check(field, n as f64)?;
    Ok(())
}

impl ServoDesign {
    /// Checks the sizes and ranges of the design: point and speed counts, each speed
    /// ([`ShaftSpeed`]), each point's X ∈ [0, 0.5] and Y ∈ [−1, 1], and the drive. The spline's
    /// own rules (order, end values) are checked by [`ServoDesign::spline`].
    pub fn check(&self) -> Result<()> {
        count("points", self.points.len(), crate::MIN_POINTS, MAX_DEF_POINTS)?;
        count("speeds_rpm", self.speeds_rpm.len(), 1, MAX_SPEEDS)?;
        for (i, &n) in self.speeds_rpm.iter().enumerate() {
            ShaftSpeed::from_rpm_field(&format!("speeds_rpm[{i}]"), n)?;
        }
        for (i, p) in self.points.iter().enumerate() {
            Range::closed(0.0, 0.5, "").check(&format!("points[{i}][0]"), p[0])?;
            Range::closed(-1.0, 1.0, "").check(&format!("points[{i}][1]"), p[1])?;
        }
        self.drive.validate()
    }

    /// Checks the design and builds its spline law.
    pub fn spline(&self) -> Result<SplineLaw> {
        self.check()?;
        SplineLaw::new(&self.points, self.end)
    }

    /// The design as file text ([`DesignFormat::Auto`] writes JSON); TOML starts with a comment
    /// line naming the contents.
    pub fn to_text(&self, format: DesignFormat) -> Result<String> {
        let failed = |format: &str, e: &dyn std::fmt::Display| ServoError::Parse {
            field: "design".into(),
            text: e.to_string(),
            expected: format!("a design {format} can hold"),
        };
        match format {
            DesignFormat::Json | DesignFormat::Auto => {
                serde_json::to_string_pretty(self).map(|s| s + "\n").map_err(|e| failed("JSON", &e))
            }
            DesignFormat::Toml => {
                let header = "# loomkin servo design: definition points [X, Y], spline start condition, \
                              speeds (rpm), drive (SI units)\n";
                toml::to_string(self).map(|s| format!("{header}{s}")).map_err(|e| failed("TOML", &e))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use loomkin_units::FieldError;

    #[test]
    fn the_design_keys_are_the_struct_s_keys() {
        let v = serde_json::to_value(ServoDesign::default()).unwrap();
        let mut keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
        keys.sort_unstable();
        let mut expected: Vec<&str> = crate::DESIGN_KEYS.iter().copied().chain(["drive"]).collect();
        expected.sort_unstable();
        assert_eq!(keys, expected);
    }

    #[test]
    fn json_and_toml_round_trip_exactly() {
        let mut d = ServoDesign::default();
        d.points[2] = [0.1 + 1.0 / 3.0 * 1e-3, 0.123_456_789_012_345_67];
        d.end = SplineEnd::Clamped;
        d.drive.return_angle_deg = Some(140.0);
        d.speeds_rpm = vec![600.0, 712.345_678_9];
        let json: ServoDesign = serde_json::from_str(&d.to_text(DesignFormat::Json).unwrap()).unwrap();
        let toml: ServoDesign = toml::from_str(&d.to_text(DesignFormat::Toml).unwrap()).unwrap();
        assert_eq!(json, d);
        assert_eq!(toml, d);
        assert_eq!(DesignFormat::Auto.of(" {"), DesignFormat::Json);
        assert_eq!(DesignFormat::Auto.of("points = []"), DesignFormat::Toml);
    }

    #[test]
    fn checks_name_the_field() {
        let d = ServoDesign { speeds_rpm: vec![600.0, -5.0], ..Default::default() };
        assert_eq!(d.check().unwrap_err().field(), Some("speeds_rpm[1]"));
        let mut d = ServoDesign::default();
        d.points[1][1] = 1.5;
        assert_eq!(d.check().unwrap_err().field(), Some("points[1][1]"));
        let d = ServoDesign { speeds_rpm: vec![600.0; 7], ..Default::default() };
        assert_eq!(d.check().unwrap_err().field(), Some("speeds_rpm"));
        let mut d = ServoDesign::default();
        d.drive.efficiency = 2.0;
        assert_eq!(d.check().unwrap_err().field(), Some("drive.efficiency"));
        assert!(ServoDesign::default().spline().is_ok());
    }
}
