//! loomkin servo.
