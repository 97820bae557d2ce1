//! Compensation: simulating the compensated input gives the designed motion back.

use differential_equations::prelude::{ExplicitRungeKutta, IVP, ODE};
use loomkin_dynamics::{Compensation, Excitation, Follower, Response, Start, compensate, input_excitation};
use loomkin_laws::Cycle;
use loomkin_units::ShaftSpeed;

const HEALD: &str = include_str!("../../../../examples/heald-frame-cycle.toml");

fn designed(rpm: f64) -> Excitation {
    Excitation::from_cycle(&Cycle::from_toml(HEALD).unwrap(), ShaftSpeed::from_rpm(rpm).unwrap())
}

fn x_at(exc: &Excitation, t: f64) -> [f64; 5] {
    let i = exc.piece_at(t);
    let p = &exc.pieces[i];
    p.derivs((t - p.t0).clamp(0.0, p.duration))
}

/// Undamped: the polydyne input, simulated by the closed form, reproduces x to 1e-9 of the stroke.
#[test]
fn undamped_polydyne_gives_x_back() {
    for (rpm, fn_hz, loads) in [(600.0, 54.0, false), (900.0, 80.0, true)] {
        let exc = designed(rpm);
        let mut f = Follower::new(fn_hz, 0.0).unwrap();
        if loads {
            f = f.with_loads(15.0, 4e3, 250.0).unwrap();
        }
        let comp = compensate(&exc, &f).unwrap();
        assert_eq!(comp.designed_class, 2, "modified sine / trapezoid: C² (jerk jumps)");
        assert_eq!(comp.input_class, 0);
        let input = input_excitation(&exc, &comp).unwrap();
        let s0 = comp.eval(0.0);
        let x0 = x_at(&exc, 0.0);
        let r = Response::from_excitation(input, &f, Start::State(x0[0] - s0[0], x0[1] - s0[1]), 2).unwrap();
        let mut worst: f64 = 0.0;
        for i in 0..=2000 {
            let t = r.duration_s() * i as f64 / 2000.0;
            let st = r.state(t);
            let x = x_at(&exc, t % exc.period_s)[0];
            worst = worst.max((st[0] + st[3] - x).abs());
        }
        assert!(worst < 1e-9 * exc.stroke_si, "{rpm} rpm: |x_sim − x| = {worst:e} m");
        // The dwells are quiet.
        assert!(r.summary().residual_amplitude_si < 1e-9 * exc.stroke_si);
    }
}

struct Model<'a> {
    comp: &'a Compensation,
    w: f64,
    z: f64,
}

impl ODE<f64, [f64; 2]> for Model<'_> {
    fn diff(&self, t: f64, x: &[f64; 2], d: &mut [f64; 2]) {
        let s = self.comp.eval(t);
        d[0] = x[1];
        d[1] = -2.0 * self.z * self.w * (x[1] - s[1]) - self.w * self.w * (x[0] - s[0]);
    }
}

/// Damped: the periodic first-order solution, integrated by DOP853 through the model, gives x back.
#[test]
fn damped_compensation_gives_x_back() {
    let exc = designed(700.0);
    let f = Follower::new(60.0, 0.08).unwrap();
    let comp = compensate(&exc, &f).unwrap();
    assert_eq!(comp.input_class, 1);
    // Periodic: the input closes.
    let (a, b) = (comp.eval(0.0)[0], comp.eval(exc.period_s)[0]);
    assert!((a - b).abs() < 1e-12 * exc.stroke_si);
    let model = Model { comp: &comp, w: f.oscillator().omega_n(), z: 0.08 };
    let x0 = x_at(&exc, 0.0);
    let mut y = [x0[0], x0[1]];
    let mut worst: f64 = 0.0;
    for p in &exc.pieces {
        let method = ExplicitRungeKutta::dop853().rtol(1e-13).atol(1e-16).max_steps(1_000_000);
        let sol = IVP::ode(&model, p.t0, p.t0 + p.duration, y).method(method).solve().expect("DOP853 ran");
        let (ts, ys) = sol.into_tuple();
        for (t, x) in ts.iter().zip(&ys) {
            worst = worst.max((x[0] - x_at(&exc, *t)[0]).abs());
        }
        y = *ys.last().unwrap();
    }
    assert!(worst < 1e-9 * exc.stroke_si, "|x_sim − x| = {worst:e} m");
}

/// A designed law whose acceleration jumps (harmonic rise from a dwell) has no undamped compensation.
#[test]
fn refuses_a_jumping_input() {
    let text = HEALD.replace("law = \"modified-sine\"", "law = \"harmonic\"");
    let exc = Excitation::from_cycle(&Cycle::from_toml(&text).unwrap(), ShaftSpeed::from_rpm(600.0).unwrap());
    let e = compensate(&exc, &Follower::new(54.0, 0.0).unwrap()).unwrap_err().to_string();
    assert!(e.contains("x'' jumps") && e.contains("60.0000°"), "{e}");
    // With damping the input is continuous (its velocity jumps): it exists.
    let c = compensate(&exc, &Follower::new(54.0, 0.05).unwrap()).unwrap();
    assert_eq!(c.input_class, 0);
}
