//! The uniform-grid sampler (lane recurrence for the sinusoids, re-seeded every 128 points)
//! against direct evaluation (`sin_cos` at every point) over 10⁷ points.

use loomkin_laws::LawSpec;

/// Largest difference of each quantity between `sample_into` and `Law::eval` at the same x,
/// relative to the quantity's largest magnitude over the law.
fn worst_relative_error(name: &str, n: usize) -> [f64; 4] {
    let law = LawSpec::parse::<&str, &str>(name, &[]).unwrap().build().unwrap();
    let (mut err, mut scale) = ([0.0f64; 4], [0.0f64; 4]);
    // `samples` is `sample_into` a block at a time, bit for bit (tests/properties.rs), without
    // holding 320 MB.
    for (x, k) in law.samples(n) {
        let e = law.eval(x);
        for q in 0..4 {
            err[q] = err[q].max((k.order(q) - e.order(q)).abs());
            scale[q] = scale[q].max(e.order(q).abs());
        }
    }
    std::array::from_fn(|q| err[q] / scale[q])
}

#[test]
fn recurrence_stays_within_1e_13_of_direct_sin_cos_over_ten_million_points() {
    // Cycloidal: one sinusoid over the whole rise; modified sine: three segments with sinusoids of
    // two frequencies. The bound is the re-seeding: no lane rotates more than 32 times from an
    // exact `sin_cos`, so its error is a few ulps of the amplitude (measured: at most 3.2e-15; the
    // tolerance leaves a factor 30 for other platforms' `sin_cos`).
    for (name, n) in [("cycloidal", 10_000_000), ("modified-sine", 10_000_000)] {
        let err = worst_relative_error(name, n);
        println!(
            "{name}: s, v, a, j within {:.1e}, {:.1e}, {:.1e}, {:.1e} of their scales",
            err[0], err[1], err[2], err[3]
        );
        for (q, e) in err.iter().enumerate() {
            assert!(*e <= 1e-13, "{name}: order {q} differs by {e:e} of its scale");
        }
    }
}
