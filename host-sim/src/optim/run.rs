//! What a recorded optimisation run keeps, whatever its problem: the per-generation
//! [`Record`] (counts, feasible fraction, front and its hypervolume), the [`Checkpoint`] of
//! an algorithm's state with the records so far (checked on restore by [`check_records`]),
//! the result front's order ([`front_order`]) and the population CSV text
//! ([`population_csv`]). The files themselves are written by the problem's run (the re-entry
//! runs: `crate::design::run`); this module, like all of `optim`, imports nothing else of
//! host-sim.

use std::fmt::Write as _;

use serde::{Deserialize, Serialize};

use super::algorithm::Algorithm;
use super::error::StateError;
use super::hypervolume::hypervolume;
use super::population::{Individual, feasible_fraction, feasible_front_indices};
use super::problem::Problem;

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

/// The population as CSV text: a header `x1..,f1..,g1..,violation`, then one row per
/// individual in `{:e}` form. Variable-length decisions (SCEA) are padded with empty fields
/// to the longest.
#[must_use]
pub fn population_csv(pop: &[Individual<Vec<f64>>]) -> String {
    let mut s = String::new();
    let n = pop.iter().map(|i| i.decision.len()).max().unwrap_or(0);
    let (m, c) = pop
        .first()
        .map_or((0, 0), |i| (i.objectives.len(), i.constraints.len()));
    let head: Vec<String> = (1..=n)
        .map(|i| format!("x{i}"))
        .chain((1..=m).map(|i| format!("f{i}")))
        .chain((1..=c).map(|i| format!("g{i}")))
        .chain(["violation".into()])
        .collect();
    let _ = writeln!(s, "{}", head.join(","));
    for ind in pop {
        let pad = n - ind.decision.len();
        let row: Vec<String> = ind
            .decision
            .iter()
            .map(|v| format!("{v:e}"))
            .chain(std::iter::repeat_n(String::new(), pad))
            .chain(
                ind.objectives
                    .iter()
                    .chain(&ind.constraints)
                    .chain(std::iter::once(&ind.violation))
                    .map(|v| format!("{v:e}")),
            )
            .collect();
        let _ = writeln!(s, "{}", row.join(","));
    }
    s
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
