//! The crank-and-lever transmission: a crank on the motor shaft, a connecting rod, a rocking lever
//! whose output arm lifts the slave (a heald frame) through a frame link.
//!
//! # The model
//!
//! In the plane of the linkage, `x` horizontal from the rocking shaft toward the frame, `y` up:
//!
//! ```text
//!                   G   frame pin: the frame slides on the vertical through P at mid-stroke
//!                   |
//!                   |   L  frame link (optional)
//!                   |
//!    Q o------------o P   output arm e at angle φ (0: horizontal, the frame at mid-stroke)
//!       \  δ
//!        \  c  input arm, at δ from the output arm (counter-clockwise)
//!         o B
//!         |
//!         |  b  rod
//!         |
//!         o A
//!        /   r  crank at α, the motor's angle (from +x, counter-clockwise)
//!       o O  motor shaft; Q = (rocking_shaft_x_mm, rocking_shaft_y_mm) from O
//! ```
//!
//! The crank pin is `A = r·e(α)`, `e(x) = (cos x, sin x)`; the rod `b` joins it to the pin `B =
//! Q + c·e(θ)` of the lever's input arm (length `c`); the output arm (length `e`) is at angle `φ =
//! θ − δ` (`δ` = `lever_angle_deg`, the input arm's angle from the output arm, counter-clockwise),
//! its tip at `P = Q + e·e(φ)`. The frame moves on the vertical line through the tip's place at
//! `φ = 0`; its pin `G` hangs on the frame link `L` from `P`, above it. The frame's height over
//! mid-stroke (the output arm horizontal) is
//!
//! $$ y = e\sin\varphi + \sqrt{L^2 - e^2(1-\cos\varphi)^2} - L, $$
//!
//! or `y = e·sin φ` without a frame link (the frame driven from the tip's height directly, a
//! block in a slot). The lever angle is the four-bar's closed form: with `d = A − Q`, `s = |d|`,
//!
//! $$ \theta = \operatorname{atan2}(d) + \kappa\,\gamma,\qquad \gamma = \operatorname{atan2}\!\big(\sqrt{(s+b+c)(-s+b+c)(s-b+c)(s+b-c)},\ s^2 + c^2 - b^2\big), $$
//!
//! κ = ±1 the assembly (taken from the linkage at mid-stroke). `y(α)` and every derivative
//! `dᵏy/dαᵏ` (k ≤ 5) come from the same formulas evaluated on truncated Taylor series
//! ([`loomkin_cams::profile::Jet`]): exact to rounding, no finite differences.
//!
//! **The inverse** `α(y)` is the same chain run backwards, two circle intersections in closed
//! form: the tip `P` on the circle of radius `e` about `Q` at distance `L` from `G` (the clockwise
//! one of `Q → G`, the branch with `φ = 0` at mid-stroke; `φ = asin(y/e)` without a link), then the
//! crank pin on the circle of radius `r` about `O` at distance `b` from `B`, on the side of `O → B`
//! that `crank_branch` names (`ccw` or `cw`). One motor angle per frame height on the branch; the
//! angle is taken continuous from its value at mid-stroke.
//!
//! **The motor from the frame's law** by the chain rule, `α̇ = ẏ/y'`, `α̈ = (ÿ − y''α̇²)/y'` (`'` =
//! d/dα) — worked to every order at once by reverting the series of `y(α)` about the current angle.
//!
//! **The torque.** The frame (mass `m`, the load force `F = m ÿ + c ẏ + F_μ sgn ẏ + k_s y + F₀` of
//! [`crate::Axis`]) and the lever (inertia `J_L` about its shaft, kinetic energy `½ J_L φ̇²`) are
//! the load; by virtual work the motor gives
//!
//! $$ T = (J_m + J_x)\,\ddot\alpha + \frac{F\,y' + J_L\,\ddot\varphi\,\varphi'}{\eta}, $$
//!
//! `J_L φ̈ φ' = J_L(φ'² α̈ + φ' φ'' α̇²)`: the lever's reflected inertia and its rate of change.
//! With a gearbox of `i` motor turns per crank turn (`gear_ratio`) the motor turns by `i·α` and
//! gives `(J_m + J_x)·i·α̈ + (F·y' + J_L·φ̈·φ')/(i·η)`.
//! The crank's own inertia belongs in `extra_inertia_kg_m2`; the rod and the frame link are taken
//! as massless (add their masses to the frame's or the lever's where they move with them).
//!
//! **Refused.** A geometry whose crank cannot reach the lever at mid-stroke, or that cannot move
//! the frame over its whole stroke without passing a dead centre: the crank's (crank and rod in
//! line, `y' = 0`: the frame's extreme on the branch), the lever's (rod and input arm in line,
//! `y' = ∞`: the linkage locks) or the frame link's (the output arm or the link beyond the
//! vertical). [`CrankLever::check_stroke`] names the field and what the stroke needs.

use crate::{Result, ServoError};
use loomkin_cams::profile::Jet;
use loomkin_units::{Field, Range};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The side of the line from the motor shaft to the rod's pin on the lever that the crank pin
/// lies on (looking at the linkage with `x` toward the frame and `y` up): the branch of the
/// crank's motion, between its two dead centres.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CrankBranch {
    /// Counter-clockwise of `O → B`.
    #[default]
    Ccw,
    /// Clockwise of `O → B`.
    Cw,
}

impl CrankBranch {
    fn sign(self) -> f64 {
        match self {
            Self::Ccw => 1.0,
            Self::Cw => -1.0,
        }
    }
}

/// The geometry of a crank-and-lever transmission (see the module). Lengths in mm.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CrankLever {
    /// Crank radius `r`, mm ([`CrankLever::CRANK_RADIUS_MM`]).
    pub crank_radius_mm: f64,
    /// Connecting rod `b`, crank pin to the lever's input pin, mm ([`CrankLever::ROD_LENGTH_MM`]).
    pub rod_length_mm: f64,
    /// Lever input arm `c`, rocking shaft to the rod's pin, mm ([`CrankLever::LEVER_INPUT_ARM_MM`]).
    pub lever_input_arm_mm: f64,
    /// Lever output arm `e`, rocking shaft to the frame link's pin, mm
    /// ([`CrankLever::LEVER_OUTPUT_ARM_MM`]).
    pub lever_output_arm_mm: f64,
    /// Angle `δ` of the input arm from the output arm, counter-clockwise, deg
    /// ([`CrankLever::LEVER_ANGLE_DEG`]).
    #[serde(default)]
    pub lever_angle_deg: f64,
    /// The rocking shaft's position from the motor shaft, x (toward the frame), mm
    /// ([`CrankLever::ROCKING_SHAFT_X_MM`]).
    pub rocking_shaft_x_mm: f64,
    /// The rocking shaft's position from the motor shaft, y (up), mm
    /// ([`CrankLever::ROCKING_SHAFT_Y_MM`]).
    pub rocking_shaft_y_mm: f64,
    /// Frame link `L` from the output arm's tip up to the frame, mm; none: the frame follows the
    /// tip's height ([`CrankLever::FRAME_LINK_MM`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frame_link_mm: Option<f64>,
    /// The lever's inertia about its shaft, kg·m² ([`CrankLever::LEVER_INERTIA_KG_M2`]).
    #[serde(default)]
    pub lever_inertia_kg_m2: f64,
    /// The crank's branch.
    #[serde(default)]
    pub crank_branch: CrankBranch,
    /// Motor turns per crank turn, a gearbox between them ([`CrankLever::GEAR_RATIO`]).
    #[serde(default = "CrankLever::default_gear")]
    pub gear_ratio: f64,
    /// The slave position (of the cycle moved) at which the frame is at mid-stroke, mm
    /// ([`CrankLever::MID_STROKE_MM`]).
    #[serde(default)]
    pub mid_stroke_mm: f64,
}

impl CrankLever {
    /// `crank_radius_mm`: 0.01 … 10⁴ mm.
    pub const CRANK_RADIUS_MM: Field = Field::new(
        "crank_radius_mm",
        Range::closed(0.01, 1e4, "mm"),
        "Crank radius r on the motor shaft (or the eccentric's throw): 0.01 … 10⁴ mm; required with a \
         crank and lever.",
    );
    /// `rod_length_mm`: 0.01 … 10⁵ mm.
    pub const ROD_LENGTH_MM: Field = Field::new(
        "rod_length_mm",
        Range::closed(0.01, 1e5, "mm"),
        "Connecting rod b, crank pin to the lever's input pin: 0.01 … 10⁵ mm; required with a crank and lever.",
    );
    /// `lever_input_arm_mm`: 0.01 … 10⁵ mm.
    pub const LEVER_INPUT_ARM_MM: Field = Field::new(
        "lever_input_arm_mm",
        Range::closed(0.01, 1e5, "mm"),
        "Lever input arm c, rocking shaft to the rod's pin: 0.01 … 10⁵ mm; required with a crank and lever.",
    );
    /// `lever_output_arm_mm`: 0.01 … 10⁵ mm.
    pub const LEVER_OUTPUT_ARM_MM: Field = Field::new(
        "lever_output_arm_mm",
        Range::closed(0.01, 1e5, "mm"),
        "Lever output arm e, rocking shaft to the frame link's pin (horizontal at mid-stroke): 0.01 … 10⁵ mm; \
         required with a crank and lever.",
    );
    /// `lever_angle_deg`: −180 … 180°; 0 when left out.
    pub const LEVER_ANGLE_DEG: Field = Field::new(
        "lever_angle_deg",
        Range::closed(-180.0, 180.0, "deg"),
        "Angle of the lever's input arm from its output arm, counter-clockwise (0: one straight arm, the rod \
         and the frame link on it): −180 … 180°; 0 when left out.",
    )
    .with_default(0.0);
    /// `rocking_shaft_x_mm`: ±10⁵ mm.
    pub const ROCKING_SHAFT_X_MM: Field = Field::new(
        "rocking_shaft_x_mm",
        Range::closed(-1e5, 1e5, "mm"),
        "The rocking shaft's x from the motor shaft (x horizontal, toward the frame): ±10⁵ mm; required with a \
         crank and lever.",
    );
    /// `rocking_shaft_y_mm`: ±10⁵ mm.
    pub const ROCKING_SHAFT_Y_MM: Field = Field::new(
        "rocking_shaft_y_mm",
        Range::closed(-1e5, 1e5, "mm"),
        "The rocking shaft's y from the motor shaft (up): ±10⁵ mm; required with a crank and lever.",
    );
    /// `frame_link_mm`: 0.01 … 10⁶ mm; none (the frame follows the tip's height) when left out.
    pub const FRAME_LINK_MM: Field = Field::new(
        "frame_link_mm",
        Range::closed(0.01, 1e6, "mm"),
        "Frame link L from the output arm's tip up to the frame, which slides on the vertical through the tip \
         at mid-stroke: 0.01 … 10⁶ mm; none (the frame follows the tip's height, a block in a slot) when left \
         out.",
    );
    /// `lever_inertia_kg_m2`: 0 … 10³ kg·m²; 0 when left out.
    pub const LEVER_INERTIA_KG_M2: Field = Field::new(
        "lever_inertia_kg_m2",
        Range::closed(0.0, 1e3, "kg·m²"),
        "Inertia of the lever (both arms, the rocking shaft) about its shaft: 0 … 10³ kg·m²; 0 when left out.",
    )
    .with_default(0.0);
    /// `gear_ratio`: 0.01 … 10⁴ motor turns per crank turn; 1 (the crank on the motor shaft) when left out.
    pub const GEAR_RATIO: Field = Field::new(
        "gear_ratio",
        Range::closed(0.01, 1e4, ""),
        "Motor turns per crank turn (a gearbox between the motor and the crank; its inertia on the motor side \
         belongs in extra_inertia_kg_m2): 0.01 … 10⁴; 1 (the crank on the motor shaft) when left out.",
    )
    .with_default(1.0);
    /// `mid_stroke_mm`: ±10⁶ mm; 0 when left out.
    pub const MID_STROKE_MM: Field = Field::new(
        "mid_stroke_mm",
        Range::closed(-1e6, 1e6, "mm"),
        "The slave position of the cycle at which the frame is at mid-stroke (the lever's output arm \
         horizontal): ±10⁶ mm; 0 when left out.",
    )
    .with_default(0.0);

    /// The descriptors, in the order of the fields.
    pub const FIELDS: [Field; 11] = [
        Self::CRANK_RADIUS_MM,
        Self::ROD_LENGTH_MM,
        Self::LEVER_INPUT_ARM_MM,
        Self::LEVER_OUTPUT_ARM_MM,
        Self::LEVER_ANGLE_DEG,
        Self::ROCKING_SHAFT_X_MM,
        Self::ROCKING_SHAFT_Y_MM,
        Self::FRAME_LINK_MM,
        Self::LEVER_INERTIA_KG_M2,
        Self::GEAR_RATIO,
        Self::MID_STROKE_MM,
    ];

    fn default_gear() -> f64 {
        Self::GEAR_RATIO.default_value()
    }

    /// Checks every field against its range (named `{at}.{field}`) and that the crank reaches the
    /// lever with the frame at mid-stroke.
    pub fn check(&self, at: &str) -> Result<()> {
        let f = |field: Field, v: f64| field.check_as(&format!("{at}.{}", field.name), v).map(|_| ());
        f(Self::CRANK_RADIUS_MM, self.crank_radius_mm)?;
        f(Self::ROD_LENGTH_MM, self.rod_length_mm)?;
        f(Self::LEVER_INPUT_ARM_MM, self.lever_input_arm_mm)?;
        f(Self::LEVER_OUTPUT_ARM_MM, self.lever_output_arm_mm)?;
        f(Self::LEVER_ANGLE_DEG, self.lever_angle_deg)?;
        f(Self::ROCKING_SHAFT_X_MM, self.rocking_shaft_x_mm)?;
        f(Self::ROCKING_SHAFT_Y_MM, self.rocking_shaft_y_mm)?;
        if let Some(l) = self.frame_link_mm {
            f(Self::FRAME_LINK_MM, l)?;
        }
        f(Self::LEVER_INERTIA_KG_M2, self.lever_inertia_kg_m2)?;
        f(Self::GEAR_RATIO, self.gear_ratio)?;
        f(Self::MID_STROKE_MM, self.mid_stroke_mm)?;
        self.linkage().map(|_| ()).map_err(|reason| ServoError::Cycle { field: format!("{at}.rod_length_mm"), reason })
    }

    /// The linkage in metres, its assembly and its motor angle at mid-stroke; why not, when the
    /// crank cannot reach the lever there.
    pub fn linkage(&self) -> std::result::Result<Linkage, String> {
        let mm = 1e-3;
        let mut l = Linkage {
            r: self.crank_radius_mm * mm,
            b: self.rod_length_mm * mm,
            c: self.lever_input_arm_mm * mm,
            e: self.lever_output_arm_mm * mm,
            delta: self.lever_angle_deg.to_radians(),
            q: [self.rocking_shaft_x_mm * mm, self.rocking_shaft_y_mm * mm],
            link: self.frame_link_mm.map(|v| v * mm),
            sigma: self.crank_branch.sign(),
            kappa: 1.0,
            alpha_mid: 0.0,
            ascent: 1.0,
            mid_m: self.mid_stroke_mm * mm,
            lever_inertia: self.lever_inertia_kg_m2,
            gear: self.gear_ratio,
        };
        let b_mid = l.rod_pin(0.0);
        let d = b_mid[0].hypot(b_mid[1]);
        let Some(a) = l.crank_pin(b_mid) else {
            return Err(format!(
                "the crank cannot reach the lever with the frame at mid-stroke: the rod's pin on the lever is {} mm \
                 from the motor shaft, the crank and rod reach {} … {} mm (|rod_length_mm − crank_radius_mm| … \
                 their sum)",
                loomkin_units::compact(d * 1e3),
                loomkin_units::compact((l.b - l.r).abs() * 1e3),
                loomkin_units::compact((l.b + l.r) * 1e3)
            ));
        };
        l.alpha_mid = a[1].atan2(a[0]);
        let cross = (a[0] - l.q[0]) * (b_mid[1] - l.q[1]) - (a[1] - l.q[1]) * (b_mid[0] - l.q[0]);
        l.kappa = if cross < 0.0 { -1.0 } else { 1.0 };
        l.ascent = l.height(Jet::var(l.alpha_mid)).0.d(1).signum();
        Ok(l)
    }

    /// Checks that the linkage moves the frame from `lo_m` to `hi_m` (slave positions, m) without
    /// a dead centre: the stroke (with mid-stroke) must lie strictly between the first dead centre
    /// below mid-stroke and the first above it, both in closed form ([`Linkage::reach`]). The error
    /// names `{at}.{field}`, the field that moves the dead centre that limits the stroke.
    pub fn check_stroke(&self, lo_m: f64, hi_m: f64, at: &str) -> Result<()> {
        let l = self.linkage().map_err(|reason| ServoError::Cycle { field: format!("{at}.rod_length_mm"), reason })?;
        let (lo, hi) = (lo_m - l.mid_m, hi_m - l.mid_m);
        for (up, need) in [(true, hi), (false, lo)] {
            let reach = l.reach(up);
            let inside = if up { need < reach.height_m } else { need > reach.height_m };
            if inside {
                continue;
            }
            let (field, what) = match reach.kind {
                DeadCentre::Crank => (
                    "crank_radius_mm",
                    "the crank reaches its dead centre (crank and rod in line): a longer crank_radius_mm, or a longer \
                     lever_output_arm_mm against lever_input_arm_mm",
                ),
                DeadCentre::Lever => (
                    "rod_length_mm",
                    "the rod and the lever's input arm come in line (the linkage locks): change rod_length_mm, \
                     lever_input_arm_mm or the rocking shaft's position",
                ),
                DeadCentre::OutputArm if l.link.is_some() => (
                    "lever_output_arm_mm",
                    "the output arm and the frame link come in line: a longer lever_output_arm_mm or frame_link_mm",
                ),
                DeadCentre::OutputArm => {
                    ("lever_output_arm_mm", "the output arm reaches the vertical: a longer lever_output_arm_mm")
                }
                DeadCentre::FrameLink => (
                    "frame_link_mm",
                    "the frame link comes level with the output arm's tip (the linkage locks): a longer frame_link_mm",
                ),
            };
            return Err(ServoError::Cycle {
                field: format!("{at}.{field}"),
                reason: format!(
                    "the crank and lever move the frame only to {} mm {} mid-stroke, the stroke needs {} … {} mm: \
                     {what}",
                    loomkin_units::compact((reach.height_m.abs() * 1e6).round() / 1e3),
                    if up { "above" } else { "below" },
                    loomkin_units::compact(lo * 1e3),
                    loomkin_units::compact(hi * 1e3)
                ),
            });
        }
        Ok(())
    }
}

/// The kinds of dead centre that end the frame's travel on the crank's branch ([`Linkage::reach`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DeadCentre {
    /// The crank and the rod in line (`|B| = b ± r`): `dy/dα = 0`, the frame's extreme on the
    /// branch; beyond it the crank cannot reach the rod's pin.
    Crank,
    /// The rod and the lever's input arm in line (`|A − Q| = b ± c`): `dy/dα = ∞`, the linkage
    /// locks (the crank turns back).
    Lever,
    /// The output arm and the frame link in line (`|G − Q| = e + L`, or `L − e` with `L ≥ 2e`), or
    /// without a frame link the output arm vertical: `dy/dα = 0`, the frame's extreme.
    OutputArm,
    /// The frame link level with the output arm's tip (`e(1 − cos φ) = L`, with `L ≤ 2e`):
    /// `dy/dα = ∞`, the lever turns back while the frame moves on.
    FrameLink,
}

/// The first dead centre on one side of mid-stroke ([`Linkage::reach`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reach {
    /// Which dead centre.
    pub kind: DeadCentre,
    /// The output arm's angle φ there, rad.
    pub lever_angle_rad: f64,
    /// The frame's height over mid-stroke there, m.
    pub height_m: f64,
}

/// A checked crank-and-lever in metres and radians ([`CrankLever::linkage`]): the forward
/// kinematics on Taylor series and the closed-form inverse.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Linkage {
    /// Crank radius, m.
    pub r: f64,
    /// Rod, m.
    pub b: f64,
    /// Input arm, m.
    pub c: f64,
    /// Output arm, m.
    pub e: f64,
    /// Input arm's angle from the output arm, rad.
    pub delta: f64,
    /// Rocking shaft from the motor shaft, m.
    pub q: [f64; 2],
    /// Frame link, m.
    pub link: Option<f64>,
    /// The crank's branch, ±1.
    pub sigma: f64,
    /// The four-bar's assembly, ±1 (from mid-stroke).
    pub kappa: f64,
    /// Motor angle at mid-stroke, rad.
    pub alpha_mid: f64,
    /// The way the crank turns as the frame rises: the sign of `dy/dα` at mid-stroke, ±1.
    pub ascent: f64,
    /// Slave position at mid-stroke, m.
    pub mid_m: f64,
    /// Lever inertia, kg·m².
    pub lever_inertia: f64,
    /// Motor turns per crank turn.
    pub gear: f64,
}

/// `atan2(y, x)` of jets: the value from `f64::atan2`, the rates from `atan` of the better
/// conditioned quotient (the two differ by a constant).
fn atan2(y: Jet, x: Jet) -> Jet {
    let mut q = if x.v().abs() >= y.v().abs() { y.div(&x).atan() } else { -(x.div(&y).atan()) };
    q.0[0] = y.v().atan2(x.v());
    q
}

/// `Σ f_k δᵏ` (`δ` without a constant term): the series `f` about a point composed with `δ`, by
/// Horner's rule. Each product `acc·δ` is `Jet`'s (its order-`k` sum from 0.0 over `i = 0 … k`)
/// without the terms `acc_k·δ₀` it would add: `±0`, and a sum begun at `+0.0` is never `−0`, so
/// leaving them out changes no bit (for finite `δ`); the first `acc` is a constant.
fn compose(f: &Jet, delta: &Jet) -> Jet {
    debug_assert_eq!(delta.0[0], 0.0);
    let n = f.0.len();
    let d = &delta.0;
    // acc = cst(f_top)·δ + … : the first product has the one term f_top·δ_k.
    let mut acc = Jet::cst(0.0).0;
    for (k, a) in acc.iter_mut().enumerate().skip(1) {
        *a = 0.0 + f.0[n - 1] * d[k];
    }
    acc[0] = 0.0 + f.0[n - 2];
    for fk in f.0[..n - 2].iter().rev() {
        let mut h = Jet::cst(0.0).0;
        for (k, hk) in h.iter_mut().enumerate().skip(1) {
            for i in 0..k {
                *hk += acc[i] * d[k - i];
            }
        }
        h[0] = 0.0 + fk;
        acc = h;
    }
    Jet(acc)
}

/// The motor's motion for a slave motion ([`Linkage::motor`]), as series in time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotorMotion {
    /// Crank angle α(t), rad (its derivatives: the crank's speed, acceleration, …; the motor's are
    /// `gear_ratio` times these).
    pub alpha: Jet,
    /// `y'(α(t))`, m/rad.
    pub dy_dalpha: Jet,
    /// The lever's output arm angle φ(t), rad.
    pub lever: Jet,
    /// `φ'(α(t))`.
    pub dlever_dalpha: Jet,
}

impl Linkage {
    /// The rod's pin `B` with the output arm at angle `φ`.
    fn rod_pin(&self, phi: f64) -> [f64; 2] {
        let t = phi + self.delta;
        [self.q[0] + self.c * t.cos(), self.q[1] + self.c * t.sin()]
    }

    /// The first dead centre above mid-stroke (`up`) or below it, in closed form: the frame moves
    /// from mid-stroke to its height, `dy/dα` keeping its sign and finite, and no farther.
    ///
    /// The output arm's angle φ moves one way with the frame (`dy/dφ = e > 0` at mid-stroke) until
    /// the output arm and the frame link come in line (`dy/dφ = 0`: with `P − Q ∥ G − P`,
    /// `e(1 − cos φ) = L|cos φ|`, so `cos φ = e/(e + L)` above and `e/(e − L)` below when `L ≥ 2e`;
    /// the output arm vertical without a link) or the link comes level with the tip (`dy/dφ = ∞`:
    /// `cos φ = 1 − L/e` below when `L ≤ 2e`). On the way the four-bar gives the crank angle until
    /// the crank and rod come in line (`dφ/dα = 0`: `|B(φ)| = b ± r`, `cos(φ + δ − ψ) = ((b ±
    /// r)² − |Q|² − c²)/(2c|Q|)`, `ψ` the direction of `Q`) or the rod and input arm do (`dφ/dα =
    /// ∞`: `|A(α) − Q| = b ± c`, `cos(α − ψ) = (r² + |Q|² − (b ± c)²)/(2r|Q|)`, counted where the
    /// crank pin lies on the crank's branch). The nearest of these in the direction of travel is
    /// the reach; the height is the frame's at that φ.
    pub fn reach(&self, up: bool) -> Reach {
        let side = if up { 1.0 } else { -1.0 };
        let e = self.e;
        // The output arm and the frame link: the first φ (signed) on this side.
        let (phi_link, link_kind) = match self.link {
            None => (side * PI / 2.0, DeadCentre::OutputArm),
            Some(l) if up => ((e / (e + l)).acos(), DeadCentre::OutputArm),
            Some(l) if l < 2.0 * e => (-(1.0 - l / e).acos(), DeadCentre::FrameLink),
            Some(l) => (-(e / (e - l)).acos(), DeadCentre::OutputArm),
        };
        // The four-bar's dead centres as output arm angles; their distance in the direction of travel.
        let rho = self.q[0].hypot(self.q[1]);
        let psi = self.q[1].atan2(self.q[0]);
        let mut best: Option<(f64, DeadCentre)> = None;
        let mut consider = |phi: f64, kind: DeadCentre| {
            let d = (side * phi).rem_euclid(2.0 * PI);
            if d > 0.0 && best.is_none_or(|(b, _)| d < b) {
                best = Some((d, kind));
            }
        };
        if rho > 0.0 {
            for reach in [self.b + self.r, (self.b - self.r).abs()] {
                let k = (reach * reach - rho * rho - self.c * self.c) / (2.0 * self.c * rho);
                if k.abs() <= 1.0 {
                    let w = k.acos();
                    consider(psi - self.delta + w, DeadCentre::Crank);
                    consider(psi - self.delta - w, DeadCentre::Crank);
                }
            }
            for (reach, toward) in [(self.b + self.c, 1.0), (self.b - self.c, (self.c - self.b).signum())] {
                if reach == 0.0 {
                    continue;
                }
                let k = (self.r * self.r + rho * rho - reach * reach) / (2.0 * self.r * rho);
                if k.abs() > 1.0 {
                    continue;
                }
                let w = k.acos();
                for alpha in [psi + w, psi - w] {
                    let a = [self.r * alpha.cos(), self.r * alpha.sin()];
                    let (ux, uy) = ((a[0] - self.q[0]) / reach.abs(), (a[1] - self.q[1]) / reach.abs());
                    let b = [self.q[0] + toward * self.c * ux, self.q[1] + toward * self.c * uy];
                    if (b[0] * a[1] - b[1] * a[0]) * self.sigma > 0.0 {
                        consider((toward * uy).atan2(toward * ux) - self.delta, DeadCentre::Lever);
                    }
                }
            }
        }
        let (phi, kind) = match best {
            Some((d, kind)) if d < side * phi_link => (side * d, kind),
            _ => (phi_link, link_kind),
        };
        let mut height = e * phi.sin();
        if let Some(l) = self.link {
            let u = e * (1.0 - phi.cos());
            height += (l * l - u * u).max(0.0).sqrt() - l;
        }
        Reach { kind, lever_angle_rad: phi, height_m: height }
    }

    /// The crank pin `A` for the rod's pin `B` on the crank's branch (`None`: out of reach).
    fn crank_pin(&self, b: [f64; 2]) -> Option<[f64; 2]> {
        let d = b[0].hypot(b[1]);
        let a = (self.r * self.r - self.b * self.b + d * d) / (2.0 * d);
        let h2 = self.r * self.r - a * a;
        if h2.is_nan() || h2 < 0.0 || d == 0.0 {
            return None;
        }
        let h = h2.sqrt();
        let (ux, uy) = (b[0] / d, b[1] / d);
        Some([a * ux - self.sigma * h * uy, a * uy + self.sigma * h * ux])
    }

    /// The output arm's angle φ with the frame at height `y` over mid-stroke (`None`: out of reach).
    pub fn lever_angle(&self, y: f64) -> Option<f64> {
        let e = self.e;
        match self.link {
            None => {
                let s = y / e;
                (s.abs() <= 1.0).then(|| s.asin())
            }
            Some(l) => {
                // The tip on the circle (Q, e) at distance L from G = (e, L + y), the clockwise one.
                let (gx, gy) = (e, l + y);
                let d = gx.hypot(gy);
                let a = (e * e - l * l + d * d) / (2.0 * d);
                let h2 = e * e - a * a;
                if h2.is_nan() || h2 < 0.0 {
                    return None;
                }
                let h = h2.sqrt();
                let (ux, uy) = (gx / d, gy / d);
                let (px, py) = (a * ux + h * uy, a * uy - h * ux);
                Some(py.atan2(px))
            }
        }
    }

    /// The motor angle α with the frame at height `y` over mid-stroke (m), closed form, continuous
    /// from mid-stroke (`None`: out of reach on the branch). Between its dead centres the crank
    /// turns one way as the frame rises ([`Linkage::ascent`]), by less than a turn in all: the
    /// angle from mid-stroke's is taken within ±180°, and a turn further where that puts it on the
    /// wrong side (the crank more than half a turn from mid-stroke; not for the rounding of a
    /// height next to mid-stroke's).
    pub fn motor_angle(&self, y: f64) -> Option<f64> {
        let phi = self.lever_angle(y)?;
        let a = self.crank_pin(self.rod_pin(phi))?;
        let raw = a[1].atan2(a[0]);
        let r = (raw - self.alpha_mid + PI).rem_euclid(2.0 * PI);
        let (w, ahead) = (r - PI, y * self.ascent);
        if w * ahead < 0.0 && w.abs() > 1e-6 {
            return Some(self.alpha_mid + w + 2.0 * PI * ahead.signum());
        }
        Some(self.alpha_mid + r - PI)
    }

    /// The crank angle's series while the slave moves by `s` ([`Linkage::motor`]'s `alpha` alone).
    pub fn crank_series(&self, s: Jet) -> Option<Jet> {
        self.revert(s).map(|r| r.0)
    }

    /// `(α, α − α₀, y(α₀ + ·), φ(α₀ + ·))`: the crank angle's series for the slave's, by the
    /// closed-form inverse and the reverted series of `y`.
    fn revert(&self, s: Jet) -> Option<(Jet, Jet, Jet, Jet)> {
        let a0 = self.motor_angle(s.v() - self.mid_m)?;
        let (y, phi) = self.height(Jet::var(a0));
        let mut eta = s;
        eta.0[0] = 0.0;
        let mut f = y;
        f.0[0] = 0.0;
        let c1 = f.0[1];
        let mut delta = Jet::cst(0.0);
        for _ in 1..eta.0.len() {
            delta = delta + (eta - compose(&f, &delta)).scale(1.0 / c1);
        }
        let mut alpha = delta;
        alpha.0[0] = a0;
        Some((alpha, delta, y, phi))
    }

    /// The frame's height over mid-stroke `y` and the output arm's angle φ at the motor angle
    /// `alpha` (a series: every derivative with respect to the motor angle, or to time).
    pub fn height(&self, alpha: Jet) -> (Jet, Jet) {
        let (sa, ca) = alpha.sin_cos();
        let dx = ca.scale(self.r) - Jet::cst(self.q[0]);
        let dy = sa.scale(self.r) - Jet::cst(self.q[1]);
        let s = (dx * dx + dy * dy).sqrt();
        let (b, c) = (Jet::cst(self.b), Jet::cst(self.c));
        let area16 = (s + b + c) * (b + c - s) * (s - b + c) * (s + b - c);
        let gamma = atan2(area16.sqrt(), s * s + c * c - b * b);
        let theta = atan2(dy, dx) + gamma.scale(self.kappa);
        let phi = theta - Jet::cst(self.delta);
        let (sp, cp) = phi.sin_cos();
        let mut y = sp.scale(self.e);
        if let Some(l) = self.link {
            let u = (Jet::cst(1.0) - cp).scale(self.e);
            y = y + (Jet::cst(l * l) - u * u).sqrt() - Jet::cst(l);
        }
        (y, phi)
    }

    /// The motor's motion while the slave moves by `s` (a series in time of the slave position,
    /// m): the motor angle by the closed-form inverse, its rates by reverting the series of
    /// `y(α)` (each pass fixes one more order). `None` where the frame is out of reach.
    pub fn motor(&self, s: Jet) -> Option<MotorMotion> {
        let (alpha, delta, y, phi) = self.revert(s)?;
        Some(MotorMotion {
            alpha,
            dy_dalpha: compose(&y.deriv(), &delta),
            lever: compose(&phi, &delta),
            dlever_dalpha: compose(&phi.deriv(), &delta),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `compose` against Horner's rule on `Jet`'s own product and sum, bit for bit (the terms it
    /// leaves out are `±0`), on series with mixed signs, zeros and `−0`.
    #[test]
    fn compose_is_horner_on_jets_bit_for_bit() {
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            match x % 7 {
                0 => 0.0,
                1 => -0.0,
                _ => ((x >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 10f64.powi((x % 9) as i32 - 4),
            }
        };
        for _ in 0..2000 {
            let f = Jet(std::array::from_fn(|_| next()));
            let mut d = Jet(std::array::from_fn(|_| next()));
            d.0[0] = 0.0;
            let mut want = Jet::cst(f.0[f.0.len() - 1]);
            for k in (0..f.0.len() - 1).rev() {
                want = want * d + Jet::cst(f.0[k]);
            }
            let got = compose(&f, &d);
            assert_eq!(got.0.map(f64::to_bits), want.0.map(f64::to_bits), "{f:?} ∘ {d:?}");
        }
    }
}
