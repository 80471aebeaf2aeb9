//! MOEA/D-DE (Zhang & Li 2007; Li & Zhang 2009) with pagmo's semantics and defaults, plus
//! Lampinen's constraint rules (thesis 4.1.3).
//!
//! Per generation the subproblems are visited in a fresh random order. For subproblem `n`:
//! with probability `realb` (or always, without `preserve_diversity`) the parents come from
//! its neighbourhood, else from the whole population; two distinct parents `a, b` are drawn;
//! the child is `x_n + F (x_a - x_b)` per variable with probability `CR` (bound repair as in
//! pagmo), then polynomial mutation (probability `1/dim` unless set, index `eta_m`). The child
//! updates the ideal point and then replaces, in random order, members of the same pool whose
//! subproblem it solves better, at most `limit` of them when `preserve_diversity` is on.
//!
//! "Better" follows Lampinen (2002): a feasible child beats an infeasible member; of two
//! infeasible the child wins with a violation lower or equal; of two feasible the child wins
//! with a strictly lower decomposed value. The ideal point is the minimum over feasible
//! individuals only (for unconstrained problems that is pagmo's ideal point).
//!
//! Ask/tell: `batch_size` offspring are made from the same population state and applied in
//! index order when all are told. `batch_size = 1` (default) is pagmo's steady-state loop;
//! larger batches allow parallel evaluation at the price of slightly staler parents.

use serde::{Deserialize, Serialize};

use crate::optim::algorithm::{Algorithm, Batch, check_objectives};
use crate::optim::error::{ConfigError, OptimError};
use crate::optim::operators::{de_step, polynomial_mutation, random_point};
use crate::optim::population::Individual;
use crate::optim::problem::{Evaluation, RealProblem};
use crate::optim::rng::OptimRng;
use crate::optim::weights::{Decomposition, WeightGeneration, decompose, generate, neighbourhoods};

use super::check_range;

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
        }
    }
}

impl MoeadConfig {
    pub(crate) fn check(&self, dim: usize, objectives: usize) -> Result<(), ConfigError> {
        if objectives < 2 {
            return Err(ConfigError::TooFewObjectives {
                algorithm: NAME,
                objectives,
            });
        }
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
        let _ = dim;
        Ok(())
    }
}

/// Which pool the parents of one child came from.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
struct ChildOrigin {
    subproblem: usize,
    whole_population: bool,
}

/// MOEA/D state (serialisable: checkpoint and resume give the bit-identical run).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Moead {
    config: MoeadConfig,
    rng: OptimRng,
    population: Vec<Individual<Vec<f64>>>,
    weights: Vec<Vec<f64>>,
    neighbourhoods: Vec<Vec<usize>>,
    ideal: Vec<f64>,
    /// Subproblem order of the current generation and the next position in it.
    order: Vec<usize>,
    cursor: usize,
    batch: Batch<Vec<f64>>,
    origins: Vec<ChildOrigin>,
    initialised: bool,
    generation: u64,
    evaluations: u64,
    #[serde(skip)]
    scratch: Vec<usize>,
}

impl Moead {
    /// A new run with `config`, seeded with `seed`.
    #[must_use]
    pub fn new(config: MoeadConfig, seed: u64) -> Self {
        Self {
            config,
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
            scratch: Vec::new(),
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

    fn start<P: RealProblem>(&mut self, problem: &P) -> Result<(), OptimError> {
        check_objectives(problem)?;
        let m = problem.objectives();
        self.config.check(problem.bounds().dim(), m)?;
        let n = self.config.population;
        self.weights = generate(n, m, self.config.weights, &mut self.rng)?;
        self.neighbourhoods = neighbourhoods(&self.weights, self.config.neighbours);
        self.ideal = vec![f64::MAX; m];
        let decisions = (0..n)
            .map(|_| random_point(problem.bounds(), &mut self.rng))
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

    fn make_offspring(&mut self, bounds: &crate::optim::problem::Bounds) {
        let np = self.config.population;
        let count = self.config.batch_size.min(np - self.cursor);
        let rate = self
            .config
            .mutation_probability
            .unwrap_or(1.0 / bounds.dim() as f64);
        let mut decisions = Vec::with_capacity(count);
        self.origins.clear();
        for k in 0..count {
            let n = self.order[self.cursor + k];
            let whole = self.config.preserve_diversity && self.rng.uniform() >= self.config.realb;
            let [a, b] = self.select_parents(n, whole);
            let mut child = Vec::with_capacity(bounds.dim());
            de_step(
                &self.population[n].decision,
                &self.population[a].decision,
                &self.population[b].decision,
                self.config.f,
                self.config.cr,
                bounds,
                &mut self.rng,
                &mut child,
            );
            polynomial_mutation(&mut child, bounds, rate, self.config.eta_m, &mut self.rng);
            decisions.push(child);
            self.origins.push(ChildOrigin {
                subproblem: n,
                whole_population: whole,
            });
        }
        self.batch.open(decisions);
    }

    fn update_ideal(ideal: &mut [f64], ind: &Individual<Vec<f64>>) {
        if ind.is_feasible() {
            for (z, &f) in ideal.iter_mut().zip(&ind.objectives) {
                if f < *z {
                    *z = f;
                }
            }
        }
    }

    /// Lampinen's selection: does `child` replace `member` on subproblem `weight`?
    fn child_wins(
        &self,
        child: &Individual<Vec<f64>>,
        member: &Individual<Vec<f64>>,
        weight: &[f64],
    ) -> bool {
        match (child.is_feasible(), member.is_feasible()) {
            (true, true) => {
                let kind = self.config.decomposition;
                decompose(kind, &child.objectives, weight, &self.ideal)
                    < decompose(kind, &member.objectives, weight, &self.ideal)
            }
            (true, false) => true,
            (false, true) => false,
            (false, false) => child.violation <= member.violation,
        }
    }

    fn apply(&mut self, child: &Individual<Vec<f64>>, origin: ChildOrigin) {
        Self::update_ideal(&mut self.ideal, child);
        let np = self.population.len();
        let size = if origin.whole_population {
            np
        } else {
            self.neighbourhoods[origin.subproblem].len()
        };
        let mut pool = std::mem::take(&mut self.scratch);
        pool.clear();
        pool.extend(0..size);
        self.rng.shuffle(&mut pool);
        let mut replaced = 0;
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
        self.scratch = pool;
    }

    fn new_generation_order(&mut self) {
        self.order = (0..self.config.population).collect();
        self.rng.shuffle(&mut self.order);
        self.cursor = 0;
    }
}

impl<P: RealProblem> Algorithm<P> for Moead {
    fn name(&self) -> &'static str {
        NAME
    }

    fn ask(&mut self, problem: &P) -> Result<&[Vec<f64>], OptimError> {
        if !self.batch.is_open() {
            if self.initialised {
                self.make_offspring(problem.bounds());
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
        let told = self.batch.take();
        if self.initialised {
            let origins = std::mem::take(&mut self.origins);
            for (child, origin) in told.iter().zip(&origins) {
                self.apply(child, *origin);
            }
            self.origins = origins;
            self.cursor += told.len();
            if self.cursor >= self.config.population {
                self.generation += 1;
                self.new_generation_order();
            }
        } else {
            for ind in &told {
                Self::update_ideal(&mut self.ideal, ind);
            }
            self.population = told;
            self.initialised = true;
            self.new_generation_order();
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
}
