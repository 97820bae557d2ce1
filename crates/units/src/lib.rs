//! # loomkin-units — the words every loomkin crate shares
//!
//! One range error with one number format, one shaft-speed type, unit conversions named once and one
//! syntax for stepped sweeps, and one budget of memory and time ([`Budget`]) a run is estimated
//! against before it starts. Every library error embeds a [`RangeError`] for an out-of-range number,
//! so one quantity has one bound in the library, the CLI and the workbench, and a front end finds the
//! offending field from data ([`FieldError::field`]), never from message text.
//!
//! ```
//! use loomkin_units::{Range, ShaftSpeed};
//!
//! let speed = ShaftSpeed::from_rpm(600.0)?;
//! assert!((speed.rad_per_s() - 20.0 * std::f64::consts::PI).abs() < 1e-12);
//! assert!((speed.cycle_time_s() - 0.1).abs() < 1e-15);
//!
//! let ramp = Range::open_closed(0.0, 0.25, "");
//! let err = ramp.check("ramp", 0.0).unwrap_err();
//! assert_eq!(err.to_string(), "ramp = 0 is out of range: allowed 0 < ramp ≤ 0.25");
//! # Ok::<(), loomkin_units::RangeError>(())
//! ```
#![deny(missing_docs)]

mod budget;
mod convert;
mod field;
mod format;
mod range;
pub mod schema;
mod speed;
mod stop;
mod sweep;
mod toml_text;

pub use budget::{Budget, BudgetError, BudgetParseError, Cost, bytes_text, seconds_text};
pub use convert::{
    MM_PER_M, STANDARD_GRAVITY_M_S2, deg_from_rad, m_from_mm, mm_from_m, ms_from_s, rad_from_deg, rad_per_s_from_rpm,
    rpm_from_rad_per_s,
};
pub use field::{Field, FieldList};
pub use format::{compact, exact, fixed, sig4, to_12_digits};
pub use range::{Bound, FieldError, Range, RangeError, check_count};
pub use speed::ShaftSpeed;
pub use stop::{StopFlag, Stopped, to_the_end};
pub use sweep::{Shard, Span, SweepError};
pub use toml_text::toml_reason;

/// The descriptors this crate declares.
pub const FIELDS: FieldList = field_list![ShaftSpeed::SPEED];
