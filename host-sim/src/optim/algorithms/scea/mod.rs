//! SCEA, the structured-chromosome evolutionary algorithm of the thesis (sec. 4.1.5,
//! Algorithm 1): MOEA/D (pagmo semantics, Lampinen's constraint rules; see
//! [`super::moead`]) over variable-length chromosomes ([`Chromosome`]: fixed genes, a number of
//! legs, a number of nodes per leg) whose counts are either free decisions or dictated by the
//! problem ([`StructuredProblem`]).
//!
//! The generation loop, weights, neighbourhoods, mating pools, ideal point and replacement
//! (at most `limit` members, Lampinen's rules: feasible beats infeasible, two infeasible by
//! violation (lower or equal wins), two feasible by the decomposed value) are MOEA/D's; only
//! the variation differs ([`variation`]). Appended genes are random (the thesis) or taken from
//! the population's history (its recommendation), selectable by [`SceaConfig::new_genes`].

pub mod variation;

#[cfg(test)]
mod tests;

use serde::{Deserialize, Serialize};

pub use variation::NewGenes;

use crate::optim::algorithm::{Algorithm, Batch, check_objectives};
use crate::optim::chromosome::{Chromosome, StructuredProblem};
use crate::optim::error::OptimError;
use crate::optim::population::Individual;
use crate::optim::problem::Evaluation;
use crate::optim::rng::OptimRng;
use crate::optim::weights::{decompose, generate, neighbourhoods};

use super::check_range;
use super::moead::MoeadConfig;
use variation::{NodeMemory, Settings, child, random_chromosome, remember};

const NAME: &str = "scea";

/// SCEA settings: MOEA/D's (pagmo defaults) plus the structured-chromosome ones.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SceaConfig {
    /// The MOEA/D settings (population, weights, decomposition, neighbours, CR, F, eta_m,
    /// realb, limit, preserve_diversity, mutation probability (default 1 / number of real
    /// genes of the child), batch size).
    pub moead: MoeadConfig,
    /// Source of the genes of appended nodes (default: the population's history).
    pub new_genes: NewGenes,
    /// Probability of a +-1 step of each count gene (default 0.1).
    pub count_mutation: f64,
}

impl Default for SceaConfig {
    fn default() -> Self {
        Self {
            moead: MoeadConfig::default(),
            new_genes: NewGenes::History,
            count_mutation: 0.1,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
struct ChildOrigin {
    subproblem: usize,
    whole_population: bool,
}

/// SCEA state (serialisable: checkpoint and resume give the bit-identical run).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Scea {
    config: SceaConfig,
    rng: OptimRng,
    population: Vec<Individual<Chromosome>>,
    weights: Vec<Vec<f64>>,
    neighbourhoods: Vec<Vec<usize>>,
    ideal: Vec<f64>,
    memory: NodeMemory,
    order: Vec<usize>,
    cursor: usize,
    batch: Batch<Chromosome>,
    origins: Vec<ChildOrigin>,
    initialised: bool,
    generation: u64,
    evaluations: u64,
}

/// Lampinen's selection: does `child` replace `member` on a subproblem with decomposed values
/// `child_value` and `member_value`?
fn lampinen_wins<D>(
    child: &Individual<D>,
    member: &Individual<D>,
    child_value: impl FnOnce() -> f64,
    member_value: impl FnOnce() -> f64,
) -> bool {
    match (child.is_feasible(), member.is_feasible()) {
        (true, true) => child_value() < member_value(),
        (true, false) => true,
        (false, true) => false,
        (false, false) => child.violation <= member.violation,
    }
}

impl Scea {
    /// A new run with `config`, seeded with `seed`.
    #[must_use]
    pub fn new(config: SceaConfig, seed: u64) -> Self {
        Self {
            config,
            rng: OptimRng::new(seed),
            population: Vec::new(),
            weights: Vec::new(),
            neighbourhoods: Vec::new(),
            ideal: Vec::new(),
            memory: Vec::new(),
            order: Vec::new(),
            cursor: 0,
            batch: Batch::default(),
            origins: Vec::new(),
            initialised: false,
            generation: 0,
            evaluations: 0,
        }
    }

    /// The settings.
    #[must_use]
    pub fn config(&self) -> &SceaConfig {
        &self.config
    }

    /// The current population.
    #[must_use]
    pub fn population(&self) -> &[Individual<Chromosome>] {
        &self.population
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

    /// The initial population has been evaluated.
    #[must_use]
    pub fn is_initialised(&self) -> bool {
        self.initialised
    }

    fn settings(&self) -> Settings {
        let m = &self.config.moead;
        Settings {
            cr: m.cr,
            f: m.f,
            eta_m: m.eta_m,
            mutation_probability: m.mutation_probability,
            count_mutation: self.config.count_mutation,
            new_genes: self.config.new_genes,
        }
    }

    fn start<P: StructuredProblem>(&mut self, problem: &P) -> Result<(), OptimError> {
        check_objectives(problem)?;
        let m = problem.objectives();
        self.config.moead.check(0, m)?;
        check_range(
            NAME,
            "count_mutation",
            self.config.count_mutation,
            0.0,
            1.0,
            "[0, 1]",
        )?;
        let n = self.config.moead.population;
        self.weights = generate(n, m, self.config.moead.weights, &mut self.rng)?;
        self.neighbourhoods = neighbourhoods(&self.weights, self.config.moead.neighbours);
        self.ideal = vec![f64::MAX; m];
        let decisions = (0..n)
            .map(|_| random_chromosome(problem, &mut self.rng))
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

    fn make_offspring<P: StructuredProblem>(&mut self, problem: &P) {
        let np = self.config.moead.population;
        let count = self.config.moead.batch_size.min(np - self.cursor);
        let settings = self.settings();
        let mut decisions = Vec::with_capacity(count);
        self.origins.clear();
        for k in 0..count {
            let n = self.order[self.cursor + k];
            let whole = self.config.moead.preserve_diversity
                && self.rng.uniform() >= self.config.moead.realb;
            let [a, b] = self.select_parents(n, whole);
            let c = child(
                problem,
                &self.population[n].decision,
                &self.population[a].decision,
                &self.population[b].decision,
                &self.population,
                &self.memory,
                &settings,
                &mut self.rng,
            );
            decisions.push(c);
            self.origins.push(ChildOrigin {
                subproblem: n,
                whole_population: whole,
            });
        }
        self.batch.open(decisions);
    }

    fn update_ideal(&mut self, ind: &Individual<Chromosome>) {
        if ind.is_feasible() {
            for (z, &f) in self.ideal.iter_mut().zip(&ind.objectives) {
                *z = z.min(f);
            }
        }
    }

    fn apply(&mut self, child: &Individual<Chromosome>, origin: ChildOrigin) {
        self.update_ideal(child);
        let size = if origin.whole_population {
            self.population.len()
        } else {
            self.neighbourhoods[origin.subproblem].len()
        };
        let mut pool: Vec<usize> = (0..size).collect();
        self.rng.shuffle(&mut pool);
        let kind = self.config.moead.decomposition;
        let mut replaced = 0;
        for k in pool {
            let pick = if origin.whole_population {
                k
            } else {
                self.neighbourhoods[origin.subproblem][k]
            };
            let (w, z) = (&self.weights[pick], &self.ideal);
            let member = &self.population[pick];
            if lampinen_wins(
                child,
                member,
                || decompose(kind, &child.objectives, w, z),
                || decompose(kind, &member.objectives, w, z),
            ) {
                self.population[pick].clone_from(child);
                replaced += 1;
            }
            if replaced >= self.config.moead.limit && self.config.moead.preserve_diversity {
                break;
            }
        }
        if replaced > 0 {
            remember(&mut self.memory, &child.decision);
        }
    }

    fn new_generation_order(&mut self) {
        self.order = (0..self.config.moead.population).collect();
        self.rng.shuffle(&mut self.order);
        self.cursor = 0;
    }
}

impl<P: StructuredProblem> Algorithm<P> for Scea {
    fn name(&self) -> &'static str {
        NAME
    }

    fn ask(&mut self, problem: &P) -> Result<&[Chromosome], OptimError> {
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
        let told = self.batch.take();
        if self.initialised {
            let origins = std::mem::take(&mut self.origins);
            for (c, origin) in told.iter().zip(&origins) {
                self.apply(c, *origin);
            }
            self.origins = origins;
            self.cursor += told.len();
            if self.cursor >= self.config.moead.population {
                self.generation += 1;
                self.new_generation_order();
            }
        } else {
            for ind in &told {
                self.update_ideal(ind);
                remember(&mut self.memory, &ind.decision);
            }
            self.population = told;
            self.initialised = true;
            self.new_generation_order();
        }
        Ok(())
    }

    fn population(&self) -> &[Individual<Chromosome>] {
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
