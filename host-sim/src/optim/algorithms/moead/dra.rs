//! Opt-in dynamic resource allocation of MOEA/D-DRA (Zhang, Liu & Li, "The performance of a
//! new version of MOEA/D on CEC09 unconstrained MOP test instances", IEEE CEC 2009; the
//! CEC 2009 MOO competition's winner). Not pagmo.
//!
//! Every subproblem `i` has a utility `pi_i` (1 at the start). Each generation works on a
//! *selection* of subproblems instead of all of them: the boundary subproblems (for each
//! objective, the subproblem whose weight is largest in it), then, until `per_generation`
//! (default population / 5) are chosen, the winner of a `tournament`-way tournament on
//! utility among the not yet chosen (candidates drawn uniformly with replacement, the first
//! drawn wins ties; the winner leaves the candidates), as in the reference implementation.
//! Every `period` generations (the paper's 50) each subproblem's relative improvement
//! `Delta_i = (g_old - g_new) / g_old` of its member's decomposed value since the last update
//! (both values with the *current* ideal point) sets `pi_i = 1` if `Delta_i > 0.001`, else
//! `pi_i *= 0.95 + 0.05 Delta_i / 0.001`.
//!
//! Extensions beyond the paper, which has neither constraints nor a guard for a worse value:
//! * a negative `Delta_i` (the member's value with the moved ideal point is worse than the
//!   saved one's) counts as 0 (factor 0.95), so utilities stay in [0, 1];
//! * constraints (Lampinen's rules never let an infeasible child replace a feasible member):
//!   a member that became feasible has improved (`pi_i = 1`); for two infeasible ones
//!   `Delta_i` is the relative decrease of the violation;
//! * `g_old = 0` (or non-finite): improvement iff `g_new < g_old`.

use serde::{Deserialize, Serialize};

use crate::optim::error::ConfigError;
use crate::optim::population::Individual;
use crate::optim::rng::OptimRng;

const NAME: &str = "moead";

/// Settings of MOEA/D-DRA's dynamic resource allocation (defaults: the paper's).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ResourceAllocation {
    /// Generations between utility updates (paper: 50; at least 1).
    pub period: u64,
    /// Tournament size of the selection on utility (paper: 10; at least 1).
    pub tournament: usize,
    /// Subproblems worked on per generation, boundary ones included; `None` (default):
    /// population / 5 as in the paper (at least the number of objectives). One generation
    /// then makes this many children, so 25,000 evaluations are 25,000 / (population / 5)
    /// generations.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub per_generation: Option<usize>,
}

impl Default for ResourceAllocation {
    fn default() -> Self {
        Self {
            period: 50,
            tournament: 10,
            per_generation: None,
        }
    }
}

impl ResourceAllocation {
    /// Subproblems per generation for `population` subproblems and `objectives` objectives.
    #[must_use]
    pub fn subproblems_per_generation(&self, population: usize, objectives: usize) -> usize {
        self.per_generation
            .unwrap_or((population / 5).max(objectives).min(population))
    }

    pub(super) fn check(&self, population: usize) -> Result<(), ConfigError> {
        if self.period == 0 {
            return Err(ConfigError::Count {
                algorithm: NAME,
                name: "resource_allocation.period",
                value: 0,
                range: "[1, inf) generations (the paper: 50)",
            });
        }
        if self.tournament == 0 {
            return Err(ConfigError::Count {
                algorithm: NAME,
                name: "resource_allocation.tournament",
                value: 0,
                range: "[1, population] (the paper: 10)",
            });
        }
        if let Some(k) = self.per_generation
            && (k == 0 || k > population)
        {
            return Err(ConfigError::Count {
                algorithm: NAME,
                name: "resource_allocation.per_generation",
                value: k,
                range: "[1, population] (or leave it out: population / 5)",
            });
        }
        Ok(())
    }
}

/// Utility state of a DRA run (serialised with the run).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub(super) struct DraState {
    /// Utility `pi_i` per subproblem.
    #[serde(with = "crate::optim::nonfinite::vec")]
    pub(super) utility: Vec<f64>,
    /// Objectives of each subproblem's member at the last update.
    #[serde(with = "crate::optim::nonfinite::vec2")]
    saved_objectives: Vec<Vec<f64>>,
    /// Violation of each subproblem's member at the last update.
    #[serde(with = "crate::optim::nonfinite::vec")]
    saved_violation: Vec<f64>,
}

impl DraState {
    /// Check a restored state: one utility, saved objective vector and violation per
    /// subproblem, not NaN.
    pub(super) fn validate(&self, n: usize, m: usize) -> Result<(), crate::optim::StateError> {
        use crate::optim::restore::{bad, count};
        count("dra.utility.len()", self.utility.len(), n)?;
        count("dra.saved_objectives.len()", self.saved_objectives.len(), n)?;
        count("dra.saved_violation.len()", self.saved_violation.len(), n)?;
        for (i, f) in self.saved_objectives.iter().enumerate() {
            count(&format!("dra.saved_objectives[{i}].len()"), f.len(), m)?;
        }
        let all = self
            .utility
            .iter()
            .chain(&self.saved_violation)
            .chain(self.saved_objectives.iter().flatten());
        if all.clone().any(|x| x.is_nan()) {
            return Err(bad(
                "dra",
                "NaN",
                "utilities and saved values must be numbers",
            ));
        }
        Ok(())
    }
}

/// Improvement above which a subproblem's utility is reset to 1 (the paper's 0.001).
const IMPROVING: f64 = 0.001;

/// Relative decrease from `old` to `new` (see the module notes for the guards).
fn relative_decrease(old: f64, new: f64) -> f64 {
    if old != 0.0 && old.is_finite() {
        let d = (old - new) / old.abs();
        if d.is_nan() { 0.0 } else { d }
    } else if new < old {
        f64::INFINITY
    } else {
        0.0
    }
}

impl DraState {
    /// Utilities 1 and the initial population saved.
    pub(super) fn new<D>(population: &[Individual<D>]) -> Self {
        Self {
            utility: vec![1.0; population.len()],
            saved_objectives: population.iter().map(|i| i.objectives.clone()).collect(),
            saved_violation: population.iter().map(|i| i.violation).collect(),
        }
    }

    /// The utility update: `value(i, objectives)` is subproblem `i`'s decomposed value with
    /// the current ideal point.
    pub(super) fn update<D>(
        &mut self,
        population: &[Individual<D>],
        value: impl Fn(usize, &[f64]) -> f64,
    ) {
        for (i, member) in population.iter().enumerate() {
            let was_feasible = self.saved_violation[i] == 0.0;
            let delta = match (was_feasible, member.is_feasible()) {
                (true, true) => relative_decrease(
                    value(i, &self.saved_objectives[i]),
                    value(i, &member.objectives),
                ),
                (false, true) => f64::INFINITY,
                (false, false) => relative_decrease(self.saved_violation[i], member.violation),
                (true, false) => 0.0,
            };
            let pi = &mut self.utility[i];
            if delta > IMPROVING {
                *pi = 1.0;
            } else {
                *pi *= 0.95 + 0.05 * delta.max(0.0) / IMPROVING;
            }
            self.saved_objectives[i].clone_from(&member.objectives);
            self.saved_violation[i] = member.violation;
        }
    }

    /// This generation's subproblems: `boundary` first, then tournament winners on utility
    /// until `count` are chosen. `candidates` is a reused buffer.
    pub(super) fn select(
        &self,
        boundary: &[usize],
        count: usize,
        tournament: usize,
        rng: &mut OptimRng,
        order: &mut Vec<usize>,
        candidates: &mut Vec<usize>,
    ) {
        order.clear();
        order.extend(boundary.iter().copied().take(count));
        candidates.clear();
        candidates.extend((0..self.utility.len()).filter(|i| !boundary.contains(i)));
        while order.len() < count && !candidates.is_empty() {
            let mut best = rng.below(candidates.len());
            for _ in 1..tournament {
                let k = rng.below(candidates.len());
                if self.utility[candidates[k]] > self.utility[candidates[best]] {
                    best = k;
                }
            }
            order.push(candidates.swap_remove(best));
        }
    }
}

/// The boundary subproblems: for each objective the first subproblem whose weight is largest
/// in it (the unit vectors of grid and low-discrepancy weights), without repeats.
pub(super) fn boundary_subproblems(weights: &[Vec<f64>], objectives: usize) -> Vec<usize> {
    let mut out = Vec::with_capacity(objectives);
    for j in 0..objectives {
        let mut best = 0;
        for (i, w) in weights.iter().enumerate() {
            if w[j] > weights[best][j] {
                best = i;
            }
        }
        if !out.contains(&best) {
            out.push(best);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ind(f: [f64; 2], violation: f64) -> Individual<()> {
        Individual {
            decision: (),
            objectives: f.to_vec(),
            constraints: vec![violation],
            violation,
        }
    }

    /// The paper's rule: reset to 1 above 0.001 relative improvement, else scaled by
    /// 0.95 + 0.05 Delta / 0.001 (0.95 without improvement); worse counts as no improvement;
    /// constraints as documented.
    #[test]
    fn utility_update_follows_the_paper() {
        let start = [
            ind([1.0, 1.0], 0.0),
            ind([1.0, 1.0], 0.0),
            ind([1.0, 1.0], 0.0),
            ind([1.0, 1.0], 0.0),
            ind([1.0, 1.0], 2.0),
            ind([1.0, 1.0], 2.0),
        ];
        let mut s = DraState::new(&start);
        s.utility = vec![0.5; 6];
        let now = [
            ind([0.99, 1.0], 0.0),   // 1 % better: reset
            ind([1.0, 1.0], 0.0),    // unchanged: x 0.95
            ind([0.9995, 1.0], 0.0), // Delta 0.0005: x 0.975
            ind([1.2, 1.0], 0.0),    // worse: x 0.95
            ind([5.0, 5.0], 0.0),    // became feasible: reset
            ind([1.0, 1.0], 1.0),    // violation halved: reset
        ];
        s.update(&now, |_, f| f[0]);
        let want = [1.0, 0.475, 0.4875, 0.475, 1.0, 1.0];
        for (u, w) in s.utility.iter().zip(want) {
            assert!((u - w).abs() < 1e-12, "{:?}", s.utility);
        }
        // The saved values are now the current members: no change, x 0.95 everywhere.
        s.update(&now, |_, f| f[0]);
        for (u, w) in s.utility.iter().zip(want) {
            assert!((u - 0.95 * w).abs() < 1e-12, "{:?}", s.utility);
        }
    }

    #[test]
    fn selection_takes_the_boundary_then_distinct_high_utility_subproblems() {
        let weights: Vec<Vec<f64>> = (0..10)
            .map(|i| vec![i as f64 / 9.0, 1.0 - i as f64 / 9.0])
            .collect();
        let boundary = boundary_subproblems(&weights, 2);
        assert_eq!(boundary, vec![9, 0]);
        let mut s = DraState::new(&vec![ind([1.0, 1.0], 0.0); 10]);
        s.utility = vec![0.1; 10];
        s.utility[4] = 1.0;
        s.utility[6] = 0.9;
        let mut rng = OptimRng::new(3);
        let (mut order, mut cand) = (Vec::new(), Vec::new());
        // A tournament as large as the population nearly always finds the best.
        let mut hits = [0usize; 10];
        for _ in 0..200 {
            s.select(&boundary, 4, 10, &mut rng, &mut order, &mut cand);
            assert_eq!(order.len(), 4);
            assert_eq!(&order[..2], &[9, 0]);
            let mut sorted = order.clone();
            sorted.sort_unstable();
            sorted.dedup();
            assert_eq!(sorted.len(), 4, "{order:?}");
            for &i in &order[2..] {
                hits[i] += 1;
            }
        }
        assert!(hits[4] > 180 && hits[6] > 150, "{hits:?}");
        // Tournament 1 is uniform among the non-boundary subproblems.
        s.select(&boundary, 10, 1, &mut rng, &mut order, &mut cand);
        let mut all = order.clone();
        all.sort_unstable();
        assert_eq!(all, (0..10).collect::<Vec<_>>());
    }

    #[test]
    fn bad_settings_name_the_field() {
        for (ra, name) in [
            (
                ResourceAllocation {
                    period: 0,
                    ..ResourceAllocation::default()
                },
                "resource_allocation.period",
            ),
            (
                ResourceAllocation {
                    tournament: 0,
                    ..ResourceAllocation::default()
                },
                "resource_allocation.tournament",
            ),
            (
                ResourceAllocation {
                    per_generation: Some(101),
                    ..ResourceAllocation::default()
                },
                "resource_allocation.per_generation",
            ),
        ] {
            let e = ra.check(100).unwrap_err();
            assert!(e.to_string().contains(name), "{e}");
        }
        assert!(ResourceAllocation::default().check(100).is_ok());
        assert_eq!(
            ResourceAllocation::default().subproblems_per_generation(100, 2),
            20
        );
    }
}
