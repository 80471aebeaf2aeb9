//! Pareto dominance (plain and Deb's constrained), non-dominated sorting and crowding
//! distance. All orderings are total and tie-broken by index, so results never depend on
//! sort stability or thread timing.

use std::cmp::Ordering;

/// `a` dominates `b` (minimisation): no worse in every objective, better in at least one.
#[inline]
#[must_use]
pub fn dominates(a: &[f64], b: &[f64]) -> bool {
    let mut better = false;
    for (x, y) in a.iter().zip(b) {
        if x > y {
            return false;
        }
        if x < y {
            better = true;
        }
    }
    better
}

/// Deb's constrained domination: a feasible point (violation 0) beats an infeasible one; of two
/// infeasible points the smaller violation wins; two feasible points compare by Pareto
/// dominance.
#[inline]
#[must_use]
pub fn constrained_dominates(a: &[f64], va: f64, b: &[f64], vb: f64) -> bool {
    match (va == 0.0, vb == 0.0) {
        (true, true) => dominates(a, b),
        (true, false) => true,
        (false, true) => false,
        (false, false) => va < vb,
    }
}

/// Indices (ascending) of the points no other point dominates.
#[must_use]
pub fn non_dominated<P: AsRef<[f64]>>(points: &[P]) -> Vec<usize> {
    sort_fronts(points).into_iter().next().unwrap_or_default()
}

/// Non-dominated sorting: fronts of point indices, best first, each ascending.
///
/// Two objectives use an O(n log n) sweep; more use Deb's O(m n^2) fast non-dominated sort.
#[must_use]
pub fn sort_fronts<P: AsRef<[f64]>>(points: &[P]) -> Vec<Vec<usize>> {
    let idx: Vec<usize> = (0..points.len()).collect();
    sort_subset(points, &idx)
}

/// Deb's constrained non-dominated sorting: the feasible points (violation exactly 0) sorted
/// into Pareto fronts first, then the infeasible ones, one front per distinct violation value
/// in increasing order.
#[must_use]
pub fn constrained_sort_fronts<P: AsRef<[f64]>>(
    points: &[P],
    violation: &[f64],
) -> Vec<Vec<usize>> {
    let feasible: Vec<usize> = (0..points.len()).filter(|&i| violation[i] == 0.0).collect();
    let mut fronts = sort_subset(points, &feasible);
    let mut infeasible: Vec<usize> = (0..points.len()).filter(|&i| violation[i] != 0.0).collect();
    infeasible.sort_unstable_by(|&a, &b| violation[a].total_cmp(&violation[b]).then(a.cmp(&b)));
    let mut k = 0;
    while k < infeasible.len() {
        let v = violation[infeasible[k]];
        let mut front = Vec::new();
        while k < infeasible.len() && violation[infeasible[k]] == v {
            front.push(infeasible[k]);
            k += 1;
        }
        fronts.push(front);
    }
    fronts
}

fn sort_subset<P: AsRef<[f64]>>(points: &[P], subset: &[usize]) -> Vec<Vec<usize>> {
    if subset.is_empty() {
        return Vec::new();
    }
    let m = points[subset[0]].as_ref().len();
    let mut fronts = if m == 2 {
        sort_2d(points, subset)
    } else {
        sort_deb(points, subset)
    };
    for f in &mut fronts {
        f.sort_unstable();
    }
    fronts
}

/// Lexicographic sweep for two objectives: after sorting by (f1, f2) no later point dominates
/// an earlier one, and a point is dominated by a front exactly when it is dominated by the
/// front's last point; fronts are searched by bisection (domination by front k implies
/// domination by every front before it).
fn sort_2d<P: AsRef<[f64]>>(points: &[P], subset: &[usize]) -> Vec<Vec<usize>> {
    let mut order = subset.to_vec();
    order.sort_unstable_by(|&a, &b| {
        let (pa, pb) = (points[a].as_ref(), points[b].as_ref());
        pa[0]
            .total_cmp(&pb[0])
            .then(pa[1].total_cmp(&pb[1]))
            .then(a.cmp(&b))
    });
    let mut fronts: Vec<Vec<usize>> = Vec::new();
    for &q in &order {
        let pq = points[q].as_ref();
        let dominated_by = |front: &Vec<usize>| -> bool {
            front
                .last()
                .is_some_and(|&l| dominates(points[l].as_ref(), pq))
        };
        // First front that does not dominate q.
        let (mut lo, mut hi) = (0usize, fronts.len());
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            if dominated_by(&fronts[mid]) {
                lo = mid + 1;
            } else {
                hi = mid;
            }
        }
        if lo == fronts.len() {
            fronts.push(vec![q]);
        } else {
            fronts[lo].push(q);
        }
    }
    fronts
}

/// Deb's fast non-dominated sort.
fn sort_deb<P: AsRef<[f64]>>(points: &[P], subset: &[usize]) -> Vec<Vec<usize>> {
    let n = subset.len();
    let mut dominated_count = vec![0usize; n];
    let mut dominates_list: Vec<Vec<usize>> = vec![Vec::new(); n];
    for i in 0..n {
        for j in (i + 1)..n {
            let (a, b) = (points[subset[i]].as_ref(), points[subset[j]].as_ref());
            if dominates(a, b) {
                dominates_list[i].push(j);
                dominated_count[j] += 1;
            } else if dominates(b, a) {
                dominates_list[j].push(i);
                dominated_count[i] += 1;
            }
        }
    }
    let mut fronts = Vec::new();
    let mut current: Vec<usize> = (0..n).filter(|&i| dominated_count[i] == 0).collect();
    while !current.is_empty() {
        let mut next = Vec::new();
        for &i in &current {
            for &j in &dominates_list[i] {
                dominated_count[j] -= 1;
                if dominated_count[j] == 0 {
                    next.push(j);
                }
            }
        }
        fronts.push(current.iter().map(|&i| subset[i]).collect());
        current = next;
    }
    fronts
}

/// Crowding distance (Deb et al. 2002) of the points of one front, aligned with `front`:
/// boundary points get `f64::INFINITY`; an objective with zero spread adds nothing; fronts of
/// one or two points are all infinite.
#[must_use]
pub fn crowding_distance<P: AsRef<[f64]>>(points: &[P], front: &[usize]) -> Vec<f64> {
    let n = front.len();
    let mut d = vec![0.0; n];
    if n <= 2 {
        return vec![f64::INFINITY; n];
    }
    let m = points[front[0]].as_ref().len();
    let mut order: Vec<usize> = (0..n).collect();
    for k in 0..m {
        let val = |i: usize| points[front[i]].as_ref()[k];
        order.sort_unstable_by(|&a, &b| val(a).total_cmp(&val(b)).then(front[a].cmp(&front[b])));
        let (lo, hi) = (val(order[0]), val(order[n - 1]));
        d[order[0]] = f64::INFINITY;
        d[order[n - 1]] = f64::INFINITY;
        let spread = hi - lo;
        if spread <= 0.0 || !spread.is_finite() {
            continue;
        }
        for w in 1..n - 1 {
            d[order[w]] += (val(order[w + 1]) - val(order[w - 1])) / spread;
        }
    }
    d
}

/// Total order used by NSGA-II's survival: lower rank first, then larger crowding distance,
/// then lower index.
#[must_use]
pub fn rank_crowding_cmp(rank: (usize, f64, usize), other: (usize, f64, usize)) -> Ordering {
    rank.0
        .cmp(&other.0)
        .then(other.1.total_cmp(&rank.1))
        .then(rank.2.cmp(&other.2))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optim::rng::OptimRng;

    fn brute_fronts(points: &[Vec<f64>]) -> Vec<Vec<usize>> {
        let mut left: Vec<usize> = (0..points.len()).collect();
        let mut fronts = Vec::new();
        while !left.is_empty() {
            let front: Vec<usize> = left
                .iter()
                .copied()
                .filter(|&i| !left.iter().any(|&j| dominates(&points[j], &points[i])))
                .collect();
            left.retain(|i| !front.contains(i));
            fronts.push(front);
        }
        fronts
    }

    #[test]
    fn fast_sorts_agree_with_brute_force_including_ties() {
        let mut rng = OptimRng::new(3);
        for m in 2..=4 {
            for _ in 0..30 {
                let n = 1 + rng.below(40);
                // Coarse values force duplicates and ties.
                let pts: Vec<Vec<f64>> = (0..n)
                    .map(|_| (0..m).map(|_| rng.below(5) as f64).collect())
                    .collect();
                assert_eq!(sort_fronts(&pts), brute_fronts(&pts), "m={m} {pts:?}");
            }
        }
    }

    #[test]
    fn constrained_sort_puts_feasible_first_then_by_violation() {
        let pts = vec![
            vec![0.0, 0.0],
            vec![1.0, 1.0],
            vec![2.0, 0.5],
            vec![0.5, 3.0],
            vec![0.1, 0.1],
        ];
        let v = [2.0, 0.0, 0.0, 0.0, 0.5];
        let fronts = constrained_sort_fronts(&pts, &v);
        assert_eq!(fronts, vec![vec![1, 2, 3], vec![4], vec![0]]);
        assert!(constrained_dominates(&[5.0], 0.0, &[0.0], 1.0));
        assert!(!constrained_dominates(&[0.0], 1.0, &[5.0], 0.0));
        assert!(constrained_dominates(&[5.0], 0.5, &[0.0], 1.0));
    }

    #[test]
    fn crowding_distance_of_a_line() {
        let pts = vec![
            vec![0.0, 4.0],
            vec![1.0, 3.0],
            vec![3.0, 1.0],
            vec![4.0, 0.0],
        ];
        let d = crowding_distance(&pts, &[0, 1, 2, 3]);
        assert!(d[0].is_infinite() && d[3].is_infinite());
        assert!((d[1] - 1.5).abs() < 1e-12 && (d[2] - 1.5).abs() < 1e-12);
    }
}
