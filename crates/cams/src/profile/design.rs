//! What the user chooses: the follower, the closure, the roller and the size.

use crate::Result;
use loomkin_units::Range;

/// The follower of a disc cam.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Follower {
    /// Translating roller follower; the line of motion is offset by `offset_mm` (ε) from the cam
    /// centre, positive to the right of the centre when the follower stands above it (the side on
    /// which a counter-clockwise cam's rise has the smaller pressure angle).
    Translating {
        /// Offset ε (mm).
        offset_mm: f64,
    },
    /// Oscillating (swinging) roller follower: arm length `arm_mm` about a pivot `pivot_mm` from the
    /// cam centre; the cycle gives the swing in deg.
    Oscillating {
        /// Arm length L, pivot to roller centre (mm).
        arm_mm: f64,
        /// Distance d from the cam centre to the pivot (mm).
        pivot_mm: f64,
    },
    /// Flat-faced translating follower, the face perpendicular to the line of motion through the
    /// cam centre.
    Flat,
}

/// How the follower is kept on the cam.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Closure {
    /// One cam, one roller held on it by a spring (force closure).
    #[default]
    Single,
    /// The conjugate pair: two cams on one shaft, two rollers on one follower, one pushing each way.
    Conjugate,
    /// A groove cam: one roller running between two walls.
    Groove,
}

/// How the cam's size is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Size {
    /// The prime circle radius `R_p` (mm): the least radius of the pitch curve (base circle + roller).
    PrimeRadiusMm(f64),
    /// The least prime circle for which the largest pressure angle is at most this (deg).
    MaxPressureDeg(f64),
}

/// A cam design: follower, closure, roller and size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CamDesign {
    /// The follower.
    pub follower: Follower,
    /// Single, conjugate or groove.
    pub closure: Closure,
    /// Roller radius (mm); 0 for a knife edge (the profile is the pitch curve). Ignored by a flat face.
    pub roller_radius_mm: f64,
    /// The size.
    pub size: Size,
}

/// Allowed lengths (mm): prime radius, arm, pivot distance (a micrometre up to 100 m).
pub const LENGTH_RANGE: Range = Range::closed(1e-3, 1e5, "mm");
/// Allowed roller radius (mm).
pub const ROLLER_RANGE: Range = Range::closed(0.0, 1e5, "mm");
/// Allowed offset (mm).
pub const OFFSET_RANGE: Range = Range::closed(-1e5, 1e5, "mm");
/// Allowed largest pressure angle (deg).
pub const PRESSURE_RANGE: Range = Range::open(0.0, 89.0, "deg");
/// The largest pressure angle a cam is sized for when the design gives neither a prime radius
/// nor a pressure angle (deg): the customary limit for a translating roller follower, also the
/// limit line drawn for a cam of a given prime radius.
pub const DEFAULT_MAX_PRESSURE_DEG: f64 = 30.0;

impl Size {
    /// The size when the design names none: the least prime circle for
    /// [`DEFAULT_MAX_PRESSURE_DEG`].
    pub const DEFAULT: Size = Size::MaxPressureDeg(DEFAULT_MAX_PRESSURE_DEG);
}

impl CamDesign {
    /// Checks every number against its range, naming the field.
    pub fn check(&self) -> Result<()> {
        ROLLER_RANGE.check("roller_radius_mm", self.roller_radius_mm)?;
        match self.follower {
            Follower::Translating { offset_mm } => {
                OFFSET_RANGE.check("offset_mm", offset_mm)?;
            }
            Follower::Oscillating { arm_mm, pivot_mm } => {
                LENGTH_RANGE.check("arm_mm", arm_mm)?;
                LENGTH_RANGE.check("pivot_mm", pivot_mm)?;
            }
            Follower::Flat => {}
        }
        match self.size {
            Size::PrimeRadiusMm(r) => {
                LENGTH_RANGE.check("prime_radius_mm", r)?;
            }
            Size::MaxPressureDeg(a) => {
                PRESSURE_RANGE.check("max_pressure_deg", a)?;
            }
        }
        Ok(())
    }
}
