//! DTLZ1-7 (Deb, Thiele, Laumanns & Zitzler 2002) with `m` objectives and `m + k - 1`
//! variables in [0, 1] (standard k: 5 for DTLZ1, 10 for DTLZ2-6, 20 for DTLZ7).

use std::f64::consts::PI;

use crate::optim::error::EvalError;
use crate::optim::pareto::non_dominated;
use crate::optim::problem::{Bounds, Evaluation, Problem, RealProblem};
use crate::optim::rng::OptimRng;

use super::TestProblemError;
use crate::optim::weights::{WeightGeneration, generate, grid_sizes_around};

/// One DTLZ problem.
#[derive(Clone, Debug, PartialEq)]
pub struct Dtlz {
    id: u8,
    m: usize,
    bounds: Bounds,
}

impl Dtlz {
    /// DTLZ `id` (1..=7) with `m >= 2` objectives and `k >= 1` distance variables.
    ///
    /// # Errors
    /// [`TestProblemError`] for an unknown id, `m < 2` or `k == 0`.
    pub fn new(id: u8, m: usize, k: usize) -> Result<Self, TestProblemError> {
        if !(1..=7).contains(&id) {
            return Err(TestProblemError::UnknownDtlz { id });
        }
        if m < 2 {
            return Err(TestProblemError::TooFewObjectives {
                problem: format!("dtlz{id}"),
                given: m,
            });
        }
        if k == 0 {
            return Err(TestProblemError::TooFewVariables {
                problem: format!("dtlz{id}"),
                given: m - 1,
                minimum: m,
            });
        }
        let n = m + k - 1;
        Ok(Self {
            id,
            m,
            bounds: Bounds::from_checked(vec![0.0; n], vec![1.0; n]),
        })
    }

    /// DTLZ `id` with `m` objectives and the standard k.
    ///
    /// # Errors
    /// As [`Dtlz::new`].
    pub fn standard(id: u8, m: usize) -> Result<Self, TestProblemError> {
        let k = match id {
            1 => 5,
            7 => 20,
            _ => 10,
        };
        Self::new(id, m, k)
    }

    /// Which DTLZ.
    #[must_use]
    pub fn id(&self) -> u8 {
        self.id
    }

    /// The reference point used for hypervolumes here: 1.1 x the nadir of the true front
    /// (0.55 for DTLZ1, 1.1 for DTLZ2-6; DTLZ7: 1.1 for the first m - 1, 2.2 m for the last).
    #[must_use]
    pub fn reference_point(&self) -> Vec<f64> {
        match self.id {
            1 => vec![0.55; self.m],
            7 => {
                let mut r = vec![1.1; self.m];
                r[self.m - 1] = 2.2 * self.m as f64;
                r
            }
            _ => vec![1.1; self.m],
        }
    }

    /// About `n` points of the true front (simplex lattice for DTLZ1-4, a curve for DTLZ5/6,
    /// the non-dominated part of a grid for DTLZ7).
    #[must_use]
    pub fn pareto_front(&self, n: usize) -> Vec<Vec<f64>> {
        let m = self.m;
        match self.id {
            1..=4 => {
                let (_, size) = grid_sizes_around(n.max(m), m);
                let w = generate(size, m, WeightGeneration::Grid, &mut OptimRng::new(0))
                    .unwrap_or_default();
                w.into_iter()
                    .map(|v| {
                        if self.id == 1 {
                            v.iter().map(|x| 0.5 * x).collect()
                        } else {
                            let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
                            v.iter().map(|x| x / norm).collect()
                        }
                    })
                    .collect()
            }
            5 | 6 => {
                let opt = if self.id == 5 { 0.5 } else { 0.0 };
                let n = n.max(2);
                (0..n)
                    .filter_map(|i| {
                        let mut x = vec![opt; self.bounds.dim()];
                        x[0] = i as f64 / (n - 1) as f64;
                        for v in x.iter_mut().take(m - 1).skip(1) {
                            *v = 0.5;
                        }
                        self.evaluate(&x).ok().map(|e| e.objectives)
                    })
                    .collect()
            }
            _ => {
                // Grid over the m - 1 position variables, distance variables 0.
                let per = ((n.max(2) as f64).powf(1.0 / (m - 1) as f64).ceil() as usize).max(2);
                let mut pts = Vec::new();
                let mut idx = vec![0usize; m - 1];
                loop {
                    let mut x = vec![0.0; self.bounds.dim()];
                    for (j, &i) in idx.iter().enumerate() {
                        x[j] = i as f64 / (per - 1) as f64;
                    }
                    if let Ok(e) = self.evaluate(&x) {
                        pts.push(e.objectives);
                    }
                    let mut j = 0;
                    while j < idx.len() {
                        idx[j] += 1;
                        if idx[j] < per {
                            break;
                        }
                        idx[j] = 0;
                        j += 1;
                    }
                    if j == idx.len() {
                        break;
                    }
                }
                non_dominated(&pts)
                    .into_iter()
                    .map(|i| pts[i].clone())
                    .collect()
            }
        }
    }

    /// Exact hypervolume of the true front (DTLZ1: `prod r - 0.5^m / m!` for `r_i >= 0.5`;
    /// DTLZ2-4: `prod r - V_m / 2^m`, the positive orthant of the unit ball, for `r_i >= 1`;
    /// `None` otherwise).
    #[must_use]
    pub fn front_hypervolume(&self, reference: &[f64]) -> Option<f64> {
        if reference.len() != self.m {
            return None;
        }
        let m = self.m;
        let prod: f64 = reference.iter().product();
        match self.id {
            1 if reference.iter().all(|&r| r >= 0.5) => {
                let fact: f64 = (1..=m).map(|i| i as f64).product();
                Some(prod - 0.5f64.powi(m as i32) / fact)
            }
            2..=4 if reference.iter().all(|&r| r >= 1.0) => {
                // Unit-ball volume: V_0 = 1, V_1 = 2, V_m = 2 pi / m V_{m-2}.
                let mut v = [1.0, 2.0];
                for k in 2..=m {
                    v[k % 2] *= 2.0 * PI / k as f64;
                }
                Some(prod - v[m % 2] / 2f64.powi(m as i32))
            }
            _ => None,
        }
    }
}

impl Problem for Dtlz {
    type Decision = Vec<f64>;

    fn objectives(&self) -> usize {
        self.m
    }

    fn evaluate(&self, x: &Vec<f64>) -> Result<Evaluation, EvalError> {
        self.bounds.check_dim(x)?;
        let m = self.m;
        let (pos, dist) = x.split_at(m - 1);
        let k = dist.len() as f64;
        let g_rastrigin = || {
            100.0
                * (k + dist
                    .iter()
                    .map(|v| (v - 0.5).powi(2) - (20.0 * PI * (v - 0.5)).cos())
                    .sum::<f64>())
        };
        let g_sphere = || dist.iter().map(|v| (v - 0.5).powi(2)).sum::<f64>();
        let mut f = vec![0.0; m];
        match self.id {
            1 => {
                let g = g_rastrigin();
                for (i, fi) in f.iter_mut().enumerate() {
                    let mut v = 0.5 * (1.0 + g);
                    for p in &pos[..m - 1 - i] {
                        v *= p;
                    }
                    if i > 0 {
                        v *= 1.0 - pos[m - 1 - i];
                    }
                    *fi = v;
                }
            }
            7 => {
                let g = 1.0 + 9.0 / k * dist.iter().sum::<f64>();
                f[..m - 1].copy_from_slice(pos);
                let h = m as f64
                    - pos
                        .iter()
                        .map(|&fi| fi / (1.0 + g) * (1.0 + (3.0 * PI * fi).sin()))
                        .sum::<f64>();
                f[m - 1] = (1.0 + g) * h;
            }
            _ => {
                let (g, theta): (f64, Vec<f64>) = match self.id {
                    2 => (g_sphere(), pos.iter().map(|p| p * PI / 2.0).collect()),
                    3 => (g_rastrigin(), pos.iter().map(|p| p * PI / 2.0).collect()),
                    4 => (
                        g_sphere(),
                        pos.iter().map(|p| p.powi(100) * PI / 2.0).collect(),
                    ),
                    _ => {
                        let g = if self.id == 5 {
                            g_sphere()
                        } else {
                            dist.iter().map(|v| v.powf(0.1)).sum::<f64>()
                        };
                        let t = pos
                            .iter()
                            .enumerate()
                            .map(|(j, &p)| {
                                if j == 0 {
                                    p * PI / 2.0
                                } else {
                                    PI / (4.0 * (1.0 + g)) * (1.0 + 2.0 * g * p)
                                }
                            })
                            .collect();
                        (g, t)
                    }
                };
                for (i, fi) in f.iter_mut().enumerate() {
                    let mut v = 1.0 + g;
                    for t in &theta[..m - 1 - i] {
                        v *= t.cos();
                    }
                    if i > 0 {
                        v *= theta[m - 1 - i].sin();
                    }
                    *fi = v;
                }
            }
        }
        Ok(Evaluation::new(f))
    }
}

impl RealProblem for Dtlz {
    fn bounds(&self) -> &Bounds {
        &self.bounds
    }
}
