//! # loomkin-cams — from a law to a part
//!
//! Controller cam tables for any law or machine cycle ([`table`]).
#![deny(missing_docs)]

mod error;
pub mod table;

pub use error::{CamError, Result};
