//! The re-entry design runs ([`super`]'s problems under the generic optimisers of
//! [`crate::optim`]): the run file ([`ReentryRunConfig`], config.toml) and its checks, the
//! algorithm it names, and the run directory: config.toml, checkpoint.json written atomically
//! after every generation, per-generation records and populations, the final front with one
//! scenario file per member, plots ([`files`]). A run resumed from its directory
//! ([`run`] with `resume`) continues from its last checkpoint to the same final front as an
//! uninterrupted run. `host-sim optimize` maps its flags to a [`ReentryRunConfig`] and
//! prints; everything else is here.

pub mod files;
mod progress;
#[cfg(test)]
mod tests;

pub use progress::ProgressBar;

use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use self::files::{MemberFlights, write_final, write_generation};
use super::{
    DesignConfig, DesignError, ReentryProblem, RobustConfig, RobustProblem, VariableReentry,
    robust::read_nominal_front,
};
use crate::optim::chromosome::Chromosome;
use crate::optim::run::{Checkpoint, Record, check_records, record_of};
use crate::optim::spec::{MhacoConstraints, MoeadOperator, OptionsAlgorithm, RunOptions};
use crate::optim::{
    Algorithm, AlgorithmSpec, BatchEvaluator, Budget, BuiltAlgorithm, ChromosomeAlgorithm,
    ConstraintHandling, Executor, Individual, MhacoConfig, MoeadConfig, NewGenes, Nsga2Config,
    OptimError, Problem, RealAlgorithm, SceaConfig, Stop, Threads,
};
use crate::report::{ReportError, write_atomic};
use crate::scenario::Scenario;

/// A re-entry optimisation run: algorithm settings and the problem (file units).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReentryRunConfig {
    /// `moead`, `nsga2`, `scea` (variable length: 4 to `problem.encoding.nodes` nodes),
    /// `mhaco` (feasible candidates first) or `mhaco-objectives` (MHACO with the constraints
    /// as extra objectives, the thesis' sec. 9.3.2: `c / c_max` capped at 2, 0.5 added to
    /// every objective per violated constraint).
    pub algorithm: String,
    /// Population size.
    pub population: usize,
    /// Generations after the initial population.
    pub generations: u64,
    /// Seed.
    pub seed: u64,
    /// Evaluation threads (the result does not depend on it).
    pub threads: usize,
    /// MOEA/D offspring per batch (1: pagmo's steady state; larger: parallel evaluation).
    pub batch_size: usize,
    /// MOEA/D neighbourhood size (thesis: 20).
    pub neighbours: usize,
    /// MOEA/D replacement limit (thesis: 1).
    pub limit: usize,
    /// MOEA/D per-variable mutation probability (thesis: 1 / population; default
    /// 1 / variables).
    pub mutation_probability: Option<f64>,
    /// SCEA: source of the genes of appended nodes, `random` (the thesis) or `population`
    /// (history-based, the thesis' recommendation sec. 10.2; the default, also for files
    /// written before the field existed).
    #[serde(default = "history_genes")]
    pub scea_genes: NewGenes,
    /// MOEA/D, NSGA-II and SCEA: capacity of the external archive of the feasible
    /// non-dominated solutions found during the run (Zhang & Li 2007's external population,
    /// hypervolume truncation; not in pagmo), whose front is then the run's front (front.csv,
    /// the member scenarios, the recorded front and hypervolume). Absent (default): pagmo's
    /// semantics, the final population's front.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub archive: Option<usize>,
    /// Hypervolume reference point `[f_r, f_Q]` (objective units).
    pub reference: Vec<f64>,
    /// The design problem.
    pub problem: DesignConfig,
    /// Robust design ([`super::RobustProblem`]): every candidate judged by a dispersion
    /// campaign of the base scenario's guidance stack, its objectives and constraint from the
    /// campaign's statistics (then `problem.limits` and `problem.objectives` are not used and
    /// must be left out). Absent: the nominal problem.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub robust: Option<RobustConfig>,
}

impl ReentryRunConfig {
    /// The run file's algorithm and its settings as the library's one specification
    /// ([`AlgorithmSpec`]): `moead`, `scea` (MOEA/D's settings and `scea_genes`), `nsga2`,
    /// `mhaco` (feasible candidates first), `mhaco-objectives` (the constraints as extra
    /// objectives, the thesis' normalisation: the problem's constraints are already
    /// `c / c_max - 1`, scale 1, cap 2, penalty 0.5). MHACO's archive is min(63, population).
    #[must_use]
    pub fn algorithm_spec(&self) -> AlgorithmSpec {
        match self.algorithm.as_str() {
            "nsga2" => AlgorithmSpec::Nsga2(Nsga2Config {
                population: self.population,
                archive: self.archive,
                ..Nsga2Config::default()
            }),
            "mhaco" | "mhaco-objectives" => AlgorithmSpec::Mhaco(MhacoConfig {
                population: self.population,
                ker: self.population.min(MhacoConfig::default().ker),
                constraints: if self.algorithm == "mhaco" {
                    ConstraintHandling::FeasibilityFirst
                } else {
                    ConstraintHandling::AsObjectives {
                        scales: None,
                        cap: 2.0,
                        penalty: 0.5,
                    }
                },
                ..MhacoConfig::default()
            }),
            "scea" => AlgorithmSpec::Scea(SceaConfig {
                moead: self.moead_config(),
                new_genes: self.scea_genes,
                ..SceaConfig::default()
            }),
            _ => AlgorithmSpec::Moead(self.moead_config()),
        }
    }

    /// The MOEA/D settings of `moead` and `scea`.
    fn moead_config(&self) -> MoeadConfig {
        MoeadConfig {
            population: self.population,
            neighbours: self.neighbours,
            limit: self.limit,
            mutation_probability: self.mutation_probability,
            batch_size: self.batch_size,
            archive: self.archive,
            ..MoeadConfig::default()
        }
    }

    /// The run directory a run of this file writes when none is named:
    /// `runs/optimize-<problem.base>` (relative to the working directory).
    #[must_use]
    pub fn default_dir(&self) -> PathBuf {
        PathBuf::from(format!("runs/optimize-{}", self.problem.base))
    }

    /// The number of objectives: the robust statistics', or the design problem's (2, or 3
    /// with the skips).
    #[must_use]
    pub fn objective_count(&self) -> usize {
        match &self.robust {
            Some(r) => r.objectives.len(),
            None => 2 + usize::from(self.problem.objectives.skips),
        }
    }
}

fn history_genes() -> NewGenes {
    NewGenes::Population
}

impl ReentryRunConfig {
    /// The thesis' settings (sec. 9.1) on a preset problem.
    ///
    /// # Errors
    /// [`DesignError::UnknownPreset`].
    pub fn thesis(preset: &str) -> Result<Self, DesignError> {
        let problem = DesignConfig::preset(preset)?;
        let m = 2 + usize::from(problem.objectives.skips);
        let mut reference = vec![0.0, 2.0];
        reference.resize(m, 10.0);
        Ok(Self {
            algorithm: "moead".into(),
            population: 64,
            generations: 128,
            seed: 123,
            threads: 1,
            batch_size: 1,
            neighbours: 20,
            limit: 1,
            mutation_probability: Some(1.0 / 64.0),
            scea_genes: history_genes(),
            archive: None,
            reference,
            problem,
            robust: None,
        })
    }
}

/// The run settings `host-sim optimize` takes as flags on a preset problem: the algorithm's
/// ([`RunOptions`], the flags' mapping shared with the test problems) and the run's. Serde:
/// the flags' names; missing fields take the flags' defaults, unknown fields are refused.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunFlags {
    /// `--problem`: a preset ([`super::PRESETS`]).
    pub preset: String,
    /// The algorithm flags (the re-entry problems take MOEA/D's DE without resource
    /// allocation, MHACO's default `ker` and `n_gen_mark`: the CLI refuses the others).
    #[serde(default)]
    pub options: RunOptions,
    /// `--generations` (default [`crate::optim::spec::DEFAULT_GENERATIONS`]).
    #[serde(default = "default_generations")]
    pub generations: u64,
    /// `--seed` (default 1).
    #[serde(default = "one")]
    pub seed: u64,
    /// `--threads` (default 1).
    #[serde(default = "one_thread")]
    pub threads: usize,
    /// `--ref` (default: the preset's, [`ReentryRunConfig::thesis`]).
    #[serde(default)]
    pub reference: Option<Vec<f64>>,
    /// `--evaluations`: refused ([`fixed_on_reentry`]: the re-entry runs count generations).
    #[serde(default)]
    pub evaluations: Option<u64>,
}

pub use super::FIXED_ON_REENTRY;

/// The first algorithm flag in `o` (or `--evaluations`, when given) that the re-entry
/// problems fix (they run MOEA/D's DE without resource allocation and MHACO's default `ker`
/// and `n_gen_mark`, and count generations), if any: the one check of it, for the CLI,
/// Python and [`ReentryRunConfig::of_flags`].
#[must_use]
pub fn fixed_on_reentry(o: &RunOptions, evaluations: Option<u64>) -> Option<&'static str> {
    [
        (o.resource_allocation, "--resource-allocation"),
        (
            o.moead_operator != MoeadOperator::De,
            "--moead-operator sbx",
        ),
        (o.ker.is_some(), "--ker"),
        (
            o.n_gen_mark != MhacoConfig::default().n_gen_mark,
            "--n-gen-mark",
        ),
        (evaluations.is_some(), "--evaluations"),
    ]
    .into_iter()
    .find_map(|(given, flag)| given.then_some(flag))
}

fn default_generations() -> u64 {
    crate::optim::spec::DEFAULT_GENERATIONS
}

fn one() -> u64 {
    1
}

fn one_thread() -> usize {
    1
}

impl ReentryRunConfig {
    /// The run file of `host-sim optimize`'s flags on a preset problem (what
    /// `--print-config` prints): the thesis' settings ([`ReentryRunConfig::thesis`]) with
    /// the flags over them; `mhaco` with `mhaco_constraints = objectives` is
    /// `mhaco-objectives`.
    ///
    /// # Errors
    /// [`DesignError::UnknownPreset`]; [`DesignError::FixedOnReentry`] for a flag the
    /// re-entry problems fix ([`fixed_on_reentry`]).
    pub fn of_flags(f: &RunFlags) -> Result<Self, DesignError> {
        let mut c = Self::thesis(&f.preset)?;
        let o = &f.options;
        if let Some(flag) = fixed_on_reentry(o, f.evaluations) {
            return Err(DesignError::FixedOnReentry { flag });
        }
        c.algorithm = match (o.algorithm, o.mhaco_constraints) {
            (OptionsAlgorithm::Mhaco, MhacoConstraints::Objectives) => "mhaco-objectives".into(),
            (a, _) => a.as_str().into(),
        };
        c.population = o.population;
        c.generations = f.generations;
        c.seed = f.seed;
        c.threads = f.threads;
        c.batch_size = o.batch_size;
        c.neighbours = o.moead_config().neighbours;
        c.mutation_probability = o.mutation_probability;
        c.scea_genes = o.scea_genes;
        c.archive = o.archive;
        if let Some(r) = &f.reference {
            c.reference.clone_from(r);
        }
        Ok(c)
    }

    /// The run file's text (TOML), as config.toml and `--print-config` write it.
    ///
    /// # Errors
    /// [`ReentryError::Parse`] naming `name` if the settings cannot be written as TOML.
    pub fn to_toml(&self, name: &str) -> Result<String, ReentryError> {
        toml::to_string(self).map_err(|e| ReentryError::Parse {
            path: PathBuf::from(name),
            message: e.to_string(),
        })
    }
}

/// Failures of a re-entry run; each names the field or file and what to change.
#[derive(Debug, thiserror::Error)]
pub enum ReentryError {
    /// The problem could not be built.
    #[error(transparent)]
    Design(#[from] DesignError),
    /// A bad setting.
    #[error("{source_name}: field `{field}` = {value}: {reason}")]
    Setting {
        /// Command line or file.
        source_name: String,
        /// Field.
        field: &'static str,
        /// Value.
        value: String,
        /// What to change.
        reason: String,
    },
    /// A file could not be read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// Cause.
        source: std::io::Error,
    },
    /// A TOML file is not valid TOML.
    #[error("{}: {source}", path.display())]
    Toml {
        /// The file.
        path: PathBuf,
        /// The parser's error (line, column, offending text).
        source: crate::toml_input::TomlSyntax,
    },
    /// A field of a TOML file is unknown, missing or of the wrong type.
    #[error("{}: field `{field}` = {value}: {reason}", path.display())]
    Field {
        /// The file.
        path: PathBuf,
        /// Dotted path of the field.
        field: String,
        /// Its value as written, or `(missing)`.
        value: String,
        /// What is wrong.
        reason: String,
    },
    /// A JSON file is malformed, or a configuration cannot be printed as TOML.
    #[error("{path}: {message}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// Parser message (with the field).
        message: String,
    },
    /// The run directory cannot be written.
    #[error("run directory {path}: cannot write: {source}; choose a writable --out")]
    RunDir {
        /// The directory.
        path: PathBuf,
        /// Cause.
        source: std::io::Error,
    },
    /// The optimiser refused its settings or failed.
    #[error("optimiser: {0}")]
    Optim(#[from] OptimError),
    /// An evaluation failed outright.
    #[error("evaluation: {0}")]
    Eval(#[from] crate::optim::EvalError),
    /// Output could not be written.
    #[error(transparent)]
    Report(#[from] ReportError),
    /// The console could not be written.
    #[error("cannot write output: {0}")]
    Io(#[from] std::io::Error),
    /// Ctrl-C: the run stopped at a generation boundary without a final file.
    #[error(
        "stopped before generation {generation} (Ctrl-C); the checkpoint of the last complete \
         generation is kept in {}: continue with --resume",
        dir.display()
    )]
    Interrupted {
        /// The generation that was not completed.
        generation: u64,
        /// The run directory.
        dir: PathBuf,
    },
}

fn read_text(path: &Path) -> Result<String, ReentryError> {
    std::fs::read_to_string(path).map_err(|source| ReentryError::Read {
        path: path.to_path_buf(),
        source,
    })
}

/// A run configuration file (config.toml, `--config`), read through host-sim's one TOML reading path
/// ([`crate::toml_input`]): errors name the file, the field and the value as written.
///
/// # Errors
/// [`ReentryError`] naming the file and the field.
pub fn parse_toml(path: &Path) -> Result<ReentryRunConfig, ReentryError> {
    parse_text(&read_text(path)?, path)
}

/// [`parse_toml`] of the text of `path`.
fn parse_text(text: &str, path: &Path) -> Result<ReentryRunConfig, ReentryError> {
    use crate::toml_input::TomlInputError;
    match crate::toml_input::parse(text) {
        Ok((c, _)) => Ok(c),
        Err(TomlInputError::Syntax(source)) => Err(ReentryError::Toml {
            path: path.to_path_buf(),
            source,
        }),
        Err(TomlInputError::Field {
            field,
            value,
            reason,
        }) => Err(ReentryError::Field {
            path: path.to_path_buf(),
            field,
            value,
            reason,
        }),
    }
}

/// A run configuration as `optimize --config FILE` reads it before its run: `text` parsed as
/// the file `path`, its settings checked, its design problem built (a base scenario file
/// relative to `path`'s folder). The input fuzzer's entry point
/// (`host-sim/examples/fuzz_inputs.rs`).
///
/// # Errors
/// [`ReentryError`] naming the file, the field and the value.
pub fn check_run_config(text: &str, path: &Path) -> Result<ReentryRunConfig, ReentryError> {
    let c = parse_text(text, path)?;
    check(&c, &path.display().to_string())?;
    let dir = path.parent().unwrap_or(Path::new("."));
    c.problem.problem(dir)?;
    // The robust settings are checked against the base's stack (no flight needed).
    if let Some(r) = c.robust.as_ref().filter(|r| !r.settings.is_empty()) {
        let stack = c.problem.stack_scenario(dir)?;
        super::robust_settings::StackSettings::new(&stack, &r.settings, &c.problem.base).map_err(
            |e| DesignError::Toml {
                label: path.display().to_string(),
                message: e.to_string(),
            },
        )?;
    }
    Ok(c)
}

/// Check a run configuration read from `src` (a file or the command line).
///
/// # Errors
/// [`ReentryError::Setting`] naming `src`, the field and the value.
pub fn check(c: &ReentryRunConfig, src: &str) -> Result<(), ReentryError> {
    let bad = |field, value: String, reason: String| {
        Err(ReentryError::Setting {
            source_name: src.to_string(),
            field,
            value,
            reason,
        })
    };
    if !matches!(
        c.algorithm.as_str(),
        "moead" | "nsga2" | "scea" | "mhaco" | "mhaco-objectives"
    ) {
        return bad(
            "algorithm",
            c.algorithm.clone(),
            "use moead, nsga2, scea, mhaco or mhaco-objectives".into(),
        );
    }
    if c.population > crate::optim::algorithms::MAX_POPULATION {
        return bad(
            "population",
            c.population.to_string(),
            "use at most 100000".into(),
        );
    }
    if c.threads == 0 || c.threads > crate::optim::evaluate::MAX_THREADS {
        return bad("threads", c.threads.to_string(), "use 1 to 1024".into());
    }
    if let Some(p) = c.mutation_probability
        && !(p > 0.0 && p <= 1.0)
    {
        return bad(
            "mutation_probability",
            crate::num_fmt::compact(p),
            "use a probability in (0, 1]".into(),
        );
    }
    match c.archive {
        Some(0) => {
            return bad(
                "archive",
                "0".into(),
                "the archive's capacity must be at least 1 (or leave the field out)".into(),
            );
        }
        Some(n) if c.algorithm.starts_with("mhaco") => {
            return bad(
                "archive",
                n.to_string(),
                format!(
                    "applies to moead, nsga2 and scea, not {}; leave it out",
                    c.algorithm
                ),
            );
        }
        _ => {}
    }
    if let Some(r) = &c.robust {
        if c.algorithm == "scea" {
            return bad(
                "algorithm",
                c.algorithm.clone(),
                "a robust run flies fixed-length profiles: use moead, nsga2, mhaco or \
                 mhaco-objectives"
                    .into(),
            );
        }
        r.validate()?;
    }
    let m = c.objective_count();
    if c.reference.len() != m || !c.reference.iter().all(|v| v.is_finite()) {
        return bad(
            "reference",
            format!("{:?}", c.reference),
            format!("give {m} finite values (one per objective)"),
        );
    }
    if c.robust.is_none()
        && c.problem.objectives.target_range_deg.is_some()
        && c.reference[0] <= 0.0
    {
        return bad(
            "reference",
            format!("{:?}", c.reference),
            "with objectives.target_range_deg the first objective is a miss distance >= 0: \
             give a first value > 0 (e.g. 1)"
                .into(),
        );
    }
    Ok(())
}

/// What a run reports while it goes: the generations to make (the initial population
/// included) and those done already (a resumed run), then each generation's record once its
/// checkpoint is written, and the end of the evolution (before the final files). Every
/// method defaults to nothing.
pub trait Progress {
    /// The run makes `total` generations records, `done` of them already (resumed).
    fn start(&mut self, total: u64, done: u64) {
        let _ = (total, done);
    }
    /// A generation is complete and checkpointed.
    fn record(&mut self, record: &Record) {
        let _ = record;
    }
    /// The evolution reached its budget (the final files follow).
    fn finish(&mut self) {}
}

/// No progress reports.
impl Progress for () {}

/// The end of a complete run.
#[derive(Clone, Debug, PartialEq)]
pub struct Finished {
    /// The last generation's record (`None`: no generation was recorded).
    pub last: Option<Record>,
    /// Wall time of the evolution in this process \[s\].
    pub wall_time_s: f64,
}

/// The run file of the run in `dir` (its config.toml), for [`run`] with `resume`: its own
/// generation total, or `generations` when given (a resumed run may be extended).
///
/// # Errors
/// [`ReentryError`] naming config.toml, the field and the value.
pub fn resumed_config(
    dir: &Path,
    generations: Option<u64>,
) -> Result<ReentryRunConfig, ReentryError> {
    let mut c = parse_toml(&dir.join("config.toml"))?;
    if let Some(g) = generations {
        c.generations = g;
    }
    Ok(c)
}

/// Run `c` (read from `src`, a file name or "command line", for the error messages) in the
/// run directory `dir`: a new run (`resume` false) replaces a previous run there and writes
/// config.toml; a resumed run continues from `dir`'s checkpoint (from the start when it has
/// none). A base scenario file of the problem is relative to `base_dir`. Ctrl-C stops the run
/// at the next generation boundary ([`ReentryError::Interrupted`]).
///
/// The batches are evaluated on the run file's `threads`, or by `external` when given (a
/// front end's evaluator, e.g. the Python package's over a Dask cluster; the threads then fly
/// only the chosen front members' reports at the end). The run directory, its checkpoints and
/// its result are the same either way when `external` returns the problem's own evaluations;
/// a run started one way resumes the other. `external` takes fixed-length runs only: the
/// decisions it gets are the genes (`x` of the design problem, or of the robust problem with
/// `[robust]`).
///
/// # Errors
/// [`ReentryError`] naming the file, field and value, or the directory;
/// [`ReentryError::Setting`] for `algorithm = "scea"` with `external`.
pub fn run(
    c: &ReentryRunConfig,
    src: &str,
    dir: &Path,
    resume: bool,
    base_dir: &Path,
    progress: &mut dyn Progress,
    external: Option<&dyn BatchEvaluator<Vec<f64>>>,
) -> Result<Finished, ReentryError> {
    check(c, src)?;
    if external.is_some() && c.algorithm_spec().is_chromosome() {
        return Err(ReentryError::Setting {
            source_name: src.to_string(),
            field: "algorithm",
            value: c.algorithm.clone(),
            reason: "a variable-length run evaluates in this process (on `threads`); an \
                     external evaluator (Dask) takes the fixed-length algorithms moead, \
                     nsga2, mhaco, mhaco-objectives"
                .into(),
        });
    }
    let problem = c.problem.problem(base_dir)?;
    // A robust problem is built (its base's campaign set up) before the directory is touched.
    let robust = match &c.robust {
        Some(r) => {
            let stack = c.problem.stack_scenario(base_dir)?;
            // Its setting errors name the run file too.
            let p = RobustProblem::new(problem.clone(), stack, r.clone(), &c.problem.base)
                .map_err(|e| match e {
                    e @ DesignError::Robust { .. } => DesignError::Toml {
                        label: src.to_string(),
                        message: e.to_string(),
                    },
                    e => e,
                })?;
            Some(p)
        }
        None => None,
    };
    // So is the nominal front it is compared with read.
    let nominal_front = match c.robust.as_ref().and_then(|r| r.nominal_front.as_ref()) {
        Some(f) => {
            let front = read_nominal_front(&base_dir.join(f), problem.encoding().dim())?;
            // Its members fly the base's own values of the robust settings.
            match &robust {
                Some(p) => front.iter().map(|x| p.with_base_settings(x)).collect(),
                None => front,
            }
        }
        None => Vec::new(),
    };
    // And are the algorithm's settings checked against the problem's shape.
    let spec = c.algorithm_spec();
    let constraints = robust
        .as_ref()
        .map_or_else(|| problem.constraints(), Problem::constraints);
    spec.check(c.objective_count(), constraints)
        .map_err(|e| ReentryError::Setting {
            source_name: src.to_string(),
            field: "algorithm",
            value: c.algorithm.clone(),
            reason: e.to_string(),
        })?;
    if !resume {
        // A new run: never into a directory that is not a run; a previous run there is
        // removed whole (no population or front file of it is left beside the new run's).
        crate::report::begin_in_place(dir).map_err(|e| match e {
            ReportError::Io { path, source } => ReentryError::RunDir { path, source },
            e => e.into(),
        })?;
    }
    std::fs::create_dir_all(dir.join("population")).map_err(|source| ReentryError::RunDir {
        path: dir.to_path_buf(),
        source,
    })?;
    if !resume {
        // The file paths of the run file are written absolute, so the run resumes from any
        // working directory (`run` with `resume` reads its base from config.toml).
        let mut written = c.clone();
        written.problem = c.problem.anchored(base_dir);
        if let Some(r) = written.robust.as_mut()
            && let Some(f) = r.nominal_front.as_mut()
            && let Ok(p) = std::path::absolute(base_dir.join(&*f))
        {
            *f = p.display().to_string();
        }
        let text = written.to_toml(&dir.join("config.toml").display().to_string())?;
        write_atomic(&dir.join("config.toml"), text.as_bytes())?;
    }
    let pool = Threads::new(c.threads).map_err(|e| ReentryError::Setting {
        source_name: src.to_string(),
        field: "threads",
        value: c.threads.to_string(),
        reason: e.to_string(),
    })?;
    if spec.is_chromosome() {
        let nodes = [4.min(c.problem.encoding.nodes), c.problem.encoding.nodes];
        let vproblem = VariableReentry::new(problem, nodes)?;
        let ctx = Ctx {
            c,
            dir,
            problem: &vproblem,
            pool,
            resume,
            nominal_front: &nominal_front,
            external: None,
        };
        return drive_variable(&ctx, spec, progress);
    }
    if let Some(robust) = robust {
        let ctx = Ctx {
            c,
            dir,
            problem: &robust,
            pool,
            resume,
            nominal_front: &nominal_front,
            external,
        };
        return drive_fixed(&ctx, spec, progress);
    }
    let ctx = Ctx {
        c,
        dir,
        problem: &problem,
        pool,
        resume,
        nominal_front: &nominal_front,
        external,
    };
    drive_fixed(&ctx, spec, progress)
}

/// [`drive`] with the variable-length algorithm the run file names (its checkpoint holds the
/// algorithm's own state, as [`drive_fixed`]'s).
fn drive_variable(
    ctx: &Ctx<'_, VariableReentry>,
    spec: AlgorithmSpec,
    progress: &mut dyn Progress,
) -> Result<Finished, ReentryError> {
    match spec.build(ctx.c.seed) {
        BuiltAlgorithm::Chromosome(ChromosomeAlgorithm::Scea(a)) => drive(ctx, a, progress),
        BuiltAlgorithm::Chromosome(ChromosomeAlgorithm::VlMhaco(a)) => drive(ctx, a, progress),
        BuiltAlgorithm::Real(_) => Err(not_this_length(ctx.c, "a variable-length")),
    }
}

/// The run file's algorithm does not fly `problem` (a variable- or fixed-length problem):
/// the dispatch above picks the problem by the algorithm, so this is never reached by a
/// checked run file, and says so rather than panicking if it is.
fn not_this_length(c: &ReentryRunConfig, problem: &str) -> ReentryError {
    ReentryError::Setting {
        source_name: "run file".into(),
        field: "algorithm",
        value: c.algorithm.clone(),
        reason: format!("does not run on {problem} problem"),
    }
}

/// [`drive`] with the fixed-length algorithm the run file names.
fn drive_fixed<P>(
    ctx: &Ctx<'_, P>,
    spec: AlgorithmSpec,
    progress: &mut dyn Progress,
) -> Result<Finished, ReentryError>
where
    P: RunProblem<Decision = Vec<f64>> + crate::optim::RealProblem,
{
    match spec.build(ctx.c.seed) {
        BuiltAlgorithm::Real(RealAlgorithm::Moead(a)) => drive(ctx, a, progress),
        BuiltAlgorithm::Real(RealAlgorithm::MoeadSbx(a)) => drive(ctx, a, progress),
        BuiltAlgorithm::Real(RealAlgorithm::Nsga2(a)) => drive(ctx, a, progress),
        BuiltAlgorithm::Real(RealAlgorithm::Mhaco(a)) => drive(ctx, a, progress),
        BuiltAlgorithm::Chromosome(_) => Err(not_this_length(ctx.c, "a fixed-length")),
    }
}

/// What the run directory needs of a design problem's decisions: their genes as a flat row
/// and the scenario they fly.
pub trait RunProblem: Problem {
    /// The decision's genes, flat (a variable-length decision gives a shorter row).
    fn genes(d: &Self::Decision) -> Vec<f64>;
    /// The scenario the decision flies.
    fn scenario(&self, d: &Self::Decision) -> Option<Scenario>;
    /// The fixed-length problem (its simulator flies the chosen front members).
    fn reentry(&self) -> &ReentryProblem;
    /// The robust problem whose campaign the chosen front members fly again for their
    /// report (`None`: a nominal problem).
    fn robust(&self) -> Option<&RobustProblem> {
        None
    }
}

impl RunProblem for ReentryProblem {
    fn genes(d: &Vec<f64>) -> Vec<f64> {
        d.clone()
    }
    fn scenario(&self, d: &Vec<f64>) -> Option<Scenario> {
        self.scenario_of(d).ok()
    }
    fn reentry(&self) -> &ReentryProblem {
        self
    }
}

impl RunProblem for RobustProblem {
    fn genes(d: &Vec<f64>) -> Vec<f64> {
        d.clone()
    }
    fn scenario(&self, d: &Vec<f64>) -> Option<Scenario> {
        self.scenario_of(d).ok()
    }
    fn reentry(&self) -> &ReentryProblem {
        self.inner()
    }
    fn robust(&self) -> Option<&RobustProblem> {
        Some(self)
    }
}

impl RunProblem for VariableReentry {
    fn genes(d: &Chromosome) -> Vec<f64> {
        d.fixed
            .iter()
            .chain(d.legs.iter().flatten().flatten())
            .copied()
            .collect()
    }
    fn scenario(&self, d: &Chromosome) -> Option<Scenario> {
        let (table, h) = self.table_of(d).ok()?;
        Some(self.inner().scenario_of_table(table, h))
    }
    fn reentry(&self) -> &ReentryProblem {
        self.inner()
    }
}

fn flat<P: RunProblem>(pop: &[Individual<P::Decision>]) -> Vec<Individual<Vec<f64>>> {
    pop.iter()
        .map(|i| Individual {
            decision: P::genes(&i.decision),
            objectives: i.objectives.clone(),
            constraints: i.constraints.clone(),
            violation: i.violation,
        })
        .collect()
}

struct Ctx<'a, P: Problem> {
    c: &'a ReentryRunConfig,
    dir: &'a Path,
    problem: &'a P,
    pool: Threads,
    resume: bool,
    /// A robust run's nominal front to fly in its campaign at the end (`robust.nominal_front`).
    nominal_front: &'a [Vec<f64>],
    /// The front end's batch evaluator ([`run`]); `None`: the run's threads.
    external: Option<&'a dyn BatchEvaluator<P::Decision>>,
}

fn drive<P, A>(
    ctx: &Ctx<'_, P>,
    fresh: A,
    progress: &mut dyn Progress,
) -> Result<Finished, ReentryError>
where
    P: RunProblem,
    A: Algorithm<P> + Serialize + DeserializeOwned,
{
    let ck_path = ctx.dir.join("checkpoint.json");
    if ctx.resume {
        // Leftovers of a killed run (temporary files of atomic writes, a staged front).
        crate::report::clean_stale(ctx.dir);
        crate::report::clean_stale(&ctx.dir.join("population"));
    }
    // A run stopped before its first checkpoint (during the initial population) resumes
    // from the start.
    let resume = ctx.resume && ck_path.exists();
    let (alg, mut records) = if resume {
        let text = read_text(&ck_path)?;
        let mut de = serde_json::Deserializer::from_str(&text);
        let ck: Checkpoint<A> =
            serde_path_to_error::deserialize(&mut de).map_err(|e| ReentryError::Parse {
                path: ck_path.clone(),
                message: format!("field `{}`: {}", e.path(), e.inner()),
            })?;
        // A checkpoint that was edited or corrupted must not panic or run forever: the state
        // is checked against itself and the problem, and the records against the state.
        let invalid = |e: &dyn std::fmt::Display| ReentryError::Parse {
            path: ck_path.clone(),
            message: e.to_string(),
        };
        ck.algorithm
            .validate(ctx.problem)
            .map_err(|e| invalid(&e))?;
        check_records(&ck.records, &ck.algorithm, ctx.c.reference.len())
            .map_err(|e| invalid(&e))?;
        (ck.algorithm, ck.records)
    } else {
        (fresh, Vec::new())
    };
    let total = ctx.c.generations;
    progress.start(total + 1, records.len() as u64);
    let mut save = |alg: &A, records: &mut Vec<Record>| -> Result<(), ReentryError> {
        let pop = flat::<P>(alg.population());
        let result = alg.external_archive().map(flat::<P>);
        let rec = record_of(
            alg.generation(),
            alg.evaluations(),
            &pop,
            result.as_deref().unwrap_or(&pop),
            &ctx.c.reference,
        );
        progress.record(&rec);
        write_generation(ctx.dir, &pop, rec.generation)?;
        records.push(rec);
        let ck = Checkpoint {
            algorithm: alg,
            records: records.clone(),
        };
        let json = serde_json::to_string(&ck).map_err(ReportError::Json)?;
        write_atomic(&ck_path, json.as_bytes())?;
        Ok(())
    };
    // Ctrl-C asks the run to stop (it does not exit the process while this lives): a flight
    // it interrupts is no evaluation (`EvalError::Interrupted`), and the run stops at the next
    // generation boundary with the last complete generation's checkpoint and no final file.
    let _active = crate::sim::ActiveRun::start();
    let stop = crate::sim::stop_requested;
    let executor = Executor::new(ctx.problem, alg)
        .budget(Budget::Generations(ctx.c.generations))
        .threads(ctx.pool.clone())
        .stop_when(&stop);
    let executor = match ctx.external {
        Some(e) => executor.external(e),
        None => executor,
    };
    let run = executor.run_with(|alg: &A| save(alg, &mut records))?;
    let (alg, wall) = (run.algorithm, run.wall_time_s);
    if run.stop == Stop::Interrupted {
        return Err(ReentryError::Interrupted {
            generation: alg.generation() + u64::from(alg.is_initialised()),
            dir: ctx.dir.to_path_buf(),
        });
    }
    progress.finish();
    let last = records.last().cloned();
    // The front's members: the external archive's when the run keeps one.
    let scenarios: Vec<Option<Scenario>> = alg
        .result()
        .iter()
        .map(|i| ctx.problem.scenario(&i.decision))
        .collect();
    let members = MemberFlights {
        analytical: ctx.problem.reentry().analytical(),
        robust: ctx.problem.robust(),
        objectives: ctx.problem.reentry().objective_settings(),
        threads: &ctx.pool,
        nominal_front: ctx.nominal_front,
    };
    write_final(
        ctx.dir,
        &scenarios,
        &flat::<P>(alg.population()),
        &flat::<P>(alg.result()),
        &records,
        &ctx.c.problem.base,
        &members,
    )?;
    Ok(Finished {
        last,
        wall_time_s: wall,
    })
}
