//! `host-sim optimize scea`: SCEA on the fixed-length test problems (as chromosomes of fixed
//! genes only, reported as real vectors) and on the variable-length problems of Li & Deb
//! (`vlmop1` ... `vlmop5`; population.csv one chromosome per row,
//! [`crate::optim::run::chromosome_csv`]).

use std::io::Write;

use super::optimize_common::{OptimizeArgs, OptimizeError, finish, reference, run_options};
use crate::optim::chromosome::{FixedLength, StructuredProblem};
use crate::optim::problems::{TestProblem, Vlmop};
use crate::optim::run::{RunResult, RunSettings, run_report, vlmop_run_report};
use crate::optim::{Algorithm, Budget, Executor, Problem, Scea, SceaConfig, Threads};

/// SCEA of the flags run on `problem`, with the evolution's wall time \[s\].
fn evolve<P: StructuredProblem>(
    a: &OptimizeArgs,
    problem: &P,
    threads: Threads,
) -> Result<(Scea, f64), OptimizeError> {
    let d = SceaConfig::default();
    let config = SceaConfig {
        moead: run_options(a).moead_config(),
        new_genes: a.scea_genes().unwrap_or(d.new_genes),
        ..d
    };
    let run = Executor::new(problem, Scea::new(config, a.seed))
        .budget(Budget::Generations(a.generations))
        .threads(threads)
        .run()?;
    Ok((run.algorithm, run.wall_time_s))
}

/// The settings SCEA's summary reports.
fn settings<'a>(a: &'a OptimizeArgs, reference: &'a [f64]) -> RunSettings<'a> {
    let o = run_options(a);
    RunSettings {
        problem: &a.problem,
        algorithm: "scea",
        population: a.population,
        generations: a.generations,
        seed: a.seed,
        reference,
        archive_capacity: o.archive,
        resource_allocation: o.resource_allocation,
        moead_operator: None,
        threads: a.threads,
    }
}

/// SCEA on a fixed-length test problem.
pub(super) fn run_fixed_length(
    a: &OptimizeArgs,
    problem: &TestProblem,
    reference: &[f64],
    threads: Threads,
    out: &mut dyn Write,
) -> Result<(), OptimizeError> {
    type Fixed = FixedLength<TestProblem>;
    let wrapped = FixedLength::new(problem.clone());
    let (alg, wall_time_s) = evolve(a, &wrapped, threads)?;
    let population = wrapped.real_individuals(Algorithm::<Fixed>::population(&alg));
    let archive = Algorithm::<Fixed>::external_archive(&alg).map(|m| wrapped.real_individuals(m));
    let result = RunResult {
        population: &population,
        archive: archive.as_deref(),
        evaluations: Algorithm::<Fixed>::evaluations(&alg),
        wall_time_s,
    };
    let report = run_report(problem, &settings(a, reference), result)?;
    finish(a, &report, out)
}

/// `optimize` on a variable-length problem (SCEA only).
pub(super) fn run_variable_length(
    a: &OptimizeArgs,
    problem: &Vlmop,
    out: &mut dyn Write,
) -> Result<(), OptimizeError> {
    let reference = reference(a, problem.objectives(), || problem.reference_point())?;
    let (alg, wall_time_s) = evolve(a, problem, Threads::new(a.threads)?)?;
    let result = RunResult::of::<Vlmop, _>(&alg, wall_time_s);
    let report = vlmop_run_report(problem, &settings(a, &reference), result)?;
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
        let e = run(&args("vlmop1", "moead"), &mut Vec::new()).unwrap_err();
        assert!(matches!(e, OptimizeError::NotForProblem { .. }), "{e}");
        assert!(e.to_string().contains("use `optimize scea`"), "{e}");
        let e = run(&args("vlmop9", "scea"), &mut Vec::new()).unwrap_err();
        assert!(e.to_string().contains("vlmop1, vlmop2"), "{e}");
    }
}
