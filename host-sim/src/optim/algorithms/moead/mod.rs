//! MOEA/D-DE (Zhang & Li 2007; Li & Zhang 2009) with pagmo's semantics and defaults, plus
//! Lampinen's constraint rules (thesis 4.1.3).
//!
//! Per generation the subproblems are visited in a fresh random order. For subproblem `n`:
//! with probability `realb` (or always, without `preserve_diversity`) the parents come from
//! its neighbourhood (the `neighbours` nearest *other* weights, pagmo's `kNN`: `n` is not its
//! own neighbour), else from the whole population; two distinct parents `a, b` are drawn;
//! the child is `x_n + F (x_a - x_b)` per variable with probability `CR` (bound repair as in
//! pagmo), then polynomial mutation (probability `1/dim` unless set, index `eta_m`). The child
//! updates the ideal point, replaces the member of subproblem `n` if it solves `n` better, and
//! then, in random order, members of the same pool whose subproblems it solves better, at most
//! `limit` replacements in all when `preserve_diversity` is on.
//!
//! "Better" follows Lampinen (2002): a feasible child beats an infeasible member; of two
//! infeasible the child wins with a violation lower or equal; of two feasible the child wins
//! with a strictly lower decomposed value. The ideal point is the minimum over feasible
//! individuals only (for unconstrained problems that is pagmo's ideal point).
//!
//! Ask/tell: `batch_size` offspring are made from the same population state and applied in
//! index order when all are told. `batch_size = 1` (default) is pagmo's steady-state loop;
//! larger batches allow parallel evaluation at the price of slightly staler parents.
//!
//! Opt-in (`archive: Some(capacity)`, not pagmo): Zhang & Li's (2007) external population.
//! Every evaluated individual (the initial population, then each child) is offered, in batch
//! order, to a bounded [`ParetoArchive`] of the feasible non-dominated solutions found so far,
//! which is then the run's result front ([`Algorithm::external_archive`]). The archive never
//! feeds back into selection, so the population evolves exactly as without it.
//!
//! Opt-in (`resource_allocation: Some(..)`, not pagmo): MOEA/D-DRA's dynamic resource
//! allocation (Zhang, Liu & Li 2009, [`ResourceAllocation`]): a generation works on the
//! boundary subproblems and tournament winners on utility (population / 5 in all) instead of
//! every subproblem, so a generation has fewer evaluations; the variation and replacement of
//! each chosen subproblem are the above.

use std::fmt::Debug;

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use crate::optim::algorithm::{Algorithm, Batch, Scratch, check_objectives};
use crate::optim::archive::{ParetoArchive, check_capacity};
use crate::optim::error::{ConfigError, OptimError};
use crate::optim::operators::{de_step, polynomial_mutation, random_point};
use crate::optim::population::Individual;
use crate::optim::problem::{Decision, Evaluation, Problem, RealProblem};
use crate::optim::rng::OptimRng;
use crate::optim::weights::{
    Decomposition, WeightGeneration, decompose, generate, neighbourhoods, tchebycheff,
};

use super::check_range;

mod dra;
mod restore;
mod sbx;

pub use dra::ResourceAllocation;
use dra::{DraState, boundary_subproblems};
pub use sbx::{MoeadSbx, SbxVariation};

const NAME: &str = "moead";

/// MOEA/D settings (defaults are pagmo's).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MoeadConfig {
    /// Population size = number of subproblems (default 100).
    pub population: usize,
    /// Weight generation (default grid).
    pub weights: WeightGeneration,
    /// Decomposition (default Tchebycheff).
    pub decomposition: Decomposition,
    /// Neighbourhood size T (default 20; at least 2, at most population - 1).
    pub neighbours: usize,
    /// DE crossover probability CR in [0, 1] (default 1.0).
    pub cr: f64,
    /// DE weight F in [0, 1] (default 0.5).
    pub f: f64,
    /// Polynomial-mutation distribution index in [0, 100] (default 20).
    pub eta_m: f64,
    /// Probability of mating within the neighbourhood, in [0, 1] (default 0.9).
    pub realb: f64,
    /// Most members one child may replace (default 2).
    pub limit: usize,
    /// Diversity preservation (realb and limit active; default true).
    pub preserve_diversity: bool,
    /// Per-variable mutation probability; `None` (default) is 1/dim. (The thesis used
    /// 1/population.)
    pub mutation_probability: Option<f64>,
    /// Offspring per ask (default 1: pagmo's steady state).
    pub batch_size: usize,
    /// Capacity of an external archive of the feasible non-dominated solutions found during
    /// the run (Zhang & Li 2007's external population, bounded by hypervolume truncation:
    /// [`ParetoArchive`]); it is then the run's result front. `None` (default): pagmo's
    /// semantics, no archive, the result is the final population.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub archive: Option<usize>,
    /// MOEA/D-DRA's dynamic resource allocation (Zhang, Liu & Li 2009): each generation
    /// works on the boundary subproblems and tournament winners on utility (population / 5
    /// by default) rather than on all subproblems. `None` (default): pagmo's semantics.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub resource_allocation: Option<ResourceAllocation>,
}

impl Default for MoeadConfig {
    fn default() -> Self {
        Self {
            population: 100,
            weights: WeightGeneration::Grid,
            decomposition: Decomposition::Tchebycheff,
            neighbours: 20,
            cr: 1.0,
            f: 0.5,
            eta_m: 20.0,
            realb: 0.9,
            limit: 2,
            preserve_diversity: true,
            mutation_probability: None,
            batch_size: 1,
            archive: None,
            resource_allocation: None,
        }
    }
}

impl MoeadConfig {
    /// The neighbourhood size used when none is given: the thesis' 20, or `population - 1`
    /// for smaller populations (at least 2).
    #[must_use]
    pub fn default_neighbours(population: usize) -> usize {
        20.min(population.saturating_sub(1)).max(2)
    }

    pub(crate) fn check(&self, objectives: usize) -> Result<(), ConfigError> {
        if objectives < 2 {
            return Err(ConfigError::TooFewObjectives {
                algorithm: NAME,
                objectives,
            });
        }
        super::check_size(NAME, "population", self.population)?;
        if self.population < 3 {
            return Err(ConfigError::PopulationTooSmall {
                algorithm: NAME,
                population: self.population,
                minimum: 3,
            });
        }
        if self.neighbours < 2 {
            return Err(ConfigError::Count {
                algorithm: NAME,
                name: "neighbours",
                value: self.neighbours,
                range: "[2, population - 1]",
            });
        }
        if self.neighbours > self.population - 1 {
            return Err(ConfigError::TooManyNeighbours {
                neighbours: self.neighbours,
                population: self.population,
            });
        }
        if self.batch_size == 0 || self.batch_size > self.population {
            return Err(ConfigError::Count {
                algorithm: NAME,
                name: "batch_size",
                value: self.batch_size,
                range: "[1, population]",
            });
        }
        check_range(NAME, "cr", self.cr, 0.0, 1.0, "[0, 1]")?;
        check_range(NAME, "f", self.f, 0.0, 1.0, "[0, 1]")?;
        check_range(NAME, "eta_m", self.eta_m, 0.0, 100.0, "[0, 100]")?;
        check_range(NAME, "realb", self.realb, 0.0, 1.0, "[0, 1]")?;
        if let Some(p) = self.mutation_probability {
            check_range(NAME, "mutation_probability", p, 0.0, 1.0, "[0, 1]")?;
        }
        if let Some(capacity) = self.archive {
            check_capacity(NAME, capacity)?;
        }
        if let Some(ra) = &self.resource_allocation {
            ra.check(self.population)?;
        }
        Ok(())
    }
}

/// Which pool the parents of one child came from.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
struct ChildOrigin {
    subproblem: usize,
    whole_population: bool,
}

/// How MOEA/D makes decisions: the random initial ones, and the child of a subproblem's
/// member and two parents. [`DeVariation`] is pagmo's operator for real vectors; a
/// structured-chromosome variation (SCEA) plugs in here and inherits the rest of MOEA/D
/// (weights, neighbourhoods, decomposition, Lampinen's rules, ask/tell, checkpoints).
pub trait MoeadVariation<P: Problem>:
    Clone + Debug + PartialEq + Serialize + DeserializeOwned
{
    /// Check the settings against the problem (called by the first `ask`).
    ///
    /// # Errors
    /// [`ConfigError`] naming the setting to change.
    fn check(&self, _problem: &P, _config: &MoeadConfig) -> Result<(), ConfigError> {
        Ok(())
    }

    /// A random decision for the initial population.
    fn random(&self, problem: &P, rng: &mut OptimRng) -> P::Decision;

    /// Check a restored decision (`field` names it) against the problem: its dimension and
    /// finite values within the bounds. Default: accept any.
    ///
    /// # Errors
    /// [`crate::optim::StateError`] naming the field.
    fn check_decision(
        &self,
        problem: &P,
        field: &str,
        decision: &P::Decision,
    ) -> Result<(), crate::optim::StateError> {
        let _ = (problem, field, decision);
        Ok(())
    }

    /// The child of subproblem member `x` with parents `a` and `b`. `reuse` is a spent
    /// decision whose allocation may be recycled (its contents are meaningless).
    #[allow(clippy::too_many_arguments)] // the operator has exactly these inputs
    fn child(
        &self,
        problem: &P,
        config: &MoeadConfig,
        x: &P::Decision,
        a: &P::Decision,
        b: &P::Decision,
        reuse: Option<P::Decision>,
        rng: &mut OptimRng,
    ) -> P::Decision;
}

/// pagmo's MOEA/D operator for real vectors: the DE step `x + F (a - b)` per variable with
/// probability CR (pagmo's bound repair), then polynomial mutation with probability
/// `mutation_probability` (default 1/dim) and index `eta_m`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct DeVariation;

impl<P: RealProblem> MoeadVariation<P> for DeVariation {
    fn random(&self, problem: &P, rng: &mut OptimRng) -> Vec<f64> {
        random_point(problem.bounds(), rng)
    }

    fn check_decision(
        &self,
        problem: &P,
        field: &str,
        decision: &Vec<f64>,
    ) -> Result<(), crate::optim::StateError> {
        crate::optim::restore::real_decision(field, decision, problem.bounds())
    }

    fn child(
        &self,
        problem: &P,
        config: &MoeadConfig,
        x: &Vec<f64>,
        a: &Vec<f64>,
        b: &Vec<f64>,
        reuse: Option<Vec<f64>>,
        rng: &mut OptimRng,
    ) -> Vec<f64> {
        let bounds = problem.bounds();
        let rate = config
            .mutation_probability
            .unwrap_or(1.0 / bounds.dim() as f64);
        let mut child = reuse.unwrap_or_default();
        de_step(x, a, b, config.f, config.cr, bounds, rng, &mut child);
        polynomial_mutation(&mut child, bounds, rate, config.eta_m, rng);
        child
    }
}

/// MOEA/D on real vectors with pagmo's operator.
pub type Moead = MoeadWith<Vec<f64>, DeVariation>;

/// MOEA/D state for decisions `D` made by variation `V` (serialisable: checkpoint and resume
/// give the bit-identical run).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(bound(
    serialize = "D: Serialize, V: Serialize",
    deserialize = "D: DeserializeOwned, V: DeserializeOwned"
))]
pub struct MoeadWith<D, V> {
    config: MoeadConfig,
    variation: V,
    rng: OptimRng,
    population: Vec<Individual<D>>,
    weights: Vec<Vec<f64>>,
    neighbourhoods: Vec<Vec<usize>>,
    #[serde(with = "crate::optim::nonfinite::vec")]
    ideal: Vec<f64>,
    /// Subproblem order of the current generation and the next position in it.
    order: Vec<usize>,
    cursor: usize,
    batch: Batch<D>,
    origins: Vec<ChildOrigin>,
    initialised: bool,
    generation: u64,
    evaluations: u64,
    /// The external archive (`config.archive`), every evaluated individual offered in batch
    /// order.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    archive: Option<ParetoArchive<D>>,
    /// MOEA/D-DRA's utilities (`config.resource_allocation`), created with the population.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    dra: Option<DraState>,
    #[serde(skip)]
    scratch: Scratch<Buffers<D>>,
}

/// Reused allocations (not state).
#[derive(Clone, Debug)]
struct Buffers<D> {
    pool: Vec<usize>,
    told: Vec<Individual<D>>,
    spare: Vec<D>,
    candidates: Vec<usize>,
}

impl<D> Default for Buffers<D> {
    fn default() -> Self {
        Self {
            pool: Vec::new(),
            told: Vec::new(),
            spare: Vec::new(),
            candidates: Vec::new(),
        }
    }
}

impl Moead {
    /// A new run with `config` and pagmo's operator, seeded with `seed`.
    #[must_use]
    pub fn new(config: MoeadConfig, seed: u64) -> Self {
        Self::with_variation(config, DeVariation, seed)
    }
}

impl<D: Decision, V> MoeadWith<D, V> {
    /// A new run with `config` and `variation`, seeded with `seed`.
    #[must_use]
    pub fn with_variation(config: MoeadConfig, variation: V, seed: u64) -> Self {
        Self {
            config,
            variation,
            rng: OptimRng::new(seed),
            population: Vec::new(),
            weights: Vec::new(),
            neighbourhoods: Vec::new(),
            ideal: Vec::new(),
            order: Vec::new(),
            cursor: 0,
            batch: Batch::default(),
            origins: Vec::new(),
            initialised: false,
            generation: 0,
            evaluations: 0,
            archive: None,
            dra: None,
            scratch: Scratch::default(),
        }
    }

    /// The current population (parents).
    #[must_use]
    pub fn population(&self) -> &[Individual<D>] {
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

    /// The settings.
    #[must_use]
    pub fn config(&self) -> &MoeadConfig {
        &self.config
    }

    /// The weight vectors (one per subproblem; empty before the first ask).
    #[must_use]
    pub fn weights(&self) -> &[Vec<f64>] {
        &self.weights
    }

    /// The ideal point (minimum of each objective over feasible individuals; `f64::MAX`
    /// while none is feasible).
    #[must_use]
    pub fn ideal(&self) -> &[f64] {
        &self.ideal
    }

    /// The variation operator.
    #[must_use]
    pub fn variation(&self) -> &V {
        &self.variation
    }

    /// The external archive, when `config.archive` is set (created by the first ask).
    #[must_use]
    pub fn archive(&self) -> Option<&ParetoArchive<D>> {
        self.archive.as_ref()
    }

    fn start<P>(&mut self, problem: &P) -> Result<(), OptimError>
    where
        P: Problem<Decision = D>,
        V: MoeadVariation<P>,
    {
        check_objectives(problem)?;
        let m = problem.objectives();
        self.config.check(m)?;
        self.variation.check(problem, &self.config)?;
        let n = self.config.population;
        self.weights = generate(n, m, self.config.weights, &mut self.rng)?;
        self.neighbourhoods = neighbourhoods(&self.weights, self.config.neighbours);
        self.ideal = vec![f64::MAX; m];
        self.archive = self.config.archive.map(ParetoArchive::new).transpose()?;
        let decisions = (0..n)
            .map(|_| self.variation.random(problem, &mut self.rng))
            .collect();
        self.batch.open(decisions);
        Ok(())
    }

    fn select_parents(&mut self, n: usize, whole: bool) -> [usize; 2] {
        let hood = &self.neighbourhoods[n];
        let np = self.population.len();
        let draw = |rng: &mut OptimRng| {
            if whole {
                rng.below(np)
            } else {
                hood[rng.below(hood.len())]
            }
        };
        let a = draw(&mut self.rng);
        let mut b = draw(&mut self.rng);
        while b == a {
            b = draw(&mut self.rng);
        }
        [a, b]
    }

    fn make_offspring<P>(&mut self, problem: &P)
    where
        P: Problem<Decision = D>,
        V: MoeadVariation<P>,
    {
        let count = self.config.batch_size.min(self.order.len() - self.cursor);
        let mut batch = std::mem::take(&mut self.batch);
        let mut spare = std::mem::take(&mut self.scratch.0.spare);
        self.origins.clear();
        batch.open_with(|decisions| {
            for k in 0..count {
                decisions.push(self.offspring(problem, k, &mut spare));
            }
        });
        self.batch = batch;
        self.scratch.0.spare = spare;
    }

    fn offspring<P>(&mut self, problem: &P, k: usize, spare: &mut Vec<D>) -> D
    where
        P: Problem<Decision = D>,
        V: MoeadVariation<P>,
    {
        let n = self.order[self.cursor + k];
        let whole = self.config.preserve_diversity && self.rng.uniform() >= self.config.realb;
        let [a, b] = self.select_parents(n, whole);
        let child = self.variation.child(
            problem,
            &self.config,
            &self.population[n].decision,
            &self.population[a].decision,
            &self.population[b].decision,
            spare.pop(),
            &mut self.rng,
        );
        self.origins.push(ChildOrigin {
            subproblem: n,
            whole_population: whole,
        });
        child
    }

    fn update_ideal(ideal: &mut [f64], ind: &Individual<D>) {
        if ind.is_feasible() {
            for (z, &f) in ideal.iter_mut().zip(&ind.objectives) {
                if f < *z {
                    *z = f;
                }
            }
        }
    }

    /// Lampinen's selection: does `child` replace `member` on subproblem `weight`?
    fn child_wins(&self, child: &Individual<D>, member: &Individual<D>, weight: &[f64]) -> bool {
        match (child.is_feasible(), member.is_feasible()) {
            (true, true) => match self.config.decomposition {
                Decomposition::Tchebycheff => {
                    tchebycheff(&child.objectives, weight, &self.ideal)
                        < tchebycheff(&member.objectives, weight, &self.ideal)
                }
                kind => {
                    decompose(kind, &child.objectives, weight, &self.ideal)
                        < decompose(kind, &member.objectives, weight, &self.ideal)
                }
            },
            (true, false) => true,
            (false, true) => false,
            (false, false) => child.violation <= member.violation,
        }
    }

    fn apply(&mut self, child: &Individual<D>, origin: ChildOrigin) {
        Self::update_ideal(&mut self.ideal, child);
        let np = self.population.len();
        let size = if origin.whole_population {
            np
        } else {
            self.neighbourhoods[origin.subproblem].len()
        };
        // First the child's own subproblem (pagmo: "first try on problem n"), then the pool in
        // random order (the neighbourhood, which does not hold n, or the whole population);
        // both count towards `limit`.
        let n = origin.subproblem;
        let mut replaced = 0;
        if self.child_wins(child, &self.population[n], &self.weights[n]) {
            self.population[n].clone_from(child);
            replaced += 1;
        }
        let mut pool = std::mem::take(&mut self.scratch.0.pool);
        pool.clear();
        pool.extend(0..size);
        self.rng.shuffle(&mut pool);
        for &k in &pool {
            let pick = if origin.whole_population {
                k
            } else {
                self.neighbourhoods[origin.subproblem][k]
            };
            if self.child_wins(child, &self.population[pick], &self.weights[pick]) {
                self.population[pick].clone_from(child);
                replaced += 1;
            }
            if replaced >= self.config.limit && self.config.preserve_diversity {
                break;
            }
        }
        self.scratch.0.pool = pool;
    }

    /// The subproblems the current generation works on, in order (all of them, shuffled, in
    /// pagmo's MOEA/D; the DRA selection with resource allocation; empty before the initial
    /// population is told).
    #[must_use]
    pub fn subproblems_this_generation(&self) -> &[usize] {
        &self.order
    }

    /// The utilities of subproblems `0..n` (MOEA/D-DRA), `None` without resource allocation.
    #[must_use]
    pub fn utilities(&self) -> Option<&[f64]> {
        self.dra.as_ref().map(|d| d.utility.as_slice())
    }

    /// MOEA/D-DRA: every `period` generations, the utilities from each member's relative
    /// improvement of its decomposed value (with the current ideal point).
    fn update_utilities(&mut self) {
        let (Some(ra), Some(dra)) = (&self.config.resource_allocation, &mut self.dra) else {
            return;
        };
        if !self.generation.is_multiple_of(ra.period) {
            return;
        }
        let (kind, weights, ideal) = (self.config.decomposition, &self.weights, &self.ideal);
        dra.update(&self.population, |i, f| {
            decompose(kind, f, &weights[i], ideal)
        });
    }

    fn new_generation_order(&mut self) {
        self.cursor = 0;
        if let (Some(ra), Some(dra)) = (&self.config.resource_allocation, &self.dra) {
            let m = self.ideal.len();
            let count = ra.subproblems_per_generation(self.population.len(), m);
            let boundary = boundary_subproblems(&self.weights, m);
            let mut candidates = std::mem::take(&mut self.scratch.0.candidates);
            dra.select(
                &boundary,
                count,
                ra.tournament,
                &mut self.rng,
                &mut self.order,
                &mut candidates,
            );
            self.scratch.0.candidates = candidates;
            return;
        }
        self.order = (0..self.config.population).collect();
        self.rng.shuffle(&mut self.order);
    }
}

impl<P, V> Algorithm<P> for MoeadWith<P::Decision, V>
where
    P: Problem,
    V: MoeadVariation<P>,
{
    fn name(&self) -> &'static str {
        NAME
    }

    fn ask(&mut self, problem: &P) -> Result<&[P::Decision], OptimError> {
        if !self.batch.is_open() {
            if self.initialised {
                self.make_offspring(problem);
            } else {
                self.start(problem)?;
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
        if self.initialised {
            let mut told = std::mem::take(&mut self.scratch.0.told);
            self.batch.take_into(&mut told);
            let origins = std::mem::take(&mut self.origins);
            for (child, origin) in told.iter().zip(&origins) {
                self.apply(child, *origin);
            }
            if let Some(archive) = &mut self.archive {
                for child in &told {
                    archive.offer(child);
                }
            }
            self.origins = origins;
            self.cursor += told.len();
            self.scratch
                .0
                .spare
                .extend(told.drain(..).map(|i| i.decision));
            self.scratch.0.told = told;
            if self.cursor >= self.order.len() {
                self.generation += 1;
                self.update_utilities();
                self.new_generation_order();
            }
        } else {
            let told = self.batch.take();
            for ind in &told {
                Self::update_ideal(&mut self.ideal, ind);
                if let Some(archive) = &mut self.archive {
                    archive.offer(ind);
                }
            }
            self.population = told;
            if self.config.resource_allocation.is_some() {
                self.dra = Some(DraState::new(&self.population));
            }
            self.initialised = true;
            self.new_generation_order();
        }
        Ok(())
    }

    fn population(&self) -> &[Individual<P::Decision>] {
        &self.population
    }

    fn external_archive(&self) -> Option<&[Individual<P::Decision>]> {
        self.archive.as_ref().map(ParetoArchive::members)
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

    fn validate(&self, problem: &P) -> Result<(), crate::optim::StateError> {
        self.validate_state(problem)
    }
}

#[cfg(test)]
mod tests;
