//! What the `host-sim optimize` runs share, below all of them: the arguments and the errors,
//! and the flags' mapping onto the library's [`RunOptions`] (the summary and the run
//! directory are the library's: [`crate::optim::run::run_report`],
//! [`crate::report::write_optimize_run`]). The test-problem run ([`super::optimize_cmd`]),
//! the re-entry run ([`super::optimize_reentry`]) and SCEA ([`super::optimize_structured`]) import this
//! module and not each other's arguments, so the four files form no import cycle.

use std::path::PathBuf;

use clap::ValueEnum;

use super::reference_arg::parse_reference;
use crate::optim::hypervolume::HypervolumeError;
use crate::optim::problems::{NAMES, TestProblemError};
use crate::optim::spec::{MhacoConstraints, MoeadOperator, OptionsAlgorithm, RunOptions};
use crate::optim::{
    Individual, MoeadConfig, NewGenes, OptimError, Threads, ThreadsError, WeightGeneration,
};

/// The algorithms `optimize` offers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum AlgorithmName {
    /// MOEA/D (pagmo semantics, Lampinen constraint rules).
    Moead,
    /// NSGA-II (Deb's constrained domination).
    Nsga2,
    /// MHACO (pagmo maco semantics, ker = min(63, population), feasibility-first archive).
    Mhaco,
    /// SCEA (structured chromosomes; the only one for the variable-length problems).
    Scea,
}

impl AlgorithmName {
    pub(super) fn as_str(self) -> &'static str {
        match self {
            Self::Moead => "moead",
            Self::Nsga2 => "nsga2",
            Self::Mhaco => "mhaco",
            Self::Scea => "scea",
        }
    }
}

/// MOEA/D weight generation on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum WeightsArg {
    /// Simplex lattice (population must be C(H + m - 1, m - 1)).
    Grid,
    /// Unit vectors then a Halton sequence.
    LowDiscrepancy,
    /// Unit vectors then random simplex points.
    Random,
}

/// MOEA/D's variation operator on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum MoeadOperatorArg {
    /// pagmo's MOEA/D-DE (Li & Zhang 2009): DE step (CR 1, F 0.5), polynomial mutation.
    De,
    /// Zhang & Li's (2007) original MOEA/D: SBX (index 20, probability 1) of the two
    /// parents, polynomial mutation. Not pagmo.
    Sbx,
}

/// MHACO constraint handling on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum MhacoConstraintsArg {
    /// Feasible candidates first, then infeasible ones by violation (thesis sec. 10.2).
    FeasibilityFirst,
    /// Constraints as extra objectives, the thesis' normalisation (sec. 9.3.2: unit scales,
    /// cap 2.0, penalty 0.5).
    Objectives,
}

/// Arguments of `optimize`.
#[derive(Debug, clap::Args)]
pub struct OptimizeArgs {
    /// Test problem (zdt1, zdt2, zdt3, zdt4, zdt6, dtlz1 ... dtlz7, constr, vlmop1 ... vlmop5:
    /// variable-length, SCEA only) or re-entry design preset (horus-2b, srm, srm-altitude,
    /// srm-analytical, srm-analytical-altitude: thesis sec. 4.2, 9.1 and 9.2 settings; the
    /// last two on the analytical simulator).
    #[arg(long, default_value = "zdt1")]
    pub problem: String,
    /// Algorithm.
    #[arg(long, value_enum, default_value = "moead")]
    pub algorithm: AlgorithmName,
    /// Population size.
    #[arg(long, default_value_t = 100)]
    pub population: usize,
    /// Generations after the initial population (with --resource-allocation a generation
    /// makes population / 5 children, not population: see --evaluations).
    #[arg(long, default_value_t = DEFAULT_GENERATIONS)]
    pub generations: u64,
    /// MOEA/D and NSGA-II on the test problems: budget in evaluations, initial population
    /// included, instead of --generations: runs the fewest whole generations that reach it
    /// (generations = ceil((E - population) / children per generation); population 100 and
    /// E = 25100: 250 generations, or 1250 with --resource-allocation).
    #[arg(long, value_name = "E", conflicts_with = "generations")]
    pub evaluations: Option<u64>,
    /// Seed of the run's random-number generator.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Objectives of a DTLZ problem.
    #[arg(long, default_value_t = 3)]
    pub objectives: usize,
    /// MOEA/D and SCEA weight generation.
    #[arg(long, value_enum, default_value = "grid")]
    pub weights: WeightsArg,
    /// MOEA/D and SCEA neighbourhood size (at most population - 1; default: 20, or
    /// population - 1 for populations of 20 or less).
    #[arg(long)]
    pub neighbours: Option<usize>,
    /// MOEA/D per-variable mutation probability (default 1/variables; the thesis used
    /// 1/population).
    #[arg(long, value_name = "P")]
    pub mutation_probability: Option<f64>,
    /// MOEA/D offspring per ask/tell batch (1: pagmo's steady state; larger batches let
    /// --threads evaluate in parallel).
    #[arg(long, default_value_t = 1)]
    pub batch_size: usize,
    /// MHACO solution archive size ker, in [2, population] (default min(63, population)).
    #[arg(long, value_name = "K")]
    pub ker: Option<usize>,
    /// MHACO period of the standard-deviation schedule (pagmo's n_gen_mark), at least 1.
    #[arg(long, value_name = "G", default_value_t = 7)]
    pub n_gen_mark: u64,
    /// MHACO constraint handling (no effect on unconstrained problems).
    #[arg(long, value_enum, default_value = "feasibility-first")]
    pub mhaco_constraints: MhacoConstraintsArg,
    /// SCEA: source of the genes of appended nodes: `random` (the thesis' SCEA) or
    /// `population` (alias `history`: history-based, from a mating parent; the default).
    #[arg(long, value_enum, default_value = "population")]
    pub scea_genes: super::optimize_common::SceaGenesArg,
    /// MOEA/D, NSGA-II and SCEA: keep an external archive of the feasible non-dominated
    /// solutions found during the run (Zhang & Li 2007's external population, not in pagmo),
    /// at most N members, truncated by least exclusive hypervolume contribution; the front
    /// written, printed and scored is then the archive's (summary.json: "front_source":
    /// "archive"; re-entry runs: `archive` in config.toml). Default: none (pagmo's
    /// semantics: the final population's front).
    #[arg(long, value_name = "N")]
    pub archive: Option<usize>,
    /// MOEA/D and SCEA: MOEA/D-DRA's dynamic resource allocation (Zhang, Liu & Li, CEC 2009;
    /// not in pagmo): each generation works on the boundary subproblems and 10-way
    /// tournament winners on utility, population / 5 in all, utilities updated every 50
    /// generations. A generation then makes population / 5 children: compare budgets with
    /// --evaluations. Default: off (pagmo's semantics).
    #[arg(long)]
    pub resource_allocation: bool,
    /// MOEA/D variation: `de` (pagmo's MOEA/D-DE, the default) or `sbx` (Zhang & Li 2007's
    /// original MOEA/D: SBX with index 20 and probability 1, then polynomial mutation; not
    /// in pagmo).
    #[arg(long, value_enum, default_value = "de")]
    pub moead_operator: MoeadOperatorArg,
    /// Evaluation threads (1: serial). The result is the same for every value; MOEA/D
    /// gains only with --batch-size > 1.
    #[arg(long, default_value_t = 1)]
    pub threads: usize,
    /// Hypervolume reference point, comma-separated (default: the problem's).
    #[arg(long = "ref", value_name = "R1,R2,...", allow_hyphen_values = true)]
    pub reference: Option<String>,
    /// Write population.csv, front.csv and summary.json here (re-entry problems: the run
    /// directory, default `runs/optimize-<problem>`).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Re-entry run settings from a TOML file (see --print-config).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Print the re-entry run settings of the other flags as a TOML template and exit.
    #[arg(long)]
    pub print_config: bool,
    /// Continue the re-entry run in DIR from its last checkpoint (--generations sets a new
    /// total; by default the run's own).
    #[arg(long, value_name = "DIR", conflicts_with = "config")]
    pub resume: Option<PathBuf>,
}

impl OptimizeArgs {
    /// `--neighbours`, or the default for the population
    /// ([`MoeadConfig::default_neighbours`]).
    pub(super) fn neighbours(&self) -> usize {
        self.neighbours
            .unwrap_or_else(|| MoeadConfig::default_neighbours(self.population))
    }

    /// The algorithm's name as in files.
    #[must_use]
    pub fn algorithm_name(&self) -> &'static str {
        self.algorithm.as_str()
    }

    /// Whether `--generations` differs from its default (a resumed run keeps its own).
    #[must_use]
    pub fn generations_given(&self) -> bool {
        self.generations != DEFAULT_GENERATIONS
    }
}

/// The library's options of the flags (one mapping onto the algorithms, shared with the
/// Python front end). SCEA takes MOEA/D's weights and neighbourhood from them.
pub(super) fn run_options(a: &OptimizeArgs) -> RunOptions {
    RunOptions {
        algorithm: match a.algorithm {
            AlgorithmName::Moead | AlgorithmName::Scea => OptionsAlgorithm::Moead,
            AlgorithmName::Nsga2 => OptionsAlgorithm::Nsga2,
            AlgorithmName::Mhaco => OptionsAlgorithm::Mhaco,
        },
        moead_operator: match a.moead_operator {
            MoeadOperatorArg::De => MoeadOperator::De,
            MoeadOperatorArg::Sbx => MoeadOperator::Sbx,
        },
        population: a.population,
        weights: match a.weights {
            WeightsArg::Grid => WeightGeneration::Grid,
            WeightsArg::LowDiscrepancy => WeightGeneration::LowDiscrepancy,
            WeightsArg::Random => WeightGeneration::Random,
        },
        neighbours: a.neighbours,
        mutation_probability: a.mutation_probability,
        batch_size: a.batch_size,
        archive: a.archive,
        resource_allocation: a.resource_allocation,
        ker: a.ker,
        n_gen_mark: a.n_gen_mark,
        mhaco_constraints: match a.mhaco_constraints {
            MhacoConstraintsArg::FeasibilityFirst => MhacoConstraints::FeasibilityFirst,
            MhacoConstraintsArg::Objectives => MhacoConstraints::Objectives,
        },
    }
}

/// The MHACO settings of the flags.
#[cfg(test)]
pub(super) fn mhaco_config(a: &OptimizeArgs) -> crate::optim::MhacoConfig {
    run_options(a).mhaco_config()
}

/// Default of `--generations`.
pub const DEFAULT_GENERATIONS: u64 = 250;

/// Failures of `optimize`; each says what to change.
#[derive(Debug, thiserror::Error)]
pub enum OptimizeError {
    /// Unknown problem name.
    #[error(
        "command line: --problem {name}: unknown; use one of {list}, {vl}",
        list = NAMES.join(", "),
        vl = crate::optim::problems::VL_NAMES.join(", ")
    )]
    UnknownProblem {
        /// The name given.
        name: String,
    },
    /// The problem could not be built (e.g. a DTLZ with fewer than 2 objectives).
    #[error("command line: --problem {name} --objectives {objectives}: {source}")]
    Problem {
        /// Problem name.
        name: String,
        /// Objectives asked for.
        objectives: usize,
        /// Cause.
        source: TestProblemError,
    },
    /// A reference point of the wrong dimension.
    #[error(
        "command line: --ref has {got} values {values:?}; the problem has {expected} objectives"
    )]
    Reference {
        /// Objectives of the problem.
        expected: usize,
        /// Values given.
        got: usize,
        /// The values.
        values: Vec<f64>,
    },
    /// A malformed `--ref` (not a number, not finite).
    #[error(transparent)]
    ReferenceText(#[from] super::reference_arg::ReferenceArgError),
    /// A fixed-length algorithm on a variable-length problem.
    #[error(
        "command line: --algorithm {algorithm} cannot run the variable-length problem {problem}; use --algorithm scea"
    )]
    NeedsFixedLength {
        /// Algorithm asked for.
        algorithm: &'static str,
        /// Problem asked for.
        problem: String,
    },
    /// `--scea-genes random` for another algorithm (it would be ignored).
    #[error(
        "command line: --scea-genes random applies to --algorithm scea only (given --algorithm {algorithm}); drop it or use --algorithm scea"
    )]
    SceaGenesWithoutScea {
        /// Algorithm asked for.
        algorithm: &'static str,
    },
    /// `--threads` 0 or above 1024.
    #[error("command line: --threads: use 1 to 1024")]
    Threads,
    /// `--archive 0`.
    #[error(
        "command line: --archive 0: the archive's capacity must be at least 1 (or drop --archive)"
    )]
    ArchiveZero,
    /// `--archive` with an algorithm that keeps none.
    #[error(
        "command line: --archive applies to --algorithm moead, nsga2 or scea (given --algorithm {algorithm}); drop it"
    )]
    ArchiveNotHere {
        /// Algorithm asked for.
        algorithm: &'static str,
    },
    /// `--resource-allocation` with an algorithm or problem that does not take it.
    #[error(
        "command line: --resource-allocation applies to --algorithm moead or scea on the test problems (given --algorithm {algorithm} --problem {problem}); drop it"
    )]
    ResourceAllocationNotHere {
        /// Algorithm asked for.
        algorithm: &'static str,
        /// Problem asked for.
        problem: String,
    },
    /// `--moead-operator sbx` with another algorithm or a re-entry problem.
    #[error(
        "command line: --moead-operator sbx applies to --algorithm moead on the test problems (given --algorithm {algorithm} --problem {problem}); drop it"
    )]
    OperatorNotHere {
        /// Algorithm asked for.
        algorithm: &'static str,
        /// Problem asked for.
        problem: String,
    },
    /// `--evaluations` with an algorithm or problem that does not take it, or below the
    /// initial population.
    #[error("command line: --evaluations {evaluations}: {why}")]
    Evaluations {
        /// Budget given.
        evaluations: u64,
        /// What to change.
        why: String,
    },
    /// `--archive` beside `--config` or `--resume`.
    #[error(
        "command line: --archive with --config or --resume: the run file decides; set `archive = N` in it instead"
    )]
    ArchiveInFile,
    /// The rayon pool could not be built.
    #[error("cannot start {threads} evaluation threads: {source}")]
    Pool {
        /// Threads asked for.
        threads: usize,
        /// Cause.
        source: rayon::ThreadPoolBuildError,
    },
    /// The optimiser refused its settings or an evaluation failed.
    #[error("command line: {0}")]
    Optim(#[from] OptimError),
    /// Hypervolume failed.
    #[error("hypervolume: {0}")]
    Hypervolume(#[from] HypervolumeError),
    /// Output could not be written.
    #[error(transparent)]
    Report(#[from] crate::report::ReportError),
    /// Writing to the console failed.
    #[error("cannot write output: {0}")]
    Io(#[from] std::io::Error),
    /// A re-entry design run failed.
    #[error(transparent)]
    Reentry(#[from] crate::design::run::ReentryError),
}

pub(super) struct Outcome {
    pub(super) population: Vec<Individual<Vec<f64>>>,
    /// The external archive's members, when the run kept one (the result front).
    pub(super) archive: Option<Vec<Individual<Vec<f64>>>>,
    pub(super) evaluations: u64,
    pub(super) wall_time_s: f64,
}

/// `--archive`: at least 1, only for the algorithms that keep one (MOEA/D, NSGA-II, SCEA), and
/// not beside a run file (`--config`, `--resume`: the file's `archive` field decides).
pub(super) fn check_archive(a: &OptimizeArgs) -> Result<(), OptimizeError> {
    match a.archive {
        None => Ok(()),
        Some(0) => Err(OptimizeError::ArchiveZero),
        Some(_) if a.config.is_some() || a.resume.is_some() => Err(OptimizeError::ArchiveInFile),
        Some(_) if a.algorithm == AlgorithmName::Mhaco => Err(OptimizeError::ArchiveNotHere {
            algorithm: a.algorithm_name(),
        }),
        Some(_) => Ok(()),
    }
}

/// MOEA/D settings from the arguments (also SCEA's).
pub(super) fn moead_config(a: &OptimizeArgs) -> MoeadConfig {
    run_options(a).moead_config()
}

/// `--resource-allocation`: MOEA/D or SCEA on a test problem only (re-entry runs take their
/// settings from the run file).
pub(super) fn check_resource_allocation(a: &OptimizeArgs) -> Result<(), OptimizeError> {
    let here =
        matches!(a.algorithm, AlgorithmName::Moead | AlgorithmName::Scea) && !wants_reentry(a);
    if a.resource_allocation && !here {
        return Err(OptimizeError::ResourceAllocationNotHere {
            algorithm: a.algorithm_name(),
            problem: a.problem.clone(),
        });
    }
    if a.moead_operator != MoeadOperatorArg::De
        && (a.algorithm != AlgorithmName::Moead || wants_reentry(a))
    {
        return Err(OptimizeError::OperatorNotHere {
            algorithm: a.algorithm_name(),
            problem: a.problem.clone(),
        });
    }
    Ok(())
}

/// The generations to run: `--generations`, or the fewest whole generations whose
/// evaluations, initial population included, reach `--evaluations`.
pub(super) fn generations_to_run(
    a: &OptimizeArgs,
    objectives: usize,
) -> Result<u64, OptimizeError> {
    let Some(e) = a.evaluations else {
        return Ok(a.generations);
    };
    run_options(a)
        .generations_for(e, objectives)
        .map_err(|why| OptimizeError::Evaluations {
            evaluations: e,
            why,
        })
}

/// The evaluation threads for `--threads`.
pub(super) fn threads(count: usize) -> Result<Threads, OptimizeError> {
    Threads::new(count).map_err(|e| match e {
        ThreadsError::Count(_) => OptimizeError::Threads,
        ThreadsError::Pool { threads, source } => OptimizeError::Pool { threads, source },
    })
}

/// The hypervolume reference point: `--ref` when given (checked against the problem's `m`
/// objectives), otherwise the problem's `default`.
pub(super) fn reference(
    a: &OptimizeArgs,
    m: usize,
    default: impl FnOnce() -> Vec<f64>,
) -> Result<Vec<f64>, OptimizeError> {
    match a.reference.as_deref().map(parse_reference).transpose()? {
        Some(r) if r.len() == m => Ok(r),
        Some(r) => Err(OptimizeError::Reference {
            expected: m,
            got: r.len(),
            values: r,
        }),
        None => Ok(default()),
    }
}

/// Where SCEA takes the genes of a node it appends (`--scea-genes`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum SceaGenesArg {
    /// Uniformly random in the node bounds (the thesis' SCEA, sec. 4.1.5).
    Random,
    /// History-based: the same node of a mating parent from the population (the thesis'
    /// recommendation, sec. 10.2); random when neither parent has it. The default.
    #[value(alias = "history")]
    Population,
}

impl SceaGenesArg {
    /// The library's gene source.
    #[must_use]
    pub fn new_genes(self) -> NewGenes {
        match self {
            Self::Random => NewGenes::Random,
            Self::Population => NewGenes::Population,
        }
    }
}

/// Whether `optimize` arguments ask for a re-entry run.
pub(super) fn wants_reentry(a: &OptimizeArgs) -> bool {
    a.print_config
        || a.config.is_some()
        || a.resume.is_some()
        || crate::design::PRESETS.contains(&a.problem.as_str())
}

#[cfg(test)]
mod tests {
    use clap::Parser;

    use super::*;
    use crate::cli::{Cli, Command};

    fn parse(flags: &[&str]) -> OptimizeArgs {
        let argv = ["host-sim", "optimize"].iter().chain(flags);
        match Cli::try_parse_from(argv).unwrap().command {
            Command::Optimize(a) => a,
            _ => unreachable!("optimize parses as optimize"),
        }
    }

    /// The library's `RunOptions` defaults are the command line's (the Python front end
    /// relies on them), and every flag reaches its field.
    #[test]
    fn run_options_defaults_and_fields_are_the_flags() {
        assert_eq!(run_options(&parse(&[])), RunOptions::default());
        let a = parse(&[
            "--algorithm",
            "mhaco",
            "--moead-operator",
            "sbx",
            "--population",
            "24",
            "--weights",
            "random",
            "--neighbours",
            "5",
            "--mutation-probability",
            "0.25",
            "--batch-size",
            "3",
            "--archive",
            "7",
            "--resource-allocation",
            "--ker",
            "9",
            "--n-gen-mark",
            "2",
            "--mhaco-constraints",
            "objectives",
        ]);
        let o = run_options(&a);
        assert_eq!(
            o,
            RunOptions {
                algorithm: OptionsAlgorithm::Mhaco,
                moead_operator: MoeadOperator::Sbx,
                population: 24,
                weights: WeightGeneration::Random,
                neighbours: Some(5),
                mutation_probability: Some(0.25),
                batch_size: 3,
                archive: Some(7),
                resource_allocation: true,
                ker: Some(9),
                n_gen_mark: 2,
                mhaco_constraints: MhacoConstraints::Objectives,
            }
        );
        // JSON with the flags' names reads back to the same options; unknown names are refused.
        let json = serde_json::to_string(&o).unwrap();
        assert!(
            json.contains("\"mhaco_constraints\":\"objectives\""),
            "{json}"
        );
        assert_eq!(serde_json::from_str::<RunOptions>(&json).unwrap(), o);
        let e = serde_json::from_str::<RunOptions>(r#"{"neighbors": 5}"#).unwrap_err();
        assert!(e.to_string().contains("unknown field `neighbors`"), "{e}");
        // --evaluations: MOEA/D and NSGA-II only, at least the initial population.
        let mut o = RunOptions {
            population: 20,
            ..RunOptions::default()
        };
        assert_eq!(o.generations_for(2000, 2), Ok(99));
        assert!(
            o.generations_for(19, 2)
                .unwrap_err()
                .contains("at least 20")
        );
        o.algorithm = OptionsAlgorithm::Mhaco;
        assert!(
            o.generations_for(2000, 2)
                .unwrap_err()
                .contains("--generations")
        );
    }
}
