//! Invariants over random designs.

use loomkin_laws::LawSpec;
use loomkin_mech::{
    AnalysisOptions, Cam, ClosedSpline, ModulatorGeometry, OutputLawSpec, PlaneCurve, SynthesisOptions, Vec2, analyze,
    e, synthesize,
};
use proptest::prelude::*;

fn rise() -> impl Strategy<Value = LawSpec> {
    prop_oneof![Just(LawSpec::Cycloidal), Just(LawSpec::Poly345), Just(LawSpec::ModifiedSine), Just(LawSpec::Harmonic)]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Any accepted synthesis closes its loops, its curves and turns the output once.
    #[test]
    fn synthesis_closes(alpha in 37.0..70.0f64, dwell in 0.0..60.0f64, rise in rise(), cycles in 1u32..3) {
        let g = ModulatorGeometry::PAPER.with_alpha_deg(alpha).unwrap();
        let law = OutputLawSpec { dwell_deg: dwell, rise, cycles, ..OutputLawSpec::default() };
        match synthesize(&g, &law, &SynthesisOptions { step_deg: 2.0, ..Default::default() }) {
            Ok(s) => {
                prop_assert!(s.summary.checks.closure_gap_b_m < 1e-12);
                prop_assert!((s.summary.checks.phi6_turn_deg - 360.0).abs() < 1e-9);
                for st in &s.states {
                    let a = st.a(&g);
                    prop_assert!(((st.b[0] - a).norm() - g.l3_m).abs() < 1e-13);
                    prop_assert!((a - st.s53[0] * e(st.phi3[0]) - st.d(&g)).norm() < 1e-13);
                    prop_assert!(st.mu_b_deg(&g) <= 90.0 && st.mu_out_deg() < 90.0);
                }
            }
            Err(err) => {
                let msg = err.to_string();
                prop_assert!(msg.contains("φ2 =") && !msg.contains("NaN"), "{}", msg);
            }
        }
    }

    /// The analysis of random ellipses either succeeds with a closed revolution or names why not.
    #[test]
    fn analysis_of_ellipses(a in 0.25..0.5f64, b in 0.4..0.7f64, alpha in 30.0..60.0f64) {
        let g = ModulatorGeometry::PAPER.with_alpha_deg(alpha).unwrap();
        match analyze(&g, &Cam::ellipse(a, b).unwrap(), &AnalysisOptions { step_deg: 2.0, ..Default::default() }) {
            Ok(r) => {
                prop_assert!(r.summary.checks.closure_gap_b_m < 1e-8);
                prop_assert!((r.summary.checks.phi6_turn_deg - 360.0).abs() < 1e-6);
                prop_assert!(r.rows.iter().all(|x| x.omega6_rad_s.is_finite() && x.eps6_rad_s2.is_finite()));
            }
            Err(err) => {
                let msg = err.to_string();
                prop_assert!(msg.contains("φ2 =") && !msg.contains("NaN"), "{}", msg);
            }
        }
    }

    /// The spline passes through its points whatever their spacing.
    #[test]
    fn spline_interpolates(n in 8usize..40, jitter in 0.0..0.3f64) {
        let pts: Vec<Vec2> = (0..n).map(|i| {
            let t = std::f64::consts::TAU * (i as f64 + jitter * ((i * 7) as f64).sin()) / n as f64;
            Vec2::new(0.4 * t.cos(), 0.6 * t.sin())
        }).collect();
        let sp = ClosedSpline::new(&pts).unwrap();
        let mut u = 0.0;
        for i in 0..n {
            prop_assert!((sp.eval(u).r - pts[i]).norm() < 1e-12);
            u += (pts[(i + 1) % n] - pts[i]).norm();
        }
        prop_assert!((u - sp.period()).abs() < 1e-12);
    }
}
