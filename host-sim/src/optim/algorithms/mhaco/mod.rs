//! MHACO, the multi-objective hypervolume-based ant colony optimiser (Acciarini, Izzo & Mooij
//! 2020), with pagmo's `maco` semantics and defaults (ker 63, q 1.0, threshold 1,
//! n_gen_mark 7, evalstop 100000, focus 0), as an ask/tell algorithm, plus two ways of handling
//! constraints (pagmo's `maco` refuses constrained problems): see [`ConstraintHandling`].
//!
//! A generation, as in pagmo:
//! 1. the solution archive (`ker` members) and the ants just evaluated are ranked together
//!    (non-dominated fronts, each ordered by exclusive hypervolume contribution; see
//!    [`archive`]) and the best `ker` form the new archive (the initial population alone the
//!    first time, with a reference offset of 0.1 instead of 0.01);
//! 2. progress: if the ideal point of archive + ants equals the archive's (no improvement),
//!    a stall counter grows, else it resets; `gen_mark` grows by one when the counter is 0 or
//!    above 2 and wraps to 1 past `n_gen_mark`; `evalstop` consecutive stalls stop the run
//!    ([`Algorithm::is_finished`]). (pagmo's code counts the other way round, improvements
//!    rather than stalls, against its own comment and documentation; the documented meaning
//!    is implemented here.)
//! 3. pheromones: rank weights from `q` (which becomes 0.01 at generation `threshold`, so
//!    with pagmo's default threshold of 1 the search is greedy from the start) and per-variable
//!    standard deviations (see [`kernel`]);
//! 4. `population` new ants are sampled around archive members picked by weight.
//!
//! Ask/tell: each batch is one generation's `population` ants; the batch is processed in index
//! order when its last evaluation arrives, so tell order and thread count never change the
//! result. [`Algorithm::population`] is the archive (best first) followed by the ants of the
//! last batch that did not enter it, `population` individuals in all (pagmo returns the archive
//! in the first `ker` slots likewise).

pub mod archive;
pub mod kernel;
pub mod variable;

#[cfg(test)]
mod tests;

use serde::{Deserialize, Serialize};

pub use archive::ConstraintHandling;
pub use variable::VlMhaco;

use crate::optim::algorithm::{Algorithm, Batch, check_objectives};
use crate::optim::error::{ConfigError, OptimError};
use crate::optim::operators::random_point;
use crate::optim::population::Individual;
use crate::optim::problem::{Evaluation, RealProblem};
use crate::optim::rng::OptimRng;

use super::check_range;
use kernel::{Normal, ant, cumulative_weights, pick, sigmas};

const NAME: &str = "mhaco";

/// MHACO settings (defaults are pagmo's `maco`; population 100 as the other algorithms).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MhacoConfig {
    /// Ants per generation (default 100).
    pub population: usize,
    /// Solution archive size, in [2, population] (default 63).
    pub ker: usize,
    /// Convergence speed q > 0 (default 1.0); replaced by 0.01 at generation `threshold`.
    pub q: f64,
    /// Generation (from 1) at which q becomes 0.01 (default 1); at least 1.
    pub threshold: u64,
    /// Period of the standard-deviation schedule `gen_mark`, at least 1 (default 7).
    pub n_gen_mark: u64,
    /// Stop after this many consecutive generations without a better ideal point; 0 never
    /// (default 100000).
    pub evalstop: u64,
    /// Greediness focus >= 0 (default 0: off).
    pub focus: f64,
    /// Constraint handling (default feasibility-first; unconstrained problems: no effect).
    pub constraints: ConstraintHandling,
}

impl Default for MhacoConfig {
    fn default() -> Self {
        Self {
            population: 100,
            ker: 63,
            q: 1.0,
            threshold: 1,
            n_gen_mark: 7,
            evalstop: 100_000,
            focus: 0.0,
            constraints: ConstraintHandling::FeasibilityFirst,
        }
    }
}

impl MhacoConfig {
    pub(crate) fn check(&self, objectives: usize, constraints: usize) -> Result<(), ConfigError> {
        let ranked = match self.constraints {
            ConstraintHandling::AsObjectives { .. } => objectives + constraints,
            ConstraintHandling::FeasibilityFirst => objectives,
        };
        if ranked < 2 {
            return Err(ConfigError::TooFewObjectives {
                algorithm: NAME,
                objectives: ranked,
            });
        }
        super::check_size(NAME, "population", self.population)?;
        if self.population < 2 {
            return Err(ConfigError::PopulationTooSmall {
                algorithm: NAME,
                population: self.population,
                minimum: 2,
            });
        }
        if self.ker < 2 || self.ker > self.population {
            return Err(ConfigError::Count {
                algorithm: NAME,
                name: "ker (solution archive size)",
                value: self.ker,
                range: "[2, population]",
            });
        }
        if !(self.q > 0.0 && self.q.is_finite()) {
            return Err(ConfigError::Parameter {
                algorithm: NAME,
                name: "q",
                value: self.q,
                range: "(0, inf)",
            });
        }
        for (name, value) in [
            ("threshold", self.threshold),
            ("n_gen_mark", self.n_gen_mark),
        ] {
            if value == 0 {
                return Err(ConfigError::Count {
                    algorithm: NAME,
                    name,
                    value: 0,
                    range: "[1, inf)",
                });
            }
        }
        check_range(NAME, "focus", self.focus, 0.0, f64::MAX, "[0, inf)")?;
        if let ConstraintHandling::AsObjectives {
            scales,
            cap,
            penalty,
        } = &self.constraints
        {
            check_range(NAME, "cap", *cap, f64::MIN_POSITIVE, f64::MAX, "(0, inf)")?;
            check_range(NAME, "penalty", *penalty, 0.0, f64::MAX, "[0, inf)")?;
            if let Some(s) = scales {
                if s.len() != constraints {
                    return Err(ConfigError::Count {
                        algorithm: NAME,
                        name: "scales (one per constraint of the problem)",
                        value: s.len(),
                        range: "exactly the problem's number of constraints",
                    });
                }
                for &v in s {
                    check_range(
                        NAME,
                        "scales[i]",
                        v,
                        f64::MIN_POSITIVE,
                        f64::MAX,
                        "(0, inf)",
                    )?;
                }
            }
        }
        Ok(())
    }
}

/// MHACO state (serialisable: checkpoint and resume give the bit-identical run).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Mhaco {
    config: MhacoConfig,
    rng: OptimRng,
    normal: Normal,
    /// Archive (first `archive_len`, best first), then the rest of the last batch.
    population: Vec<Individual<Vec<f64>>>,
    archive_len: usize,
    /// Current convergence parameter (pagmo's mutable `m_q`).
    q: f64,
    gen_mark: u64,
    stalls: u64,
    finished: bool,
    batch: Batch<Vec<f64>>,
    initialised: bool,
    generation: u64,
    evaluations: u64,
}

impl Mhaco {
    /// A new run with `config`, seeded with `seed`.
    #[must_use]
    pub fn new(config: MhacoConfig, seed: u64) -> Self {
        let q = config.q;
        Self {
            config,
            rng: OptimRng::new(seed),
            normal: Normal,
            population: Vec::new(),
            archive_len: 0,
            q,
            gen_mark: 1,
            stalls: 0,
            finished: false,
            batch: Batch::default(),
            initialised: false,
            generation: 0,
            evaluations: 0,
        }
    }

    /// The archive followed by the other ants of the last batch.
    #[must_use]
    pub fn population(&self) -> &[Individual<Vec<f64>>] {
        &self.population
    }

    /// The initial population has been evaluated.
    #[must_use]
    pub fn is_initialised(&self) -> bool {
        self.initialised
    }

    /// Completed generations after the initial population.
    #[must_use]
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// Evaluations told so far.
    #[must_use]
    pub fn evaluations(&self) -> u64 {
        self.evaluations
    }

    /// Stopped by `evalstop`.
    #[must_use]
    pub fn is_finished(&self) -> bool {
        self.finished
    }

    /// The settings.
    #[must_use]
    pub fn config(&self) -> &MhacoConfig {
        &self.config
    }

    /// The solution archive, best first (empty before the initial population is told).
    #[must_use]
    pub fn archive(&self) -> &[Individual<Vec<f64>>] {
        &self.population[..self.archive_len]
    }

    /// Current `gen_mark` (divisor of the standard deviations).
    #[must_use]
    pub fn gen_mark(&self) -> u64 {
        self.gen_mark
    }

    /// Consecutive generations without a better ideal point.
    #[must_use]
    pub fn stalls(&self) -> u64 {
        self.stalls
    }

    fn make_ants<P: RealProblem>(&mut self, problem: &P) {
        let generation = self.generation + 1;
        if generation == self.config.threshold {
            self.q = 0.01;
        }
        let cumulative = cumulative_weights(self.archive_len, self.q);
        let bounds = problem.bounds();
        let kernels: Vec<&[f64]> = self.population[..self.archive_len]
            .iter()
            .map(|i| i.decision.as_slice())
            .collect();
        let sigma = sigmas(
            &kernels,
            bounds,
            self.gen_mark,
            self.config.focus,
            generation,
        );
        let ants = (0..self.config.population)
            .map(|_| {
                let k = pick(&cumulative, self.rng.uniform());
                ant(kernels[k], &sigma, bounds, &mut self.normal, &mut self.rng)
            })
            .collect();
        self.batch.open(ants);
    }

    fn update_archive(
        &mut self,
        merged: Vec<Individual<Vec<f64>>>,
        batch_start: usize,
        offset: f64,
    ) {
        (self.population, self.archive_len) = select(&self.config, merged, batch_start, offset);
    }

    fn count_progress(&mut self, improved: bool) {
        self.finished |= advance(&self.config, improved, &mut self.stalls, &mut self.gen_mark);
    }
}

/// Rank `merged` (old archive first, then the batch starting at `batch_start`), keep the best
/// `ker` as the archive and fill up with the batch's other members: the new population and
/// the archive's length (shared by [`Mhaco`] and [`VlMhaco`]).
pub(crate) fn select<D>(
    config: &MhacoConfig,
    merged: Vec<Individual<D>>,
    batch_start: usize,
    offset: f64,
) -> (Vec<Individual<D>>, usize) {
    let keep = config.ker.min(merged.len());
    let order = archive::rank(&merged, &config.constraints, keep, offset);
    let mut slots: Vec<Option<Individual<D>>> = merged.into_iter().map(Some).collect();
    let mut population = Vec::with_capacity(config.population);
    for &i in &order {
        if let Some(ind) = slots[i].take() {
            population.push(ind);
        }
    }
    let archive_len = population.len();
    for ind in slots.into_iter().skip(batch_start).flatten() {
        if population.len() >= config.population {
            break;
        }
        population.push(ind);
    }
    (population, archive_len)
}

/// Progress bookkeeping of pagmo's step 2 (see the module documentation); `true` when
/// `evalstop` stops the run.
pub(crate) fn advance(
    config: &MhacoConfig,
    improved: bool,
    stalls: &mut u64,
    gen_mark: &mut u64,
) -> bool {
    if improved {
        *stalls = 0;
    } else {
        *stalls += 1;
    }
    if *stalls == 0 || *stalls > 2 {
        *gen_mark += 1;
    }
    if *gen_mark > config.n_gen_mark {
        *gen_mark = 1;
    }
    config.evalstop != 0 && *stalls >= config.evalstop
}

impl<P: RealProblem> Algorithm<P> for Mhaco {
    fn name(&self) -> &'static str {
        NAME
    }

    fn ask(&mut self, problem: &P) -> Result<&[Vec<f64>], OptimError> {
        if self.finished {
            return Ok(&[]);
        }
        if !self.batch.is_open() {
            if self.initialised {
                self.make_ants(problem);
            } else {
                check_objectives(problem)?;
                self.config
                    .check(problem.objectives(), problem.constraints())?;
                let decisions = (0..self.config.population)
                    .map(|_| random_point(problem.bounds(), &mut self.rng))
                    .collect();
                self.batch.open(decisions);
            }
        }
        Ok(self.batch.decisions())
    }

    fn tell(
        &mut self,
        problem: &P,
        index: usize,
        evaluation: Evaluation,
    ) -> Result<(), OptimError> {
        let complete = self.batch.tell(
            index,
            evaluation,
            problem.objectives(),
            problem.constraints(),
        )?;
        self.evaluations += 1;
        if !complete {
            return Ok(());
        }
        let told = self.batch.take();
        if self.initialised {
            let handling = &self.config.constraints;
            let before = archive::progress_marker(self.archive(), handling);
            let mut merged = std::mem::take(&mut self.population);
            merged.truncate(self.archive_len);
            let start = merged.len();
            merged.extend(told);
            let after = archive::progress_marker(&merged, handling);
            self.count_progress(before != after);
            self.update_archive(merged, start, 0.01);
            self.generation += 1;
        } else {
            self.update_archive(told, 0, 0.1);
            self.initialised = true;
            self.count_progress(true);
        }
        Ok(())
    }

    fn population(&self) -> &[Individual<Vec<f64>>] {
        &self.population
    }

    fn is_initialised(&self) -> bool {
        self.initialised
    }

    fn generation(&self) -> u64 {
        self.generation
    }

    fn evaluations(&self) -> u64 {
        self.evaluations
    }

    fn is_told(&self, index: usize) -> bool {
        self.batch.is_told(index)
    }

    fn is_finished(&self) -> bool {
        self.finished
    }

    fn validate(&self, problem: &P) -> Result<(), crate::optim::StateError> {
        use crate::optim::restore::{bad, count, individuals, real_decision};
        let (m, c) = (problem.objectives(), problem.constraints());
        self.config
            .check(m, c)
            .map_err(|e| bad("config", "(restored)", e.to_string()))?;
        let n = self.config.population;
        let dec = |f: &str, d: &Vec<f64>| real_decision(f, d, problem.bounds());
        self.batch.validate("batch", m, c, &dec)?;
        if self.batch.is_open() {
            count("batch.decisions.len()", self.batch.decisions().len(), n)?;
        }
        if !(self.q > 0.0 && self.q.is_finite()) {
            return Err(bad("q", self.q, "must be finite and > 0"));
        }
        if !(1..=self.config.n_gen_mark).contains(&self.gen_mark) {
            return Err(bad(
                "gen_mark",
                self.gen_mark,
                format!("must be in [1, n_gen_mark = {}]", self.config.n_gen_mark),
            ));
        }
        if !self.initialised {
            count("population.len()", self.population.len(), 0)?;
            count("generation", self.generation as usize, 0)?;
            return Ok(());
        }
        let len = self.population.len();
        if self.archive_len == 0 || self.archive_len > self.config.ker.min(len) {
            return Err(bad(
                "archive_len",
                self.archive_len,
                format!(
                    "must be in [1, min(ker, population.len()) = {}]",
                    self.config.ker.min(len)
                ),
            ));
        }
        if len > self.config.ker + n {
            return Err(bad(
                "population.len()",
                len,
                format!("must be at most ker + population = {}", self.config.ker + n),
            ));
        }
        individuals("population", &self.population, m, c, &dec)
    }
}
