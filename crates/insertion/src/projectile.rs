//! Torsion-bar projectile picking (the Sulzer type): the bar's energy, the launch, the flight
//! across the reed and the receiver's brake.
//!
//! **The bar.** A round torsion bar of diameter `d`, free length `ℓ` and shear modulus `G` has the
//! torsional stiffness `k = G·J/ℓ`, `J = π·d⁴/32` (the polar second moment of a solid round bar);
//! `bar_stiffness_n_m_per_rad` gives `k` directly instead. Twisted through `φ` it stores
//! `E = ½·k·φ²`.
//!
//! **The launch.** The picking lever turns with the bar and throws the projectile; a share `η`
//! (`efficiency`) of the stored energy reaches the moving masses (the rest is lost in the bar's
//! and the lever's damping, the shoe's impact, the lever's bearings). At release the projectile
//! and the lever's tip move together, so the lever's mass referred to its tip, `m_l`
//! (`lever_mass_g`, 0 when left out), shares the energy and is then stopped by the lever's buffer:
//! `½·(m + m_l)·v₀² = η·E`, so `v₀ = √(2·η·E/(m + m_l))`.
//!
//! **The flight** (a model; its two parameters are the user's). In the guide teeth the projectile
//! slides with Coulomb friction on its own weight, `μ·g` (`guide_friction`), and is slowed by air
//! drag `½·ρ·C_d·A·v²` (`drag_area_mm2` = `C_d·A`, `ρ` [`Atmosphere::AIR_DENSITY_KG_M3`]):
//!
//! $$ \dot v = -a - c\,v^2, \qquad a = \mu g, \quad c = \frac{\rho\,C_dA}{2m} $$
//!
//! which integrates in closed form (with `ω = √(a·c)`, `s = √(c/a)`, `θ₀ = atan(v₀·s)`):
//! `v(t) = tan(θ₀ − ω·t)/s`, `x(t) = ln(cos(θ₀ − ω·t)/cos θ₀)/c`, `v²(x) = v₀²·e^{−2cx} − (a/c)·(1 −
//! e^{−2cx})` and `t(x) = (θ₀ − atan(v(x)·s))/ω`; the limits `a = 0` and `c = 0` have their own
//! closed forms. The formulas are written with `expm1`, `ln1p` and the difference of arctangents
//! so that they hold their accuracy when `c·x` or `a/v²` is small. The flight runs from the
//! launch (the projectile's head `run_in_mm` before the entering selvedge) until the head reaches
//! the brake, `run_in + W + L + run_out` away (`W` the reed space, `L` the projectile's length: the
//! projectile is out of the shed when its tail passes the far selvedge, `run_out_mm` further
//! on its head enters the brake).
//!
//! **On the main shaft.** The projectile leaves at `launch_deg`; at `n` rpm the shaft turns `6·n`
//! degrees a second, so it arrives at `launch_deg + 6·n·t_flight` and is in the shed between the
//! angles at which its head passes the entering selvedge and its tail the far one.
//!
//! **The receiver.** The brake stops the projectile over `brake_mm` with a constant force:
//! `F = m·v²/(2·s_b)`, energy `½·m·v²`, time `2·s_b/v`.

use loomkin_units::{Field, Range, ShaftSpeed};
use serde::{Deserialize, Serialize};

use crate::Atmosphere;

/// A wrong projectile or air-jet description: the one [`InsertionError`](crate::InsertionError)
/// (the name kept for the projectile's and the air jet's callers).
pub type CarrierError = crate::InsertionError;

/// The `[insertion.projectile]` table: the torsion bar, the projectile, its flight and brake.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProjectileTable {
    /// Torsion bar diameter, mm ([`ProjectileTable::BAR_DIAMETER_MM`]).
    #[serde(default)]
    pub bar_diameter_mm: Option<f64>,
    /// Torsion bar free length, mm ([`ProjectileTable::BAR_LENGTH_MM`]).
    #[serde(default)]
    pub bar_length_mm: Option<f64>,
    /// Shear modulus of the bar, GPa ([`ProjectileTable::SHEAR_MODULUS_GPA`]).
    #[serde(default)]
    pub shear_modulus_gpa: Option<f64>,
    /// The bar's stiffness given directly, N·m/rad ([`ProjectileTable::BAR_STIFFNESS_N_M_PER_RAD`]).
    #[serde(default)]
    pub bar_stiffness_n_m_per_rad: Option<f64>,
    /// Twist of the bar before the pick, deg ([`ProjectileTable::TWIST_DEG`]).
    pub twist_deg: f64,
    /// Share of the stored energy that reaches the moving masses ([`ProjectileTable::EFFICIENCY`]).
    pub efficiency: f64,
    /// Projectile mass, g ([`ProjectileTable::PROJECTILE_MASS_G`]).
    pub projectile_mass_g: f64,
    /// The picking lever's mass referred to its tip, g ([`ProjectileTable::LEVER_MASS_G`]).
    #[serde(default)]
    pub lever_mass_g: Option<f64>,
    /// Coulomb friction coefficient in the guide teeth ([`ProjectileTable::GUIDE_FRICTION`]).
    pub guide_friction: f64,
    /// Drag coefficient times frontal area, mm² ([`ProjectileTable::DRAG_AREA_MM2`]).
    pub drag_area_mm2: f64,
    /// Air density, kg/m³ ([`Atmosphere::AIR_DENSITY_KG_M3`]).
    #[serde(default)]
    pub air_density_kg_m3: Option<f64>,
    /// The head's run from the launch to the entering selvedge, mm ([`ProjectileTable::RUN_IN_MM`]).
    #[serde(default)]
    pub run_in_mm: Option<f64>,
    /// From the tail passing the far selvedge to the head entering the brake, mm
    /// ([`ProjectileTable::RUN_OUT_MM`]).
    #[serde(default)]
    pub run_out_mm: Option<f64>,
    /// Braking distance in the receiver, mm ([`ProjectileTable::BRAKE_MM`]).
    pub brake_mm: f64,
    /// Main-shaft angle of the launch, deg ([`ProjectileTable::LAUNCH_DEG`]).
    pub launch_deg: f64,
}

impl ProjectileTable {
    /// `bar_diameter_mm`: 0 < d ≤ 100 mm.
    pub const BAR_DIAMETER_MM: Field = Field::new(
        "bar_diameter_mm",
        Range::open_closed(0.0, 100.0, "mm"),
        "Torsion bar diameter: 0 < d ≤ 100 mm (picking bars are 10–20 mm; give bar_stiffness_n_m_per_rad \
         instead for a bar that is not a solid round one).",
    );
    /// `bar_length_mm`: 0 < ℓ ≤ 5000 mm.
    pub const BAR_LENGTH_MM: Field = Field::new(
        "bar_length_mm",
        Range::open_closed(0.0, 5000.0, "mm"),
        "Torsion bar free length, between its clamp and the picking lever: 0 < ℓ ≤ 5000 mm.",
    );
    /// `shear_modulus_gpa`: 0 < G ≤ 500 GPa, default 80 GPa.
    pub const SHEAR_MODULUS_GPA: Field = Field::new(
        "shear_modulus_gpa",
        Range::open_closed(0.0, 500.0, "GPa"),
        "Shear modulus of the bar's material: 0 < G ≤ 500 GPa; 80 GPa (spring steel) when left out.",
    )
    .with_default(80.0);
    /// `bar_stiffness_n_m_per_rad`: 0 < k ≤ 10⁶ N·m/rad.
    pub const BAR_STIFFNESS_N_M_PER_RAD: Field = Field::new(
        "bar_stiffness_n_m_per_rad",
        Range::open_closed(0.0, 1e6, "N·m/rad"),
        "The bar's torsional stiffness given directly, instead of its diameter and length: 0 < k ≤ 1000000 \
         N·m/rad.",
    );
    /// `twist_deg`: 0 < φ ≤ 90°.
    pub const TWIST_DEG: Field = Field::new(
        "twist_deg",
        Range::open_closed(0.0, 90.0, "deg"),
        "Twist of the bar before the pick: 0 < φ ≤ 90° (picking bars are twisted some 20–40°; past 90° a \
         bar of useful diameter yields).",
    );
    /// `efficiency`: 0 < η ≤ 1.
    pub const EFFICIENCY: Field = Field::new(
        "efficiency",
        Range::open_closed(0.0, 1.0, ""),
        "Share of the bar's stored energy that reaches the projectile and the lever: 0 < η ≤ 1.",
    );
    /// `projectile_mass_g`: 0 < m ≤ 1000 g.
    pub const PROJECTILE_MASS_G: Field = Field::new(
        "projectile_mass_g",
        Range::open_closed(0.0, 1000.0, "g"),
        "Projectile mass: 0 < m ≤ 1000 g (steel projectiles weigh about 40 g, light-alloy ones about 15 g).",
    );
    /// `lever_mass_g`: 0 ≤ m_l ≤ 10⁴ g, default 0.
    pub const LEVER_MASS_G: Field = Field::new(
        "lever_mass_g",
        Range::closed(0.0, 1e4, "g"),
        "The picking lever's moving mass referred to its tip (its inertia about the bar's axis over the \
         tip's radius squared): 0 ≤ m_l ≤ 10000 g; it shares the launch energy and is stopped by the lever's \
         buffer. 0 when left out.",
    )
    .with_default(0.0);
    /// `guide_friction`: 0 ≤ μ ≤ 2.
    pub const GUIDE_FRICTION: Field = Field::new(
        "guide_friction",
        Range::closed(0.0, 2.0, ""),
        "Coulomb friction coefficient of the projectile in the guide teeth, on its own weight (deceleration \
         μ·g): 0 ≤ μ ≤ 2.",
    );
    /// `drag_area_mm2`: 0 ≤ C_d·A ≤ 10⁵ mm².
    pub const DRAG_AREA_MM2: Field = Field::new(
        "drag_area_mm2",
        Range::closed(0.0, 1e5, "mm²"),
        "Drag coefficient times frontal area of the projectile, C_d·A: 0 ≤ C_d·A ≤ 100000 mm² (a 14 × 6 mm \
         projectile with C_d ≈ 1 has about 84 mm²).",
    );
    /// `run_in_mm`: 0 ≤ s ≤ 5000 mm, default 0.
    pub const RUN_IN_MM: Field = Field::new(
        "run_in_mm",
        Range::closed(0.0, 5000.0, "mm"),
        "The projectile head's run from the launch to the entering selvedge: 0 ≤ s ≤ 5000 mm; 0 when left out.",
    )
    .with_default(0.0);
    /// `run_out_mm`: 0 ≤ s ≤ 5000 mm, default 0.
    pub const RUN_OUT_MM: Field = Field::new(
        "run_out_mm",
        Range::closed(0.0, 5000.0, "mm"),
        "From the projectile's tail passing the far selvedge to its head entering the brake: 0 ≤ s ≤ 5000 mm; \
         0 when left out.",
    )
    .with_default(0.0);
    /// `brake_mm`: 0 < s_b ≤ 1000 mm.
    pub const BRAKE_MM: Field = Field::new(
        "brake_mm",
        Range::open_closed(0.0, 1000.0, "mm"),
        "Braking distance in the receiver, at a constant force: 0 < s_b ≤ 1000 mm.",
    );
    /// `launch_deg`: 0 ≤ φ < 360°.
    pub const LAUNCH_DEG: Field = Field::new(
        "launch_deg",
        Range::closed_open(0.0, 360.0, "deg"),
        "Main-shaft angle at which the projectile leaves the picking shoe: 0 ≤ φ < 360°.",
    );
}

/// The flight `v̇ = −a − c·v²` from `v₀` in closed form (module notes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flight {
    /// Launch speed, m/s.
    pub v0: f64,
    /// Constant deceleration (guide friction), m/s².
    pub a: f64,
    /// Drag per unit mass and speed squared, 1/m.
    pub c: f64,
}

impl Flight {
    /// Speed at time `t` (s) after the launch, m/s (negative past the stop: the formula's
    /// continuation, not a motion).
    pub fn v_at(&self, t: f64) -> f64 {
        let (v0, a, c) = (self.v0, self.a, self.c);
        match (a > 0.0, c > 0.0) {
            (true, true) => {
                let (w, s) = ((a * c).sqrt(), (c / a).sqrt());
                ((v0 * s).atan() - w * t).tan() / s
            }
            (true, false) => v0 - a * t,
            (false, true) => v0 / (1.0 + c * v0 * t),
            (false, false) => v0,
        }
    }

    /// Distance from the launch at time `t` (s), m; valid up to the stop.
    pub fn x_at(&self, t: f64) -> f64 {
        let (v0, a, c) = (self.v0, self.a, self.c);
        match (a > 0.0, c > 0.0) {
            (true, true) => {
                // ln(cos(θ₀ − ωt)/cos θ₀) = ln(1 + tan θ₀·sin ωt − 2·sin²(ωt/2)).
                let (w, s) = ((a * c).sqrt(), (c / a).sqrt());
                let h = (0.5 * w * t).sin();
                ((v0 * s) * (w * t).sin() - 2.0 * h * h).ln_1p() / c
            }
            (true, false) => v0 * t - 0.5 * a * t * t,
            (false, true) => (c * v0 * t).ln_1p() / c,
            (false, false) => v0 * t,
        }
    }

    /// Speed squared at distance `x` (m) from the launch, m²/s² (negative: it stops before).
    pub fn v2_at_x(&self, x: f64) -> f64 {
        self.v0 * self.v0 - self.v2_lost(x)
    }

    /// `v₀² − v²(x)`, written without the difference (`−expm1(−2cx)·(v₀² + a/c)`, or `2·a·x`).
    fn v2_lost(&self, x: f64) -> f64 {
        let (v0, a, c) = (self.v0, self.a, self.c);
        if c > 0.0 { -(-2.0 * c * x).exp_m1() * (v0 * v0 + a / c) } else { 2.0 * a * x }
    }

    /// The distance at which it stops, m (infinite without friction).
    pub fn stop_distance_m(&self) -> f64 {
        let (v0, a, c) = (self.v0, self.a, self.c);
        match (a > 0.0, c > 0.0) {
            (true, true) => (c * v0 * v0 / a).ln_1p() / (2.0 * c),
            (true, false) => v0 * v0 / (2.0 * a),
            _ => f64::INFINITY,
        }
    }

    /// Time to reach `x` (m) from the launch, s; `x` must lie before the stop.
    pub fn t_at_x(&self, x: f64) -> f64 {
        let (v0, a, c) = (self.v0, self.a, self.c);
        let lost = self.v2_lost(x);
        let v = (v0 * v0 - lost).max(0.0).sqrt();
        let dv = lost / (v0 + v);
        match (a > 0.0, c > 0.0) {
            // atan(v₀s) − atan(vs) = atan((v₀ − v)·s/(1 + v₀·v·s²)), both arguments ≥ 0.
            (true, true) => {
                let (w, s) = ((a * c).sqrt(), (c / a).sqrt());
                (dv * s / (1.0 + v0 * v * s * s)).atan() / w
            }
            (true, false) => dv / a,
            (false, true) => (c * x).exp_m1() / (c * v0),
            (false, false) => x / v0,
        }
    }
}

/// A checked torsion-bar picking across a reed space.
#[derive(Debug, Clone, PartialEq)]
pub struct Projectile {
    /// The table as checked (defaults filled).
    pub table: ProjectileTable,
    /// The bar's torsional stiffness, N·m/rad.
    pub stiffness_n_m_per_rad: f64,
    /// Projectile mass, kg.
    pub mass_kg: f64,
    /// Lever mass at its tip, kg.
    pub lever_mass_kg: f64,
    /// The flight from the launch.
    pub flight: Flight,
    /// The head's run to the entering selvedge, m.
    pub run_in_m: f64,
    /// Reed space, m.
    pub reed_width_m: f64,
    /// Projectile length, m.
    pub length_m: f64,
    /// From the tail at the far selvedge to the head at the brake, m.
    pub run_out_m: f64,
    /// Braking distance, m.
    pub brake_m: f64,
}

/// The projectile's figures at a loom speed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ProjectileReport {
    /// Loom speed, rpm.
    pub speed_rpm: f64,
    /// The bar's torsional stiffness, N·m/rad.
    pub bar_stiffness_n_m_per_rad: f64,
    /// Energy stored in the twisted bar, ½·k·φ², J.
    pub stored_energy_j: f64,
    /// The projectile's kinetic energy at launch, J.
    pub launch_energy_j: f64,
    /// Launch speed, m/s.
    pub projectile_speed_m_s: f64,
    /// From the launch to the brake, mm.
    pub flight_distance_mm: f64,
    /// Flight time from the launch to the brake, ms.
    pub flight_time_ms: f64,
    /// Speed entering the brake, m/s.
    pub arrival_speed_m_s: f64,
    /// Main-shaft angle of the launch, deg.
    pub launch_deg: f64,
    /// Main-shaft angle at which it enters the brake, deg (past 360°: in the next turn).
    pub arrival_deg: f64,
    /// Angle at which its head passes the entering selvedge, deg.
    pub shed_entry_deg: f64,
    /// Angle at which its tail passes the far selvedge, deg.
    pub shed_exit_deg: f64,
    /// Mean speed over the reed space plus its length, m/s (for `insert budget`).
    pub mean_speed_in_shed_m_s: f64,
    /// Energy lost to guide friction over the flight, J.
    pub friction_energy_j: f64,
    /// Energy lost to air drag over the flight, J.
    pub drag_energy_j: f64,
    /// Braking distance, mm.
    pub brake_mm: f64,
    /// The brake's constant force, N.
    pub brake_force_n: f64,
    /// Energy the brake takes, J.
    pub brake_energy_j: f64,
    /// Time to stop in the brake, ms.
    pub brake_time_ms: f64,
}

impl Projectile {
    /// The projectile of a `[insertion.projectile]` table across `reed_width_m`, the projectile
    /// `length_m` long (the file's `carrier_length_mm`); errors name `{prefix}.…`.
    pub fn new(t: &ProjectileTable, reed_width_m: f64, length_m: f64, prefix: &str) -> Result<Self, CarrierError> {
        let name = |k: &str| format!("{prefix}.{k}");
        let k = match (t.bar_stiffness_n_m_per_rad, t.bar_diameter_mm, t.bar_length_mm) {
            (Some(k), None, None) if t.shear_modulus_gpa.is_none() => {
                ProjectileTable::BAR_STIFFNESS_N_M_PER_RAD.check_as(&name("bar_stiffness_n_m_per_rad"), k)?
            }
            (None, Some(d), Some(l)) => {
                let d = ProjectileTable::BAR_DIAMETER_MM.check_as(&name("bar_diameter_mm"), d)? * 1e-3;
                let l = ProjectileTable::BAR_LENGTH_MM.check_as(&name("bar_length_mm"), l)? * 1e-3;
                let g = match t.shear_modulus_gpa {
                    Some(g) => ProjectileTable::SHEAR_MODULUS_GPA.check_as(&name("shear_modulus_gpa"), g)?,
                    None => ProjectileTable::SHEAR_MODULUS_GPA.default_value(),
                };
                torsion_stiffness(g * 1e9, d, l)
            }
            _ => {
                return Err(CarrierError::field(
                    name("bar_stiffness_n_m_per_rad"),
                    "give the bar as bar_diameter_mm and bar_length_mm (with shear_modulus_gpa), or its stiffness \
                     bar_stiffness_n_m_per_rad alone",
                ));
            }
        };
        let twist = ProjectileTable::TWIST_DEG.check_as(&name("twist_deg"), t.twist_deg)?;
        let eta = ProjectileTable::EFFICIENCY.check_as(&name("efficiency"), t.efficiency)?;
        let m = ProjectileTable::PROJECTILE_MASS_G.check_as(&name("projectile_mass_g"), t.projectile_mass_g)? * 1e-3;
        let lever = ProjectileTable::LEVER_MASS_G
            .check_as(&name("lever_mass_g"), ProjectileTable::LEVER_MASS_G.or_default(t.lever_mass_g)?)?
            * 1e-3;
        let mu = ProjectileTable::GUIDE_FRICTION.check_as(&name("guide_friction"), t.guide_friction)?;
        let cda = ProjectileTable::DRAG_AREA_MM2.check_as(&name("drag_area_mm2"), t.drag_area_mm2)? * 1e-6;
        let rho = Atmosphere::AIR_DENSITY_KG_M3
            .check_as(&name("air_density_kg_m3"), Atmosphere::AIR_DENSITY_KG_M3.or_default(t.air_density_kg_m3)?)?;
        let run_in = ProjectileTable::RUN_IN_MM
            .check_as(&name("run_in_mm"), ProjectileTable::RUN_IN_MM.or_default(t.run_in_mm)?)?
            * 1e-3;
        let run_out = ProjectileTable::RUN_OUT_MM
            .check_as(&name("run_out_mm"), ProjectileTable::RUN_OUT_MM.or_default(t.run_out_mm)?)?
            * 1e-3;
        let brake = ProjectileTable::BRAKE_MM.check_as(&name("brake_mm"), t.brake_mm)? * 1e-3;
        let launch = ProjectileTable::LAUNCH_DEG.check_as(&name("launch_deg"), t.launch_deg)?;
        let phi = twist.to_radians();
        let v0 = (2.0 * eta * 0.5 * k * phi * phi / (m + lever)).sqrt();
        let flight = Flight { v0, a: mu * Atmosphere::GRAVITY_M_S2, c: rho * cda / (2.0 * m) };
        let p = Self {
            table: ProjectileTable {
                shear_modulus_gpa: t
                    .shear_modulus_gpa
                    .or(t.bar_diameter_mm.map(|_| ProjectileTable::SHEAR_MODULUS_GPA.default_value())),
                lever_mass_g: Some(lever * 1e3),
                air_density_kg_m3: Some(rho),
                run_in_mm: Some(run_in * 1e3),
                run_out_mm: Some(run_out * 1e3),
                launch_deg: launch,
                ..t.clone()
            },
            stiffness_n_m_per_rad: k,
            mass_kg: m,
            lever_mass_kg: lever,
            flight,
            run_in_m: run_in,
            reed_width_m,
            length_m,
            run_out_m: run_out,
            brake_m: brake,
        };
        let stop = flight.stop_distance_m();
        if stop <= p.flight_distance_m() {
            return Err(CarrierError::field(
                name("twist_deg"),
                format!(
                    "the projectile stops {:.1} mm after the launch, short of the brake {:.1} mm away (launched at \
                     {:.3} m/s): twist the bar more, or lower guide_friction or drag_area_mm2",
                    stop * 1e3,
                    p.flight_distance_m() * 1e3,
                    v0
                ),
            ));
        }
        Ok(p)
    }

    /// From the launch to the brake, m.
    pub fn flight_distance_m(&self) -> f64 {
        self.run_in_m + self.reed_width_m + self.length_m + self.run_out_m
    }

    /// The distances from the launch (m) at which the projectile is in the shed: its head at the
    /// entering selvedge, its tail at the far one.
    pub fn in_shed_m(&self) -> (f64, f64) {
        (self.run_in_m, self.run_in_m + self.reed_width_m + self.length_m)
    }

    /// The projectile's path on the main shaft at `speed`: when it is in the shed and where.
    pub fn path(&self, speed: ShaftSpeed) -> ProjectilePath {
        ProjectilePath {
            flight: self.flight,
            launch_deg: self.table.launch_deg,
            deg_per_s: 6.0 * speed.rpm(),
            run_in_m: self.run_in_m,
            shed_m: self.in_shed_m(),
        }
    }

    /// The figures at `speed`.
    pub fn report(&self, speed: ShaftSpeed) -> ProjectileReport {
        let f = &self.flight;
        let deg_per_s = 6.0 * speed.rpm();
        let d = self.flight_distance_m();
        let t = f.t_at_x(d);
        let v = f.v2_at_x(d).max(0.0).sqrt();
        let (x_in, x_out) = self.in_shed_m();
        let (t_in, t_out) = (f.t_at_x(x_in), f.t_at_x(x_out));
        let phi = self.table.twist_deg.to_radians();
        let stored = 0.5 * self.stiffness_n_m_per_rad * phi * phi;
        let launch_energy = 0.5 * self.mass_kg * f.v0 * f.v0;
        let arrival_energy = 0.5 * self.mass_kg * v * v;
        let friction = self.mass_kg * f.a * d;
        let launch = self.table.launch_deg;
        ProjectileReport {
            speed_rpm: speed.rpm(),
            bar_stiffness_n_m_per_rad: self.stiffness_n_m_per_rad,
            stored_energy_j: stored,
            launch_energy_j: launch_energy,
            projectile_speed_m_s: f.v0,
            flight_distance_mm: d * 1e3,
            flight_time_ms: t * 1e3,
            arrival_speed_m_s: v,
            launch_deg: launch,
            arrival_deg: launch + deg_per_s * t,
            shed_entry_deg: launch + deg_per_s * t_in,
            shed_exit_deg: launch + deg_per_s * t_out,
            mean_speed_in_shed_m_s: (x_out - x_in) / (t_out - t_in),
            friction_energy_j: friction,
            drag_energy_j: launch_energy - arrival_energy - friction,
            brake_mm: self.brake_m * 1e3,
            brake_force_n: arrival_energy / self.brake_m,
            brake_energy_j: arrival_energy,
            brake_time_ms: 2.0 * self.brake_m / v * 1e3,
        }
    }
}

/// The torsional stiffness of a solid round bar, `G·π·d⁴/(32·ℓ)`, N·m/rad (SI inputs).
pub fn torsion_stiffness(shear_modulus_pa: f64, diameter_m: f64, length_m: f64) -> f64 {
    shear_modulus_pa * std::f64::consts::PI * diameter_m.powi(4) / (32.0 * length_m)
}

/// A projectile's flight on the main shaft at one loom speed: the carrier path of the clearance
/// check (`loomkin_loom::insertion::CarrierPath`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProjectilePath {
    /// The flight from the launch.
    pub flight: Flight,
    /// Launch angle, deg.
    pub launch_deg: f64,
    /// Main-shaft degrees per second.
    pub deg_per_s: f64,
    /// The head's run to the entering selvedge, m.
    pub run_in_m: f64,
    /// The distances from the launch between which it is in the shed, m.
    pub shed_m: (f64, f64),
}

impl ProjectilePath {
    /// The angles (deg) between which the projectile is in the shed.
    pub fn in_shed_deg(&self) -> (f64, f64) {
        let at = |x: f64| self.launch_deg + self.deg_per_s * self.flight.t_at_x(x);
        (at(self.shed_m.0), at(self.shed_m.1))
    }

    /// The head's position from the entering selvedge at `angle_deg`, m (negative before it
    /// reaches the selvedge). From the entry angle of [`ProjectilePath::in_shed_deg`] on it is
    /// never below +0: that angle is root-found, and the flight gives back the run-in there only
    /// to rounding (a head at −1e-16 m would print as "-0.0 mm from the entering selvedge").
    pub fn position_m(&self, angle_deg: f64) -> f64 {
        let x = self.flight.x_at((angle_deg - self.launch_deg) / self.deg_per_s) - self.run_in_m;
        if x <= 0.0 && angle_deg >= self.in_shed_deg().0 { 0.0 } else { x }
    }
}
