//! A run on a variable-length test problem (`host-sim optimize --problem vlmopN scea|mhaco`,
//! `reentry.run_variable_length` in Python): the structured-chromosome algorithm of the
//! flags' options ([`RunOptions::variable_length_spec`]: SCEA, or MHACO as the
//! variable-length MHACO) evolved by the [`Executor`], and its report. The front ends only
//! map their arguments and write the report ([`crate::report::write_chromosome_run_report`]).

use super::chromosome::Chromosome;
use super::problems::Vlmop;
use super::run::{RunReport, RunReportError, RunResult, RunSettings, vlmop_run_report};
use super::spec::{ChromosomeAlgorithm, RunOptions};
use super::{Budget, BuiltAlgorithm, Executor, OptimError, Threads};

/// Why MOEA/D and NSGA-II do not run on a variable-length problem (the CLI's message, and
/// [`VariableLengthRunError::NotVariableLength`]'s).
pub const VARIABLE_LENGTH_ALGORITHMS: &str = "a variable-length problem runs with SCEA or \
     MHACO (the variable-length MHACO) only; use `optimize scea` or `optimize mhaco`";

/// Why a variable-length run could not be made.
#[derive(Debug, thiserror::Error)]
pub enum VariableLengthRunError {
    /// MOEA/D or NSGA-II (real vectors only).
    #[error("{algorithm}: {VARIABLE_LENGTH_ALGORITHMS}")]
    NotVariableLength {
        /// The algorithm of the options.
        algorithm: &'static str,
    },
    /// The algorithm refused its settings or an evaluation failed.
    #[error(transparent)]
    Optim(#[from] OptimError),
}

/// A finished run on a variable-length problem.
#[derive(Clone, Debug)]
pub struct VariableLengthRun {
    /// The algorithm after the run.
    pub algorithm: ChromosomeAlgorithm,
    /// Generations run after the initial population.
    pub generations: u64,
    /// Wall time of the evolution alone \[s\].
    pub wall_time_s: f64,
}

impl VariableLengthRun {
    /// Evolve the algorithm of `options` (seeded with `seed`) on `problem` for `generations`
    /// generations after the initial population, evaluating on `threads`.
    ///
    /// # Errors
    /// [`VariableLengthRunError::NotVariableLength`] for MOEA/D and NSGA-II; the
    /// algorithm's [`OptimError`] (its settings, an evaluation).
    pub fn evolve(
        problem: &Vlmop,
        options: &RunOptions,
        seed: u64,
        generations: u64,
        threads: Threads,
    ) -> Result<Self, VariableLengthRunError> {
        let Some(BuiltAlgorithm::Chromosome(algorithm)) =
            options.variable_length_spec().map(|s| s.build(seed))
        else {
            return Err(VariableLengthRunError::NotVariableLength {
                algorithm: options.algorithm.as_str(),
            });
        };
        let done = Executor::new(problem, algorithm)
            .budget(Budget::Generations(generations))
            .threads(threads)
            .run()?;
        Ok(Self {
            algorithm: done.algorithm,
            generations,
            wall_time_s: done.wall_time_s,
        })
    }

    /// The run's report (summary, population, front) on `problem` called `name`, with the
    /// run's `seed`, the hypervolume `reference` point and the evaluation `threads` the
    /// summary reports.
    ///
    /// # Errors
    /// [`RunReportError`] (a reference point of another dimension, the hypervolume).
    pub fn report<'a>(
        &'a self,
        problem: &Vlmop,
        name: &'a str,
        seed: u64,
        reference: &'a [f64],
        threads: usize,
    ) -> Result<RunReport<'a, Chromosome>, RunReportError> {
        let settings = RunSettings::of_chromosome_algorithm(
            &self.algorithm,
            name,
            self.generations,
            seed,
            reference,
            threads,
        );
        let result = RunResult::of::<Vlmop, _>(&self.algorithm, self.wall_time_s);
        vlmop_run_report(problem, &settings, result)
    }
}
