//! The compass search against a brute-force search of its final grid, its box and its constraint.

use loomkin_numeric::compass_min;

const STEPS: [f64; 4] = [1.0, 0.5, 0.25, 0.125];

/// Every point of the grid of step `h` in `[lo, hi]²` (the box's corners on the grid).
fn grid(lo: f64, hi: f64, h: f64) -> Vec<[f64; 2]> {
    let n = ((hi - lo) / h).round() as usize;
    (0..=n).flat_map(|i| (0..=n).map(move |j| [lo + i as f64 * h, lo + j as f64 * h])).collect()
}

#[test]
fn a_separable_convex_function_ends_at_the_best_point_of_the_last_grid() {
    // Optima off the grid: the compass search must end at the grid point a brute force finds.
    for (a, b) in [(1.3, -0.6), (-2.7, 0.05), (0.0, 3.9), (5.0, -5.0)] {
        let f = |p: &[f64]| (p[0] - a).powi(2) + 3.0 * (p[1] - b).powi(2);
        let (x, fx) = compass_min(
            &mut (),
            vec![0.0, 0.0],
            f(&[0.0, 0.0]),
            &STEPS,
            &[-4.0; 2],
            &[4.0; 2],
            |_, p| Ok::<_, ()>(f(p)),
            |_, _| Ok(true),
            |_| {},
        )
        .unwrap();
        let best = grid(-4.0, 4.0, 0.125).into_iter().min_by(|p, q| f(p).total_cmp(&f(q))).unwrap();
        assert_eq!(x, best.to_vec(), "optimum ({a}, {b})");
        assert_eq!(fx, f(&best));
        // The box holds: the optimum (5, −5) lies outside it.
        assert!(x.iter().all(|v| v.abs() <= 4.0));
    }
}

#[test]
fn the_constraint_is_asked_only_for_improving_moves_and_always_holds() {
    // Minimise the distance to (2, 2) keeping inside the disc of radius 1.5 about the origin.
    let f = |p: &[f64]| (p[0] - 2.0).powi(2) + (p[1] - 2.0).powi(2);
    let inside = |p: &[f64]| p[0] * p[0] + p[1] * p[1] <= 2.25;
    let mut calls = (0usize, 0usize);
    let (x, fx) = compass_min(
        &mut calls,
        vec![0.0, 0.0],
        f(&[0.0, 0.0]),
        &STEPS,
        &[-3.0; 2],
        &[3.0; 2],
        |c, p| {
            c.0 += 1;
            Ok::<_, ()>(f(p))
        },
        |c, p| {
            c.1 += 1;
            Ok(inside(p))
        },
        |_| {},
    )
    .unwrap();
    assert!(inside(&x));
    assert!(calls.1 < calls.0, "{calls:?}");
    // No single move of the last step both improves and keeps the constraint.
    for j in 0..2 {
        for d in [0.125, -0.125] {
            let mut y = x.clone();
            y[j] += d;
            assert!(!(f(&y) < fx && inside(&y)), "{y:?} improves on {x:?}");
        }
    }
    // The best grid point in the disc is no better than a local step away: within one step of it.
    let best = grid(-3.0, 3.0, 0.125).into_iter().filter(|p| inside(p)).min_by(|p, q| f(p).total_cmp(&f(q))).unwrap();
    assert!(fx <= f(&best) + 2.0 * 0.125 * 0.125 * 4.0, "{fx} vs grid best {}", f(&best));
}

#[test]
fn the_first_error_ends_the_search_and_stages_are_counted() {
    let mut stages = 0;
    let r = compass_min(
        &mut stages,
        vec![0.0],
        0.0,
        &STEPS,
        &[-1.0],
        &[1.0],
        |_, p| if p[0] > 0.0 { Err("no") } else { Ok(-p[0]) },
        |_, _| Ok(true),
        |s| *s += 1,
    );
    assert_eq!(r, Err("no"));
    assert_eq!(stages, 1);
}
