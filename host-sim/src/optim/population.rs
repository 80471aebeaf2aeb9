//! Evaluated individuals and the population views an observer or a caller reads.
//!
//! Constraint violation is the sum of the positive parts of the constraint values
//! (`sum max(0, g_i)`); an individual is feasible when it is exactly zero. An evaluation with
//! a non-finite objective or constraint value (NaN or infinite) marks the individual *failed*:
//! its violation is `f64::MAX` (worse than any real violation) and its non-finite values are
//! stored as `f64::MAX`, so failed individuals lose every comparison, never reach the
//! hypervolume code, and checkpoints stay representable in JSON.

use serde::{Deserialize, Serialize};

use super::error::TellError;
use super::pareto;
use super::problem::Evaluation;

/// One evaluated decision.
#[derive(Debug, PartialEq, Serialize, Deserialize)]
pub struct Individual<D> {
    /// The decision (chromosome).
    pub decision: D,
    /// Objective values (minimised).
    #[serde(with = "crate::optim::nonfinite::vec")]
    pub objectives: Vec<f64>,
    /// Constraint values (`<= 0` satisfied).
    #[serde(with = "crate::optim::nonfinite::vec")]
    pub constraints: Vec<f64>,
    /// Total violation `sum max(0, g_i)`; `f64::MAX` for a failed evaluation.
    #[serde(with = "crate::optim::nonfinite::scalar")]
    pub violation: f64,
}

impl<D: Clone> Clone for Individual<D> {
    fn clone(&self) -> Self {
        Self {
            decision: self.decision.clone(),
            objectives: self.objectives.clone(),
            constraints: self.constraints.clone(),
            violation: self.violation,
        }
    }

    /// Reuses the buffers of `self` (no allocation when the sizes match).
    fn clone_from(&mut self, source: &Self) {
        self.decision.clone_from(&source.decision);
        self.objectives.clone_from(&source.objectives);
        self.constraints.clone_from(&source.constraints);
        self.violation = source.violation;
    }
}

impl<D> Individual<D> {
    /// Build from an evaluation, checking its shape against the problem's declaration.
    ///
    /// # Errors
    /// [`TellError::Objectives`] / [`TellError::Constraints`] for wrong counts.
    pub fn from_evaluation(
        decision: D,
        evaluation: Evaluation,
        index: usize,
        objectives: usize,
        constraints: usize,
    ) -> Result<Self, TellError> {
        let Evaluation {
            objectives: mut f,
            constraints: mut g,
        } = evaluation;
        if f.len() != objectives {
            return Err(TellError::Objectives {
                index,
                expected: objectives,
                got: f.len(),
            });
        }
        if g.len() != constraints {
            return Err(TellError::Constraints {
                index,
                expected: constraints,
                got: g.len(),
            });
        }
        let violation = sanitize(&mut f, &mut g);
        Ok(Self {
            decision,
            objectives: f,
            constraints: g,
            violation,
        })
    }

    /// Feasible: every constraint satisfied and the evaluation finite.
    #[must_use]
    pub fn is_feasible(&self) -> bool {
        self.violation == 0.0
    }

    /// The evaluation failed (non-finite values).
    #[must_use]
    pub fn is_failed(&self) -> bool {
        self.violation == f64::MAX
    }
}

/// Replace non-finite values by `f64::MAX` and return the violation (`f64::MAX` if any value
/// was non-finite).
pub(crate) fn sanitize(f: &mut [f64], g: &mut [f64]) -> f64 {
    let mut failed = false;
    for v in f.iter_mut().chain(g.iter_mut()) {
        if !v.is_finite() {
            *v = f64::MAX;
            failed = true;
        }
    }
    if failed {
        return f64::MAX;
    }
    let v: f64 = g.iter().map(|&gi| gi.max(0.0)).sum();
    if v.is_finite() { v } else { f64::MAX }
}

/// Fraction of feasible individuals (0 for an empty slice).
#[must_use]
pub fn feasible_fraction<D>(pop: &[Individual<D>]) -> f64 {
    if pop.is_empty() {
        return 0.0;
    }
    pop.iter().filter(|i| i.is_feasible()).count() as f64 / pop.len() as f64
}

/// Indices of the feasible individuals that no other feasible individual dominates.
#[must_use]
pub fn feasible_front_indices<D>(pop: &[Individual<D>]) -> Vec<usize> {
    let feasible: Vec<usize> = (0..pop.len()).filter(|&i| pop[i].is_feasible()).collect();
    let points: Vec<&[f64]> = feasible
        .iter()
        .map(|&i| pop[i].objectives.as_slice())
        .collect();
    pareto::non_dominated(&points)
        .into_iter()
        .map(|k| feasible[k])
        .collect()
}

/// Objective vectors of the feasible non-dominated individuals (the current front).
#[must_use]
pub fn feasible_front<D>(pop: &[Individual<D>]) -> Vec<Vec<f64>> {
    feasible_front_indices(pop)
        .into_iter()
        .map(|i| pop[i].objectives.clone())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn violation_and_failures() {
        let ind = Individual::from_evaluation(
            (),
            Evaluation::with_constraints(vec![1.0], vec![-1.0, 0.5, 0.25]),
            0,
            1,
            3,
        )
        .unwrap();
        assert_eq!(ind.violation, 0.75);
        assert!(!ind.is_feasible());
        let ok = Individual::from_evaluation(
            (),
            Evaluation::with_constraints(vec![1.0], vec![0.0]),
            0,
            1,
            1,
        )
        .unwrap();
        assert!(ok.is_feasible());
        let bad =
            Individual::from_evaluation((), Evaluation::new(vec![f64::NAN, 1.0]), 0, 2, 0).unwrap();
        assert!(bad.is_failed() && !bad.is_feasible());
        let failure = Individual::from_evaluation((), Evaluation::failure(2, 1), 0, 2, 1).unwrap();
        assert!(failure.is_failed());
        assert_eq!(failure.objectives, vec![f64::MAX, f64::MAX]);
        assert_eq!(bad.objectives, vec![f64::MAX, 1.0]);
        assert_eq!(
            Individual::from_evaluation((), Evaluation::new(vec![1.0]), 3, 2, 0),
            Err(TellError::Objectives {
                index: 3,
                expected: 2,
                got: 1
            })
        );
        assert_eq!(
            Individual::from_evaluation((), Evaluation::new(vec![1.0]), 3, 1, 1),
            Err(TellError::Constraints {
                index: 3,
                expected: 1,
                got: 0
            })
        );
    }

    #[test]
    fn front_skips_infeasible() {
        let mk = |f: Vec<f64>, g: f64| {
            Individual::from_evaluation((), Evaluation::with_constraints(f, vec![g]), 0, 2, 1)
                .unwrap()
        };
        let pop = vec![
            mk(vec![0.0, 0.0], 1.0),
            mk(vec![1.0, 2.0], 0.0),
            mk(vec![2.0, 1.0], 0.0),
            mk(vec![2.0, 2.0], 0.0),
        ];
        assert_eq!(feasible_front_indices(&pop), vec![1, 2]);
        assert_eq!(feasible_fraction(&pop), 0.75);
    }
}
