//! The run executor with a front end's batch evaluator ([`super::run`]): the run directory
//! it writes is the in-process run's, a run started one way resumes the other, and a broken
//! evaluator stops the run with an error.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use super::{ReentryError, ReentryRunConfig, resumed_config, run};
use crate::optim::{EvalError, Evaluation, Problem};

fn base_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn small(generations: u64) -> ReentryRunConfig {
    let mut c = ReentryRunConfig::thesis("srm").unwrap();
    c.population = 6;
    c.neighbours = 5;
    c.generations = generations;
    c.threads = 2;
    c
}

fn tmp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("host-sim-run-on-{name}-{}", std::process::id()))
}

fn read(dir: &Path, file: &str) -> String {
    std::fs::read_to_string(dir.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"))
}

/// The files of a run that do not depend on timing: the checkpoint (algorithm state and
/// records) and the final front.
fn result_files(dir: &Path) -> (String, String) {
    (read(dir, "checkpoint.json"), read(dir, "front.csv"))
}

#[test]
fn an_external_evaluator_writes_the_in_process_run_and_resumes_either_way() {
    let c = small(2);
    let problem = c.problem.problem(&base_dir()).unwrap();
    let calls = AtomicUsize::new(0);
    let external = |xs: &[Vec<f64>]| -> Vec<Result<Evaluation, EvalError>> {
        calls.fetch_add(1, Ordering::Relaxed);
        xs.iter().map(|x| problem.evaluate(x)).collect()
    };
    let threads = tmp("threads");
    run(&c, "test", &threads, false, &base_dir(), &mut (), None).unwrap();
    let by_external = tmp("external");
    run(
        &c,
        "test",
        &by_external,
        false,
        &base_dir(),
        &mut (),
        Some(&external),
    )
    .unwrap();
    // The initial population in one batch, then two generations of 6 children asked one at a
    // time (batch size 1, pagmo's steady state).
    assert_eq!(calls.load(Ordering::Relaxed), 1 + 12);
    assert_eq!(result_files(&by_external), result_files(&threads));
    assert_eq!(
        read(&by_external, "config.toml"),
        read(&threads, "config.toml")
    );

    // One generation by the external evaluator, resumed to two in process; and the other way.
    for (first_external, name) in [(true, "ext-then-threads"), (false, "threads-then-ext")] {
        let dir = tmp(name);
        let one = small(1);
        let first = first_external.then_some(&external as &dyn crate::optim::BatchEvaluator<_>);
        run(&one, "test", &dir, false, &base_dir(), &mut (), first).unwrap();
        let resumed = resumed_config(&dir, Some(2)).unwrap();
        assert_eq!(resumed, c);
        let second = (!first_external).then_some(&external as &dyn crate::optim::BatchEvaluator<_>);
        run(&resumed, "test", &dir, true, &base_dir(), &mut (), second).unwrap();
        assert_eq!(result_files(&dir), result_files(&threads), "{name}");
        let _ = std::fs::remove_dir_all(&dir);
    }
    for d in [threads, by_external] {
        let _ = std::fs::remove_dir_all(d);
    }
}

#[test]
fn a_broken_external_evaluator_stops_the_run_and_scea_refuses_one() {
    let c = small(1);
    let short = |xs: &[Vec<f64>]| -> Vec<Result<Evaluation, EvalError>> {
        xs.iter()
            .skip(1)
            .map(|_| Ok(Evaluation::default()))
            .collect()
    };
    let dir = tmp("short");
    let e = run(&c, "test", &dir, false, &base_dir(), &mut (), Some(&short)).unwrap_err();
    assert!(
        e.to_string()
            .contains("returned 5 results for a batch of 6"),
        "{e}"
    );
    assert!(!dir.join("checkpoint.json").exists());
    let _ = std::fs::remove_dir_all(&dir);

    let mut scea = small(1);
    scea.algorithm = "scea".into();
    let e = run(
        &scea,
        "test",
        &tmp("scea"),
        false,
        &base_dir(),
        &mut (),
        Some(&short),
    )
    .unwrap_err();
    assert!(
        matches!(&e, ReentryError::Setting { field: "algorithm", value, .. } if value == "scea"),
        "{e}"
    );
    assert!(
        !tmp("scea").exists(),
        "refused before the directory is touched"
    );
}

/// A run whose base is a scenario file resumes wherever it is resumed from: config.toml names
/// the base by its absolute path (a resumed run once looked for it in the working directory).
#[test]
fn a_run_with_a_file_base_resumes_from_any_directory() {
    let mut c = small(1);
    c.problem.base = "srm-glide-replanning.toml".into();
    let examples = base_dir().join("examples");
    let dir = tmp("file-base");
    run(&c, "test", &dir, false, &examples, &mut (), None).unwrap();
    let resumed = resumed_config(&dir, Some(2)).unwrap();
    assert!(
        Path::new(&resumed.problem.base).is_absolute(),
        "{resumed:?}"
    );
    let done = run(
        &resumed,
        "test",
        &dir,
        true,
        Path::new("no-such-dir"),
        &mut (),
        None,
    )
    .unwrap();
    assert_eq!(done.last.unwrap().generation, 2);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The algorithm's settings are checked against the problem before the run directory is
/// touched (a previous run there stays), naming the run file and the algorithm.
#[test]
fn algorithm_settings_are_refused_before_the_directory_is_touched() {
    let dir = tmp("refused");
    run(&small(0), "test", &dir, false, &base_dir(), &mut (), None).unwrap();
    let before = read(&dir, "config.toml");
    for (algorithm, population, neighbours, what) in [
        ("moead", 6, 6, "neighbours"),
        ("scea", 6, 6, "neighbours"),
        ("nsga2", 6, 5, "population"),
        ("mhaco", 1, 5, "population"),
    ] {
        let mut c = small(1);
        c.algorithm = algorithm.into();
        c.population = population;
        c.neighbours = neighbours;
        let e = run(&c, "run.toml", &dir, false, &base_dir(), &mut (), None).unwrap_err();
        let text = e.to_string();
        assert!(
            text.starts_with(&format!("run.toml: field `algorithm` = {algorithm}:"))
                && text.contains(what),
            "{text}"
        );
        assert_eq!(read(&dir, "config.toml"), before, "{algorithm}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The flags the re-entry problems fix are refused by the flags' mapping itself (what the
/// CLI and the Python front ends call), each named; the others reach the run file.
#[test]
fn run_flags_refuse_what_the_reentry_problems_fix() {
    use super::{RunFlags, fixed_on_reentry};
    use crate::design::DesignError;
    use crate::optim::spec::{MoeadOperator, RunOptions};
    let flags = |options: RunOptions, evaluations: Option<u64>| RunFlags {
        preset: "srm".into(),
        options,
        generations: 3,
        seed: 4,
        threads: 1,
        reference: Some(vec![0.0, 1.5]),
        evaluations,
    };
    let c = ReentryRunConfig::of_flags(&flags(
        RunOptions {
            population: 8,
            neighbours: Some(5),
            ..RunOptions::default()
        },
        None,
    ))
    .unwrap();
    assert_eq!(
        (c.population, c.neighbours, c.generations, c.seed),
        (8, 5, 3, 4)
    );
    assert_eq!(c.reference, vec![0.0, 1.5]);
    let fixed = [
        (
            RunOptions {
                resource_allocation: true,
                ..RunOptions::default()
            },
            None,
            "--resource-allocation",
        ),
        (
            RunOptions {
                moead_operator: MoeadOperator::Sbx,
                ..RunOptions::default()
            },
            None,
            "--moead-operator sbx",
        ),
        (
            RunOptions {
                ker: Some(9),
                ..RunOptions::default()
            },
            None,
            "--ker",
        ),
        (
            RunOptions {
                n_gen_mark: 2,
                ..RunOptions::default()
            },
            None,
            "--n-gen-mark",
        ),
        (RunOptions::default(), Some(600), "--evaluations"),
    ];
    for (o, evaluations, flag) in fixed {
        assert_eq!(fixed_on_reentry(&o, evaluations), Some(flag));
        match ReentryRunConfig::of_flags(&flags(o, evaluations)) {
            Err(e @ DesignError::FixedOnReentry { .. }) => {
                let m = e.to_string();
                assert!(m.starts_with(flag) && m.contains("drop it"), "{m}");
            }
            other => panic!("{flag}: {other:?}"),
        }
    }
    assert_eq!(fixed_on_reentry(&RunOptions::default(), None), None);
}
