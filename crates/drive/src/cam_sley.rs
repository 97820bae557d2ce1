//! The cam-driven sley: the rocking shaft swung by a cam on the main shaft (conjugate cams on
//! rapier and projectile looms), and [`Sley`], the sley of a loom file whichever drive it has.
//!
//! **What the designer gives.** The cam law as a cycle (`[sley.cycle]`, the format of a cycle file,
//! `unit = "deg"`): the swing of the sley's rocking shaft against the main-shaft angle, one cycle
//! per turn (`period_deg = 360`), rising from the back position to the front (beat-up) and
//! returning. The swing, not the reed's travel, is what the cam drives: the cam's oscillating
//! follower is an arm on the rocking shaft, so the same cycle sizes the cam ([`CamSley::cam`], the
//! profile of loomkin-cams for `arm_mm`, `pivot_mm`, `roller_radius_mm`, the closure and the size).
//! The reed's travel is the arc `x = h·s` of its beating point, `h = reed_height_mm`.
//!
//! **Phase.** As with the four-bar, the front position (the largest swing) is put at the
//! main-shaft angle `beat_up_deg`: the cycle is shifted so that the middle of its highest stretch
//! (one angle for a law that turns at the front) falls there. A cycle written against the main
//! shaft with its peak at the beat-up needs no shift.
//!
//! **Kinematics.** With `s(φ)` the law's swing above its least value (rad) and its derivatives per
//! radian of main shaft from the law in closed form (loomkin-cams' [`Lift`]), the sword's angle from
//! +x is `θ = θ_back − κ·s`, κ = sign(sin θ_back) (an upright sword leans toward the fell as it
//! swings forward), the reed's displacement `x = h·s`, the reduced inertia `J = J_Q·s'²`,
//! `dJ/dφ = 2·J_Q·s'·s''`, the load torque by power balance `F(φ)·h·s' + m·g₀·g·cos θ·θ'` (the
//! beat-up resistance of [`FourBarSley::beat_up_force_n`]'s model and the weight), and the cam
//! shaft's torque `½·dJ/dφ·ω² + load` at constant speed.

use std::f64::consts::TAU;

use crate::sley::{Frame, ReedMotion, SleyAnalysis, SleyError, SleyForces, SleyRow, SleyTable, analysis_of, curve_of};
use crate::{FourBarSley, SleyJoints};
use loomkin_cams::profile::{CamDesign, CamProfile, Closure, DesignInputs, FollowerKind, Jet, Lift, Track};
use loomkin_cams::table::Motion;
use loomkin_laws::{Cycle, CycleSpec, StrokeUnit};
use loomkin_units::{Field, Range, ShaftSpeed};
use serde::{Deserialize, Serialize};

/// The drive of a `[sley]` table given as `drive = "cam"`: the only value (a table without `drive`
/// is the crank-rocker four-bar, [`SleyTable`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SleyDrive {
    /// A cam on the main shaft swings the rocking shaft.
    #[default]
    Cam,
}

/// How the cam holds the follower (`closure`), as loomkin-cams' [`Closure`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SleyClosure {
    /// Two cams on the main shaft, two rollers on the follower, one pushing each way (the default:
    /// the rule for sleys, whose beat-up and return both need a positive drive).
    #[default]
    Conjugate,
    /// One roller in a groove.
    Groove,
    /// One cam, the roller held on by a spring.
    Single,
}

fn default_back_angle() -> f64 {
    CamSleyTable::BACK_ANGLE_DEG.default_value()
}

fn default_roller() -> f64 {
    CamDesign::ROLLER_RADIUS_MM.default_value()
}

/// The `[sley]` table of a cam-driven sley as written (`drive = "cam"`); [`CamSley::new`] checks it.
/// The sley's own keys mean what they mean for the four-bar ([`SleyTable`]); the follower's are
/// loomkin-cams' ([`CamDesign`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CamSleyTable {
    /// `cam`.
    pub drive: SleyDrive,
    /// Rocking shaft to the reed's beating point, mm ([`SleyTable::REED_HEIGHT_MM`]).
    pub reed_height_mm: f64,
    /// The sley's moving mass, kg ([`SleyTable::MASS_KG`]).
    pub mass_kg: f64,
    /// Radius of gyration about the rocking shaft, mm ([`SleyTable::GYRATION_MM`]).
    pub gyration_mm: f64,
    /// Rocking shaft to the centre of mass, mm ([`SleyTable::CENTRE_MM`]); left out: `gyration_mm`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub centre_mm: Option<f64>,
    /// The sword's angle from +x (toward the fell, counter-clockwise) at the back position, deg
    /// ([`CamSleyTable::BACK_ANGLE_DEG`]).
    #[serde(default = "default_back_angle")]
    pub back_angle_deg: f64,
    /// Main-shaft angle of the front position, deg ([`SleyTable::BEAT_UP_DEG`]).
    #[serde(default = "crate::sley::default_beat_up_deg")]
    pub beat_up_deg: f64,
    /// Largest beat-up resistance, N ([`SleyTable::BEAT_UP_FORCE_N`]).
    #[serde(default = "crate::sley::default_zero_force")]
    pub beat_up_force_n: f64,
    /// Main-shaft angle over which it rises before the front position, deg
    /// ([`SleyTable::BEAT_UP_RANGE_DEG`]).
    #[serde(default = "crate::sley::default_zero_range")]
    pub beat_up_range_deg: f64,
    /// The follower's arm, rocking shaft to the roller's centre, mm ([`CamDesign::ARM_MM`]).
    pub arm_mm: f64,
    /// Main shaft (the cam's centre) to the rocking shaft, mm ([`CamDesign::PIVOT_MM`]).
    pub pivot_mm: f64,
    /// Roller radius, mm ([`CamDesign::ROLLER_RADIUS_MM`]; 0, a knife edge, when left out).
    #[serde(default = "default_roller")]
    pub roller_radius_mm: f64,
    /// `conjugate` (the default), `groove` or `single`.
    #[serde(default)]
    pub closure: SleyClosure,
    /// The cam's prime circle radius, mm ([`CamDesign::PRIME_RADIUS_MM`]); or
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub prime_radius_mm: Option<f64>,
    /// the largest pressure angle to size the cam for, deg ([`CamDesign::MAX_PRESSURE_DEG`]; 30°
    /// when neither is given).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_pressure_deg: Option<f64>,
    /// The cam law: the rocking shaft's swing (deg) against the main-shaft angle.
    pub cycle: CycleSpec,
}

impl CamSleyTable {
    /// `back_angle_deg`: −180 < θ ≤ 180°, default 90° (an upright sword at the back).
    pub const BACK_ANGLE_DEG: Field = Field::new(
        "sley.back_angle_deg",
        Range::open_closed(-180.0, 180.0, "deg"),
        "The cam sley's sword (rocking shaft to the reed) at the back position, from +x (toward the fell), \
         counter-clockwise: −180 < θ ≤ 180°, 90° (upright) when left out; the sword must not pass the \
         horizontal over its swing. Only the weight's torque and the side view depend on it.",
    )
    .with_default(90.0);
}

/// A checked cam-driven sley (lengths in m inside).
#[derive(Debug, Clone)]
pub struct CamSley {
    table: CamSleyTable,
    lift: Lift,
    cam: CamProfile,
    /// First angle of the cycle, deg.
    start_deg: f64,
    /// Main-shaft angle minus cycle angle, rad.
    shift: f64,
    h: f64,
    j_q: f64,
    g: f64,
    theta_back: f64,
    kappa: f64,
    stroke: f64,
    phi_front: f64,
    phi_back: f64,
    beat_force: f64,
    beat_range: f64,
}

/// The cam's push on a cam sley's follower at one angle ([`CamSley::contact`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CamContact {
    /// The contact force, N, signed by the closure: a conjugate pair's positive on the cam pushing
    /// the sley forward (track 0), negative on the return cam (track 1); a groove's positive on its
    /// inner wall, negative on its outer; a single cam's negative where the roller would lift off
    /// (no spring holds it).
    pub force_n: f64,
    /// The track that carries it (0, or 1 the conjugate's return cam).
    pub track: usize,
    /// The force on the follower's roller in the side view (x toward the fell, y up), N.
    pub on_roller_n: [f64; 2],
    /// The roller's centre in the side view, m from the main shaft.
    pub roller_m: [f64; 2],
    /// The cam shaft's torque from the contact, N·m: `q × F`.
    pub cam_torque_n_m: f64,
}

impl PartialEq for CamSley {
    fn eq(&self, other: &Self) -> bool {
        self.table == other.table
    }
}

/// An error of loomkin-cams named as a key of the `[sley]` table.
fn cam_error(e: loomkin_cams::CamError) -> SleyError {
    use loomkin_units::FieldError;
    let field = e.field().unwrap_or("cycle").to_string();
    let reason = match &e {
        loomkin_cams::CamError::Range(r) => {
            return SleyError::Range(r.clone().renamed(format!("sley.{}", r.field.trim_start_matches("sley."))));
        }
        loomkin_cams::CamError::Law { reason, .. }
        | loomkin_cams::CamError::Usage { reason, .. }
        | loomkin_cams::CamError::Parse { reason, .. } => reason.clone(),
        other => other.to_string(),
    };
    let field = if field == "segment" || field == "law" { "sley.cycle".into() } else { format!("sley.{field}") };
    SleyError::Infeasible { fields: field, reason }
}

/// The follower and cam size of a cam sley's table, for loomkin-cams.
fn design_inputs(t: &CamSleyTable) -> DesignInputs {
    DesignInputs {
        follower: FollowerKind::Oscillating,
        closure: match t.closure {
            SleyClosure::Conjugate => Closure::Conjugate,
            SleyClosure::Groove => Closure::Groove,
            SleyClosure::Single => Closure::Single,
        },
        prime_radius_mm: t.prime_radius_mm,
        max_pressure_deg: t.max_pressure_deg,
        roller_radius_mm: t.roller_radius_mm,
        offset_mm: 0.0,
        arm_mm: Some(t.arm_mm),
        pivot_mm: Some(t.pivot_mm),
    }
}

/// The middle of the stretch of one turn `[lo, lo + 2π)` where `f ≥ top − tol` around `at` (a
/// point of it), rad.
fn plateau_middle(f: &dyn Fn(f64) -> f64, at: f64, level: f64) -> f64 {
    let step = 0.05_f64.to_radians();
    let edge = |dir: f64| {
        let mut a = at;
        let mut k = 0;
        while f(a + dir * step) >= level && k < 7200 {
            a += dir * step;
            k += 1;
        }
        // Bisect the crossing between a (inside) and a + dir·step (outside).
        let (mut inside, mut outside) = (a, a + dir * step);
        for _ in 0..60 {
            let mid = 0.5 * (inside + outside);
            if f(mid) >= level {
                inside = mid;
            } else {
                outside = mid;
            }
        }
        inside
    };
    0.5 * (edge(-1.0) + edge(1.0))
}

impl CamSley {
    /// Checks a cam sley's table: every number against its field, the cycle (one turn, in deg,
    /// closing), the cam for the follower (loomkin-cams' profile: it must be made, undercut-free),
    /// and the sword not passing the horizontal.
    pub fn new(t: CamSleyTable) -> Result<Self, SleyError> {
        let h = SleyTable::REED_HEIGHT_MM.check(t.reed_height_mm)?;
        let m = SleyTable::MASS_KG.check(t.mass_kg)?;
        let k = SleyTable::GYRATION_MM.check(t.gyration_mm)?;
        let g = match t.centre_mm {
            Some(g) => Range::closed(0.0, k, "mm").check(SleyTable::CENTRE_MM.name, g)?,
            None => k,
        };
        let back = CamSleyTable::BACK_ANGLE_DEG.check(t.back_angle_deg)?;
        let beat = SleyTable::BEAT_UP_DEG.check(t.beat_up_deg)?;
        let force = SleyTable::BEAT_UP_FORCE_N.check(t.beat_up_force_n)?;
        let range = SleyTable::BEAT_UP_RANGE_DEG.check(t.beat_up_range_deg)?;
        let sley_field = |f: &Field, v: f64| f.check_as(&format!("sley.{}", f.name), v);
        sley_field(&CamDesign::ARM_MM, t.arm_mm)?;
        sley_field(&CamDesign::PIVOT_MM, t.pivot_mm)?;
        sley_field(&CamDesign::ROLLER_RADIUS_MM, t.roller_radius_mm)?;
        if let Some(r) = t.prime_radius_mm {
            sley_field(&CamDesign::PRIME_RADIUS_MM, r)?;
        }
        if let Some(a) = t.max_pressure_deg {
            sley_field(&CamDesign::MAX_PRESSURE_DEG, a)?;
        }
        if t.cycle.unit != StrokeUnit::Deg {
            return Err(SleyError::Infeasible {
                fields: "sley.cycle.unit".into(),
                reason: "a cam sley's cycle gives the rocking shaft's swing: unit = \"deg\" (the reed travels \
                         reed_height_mm × the swing)"
                    .into(),
            });
        }
        if t.cycle.period_deg != 360.0 {
            return Err(SleyError::Infeasible {
                fields: "sley.cycle.period_deg".into(),
                reason: format!(
                    "{}°: the sley beats up once a turn, so its cam turns with the main shaft (period_deg = 360)",
                    loomkin_units::compact(t.cycle.period_deg)
                ),
            });
        }
        let cycle = Cycle::new(&t.cycle).map_err(|e| SleyError::Infeasible {
            fields: format!("sley.cycle.{}", loomkin_units::FieldError::field(&e).unwrap_or("segment")),
            reason: e.to_string(),
        })?;
        let motion = Motion::from_cycle(&cycle);
        let lift = Lift::new(&motion).map_err(cam_error)?;
        let design = design_inputs(&t).design().map_err(cam_error)?;
        let cam = CamProfile::new(&motion, &design).map_err(cam_error)?;
        if let Some(at) = cam.undercut_at_deg() {
            return Err(SleyError::Infeasible {
                fields: "sley.roller_radius_mm".into(),
                reason: format!(
                    "the cam is undercut at {}° of its cycle: a smaller roller or a larger cam (prime_radius_mm)",
                    loomkin_units::sig4(at)
                ),
            });
        }
        let start_deg = motion.start_deg();
        let stroke = lift.stroke();
        let mm = 1e-3;
        let theta_back = back.to_radians();
        let kappa = if theta_back.sin() >= 0.0 { 1.0 } else { -1.0 };
        let theta_front = theta_back - kappa * stroke;
        if theta_back.sin() * kappa <= 0.0 || theta_front.sin() * kappa <= 0.0 {
            return Err(SleyError::Infeasible {
                fields: CamSleyTable::BACK_ANGLE_DEG.name.into(),
                reason: format!(
                    "{}° with a swing of {}°: the sword lies on or passes the horizontal, where the reed no longer \
                     moves toward the fell",
                    loomkin_units::compact(back),
                    loomkin_units::sig4(stroke.to_degrees())
                ),
            });
        }
        let mut s = Self {
            table: t,
            lift,
            cam,
            start_deg,
            shift: 0.0,
            h: h * mm,
            j_q: m * (k * mm) * (k * mm),
            g: g * mm,
            theta_back,
            kappa,
            stroke,
            phi_front: beat.to_radians(),
            phi_back: 0.0,
            beat_force: force,
            beat_range: range.to_radians(),
        };
        // The front: the middle of the law's highest stretch, put at the beat-up.
        let (front_u, back_u) = {
            let lo = start_deg.to_radians();
            let sw = |u: f64| s.swing_at_cycle(u)[0];
            // The extreme: the middle of a stretch where the law stays at it (a dwell there), else
            // the root of s' between the grid's neighbours of the scan's peak.
            let turn = |sign: f64| {
                let top = loomkin_numeric::scan_max(lo, lo + TAU, 1440, |u| sign * sw(u));
                let flat = |u: f64| sign * sw(u);
                let mid = plateau_middle(&flat, top.at, top.value - 1e-12 * stroke);
                let step = TAU / 1440.0;
                if (mid - top.at).abs() > 0.5 * step {
                    return mid;
                }
                let gd = |u: f64| {
                    let j = s.swing_at_cycle(u);
                    (sign * j[1], sign * j[2])
                };
                let (a, b) = (top.at - step, top.at + step);
                if gd(a).0 > 0.0 && gd(b).0 < 0.0 { loomkin_numeric::refine_root(a, b, false, gd) } else { mid }
            };
            (turn(1.0), turn(-1.0))
        };
        s.shift = s.phi_front - front_u;
        s.phi_back = (back_u + s.shift).rem_euclid(TAU);
        // The resistance only opposes the reed moving toward the fell: its range lies within the
        // forward move, back from the front to where s' last vanished.
        let forward_deg = {
            let step = 0.05_f64.to_radians();
            let d1 = |p: f64| s.swing(p)[1];
            let mut a = s.phi_front - step;
            while d1(a) > 0.0 && s.phi_front - a < TAU {
                a -= step;
            }
            let start = loomkin_numeric::refine_root(a, a + step, true, |p| {
                let j = s.swing(p);
                (j[1], j[2])
            });
            (s.phi_front - start).to_degrees()
        };
        Range::closed(0.0, forward_deg, "deg").check(SleyTable::BEAT_UP_RANGE_DEG.name, range)?;
        Ok(s)
    }

    /// The swing above its least value and its first three rates at cycle angle `u` (rad), any
    /// real `u` (wrapped into the cycle).
    fn swing_at_cycle(&self, u: f64) -> [f64; 4] {
        let j = self.lift_jet(u);
        [j.v(), j.d(1), j.d(2), j.d(3)]
    }

    /// The law's jet (the swing and its rates per radian of cam) at cycle angle `u` (rad), wrapped.
    fn lift_jet(&self, u: f64) -> Jet {
        let lo = self.start_deg.to_radians();
        let w = lo + (u - lo).rem_euclid(TAU);
        self.lift.jet_at(self.lift.psi(w.to_degrees()))
    }

    /// The swing `s` above the back position (rad) and `s'`, `s''`, `s'''` per radian of main
    /// shaft at main-shaft angle φ.
    pub fn swing(&self, phi_rad: f64) -> [f64; 4] {
        self.swing_at_cycle(phi_rad - self.shift)
    }

    /// The table this sley was built from.
    pub fn table(&self) -> &CamSleyTable {
        &self.table
    }

    /// The cam (loomkin-cams' profile of the oscillating follower for the cycle as written: its
    /// angles are the cycle's, the main shaft's less [`CamSley::phase_deg`]).
    pub fn cam(&self) -> &CamProfile {
        &self.cam
    }

    /// The cam another law (a cycle as `[sley.cycle]`, e.g. a time-true correction of this one)
    /// needs on this sley's follower with this sley's cam size: the same arm, pivot, roller and
    /// closure and the prime circle of [`CamSley::cam`]. Its pressure angle and curvature tell
    /// whether the follower the cam was designed for can take the other law; it is made whether
    /// or not it is undercut ([`CamProfile::undercut_at_deg`] says).
    pub fn cam_for(&self, cycle: &CycleSpec) -> Result<CamProfile, SleyError> {
        let cycle = Cycle::new(cycle).map_err(|e| SleyError::Infeasible {
            fields: format!("sley.cycle.{}", loomkin_units::FieldError::field(&e).unwrap_or("segment")),
            reason: e.to_string(),
        })?;
        let motion = Motion::from_cycle(&cycle);
        let design = DesignInputs {
            prime_radius_mm: Some(self.cam.prime_radius_mm()),
            max_pressure_deg: None,
            ..self.design_inputs()
        }
        .design()
        .map_err(cam_error)?;
        CamProfile::new(&motion, &design).map_err(cam_error)
    }

    /// The largest pressure angle the sley's cam is allowed, deg: `max_pressure_deg` when the cam
    /// was sized for one, else loomkin-cams' default ([`CamDesign::MAX_PRESSURE_DEG`]).
    pub fn pressure_limit_deg(&self) -> f64 {
        self.table.max_pressure_deg.unwrap_or_else(|| CamDesign::MAX_PRESSURE_DEG.default_value())
    }

    /// The follower and cam size of the table, for loomkin-cams.
    fn design_inputs(&self) -> DesignInputs {
        design_inputs(&self.table)
    }

    /// Main-shaft angle less the cycle's angle, deg in [0, 360): where the cycle's 0° falls.
    pub fn phase_deg(&self) -> f64 {
        self.shift.to_degrees().rem_euclid(360.0)
    }

    /// The sword's angle from +x at main-shaft angle φ, rad.
    pub fn rocker_rad(&self, phi_rad: f64) -> f64 {
        self.theta_back - self.kappa * self.swing(phi_rad)[0]
    }

    /// Main-shaft angle of the front position (beat-up), rad.
    pub fn front_dead_centre_rad(&self) -> f64 {
        self.phi_front
    }

    /// Main-shaft angle of the back position (the middle of the law's lowest stretch), rad in [0, 2π).
    pub fn back_dead_centre_rad(&self) -> f64 {
        self.phi_back
    }

    /// Main-shaft angle from the back position forward to the front, rad.
    pub fn forward_stroke_rad(&self) -> f64 {
        (self.phi_front - self.phi_back).rem_euclid(TAU)
    }

    /// The reed's stroke, m.
    pub fn stroke_m(&self) -> f64 {
        self.h * self.stroke
    }

    /// The sley's moment of inertia about its rocking shaft, kg·m².
    pub fn inertia_kg_m2(&self) -> f64 {
        self.j_q
    }

    /// The reed's motion at main-shaft angle φ (per radian of main shaft).
    pub fn reed(&self, phi_rad: f64) -> ReedMotion {
        let s = self.swing(phi_rad);
        ReedMotion { x_m: self.h * s[0], dx_m: self.h * s[1], d2x_m: self.h * s[2], d3x_m: self.h * s[3] }
    }

    /// `(J, dJ/dφ)` = `(J_Q·s'², 2·J_Q·s'·s'')`, kg·m² and kg·m²/rad.
    pub fn reduced_inertia_kg_m2(&self, phi_rad: f64) -> (f64, f64) {
        let s = self.swing(phi_rad);
        (self.j_q * s[1] * s[1], 2.0 * self.j_q * s[1] * s[2])
    }

    /// The beat-up resistance at φ, N: the four-bar's model ([`FourBarSley::beat_up_force_n`]).
    pub fn beat_up_force_n(&self, phi_rad: f64) -> f64 {
        crate::sley::beat_up_model(self.beat_force, self.beat_range, self.phi_front, phi_rad)
    }

    /// The non-inertial torque the sley asks of the main shaft at φ, N·m: `F·h·s'` (beat-up) plus
    /// `m·g₀·g·cos θ·θ'` (the rate of the weight's potential energy).
    pub fn load_torque_n_m(&self, phi_rad: f64) -> f64 {
        let s = self.swing(phi_rad);
        let theta = self.theta_back - self.kappa * s[0];
        let weight = self.table.mass_kg * loomkin_units::STANDARD_GRAVITY_M_S2 * self.g * theta.cos();
        self.beat_up_force_n(phi_rad) * self.h * s[1] + weight * (-self.kappa * s[1])
    }

    /// The moment about the rocking shaft, in the direction of a growing swing, that the cam must
    /// give the sley at φ and constant speed ω, N·m: `J_Q·s''·ω² + F·h − κ·m·g₀·g·cos θ` (its
    /// inertia, the beat-up resistance, the weight). The cam shaft's torque is `s'` times it.
    pub fn cam_moment_n_m(&self, phi_rad: f64, omega: f64) -> f64 {
        let s = self.swing(phi_rad);
        let theta = self.theta_back - self.kappa * s[0];
        let weight = self.table.mass_kg * loomkin_units::STANDARD_GRAVITY_M_S2 * self.g * theta.cos();
        self.j_q * s[2] * omega * omega + self.beat_up_force_n(phi_rad) * self.h - self.kappa * weight
    }

    /// The cam's push on the follower at φ and constant speed ω ([`CamContact`]).
    ///
    /// Each track of the cam (loomkin-cams' [`Track::Oscillating`]: the roller's centre `q` about the
    /// pivot, `e` its direction of motion as the swing grows) at the law's jet gives the pitch
    /// curve's tangent in the fixed frame `t = dq/dψ − J·q` (`J` the rotation by +90°) and its
    /// outward normal `n = J·t/|t|`, the line through the roller's centre along which a roller
    /// outside the cam is pushed. A force `N·n` gives the rocking shaft the moment `N·L·(n·e)`, so
    /// `N = M/(L·(n·e))` with `M` [`CamSley::cam_moment_n_m`]. A conjugate pair: the track with `N ≥ 0`
    /// carries it (track 0 pushes the sley forward, track 1 back); a groove: one track, the inner
    /// wall when `N > 0`, the outer when `N < 0`; a single cam: `N < 0` is the roller lifting off.
    /// The cam shaft's torque is `q × N·n` (the contact point lies on the same normal).
    pub fn contact(&self, phi_rad: f64, omega: f64) -> CamContact {
        let moment = self.cam_moment_n_m(phi_rad, omega);
        let jet = self.lift_jet(phi_rad - self.shift);
        let mm = 1e-3;
        // Each track's normal, lever (m) and roller centre (mm) in the cam's frame.
        let at = |k: usize| {
            let track = self.cam.track(k);
            let (q, e) = track.q_e(jet);
            let l = match track {
                Track::Oscillating { l, .. } => l,
                _ => self.table.arm_mm,
            };
            let t = [q[0].d(1) + q[1].v(), q[1].d(1) - q[0].v()];
            let len = t[0].hypot(t[1]);
            let n = [-t[1] / len, t[0] / len];
            let lever = l * mm * (n[0] * e[0].v() + n[1] * e[1].v());
            (n, lever, [q[0].v(), q[1].v()])
        };
        let (n0, lever0, q0) = at(0);
        let conjugate = self.cam.track_count() > 1;
        let (track, n, lever, q) = if conjugate && (moment >= 0.0) != (lever0 > 0.0) {
            let (n1, lever1, q1) = at(1);
            (1, n1, lever1, q1)
        } else {
            (0, n0, lever0, q0)
        };
        let force = moment / lever;
        let on = [force * n[0], force * n[1]];
        let torque = (q[0] * on[1] - q[1] * on[0]) * mm;
        let side = |v: [f64; 2]| [v[0], self.kappa * v[1]];
        CamContact {
            force_n: if track == 1 { -force } else { force },
            track,
            on_roller_n: side(on),
            roller_m: side([q[0] * mm, q[1] * mm]),
            cam_torque_n_m: torque,
        }
    }

    /// The forces at φ and constant speed ω: the inertia force along the reed's path, the beat-up
    /// resistance, the cam shaft's torque (inertia and load parts), the cam's contact force
    /// ([`CamSley::contact`]) and the rocking shaft's bearing force `m·a_G − F_cam − κ·F·e⊥(θ) +
    /// (0, m·g₀)` on the sley (`a_G = g·(θ̈·e⊥(θ) − θ̇²·e(θ))`); the main shaft's bearing carries the
    /// contact force (the cams massless). There is no rod: `rod_force_n` and `crank_pin_n` are 0.
    ///
    /// The side view is the cams' frame (loomkin-cams': the main shaft at the origin, the rocking
    /// shaft `pivot_mm` along +x, the cams turning counter-clockwise, the follower clockwise as the
    /// swing grows) when the sword turns clockwise as the sley swings forward (`κ = 1`, a sword
    /// standing up); mirrored top to bottom otherwise.
    pub fn forces(&self, phi_rad: f64, omega: f64) -> SleyForces {
        let s = self.swing(phi_rad);
        let w2 = omega * omega;
        let inertia_torque = self.j_q * s[1] * s[2] * w2;
        let load = self.load_torque_n_m(phi_rad);
        let c = self.contact(phi_rad, omega);
        let theta = self.theta_back - self.kappa * s[0];
        let (theta_d, theta_dd) = (-self.kappa * s[1] * omega, -self.kappa * s[2] * w2);
        let (st, ct) = theta.sin_cos();
        let m = self.table.mass_kg;
        let ag =
            [self.g * (-theta_dd * st - theta_d * theta_d * ct), self.g * (theta_dd * ct - theta_d * theta_d * st)];
        let f = self.beat_up_force_n(phi_rad);
        let bearing = [
            m * ag[0] - c.on_roller_n[0] - self.kappa * f * (-st),
            m * ag[1] - c.on_roller_n[1] - self.kappa * f * ct + m * loomkin_units::STANDARD_GRAVITY_M_S2,
        ];
        SleyForces {
            inertia_force_n: self.j_q * s[2] * w2 / self.h,
            beat_up_force_n: f,
            rod_force_n: 0.0,
            crank_pin_n: 0.0,
            crank_bearing_n: c.force_n.abs(),
            rocking_shaft_n: bearing,
            crank_torque_n_m: inertia_torque + load,
            inertia_torque_n_m: inertia_torque,
            load_torque_n_m: load,
        }
    }

    /// The sley seen from the side at φ, m from the main shaft (the cam's centre), x toward the
    /// fell, y up: the rocking shaft `pivot_mm` in front of the main shaft at its height, the
    /// follower's roller on the arm opposite the sword (as `sword_pin`), the reed. `crank_pin` is the
    /// main shaft (a cam has no crank pin).
    pub fn joints_m(&self, phi_rad: f64) -> SleyJoints {
        let q = [self.table.pivot_mm * 1e-3, 0.0];
        let th = self.rocker_rad(phi_rad);
        let (st, ct) = th.sin_cos();
        let arm = self.table.arm_mm * 1e-3;
        SleyJoints {
            crank_pin: [0.0, 0.0],
            sword_pin: [q[0] - arm * ct, q[1] - arm * st],
            rocking_shaft: q,
            reed: [q[0] + self.h * ct, q[1] + self.h * st],
        }
    }

    /// The back dwell for a tolerance `tol_m`: the main-shaft angles `(start, end)` (rad, `end >
    /// start`) of the stretch around the back position over which the reed stays within `tol_m` of
    /// it (a cam law may move the reed to and fro; the stretch is the one holding the back position).
    pub fn back_dwell_rad(&self, tol_m: f64) -> Result<(f64, f64), SleyError> {
        let stroke = self.stroke_m();
        Range::open(0.0, stroke * 1e3, "mm").check(SleyAnalysis::DWELL_TOLERANCE_MM.name, tol_m * 1e3)?;
        let back = self.phi_back;
        // The stretch's ends: scanned outward from the back position every 0.05°, the crossing of
        // x = tol refined by safeguarded Newton in the step that holds it.
        let step = 0.05_f64.to_radians();
        let gd = |phi: f64| {
            let m = self.reed(phi);
            (m.x_m - tol_m, m.dx_m)
        };
        let end_of = |dir: f64| {
            let mut a = back;
            while self.reed(a + dir * step).x_m <= tol_m && (a - back).abs() < TAU {
                a += dir * step;
            }
            let b = a + dir * step;
            if dir > 0.0 {
                loomkin_numeric::refine_root(a, b, true, gd)
            } else {
                loomkin_numeric::refine_root(b, a, false, gd)
            }
        };
        Ok((end_of(-1.0), end_of(1.0)))
    }

    /// The analysis `loomkin sley analyze` prints, with the four-bar's keys: the crank torque is the
    /// cam shaft's; the least transmission angle is 90° less the cam's largest pressure angle; the
    /// rod and rocking-shaft forces are left out (not modelled for a cam).
    pub fn analyze(&self, speed: ShaftSpeed, dwell_tolerance_mm: f64) -> Result<SleyAnalysis, SleyError> {
        let tol = SleyAnalysis::DWELL_TOLERANCE_MM.check(dwell_tolerance_mm)?;
        let dwell = self.back_dwell_rad(tol * 1e-3)?;
        // A finer grid than the four-bar's: a cam law's extremes may sit close together.
        let frame = Frame {
            front: self.phi_front,
            back: self.phi_back,
            stroke_m: self.stroke_m(),
            inertia: self.j_q,
            intervals: 4 * SleyAnalysis::SCAN_INTERVALS,
        };
        let mut r = analysis_of(&frame, speed, tol, dwell, &|p| self.reed(p), &|p, w| self.forces(p, w));
        let w = speed.rad_per_s();
        let scan = |f: &dyn Fn(f64) -> f64| {
            let m = loomkin_numeric::scan_max(frame.front, frame.front + TAU, frame.intervals, f);
            (m.value, m.at.rem_euclid(TAU).to_degrees())
        };
        let (c_max, c_max_at) = scan(&|p| self.contact(p, w).force_n);
        let (c_min, c_min_at) = scan(&|p| -self.contact(p, w).force_n);
        let (peak, peak_at) = if c_max >= c_min { (c_max, c_max_at) } else { (c_min, c_min_at) };
        r.peak_contact_force_n = Some(peak);
        r.peak_contact_force_deg = Some(peak_at);
        r.max_contact_force_n = Some(c_max);
        r.max_contact_force_deg = Some(c_max_at);
        r.min_contact_force_n = Some(-c_min);
        r.min_contact_force_deg = Some(c_min_at);
        r.contact_force_sign = Some(match self.table.closure {
            SleyClosure::Conjugate => "positive: the cam pushing the sley forward; negative: the return cam",
            SleyClosure::Groove => "positive: the groove's inner wall; negative: its outer wall",
            SleyClosure::Single => "negative: the roller lifts off the cam (no spring is modelled)",
        });
        r.peak_rocking_shaft_force_n = Some(scan(&|p| self.forces(p, w).rocking_shaft_magnitude_n()).0);
        let (pressure, _, _) = self.cam.max_pressure_angle();
        r.min_transmission_angle_deg = 90.0 - pressure;
        r.drive = Some("cam");
        r.max_pressure_angle_deg = Some(pressure);
        r.prime_radius_mm = Some(self.cam.prime_radius_mm());
        Ok(r)
    }

    /// Rows of the curves over one revolution (`points + 1` rows) at ω; no rod force.
    pub fn curve(&self, points: usize, omega: f64) -> Vec<SleyRow> {
        curve_of(points, omega, &|p| (self.reed(p), self.forces(p, omega), false))
    }

    /// The main-shaft angles where the sley's law has a joint (between its segments and inside a
    /// law made of pieces, as the modified sine's eighths): where `J` is not smooth, rad in [0, 2π).
    pub fn law_joints_rad(&self) -> Vec<f64> {
        self.lift.joints_deg().into_iter().map(|d| (d.to_radians() + self.shift).rem_euclid(TAU)).collect()
    }

    /// The main-shaft angles where the sley's law or its beat-up model has a joint, rad in [0, 2π).
    pub fn breaks_rad(&self) -> Vec<f64> {
        let mut out = self.law_joints_rad();
        if self.beat_force > 0.0 && self.beat_range > 0.0 {
            out.push(self.phi_front);
            out.push((self.phi_front - self.beat_range).rem_euclid(TAU));
        }
        out
    }
}

/// The sley of a loom file: the crank-rocker four-bar or the cam-driven sley.
#[derive(Debug, Clone, PartialEq)]
#[allow(clippy::large_enum_variant)]
pub enum Sley {
    /// A crank-rocker four-bar ([`FourBarSley`]).
    FourBar(FourBarSley),
    /// A cam on the main shaft ([`CamSley`]).
    Cam(CamSley),
}

impl From<FourBarSley> for Sley {
    fn from(s: FourBarSley) -> Self {
        Self::FourBar(s)
    }
}

impl From<CamSley> for Sley {
    fn from(s: CamSley) -> Self {
        Self::Cam(s)
    }
}

macro_rules! either {
    ($self:ident, $s:ident => $e:expr) => {
        match $self {
            Sley::FourBar($s) => $e,
            Sley::Cam($s) => $e,
        }
    };
}

impl Sley {
    /// The four-bar, if this is one.
    pub fn four_bar(&self) -> Option<&FourBarSley> {
        match self {
            Self::FourBar(s) => Some(s),
            Self::Cam(_) => None,
        }
    }

    /// The cam sley, if this is one.
    pub fn cam(&self) -> Option<&CamSley> {
        match self {
            Self::Cam(s) => Some(s),
            Self::FourBar(_) => None,
        }
    }

    /// `four-bar` or `cam`.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::FourBar(_) => "four-bar",
            Self::Cam(_) => "cam",
        }
    }

    /// Main-shaft angle of the front dead centre (beat-up), rad.
    pub fn front_dead_centre_rad(&self) -> f64 {
        either!(self, s => s.front_dead_centre_rad())
    }

    /// Main-shaft angle of the back dead centre, rad in [0, 2π).
    pub fn back_dead_centre_rad(&self) -> f64 {
        either!(self, s => s.back_dead_centre_rad())
    }

    /// The reed's stroke, m.
    pub fn stroke_m(&self) -> f64 {
        either!(self, s => s.stroke_m())
    }

    /// The sley's moment of inertia about its rocking shaft, kg·m².
    pub fn inertia_kg_m2(&self) -> f64 {
        either!(self, s => s.inertia_kg_m2())
    }

    /// The reed's motion at φ.
    pub fn reed(&self, phi_rad: f64) -> ReedMotion {
        either!(self, s => s.reed(phi_rad))
    }

    /// `(J, dJ/dφ)` referred to the main shaft.
    pub fn reduced_inertia_kg_m2(&self, phi_rad: f64) -> (f64, f64) {
        either!(self, s => s.reduced_inertia_kg_m2(phi_rad))
    }

    /// The non-inertial torque on the main shaft, N·m.
    pub fn load_torque_n_m(&self, phi_rad: f64) -> f64 {
        either!(self, s => s.load_torque_n_m(phi_rad))
    }

    /// The forces at φ and ω.
    pub fn forces(&self, phi_rad: f64, omega: f64) -> SleyForces {
        either!(self, s => s.forces(phi_rad, omega))
    }

    /// The joints seen from the side, m.
    pub fn joints_m(&self, phi_rad: f64) -> SleyJoints {
        either!(self, s => s.joints_m(phi_rad))
    }

    /// The back dwell `(start, end)` for a tolerance, rad.
    pub fn back_dwell_rad(&self, tol_m: f64) -> Result<(f64, f64), SleyError> {
        either!(self, s => s.back_dwell_rad(tol_m))
    }

    /// What `loomkin sley analyze` prints.
    pub fn analyze(&self, speed: ShaftSpeed, dwell_tolerance_mm: f64) -> Result<SleyAnalysis, SleyError> {
        either!(self, s => s.analyze(speed, dwell_tolerance_mm))
    }

    /// The curves over one revolution.
    pub fn curve(&self, points: usize, omega: f64) -> Vec<SleyRow> {
        either!(self, s => s.curve(points, omega))
    }

    /// Main-shaft angles within a turn where the sley's J has a joint (a cam law's joints; none
    /// for the four-bar, whose J is smooth), rad in [0, 2π).
    pub fn inertia_joints_rad(&self) -> Vec<f64> {
        match self {
            Self::FourBar(_) => Vec::new(),
            Self::Cam(s) => s.law_joints_rad(),
        }
    }

    /// Main-shaft angles within a turn where the sley's J or load has a joint (the beat-up model's
    /// ends; a cam law's joints too), rad in [0, 2π).
    pub fn breaks_rad(&self) -> Vec<f64> {
        match self {
            Self::FourBar(s) => {
                let range = s.table().beat_up_range_deg.to_radians();
                if s.table().beat_up_force_n > 0.0 && range > 0.0 {
                    vec![s.front_dead_centre_rad(), s.front_dead_centre_rad() - range]
                } else {
                    Vec::new()
                }
            }
            Self::Cam(s) => s.breaks_rad(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::plateau_middle;

    #[test]
    fn the_middle_of_a_flat_top() {
        // f = 1 on [1, 2], falling linearly either side: the middle is 1.5.
        let f = |x: f64| {
            if x < 1.0 {
                x
            } else if x <= 2.0 {
                1.0
            } else {
                3.0 - x
            }
        };
        assert!((plateau_middle(&f, 1.2, 1.0 - 1e-12) - 1.5).abs() < 1e-9);
    }
}
