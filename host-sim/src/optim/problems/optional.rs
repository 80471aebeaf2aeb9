//! A test problem with a known answer for nodes with an optional gene
//! ([`crate::optim::chromosome::Layout::with_optional`]): some nodes need the extra gene,
//! the others are better without it, and which ones depends on the position on the front.
//!
//! Decision: the position `x` in `[0, 1]` (the fixed gene) and one leg of `K` nodes
//! (`K` = [`OptionalNodes::nodes`], 4 by default), each with a gene `y_k` in `[0, 1]` and,
//! optionally, a gene `z_k` in `[0, 1]`. Node `k` (from 0) needs the extra gene when
//! `k < m(x) = min(K, floor(x (K + 1)))`; its target is `T_k = 1.5` then, else `0.5`. With
//! `v_k = y_k + z_k` when node `k` carries `z_k`, else `y_k`:
//!
//! `g = sum_k (v_k - T_k)^2 + 0.1 [node k carries z_k but does not need it]`,
//! `f = ((1 + g) x, (1 + g) (1 - x))`.
//!
//! A node that needs the extra gene and lacks it misses its target by at least 0.5
//! (`y_k <= 1`), one that carries it without need pays 0.1: `g = 0` exactly when the nodes
//! `k < m(x)`, and only those, carry the extra gene, with `y_k + z_k = 1.5`, and the others
//! have `y_k = 0.5`. The front is the segment from (0, 1) to (1, 0); its hypervolume for a
//! reference point `r >= (1, 1)` is `r_1 r_2 - 1/2`.

use crate::optim::chromosome::{Chromosome, CountRange, Layout, StructuredProblem};
use crate::optim::error::{BoundsError, EvalError};
use crate::optim::hypervolume::hypervolume;
use crate::optim::pareto::dominates;
use crate::optim::population::{Individual, feasible_front};
use crate::optim::problem::{Bounds, Evaluation, Problem};

/// Cost of an extra gene on a node that does not need it.
pub const UNNEEDED_COST: f64 = 0.1;

/// The optional-gene test problem (see the module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct OptionalNodes {
    nodes: usize,
    layout: Layout,
}

impl OptionalNodes {
    /// The problem with `nodes >= 1` nodes.
    ///
    /// # Errors
    /// [`BoundsError::Empty`] for `nodes == 0`.
    pub fn new(nodes: usize) -> Result<Self, BoundsError> {
        if nodes == 0 {
            return Err(BoundsError::Empty);
        }
        let layout = Layout::new(
            Some(Bounds::uniform(1, 0.0, 1.0)?),
            CountRange { min: 1, max: 1 },
            CountRange {
                min: nodes,
                max: nodes,
            },
            Bounds::uniform(1, 0.0, 1.0)?,
        )?
        .with_optional(Bounds::uniform(1, 0.0, 1.0)?);
        Ok(Self { nodes, layout })
    }

    /// The problem with 4 nodes.
    ///
    /// # Errors
    /// Never (as [`OptionalNodes::new`]).
    pub fn standard() -> Result<Self, BoundsError> {
        Self::new(4)
    }

    /// Number of nodes `K`.
    #[must_use]
    pub fn nodes(&self) -> usize {
        self.nodes
    }

    /// `m(x)`: the number of leading nodes that need the extra gene at position `x`.
    #[must_use]
    pub fn needed(&self, x: f64) -> usize {
        let m = (x * (self.nodes + 1) as f64).floor();
        if m.is_finite() && m > 0.0 {
            (m as usize).min(self.nodes)
        } else {
            0
        }
    }

    /// Reference point for hypervolumes: (1.1, 1.1).
    #[must_use]
    pub fn reference_point(&self) -> Vec<f64> {
        vec![1.1, 1.1]
    }

    /// Exact hypervolume of the front for a reference point `>= (1, 1)` (`None` otherwise).
    #[must_use]
    pub fn front_hypervolume(&self, reference: &[f64]) -> Option<f64> {
        match *reference {
            [r1, r2] if r1 >= 1.0 && r2 >= 1.0 => Some(r1 * r2 - 0.5),
            _ => None,
        }
    }

    /// A decision on the front at position `x` (extra genes `z = 1`, `y = 0.5`).
    #[must_use]
    pub fn optimal_decision(&self, x: f64) -> Chromosome {
        let m = self.needed(x);
        let leg = (0..self.nodes)
            .map(|k| if k < m { vec![0.5, 1.0] } else { vec![0.5] })
            .collect();
        Chromosome {
            fixed: vec![x],
            legs: vec![leg],
        }
    }

    /// Whether every node of `c` carries the extra gene exactly where position `c.fixed[0]`
    /// needs it.
    #[must_use]
    pub fn has_optimal_pattern(&self, c: &Chromosome) -> bool {
        let (Some(&x), Some(leg)) = (c.fixed.first(), c.legs.first()) else {
            return false;
        };
        let m = self.needed(x);
        leg.len() == self.nodes
            && leg
                .iter()
                .enumerate()
                .all(|(k, n)| self.layout.carries_optional(n) == (k < m))
    }

    /// How well a population solved the problem: the hypervolume of its feasible front over
    /// the true front's (for [`Self::reference_point`]), and the share of its non-dominated
    /// members with [`Self::has_optimal_pattern`]. `None` for an empty population.
    #[must_use]
    pub fn scores(&self, population: &[Individual<Chromosome>]) -> Option<(f64, f64)> {
        let r = self.reference_point();
        let ratio =
            hypervolume(&feasible_front(population), &r).ok()? / self.front_hypervolume(&r)?;
        let front: Vec<&Individual<Chromosome>> = population
            .iter()
            .filter(|i| {
                !population
                    .iter()
                    .any(|j| dominates(&j.objectives, &i.objectives))
            })
            .collect();
        if front.is_empty() {
            return None;
        }
        let right = front
            .iter()
            .filter(|i| self.has_optimal_pattern(&i.decision))
            .count();
        Some((ratio, right as f64 / front.len() as f64))
    }
}

impl Problem for OptionalNodes {
    type Decision = Chromosome;

    fn objectives(&self) -> usize {
        2
    }

    fn evaluate(&self, c: &Chromosome) -> Result<Evaluation, EvalError> {
        self.layout.check(c, None)?;
        let x = c.fixed[0];
        let m = self.needed(x);
        let g: f64 = c.legs[0]
            .iter()
            .enumerate()
            .map(|(k, n)| {
                let extra = self.layout.optional_genes(n);
                let v = n[0] + extra.map_or(0.0, |z| z[0]);
                let target = if k < m { 1.5 } else { 0.5 };
                let unneeded = if extra.is_some() && k >= m {
                    UNNEEDED_COST
                } else {
                    0.0
                };
                (v - target).powi(2) + unneeded
            })
            .sum();
        Ok(Evaluation::new(vec![(1.0 + g) * x, (1.0 + g) * (1.0 - x)]))
    }
}

impl StructuredProblem for OptionalNodes {
    fn layout(&self) -> &Layout {
        &self.layout
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optim::hypervolume::hypervolume;
    use crate::optim::pareto::dominates;
    use crate::optim::rng::OptimRng;

    #[test]
    fn optimal_decisions_reach_the_front_and_other_patterns_do_not() {
        let p = OptionalNodes::standard().unwrap();
        assert_eq!(p.needed(0.0), 0);
        assert_eq!(p.needed(0.19), 0);
        assert_eq!(p.needed(0.2), 1);
        assert_eq!(p.needed(0.79), 3);
        assert_eq!(p.needed(1.0), 4);
        let mut rng = OptimRng::new(5);
        for _ in 0..500 {
            let x = rng.uniform();
            let opt = p.optimal_decision(x);
            assert!(p.has_optimal_pattern(&opt));
            let f = p.evaluate(&opt).unwrap().objectives;
            assert_eq!(f, vec![x, 1.0 - x], "g = 0 at x = {x}");
            // Any other presence pattern, whatever its genes, is dominated by the optimum.
            let pattern = rng.below(16);
            let leg: Vec<Vec<f64>> = (0..4)
                .map(|k| {
                    let y = rng.uniform();
                    if pattern & (1 << k) != 0 {
                        vec![y, rng.uniform()]
                    } else {
                        vec![y]
                    }
                })
                .collect();
            let c = Chromosome {
                fixed: vec![x],
                legs: vec![leg],
            };
            let e = p.evaluate(&c).unwrap().objectives;
            if !p.has_optimal_pattern(&c) && x > 0.0 && x < 1.0 {
                assert!(dominates(&f, &e), "x = {x}, pattern {pattern:04b}: {e:?}");
            }
        }
        // The exact hypervolume against a dense front.
        let r = p.reference_point();
        let dense: Vec<Vec<f64>> = (0..=20_000)
            .map(|i| {
                let x = f64::from(i) / 20_000.0;
                vec![x, 1.0 - x]
            })
            .collect();
        let exact = p.front_hypervolume(&r).unwrap();
        assert!((hypervolume(&dense, &r).unwrap() - exact).abs() < 1e-4);
        assert!((exact - 0.71).abs() < 1e-12);
    }

    #[test]
    fn node_lengths_other_than_with_or_without_the_extra_gene_are_errors() {
        let p = OptionalNodes::standard().unwrap();
        let mut c = p.optimal_decision(0.5);
        c.legs[0][0] = vec![0.5, 1.0, 0.0];
        assert!(matches!(
            p.evaluate(&c),
            Err(EvalError::Dimension {
                expected: 2,
                got: 3
            })
        ));
        c.legs[0][0] = Vec::new();
        assert!(matches!(p.evaluate(&c), Err(EvalError::Dimension { .. })));
        assert!(OptionalNodes::new(0).is_err());
    }
}
