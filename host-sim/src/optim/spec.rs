//! One algorithm specification: [`AlgorithmSpec`], which algorithm with which settings
//! (serde, tagged by `algorithm`: `moead`, `moead-sbx`, `nsga2`, `mhaco` on real vectors,
//! `scea`, `vl-mhaco` on structured chromosomes), checked against a problem's shape by
//! [`AlgorithmSpec::check`] and built by [`AlgorithmSpec::build`] into a [`BuiltAlgorithm`]:
//! a [`RealAlgorithm`] or a [`ChromosomeAlgorithm`], the enums over the running algorithms
//! that every front end drives (the CLI's test-problem runs, the re-entry design run, the
//! Python `Optimizer`). A chromosome algorithm runs on a variable-length problem, or on a
//! fixed-length one through [`crate::optim::chromosome::FixedLength`]. Each variant carries
//! only its own configuration (MOEA/D's SBX settings exist only in `moead-sbx`, NSGA-II has
//! no neighbourhood), so a combination the algorithms do not have cannot be built.

use serde::{Deserialize, Serialize};

use super::algorithm::Algorithm;
use super::algorithms::{
    ConstraintHandling, Mhaco, MhacoConfig, Moead, MoeadConfig, MoeadSbx, NewGenes, Nsga2,
    Nsga2Config, ResourceAllocation, SbxVariation, Scea, SceaConfig, VlMhaco,
};
use super::chromosome::{Chromosome, StructuredProblem};
use super::error::{ConfigError, OptimError, StateError};
use super::population::Individual;
use super::problem::{Evaluation, RealProblem};
use super::weights::WeightGeneration;

/// An algorithm and its settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "algorithm", rename_all = "kebab-case")]
pub enum AlgorithmSpec {
    /// MOEA/D with pagmo's DE variation.
    Moead(MoeadConfig),
    /// MOEA/D with Zhang & Li's (2007) SBX variation.
    MoeadSbx {
        /// MOEA/D's settings (its DE fields `cr` and `f` unused).
        moead: MoeadConfig,
        /// The SBX variation's settings.
        sbx: SbxVariation,
    },
    /// NSGA-II (pagmo's).
    Nsga2(Nsga2Config),
    /// MHACO (pagmo's `maco`).
    Mhaco(MhacoConfig),
    /// SCEA, MOEA/D over structured chromosomes (thesis sec. 4.1.5).
    Scea(SceaConfig),
    /// The variable-length MHACO over structured chromosomes (MHACO's settings).
    VlMhaco(MhacoConfig),
}

/// The names [`AlgorithmSpec::defaults`] knows, as in the `algorithm` tag.
pub const SPEC_NAMES: [&str; 6] = ["moead", "moead-sbx", "nsga2", "mhaco", "scea", "vl-mhaco"];

/// What an algorithm built from an [`AlgorithmSpec`] is.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
pub enum BuiltAlgorithm {
    /// On real vectors ([`crate::optim::RealProblem`]).
    Real(RealAlgorithm),
    /// On structured chromosomes ([`StructuredProblem`]).
    Chromosome(ChromosomeAlgorithm),
}

impl AlgorithmSpec {
    /// The algorithm `name` (one of [`SPEC_NAMES`]) with its default settings (pagmo's).
    #[must_use]
    pub fn defaults(name: &str) -> Option<Self> {
        Some(match name {
            "moead" => Self::Moead(MoeadConfig::default()),
            "moead-sbx" => Self::MoeadSbx {
                moead: MoeadConfig::default(),
                sbx: SbxVariation::default(),
            },
            "nsga2" => Self::Nsga2(Nsga2Config::default()),
            "mhaco" => Self::Mhaco(MhacoConfig::default()),
            "scea" => Self::Scea(SceaConfig::default()),
            "vl-mhaco" => Self::VlMhaco(MhacoConfig::default()),
            _ => return None,
        })
    }

    /// The `algorithm` tag.
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Self::Moead(_) => "moead",
            Self::MoeadSbx { .. } => "moead-sbx",
            Self::Nsga2(_) => "nsga2",
            Self::Mhaco(_) => "mhaco",
            Self::Scea(_) => "scea",
            Self::VlMhaco(_) => "vl-mhaco",
        }
    }

    /// Whether it runs on structured chromosomes ([`BuiltAlgorithm::Chromosome`]).
    #[must_use]
    pub fn is_chromosome(&self) -> bool {
        matches!(self, Self::Scea(_) | Self::VlMhaco(_))
    }

    /// Population size.
    #[must_use]
    pub fn population(&self) -> usize {
        match self {
            Self::Moead(c) | Self::MoeadSbx { moead: c, .. } => c.population,
            Self::Nsga2(c) => c.population,
            Self::Mhaco(c) | Self::VlMhaco(c) => c.population,
            Self::Scea(c) => c.moead.population,
        }
    }

    /// Check the settings for a problem of `objectives` objectives and `constraints`
    /// constraints (what the algorithm's first `ask` would refuse).
    ///
    /// # Errors
    /// [`ConfigError`] naming the algorithm, the field, its value and the range.
    pub fn check(&self, objectives: usize, constraints: usize) -> Result<(), ConfigError> {
        match self {
            Self::Moead(c) => c.check(objectives),
            Self::MoeadSbx { moead, sbx } => {
                moead.check(objectives)?;
                sbx.check_ranges()
            }
            Self::Nsga2(c) => c.check(),
            Self::Mhaco(c) | Self::VlMhaco(c) => c.check(objectives, constraints),
            Self::Scea(c) => c.check(objectives),
        }
    }

    /// A new run of this algorithm seeded with `seed`.
    #[must_use]
    pub fn build(&self, seed: u64) -> BuiltAlgorithm {
        use BuiltAlgorithm::{Chromosome as C, Real as R};
        match self {
            Self::Moead(c) => R(RealAlgorithm::Moead(Moead::new(c.clone(), seed))),
            Self::MoeadSbx { moead, sbx } => R(RealAlgorithm::MoeadSbx(MoeadSbx::sbx(
                moead.clone(),
                *sbx,
                seed,
            ))),
            Self::Nsga2(c) => R(RealAlgorithm::Nsga2(Nsga2::new(c.clone(), seed))),
            Self::Mhaco(c) => R(RealAlgorithm::Mhaco(Mhaco::new(c.clone(), seed))),
            Self::Scea(c) => C(ChromosomeAlgorithm::Scea(Scea::new(c.clone(), seed))),
            Self::VlMhaco(c) => C(ChromosomeAlgorithm::VlMhaco(VlMhaco::new(c.clone(), seed))),
        }
    }
}

/// Generations after the initial population of a run when none are given (`host-sim
/// optimize --generations`' default).
pub const DEFAULT_GENERATIONS: u64 = 250;

/// The algorithms by the names of `host-sim optimize`'s subcommands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OptionsAlgorithm {
    /// MOEA/D (its variation: [`RunOptions::moead_operator`]).
    Moead,
    /// NSGA-II.
    Nsga2,
    /// MHACO (on a variable-length problem the variable-length MHACO:
    /// [`RunOptions::variable_length_spec`]).
    Mhaco,
    /// SCEA (MOEA/D's fields and [`RunOptions::scea_genes`]).
    Scea,
}

impl OptionsAlgorithm {
    /// The name, as in files (`summary.json`'s `algorithm`).
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Moead => "moead",
            Self::Nsga2 => "nsga2",
            Self::Mhaco => "mhaco",
            Self::Scea => "scea",
        }
    }
}

/// MOEA/D's variation operator (`--moead-operator`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum MoeadOperator {
    /// pagmo's MOEA/D-DE (Li & Zhang 2009): DE step (CR 1, F 0.5), polynomial mutation.
    #[default]
    De,
    /// Zhang & Li's (2007) original MOEA/D, not in pagmo: SBX (index 20, probability 1) of
    /// the two parents, polynomial mutation (the default `SbxVariation`).
    Sbx,
}

/// MHACO's constraint handling (`--mhaco-constraints`; the variants' text is its help).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum MhacoConstraints {
    /// Feasible candidates first, then infeasible ones by violation (thesis sec. 10.2;
    /// `ConstraintHandling::FeasibilityFirst`).
    #[default]
    FeasibilityFirst,
    /// Constraints as extra objectives, the thesis' normalisation (sec. 9.3.2: unit scales,
    /// cap 2.0, penalty 0.5; `ConstraintHandling::thesis_objectives`).
    Objectives,
}

/// The algorithm settings of a real-vector run on a test problem as `host-sim optimize`
/// takes them: its flags' names (`--batch-size` is `batch_size`) and defaults, mapped onto
/// an [`AlgorithmSpec`] by [`RunOptions::spec`]. Every front end that offers those flags
/// (the CLI, `reentry-dask optimize`) goes through this one mapping. Serde: missing fields
/// take the defaults, unknown fields are refused.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RunOptions {
    /// The subcommand of `host-sim optimize` (`moead`, `nsga2`, `mhaco`, `scea`; SCEA takes
    /// MOEA/D's fields).
    pub algorithm: OptionsAlgorithm,
    /// `--moead-operator` (MOEA/D only).
    pub moead_operator: MoeadOperator,
    /// `--population`.
    pub population: usize,
    /// `--weights` (MOEA/D).
    pub weights: WeightGeneration,
    /// `--neighbours` (MOEA/D; default [`MoeadConfig::default_neighbours`]).
    pub neighbours: Option<usize>,
    /// `--mutation-probability` (MOEA/D; default 1/variables).
    pub mutation_probability: Option<f64>,
    /// `--batch-size` (MOEA/D).
    pub batch_size: usize,
    /// `--archive` (MOEA/D, NSGA-II).
    pub archive: Option<usize>,
    /// `--resource-allocation` (MOEA/D: MOEA/D-DRA's default [`ResourceAllocation`]).
    pub resource_allocation: bool,
    /// `--ker` (MHACO; default min(63, population)).
    pub ker: Option<usize>,
    /// `--n-gen-mark` (MHACO).
    pub n_gen_mark: u64,
    /// `--mhaco-constraints` (MHACO).
    pub mhaco_constraints: MhacoConstraints,
    /// `--scea-genes` (SCEA).
    pub scea_genes: NewGenes,
}

impl Default for RunOptions {
    fn default() -> Self {
        Self {
            algorithm: OptionsAlgorithm::Moead,
            moead_operator: MoeadOperator::De,
            population: 100,
            weights: WeightGeneration::Grid,
            neighbours: None,
            mutation_probability: None,
            batch_size: 1,
            archive: None,
            resource_allocation: false,
            ker: None,
            n_gen_mark: MhacoConfig::default().n_gen_mark,
            mhaco_constraints: MhacoConstraints::FeasibilityFirst,
            scea_genes: SceaConfig::default().new_genes,
        }
    }
}

impl RunOptions {
    /// The MOEA/D settings (also SCEA's neighbourhood and weights).
    #[must_use]
    pub fn moead_config(&self) -> MoeadConfig {
        MoeadConfig {
            population: self.population,
            weights: self.weights,
            neighbours: self
                .neighbours
                .unwrap_or_else(|| MoeadConfig::default_neighbours(self.population)),
            mutation_probability: self.mutation_probability,
            batch_size: self.batch_size,
            archive: self.archive,
            resource_allocation: self.resource_allocation.then(ResourceAllocation::default),
            ..MoeadConfig::default()
        }
    }

    /// The MHACO settings.
    #[must_use]
    pub fn mhaco_config(&self) -> MhacoConfig {
        MhacoConfig {
            population: self.population,
            ker: self
                .ker
                .unwrap_or_else(|| self.population.min(MhacoConfig::default().ker)),
            n_gen_mark: self.n_gen_mark,
            constraints: match self.mhaco_constraints {
                MhacoConstraints::FeasibilityFirst => ConstraintHandling::FeasibilityFirst,
                MhacoConstraints::Objectives => ConstraintHandling::thesis_objectives(),
            },
            ..MhacoConfig::default()
        }
    }

    /// The algorithm and its settings on a fixed-length problem (SCEA through
    /// [`crate::optim::chromosome::FixedLength`]).
    #[must_use]
    pub fn spec(&self) -> AlgorithmSpec {
        match self.algorithm {
            OptionsAlgorithm::Moead => match self.moead_operator {
                MoeadOperator::De => AlgorithmSpec::Moead(self.moead_config()),
                MoeadOperator::Sbx => AlgorithmSpec::MoeadSbx {
                    moead: self.moead_config(),
                    sbx: SbxVariation::default(),
                },
            },
            OptionsAlgorithm::Nsga2 => AlgorithmSpec::Nsga2(Nsga2Config {
                population: self.population,
                archive: self.archive,
                ..Nsga2Config::default()
            }),
            OptionsAlgorithm::Mhaco => AlgorithmSpec::Mhaco(self.mhaco_config()),
            OptionsAlgorithm::Scea => AlgorithmSpec::Scea(SceaConfig {
                moead: self.moead_config(),
                new_genes: self.scea_genes,
                ..SceaConfig::default()
            }),
        }
    }

    /// The algorithm and its settings on a variable-length problem: SCEA, or MHACO's
    /// settings as the variable-length MHACO; `None` for MOEA/D and NSGA-II (real vectors
    /// only).
    #[must_use]
    pub fn variable_length_spec(&self) -> Option<AlgorithmSpec> {
        match self.algorithm {
            OptionsAlgorithm::Scea => Some(self.spec()),
            OptionsAlgorithm::Mhaco => Some(AlgorithmSpec::VlMhaco(self.mhaco_config())),
            OptionsAlgorithm::Moead | OptionsAlgorithm::Nsga2 => None,
        }
    }

    /// Children made per generation on a problem of `objectives` objectives (the
    /// population; with MOEA/D-DRA the subproblems it works on).
    #[must_use]
    pub fn children_per_generation(&self, objectives: usize) -> usize {
        match (self.algorithm, self.resource_allocation) {
            (OptionsAlgorithm::Moead, true) => ResourceAllocation::default()
                .subproblems_per_generation(self.population, objectives),
            _ => self.population,
        }
    }

    /// The fewest whole generations whose evaluations, initial population included, reach
    /// `evaluations` (`--evaluations`).
    ///
    /// # Errors
    /// What to change: `evaluations` below the initial population, or MHACO or SCEA
    /// (whose generations are counted by `--generations` only).
    pub fn generations_for(&self, evaluations: u64, objectives: usize) -> Result<u64, String> {
        if matches!(
            self.algorithm,
            OptionsAlgorithm::Mhaco | OptionsAlgorithm::Scea
        ) {
            return Err(format!(
                "applies to the moead and nsga2 subcommands (given {}); use --generations",
                self.algorithm.as_str()
            ));
        }
        let per_generation = self.children_per_generation(objectives);
        let n = self.population as u64;
        if evaluations < n || per_generation == 0 {
            return Err(format!(
                "below the initial population of {n}; use at least {n}"
            ));
        }
        Ok((evaluations - n).div_ceil(per_generation as u64))
    }
}

/// A running real-vector algorithm: the state of any [`AlgorithmSpec`] (serde: the whole
/// state, as a checkpoint keeps it).
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, Serialize, Deserialize)]
pub enum RealAlgorithm {
    /// MOEA/D (DE).
    Moead(Moead),
    /// MOEA/D (SBX).
    MoeadSbx(MoeadSbx),
    /// NSGA-II.
    Nsga2(Nsga2),
    /// MHACO.
    Mhaco(Mhaco),
}

/// `$body` with `$a` bound to the algorithm inside `$algo`.
macro_rules! each {
    ($algo:expr, $a:ident => $body:expr) => {
        match $algo {
            RealAlgorithm::Moead($a) => $body,
            RealAlgorithm::MoeadSbx($a) => $body,
            RealAlgorithm::Nsga2($a) => $body,
            RealAlgorithm::Mhaco($a) => $body,
        }
    };
}

impl<P: RealProblem> Algorithm<P> for RealAlgorithm {
    fn name(&self) -> &'static str {
        match self {
            Self::MoeadSbx(_) => "moead-sbx",
            _ => each!(self, a => Algorithm::<P>::name(a)),
        }
    }

    fn ask(&mut self, problem: &P) -> Result<&[Vec<f64>], OptimError> {
        each!(self, a => a.ask(problem))
    }

    fn tell(
        &mut self,
        problem: &P,
        index: usize,
        evaluation: Evaluation,
    ) -> Result<(), OptimError> {
        each!(self, a => a.tell(problem, index, evaluation))
    }

    fn population(&self) -> &[Individual<Vec<f64>>] {
        each!(self, a => Algorithm::<P>::population(a))
    }

    fn external_archive(&self) -> Option<&[Individual<Vec<f64>>]> {
        each!(self, a => Algorithm::<P>::external_archive(a))
    }

    fn is_initialised(&self) -> bool {
        each!(self, a => Algorithm::<P>::is_initialised(a))
    }

    fn generation(&self) -> u64 {
        each!(self, a => Algorithm::<P>::generation(a))
    }

    fn evaluations(&self) -> u64 {
        each!(self, a => Algorithm::<P>::evaluations(a))
    }

    fn is_told(&self, index: usize) -> bool {
        each!(self, a => Algorithm::<P>::is_told(a, index))
    }

    fn is_finished(&self) -> bool {
        each!(self, a => Algorithm::<P>::is_finished(a))
    }

    fn validate(&self, problem: &P) -> Result<(), StateError> {
        each!(self, a => a.validate(problem))
    }
}

/// A running structured-chromosome algorithm: the state of an [`AlgorithmSpec`] `scea` or
/// `vl-mhaco` (serde: the whole state).
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, Serialize, Deserialize)]
pub enum ChromosomeAlgorithm {
    /// SCEA.
    Scea(Scea),
    /// The variable-length MHACO.
    VlMhaco(VlMhaco),
}

/// `$body` with `$a` bound to the algorithm inside `$algo`.
macro_rules! each_chromosome {
    ($algo:expr, $a:ident => $body:expr) => {
        match $algo {
            ChromosomeAlgorithm::Scea($a) => $body,
            ChromosomeAlgorithm::VlMhaco($a) => $body,
        }
    };
}

impl<P: StructuredProblem> Algorithm<P> for ChromosomeAlgorithm {
    fn name(&self) -> &'static str {
        match self {
            Self::Scea(_) => "scea",
            Self::VlMhaco(a) => Algorithm::<P>::name(a),
        }
    }

    fn ask(&mut self, problem: &P) -> Result<&[Chromosome], OptimError> {
        each_chromosome!(self, a => a.ask(problem))
    }

    fn tell(
        &mut self,
        problem: &P,
        index: usize,
        evaluation: Evaluation,
    ) -> Result<(), OptimError> {
        each_chromosome!(self, a => a.tell(problem, index, evaluation))
    }

    fn population(&self) -> &[Individual<Chromosome>] {
        each_chromosome!(self, a => Algorithm::<P>::population(a))
    }

    fn external_archive(&self) -> Option<&[Individual<Chromosome>]> {
        each_chromosome!(self, a => Algorithm::<P>::external_archive(a))
    }

    fn is_initialised(&self) -> bool {
        each_chromosome!(self, a => Algorithm::<P>::is_initialised(a))
    }

    fn generation(&self) -> u64 {
        each_chromosome!(self, a => Algorithm::<P>::generation(a))
    }

    fn evaluations(&self) -> u64 {
        each_chromosome!(self, a => Algorithm::<P>::evaluations(a))
    }

    fn is_told(&self, index: usize) -> bool {
        each_chromosome!(self, a => Algorithm::<P>::is_told(a, index))
    }

    fn is_finished(&self) -> bool {
        each_chromosome!(self, a => Algorithm::<P>::is_finished(a))
    }

    fn validate(&self, problem: &P) -> Result<(), StateError> {
        each_chromosome!(self, a => a.validate(problem))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optim::problems::TestProblem;
    use crate::optim::{NoObserver, Serial, evolve};

    /// Every name round-trips through its tag, a spec reads back from JSON as written, and
    /// the checks name the algorithm and the field.
    #[test]
    fn specs_are_tagged_checked_and_read_back() {
        for name in SPEC_NAMES {
            let s = AlgorithmSpec::defaults(name).unwrap();
            assert_eq!(s.name(), name);
            let json = serde_json::to_string(&s).unwrap();
            assert!(
                json.contains(&format!("\"algorithm\":\"{name}\"")),
                "{json}"
            );
            let back: AlgorithmSpec = serde_json::from_str(&json).unwrap();
            assert_eq!(back, s);
            assert!(s.check(2, 0).is_ok(), "{name}");
        }
        assert!(AlgorithmSpec::defaults("maco").is_none());
        let unknown: Result<AlgorithmSpec, _> =
            serde_json::from_str(r#"{"algorithm": "maco", "population": 20}"#);
        assert!(unknown.is_err());
        let e = AlgorithmSpec::Scea(SceaConfig {
            count_mutation: 1.5,
            ..SceaConfig::default()
        })
        .check(2, 0)
        .unwrap_err();
        assert!(
            e.to_string().contains("scea") && e.to_string().contains("count_mutation = 1.5"),
            "{e}"
        );
        let e = AlgorithmSpec::VlMhaco(MhacoConfig {
            ker: 0,
            ..MhacoConfig::default()
        })
        .check(2, 0)
        .unwrap_err();
        assert!(e.to_string().contains("ker"), "{e}");
        let e = AlgorithmSpec::Nsga2(Nsga2Config {
            population: 10,
            ..Nsga2Config::default()
        })
        .check(2, 0)
        .unwrap_err();
        assert!(e.to_string().contains("nsga2"), "{e}");
        let e = AlgorithmSpec::MoeadSbx {
            moead: MoeadConfig::default(),
            sbx: SbxVariation {
                eta_c: 0.5,
                ..SbxVariation::default()
            },
        }
        .check(2, 0)
        .unwrap_err();
        assert!(e.to_string().contains("eta_c"), "{e}");
        assert!(
            AlgorithmSpec::defaults("moead")
                .unwrap()
                .check(1, 0)
                .is_err()
        );
    }

    /// A built algorithm runs as the algorithm itself does, bit for bit.
    #[test]
    fn built_algorithm_runs_as_the_algorithm_itself() {
        let problem = TestProblem::by_name("zdt1", 2).unwrap().unwrap();
        let config = MoeadConfig {
            population: 20,
            neighbours: 5,
            ..MoeadConfig::default()
        };
        let spec = AlgorithmSpec::MoeadSbx {
            moead: config.clone(),
            sbx: SbxVariation::default(),
        };
        let BuiltAlgorithm::Real(mut built) = spec.build(7) else {
            panic!("moead-sbx builds a real-vector algorithm")
        };
        let mut direct = MoeadSbx::sbx(config.clone(), SbxVariation::default(), 7);
        evolve(&mut built, &problem, &Serial, 3, &mut NoObserver).unwrap();
        evolve(&mut direct, &problem, &Serial, 3, &mut NoObserver).unwrap();
        assert_eq!(
            Algorithm::<TestProblem>::population(&built),
            Algorithm::<TestProblem>::population(&direct)
        );
        assert_eq!(Algorithm::<TestProblem>::name(&built), "moead-sbx");
        let BuiltAlgorithm::Real(mut nsga2) = AlgorithmSpec::Nsga2(Nsga2Config {
            population: 24,
            ..Nsga2Config::default()
        })
        .build(3) else {
            panic!("nsga2 builds a real-vector algorithm")
        };
        evolve(&mut nsga2, &problem, &Serial, 2, &mut NoObserver).unwrap();
        assert_eq!(Algorithm::<TestProblem>::generation(&nsga2), 2);
    }

    /// SCEA and the variable-length MHACO built from their specs run as the algorithms
    /// themselves, bit for bit, on a fixed-length problem through `FixedLength` and on a
    /// variable-length one; `RunOptions` maps `mhaco` on a variable-length problem to it.
    #[test]
    fn chromosome_specs_run_as_the_algorithms_themselves() {
        use crate::optim::chromosome::FixedLength;
        use crate::optim::problems::Vlmop;
        let zdt1 = FixedLength::new(TestProblem::by_name("zdt1", 2).unwrap().unwrap());
        let vlmop1 = Vlmop::by_name("vlmop1").unwrap();
        let options = RunOptions {
            algorithm: OptionsAlgorithm::Scea,
            population: 20,
            scea_genes: NewGenes::Random,
            ..RunOptions::default()
        };
        let scea = options.spec();
        assert_eq!(options.variable_length_spec(), Some(scea.clone()));
        let AlgorithmSpec::Scea(config) = &scea else {
            panic!("{scea:?}")
        };
        assert_eq!(config.new_genes, NewGenes::Random);
        assert_eq!(config.moead, options.moead_config());
        let mhaco = RunOptions {
            algorithm: OptionsAlgorithm::Mhaco,
            ..options.clone()
        };
        let vl = mhaco.variable_length_spec().unwrap();
        assert_eq!(vl, AlgorithmSpec::VlMhaco(mhaco.mhaco_config()));
        let moead = RunOptions {
            algorithm: OptionsAlgorithm::Moead,
            ..options.clone()
        };
        assert_eq!(moead.variable_length_spec(), None);
        for spec in [scea, vl] {
            assert!(spec.is_chromosome());
            let BuiltAlgorithm::Chromosome(mut on_zdt1) = spec.build(5) else {
                panic!("{spec:?} builds a chromosome algorithm")
            };
            let mut on_vlmop1 = on_zdt1.clone();
            evolve(&mut on_zdt1, &zdt1, &Serial, 3, &mut NoObserver).unwrap();
            evolve(&mut on_vlmop1, &vlmop1, &Serial, 3, &mut NoObserver).unwrap();
            let population = |a: &ChromosomeAlgorithm| Algorithm::<Vlmop>::population(a).to_vec();
            match &spec {
                AlgorithmSpec::Scea(c) => {
                    let mut direct = Scea::new(c.clone(), 5);
                    evolve(&mut direct, &vlmop1, &Serial, 3, &mut NoObserver).unwrap();
                    assert_eq!(
                        population(&on_vlmop1),
                        Algorithm::<Vlmop>::population(&direct)
                    );
                    assert_eq!(Algorithm::<Vlmop>::name(&on_vlmop1), "scea");
                }
                AlgorithmSpec::VlMhaco(c) => {
                    let mut direct = VlMhaco::new(c.clone(), 5);
                    evolve(&mut direct, &vlmop1, &Serial, 3, &mut NoObserver).unwrap();
                    assert_eq!(
                        population(&on_vlmop1),
                        Algorithm::<Vlmop>::population(&direct)
                    );
                    assert_eq!(Algorithm::<Vlmop>::name(&on_vlmop1), "vl-mhaco");
                }
                _ => unreachable!(),
            }
            assert_eq!(
                Algorithm::<FixedLength<TestProblem>>::generation(&on_zdt1),
                3
            );
        }
        assert!(!AlgorithmSpec::defaults("mhaco").unwrap().is_chromosome());
    }
}
