//! The criteria a designer weighs: dwells and the weft-insertion window (degrees), characteristic
//! values of the law (dimensionless) and their physical values for a stroke and a speed.

use crate::dwell::{band_crossings, lead, tail};
use crate::{Conditions, Result, ShedError, ShedLaw, check_threshold};
use loomkin_laws::Law;
use serde::Serialize;

/// Dimensionless criteria of a normalised rise at one threshold `T` — everything that does not
/// depend on the motion angle, the stroke or the speed.
///
/// `x` is the fraction of the motion angle. The frame counts as still while it is within `1 − T`
/// of the stroke from an end position. The rise enters that band around the top position at
/// `x_arrive` (the last entry: an upward crossing of `s = T`, or, for a law that overshoots its end
/// by more than `1 − T`, a downward crossing of `s = 2 − T`) and, the next pick, the same law run
/// downwards (`1 − s(x)`) leaves it at `x_depart` (the first exit: an upward crossing of
/// `s = 1 − T`, or a downward crossing of `s = −(1 − T)` for a law that first undershoots). The
/// frame arrives at and leaves the bottom position at the same fractions (it falls with `1 − s`
/// and rises with `s`), so the band is the same around both dwells. For a symmetric law
/// `x_depart = 1 − x_arrive`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Dimensionless {
    /// The threshold `T` used.
    pub threshold: f64,
    /// Cv = max ds/dx.
    pub cv: f64,
    /// Ca = max |d²s/dx²|.
    pub ca: f64,
    /// Cj = max |d³s/dx³| inside segments.
    pub cj: f64,
    /// Cm = max (v·a).
    pub cm: f64,
    /// RMS acceleration over the motion, √(∫₀¹ a² dx).
    pub ca_rms: f64,
    /// Largest jump of the acceleration, at a joint or against the dwells at `x = 0` and `x = 1`
    /// (a jump means an unbounded jerk, which `cj` does not count); 0 where the law's continuity
    /// judgement ([`loomkin_laws::DerivativeScale`]) finds none.
    pub a_jump: f64,
    /// End of the leading stretch at rest (`s ≡ 0`), fraction of the motion.
    pub lead: f64,
    /// Start of the trailing stretch at rest (`s ≡ 1`), fraction of the motion.
    pub tail: f64,
    /// First `x` with `|s(x)| > 1 − T` (the frame leaves the band around its start position).
    pub x_depart: f64,
    /// Last `x` with `|s(x) − 1| > 1 − T` (the frame enters the band around its end position).
    pub x_arrive: f64,
}

impl Dimensionless {
    /// The criteria of a law of the core, from its closed form: [`Law::metrics`] for the peaks and
    /// root finding on `s(x) = T`, `s(x) = 1 − T` (and `s = 2 − T`, `s = −(1 − T)` for laws that
    /// overshoot their ends) for the dwell.
    pub fn of_law(law: &Law, threshold: f64) -> Result<Self> {
        check_threshold(threshold)?;
        let m = law.metrics();
        // Last entry into |s − 1| ≤ 1 − T, first exit from |s| ≤ 1 − T.
        let (arrive, depart) = band_crossings(law, 1.0 - threshold);
        let (Some(x_arrive), Some(x_depart)) = (arrive, depart) else {
            return Err(ShedError::NotARise {
                field: "law".into(),
                reason: format!("the displacement never crosses the threshold {threshold}"),
            });
        };
        Ok(Self {
            threshold,
            cv: m.cv,
            ca: m.ca,
            cj: m.cj,
            cm: m.cm,
            ca_rms: m.ca_rms,
            a_jump: {
                // Where the law's continuity judgement finds the acceleration continuous, the
                // difference of the two sides is rounding, not a jump.
                let c = law.continuity();
                std::iter::once(&c.start)
                    .chain(&c.joints)
                    .chain(std::iter::once(&c.end))
                    .filter(|j| !j.flags()[2])
                    .fold(0.0, |m: f64, j| m.max(j.da.abs()))
            },
            lead: lead(law),
            tail: tail(law),
            x_depart,
            x_arrive,
        })
    }

    /// Whether the acceleration jumps somewhere: `a_jump` above [`loomkin_laws::CONTINUITY_TOL`]
    /// of the law's peak acceleration `ca` (the continuity judgement's rule; the fast path's
    /// `a_jump` is a difference of exact levels, this path's is already judged).
    pub fn accel_jumps(&self) -> bool {
        self.a_jump > loomkin_laws::CONTINUITY_TOL * self.ca
    }

    /// Fraction of the motion that lies inside the weft-insertion window (the frame within
    /// `1 − T` of its extreme): `c = x_depart + (1 − x_arrive)`.
    pub fn window_fraction(&self) -> f64 {
        self.x_depart + (1.0 - self.x_arrive)
    }

    /// Window `φ_пп* = 360° − Φ·(1 − c)` for a motion angle `Φ` in degrees.
    pub fn window_deg(&self, motion_deg: f64) -> f64 {
        360.0 - motion_deg * (1.0 - self.window_fraction())
    }
}

/// All criteria of a heald-frame law at given [`Conditions`].
///
/// Angles are degrees of the main shaft over one pick (360°):
/// `dwell_deg = φ_вр = 360° − Φ + Φ·(lead + 1 − tail)` (the nominal dwell plus any stretch of the
/// motion at rest), `conditional_dwell_deg = φ_ув = Φ·[(x_depart − lead) + (tail − x_arrive)]`
/// (both sides of the dwell, already doubled for a symmetric law), `window_deg = φ_пп* = φ_вр + φ_ув`.
/// Physical peaks for stroke `h` (m), `ω = 2πn/60` (rad/s) and `Φ` (rad):
/// `v = h·Cv·ω/Φ`, `a = h·Ca·(ω/Φ)²`, `j = h·Cj·(ω/Φ)³`, `(v·a)max = h²·Cm·(ω/Φ)³`.
/// `peak_jerk_m_s3` is the jerk inside segments; where the acceleration jumps
/// (`accel_jump_m_s2 > 0`) the jerk is unbounded.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Criteria {
    /// Motion angle `φ_дв`, deg.
    pub motion_deg: f64,
    /// Absolute dwell `φ_вр`, deg.
    pub dwell_deg: f64,
    /// Conditional dwell `φ_ув` at the threshold, deg.
    pub conditional_dwell_deg: f64,
    /// Weft-insertion window `φ_пп* = φ_вр + φ_ув`, deg.
    pub window_deg: f64,
    /// The threshold `T`.
    pub threshold: f64,
    /// Cv, dimensionless peak velocity.
    pub cv: f64,
    /// Ca, dimensionless peak acceleration (per unit stroke and unit motion angle).
    pub ca: f64,
    /// Cj, dimensionless peak jerk.
    pub cj: f64,
    /// Cm, dimensionless peak of v·a.
    pub cm: f64,
    /// Dimensionless RMS acceleration over the motion.
    pub ca_rms: f64,
    /// Dimensionless largest jump of the acceleration (0 for a law without jumps).
    pub a_jump: f64,
    /// Peak acceleration per unit stroke on the scale of a full turn, `Ca·(360°/φ_дв)²`
    /// (comparable between motion angles).
    pub ca_turn: f64,
    /// Peak frame velocity, m/s.
    pub peak_velocity_m_s: f64,
    /// Peak frame acceleration, m/s².
    pub peak_accel_m_s2: f64,
    /// Peak frame jerk, m/s³.
    pub peak_jerk_m_s3: f64,
    /// Peak of v·a (drive power per unit moving mass), W/kg = m²/s³.
    pub peak_power_w_kg: f64,
    /// RMS frame acceleration over the motion, m/s².
    pub rms_accel_m_s2: f64,
    /// Largest jump of the frame acceleration, m/s² (where the jerk is unbounded).
    pub accel_jump_m_s2: f64,
}

impl Criteria {
    /// Combines dimensionless criteria with a motion angle and the physical conditions. The
    /// threshold of `d` is used (the one in `c` is ignored).
    pub fn new(motion_deg: f64, d: &Dimensionless, c: &Conditions) -> Self {
        let phi = motion_deg;
        let dwell = 360.0 - phi + phi * (d.lead + 1.0 - d.tail);
        let cond = phi * ((d.x_depart - d.lead) + (d.tail - d.x_arrive));
        let turn = 360.0 / phi;
        Self {
            motion_deg: phi,
            dwell_deg: dwell,
            conditional_dwell_deg: cond,
            window_deg: dwell + cond,
            threshold: d.threshold,
            cv: d.cv,
            ca: d.ca,
            cj: d.cj,
            cm: d.cm,
            ca_rms: d.ca_rms,
            a_jump: d.a_jump,
            ca_turn: d.ca * turn * turn,
            peak_velocity_m_s: d.cv * c.scale(phi, 1),
            peak_accel_m_s2: d.ca * c.scale(phi, 2),
            peak_jerk_m_s3: d.cj * c.scale(phi, 3),
            peak_power_w_kg: d.cm * c.scale(phi, 1) * c.scale(phi, 2),
            rms_accel_m_s2: d.ca_rms * c.scale(phi, 2),
            accel_jump_m_s2: d.a_jump * c.scale(phi, 2),
        }
    }
}

/// Checks that the physical factors `h·(ω/Φ)^k` (k = 1, 2, 3) and the power factor are finite for a
/// motion angle (a tiny `Φ` overflows them).
pub(crate) fn check_scales(motion_deg: f64, conditions: &Conditions) -> Result<()> {
    let (s1, s2, s3) =
        (conditions.scale(motion_deg, 1), conditions.scale(motion_deg, 2), conditions.scale(motion_deg, 3));
    // Leave room for the dimensionless peaks (Ca, Cj up to ~1e6 for the shortest parts).
    if [s1, s2, s3, s1 * s2].iter().all(|v| v.is_finite() && *v < 1e290) {
        Ok(())
    } else {
        Err(ShedError::NotFinite { field: "motion_deg".into(), value: motion_deg })
    }
}

/// Every criterion of a law at the given conditions, through the law core (the generic path).
pub fn evaluate(law: &ShedLaw, conditions: &Conditions) -> Result<Criteria> {
    check_scales(law.motion_deg(), conditions)?;
    let built = law.build()?;
    let d = Dimensionless::of_law(&built, conditions.threshold())?;
    Ok(Criteria::new(law.motion_deg(), &d, conditions))
}
