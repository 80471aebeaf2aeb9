//! ZDT1-4 and ZDT6 (Zitzler, Deb & Thiele 2000): two objectives, true fronts at
//! `x_2 = ... = x_n = 0`.

use std::f64::consts::PI;

use crate::optim::error::EvalError;
use crate::optim::pareto::non_dominated;
use crate::optim::problem::{Bounds, Evaluation, Problem, RealProblem};

use super::TestProblemError;

/// One ZDT problem.
#[derive(Clone, Debug, PartialEq)]
pub struct Zdt {
    id: u8,
    bounds: Bounds,
}

/// The smallest f1 of ZDT6's front: min over x in [0, 1/6] of 1 - exp(-4x) sin^6(6 pi x)
/// (golden-section search; about 0.2807753191).
#[must_use]
pub fn zdt6_front_start() -> f64 {
    let h = |x: f64| 1.0 - (-4.0 * x).exp() * (6.0 * PI * x).sin().powi(6);
    let (mut a, mut b) = (0.0, 1.0 / 6.0);
    let r = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..200 {
        let c = b - r * (b - a);
        let d = a + r * (b - a);
        if h(c) < h(d) {
            b = d;
        } else {
            a = c;
        }
    }
    h(0.5 * (a + b))
}

impl Zdt {
    /// ZDT `id` (1, 2, 3, 4 or 6) with `dim` variables (the standard sizes are 30, 30, 30, 10,
    /// 10; at least 2).
    ///
    /// # Errors
    /// [`TestProblemError`] for an unknown id or `dim < 2`.
    pub fn new(id: u8, dim: usize) -> Result<Self, TestProblemError> {
        if !matches!(id, 1 | 2 | 3 | 4 | 6) {
            return Err(TestProblemError::UnknownZdt { id });
        }
        if dim < 2 {
            return Err(TestProblemError::TooFewVariables {
                problem: format!("zdt{id}"),
                given: dim,
                minimum: 2,
            });
        }
        let bounds = if id == 4 {
            let mut lo = vec![-5.0; dim];
            let mut hi = vec![5.0; dim];
            lo[0] = 0.0;
            hi[0] = 1.0;
            Bounds::from_checked(lo, hi)
        } else {
            Bounds::from_checked(vec![0.0; dim], vec![1.0; dim])
        };
        Ok(Self { id, bounds })
    }

    /// ZDT `id` with its standard number of variables.
    ///
    /// # Errors
    /// As [`Zdt::new`].
    pub fn standard(id: u8) -> Result<Self, TestProblemError> {
        Self::new(id, if id <= 3 { 30 } else { 10 })
    }

    /// Which ZDT.
    #[must_use]
    pub fn id(&self) -> u8 {
        self.id
    }

    /// `n` points of the true front (non-dominated; for ZDT3 fewer than `n` remain).
    #[must_use]
    pub fn pareto_front(&self, n: usize) -> Vec<Vec<f64>> {
        let n = n.max(2);
        let (start, end) = match self.id {
            6 => (zdt6_front_start(), 1.0),
            3 => (0.0, 0.852),
            _ => (0.0, 1.0),
        };
        let pts: Vec<Vec<f64>> = (0..n)
            .map(|i| {
                let f1 = start + (end - start) * i as f64 / (n - 1) as f64;
                let f2 = match self.id {
                    1 | 4 => 1.0 - f1.sqrt(),
                    2 | 6 => 1.0 - f1 * f1,
                    _ => 1.0 - f1.sqrt() - f1 * (10.0 * PI * f1).sin(),
                };
                vec![f1, f2]
            })
            .collect();
        non_dominated(&pts)
            .into_iter()
            .map(|i| pts[i].clone())
            .collect()
    }

    /// Exact hypervolume of the true front for a reference point with `r1 >= 1` and
    /// `r2 >= 1` (ZDT1/2/4/6; `None` for ZDT3 and smaller reference points).
    #[must_use]
    pub fn front_hypervolume(&self, reference: &[f64]) -> Option<f64> {
        let &[r1, r2] = reference else {
            return None;
        };
        if r1 < 1.0 || r2 < 1.0 {
            return None;
        }
        let tail = (r1 - 1.0) * r2;
        match self.id {
            1 | 4 => Some(r2 - 1.0 + 2.0 / 3.0 + tail),
            2 => Some(r2 - 1.0 + 1.0 / 3.0 + tail),
            6 => {
                let a = zdt6_front_start();
                Some((r2 - 1.0) * (1.0 - a) + (1.0 - a * a * a) / 3.0 + tail)
            }
            _ => None,
        }
    }
}

impl Problem for Zdt {
    type Decision = Vec<f64>;

    fn objectives(&self) -> usize {
        2
    }

    fn evaluate(&self, x: &Vec<f64>) -> Result<Evaluation, EvalError> {
        self.bounds.check_dim(x)?;
        let n = x.len();
        let rest = &x[1..];
        let (f1, g) = match self.id {
            4 => {
                let s: f64 = rest
                    .iter()
                    .map(|v| v * v - 10.0 * (4.0 * PI * v).cos())
                    .sum();
                (x[0], 1.0 + 10.0 * (n - 1) as f64 + s)
            }
            6 => {
                let f1 = 1.0 - (-4.0 * x[0]).exp() * (6.0 * PI * x[0]).sin().powi(6);
                let s: f64 = rest.iter().sum::<f64>() / (n - 1) as f64;
                (f1, 1.0 + 9.0 * s.powf(0.25))
            }
            _ => (x[0], 1.0 + 9.0 * rest.iter().sum::<f64>() / (n - 1) as f64),
        };
        let r = f1 / g;
        let h = match self.id {
            1 | 4 => 1.0 - r.sqrt(),
            2 | 6 => 1.0 - r * r,
            _ => 1.0 - r.sqrt() - r * (10.0 * PI * f1).sin(),
        };
        Ok(Evaluation::new(vec![f1, g * h]))
    }
}

impl RealProblem for Zdt {
    fn bounds(&self) -> &Bounds {
        &self.bounds
    }
}
