//! loomkin io.
