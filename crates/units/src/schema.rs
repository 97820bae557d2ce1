//! A range as JSON Schema: the keywords a front end serves with its request schemas (the
//! workbench's `GET /api/schema`), so that a schema's bounds are the library's own.
//!
//! Each function here returns a [`schemars`] transform for a field of a type that derives
//! `JsonSchema`:
//!
//! ```
//! use loomkin_units::{ShaftSpeed, schema};
//!
//! #[derive(schemars::JsonSchema)]
//! struct Request {
//!     #[schemars(transform = schema::bounds(ShaftSpeed::RANGE))]
//!     speed_rpm: f64,
//! }
//!
//! let s = schemars::schema_for!(Request);
//! let speed = &s.as_value()["properties"]["speed_rpm"];
//! assert_eq!(speed["minimum"], 0.001);
//! assert_eq!(speed["maximum"], 100000.0);
//! assert_eq!(speed["x-unit"], "rpm");
//! ```

use crate::range::{Bound, Range};
use schemars::Schema;

/// Puts `range` on a number's schema: `minimum` / `exclusiveMinimum`, `maximum` /
/// `exclusiveMaximum` (JSON Schema 2020-12: exclusive bounds are numbers) and the unit as
/// `x-unit` (absent for a dimensionless quantity).
pub fn apply_bounds(schema: &mut Schema, range: &Range) {
    match range.lo {
        Bound::Unbounded => {}
        Bound::Closed(v) => {
            schema.insert("minimum".into(), v.into());
        }
        Bound::Open(v) => {
            schema.insert("exclusiveMinimum".into(), v.into());
        }
    }
    match range.hi {
        Bound::Unbounded => {}
        Bound::Closed(v) => {
            schema.insert("maximum".into(), v.into());
        }
        Bound::Open(v) => {
            schema.insert("exclusiveMaximum".into(), v.into());
        }
    }
    if !range.unit.is_empty() {
        schema.insert("x-unit".into(), range.unit.into());
    }
}

/// The range of a number as a schemars transform: `#[schemars(transform = bounds(RANGE))]`.
pub fn bounds(range: Range) -> impl FnMut(&mut Schema) {
    move |schema: &mut Schema| apply_bounds(schema, &range)
}

/// The range of a quantity a request takes in another unit (`stroke_mm` for a stroke the library
/// keeps in m): the bounds multiplied by `factor` (> 0), under `unit`.
pub fn bounds_in_unit(range: Range, factor: f64, unit: &'static str) -> impl FnMut(&mut Schema) {
    let scale = move |b: Bound| match b {
        Bound::Unbounded => Bound::Unbounded,
        Bound::Closed(v) => Bound::Closed(v * factor),
        Bound::Open(v) => Bound::Open(v * factor),
    };
    let scaled = Range { lo: scale(range.lo), hi: scale(range.hi), unit };
    move |schema: &mut Schema| apply_bounds(schema, &scaled)
}

/// The range of every item of an array of numbers (`motions_deg: Vec<f64>`).
pub fn item_bounds(range: Range) -> impl FnMut(&mut Schema) {
    move |schema: &mut Schema| {
        if let Some(items) = schema.get_mut("items").and_then(|v| <&mut Schema>::try_from(v).ok()) {
            apply_bounds(items, &range);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn open_and_closed_sides_become_the_matching_keywords() {
        let mut s = Schema::default();
        apply_bounds(&mut s, &Range::open_closed(0.0, 0.25, ""));
        let v = s.as_value();
        assert_eq!(v["exclusiveMinimum"], 0.0);
        assert_eq!(v["maximum"], 0.25);
        assert!(v.get("minimum").is_none() && v.get("exclusiveMaximum").is_none() && v.get("x-unit").is_none());
        let mut s = Schema::default();
        apply_bounds(&mut s, &Range::below(90.0, "deg"));
        let v = s.as_value();
        assert_eq!((v["exclusiveMaximum"].as_f64(), v["x-unit"].as_str()), (Some(90.0), Some("deg")));
        assert!(v.get("minimum").is_none() && v.get("exclusiveMinimum").is_none());
    }

    #[test]
    fn items_of_an_array_take_the_range() {
        #[derive(schemars::JsonSchema)]
        #[allow(dead_code)]
        struct R {
            #[schemars(transform = item_bounds(Range::closed(1.0, 360.0, "deg")))]
            motions_deg: Vec<f64>,
        }
        let s = schemars::schema_for!(R);
        let items = &s.as_value()["properties"]["motions_deg"]["items"];
        assert_eq!((items["minimum"].as_f64(), items["maximum"].as_f64()), (Some(1.0), Some(360.0)));
    }
}
