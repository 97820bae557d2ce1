//! # loomkin-drive — the sley and the main-shaft drive
//!
//! Every other study in loomkin assumes the main shaft turns at a constant speed. This crate is
//! where that assumption is dropped: the sley (batten) linkage the main shaft drives, the moment
//! of inertia the loom's mechanisms present to the shaft as it turns (J(φ)), the periodic motion
//! of the shaft under a motor and a load (speed ripple, flywheel sizing), and cam laws corrected
//! for the shaft's real speed (time-true cams).
//!
//! It sits below `loomkin-loom`: the mechanisms and the solvers live here, as library types with
//! their own bounds; the whole loom (its file, its frames over a pattern repeat) assembles them.
#![deny(missing_docs)]
