//! [`Executor`]: one optimisation run (argmin's `Executor` is the model). It owns the loop:
//! the initial population, then one generation after the other until the [`Budget`] is spent,
//! the algorithm finishes or a stop is requested (Ctrl-C: the front end passes its stop flag,
//! the library never installs a handler and never prints); the evaluator ([`Threads`]: serial
//! or a pool of N threads, one dispatch); an observer of every generation's report (records,
//! progress) and an after-generation hook (checkpoints), called after the initial population
//! and after each generation with the algorithm's whole state.
//!
//! Stepping one generation at a time gives the same run as [`evolve`] over all of them: the
//! ask/tell sequence, and so every result, is bit-identical (tested below).

use std::time::Instant;

use super::algorithm::Algorithm;
use super::error::OptimError;
use super::evaluate::{BatchEvaluator, External, Threads, evolve};
use super::observe::{NoObserver, Observer};
use super::problem::Problem;

/// How long a run goes on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Budget {
    /// Until the algorithm's generation counter reaches this (the initial population is
    /// generation 0; a resumed run continues to the same total).
    Generations(u64),
    /// The fewest whole generations whose evaluations (initial population included) reach
    /// this many.
    Evaluations(u64),
}

/// Why a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// The budget is spent.
    Budget,
    /// The algorithm says it is finished ([`Algorithm::is_finished`]).
    Finished,
    /// A stop was requested; the algorithm holds the last complete generation (or the
    /// initial population, or nothing when stopped before it was complete).
    Interrupted,
}

/// A finished (or stopped) run.
#[derive(Debug)]
pub struct Run<A> {
    /// The algorithm with its final state.
    pub algorithm: A,
    /// Why the run ended.
    pub stop: Stop,
    /// Generations completed by this run (the initial population not counted).
    pub generations: u64,
    /// Wall-clock time of this run \[s\].
    pub wall_time_s: f64,
}

/// How a run evaluates its batches: on its [`Threads`], or by a [`BatchEvaluator`] from
/// outside the library.
enum Evaluation<'a, D> {
    Threads(Threads),
    External(&'a dyn BatchEvaluator<D>),
}

/// One optimisation run of algorithm `A` on problem `P`: build it, set what differs from the
/// defaults (budget 0 generations, serial evaluation, no observer, no stop), then
/// [`Executor::run`] or [`Executor::run_with`].
///
/// ```
/// use host_sim::optim::problems::Zdt;
/// use host_sim::optim::{Algorithm, Budget, Executor, Nsga2, Nsga2Config, Stop, Threads};
/// let problem = Zdt::new(1, 30)?;
/// let run = Executor::new(&problem, Nsga2::new(Nsga2Config::default(), 1))
///     .budget(Budget::Evaluations(2_000))
///     .threads(Threads::new(2)?)
///     .run()?;
/// assert_eq!(run.stop, Stop::Budget);
/// let evaluations = Algorithm::<Zdt>::evaluations(&run.algorithm);
/// assert_eq!((run.generations, evaluations), (19, 2_000));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Executor<'a, P: Problem, A> {
    problem: &'a P,
    algorithm: A,
    budget: Budget,
    evaluation: Evaluation<'a, P::Decision>,
    observer: Option<&'a mut dyn Observer<P::Decision>>,
    stop: Option<&'a dyn Fn() -> bool>,
}

impl<'a, P: Problem, A: Algorithm<P>> Executor<'a, P, A> {
    /// A run of `algorithm` (fresh, or restored from a checkpoint) on `problem`.
    #[must_use]
    pub fn new(problem: &'a P, algorithm: A) -> Self {
        Self {
            problem,
            algorithm,
            budget: Budget::Generations(0),
            evaluation: Evaluation::Threads(Threads::serial()),
            observer: None,
            stop: None,
        }
    }

    /// How long to run.
    #[must_use]
    pub fn budget(mut self, budget: Budget) -> Self {
        self.budget = budget;
        self
    }

    /// Evaluate the batches on these threads (the default: serially).
    #[must_use]
    pub fn threads(mut self, threads: Threads) -> Self {
        self.evaluation = Evaluation::Threads(threads);
        self
    }

    /// Evaluate the batches with `evaluator` instead (a front end's, e.g. over a Dask
    /// cluster): the run is the same as on threads when it returns the problem's own
    /// evaluations.
    #[must_use]
    pub fn external(mut self, evaluator: &'a dyn BatchEvaluator<P::Decision>) -> Self {
        self.evaluation = Evaluation::External(evaluator);
        self
    }

    /// The observer of every generation's report (the initial population's included).
    #[must_use]
    pub fn observer(mut self, observer: &'a mut dyn Observer<P::Decision>) -> Self {
        self.observer = Some(observer);
        self
    }

    /// A stop request (Ctrl-C): asked before every generation and after the last; when it
    /// says stop, the run ends with [`Stop::Interrupted`] at that generation boundary, and an
    /// evaluation error raised while it says stop (an interrupted flight) is no error.
    #[must_use]
    pub fn stop_when(mut self, stop: &'a dyn Fn() -> bool) -> Self {
        self.stop = Some(stop);
        self
    }

    /// Run, without an after-generation hook.
    ///
    /// # Errors
    /// [`OptimError`] of the algorithm or an evaluation.
    pub fn run(self) -> Result<Run<A>, OptimError> {
        self.run_with(|_: &A| Ok::<(), OptimError>(()))
    }

    /// Run, calling `after` with the algorithm after the initial population and after every
    /// generation (checkpoints, records); its error ends the run.
    ///
    /// # Errors
    /// [`OptimError`] of the algorithm or an evaluation (as `E`), or `after`'s error.
    pub fn run_with<E: From<OptimError>>(
        self,
        mut after: impl FnMut(&A) -> Result<(), E>,
    ) -> Result<Run<A>, E> {
        let Self {
            problem,
            mut algorithm,
            budget,
            evaluation,
            observer,
            stop,
        } = self;
        let mut none = NoObserver;
        let observer: &mut dyn Observer<P::Decision> = match observer {
            Some(o) => o,
            None => &mut none,
        };
        let stopped = || stop.is_some_and(|s| s());
        let start = Instant::now();
        let first = algorithm.generation();
        let mut step = |algorithm: &mut A, generations: u64| -> Result<bool, E> {
            let evolved = match &evaluation {
                Evaluation::Threads(t) => {
                    evolve(algorithm, problem, t, generations, &mut *observer)
                }
                Evaluation::External(e) => evolve(
                    algorithm,
                    problem,
                    &External(*e),
                    generations,
                    &mut *observer,
                ),
            };
            match evolved {
                Err(_) if stopped() => Ok(false),
                Err(e) => Err(e.into()),
                Ok(()) => Ok(true),
            }
        };
        let mut end = Stop::Budget;
        if !algorithm.is_initialised() {
            if !step(&mut algorithm, 0)? {
                end = Stop::Interrupted;
            } else {
                after(&algorithm)?;
            }
        }
        while end != Stop::Interrupted {
            let spent = match budget {
                Budget::Generations(g) => algorithm.generation() >= g,
                Budget::Evaluations(e) => algorithm.evaluations() >= e,
            };
            if spent {
                break;
            }
            if algorithm.is_finished() {
                end = Stop::Finished;
                break;
            }
            if stopped() || !step(&mut algorithm, 1)? {
                end = Stop::Interrupted;
                break;
            }
            after(&algorithm)?;
        }
        if stopped() {
            end = Stop::Interrupted;
        }
        Ok(Run {
            generations: algorithm.generation().saturating_sub(first),
            wall_time_s: start.elapsed().as_secs_f64(),
            algorithm,
            stop: end,
        })
    }
}

#[cfg(test)]
mod tests {
    use std::cell::Cell;

    use super::*;
    use crate::optim::problems::Zdt;
    use crate::optim::{Moead, MoeadConfig, Nsga2, Nsga2Config};

    fn objectives<A: Algorithm<Zdt>>(a: &A) -> Vec<Vec<u64>> {
        a.population()
            .iter()
            .map(|i| i.objectives.iter().map(|v| v.to_bits()).collect())
            .collect()
    }

    /// The executor's generation-by-generation loop is the same run as one `evolve` call,
    /// bit for bit, serial and on 3 threads.
    #[test]
    fn stepping_is_bit_identical_to_evolve() {
        let p = Zdt::new(1, 10).unwrap();
        let config = MoeadConfig {
            population: 30,
            neighbours: 10,
            batch_size: 4,
            ..MoeadConfig::default()
        };
        let mut reference = Moead::new(config.clone(), 5);
        evolve(&mut reference, &p, &Threads::serial(), 12, &mut NoObserver).unwrap();
        for t in [1, 3] {
            let run = Executor::new(&p, Moead::new(config.clone(), 5))
                .budget(Budget::Generations(12))
                .threads(Threads::new(t).unwrap())
                .run()
                .unwrap();
            assert_eq!((run.stop, run.generations), (Stop::Budget, 12));
            assert_eq!(
                objectives(&run.algorithm),
                objectives(&reference),
                "{t} threads"
            );
            assert_eq!(
                Algorithm::<Zdt>::evaluations(&run.algorithm),
                Algorithm::<Zdt>::evaluations(&reference)
            );
        }
    }

    /// An evaluation budget runs the fewest whole generations that reach it:
    /// ceil((E - population) / population) for NSGA-II.
    #[test]
    fn evaluation_budget_runs_the_fewest_whole_generations() {
        let p = Zdt::new(1, 5).unwrap();
        let config = Nsga2Config {
            population: 20,
            ..Nsga2Config::default()
        };
        for (e, want) in [(20, 0), (21, 1), (40, 1), (41, 2), (205, 10)] {
            let run = Executor::new(&p, Nsga2::new(config.clone(), 1))
                .budget(Budget::Evaluations(e))
                .run()
                .unwrap();
            assert_eq!(run.generations, want, "E = {e}");
            assert_eq!(
                Algorithm::<Zdt>::evaluations(&run.algorithm),
                20 * (want + 1),
                "E = {e}"
            );
        }
    }

    /// The hook sees the initial population and every generation; a stop request ends the run
    /// at the next generation boundary; a resumed algorithm continues to the same total.
    #[test]
    fn hook_stop_and_resume() {
        let p = Zdt::new(1, 5).unwrap();
        let config = Nsga2Config {
            population: 12,
            ..Nsga2Config::default()
        };
        let mut seen = Vec::new();
        let asks = Cell::new(0);
        // Asked before each generation: the fifth ask says stop.
        let stop = || {
            asks.set(asks.get() + 1);
            asks.get() >= 5
        };
        let run = Executor::new(&p, Nsga2::new(config.clone(), 2))
            .budget(Budget::Generations(10))
            .stop_when(&stop)
            .run_with(|a: &Nsga2| {
                seen.push(Algorithm::<Zdt>::generation(a));
                Ok::<(), OptimError>(())
            })
            .unwrap();
        assert_eq!(run.stop, Stop::Interrupted);
        assert!(seen.len() >= 2 && seen.len() < 11, "{seen:?}");
        assert_eq!(seen, (0..seen.len() as u64).collect::<Vec<_>>());
        let stopped_at = Algorithm::<Zdt>::generation(&run.algorithm);
        let resumed = Executor::new(&p, run.algorithm)
            .budget(Budget::Generations(10))
            .run()
            .unwrap();
        assert_eq!(
            (resumed.stop, resumed.generations),
            (Stop::Budget, 10 - stopped_at)
        );
        let straight = Executor::new(&p, Nsga2::new(config, 2))
            .budget(Budget::Generations(10))
            .run()
            .unwrap();
        assert_eq!(
            objectives(&resumed.algorithm),
            objectives(&straight.algorithm)
        );
    }
}
