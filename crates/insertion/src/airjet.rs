//! The air jet: a main nozzle and relay nozzles along the reed carry the weft's tip across.
//!
//! **The air along the reed** (a model; every parameter the user's). `x` runs from the main
//! nozzle's exit along the reed channel; the entering selvedge lies at `reed_entry_mm`, the far
//! one `W` further. Each jet — the main nozzle's, and each relay nozzle's downstream of it — has the
//! form Uno (1972) fitted to measured axial air speeds of a free jet, `V = B·V₀/(x − A)`, with a
//! core of constant speed before it: at a distance `ξ` downstream of its nozzle a jet of exit
//! speed `U₀` and core `ξ_c` blows at
//!
//! $$ U(\xi) = U_0 \quad (\xi \le \xi_c), \qquad U(\xi) = U_0\,\xi_c/\xi \quad (\xi > \xi_c) $$
//!
//! (continuous at the core's end; `A = 0`, `B·V₀ = U₀·ξ_c`). Relay nozzles stand every
//! `relay_pitch_mm` from `first_relay_mm` past the entering selvedge, `nozzles_per_group` to a
//! group on one valve, `groups` groups. The yarn's tip feels the strongest air where it is: the
//! main jet's, or the jet of the nearest relay nozzle upstream of it, whichever is faster. A relay
//! jet reaches from its nozzle to the next one (where the next takes over); a group's **reach** is
//! the span of its nozzles' reaches.
//!
//! **The drag** (Uno 1972: the friction coefficient of spun yarns in an air stream,
//! `C_f = 0.02 + 1/(V′ + 2)`, `V′` the air's speed relative to the yarn in m/s). Here
//! `C_f = cf_floor + cf_scale_m_s/(|w| + cf_offset_m_s)` with Uno's 0.02, 1 and 2 as defaults, `w =
//! U − v`. On a yarn of diameter `d` the air pulls `½·ρ·C_f·π·d·w·|w|` per metre.
//!
//! **The yarn's motion.** The moving yarn runs from the drum's stopper to the tip: `ℓ₀ + x` long
//! (`tail_mm` = ℓ₀, the yarn between the stopper and the main nozzle's exit), of mass `μ` per metre
//! (`yarn_tex`). The model takes the air at the tip to pull along the whole moving length, as in
//! the textbook form of Uno's equation; mass and pull then grow together and the growing mass
//! cancels from the acceleration. What does not cancel is the momentum given to the yarn that
//! starts moving as it leaves the drum at rest, `μ·v²` (`draw_off` = 1; 0 leaves it out):
//!
//! $$ \dot v = k\,C_f(|w|)\,w|w| - \beta\,\frac{v^2}{\ell_0 + x}, \qquad k = \frac{\rho\,\pi d}{2\mu},
//!    \quad w = U(x) - v $$
//!
//! from rest at the main nozzle's exit at `launch_deg`, until the tip reaches the far selvedge
//! (`arrival_deg`, `tip_speed_at_exit_m_s`). At constant air `V` with a constant `C_f` and no
//! draw-off it is `v̇ = k·C_f·(V − v)²`, whose closed form the tests hold it to.
//!
//! **Integration.** Classical fourth-order Runge–Kutta in time with a fixed step
//! ([`Airjet::STEP_S`]), each step extrapolated from one full and two half steps (Richardson:
//! fifth order). The field's breaks (nozzles, cores' ends, where the main jet and a relay jet cross)
//! are landed on exactly: a step that would pass one is shortened to end on it (the step's end
//! position as a function of its length, solved by regula falsi), so each step sees one smooth
//! formula; so is the place where the tip overtakes the air or falls behind it (`w = 0`, where
//! `C_f(|w|)` has a kink). Against DOP853 at 1e-13 the arrival time and exit speed agree within
//! 3e-11 (tests; docs/design/insertion.md).
//!
//! **The relay plan.** Under this model a relay group changes the flight only while the tip is in
//! its reach where its jet is the strongest; there it must blow, elsewhere its air is wasted. So
//! the plan opens each group when the tip enters the first stretch its jet leads and closes it when
//! the tip leaves the last: the least open time of any one-opening-per-pick plan that gives the tip
//! the same air (a group whose jet never leads is not opened). The air consumed is the sum of the
//! open times.

use loomkin_units::{Field, Range, ShaftSpeed};
use serde::{Deserialize, Serialize};

use crate::{Atmosphere, CarrierError};

/// The `[insertion.airjet]` table.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AirjetTable {
    /// Yarn linear density, tex ([`AirjetTable::YARN_TEX`]).
    pub yarn_tex: f64,
    /// Yarn diameter, mm ([`AirjetTable::YARN_DIAMETER_MM`]).
    pub yarn_diameter_mm: f64,
    /// Moving yarn behind the main nozzle's exit, mm ([`AirjetTable::TAIL_MM`]).
    pub tail_mm: f64,
    /// Share of the draw-off momentum taken ([`AirjetTable::DRAW_OFF`]).
    #[serde(default)]
    pub draw_off: Option<f64>,
    /// Main jet's exit speed, m/s ([`AirjetTable::MAIN_SPEED_M_S`]).
    pub main_speed_m_s: f64,
    /// Main jet's core, mm ([`AirjetTable::MAIN_CORE_MM`]).
    pub main_core_mm: f64,
    /// Main nozzle's exit to the entering selvedge, mm ([`AirjetTable::REED_ENTRY_MM`]).
    pub reed_entry_mm: f64,
    /// Relay jets' exit speed, m/s ([`AirjetTable::RELAY_SPEED_M_S`]).
    pub relay_speed_m_s: f64,
    /// Relay jets' core, mm ([`AirjetTable::RELAY_CORE_MM`]).
    pub relay_core_mm: f64,
    /// Relay nozzle pitch, mm ([`AirjetTable::RELAY_PITCH_MM`]).
    pub relay_pitch_mm: f64,
    /// First relay nozzle past the entering selvedge, mm ([`AirjetTable::FIRST_RELAY_MM`]).
    #[serde(default)]
    pub first_relay_mm: Option<f64>,
    /// Nozzles on one valve ([`AirjetTable::NOZZLES_PER_GROUP`]).
    pub nozzles_per_group: usize,
    /// Relay groups ([`AirjetTable::GROUPS`]).
    pub groups: usize,
    /// `C_f`'s floor ([`AirjetTable::CF_FLOOR`]).
    #[serde(default)]
    pub cf_floor: Option<f64>,
    /// `C_f`'s scale, m/s ([`AirjetTable::CF_SCALE_M_S`]).
    #[serde(default)]
    pub cf_scale_m_s: Option<f64>,
    /// `C_f`'s offset, m/s ([`AirjetTable::CF_OFFSET_M_S`]).
    #[serde(default)]
    pub cf_offset_m_s: Option<f64>,
    /// Air density, kg/m³ ([`Atmosphere::AIR_DENSITY_KG_M3`]).
    #[serde(default)]
    pub air_density_kg_m3: Option<f64>,
    /// Main-shaft angle at which the main nozzle releases the yarn, deg ([`AirjetTable::LAUNCH_DEG`]).
    pub launch_deg: f64,
}

/// A jet speed: 0 < U ≤ 600 m/s.
const JET_SPEED: Range = Range::open_closed(0.0, 600.0, "m/s");
/// A length along the reed: 0 < ℓ ≤ 10⁴ mm.
const LENGTH: Range = Range::open_closed(0.0, 1e4, "mm");

impl AirjetTable {
    /// `yarn_tex`: 0 < μ ≤ 1000 tex.
    pub const YARN_TEX: Field = Field::new(
        "yarn_tex",
        Range::open_closed(0.0, 1000.0, "tex"),
        "Weft linear density: 0 < μ ≤ 1000 tex (g/km; air jets weave some 5–100 tex).",
    );
    /// `yarn_diameter_mm`: 0 < d ≤ 5 mm.
    pub const YARN_DIAMETER_MM: Field = Field::new(
        "yarn_diameter_mm",
        Range::open_closed(0.0, 5.0, "mm"),
        "Weft diameter, the surface the air pulls on: 0 < d ≤ 5 mm.",
    );
    /// `tail_mm`: 0 < ℓ₀ ≤ 10⁴ mm.
    pub const TAIL_MM: Field = Field::new(
        "tail_mm",
        LENGTH,
        "The moving yarn behind the main nozzle's exit at the launch (from the drum's stopper): 0 < ℓ₀ ≤ 10000 mm.",
    );
    /// `draw_off`: 0 ≤ β ≤ 1, default 1.
    pub const DRAW_OFF: Field = Field::new(
        "draw_off",
        Range::closed(0.0, 1.0, ""),
        "Share of the momentum μ·v² of the yarn leaving the drum at rest that the jets must give: 0 ≤ β ≤ 1; 1 \
         when left out (0 leaves it out, the textbook form).",
    )
    .with_default(1.0);
    /// `main_speed_m_s`.
    pub const MAIN_SPEED_M_S: Field = Field::new(
        "main_speed_m_s",
        JET_SPEED,
        "Air speed at the main nozzle's exit: 0 < U ≤ 600 m/s (Uno advises over 200 m/s; sonic is about 340 m/s).",
    );
    /// `main_core_mm`.
    pub const MAIN_CORE_MM: Field = Field::new(
        "main_core_mm",
        LENGTH,
        "The main jet's core, where it keeps its exit speed; past it the speed falls as 1/distance: 0 < ξ ≤ \
         10000 mm.",
    );
    /// `reed_entry_mm`: 0 ≤ s ≤ 10⁴ mm.
    pub const REED_ENTRY_MM: Field = Field::new(
        "reed_entry_mm",
        Range::closed(0.0, 1e4, "mm"),
        "From the main nozzle's exit to the entering selvedge: 0 ≤ s ≤ 10000 mm.",
    );
    /// `relay_speed_m_s`.
    pub const RELAY_SPEED_M_S: Field =
        Field::new("relay_speed_m_s", JET_SPEED, "Air speed of a relay jet at its nozzle: 0 < U ≤ 600 m/s.");
    /// `relay_core_mm`.
    pub const RELAY_CORE_MM: Field = Field::new(
        "relay_core_mm",
        LENGTH,
        "A relay jet's core along the reed, where it keeps its speed; past it the speed falls as 1/distance: 0 \
         < ξ ≤ 10000 mm.",
    );
    /// `relay_pitch_mm`.
    pub const RELAY_PITCH_MM: Field =
        Field::new("relay_pitch_mm", LENGTH, "Distance between neighbouring relay nozzles: 0 < p ≤ 10000 mm.");
    /// `first_relay_mm`: 0 ≤ s ≤ 10⁴ mm, default 0.
    pub const FIRST_RELAY_MM: Field = Field::new(
        "first_relay_mm",
        Range::closed(0.0, 1e4, "mm"),
        "The first relay nozzle past the entering selvedge: 0 ≤ s ≤ 10000 mm; 0 when left out.",
    )
    .with_default(0.0);
    /// `nozzles_per_group`: 1 … 32.
    pub const NOZZLES_PER_GROUP: Field =
        Field::count("nozzles_per_group", Range::closed(1.0, 32.0, ""), "Relay nozzles on one valve: 1 … 32.");
    /// `groups`: 1 … 256.
    pub const GROUPS: Field =
        Field::count("groups", Range::closed(1.0, 256.0, ""), "Relay groups (valves) along the reed: 1 … 256.");
    /// `cf_floor`: 0 ≤ a ≤ 10, default 0.02.
    pub const CF_FLOOR: Field = Field::new(
        "cf_floor",
        Range::closed(0.0, 10.0, ""),
        "The friction coefficient's floor in C_f = a + b/(|w| + c): 0 ≤ a ≤ 10; Uno's 0.02 for spun yarns when \
         left out.",
    )
    .with_default(0.02);
    /// `cf_scale_m_s`: 0 ≤ b ≤ 1000 m/s, default 1.
    pub const CF_SCALE_M_S: Field = Field::new(
        "cf_scale_m_s",
        Range::closed(0.0, 1000.0, "m/s"),
        "b in C_f = a + b/(|w| + c): 0 ≤ b ≤ 1000 m/s; Uno's 1 m/s when left out (0: a constant C_f).",
    )
    .with_default(1.0);
    /// `cf_offset_m_s`: 0 < c ≤ 1000 m/s, default 2.
    pub const CF_OFFSET_M_S: Field = Field::new(
        "cf_offset_m_s",
        Range::open_closed(0.0, 1000.0, "m/s"),
        "c in C_f = a + b/(|w| + c): 0 < c ≤ 1000 m/s; Uno's 2 m/s when left out.",
    )
    .with_default(2.0);
    /// `launch_deg`: 0 ≤ φ < 360°.
    pub const LAUNCH_DEG: Field = Field::new(
        "launch_deg",
        Range::closed_open(0.0, 360.0, "deg"),
        "Main-shaft angle at which the main nozzle blows and the drum releases the yarn: 0 ≤ φ < 360°.",
    );
}

/// Which jet leads the air on a stretch of the reed, and in which regime.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Jet {
    /// The main jet.
    Main,
    /// Relay nozzle `j` (0-based along the reed).
    Relay(usize),
}

/// A stretch of the channel on which one jet leads in one regime (core or decay): one smooth formula.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Piece {
    x0: f64,
    x1: f64,
    jet: Jet,
    /// The jet's nozzle position and exit speed, and whether this stretch is in its core.
    origin: f64,
    speed: f64,
    core_m: f64,
    in_core: bool,
}

impl Piece {
    /// The air speed by this stretch's formula (continued past its ends), m/s.
    fn air(&self, x: f64) -> f64 {
        if self.in_core { self.speed } else { self.speed * self.core_m / (x - self.origin) }
    }
}

/// A checked air-jet insertion across a reed space.
#[derive(Debug, Clone, PartialEq)]
pub struct Airjet {
    /// The table as given.
    pub table: AirjetTable,
    /// `k = ρ·π·d/(2·μ)`, 1/m.
    pub k: f64,
    /// `C_f = a + b/(|w| + c)`: (a, b, c).
    pub cf: [f64; 3],
    /// Draw-off share β.
    pub draw_off: f64,
    /// Moving yarn behind the nozzle's exit, m.
    pub tail_m: f64,
    /// Main nozzle (speed m/s, core m).
    pub main: (f64, f64),
    /// Relay jets (speed m/s, core m).
    pub relay: (f64, f64),
    /// The relay nozzles' positions from the main nozzle's exit, m.
    pub nozzles_m: Vec<f64>,
    /// Nozzles per group.
    pub per_group: usize,
    /// Main nozzle's exit to the entering selvedge, m.
    pub reed_entry_m: f64,
    /// Reed space, m.
    pub reed_width_m: f64,
    /// Launch angle, deg.
    pub launch_deg: f64,
    pieces: Vec<Piece>,
}

/// One relay group's opening.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RelayOpen {
    /// The group, 1 = the one nearest the main nozzle.
    pub group: usize,
    /// Main-shaft angle at which its valve opens, deg (past 360°: the next turn).
    pub open_deg: f64,
    /// Angle at which it closes, deg.
    pub close_deg: f64,
}

/// A point of the tip's flight.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TipPoint {
    /// Time from the launch, s.
    pub t_s: f64,
    /// The tip from the main nozzle's exit, m.
    pub x_m: f64,
    /// Its speed, m/s.
    pub v_m_s: f64,
    /// The air's speed there, m/s.
    pub air_m_s: f64,
}

/// The air jet's figures at a loom speed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AirjetReport {
    /// Loom speed, rpm.
    pub speed_rpm: f64,
    /// Launch angle, deg.
    pub launch_deg: f64,
    /// Angle at which the tip passes the entering selvedge, deg.
    pub reed_entry_deg: f64,
    /// Angle at which it reaches the far selvedge, deg.
    pub arrival_deg: f64,
    /// From the launch to the far selvedge, ms.
    pub flight_time_ms: f64,
    /// The tip's speed at the far selvedge, m/s.
    pub tip_speed_at_exit_m_s: f64,
    /// The tip's largest speed, m/s.
    pub peak_tip_speed_m_s: f64,
    /// The relay groups' openings (the groups whose jet leads somewhere), in order along the reed.
    pub relay_plan: Vec<RelayOpen>,
    /// The air consumed: the relay valves' open times summed, ms.
    pub relay_open_ms: f64,
    /// The same in degrees of main shaft.
    pub relay_open_deg: f64,
    /// Relay groups along the reed.
    pub groups: usize,
}

impl Airjet {
    /// The fixed step of the integration, s (10 µs: arrival time and exit speed within 3e-11 of DOP853
    /// at 1e-13 in the tests; 5 µs: 7e-12).
    pub const STEP_S: f64 = 1e-5;

    /// The air jet of a `[insertion.airjet]` table across `reed_width_m`; errors name `{prefix}.…`.
    pub fn new(t: &AirjetTable, reed_width_m: f64, prefix: &str) -> Result<Self, CarrierError> {
        let name = |k: &str| format!("{prefix}.{k}");
        let opt = |f: &Field, v: Option<f64>| -> Result<f64, CarrierError> {
            Ok(f.check_as(&name(f.name), v.unwrap_or_else(|| f.default_value()))?)
        };
        let req = |f: &Field, v: f64| -> Result<f64, CarrierError> { Ok(f.check_as(&name(f.name), v)?) };
        let tex = req(&AirjetTable::YARN_TEX, t.yarn_tex)?;
        let d = req(&AirjetTable::YARN_DIAMETER_MM, t.yarn_diameter_mm)? * 1e-3;
        let rho = opt(&Atmosphere::AIR_DENSITY_KG_M3, t.air_density_kg_m3)?;
        let mu = tex * 1e-6;
        let per_group =
            AirjetTable::NOZZLES_PER_GROUP.check_count_as(&name("nozzles_per_group"), t.nozzles_per_group)?;
        let groups = AirjetTable::GROUPS.check_count_as(&name("groups"), t.groups)?;
        let reed_entry = req(&AirjetTable::REED_ENTRY_MM, t.reed_entry_mm)? * 1e-3;
        let first = opt(&AirjetTable::FIRST_RELAY_MM, t.first_relay_mm)? * 1e-3;
        let pitch = req(&AirjetTable::RELAY_PITCH_MM, t.relay_pitch_mm)? * 1e-3;
        let nozzles_m: Vec<f64> = (0..groups * per_group).map(|j| reed_entry + first + pitch * j as f64).collect();
        let mut a = Self {
            table: t.clone(),
            k: rho * std::f64::consts::PI * d / (2.0 * mu),
            cf: [
                opt(&AirjetTable::CF_FLOOR, t.cf_floor)?,
                opt(&AirjetTable::CF_SCALE_M_S, t.cf_scale_m_s)?,
                opt(&AirjetTable::CF_OFFSET_M_S, t.cf_offset_m_s)?,
            ],
            draw_off: opt(&AirjetTable::DRAW_OFF, t.draw_off)?,
            tail_m: req(&AirjetTable::TAIL_MM, t.tail_mm)? * 1e-3,
            main: (
                req(&AirjetTable::MAIN_SPEED_M_S, t.main_speed_m_s)?,
                req(&AirjetTable::MAIN_CORE_MM, t.main_core_mm)? * 1e-3,
            ),
            relay: (
                req(&AirjetTable::RELAY_SPEED_M_S, t.relay_speed_m_s)?,
                req(&AirjetTable::RELAY_CORE_MM, t.relay_core_mm)? * 1e-3,
            ),
            nozzles_m,
            per_group,
            reed_entry_m: reed_entry,
            reed_width_m,
            launch_deg: req(&AirjetTable::LAUNCH_DEG, t.launch_deg)?,
            pieces: Vec::new(),
        };
        if a.cf[0] == 0.0 && a.cf[1] == 0.0 {
            return Err(CarrierError::field(name("cf_floor"), "C_f is zero: give cf_floor or cf_scale_m_s above 0"));
        }
        a.pieces = a.build_pieces();
        Ok(a)
    }

    /// The far selvedge from the main nozzle's exit, m.
    pub fn exit_m(&self) -> f64 {
        self.reed_entry_m + self.reed_width_m
    }

    /// The main jet's speed at `x`, m/s.
    pub fn main_air(&self, x: f64) -> f64 {
        let (u, c) = self.main;
        if x <= c { u } else { u * c / x }
    }

    /// The relay jets' speed at `x` (the nearest nozzle upstream; 0 before the first), m/s.
    pub fn relay_air(&self, x: f64) -> f64 {
        let (u, c) = self.relay;
        match self.nozzles_m.iter().rposition(|&n| n <= x) {
            Some(j) => {
                let xi = x - self.nozzles_m[j];
                if xi <= c { u } else { u * c / xi }
            }
            None => 0.0,
        }
    }

    /// The air at the tip at `x`: the faster of the main jet and the relay jets, m/s.
    pub fn air(&self, x: f64) -> f64 {
        self.main_air(x).max(self.relay_air(x))
    }

    /// The channel cut into stretches of one smooth formula each, from the nozzle's exit to the
    /// far selvedge.
    fn build_pieces(&self) -> Vec<Piece> {
        let end = self.exit_m();
        let (um, cm) = self.main;
        let (ur, cr) = self.relay;
        let mut cuts = vec![0.0, cm, self.reed_entry_m, end];
        for (j, &n) in self.nozzles_m.iter().enumerate() {
            cuts.push(n);
            let next = self.nozzles_m.get(j + 1).copied().unwrap_or(f64::INFINITY);
            if n + cr < next {
                cuts.push(n + cr);
            }
        }
        cuts.retain(|&c| (0.0..=end).contains(&c));
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        let main_piece = |x0: f64, x1: f64| Piece {
            x0,
            x1,
            jet: Jet::Main,
            origin: 0.0,
            speed: um,
            core_m: cm,
            in_core: 0.5 * (x0 + x1) <= cm,
        };
        let relay_piece = |x0: f64, x1: f64| -> Option<Piece> {
            let mid = 0.5 * (x0 + x1);
            let j = self.nozzles_m.iter().rposition(|&n| n <= mid)?;
            let origin = self.nozzles_m[j];
            Some(Piece { x0, x1, jet: Jet::Relay(j), origin, speed: ur, core_m: cr, in_core: mid - origin <= cr })
        };
        let mut pieces = Vec::new();
        for w in cuts.windows(2) {
            let (x0, x1) = (w[0], w[1]);
            let m = main_piece(x0, x1);
            let Some(r) = relay_piece(x0, x1) else {
                pieces.push(m);
                continue;
            };
            // Main minus relay is monotone on a stretch (module notes): at most one crossing.
            let d = |x: f64| m.air(x) - r.air(x);
            let (d0, d1) = (d(x0), d(x1));
            let lead = |x0: f64, x1: f64, dm: f64| {
                let p = if dm >= 0.0 { m } else { r };
                Piece { x0, x1, ..p }
            };
            if d0 * d1 < 0.0 {
                let xc = loomkin_numeric::illinois_root(x0, x1, d0, d1, d);
                pieces.push(lead(x0, xc, d0));
                pieces.push(lead(xc, x1, d1));
            } else {
                pieces.push(lead(x0, x1, d(0.5 * (x0 + x1))));
            }
        }
        pieces
    }

    /// The tip's acceleration at `x` with speed `v` in the air of `piece`, m/s².
    fn accel(&self, piece: &Piece, x: f64, v: f64) -> f64 {
        let w = piece.air(x) - v;
        let [a, b, c] = self.cf;
        let cf = a + b / (w.abs() + c);
        self.k * cf * w * w.abs() - self.draw_off * v * v / (self.tail_m + x)
    }

    /// One classical Runge–Kutta step of length `h` from `(x, v)` in the air of `piece`.
    fn rk4(&self, piece: &Piece, x: f64, v: f64, h: f64) -> (f64, f64) {
        let f = |x: f64, v: f64| (v, self.accel(piece, x, v));
        let k1 = f(x, v);
        let k2 = f(x + 0.5 * h * k1.0, v + 0.5 * h * k1.1);
        let k3 = f(x + 0.5 * h * k2.0, v + 0.5 * h * k2.1);
        let k4 = f(x + h * k3.0, v + h * k3.1);
        (x + h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0), v + h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1))
    }

    /// One step of length `h`: a classical Runge–Kutta step and two half steps, extrapolated
    /// (`y₂ + (y₂ − y₁)/15`, Richardson: fifth order).
    fn step(&self, piece: &Piece, x: f64, v: f64, h: f64) -> (f64, f64) {
        let (x1, v1) = self.rk4(piece, x, v, h);
        let (xm, vm) = self.rk4(piece, x, v, 0.5 * h);
        let (x2, v2) = self.rk4(piece, xm, vm, 0.5 * h);
        (x2 + (x2 - x1) / 15.0, v2 + (v2 - v1) / 15.0)
    }

    /// The flight from the launch to the far selvedge: every step's point, and the time at which
    /// the tip ends each stretch. Fails when the tip stalls or takes longer than `max_s`.
    fn fly(&self, max_s: f64, mut each: impl FnMut(&TipPoint)) -> Result<Vec<f64>, CarrierError> {
        let (mut t, mut x, mut v) = (0.0, 0.0, 0.0);
        let h = Self::STEP_S;
        let mut ends = Vec::with_capacity(self.pieces.len());
        for p in &self.pieces {
            each(&TipPoint { t_s: t, x_m: x, v_m_s: v, air_m_s: p.air(x) });
            // Just landed where the tip and the air pass each other: the next step starts on it.
            let mut on_kink = false;
            loop {
                let (x1, v1) = self.step(p, x, v, h);
                if x1 >= p.x1 {
                    let hs = if x >= p.x1 {
                        0.0
                    } else {
                        loomkin_numeric::illinois_root(0.0, h, x - p.x1, x1 - p.x1, |s| self.step(p, x, v, s).0 - p.x1)
                    };
                    let (_, vs) = self.step(p, x, v, hs);
                    (t, x, v) = (t + hs, p.x1, vs);
                    break;
                }
                // Where the air and the tip pass each other (w = 0) the drag's C_f(|w|) has a kink:
                // the step ends there too, so that each step sees a smooth right-hand side.
                let w0 = p.air(x) - v;
                let w1 = p.air(x1) - v1;
                if w0 * w1 < 0.0 && !on_kink {
                    let g = |s: f64| {
                        let (xs, vs) = self.step(p, x, v, s);
                        p.air(xs) - vs
                    };
                    let hs = loomkin_numeric::illinois_root(0.0, h, w0, w1, g);
                    let (xs, vs) = self.step(p, x, v, hs);
                    (t, x, v) = (t + hs, xs, vs);
                    on_kink = true;
                    each(&TipPoint { t_s: t, x_m: x, v_m_s: v, air_m_s: p.air(x) });
                    continue;
                }
                on_kink = false;
                (t, x, v) = (t + h, x1, v1);
                if t > max_s || v1 <= 0.0 && t > h {
                    return Err(CarrierError::field(
                        "insertion.airjet",
                        format!(
                            "the yarn's tip does not reach the far selvedge within {:.1} ms (it is {:.1} mm from the \
                             main nozzle at {:.3} m/s): faster or longer jets, or a closer relay pitch",
                            max_s * 1e3,
                            x * 1e3,
                            v
                        ),
                    ));
                }
                each(&TipPoint { t_s: t, x_m: x, v_m_s: v, air_m_s: p.air(x) });
            }
            ends.push(t);
        }
        each(&TipPoint { t_s: t, x_m: x, v_m_s: v, air_m_s: self.air(x) });
        Ok(ends)
    }

    /// The flight's points (every integration step) at `speed`, for plots; the flight may take
    /// at most one turn of the main shaft.
    pub fn trajectory(&self, speed: ShaftSpeed) -> Result<Vec<TipPoint>, CarrierError> {
        let mut out = Vec::new();
        self.fly(60.0 / speed.rpm(), |p| out.push(*p))?;
        Ok(out)
    }

    /// The figures at `speed`. Fails when the tip takes more than a turn of the main shaft.
    pub fn report(&self, speed: ShaftSpeed) -> Result<AirjetReport, CarrierError> {
        let deg_per_s = 6.0 * speed.rpm();
        let mut last = TipPoint { t_s: 0.0, x_m: 0.0, v_m_s: 0.0, air_m_s: 0.0 };
        let mut peak = 0.0f64;
        let ends = self.fly(60.0 / speed.rpm(), |p| {
            peak = peak.max(p.v_m_s);
            last = *p;
        })?;
        // The entering selvedge is a cut: the time the tip ends the stretch that ends there.
        let entry_t = self.pieces.iter().position(|p| p.x1 == self.reed_entry_m).map_or(0.0, |i| ends[i]);
        let angle = |t: f64| self.launch_deg + deg_per_s * t;
        let groups = self.nozzles_m.len() / self.per_group;
        let mut plan: Vec<RelayOpen> = Vec::new();
        for (i, p) in self.pieces.iter().enumerate() {
            if let Jet::Relay(j) = p.jet {
                let g = j / self.per_group + 1;
                let start = if i == 0 { 0.0 } else { ends[i - 1] };
                match plan.last_mut() {
                    Some(o) if o.group == g => o.close_deg = angle(ends[i]),
                    _ => plan.push(RelayOpen { group: g, open_deg: angle(start), close_deg: angle(ends[i]) }),
                }
            }
        }
        let open_deg: f64 = plan.iter().map(|o| o.close_deg - o.open_deg).sum();
        Ok(AirjetReport {
            speed_rpm: speed.rpm(),
            launch_deg: self.launch_deg,
            reed_entry_deg: angle(entry_t),
            arrival_deg: angle(last.t_s),
            flight_time_ms: last.t_s * 1e3,
            tip_speed_at_exit_m_s: last.v_m_s,
            peak_tip_speed_m_s: peak,
            relay_plan: plan,
            relay_open_ms: open_deg / deg_per_s * 1e3,
            relay_open_deg: open_deg,
            groups,
        })
    }

    /// The stretches of one formula: (from, to, m from the nozzle's exit) and the group whose jet
    /// leads there (0: the main jet), for tests and plots.
    pub fn stretches(&self) -> Vec<(f64, f64, usize)> {
        self.pieces
            .iter()
            .map(|p| {
                let g = match p.jet {
                    Jet::Main => 0,
                    Jet::Relay(j) => j / self.per_group + 1,
                };
                (p.x0, p.x1, g)
            })
            .collect()
    }
}
