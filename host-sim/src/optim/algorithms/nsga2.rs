//! NSGA-II (Deb et al. 2002) with Deb's constrained domination, pagmo's loop and defaults.
//!
//! Per generation: non-dominated ranks (constrained: feasible fronts first, then infeasible by
//! violation) and crowding distances of the parents; two shuffled copies of the population
//! feed binary tournaments (lower rank, then larger crowding, then a coin) in groups of four,
//! each pair of winners gives two children by SBX (probability `cr`, index `eta_c`) and
//! polynomial mutation (per-variable probability `m`, index `eta_m`). Survival keeps the best
//! `population` of parents + children by front, the last front cut by crowding distance.
//!
//! Opt-in (`archive: Some(capacity)`, not pagmo): every evaluated individual is also offered,
//! in batch order, to an external [`ParetoArchive`], which is then the run's result front.

use serde::{Deserialize, Serialize};

use crate::optim::algorithm::{Algorithm, Batch, check_objectives};
use crate::optim::archive::{ParetoArchive, check_capacity};
use crate::optim::error::{ConfigError, OptimError};
use crate::optim::operators::{polynomial_mutation, random_point, sbx};
use crate::optim::pareto::{constrained_sort_fronts, crowding_distance, rank_crowding_cmp};
use crate::optim::population::Individual;
use crate::optim::problem::{Evaluation, RealProblem};
use crate::optim::rng::OptimRng;

use super::check_range;

const NAME: &str = "nsga2";

/// NSGA-II settings (defaults are pagmo's).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Nsga2Config {
    /// Population size: a multiple of 4, at least 8 (default 100).
    pub population: usize,
    /// SBX crossover probability in [0, 1] (default 0.95).
    pub cr: f64,
    /// SBX distribution index in [1, 100] (default 10).
    pub eta_c: f64,
    /// Per-variable mutation probability in [0, 1] (default 0.01).
    pub m: f64,
    /// Polynomial-mutation distribution index in [1, 100] (default 50).
    pub eta_m: f64,
    /// Capacity of an external archive of the feasible non-dominated solutions found during
    /// the run ([`ParetoArchive`], hypervolume truncation); it is then the run's result
    /// front. `None` (default): pagmo's semantics, the result is the final population.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub archive: Option<usize>,
}

impl Default for Nsga2Config {
    fn default() -> Self {
        Self {
            population: 100,
            cr: 0.95,
            eta_c: 10.0,
            m: 0.01,
            eta_m: 50.0,
            archive: None,
        }
    }
}

impl Nsga2Config {
    pub(crate) fn check(&self) -> Result<(), ConfigError> {
        let n = self.population;
        super::check_size(NAME, "population", n)?;
        if n < 8 {
            return Err(ConfigError::PopulationTooSmall {
                algorithm: NAME,
                population: n,
                minimum: 8,
            });
        }
        if !n.is_multiple_of(4) {
            return Err(ConfigError::PopulationNotMultiple {
                algorithm: NAME,
                population: n,
                multiple: 4,
                below: n / 4 * 4,
                above: n / 4 * 4 + 4,
            });
        }
        check_range(NAME, "cr", self.cr, 0.0, 1.0, "[0, 1]")?;
        check_range(NAME, "eta_c", self.eta_c, 1.0, 100.0, "[1, 100]")?;
        check_range(NAME, "m", self.m, 0.0, 1.0, "[0, 1]")?;
        check_range(NAME, "eta_m", self.eta_m, 1.0, 100.0, "[1, 100]")?;
        if let Some(capacity) = self.archive {
            check_capacity(NAME, capacity)?;
        }
        Ok(())
    }
}

/// NSGA-II state (serialisable: checkpoint and resume give the bit-identical run).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Nsga2 {
    config: Nsga2Config,
    rng: OptimRng,
    population: Vec<Individual<Vec<f64>>>,
    batch: Batch<Vec<f64>>,
    initialised: bool,
    generation: u64,
    evaluations: u64,
    /// The external archive (`config.archive`), every evaluated individual offered in batch
    /// order.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    archive: Option<ParetoArchive<Vec<f64>>>,
}

impl Nsga2 {
    /// A new run with `config`, seeded with `seed`.
    #[must_use]
    pub fn new(config: Nsga2Config, seed: u64) -> Self {
        Self {
            config,
            rng: OptimRng::new(seed),
            population: Vec::new(),
            batch: Batch::default(),
            initialised: false,
            generation: 0,
            evaluations: 0,
            archive: None,
        }
    }

    /// The current population (parents).
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

    /// The settings.
    #[must_use]
    pub fn config(&self) -> &Nsga2Config {
        &self.config
    }

    /// The external archive, when `config.archive` is set (created by the first ask).
    #[must_use]
    pub fn archive(&self) -> Option<&ParetoArchive<Vec<f64>>> {
        self.archive.as_ref()
    }

    /// Rank (front number) and crowding distance of every member of `pop`.
    fn rank_and_crowding(pop: &[Individual<Vec<f64>>]) -> (Vec<usize>, Vec<f64>) {
        let objs: Vec<&[f64]> = pop.iter().map(|i| i.objectives.as_slice()).collect();
        let viol: Vec<f64> = pop.iter().map(|i| i.violation).collect();
        let fronts = constrained_sort_fronts(&objs, &viol);
        let mut rank = vec![0; pop.len()];
        let mut crowd = vec![0.0; pop.len()];
        for (r, front) in fronts.iter().enumerate() {
            let d = crowding_distance(&objs, front);
            for (&i, di) in front.iter().zip(d) {
                rank[i] = r;
                crowd[i] = di;
            }
        }
        (rank, crowd)
    }

    fn tournament(&mut self, a: usize, b: usize, rank: &[usize], crowd: &[f64]) -> usize {
        if rank[a] != rank[b] {
            return if rank[a] < rank[b] { a } else { b };
        }
        if crowd[a] != crowd[b] {
            return if crowd[a] > crowd[b] { a } else { b };
        }
        if self.rng.uniform() < 0.5 { a } else { b }
    }

    fn make_offspring(&mut self, bounds: &crate::optim::problem::Bounds) {
        let n = self.population.len();
        let (rank, crowd) = Self::rank_and_crowding(&self.population);
        let mut s1: Vec<usize> = (0..n).collect();
        let mut s2: Vec<usize> = (0..n).collect();
        self.rng.shuffle(&mut s1);
        self.rng.shuffle(&mut s2);
        let mut children = Vec::with_capacity(n);
        for i in (0..n).step_by(4) {
            for s in [&s1, &s2] {
                let p1 = self.tournament(s[i], s[i + 1], &rank, &crowd);
                let p2 = self.tournament(s[i + 2], s[i + 3], &rank, &crowd);
                let (mut c1, mut c2) = sbx(
                    &self.population[p1].decision,
                    &self.population[p2].decision,
                    bounds,
                    self.config.cr,
                    self.config.eta_c,
                    &mut self.rng,
                );
                polynomial_mutation(
                    &mut c1,
                    bounds,
                    self.config.m,
                    self.config.eta_m,
                    &mut self.rng,
                );
                polynomial_mutation(
                    &mut c2,
                    bounds,
                    self.config.m,
                    self.config.eta_m,
                    &mut self.rng,
                );
                children.push(c1);
                children.push(c2);
            }
        }
        self.batch.open(children);
    }

    /// Keep the best `n` of parents + children: whole fronts in order, the front that
    /// overflows cut by decreasing crowding distance (ties by index).
    fn survive(&mut self, children: Vec<Individual<Vec<f64>>>) {
        let n = self.config.population;
        let mut all = std::mem::take(&mut self.population);
        all.extend(children);
        let mut keep = vec![false; all.len()];
        {
            let objs: Vec<&[f64]> = all.iter().map(|i| i.objectives.as_slice()).collect();
            let viol: Vec<f64> = all.iter().map(|i| i.violation).collect();
            let mut left = n;
            for front in constrained_sort_fronts(&objs, &viol) {
                if front.len() <= left {
                    for &i in &front {
                        keep[i] = true;
                    }
                    left -= front.len();
                } else {
                    let d = crowding_distance(&objs, &front);
                    let mut order: Vec<usize> = (0..front.len()).collect();
                    order.sort_unstable_by(|&a, &b| {
                        rank_crowding_cmp((0, d[a], front[a]), (0, d[b], front[b]))
                    });
                    for &k in order.iter().take(left) {
                        keep[front[k]] = true;
                    }
                    left = 0;
                }
                if left == 0 {
                    break;
                }
            }
        }
        self.population = all
            .into_iter()
            .zip(keep)
            .filter_map(|(ind, k)| k.then_some(ind))
            .collect();
    }
}

impl<P: RealProblem> Algorithm<P> for Nsga2 {
    fn name(&self) -> &'static str {
        NAME
    }

    fn ask(&mut self, problem: &P) -> Result<&[Vec<f64>], OptimError> {
        if !self.batch.is_open() {
            if self.initialised {
                self.make_offspring(problem.bounds());
            } else {
                check_objectives(problem)?;
                self.config.check()?;
                self.archive = self.config.archive.map(ParetoArchive::new).transpose()?;
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
        if let Some(archive) = &mut self.archive {
            for ind in &told {
                archive.offer(ind);
            }
        }
        if self.initialised {
            self.survive(told);
            self.generation += 1;
        } else {
            self.population = told;
            self.initialised = true;
        }
        Ok(())
    }

    fn population(&self) -> &[Individual<Vec<f64>>] {
        &self.population
    }

    fn external_archive(&self) -> Option<&[Individual<Vec<f64>>]> {
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
        use crate::optim::restore::{bad, count, individuals, real_decision};
        let (m, c) = (problem.objectives(), problem.constraints());
        self.config
            .check()
            .map_err(|e| bad("config", "(restored)", e.to_string()))?;
        let n = self.config.population;
        let dec = |f: &str, d: &Vec<f64>| real_decision(f, d, problem.bounds());
        self.batch.validate("batch", m, c, &dec)?;
        if self.batch.is_open() {
            count("batch.decisions.len()", self.batch.decisions().len(), n)?;
        }
        match (&self.archive, self.config.archive) {
            (Some(a), cap) => a.validate("archive", cap, m, c, &dec)?,
            (None, Some(_)) if self.initialised || self.batch.is_open() => {
                return Err(bad("archive", "absent", "the configuration has an archive"));
            }
            _ => {}
        }
        if self.initialised {
            count("population.len()", self.population.len(), n)?;
            individuals("population", &self.population, m, c, &dec)?;
        } else {
            count("population.len()", self.population.len(), 0)?;
            count("generation", self.generation as usize, 0)?;
        }
        Ok(())
    }
}
