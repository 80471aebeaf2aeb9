//! What the `host-sim optimize` runs share, below all of them: the arguments (the common
//! flags and one subcommand per algorithm holding its own), their mapping onto the library's
//! [`RunOptions`], the checks clap cannot make ([`check`]), and the errors (the summary and
//! the run directory are the library's: [`crate::optim::run::run_report`],
//! [`crate::report::write_run_report`]). The test-problem run ([`super::optimize_cmd`]), the
//! re-entry run ([`super::optimize_reentry`]) and SCEA ([`super::optimize_structured`])
//! import this module and not each other, so the four files form no import cycle.

use std::path::PathBuf;

use crate::optim::problems::{NAMES, TestProblemError};
use crate::optim::reference::parse_reference;
use crate::optim::spec::{MhacoConstraints, MoeadOperator, OptionsAlgorithm, RunOptions};
use crate::optim::{MhacoConfig, NewGenes, OptimError, ThreadsError, WeightGeneration};

/// Arguments of `optimize`: the flags every algorithm takes (`global`: before or after the
/// subcommand) and the algorithm's subcommand with its own flags.
#[derive(Debug, clap::Args)]
#[command(next_help_heading = "Common options (before or after the algorithm)")]
pub struct OptimizeArgs {
    /// The algorithm and its own flags (default: `moead` with its defaults).
    #[command(subcommand)]
    pub algorithm: Option<AlgorithmArgs>,
    /// Test problem (zdt1, zdt2, zdt3, zdt4, zdt6, dtlz1 ... dtlz7, constr, vlmop1 ... vlmop5:
    /// variable-length, SCEA or MHACO (its variable-length form) only) or re-entry design preset (horus-2b, srm, srm-altitude,
    /// srm-analytical, srm-analytical-altitude: thesis sec. 4.2, 9.1 and 9.2 settings; the
    /// last two on the analytical simulator).
    #[arg(long, global = true, default_value = "zdt1")]
    pub problem: String,
    /// Population size.
    #[arg(long, global = true, default_value_t = RunOptions::default().population)]
    pub population: usize,
    /// Generations after the initial population (with --resource-allocation a generation
    /// makes population / 5 children, not population: see --evaluations).
    #[arg(long, global = true, default_value_t = DEFAULT_GENERATIONS)]
    pub generations: u64,
    /// moead and nsga2 on the test problems: budget in evaluations, initial population
    /// included, instead of --generations: runs the fewest whole generations that reach it
    /// (generations = ceil((E - population) / children per generation); population 100 and
    /// E = 25100: 250 generations, or 1250 with --resource-allocation).
    #[arg(long, global = true, value_name = "E", conflicts_with_all = ["generations", "config"])]
    pub evaluations: Option<u64>,
    /// Seed of the run's random-number generator.
    #[arg(long, global = true, default_value_t = 1)]
    pub seed: u64,
    /// Objectives of a DTLZ problem.
    #[arg(long, global = true, default_value_t = 3)]
    pub objectives: usize,
    /// Evaluation threads (1: serial). The result is the same for every value; MOEA/D
    /// gains only with --batch-size > 1.
    #[arg(long, global = true, default_value_t = 1)]
    pub threads: usize,
    /// Hypervolume reference point, comma-separated (default: the problem's).
    #[arg(
        long = "ref",
        global = true,
        value_name = "R1,R2,...",
        allow_hyphen_values = true
    )]
    pub reference: Option<String>,
    /// Write population.csv, front.csv and summary.json here (re-entry problems: the run
    /// directory, default `runs/optimize-<problem>`).
    #[arg(long, global = true, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Re-entry run settings from a TOML file (see --print-config); the file decides the
    /// algorithm and its settings.
    #[arg(long, global = true, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Print the re-entry run settings of the other flags as a TOML template and exit.
    #[arg(long, global = true)]
    pub print_config: bool,
    /// Continue the re-entry run in DIR from its last checkpoint with its own settings
    /// (--generations sets a new total; by default the run's own).
    #[arg(long, global = true, value_name = "DIR", conflicts_with_all = [
        "problem", "population", "evaluations", "seed", "objectives", "threads", "reference",
        "out", "config", "print_config",
    ])]
    pub resume: Option<PathBuf>,
}

/// `optimize`'s algorithms, each with only its own flags.
#[derive(Clone, Debug, clap::Subcommand)]
pub enum AlgorithmArgs {
    /// MOEA/D (pagmo semantics, Lampinen constraint rules); the default.
    Moead(MoeadArgs),
    /// NSGA-II (Deb's constrained domination).
    Nsga2(Nsga2Args),
    /// MHACO (pagmo maco semantics, ker = min(63, population), feasibility-first archive; on
    /// the variable-length problems the variable-length MHACO).
    Mhaco(MhacoArgs),
    /// SCEA (structured chromosomes; with MHACO the one for the variable-length problems).
    Scea(SceaArgs),
}

/// The decomposition flags of MOEA/D and SCEA.
#[derive(Clone, Debug, clap::Args)]
pub struct DecompositionArgs {
    /// Weight generation.
    #[arg(long, value_enum, default_value_t = WeightGeneration::Grid)]
    pub weights: WeightGeneration,
    /// Neighbourhood size (at most population - 1; default: 20, or population - 1 for
    /// populations of 20 or less).
    #[arg(long)]
    pub neighbours: Option<usize>,
    /// Per-variable mutation probability (default 1/variables; the thesis used
    /// 1/population).
    #[arg(long, value_name = "P")]
    pub mutation_probability: Option<f64>,
    /// Offspring per ask/tell batch (1: pagmo's steady state; larger batches let --threads
    /// evaluate in parallel).
    #[arg(long, default_value_t = 1)]
    pub batch_size: usize,
    /// External archive of at most N feasible non-dominated solutions (see `nsga2 --help`).
    #[arg(long, value_name = "N", value_parser = archive_capacity())]
    pub archive: Option<usize>,
    /// MOEA/D-DRA's dynamic resource allocation (Zhang, Liu & Li, CEC 2009; not in pagmo),
    /// test problems only: each generation works on the boundary subproblems and 10-way
    /// tournament winners on utility, population / 5 in all, utilities updated every 50
    /// generations. A generation then makes population / 5 children: compare budgets with
    /// --evaluations. Default: off (pagmo's semantics).
    #[arg(long)]
    pub resource_allocation: bool,
}

/// `optimize moead`.
#[derive(Clone, Debug, clap::Args)]
pub struct MoeadArgs {
    /// Weights, neighbourhood, mutation, batches, archive, resource allocation.
    #[command(flatten)]
    pub decomposition: DecompositionArgs,
    /// Variation (`sbx`: test problems only).
    #[arg(long, value_enum, default_value_t = MoeadOperator::De)]
    pub moead_operator: MoeadOperator,
}

/// `optimize nsga2`.
#[derive(Clone, Debug, clap::Args)]
pub struct Nsga2Args {
    /// Keep an external archive of the feasible non-dominated solutions found during the run
    /// (Zhang & Li 2007's external population, not in pagmo), at most N members, truncated by
    /// least exclusive hypervolume contribution; the front written, printed and scored is
    /// then the archive's (summary.json: "front_source": "archive"; re-entry runs: `archive`
    /// in config.toml). Default: none (pagmo's semantics: the final population's front).
    #[arg(long, value_name = "N", value_parser = archive_capacity())]
    pub archive: Option<usize>,
}

/// `optimize mhaco`.
#[derive(Clone, Debug, clap::Args)]
pub struct MhacoArgs {
    /// Solution archive size ker, in [2, population] (default min(63, population); test
    /// problems only).
    #[arg(long, value_name = "K")]
    pub ker: Option<usize>,
    /// Period of the standard-deviation schedule (pagmo's n_gen_mark), at least 1 (test
    /// problems only).
    #[arg(long, value_name = "G", default_value_t = MhacoConfig::default().n_gen_mark)]
    pub n_gen_mark: u64,
    /// Constraint handling (no effect on unconstrained problems).
    #[arg(long, value_enum, default_value_t = MhacoConstraints::FeasibilityFirst)]
    pub mhaco_constraints: MhacoConstraints,
}

/// `optimize scea`.
#[derive(Clone, Debug, clap::Args)]
pub struct SceaArgs {
    /// MOEA/D's weights, neighbourhood, mutation, batches, archive, resource allocation.
    #[command(flatten)]
    pub decomposition: DecompositionArgs,
    /// Source of the genes of appended nodes: `random` (the thesis' SCEA) or `population`
    /// (alias `history`: history-based, from a mating parent).
    #[arg(long, value_enum, default_value_t = NewGenes::Population)]
    pub scea_genes: NewGenes,
}

/// `--archive`: a capacity of at least 1.
fn archive_capacity() -> clap::builder::RangedU64ValueParser<usize> {
    clap::builder::RangedU64ValueParser::new().range(1..)
}

impl OptimizeArgs {
    /// The algorithm's name as in files (`moead`, `nsga2`, `mhaco`, `scea`).
    #[must_use]
    pub fn algorithm_name(&self) -> &'static str {
        match &self.algorithm {
            None | Some(AlgorithmArgs::Moead(_)) => "moead",
            Some(AlgorithmArgs::Nsga2(_)) => "nsga2",
            Some(AlgorithmArgs::Mhaco(_)) => "mhaco",
            Some(AlgorithmArgs::Scea(_)) => "scea",
        }
    }

    /// Whether `--generations` differs from its default (a resumed run keeps its own).
    #[must_use]
    pub fn generations_given(&self) -> bool {
        self.generations != DEFAULT_GENERATIONS
    }
}

/// The library's options of the flags (one mapping onto the algorithms, shared with the
/// Python front end; no subcommand: MOEA/D's defaults). SCEA takes MOEA/D's fields.
pub(super) fn run_options(a: &OptimizeArgs) -> RunOptions {
    let base = RunOptions {
        population: a.population,
        ..RunOptions::default()
    };
    let decomposition = |d: &DecompositionArgs| RunOptions {
        weights: d.weights,
        neighbours: d.neighbours,
        mutation_probability: d.mutation_probability,
        batch_size: d.batch_size,
        archive: d.archive,
        resource_allocation: d.resource_allocation,
        ..base.clone()
    };
    match &a.algorithm {
        None => base,
        Some(AlgorithmArgs::Moead(m)) => RunOptions {
            moead_operator: m.moead_operator,
            ..decomposition(&m.decomposition)
        },
        Some(AlgorithmArgs::Scea(s)) => RunOptions {
            algorithm: OptionsAlgorithm::Scea,
            scea_genes: s.scea_genes,
            ..decomposition(&s.decomposition)
        },
        Some(AlgorithmArgs::Nsga2(n)) => RunOptions {
            algorithm: OptionsAlgorithm::Nsga2,
            archive: n.archive,
            ..base
        },
        Some(AlgorithmArgs::Mhaco(m)) => RunOptions {
            algorithm: OptionsAlgorithm::Mhaco,
            ker: m.ker,
            n_gen_mark: m.n_gen_mark,
            mhaco_constraints: m.mhaco_constraints,
            ..base
        },
    }
}

/// Default of `--generations` (the library's).
pub use crate::optim::spec::DEFAULT_GENERATIONS;

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
    ReferenceText(#[from] crate::optim::reference::ReferenceArgError),
    /// A flag or subcommand the problem does not take (the re-entry problems fix some
    /// settings; a variable-length problem runs with SCEA or MHACO only).
    #[error("command line: {what} does not apply to --problem {problem}: {why}")]
    NotForProblem {
        /// The flag or subcommand given.
        what: String,
        /// Problem asked for.
        problem: String,
        /// What to change.
        why: &'static str,
    },
    /// `--threads` 0 or above 1024, or the pool could not be built.
    #[error("command line: --threads: {0}")]
    Threads(#[from] ThreadsError),
    /// `--evaluations` with an algorithm that does not take it, or below the initial
    /// population.
    #[error("command line: --evaluations {evaluations}: {why}")]
    Evaluations {
        /// Budget given.
        evaluations: u64,
        /// What to change.
        why: String,
    },
    /// An algorithm subcommand beside `--config` or `--resume`.
    #[error(
        "command line: `optimize {algorithm}` with --config or --resume: the run file decides the algorithm and its settings; drop the subcommand and its flags (or set them in the file)"
    )]
    AlgorithmInFile {
        /// The subcommand given.
        algorithm: &'static str,
    },
    /// The optimiser refused its settings or an evaluation failed.
    #[error("command line: {0}")]
    Optim(#[from] OptimError),
    /// The run's report could not be made.
    #[error(transparent)]
    RunReport(#[from] crate::optim::run::RunReportError),
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

/// The checks clap cannot make, in one place: an algorithm subcommand beside a run file
/// (`--config`, `--resume`: the file decides), the flags a problem does not take (the
/// re-entry problems fix MOEA/D's variation and resource allocation, MHACO's ker and
/// schedule, and count generations; a variable-length problem runs with SCEA or MHACO only:
/// [`RunOptions::variable_length_spec`]).
pub(super) fn check(a: &OptimizeArgs, o: &RunOptions) -> Result<(), OptimizeError> {
    let algorithm = a.algorithm_name();
    if a.algorithm.is_some() && (a.config.is_some() || a.resume.is_some()) {
        return Err(OptimizeError::AlgorithmInFile { algorithm });
    }
    let not_for = |what: String, why| OptimizeError::NotForProblem {
        what,
        problem: a.problem.clone(),
        why,
    };
    if wants_reentry(a) {
        if let Some(flag) = crate::design::run::fixed_on_reentry(o, a.evaluations) {
            return Err(not_for(flag.into(), crate::design::run::FIXED_ON_REENTRY));
        }
    } else if crate::optim::problems::Vlmop::by_name(&a.problem).is_some()
        && o.variable_length_spec().is_none()
    {
        return Err(not_for(
            format!("`optimize {algorithm}`"),
            crate::optim::variable_length_run::VARIABLE_LENGTH_ALGORITHMS,
        ));
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

/// Print the summary line and, with `--out`, write the run directory.
pub(super) fn finish(
    a: &OptimizeArgs,
    report: &crate::optim::run::RunReport<'_>,
    out: &mut dyn std::io::Write,
) -> Result<(), OptimizeError> {
    writeln!(out, "{}", report.summary.line())?;
    if let Some(dir) = &a.out {
        crate::report::write_run_report(dir, report)?;
        writeln!(out, "wrote {}", dir.display())?;
    }
    Ok(())
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
    use super::*;

    use super::super::optimize_variants_tests::parse_flags as parse;

    /// The library's `RunOptions` defaults are the command line's (the Python front end
    /// relies on them), and every flag of every subcommand reaches its field.
    #[test]
    fn run_options_defaults_and_fields_are_the_flags() {
        assert_eq!(run_options(&parse(&[])), RunOptions::default());
        assert_eq!(run_options(&parse(&["moead"])), RunOptions::default());
        let decomposition = [
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
        ];
        let moead = RunOptions {
            population: 24,
            weights: WeightGeneration::Random,
            neighbours: Some(5),
            mutation_probability: Some(0.25),
            batch_size: 3,
            archive: Some(7),
            resource_allocation: true,
            ..RunOptions::default()
        };
        let flags = |sub: &str, extra: &[&'static str]| {
            let mut v = vec![sub];
            v.extend(decomposition);
            v.extend(extra);
            parse(&v)
        };
        let a = flags("scea", &["--scea-genes", "random"]);
        assert_eq!(
            run_options(&a),
            RunOptions {
                algorithm: OptionsAlgorithm::Scea,
                scea_genes: NewGenes::Random,
                ..moead.clone()
            }
        );
        let a = flags("scea", &["--scea-genes", "history"]);
        assert_eq!(run_options(&a).scea_genes, NewGenes::Population);
        let a = flags("moead", &["--moead-operator", "sbx"]);
        assert_eq!(
            run_options(&a),
            RunOptions {
                moead_operator: MoeadOperator::Sbx,
                ..moead
            }
        );
        let nsga2 = parse(&["nsga2", "--archive", "4"]);
        assert_eq!(
            (run_options(&nsga2).algorithm, run_options(&nsga2).archive),
            (OptionsAlgorithm::Nsga2, Some(4))
        );
        // The common flags before or after the subcommand.
        let a = parse(&[
            "--population",
            "24",
            "mhaco",
            "--ker",
            "9",
            "--n-gen-mark",
            "2",
            "--mhaco-constraints",
            "objectives",
            "--seed",
            "5",
        ]);
        assert_eq!((a.algorithm_name(), a.seed), ("mhaco", 5));
        let o = run_options(&a);
        assert_eq!(
            o,
            RunOptions {
                algorithm: OptionsAlgorithm::Mhaco,
                population: 24,
                ker: Some(9),
                n_gen_mark: 2,
                mhaco_constraints: MhacoConstraints::Objectives,
                ..RunOptions::default()
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
