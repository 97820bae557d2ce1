//! Pareto-front invariants by property test: no member dominates another, every excluded point is
//! dominated by a member, and ranks agree with brute force.

use loomkin_study::{Sense, dominates, non_dominated_ranks, pareto_front};
use proptest::prelude::*;

fn points(m: usize) -> impl Strategy<Value = Vec<Vec<f64>>> {
    // Coarse integer values make ties and duplicates common.
    prop::collection::vec(prop::collection::vec((0i32..12).prop_map(f64::from), m), 0..80)
}

fn senses(m: usize) -> impl Strategy<Value = Vec<Sense>> {
    prop::collection::vec(prop_oneof![Just(Sense::Minimize), Just(Sense::Maximize)], m)
}

fn check(p: &[Vec<f64>], s: &[Sense]) {
    let front = pareto_front(p, s).unwrap();
    let on: Vec<bool> = (0..p.len()).map(|i| front.contains(&i)).collect();
    for &a in &front {
        for &b in &front {
            assert!(!dominates(&p[a], &p[b], s), "front member {a} dominates front member {b}");
        }
    }
    for i in 0..p.len() {
        let dominated_by_any = (0..p.len()).any(|j| dominates(&p[j], &p[i], s));
        assert_eq!(!dominated_by_any, on[i], "point {i}: brute force and front disagree");
        if !on[i] {
            assert!(front.iter().any(|&f| dominates(&p[f], &p[i], s)), "excluded {i} not dominated by a member");
        }
    }
    // Ranks: rank r points are non-dominated among points of rank ≥ r, and dominated by some
    // point of rank r − 1.
    let rank = non_dominated_ranks(p, s).unwrap();
    for i in 0..p.len() {
        for j in 0..p.len() {
            if rank[j] >= rank[i] {
                assert!(!dominates(&p[j], &p[i], s));
            }
        }
        if rank[i] > 0 {
            assert!((0..p.len()).any(|j| rank[j] + 1 == rank[i] && dominates(&p[j], &p[i], s)));
        }
    }
}

proptest! {
    #[test]
    fn two_objectives(p in points(2), s in senses(2)) {
        check(&p, &s);
    }

    #[test]
    fn three_objectives(p in points(3), s in senses(3)) {
        check(&p, &s);
    }
}
