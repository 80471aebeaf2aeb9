//! `host-sim sample`: a Latin-hypercube design of a re-entry design problem's decision space,
//! evaluated in parallel (closed-loop flights), written as samples.csv (decision, objectives,
//! constraints, violation; one row per point in design order, whatever the thread count).

use std::io::Write;
use std::path::PathBuf;

use rayon::prelude::*;

use super::optimize_reentry::ReentryError;
use crate::design::{DesignConfig, latin_hypercube};
use crate::optim::population::sanitize;
use crate::optim::rows::{Exp, PopulationRow, population_header, write_csv};
use crate::optim::{Problem, RealProblem};
use crate::report::write_atomic;

/// Most points of one design.
const MAX_COUNT: usize = 1_000_000;

/// Arguments of `sample`.
#[derive(Debug, clap::Args)]
pub struct SampleArgs {
    /// Design preset: horus-2b, srm, srm-altitude.
    #[arg(long, default_value = "horus-2b")]
    pub problem: String,
    /// Number of points (thesis: 4000).
    #[arg(long, default_value_t = 4000)]
    pub count: usize,
    /// Seed of the design.
    #[arg(long, default_value_t = 123)]
    pub seed: u64,
    /// Evaluation threads.
    #[arg(long, default_value_t = 2)]
    pub threads: usize,
    /// Output CSV.
    #[arg(long, default_value = "samples.csv")]
    pub out: PathBuf,
}

/// Run `sample`.
///
/// # Errors
/// [`ReentryError`] naming the field.
pub fn run(a: &SampleArgs, out: &mut dyn Write) -> Result<(), ReentryError> {
    let bad = |field, value: String, reason: &str| ReentryError::Setting {
        source_name: "command line".into(),
        field,
        value,
        reason: reason.into(),
    };
    if a.count == 0 {
        return Err(bad("--count", "0".into(), "use at least 1"));
    }
    if a.threads == 0 || a.threads > crate::optim::evaluate::MAX_THREADS {
        return Err(bad("--threads", a.threads.to_string(), "use 1 to 1024"));
    }
    if a.count > MAX_COUNT {
        return Err(bad("--count", a.count.to_string(), "use at most 1000000"));
    }
    let p = DesignConfig::preset(&a.problem)?.problem(std::path::Path::new("."))?;
    let pts = latin_hypercube(p.bounds(), a.count, a.seed);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(a.threads)
        .build()
        .map_err(|e| bad("--threads", a.threads.to_string(), &e.to_string()))?;
    let evals: Vec<_> = pool.install(|| pts.par_iter().map(|x| p.evaluate(x)).collect());
    let (m, c) = (p.objectives(), p.constraints());
    let exps = |v: &[f64]| v.iter().copied().map(Exp).collect::<Vec<_>>();
    let mut rows = Vec::with_capacity(pts.len());
    let mut feasible = 0usize;
    for (x, e) in pts.iter().zip(evals) {
        let e = e?;
        // The optimisers' violation: a failed evaluation (NaN values) is infeasible, written
        // as an infinite violation (`f64::max` would take NaN for 0: feasible).
        let (mut f, mut g) = (e.objectives.clone(), e.constraints.clone());
        let v = match sanitize(&mut f, &mut g) {
            v if v == f64::MAX => f64::INFINITY,
            v => v,
        };
        feasible += usize::from(v == 0.0);
        rows.push(PopulationRow {
            x: x.iter().map(|&v| Some(Exp(v))).collect(),
            f: exps(&e.objectives),
            g: exps(&e.constraints),
            violation: Exp(v),
        });
    }
    let csv = write_csv(&population_header(p.bounds().dim(), m, c), rows)
        .map_err(crate::report::ReportError::from)?;
    write_atomic(&a.out, csv.as_bytes())?;
    writeln!(
        out,
        "{} Latin-hypercube points of {} (seed {}): {} feasible; wrote {}",
        a.count,
        a.problem,
        a.seed,
        feasible,
        a.out.display()
    )?;
    Ok(())
}
