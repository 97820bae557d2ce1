//! Torsion-bar projectile picking: the closed-form flight against an adaptive ODE, the energy
//! balance, the bar's stiffness, monotonicity, the brake and the refusals.

use differential_equations::prelude::{ExplicitRungeKutta, IVP, ODE};
use loomkin_insertion::{Atmosphere, Flight, Projectile, ProjectileTable, torsion_stiffness};
use loomkin_units::ShaftSpeed;
use proptest::prelude::*;

/// A Sulzer-like picking: a 12 mm bar 700 mm long twisted 30°, a 40 g projectile.
fn table() -> ProjectileTable {
    ProjectileTable {
        bar_diameter_mm: Some(12.0),
        bar_length_mm: Some(700.0),
        twist_deg: 30.0,
        efficiency: 0.5,
        projectile_mass_g: 40.0,
        lever_mass_g: Some(20.0),
        guide_friction: 0.4,
        drag_area_mm2: 84.0,
        run_in_mm: Some(250.0),
        run_out_mm: Some(150.0),
        brake_mm: 80.0,
        launch_deg: 100.0,
        ..Default::default()
    }
}

fn projectile(t: &ProjectileTable) -> Projectile {
    Projectile::new(t, 1.9, 0.09, "insertion.projectile").unwrap()
}

struct Decel(Flight);

impl ODE<f64, [f64; 2]> for Decel {
    fn diff(&self, _t: f64, y: &[f64; 2], dydt: &mut [f64; 2]) {
        dydt[0] = y[1];
        dydt[1] = -self.0.a - self.0.c * y[1] * y[1];
    }
}

/// (x, v) after `t` seconds by DOP853 at 1e-13.
fn ode(f: Flight, t: f64) -> [f64; 2] {
    let method = ExplicitRungeKutta::dop853().rtol(1e-13).atol(1e-15);
    let sol = IVP::ode(&Decel(f), 0.0, t, [0.0, f.v0]).method(method).solve().unwrap();
    *sol.y.last().unwrap()
}

/// The closed forms x(t), v(t), v²(x), t(x) against an adaptive integration of v̇ = −a − c·v², in
/// every branch (friction and drag, either alone, neither), at 1e-10 relative.
#[test]
fn closed_form_flight_matches_the_ode() {
    for (a, c) in [(3.9, 1.26e-3), (3.9, 0.0), (0.0, 1.26e-3), (0.0, 0.0), (40.0, 0.05), (1e-6, 1e-7)] {
        let f = Flight { v0: 24.0, a, c };
        for t in [0.01, 0.05, 0.1, 0.2] {
            let [x, v] = ode(f, t);
            assert!((f.x_at(t) / x - 1.0).abs() < 1e-10, "x: a {a} c {c} t {t}: {} vs {x}", f.x_at(t));
            assert!((f.v_at(t) / v - 1.0).abs() < 1e-10, "v: a {a} c {c} t {t}: {} vs {v}", f.v_at(t));
            assert!((f.v2_at_x(x) / (v * v) - 1.0).abs() < 1e-10, "v²(x): a {a} c {c} t {t}");
            assert!((f.t_at_x(x) / t - 1.0).abs() < 1e-10, "t(x): a {a} c {c} t {t}: {}", f.t_at_x(x));
        }
        if a > 0.0 {
            // At the stop distance the speed is zero.
            assert!(f.v2_at_x(f.stop_distance_m()).abs() < 1e-9 * f.v0 * f.v0, "a {a} c {c}");
        }
    }
}

/// ½·k·φ² at the bar, η of it shared by projectile and lever at one speed; over the flight the
/// projectile's kinetic energy lost equals the friction work m·a·D plus the drag work ∫ m·c·v² dx
/// (integrated here by Simpson's rule on v²(x), an independent route to the report's difference).
#[test]
fn energy_balance() {
    let t = table();
    let p = projectile(&t);
    let r = p.report(ShaftSpeed::from_rpm(400.0).unwrap());
    let k = torsion_stiffness(80e9, 0.012, 0.7);
    assert!((r.bar_stiffness_n_m_per_rad / k - 1.0).abs() < 1e-15);
    let phi = 30f64.to_radians();
    assert!((r.stored_energy_j - 0.5 * k * phi * phi).abs() < 1e-12 * r.stored_energy_j);
    let v0 = r.projectile_speed_m_s;
    assert!((0.5 * (0.040 + 0.020) * v0 * v0 / (0.5 * r.stored_energy_j) - 1.0).abs() < 1e-14);
    assert!((r.launch_energy_j - 0.5 * 0.04 * v0 * v0).abs() < 1e-14);
    let d = r.flight_distance_mm * 1e-3;
    assert!((d - (0.25 + 1.9 + 0.09 + 0.15)).abs() < 1e-15);
    let f = p.flight;
    let n = 2000;
    let h = d / n as f64;
    let simpson: f64 = (0..=n)
        .map(|i| {
            let w = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            w * f.v2_at_x(i as f64 * h)
        })
        .sum::<f64>()
        * h
        / 3.0;
    let drag = p.mass_kg * f.c * simpson;
    assert!((r.drag_energy_j / drag - 1.0).abs() < 1e-9, "{} vs {drag}", r.drag_energy_j);
    assert!((r.friction_energy_j - 0.04 * 0.4 * Atmosphere::GRAVITY_M_S2 * d).abs() < 1e-14);
    // The brake: force × distance is the arrival energy; the time at a constant deceleration.
    assert!((r.brake_force_n * 0.08 / r.brake_energy_j - 1.0).abs() < 1e-14);
    assert!((r.brake_energy_j - 0.5 * 0.04 * r.arrival_speed_m_s.powi(2)).abs() < 1e-14);
    let decel = r.brake_force_n / 0.04;
    assert!((r.brake_time_ms * 1e-3 * decel / r.arrival_speed_m_s - 1.0).abs() < 1e-12);
}

/// The bar's stiffness by hand: 80 GPa, 10 mm, 1 m: J = π·10⁻⁸/32 m⁴, k = G·J/ℓ = 78.5398… N·m/rad;
/// the given stiffness gives the same launch.
#[test]
fn bar_stiffness() {
    let k = torsion_stiffness(80e9, 0.010, 1.0);
    assert!((k - 80e9 * std::f64::consts::PI * 1e-8 / 32.0).abs() < 1e-12);
    assert!((k - 78.539_816_339_744_83).abs() < 1e-11);
    let by_size = projectile(&table());
    let given = ProjectileTable {
        bar_diameter_mm: None,
        bar_length_mm: None,
        bar_stiffness_n_m_per_rad: Some(by_size.stiffness_n_m_per_rad),
        ..table()
    };
    assert_eq!(projectile(&given).flight, by_size.flight);
}

/// The angles: arrival at launch + 6·n·t; in the shed from the head at the entering selvedge to
/// the tail at the far one; the path's position at those angles.
#[test]
fn angles_and_path() {
    let p = projectile(&table());
    let speed = ShaftSpeed::from_rpm(400.0).unwrap();
    let r = p.report(speed);
    assert!((r.arrival_deg - (100.0 + 2400.0 * r.flight_time_ms * 1e-3)).abs() < 1e-12);
    let path = p.path(speed);
    let (a, b) = path.in_shed_deg();
    assert_eq!((a, b), (r.shed_entry_deg, r.shed_exit_deg));
    assert!(path.position_m(a).abs() < 1e-12, "{}", path.position_m(a));
    assert!((path.position_m(b) - 1.99).abs() < 1e-12, "{}", path.position_m(b));
    assert!(100.0 < a && a < b && b < r.arrival_deg);
    // The mean speed in the shed lies between the arrival and launch speeds.
    assert!(r.arrival_speed_m_s < r.mean_speed_in_shed_m_s && r.mean_speed_in_shed_m_s < r.projectile_speed_m_s);
}

#[test]
fn refusals_name_the_field() {
    let e =
        Projectile::new(&ProjectileTable { twist_deg: 2.0, ..table() }, 1.9, 0.09, "insertion.projectile").unwrap_err();
    let s = e.to_string();
    assert!(s.starts_with("insertion.projectile.twist_deg: the projectile stops"), "{s}");
    let both = ProjectileTable { bar_stiffness_n_m_per_rad: Some(100.0), ..table() };
    let e = Projectile::new(&both, 1.9, 0.09, "insertion.projectile").unwrap_err();
    assert_eq!(e.field_name(), "insertion.projectile.bar_stiffness_n_m_per_rad");
    let e = Projectile::new(&ProjectileTable { efficiency: 1.5, ..table() }, 1.9, 0.09, "insertion.projectile")
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "insertion.projectile.efficiency = 1.5 is out of range: allowed 0 < insertion.projectile.efficiency ≤ 1"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    /// At its root-found entry angle the head is at the entering selvedge, never behind it by a
    /// rounding (no "-0.0 mm" printed): the position there is +0 or a positive rounding; just
    /// before the entry it is behind the selvedge; and inside the shed it never goes back.
    #[test]
    fn entry_position_has_no_negative_sign(rpm in 100.0f64..600.0, twist in 20.0f64..60.0, reed in 0.5f64..4.0) {
        let p = Projectile::new(&ProjectileTable { twist_deg: twist, ..table() }, reed, 0.09, "p").unwrap();
        let path = p.path(ShaftSpeed::from_rpm(rpm).unwrap());
        let (a, b) = path.in_shed_deg();
        let x = path.position_m(a);
        prop_assert!(x.is_sign_positive() && x < 1e-12, "{x:e}");
        prop_assert_eq!(format!("{:.1}", x * 1e3), "0.0");
        prop_assert!(path.position_m(a - 1e-3 * (b - a)) < 0.0);
        let mut last = x;
        for k in 1..=50 {
            let now = path.position_m(a + (b - a) * k as f64 / 50.0);
            prop_assert!(now >= last, "{now} < {last}");
            last = now;
        }
    }

    /// More twist never arrives later; a wider reed never arrives earlier.
    #[test]
    fn monotone(twist in 10.0f64..60.0, extra in 0.0f64..10.0, reed in 0.5f64..4.0, wider in 0.0f64..1.0) {
        let speed = ShaftSpeed::from_rpm(400.0).unwrap();
        let at = |twist: f64, reed: f64| {
            Projectile::new(&ProjectileTable { twist_deg: twist, ..table() }, reed, 0.09, "p")
                .map(|p| p.report(speed).arrival_deg)
        };
        if let (Ok(a), Ok(b)) = (at(twist, reed), at(twist + extra, reed)) {
            prop_assert!(b <= a, "twist {twist} +{extra}: {a} then {b}");
        }
        if let (Ok(a), Ok(b)) = (at(twist, reed), at(twist, reed + wider)) {
            prop_assert!(b >= a, "reed {reed} +{wider}: {a} then {b}");
        }
    }
}
