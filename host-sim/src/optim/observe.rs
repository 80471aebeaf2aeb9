//! Per-generation observation. The library never prints: a caller who wants a log, a
//! progress bar or a convergence history passes an [`Observer`] (a closure works).

use serde::{Deserialize, Serialize};

use super::hypervolume::{HypervolumeError, hypervolume};
use super::population::{Individual, feasible_fraction, feasible_front};

/// What an observer sees after each generation (and after the initial population,
/// generation 0).
#[derive(Debug)]
pub struct GenerationReport<'a, D> {
    /// Algorithm name.
    pub algorithm: &'static str,
    /// Completed generations after the initial population.
    pub generation: u64,
    /// Evaluations so far.
    pub evaluations: u64,
    /// The population (decisions, objectives, constraint values and violations).
    pub population: &'a [Individual<D>],
    /// The algorithm's external archive of feasible non-dominated solutions, if it keeps one
    /// ([`crate::optim::Algorithm::external_archive`]); then it is the reported front.
    pub archive: Option<&'a [Individual<D>]>,
}

impl<D> GenerationReport<'_, D> {
    /// Fraction of feasible individuals.
    #[must_use]
    pub fn feasible_fraction(&self) -> f64 {
        feasible_fraction(self.population)
    }

    /// Objective vectors of the feasible non-dominated individuals: of the external archive
    /// when the algorithm keeps one, else of the population.
    #[must_use]
    pub fn front(&self) -> Vec<Vec<f64>> {
        feasible_front(self.archive.unwrap_or(self.population))
    }

    /// Hypervolume of [`Self::front`] with respect to `reference` (failed and infeasible
    /// individuals never reach the hypervolume code; 0 when none is feasible).
    ///
    /// # Errors
    /// [`HypervolumeError`] for a reference point of the wrong dimension.
    pub fn hypervolume(&self, reference: &[f64]) -> Result<f64, HypervolumeError> {
        hypervolume(&self.front(), reference)
    }

    /// Smallest constraint violation in the population (0 when some individual is feasible).
    #[must_use]
    pub fn min_violation(&self) -> f64 {
        self.population
            .iter()
            .map(|i| i.violation)
            .fold(f64::INFINITY, f64::min)
    }
}

/// Receives a report after every generation.
pub trait Observer<D> {
    /// Called once per generation, in order.
    fn observe(&mut self, report: &GenerationReport<'_, D>);
}

impl<D, F> Observer<D> for F
where
    F: FnMut(&GenerationReport<'_, D>),
{
    fn observe(&mut self, report: &GenerationReport<'_, D>) {
        self(report);
    }
}

/// Observes nothing.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoObserver;

impl<D> Observer<D> for NoObserver {
    fn observe(&mut self, _report: &GenerationReport<'_, D>) {}
}

/// One generation's summary, as recorded by [`History`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GenerationRecord {
    /// Generation (0 = initial population).
    pub generation: u64,
    /// Evaluations so far.
    pub evaluations: u64,
    /// Fraction of feasible individuals.
    #[serde(with = "crate::optim::nonfinite::scalar")]
    pub feasible_fraction: f64,
    /// Smallest violation in the population.
    #[serde(with = "crate::optim::nonfinite::scalar")]
    pub min_violation: f64,
    /// Hypervolume of the feasible front, if a reference point was given and valid.
    #[serde(with = "crate::optim::nonfinite::option")]
    pub hypervolume: Option<f64>,
}

/// Records a [`GenerationRecord`] per generation.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct History {
    /// Reference point for the hypervolume (none: no hypervolume recorded).
    pub reference: Option<Vec<f64>>,
    /// The records, in generation order.
    pub records: Vec<GenerationRecord>,
}

impl History {
    /// A history that also records the hypervolume with respect to `reference`.
    #[must_use]
    pub fn with_reference(reference: Vec<f64>) -> Self {
        Self {
            reference: Some(reference),
            records: Vec::new(),
        }
    }
}

impl<D> Observer<D> for History {
    fn observe(&mut self, report: &GenerationReport<'_, D>) {
        let hypervolume = self
            .reference
            .as_deref()
            .and_then(|r| report.hypervolume(r).ok());
        self.records.push(GenerationRecord {
            generation: report.generation,
            evaluations: report.evaluations,
            feasible_fraction: report.feasible_fraction(),
            min_violation: report.min_violation(),
            hypervolume,
        });
    }
}
