//! The paper's technical units (kgf, cm, s) and their conversion to SI — done once, here.
//!
//! Jederán gives forces in kilogram-force, lengths in cm, compliances in cm/kgf, the moment of
//! inertia in kgf·cm·s² and the shuttle mass in kgf·s²/cm. With g₀ = 9.80665 m/s² (standard
//! gravity, the definition of the kgf):
//!
//! | paper unit | SI | factor |
//! |---|---|---|
//! | kgf | N | 9.80665 |
//! | cm | m | 0.01 |
//! | cm/kgf (compliance) | m/N | 0.01 / 9.80665 = 1.019716e-3 |
//! | kgf·cm·s² (moment of inertia) | kg·m² | 9.80665 · 0.01 = 0.0980665 |
//! | kgf·s²/cm (mass) | kg | 9.80665 / 0.01 = 980.665 |

/// Standard gravity g₀ in m/s²: one kilogram-force is g₀ newtons.
pub const G0_M_S2: f64 = loomkin_units::STANDARD_GRAVITY_M_S2;
/// Newtons per kilogram-force.
pub const N_PER_KGF: f64 = G0_M_S2;
/// Metres per centimetre.
pub const M_PER_CM: f64 = 0.01;
/// Metres per millimetre.
pub const M_PER_MM: f64 = 0.001;
/// (m/N) per (cm/kgf): converts a compliance.
pub const M_PER_N_PER_CM_PER_KGF: f64 = M_PER_CM / N_PER_KGF;
/// (kg·m²) per (kgf·cm·s²): converts a moment of inertia.
pub const KG_M2_PER_KGF_CM_S2: f64 = N_PER_KGF * M_PER_CM;
/// kg per (kgf·s²/cm): converts a mass.
pub const KG_PER_KGF_S2_PER_CM: f64 = N_PER_KGF / M_PER_CM;
/// Kilograms per gram (a shuttle "weight" in grams is its mass in grams).
pub const KG_PER_G: f64 = 0.001;
