//! Batch evaluators (serial, rayon) and [`evolve`], which drives an algorithm's ask/tell loop
//! with one of them and reports every generation to an observer.

use std::sync::Arc;

use rayon::prelude::*;

use super::algorithm::Algorithm;
use super::error::{EvalError, OptimError};
use super::observe::{GenerationReport, Observer};
use super::problem::{Evaluation, Problem};

/// Evaluates a batch of decisions of type `D`; results are returned in batch order.
pub trait Evaluator<D> {
    /// Evaluate every decision of `batch`.
    fn evaluate<P: Problem<Decision = D>>(
        &self,
        problem: &P,
        batch: &[D],
    ) -> Vec<Result<Evaluation, EvalError>>;
}

/// A batch evaluator from outside the library: a front end's map over a batch (the Python
/// package's, which spreads it over a Dask cluster). It gets the decisions of a batch and
/// returns one result per decision, in batch order; it is called from the run's thread, one
/// batch at a time. A run is bit-identical to the in-process run when the evaluator returns
/// what the problem's own `evaluate` would (the Python package's evaluators call it).
/// Closures `Fn(&[D]) -> Vec<Result<Evaluation, EvalError>> + Sync` are batch evaluators.
pub trait BatchEvaluator<D>: Sync {
    /// Evaluate every decision of `batch`.
    fn evaluate_batch(&self, batch: &[D]) -> Vec<Result<Evaluation, EvalError>>;
}

impl<D, F> BatchEvaluator<D> for F
where
    F: Fn(&[D]) -> Vec<Result<Evaluation, EvalError>> + Sync,
{
    fn evaluate_batch(&self, batch: &[D]) -> Vec<Result<Evaluation, EvalError>> {
        self(batch)
    }
}

/// A [`BatchEvaluator`] as an [`Evaluator`]: a result list of the wrong length fails every
/// decision of the batch (the run stops with that error; it never asks again forever).
pub struct External<'a, D>(pub &'a dyn BatchEvaluator<D>);

impl<D> Evaluator<D> for External<'_, D> {
    fn evaluate<P: Problem<Decision = D>>(
        &self,
        _problem: &P,
        batch: &[D],
    ) -> Vec<Result<Evaluation, EvalError>> {
        let out = self.0.evaluate_batch(batch);
        if out.len() == batch.len() {
            return out;
        }
        let got = out.len();
        (0..batch.len())
            .map(|_| {
                Err(EvalError::Failed(
                    format!(
                        "the external evaluator returned {got} results for a batch of {}",
                        batch.len()
                    )
                    .into(),
                ))
            })
            .collect()
    }
}

/// One decision after the other on the calling thread.
#[derive(Clone, Copy, Debug, Default)]
pub struct Serial;

impl<D> Evaluator<D> for Serial {
    fn evaluate<P: Problem<Decision = D>>(
        &self,
        problem: &P,
        batch: &[D],
    ) -> Vec<Result<Evaluation, EvalError>> {
        batch.iter().map(|d| problem.evaluate(d)).collect()
    }
}

/// In parallel on rayon threads: the global pool, or a given one.
#[derive(Clone, Debug, Default)]
pub struct Rayon {
    pool: Option<Arc<rayon::ThreadPool>>,
}

impl Rayon {
    /// Use rayon's global pool.
    #[must_use]
    pub fn global() -> Self {
        Self { pool: None }
    }

    /// Use this pool.
    #[must_use]
    pub fn with_pool(pool: Arc<rayon::ThreadPool>) -> Self {
        Self { pool: Some(pool) }
    }
}

impl<D: Sync> Evaluator<D> for Rayon {
    fn evaluate<P: Problem<Decision = D>>(
        &self,
        problem: &P,
        batch: &[D],
    ) -> Vec<Result<Evaluation, EvalError>> {
        let run = || batch.par_iter().map(|d| problem.evaluate(d)).collect();
        match &self.pool {
            Some(pool) => pool.install(run),
            None => run(),
        }
    }
}

/// Most evaluation threads a command or a campaign accepts (a thread pool of 100 000 threads
/// takes minutes to build and then thrashes); larger counts are refused naming the option.
pub const MAX_THREADS: usize = 1024;

/// How a run evaluates its batches: serially on the calling thread (1 thread) or on its own
/// rayon pool of N threads. The one dispatch every front end uses (`host-sim optimize`, the
/// re-entry and variable-length runs); the result does not depend on the count.
#[derive(Clone, Debug)]
pub struct Threads {
    count: usize,
    pool: Option<Arc<rayon::ThreadPool>>,
}

/// `Threads::new` refused the count or could not start the pool.
#[derive(Debug, thiserror::Error)]
pub enum ThreadsError {
    /// 0, or more than [`MAX_THREADS`].
    #[error("{0} evaluation threads: use 1 to {MAX_THREADS}")]
    Count(usize),
    /// The rayon pool could not be built.
    #[error("cannot start {threads} evaluation threads: {source}")]
    Pool {
        /// Threads asked for.
        threads: usize,
        /// Cause.
        source: rayon::ThreadPoolBuildError,
    },
}

impl Threads {
    /// Serial evaluation (1 thread).
    #[must_use]
    pub fn serial() -> Self {
        Self {
            count: 1,
            pool: None,
        }
    }

    /// `count` evaluation threads: 1 is serial, more build a pool of that size.
    ///
    /// # Errors
    /// [`ThreadsError::Count`] for 0 or above [`MAX_THREADS`], [`ThreadsError::Pool`] if rayon
    /// cannot start the threads.
    pub fn new(count: usize) -> Result<Self, ThreadsError> {
        match count {
            0 => Err(ThreadsError::Count(count)),
            c if c > MAX_THREADS => Err(ThreadsError::Count(count)),
            1 => Ok(Self::serial()),
            c => {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(c)
                    .build()
                    .map_err(|source| ThreadsError::Pool { threads: c, source })?;
                Ok(Self {
                    count: c,
                    pool: Some(Arc::new(pool)),
                })
            }
        }
    }

    /// Number of evaluation threads (1: serial).
    #[must_use]
    pub fn count(&self) -> usize {
        self.count
    }
}

impl<D: Sync> Evaluator<D> for Threads {
    fn evaluate<P: Problem<Decision = D>>(
        &self,
        problem: &P,
        batch: &[D],
    ) -> Vec<Result<Evaluation, EvalError>> {
        match &self.pool {
            Some(pool) => pool.install(|| batch.par_iter().map(|d| problem.evaluate(d)).collect()),
            None => Serial.evaluate(problem, batch),
        }
    }
}

/// Run `generations` more generations of `algorithm` on `problem` (first completing the
/// initial population if needed), evaluating each batch with `evaluator`. The observer sees
/// the initial population (generation 0) and every completed generation.
///
/// On an evaluation error the run stops with [`OptimError::Evaluation`]; the algorithm keeps
/// the evaluations told before it.
///
/// # Errors
/// [`OptimError`] from the algorithm or the evaluation.
///
/// NSGA-II (100 members) on ZDT1 (30 variables) for 100 generations, then the hypervolume of its
/// population (the true front's is 0.8767 w.r.t. (1.1, 1.1)):
///
/// ```
/// use host_sim::optim::hypervolume::hypervolume;
/// use host_sim::optim::problems::Zdt;
/// use host_sim::optim::{Algorithm, NoObserver, Nsga2, Nsga2Config, Serial, evolve};
/// let problem = Zdt::new(1, 30)?;
/// let mut nsga2 = Nsga2::new(Nsga2Config::default(), 1);
/// evolve(&mut nsga2, &problem, &Serial, 100, &mut NoObserver)?;
/// let front: Vec<&[f64]> = nsga2.population().iter().map(|i| i.objectives.as_slice()).collect();
/// let hv = hypervolume(&front, &[1.1, 1.1])?;
/// assert!(hv > 0.75 && hv < 0.8767, "{hv}"); // 0.7996 with seed 1
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn evolve<P, A, E, O>(
    algorithm: &mut A,
    problem: &P,
    evaluator: &E,
    generations: u64,
    observer: &mut O,
) -> Result<(), OptimError>
where
    P: Problem,
    A: Algorithm<P> + ?Sized,
    E: Evaluator<P::Decision> + ?Sized,
    O: Observer<P::Decision> + ?Sized,
{
    let target = if algorithm.is_initialised() {
        algorithm.generation() + generations
    } else {
        generations
    };
    loop {
        let before = (algorithm.is_initialised(), algorithm.generation());
        if (before.0 && before.1 >= target) || algorithm.is_finished() {
            return Ok(());
        }
        // `ask` is idempotent while the batch is open: ask once for its size, once to borrow it.
        let n = algorithm.ask(problem)?.len();
        let generation = before.1 + u64::from(before.0);
        let fail = |index| {
            move |source| OptimError::Evaluation {
                index,
                generation,
                source,
            }
        };
        if (0..n).all(|i| !algorithm.is_told(i)) {
            let results = evaluator.evaluate(problem, algorithm.ask(problem)?);
            for (index, r) in results.into_iter().enumerate() {
                algorithm.tell(problem, index, r.map_err(fail(index))?)?;
            }
        } else {
            // Resumed from a checkpoint taken mid-batch: evaluate only what is missing.
            let untold: Vec<usize> = (0..n).filter(|&i| !algorithm.is_told(i)).collect();
            let batch = algorithm.ask(problem)?;
            let missing: Vec<P::Decision> = untold.iter().map(|&i| batch[i].clone()).collect();
            let results = evaluator.evaluate(problem, &missing);
            for (&index, r) in untold.iter().zip(results) {
                algorithm.tell(problem, index, r.map_err(fail(index))?)?;
            }
        }
        let after = (algorithm.is_initialised(), algorithm.generation());
        if after != before && after.0 {
            observer.observe(&GenerationReport {
                algorithm: algorithm.name(),
                generation: after.1,
                evaluations: algorithm.evaluations(),
                population: algorithm.population(),
                archive: algorithm.external_archive(),
            });
        }
    }
}
