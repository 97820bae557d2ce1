//! The spline law: D against a 4×4 solve, the spline conditions, symmetry, smoothness,
//! and closeness to the cycloid when the points are sampled from it.

use loomkin_laws::{LawSpec, Metrics};
use loomkin_servo::{SplineEnd, SplineLaw, default_points, slope_at_middle};
use proptest::prelude::*;

/// Solves a dense 4×4 system by Gaussian elimination with partial pivoting.
fn solve4(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> [f64; 4] {
    for c in 0..4 {
        let p = (c..4).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs())).unwrap();
        a.swap(c, p);
        b.swap(c, p);
        for r in c + 1..4 {
            let f = a[r][c] / a[c][c];
            for k in c..4 {
                a[r][k] -= f * a[c][k];
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = [0.0; 4];
    for r in (0..4).rev() {
        x[r] = (b[r] - (r + 1..4).map(|k| a[r][k] * x[k]).sum::<f64>()) / a[r][r];
    }
    x
}

/// D from the paper's route: fit g = B1 + B2 x + B3 x² + B4 x³ through the four points by a
/// 4×4 solve and differentiate at x = 0.5.
fn d_by_4x4(p5: [f64; 2], p6: [f64; 2]) -> f64 {
    let xs = [p5[0], p6[0], 1.0 - p5[0], 1.0 - p6[0]];
    let ys = [p5[1], p6[1], -p5[1], -p6[1]];
    let a = xs.map(|x| [1.0, x, x * x, x * x * x]);
    let b = solve4(a, ys);
    b[1] + 2.0 * b[2] * 0.5 + 3.0 * b[3] * 0.25
}

/// The paper's printed closed form for D (X5, Y5, X6, Y6).
fn d_paper(x5: f64, y5: f64, x6: f64, y6: f64) -> f64 {
    let num = 8.0 * x5.powi(3) * y6 - 8.0 * x6.powi(3) * y5 - 12.0 * x5 * x5 * y6 + 12.0 * x6 * x6 * y5 + 6.0 * x5 * y6
        - 6.0 * x6 * y5
        + y5
        - y6;
    let den = 2.0
        * (2.0 * x6 - 1.0)
        * (2.0 * x5.powi(3) - 2.0 * x5 * x6 * x6 - 3.0 * x5 * x5 + 2.0 * x5 * x6 + x6 * x6 + x5 - x6);
    num / den
}

/// Random valid definition points: n in 4..=10, increasing X with gaps ≥ 0.01, Y in [0.05, 1].
fn points() -> impl Strategy<Value = Vec<[f64; 2]>> {
    (4usize..=10).prop_flat_map(|n| {
        (prop::collection::vec(0.2f64..1.0, n - 1), prop::collection::vec(0.05f64..1.0, n - 2)).prop_map(
            move |(g, y)| {
                let total: f64 = g.iter().sum();
                let mut pts = vec![[0.0, 0.0]];
                let mut x = 0.0;
                for j in 0..n - 2 {
                    x += 0.5 * g[j] / total;
                    pts.push([x, y[j]]);
                }
                pts.push([0.5, 0.0]);
                pts
            },
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn d_matches_the_4x4_solve_and_the_paper(pts in points()) {
        let n = pts.len();
        let (p5, p6) = (pts[n - 3], pts[n - 2]);
        let d = slope_at_middle(p5, p6);
        let d4 = d_by_4x4(p5, p6);
        let dp = d_paper(p5[0], p5[1], p6[0], p6[1]);
        let scale = 1.0 + d.abs();
        prop_assert!((d - d4).abs() < 1e-8 * scale, "D {d} vs 4×4 {d4}");
        prop_assert!((d - dp).abs() < 1e-9 * scale, "D {d} vs paper {dp}");
    }

    #[test]
    fn spline_interpolates_with_the_right_end_conditions(pts in points(), clamped in any::<bool>()) {
        let end = if clamped { SplineEnd::Clamped } else { SplineEnd::Natural };
        // Positive Y do not guarantee a rise: a steep D can swing the spline negative between the
        // last points. Such sets are rejected (NoRise), which is checked elsewhere.
        let law = SplineLaw::new(&pts, end);
        prop_assume!(law.is_ok());
        let law = law.unwrap();
        for p in &pts {
            prop_assert!((law.accel_image(p[0]) - p[1]).abs() < 1e-12);
        }
        let b = law.spline_coefficients();
        // Slope D at 0.5 from the last interval's coefficients; the mirror has the same slope.
        let l = b[b.len() - 1];
        let slope = l[1] + l[2] + 0.75 * l[3];
        prop_assert!((slope - law.d()).abs() < 1e-8 * (1.0 + law.d().abs()), "{slope} vs {}", law.d());
        let h = 1e-7;
        let right = (law.accel_image(0.5 + 2.0 * h) - law.accel_image(0.5 + h)) / h;
        // one-sided difference: error ≈ 1.5·h·|f''(0.5)| plus rounding ~1e-16/h
        let fpp = 2.0 * l[2] + 3.0 * l[3];
        prop_assert!((right - law.d()).abs() < 2.0 * h * fpp.abs() + 1e-7 * (1.0 + law.d().abs()), "{right}");
        if clamped {
            prop_assert!(b[0][1].abs() < 1e-9 * (1.0 + b[0][2].abs()), "f'(0) = {}", b[0][1]);
        } else {
            prop_assert!(b[0][2].abs() < 1e-9 * (1.0 + b[0][1].abs()), "f''(0)/2 = {}", b[0][2]);
        }
        // C2 of f at the interior knots, from the global coefficients of adjacent intervals.
        for j in 1..pts.len() - 1 {
            let x = pts[j][0];
            let (l, r) = (b[j - 1], b[j]);
            let d1 = |c: [f64; 4]| c[1] + 2.0 * c[2] * x + 3.0 * c[3] * x * x;
            let d2 = |c: [f64; 4]| 2.0 * c[2] + 6.0 * c[3] * x;
            let sc = 1.0 + d1(l).abs() + d2(l).abs();
            prop_assert!((d1(l) - d1(r)).abs() < 1e-8 * sc && (d2(l) - d2(r)).abs() < 1e-8 * sc);
        }
    }

    #[test]
    fn unit_law_is_normalised_symmetric_and_c2(pts in points(), clamped in any::<bool>()) {
        let end = if clamped { SplineEnd::Clamped } else { SplineEnd::Natural };
        let sl = SplineLaw::new(&pts, end);
        prop_assume!(sl.is_ok());
        let sl = sl.unwrap();
        let law = sl.law();
        let k0 = law.eval(0.0);
        let k1 = law.eval(1.0);
        prop_assert!(k0.s.abs() < 1e-12 && k0.v.abs() < 1e-12 && k0.a.abs() < 1e-12);
        prop_assert!((k1.s - 1.0).abs() < 1e-12 && k1.v.abs() < 1e-12 && k1.a.abs() < 1e-11);
        for i in 0..=50 {
            let x = i as f64 / 50.0;
            let (a, b) = (law.eval(x), law.eval(1.0 - x));
            prop_assert!((a.s + b.s - 1.0).abs() < 1e-12, "s at {x}");
            prop_assert!((a.v - b.v).abs() < 1e-10, "v at {x}");
            prop_assert!((a.a + b.a).abs() < 1e-9 * (1.0 + a.a.abs()), "a at {x}");
            // the law's acceleration is the image scaled by 1/F(1)
            prop_assert!((a.a - sl.scale() * sl.accel_image(x)).abs() < 1e-9 * (1.0 + a.a.abs()));
        }
        // C2 against the dwells and at every joint; with a clamped start the jerk is continuous too
        // (f is C1 on [0, 1], including x = 0.5 where both sides have slope D).
        let c = law.continuity();
        prop_assert!(c.class >= 2, "the law must be C2, is C{}", c.class);
        let scale = 1.0 + law.metrics().cj;
        for j in &c.joints {
            prop_assert!(j.dj.abs() < 1e-8 * scale, "jerk jump {} at {}", j.dj, j.x);
        }
        if clamped {
            prop_assert!(c.start.dj.abs() < 1e-8 * scale && c.end.dj.abs() < 1e-8 * scale);
        }
    }
}

fn close(a: &Metrics, b: &Metrics, tol: f64) {
    for (name, x, y) in [("cv", a.cv, b.cv), ("ca", a.ca, b.ca), ("cm", a.cm, b.cm), ("ca_rms", a.ca_rms, b.ca_rms)] {
        assert!((x - y).abs() < tol * y.abs(), "{name}: {x} vs {y}");
    }
}

#[test]
fn points_sampled_from_the_cycloid_give_cycloid_metrics() {
    let cyc = LawSpec::Cycloidal.build().unwrap().metrics();
    // f = sin(2πx) sampled at 11 points: the spline reproduces the cycloid to ~1e-3.
    let n = 11;
    let pts: Vec<[f64; 2]> = (0..n)
        .map(|j| {
            let x = 0.5 * j as f64 / (n - 1) as f64;
            let y = if j == 0 || j == n - 1 { 0.0 } else { (2.0 * std::f64::consts::PI * x).sin() };
            [x, y]
        })
        .collect();
    let m = SplineLaw::new(&pts, SplineEnd::Natural).unwrap().law().metrics();
    close(&m, &cyc, 1e-3);
    // The cycloid's jerk at 0 is 4π², not 0: the natural spline (f'' = 0 at 0, true for sin)
    // fits it, so Cj is close too.
    assert!((m.cj - cyc.cj).abs() < 2e-2 * cyc.cj, "cj {} vs {}", m.cj, cyc.cj);
    // The default seven points (j/12) are coarser but still within 1 %.
    let m7 = SplineLaw::new(&default_points(), SplineEnd::Natural).unwrap().law().metrics();
    close(&m7, &cyc, 1e-2);
}

#[test]
fn more_points_converge_to_the_cycloid() {
    let cyc = LawSpec::Cycloidal.build().unwrap().metrics();
    let err = |n: usize| {
        let pts: Vec<[f64; 2]> = (0..n)
            .map(|j| {
                let x = 0.5 * j as f64 / (n - 1) as f64;
                [x, if j == 0 || j == n - 1 { 0.0 } else { (2.0 * std::f64::consts::PI * x).sin() }]
            })
            .collect();
        let m = SplineLaw::new(&pts, SplineEnd::Natural).unwrap().law().metrics();
        (m.ca - cyc.ca).abs()
    };
    let (e6, e12, e24) = (err(6), err(12), err(24));
    assert!(e12 < e6 / 4.0 && e24 < e12 / 4.0, "{e6} {e12} {e24}");
}
