//! The sley (batten): a crank-rocker four-bar the main shaft drives, solved in closed form.
//!
//! **Frame.** The crank centre O is the origin, x points toward the cloth fell, y up. The crank
//! turns with the main shaft, counter-clockwise in this view: its angle from +x is
//! `α = φ + φ₀`, where φ is the main-shaft angle and the phase φ₀ is set so that the reed reaches
//! its front dead centre at `φ = beat_up_deg`. The crank pin is `A = r·e(α)`, the rocking shaft
//! `Q = (pivot_x, pivot_y)`, the sword's pin (where the rod meets the sley) `B = Q + c·e(θ)` and the
//! rod `B − A = b·e(β)`; `e(x) = (cos x, sin x)`. The reed's beating point lies on the sword's line
//! at `R = Q + h·e(θ)`.
//!
//! **Loop.** With `d = A − Q`, `s = |d|`, the triangle Q-A-B has sides `s`, `c`, `b`; its angle at Q
//! is `γ = atan2(√((s+b+c)(−s+b+c)(s−b+c)(s+b−c)), s² + c² − b²)` and
//! `θ = atan2(d) + κ·γ`, where κ = ±1 is the assembly branch ([`Assembly`]). For a crank-rocker
//! (checked exactly by [`FourBarSley::new`]) `0 < γ < π` at every crank angle, so the branch never
//! changes and every derivative is finite.
//!
//! **Derivatives** (per radian of main shaft) from the loop `A + b·e(β) = Q + c·e(θ)` differentiated
//! once, twice and three times and projected on `e(β)` (which removes the rod's unknown rates) and
//! on `e(θ)`:
//! `θ' = r·sin(β−α) / (c·sin(β−θ))`, `β' = r·sin(α−θ) / (b·sin(θ−β))`,
//! `θ'' = (c·θ'²·cos(θ−β) − r·cos(α−β) − b·β'²) / (c·sin(β−θ))`,
//! `β'' = (r·cos(α−θ) + b·β'²·cos(β−θ) − c·θ'²) / (b·sin(θ−β))`,
//! `θ''' = θ'³ + (3c·θ'·θ''·cos(θ−β) − r·sin(β−α) − 3b·β'·β'') / (c·sin(β−θ))`.
//!
//! **Dead centres** are where crank and rod are collinear (`θ' = 0`): the sword's pin at distance
//! `b + r` (extended) or `b − r` (folded) from O, each on the circle of radius `c` about Q — a circle
//! intersection in closed form, the candidate on the linkage's branch.
//!
//! **Reed.** The displacement along the reed's path is the arc of the beating point from its back
//! dead centre, positive toward the fell: `x(φ) = σ·h·(θ(φ) − θ_back)`, `0 ≤ x ≤ stroke`, where
//! σ = ±1 makes the front dead centre (the one whose beating point lies nearer the fell) positive.

use std::f64::consts::{PI, TAU};

use crate::fourbar::{Breaks, CrankRocker};
use loomkin_units::{Field, FieldError, Range, RangeError, ShaftSpeed};
use serde::{Deserialize, Serialize};
use thiserror::Error;

pub mod synth;

/// A wrong or infeasible sley.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SleyError {
    /// A number outside its allowed range, or not a finite number.
    #[error(transparent)]
    Range(#[from] RangeError),
    /// Dimensions that do not make a crank-rocker, or a target no linkage meets.
    #[error("{fields}: {reason}")]
    Infeasible {
        /// The fields at fault, comma-separated (`sley.crank_mm, sley.pivot_x_mm, sley.pivot_y_mm`).
        fields: String,
        /// Why, with the numbers.
        reason: String,
    },
}

impl SleyError {
    fn infeasible(fields: &str, reason: String) -> Self {
        Self::Infeasible { fields: fields.into(), reason }
    }
}

impl FieldError for SleyError {
    fn field(&self) -> Option<&str> {
        match self {
            Self::Range(e) => Some(&e.field),
            Self::Infeasible { fields, .. } => Some(fields.split(", ").next().unwrap_or(fields)),
        }
    }
}

/// Which of the two assemblies of the four-bar. `left` and `right` name the side of the line from
/// the rocking shaft Q to the crank pin A on which the sword's pin B lies, seen with x toward the fell
/// and y up; `up` and `down` pick the branch whose sword's pin lies higher (lower) midway between its
/// dead centres, whatever the layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Assembly {
    /// The branch whose sword stands higher: a sley standing on its rocking shaft (the default).
    #[default]
    Up,
    /// The branch whose sword hangs lower: a sley hanging from a rocking shaft above.
    Down,
    /// B counter-clockwise from Q→A (to its left).
    Left,
    /// B clockwise from Q→A (to its right).
    Right,
}

pub(crate) fn default_beat_up_deg() -> f64 {
    SleyTable::BEAT_UP_DEG.default_value()
}

pub(crate) fn default_zero_force() -> f64 {
    SleyTable::BEAT_UP_FORCE_N.default_value()
}

pub(crate) fn default_zero_range() -> f64 {
    SleyTable::BEAT_UP_RANGE_DEG.default_value()
}

/// The `[sley]` table of a loom file as written: a crank-rocker four-bar, lengths in mm, angles in
/// degrees. [`FourBarSley::new`] checks it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SleyTable {
    /// Crank radius r, mm ([`SleyTable::CRANK_MM`]).
    pub crank_mm: f64,
    /// Connecting rod b, crank pin to the sword's pin, mm ([`SleyTable::ROD_MM`]).
    pub rod_mm: f64,
    /// Sword c, rocking shaft to the rod's pin, mm ([`SleyTable::SWORD_MM`]).
    pub sword_mm: f64,
    /// The rocking shaft's x from the crank centre (toward the fell), mm ([`SleyTable::PIVOT_X_MM`]).
    pub pivot_x_mm: f64,
    /// The rocking shaft's y from the crank centre (up), mm ([`SleyTable::PIVOT_Y_MM`]).
    pub pivot_y_mm: f64,
    /// Rocking shaft to the reed's beating point, on the sword's line, mm ([`SleyTable::REED_HEIGHT_MM`]).
    pub reed_height_mm: f64,
    /// The sley's moving mass (swords, beam, reed), kg ([`SleyTable::MASS_KG`]).
    pub mass_kg: f64,
    /// Radius of gyration about the rocking shaft, mm ([`SleyTable::GYRATION_MM`]).
    pub gyration_mm: f64,
    /// Rocking shaft to the centre of mass, on the sword's line, mm ([`SleyTable::CENTRE_MM`]);
    /// left out: `gyration_mm`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub centre_mm: Option<f64>,
    /// Main-shaft angle of the reed's front dead centre, deg ([`SleyTable::BEAT_UP_DEG`]).
    #[serde(default = "default_beat_up_deg")]
    pub beat_up_deg: f64,
    /// Largest beat-up resistance at the reed, N ([`SleyTable::BEAT_UP_FORCE_N`]).
    #[serde(default = "default_zero_force")]
    pub beat_up_force_n: f64,
    /// Main-shaft angle over which the resistance rises before front dead centre, deg
    /// ([`SleyTable::BEAT_UP_RANGE_DEG`]).
    #[serde(default = "default_zero_range")]
    pub beat_up_range_deg: f64,
    /// The assembly branch: `up` (the default), `down`, `left` or `right` ([`Assembly`]).
    #[serde(default)]
    pub assembly: Assembly,
}

/// Longest length of the linkage, mm: 10 m, far above any loom (a sley's sword is under a metre).
const MAX_LENGTH_MM: f64 = 1e4;

impl SleyTable {
    /// `crank_mm`: 0 < r ≤ 10⁴ mm.
    pub const CRANK_MM: Field = Field::new(
        "sley.crank_mm",
        Range::open_closed(0.0, MAX_LENGTH_MM, "mm"),
        "Crank radius r of the sley drive: 0 < r ≤ 10000 mm (a length; the crank must also be the linkage's \
         shortest link, checked with the other lengths).",
    );
    /// `rod_mm`: 0 < b ≤ 10⁴ mm.
    pub const ROD_MM: Field = Field::new(
        "sley.rod_mm",
        Range::open_closed(0.0, MAX_LENGTH_MM, "mm"),
        "Connecting rod b, crank pin to the sword's pin: 0 < b ≤ 10000 mm (the loop's closure is checked with \
         the other lengths).",
    );
    /// `sword_mm`: 0 < c ≤ 10⁴ mm.
    pub const SWORD_MM: Field = Field::new(
        "sley.sword_mm",
        Range::open_closed(0.0, MAX_LENGTH_MM, "mm"),
        "Sword c, rocking shaft to the rod's pin: 0 < c ≤ 10000 mm.",
    );
    /// `pivot_x_mm`: |x| ≤ 10⁴ mm.
    pub const PIVOT_X_MM: Field = Field::new(
        "sley.pivot_x_mm",
        Range::closed(-MAX_LENGTH_MM, MAX_LENGTH_MM, "mm"),
        "The rocking shaft's x from the crank centre, toward the fell: −10000 … 10000 mm (it must lie farther \
         from the crank centre than the crank radius).",
    );
    /// `pivot_y_mm`: |y| ≤ 10⁴ mm.
    pub const PIVOT_Y_MM: Field = Field::new(
        "sley.pivot_y_mm",
        Range::closed(-MAX_LENGTH_MM, MAX_LENGTH_MM, "mm"),
        "The rocking shaft's y from the crank centre, up: −10000 … 10000 mm.",
    );
    /// `reed_height_mm`: 0 < h ≤ 10⁴ mm.
    pub const REED_HEIGHT_MM: Field = Field::new(
        "sley.reed_height_mm",
        Range::open_closed(0.0, MAX_LENGTH_MM, "mm"),
        "Rocking shaft to the reed's beating point, on the sword's line: 0 < h ≤ 10000 mm (the reed's travel \
         and the inertia force at the reed scale with it).",
    );
    /// `mass_kg`: 0 < m ≤ 10⁴ kg.
    pub const MASS_KG: Field = Field::new(
        "sley.mass_kg",
        Range::open_closed(0.0, 1e4, "kg"),
        "The sley's moving mass (swords, beam, reed, race board): 0 < m ≤ 10000 kg.",
    );
    /// `gyration_mm`: 0 < k ≤ 10⁴ mm.
    pub const GYRATION_MM: Field = Field::new(
        "sley.gyration_mm",
        Range::open_closed(0.0, MAX_LENGTH_MM, "mm"),
        "Radius of gyration k of the sley about the rocking shaft (J = m·k²): 0 < k ≤ 10000 mm.",
    );
    /// `centre_mm`: 0 ≤ g ≤ k; left out, `gyration_mm`.
    pub const CENTRE_MM: Field = Field::new(
        "sley.centre_mm",
        Range::closed(0.0, MAX_LENGTH_MM, "mm"),
        "Rocking shaft to the sley's centre of mass, on the sword's line: 0 ≤ g ≤ gyration_mm (the inertia \
         about the centre of mass, m·(k² − g²), cannot be negative); left out, gyration_mm (the mass taken at \
         its radius of gyration). Only the rocking shaft's bearing force depends on it.",
    );
    /// `beat_up_deg`: 0 ≤ φ_b < 360°, default 0.
    pub const BEAT_UP_DEG: Field = Field::new(
        "sley.beat_up_deg",
        Range::closed_open(0.0, 360.0, "deg"),
        "Main-shaft angle at which the reed reaches its front dead centre (beat-up): 0 ≤ φ_b < 360°; 0° when \
         left out (loomkin's angles count from beat-up).",
    )
    .with_default(0.0);
    /// `beat_up_force_n`: 0 ≤ F ≤ 10⁶ N, default 0 (none).
    pub const BEAT_UP_FORCE_N: Field = Field::new(
        "sley.beat_up_force_n",
        Range::closed(0.0, 1e6, "N"),
        "Largest beat-up resistance of the cloth fell at the reed, reached at front dead centre: 0 ≤ F ≤ 10⁶ N; \
         0 (none) when left out.",
    )
    .with_default(0.0);
    /// `beat_up_range_deg`: 0 ≤ Δ < 360°, default 0; at most the reed's forward stroke (checked).
    pub const BEAT_UP_RANGE_DEG: Field = Field::new(
        "sley.beat_up_range_deg",
        Range::closed_open(0.0, 360.0, "deg"),
        "Main-shaft angle before front dead centre over which the beat-up resistance rises from 0 to \
         beat_up_force_n: 0 ≤ Δ and at most the reed's forward stroke from back to front dead centre (the \
         resistance only opposes the reed moving toward the fell); 0 (none) when left out.",
    )
    .with_default(0.0);
}

/// A checked crank-rocker sley with its dead centres and phase, lengths in m inside.
///
/// ```
/// use loomkin_drive::{FourBarSley, SleyTable, Assembly};
///
/// let t = SleyTable {
///     crank_mm: 50.0, rod_mm: 250.0, sword_mm: 500.0, pivot_x_mm: -250.0, pivot_y_mm: -480.0,
///     reed_height_mm: 600.0, mass_kg: 25.0, gyration_mm: 450.0, centre_mm: None, beat_up_deg: 0.0,
///     beat_up_force_n: 0.0, beat_up_range_deg: 0.0, assembly: Assembly::Left,
/// };
/// let sley = FourBarSley::new(t)?;
/// // At beat-up the reed is at its front dead centre: the full stroke, at rest.
/// let m = sley.reed(0.0);
/// assert!((m.x_m - sley.stroke_m()).abs() < 1e-12 && m.dx_m.abs() < 1e-12);
/// # Ok::<(), loomkin_drive::SleyError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "SleyTable", into = "SleyTable")]
pub struct FourBarSley {
    table: SleyTable,
    r: f64,
    b: f64,
    c: f64,
    qx: f64,
    qy: f64,
    h: f64,
    /// m·k², kg·m².
    j_q: f64,
    /// Centre-of-mass distance, m.
    g: f64,
    kappa: f64,
    sigma: f64,
    /// Crank angle at φ = 0, rad.
    phase: f64,
    theta_back: f64,
    theta_front: f64,
    /// Main-shaft angles of the front and back dead centres, rad in [0, 2π).
    phi_front: f64,
    phi_back: f64,
    beat_force: f64,
    beat_range: f64,
}

impl TryFrom<SleyTable> for FourBarSley {
    type Error = SleyError;
    fn try_from(t: SleyTable) -> Result<Self, SleyError> {
        Self::new(t)
    }
}

impl From<FourBarSley> for SleyTable {
    fn from(s: FourBarSley) -> Self {
        s.table
    }
}

/// The linkage's position and its rates at one main-shaft angle (rates per radian of main shaft).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SleyState {
    /// Main-shaft angle φ, rad.
    pub phi_rad: f64,
    /// Crank angle α from +x, rad.
    pub crank_rad: f64,
    /// Rocker (sword) angle θ from +x, rad.
    pub rocker_rad: f64,
    /// dθ/dφ.
    pub rocker_d1: f64,
    /// d²θ/dφ², per rad².
    pub rocker_d2: f64,
    /// d³θ/dφ³, per rad³.
    pub rocker_d3: f64,
    /// Rod angle β from +x (direction from crank pin to sword's pin), rad.
    pub rod_rad: f64,
    /// dβ/dφ.
    pub rod_d1: f64,
    /// d²β/dφ².
    pub rod_d2: f64,
}

/// Where the sley's joints are at one main-shaft angle ([`FourBarSley::joints_m`]), m from the
/// crank centre, x toward the fell, y up.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SleyJoints {
    /// The crank pin.
    pub crank_pin: [f64; 2],
    /// The sword's pin, where the rod drives the sword.
    pub sword_pin: [f64; 2],
    /// The rocking shaft (fixed).
    pub rocking_shaft: [f64; 2],
    /// The reed's beating point.
    pub reed: [f64; 2],
}

/// The reed's motion along its path at one main-shaft angle, per radian of main shaft.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ReedMotion {
    /// Displacement from the back dead centre toward the fell (arc of the beating point), m.
    pub x_m: f64,
    /// dx/dφ, m/rad.
    pub dx_m: f64,
    /// d²x/dφ², m/rad².
    pub d2x_m: f64,
    /// d³x/dφ³, m/rad³.
    pub d3x_m: f64,
}

impl ReedMotion {
    /// Velocity at the constant shaft speed ω (rad/s), m/s.
    pub fn velocity_m_s(&self, omega: f64) -> f64 {
        self.dx_m * omega
    }
    /// Acceleration at ω, m/s².
    pub fn acceleration_m_s2(&self, omega: f64) -> f64 {
        self.d2x_m * omega * omega
    }
    /// Jerk at ω, m/s³.
    pub fn jerk_m_s3(&self, omega: f64) -> f64 {
        self.d3x_m * omega * omega * omega
    }
}

/// The forces of the sley at one main-shaft angle at a constant shaft speed (the crank and the rod
/// massless, the sley a rigid body about its rocking shaft under its weight; no friction).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SleyForces {
    /// The sley's inertia as a force along the reed's path at the beating point, N:
    /// `J_Q·θ̈·σ / h`, positive toward the fell (the force that accelerates the sley; the d'Alembert
    /// inertia force is its negative).
    pub inertia_force_n: f64,
    /// The beat-up resistance at the reed (opposing its motion toward the fell), N, ≥ 0.
    pub beat_up_force_n: f64,
    /// Force in the connecting rod, N: positive in tension.
    pub rod_force_n: f64,
    /// Crank-pin bearing force (the rod's force), N.
    pub crank_pin_n: f64,
    /// Main-shaft (crank) bearing force, N: the rod's force, the crank being massless.
    pub crank_bearing_n: f64,
    /// Rocking-shaft bearing force on the sley, x and y, N.
    pub rocking_shaft_n: [f64; 2],
    /// Torque the main shaft gives the crank, N·m: the inertia part plus the load part.
    pub crank_torque_n_m: f64,
    /// The inertia part of the crank torque, N·m (`½·dJ/dφ·ω²`).
    pub inertia_torque_n_m: f64,
    /// The non-inertial part of the crank torque (beat-up and weight), N·m
    /// ([`FourBarSley::load_torque_n_m`]).
    pub load_torque_n_m: f64,
}

impl SleyForces {
    /// Magnitude of the rocking-shaft bearing force, N.
    pub fn rocking_shaft_magnitude_n(&self) -> f64 {
        self.rocking_shaft_n[0].hypot(self.rocking_shaft_n[1])
    }
}

/// The beat-up resistance model (N): rising linearly in main-shaft angle from 0 at `range` (rad)
/// before the front position `front` (rad) to `force` at it, 0 elsewhere. One model for every sley.
pub(crate) fn beat_up_model(force: f64, range: f64, front: f64, phi_rad: f64) -> f64 {
    if force == 0.0 || range == 0.0 {
        return 0.0;
    }
    let before = (front - phi_rad).rem_euclid(TAU);
    if before <= range { force * (1.0 - before / range) } else { 0.0 }
}

/// Angle wrapped to (−π, π].
fn wrap(a: f64) -> f64 {
    let w = a.rem_euclid(TAU);
    if w > PI { w - TAU } else { w }
}

impl FourBarSley {
    /// Checks a `[sley]` table: every number against its field's range, then the linkage exactly.
    /// A crank-rocker that assembles at every crank angle needs (with `d = |Q|`):
    /// `r < d` (the crank cannot reach the rocking shaft), `d + r < b + c` (the loop closes with the
    /// crank pointing away from the rocking shaft) and `d − r > |b − c|` (and pointing toward it);
    /// strict, so the rod and sword are never collinear and every rate is finite. Together these are
    /// Grashof's condition with the crank the shortest link.
    pub fn new(t: SleyTable) -> Result<Self, SleyError> {
        let r = SleyTable::CRANK_MM.check(t.crank_mm)?;
        let b = SleyTable::ROD_MM.check(t.rod_mm)?;
        let c = SleyTable::SWORD_MM.check(t.sword_mm)?;
        let px = SleyTable::PIVOT_X_MM.check(t.pivot_x_mm)?;
        let py = SleyTable::PIVOT_Y_MM.check(t.pivot_y_mm)?;
        let h = SleyTable::REED_HEIGHT_MM.check(t.reed_height_mm)?;
        let m = SleyTable::MASS_KG.check(t.mass_kg)?;
        let k = SleyTable::GYRATION_MM.check(t.gyration_mm)?;
        let g = match t.centre_mm {
            Some(g) => Range::closed(0.0, k, "mm").check(SleyTable::CENTRE_MM.name, g)?,
            None => k,
        };
        let beat = SleyTable::BEAT_UP_DEG.check(t.beat_up_deg)?;
        let force = SleyTable::BEAT_UP_FORCE_N.check(t.beat_up_force_n)?;
        let range = SleyTable::BEAT_UP_RANGE_DEG.check(t.beat_up_range_deg)?;
        let d = px.hypot(py);
        let breaks = CrankRocker::check(r, b, c, px, py);
        if breaks == Some(Breaks::CrankReachesPivot) {
            return Err(SleyError::infeasible(
                "sley.crank_mm, sley.pivot_x_mm, sley.pivot_y_mm",
                format!(
                    "the crank ({r} mm) reaches the rocking shaft ({} mm from the crank centre): a crank-rocker \
                     needs crank_mm < the pivot distance",
                    loomkin_units::compact(d)
                ),
            ));
        }
        if breaks == Some(Breaks::OpensAway) {
            return Err(SleyError::infeasible(
                "sley.crank_mm, sley.rod_mm, sley.sword_mm, sley.pivot_x_mm, sley.pivot_y_mm",
                format!(
                    "the loop does not close with the crank pointing away from the rocking shaft: crank + pivot \
                     distance = {} mm, not less than rod + sword = {} mm",
                    loomkin_units::compact(d + r),
                    loomkin_units::compact(b + c)
                ),
            ));
        }
        if breaks == Some(Breaks::OpensToward) {
            return Err(SleyError::infeasible(
                "sley.crank_mm, sley.rod_mm, sley.sword_mm, sley.pivot_x_mm, sley.pivot_y_mm",
                format!(
                    "the loop does not close with the crank pointing toward the rocking shaft: pivot distance − \
                     crank = {} mm, not more than |rod − sword| = {} mm",
                    loomkin_units::compact(d - r),
                    loomkin_units::compact((b - c).abs())
                ),
            ));
        }
        let mm = 1e-3;
        let mut s = Self {
            table: t,
            r: r * mm,
            b: b * mm,
            c: c * mm,
            qx: px * mm,
            qy: py * mm,
            h: h * mm,
            j_q: m * (k * mm) * (k * mm),
            g: g * mm,
            kappa: 1.0,
            sigma: 1.0,
            phase: 0.0,
            theta_back: 0.0,
            theta_front: 0.0,
            phi_front: beat.to_radians(),
            phi_back: 0.0,
            beat_force: force,
            beat_range: range.to_radians(),
        };
        // The branch: given, or the one whose sword's pin is higher (lower) midway between its dead centres.
        let mid_height = |kappa: f64| {
            let k = Self { kappa, ..s };
            let (a, b) = (k.dead_centre(true).1, k.dead_centre(false).1);
            (b + 0.5 * wrap(a - b)).sin()
        };
        s.kappa = match t.assembly {
            Assembly::Left => 1.0,
            Assembly::Right => -1.0,
            Assembly::Up if mid_height(1.0) >= mid_height(-1.0) => 1.0,
            Assembly::Down if mid_height(1.0) <= mid_height(-1.0) => 1.0,
            Assembly::Up | Assembly::Down => -1.0,
        };
        let ext = s.dead_centre(true);
        let fold = s.dead_centre(false);
        let reed_x = |theta: f64| s.qx + s.h * theta.cos();
        let (front, back) = if reed_x(ext.1) >= reed_x(fold.1) { (ext, fold) } else { (fold, ext) };
        if reed_x(front.1) - reed_x(back.1) <= 1e-12 * s.h {
            return Err(SleyError::infeasible(
                "sley.pivot_x_mm, sley.pivot_y_mm, sley.assembly",
                "the reed's two dead centres lie equally far from the fell: the reed does not beat toward it (the \
                 sword swings about the horizontal)"
                    .into(),
            ));
        }
        s.theta_front = front.1;
        s.theta_back = back.1;
        s.sigma = if wrap(front.1 - back.1) > 0.0 { 1.0 } else { -1.0 };
        s.phase = front.0 - s.phi_front;
        s.phi_back = (back.0 - s.phase).rem_euclid(TAU);
        let forward_deg = s.forward_stroke_rad().to_degrees();
        Range::closed(0.0, forward_deg, "deg").check(SleyTable::BEAT_UP_RANGE_DEG.name, range)?;
        Ok(s)
    }

    /// The loop of this sley: crank, rod, sword and rocking shaft on its branch (lengths in m).
    pub fn linkage(&self) -> CrankRocker {
        CrankRocker { r: self.r, b: self.b, c: self.c, qx: self.qx, qy: self.qy, kappa: self.kappa }
    }

    /// The crank angle α and the rocker angle θ of a dead centre ([`CrankRocker::dead_centre`]).
    fn dead_centre(&self, extended: bool) -> (f64, f64) {
        self.linkage().dead_centre(extended)
    }

    /// The branch the linkage is assembled on: [`Assembly::Left`] or [`Assembly::Right`] (`up` and
    /// `down` resolved).
    pub fn branch(&self) -> Assembly {
        if self.kappa > 0.0 { Assembly::Left } else { Assembly::Right }
    }

    /// The table this sley was built from.
    pub fn table(&self) -> &SleyTable {
        &self.table
    }

    /// Main-shaft angle of the front dead centre (beat-up), rad.
    pub fn front_dead_centre_rad(&self) -> f64 {
        self.phi_front
    }

    /// Main-shaft angle of the back dead centre, rad in [0, 2π).
    pub fn back_dead_centre_rad(&self) -> f64 {
        self.phi_back
    }

    /// Main-shaft angle from the back dead centre forward to the front dead centre, rad.
    pub fn forward_stroke_rad(&self) -> f64 {
        (self.phi_front - self.phi_back).rem_euclid(TAU)
    }

    /// The reed's stroke, the arc of the beating point between its dead centres, m.
    pub fn stroke_m(&self) -> f64 {
        self.h * wrap(self.theta_front - self.theta_back).abs()
    }

    /// The sley's moment of inertia about its rocking shaft, m·k², kg·m².
    pub fn inertia_kg_m2(&self) -> f64 {
        self.j_q
    }

    /// Rocking shaft to the reed's beating point, m.
    pub fn reed_height_m(&self) -> f64 {
        self.h
    }

    /// The crank angle at main-shaft angle φ, rad.
    pub fn crank_rad(&self, phi_rad: f64) -> f64 {
        phi_rad + self.phase
    }

    /// The linkage at main-shaft angle φ: positions in closed form and the rocker's first three and
    /// the rod's first two rates per radian of main shaft ([`CrankRocker::at_crank`]; the crank turns
    /// with the main shaft, so its rates are the main shaft's).
    pub fn state(&self, phi_rad: f64) -> SleyState {
        let l = self.linkage().at_crank(self.crank_rad(phi_rad));
        SleyState {
            phi_rad,
            crank_rad: l.crank_rad,
            rocker_rad: l.rocker_rad,
            rocker_d1: l.rocker_d1,
            rocker_d2: l.rocker_d2,
            rocker_d3: l.rocker_d3,
            rod_rad: l.rod_rad,
            rod_d1: l.rod_d1,
            rod_d2: l.rod_d2,
        }
    }

    /// The linkage's joints at main-shaft angle φ, m from the crank centre (x toward the fell, y
    /// up): the crank pin, the sword's pin (the rod's other end), the rocking shaft and the reed's
    /// beating point (on the sword's line, `reed_height_mm` from the rocking shaft).
    pub fn joints_m(&self, phi_rad: f64) -> SleyJoints {
        let st = self.state(phi_rad);
        let (sa, ca) = st.crank_rad.sin_cos();
        let (st_, ct) = st.rocker_rad.sin_cos();
        SleyJoints {
            crank_pin: [self.r * ca, self.r * sa],
            sword_pin: [self.qx + self.c * ct, self.qy + self.c * st_],
            rocking_shaft: [self.qx, self.qy],
            reed: [self.qx + self.h * ct, self.qy + self.h * st_],
        }
    }

    /// The reed's motion along its path at main-shaft angle φ (per radian of main shaft).
    pub fn reed(&self, phi_rad: f64) -> ReedMotion {
        self.reed_of(&self.state(phi_rad))
    }

    /// The reed's motion of a state already computed.
    pub fn reed_of(&self, st: &SleyState) -> ReedMotion {
        let k = self.sigma * self.h;
        ReedMotion {
            x_m: k * wrap(st.rocker_rad - self.theta_back),
            dx_m: k * st.rocker_d1,
            d2x_m: k * st.rocker_d2,
            d3x_m: k * st.rocker_d3,
        }
    }

    /// The sley's moment of inertia referred to the main shaft and its rate, `(J, dJ/dφ)` in kg·m²
    /// and kg·m²/rad: `J = J_Q·θ'²`, `dJ/dφ = 2·J_Q·θ'·θ''`. The sley only: the crank and rod are
    /// taken massless (their share belongs to the rotating parts and is not modelled here).
    pub fn reduced_inertia_kg_m2(&self, phi_rad: f64) -> (f64, f64) {
        let st = self.state(phi_rad);
        (self.j_q * st.rocker_d1 * st.rocker_d1, 2.0 * self.j_q * st.rocker_d1 * st.rocker_d2)
    }

    /// The beat-up resistance at the reed at main-shaft angle φ, N (≥ 0, opposing the reed's motion
    /// toward the fell). A model, not a measured law: it rises linearly with the main-shaft angle from
    /// 0 at `beat_up_range_deg` before the front dead centre to `beat_up_force_n` at it, and is 0 from
    /// front dead centre until the next rise (the reed leaves the fell).
    pub fn beat_up_force_n(&self, phi_rad: f64) -> f64 {
        beat_up_model(self.beat_force, self.beat_range, self.phi_front, phi_rad)
    }

    /// The sley's weight as a moment about its rocking shaft at rocker angle θ, N·m
    /// (counter-clockwise positive): `−m·g₀·g·cos θ`, the centre of mass at `centre_mm` on the sword's line.
    fn weight_moment(&self, theta: f64) -> f64 {
        -self.table.mass_kg * loomkin_units::STANDARD_GRAVITY_M_S2 * self.g * theta.cos()
    }

    /// The non-inertial torque the sley asks of the main shaft at angle φ, N·m (positive: the shaft
    /// must give it), speed-independent, by power balance: the beat-up resistance, `F(φ)·dx/dφ`, and
    /// the sley's weight, `m·g₀·g·cos θ·θ'` (the rate of its potential energy, so its integral over
    /// a turn is zero).
    pub fn load_torque_n_m(&self, phi_rad: f64) -> f64 {
        let st = self.state(phi_rad);
        (self.sigma * self.beat_up_force_n(phi_rad) * self.h - self.weight_moment(st.rocker_rad)) * st.rocker_d1
    }

    /// The forces at main-shaft angle φ and the constant shaft speed `omega` (rad/s).
    pub fn forces(&self, phi_rad: f64, omega: f64) -> SleyForces {
        self.forces_of(&self.state(phi_rad), omega)
    }

    /// [`FourBarSley::forces`] of a state already computed.
    ///
    /// The sley about Q: `J_Q·θ̈ = −N·c·sin(β−θ) − σ·F·h + M_w`, N the rod's tension, F the beat-up
    /// resistance, `M_w = −m·g₀·g·cos θ` the weight's moment; the crank (massless) balances the rod:
    /// torque `−N·r·sin(β−α)`; the rocking shaft carries `m·a_G + N·e(β) + σ·F·e⊥(θ) + (0, m·g₀)`,
    /// `a_G = g·(θ̈·e⊥(θ) − θ̇²·e(θ))`.
    pub fn forces_of(&self, st: &SleyState, omega: f64) -> SleyForces {
        let w2 = omega * omega;
        let (theta, beta, alpha) = (st.rocker_rad, st.rod_rad, st.crank_rad);
        let theta_dd = st.rocker_d2 * w2;
        let theta_d = st.rocker_d1 * omega;
        let f = self.beat_up_force_n(st.phi_rad);
        let moment = self.j_q * theta_dd + self.sigma * f * self.h - self.weight_moment(theta);
        let tension = -moment / (self.c * (beta - theta).sin());
        let crank_torque = -tension * self.r * (beta - alpha).sin();
        let (ct, stt) = (theta.cos(), theta.sin());
        let m = self.table.mass_kg;
        let ag =
            [self.g * (-theta_dd * stt - theta_d * theta_d * ct), self.g * (theta_dd * ct - theta_d * theta_d * stt)];
        let (eb, et_perp) = ([beta.cos(), beta.sin()], [-stt, ct]);
        let bearing = [
            m * ag[0] + tension * eb[0] + self.sigma * f * et_perp[0],
            m * ag[1] + tension * eb[1] + self.sigma * f * et_perp[1] + m * loomkin_units::STANDARD_GRAVITY_M_S2,
        ];
        let inertia_torque = self.j_q * st.rocker_d1 * st.rocker_d2 * w2;
        SleyForces {
            inertia_force_n: self.sigma * self.j_q * theta_dd / self.h,
            beat_up_force_n: f,
            rod_force_n: tension,
            crank_pin_n: tension.abs(),
            crank_bearing_n: tension.abs(),
            rocking_shaft_n: bearing,
            crank_torque_n_m: crank_torque,
            inertia_torque_n_m: inertia_torque,
            load_torque_n_m: crank_torque - inertia_torque,
        }
    }

    /// The transmission angle at main-shaft angle φ, rad in (0, π/2]: the acute angle between the
    /// rod and the sword (π/2 is the best, 0 the toggle).
    pub fn transmission_rad(&self, phi_rad: f64) -> f64 {
        let st = self.state(phi_rad);
        (st.rod_rad - st.rocker_rad).sin().abs().asin()
    }

    /// The least transmission angle over a revolution, rad, in closed form: the angle between rod and
    /// sword is extreme where the crank lies on the line O–Q (`|A − Q| = d ∓ r`), so the least is the
    /// smaller of those two positions' acute angles.
    pub fn min_transmission_rad(&self) -> f64 {
        self.linkage().min_transmission_rad()
    }

    /// The back dwell for a tolerance `tol_m`: the main-shaft angles `(start, end)` (rad, `end >
    /// start`, `end − start` the dwell) between which the reed stays within `tol_m` of its back dead
    /// centre. The reed moves monotonically between its dead centres (θ' vanishes only there), so
    /// each end is the one root of `x(φ) = tol` on its side of the back dead centre, found by
    /// safeguarded Newton ([`loomkin_numeric::refine_root`]) in the bracket of the two dead centres.
    /// `tol_m` must lie inside (0, stroke).
    pub fn back_dwell_rad(&self, tol_m: f64) -> Result<(f64, f64), SleyError> {
        let stroke = self.stroke_m();
        Range::open(0.0, stroke * 1e3, "mm").check(SleyAnalysis::DWELL_TOLERANCE_MM.name, tol_m * 1e3)?;
        let gd = |phi: f64| {
            let m = self.reed(phi);
            (m.x_m - tol_m, m.dx_m)
        };
        let front = self.phi_front;
        let back = front + (self.phi_back - front).rem_euclid(TAU);
        let start = loomkin_numeric::refine_root(front, back, false, gd);
        let end = loomkin_numeric::refine_root(back, front + TAU, true, gd);
        Ok((start, end))
    }

    /// The analysis at the loom speed with a dwell tolerance: the figures `loomkin sley analyze`
    /// prints. Every extreme is located by [`loomkin_numeric::scan_max`] (a 720-interval grid whose
    /// peaks are refined by golden section), not read off a grid.
    pub fn analyze(&self, speed: ShaftSpeed, dwell_tolerance_mm: f64) -> Result<SleyAnalysis, SleyError> {
        let tol = SleyAnalysis::DWELL_TOLERANCE_MM.check(dwell_tolerance_mm)?;
        let dwell = self.back_dwell_rad(tol * 1e-3)?;
        let w = speed.rad_per_s();
        let frame = Frame {
            front: self.phi_front,
            back: self.phi_back,
            stroke_m: self.stroke_m(),
            inertia: self.j_q,
            intervals: SleyAnalysis::SCAN_INTERVALS,
        };
        let mut r = analysis_of(&frame, speed, tol, dwell, &|p| self.reed(p), &|p, w| self.forces(p, w));
        let peak = |f: &dyn Fn(f64) -> f64| {
            loomkin_numeric::scan_max(frame.front, frame.front + TAU, SleyAnalysis::SCAN_INTERVALS, f).value
        };
        r.peak_rod_force_n = Some(peak(&|p| self.forces(p, w).rod_force_n.abs()));
        r.peak_rocking_shaft_force_n = Some(peak(&|p| self.forces(p, w).rocking_shaft_magnitude_n()));
        r.min_transmission_angle_deg = self.min_transmission_rad().to_degrees();
        Ok(r)
    }

    /// Rows of the curves over one revolution from `0` to `360°` in `points` steps (`points + 1`
    /// rows), at the constant speed ω (rad/s).
    pub fn curve(&self, points: usize, omega: f64) -> Vec<SleyRow> {
        curve_of(points, omega, &|p| {
            let st = self.state(p);
            (self.reed_of(&st), self.forces_of(&st, omega), true)
        })
    }
}

/// Where a sley's turn is: the front and back positions (main-shaft rad), the stroke (m), J about
/// the rocking shaft (kg·m²), the grid of the peak scan.
pub(crate) struct Frame {
    pub front: f64,
    pub back: f64,
    pub stroke_m: f64,
    pub inertia: f64,
    pub intervals: usize,
}

/// The figures of `sley analyze` every sley has, from its reed motion and forces: every extreme
/// by [`loomkin_numeric::scan_max`] over the turn from the front position (a grid whose peaks are
/// refined by golden section). The four-bar's own figures (rod, rocking shaft, transmission) are
/// left `None` / 0 for the caller.
pub(crate) fn analysis_of(
    frame: &Frame,
    speed: ShaftSpeed,
    tol_mm: f64,
    (start, end): (f64, f64),
    reed: &dyn Fn(f64) -> ReedMotion,
    forces: &dyn Fn(f64, f64) -> SleyForces,
) -> SleyAnalysis {
    let w = speed.rad_per_s();
    let lo = frame.front;
    let peak = |f: &dyn Fn(f64) -> f64| {
        let m = loomkin_numeric::scan_max(lo, lo + TAU, frame.intervals, f);
        (m.value, m.at.rem_euclid(TAU).to_degrees())
    };
    let (acc_max, acc_max_at) = peak(&|p| reed(p).acceleration_m_s2(w).abs());
    let (f_max, f_max_at) = peak(&|p| forces(p, w).inertia_force_n);
    let (f_min, f_min_at) = peak(&|p| -forces(p, w).inertia_force_n);
    let (t_max, t_max_at) = peak(&|p| forces(p, w).crank_torque_n_m.abs());
    let (v_max, _) = peak(&|p| reed(p).velocity_m_s(w).abs());
    let (j_max, _) = peak(&|p| reed(p).jerk_m_s3(w).abs());
    SleyAnalysis {
        speed_rpm: speed.rpm(),
        reed_stroke_mm: frame.stroke_m * 1e3,
        back_dwell_deg: (end - start).to_degrees(),
        dwell_start_deg: start.rem_euclid(TAU).to_degrees(),
        dwell_end_deg: end.rem_euclid(TAU).to_degrees(),
        dwell_tolerance_mm: tol_mm,
        front_dead_centre_deg: frame.front.to_degrees(),
        back_dead_centre_deg: frame.back.to_degrees(),
        peak_reed_velocity_m_s: v_max,
        peak_reed_acceleration_m_s2: acc_max,
        peak_reed_acceleration_deg: acc_max_at,
        peak_reed_jerk_m_s3: j_max,
        max_inertia_force_n: f_max,
        max_inertia_force_deg: f_max_at,
        min_inertia_force_n: -f_min,
        min_inertia_force_deg: f_min_at,
        peak_crank_torque_n_m: t_max,
        peak_crank_torque_deg: t_max_at,
        peak_rod_force_n: None,
        peak_rocking_shaft_force_n: None,
        min_transmission_angle_deg: 0.0,
        inertia_kg_m2: frame.inertia,
        drive: None,
        max_pressure_angle_deg: None,
        prime_radius_mm: None,
        peak_contact_force_n: None,
        peak_contact_force_deg: None,
        max_contact_force_n: None,
        max_contact_force_deg: None,
        min_contact_force_n: None,
        min_contact_force_deg: None,
        contact_force_sign: None,
    }
}

/// Rows of a sley's curves over one turn (`points + 1` rows at ω): `at(φ)` gives the reed's
/// motion, the forces and whether the sley has a rod (its force in the rows).
pub(crate) fn curve_of(points: usize, omega: f64, at: &dyn Fn(f64) -> (ReedMotion, SleyForces, bool)) -> Vec<SleyRow> {
    (0..=points)
        .map(|i| {
            let deg = 360.0 * i as f64 / points as f64;
            let (m, f, rod) = at(deg.to_radians());
            SleyRow {
                angle_deg: deg,
                reed_mm: m.x_m * 1e3,
                velocity_m_s: m.velocity_m_s(omega),
                acceleration_m_s2: m.acceleration_m_s2(omega),
                jerk_m_s3: m.jerk_m_s3(omega),
                inertia_force_n: f.inertia_force_n,
                rod_force_n: rod.then_some(f.rod_force_n),
                crank_torque_n_m: f.crank_torque_n_m,
            }
        })
        .collect()
}

/// One row of the sley's curves.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SleyRow {
    /// Main-shaft angle, deg.
    pub angle_deg: f64,
    /// Reed displacement from its back dead centre toward the fell, mm.
    pub reed_mm: f64,
    /// Reed velocity, m/s.
    pub velocity_m_s: f64,
    /// Reed acceleration, m/s².
    pub acceleration_m_s2: f64,
    /// Reed jerk, m/s³.
    pub jerk_m_s3: f64,
    /// Inertia force along the reed's path, N.
    pub inertia_force_n: f64,
    /// Rod force, N (tension positive); none for a cam sley (no rod).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rod_force_n: Option<f64>,
    /// Crank torque, N·m.
    pub crank_torque_n_m: f64,
}

/// What `loomkin sley analyze` reports (keys of its `--json`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SleyAnalysis {
    /// The loom speed, rpm.
    pub speed_rpm: f64,
    /// The reed's stroke (arc of the beating point), mm.
    pub reed_stroke_mm: f64,
    /// Main-shaft angle over which the reed stays within `dwell_tolerance_mm` of its back position, deg.
    pub back_dwell_deg: f64,
    /// Where the back dwell starts, deg in [0, 360).
    pub dwell_start_deg: f64,
    /// Where it ends, deg in [0, 360).
    pub dwell_end_deg: f64,
    /// The dwell tolerance, mm.
    pub dwell_tolerance_mm: f64,
    /// Main-shaft angle of the front dead centre (beat-up), deg.
    pub front_dead_centre_deg: f64,
    /// Main-shaft angle of the back dead centre, deg.
    pub back_dead_centre_deg: f64,
    /// Largest reed speed, m/s.
    pub peak_reed_velocity_m_s: f64,
    /// Largest magnitude of the reed's acceleration, m/s².
    pub peak_reed_acceleration_m_s2: f64,
    /// Where, deg.
    pub peak_reed_acceleration_deg: f64,
    /// Largest magnitude of the reed's jerk, m/s³.
    pub peak_reed_jerk_m_s3: f64,
    /// Largest inertia force along the reed's path (toward the fell), N.
    pub max_inertia_force_n: f64,
    /// Where, deg.
    pub max_inertia_force_deg: f64,
    /// Smallest (most negative: toward the back) inertia force along the reed's path, N.
    pub min_inertia_force_n: f64,
    /// Where, deg.
    pub min_inertia_force_deg: f64,
    /// Largest magnitude of the crank torque, N·m.
    pub peak_crank_torque_n_m: f64,
    /// Where, deg.
    pub peak_crank_torque_deg: f64,
    /// Largest magnitude of the rod force, N (a four-bar's; left out for a cam sley).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_rod_force_n: Option<f64>,
    /// Largest rocking-shaft bearing force, N.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_rocking_shaft_force_n: Option<f64>,
    /// Least transmission angle over the cycle, deg (a cam sley: 90° less the cam's largest
    /// pressure angle).
    pub min_transmission_angle_deg: f64,
    /// The sley's moment of inertia about its rocking shaft, kg·m².
    pub inertia_kg_m2: f64,
    /// `cam` for a cam-driven sley (left out for the four-bar).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub drive: Option<&'static str>,
    /// A cam sley's largest pressure angle over its cams, deg (loomkin-cams' profile).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_pressure_angle_deg: Option<f64>,
    /// A cam sley's prime circle radius, mm (given, or the least for its largest pressure angle).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub prime_radius_mm: Option<f64>,
    /// A cam sley's largest contact force between cam and roller, N (the magnitude; signed by
    /// `contact_force_sign`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_contact_force_n: Option<f64>,
    /// Where, deg.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_contact_force_deg: Option<f64>,
    /// A cam sley's largest signed contact force, N (a conjugate pair's: the forward cam's peak).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_contact_force_n: Option<f64>,
    /// Where, deg.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_contact_force_deg: Option<f64>,
    /// A cam sley's least signed contact force, N: below 0 a single cam loses contact; a conjugate
    /// pair's or a groove's negative is carried by the return cam or the outer wall.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_contact_force_n: Option<f64>,
    /// Where, deg.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_contact_force_deg: Option<f64>,
    /// What the contact force's sign means for this cam's closure.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_force_sign: Option<&'static str>,
}

impl SleyAnalysis {
    /// `dwell_tolerance_mm`: 0 < tol ≤ 10⁴ mm, default 1 mm; also below the reed's stroke (checked).
    pub const DWELL_TOLERANCE_MM: Field = Field::new(
        "dwell_tolerance_mm",
        Range::open_closed(0.0, MAX_LENGTH_MM, "mm"),
        "How near its back position the reed counts as dwelling: 0 < tol and below the reed's stroke; 1 mm when \
         left out (a clearance the carrier's path keeps to the reed).",
    )
    .with_default(1.0);

    /// Rows of the curves over one turn (`--points`): 720, every 0.5°, when left out.
    pub const POINTS: Field = Field::count(
        "points",
        Range::closed(2.0, 1e6, ""),
        "Intervals of the sley's curves over one turn: 2 … 10⁶ (the rows are held in memory, 64 bytes each); \
         720 (every 0.5°) when left out.",
    )
    .with_default(720.0);

    /// The back dwell as main-shaft angle intervals within one turn `[0, 360]`, deg: one, or two
    /// when the dwell straddles 0°.
    pub fn dwell_bands_deg(&self) -> Vec<(f64, f64)> {
        let (a, b) = (self.dwell_start_deg, self.dwell_end_deg);
        if a <= b { vec![(a, b)] } else { vec![(a, 360.0), (0.0, b)] }
    }

    /// Intervals of the grid whose peaks the analysis refines: 0.5° apart, so no two extremes of a
    /// four-bar's curves (a handful per turn) share one.
    pub const SCAN_INTERVALS: usize = 720;
}
