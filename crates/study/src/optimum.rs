//! The constrained optimum of an evaluated table.

use rayon::prelude::*;

/// Index of the item of least `objective` among those for which `feasible` holds (evaluated in
/// parallel). Items whose objective is not finite are skipped; ties go to the lowest index.
/// `None` when no item is feasible.
pub fn argmin_subject_to<T, O, C>(items: &[T], objective: O, feasible: C) -> Option<usize>
where
    T: Sync,
    O: Fn(&T) -> f64 + Sync,
    C: Fn(&T) -> bool + Sync,
{
    items
        .par_iter()
        .enumerate()
        .filter(|(_, t)| feasible(t))
        .map(|(i, t)| (objective(t), i))
        .filter(|(v, _)| v.is_finite())
        .reduce_with(|a, b| match a.0.total_cmp(&b.0) {
            std::cmp::Ordering::Less => a,
            std::cmp::Ordering::Greater => b,
            std::cmp::Ordering::Equal => {
                if a.1 <= b.1 {
                    a
                } else {
                    b
                }
            }
        })
        .map(|(_, i)| i)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn picks_the_least_feasible() {
        let items: Vec<(f64, f64)> = (0..10_000).map(|i| (i as f64, ((i * 7919) % 10_007) as f64)).collect();
        // Least second value among items whose first value is at least 5000, by brute force.
        let expect = (0..items.len())
            .filter(|&i| items[i].0 >= 5000.0)
            .min_by(|&a, &b| items[a].1.total_cmp(&items[b].1).then(a.cmp(&b)))
            .unwrap();
        assert_eq!(argmin_subject_to(&items, |t| t.1, |t| t.0 >= 5000.0), Some(expect));
        assert_eq!(argmin_subject_to(&items, |t| t.1, |t| t.0 < 0.0), None);
        let ties = [3.0, 1.0, 1.0, f64::NAN];
        assert_eq!(argmin_subject_to(&ties, |t| *t, |_| true), Some(1));
    }
}
