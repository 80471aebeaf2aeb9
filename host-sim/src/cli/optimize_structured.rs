//! `host-sim optimize` with SCEA: on the fixed-length test problems (as chromosomes of fixed
//! genes only) and on the variable-length problems of Li & Deb (`vlmop1` ... `vlmop5`). The
//! variable-length population CSV is [`crate::optim::run::chromosome_csv`]'s: one chromosome
//! per row.

use std::io::Write;

use super::optimize_common::{
    OptimizeArgs, OptimizeError, Outcome, reference, run_options, threads,
};
use crate::optim::chromosome::{Chromosome, FixedLength, StructuredProblem};
use crate::optim::hypervolume::hypervolume;
use crate::optim::population::{feasible_fraction, feasible_front_indices};
use crate::optim::problems::{TestProblem, Vlmop};
use crate::optim::run::{RunSummary, chromosome_csv};
use crate::optim::{
    Algorithm, Budget, Executor, Individual, OptimError, Problem, Scea, SceaConfig, Threads,
};

fn scea_config(a: &OptimizeArgs) -> SceaConfig {
    let d = SceaConfig::default();
    SceaConfig {
        moead: run_options(a).moead_config(),
        new_genes: a.scea_genes().unwrap_or(d.new_genes),
        ..d
    }
}

/// What an SCEA run leaves: the population, the external archive (`--archive`), the
/// evaluations and the evolution's wall time [s].
type SceaOutcome = (
    Vec<Individual<Chromosome>>,
    Option<Vec<Individual<Chromosome>>>,
    u64,
    f64,
);

/// Evolve SCEA on `problem`.
fn evolve_scea<P: StructuredProblem>(
    a: &OptimizeArgs,
    problem: &P,
    threads: &Threads,
) -> Result<SceaOutcome, OptimError> {
    let run = Executor::new(problem, Scea::new(scea_config(a), a.seed))
        .budget(Budget::Generations(a.generations))
        .threads(threads.clone())
        .run()?;
    let (alg, wall) = (run.algorithm, run.wall_time_s);
    Ok((
        <Scea as Algorithm<P>>::population(&alg).to_vec(),
        <Scea as Algorithm<P>>::external_archive(&alg).map(<[_]>::to_vec),
        alg.evaluations(),
        wall,
    ))
}

/// SCEA on a fixed-length test problem; the decisions are the chromosomes' fixed genes.
pub(super) fn drive_scea(
    a: &OptimizeArgs,
    problem: &TestProblem,
    threads: &Threads,
) -> Result<Outcome, OptimError> {
    let wrapped = FixedLength::new(problem.clone());
    let (population, archive, evaluations, wall_time_s) = evolve_scea(a, &wrapped, threads)?;
    let fixed = |inds: Vec<Individual<Chromosome>>| -> Vec<Individual<Vec<f64>>> {
        inds.into_iter()
            .map(|i| Individual {
                decision: i.decision.fixed,
                objectives: i.objectives,
                constraints: i.constraints,
                violation: i.violation,
            })
            .collect()
    };
    Ok(Outcome {
        population: fixed(population),
        archive: archive.map(fixed),
        evaluations,
        wall_time_s,
    })
}

/// `optimize` on a variable-length problem (SCEA only).
pub(super) fn run_variable_length(
    a: &OptimizeArgs,
    problem: &Vlmop,
    out: &mut dyn Write,
) -> Result<(), OptimizeError> {
    let m = problem.objectives();
    let reference = reference(a, m, || problem.reference_point())?;
    let (pop, archive, evaluations, wall_time_s) = evolve_scea(a, problem, &threads(a.threads)?)?;
    let result = archive.as_deref().unwrap_or(&pop);
    let front: Vec<&[f64]> = feasible_front_indices(result)
        .into_iter()
        .map(|i| result[i].objectives.as_slice())
        .collect();
    let hv = hypervolume(&front, &reference)?;
    let true_hv = problem
        .front_hypervolume(&reference)
        .or_else(|| hypervolume(&problem.pareto_front(2000), &reference).ok());
    let layout = problem.layout();
    let summary = RunSummary {
        problem: &a.problem,
        algorithm: "scea",
        population: a.population,
        generations: a.generations,
        seed: a.seed,
        objectives: m,
        variables: layout.fixed_dim()
            + layout.legs().max * layout.nodes().max * layout.node().dim(),
        constraints: problem.constraints(),
        evaluations,
        reference_point: &reference,
        hypervolume: hv,
        true_front_hypervolume: true_hv,
        hypervolume_ratio: true_hv.filter(|t| *t > 0.0).map(|t| hv / t),
        feasible_fraction: feasible_fraction(&pop),
        front_source: if archive.is_some() {
            "archive"
        } else {
            "population"
        },
        archive_capacity: run_options(a).archive,
        resource_allocation: run_options(a).resource_allocation,
        moead_operator: None,
        front_size: front.len(),
        wall_time_s,
        threads: a.threads,
    };
    writeln!(out, "{}", summary.line())?;
    if let Some(dir) = &a.out {
        let population = chromosome_csv(&pop, m, problem.constraints())
            .map_err(crate::report::ReportError::from)?;
        crate::report::write_optimize_run(dir, &population, &front, &summary)?;
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
