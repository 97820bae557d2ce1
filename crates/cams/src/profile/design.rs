//! What the user chooses: the follower, the closure, the roller and the size.

use crate::{CamError, Result};
use loomkin_units::{Field, Range};

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

/// The kind of follower, as a front end names it (`--follower`, `follower`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FollowerKind {
    /// Translating roller follower (radial, or offset by `offset_mm`).
    #[default]
    Translating,
    /// Oscillating roller follower (`arm_mm`, `pivot_mm`).
    Oscillating,
    /// Flat-faced translating follower.
    Flat,
}

/// A cam design as a front end takes it, each option as given: [`DesignInputs::design`] applies the
/// rules every front end shares (which options go with which follower, the default size).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DesignInputs {
    /// The follower.
    pub follower: FollowerKind,
    /// Single, conjugate or groove.
    pub closure: Closure,
    /// The prime radius, if given (mm).
    pub prime_radius_mm: Option<f64>,
    /// The largest pressure angle to size for, if given (deg).
    pub max_pressure_deg: Option<f64>,
    /// Roller radius (mm; [`CamDesign::ROLLER_RADIUS_MM`]'s default 0 is a knife edge).
    pub roller_radius_mm: f64,
    /// Offset of a translating follower (mm; default 0).
    pub offset_mm: f64,
    /// Arm length of an oscillating follower, if given (mm).
    pub arm_mm: Option<f64>,
    /// Pivot distance of an oscillating follower, if given (mm).
    pub pivot_mm: Option<f64>,
}

impl DesignInputs {
    /// The design, refusing what does not go together, naming the option:
    /// an oscillating follower needs `arm_mm` and `pivot_mm` (and only it takes them); only a
    /// translating follower takes `offset_mm`; a flat face has no roller and needs
    /// `prime_radius_mm`; the size is `prime_radius_mm` or `max_pressure_deg`, not both, and a
    /// roller follower given neither is sized for [`CamDesign::MAX_PRESSURE_DEG`]'s default (30°).
    /// The numbers are checked against their ranges by [`CamDesign::check`].
    pub fn design(&self) -> Result<CamDesign> {
        let usage = |field: &str, reason: &str| CamError::Usage { field: field.into(), reason: reason.into() };
        let follower = match self.follower {
            FollowerKind::Translating => Follower::Translating { offset_mm: self.offset_mm },
            FollowerKind::Oscillating => match (self.arm_mm, self.pivot_mm) {
                (Some(arm_mm), Some(pivot_mm)) => Follower::Oscillating { arm_mm, pivot_mm },
                (None, _) => return Err(usage("arm_mm", "an oscillating follower needs arm_mm and pivot_mm")),
                (_, None) => return Err(usage("pivot_mm", "an oscillating follower needs arm_mm and pivot_mm")),
            },
            FollowerKind::Flat => Follower::Flat,
        };
        if self.follower != FollowerKind::Oscillating && (self.arm_mm.is_some() || self.pivot_mm.is_some()) {
            return Err(usage("arm_mm", "arm_mm and pivot_mm are for an oscillating follower"));
        }
        if self.follower != FollowerKind::Translating && self.offset_mm != 0.0 {
            return Err(usage("offset_mm", "offset_mm is for a translating follower"));
        }
        if self.follower == FollowerKind::Flat && self.roller_radius_mm != 0.0 {
            return Err(usage("roller_radius_mm", "a flat-faced follower has no roller"));
        }
        let size = match (self.prime_radius_mm, self.max_pressure_deg) {
            (Some(_), Some(_)) => {
                return Err(usage("max_pressure_deg", "give prime_radius_mm or max_pressure_deg, not both"));
            }
            (Some(r), None) => Size::PrimeRadiusMm(r),
            (None, Some(p)) => Size::MaxPressureDeg(p),
            (None, None) if self.follower == FollowerKind::Flat => {
                return Err(usage(
                    "prime_radius_mm",
                    "a flat-faced follower needs prime_radius_mm (its pressure angle is 0 everywhere)",
                ));
            }
            (None, None) => Size::DEFAULT,
        };
        Ok(CamDesign { follower, closure: self.closure, roller_radius_mm: self.roller_radius_mm, size })
    }
}

impl CamDesign {
    /// `roller_radius_mm`: 0 (a knife edge: the profile is the pitch curve) up to 100 m.
    pub const ROLLER_RADIUS_MM: Field = Field::new(
        "roller_radius_mm",
        ROLLER_RANGE,
        "Roller radius: 0 (a knife edge, the profile is the pitch curve) … 100 m; 0 when left out.",
    )
    .with_default(0.0);
    /// `offset_mm`: the offset ε of a translating follower, ±100 m.
    pub const OFFSET_MM: Field = Field::new(
        "offset_mm",
        OFFSET_RANGE,
        "Offset ε of a translating follower's line of motion (positive: right of the cam centre, the \
         follower above it): ±100 m; 0 (radial) when left out.",
    )
    .with_default(0.0);
    /// `prime_radius_mm`: a micrometre up to 100 m.
    pub const PRIME_RADIUS_MM: Field = Field::new(
        "prime_radius_mm",
        LENGTH_RANGE,
        "Prime circle radius R (base circle + roller), a micrometre … 100 m; left out, the least R whose \
         largest pressure angle is max_pressure_deg.",
    );
    /// `max_pressure_deg`: 0 < α < 89° (at 90° the follower jams); 30° for a roller follower given
    /// neither this nor a prime radius (the usual limit of a translating roller follower).
    pub const MAX_PRESSURE_DEG: Field = Field::new(
        "max_pressure_deg",
        PRESSURE_RANGE,
        "Size the cam for this largest pressure angle: 0 < α < 89° (at 90° the follower jams); 30° for a \
         roller follower given neither this nor prime_radius_mm (the usual limit of a roller follower).",
    )
    .with_default(DEFAULT_MAX_PRESSURE_DEG);
    /// `arm_mm`: the arm length of an oscillating follower, a micrometre up to 100 m.
    pub const ARM_MM: Field = Field::new(
        "arm_mm",
        LENGTH_RANGE,
        "Arm length L of an oscillating follower (pivot to roller centre): a micrometre … 100 m.",
    );
    /// `pivot_mm`: the pivot distance of an oscillating follower, a micrometre up to 100 m.
    pub const PIVOT_MM: Field = Field::new(
        "pivot_mm",
        LENGTH_RANGE,
        "Distance d from the cam centre to an oscillating follower's pivot: a micrometre … 100 m.",
    );

    /// Checks every number against its range, naming the field.
    pub fn check(&self) -> Result<()> {
        Self::ROLLER_RADIUS_MM.check(self.roller_radius_mm)?;
        match self.follower {
            Follower::Translating { offset_mm } => {
                Self::OFFSET_MM.check(offset_mm)?;
            }
            Follower::Oscillating { arm_mm, pivot_mm } => {
                Self::ARM_MM.check(arm_mm)?;
                Self::PIVOT_MM.check(pivot_mm)?;
            }
            Follower::Flat => {}
        }
        match self.size {
            Size::PrimeRadiusMm(r) => {
                Self::PRIME_RADIUS_MM.check(r)?;
            }
            Size::MaxPressureDeg(a) => {
                Self::MAX_PRESSURE_DEG.check(a)?;
            }
        }
        Ok(())
    }
}
