//! `host-sim optimize` with a structured-chromosome algorithm (SCEA, the variable-length
//! MHACO: [`crate::optim::ChromosomeAlgorithm`], built from the library's
//! [`crate::optim::AlgorithmSpec`] as every algorithm is): SCEA on the fixed-length test
//! problems (as chromosomes of fixed genes only, reported as real vectors), SCEA or MHACO
//! (as the variable-length MHACO) on the variable-length problems of Li & Deb (`vlmop1` ...
//! `vlmop5`; population.csv one chromosome per row, [`crate::optim::run::chromosome_csv`]).

use std::io::Write;

use super::optimize_common::{OptimizeArgs, OptimizeError, finish, generations_to_run, reference};
use crate::optim::chromosome::FixedLength;
use crate::optim::problems::{TestProblem, Vlmop};
use crate::optim::run::{RunResult, RunSettings, run_report};
use crate::optim::spec::RunOptions;
use crate::optim::variable_length_run::{VariableLengthRun, VariableLengthRunError};
use crate::optim::{Algorithm, Budget, ChromosomeAlgorithm, Executor, Problem, Threads};

/// SCEA (`algorithm`, new) on a fixed-length test problem for `generations` generations,
/// on `threads`, scored against `reference`.
pub(super) fn run_fixed_length(
    a: &OptimizeArgs,
    problem: &TestProblem,
    algorithm: ChromosomeAlgorithm,
    generations: u64,
    reference: &[f64],
    threads: Threads,
    out: &mut dyn Write,
) -> Result<(), OptimizeError> {
    type Fixed = FixedLength<TestProblem>;
    let wrapped = FixedLength::new(problem.clone());
    let run = Executor::new(&wrapped, algorithm)
        .budget(Budget::Generations(generations))
        .threads(threads)
        .run()?;
    let alg = &run.algorithm;
    let population = wrapped.real_individuals(Algorithm::<Fixed>::population(alg));
    let archive = Algorithm::<Fixed>::external_archive(alg).map(|m| wrapped.real_individuals(m));
    let result = RunResult {
        population: &population,
        archive: archive.as_deref(),
        evaluations: Algorithm::<Fixed>::evaluations(alg),
        wall_time_s: run.wall_time_s,
    };
    let settings = RunSettings::of_chromosome_algorithm(
        alg,
        &a.problem,
        generations,
        a.seed,
        reference,
        a.threads,
    );
    let report = run_report(problem, &settings, result)?;
    finish(a, &report, out)
}

/// `optimize` on a variable-length problem (SCEA, or MHACO as the variable-length MHACO:
/// [`VariableLengthRun`]; the others are refused before, by `optimize_common::check`).
pub(super) fn run_variable_length(
    a: &OptimizeArgs,
    options: &RunOptions,
    problem: &Vlmop,
    out: &mut dyn Write,
) -> Result<(), OptimizeError> {
    let m = problem.objectives();
    let reference = reference(a, m, || problem.reference_point())?;
    let generations = generations_to_run(a, m)?;
    let run = VariableLengthRun::evolve(
        problem,
        options,
        a.seed,
        generations,
        Threads::new(a.threads)?,
    )
    .map_err(|e| match e {
        VariableLengthRunError::Optim(e) => OptimizeError::Optim(e),
        VariableLengthRunError::NotVariableLength { .. } => OptimizeError::NotForProblem {
            what: a.algorithm_name().to_string(),
            problem: a.problem.clone(),
            why: crate::optim::variable_length_run::VARIABLE_LENGTH_ALGORITHMS,
        },
    })?;
    let report = run.report(problem, &a.problem, a.seed, &reference, a.threads)?;
    writeln!(out, "{}", report.summary.line())?;
    if let Some(dir) = &a.out {
        crate::report::write_chromosome_run_report(dir, &report)?;
        writeln!(out, "wrote {}", dir.display())?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::optimize_cmd::run;
    use super::super::optimize_variants_tests::small_args;
    use super::*;

    fn args(problem: &str, algorithm: &str) -> OptimizeArgs {
        let mut a = small_args(problem, algorithm, &[]);
        a.generations = 10;
        a
    }

    #[test]
    fn optimize_runs_mhaco_and_scea_and_the_variable_length_problems() {
        let mut out = Vec::new();
        run(&args("zdt1", "mhaco"), &mut out).unwrap();
        run(&args("constr", "scea"), &mut out).unwrap();
        let dir = std::env::temp_dir().join(format!("host-sim-optimize-vl-{}", std::process::id()));
        let mut a = args("vlmop2", "scea");
        a.out = Some(dir.clone());
        a.threads = 2;
        run(&a, &mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        assert!(text.contains("mhaco on zdt1: 220 evaluations"), "{text}");
        assert!(text.contains("scea on constr: 220 evaluations"), "{text}");
        assert!(text.contains("scea on vlmop2: 220 evaluations"), "{text}");
        assert!(text.contains("of the true front"), "{text}");
        let pop = std::fs::read_to_string(dir.join("population.csv")).unwrap();
        assert!(
            pop.starts_with("f1,f2,g1,violation,x,nodes,genes\n"),
            "{pop}"
        );
        assert_eq!(pop.lines().count(), 21);
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap())
                .unwrap();
        let truth = json["true_front_hypervolume"].as_f64().unwrap();
        assert!((truth - 0.535).abs() < 1e-12, "{truth}");
        std::fs::remove_dir_all(&dir).unwrap();
        for alg in ["moead", "nsga2"] {
            let e = run(&args("vlmop1", alg), &mut Vec::new()).unwrap_err();
            assert!(matches!(e, OptimizeError::NotForProblem { .. }), "{e}");
            assert!(
                e.to_string()
                    .contains("use `optimize scea` or `optimize mhaco`"),
                "{e}"
            );
        }
        let e = run(&args("vlmop9", "scea"), &mut Vec::new()).unwrap_err();
        assert!(e.to_string().contains("vlmop1, vlmop2"), "{e}");
    }

    /// `optimize mhaco` on a variable-length problem runs the variable-length MHACO of the
    /// library's spec: the run is `VlMhaco`'s own, bit for bit, its flags reach it, and
    /// `--evaluations` is refused as for MHACO on the fixed-length problems.
    #[test]
    fn optimize_mhaco_on_a_variable_length_problem_runs_vl_mhaco() {
        use crate::optim::problems::Vlmop;
        use crate::optim::{NoObserver, Serial, VlMhaco};
        let dir =
            std::env::temp_dir().join(format!("host-sim-optimize-vlm-{}", std::process::id()));
        let mut a = small_args("vlmop1", "mhaco", &["--ker", "10", "--n-gen-mark", "3"]);
        (a.generations, a.seed, a.out) = (8, 4, Some(dir.clone()));
        let mut out = Vec::new();
        run(&a, &mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        assert!(
            text.contains("vl-mhaco on vlmop1: 180 evaluations"),
            "{text}"
        );
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(json["algorithm"], "vl-mhaco");
        let pop = std::fs::read_to_string(dir.join("population.csv")).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        let config = super::super::optimize_common::run_options(&a).mhaco_config();
        assert_eq!((config.ker, config.n_gen_mark), (10, 3));
        let problem = Vlmop::by_name("vlmop1").unwrap();
        let mut direct = VlMhaco::new(config, 4);
        crate::optim::evolve(&mut direct, &problem, &Serial, 8, &mut NoObserver).unwrap();
        let expected = crate::optim::run::chromosome_csv(
            Algorithm::<Vlmop>::population(&direct),
            problem.objectives(),
            problem.constraints(),
        )
        .unwrap();
        assert_eq!(pop, expected);
        let mut a = small_args("vlmop1", "mhaco", &[]);
        a.evaluations = Some(100);
        let e = run(&a, &mut Vec::new()).unwrap_err();
        assert!(
            e.to_string().contains("(given mhaco); use --generations"),
            "{e}"
        );
    }
}
