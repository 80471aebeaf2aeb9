//! MHACO's solution archive: which `ker` of the archive and the new ants survive, and in which
//! order (the order is the rank that the pheromone weights act on).
//!
//! As pagmo's `maco`: the candidates are sorted into non-dominated fronts; each front, best
//! first, is ordered by exclusive hypervolume contribution (largest first; ties by candidate
//! index) with respect to the front's own nadir point plus `offset` in every objective (pagmo:
//! 0.1 for the initial population, 0.01 afterwards), and the archive is filled front by front.
//!
//! What is ranked depends on [`ConstraintHandling`]:
//! * [`ConstraintHandling::AsObjectives`]: the thesis' set-up (sec. 9.3.2): each constraint
//!   becomes an extra objective `min(cap, 1 + g_i / s_i)` and every objective gets `penalty`
//!   per violated constraint;
//! * [`ConstraintHandling::FeasibilityFirst`]: the thesis' recommendation (sec. 10.2): the
//!   feasible candidates fill the archive first (fronts and hypervolume as above, objectives
//!   only), then the infeasible ones by increasing violation (Lampinen / Deb).
//!
//! In both modes a failed evaluation (a non-finite objective or constraint, stored with
//! violation `f64::MAX`) is never ranked by hypervolume: failed candidates come last, by
//! index. Non-finite values therefore never reach the hypervolume code.

use serde::{Deserialize, Serialize};

use crate::optim::hypervolume::contributions;
use crate::optim::pareto::sort_fronts;
use crate::optim::population::Individual;

/// How MHACO treats the problem's inequality constraints `g_i <= 0`. For unconstrained
/// problems both modes are pagmo's `maco`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ConstraintHandling {
    /// Constraints as extra objectives with the thesis' normalisation (sec. 9.3.2).
    AsObjectives {
        /// Scale `s_i > 0` of each constraint (the limit a constraint `c_i <= c_max` was
        /// written against as `g_i = c_i - c_max`, so that `1 + g_i / s_i = c_i / c_max`);
        /// `None`: 1 for every constraint.
        scales: Option<Vec<f64>>,
        /// Upper cap of a normalised constraint objective (thesis: 2.0).
        cap: f64,
        /// Added to every objective per violated constraint (thesis: 0.5).
        penalty: f64,
    },
    /// Feasible candidates first, then infeasible ones by violation (sec. 10.2).
    FeasibilityFirst,
}

impl ConstraintHandling {
    /// The thesis' settings of the constraints-as-objectives mode: unit scales, cap 2.0,
    /// penalty 0.5.
    #[must_use]
    pub fn thesis_objectives() -> Self {
        Self::AsObjectives {
            scales: None,
            cap: 2.0,
            penalty: 0.5,
        }
    }

    /// The vector an individual is ranked by in the constraints-as-objectives mode:
    /// objectives (with penalties) followed by the normalised constraints; `None` for a
    /// failed individual or one whose transformed values are not finite.
    #[must_use]
    pub fn ranking_vector<D>(&self, ind: &Individual<D>) -> Option<Vec<f64>> {
        if ind.is_failed() {
            return None;
        }
        let v = match self {
            Self::FeasibilityFirst => ind.objectives.clone(),
            Self::AsObjectives {
                scales,
                cap,
                penalty,
            } => {
                let violated = ind.constraints.iter().filter(|&&g| g > 0.0).count();
                let add = penalty * violated as f64;
                let mut v: Vec<f64> = ind.objectives.iter().map(|f| f + add).collect();
                for (i, &g) in ind.constraints.iter().enumerate() {
                    let s = scales.as_ref().map_or(1.0, |s| s[i]);
                    v.push((1.0 + g / s).min(*cap));
                }
                v
            }
        };
        v.iter().all(|x| x.is_finite()).then_some(v)
    }
}

/// Order `points` (one front) by exclusive hypervolume contribution, largest first, ties by
/// position. The reference point is the front's nadir plus `offset`. Should the volumes
/// overflow, the front is first mapped affinely onto the unit box (which scales every
/// contribution by the same factor, so the order is that of the raw values).
fn order_by_contribution(points: &[&[f64]], offset: f64) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    if points.len() <= 1 {
        return order;
    }
    let d = points[0].len();
    let nadir: Vec<f64> = (0..d)
        .map(|k| {
            points
                .iter()
                .map(|p| p[k])
                .fold(f64::NEG_INFINITY, f64::max)
        })
        .collect();
    let reference: Vec<f64> = nadir.iter().map(|v| v + offset).collect();
    let contrib = match contributions(points, &reference) {
        Ok(c) => c,
        Err(_) => {
            let ideal: Vec<f64> = (0..d)
                .map(|k| points.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min))
                .collect();
            let scale: Vec<f64> = (0..d)
                .map(|k| {
                    let s = nadir[k] - ideal[k];
                    if s > 0.0 && s.is_finite() { s } else { 1.0 }
                })
                .collect();
            let unit: Vec<Vec<f64>> = points
                .iter()
                .map(|p| (0..d).map(|k| (p[k] - ideal[k]) / scale[k]).collect())
                .collect();
            let reference: Vec<f64> = (0..d)
                .map(|k| (nadir[k] - ideal[k]) / scale[k] + offset)
                .collect();
            contributions(&unit, &reference).unwrap_or_else(|_| vec![0.0; points.len()])
        }
    };
    order.sort_by(|&a, &b| contrib[b].total_cmp(&contrib[a]).then(a.cmp(&b)));
    order
}

/// Fill `out` with the hypervolume ranking of `subset` (indices into `vectors`) front by
/// front until it holds `keep` indices.
fn fill_by_fronts(
    vectors: &[&[f64]],
    subset: &[usize],
    keep: usize,
    offset: f64,
    out: &mut Vec<usize>,
) {
    if subset.is_empty() || out.len() >= keep {
        return;
    }
    let points: Vec<&[f64]> = subset.iter().map(|&i| vectors[i]).collect();
    for front in sort_fronts(&points) {
        if out.len() >= keep {
            break;
        }
        let members: Vec<&[f64]> = front.iter().map(|&k| points[k]).collect();
        for k in order_by_contribution(&members, offset) {
            if out.len() >= keep {
                break;
            }
            out.push(subset[front[k]]);
        }
    }
}

/// Indices of the best `keep` candidates, best first (see the module documentation).
#[must_use]
pub fn rank<D>(
    candidates: &[Individual<D>],
    handling: &ConstraintHandling,
    keep: usize,
    offset: f64,
) -> Vec<usize> {
    let keep = keep.min(candidates.len());
    let mut out = Vec::with_capacity(keep);
    let mut failed = Vec::new();
    match handling {
        ConstraintHandling::AsObjectives { .. } => {
            let mut vectors = Vec::with_capacity(candidates.len());
            let mut ok = Vec::with_capacity(candidates.len());
            for (i, c) in candidates.iter().enumerate() {
                match handling.ranking_vector(c) {
                    Some(v) => {
                        ok.push(i);
                        vectors.push(v);
                    }
                    None => {
                        failed.push(i);
                        vectors.push(Vec::new());
                    }
                }
            }
            let refs: Vec<&[f64]> = vectors.iter().map(Vec::as_slice).collect();
            fill_by_fronts(&refs, &ok, keep, offset, &mut out);
        }
        ConstraintHandling::FeasibilityFirst => {
            let vectors: Vec<&[f64]> = candidates.iter().map(|c| c.objectives.as_slice()).collect();
            let feasible: Vec<usize> = (0..candidates.len())
                .filter(|&i| candidates[i].is_feasible())
                .collect();
            fill_by_fronts(&vectors, &feasible, keep, offset, &mut out);
            let mut infeasible: Vec<usize> = (0..candidates.len())
                .filter(|&i| !candidates[i].is_feasible())
                .collect();
            infeasible.sort_by(|&a, &b| {
                candidates[a]
                    .violation
                    .total_cmp(&candidates[b].violation)
                    .then(a.cmp(&b))
            });
            for i in infeasible {
                if candidates[i].is_failed() {
                    failed.push(i);
                } else if out.len() < keep {
                    out.push(i);
                }
            }
        }
    }
    for i in failed {
        if out.len() >= keep {
            break;
        }
        out.push(i);
    }
    out
}

/// The ideal point of the ranked vectors of `members` (`f64::MAX` where none), with the
/// smallest violation appended: MHACO's progress marker for `evalstop` and `n_gen_mark`.
#[must_use]
pub fn progress_marker<D>(members: &[Individual<D>], handling: &ConstraintHandling) -> Vec<f64> {
    let mut ideal: Vec<f64> = Vec::new();
    let mut min_violation = f64::MAX;
    for m in members {
        min_violation = min_violation.min(m.violation);
        let v = match handling {
            ConstraintHandling::FeasibilityFirst if !m.is_feasible() => continue,
            ConstraintHandling::FeasibilityFirst => Some(m.objectives.clone()),
            ConstraintHandling::AsObjectives { .. } => handling.ranking_vector(m),
        };
        let Some(v) = v else { continue };
        if ideal.is_empty() {
            ideal = v;
        } else {
            for (z, x) in ideal.iter_mut().zip(v) {
                *z = z.min(x);
            }
        }
    }
    ideal.push(min_violation);
    ideal
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optim::problem::Evaluation;

    fn ind(f: Vec<f64>, g: Vec<f64>) -> Individual<()> {
        let (m, c) = (f.len(), g.len());
        Individual::from_evaluation((), Evaluation::with_constraints(f, g), 0, m, c).unwrap()
    }

    #[test]
    fn fronts_then_largest_contribution_first() {
        // Front 1: (0,3) (1,1) (3,0); (1,1) holds the largest exclusive box (2 x 2) with the
        // reference nadir (3,3) + 0.01. Then (2,2), then (4,4), one front each.
        let c = vec![
            ind(vec![4.0, 4.0], vec![]),
            ind(vec![0.0, 3.0], vec![]),
            ind(vec![2.0, 2.0], vec![]),
            ind(vec![1.0, 1.0], vec![]),
            ind(vec![3.0, 0.0], vec![]),
        ];
        let r = rank(&c, &ConstraintHandling::FeasibilityFirst, 5, 0.01);
        assert_eq!(r[0], 3);
        assert_eq!(r[3..], [2, 0]);
        // Both extremes contribute 1 x 0.01: index order.
        assert_eq!(r[1..3], [1, 4]);
        assert_eq!(
            rank(&c, &ConstraintHandling::thesis_objectives(), 2, 0.01),
            vec![3, 1]
        );
    }

    #[test]
    fn failed_individuals_never_reach_the_hypervolume_and_come_last() {
        let c = vec![
            ind(vec![f64::NAN, 1.0], vec![]),
            ind(vec![1.0, f64::INFINITY], vec![]),
            ind(vec![1.0, 2.0], vec![]),
            ind(vec![2.0, 1.0], vec![]),
            // Finite but enormous: the volumes overflow, the ranking still works.
            ind(vec![-1e308, 1e308], vec![]),
        ];
        for h in [
            ConstraintHandling::FeasibilityFirst,
            ConstraintHandling::thesis_objectives(),
        ] {
            let r = rank(&c, &h, 5, 0.01);
            assert_eq!(r.len(), 5);
            assert_eq!(r[3..], [0, 1], "{h:?}");
            let marker = progress_marker(&c, &h);
            assert!(marker.iter().all(|v| v.is_finite()), "{marker:?}");
        }
    }

    #[test]
    fn feasibility_first_then_violation() {
        let c = vec![
            ind(vec![0.0, 0.0], vec![0.5]),
            ind(vec![5.0, 5.0], vec![-1.0]),
            ind(vec![0.0, 0.0], vec![0.1]),
            ind(vec![6.0, 4.0], vec![0.0]),
        ];
        let r = rank(&c, &ConstraintHandling::FeasibilityFirst, 4, 0.01);
        assert_eq!(r, vec![1, 3, 2, 0]);
        // As objectives: (0,0)+0.5 with constraint objective 1.1 / 1.5 competes.
        let h = ConstraintHandling::thesis_objectives();
        assert_eq!(
            h.ranking_vector(&c[0]).unwrap(),
            vec![0.5, 0.5, 1.5],
            "penalty 0.5 per violated constraint, 1 + g"
        );
        assert_eq!(h.ranking_vector(&c[1]).unwrap(), vec![5.0, 5.0, 0.0]);
        let big = ind(vec![0.0, 0.0], vec![7.0]);
        assert_eq!(h.ranking_vector(&big).unwrap()[2], 2.0, "capped");
        let scaled = ConstraintHandling::AsObjectives {
            scales: Some(vec![2.0]),
            cap: 2.0,
            penalty: 0.5,
        };
        assert_eq!(scaled.ranking_vector(&c[0]).unwrap()[2], 1.25);
    }
}
