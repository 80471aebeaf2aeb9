//! The variable-length re-entry problem for SCEA (thesis sec. 4.2.1: 4 to 8 nodes, one leg):
//! a [`Chromosome`] with one leg of 2 to 6 free nodes (each `[E, alpha_deg, sigma_deg]`, or
//! `[E, sigma_deg]` bank-only) and, when the entry altitude is a variable, one fixed gene
//! (km). It maps through the same [`super::Encoding::table_of`] to a node table with the fixed
//! end nodes and flies it like the fixed-length [`ReentryProblem`].

use super::{DesignError, ReentryProblem};
use crate::optim::chromosome::{Chromosome, CountRange, Layout, StructuredProblem};
use crate::optim::{Bounds, EvalError, Evaluation, Problem};

/// [`ReentryProblem`] over variable-length chromosomes.
#[derive(Clone, Debug)]
pub struct VariableReentry {
    inner: ReentryProblem,
    layout: Layout,
    nodes: [usize; 2],
}

impl VariableReentry {
    /// The problem with `nodes` = `[min, max]` table nodes (fixed ends included; thesis 4
    /// to 8).
    ///
    /// # Errors
    /// [`DesignError::Setting`] for fewer than 3 nodes or `min > max`; [`DesignError::Bounds`].
    pub fn new(inner: ReentryProblem, nodes: [usize; 2]) -> Result<Self, DesignError> {
        let [lo, hi] = nodes;
        if lo < 3 || lo > hi || hi > 256 {
            return Err(DesignError::Setting {
                field: "encoding.nodes",
                value: format!("[{lo}, {hi}]"),
                reason: "use 3 <= min <= max <= 256 table nodes",
            });
        }
        let e = inner.encoding();
        let (l, u) = e.node_bounds();
        let fixed = match e.entry_altitude_km {
            Some([a, b]) => Some(Bounds::new(vec![a], vec![b])?),
            None => None,
        };
        let layout = Layout::new(
            fixed,
            CountRange { min: 1, max: 1 },
            CountRange {
                min: lo - 2,
                max: hi - 2,
            },
            Bounds::new(l, u)?,
        )?;
        Ok(Self {
            inner,
            layout,
            nodes,
        })
    }

    /// `[min, max]` table nodes, fixed ends included.
    #[must_use]
    pub fn nodes(&self) -> [usize; 2] {
        self.nodes
    }

    /// The length of the padded encoding's decision: the genes of the largest number of free
    /// nodes, the entry altitude \[km\] when it is a variable, then the free-node count.
    ///
    /// The padded encoding is this problem over a fixed-length vector, for the fixed-length
    /// algorithms (pygmo's, or MOEA/D and NSGA-II through Python): only the first `count`
    /// nodes reach the chromosome ([`VariableReentry::chromosome_of_padded`]).
    #[must_use]
    pub fn padded_dim(&self) -> usize {
        let e = self.inner.encoding();
        (self.nodes[1] - 2) * e.genes_per_node() + usize::from(e.entry_altitude_km.is_some()) + 1
    }

    /// The padded decision's bounds (lower, upper): the largest number of free nodes' genes,
    /// the entry altitude \[km\] if a variable, and the free-node count in
    /// `[min - 2, max - 2]`.
    #[must_use]
    pub fn padded_bounds(&self) -> (Vec<f64>, Vec<f64>) {
        let (mut lo, mut hi) = self.inner.encoding().bounds_of(self.nodes[1] - 2);
        lo.push((self.nodes[0] - 2) as f64);
        hi.push((self.nodes[1] - 2) as f64);
        (lo, hi)
    }

    /// The chromosome of a padded decision `x` ([`VariableReentry::padded_dim`] values; the
    /// last, the free-node count, rounded to the nearest integer).
    ///
    /// # Errors
    /// [`DesignError::Dimension`] for another length; [`DesignError::PaddedCount`] for a count
    /// that does not round into `[min - 2, max - 2]` (or is not finite).
    pub fn chromosome_of_padded(&self, x: &[f64]) -> Result<Chromosome, DesignError> {
        let dim = self.padded_dim();
        let (Some(&raw), true) = (x.last(), x.len() == dim) else {
            return Err(DesignError::Dimension {
                expected: dim,
                got: x.len(),
            });
        };
        let e = self.inner.encoding();
        let g = e.genes_per_node();
        let (lo, hi) = (self.nodes[0] - 2, self.nodes[1] - 2);
        let count = raw.round();
        if !(count >= lo as f64 && count <= hi as f64) {
            return Err(DesignError::PaddedCount {
                value: raw,
                min: lo,
                max: hi,
            });
        }
        // In range, checked above: an exact small integer.
        let count = count as usize;
        let nodes = x[..hi * g]
            .chunks_exact(g)
            .take(count)
            .map(<[f64]>::to_vec)
            .collect();
        let fixed = if e.entry_altitude_km.is_some() {
            vec![x[hi * g]]
        } else {
            Vec::new()
        };
        Ok(Chromosome {
            fixed,
            legs: vec![nodes],
        })
    }

    /// The fixed-length problem it wraps.
    #[must_use]
    pub fn inner(&self) -> &ReentryProblem {
        &self.inner
    }

    /// The node table `[E-hat, alpha_rad, sigma_rad]` and entry altitude \[m\] of a
    /// chromosome.
    ///
    /// # Errors
    /// [`EvalError`] when the chromosome does not fit the layout.
    pub fn table_of(&self, c: &Chromosome) -> Result<(Vec<[f64; 3]>, Option<f64>), EvalError> {
        self.layout.check(c, None)?;
        let genes: Vec<f64> = c.legs.iter().flatten().flatten().copied().collect();
        let h = c.fixed.first().map(|km| km * 1e3);
        Ok((self.inner.encoding().table_of(&genes), h))
    }
}

impl Problem for VariableReentry {
    type Decision = Chromosome;

    fn objectives(&self) -> usize {
        self.inner.objectives()
    }

    fn constraints(&self) -> usize {
        self.inner.constraints()
    }

    fn evaluate(&self, c: &Chromosome) -> Result<Evaluation, EvalError> {
        let (table, h) = self.table_of(c)?;
        self.inner
            .try_evaluate_scenario(&self.inner.scenario_of_table(table, h))
    }
}

impl StructuredProblem for VariableReentry {
    fn layout(&self) -> &Layout {
        &self.layout
    }
}
