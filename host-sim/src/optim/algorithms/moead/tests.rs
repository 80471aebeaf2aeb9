//! Unit tests of MOEA/D's selection rules.

use super::*;

fn ind(f: [f64; 2], violation: f64) -> Individual<Vec<f64>> {
    Individual {
        decision: vec![0.0],
        objectives: f.to_vec(),
        constraints: vec![violation],
        violation,
    }
}

/// Lampinen's rules (thesis 4.1.3) on one subproblem with weight (0.5, 0.5), ideal (0, 0).
#[test]
fn lampinen_rules_decide_replacement() {
    let mut m = Moead::new(MoeadConfig::default(), 0);
    m.ideal = vec![0.0, 0.0];
    let w = [0.5, 0.5];
    let good = ind([1.0, 1.0], 0.0);
    let worse = ind([2.0, 1.0], 0.0);
    // Both feasible: strictly lower decomposed value wins; equal does not.
    assert!(m.child_wins(&good, &worse, &w));
    assert!(!m.child_wins(&worse, &good, &w));
    assert!(!m.child_wins(&good, &good.clone(), &w));
    // Feasible beats infeasible whatever the objectives, never the reverse.
    let infeasible_great = ind([0.0, 0.0], 0.1);
    assert!(m.child_wins(&worse, &infeasible_great, &w));
    assert!(!m.child_wins(&infeasible_great, &worse, &w));
    // Two infeasible: lower or equal violation wins, objectives ignored.
    let a = ind([9.0, 9.0], 0.1);
    let b = ind([0.0, 0.0], 0.2);
    assert!(m.child_wins(&a, &b, &w));
    assert!(!m.child_wins(&b, &a, &w));
    assert!(m.child_wins(&b, &ind([5.0, 5.0], 0.2), &w));
}

/// For unconstrained problems the ideal point is pagmo's: the minimum of every objective
/// over everything evaluated; infeasible points never move it.
#[test]
fn ideal_point_tracks_feasible_minimum() {
    let mut z = vec![f64::MAX; 2];
    Moead::update_ideal(&mut z, &ind([3.0, 1.0], 0.0));
    Moead::update_ideal(&mut z, &ind([1.0, 4.0], 0.0));
    Moead::update_ideal(&mut z, &ind([0.0, 0.0], 1.0));
    assert_eq!(z, vec![1.0, 1.0]);
}
