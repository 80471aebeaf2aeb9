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
        let mut l = vec![e.energy[0]];
        let mut u = vec![e.energy[1]];
        if e.free_alpha {
            l.push(e.alpha_deg[0]);
            u.push(e.alpha_deg[1]);
        }
        l.push(e.sigma_deg[0]);
        u.push(e.sigma_deg[1]);
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
        Ok(Self { inner, layout })
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
