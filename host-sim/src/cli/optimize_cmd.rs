//! `host-sim optimize`: run a multi-objective optimiser on a standard test problem, print a
//! summary, and with `--out DIR` write the final population, its feasible front (CSV) and a
//! summary JSON (hypervolume, reference point, evaluations, wall time of the evolution alone).

use std::fmt::Write as _;
use std::io::Write;
use std::path::{Path, PathBuf};

use clap::ValueEnum;
use serde::Serialize;

use crate::optim::hypervolume::{HypervolumeError, hypervolume};
use crate::optim::population::{feasible_fraction, feasible_front_indices};
use crate::optim::problems::{NAMES, TestProblem, TestProblemError};
use crate::optim::{
    Algorithm, Budget, ConstraintHandling, Executor, Individual, Mhaco, MhacoConfig, Moead,
    MoeadConfig, MoeadSbx, Nsga2, Nsga2Config, OptimError, Problem, SbxVariation, Threads,
    ThreadsError, WeightGeneration,
};
use crate::report::{ReportError, RunDir};

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
    pub scea_genes: super::optimize_structured::SceaGenesArg,
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
    #[arg(
        long = "ref",
        value_name = "R1,R2,...",
        value_delimiter = ',',
        allow_negative_numbers = true
    )]
    pub reference: Option<Vec<f64>>,
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

/// The MHACO settings of the flags.
pub(super) fn mhaco_config(a: &OptimizeArgs) -> MhacoConfig {
    MhacoConfig {
        population: a.population,
        ker: a
            .ker
            .unwrap_or_else(|| a.population.min(MhacoConfig::default().ker)),
        n_gen_mark: a.n_gen_mark,
        constraints: match a.mhaco_constraints {
            MhacoConstraintsArg::FeasibilityFirst => ConstraintHandling::FeasibilityFirst,
            MhacoConstraintsArg::Objectives => ConstraintHandling::thesis_objectives(),
        },
        ..MhacoConfig::default()
    }
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
    /// A reference point of the wrong dimension or with non-finite values.
    #[error(
        "command line: --ref has {got} values {values:?}; the problem has {expected} objectives and every value must be finite"
    )]
    Reference {
        /// Objectives of the problem.
        expected: usize,
        /// Values given.
        got: usize,
        /// The values.
        values: Vec<f64>,
    },
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
    Report(#[from] ReportError),
    /// Writing to the console failed.
    #[error("cannot write output: {0}")]
    Io(#[from] std::io::Error),
    /// A re-entry design run failed.
    #[error(transparent)]
    Reentry(#[from] super::optimize_reentry::ReentryError),
}

/// The summary JSON.
#[derive(Debug, Serialize)]
pub(super) struct Summary<'a> {
    pub(super) problem: &'a str,
    pub(super) algorithm: &'static str,
    pub(super) population: usize,
    pub(super) generations: u64,
    pub(super) seed: u64,
    pub(super) objectives: usize,
    pub(super) variables: usize,
    pub(super) constraints: usize,
    pub(super) evaluations: u64,
    pub(super) reference_point: &'a [f64],
    pub(super) hypervolume: f64,
    pub(super) true_front_hypervolume: Option<f64>,
    pub(super) hypervolume_ratio: Option<f64>,
    pub(super) feasible_fraction: f64,
    /// What the front (front.csv, hypervolume, front_size) is taken from: "population" (the
    /// final population; pagmo's semantics) or "archive" (the external archive, `--archive`).
    pub(super) front_source: &'static str,
    /// Capacity of the external archive (`--archive`), if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) archive_capacity: Option<usize>,
    /// MOEA/D-DRA's resource allocation was on (`--resource-allocation`).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub(super) resource_allocation: bool,
    /// MOEA/D's variation when not pagmo's DE (`--moead-operator sbx`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) moead_operator: Option<&'static str>,
    pub(super) front_size: usize,
    /// Wall time of the evolution alone (no problem set-up, no output) [s].
    pub(super) wall_time_s: f64,
    pub(super) threads: usize,
}

pub(super) struct Outcome {
    pub(super) population: Vec<Individual<Vec<f64>>>,
    /// The external archive's members, when the run kept one (the result front).
    pub(super) archive: Option<Vec<Individual<Vec<f64>>>>,
    pub(super) evaluations: u64,
    pub(super) wall_time_s: f64,
}

fn drive<A: Algorithm<TestProblem>>(
    alg: A,
    problem: &TestProblem,
    generations: u64,
    threads: &Threads,
) -> Result<Outcome, OptimError> {
    let run = Executor::new(problem, alg)
        .budget(Budget::Generations(generations))
        .threads(threads.clone())
        .run()?;
    let (alg, wall_time_s) = (run.algorithm, run.wall_time_s);
    Ok(Outcome {
        population: alg.population().to_vec(),
        archive: alg.external_archive().map(<[_]>::to_vec),
        evaluations: alg.evaluations(),
        wall_time_s,
    })
}

/// `--archive`: at least 1, only for the algorithms that keep one (MOEA/D, NSGA-II, SCEA), and
/// not beside a run file (`--config`, `--resume`: the file's `archive` field decides).
fn check_archive(a: &OptimizeArgs) -> Result<(), OptimizeError> {
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
    let weights = match a.weights {
        WeightsArg::Grid => WeightGeneration::Grid,
        WeightsArg::LowDiscrepancy => WeightGeneration::LowDiscrepancy,
        WeightsArg::Random => WeightGeneration::Random,
    };
    MoeadConfig {
        population: a.population,
        weights,
        neighbours: a.neighbours(),
        mutation_probability: a.mutation_probability,
        batch_size: a.batch_size,
        archive: a.archive,
        resource_allocation: a
            .resource_allocation
            .then(crate::optim::ResourceAllocation::default),
        ..MoeadConfig::default()
    }
}

/// `--resource-allocation`: MOEA/D or SCEA on a test problem only (re-entry runs take their
/// settings from the run file).
fn check_resource_allocation(a: &OptimizeArgs) -> Result<(), OptimizeError> {
    let here = matches!(a.algorithm, AlgorithmName::Moead | AlgorithmName::Scea)
        && !super::optimize_reentry::wants_reentry(a);
    if a.resource_allocation && !here {
        return Err(OptimizeError::ResourceAllocationNotHere {
            algorithm: a.algorithm_name(),
            problem: a.problem.clone(),
        });
    }
    if a.moead_operator != MoeadOperatorArg::De
        && (a.algorithm != AlgorithmName::Moead || super::optimize_reentry::wants_reentry(a))
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
fn generations_to_run(a: &OptimizeArgs, objectives: usize) -> Result<u64, OptimizeError> {
    let Some(e) = a.evaluations else {
        return Ok(a.generations);
    };
    let err = |why: String| OptimizeError::Evaluations {
        evaluations: e,
        why,
    };
    let per_generation = match a.algorithm {
        AlgorithmName::Moead => moead_config(a)
            .resource_allocation
            .map_or(a.population, |ra| {
                ra.subproblems_per_generation(a.population, objectives)
            }),
        _ => a.population,
    };
    let n = a.population as u64;
    if e < n || per_generation == 0 {
        return Err(err(format!(
            "below the initial population of {n}; use at least {n}"
        )));
    }
    Ok((e - n).div_ceil(per_generation as u64))
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
    match &a.reference {
        Some(r) if r.len() == m && r.iter().all(|v| v.is_finite()) => Ok(r.clone()),
        Some(r) => Err(OptimizeError::Reference {
            expected: m,
            got: r.len(),
            values: r.clone(),
        }),
        None => Ok(default()),
    }
}

/// Run `optimize` with arguments `a`, printing the summary to `out`.
///
/// # Errors
/// [`OptimizeError`].
pub fn run(a: &OptimizeArgs, out: &mut dyn Write) -> Result<(), OptimizeError> {
    // A config file or a resumed run decides its own algorithm and gene source.
    if a.scea_genes == super::optimize_structured::SceaGenesArg::Random
        && a.algorithm != AlgorithmName::Scea
        && a.config.is_none()
        && a.resume.is_none()
    {
        return Err(OptimizeError::SceaGenesWithoutScea {
            algorithm: a.algorithm_name(),
        });
    }
    check_archive(a)?;
    check_resource_allocation(a)?;
    if let Some(evaluations) = a.evaluations {
        let fixed = matches!(a.algorithm, AlgorithmName::Moead | AlgorithmName::Nsga2);
        if !fixed || super::optimize_reentry::wants_reentry(a) {
            return Err(OptimizeError::Evaluations {
                evaluations,
                why: format!(
                    "applies to --algorithm moead or nsga2 on the test problems (given --algorithm {} --problem {}); use --generations",
                    a.algorithm_name(),
                    a.problem
                ),
            });
        }
    }
    if super::optimize_reentry::wants_reentry(a) {
        return Ok(super::optimize_reentry::run(a, out)?);
    }
    if let Some(vl) = crate::optim::problems::Vlmop::by_name(&a.problem) {
        return super::optimize_structured::run_variable_length(a, &vl, out);
    }
    let problem = TestProblem::by_name(&a.problem, a.objectives)
        .map_err(|source| OptimizeError::Problem {
            name: a.problem.clone(),
            objectives: a.objectives,
            source,
        })?
        .ok_or_else(|| OptimizeError::UnknownProblem {
            name: a.problem.clone(),
        })?;
    let m = problem.objectives();
    let reference = reference(a, m, || problem.reference_point())?;
    let generations = generations_to_run(a, m)?;
    let pool = threads(a.threads)?;
    let outcome = match a.algorithm {
        AlgorithmName::Moead => {
            let config = moead_config(a);
            match a.moead_operator {
                MoeadOperatorArg::De => {
                    drive(Moead::new(config, a.seed), &problem, generations, &pool)?
                }
                MoeadOperatorArg::Sbx => drive(
                    MoeadSbx::sbx(config, SbxVariation::default(), a.seed),
                    &problem,
                    generations,
                    &pool,
                )?,
            }
        }
        AlgorithmName::Nsga2 => {
            let config = Nsga2Config {
                population: a.population,
                archive: a.archive,
                ..Nsga2Config::default()
            };
            drive(Nsga2::new(config, a.seed), &problem, generations, &pool)?
        }
        AlgorithmName::Mhaco => {
            let config = mhaco_config(a);
            drive(Mhaco::new(config, a.seed), &problem, a.generations, &pool)?
        }
        AlgorithmName::Scea => super::optimize_structured::drive_scea(a, &problem, &pool)?,
    };
    let pop = &outcome.population;
    let result = outcome.archive.as_deref().unwrap_or(pop);
    let front_idx = feasible_front_indices(result);
    let front: Vec<&[f64]> = front_idx
        .iter()
        .map(|&i| result[i].objectives.as_slice())
        .collect();
    let hv = hypervolume(&front, &reference)?;
    let true_hv = problem.front_hypervolume(&reference, 20_000);
    let summary = Summary {
        problem: &a.problem,
        algorithm: a.algorithm.as_str(),
        population: a.population,
        generations,
        seed: a.seed,
        objectives: m,
        variables: crate::optim::RealProblem::bounds(&problem).dim(),
        constraints: problem.constraints(),
        evaluations: outcome.evaluations,
        reference_point: &reference,
        hypervolume: hv,
        true_front_hypervolume: true_hv,
        hypervolume_ratio: true_hv.filter(|t| *t > 0.0).map(|t| hv / t),
        feasible_fraction: feasible_fraction(pop),
        front_source: if outcome.archive.is_some() {
            "archive"
        } else {
            "population"
        },
        archive_capacity: a.archive,
        resource_allocation: a.resource_allocation,
        moead_operator: (a.moead_operator == MoeadOperatorArg::Sbx).then_some("sbx"),
        front_size: front.len(),
        wall_time_s: outcome.wall_time_s,
        threads: a.threads,
    };
    print_summary(out, &summary, hv, &reference, front.len())?;
    if let Some(dir) = &a.out {
        write_outputs(dir, pop, &front, &summary)?;
        writeln!(out, "wrote {}", dir.display())?;
    }
    Ok(())
}

pub(super) fn write_outputs(
    dir: &Path,
    pop: &[Individual<Vec<f64>>],
    front: &[&[f64]],
    summary: &Summary<'_>,
) -> Result<(), OptimizeError> {
    let mut rd = RunDir::begin(dir)?;
    let nf = summary.objectives;
    let mut csv = String::new();
    let header: Vec<String> = (1..=summary.variables)
        .map(|i| format!("x{i}"))
        .chain((1..=nf).map(|i| format!("f{i}")))
        .chain((1..=summary.constraints).map(|i| format!("g{i}")))
        .chain(["violation".to_string()])
        .collect();
    let _ = writeln!(csv, "{}", header.join(","));
    for ind in pop {
        let row: Vec<String> = ind
            .decision
            .iter()
            .chain(&ind.objectives)
            .chain(&ind.constraints)
            .chain(std::iter::once(&ind.violation))
            .map(|v| format!("{v:e}"))
            .collect();
        let _ = writeln!(csv, "{}", row.join(","));
    }
    rd.write("population.csv", csv.as_bytes())?;
    let mut csv = String::new();
    let header: Vec<String> = (1..=nf).map(|i| format!("f{i}")).collect();
    let _ = writeln!(csv, "{}", header.join(","));
    for f in front {
        let row: Vec<String> = f.iter().map(|v| format!("{v:e}")).collect();
        let _ = writeln!(csv, "{}", row.join(","));
    }
    rd.write("front.csv", csv.as_bytes())?;
    let json = serde_json::to_string_pretty(summary).map_err(ReportError::Json)?;
    rd.write("summary.json", json.as_bytes())?;
    rd.commit()?;
    Ok(())
}

/// The one-line result of an optimisation run (both `optimize` paths print it).
pub(super) fn print_summary(
    out: &mut dyn Write,
    summary: &Summary,
    hv: f64,
    reference: &[f64],
    front_points: usize,
) -> std::io::Result<()> {
    let ratio = summary
        .hypervolume_ratio
        .map_or_else(String::new, |r| format!(" ({r:.4} of the true front)"));
    writeln!(
        out,
        "{} on {}: {} evaluations in {:.3} s, hypervolume {:.6}{} w.r.t. {:?}, {} front points, feasible {:.0} %",
        summary.algorithm,
        summary.problem,
        summary.evaluations,
        summary.wall_time_s,
        hv,
        ratio,
        reference,
        front_points,
        100.0 * summary.feasible_fraction
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(problem: &str, algorithm: AlgorithmName, out: Option<PathBuf>) -> OptimizeArgs {
        OptimizeArgs {
            problem: problem.into(),
            algorithm,
            population: 20,
            generations: 5,
            seed: 3,
            objectives: 3,
            weights: WeightsArg::Grid,
            neighbours: Some(5),
            mutation_probability: None,
            batch_size: 1,
            ker: None,
            n_gen_mark: 7,
            mhaco_constraints: MhacoConstraintsArg::FeasibilityFirst,
            scea_genes: super::super::optimize_structured::SceaGenesArg::Population,
            archive: None,
            resource_allocation: false,
            moead_operator: MoeadOperatorArg::De,
            evaluations: None,
            threads: 1,
            reference: None,
            out,
            config: None,
            print_config: false,
            resume: None,
        }
    }

    #[test]
    fn optimize_writes_population_front_and_summary() {
        let dir = std::env::temp_dir().join(format!("host-sim-optimize-{}", std::process::id()));
        let mut out = Vec::new();
        let mut a = args("zdt1", AlgorithmName::Nsga2, Some(dir.clone()));
        a.generations = 60;
        run(&a, &mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        assert!(text.contains("nsga2 on zdt1: 1220 evaluations"), "{text}");
        let pop = std::fs::read_to_string(dir.join("population.csv")).unwrap();
        assert_eq!(pop.lines().count(), 21);
        assert!(pop.starts_with("x1,x2,"));
        let front = std::fs::read_to_string(dir.join("front.csv")).unwrap();
        assert!(front.starts_with("f1,f2\n") && front.lines().count() > 1);
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(json["evaluations"], 1220);
        assert_eq!(json["reference_point"], serde_json::json!([1.1, 1.1]));
        assert!(json["hypervolume"].as_f64().unwrap() > 0.0);
        assert!(json["wall_time_s"].as_f64().unwrap() >= 0.0);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn optimize_bad_input_says_what_to_change() {
        let mut out = Vec::new();
        let e = run(&args("zdt5", AlgorithmName::Moead, None), &mut out).unwrap_err();
        assert!(e.to_string().contains("--problem zdt5: unknown"), "{e}");
        let e = run(&args("dtlz2", AlgorithmName::Moead, None), &mut out).unwrap_err();
        assert!(
            e.to_string().contains("nearest legal sizes are 15 and 21"),
            "{e}"
        );
        let mut a = args("zdt1", AlgorithmName::Moead, None);
        a.reference = Some(vec![1.0]);
        let e = run(&a, &mut out).unwrap_err();
        assert!(e.to_string().contains("--ref has 1 values"), "{e}");
        let mut a = args("zdt1", AlgorithmName::Nsga2, None);
        a.population = 22;
        let e = run(&a, &mut out).unwrap_err();
        assert!(e.to_string().contains("use 20 or 24"), "{e}");
        let mut a = args("zdt1", AlgorithmName::Moead, None);
        a.batch_size = 21;
        let e = run(&a, &mut out).unwrap_err();
        assert!(
            e.to_string()
                .contains("batch_size = 21 is outside [1, population]"),
            "{e}"
        );
        let mut a = args("zdt1", AlgorithmName::Moead, None);
        a.mutation_probability = Some(1.5);
        let e = run(&a, &mut out).unwrap_err();
        assert!(e.to_string().contains("mutation_probability = 1.5"), "{e}");
        let mut a = args("zdt1", AlgorithmName::Nsga2, None);
        a.threads = 0;
        assert!(matches!(run(&a, &mut out), Err(OptimizeError::Threads)));
    }

    #[test]
    fn optimize_mhaco_flags_reach_the_algorithm() {
        let dir = |t: &str| {
            std::env::temp_dir().join(format!(
                "host-sim-optimize-mhaco-{t}-{}",
                std::process::id()
            ))
        };
        let mut a = args("constr", AlgorithmName::Mhaco, None);
        let default = mhaco_config(&a);
        assert_eq!((default.ker, default.n_gen_mark), (20, 7));
        assert_eq!(default.constraints, ConstraintHandling::FeasibilityFirst);
        a.ker = Some(10);
        a.n_gen_mark = 3;
        a.mhaco_constraints = MhacoConstraintsArg::Objectives;
        let c = mhaco_config(&a);
        assert_eq!((c.ker, c.n_gen_mark), (10, 3));
        assert_eq!(c.constraints, ConstraintHandling::thesis_objectives());
        // Each flag changes the run (same seed).
        let mut runs = Vec::new();
        for (tag, ker, mark, mode) in [
            ("base", None, 7, MhacoConstraintsArg::FeasibilityFirst),
            ("ker", Some(10), 7, MhacoConstraintsArg::FeasibilityFirst),
            ("mark", None, 2, MhacoConstraintsArg::FeasibilityFirst),
            ("obj", None, 7, MhacoConstraintsArg::Objectives),
        ] {
            let mut a = args("constr", AlgorithmName::Mhaco, Some(dir(tag)));
            a.generations = 20;
            (a.ker, a.n_gen_mark, a.mhaco_constraints) = (ker, mark, mode);
            run(&a, &mut Vec::new()).unwrap();
            runs.push(std::fs::read_to_string(dir(tag).join("population.csv")).unwrap());
            std::fs::remove_dir_all(dir(tag)).unwrap();
        }
        for (i, r) in runs.iter().enumerate().skip(1) {
            assert_ne!(&runs[0], r, "flag set {i} left the run unchanged");
        }
        // Bad values are the algorithm's typed errors naming the setting.
        let mut a = args("zdt1", AlgorithmName::Mhaco, None);
        a.ker = Some(21);
        let e = run(&a, &mut Vec::new()).unwrap_err();
        assert!(e.to_string().contains("ker"), "{e}");
        a.ker = None;
        a.n_gen_mark = 0;
        let e = run(&a, &mut Vec::new()).unwrap_err();
        assert!(e.to_string().contains("n_gen_mark"), "{e}");
    }

    #[test]
    fn optimize_archive_reports_the_archive_front_and_refuses_bad_values() {
        let dir = |t: &str| {
            std::env::temp_dir().join(format!(
                "host-sim-optimize-archive-{t}-{}",
                std::process::id()
            ))
        };
        let summary = |d: &Path| -> serde_json::Value {
            serde_json::from_str(&std::fs::read_to_string(d.join("summary.json")).unwrap()).unwrap()
        };
        for alg in [AlgorithmName::Moead, AlgorithmName::Nsga2] {
            let mut a = args("zdt1", alg, Some(dir("plain")));
            a.generations = 30;
            run(&a, &mut Vec::new()).unwrap();
            a.archive = Some(12);
            a.out = Some(dir("archive"));
            let mut text = Vec::new();
            run(&a, &mut text).unwrap();
            let (plain, with) = (summary(&dir("plain")), summary(&dir("archive")));
            assert_eq!(plain["front_source"], "population", "{alg:?}");
            assert!(plain.get("archive_capacity").is_none());
            assert_eq!(with["front_source"], "archive", "{alg:?}");
            assert_eq!(with["archive_capacity"], 12);
            assert_eq!(with["front_size"], 12);
            // The population is the same run's; the front is the archive's.
            let read = |d: PathBuf, f: &str| std::fs::read_to_string(d.join(f)).unwrap();
            assert_eq!(
                read(dir("plain"), "population.csv"),
                read(dir("archive"), "population.csv")
            );
            assert_eq!(read(dir("archive"), "front.csv").lines().count(), 13);
            let text = String::from_utf8(text).unwrap();
            assert!(text.contains("12 front points"), "{text}");
            for t in ["plain", "archive"] {
                std::fs::remove_dir_all(dir(t)).unwrap();
            }
        }
        let mut a = args("zdt1", AlgorithmName::Moead, None);
        a.archive = Some(0);
        let e = run(&a, &mut Vec::new()).unwrap_err();
        assert!(e.to_string().contains("--archive 0"), "{e}");
        for problem in ["zdt1", "srm"] {
            let mut a = args(problem, AlgorithmName::Mhaco, None);
            a.archive = Some(10);
            let e = run(&a, &mut Vec::new()).unwrap_err();
            assert!(matches!(e, OptimizeError::ArchiveNotHere { .. }), "{e}");
            assert!(e.to_string().contains("--archive applies to"), "{e}");
        }
        let mut a = args("srm", AlgorithmName::Moead, None);
        a.archive = Some(10);
        a.resume = Some(PathBuf::from("runs/none"));
        let e = run(&a, &mut Vec::new()).unwrap_err();
        assert!(matches!(e, OptimizeError::ArchiveInFile), "{e}");
        // SCEA on a fixed-length and on a variable-length problem reports its archive too.
        for problem in ["zdt1", "vlmop1"] {
            let mut a = args(problem, AlgorithmName::Scea, Some(dir("scea")));
            a.archive = Some(6);
            run(&a, &mut Vec::new()).unwrap();
            let s = summary(&dir("scea"));
            assert_eq!(s["front_source"], "archive", "{problem}");
            let n = s["front_size"].as_u64().unwrap();
            assert!((1..=6).contains(&n), "{problem}: {s}");
            std::fs::remove_dir_all(dir("scea")).unwrap();
        }
    }

    #[test]
    fn optimize_threads_do_not_change_the_result() {
        let dir =
            |t| std::env::temp_dir().join(format!("host-sim-optimize-t{t}-{}", std::process::id()));
        for (alg, archive) in [
            (AlgorithmName::Nsga2, None),
            (AlgorithmName::Moead, None),
            (AlgorithmName::Nsga2, Some(7)),
            (AlgorithmName::Moead, Some(7)),
        ] {
            for t in [1usize, 3] {
                let mut a = args("constr", alg, Some(dir(t)));
                a.threads = t;
                a.batch_size = 8;
                a.archive = archive;
                run(&a, &mut Vec::new()).unwrap();
            }
            for f in ["population.csv", "front.csv"] {
                let read = |t| std::fs::read_to_string(dir(t).join(f)).unwrap();
                assert_eq!(read(1), read(3), "{alg:?} {archive:?} {f}");
            }
            for t in [1usize, 3] {
                std::fs::remove_dir_all(dir(t)).unwrap();
            }
        }
    }
}
