//! The spline law, its export and the cam-table errors against routes that share no code with
//! the crate: the paper's full system for the 4(N − 1) spline coefficients, quadrature of the
//! acceleration image, and brute-force sampling of re-interpolated tables.

use loomkin_servo::{
    Drive, ExportFormat, Interpolation, SplineEnd, SplineLaw, export, export_coefficients, slope_at_middle,
};
use proptest::prelude::*;

/// Gaussian elimination with partial pivoting on a dense n×n system.
fn solve_dense(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for c in 0..n {
        let p = (c..n).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs())).unwrap();
        a.swap(c, p);
        b.swap(c, p);
        for r in c + 1..n {
            let f = a[r][c] / a[c][c];
            for k in c..n {
                a[r][k] -= f * a[c][k];
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = vec![0.0; n];
    for r in (0..n).rev() {
        x[r] = (b[r] - (r + 1..n).map(|k| a[r][k] * x[k]).sum::<f64>()) / a[r][r];
    }
    x
}

/// The paper's route: the 4(N − 1) unknowns b_{k,j} of f_j(x) = b1 + b2 x + b3 x² + b4 x³ in
/// global x from 2(N − 1) interpolation rows, N − 2 rows each of C1 and C2 at the inner knots,
/// the start condition and f'(0.5) = D.
fn spline_by_full_system(pts: &[[f64; 2]], end: SplineEnd, d: f64) -> Vec<[f64; 4]> {
    let m = pts.len() - 1;
    let n = 4 * m;
    let (mut a, mut b) = (Vec::new(), Vec::new());
    let row = |j: usize, x: f64, order: usize| {
        let mut r = vec![0.0; n];
        for k in order..4 {
            let fall: f64 = (0..order).map(|i| (k - i) as f64).product();
            r[4 * j + k] = fall * x.powi((k - order) as i32);
        }
        r
    };
    for j in 0..m {
        a.push(row(j, pts[j][0], 0));
        b.push(pts[j][1]);
        a.push(row(j, pts[j + 1][0], 0));
        b.push(pts[j + 1][1]);
    }
    for j in 1..m {
        for order in [1, 2] {
            let (l, r) = (row(j - 1, pts[j][0], order), row(j, pts[j][0], order));
            a.push(l.iter().zip(&r).map(|(p, q)| p - q).collect());
            b.push(0.0);
        }
    }
    a.push(row(0, 0.0, if end == SplineEnd::Natural { 2 } else { 1 }));
    b.push(0.0);
    a.push(row(m - 1, 0.5, 1));
    b.push(d);
    let x = solve_dense(a, b);
    (0..m).map(|j| [x[4 * j], x[4 * j + 1], x[4 * j + 2], x[4 * j + 3]]).collect()
}

/// `∫_a^b g` by the 3-point Gauss–Legendre rule on 4 panels: exact for polynomials of degree
/// ≤ 5 (the integrands here are of degree ≤ 4 between knots).
fn integrate(a: f64, b: f64, g: impl Fn(f64) -> f64) -> f64 {
    let r = (0.6f64).sqrt();
    let h = (b - a) / 4.0;
    (0..4)
        .map(|i| {
            let m = a + (i as f64 + 0.5) * h;
            h / 2.0 * (5.0 / 9.0 * g(m - 0.5 * h * r) + 8.0 / 9.0 * g(m) + 5.0 / 9.0 * g(m + 0.5 * h * r))
        })
        .sum()
}

/// Random valid point sets: N in 4..=12, X gaps ≥ 0.01 of the half, Y in [−0.3, 1].
fn points() -> impl Strategy<Value = Vec<[f64; 2]>> {
    (4usize..=12).prop_flat_map(|n| {
        (prop::collection::vec(0.2f64..1.0, n - 1), prop::collection::vec(-0.3f64..1.0, n - 2)).prop_map(
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
    #![proptest_config(ProptestConfig { cases: 120, ..ProptestConfig::default() })]

    /// The tridiagonal moments give the same coefficients as the paper's full system.
    #[test]
    fn spline_equals_the_full_linear_system(pts in points(), clamped in any::<bool>()) {
        let end = if clamped { SplineEnd::Clamped } else { SplineEnd::Natural };
        let Ok(sl) = SplineLaw::new(&pts, end) else { return Ok(()) };
        let n = pts.len();
        let full = spline_by_full_system(&pts, end, slope_at_middle(pts[n - 3], pts[n - 2]));
        for (j, (a, b)) in sl.spline_coefficients().iter().zip(&full).enumerate() {
            // Compare the polynomials on their interval (the global coefficients themselves are
            // ill-conditioned far from x = 0).
            for k in 0..=8 {
                let x = pts[j][0] + (pts[j + 1][0] - pts[j][0]) * k as f64 / 8.0;
                let (fa, fb) = (
                    a[0] + x * (a[1] + x * (a[2] + x * a[3])),
                    b[0] + x * (b[1] + x * (b[2] + x * b[3])),
                );
                let size: f64 = b.iter().enumerate().map(|(i, c)| (c * x.powi(i as i32)).abs()).sum();
                prop_assert!((fa - fb).abs() < 1e-10 * (1.0 + size), "interval {j} at {x}: {fa} vs {fb}");
            }
        }
    }

    /// u°(x) = ∫₀ˣ (x − t) f(t) dt / F(1) with F(1) = ∫₀¹ (1 − t) f(t) dt, by quadrature of the
    /// acceleration image; and u°(1) = 1, the odd mirror, the scale.
    #[test]
    fn unit_law_equals_quadrature_of_the_image(pts in points(), clamped in any::<bool>()) {
        let end = if clamped { SplineEnd::Clamped } else { SplineEnd::Natural };
        let Ok(sl) = SplineLaw::new(&pts, end) else { return Ok(()) };
        let f = |t: f64| sl.accel_image(t);
        // Integrate knot to knot (the image is a cubic on each), mirrored knots included.
        let mut knots: Vec<f64> = pts.iter().map(|p| p[0]).chain(pts.iter().map(|p| 1.0 - p[0])).collect();
        knots.sort_by(f64::total_cmp);
        knots.dedup();
        let moment = |x: f64| -> f64 {
            knots.windows(2).filter(|w| w[0] < x).map(|w| integrate(w[0], w[1].min(x), |t| (x - t) * f(t))).sum()
        };
        let f1 = moment(1.0);
        prop_assert!((sl.scale() * f1 - 1.0).abs() < 1e-9, "scale {} vs 1/F(1) {}", sl.scale(), 1.0 / f1);
        for x in [0.05, 0.21, 0.5, 0.63, 0.97] {
            let s = moment(x) / f1;
            let k = sl.law().eval(x);
            prop_assert!((k.s - s).abs() < 1e-9, "u({x}) = {} vs quadrature {s}", k.s);
            prop_assert!((f(x) + f(1.0 - x)).abs() < 1e-12, "odd mirror at {x}");
        }
    }

    /// Multiplying every Y by the same positive factor leaves the law unchanged (the paper's
    /// normalisation), which the optimiser relies on when it reports points with max |Y| = 1.
    #[test]
    fn the_law_does_not_depend_on_the_scale_of_y(pts in points(), k in 0.01f64..1.0) {
        let Ok(a) = SplineLaw::new(&pts, SplineEnd::Natural) else { return Ok(()) };
        let scaled: Vec<[f64; 2]> = pts.iter().map(|p| [p[0], k * p[1]]).collect();
        let b = SplineLaw::new(&scaled, SplineEnd::Natural).unwrap();
        // Displacement is compared relative to the law's own size: where the normalising integral
        // F(1) nearly cancels, the law swings far past [0, 1] (a regression case reaches |s| = 53
        // with scale 4e4) and the rounding of k·Y, amplified alike, moved s by 5e-12 = 1e-13 of
        // that size. The acceleration was already compared relative to its value.
        let size = 1.0 + (0..=20).map(|i| a.law().eval(i as f64 / 20.0).s.abs()).fold(0.0, f64::max);
        for i in 0..=20 {
            let x = i as f64 / 20.0;
            let (p, q) = (a.law().eval(x), b.law().eval(x));
            prop_assert!((p.s - q.s).abs() < 1e-12 * size && (p.a - q.a).abs() < 1e-9 * (1.0 + p.a.abs()));
        }
    }
}

/// The exported global-x polynomials reproduce the unit law to the rounding their
/// monomial form allows: the error bound is a few ε·Σ|c_k|·|x|^k, which is below 1e-9 for
/// moderately spaced points (checked here: 1e-10 for the default points and a clamped set).
#[test]
fn exported_polynomials_reproduce_the_quadrature_law() {
    for (pts, end) in [
        (loomkin_servo::default_points(), SplineEnd::Natural),
        (vec![[0.0, 0.0], [0.07, 0.6], [0.15, 1.0], [0.3, 0.85], [0.42, 0.4], [0.5, 0.0]], SplineEnd::Clamped),
        (
            vec![[0.0, 0.0], [0.02, 0.9], [0.06, 0.3], [0.1, 1.0], [0.2, 0.2], [0.45, 0.7], [0.49, 0.1], [0.5, 0.0]],
            SplineEnd::Natural,
        ),
    ] {
        let sl = SplineLaw::new(&pts, end).unwrap();
        let e = export_coefficients(&sl);
        let mut knots: Vec<f64> = pts.iter().map(|p| p[0]).chain(pts.iter().map(|p| 1.0 - p[0])).collect();
        knots.sort_by(f64::total_cmp);
        knots.dedup();
        // ∫₀ˣ g, knot to knot (the image is one cubic between knots).
        let q = |x: f64, g: &dyn Fn(f64) -> f64| -> f64 {
            knots.windows(2).filter(|w| w[0] < x).map(|w| integrate(w[0], w[1].min(x), g)).sum()
        };
        // Independent: u° and u°' by quadrature of the image, the scale from F(1) likewise.
        let f1 = q(1.0, &|t| (1.0 - t) * sl.accel_image(t));
        for iv in &e.intervals {
            for k in 0..=10 {
                let x = iv.x_start + (iv.x_end - iv.x_start) * k as f64 / 10.0;
                let s = q(x, &|t| (x - t) * sl.accel_image(t)) / f1;
                let v = q(x, &|t| sl.accel_image(t)) / f1;
                let eval = |c: &[f64]| c.iter().rev().fold(0.0, |acc, &ck| acc * x + ck);
                let bound = |c: &[f64]| {
                    64.0 * f64::EPSILON * c.iter().enumerate().map(|(i, ck)| (ck * x.powi(i as i32)).abs()).sum::<f64>()
                };
                let (ds, dv) = ((eval(&iv.position) - s).abs(), (eval(&iv.velocity) - v).abs());
                assert!(ds < bound(&iv.position) + 1e-12, "s at {x}: {ds:e}");
                assert!(dv < bound(&iv.velocity) + 1e-12, "v at {x}: {dv:e}");
                if pts.len() < 8 {
                    assert!(ds < 1e-10 && dv < 1e-10, "at {x}: {ds:e} {dv:e}");
                }
            }
        }
    }
}

/// `[Y, dY/dX, d²Y/dX²]` (mm, mm/deg, mm/deg²) at master angle `deg` of the drive's turn, from the
/// law's own formula (shares no code with the cam-table engine's motion).
fn slave_mm(law: &loomkin_laws::Law, d: &Drive, deg: f64) -> [f64; 3] {
    let lay = d.layout().unwrap();
    let st = lay.starts_deg();
    let h = d.stroke_m * 1e3;
    if deg < st[1] {
        let k = law.eval(deg / lay.rise_deg);
        [h * k.s, h * k.v / lay.rise_deg, h * k.a / lay.rise_deg.powi(2)]
    } else if deg < st[2] {
        [h, 0.0, 0.0]
    } else if deg < st[3] {
        let k = law.eval((deg - st[2]) / lay.return_deg);
        [h * (1.0 - k.s), -h * k.v / lay.return_deg, -h * k.a / lay.return_deg.powi(2)]
    } else {
        [0.0; 3]
    }
}

/// The reported worst re-interpolation errors of `servo export`'s cam table equal a brute-force
/// search: the table re-read from the file, re-interpolated by interpolants written here (the
/// natural cubic spline and the quintic Hermite by the dense solver above, on the table's uneven
/// steps), compared with the exact cycle on a fine grid that includes every joint of the law.
#[test]
fn reinterpolation_errors_equal_a_brute_force_search() {
    let pts = [[0.0, 0.0], [0.03, 0.5], [0.11, 0.95], [0.23, 1.0], [0.31, 0.8], [0.44, 0.35], [0.5, 0.0]];
    let sl = SplineLaw::new(&pts, SplineEnd::Natural).unwrap();
    let law = sl.law();
    let mut d = Drive::pure_inertia(0.08, 113.0, 1.0, 0.02);
    d.return_angle_deg = Some(131.0);
    for step in [1.0, 2.5] {
        let file = export(&sl, &d, ExportFormat::Csv, step).unwrap();
        let report = file.table.unwrap();
        let tp = loomkin_cams::table::csv::read(&file.text).unwrap();
        assert_eq!(tp.len(), report.points);
        let n = tp.len();
        let hs: Vec<f64> = tp.windows(2).map(|w| w[1].master_deg - w[0].master_deg).collect();
        // Natural cubic spline through the positions, on the uneven steps, by the dense solver.
        let mut a = vec![vec![0.0; n]; n];
        let mut r = vec![0.0; n];
        a[0][0] = 1.0;
        a[n - 1][n - 1] = 1.0;
        for i in 1..n - 1 {
            a[i][i - 1] = hs[i - 1];
            a[i][i] = 2.0 * (hs[i - 1] + hs[i]);
            a[i][i + 1] = hs[i];
            r[i] = 6.0 * ((tp[i + 1].y - tp[i].y) / hs[i] - (tp[i].y - tp[i - 1].y) / hs[i - 1]);
        }
        let mm = solve_dense(a, r);
        for mode in Interpolation::ALL {
            let rep = report.reinterpolation.iter().find(|e| e.mode == mode).unwrap();
            let mut worst = [0.0f64; 3];
            for i in 0..n - 1 {
                let (p0, p1, h) = (tp[i], tp[i + 1], hs[i]);
                // The quintic through (Y, V, A) at both ends: its 6×6 system solved densely.
                let quintic = {
                    let row = |t: f64, d: usize| -> Vec<f64> {
                        (0..6)
                            .map(|k| {
                                if k < d {
                                    0.0
                                } else {
                                    (0..d).map(|i| (k - i) as f64).product::<f64>() * t.powi((k - d) as i32)
                                }
                            })
                            .collect()
                    };
                    let m: Vec<Vec<f64>> = (0..6).map(|q| row(if q < 3 { 0.0 } else { h }, q % 3)).collect();
                    solve_dense(m, vec![p0.y, p0.v, p0.a, p1.y, p1.v, p1.a])
                };
                let interp = |t: f64| -> [f64; 3] {
                    match mode {
                        Interpolation::Linear => [p0.y + (p1.y - p0.y) * t / h, (p1.y - p0.y) / h, 0.0],
                        Interpolation::CubicSpline => {
                            let (s, u) = (h - t, t);
                            [
                                (mm[i] * s.powi(3) + mm[i + 1] * u.powi(3)) / (6.0 * h)
                                    + (p0.y / h - mm[i] * h / 6.0) * s
                                    + (p1.y / h - mm[i + 1] * h / 6.0) * u,
                                (-mm[i] * s * s + mm[i + 1] * u * u) / (2.0 * h) + (p1.y - p0.y) / h
                                    - (mm[i + 1] - mm[i]) * h / 6.0,
                                (mm[i] * s + mm[i + 1] * u) / h,
                            ]
                        }
                        _ => {
                            let e = |d: usize| {
                                (d..6)
                                    .map(|k| {
                                        let f: f64 = (0..d).map(|i| (k - i) as f64).product();
                                        f * quintic[k] * t.powi((k - d) as i32)
                                    })
                                    .sum::<f64>()
                            };
                            [e(0), e(1), e(2)]
                        }
                    }
                };
                // Fine grid plus the law's joints inside this step, approached from both sides.
                let mut ts: Vec<f64> = (0..=400).map(|k| h * k as f64 / 400.0).collect();
                for (start, len) in [(0.0, 113.0), (113.0 + 58.0, 131.0)] {
                    for p in pts.iter().map(|p| p[0]).chain(pts.iter().map(|p| 1.0 - p[0])) {
                        let t = start + len * p - p0.master_deg;
                        if t > 0.0 && t < h {
                            ts.extend([t - 1e-9, t, t + 1e-9]);
                        }
                    }
                }
                for t in ts {
                    let t = t.clamp(1e-12, h - 1e-12);
                    let ex = slave_mm(law, &d, p0.master_deg + t);
                    let ip = interp(t);
                    for q in 0..3 {
                        worst[q] = worst[q].max((ip[q] - ex[q]).abs());
                    }
                }
            }
            // The report is in m, m/deg, m/deg².
            let got = [rep.max_position_error_m, rep.max_velocity_error_m_per_deg, rep.max_accel_error_m_per_deg2]
                .map(|e| e * 1e3);
            for q in 0..3 {
                // The exact search may only find more than the sampling, and not much more; the
                // rounding of the dense quintic solve bounds the agreement at small errors.
                assert!(
                    got[q] >= worst[q] * (1.0 - 1e-6) - 1e-12 && got[q] <= worst[q] * 1.02 + 1e-12,
                    "{mode:?} step {step} quantity {q}: reported {:e}, brute force {:e}",
                    got[q],
                    worst[q]
                );
            }
        }
    }
}
