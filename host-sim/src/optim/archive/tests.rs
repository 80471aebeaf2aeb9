//! Archive tests: dominance, duplicates, non-finite and infeasible candidates, capacity,
//! truncation against brute-force hypervolume differences, insertion order.

use super::*;
use crate::optim::hypervolume::hypervolume;
use crate::optim::pareto::non_dominated;
use crate::optim::rng::OptimRng;

fn ind(f: &[f64], violation: f64) -> Individual<usize> {
    Individual {
        decision: 0,
        objectives: f.to_vec(),
        constraints: vec![violation],
        violation,
    }
}

fn objectives(a: &ParetoArchive<usize>) -> Vec<Vec<f64>> {
    a.members().iter().map(|m| m.objectives.clone()).collect()
}

#[test]
fn dominated_and_duplicate_candidates_are_refused_dominated_members_leave() {
    for m in [2, 3] {
        let p = |v: &[f64]| {
            let mut x = v.to_vec();
            x.resize(m, 1.0);
            x
        };
        let mut a = ParetoArchive::new(10).unwrap();
        assert!(a.offer(&ind(&p(&[1.0, 2.0]), 0.0)));
        assert!(a.offer(&ind(&p(&[2.0, 1.0]), 0.0)));
        // Dominated, weakly dominated (equal in one objective) and duplicates are refused.
        assert!(!a.offer(&ind(&p(&[2.0, 3.0]), 0.0)));
        assert!(!a.offer(&ind(&p(&[1.0, 2.5]), 0.0)));
        assert!(!a.offer(&ind(&p(&[1.0, 2.0]), 0.0)));
        assert_eq!(a.len(), 2, "m={m}");
        // A point dominating both replaces them.
        assert!(a.offer(&ind(&p(&[0.5, 0.5]), 0.0)));
        assert_eq!(objectives(&a), vec![p(&[0.5, 0.5])], "m={m}");
        // Equal in one objective, better in the other: dominates.
        assert!(a.offer(&ind(&p(&[0.5, 0.25]), 0.0)));
        assert_eq!(objectives(&a), vec![p(&[0.5, 0.25])], "m={m}");
    }
}

#[test]
fn infeasible_failed_and_non_finite_candidates_never_enter() {
    let mut a = ParetoArchive::new(4).unwrap();
    assert!(!a.offer(&ind(&[0.0, 0.0], 0.5)));
    assert!(!a.offer(&ind(&[0.0, 0.0], f64::MAX)));
    assert!(!a.offer(&ind(&[f64::NAN, 0.0], 0.0)));
    assert!(!a.offer(&ind(&[0.0, f64::INFINITY], 0.0)));
    assert!(!a.offer(&ind(&[f64::NEG_INFINITY, 0.0], 0.0)));
    assert!(!a.offer(&ind(&[], 0.0)));
    assert!(a.is_empty());
    assert!(a.offer(&ind(&[1.0, 1.0], 0.0)));
    // A NaN that would "not be dominated" by anything still stays out.
    assert!(!a.offer(&ind(&[f64::NAN, f64::NAN], 0.0)));
    // Wrong dimension.
    assert!(!a.offer(&ind(&[0.0, 0.0, 0.0], 0.0)));
    assert_eq!(objectives(&a), vec![vec![1.0, 1.0]]);
    assert!(matches!(
        ParetoArchive::<usize>::new(0),
        Err(ConfigError::Count {
            name: "archive",
            value: 0,
            ..
        })
    ));
}

/// Random points with coarse values (ties and duplicates) offered in any order: below
/// capacity the archive is exactly the distinct non-dominated set, in lexicographic order.
#[test]
fn below_capacity_the_archive_is_the_non_dominated_set_whatever_the_order() {
    let mut rng = OptimRng::new(11);
    for m in [2, 3, 4] {
        for _ in 0..40 {
            let n = 1 + rng.below(60);
            let pts: Vec<Vec<f64>> = (0..n)
                .map(|_| (0..m).map(|_| rng.below(6) as f64).collect())
                .collect();
            let mut expected: Vec<Vec<f64>> = non_dominated(&pts)
                .into_iter()
                .map(|i| pts[i].clone())
                .collect();
            expected.sort_by(|a, b| lex_cmp(a, b));
            expected.dedup();
            let mut reference: Option<ParetoArchive<usize>> = None;
            for shuffle in 0..3 {
                let mut order: Vec<usize> = (0..n).collect();
                if shuffle > 0 {
                    rng.shuffle(&mut order);
                }
                let mut a = ParetoArchive::new(1000).unwrap();
                for &i in &order {
                    a.offer(&ind(&pts[i], 0.0));
                }
                assert_eq!(objectives(&a), expected, "m={m} {pts:?}");
                if let Some(r) = &reference {
                    assert_eq!(r, &a);
                }
                reference = Some(a);
            }
        }
    }
}

/// Points on a random front (distinct, mutually non-dominated).
fn front_points(rng: &mut OptimRng, n: usize, m: usize) -> Vec<Vec<f64>> {
    (0..n)
        .map(|_| {
            // Positive direction scaled onto the sphere ||f|| = 1 (concave front), plus noise
            // along the ray keeps them mutually non-dominated only up to luck: filter below.
            let mut d: Vec<f64> = (0..m).map(|_| 0.05 + rng.uniform()).collect();
            let norm = d.iter().map(|v| v * v).sum::<f64>().sqrt();
            d.iter_mut().for_each(|v| *v = 3.0 * *v / norm - 1.0);
            d
        })
        .collect()
}

/// Brute force: the index whose removal loses the least hypervolume, with the reference point
/// nadir + 0.1 (nadir - ideal) of the raw points.
fn brute_least(pts: &[Vec<f64>]) -> usize {
    let m = pts[0].len();
    let r: Vec<f64> = (0..m)
        .map(|k| {
            let lo = pts.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
            let hi = pts.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
            hi + 0.1 * (hi - lo)
        })
        .collect();
    let all = hypervolume(pts, &r).unwrap();
    let loss = |i: usize| {
        let rest: Vec<&Vec<f64>> = pts
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(_, p)| p)
            .collect();
        all - hypervolume(&rest, &r).unwrap()
    };
    (0..pts.len())
        .min_by(|&a, &b| loss(a).total_cmp(&loss(b)))
        .unwrap()
}

#[test]
fn truncation_removes_the_least_contributor_as_brute_force_does() {
    let mut rng = OptimRng::new(5);
    for m in [2, 3, 4] {
        for _ in 0..30 {
            let cap = 2 + rng.below(12);
            let raw = front_points(&mut rng, 3 * cap, m);
            let idx = non_dominated(&raw);
            if idx.len() < cap + 1 {
                continue;
            }
            let pts: Vec<Vec<f64>> = idx.iter().take(cap + 1).map(|&i| raw[i].clone()).collect();
            let mut a = ParetoArchive::new(cap).unwrap();
            for p in &pts[..cap] {
                assert!(a.offer(&ind(p, 0.0)));
            }
            let entered = a.offer(&ind(&pts[cap], 0.0));
            assert_eq!(a.len(), cap);
            let gone = brute_least(&pts);
            assert_eq!(entered, gone != cap, "m={m}");
            let mut expected: Vec<Vec<f64>> = pts
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != gone)
                .map(|(_, p)| p.clone())
                .collect();
            expected.sort_by(|a, b| lex_cmp(a, b));
            assert_eq!(objectives(&a), expected, "m={m} cap={cap}");
        }
    }
}

#[test]
fn capacity_is_held_and_members_stay_non_dominated() {
    let mut rng = OptimRng::new(8);
    for m in [2, 3] {
        let mut a = ParetoArchive::new(7).unwrap();
        for step in 0..400 {
            // Points drifting towards the front, so the archive keeps changing.
            let shift = 1.0 - step as f64 / 400.0;
            let mut p = front_points(&mut rng, 1, m).remove(0);
            p.iter_mut().for_each(|v| *v += shift * rng.uniform());
            a.offer(&ind(&p, 0.0));
            assert!(a.len() <= 7);
            let f = objectives(&a);
            assert_eq!(non_dominated(&f).len(), f.len());
            assert!(f.windows(2).all(|w| lex_cmp(&w[0], &w[1]).is_lt()));
        }
        assert_eq!(a.len(), 7, "m={m}");
        let json = serde_json::to_string(&a).unwrap();
        let back: ParetoArchive<usize> = serde_json::from_str(&json).unwrap();
        assert_eq!(back, a);
    }
}

/// A full 2-D archive on the line f1 + f2 = 1 keeps the extremes and spreads evenly: the
/// greedy hypervolume truncation of 0, 0.1, ..., 1 offered with midpoints keeps the grid.
#[test]
fn hypervolume_truncation_keeps_extremes_and_spread_in_2d() {
    let mut a = ParetoArchive::new(11).unwrap();
    for i in 0..=10 {
        let x = f64::from(i) / 10.0;
        assert!(a.offer(&ind(&[x, 1.0 - x], 0.0)));
    }
    // A point between two grid points has the smallest box; it is refused at once.
    assert!(!a.offer(&ind(&[0.31, 0.69], 0.0)));
    let xs: Vec<f64> = a.members().iter().map(|m| m.objectives[0]).collect();
    assert_eq!(xs.len(), 11);
    assert_eq!((xs[0], xs[10]), (0.0, 1.0));
}

/// Magnitudes near the float limits and extents lost to rounding: no panic, no NaN, the
/// capacity held (the margin falls back to the unit box, or the last member leaves).
#[test]
fn extreme_magnitudes_keep_the_archive_bounded() {
    for m in [2, 3] {
        let mut a = ParetoArchive::new(3).unwrap();
        let cases: [(f64, f64); 3] = [(1e308, -1e307), (1e16, 1.0), (1e-300, 1e-310)];
        for (base, step) in cases {
            for i in 0..8 {
                let t = f64::from(i);
                let mut p = vec![base + t * step, base - t * step];
                p.resize(m, base);
                a.offer(&ind(&p, 0.0));
                assert!(a.len() <= 3, "m={m} {p:?}");
                assert!(
                    a.members()
                        .iter()
                        .all(|x| x.objectives.iter().all(|v| v.is_finite()))
                );
            }
        }
    }
}
