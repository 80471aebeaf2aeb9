//! The ask/tell contract every algorithm implements, and the batch bookkeeping they share.
//!
//! `ask` hands out a batch of decisions; `tell(index, evaluation)` takes their evaluations back
//! one by one, in any order. When the last one of the batch arrives the algorithm advances
//! (selection, archive updates). Nothing random happens in `tell` before the batch is
//! complete, and completion processes the batch in index order, so the result is the same
//! whatever order (or thread) the evaluations come from.
//!
//! Generations: the initial population is built from the first batches; after it is complete
//! `is_initialised` is true and `generation` is 0. Every further `population`-sized round of
//! offspring increments `generation` by one (MOEA/D's steady-state batches of one offspring
//! count `population` of them per generation).

use serde::{Deserialize, Serialize};

use super::error::{OptimError, TellError};
use super::population::Individual;
use super::problem::{Evaluation, Problem};

/// An ask/tell multi-objective optimiser for problems of type `P`.
pub trait Algorithm<P: Problem> {
    /// Short name ("moead", "nsga2", ...).
    fn name(&self) -> &'static str;

    /// The batch of decisions to evaluate next. Calling `ask` again before the batch is
    /// complete returns the same batch.
    ///
    /// # Errors
    /// [`OptimError::Config`] if the algorithm's settings do not fit the problem.
    fn ask(&mut self, problem: &P) -> Result<&[P::Decision], OptimError>;

    /// The evaluation of decision `index` of the current batch (any order).
    ///
    /// # Errors
    /// [`OptimError::Tell`] for an index outside the batch, told twice, or with the wrong
    /// number of objectives or constraints.
    fn tell(&mut self, problem: &P, index: usize, evaluation: Evaluation)
    -> Result<(), OptimError>;

    /// The current population (parents), evaluated.
    fn population(&self) -> &[Individual<P::Decision>];

    /// The external archive of feasible non-dominated solutions found during the run, when
    /// the algorithm keeps one ([`crate::optim::ParetoArchive`]: MOEA/D, SCEA and NSGA-II with
    /// `archive: Some(capacity)`). Default: none (pagmo's semantics).
    fn external_archive(&self) -> Option<&[Individual<P::Decision>]> {
        None
    }

    /// The individuals the run's result front is taken from: the external archive when there
    /// is one, else the population.
    fn result(&self) -> &[Individual<P::Decision>] {
        self.external_archive().unwrap_or_else(|| self.population())
    }

    /// The initial population has been evaluated.
    fn is_initialised(&self) -> bool;

    /// Completed generations after the initial population.
    fn generation(&self) -> u64;

    /// Evaluations told so far.
    fn evaluations(&self) -> u64;

    /// Decision `index` of the open batch has been told already (a run resumed from a
    /// checkpoint taken mid-batch); [`crate::optim::evolve`] evaluates only the others. The
    /// default, `false`, suits algorithms that do not track it.
    fn is_told(&self, index: usize) -> bool {
        let _ = index;
        false
    }

    /// The algorithm has stopped by its own criterion (MHACO's `evalstop`); `evolve` returns
    /// early and `ask` hands out no more decisions. Default: never.
    fn is_finished(&self) -> bool {
        false
    }

    /// Check a restored (deserialised) state against itself and `problem` before it runs:
    /// sizes, indices, counters, vector lengths, finite values. Every algorithm of this
    /// module checks its whole state; the default (for algorithms outside it) accepts any.
    ///
    /// # Errors
    /// [`super::StateError`] naming the field.
    fn validate(&self, problem: &P) -> Result<(), super::StateError> {
        let _ = problem;
        Ok(())
    }
}

/// An open batch: the decisions handed out and the evaluations told so far.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Batch<D> {
    decisions: Vec<D>,
    told: Vec<Option<Individual<()>>>,
    remaining: usize,
}

impl<D> Default for Batch<D> {
    fn default() -> Self {
        Self {
            decisions: Vec::new(),
            told: Vec::new(),
            remaining: 0,
        }
    }
}

impl<D> Batch<D> {
    /// A batch is open (handed out, not complete).
    #[must_use]
    pub fn is_open(&self) -> bool {
        self.remaining > 0
    }

    /// Open a new batch with these decisions.
    pub fn open(&mut self, decisions: Vec<D>) {
        self.decisions = decisions;
        self.reset_told();
    }

    /// Open a new batch filled by `fill` (the decision buffer's allocation is reused).
    pub fn open_with(&mut self, fill: impl FnOnce(&mut Vec<D>)) {
        self.decisions.clear();
        fill(&mut self.decisions);
        self.reset_told();
    }

    fn reset_told(&mut self) {
        self.remaining = self.decisions.len();
        self.told.clear();
        self.told.resize_with(self.decisions.len(), || None);
    }

    /// Decision `index` of the open batch has been told.
    #[must_use]
    pub fn is_told(&self, index: usize) -> bool {
        self.remaining > 0 && self.told.get(index).is_some_and(Option::is_some)
    }

    /// Evaluations not yet told.
    pub(crate) fn remaining(&self) -> usize {
        self.remaining
    }

    /// The told slots, one per decision.
    pub(crate) fn told_slots(&self) -> &[Option<Individual<()>>] {
        &self.told
    }

    /// The decisions of the batch.
    #[must_use]
    pub fn decisions(&self) -> &[D] {
        &self.decisions
    }

    /// Record one evaluation; returns true when the batch is complete.
    ///
    /// # Errors
    /// [`TellError`] as described on [`Algorithm::tell`].
    pub fn tell(
        &mut self,
        index: usize,
        evaluation: Evaluation,
        objectives: usize,
        constraints: usize,
    ) -> Result<bool, TellError> {
        if self.remaining == 0 {
            return Err(TellError::NoBatch);
        }
        let batch = self.told.len();
        let slot = self
            .told
            .get_mut(index)
            .ok_or(TellError::IndexOutOfRange { index, batch })?;
        if slot.is_some() {
            return Err(TellError::AlreadyTold { index });
        }
        *slot = Some(Individual::from_evaluation(
            (),
            evaluation,
            index,
            objectives,
            constraints,
        )?);
        self.remaining -= 1;
        Ok(self.remaining == 0)
    }

    /// Take the complete batch as individuals, in index order.
    #[must_use]
    pub fn take(&mut self) -> Vec<Individual<D>> {
        let mut out = Vec::with_capacity(self.decisions.len());
        self.take_into(&mut out);
        out
    }

    /// Append the complete batch's individuals to `out`, in index order, keeping this batch's
    /// buffers for the next one.
    pub fn take_into(&mut self, out: &mut Vec<Individual<D>>) {
        self.remaining = 0;
        out.extend(
            self.decisions
                .drain(..)
                .zip(self.told.drain(..))
                .filter_map(|(decision, t)| {
                    t.map(|t| Individual {
                        decision,
                        objectives: t.objectives,
                        constraints: t.constraints,
                        violation: t.violation,
                    })
                }),
        );
    }
}

/// Working memory that is not part of an algorithm's state: never serialised, always equal,
/// so checkpoints and state comparisons ignore it.
#[derive(Clone, Default)]
pub struct Scratch<T>(pub T);

impl<T> PartialEq for Scratch<T> {
    fn eq(&self, _other: &Self) -> bool {
        true
    }
}

impl<T> std::fmt::Debug for Scratch<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Scratch")
    }
}

/// Check what every algorithm needs of a problem: at least one objective.
///
/// # Errors
/// [`super::error::ConfigError::ZeroObjectives`].
pub fn check_objectives<P: Problem>(problem: &P) -> Result<(), OptimError> {
    if problem.objectives() == 0 {
        return Err(super::error::ConfigError::ZeroObjectives.into());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn batch_protocol_errors() {
        let mut b: Batch<u8> = Batch::default();
        assert_eq!(
            b.tell(0, Evaluation::new(vec![1.0]), 1, 0),
            Err(TellError::NoBatch)
        );
        b.open(vec![10, 11]);
        assert_eq!(
            b.tell(2, Evaluation::new(vec![1.0]), 1, 0),
            Err(TellError::IndexOutOfRange { index: 2, batch: 2 })
        );
        assert_eq!(b.tell(1, Evaluation::new(vec![1.0]), 1, 0), Ok(false));
        assert_eq!(
            b.tell(1, Evaluation::new(vec![1.0]), 1, 0),
            Err(TellError::AlreadyTold { index: 1 })
        );
        assert_eq!(b.tell(0, Evaluation::new(vec![0.5]), 1, 0), Ok(true));
        let inds = b.take();
        assert_eq!(inds.len(), 2);
        assert_eq!((inds[0].decision, inds[0].objectives[0]), (10, 0.5));
        assert!(!b.is_open());
    }
}
