//! What a recorded optimisation run keeps, whatever its problem: the per-generation
//! [`Record`] (counts, feasible fraction, front and its hypervolume), the [`Checkpoint`] of
//! an algorithm's state with the records so far (checked on restore by [`check_records`]),
//! the result front's order ([`front_order`]), the CSV text of the records
//! ([`records_csv`]) and populations ([`population_csv`], [`chromosome_csv`]), and a run's
//! [`RunSummary`] (summary.json of `optimize` on a test problem) with its [`front_csv`] and
//! one-line [`RunSummary::line`], built from a finished run by [`run_report`] ([`RunSettings`],
//! [`RunResult`]). Every CSV file is written through its serde row type of
//! [`super::rows`] (the `csv` crate).
//! The files themselves are written by the caller (atomically, through host-sim's report
//! module; the re-entry runs: `crate::design::run`); this module, like all of `optim`,
//! imports nothing else of host-sim.

use serde::{Deserialize, Serialize};

use super::algorithm::Algorithm;
use super::chromosome::Chromosome;
use super::error::StateError;
use super::hypervolume::hypervolume;
use super::population::{Individual, feasible_fraction, feasible_front_indices};
use super::problem::Problem;
use super::rows::{
    ChromosomeRow, Dec, Exp, FrontRow, PopulationRow, RECORD_HEADER, RecordRow, RowsError, Semi,
    population_header, write_csv,
};

/// One generation's record.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Record {
    /// Generation (0: the initial population).
    pub generation: u64,
    /// Evaluations so far.
    pub evaluations: u64,
    /// Fraction of feasible individuals.
    #[serde(with = "super::nonfinite::scalar")]
    pub feasible_fraction: f64,
    /// Hypervolume of the feasible front (0 without feasible members): of the external
    /// archive when the run keeps one.
    #[serde(with = "super::nonfinite::scalar")]
    pub hypervolume: f64,
    /// Smallest violation in the population.
    #[serde(with = "super::nonfinite::scalar")]
    pub min_violation: f64,
    /// Best (smallest) feasible value per objective (NaN: none feasible).
    #[serde(with = "super::nonfinite::vec")]
    pub best: Vec<f64>,
    /// Mean feasible value per objective (NaN: none feasible).
    #[serde(with = "super::nonfinite::vec")]
    pub mean: Vec<f64>,
    /// The feasible front's objective vectors (the external archive's, if any).
    #[serde(with = "super::nonfinite::vec2")]
    pub front: Vec<Vec<f64>>,
}

/// The record of a population; the front and its hypervolume are those of `result` (the
/// population itself, or the run's external archive).
#[must_use]
pub fn record_of(
    generation: u64,
    evaluations: u64,
    pop: &[Individual<Vec<f64>>],
    result: &[Individual<Vec<f64>>],
    reference: &[f64],
) -> Record {
    let m = reference.len();
    let feas: Vec<&Individual<Vec<f64>>> = pop.iter().filter(|i| i.violation == 0.0).collect();
    let mut best = vec![f64::NAN; m];
    let mut mean = vec![f64::NAN; m];
    if !feas.is_empty() {
        for k in 0..m {
            best[k] = feas
                .iter()
                .map(|i| i.objectives[k])
                .fold(f64::INFINITY, f64::min);
            mean[k] = feas.iter().map(|i| i.objectives[k]).sum::<f64>() / feas.len() as f64;
        }
    }
    // Each distinct objective vector once (members with equal values are one point).
    let mut front: Vec<Vec<f64>> = front_order(result)
        .into_iter()
        .map(|i| result[i].objectives.clone())
        .collect();
    front.sort_by(|a, b| {
        a.iter()
            .zip(b)
            .map(|(x, y)| x.total_cmp(y))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    front.dedup_by(|a, b| {
        a.iter()
            .zip(b.iter())
            .all(|(x, y)| x.to_bits() == y.to_bits())
    });
    Record {
        generation,
        evaluations,
        feasible_fraction: feasible_fraction(pop),
        hypervolume: hypervolume(&front, reference).unwrap_or(f64::NAN),
        min_violation: pop
            .iter()
            .map(|i| i.violation)
            .fold(f64::INFINITY, f64::min),
        best,
        mean,
        front,
    }
}

/// The population as CSV text ([`PopulationRow`]): a header `x1..,f1..,g1..,violation`,
/// then one row per individual in `{:e}` form. Variable-length decisions (SCEA) are padded
/// with empty fields to the longest.
///
/// # Errors
/// [`RowsError`] (not expected: every row has the header's length).
pub fn population_csv(pop: &[Individual<Vec<f64>>]) -> Result<String, RowsError> {
    let n = pop.iter().map(|i| i.decision.len()).max().unwrap_or(0);
    let (m, c) = pop
        .first()
        .map_or((0, 0), |i| (i.objectives.len(), i.constraints.len()));
    let rows = pop.iter().map(|ind| PopulationRow {
        x: (0..n)
            .map(|k| ind.decision.get(k).copied().map(Exp))
            .collect(),
        f: ind.objectives.iter().copied().map(Exp).collect(),
        g: ind.constraints.iter().copied().map(Exp).collect(),
        violation: Exp(ind.violation),
    });
    write_csv(&population_header(n, m, c), rows)
}

/// The indices of `result`'s feasible front sorted by the first objective, each distinct
/// member once (identical decisions with identical values are one member).
#[must_use]
pub fn front_order(result: &[Individual<Vec<f64>>]) -> Vec<usize> {
    let mut idx = feasible_front_indices(result);
    idx.sort_by(|&a, &b| result[a].objectives[0].total_cmp(&result[b].objectives[0]));
    let bits = |i: &Individual<Vec<f64>>| -> Vec<u64> {
        i.decision
            .iter()
            .chain(&i.objectives)
            .chain(&i.constraints)
            .map(|v| v.to_bits())
            .collect()
    };
    let mut seen = std::collections::HashSet::new();
    idx.retain(|&i| seen.insert(bits(&result[i])));
    idx
}

/// A run's checkpoint (checkpoint.json): the algorithm's whole state and the records of the
/// generations so far.
#[derive(Serialize, Deserialize)]
pub struct Checkpoint<A> {
    /// The algorithm's state.
    pub algorithm: A,
    /// One record per completed generation.
    pub records: Vec<Record>,
}

/// The records of a restored checkpoint: one per generation up to the state's, each with
/// `objectives` values.
///
/// # Errors
/// [`StateError`] naming the record and field.
pub fn check_records<P: Problem, A: Algorithm<P>>(
    records: &[Record],
    alg: &A,
    objectives: usize,
) -> Result<(), StateError> {
    use super::restore::{bad, count};
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
    let m = objectives;
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

/// The summary of a run on a test problem (summary.json).
#[derive(Debug, Serialize)]
pub struct RunSummary<'a> {
    /// Problem name.
    pub problem: &'a str,
    /// Algorithm name.
    pub algorithm: &'static str,
    /// Population size.
    pub population: usize,
    /// Generations after the initial population.
    pub generations: u64,
    /// Seed.
    pub seed: u64,
    /// Objectives.
    pub objectives: usize,
    /// Decision variables (a variable-length problem: the longest chromosome's genes).
    pub variables: usize,
    /// Constraints.
    pub constraints: usize,
    /// Evaluations, initial population included.
    pub evaluations: u64,
    /// Hypervolume reference point.
    pub reference_point: &'a [f64],
    /// Hypervolume of the feasible front.
    pub hypervolume: f64,
    /// Hypervolume of the problem's true front, when known.
    pub true_front_hypervolume: Option<f64>,
    /// `hypervolume / true_front_hypervolume`.
    pub hypervolume_ratio: Option<f64>,
    /// Fraction of feasible individuals in the final population.
    pub feasible_fraction: f64,
    /// What the front (front.csv, hypervolume, front_size) is taken from: "population" (the
    /// final population; pagmo's semantics) or "archive" (the external archive).
    pub front_source: &'static str,
    /// Capacity of the external archive, if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub archive_capacity: Option<usize>,
    /// MOEA/D-DRA's resource allocation was on.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub resource_allocation: bool,
    /// MOEA/D's variation when not pagmo's DE ("sbx").
    #[serde(skip_serializing_if = "Option::is_none")]
    pub moead_operator: Option<&'static str>,
    /// Points of the feasible front.
    pub front_size: usize,
    /// Wall time of the evolution alone (no problem set-up, no output) \[s\].
    pub wall_time_s: f64,
    /// Evaluation threads.
    pub threads: usize,
}

impl RunSummary<'_> {
    /// The one-line result of the run (no newline).
    #[must_use]
    pub fn line(&self) -> String {
        let ratio = self
            .hypervolume_ratio
            .map_or_else(String::new, |r| format!(" ({r:.4} of the true front)"));
        format!(
            "{} on {}: {} evaluations in {:.3} s, hypervolume {:.6}{} w.r.t. {:?}, {} front points, feasible {:.0} %",
            self.algorithm,
            self.problem,
            self.evaluations,
            self.wall_time_s,
            self.hypervolume,
            ratio,
            self.reference_point,
            self.front_size,
            100.0 * self.feasible_fraction
        )
    }
}

/// The settings of a run that its [`RunSummary`] reports.
#[derive(Clone, Copy, Debug)]
pub struct RunSettings<'a> {
    /// Problem name, as given.
    pub problem: &'a str,
    /// Algorithm name (`moead` for both MOEA/D variations).
    pub algorithm: &'static str,
    /// Population size.
    pub population: usize,
    /// Generations after the initial population.
    pub generations: u64,
    /// Seed of the run.
    pub seed: u64,
    /// Hypervolume reference point.
    pub reference: &'a [f64],
    /// Capacity of the external archive, if any.
    pub archive_capacity: Option<usize>,
    /// MOEA/D-DRA's resource allocation was on.
    pub resource_allocation: bool,
    /// MOEA/D's variation when not pagmo's DE ("sbx").
    pub moead_operator: Option<&'static str>,
    /// Evaluation threads (or workers).
    pub threads: usize,
}

impl<'a> RunSettings<'a> {
    /// The settings of a run of `algorithm` (its name, population, archive, MOEA/D's
    /// resource allocation and variation are the algorithm's own) with the rest given.
    #[must_use]
    pub fn of_algorithm(
        algorithm: &super::spec::RealAlgorithm,
        problem: &'a str,
        generations: u64,
        seed: u64,
        reference: &'a [f64],
        threads: usize,
    ) -> Self {
        use super::spec::RealAlgorithm as R;
        let (name, population, archive_capacity, resource_allocation, moead_operator) =
            match algorithm {
                R::Moead(a) => {
                    let c = a.config();
                    let ra = c.resource_allocation.is_some();
                    ("moead", c.population, c.archive, ra, None)
                }
                R::MoeadSbx(a) => {
                    let c = a.config();
                    let ra = c.resource_allocation.is_some();
                    ("moead", c.population, c.archive, ra, Some("sbx"))
                }
                R::Nsga2(a) => (
                    "nsga2",
                    a.config().population,
                    a.config().archive,
                    false,
                    None,
                ),
                R::Mhaco(a) => ("mhaco", a.config().population, None, false, None),
            };
        Self {
            algorithm: name,
            population,
            archive_capacity,
            resource_allocation,
            moead_operator,
            ..Self::of_run(problem, generations, seed, reference, threads)
        }
    }

    /// The settings of the run itself, before the algorithm's are filled in.
    fn of_run(
        problem: &'a str,
        generations: u64,
        seed: u64,
        reference: &'a [f64],
        threads: usize,
    ) -> Self {
        Self {
            problem,
            algorithm: "",
            population: 0,
            generations,
            seed,
            reference,
            archive_capacity: None,
            resource_allocation: false,
            moead_operator: None,
            threads,
        }
    }
}

impl<'a> RunSettings<'a> {
    /// [`RunSettings::of_algorithm`] of a structured-chromosome algorithm (SCEA: MOEA/D's
    /// population, archive and resource allocation).
    #[must_use]
    pub fn of_chromosome_algorithm(
        algorithm: &super::spec::ChromosomeAlgorithm,
        problem: &'a str,
        generations: u64,
        seed: u64,
        reference: &'a [f64],
        threads: usize,
    ) -> Self {
        use super::spec::ChromosomeAlgorithm as C;
        let (name, population, archive_capacity, resource_allocation) = match algorithm {
            C::Scea(a) => {
                let c = a.config();
                (
                    "scea",
                    c.population,
                    c.archive,
                    c.resource_allocation.is_some(),
                )
            }
            C::VlMhaco(a) => ("vl-mhaco", a.config().population, None, false),
        };
        Self {
            algorithm: name,
            population,
            archive_capacity,
            resource_allocation,
            ..Self::of_run(problem, generations, seed, reference, threads)
        }
    }
}

/// A finished run (real vectors, or chromosomes `D = Chromosome`): what the algorithm holds
/// at its end.
#[derive(Debug)]
pub struct RunResult<'a, D = Vec<f64>> {
    /// The final population.
    pub population: &'a [Individual<D>],
    /// The external archive's members, when the run kept one (the result front).
    pub archive: Option<&'a [Individual<D>]>,
    /// Evaluations, initial population included.
    pub evaluations: u64,
    /// Wall time of the evolution alone \[s\].
    pub wall_time_s: f64,
}

impl<D> Clone for RunResult<'_, D> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<D> Copy for RunResult<'_, D> {}

impl<'a, D> RunResult<'a, D> {
    /// What `algorithm` (run on a problem of type `P`) holds, with the run's wall time.
    #[must_use]
    pub fn of<P: Problem<Decision = D>, A: Algorithm<P>>(
        algorithm: &'a A,
        wall_time_s: f64,
    ) -> Self {
        Self {
            population: algorithm.population(),
            archive: algorithm.external_archive(),
            evaluations: algorithm.evaluations(),
            wall_time_s,
        }
    }
}

/// A finished run's summary, with the population and the feasible front it was made of.
#[derive(Debug)]
pub struct RunReport<'a, D = Vec<f64>> {
    /// summary.json.
    pub summary: RunSummary<'a>,
    /// The final population (population.csv).
    pub population: &'a [Individual<D>],
    /// The feasible front of the archive, or else of the population (front.csv).
    pub front: Vec<&'a [f64]>,
}

/// Why a run's report could not be made.
#[derive(Debug, thiserror::Error)]
pub enum RunReportError {
    /// A reference point of another dimension than the problem's objectives.
    #[error("reference point has {got} values {values:?}; the problem has {expected} objectives")]
    Reference {
        /// Objectives of the problem.
        expected: usize,
        /// Values given.
        got: usize,
        /// The values.
        values: Vec<f64>,
    },
    /// Hypervolume failed.
    #[error("hypervolume: {0}")]
    Hypervolume(#[from] super::hypervolume::HypervolumeError),
}

/// Whether `reference` has one value per objective of a problem of `objectives` objectives
/// (what [`run_report`] refuses at the end of a run; a front end checks it before).
///
/// # Errors
/// [`RunReportError::Reference`].
pub fn check_reference(reference: &[f64], objectives: usize) -> Result<(), RunReportError> {
    if reference.len() == objectives {
        Ok(())
    } else {
        Err(RunReportError::Reference {
            expected: objectives,
            got: reference.len(),
            values: reference.to_vec(),
        })
    }
}

/// The report of a finished run on the test problem `problem` (`host-sim optimize` on a
/// test problem): the hypervolume of the feasible front of the external archive if the run
/// kept one, else of the final population; the true front's hypervolume (exact where known,
/// else of 20 000 front points) and the ratio; the feasible fraction of the population.
///
/// # Errors
/// [`RunReportError`]: a reference point of another dimension, a failed hypervolume.
pub fn run_report<'a>(
    problem: &super::problems::TestProblem,
    settings: &RunSettings<'a>,
    result: RunResult<'a>,
) -> Result<RunReport<'a>, RunReportError> {
    check_reference(settings.reference, problem.objectives())?;
    let true_hv = problem.front_hypervolume(settings.reference, 20_000);
    real_run_report(problem, true_hv, settings, result)
}

/// [`run_report`] on any real-vector problem whose true front's hypervolume is
/// `true_front_hypervolume` (`None`: unknown).
///
/// # Errors
/// [`RunReportError`].
pub fn real_run_report<'a, P: super::problem::RealProblem>(
    problem: &P,
    true_front_hypervolume: Option<f64>,
    settings: &RunSettings<'a>,
    result: RunResult<'a>,
) -> Result<RunReport<'a>, RunReportError> {
    let shape = [
        problem.objectives(),
        problem.bounds().dim(),
        problem.constraints(),
    ];
    report_of(shape, true_front_hypervolume, settings, result)
}

/// The report of a finished SCEA run on a variable-length test problem: as
/// [`run_report`]'s, the true front's hypervolume exact where known, else of 2000 front
/// points; the variables those of the longest chromosome.
///
/// # Errors
/// [`RunReportError`].
pub fn vlmop_run_report<'a>(
    problem: &super::problems::Vlmop,
    settings: &RunSettings<'a>,
    result: RunResult<'a, Chromosome>,
) -> Result<RunReport<'a, Chromosome>, RunReportError> {
    use super::chromosome::StructuredProblem;
    check_reference(settings.reference, problem.objectives())?;
    let true_hv = problem
        .front_hypervolume(settings.reference)
        .or_else(|| hypervolume(&problem.pareto_front(2000), settings.reference).ok());
    let l = problem.layout();
    let variables = l.fixed_dim() + l.legs().max * l.nodes().max * l.node().dim();
    let shape = [problem.objectives(), variables, problem.constraints()];
    report_of(shape, true_hv, settings, result)
}

/// The report of a run on a problem of `[objectives, variables, constraints]`.
fn report_of<'a, D>(
    [m, variables, constraints]: [usize; 3],
    true_front_hypervolume: Option<f64>,
    settings: &RunSettings<'a>,
    result: RunResult<'a, D>,
) -> Result<RunReport<'a, D>, RunReportError> {
    let reference = settings.reference;
    check_reference(reference, m)?;
    let pop = result.population;
    let front_of = result.archive.unwrap_or(pop);
    let front: Vec<&[f64]> = feasible_front_indices(front_of)
        .iter()
        .map(|&i| front_of[i].objectives.as_slice())
        .collect();
    let hv = hypervolume(&front, reference)?;
    let true_hv = true_front_hypervolume;
    let summary = RunSummary {
        problem: settings.problem,
        algorithm: settings.algorithm,
        population: settings.population,
        generations: settings.generations,
        seed: settings.seed,
        objectives: m,
        variables,
        constraints,
        evaluations: result.evaluations,
        reference_point: reference,
        hypervolume: hv,
        true_front_hypervolume: true_hv,
        hypervolume_ratio: true_hv.filter(|t| *t > 0.0).map(|t| hv / t),
        feasible_fraction: feasible_fraction(pop),
        front_source: if result.archive.is_some() {
            "archive"
        } else {
            "population"
        },
        archive_capacity: settings.archive_capacity,
        resource_allocation: settings.resource_allocation,
        moead_operator: settings.moead_operator,
        front_size: front.len(),
        wall_time_s: result.wall_time_s,
        threads: settings.threads,
    };
    Ok(RunReport {
        summary,
        population: pop,
        front,
    })
}

/// The front's objective vectors as CSV text ([`FrontRow`]; header `f1,f2,...` for
/// `objectives`).
///
/// # Errors
/// [`RowsError`] if a point has another number of objectives.
pub fn front_csv(front: &[&[f64]], objectives: usize) -> Result<String, RowsError> {
    let header: Vec<String> = (1..=objectives).map(|i| format!("f{i}")).collect();
    let rows = front.iter().map(|f| FrontRow {
        f: f.iter().copied().map(Exp).collect(),
    });
    write_csv(&header, rows)
}

/// A variable-length population as CSV text ([`ChromosomeRow`]), one chromosome per row:
/// objectives, constraints, violation, then `x` (fixed genes), `nodes` (node count of each
/// leg) and `genes` (all node genes), each a `;`-separated list.
///
/// # Errors
/// [`RowsError`] if an individual has another number of objectives or constraints.
pub fn chromosome_csv(
    pop: &[Individual<Chromosome>],
    objectives: usize,
    constraints: usize,
) -> Result<String, RowsError> {
    let header: Vec<String> = (1..=objectives)
        .map(|i| format!("f{i}"))
        .chain((1..=constraints).map(|i| format!("g{i}")))
        .chain(["violation", "x", "nodes", "genes"].map(String::from))
        .collect();
    let exps = |v: &[f64]| v.iter().copied().map(Exp).collect::<Vec<_>>();
    let rows = pop.iter().map(|ind| {
        let c = &ind.decision;
        ChromosomeRow {
            f: exps(&ind.objectives),
            g: exps(&ind.constraints),
            violation: Exp(ind.violation),
            x: Semi(exps(&c.fixed)),
            nodes: Semi(c.node_counts()),
            genes: Semi(
                c.legs
                    .iter()
                    .flatten()
                    .flatten()
                    .copied()
                    .map(Exp)
                    .collect(),
            ),
        }
    });
    write_csv(&header, rows)
}

impl From<&Record> for RecordRow {
    /// The record of a two-objective run (NaN for a missing objective).
    fn from(r: &Record) -> Self {
        let at = |v: &[f64], k: usize| Exp(v.get(k).copied().unwrap_or(f64::NAN));
        Self {
            generation: r.generation,
            evaluations: r.evaluations,
            feasible_fraction: Dec(r.feasible_fraction),
            hypervolume: Exp(r.hypervolume),
            min_violation: Exp(r.min_violation),
            best_f1: at(&r.best, 0),
            best_f2: at(&r.best, 1),
            mean_f1: at(&r.mean, 0),
            mean_f2: at(&r.mean, 1),
            front_size: r.front.len(),
        }
    }
}

/// The records of a two-objective run as CSV text ([`RecordRow`]; generations.csv).
///
/// # Errors
/// [`RowsError`] (not expected: the row type fixes the columns).
pub fn records_csv(records: &[Record]) -> Result<String, RowsError> {
    let header: Vec<String> = RECORD_HEADER.split(',').map(String::from).collect();
    write_csv(&header, records.iter().map(RecordRow::from))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ind(decision: Vec<f64>, objectives: Vec<f64>, violation: f64) -> Individual<Vec<f64>> {
        Individual {
            decision,
            objectives,
            constraints: vec![violation],
            violation,
        }
    }

    #[test]
    fn population_csv_pads_shorter_decisions_and_front_order_drops_repeats() {
        let pop = [
            ind(vec![1.0, 2.0], vec![0.5, 0.25], 0.0),
            ind(vec![3.0], vec![0.25, 0.5], 0.0),
            ind(vec![3.0], vec![0.25, 0.5], 0.0),
            ind(vec![4.0], vec![0.1, 0.1], 2.0),
        ];
        let csv = population_csv(&pop).unwrap();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], "x1,x2,f1,f2,g1,violation");
        assert_eq!(lines[2], "3e0,,2.5e-1,5e-1,0e0,0e0");
        // Feasible, sorted by f1, the repeated member once, the infeasible one out.
        assert_eq!(front_order(&pop), vec![1, 0]);
        let r = record_of(0, 4, &pop, &pop, &[1.0, 1.0]);
        assert_eq!(r.front, vec![vec![0.25, 0.5], vec![0.5, 0.25]]);
        assert_eq!(r.feasible_fraction, 0.75);
        assert_eq!(r.min_violation, 0.0);
        assert_eq!(
            front_csv(&[&[0.5, 0.25]], 2).unwrap(),
            "f1,f2\n5e-1,2.5e-1\n".to_string()
        );
    }

    /// A generation without a feasible member (NaN best and mean, infinite smallest
    /// violation of an empty population, a negative infinity of a broken objective) survives
    /// generations.csv and checkpoint.json bit for bit.
    #[test]
    fn records_with_non_finite_values_round_trip_through_csv_and_checkpoint() {
        let none = Record {
            generation: 0,
            evaluations: 8,
            feasible_fraction: 0.0,
            hypervolume: 0.0,
            min_violation: f64::INFINITY,
            best: vec![f64::NAN, f64::NAN],
            mean: vec![f64::NAN, f64::NAN],
            front: vec![],
        };
        let some = Record {
            generation: 1,
            evaluations: 16,
            feasible_fraction: 0.375,
            hypervolume: 1.0 / 3.0,
            min_violation: 0.0,
            best: vec![f64::NEG_INFINITY, 0.1],
            mean: vec![-0.5, f64::INFINITY],
            front: vec![vec![f64::NEG_INFINITY, 0.1], vec![-0.5, 0.2]],
        };
        let records = vec![none, some];
        let text = records_csv(&records).unwrap();
        assert_eq!(
            text.lines().nth(1).unwrap(),
            "0,8,0,0e0,inf,NaN,NaN,NaN,NaN,0"
        );
        assert_eq!(
            text.lines().nth(2).unwrap(),
            "1,16,0.375,3.333333333333333e-1,0e0,-inf,1e-1,-5e-1,inf,2"
        );
        let rows = crate::optim::rows::read_records(&text).unwrap();
        let fields = |r: &RecordRow| {
            [
                r.feasible_fraction.0,
                r.hypervolume.0,
                r.min_violation.0,
                r.best_f1.0,
                r.best_f2.0,
                r.mean_f1.0,
                r.mean_f2.0,
            ]
            .map(f64::to_bits)
        };
        for (r, row) in records.iter().zip(&rows) {
            assert_eq!(fields(&RecordRow::from(r)), fields(row));
            assert_eq!(
                (row.generation, row.front_size),
                (r.generation, r.front.len())
            );
        }
        let header: Vec<String> = RECORD_HEADER.split(',').map(String::from).collect();
        assert_eq!(write_csv(&header, rows).unwrap(), text);
        // checkpoint.json: the records come back with the same bits.
        let ck = Checkpoint {
            algorithm: 7u8,
            records: records.clone(),
        };
        let json = serde_json::to_string(&ck).unwrap();
        let back: Checkpoint<u8> = serde_json::from_str(&json).unwrap();
        let all = |r: &Record| -> Vec<u64> {
            [r.feasible_fraction, r.hypervolume, r.min_violation]
                .iter()
                .chain(&r.best)
                .chain(&r.mean)
                .chain(r.front.iter().flatten())
                .map(|v| v.to_bits())
                .collect()
        };
        assert_eq!(back.records.len(), 2);
        for (a, b) in records.iter().zip(&back.records) {
            assert_eq!(all(a), all(b));
        }
        assert_eq!(serde_json::to_string(&back).unwrap(), json);
    }
}
