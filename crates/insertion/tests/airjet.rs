//! The air jet: the flight at constant air against its closed form, the full model against
//! DOP853, the field's stretches, the relay plan, monotonicity and the refusals.

use differential_equations::prelude::{ExplicitRungeKutta, IVP, ODE};
use loomkin_insertion::{Airjet, AirjetTable};
use loomkin_units::ShaftSpeed;
use proptest::prelude::*;

/// 20 relay groups of two nozzles 48 mm apart across 1.9 m.
fn table() -> AirjetTable {
    AirjetTable {
        yarn_tex: 20.0,
        yarn_diameter_mm: 0.25,
        tail_mm: 600.0,
        main_speed_m_s: 250.0,
        main_core_mm: 40.0,
        reed_entry_mm: 100.0,
        relay_speed_m_s: 200.0,
        relay_core_mm: 25.0,
        relay_pitch_mm: 48.0,
        first_relay_mm: Some(20.0),
        nozzles_per_group: 2,
        groups: 20,
        launch_deg: 80.0,
        ..Default::default()
    }
}

fn rpm(n: f64) -> ShaftSpeed {
    ShaftSpeed::from_rpm(n).unwrap()
}

/// At constant air `V` everywhere (both jets' cores past the far selvedge), a constant `C_f` and
/// no draw-off, `v̇ = K·(V − v)²` from rest: `v = V − V/(1 + K·V·t)`, `x = V·t − ln(1 + K·V·t)/K`.
/// The arrival (x = reed entry + W, solved by Newton) and the exit speed at 1e-10.
#[test]
fn constant_air_against_the_closed_form() {
    for (v_air, cf, width) in [(100.0, 0.03, 1.9), (250.0, 0.05, 3.6), (60.0, 0.02, 0.8)] {
        let t = AirjetTable {
            main_speed_m_s: v_air,
            relay_speed_m_s: v_air,
            main_core_mm: 1e4,
            relay_core_mm: 1e4,
            cf_floor: Some(cf),
            cf_scale_m_s: Some(0.0),
            draw_off: Some(0.0),
            ..table()
        };
        let a = Airjet::new(&t, width, "a").unwrap();
        let r = a.report(rpm(200.0)).unwrap();
        let k = a.k * cf;
        let d = 0.1 + width;
        let x = |t: f64| v_air * t - (k * v_air * t).ln_1p() / k;
        let v = |t: f64| v_air - v_air / (1.0 + k * v_air * t);
        let mut time = d / v_air;
        for _ in 0..50 {
            time -= (x(time) - d) / v(time);
        }
        let got = r.flight_time_ms * 1e-3;
        assert!((got / time - 1.0).abs() < 1e-10, "V {v_air}: {got} vs {time}");
        assert!(
            (r.tip_speed_at_exit_m_s / v(time) - 1.0).abs() < 1e-10,
            "V {v_air}: {} vs {}",
            r.tip_speed_at_exit_m_s,
            v(time)
        );
        assert!((r.arrival_deg - (80.0 + 1200.0 * got)).abs() < 1e-9);
    }
}

/// The full model (Uno's C_f, the 1/distance jets, the relay nozzles, the draw-off) against
/// DOP853 at 1e-13: in time from rest for 0.1 ms, then in position stretch by stretch (state t, v;
/// dv/dx = v̇/v), each stretch's air by its own formula (read just inside it). Arrival time and
/// exit speed agree within 1e-10.
#[test]
fn full_model_against_dop853() {
    for t in [table(), AirjetTable { groups: 5, relay_pitch_mm: 90.0, nozzles_per_group: 4, ..table() }] {
        let a = Airjet::new(&t, 1.9, "a").unwrap();
        let r = a.report(rpm(600.0)).unwrap();
        let [cf0, cf1, cf2] = a.cf;
        let acc = |air: f64, x: f64, v: f64| {
            let w = air - v;
            a.k * (cf0 + cf1 / (w.abs() + cf2)) * w * w.abs() - a.draw_off * v * v / (a.tail_m + x)
        };
        let stretches = a.stretches();
        let (s0, s1, _) = stretches[0];
        let inside = |x: f64, lo: f64, hi: f64| a.air(x.clamp(lo + 1e-12 * hi, hi - 1e-12 * hi));
        struct InTime<'a>(&'a dyn Fn(f64, f64) -> f64);
        impl ODE<f64, [f64; 2]> for InTime<'_> {
            fn diff(&self, _t: f64, y: &[f64; 2], d: &mut [f64; 2]) {
                d[0] = y[1];
                d[1] = (self.0)(y[0], y[1]);
            }
        }
        struct InPlace<'a>(&'a dyn Fn(f64, f64) -> f64);
        impl ODE<f64, [f64; 2]> for InPlace<'_> {
            fn diff(&self, x: f64, y: &[f64; 2], d: &mut [f64; 2]) {
                d[0] = 1.0 / y[1];
                d[1] = (self.0)(x, y[1]) / y[1];
            }
        }
        let method = || ExplicitRungeKutta::dop853().rtol(1e-13).atol(1e-15);
        let f0 = |x: f64, v: f64| acc(inside(x, s0, s1), x, v);
        let t0 = 1e-4;
        let sol = IVP::ode(&InTime(&f0), 0.0, t0, [0.0, 0.0]).method(method()).solve().unwrap();
        let [x0, v0] = *sol.y.last().unwrap();
        assert!(x0 < s1, "{x0}");
        let mut state = [t0, v0];
        let mut from = x0;
        for &(lo, hi, _) in &stretches {
            if hi <= from {
                continue;
            }
            let f = |x: f64, v: f64| acc(inside(x, lo, hi), x, v);
            let sol = IVP::ode(&InPlace(&f), from, hi, state).method(method()).solve().unwrap();
            state = *sol.y.last().unwrap();
            from = hi;
        }
        let [time, v] = state;
        assert!((r.flight_time_ms * 1e-3 / time - 1.0).abs() < 1e-10, "{} vs {time}", r.flight_time_ms * 1e-3);
        assert!((r.tip_speed_at_exit_m_s / v - 1.0).abs() < 1e-10, "{} vs {v}", r.tip_speed_at_exit_m_s);
    }
}

/// The field: stretches tile the channel from the nozzle to the far selvedge; on each the leading
/// jet is the faster one (checked against the field at points inside); every relay group in the
/// plan is the one leading where it is open, groups in order, open before closed, and the open
/// time is the time the tip spends on stretches relay jets lead.
#[test]
fn stretches_and_the_plan() {
    let a = Airjet::new(&table(), 1.9, "a").unwrap();
    let s = a.stretches();
    assert_eq!(s[0].0, 0.0);
    assert!((s.last().unwrap().1 - 2.0).abs() < 1e-15);
    for w in s.windows(2) {
        assert_eq!(w[0].1, w[1].0);
    }
    for &(lo, hi, g) in &s {
        for f in [0.1, 0.5, 0.9] {
            let x = lo + f * (hi - lo);
            let (m, r) = (a.main_air(x), a.relay_air(x));
            assert_eq!(g == 0, m >= r, "{lo}..{hi} lead {g}: main {m} relay {r}");
        }
    }
    let r = a.report(rpm(800.0)).unwrap();
    assert_eq!(r.relay_plan.len(), 20);
    for (i, o) in r.relay_plan.iter().enumerate() {
        assert_eq!(o.group, i + 1);
        assert!(o.open_deg < o.close_deg);
    }
    let sum: f64 = r.relay_plan.iter().map(|o| o.close_deg - o.open_deg).sum();
    assert!((sum - r.relay_open_deg).abs() < 1e-9);
    // Here relay jets lead from the first nozzle to the far selvedge without a gap: the plan's
    // open time is the tip's time from the first nozzle to the arrival.
    let first = r.relay_plan[0].open_deg;
    assert!((r.relay_open_deg - (r.arrival_deg - first)).abs() < 1e-9);
    assert!(r.launch_deg < r.reed_entry_deg && r.reed_entry_deg < first);
}

#[test]
fn refusals_name_the_field() {
    let e = Airjet::new(&AirjetTable { groups: 0, ..table() }, 1.9, "insertion.airjet").unwrap_err();
    assert!(e.to_string().starts_with("insertion.airjet.groups = 0 is out of range"), "{e}");
    let e = Airjet::new(&AirjetTable { yarn_tex: -1.0, ..table() }, 1.9, "insertion.airjet").unwrap_err();
    assert!(e.to_string().starts_with("insertion.airjet.yarn_tex = -1 is out of range"), "{e}");
    // A weak jet over a wide reed: the tip does not arrive within a turn.
    let weak = AirjetTable { main_speed_m_s: 5.0, relay_speed_m_s: 5.0, groups: 2, ..table() };
    let e = Airjet::new(&weak, 5.0, "insertion.airjet").unwrap().report(rpm(1000.0)).unwrap_err();
    assert!(e.to_string().starts_with("insertion.airjet: the yarn's tip does not reach the far selvedge"), "{e}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    /// A wider reed never arrives earlier; faster relay jets never arrive later.
    #[test]
    fn monotone(width in 0.8f64..1.9, wider in 0.0f64..0.1, relay in 120.0f64..250.0, faster in 0.0f64..30.0) {
        let at = |t: &AirjetTable, w: f64| Airjet::new(t, w, "a").unwrap().report(rpm(500.0)).unwrap().flight_time_ms;
        let t = AirjetTable { relay_speed_m_s: relay, ..table() };
        prop_assert!(at(&t, width + wider) >= at(&t, width));
        let f = AirjetTable { relay_speed_m_s: relay + faster, ..table() };
        prop_assert!(at(&f, width) <= at(&t, width));
    }
}
