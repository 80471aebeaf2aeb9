//! CONSTR (Deb 2001, "Multi-objective optimization using evolutionary algorithms", 14.1.1):
//! a two-objective problem whose front is shaped by two inequality constraints.
//!
//! minimise `f1 = x1`, `f2 = (1 + x2) / x1`, with `x1` in [0.1, 1], `x2` in [0, 5],
//! `g1 = 6 - (x2 + 9 x1) <= 0`, `g2 = 1 + x2 - 9 x1 <= 0`. Front: `x2 = 6 - 9 x1` for
//! `x1` in [7/18, 2/3], then `x2 = 0` for `x1` in [2/3, 1].

use crate::optim::error::EvalError;
use crate::optim::problem::{Bounds, Evaluation, Problem, RealProblem};

/// The CONSTR problem.
#[derive(Clone, Debug, PartialEq)]
pub struct Constr {
    bounds: Bounds,
}

impl Default for Constr {
    fn default() -> Self {
        Self {
            bounds: Bounds::from_checked(vec![0.1, 0.0], vec![1.0, 5.0]),
        }
    }
}

impl Constr {
    /// `n` points of the true front.
    #[must_use]
    pub fn pareto_front(&self, n: usize) -> Vec<Vec<f64>> {
        let n = n.max(4);
        let a = 7.0 / 18.0;
        (0..n)
            .map(|i| {
                let x1 = a + (1.0 - a) * i as f64 / (n - 1) as f64;
                let x2 = (6.0 - 9.0 * x1).max(0.0);
                vec![x1, (1.0 + x2) / x1]
            })
            .collect()
    }

    /// Exact hypervolume of the true front for a reference point with `r1 >= 1` and
    /// `r2 >= 9` (the front's largest f2, at `f1 = 7/18`): the integral of `r2 - f2(f1)` over
    /// the front plus the strip beyond `f1 = 1` (where `f2 = 1`).
    #[must_use]
    pub fn front_hypervolume(&self, reference: &[f64]) -> Option<f64> {
        let &[r1, r2] = reference else {
            return None;
        };
        let a = 7.0 / 18.0;
        if r1 < 1.0 || r2 < 9.0 {
            return None;
        }
        // Segment 1: f2 = (7 - 9 f1) / f1 = 7 / f1 - 9 on [a, 2/3];
        // segment 2: f2 = 1 / f1 on [2/3, 1].
        let b = 2.0 / 3.0;
        let s1 = r2 * (b - a) - (7.0 * (b / a).ln() - 9.0 * (b - a));
        let s2 = r2 * (1.0 - b) - (1.0f64 / b).ln();
        Some(s1 + s2 + (r1 - 1.0) * (r2 - 1.0))
    }
}

impl Problem for Constr {
    type Decision = Vec<f64>;

    fn objectives(&self) -> usize {
        2
    }

    fn constraints(&self) -> usize {
        2
    }

    fn evaluate(&self, x: &Vec<f64>) -> Result<Evaluation, EvalError> {
        self.bounds.check_dim(x)?;
        let (x1, x2) = (x[0], x[1]);
        Ok(Evaluation::with_constraints(
            vec![x1, (1.0 + x2) / x1],
            vec![6.0 - (x2 + 9.0 * x1), 1.0 + x2 - 9.0 * x1],
        ))
    }
}

impl RealProblem for Constr {
    fn bounds(&self) -> &Bounds {
        &self.bounds
    }
}
