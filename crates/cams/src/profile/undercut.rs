//! An undercut of the working profile as data: where it begins, which input to change and how far.

use super::cam::CamProfile;
use loomkin_units::{FieldError, compact};
use std::fmt;

/// The working profile is undercut: the roller is larger than the pitch curve's least convex
/// radius of curvature, or the flat face's profile has a cusp.
///
/// Its [`FieldError::field`] is the design input that cures it (`roller_radius_mm` or
/// `prime_radius_mm`), so a front end places it at its own flag or request key from data; the
/// message (`Display`) starts with that field, as every loomkin refusal does.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Undercut {
    /// Where the undercut begins (main-shaft deg).
    pub at_deg: f64,
    /// What is undercut and the limit that would avoid it.
    pub kind: UndercutKind,
}

/// What an [`Undercut`] is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum UndercutKind {
    /// A roller follower's roller is too large.
    Roller {
        /// The roller's radius (mm).
        roller_radius_mm: f64,
        /// The largest roller without undercut (mm).
        roller_max_mm: f64,
    },
    /// A flat face's profile has a cusp: the prime circle is too small.
    Cusp {
        /// The profile's least radius of curvature there (mm, ≤ 0).
        radius_mm: f64,
        /// The least prime radius without a cusp (mm).
        least_prime_radius_mm: f64,
    },
    /// Undercut, with no larger bound known (a knife edge on a concave pitch curve).
    Profile,
}

impl Undercut {
    /// The design input that cures the undercut: `prime_radius_mm` for a cusp, else `roller_radius_mm`.
    pub fn field_name(&self) -> &'static str {
        match self.kind {
            UndercutKind::Cusp { .. } => "prime_radius_mm",
            _ => "roller_radius_mm",
        }
    }
}

impl fmt::Display for Undercut {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let at = compact(self.at_deg);
        match self.kind {
            UndercutKind::Cusp { radius_mm, least_prime_radius_mm } => write!(
                f,
                "prime_radius_mm: the profile has a cusp at {at} deg (radius of curvature {} mm); the least prime \
                 radius without one is {} mm",
                compact(radius_mm),
                compact(least_prime_radius_mm)
            ),
            UndercutKind::Roller { roller_radius_mm, roller_max_mm } => write!(
                f,
                "roller_radius_mm: a {} mm roller undercuts the profile at {at} deg; the largest roller without \
                 undercut is {} mm",
                compact(roller_radius_mm),
                compact(roller_max_mm)
            ),
            UndercutKind::Profile => write!(f, "roller_radius_mm: the profile is undercut at {at} deg"),
        }
    }
}

impl std::error::Error for Undercut {}

impl FieldError for Undercut {
    fn field(&self) -> Option<&str> {
        Some(self.field_name())
    }
}

impl CamProfile {
    /// The undercut of the working profile, if there is one (see [`Undercut`]).
    pub fn undercut(&self) -> Option<Undercut> {
        let at_deg = self.undercut_at_deg()?;
        let kind = match (self.flat_extremes_report(), self.roller_max_mm()) {
            (Some(f), _) => UndercutKind::Cusp {
                radius_mm: f.min_radius_profile_mm,
                least_prime_radius_mm: f.least_prime_radius_mm,
            },
            (None, Some(roller_max_mm)) => {
                UndercutKind::Roller { roller_radius_mm: self.design().roller_radius_mm, roller_max_mm }
            }
            (None, None) => UndercutKind::Profile,
        };
        Some(Undercut { at_deg, kind })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::{CamDesign, Closure, Follower, Size};
    use crate::table::Motion;
    use loomkin_laws::{Cycle, CycleSpec, LawSpec, StrokeUnit};

    fn steep(design: CamDesign) -> CamProfile {
        let law = LawSpec::parse::<&str, &str>("cycloidal", &[]).unwrap();
        let cycle = Cycle::new(&CycleSpec::rise_return(&law, StrokeUnit::Mm, 40.0, 60.0).unwrap()).unwrap();
        CamProfile::new(&Motion::from_cycle(&cycle), &design).unwrap()
    }

    /// A roller one millimetre above the largest without undercut is undercut, named by the roller
    /// field and the limit; one at the limit's 99 % is not.
    #[test]
    fn a_roller_too_large_names_the_roller_and_the_largest() {
        let mut d = CamDesign {
            follower: Follower::Translating { offset_mm: 0.0 },
            closure: Closure::Single,
            roller_radius_mm: 0.0,
            size: Size::PrimeRadiusMm(80.0),
        };
        let rmax = steep(d).roller_max_mm().unwrap();
        d.roller_radius_mm = 0.99 * rmax;
        assert_eq!(steep(d).undercut(), None);
        d.roller_radius_mm = rmax + 1.0;
        let cam = steep(d);
        let u = cam.undercut().unwrap();
        assert_eq!(FieldError::field(&u), Some("roller_radius_mm"));
        assert_eq!(Some(u.at_deg), cam.undercut_at_deg());
        assert_eq!(u.kind, UndercutKind::Roller { roller_radius_mm: rmax + 1.0, roller_max_mm: rmax });
        let text = u.to_string();
        assert!(
            text.starts_with("roller_radius_mm: a ") && text.ends_with(&format!("is {} mm", compact(rmax))),
            "{text}"
        );
    }

    /// A flat face on too small a prime circle has a cusp, named by the prime radius.
    #[test]
    fn a_cusp_names_the_prime_radius() {
        let d = CamDesign {
            follower: Follower::Flat,
            closure: Closure::Single,
            roller_radius_mm: 0.0,
            size: Size::PrimeRadiusMm(10.0),
        };
        let cam = steep(d);
        let u = cam.undercut().unwrap();
        assert_eq!(u.field_name(), "prime_radius_mm");
        let f = cam.flat_extremes_report().unwrap();
        assert!(f.least_prime_radius_mm > 10.0, "{}", f.least_prime_radius_mm);
        assert!(u.to_string().starts_with("prime_radius_mm: the profile has a cusp at "), "{u}");
    }
}
