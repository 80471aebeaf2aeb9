//! Opt-in variation of the original MOEA/D (Zhang & Li, "MOEA/D: a multiobjective
//! evolutionary algorithm based on decomposition", IEEE TEC 11(6), 2007, sec. V-A, its
//! settings for the ZDT problems): simulated binary crossover of the two mating parents
//! (distribution index 20, probability 1; the first child is kept) then polynomial mutation
//! (index `eta_m`, probability 1/dim: MOEA/D's own settings, whose defaults are the paper's).
//! Not pagmo, whose `moead` is MOEA/D-DE (Li & Zhang 2009) only.

use serde::{Deserialize, Serialize};

use crate::optim::error::ConfigError;
use crate::optim::operators::{polynomial_mutation, random_point, sbx_child};
use crate::optim::problem::RealProblem;
use crate::optim::rng::OptimRng;

use super::{MoeadConfig, MoeadVariation, MoeadWith, NAME, check_range};

/// Zhang & Li's (2007) MOEA/D variation: SBX of the two parents, then polynomial mutation.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SbxVariation {
    /// SBX distribution index, in [1, 100] (paper: 20).
    pub eta_c: f64,
    /// Probability that the parents are crossed, in [0, 1] (paper: 1).
    pub crossover_probability: f64,
}

impl Default for SbxVariation {
    fn default() -> Self {
        Self {
            eta_c: 20.0,
            crossover_probability: 1.0,
        }
    }
}

/// MOEA/D on real vectors with Zhang & Li's (2007) SBX variation.
pub type MoeadSbx = MoeadWith<Vec<f64>, SbxVariation>;

impl SbxVariation {
    /// `eta_c` in \[1, 100\], `crossover_probability` in \[0, 1\].
    pub(crate) fn check_ranges(&self) -> Result<(), ConfigError> {
        check_range(NAME, "eta_c", self.eta_c, 1.0, 100.0, "[1, 100]")?;
        check_range(
            NAME,
            "crossover_probability",
            self.crossover_probability,
            0.0,
            1.0,
            "[0, 1]",
        )
    }
}

impl MoeadSbx {
    /// A new run with `config` and the SBX variation of Zhang & Li (2007), seeded with
    /// `seed`.
    #[must_use]
    pub fn sbx(config: MoeadConfig, variation: SbxVariation, seed: u64) -> Self {
        Self::with_variation(config, variation, seed)
    }
}

impl<P: RealProblem> MoeadVariation<P> for SbxVariation {
    fn check_decision(
        &self,
        problem: &P,
        field: &str,
        decision: &Vec<f64>,
    ) -> Result<(), crate::optim::StateError> {
        crate::optim::restore::real_decision(field, decision, problem.bounds())
    }

    fn check(&self, _problem: &P, _config: &MoeadConfig) -> Result<(), ConfigError> {
        self.check_ranges()
    }

    fn random(&self, problem: &P, rng: &mut OptimRng) -> Vec<f64> {
        random_point(problem.bounds(), rng)
    }

    fn child(
        &self,
        problem: &P,
        config: &MoeadConfig,
        _x: &Vec<f64>,
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
        sbx_child(
            a,
            b,
            bounds,
            self.crossover_probability,
            self.eta_c,
            rng,
            &mut child,
        );
        polynomial_mutation(&mut child, bounds, rate, config.eta_m, rng);
        child
    }
}
