//! `host-sim optimize`: run a multi-objective optimiser on a standard test problem, print a
//! summary, and with `--out DIR` write the final population, its feasible front (CSV) and a
//! summary JSON (hypervolume, reference point, evaluations, wall time of the evolution alone).

use std::io::Write;

use crate::optim::problems::TestProblem;
use crate::optim::run::{RunResult, RunSettings, run_report};
use crate::optim::{Budget, BuiltAlgorithm, Executor, Problem, RealAlgorithm};

pub use super::optimize_common::{AlgorithmArgs, OptimizeArgs, OptimizeError};
use super::optimize_common::{check, finish, generations_to_run, reference, run_options};

/// Run `optimize` with arguments `a`, printing the summary to `out`.
///
/// # Errors
/// [`OptimizeError`].
pub fn run(a: &OptimizeArgs, out: &mut dyn Write) -> Result<(), OptimizeError> {
    let options = run_options(a);
    check(a, &options)?;
    if super::optimize_common::wants_reentry(a) {
        return Ok(super::optimize_reentry::run(a, out)?);
    }
    if let Some(vl) = crate::optim::problems::Vlmop::by_name(&a.problem) {
        return super::optimize_structured::run_variable_length(a, &options, &vl, out);
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
    let pool = crate::optim::Threads::new(a.threads)?;
    let algorithm = match options.spec().build(a.seed) {
        BuiltAlgorithm::Real(r) => r,
        BuiltAlgorithm::Chromosome(c) => {
            return super::optimize_structured::run_fixed_length(
                a,
                &problem,
                c,
                generations,
                &reference,
                pool,
                out,
            );
        }
    };
    let run = Executor::new(&problem, algorithm)
        .budget(Budget::Generations(generations))
        .threads(pool)
        .run()?;
    let alg: &RealAlgorithm = &run.algorithm;
    let settings =
        RunSettings::of_algorithm(alg, &a.problem, generations, a.seed, &reference, a.threads);
    let report = run_report(
        &problem,
        &settings,
        RunResult::of::<TestProblem, _>(alg, run.wall_time_s),
    )?;
    finish(a, &report, out)
}

#[cfg(test)]
mod tests {
    use std::path::{Path, PathBuf};

    use super::super::optimize_variants_tests::{parse_flags, refused, small_args};
    use super::*;
    use crate::optim::ConstraintHandling;

    fn args(problem: &str, algorithm: &str, out: Option<PathBuf>) -> OptimizeArgs {
        let mut a = small_args(problem, algorithm, &[]);
        a.out = out;
        a
    }

    fn with(problem: &str, algorithm: &str, extra: &[&str]) -> OptimizeArgs {
        small_args(problem, algorithm, extra)
    }

    #[test]
    fn optimize_writes_population_front_and_summary() {
        let dir = std::env::temp_dir().join(format!("host-sim-optimize-{}", std::process::id()));
        let mut out = Vec::new();
        let mut a = args("zdt1", "nsga2", Some(dir.clone()));
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
        let e = run(&args("zdt5", "moead", None), &mut out).unwrap_err();
        assert!(e.to_string().contains("--problem zdt5: unknown"), "{e}");
        let e = run(&args("dtlz2", "moead", None), &mut out).unwrap_err();
        assert!(
            e.to_string().contains("nearest legal sizes are 15 and 21"),
            "{e}"
        );
        let mut a = args("zdt1", "moead", None);
        a.reference = Some("1".into());
        let e = run(&a, &mut out).unwrap_err();
        assert!(e.to_string().contains("--ref has 1 values"), "{e}");
        // The same parser as `hypervolume --ref`: the first bad coordinate is named.
        a.reference = Some("1,nan".into());
        let e = run(&a, &mut out).unwrap_err();
        assert!(
            e.to_string()
                .contains("--ref \"1,nan\": coordinate 2: must be finite"),
            "{e}"
        );
        let mut a = args("zdt1", "nsga2", None);
        a.population = 22;
        let e = run(&a, &mut out).unwrap_err();
        assert!(e.to_string().contains("use 20 or 24"), "{e}");
        let a = with("zdt1", "moead", &["--batch-size", "21"]);
        let e = run(&a, &mut out).unwrap_err();
        assert!(
            e.to_string()
                .contains("batch_size = 21 is outside [1, population]"),
            "{e}"
        );
        let a = with("zdt1", "moead", &["--mutation-probability", "1.5"]);
        let e = run(&a, &mut out).unwrap_err();
        assert!(e.to_string().contains("mutation_probability = 1.5"), "{e}");
        let mut a = args("zdt1", "nsga2", None);
        a.threads = 0;
        assert!(matches!(run(&a, &mut out), Err(OptimizeError::Threads(_))));
    }

    #[test]
    fn optimize_mhaco_flags_reach_the_algorithm() {
        let dir = |t: &str| {
            std::env::temp_dir().join(format!(
                "host-sim-optimize-mhaco-{t}-{}",
                std::process::id()
            ))
        };
        let mhaco_config = |a: &OptimizeArgs| run_options(a).mhaco_config();
        let default = mhaco_config(&args("constr", "mhaco", None));
        assert_eq!((default.ker, default.n_gen_mark), (20, 7));
        assert_eq!(default.constraints, ConstraintHandling::FeasibilityFirst);
        let a = with(
            "constr",
            "mhaco",
            &[
                "--ker",
                "10",
                "--n-gen-mark",
                "3",
                "--mhaco-constraints",
                "objectives",
            ],
        );
        let c = mhaco_config(&a);
        assert_eq!((c.ker, c.n_gen_mark), (10, 3));
        assert_eq!(c.constraints, ConstraintHandling::thesis_objectives());
        // Each flag changes the run (same seed).
        let mut runs = Vec::new();
        for (tag, flags) in [
            ("base", &[][..]),
            ("ker", &["--ker", "10"][..]),
            ("mark", &["--n-gen-mark", "2"][..]),
            ("obj", &["--mhaco-constraints", "objectives"][..]),
        ] {
            let mut a = with("constr", "mhaco", flags);
            (a.generations, a.out) = (20, Some(dir(tag)));
            run(&a, &mut Vec::new()).unwrap();
            runs.push(std::fs::read_to_string(dir(tag).join("population.csv")).unwrap());
            std::fs::remove_dir_all(dir(tag)).unwrap();
        }
        for (i, r) in runs.iter().enumerate().skip(1) {
            assert_ne!(&runs[0], r, "flag set {i} left the run unchanged");
        }
        // Bad values are the algorithm's typed errors naming the setting.
        let a = with("zdt1", "mhaco", &["--ker", "21"]);
        let e = run(&a, &mut Vec::new()).unwrap_err();
        assert!(e.to_string().contains("ker"), "{e}");
        let a = with("zdt1", "mhaco", &["--n-gen-mark", "0"]);
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
        for alg in ["moead", "nsga2"] {
            let mut a = args("zdt1", alg, Some(dir("plain")));
            a.generations = 30;
            run(&a, &mut Vec::new()).unwrap();
            let mut a = with("zdt1", alg, &["--archive", "12"]);
            (a.generations, a.out) = (30, Some(dir("archive")));
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
        // clap refuses a capacity of 0, and --archive of MHACO (which keeps none).
        for alg in ["moead", "nsga2", "scea"] {
            let e = refused(&[alg, "--archive", "0"]);
            assert!(e.contains("'--archive <N>'"), "{e}");
        }
        for problem in ["zdt1", "srm"] {
            let e = refused(&["--problem", problem, "mhaco", "--archive", "10"]);
            assert!(e.contains("unexpected argument '--archive'"), "{e}");
        }
        // A subcommand beside a run file: the file decides.
        for file in ["--resume", "--config"] {
            let a = parse_flags(&[file, "runs/none", "moead", "--archive", "10"]);
            let e = run(&a, &mut Vec::new()).unwrap_err();
            assert!(matches!(e, OptimizeError::AlgorithmInFile { .. }), "{e}");
            assert!(e.to_string().contains("the run file decides"), "{e}");
        }
        // SCEA on a fixed-length and on a variable-length problem reports its archive too.
        for problem in ["zdt1", "vlmop1"] {
            let mut a = with(problem, "scea", &["--archive", "6"]);
            a.out = Some(dir("scea"));
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
            ("nsga2", false),
            ("moead", false),
            ("nsga2", true),
            ("moead", true),
        ] {
            for t in [1usize, 3] {
                let mut flags = vec![];
                if alg == "moead" {
                    flags.extend(["--batch-size", "8"]);
                }
                if archive {
                    flags.extend(["--archive", "7"]);
                }
                let mut a = with("constr", alg, &flags);
                (a.threads, a.out) = (t, Some(dir(t)));
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
