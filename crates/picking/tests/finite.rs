//! Inputs inside their documented ranges that would overflow or underflow a derived quantity are
//! refused, naming the input to blame; nothing non-finite comes out.

use loomkin_picking::{Design, DesignSpec, Mechanism, Params, PickError, RequiredVelocity, simulate};

fn blamed(e: PickError) -> String {
    match e {
        PickError::NonFiniteResult { field, .. } => field,
        other => panic!("expected NonFiniteResult, got {other}"),
    }
}

#[test]
fn extreme_design_inputs_are_refused_with_the_right_field() {
    let k = Params::paper().constants();
    let spec = |f: fn(&mut DesignSpec)| {
        let mut s = DesignSpec::paper();
        f(&mut s);
        s
    };
    let e = Design::new(spec(|s| s.velocity_m_s = 1e-300), k).unwrap_err();
    assert_eq!(blamed(e), "velocity_m_s");
    let e = Design::new(spec(|s| s.first_stage_m = 1e-320), k).unwrap_err();
    assert_eq!(blamed(e), "first_stage_m");
    // A small but representable design stays finite and is accepted.
    let d = Design::new(spec(|s| s.velocity_m_s = 1e-3), k).unwrap();
    assert!([d.a_m_s2, d.mu_1_s, d.tau_s, d.t_end_s].iter().all(|v| v.is_finite() && *v > 0.0));
    // The message is one line and names the value.
    let msg = Design::new(spec(|s| s.velocity_m_s = 1e-300), k).unwrap_err().to_string();
    assert!(msg.starts_with("velocity_m_s = 1e-300") && !msg.contains('\n'), "{msg}");
}

#[test]
fn extreme_mechanism_constants_and_path_are_refused() {
    let p = Params { c4_m_per_n: 1e-320, ..Params::paper() };
    assert_eq!(blamed(Mechanism::new(p, DesignSpec::paper()).unwrap_err()), "c4_m_per_n");
    // A path below the carrier's own length is refused when the mechanism is built (it made the
    // comparison with V_r infinite at 5e-324 m and a 310-digit percentage at 1e-300 m).
    for path_m in [5e-324, 1e-300] {
        let e = Mechanism::paper_default()
            .with_required(RequiredVelocity { path_m, ..RequiredVelocity::default() })
            .unwrap_err();
        let msg = e.to_string();
        assert!(msg.starts_with("path_m = ") && msg.contains("0.01 ≤ path_m ≤ 100 m"), "{msg}");
    }
    // A free-shed angle so small that V_r overflows still stops at the comparison, naming it.
    let m = Mechanism::paper_default()
        .with_required(RequiredVelocity { free_shed_deg: 5e-324, ..RequiredVelocity::default() })
        .unwrap();
    let settings = loomkin_picking::Settings::designed(&m);
    let e = simulate(&m, &settings, loomkin_picking::Method::Closed).unwrap_err();
    assert_eq!(blamed(e), "free_shed_deg");
}
