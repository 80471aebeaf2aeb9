//! `host-sim optimize` on the re-entry design problems ([`crate::design`]): settings from
//! flags or a TOML file (`--config`, `--print-config` prints a template), a progress bar, a
//! run directory (config.toml, checkpoint.json written atomically after every generation,
//! per-generation records and populations, the final front with one scenario file per member,
//! plots) and `--resume DIR`, which continues a run from its last checkpoint to the same
//! final front as an uninterrupted run.

use std::io::Write;
use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use super::optimize_common::{MhacoConstraintsArg, OptimizeArgs};
pub use super::optimize_common::{ReentryError, ReentryRunConfig};
use super::optimize_reentry_out::{Record, record_of, write_final, write_generation};
use crate::design::{ReentryProblem, VariableReentry};
use crate::optim::chromosome::Chromosome;
use crate::optim::{
    Algorithm, Budget, ConstraintHandling, Executor, Individual, Mhaco, MhacoConfig, Moead,
    MoeadConfig, Nsga2, Nsga2Config, Problem, Scea, SceaConfig, Stop, Threads,
};
use crate::report::{ReportError, write_atomic};
use crate::scenario::Scenario;

fn read_text(path: &Path) -> Result<String, ReentryError> {
    std::fs::read_to_string(path).map_err(|source| ReentryError::Read {
        path: path.to_path_buf(),
        source,
    })
}

/// A run configuration file, read through host-sim's one TOML reading path
/// ([`crate::toml_input`]): errors name the file, the field and the value as written.
fn parse_toml(path: &Path) -> Result<ReentryRunConfig, ReentryError> {
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
/// relative to `path`'s folder). The input fuzzer's entry point (`host-sim/examples/fuzz_inputs.rs`).
///
/// # Errors
/// [`ReentryError`] naming the file, the field and the value.
pub fn check_run_config(text: &str, path: &Path) -> Result<ReentryRunConfig, ReentryError> {
    let c = parse_text(text, path)?;
    check(&c, &path.display().to_string())?;
    c.problem.problem(path.parent().unwrap_or(Path::new(".")))?;
    Ok(c)
}

/// `--FLAG VALUE` given for a re-entry problem, which fixes it.
fn flag_not_here(field: &'static str, value: String) -> ReentryError {
    ReentryError::Setting {
        source_name: "command line".into(),
        field,
        value,
        reason: "fixed on the re-entry problems (MHACO ker = min(63, population), n_gen_mark 7)"
            .into(),
    }
}

/// The run configuration of flags (a preset `--problem`) or `--config`.
fn config_of(a: &OptimizeArgs) -> Result<ReentryRunConfig, ReentryError> {
    if let Some(path) = &a.config {
        return parse_toml(path);
    }
    let mut c = ReentryRunConfig::thesis(&a.problem)?;
    // MHACO's archive size and schedule are fixed on the re-entry problems (the file has no
    // field for them): refuse the flags rather than ignore them.
    if let Some(k) = a.ker {
        return Err(flag_not_here("ker", k.to_string()));
    }
    if a.n_gen_mark != MhacoConfig::default().n_gen_mark {
        return Err(flag_not_here("n-gen-mark", a.n_gen_mark.to_string()));
    }
    c.algorithm = match (a.algorithm_name(), a.mhaco_constraints) {
        ("mhaco", MhacoConstraintsArg::Objectives) => "mhaco-objectives".into(),
        (name, _) => name.into(),
    };
    c.population = a.population;
    c.generations = a.generations;
    c.seed = a.seed;
    c.threads = a.threads;
    c.batch_size = a.batch_size;
    c.neighbours = a.neighbours();
    c.mutation_probability = a.mutation_probability;
    c.scea_genes = a.scea_genes.new_genes();
    c.archive = a.archive;
    if let Some(r) = &a.reference {
        c.reference.clone_from(r);
    }
    Ok(c)
}

fn check(c: &ReentryRunConfig, src: &str) -> Result<(), ReentryError> {
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
    let m = 2 + usize::from(c.problem.objectives.skips);
    if c.reference.len() != m || !c.reference.iter().all(|v| v.is_finite()) {
        return bad(
            "reference",
            format!("{:?}", c.reference),
            format!("give {m} finite values (one per objective)"),
        );
    }
    if c.problem.objectives.target_range_deg.is_some() && c.reference[0] <= 0.0 {
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

#[derive(Serialize, Deserialize)]
struct Checkpoint<A> {
    algorithm: A,
    records: Vec<Record>,
}

/// The flags given beside `--resume` (other than `--generations`), as `--flag`: the fields
/// of `a` that differ from the defaults.
fn flags_beside_resume(a: &OptimizeArgs) -> Vec<String> {
    use clap::{CommandFactory, FromArgMatches};
    #[derive(clap::Parser)]
    struct Defaults {
        #[command(flatten)]
        a: OptimizeArgs,
    }
    let Ok(m) = Defaults::command().try_get_matches_from(["optimize"]) else {
        return Vec::new();
    };
    let Ok(d) = Defaults::from_arg_matches(&m) else {
        return Vec::new();
    };
    // One line per top-level field in the pretty Debug form ("    name: value,"); nested
    // values are indented further and belong to the field above.
    let fields = |x: &OptimizeArgs| -> Vec<(String, String)> {
        let text = format!("{x:#?}");
        let mut out: Vec<(String, String)> = Vec::new();
        for line in text.lines().skip(1) {
            match line.strip_prefix("    ") {
                Some(l) if !l.starts_with(' ') => {
                    let (k, v) = l.split_once(':').unwrap_or((l, ""));
                    out.push((k.to_string(), v.to_string()));
                }
                _ => {
                    if let Some(last) = out.last_mut() {
                        last.1.push_str(line);
                    }
                }
            }
        }
        out
    };
    fields(a)
        .into_iter()
        .zip(fields(&d.a))
        .filter(|((k, v), (_, w))| v != w && k != "resume" && k != "generations")
        .map(|((k, _), _)| format!("--{}", k.replace('_', "-")))
        .collect()
}

/// Run `optimize` on a re-entry problem.
///
/// # Errors
/// [`ReentryError`].
pub(super) fn run(a: &OptimizeArgs, out: &mut dyn Write) -> Result<(), ReentryError> {
    if a.print_config {
        let c = config_of(a)?;
        let text = toml::to_string(&c).map_err(|e| ReentryError::Parse {
            path: PathBuf::from("(template)"),
            message: e.to_string(),
        })?;
        write!(out, "{text}")?;
        return Ok(());
    }
    let (mut c, dir, resume) = match &a.resume {
        Some(dir) => (parse_toml(&dir.join("config.toml"))?, dir.clone(), true),
        None => {
            let c = config_of(a)?;
            let dir = a
                .out
                .clone()
                .unwrap_or_else(|| PathBuf::from(format!("runs/optimize-{}", c.problem.base)));
            (c, dir, false)
        }
    };
    let src = match (&a.resume, &a.config) {
        (Some(d), _) => d.join("config.toml").display().to_string(),
        (None, Some(p)) => p.display().to_string(),
        (None, None) => "command line".to_string(),
    };
    if resume {
        let ignored = flags_beside_resume(a);
        if !ignored.is_empty() {
            return Err(ReentryError::Setting {
                source_name: "command line".into(),
                field: "resume",
                value: ignored.join(" "),
                reason: format!(
                    "a resumed run keeps the settings of {src}; only --generations may be given \
                     (to extend the run): drop the other flags"
                ),
            });
        }
    }
    if resume && a.generations_given() {
        // Resuming may extend the run (an interrupted run resumes to its own target).
        c.generations = a.generations;
    }
    check(&c, &src)?;
    let base_dir = a
        .config
        .as_deref()
        .and_then(Path::parent)
        .unwrap_or(Path::new("."))
        .to_path_buf();
    let problem = c.problem.problem(&base_dir)?;
    if !resume {
        // A new run: never into a directory that is not a run; a previous run there is
        // removed whole (no population or front file of it is left beside the new run's).
        crate::report::begin_in_place(&dir).map_err(|e| match e {
            ReportError::Io { path, source } => ReentryError::RunDir { path, source },
            e => e.into(),
        })?;
    }
    std::fs::create_dir_all(dir.join("population")).map_err(|source| ReentryError::RunDir {
        path: dir.clone(),
        source,
    })?;
    if !resume {
        let text = toml::to_string(&c).map_err(|e| ReentryError::Parse {
            path: dir.join("config.toml"),
            message: e.to_string(),
        })?;
        write_atomic(&dir.join("config.toml"), text.as_bytes())?;
    }
    let pool = Threads::new(c.threads).map_err(|e| ReentryError::Setting {
        source_name: src.clone(),
        field: "threads",
        value: c.threads.to_string(),
        reason: e.to_string(),
    })?;
    let moead = MoeadConfig {
        population: c.population,
        neighbours: c.neighbours,
        limit: c.limit,
        mutation_probability: c.mutation_probability,
        batch_size: c.batch_size,
        archive: c.archive,
        ..MoeadConfig::default()
    };
    if c.algorithm == "scea" {
        let nodes = [4.min(c.problem.encoding.nodes), c.problem.encoding.nodes];
        let vproblem = VariableReentry::new(problem, nodes)?;
        let ctx = Ctx {
            c: &c,
            dir: &dir,
            problem: &vproblem,
            pool,
            resume,
        };
        let cfg = SceaConfig {
            moead,
            new_genes: c.scea_genes,
            ..SceaConfig::default()
        };
        return drive(&ctx, Scea::new(cfg, c.seed), out);
    }
    let ctx = Ctx {
        c: &c,
        dir: &dir,
        problem: &problem,
        pool,
        resume,
    };
    match c.algorithm.as_str() {
        "nsga2" => {
            let cfg = Nsga2Config {
                population: c.population,
                archive: c.archive,
                ..Nsga2Config::default()
            };
            drive(&ctx, Nsga2::new(cfg, c.seed), out)
        }
        "mhaco" | "mhaco-objectives" => {
            let constraints = if c.algorithm == "mhaco" {
                ConstraintHandling::FeasibilityFirst
            } else {
                // The problem's constraints are already c / c_max - 1 (scale 1).
                ConstraintHandling::AsObjectives {
                    scales: None,
                    cap: 2.0,
                    penalty: 0.5,
                }
            };
            let cfg = MhacoConfig {
                population: c.population,
                ker: c.population.min(MhacoConfig::default().ker),
                constraints,
                ..MhacoConfig::default()
            };
            drive(&ctx, Mhaco::new(cfg, c.seed), out)
        }
        _ => drive(&ctx, Moead::new(moead, c.seed), out),
    }
}

/// What the run directory needs of a design problem's decisions: their genes as a flat row
/// and the scenario they fly.
trait RunProblem: Problem {
    /// The decision's genes, flat (a variable-length decision gives a shorter row).
    fn genes(d: &Self::Decision) -> Vec<f64>;
    /// The scenario the decision flies.
    fn scenario(&self, d: &Self::Decision) -> Option<Scenario>;
    /// The fixed-length problem (its simulator flies the chosen front members).
    fn reentry(&self) -> &ReentryProblem;
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

/// The records of a restored checkpoint: one per generation up to the state's, each with
/// the objectives' count of values.
fn check_records<P: Problem, A: Algorithm<P>>(
    records: &[Record],
    alg: &A,
    c: &ReentryRunConfig,
) -> Result<(), crate::optim::StateError> {
    use crate::optim::restore::{bad, count};
    let want = if alg.is_initialised() {
        alg.generation() + 1
    } else {
        0
    };
    count(
        "records.len()",
        records.len(),
        usize::try_from(want).unwrap_or(usize::MAX),
    )?;
    let m = c.reference.len();
    for (i, r) in records.iter().enumerate() {
        count(
            &format!("records[{i}].generation"),
            r.generation as usize,
            i,
        )?;
        count(&format!("records[{i}].best.len()"), r.best.len(), m)?;
        count(&format!("records[{i}].mean.len()"), r.mean.len(), m)?;
        if let Some(k) = r.front.iter().position(|f| f.len() != m) {
            return Err(bad(
                format!("records[{i}].front[{k}].len()"),
                r.front[k].len(),
                format!("must be {m}"),
            ));
        }
    }
    Ok(())
}

struct Ctx<'a, P> {
    c: &'a ReentryRunConfig,
    dir: &'a Path,
    problem: &'a P,
    pool: Threads,
    resume: bool,
}

fn drive<P, A>(ctx: &Ctx<'_, P>, fresh: A, out: &mut dyn Write) -> Result<(), ReentryError>
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
        check_records(&ck.records, &ck.algorithm, ctx.c).map_err(|e| invalid(&e))?;
        (ck.algorithm, ck.records)
    } else {
        (fresh, Vec::new())
    };
    let total = ctx.c.generations;
    let bar = indicatif::ProgressBar::new(total + 1);
    bar.set_position(records.len() as u64);
    let save = |alg: &A, records: &mut Vec<Record>| -> Result<(), ReentryError> {
        let pop = flat::<P>(alg.population());
        let result = alg.external_archive().map(flat::<P>);
        let rec = record_of(
            alg.generation(),
            alg.evaluations(),
            &pop,
            result.as_deref().unwrap_or(&pop),
            &ctx.c.reference,
        );
        bar.set_position(rec.generation + 1);
        bar.set_message(format!(
            "gen {} feasible {:.0} % best f {:?} hv {:.4}",
            rec.generation,
            100.0 * rec.feasible_fraction,
            rec.best,
            rec.hypervolume
        ));
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
    let run = Executor::new(ctx.problem, alg)
        .budget(Budget::Generations(ctx.c.generations))
        .threads(ctx.pool.clone())
        .stop_when(&stop)
        .run_with(|alg: &A| save(alg, &mut records))?;
    let (alg, wall) = (run.algorithm, run.wall_time_s);
    if run.stop == Stop::Interrupted {
        return Err(ReentryError::Interrupted {
            generation: alg.generation() + u64::from(alg.is_initialised()),
            dir: ctx.dir.to_path_buf(),
        });
    }
    bar.finish_and_clear();
    let last = records.last().cloned();
    // The front's members: the external archive's when the run keeps one.
    let scenarios: Vec<Option<Scenario>> = alg
        .result()
        .iter()
        .map(|i| ctx.problem.scenario(&i.decision))
        .collect();
    write_final(
        ctx.dir,
        &scenarios,
        &flat::<P>(alg.population()),
        &flat::<P>(alg.result()),
        &records,
        ctx.c,
        ctx.problem.reentry().analytical(),
    )?;
    if let Some(r) = last {
        writeln!(
            out,
            "{} on {}: generation {}, {} evaluations in {:.2} s in this run, feasible {:.0} %, hypervolume {:.6} w.r.t. {:?}, {} front members{}; wrote {}",
            ctx.c.algorithm,
            ctx.c.problem.base,
            r.generation,
            r.evaluations,
            wall,
            100.0 * r.feasible_fraction,
            r.hypervolume,
            ctx.c.reference,
            r.front.len(),
            ctx.c
                .archive
                .map_or_else(String::new, |n| format!(" (external archive of {n})")),
            ctx.dir.display()
        )?;
    }
    Ok(())
}
