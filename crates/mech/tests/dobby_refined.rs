//! Verdicts and printed extremes of the modulator do not depend on the output step: every one is
//! located between grid points. Each refined extreme is also checked by an independent route, a
//! dense scan of the output rows at 0.01° (nothing may exceed it; the scan's best must approach it
//! as the grid error predicts).

use loomkin_mech::{
    AnalysisOptions, Cam, MechError, ModulatorGeometry, OutputLawSpec, SynthesisOptions, analyze, synthesize,
};
use serde_json::Value;

const STEPS: [f64; 4] = [0.1, 1.0, 10.0, 30.0];

/// Every numeric leaf of two summaries, except the step itself, agrees to 1e-9 (relative above 1).
fn same_summary(a: &Value, b: &Value, path: &str) {
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            assert_eq!(x.len(), y.len(), "{path}: keys differ");
            for (k, v) in x {
                if k != "step_deg" {
                    same_summary(v, &y[k], &format!("{path}.{k}"));
                }
            }
        }
        (Value::Array(x), Value::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{path}");
            for (i, (p, q)) in x.iter().zip(y).enumerate() {
                same_summary(p, q, &format!("{path}[{i}]"));
            }
        }
        (Value::Number(p), Value::Number(q)) => {
            let (p, q) = (p.as_f64().unwrap(), q.as_f64().unwrap());
            assert!((p - q).abs() <= 1e-9 * p.abs().max(1.0), "{path}: {p} vs {q}");
        }
        _ => assert_eq!(a, b, "{path}"),
    }
}

fn syn(g: &ModulatorGeometry, step: f64, roller: f64) -> loomkin_mech::Result<loomkin_mech::Synthesis> {
    synthesize(
        g,
        &OutputLawSpec::default(),
        &SynthesisOptions { step_deg: step, roller_m: roller, ..Default::default() },
    )
}

fn ana(g: &ModulatorGeometry, step: f64) -> loomkin_mech::Result<loomkin_mech::Analysis> {
    analyze(g, &Cam::paper(), &AnalysisOptions { step_deg: step, roller_m: Some(0.03), ..Default::default() })
}

#[test]
fn synthesis_summary_and_warnings_do_not_depend_on_the_step() {
    for roller in [0.03, 0.06] {
        let base = syn(&ModulatorGeometry::PAPER, STEPS[0], roller).unwrap();
        let bj = serde_json::to_value(&base.summary).unwrap();
        for &step in &STEPS[1..] {
            let s = syn(&ModulatorGeometry::PAPER, step, roller).unwrap();
            same_summary(&bj, &serde_json::to_value(&s.summary).unwrap(), &format!("step {step}"));
            same_summary(
                &serde_json::to_value(&base.warnings).unwrap(),
                &serde_json::to_value(&s.warnings).unwrap(),
                "warnings",
            );
        }
    }
}

#[test]
fn analysis_summary_and_warnings_do_not_depend_on_the_step() {
    let base = ana(&ModulatorGeometry::PAPER, STEPS[0]).unwrap();
    let bj = serde_json::to_value(&base.summary).unwrap();
    for &step in &STEPS[1..] {
        let a = ana(&ModulatorGeometry::PAPER, step).unwrap();
        same_summary(&bj, &serde_json::to_value(&a.summary).unwrap(), &format!("step {step}"));
        same_summary(&serde_json::to_value(&base.warnings).unwrap(), &serde_json::to_value(&a.warnings).unwrap(), "w");
    }
}

/// The issue's cases: each verdict is the same at every step.
#[test]
fn the_issue_s_verdicts_hold_at_every_step() {
    let paper = ModulatorGeometry::PAPER;
    for step in STEPS {
        // α = 62.3°: the slot misses the crank; true admissible α 23.434…62.143°.
        let msg = ana(&paper.with_alpha_deg(62.3).unwrap(), step).unwrap_err().to_string();
        assert!(msg.contains("slot misses") && msg.contains("admissible α ∈ [23.434, 62.143]°"), "{step}: {msg}");
        // α = 35.5°: roller B folds near φ2 = 32.8°.
        let err = syn(&paper.with_alpha_deg(35.5).unwrap(), step, 0.03).unwrap_err();
        let MechError::CannotBuild { phi2_deg, condition, .. } = &err else { panic!("{err}") };
        assert!((phi2_deg - 32.77).abs() < 0.01 && condition.contains("fold at roller B"), "{step}: {err}");
        // l6 = 0.512 m, α = 60°: past the output dead point.
        let g = ModulatorGeometry { l6_m: 0.512, ..paper.with_alpha_deg(60.0).unwrap() };
        let msg = syn(&g, step, 0.03).unwrap_err().to_string();
        assert!(msg.contains("arccos(l6/l2)"), "{step}: {msg}");
        // Roller 0.06 m undercuts: the least radius of curvature is 0.049894 m.
        let s = syn(&paper, step, 0.06).unwrap();
        assert!(s.summary.undercut_b && s.summary.undercut_c, "{step}");
        let r = s.summary.checks.roller_max_m.unwrap();
        assert!((r - 0.049_894).abs() < 5e-7, "{step}: {r}");
    }
}

/// The admissible α range is exact: just inside each end is accepted, just outside refused, at a
/// coarse step (where a grid-only check would miss the violation).
#[test]
fn admissible_alpha_ends_are_sharp_at_a_coarse_step() {
    let paper = ModulatorGeometry::PAPER;
    let a = ana(&paper, 1.0).unwrap().summary.admissible_alpha_deg;
    for (alpha, ok) in [(a[0] + 1e-6, true), (a[0] - 1e-6, false), (a[1] - 1e-6, true), (a[1] + 1e-6, false)] {
        assert_eq!(ana(&paper.with_alpha_deg(alpha).unwrap(), 30.0).is_ok(), ok, "α = {alpha}");
    }
    let s = syn(&paper, 1.0, 0.03).unwrap().summary.admissible_alpha_deg;
    assert!(syn(&paper.with_alpha_deg(s[0] + 1e-6).unwrap(), 30.0, 0.03).is_ok());
    assert!(syn(&paper.with_alpha_deg(s[0] - 1e-6).unwrap(), 30.0, 0.03).is_err());
}

/// Independent route: the rows of a 0.01° run never exceed the refined extremes, and their best
/// comes within the grid error (a 0.01° grid misses a smooth maximum by at most ½|f″|h²).
#[test]
fn dense_rows_confirm_the_refined_extremes() {
    let s = syn(&ModulatorGeometry::PAPER, 0.01, 0.03).unwrap();
    let c = &s.summary.checks;
    let rows = &s.rows;
    let max = |f: &dyn Fn(&loomkin_mech::SynthesisRow) -> f64| rows.iter().map(f).fold(f64::NEG_INFINITY, f64::max);
    let cases: [(&str, f64, f64); 5] = [
        ("ω6 max", c.omega6_max_rad_s, max(&|r| r.omega6_rad_s)),
        ("ω6 min", -c.omega6_min_rad_s, max(&|r| -r.omega6_rad_s)),
        ("μB", c.mu_b_max_deg, max(&|r| r.mu_b_deg)),
        ("μout", c.mu_out_max_deg, max(&|r| r.mu_out_deg)),
        ("κB", 1.0 / c.rho_b_min_m.unwrap(), max(&|r| r.kappa_b_1_m.abs())),
    ];
    for (name, refined, dense) in cases {
        assert!(dense <= refined + 1e-12 * refined.abs().max(1.0), "{name}: dense {dense} > refined {refined}");
        assert!(refined - dense < 1e-5 * refined.abs().max(1.0), "{name}: dense {dense} far below {refined}");
    }
    let a = ana(&ModulatorGeometry::PAPER, 0.01).unwrap();
    let c = &a.summary.checks;
    let amax = |f: &dyn Fn(&loomkin_mech::AnalysisRow) -> f64| a.rows.iter().map(f).fold(f64::NEG_INFINITY, f64::max);
    let cases: [(&str, f64, f64); 4] = [
        ("ω6 max", c.omega6_max_rad_s, amax(&|r| r.omega6_rad_s)),
        ("ε6 max", c.eps6_max_rad_s2, amax(&|r| r.eps6_rad_s2)),
        ("μC", c.mu_c_max_deg, amax(&|r| r.mu_c_deg)),
        ("κC", 1.0 / c.rho_c_min_m.unwrap(), amax(&|r| r.kappa_c_1_m.abs())),
    ];
    for (name, refined, dense) in cases {
        assert!(dense <= refined + 1e-10 * refined.abs().max(1.0), "{name}: dense {dense} > refined {refined}");
        assert!(refined - dense < 1e-5 * refined.abs().max(1.0), "{name}: dense {dense} far below {refined}");
    }
}
