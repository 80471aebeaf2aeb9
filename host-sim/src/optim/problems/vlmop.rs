//! The five variable-length test problems of Li & Deb (2017) as in the thesis, sec. 7.3.1,
//! with the thesis' constraint `alpha_1(x) <= 0.5` (eq. 7.14).
//!
//! Decision: position variables `x` in `[0, 1]^(m-1)` (the chromosome's fixed genes) and
//! `L(x)` distance variables `y_j` in `[0, 1]` (one leg of `L(x)` one-gene nodes). The length is
//! dictated by the position: `L(x) = 1 + H(x)`, `H(x) = floor(theta(x) / theta_max (N - 1))`
//! (eq. 7.3, 7.4; clamped to `[0, N - 1]`). Objectives `f_i = (1 + g) alpha_i(x)` with the
//! shape `alpha = (x, 1 - x)` (eq. 7.1) or `(x1 (1 - x2), x1 x2, 1 - x1)` (eq. 7.10) and the
//! distance `g = sum_{j <= L} (y_j - sin(pi L / (2 N)))^2` (eq. 7.2 as printed). The front is
//! the shape at `g = 0` where `alpha_1 <= 0.5`: the segment from (0, 1) to (0.5, 0.5), or the
//! part of the unit simplex with `f1 <= 0.5`.
//!
//! The angles (the printed equations are garbled; read as the text describes them):
//! 1. `theta` = angle between `alpha` and (0, 1), `theta_max = pi/2`;
//! 2. angle to (1, 1), `theta_max = pi/4` (so the long chromosomes lie at the ends of the
//!    front; the thesis' text says the middle, which contradicts its own formula);
//! 3. the smaller angle to `v_a`, `v_b` (22.5 degrees from the axes), `theta_max = pi/8`;
//! 4. `min_i asin(alpha_i / |alpha|)`, `theta_max = asin(sqrt(3)/3)`;
//! 5. the smallest angle to `v_1 = (2/3, 1/6, 1/6)` and its permutations, `theta_max =
//!    acos(sqrt(6)/3)` (the angle at the simplex centre; the thesis prints the cosine
//!    `sqrt(6)/3` itself, which `theta` never reaches).

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, FRAC_PI_8, PI};

use crate::optim::chromosome::{Chromosome, CountRange, Layout, StructuredProblem};
use crate::optim::error::{BoundsError, EvalError};
use crate::optim::problem::{Bounds, Evaluation, Problem};
use crate::optim::rng::OptimRng;
use crate::optim::weights::{WeightGeneration, generate, grid_sizes_around};

/// Names accepted by [`Vlmop::by_name`].
pub const VL_NAMES: [&str; 5] = ["vlmop1", "vlmop2", "vlmop3", "vlmop4", "vlmop5"];

/// One of the five variable-length problems.
#[derive(Clone, Debug, PartialEq)]
pub struct Vlmop {
    id: u8,
    n_max: usize,
    layout: Layout,
}

fn angle(a: &[f64], v: &[f64]) -> f64 {
    let dot: f64 = a.iter().zip(v).map(|(x, y)| x * y).sum();
    let na = a.iter().map(|x| x * x).sum::<f64>().sqrt();
    let nv = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    (dot / (na * nv)).clamp(-1.0, 1.0).acos()
}

impl Vlmop {
    /// Problem `id` (1..=5) with at most `n_max >= 2` distance variables.
    ///
    /// # Errors
    /// [`BoundsError::Empty`] for an unknown id or `n_max < 2`.
    pub fn new(id: u8, n_max: usize) -> Result<Self, BoundsError> {
        if !(1..=5).contains(&id) || n_max < 2 {
            return Err(BoundsError::Empty);
        }
        let m = if id <= 3 { 2 } else { 3 };
        let layout = Layout::new(
            Some(Bounds::uniform(m - 1, 0.0, 1.0)?),
            CountRange { min: 1, max: 1 },
            CountRange { min: 1, max: n_max },
            Bounds::uniform(1, 0.0, 1.0)?,
        )?;
        Ok(Self { id, n_max, layout })
    }

    /// Problem `id` with N = 10.
    ///
    /// # Errors
    /// As [`Vlmop::new`].
    pub fn standard(id: u8) -> Result<Self, BoundsError> {
        Self::new(id, 10)
    }

    /// The problem called `vlmop1` ... `vlmop5` (N = 10); `None` for another name.
    #[must_use]
    pub fn by_name(name: &str) -> Option<Self> {
        let id = name
            .to_ascii_lowercase()
            .strip_prefix("vlmop")?
            .parse::<u8>()
            .ok()?;
        Self::standard(id).ok()
    }

    /// Which problem.
    #[must_use]
    pub fn id(&self) -> u8 {
        self.id
    }

    /// Largest number of distance variables N.
    #[must_use]
    pub fn n_max(&self) -> usize {
        self.n_max
    }

    /// The shape `alpha(x)`.
    #[must_use]
    pub fn alpha(&self, x: &[f64]) -> Vec<f64> {
        if self.id <= 3 {
            vec![x[0], 1.0 - x[0]]
        } else {
            vec![x[0] * (1.0 - x[1]), x[0] * x[1], 1.0 - x[0]]
        }
    }

    /// `theta(x)` and `theta_max`.
    fn theta(&self, alpha: &[f64]) -> (f64, f64) {
        match self.id {
            1 => (angle(alpha, &[0.0, 1.0]), FRAC_PI_2),
            2 => (angle(alpha, &[1.0, 1.0]), FRAC_PI_4),
            3 => {
                let (s, c) = (PI / 8.0).sin_cos();
                let t = angle(alpha, &[s, c]).min(angle(alpha, &[c, s]));
                (t, FRAC_PI_8)
            }
            4 => {
                let n = alpha.iter().map(|a| a * a).sum::<f64>().sqrt();
                let t = alpha
                    .iter()
                    .map(|a| (a / n).clamp(-1.0, 1.0).asin())
                    .fold(f64::INFINITY, f64::min);
                (t, (3f64.sqrt() / 3.0).asin())
            }
            _ => {
                let (a, b) = (2.0 / 3.0, 1.0 / 6.0);
                let t = angle(alpha, &[a, b, b])
                    .min(angle(alpha, &[b, a, b]))
                    .min(angle(alpha, &[b, b, a]));
                (t, (6f64.sqrt() / 3.0).acos())
            }
        }
    }

    /// The number of distance variables `L(x)` the position `x` dictates.
    #[must_use]
    pub fn length(&self, x: &[f64]) -> usize {
        let (theta, max) = self.theta(&self.alpha(x));
        // The relative 1e-9 keeps theta = theta_max, computed with rounding, at N - 1.
        let h = (theta / max * (self.n_max - 1) as f64 * (1.0 + 1e-9)).floor();
        let h = if h.is_finite() {
            h.max(0.0) as usize
        } else {
            0
        };
        1 + h.min(self.n_max - 1)
    }

    /// The optimal value of every distance variable for a chromosome of length `l`.
    #[must_use]
    pub fn optimal_distance_gene(&self, l: usize) -> f64 {
        (PI * l as f64 / (2.0 * self.n_max as f64)).sin()
    }

    /// Number of objectives.
    #[must_use]
    pub fn objective_count(&self) -> usize {
        if self.id <= 3 { 2 } else { 3 }
    }

    /// Reference point for hypervolumes: 1.1 in every objective.
    #[must_use]
    pub fn reference_point(&self) -> Vec<f64> {
        vec![1.1; self.objective_count()]
    }

    /// About `n` points of the constrained true front.
    #[must_use]
    pub fn pareto_front(&self, n: usize) -> Vec<Vec<f64>> {
        if self.id <= 3 {
            let n = n.max(2);
            (0..n)
                .map(|i| {
                    let f1 = 0.5 * i as f64 / (n - 1) as f64;
                    vec![f1, 1.0 - f1]
                })
                .collect()
        } else {
            // A simplex lattice of about 2n points, keeping f1 <= 0.5.
            let (_, size) = grid_sizes_around(2 * n.max(3), 3);
            generate(size, 3, WeightGeneration::Grid, &mut OptimRng::new(0))
                .unwrap_or_default()
                .into_iter()
                .filter(|w| w[0] <= 0.5)
                .collect()
        }
    }

    /// Exact hypervolume of the true front for a reference point `>= (1, 1)` (two-objective
    /// problems; `None` for the three-objective ones).
    #[must_use]
    pub fn front_hypervolume(&self, reference: &[f64]) -> Option<f64> {
        let &[r1, r2] = reference else {
            return None;
        };
        if r1 < 1.0 || r2 < 1.0 {
            return None;
        }
        // Under the segment f2 = 1 - f1, 0 <= f1 <= 0.5, plus the box right of f1 = 0.5.
        Some(0.5 * (r2 - 1.0) + 0.125 + (r1 - 0.5) * (r2 - 0.5))
    }

    /// A decision on the true front at position `x`.
    #[must_use]
    pub fn optimal_decision(&self, x: Vec<f64>) -> Chromosome {
        let l = self.length(&x);
        let y = self.optimal_distance_gene(l);
        Chromosome {
            fixed: x,
            legs: vec![vec![vec![y]; l]],
        }
    }
}

impl Problem for Vlmop {
    type Decision = Chromosome;

    fn objectives(&self) -> usize {
        self.objective_count()
    }

    fn constraints(&self) -> usize {
        1
    }

    fn evaluate(&self, c: &Chromosome) -> Result<Evaluation, EvalError> {
        let layout = &self.layout;
        if c.fixed.len() != layout.fixed_dim() {
            return Err(EvalError::Dimension {
                expected: layout.fixed_dim(),
                got: c.fixed.len(),
            });
        }
        let l = self.length(&c.fixed);
        layout.check(c, Some(&[l]))?;
        let target = self.optimal_distance_gene(l);
        let g: f64 = c.legs[0].iter().map(|y| (y[0] - target).powi(2)).sum();
        let alpha = self.alpha(&c.fixed);
        let f = alpha.iter().map(|a| (1.0 + g) * a).collect();
        Ok(Evaluation::with_constraints(f, vec![alpha[0] - 0.5]))
    }
}

impl StructuredProblem for Vlmop {
    fn layout(&self) -> &Layout {
        &self.layout
    }

    fn derived_nodes(&self, fixed: &[f64]) -> Option<Vec<usize>> {
        Some(vec![self.length(fixed)])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optim::hypervolume::hypervolume;
    use crate::optim::pareto::dominates;

    #[test]
    fn lengths_follow_the_angles() {
        let p1 = Vlmop::standard(1).unwrap();
        // alpha = (0, 1): on v, shortest; alpha = (1, 0): 90 degrees, longest.
        assert_eq!(p1.length(&[0.0]), 1);
        assert_eq!(p1.length(&[1.0]), 10);
        let p2 = Vlmop::standard(2).unwrap();
        assert_eq!(p2.length(&[0.5]), 1);
        assert_eq!(p2.length(&[0.0]), 10);
        let p3 = Vlmop::standard(3).unwrap();
        // On v_b (22.5 degrees from the f1 axis): tan(22.5) = (1 - x) / x.
        let x = 1.0 / (1.0 + (PI / 8.0).tan());
        assert_eq!(p3.length(&[x]), 1);
        assert_eq!(p3.length(&[0.5]), 10);
        let p4 = Vlmop::standard(4).unwrap();
        assert_eq!(p4.length(&[1.0, 0.0]), 1);
        // Centre of the simplex: x1 = 2/3, x2 = 1/2.
        assert_eq!(p4.length(&[2.0 / 3.0, 0.5]), 10);
        let p5 = Vlmop::standard(5).unwrap();
        assert_eq!(p5.length(&[2.0 / 3.0, 0.5]), 10);
        // On v_1 = (2/3, 1/6, 1/6): x1 = 5/6, x2 = 1/5.
        assert_eq!(p5.length(&[5.0 / 6.0, 0.2]), 1);
        for p in [&p1, &p2, &p3, &p4, &p5] {
            let mut rng = OptimRng::new(1);
            for _ in 0..500 {
                let x: Vec<f64> = (0..p.objective_count() - 1)
                    .map(|_| rng.uniform())
                    .collect();
                assert!((1..=10).contains(&p.length(&x)));
            }
        }
    }

    #[test]
    fn front_is_reached_by_optimal_decisions_and_not_dominated_by_random_ones() {
        let mut rng = OptimRng::new(2);
        for name in VL_NAMES {
            let p = Vlmop::by_name(name).unwrap();
            let m = p.objective_count();
            let front = p.pareto_front(200);
            let r = p.reference_point();
            if let Some(exact) = p.front_hypervolume(&r) {
                let dense = hypervolume(&p.pareto_front(20_000), &r).unwrap();
                assert!((dense - exact).abs() < 1e-4, "{name}: {dense} {exact}");
                assert!((exact - 0.535).abs() < 1e-12);
            }
            for _ in 0..300 {
                let x: Vec<f64> = (0..m - 1).map(|_| rng.uniform()).collect();
                let opt = p.evaluate(&p.optimal_decision(x.clone())).unwrap();
                let alpha = p.alpha(&x);
                assert_eq!(opt.objectives, alpha, "{name}: g = 0 on the front");
                assert_eq!(opt.constraints, vec![alpha[0] - 0.5]);
                let l = p.length(&x);
                let random = Chromosome {
                    fixed: x,
                    legs: vec![(0..l).map(|_| vec![rng.uniform()]).collect()],
                };
                let e = p.evaluate(&random).unwrap();
                if e.constraints[0] > 0.0 {
                    continue;
                }
                for f in &front {
                    assert!(
                        !dominates(&e.objectives, f),
                        "{name}: {e:?} dominates {f:?}"
                    );
                }
            }
            // A chromosome of the wrong length is a typed error.
            let mut bad = p.optimal_decision(vec![0.3; m - 1]);
            bad.legs[0].push(vec![0.5]);
            assert!(matches!(p.evaluate(&bad), Err(EvalError::Dimension { .. })));
        }
    }
}
