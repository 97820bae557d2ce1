//! # loomkin-insertion — weft insertion beyond the shuttle
//!
//! Today's looms insert the weft with rapiers, projectiles and air jets. For each carrier the
//! designer asks the same questions: how fast can the loom run for this reed width, does the
//! carrier pass the shed without touching the warp on every pick, and when must each element act.
//! This crate holds the carriers' models as library types with their own bounds: the time budget
//! every carrier shares, the rapier drives, torsion-bar projectile picking and the air-jet yarn
//! flight. It sits below `loomkin-loom`, which puts a carrier's path on the main-shaft angle of the
//! shed it computes (the clearance over a pattern repeat, the timing diagram).
#![deny(missing_docs)]
