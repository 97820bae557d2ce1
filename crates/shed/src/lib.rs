//! loomkin shed.
