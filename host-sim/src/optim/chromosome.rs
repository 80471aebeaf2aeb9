//! Variable-length structured chromosomes (thesis 4.1.5, Fig. 4.3/4.4) and the problems over
//! them ([`StructuredProblem`]).
//!
//! A [`Chromosome`] has fixed real genes (always present), a number of legs and, per leg, a
//! number of nodes of `node_dim` real genes each. The integer genes of the thesis (number of
//! legs, nodes per leg) are the lengths of the nested vectors. Their ranges and the real genes'
//! bounds form the problem's [`Layout`]. A problem may instead dictate the node counts from the
//! fixed genes ([`StructuredProblem::derived_nodes`]; Li & Deb's `L(x)`), in which case they
//! are not free decisions.
//!
//! A layout may give the nodes an optional group of genes ([`Layout::with_optional`]; the
//! thesis' recommendation, sec. 10.2: "a variable number of variables per node", e.g. thrust
//! at a few nodes only): a node then holds its `node_dim` genes, followed by the
//! `optional_dim` optional ones when it carries the group. Whether a node carries it is the
//! length of its vector, a further integer gene per node.

use serde::{Deserialize, Serialize};

use super::error::{BoundsError, EvalError};
use super::problem::{Bounds, Problem};

/// A structured chromosome.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Chromosome {
    /// Genes present in every individual (e.g. Li & Deb's position variables).
    pub fixed: Vec<f64>,
    /// `legs[l][k]`: the real genes of node `k` of leg `l`.
    pub legs: Vec<Vec<Vec<f64>>>,
}

impl Chromosome {
    /// Number of nodes of every leg.
    #[must_use]
    pub fn node_counts(&self) -> Vec<usize> {
        self.legs.iter().map(Vec::len).collect()
    }

    /// Total number of real genes.
    #[must_use]
    pub fn len(&self) -> usize {
        self.fixed.len() + self.legs.iter().flatten().map(Vec::len).sum::<usize>()
    }

    /// No genes at all.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// An inclusive integer range `[min, max]` with `min <= max` (legs may be `[0, 0]`: a
/// fixed-length problem; nodes need `min >= 1`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct CountRange {
    /// Smallest count.
    pub min: usize,
    /// Largest count.
    pub max: usize,
}

/// The shape of a problem's chromosomes: fixed genes, leg and node counts, node genes and the
/// optional group of genes a node may carry.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Layout {
    fixed: Option<Bounds>,
    legs: CountRange,
    nodes: CountRange,
    node: Bounds,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    optional: Option<Bounds>,
}

impl Layout {
    /// Check and build.
    ///
    /// # Errors
    /// [`BoundsError::Inverted`] (index 0 for legs, 1 for nodes) for a count range with
    /// `min > max`, or nodes with `min == 0`.
    pub fn new(
        fixed: Option<Bounds>,
        legs: CountRange,
        nodes: CountRange,
        node: Bounds,
    ) -> Result<Self, BoundsError> {
        for (index, r) in [legs, nodes].into_iter().enumerate() {
            if (index == 1 && r.min == 0) || r.min > r.max {
                return Err(BoundsError::Inverted {
                    index,
                    lower: r.min as f64,
                    upper: r.max as f64,
                });
            }
        }
        Ok(Self {
            fixed,
            legs,
            nodes,
            node,
            optional: None,
        })
    }

    /// The layout whose nodes may each carry the genes of `optional` after their own (all or
    /// none of them).
    #[must_use]
    pub fn with_optional(mut self, optional: Bounds) -> Self {
        self.optional = Some(optional);
        self
    }

    /// Bounds of the optional genes of a node (`None`: nodes have none).
    #[must_use]
    pub fn optional(&self) -> Option<&Bounds> {
        self.optional.as_ref()
    }

    /// Number of optional genes of a node that carries them (0 without a group).
    #[must_use]
    pub fn optional_dim(&self) -> usize {
        self.optional.as_ref().map_or(0, Bounds::dim)
    }

    /// Whether a node's genes include the optional group.
    #[must_use]
    pub fn carries_optional(&self, node: &[f64]) -> bool {
        self.optional.is_some() && node.len() > self.node.dim()
    }

    /// The optional genes of a node (`None`: it does not carry the group).
    #[must_use]
    pub fn optional_genes<'n>(&self, node: &'n [f64]) -> Option<&'n [f64]> {
        self.carries_optional(node)
            .then(|| node.get(self.node.dim()..))
            .flatten()
    }

    /// Bounds of the fixed genes (`None`: there are none).
    #[must_use]
    pub fn fixed(&self) -> Option<&Bounds> {
        self.fixed.as_ref()
    }

    /// Number of fixed genes.
    #[must_use]
    pub fn fixed_dim(&self) -> usize {
        self.fixed.as_ref().map_or(0, Bounds::dim)
    }

    /// Range of the number of legs.
    #[must_use]
    pub fn legs(&self) -> CountRange {
        self.legs
    }

    /// Range of the number of nodes per leg.
    #[must_use]
    pub fn nodes(&self) -> CountRange {
        self.nodes
    }

    /// Bounds of the genes of one node.
    #[must_use]
    pub fn node(&self) -> &Bounds {
        &self.node
    }

    /// Check a chromosome against the layout (and, if given, the dictated node counts): a
    /// node holds `node_dim` genes, or `node_dim + optional_dim` when it carries the optional
    /// group.
    ///
    /// # Errors
    /// [`EvalError::Dimension`] with the expected and found count of the first mismatch.
    pub fn check(&self, c: &Chromosome, derived: Option<&[usize]>) -> Result<(), EvalError> {
        let dim = |expected: usize, got: usize| {
            if expected == got {
                Ok(())
            } else {
                Err(EvalError::Dimension { expected, got })
            }
        };
        dim(self.fixed_dim(), c.fixed.len())?;
        let legs = c.legs.len().clamp(self.legs.min, self.legs.max);
        dim(legs, c.legs.len())?;
        for (l, leg) in c.legs.iter().enumerate() {
            let expected = match derived {
                Some(d) => d.get(l).copied().unwrap_or(0),
                None => leg.len().clamp(self.nodes.min, self.nodes.max),
            };
            dim(expected, leg.len())?;
            for node in leg {
                let expected = if self.carries_optional(node) {
                    self.node.dim() + self.optional_dim()
                } else {
                    self.node.dim()
                };
                dim(expected, node.len())?;
            }
        }
        Ok(())
    }
}

/// A problem over structured chromosomes (SCEA).
pub trait StructuredProblem: Problem<Decision = Chromosome> {
    /// The chromosome layout.
    fn layout(&self) -> &Layout;

    /// Node counts dictated by the fixed genes, one per leg (`None`, the default: the counts
    /// are free decisions within the layout's ranges).
    fn derived_nodes(&self, _fixed: &[f64]) -> Option<Vec<usize>> {
        None
    }
}

/// A fixed-length real problem seen as chromosomes of fixed genes only (no legs), so that
/// SCEA runs on it (the decision's `fixed` genes are the real vector).
#[derive(Clone, Debug, PartialEq)]
pub struct FixedLength<P> {
    inner: P,
    layout: Layout,
}

impl<P: super::problem::RealProblem> FixedLength<P> {
    /// Wrap `inner`.
    #[must_use]
    pub fn new(inner: P) -> Self {
        let layout = Layout {
            fixed: Some(inner.bounds().clone()),
            legs: CountRange { min: 0, max: 0 },
            nodes: CountRange { min: 1, max: 1 },
            node: Bounds::from_checked(vec![0.0], vec![1.0]),
            optional: None,
        };
        Self { inner, layout }
    }

    /// The wrapped problem.
    #[must_use]
    pub fn inner(&self) -> &P {
        &self.inner
    }

    /// Individuals of this problem as the wrapped problem's: the chromosomes' fixed genes.
    #[must_use]
    pub fn real_individuals(
        &self,
        individuals: &[super::population::Individual<Chromosome>],
    ) -> Vec<super::population::Individual<Vec<f64>>> {
        individuals
            .iter()
            .map(|i| super::population::Individual {
                decision: i.decision.fixed.clone(),
                objectives: i.objectives.clone(),
                constraints: i.constraints.clone(),
                violation: i.violation,
            })
            .collect()
    }
}

impl<P: super::problem::RealProblem> Problem for FixedLength<P> {
    type Decision = Chromosome;

    fn objectives(&self) -> usize {
        self.inner.objectives()
    }

    fn constraints(&self) -> usize {
        self.inner.constraints()
    }

    fn evaluate(&self, c: &Chromosome) -> Result<super::problem::Evaluation, EvalError> {
        self.layout.check(c, None)?;
        self.inner.evaluate(&c.fixed)
    }
}

impl<P: super::problem::RealProblem> StructuredProblem for FixedLength<P> {
    fn layout(&self) -> &Layout {
        &self.layout
    }
}
