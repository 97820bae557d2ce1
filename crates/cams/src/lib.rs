//! # loomkin-cams — from a law to a part
//!
//! Controller cam tables for any law or machine cycle ([`table`]); disc cam profiles, their
//! pressure angle, curvature, undercut and sizing ([`profile`]).
#![deny(missing_docs)]

mod error;
pub mod profile;
pub mod table;

pub use error::{CamError, Result};
