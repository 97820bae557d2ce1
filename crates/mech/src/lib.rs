//! loomkin mech.
