//! What an optimiser optimises: the [`Problem`] trait (objectives minimised, inequality
//! constraints `g(x) <= 0`), its [`Evaluation`], box [`Bounds`] and the [`RealProblem`]
//! refinement for fixed-length real vectors.
//!
//! The decision type is an associated type, so a problem over variable-length structured
//! chromosomes (SCEA) implements the same trait with its own decision type; the algorithms
//! for real vectors (MOEA/D, NSGA-II) require [`RealProblem`].

use std::fmt::Debug;

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use super::error::{BoundsError, EvalError};

/// What a decision (chromosome) must be: cloneable, sendable to evaluation threads, and
/// serialisable for checkpoints. Blanket-implemented.
pub trait Decision: Clone + Debug + PartialEq + Send + Sync + Serialize + DeserializeOwned {}

impl<T> Decision for T where
    T: Clone + Debug + PartialEq + Send + Sync + Serialize + DeserializeOwned
{
}

/// The result of evaluating one decision.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Evaluation {
    /// Objective values (all minimised), one per [`Problem::objectives`].
    pub objectives: Vec<f64>,
    /// Inequality constraint values, satisfied when `<= 0`, one per [`Problem::constraints`].
    pub constraints: Vec<f64>,
}

impl Evaluation {
    /// Unconstrained evaluation.
    #[must_use]
    pub fn new(objectives: Vec<f64>) -> Self {
        Self {
            objectives,
            constraints: Vec::new(),
        }
    }

    /// A failed evaluation that should not stop the run: `objectives` NaN objectives and
    /// `constraints` NaN constraints. The algorithms keep it as a failed individual (worst
    /// possible violation, never on a front) instead of stopping as they do on an
    /// [`EvalError`].
    #[must_use]
    pub fn failure(objectives: usize, constraints: usize) -> Self {
        Self {
            objectives: vec![f64::NAN; objectives],
            constraints: vec![f64::NAN; constraints],
        }
    }

    /// Evaluation with inequality constraints (`<= 0` satisfied).
    #[must_use]
    pub fn with_constraints(objectives: Vec<f64>, constraints: Vec<f64>) -> Self {
        Self {
            objectives,
            constraints,
        }
    }
}

/// A multi-objective minimisation problem.
///
/// `evaluate` must be a pure function of the decision (the same decision gives the same
/// evaluation): reproducibility across thread counts relies on it. It is called from several
/// threads at once by the rayon evaluator, hence `Sync`.
pub trait Problem: Sync {
    /// The decision (chromosome) type.
    type Decision: Decision;

    /// Number of objectives (minimised); at least 1.
    fn objectives(&self) -> usize;

    /// Number of inequality constraints `g_i(x) <= 0`.
    fn constraints(&self) -> usize {
        0
    }

    /// Evaluate one decision. Failures are errors, never panics.
    ///
    /// # Errors
    /// [`EvalError`] when the decision cannot be evaluated.
    fn evaluate(&self, decision: &Self::Decision) -> Result<Evaluation, EvalError>;
}

/// A problem on fixed-length real vectors inside box bounds.
pub trait RealProblem: Problem<Decision = Vec<f64>> {
    /// The box bounds (their length is the number of variables).
    fn bounds(&self) -> &Bounds;
}

/// Validated box bounds: finite, `lower < upper` for every variable.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Bounds {
    lower: Vec<f64>,
    upper: Vec<f64>,
}

impl Bounds {
    /// Check and build.
    ///
    /// # Errors
    /// [`BoundsError`] naming the variable and value.
    pub fn new(lower: Vec<f64>, upper: Vec<f64>) -> Result<Self, BoundsError> {
        if lower.len() != upper.len() {
            return Err(BoundsError::LengthMismatch {
                lower: lower.len(),
                upper: upper.len(),
            });
        }
        if lower.is_empty() {
            return Err(BoundsError::Empty);
        }
        for (index, (&lo, &hi)) in lower.iter().zip(&upper).enumerate() {
            if !lo.is_finite() {
                return Err(BoundsError::NonFinite {
                    index,
                    which: "lower",
                    value: lo,
                });
            }
            if !hi.is_finite() {
                return Err(BoundsError::NonFinite {
                    index,
                    which: "upper",
                    value: hi,
                });
            }
            if lo >= hi {
                return Err(BoundsError::Inverted {
                    index,
                    lower: lo,
                    upper: hi,
                });
            }
        }
        Ok(Self { lower, upper })
    }

    /// Bounds known to be valid at compile time (crate-internal test problems).
    pub(crate) fn from_checked(lower: Vec<f64>, upper: Vec<f64>) -> Self {
        debug_assert!(Self::new(lower.clone(), upper.clone()).is_ok());
        Self { lower, upper }
    }

    /// The same interval `[lo, hi]` for `n` variables.
    ///
    /// # Errors
    /// As [`Bounds::new`].
    pub fn uniform(n: usize, lo: f64, hi: f64) -> Result<Self, BoundsError> {
        Self::new(vec![lo; n], vec![hi; n])
    }

    /// Lower bounds.
    #[must_use]
    pub fn lower(&self) -> &[f64] {
        &self.lower
    }

    /// Upper bounds.
    #[must_use]
    pub fn upper(&self) -> &[f64] {
        &self.upper
    }

    /// Number of variables.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.lower.len()
    }

    /// Check a decision's length.
    ///
    /// # Errors
    /// [`EvalError::Dimension`].
    pub fn check_dim(&self, x: &[f64]) -> Result<(), EvalError> {
        if x.len() == self.dim() {
            Ok(())
        } else {
            Err(EvalError::Dimension {
                expected: self.dim(),
                got: x.len(),
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_bounds_are_typed_errors() {
        assert_eq!(Bounds::new(vec![], vec![]), Err(BoundsError::Empty));
        assert!(matches!(
            Bounds::new(vec![0.0], vec![1.0, 2.0]),
            Err(BoundsError::LengthMismatch { lower: 1, upper: 2 })
        ));
        assert!(matches!(
            Bounds::new(vec![0.0, 1.0], vec![1.0, 1.0]),
            Err(BoundsError::Inverted { index: 1, .. })
        ));
        assert!(matches!(
            Bounds::new(vec![f64::NEG_INFINITY], vec![1.0]),
            Err(BoundsError::NonFinite {
                index: 0,
                which: "lower",
                ..
            })
        ));
        assert!(matches!(
            Bounds::new(vec![0.0], vec![f64::NAN]),
            Err(BoundsError::NonFinite {
                index: 0,
                which: "upper",
                ..
            })
        ));
        let msg = Bounds::new(vec![2.0], vec![1.0]).unwrap_err().to_string();
        assert!(
            msg.contains("variable 0") && msg.contains("lower 2"),
            "{msg}"
        );
        assert_eq!(Bounds::uniform(3, 0.0, 1.0).unwrap().dim(), 3);
    }
}
