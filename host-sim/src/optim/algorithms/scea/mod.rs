//! SCEA, the structured-chromosome evolutionary algorithm of the thesis (sec. 4.1.5,
//! Algorithm 1): MOEA/D (pagmo semantics, Lampinen's constraint rules; [`MoeadWith`]) over
//! variable-length chromosomes ([`Chromosome`]: fixed genes, a number of legs, a number of
//! nodes per leg, and per node an optional group of genes where the layout has one) whose
//! counts are either free decisions or dictated by the problem ([`StructuredProblem`]).
//!
//! The generation loop, weights, neighbourhoods, mating pools, ideal point, replacement
//! (Lampinen's rules), ask/tell and checkpoints are MOEA/D's; only the variation differs
//! ([`SceaVariation`], [`variation`]). Appended genes are random (the thesis) or taken from the
//! population (its recommendation, sec. 10.2), selectable by [`SceaConfig::new_genes`].

pub mod variation;

#[cfg(test)]
mod tests;

use serde::{Deserialize, Serialize};

pub use variation::NewGenes;

use crate::optim::chromosome::{Chromosome, StructuredProblem};
use crate::optim::error::ConfigError;
use crate::optim::rng::OptimRng;

use super::check_range;
use super::moead::{MoeadConfig, MoeadVariation, MoeadWith};
use variation::{Settings, child, random_chromosome};

/// SCEA: MOEA/D with the structured-chromosome variation.
pub type Scea = MoeadWith<Chromosome, SceaVariation>;

/// SCEA settings: MOEA/D's (pagmo defaults) plus the structured-chromosome ones.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SceaConfig {
    /// The MOEA/D settings (population, weights, decomposition, neighbours, CR, F, eta_m,
    /// realb, limit, preserve_diversity, mutation probability (default 1 / number of real
    /// genes of the child), batch size).
    pub moead: MoeadConfig,
    /// Source of the genes of appended nodes (default: the population).
    pub new_genes: NewGenes,
    /// Probability of a +-1 step of each free count gene, in [0, 1] (default 0.1).
    pub count_mutation: f64,
}

impl Default for SceaConfig {
    fn default() -> Self {
        Self {
            moead: MoeadConfig::default(),
            new_genes: NewGenes::Population,
            count_mutation: 0.1,
        }
    }
}

impl SceaConfig {
    /// Check the settings for a problem of `objectives` objectives (what SCEA's first `ask`
    /// would refuse).
    ///
    /// # Errors
    /// [`ConfigError`] naming the algorithm, the field, its value and the range.
    pub fn check(&self, objectives: usize) -> Result<(), ConfigError> {
        self.moead.check(objectives)?;
        check_count_mutation(self.count_mutation)
    }
}

/// `count_mutation` in [0, 1].
fn check_count_mutation(p: f64) -> Result<(), ConfigError> {
    check_range("scea", "count_mutation", p, 0.0, 1.0, "[0, 1]")
}

/// The structured-chromosome variation (thesis Algorithm 1; see [`variation`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SceaVariation {
    /// Source of appended genes.
    pub new_genes: NewGenes,
    /// Probability of a +-1 step of each free count gene.
    pub count_mutation: f64,
}

impl MoeadWith<Chromosome, SceaVariation> {
    /// A new SCEA run with `config`, seeded with `seed`.
    #[must_use]
    pub fn new(config: SceaConfig, seed: u64) -> Self {
        let variation = SceaVariation {
            new_genes: config.new_genes,
            count_mutation: config.count_mutation,
        };
        Self::with_variation(config.moead, variation, seed)
    }
}

impl<P: StructuredProblem> MoeadVariation<P> for SceaVariation {
    fn check(&self, _problem: &P, _config: &MoeadConfig) -> Result<(), ConfigError> {
        check_count_mutation(self.count_mutation)
    }

    fn random(&self, problem: &P, rng: &mut OptimRng) -> Chromosome {
        random_chromosome(problem, rng)
    }

    fn check_decision(
        &self,
        problem: &P,
        field: &str,
        c: &Chromosome,
    ) -> Result<(), crate::optim::StateError> {
        use crate::optim::restore::{bad, finite};
        finite(&format!("{field}.fixed"), &c.fixed)?;
        for (l, leg) in c.legs.iter().enumerate() {
            for (k, node) in leg.iter().enumerate() {
                finite(&format!("{field}.legs[{l}][{k}]"), node)?;
            }
        }
        let derived = problem.derived_nodes(&c.fixed);
        problem
            .layout()
            .check(c, derived.as_deref())
            .map_err(|e| bad(field, "chromosome", e.to_string()))
    }

    fn child(
        &self,
        problem: &P,
        config: &MoeadConfig,
        x: &Chromosome,
        a: &Chromosome,
        b: &Chromosome,
        _reuse: Option<Chromosome>,
        rng: &mut OptimRng,
    ) -> Chromosome {
        let settings = Settings {
            cr: config.cr,
            f: config.f,
            eta_m: config.eta_m,
            mutation_probability: config.mutation_probability,
            count_mutation: self.count_mutation,
            new_genes: self.new_genes,
        };
        child(problem, x, a, b, &settings, rng)
    }
}
