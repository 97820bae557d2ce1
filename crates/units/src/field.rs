//! The field descriptor: one input quantity's name, unit, allowed range, default and the reason for
//! its bounds, declared once as a `const` on the library type that owns it and read by every front end.

use serde::Serialize;

use crate::range::{Bound, Range, RangeError};

/// One input of the library: the key it is given under, its allowed range with its unit, its default
/// and one sentence on what it is and why its range is what it is.
///
/// A descriptor is a `const` on the library type that owns the quantity (`ShaftSpeed::SPEED`,
/// a settings type's `SHUTTLE_G`, …). The CLI takes its flag's default from [`Field::default_value`]
/// (`default_value_t = ShaftSpeed::SPEED.default_value()`) and checks with [`Field::check`]; Python and
/// the workbench do the same, and the field reference (docs/reference/fields.md) is generated from
/// the descriptors. A front end that offers a narrower span (a slider) keeps that span its own and
/// still refuses with the descriptor's message.
///
/// ```
/// use loomkin_units::{Field, Range};
///
/// const RAMP: Field = Field::new("ramp", Range::open_closed(0.0, 0.25, ""), "Share of the rise spent ramping.")
///     .with_default(0.125);
/// assert_eq!(RAMP.default_value(), 0.125);
/// assert_eq!(RAMP.check(0.3).unwrap_err().to_string(), "ramp = 0.3 is out of range: allowed 0 < ramp ≤ 0.25");
/// assert_eq!(RAMP.or_default(None).unwrap(), 0.125);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Field {
    /// The key in files, JSON requests and Python keywords (`speed_rpm`); the CLI flag is the same
    /// words joined with `-` (`--speed-rpm`).
    pub name: &'static str,
    /// The allowed values, with the unit ([`Range::unit`]).
    pub range: Range,
    /// The value taken when an input leaves the field out; `None` when the field is required or
    /// when leaving it out means something else (e.g. "the file's value").
    pub default: Option<f64>,
    /// Whether the value is a whole number (a count of points, draws, picks …).
    pub count: bool,
    /// What the field is, and the reason for its bounds (one or two sentences).
    pub doc: &'static str,
}

impl Field {
    /// A real-valued field without a default.
    pub const fn new(name: &'static str, range: Range, doc: &'static str) -> Self {
        Self { name, range, default: None, count: false, doc }
    }

    /// A whole-number field (a count) without a default.
    pub const fn count(name: &'static str, range: Range, doc: &'static str) -> Self {
        Self { name, range, default: None, count: true, doc }
    }

    /// The same field with a default.
    ///
    /// # Panics
    /// At compile time (the descriptors are `const`) when the default lies outside the range.
    pub const fn with_default(mut self, value: f64) -> Self {
        assert!(self.range.contains(value), "a field's default lies outside its range");
        self.default = Some(value);
        self
    }

    /// The same field under another name (the same quantity taken as `input_rpm`, `to_rpm`, …).
    pub const fn named(mut self, name: &'static str) -> Self {
        self.name = name;
        self
    }

    /// The same quantity with another range (a narrower use of a shared quantity, e.g. a speed the
    /// dobby modulator can follow); the reason goes in `doc`.
    ///
    /// # Panics
    /// At compile time when the default lies outside the new range.
    pub const fn within(mut self, range: Range, doc: &'static str) -> Self {
        if let Some(d) = self.default {
            assert!(range.contains(d), "a field's default lies outside its range");
        }
        self.range = range;
        self.doc = doc;
        self
    }

    /// The same field with its lower bound set to `lo` (closed), for a bound that depends on another
    /// input (a peak torque at least the rated one); the descriptor's `doc` states the dependence.
    pub const fn at_least(mut self, lo: f64) -> Self {
        self.range.lo = Bound::Closed(lo);
        self
    }

    /// The same field with its upper bound set to `hi` (closed), as [`Field::at_least`].
    pub const fn at_most(mut self, hi: f64) -> Self {
        self.range.hi = Bound::Closed(hi);
        self
    }

    /// The unit of the value and its bounds (`""` for a dimensionless quantity).
    pub const fn unit(&self) -> &'static str {
        self.range.unit
    }

    /// The default value.
    ///
    /// # Panics
    /// When the field has no default (at compile time in a `const` context).
    pub const fn default_value(&self) -> f64 {
        match self.default {
            Some(v) => v,
            None => panic!("this field has no default"),
        }
    }

    /// The default of a count.
    ///
    /// # Panics
    /// When the field has no default or is not a count.
    pub const fn default_count(&self) -> usize {
        assert!(self.count, "this field is not a count");
        self.default_value() as usize
    }

    /// `Ok(v)` when `v` is inside the range, else the error naming this field.
    pub fn check(&self, v: f64) -> Result<f64, RangeError> {
        self.range.check(self.name, v)
    }

    /// `Ok(v)` when `v` is inside the range, else the error naming `field` (a front end's flag or
    /// a request's key path such as `law.stroke_mm`).
    pub fn check_as(&self, field: &str, v: f64) -> Result<f64, RangeError> {
        self.range.check(field, v)
    }

    /// A count checked against the range, named by this field.
    pub fn check_count(&self, n: usize) -> Result<usize, RangeError> {
        self.check_count_as(self.name, n)
    }

    /// A count checked against the range, named `field`.
    pub fn check_count_as(&self, field: &str, n: usize) -> Result<usize, RangeError> {
        self.range.check(field, n as f64).map(|_| n)
    }

    /// The value given, else the default, checked against the range.
    ///
    /// # Panics
    /// When `v` is `None` and the field has no default.
    pub fn or_default(&self, v: Option<f64>) -> Result<f64, RangeError> {
        self.check(v.unwrap_or_else(|| self.default_value()))
    }

    /// The range in words under this field's name: `0.001 ≤ speed_rpm ≤ 100000 rpm`.
    pub fn describe(&self) -> String {
        self.range.describe(self.name)
    }
}

/// A crate's list of its descriptors, each with the path of the `const` that declares it
/// (`"ShaftSpeed::SPEED"`): what the field reference and the Python package read.
pub type FieldList = &'static [(&'static str, Field)];

/// A [`FieldList`] from the paths of the descriptors, each written once:
/// `field_list![ShaftSpeed::SPEED, Settings::PLAY_MM]`.
#[macro_export]
macro_rules! field_list {
    ($($path:path),* $(,)?) => {
        &[$((stringify!($path), $path)),*]
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    const N: Field = Field::count("points", Range::closed(2.0, 1e6, ""), "Samples.").with_default(721.0);

    #[test]
    fn a_field_checks_under_its_name_and_gives_its_default() {
        assert_eq!(N.default_count(), 721);
        assert_eq!(
            N.check_count(1).unwrap_err().to_string(),
            "points = 1 is out of range: allowed 2 ≤ points ≤ 1000000"
        );
        assert_eq!(N.check_count_as("--points", 5).unwrap(), 5);
        let r = N.named("rows");
        assert_eq!(r.check(0.0).unwrap_err().field, "rows");
        assert_eq!(N.describe(), "2 ≤ points ≤ 1000000");
        let narrow = N.within(Range::closed(700.0, 800.0, ""), "Fewer.");
        assert!(narrow.check(801.0).is_err() && narrow.check(800.0).is_ok());
        assert_eq!(N.or_default(None).unwrap(), 721.0);
        assert!(N.or_default(Some(f64::NAN)).is_err());
    }

    #[test]
    fn a_list_names_each_descriptor_by_its_path() {
        const L: FieldList = field_list![N, crate::ShaftSpeed::SPEED];
        assert_eq!(L[0].0, "N");
        assert_eq!(L[1].0, "crate::ShaftSpeed::SPEED");
        assert_eq!(L[1].1.default, Some(300.0));
    }

    #[test]
    #[should_panic(expected = "no default")]
    fn a_field_without_default_says_so() {
        let _ = Field::new("x", Range::finite(""), "").default_value();
    }
}
