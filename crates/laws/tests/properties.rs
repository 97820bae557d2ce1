//! Property tests: derivatives against finite differences, symmetry, closed form against quadrature.

use loomkin_laws::{Law, LawSpec, Shape, ShapeSegment};
use proptest::prelude::*;

fn catalogue() -> Vec<Law> {
    ["constant-acceleration", "harmonic", "cycloidal", "poly345", "poly4567", "modified-trapezoid", "modified-sine"]
        .iter()
        .map(|n| LawSpec::parse::<&str, &str>(n, &[]).unwrap().build().unwrap())
        .collect()
}

/// A random balanced piecewise law: random positive-phase shapes, mirrored negative phase.
fn piecewise() -> impl Strategy<Value = LawSpec> {
    let shape = prop_oneof![
        (0.1..2.0f64).prop_map(|l| Shape::Constant { level: l }),
        (0.0..2.0f64, 0.0..2.0f64).prop_map(|(a, b)| Shape::Linear { from: a, to: b }),
        (0.0..2.0f64, 0.0..2.0f64).prop_map(|(a, b)| Shape::SineRamp { from: a, to: b }),
        (0.0..2.0f64, 0.0..2.0f64).prop_map(|(a, b)| Shape::CosineRamp { from: a, to: b }),
        (0.0..2.0f64, 0.0..2.0f64).prop_map(|(a, b)| Shape::HalfCosine { from: a, to: b }),
        (0.1..2.0f64).prop_map(|p| Shape::SineArc { peak: p }),
    ];
    prop::collection::vec((0.05..1.0f64, shape), 1..5).prop_map(|parts| {
        let total: f64 = parts.iter().map(|p| p.0).sum::<f64>() * 2.0;
        let mut segs: Vec<ShapeSegment> =
            parts.iter().map(|(l, s)| ShapeSegment { length: l / total, shape: *s }).collect();
        let mirror: Vec<ShapeSegment> = segs
            .iter()
            .rev()
            .map(|s| ShapeSegment { length: s.length, shape: s.shape.reversed().scaled(-1.0) })
            .collect();
        segs.extend(mirror);
        LawSpec::Piecewise { segments: segs }
    })
}

/// Central differences of order 1 over step h.
fn fd(f: impl Fn(f64) -> f64, x: f64, h: f64) -> f64 {
    (f(x + h) - f(x - h)) / (2.0 * h)
}

proptest! {
    #[test]
    fn derivatives_match_finite_differences(i in 0usize..7, x in 0.01..0.99f64) {
        let law = &catalogue()[i];
        // Stay off joints where a one-sided difference would straddle a jump.
        prop_assume!(law.joints().all(|j| (j - x).abs() > 1e-3));
        let h = 1e-5;
        let k = law.eval(x);
        prop_assert!((fd(|y| law.eval(y).s, x, h) - k.v).abs() < 1e-7);
        prop_assert!((fd(|y| law.eval(y).v, x, h) - k.a).abs() < 1e-6 * (1.0 + k.a.abs()));
        prop_assert!((fd(|y| law.eval(y).a, x, h) - k.j).abs() < 1e-5 * (1.0 + k.j.abs()));
    }

    /// Outside [0, 1] the follower dwells at the law's end values: every derivative is 0, and the
    /// finite differences of the values returned there agree (issue 27: the jerk kept 4π² = 39.48
    /// for the cycloidal law before x = 0).
    #[test]
    fn outside_the_rise_the_follower_dwells(i in 0usize..7, d in 1e-9..10.0f64) {
        let law = &catalogue()[i];
        let h = d.min(1e-3) / 2.0;
        for (x, end) in [(-d, law.eval(0.0).s), (1.0 + d, law.eval(1.0).s)] {
            let k = law.eval(x);
            prop_assert_eq!((k.s, k.v, k.a, k.j), (end, 0.0, 0.0, 0.0), "x = {}", x);
            prop_assert_eq!(fd(|y| law.eval(y).s, x, h), 0.0);
            prop_assert_eq!(fd(|y| law.eval(y).a, x, h), 0.0);
        }
    }

    #[test]
    fn symmetric_laws_are_odd_about_the_middle(i in 0usize..7, x in 0.0..1.0f64) {
        let law = &catalogue()[i];
        let (l, r) = (law.eval(x), law.eval(1.0 - x));
        prop_assert!((l.s + r.s - 1.0).abs() < 1e-12);
        prop_assert!((l.v - r.v).abs() < 1e-11);
    }

    #[test]
    fn piecewise_laws_are_normalised_and_match_quadrature(spec in piecewise()) {
        let law = spec.build().unwrap();
        let k0 = law.eval(0.0);
        let k1 = law.eval(1.0);
        prop_assert!(k0.s.abs() < 1e-15 && k0.v.abs() < 1e-15);
        prop_assert!((k1.s - 1.0).abs() < 1e-12 && k1.v.abs() < 1e-9);
        // Independent route: integrate the acceleration numerically (composite Simpson, 400 panels per
        // segment of the spec), v(b) = v(a) + ∫a, s(b) = s(a) + v(a)(b − a) + ∫(b − t) a(t) dt, and
        // compare with the closed form at every joint.
        let LawSpec::Piecewise { segments } = &spec else { unreachable!() };
        let scale = 1.0 + law.metrics().ca;
        let (mut x, mut v, mut s) = (0.0, 0.0, 0.0);
        for seg in segments {
            let (a0, b0) = (x, x + seg.length);
            let eps = 1e-13;
            let m = 400;
            let h = (b0 - a0) / m as f64;
            let acc = |t: f64| law.eval(t.clamp(a0 + eps, b0 - eps)).a;
            let (mut iv, mut is) = (0.0, 0.0);
            for k in 0..=m {
                let t = a0 + k as f64 * h;
                let w = if k == 0 || k == m { 1.0 } else if k % 2 == 1 { 4.0 } else { 2.0 };
                iv += w * acc(t);
                is += w * (b0 - t) * acc(t);
            }
            s += v * (b0 - a0) + is * h / 3.0;
            v += iv * h / 3.0;
            x = b0;
            let k = law.eval((x - 1e-15).max(0.0));
            prop_assert!((k.s - s).abs() < 1e-8 * scale, "s at {}: closed {} numeric {}", x, k.s, s);
            prop_assert!((k.v - v).abs() < 1e-8 * scale, "v at {}: closed {} numeric {}", x, k.v, v);
        }
    }

    #[test]
    fn sampler_matches_pointwise(i in 0usize..7, n in 2usize..3000) {
        let law = &catalogue()[i];
        for (x, k) in law.sample(n) {
            let e = law.eval(x);
            prop_assert!((k.s - e.s).abs() < 1e-12 && (k.a - e.a).abs() < 1e-9 * (1.0 + e.a.abs()), "x = {}", x);
        }
    }

    #[test]
    fn metrics_bound_dense_samples(spec in piecewise()) {
        let law = spec.build().unwrap();
        let m = law.metrics();
        for (_, k) in law.sample(4001) {
            prop_assert!(k.v <= m.cv * (1.0 + 1e-12) + 1e-12);
            prop_assert!(k.a <= m.ca_pos + 1e-9 && k.a >= m.ca_neg - 1e-9);
            prop_assert!(k.v * k.a <= m.cm + 1e-9);
        }
        // ... and the dense maxima come close to the exact ones.
        let vmax = law.sample(4001).iter().map(|(_, k)| k.v).fold(f64::MIN, f64::max);
        prop_assert!(m.cv - vmax < 1e-5 * m.cv);
    }
}

/// Bit-equal kinematics (the streamed samples must print the same digits).
fn same_bits(a: &loomkin_laws::Kinematics, b: &loomkin_laws::Kinematics) -> bool {
    [a.s, a.v, a.a, a.j].iter().zip([b.s, b.v, b.a, b.j]).all(|(p, q)| p.to_bits() == q.to_bits())
}

#[test]
fn streamed_samples_are_the_samples_bit_for_bit() {
    // Sizes around the block (8192) and re-seed (128) boundaries, and one of several blocks.
    for law in catalogue() {
        for n in [2, 3, 127, 128, 129, 1000, 8191, 8192, 8193, 8194, 30_001] {
            let whole = law.sample(n);
            let streamed: Vec<_> = law.samples(n).collect();
            assert_eq!(streamed.len(), n);
            for (i, ((x, k), (y, q))) in whole.iter().zip(&streamed).enumerate() {
                assert!(x.to_bits() == y.to_bits() && same_bits(k, q), "n = {n}, point {i}: {k:?} vs {q:?}");
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn streamed_samples_of_piecewise_laws(spec in piecewise(), n in 2usize..40_000) {
        let law = spec.build().unwrap();
        let whole = law.sample(n);
        let mut it = law.samples(n);
        prop_assert_eq!(it.len(), n);
        for (x, k) in &whole {
            let (y, q) = it.next().unwrap();
            prop_assert!(x.to_bits() == y.to_bits() && same_bits(k, &q));
        }
        prop_assert!(it.next().is_none());
    }
}

/// Tables at and above the size where `sample_into` writes with non-temporal stores (4 MiB,
/// 131 072 points) hold the same bits as the block sampler's, which writes with ordinary stores.
#[test]
fn large_tables_are_the_samples_bit_for_bit() {
    for law in catalogue() {
        for n in [131_071, 131_072, 200_001] {
            let mut whole = vec![loomkin_laws::Kinematics::default(); n];
            law.sample_into(&mut whole);
            let mut count = 0;
            for (i, (k, (_, q))) in whole.iter().zip(law.samples(n)).enumerate() {
                assert!(same_bits(k, &q), "n = {n}, point {i}: {k:?} vs {q:?}");
                count += 1;
            }
            assert_eq!(count, n);
        }
    }
}

/// `sample_columns` writes the block sampler's points, bit for bit, as five columns.
#[test]
fn columns_are_the_samples_bit_for_bit() {
    for law in catalogue() {
        for n in [2, 3, 127, 128, 129, 8191, 8192, 8193, 30_001] {
            let mut cols = vec![vec![f64::NAN; n]; 5];
            let [x, s, v, a, j] = &mut cols[..] else { unreachable!() };
            assert_eq!(law.sample_columns([x, s, v, a, j]), n);
            for (i, (y, q)) in law.samples(n).enumerate() {
                let got = [cols[0][i], cols[1][i], cols[2][i], cols[3][i], cols[4][i]];
                let want = [y, q.s, q.v, q.a, q.j];
                assert!(got.iter().zip(want).all(|(g, w)| g.to_bits() == w.to_bits()), "n = {n}, point {i}");
            }
        }
    }
    // Shorter and empty columns.
    let law = &catalogue()[2];
    let (mut x, mut s, mut v, mut a, mut j) =
        (vec![0.0; 10], vec![0.0; 5], vec![0.0; 10], vec![0.0; 10], vec![0.0; 10]);
    assert_eq!(law.sample_columns([&mut x, &mut s, &mut v, &mut a, &mut j]), 5);
    assert_eq!(x[4], 1.0);
    assert_eq!(x[5], 0.0);
    let mut one = [7.0];
    let (mut b, mut c, mut d, mut e) = ([7.0], [7.0], [7.0], [7.0]);
    assert_eq!(law.sample_columns([&mut one, &mut b, &mut c, &mut d, &mut e]), 0);
    assert_eq!(one, [7.0]);
}

proptest! {
    /// The continuity judgement against the shapes' definitions: in a random balanced piecewise law
    /// `a` is continuous at a joint exactly where the two shapes' levels meet (and at the ends where
    /// the level is 0), whatever the lengths; `s` and `v` are continuous everywhere, the end against
    /// the dwell included (a rest law's build and its continuity report apply the same rule).
    #[test]
    fn accel_jumps_are_where_the_levels_differ(spec in piecewise()) {
        let law = spec.build().unwrap();
        let LawSpec::Piecewise { segments } = &spec else { unreachable!() };
        let c = law.continuity();
        let levels: Vec<(f64, f64)> = segments.iter().map(|g| g.shape.end_levels()).collect();
        let mut sides = vec![(0.0, levels[0].0)];
        sides.extend(levels.windows(2).map(|w| (w[0].1, w[1].0)));
        sides.push((levels[levels.len() - 1].1, 0.0));
        let joints: Vec<_> = std::iter::once(&c.start).chain(&c.joints).chain([&c.end]).collect();
        prop_assert_eq!(joints.len(), sides.len());
        for (j, (l, r)) in joints.iter().zip(&sides) {
            prop_assert!(j.flags()[1], "s, v continuous at {}: {:?}", j.x, j);
            prop_assert_eq!(j.flags()[2], l == r, "a at {}: levels {} → {}, {:?}", j.x, l, r, j);
        }
    }
}
