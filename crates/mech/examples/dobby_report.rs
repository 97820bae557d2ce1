//! Prints the figures behind docs/design/dobby.md: task 1 with the paper's ellipse, task 2 with
//! the default law, the α sweep and the round-trip convergence.
//! Run: `cargo run --release -p loomkin-mech --example dobby_report`.

use loomkin_mech::{
    AnalysisOptions, Cam, ModulatorGeometry, OutputLawSpec, SynthesisOptions, Vec2, alpha_sweep, analyze, synthesize,
    wrap_pi,
};

fn opt(v: Option<f64>) -> String {
    v.map(|x| format!("{x:.4}")).unwrap_or_else(|| "—".into())
}

fn main() -> Result<(), loomkin_mech::MechError> {
    let g = ModulatorGeometry::default();
    let a = analyze(&g, &Cam::paper(), &AnalysisOptions { step_deg: 0.1, ..Default::default() })?;
    let c = &a.summary.checks;
    println!("## task 1: ellipse a = 0.366 m, b = 0.577 m, α = θ = 47°, step 0.1°");
    println!(
        "ω6 ∈ [{:.4}, {:.4}] rad/s, ε6 ∈ [{:.4}, {:.4}] rad/s², turn {:.6}°",
        c.omega6_min_rad_s, c.omega6_max_rad_s, c.eps6_min_rad_s2, c.eps6_max_rad_s2, c.phi6_turn_deg
    );
    println!(
        "μ6 max {:.2}° at {:.1}°, μB max {:.2}° at {:.1}°, μC max {:.2}° at {:.1}°",
        c.mu_out_max_deg,
        c.mu_out_max_at_phi2_deg,
        c.mu_b_max_deg,
        c.mu_b_max_at_phi2_deg,
        c.mu_c_max_deg,
        c.mu_c_max_at_phi2_deg
    );
    println!(
        "ρB min {} m, ρC min {} m, |φ3 − φ2| max {:.3}° (limit {:.3}°), admissible α [{:.3}, {:.3}]°, θ ({:.3}, {:.3})°",
        opt(c.rho_b_min_m),
        opt(c.rho_c_min_m),
        a.summary.slot_deviation_max_deg,
        a.summary.slot_deviation_limit_deg,
        a.summary.admissible_alpha_deg[0],
        a.summary.admissible_alpha_deg[1],
        a.summary.admissible_theta_deg[0],
        a.summary.admissible_theta_deg[1]
    );
    let r0 = &a.rows[0];
    println!(
        "start φ2 = 0: p = {:.4}°, φ3 = {:.4}°, φ6 = {:.4}°, S53 = {:.5} m, B = ({:.5}, {:.5}) m",
        r0.cam_param.to_degrees(),
        r0.phi3_deg,
        r0.phi6_deg,
        r0.s53_m,
        r0.b_x_m,
        r0.b_y_m
    );
    for w in &a.warnings {
        println!("  warning: {}", w.message);
    }

    let s = synthesize(&g, &OutputLawSpec::default(), &SynthesisOptions { step_deg: 0.1, ..Default::default() })?;
    let c = &s.summary.checks;
    println!("\n## task 2: {}, α = θ = 47°, roller {} m, step 0.1°", s.summary.law, s.summary.roller_m);
    println!(
        "ω6 max {:.4} rad/s, ε6 ∈ [{:.4}, {:.4}] rad/s², |φ6 − φ2| max {:.3}° (limit {:.3}°)",
        c.omega6_max_rad_s, c.eps6_min_rad_s2, c.eps6_max_rad_s2, s.summary.lag_max_deg, s.summary.lag_limit_deg
    );
    println!(
        "μ6 max {:.2}° at {:.1}°, μB max {:.2}° at {:.1}°, μC max {:.2}° at {:.1}°",
        c.mu_out_max_deg,
        c.mu_out_max_at_phi2_deg,
        c.mu_b_max_deg,
        c.mu_b_max_at_phi2_deg,
        c.mu_c_max_deg,
        c.mu_c_max_at_phi2_deg
    );
    println!(
        "ρB min {} m at {:.1}°, ρC min {} m at {:.1}°, undercut {}, admissible α ({:.3}, {:.3})°",
        opt(c.rho_b_min_m),
        c.rho_b_min_at_phi2_deg,
        opt(c.rho_c_min_m),
        c.rho_c_min_at_phi2_deg,
        s.summary.undercut,
        s.summary.admissible_alpha_deg[0],
        s.summary.admissible_alpha_deg[1]
    );
    let dmax = loomkin_mech::max_dwell_deg(&OutputLawSpec::default(), g.max_lag_deg())?;
    println!("largest dwell keeping |φ6 − φ2| < arccos(l6/l2): {}°", opt(dmax));
    for w in &s.warnings {
        println!("  warning: {}", w.message);
    }

    println!("\n## α sweep (θ = α): analysis of the ellipse | synthesis of the default law");
    println!(
        "| α (°) | ω6 min | ω6 max | μ6 max | μB max | μC max | ρC′ min (m) | syn μB max | syn μ6 max | syn ρ min (m) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let alphas: Vec<f64> = (0..=6).map(|i| 30.0 + 5.0 * i as f64).collect();
    let o = AnalysisOptions { step_deg: 0.5, ..Default::default() };
    let so = SynthesisOptions { step_deg: 0.5, ..Default::default() };
    let sweep = alpha_sweep(&g, &Cam::paper(), &OutputLawSpec::default(), &alphas, &o, &so)?;
    for (r, alpha) in sweep.iter().zip(&alphas) {
        let syn_mu6 = synthesize(&g.with_alpha_deg(*alpha)?, &OutputLawSpec::default(), &so)
            .map(|s| format!("{:.2}", s.summary.checks.mu_out_max_deg))
            .unwrap_or_else(|_| "—".into());
        println!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.alpha_deg,
            opt(r.an_omega6_min_rad_s),
            opt(r.an_omega6_max_rad_s),
            opt(r.an_mu_out_max_deg),
            opt(r.an_mu_b_max_deg),
            opt(r.an_mu_c_max_deg),
            opt(r.an_rho_c_min_m),
            r.syn_error.as_ref().map(|_| "fold".to_string()).unwrap_or_else(|| opt(r.syn_mu_b_max_deg)),
            syn_mu6,
            opt(r.syn_rho_b_min_m)
        );
    }

    println!("\n## independent routes (task 1, ellipse, α = 47°, 0.1° steps)");
    let a = analyze(&g, &Cam::paper(), &AnalysisOptions { step_deg: 0.1, ..Default::default() })?;
    let sys = loomkin_mech::modulator_loops(&g, &Cam::paper())?;
    let s0 = &a.states[0];
    let q0 = nalgebra::SVector::<f64, 4>::new(a.rows[0].cam_param, s0.phi3[0], s0.s53[0], s0.phi6[0]);
    let xs: Vec<f64> = a.states.iter().map(|s| s.phi2).collect();
    let full = sys.trace(&xs, q0, &loomkin_mech::NewtonOptions::default())?;
    let newton = full
        .iter()
        .zip(&a.states)
        .map(|(f, s)| (f.q[3] - s.phi6[0]).abs().max((f.dq[3] - s.phi6[1]).abs()))
        .fold(0.0, f64::max);
    println!("Newton on both loops vs closed-form loop (3): max |Δφ6|, |Δφ6′| = {newton:.3e}");
    for steps in [360usize, 720, 1440, 3600] {
        let path = sys.integrate_velocity(0.0, q0, std::f64::consts::TAU, steps)?;
        let mut worst = 0.0f64;
        let mut drift = 0.0f64;
        for (x, q) in &path {
            let st = loomkin_mech::nearest_state(&a.states, x.to_degrees()).unwrap();
            if (st.phi2 - x).abs() < 1e-9 {
                worst = worst.max((q[3] - st.phi6[0]).abs());
            }
            drift = drift.max(sys.residual(*x, q).amax());
        }
        println!(
            "RK4 on the velocity equations, {steps} steps: max |Δφ6| = {worst:.3e} rad, loop residual {drift:.3e} m"
        );
    }
    let h = 0.1f64.to_radians();
    let (mut e1, mut e2) = (0.0f64, 0.0f64);
    for k in 1..a.rows.len() - 1 {
        let (p, c, m) = (a.states[k + 1].phi6[0], a.states[k].phi6[0], a.states[k - 1].phi6[0]);
        e1 = e1.max(((p - m) / (2.0 * h) - a.states[k].phi6[1]).abs());
        e2 = e2.max(((p - 2.0 * c + m) / (h * h) - a.states[k].phi6[2]).abs());
    }
    println!("central differences (h = 0.1°) vs analytic: max |Δω6/ω2| = {e1:.3e}, max |Δε6/ω2²| = {e2:.3e}");

    println!("\n## round trip: synthesise → n points of Γ → periodic spline → analyse (0.1° steps)");
    println!("| n points | max |Δφ6| (°) | max |Δω6| (rad/s) | ratio to previous |");
    println!("|---|---|---|---|");
    let law = OutputLawSpec::default().build()?;
    let mut prev: Option<f64> = None;
    for n in [90usize, 180, 360, 720, 1440, 2880] {
        let s = synthesize(&g, law.spec(), &SynthesisOptions { step_deg: 360.0 / n as f64, ..Default::default() })?;
        let pts: Vec<Vec2> = s.cam.centre.iter().map(|p| Vec2::new(p[0], p[1])).collect();
        let a = analyze(&g, &Cam::from_points(&pts)?, &AnalysisOptions { step_deg: 0.1, ..Default::default() })?;
        let (mut e0, mut e1) = (0.0f64, 0.0f64);
        for st in &a.states {
            let o = law.eval(st.phi2);
            e0 = e0.max(wrap_pi(st.phi6[0] - o.phi6).abs().to_degrees());
            e1 = e1.max((st.phi6[1] - o.d1).abs());
        }
        let ratio = prev.map(|p| format!("{:.1}", p / e0)).unwrap_or_else(|| "—".into());
        println!("| {n} | {e0:.3e} | {e1:.3e} | {ratio} |");
        prev = Some(e0);
    }
    Ok(())
}
