//! The modulator checked by independent routes: Newton against the closed form and against RK4
//! integration of the velocity equations, analytic rates against finite differences, synthesis
//! against analysis (round trip through a point table), and the failure modes.

use loomkin_laws::LawSpec;
use loomkin_mech::{
    AnalysisOptions, Cam, Ellipse, MechError, ModulatorGeometry, NewtonOptions, OutputLawSpec, SynthesisOptions, Vec2,
    WarningCode, analyze, assemble, e, modulator_loops, synthesize, wrap_pi,
};
use nalgebra::SVector;

fn opts(step_deg: f64) -> AnalysisOptions {
    AnalysisOptions { step_deg, ..AnalysisOptions::default() }
}

/// The paper's start of task 1 (φ2 = 0): the law of cosines in triangle OAB gives the angle at A,
/// which is φ3 + α for the roller below OA.
#[test]
fn initial_assembly_matches_triangle_oab() {
    let g = ModulatorGeometry::PAPER;
    let [p, phi3] = assemble(&g, &Cam::paper(), 0.0).unwrap();
    let b = Vec2::new(0.366 * p.cos(), 0.577 * p.sin());
    assert!(b.y < 0.0, "the roller trails the crank: B below OA");
    let ob2 = b.norm_squared();
    let angle_a = ((g.l2_m.powi(2) + g.l3_m.powi(2) - ob2) / (2.0 * g.l2_m * g.l3_m)).acos();
    assert!((phi3 + g.alpha_rad() - angle_a).abs() < 1e-12, "{} vs {}", phi3 + g.alpha_rad(), angle_a);
}

/// Newton on both loops in (p, φ3, S53, φ6) against the analysis (Newton on loop 2 in (p, φ3),
/// loop 3 in closed form).
#[test]
fn full_newton_matches_the_closed_form_of_loop_3() {
    let g = ModulatorGeometry::PAPER;
    let cam = Cam::paper();
    let a = analyze(&g, &cam, &opts(1.0)).unwrap();
    let sys = modulator_loops(&g, &cam).unwrap();
    let s0 = &a.states[0];
    let q0 = SVector::<f64, 4>::new(a.rows[0].cam_param, s0.phi3[0], s0.s53[0] + 0.01, s0.phi6[0] - 0.02);
    let xs: Vec<f64> = a.states.iter().map(|s| s.phi2).collect();
    let full = sys.trace(&xs, q0, &NewtonOptions::default()).unwrap();
    for (f, s) in full.iter().zip(&a.states) {
        assert!((f.q[1] - s.phi3[0]).abs() < 1e-10);
        assert!((f.q[2] - s.s53[0]).abs() < 1e-10);
        assert!(wrap_pi(f.q[3] - s.phi6[0]).abs() < 1e-10);
        for k in 0..2 {
            let (d, dd) = (if k == 0 { f.dq[3] } else { f.dq[2] }, if k == 0 { f.ddq[3] } else { f.ddq[2] });
            let (d_ref, dd_ref) = if k == 0 { (s.phi6[1], s.phi6[2]) } else { (s.s53[1], s.s53[2]) };
            assert!((d - d_ref).abs() < 1e-9 && (dd - dd_ref).abs() < 1e-8, "rates differ at {}", s.phi2);
        }
    }
}

/// The paper's own route (Simulink): integrate the velocity equations (4), (5) from the start.
/// RK4 over 3600 steps reproduces the Newton positions to 1e-9 and closes the loops to 1e-10 m.
#[test]
fn time_integration_of_the_velocity_equations_agrees_with_newton() {
    let g = ModulatorGeometry::PAPER;
    let cam = Cam::paper();
    let a = analyze(&g, &cam, &opts(0.1)).unwrap();
    let sys = modulator_loops(&g, &cam).unwrap();
    let s0 = &a.states[0];
    let q0 = SVector::<f64, 4>::new(a.rows[0].cam_param, s0.phi3[0], s0.s53[0], s0.phi6[0]);
    let path = sys.integrate_velocity(0.0, q0, std::f64::consts::TAU, 3600).unwrap();
    let mut worst = 0.0f64;
    for ((x, q), s) in path.iter().zip(&a.states) {
        assert!((x - s.phi2).abs() < 1e-12);
        worst = worst.max((q[3] - s.phi6[0]).abs()).max((q[1] - s.phi3[0]).abs());
        assert!(sys.residual(*x, q).amax() < 1e-10);
    }
    assert!(worst < 1e-9, "RK4 vs Newton: {worst:e} rad");
}

/// ω and ε from the differentiated loops against central differences of the positions, at a real
/// input speed (ω2 = 100 rpm).
#[test]
fn analytic_rates_match_finite_differences() {
    let g = ModulatorGeometry::PAPER;
    let w2 = 100.0 * std::f64::consts::TAU / 60.0;
    let a =
        analyze(&g, &Cam::paper(), &AnalysisOptions { step_deg: 0.05, input_speed_rad_s: w2, ..opts(0.05) }).unwrap();
    let h = 0.05f64.to_radians() / w2; // time step (s)
    let r = &a.rows;
    let mut worst = [0.0f64; 3];
    for k in 1..r.len() - 1 {
        let d = |f: fn(&loomkin_mech::AnalysisRow) -> f64| (f(&r[k + 1]) - f(&r[k - 1])) / (2.0 * h);
        let dd = |f: fn(&loomkin_mech::AnalysisRow) -> f64| (f(&r[k + 1]) - 2.0 * f(&r[k]) + f(&r[k - 1])) / (h * h);
        worst[0] = worst[0].max((d(|x| x.phi6_deg.to_radians()) - r[k].omega6_rad_s).abs() / w2);
        worst[1] = worst[1].max((dd(|x| x.phi6_deg.to_radians()) - r[k].eps6_rad_s2).abs() / (w2 * w2));
        worst[2] = worst[2].max((d(|x| x.s53_m) - r[k].v53_m_s).abs() / w2);
    }
    assert!(worst[0] < 1e-6 && worst[1] < 1e-5 && worst[2] < 1e-6, "{worst:?}");
}

/// Round trip: synthesise, keep n points of cam Γ, fit the periodic spline, analyse, compare φ6 with
/// the law. Returns the largest |Δφ6| (deg).
fn round_trip(n: usize) -> f64 {
    let g = ModulatorGeometry::PAPER;
    let law = OutputLawSpec::default();
    let s =
        synthesize(&g, &law, &SynthesisOptions { step_deg: 360.0 / n as f64, ..SynthesisOptions::default() }).unwrap();
    let pts: Vec<Vec2> = s.cam.centre.iter().map(|p| Vec2::new(p[0], p[1])).collect();
    assert_eq!(pts.len(), n);
    let a = analyze(&g, &Cam::from_points(&pts).unwrap(), &opts(0.5)).unwrap();
    let out = law.build().unwrap();
    a.states.iter().map(|st| wrap_pi(st.phi6[0] - out.eval(st.phi2).phi6).abs().to_degrees()).fold(0.0, f64::max)
}

#[test]
fn round_trip_recovers_the_law_and_converges() {
    let (e180, e360, e720) = (round_trip(180), round_trip(360), round_trip(720));
    assert!(e720 < 1e-3, "|Δφ6| = {e720}° with 720 points");
    let order = (e180 / e720).log2() / 2.0;
    assert!(order > 3.0, "observed order {order} ({e180}, {e360}, {e720})");
}

#[test]
fn synthesis_starts_where_the_paper_does_and_keeps_the_lever_rigid() {
    let g = ModulatorGeometry::PAPER;
    let s = synthesize(&g, &OutputLawSpec::default(), &SynthesisOptions::default()).unwrap();
    for st in &s.states {
        let a = st.a(&g);
        assert!(((st.b[0] - a).norm() - g.l3_m).abs() < 1e-14);
        assert!(((st.c[0] - a).norm() - g.l3p_m).abs() < 1e-14);
        assert!((st.d(&g).norm() - g.l6_m).abs() < 1e-14);
        // D lies on the slot through A of direction φ3, at distance S53.
        assert!((a - st.s53[0] * e(st.phi3[0]) - st.d(&g)).norm() < 1e-14);
    }
    // Eq. (14): φ2 = φ3 = φ6 = 90°, S53 = l2 − l6.
    let r = &s.rows[90];
    assert!((r.phi2_deg - 90.0).abs() < 1e-12 && (r.phi3_deg - 90.0).abs() < 1e-9 && (r.phi6_deg - 90.0).abs() < 1e-9);
    assert!((r.s53_m - 0.26).abs() < 1e-12);
    assert!(s.summary.checks.closure_gap_b_m < 1e-12 && s.summary.checks.closure_gap_c_m < 1e-12);
    assert!((s.summary.checks.phi6_turn_deg - 360.0).abs() < 1e-9);
    // Symmetric lever (θ = α) and a law odd-symmetric about the dwell at 90°: the mirror in the y axis
    // maps the mechanism at φ2 onto the one at 180° − φ2 with arm AB onto arm AC, so
    // C(180° − φ2) = mirror(B(φ2)): Γ′ is Γ reflected.
    for k in 0..=180 {
        let (b, c) = (&s.rows[k], &s.rows[180 - k]);
        assert!((c.c_x_m + b.b_x_m).abs() < 1e-12 && (c.c_y_m - b.b_y_m).abs() < 1e-12, "φ2 = {k}°");
    }
    assert!((s.summary.checks.rho_b_min_m.unwrap() - s.summary.checks.rho_c_min_m.unwrap()).abs() < 1e-9);
}

/// The synthesised counter-cam agrees with the counter-cam the analysis derives from the
/// synthesised cam (eq. (9) both ways).
#[test]
fn analysis_of_the_synthesised_cam_gives_the_same_counter_cam() {
    let g = ModulatorGeometry::PAPER;
    let s =
        synthesize(&g, &OutputLawSpec::default(), &SynthesisOptions { step_deg: 0.5, ..Default::default() }).unwrap();
    let pts: Vec<Vec2> = s.cam.centre.iter().map(|p| Vec2::new(p[0], p[1])).collect();
    let a = analyze(&g, &Cam::from_points(&pts).unwrap(), &opts(0.5)).unwrap();
    for (ra, rs) in a.rows.iter().zip(&s.rows) {
        assert!((ra.phi2_deg - rs.phi2_deg).abs() < 1e-9);
        assert!((ra.c_x_m - rs.c_x_m).abs() < 1e-6 && (ra.c_y_m - rs.c_y_m).abs() < 1e-6);
        assert!((ra.mu_b_deg - rs.mu_b_deg).abs() < 1e-2, "μB at {}", ra.phi2_deg);
    }
}

#[test]
fn slot_missing_the_crank_names_the_angle_and_the_alpha_range() {
    // l6 = 0.3 m: the admissible α shrinks to about 33.7…51.8°, so α = 60° fails and says so.
    let g = ModulatorGeometry { l6_m: 0.3, ..ModulatorGeometry::PAPER.with_alpha_deg(60.0).unwrap() };
    let err = analyze(&g, &Cam::paper(), &opts(1.0)).unwrap_err();
    let msg = err.to_string();
    assert!(matches!(err, MechError::CannotBuild { .. }));
    assert!(msg.contains("slot misses the output crank") && msg.contains("admissible α ∈ [33.7"), "{msg}");
    // l6 = 0.2 m: no α at all.
    let g = ModulatorGeometry { l6_m: 0.2, ..ModulatorGeometry::PAPER };
    let msg = analyze(&g, &Cam::paper(), &opts(1.0)).unwrap_err().to_string();
    assert!(msg.contains("no α works for this cam"), "{msg}");
    // The range given is right: its middle works, just outside it fails.
    let a = analyze(&ModulatorGeometry::PAPER, &Cam::paper(), &opts(1.0)).unwrap().summary.admissible_alpha_deg;
    let paper = ModulatorGeometry::PAPER;
    assert!(analyze(&paper.with_alpha_deg(a[0] + 0.05).unwrap(), &Cam::paper(), &opts(1.0)).is_ok());
    assert!(analyze(&paper.with_alpha_deg(a[0] - 0.05).unwrap(), &Cam::paper(), &opts(1.0)).is_err());
    assert!(analyze(&paper.with_alpha_deg(a[1] - 0.05).unwrap(), &Cam::paper(), &opts(1.0)).is_ok());
    assert!(analyze(&paper.with_alpha_deg(a[1] + 0.05).unwrap(), &Cam::paper(), &opts(1.0)).is_err());
    // The paper's sweep 30…60° lies inside.
    assert!(a[0] < 30.0 && a[1] > 60.0, "{a:?}");
}

/// Review regression: a slot pointing away from O (|φ3 − φ2| > 90°) was reported as
/// "|sin(φ3 − φ2)| = 0.571 > l6/l2 = 0.606", a false inequality. The message now states the real
/// condition, checked here against the state computed independently from the closed triangle OAB.
#[test]
fn a_slot_pointing_away_from_o_is_named_truthfully() {
    let g = ModulatorGeometry::PAPER.with_alpha_deg(170.0).unwrap();
    let msg = analyze(&g, &Cam::paper(), &opts(1.0)).unwrap_err().to_string();
    assert!(msg.contains("points away from O") && !msg.contains("|sin(φ3 − φ2)| ="), "{msg}");
    // Where the sine form is used, the inequality it prints holds.
    let g = ModulatorGeometry { l6_m: 0.3, ..ModulatorGeometry::PAPER.with_alpha_deg(60.0).unwrap() };
    let msg = analyze(&g, &Cam::paper(), &opts(1.0)).unwrap_err().to_string();
    let num = |key: &str| -> f64 {
        let rest = &msg[msg.find(key).unwrap() + key.len()..];
        rest.split([' ', ')']).next().unwrap().parse().unwrap()
    };
    assert!(num("|sin(φ3 − φ2)| = ") > num("l6/l2 = "), "{msg}");
}

/// Review regression: the admissible α of an analysis was the raw interval `[max η − σ, min η + σ]`
/// and could start below 0° (e.g. [−12.5, 46.5]° for a flat ellipse), outside the valid lever
/// angles. It is clipped to (0°, 180°), and the clipped range is still right: α just inside the
/// upper bound assembles, just outside it does not.
#[test]
fn the_admissible_alpha_range_stays_within_valid_lever_angles() {
    let cam = Cam::ellipse(0.366, 0.31).unwrap();
    let g = ModulatorGeometry::PAPER.with_alpha_deg(20.0).unwrap();
    let a = analyze(&g, &cam, &opts(1.0)).unwrap().summary.admissible_alpha_deg;
    assert!(a[0] == 0.0 && a[1] > 40.0 && a[1] < 180.0, "{a:?}");
    assert!(analyze(&g.with_alpha_deg(1.0).unwrap(), &cam, &opts(1.0)).is_ok());
    assert!(analyze(&g.with_alpha_deg(a[1] - 0.05).unwrap(), &cam, &opts(1.0)).is_ok());
    let msg = analyze(&g.with_alpha_deg(a[1] + 0.05).unwrap(), &cam, &opts(1.0)).unwrap_err().to_string();
    assert!(msg.contains("admissible α ∈ (0.000,"), "{msg}");
}

/// Review regression: the l3 given as admissible was the distance range at one input angle only.
/// Over the whole turn the roller reaches the paper's ellipse for l3 between the largest nearest
/// distance and the smallest farthest distance from the crank circle `|A| = l2`; both occur at
/// φ2 = 0 (A on the short axis): `l2 − a = 0.294 m` and `l2 + a = 1.026 m`.
#[test]
fn out_of_reach_gives_the_l3_range_over_the_turn() {
    let g = ModulatorGeometry { l3_m: 2.0, ..ModulatorGeometry::PAPER };
    let msg = analyze(&g, &Cam::paper(), &opts(1.0)).unwrap_err().to_string();
    assert!(msg.contains("for l3 ∈ (0.294000, 1.026000) m"), "{msg}");
}

#[test]
fn a_cam_out_of_reach_is_named() {
    let cam = Cam::ellipse(0.1, 0.1).unwrap();
    let msg = analyze(&ModulatorGeometry::PAPER, &cam, &opts(1.0)).unwrap_err().to_string();
    assert!(msg.contains("cannot reach cam Γ") && msg.contains("φ2 = 0.000°"), "{msg}");
    // Reachable at the start, out of reach later: an off-centre ellipse.
    let cam = Cam::from_curve(std::sync::Arc::new(Ellipse::with_centre(0.3, 0.3, 0.35, 0.0).unwrap()), "off");
    let msg = analyze(&ModulatorGeometry::PAPER, &cam, &opts(1.0)).unwrap_err().to_string();
    assert!(msg.contains("cannot reach cam Γ"), "{msg}");
}

#[test]
fn a_fold_of_the_cam_loop_is_named() {
    // A three-lobed cam ρ(p) = 0.38 + 0.08 cos 3p (720 points): near φ2 = 61° the circle of radius
    // l3 about A touches it from inside a lobe, the arm AB is normal to Γ and the tracked root ends.
    let pts: Vec<Vec2> = (0..720)
        .map(|i| std::f64::consts::TAU * i as f64 / 720.0)
        .map(|p| (0.38 + 0.08 * (3.0 * p).cos()) * e(p))
        .collect();
    let err = analyze(&ModulatorGeometry::PAPER, &Cam::from_points(&pts).unwrap(), &opts(1.0)).unwrap_err();
    let msg = err.to_string();
    assert!(msg.contains("fold at φ2 = 61.") && msg.contains("normal to cam Γ"), "{msg}");
    // The fold is located between grid points: the same angle at every step.
    let at = |step: f64| match analyze(&ModulatorGeometry::PAPER, &Cam::from_points(&pts).unwrap(), &opts(step)) {
        Err(MechError::CannotBuild { phi2_deg, .. }) => phi2_deg,
        other => panic!("{other:?}"),
    };
    let x = at(1.0);
    assert!((61.0..62.0).contains(&x), "{x}");
    for step in [0.01, 10.0, 30.0] {
        assert!((at(step) - x).abs() < 1e-9, "step {step}: {} vs {x}", at(step));
    }
    // Independent route: at the fold the arm AB is normal to Γ, so the circle of radius l3 about A
    // is tangent to Γ: a local extremum of the distance p ↦ |A − r(p)| equals l3 there. Dense
    // sampling (2·10⁵ points) finds the extrema to ~1e-9 m.
    let g = ModulatorGeometry::PAPER;
    let a = g.l2_m * e(x.to_radians());
    let sp = Cam::from_points(&pts).unwrap();
    let c = sp.curve();
    let n = 200_000;
    let d: Vec<f64> = (0..n).map(|i| (c.eval(c.period() * i as f64 / n as f64).r - a).norm()).collect();
    let nearest = (0..n)
        .filter(|&i| {
            let (p, q) = (d[(i + n - 1) % n], d[(i + 1) % n]);
            (d[i] <= p && d[i] <= q) || (d[i] >= p && d[i] >= q)
        })
        .map(|i| (d[i] - g.l3_m).abs())
        .fold(f64::INFINITY, f64::min);
    assert!(nearest < 1e-8, "no distance extremum at l3: nearest off by {nearest:e} m");
}

#[test]
fn law_out_of_range_names_the_admissible_dwell() {
    let law = OutputLawSpec { dwell_deg: 120.0, ..OutputLawSpec::default() };
    let msg = synthesize(&ModulatorGeometry::PAPER, &law, &SynthesisOptions::default()).unwrap_err().to_string();
    assert!(msg.contains("leaves the admissible range") && msg.contains("dwell must be <"), "{msg}");
}

#[test]
fn synthesis_fold_names_the_alpha_range() {
    let g = ModulatorGeometry::PAPER.with_alpha_deg(30.0).unwrap();
    let msg = synthesize(&g, &OutputLawSpec::default(), &SynthesisOptions::default()).unwrap_err().to_string();
    assert!(msg.contains("fold at roller B") && msg.contains("admissible α ∈ (35.8"), "{msg}");
}

#[test]
fn undercut_is_a_warning_with_the_largest_roller() {
    let s = synthesize(
        &ModulatorGeometry::PAPER,
        &OutputLawSpec::default(),
        &SynthesisOptions { roller_m: 0.08, ..Default::default() },
    )
    .unwrap();
    assert!(s.summary.undercut && s.summary.undercut_b && s.summary.undercut_c);
    let w: Vec<_> = s.warnings.iter().filter(|w| w.code == WarningCode::Undercut).collect();
    assert_eq!(w.len(), 2);
    assert!(w[0].message.contains("admissible roller radius <"), "{}", w[0].message);
    // The undercut wall loops: the inner groove wall crosses itself.
    assert!(s.summary.wall_self_intersections_b > 0);
    let ok = synthesize(
        &ModulatorGeometry::PAPER,
        &OutputLawSpec::default(),
        &SynthesisOptions { roller_m: 0.04, ..Default::default() },
    )
    .unwrap();
    assert!(!ok.summary.undercut && ok.summary.wall_self_intersections_b == 0);
}

#[test]
fn every_rise_law_of_the_core_synthesises_without_nan() {
    for name in ["cycloidal", "harmonic", "poly345", "poly4567", "modified-trapezoid", "modified-sine"] {
        let rise = LawSpec::parse::<&str, &str>(name, &[]).unwrap();
        let law = OutputLawSpec { rise, ..OutputLawSpec::default() };
        let s = synthesize(&ModulatorGeometry::PAPER, &law, &SynthesisOptions::default()).unwrap();
        let json = serde_json::to_string(&s).unwrap();
        assert!(!json.contains("NaN") && !json.contains("null"), "{name}");
    }
}

/// Cam Γ of an analysis: its centre is the roller path B of the rows, its walls lie at the roller
/// radius from it, on either side, and the paper's cam is an ellipse: B on (x/0.366)² + (y/0.577)² = 1.
#[test]
fn the_analysis_cam_profile_is_the_roller_path_with_offset_walls() {
    let g = ModulatorGeometry::PAPER;
    let a = analyze(&g, &Cam::paper(), &opts(2.0)).unwrap();
    let r = 0.02;
    let p = a.cam_profile(r);
    assert_eq!(p.centre.len(), a.rows.len() - 1);
    for (i, c) in p.centre.iter().enumerate() {
        assert_eq!(*c, [a.rows[i].b_x_m, a.rows[i].b_y_m]);
        assert!(((c[0] / 0.366).powi(2) + (c[1] / 0.577).powi(2) - 1.0).abs() < 1e-9);
        for w in [p.wall_left[i], p.wall_right[i]] {
            assert!(((w[0] - c[0]).hypot(w[1] - c[1]) - r).abs() < 1e-12);
        }
    }
    assert!(a.cam_profile(0.0).wall_left.is_empty());
}
