//! Studies: the fast path against the generic one (property test), the Pareto front of a grid
//! against brute force, the constrained optimum against a search over motion angles.

use loomkin_shed::{
    Conditions, Progress, Template, best, dominates_in, evaluate_rows, fig1_design, grid_design, pareto, table,
    table1_design,
};
use proptest::prelude::*;

fn lengths(parts: usize) -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(0.0f64..1.0, parts).prop_filter_map("positive sum", |v| {
        let s: f64 = v.iter().sum();
        (s > 0.05).then(|| v.iter().map(|x| x / s).collect())
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    #[test]
    fn fast_path_equals_generic_path(k in lengths(4), threshold in 0.75f64..0.99, fam in 0usize..3) {
        let t = match fam {
            0 => Template::lead_trapezoid(),
            1 => Template::parse("ramps", "linear:0:1,sine-arc:2,half-cosine:1:0.2,cosine-ramp:0.2:0").unwrap(),
            _ => Template::parse("mixed", "sine-ramp:0:1,linear:1:0.3,constant:0.3,cosine-ramp:0.3:0").unwrap(),
        };
        let Ok(g) = t.evaluate_generic(&k, threshold) else { return Ok(()) };
        let f = t.evaluate_fast(&k, threshold).unwrap();
        for (name, a, b) in [("cv", f.cv, g.cv), ("ca", f.ca, g.ca), ("cm", f.cm, g.cm), ("ca_rms", f.ca_rms, g.ca_rms),
                             ("x_depart", f.x_depart, g.x_depart), ("x_arrive", f.x_arrive, g.x_arrive),
                             ("lead", f.lead, g.lead), ("tail", f.tail, g.tail), ("a_jump", f.a_jump, g.a_jump)] {
            prop_assert!((a - b).abs() <= 1e-9 * (1.0 + b.abs()), "{} {:?} {}: fast {} generic {}", t.name(), k, name, a, b);
        }
        prop_assert!((f.cj - g.cj).abs() <= 1e-7 * g.cj, "cj {} vs {}", f.cj, g.cj);
    }
}

#[test]
fn table1_and_fig1_designs() {
    let d = table1_design();
    assert_eq!(d.len(), 8);
    for r in d.rows() {
        assert!((r[0] - r[2]).abs() < 1e-12, "k3 = k1 in every printed experiment");
    }
    let rows = evaluate_rows(&Template::trapezoid(), &d, 0.95, Progress::Hidden).unwrap();
    let c = table(&d, &rows, &[300.0], &Conditions::default()).unwrap();
    // From nearly constant acceleration (Ca → 4) to cycloidal (2π): Ca and the window both grow.
    assert!(
        c.windows(2)
            .all(|w| w[1].criteria.ca > w[0].criteria.ca && w[1].criteria.window_deg > w[0].criteria.window_deg)
    );
    assert!((c[7].criteria.ca - 2.0 * std::f64::consts::PI).abs() < 1e-9);
    let f = fig1_design(0.1).unwrap();
    assert_eq!(f.len(), 6);
    let rows = evaluate_rows(&Template::lead_trapezoid(), &f, 0.95, Progress::Hidden).unwrap();
    let c = table(&f, &rows, &[360.0], &Conditions::default()).unwrap();
    // A longer lead is a longer absolute dwell.
    assert!(c.windows(2).all(|w| w[1].criteria.dwell_deg > w[0].criteria.dwell_deg));
    assert!((c[5].criteria.dwell_deg - 0.5 * 360.0 * 0.5 * 2.0).abs() < 1e-9);
}

#[test]
fn pareto_front_of_a_grid_against_brute_force() {
    let t = Template::lead_trapezoid();
    let d = grid_design(4, 0.0, 0.95, 0.1).unwrap();
    let rows = evaluate_rows(&t, &d, 0.95, Progress::Hidden).unwrap();
    let motions = [240.0, 300.0, 360.0];
    let cond = Conditions::default();
    let all = table(&d, &rows, &motions, &cond).unwrap();
    let front = pareto(&d, &rows, &motions, &cond).unwrap();
    assert!(!front.is_empty());
    let key = |c: &loomkin_shed::Candidate| [c.criteria.window_deg, c.criteria.peak_accel_m_s2];
    for a in &front {
        assert!(!all.iter().any(|b| dominates_in(&key(b), &key(a))), "front member dominated");
    }
    for b in &all {
        let on = front.iter().any(|a| a.row == b.row && a.criteria.motion_deg == b.criteria.motion_deg);
        if !on {
            assert!(
                front.iter().any(|a| dominates_in(&key(a), &key(b)) || key(a) == key(b)),
                "excluded law not dominated"
            );
        }
    }
    assert!(front.windows(2).all(|w| w[0].criteria.window_deg >= w[1].criteria.window_deg));
}

#[test]
fn free_motion_optimum_beats_every_motion_on_a_grid() {
    let t = Template::trapezoid();
    let d = grid_design(3, 0.0, 1.0, 0.05).unwrap();
    let rows = evaluate_rows(&t, &d, 0.95, Progress::Hidden).unwrap();
    let cond = Conditions::default();
    let motions: Vec<f64> = (2..=720).map(|i| i as f64 * 0.5).collect();
    for w in [140.0, 175.0, 250.0] {
        let free = best(&d, &rows, None, w, None, &cond).unwrap().unwrap();
        let grid = best(&d, &rows, Some(&motions), w, None, &cond).unwrap().unwrap();
        assert!(free.criteria.window_deg >= w - 1e-9);
        assert!(grid.criteria.window_deg >= w);
        assert!(free.criteria.peak_accel_m_s2 <= grid.criteria.peak_accel_m_s2 * (1.0 + 1e-12));
        // The grid's best comes within the angle step of the free optimum.
        assert!(grid.criteria.peak_accel_m_s2 <= free.criteria.peak_accel_m_s2 * 1.01, "W {w}");
    }
    assert!(best(&d, &rows, None, 360.0, None, &cond).is_err());
    // Least acceleration alone picks nearly constant acceleration (the smallest k1, k3 on the grid);
    // a jerk limit moves the choice to smoother ramps, at a higher acceleration.
    let free = best(&d, &rows, None, 175.0, None, &cond).unwrap().unwrap();
    assert!(free.criteria.ca < 4.2, "Ca {}", free.criteria.ca);
    assert!(free.criteria.accel_jump_m_s2 > 0.0, "constant acceleration jumps at the ends");
    let limit = 2000.0;
    let smooth = best(&d, &rows, None, 175.0, Some(limit), &cond).unwrap().unwrap();
    assert!(smooth.criteria.peak_jerk_m_s3 <= limit && smooth.criteria.window_deg >= 175.0 - 1e-9);
    assert!(smooth.criteria.peak_accel_m_s2 > free.criteria.peak_accel_m_s2);
    // Brute force over every row confirms the constrained optimum.
    for (i, r) in rows.iter().enumerate() {
        let Some(r) = r else { continue };
        let phi = ((360.0 - 175.0) / (1.0 - r.window_fraction())).min(360.0);
        let c = loomkin_shed::Criteria::new(phi, r, &cond);
        if c.peak_jerk_m_s3 <= limit && c.accel_jump_m_s2 == 0.0 {
            assert!(c.peak_accel_m_s2 >= smooth.criteria.peak_accel_m_s2 * (1.0 - 1e-12), "row {i}");
        }
    }
}

#[test]
fn motion_angle_lists() {
    use loomkin_shed::parse_motion_angles;
    assert_eq!(parse_motion_angles("300").unwrap(), vec![300.0]);
    assert_eq!(parse_motion_angles("180, 270").unwrap(), vec![180.0, 270.0]);
    assert_eq!(parse_motion_angles("180:360:90").unwrap(), vec![180.0, 270.0, 360.0]);
    assert!(parse_motion_angles("0").is_err());
    assert!(parse_motion_angles("300:400:50").is_err());
    assert!(parse_motion_angles("a").is_err());
    assert!(parse_motion_angles("1:2").is_err());
}

#[test]
fn a_lead_is_a_shorter_motion() {
    // Fig. 1's lead k1 of zero acceleration at motion Φ is the three-part law (k2, k3, k4)/(1 − k1)
    // at motion Φ(1 − k1): same window, same physical peaks.
    let cond = Conditions::default();
    let k = [0.2, 0.2, 0.4, 0.2];
    let a = loomkin_shed::evaluate(&Template::lead_trapezoid().law(300.0, &k).unwrap(), &cond).unwrap();
    let rest: Vec<f64> = k[1..].iter().map(|x| x / 0.8).collect();
    let b = loomkin_shed::evaluate(&Template::trapezoid().law(240.0, &rest).unwrap(), &cond).unwrap();
    assert!((a.window_deg - b.window_deg).abs() < 1e-9);
    assert!((a.dwell_deg - b.dwell_deg).abs() < 1e-9);
    assert!((a.peak_accel_m_s2 - b.peak_accel_m_s2).abs() < 1e-9 * b.peak_accel_m_s2);
    assert!((a.peak_jerk_m_s3 - b.peak_jerk_m_s3).abs() < 1e-7 * b.peak_jerk_m_s3);
}
