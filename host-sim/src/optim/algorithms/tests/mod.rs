//! Algorithm tests: bad settings, determinism across tell order and thread count,
//! checkpoint/resume, constraint handling, and fast convergence checks with fixed seeds.
//! Thresholds come from measured runs (see docs/reference/optimisers.md); heavier runs are `#[ignore]`.

use std::sync::Arc;

use super::*;
use crate::optim::algorithm::Algorithm;
use crate::optim::error::{ConfigError, EvalError, OptimError};
use crate::optim::evaluate::{Rayon, Serial, evolve};
use crate::optim::hypervolume::hypervolume;
use crate::optim::observe::{History, NoObserver};
use crate::optim::population::feasible_front;
use crate::optim::problem::{Bounds, Evaluation, Problem, RealProblem};
use crate::optim::problems::{Constr, Dtlz, TestProblem, Zdt};
use crate::optim::rng::OptimRng;
use crate::optim::weights::WeightGeneration;

fn moead(pop: usize, seed: u64) -> Moead {
    Moead::new(
        MoeadConfig {
            population: pop,
            neighbours: 20.min(pop / 4).max(2),
            ..MoeadConfig::default()
        },
        seed,
    )
}

fn nsga2(pop: usize, seed: u64) -> Nsga2 {
    Nsga2::new(
        Nsga2Config {
            population: pop,
            ..Nsga2Config::default()
        },
        seed,
    )
}

/// Hypervolume of the final feasible front divided by the true front's.
fn hv_ratio<A: Algorithm<TestProblem>>(alg: &A, p: &TestProblem) -> f64 {
    let r = p.reference_point();
    let front = feasible_front(alg.population());
    hypervolume(&front, &r).unwrap() / p.front_hypervolume(&r, 2000).unwrap()
}

fn run<A: Algorithm<TestProblem>>(mut alg: A, p: &TestProblem, gens: u64) -> A {
    evolve(&mut alg, p, &Serial, gens, &mut NoObserver).unwrap();
    alg
}

mod archive;
mod convergence;
mod variable;
mod variants;

// ---------------------------------------------------------------------------------------
// Bad settings

#[test]
fn bad_settings_are_typed_errors_naming_what_to_change() {
    let zdt = Zdt::standard(1).unwrap();
    let dtlz = Dtlz::standard(2, 3).unwrap();
    let err = |r: Result<&[Vec<f64>], OptimError>| match r {
        Err(OptimError::Config(c)) => c,
        other => panic!("expected a config error, got {other:?}"),
    };
    let e = err(moead(100, 0).ask(&dtlz));
    assert_eq!(
        e,
        ConfigError::GridSize {
            population: 100,
            objectives: 3,
            below: 91,
            above: 105
        }
    );
    let e = err(Moead::new(
        MoeadConfig {
            population: 10,
            neighbours: 10,
            weights: WeightGeneration::Random,
            ..MoeadConfig::default()
        },
        0,
    )
    .ask(&zdt));
    assert_eq!(
        e,
        ConfigError::TooManyNeighbours {
            neighbours: 10,
            population: 10
        }
    );
    assert!(e.to_string().contains("at most 9"), "{e}");
    let e = err(Moead::new(
        MoeadConfig {
            f: 1.5,
            ..MoeadConfig::default()
        },
        0,
    )
    .ask(&zdt));
    assert!(matches!(e, ConfigError::Parameter { name: "f", .. }));
    let e = err(nsga2(30, 0).ask(&zdt));
    assert!(e.to_string().contains("use 28 or 32"), "{e}");
    let e = err(nsga2(4, 0).ask(&zdt));
    assert!(matches!(
        e,
        ConfigError::PopulationTooSmall { minimum: 8, .. }
    ));

    struct NoObjectives(Bounds);
    impl Problem for NoObjectives {
        type Decision = Vec<f64>;
        fn objectives(&self) -> usize {
            0
        }
        fn evaluate(&self, _: &Vec<f64>) -> Result<Evaluation, EvalError> {
            Ok(Evaluation::default())
        }
    }
    impl RealProblem for NoObjectives {
        fn bounds(&self) -> &Bounds {
            &self.0
        }
    }
    let p = NoObjectives(Bounds::uniform(2, 0.0, 1.0).unwrap());
    assert_eq!(err(nsga2(8, 0).ask(&p)), ConfigError::ZeroObjectives);
    assert_eq!(err(moead(100, 0).ask(&p)), ConfigError::ZeroObjectives);
}

// ---------------------------------------------------------------------------------------
// Reproducibility

/// Drive ask/tell by hand, telling each batch in a shuffled order.
fn run_shuffled<A: Algorithm<TestProblem>>(alg: &mut A, p: &TestProblem, gens: u64, seed: u64) {
    let mut order_rng = OptimRng::new(seed);
    while !(alg.is_initialised() && alg.generation() >= gens) {
        let batch = alg.ask(p).unwrap().to_vec();
        let mut order: Vec<usize> = (0..batch.len()).collect();
        order_rng.shuffle(&mut order);
        for i in order {
            let e = p.evaluate(&batch[i]).unwrap();
            alg.tell(p, i, e).unwrap();
        }
    }
}

#[test]
fn same_seed_same_population_whatever_tell_order_and_thread_count() {
    let p = TestProblem::Zdt(Zdt::standard(1).unwrap());
    let pool1 = Arc::new(
        rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap(),
    );
    let pool4 = Arc::new(
        rayon::ThreadPoolBuilder::new()
            .num_threads(4)
            .build()
            .unwrap(),
    );
    let batched = |seed| {
        Moead::new(
            MoeadConfig {
                population: 20,
                neighbours: 5,
                batch_size: 7,
                ..MoeadConfig::default()
            },
            seed,
        )
    };
    // MOEA/D with batches of 7 (7 + 7 + 6 per generation of 20) and NSGA-II.
    let mut a = batched(42);
    evolve(
        &mut a,
        &p,
        &Rayon::with_pool(pool1.clone()),
        6,
        &mut NoObserver,
    )
    .unwrap();
    let mut b = batched(42);
    evolve(
        &mut b,
        &p,
        &Rayon::with_pool(pool4.clone()),
        6,
        &mut NoObserver,
    )
    .unwrap();
    let mut c = batched(42);
    run_shuffled(&mut c, &p, 6, 9);
    assert_eq!(a, b);
    assert_eq!(a, c);
    let mut other = batched(43);
    evolve(&mut other, &p, &Serial, 6, &mut NoObserver).unwrap();
    assert_ne!(a.population(), other.population());

    let mut a = nsga2(20, 7);
    evolve(&mut a, &p, &Rayon::with_pool(pool1), 6, &mut NoObserver).unwrap();
    let mut b = nsga2(20, 7);
    evolve(&mut b, &p, &Rayon::with_pool(pool4), 6, &mut NoObserver).unwrap();
    let mut c = nsga2(20, 7);
    run_shuffled(&mut c, &p, 6, 10);
    assert_eq!(a, b);
    assert_eq!(a, c);
}

fn resume_is_bit_identical<A>(make: impl Fn() -> A, p: &TestProblem)
where
    A: Algorithm<TestProblem>
        + serde::Serialize
        + serde::de::DeserializeOwned
        + PartialEq
        + std::fmt::Debug,
{
    let mut straight = make();
    evolve(&mut straight, p, &Serial, 10, &mut NoObserver).unwrap();

    let mut first = make();
    evolve(&mut first, p, &Serial, 4, &mut NoObserver).unwrap();
    let json = serde_json::to_string(&first).unwrap();
    drop(first);
    let mut resumed: A = serde_json::from_str(&json).unwrap();
    evolve(&mut resumed, p, &Serial, 6, &mut NoObserver).unwrap();
    assert_eq!(straight.population(), resumed.population());
    assert_eq!(straight.generation(), 10);
    assert_eq!(
        serde_json::to_string(&straight).unwrap(),
        serde_json::to_string(&resumed).unwrap()
    );
}

#[test]
fn checkpoint_and_resume_give_the_bit_identical_run() {
    let zdt = TestProblem::Zdt(Zdt::standard(2).unwrap());
    let constr = TestProblem::Constr(Constr::default());
    for p in [&zdt, &constr] {
        resume_is_bit_identical(|| moead(20, 5), p);
        resume_is_bit_identical(|| nsga2(20, 5), p);
    }
    // Mid-batch: checkpoint after telling part of a batch, resume, tell the rest.
    let mut straight = nsga2(16, 3);
    run_shuffled(&mut straight, &zdt, 3, 1);
    let mut part = nsga2(16, 3);
    run_shuffled(&mut part, &zdt, 2, 1);
    let batch = part.ask(&zdt).unwrap().to_vec();
    let mut order_rng = OptimRng::new(1);
    let mut order: Vec<usize> = (0..batch.len()).collect();
    order_rng.shuffle(&mut order);
    for &i in &order[..5] {
        part.tell(&zdt, i, zdt.evaluate(&batch[i]).unwrap())
            .unwrap();
    }
    let mut resumed: Nsga2 = serde_json::from_str(&serde_json::to_string(&part).unwrap()).unwrap();
    assert_eq!(resumed.ask(&zdt).unwrap(), batch.as_slice());
    for &i in &order[5..] {
        resumed
            .tell(&zdt, i, zdt.evaluate(&batch[i]).unwrap())
            .unwrap();
    }
    assert_eq!(resumed.generation(), 3);
    assert_eq!(resumed.population(), straight.population());
    // `evolve` on a checkpoint taken mid-batch evaluates only the untold decisions.
    let mut again: Nsga2 = serde_json::from_str(&serde_json::to_string(&part).unwrap()).unwrap();
    let told = |a: &Nsga2, i| <Nsga2 as Algorithm<TestProblem>>::is_told(a, i);
    assert!(told(&again, order[0]) && !told(&again, order[5]));
    let before = again.evaluations();
    evolve(&mut again, &zdt, &Serial, 1, &mut NoObserver).unwrap();
    assert_eq!(again.evaluations() - before, (batch.len() - 5) as u64);
    assert_eq!(again, resumed);
}

// ---------------------------------------------------------------------------------------
// Evaluation failures and non-finite values

struct Flaky(Bounds);
impl Problem for Flaky {
    type Decision = Vec<f64>;
    fn objectives(&self) -> usize {
        2
    }
    fn evaluate(&self, x: &Vec<f64>) -> Result<Evaluation, EvalError> {
        if x[0] > 0.9 {
            return Err(EvalError::Failed("simulation diverged".into()));
        }
        // NaN objectives in part of the space.
        let f2 = if x[1] > 0.8 {
            f64::NAN
        } else {
            1.0 - x[0] + x[1]
        };
        Ok(Evaluation::new(vec![x[0], f2]))
    }
}
impl RealProblem for Flaky {
    fn bounds(&self) -> &Bounds {
        &self.0
    }
}

#[test]
fn failed_evaluation_stops_evolve_with_its_index_and_nan_never_reaches_the_front() {
    let p = Flaky(Bounds::uniform(2, 0.0, 1.0).unwrap());
    let mut a = nsga2(40, 1);
    match evolve(&mut a, &p, &Serial, 5, &mut NoObserver) {
        Err(OptimError::Evaluation {
            index,
            generation: 0,
            source,
        }) => {
            assert!(index < 40);
            assert!(source.to_string().contains("diverged"));
        }
        other => panic!("{other:?}"),
    }
    // Telling NaN objectives directly: stored as failed, never on the front, never NaN.
    let mut a = moead(10, 1);
    let mut hist = History::with_reference(vec![2.0, 2.0]);
    let p2 = Zdt::new(1, 2).unwrap();
    while !(a.is_initialised() && a.generation() >= 3) {
        let batch = a.ask(&p2).unwrap().to_vec();
        for (i, x) in batch.iter().enumerate() {
            let mut e = p2.evaluate(x).unwrap();
            if x[1] > 0.5 {
                e.objectives[1] = f64::NAN;
            }
            a.tell(&p2, i, e).unwrap();
        }
    }
    assert!(
        a.population()
            .iter()
            .all(|i| i.objectives.iter().all(|v| !v.is_nan()))
    );
    let front = feasible_front(a.population());
    assert!(!front.is_empty() && front.iter().all(|f| f[1] < 10.0));
    evolve(&mut a, &p2, &Serial, 2, &mut hist).unwrap();
    assert_eq!(hist.records.len(), 2);
    assert!(
        hist.records
            .iter()
            .all(|r| r.hypervolume.is_some_and(f64::is_finite))
    );
}

#[test]
fn observer_sees_generation_zero_then_every_generation() {
    let p = TestProblem::Zdt(Zdt::standard(1).unwrap());
    let mut a = nsga2(20, 4);
    let mut hist = History::with_reference(vec![11.0, 11.0]);
    evolve(&mut a, &p, &Serial, 3, &mut hist).unwrap();
    let gens: Vec<(u64, u64)> = hist
        .records
        .iter()
        .map(|r| (r.generation, r.evaluations))
        .collect();
    assert_eq!(gens, vec![(0, 20), (1, 40), (2, 60), (3, 80)]);
    // Elitist survival: on this seed the hypervolume never decreases (crowding truncation
    // could in principle lose a little).
    let hv: Vec<f64> = hist
        .records
        .iter()
        .map(|r| r.hypervolume.unwrap())
        .collect();
    assert!(hv.windows(2).all(|w| w[1] >= w[0]), "{hv:?}");
    assert!(
        hist.records
            .iter()
            .all(|r| r.feasible_fraction == 1.0 && r.min_violation == 0.0)
    );
    // A closure is an observer too; a second evolve continues from generation 3.
    let mut seen = Vec::new();
    evolve(
        &mut a,
        &p,
        &Serial,
        2,
        &mut |r: &crate::optim::GenerationReport<'_, Vec<f64>>| {
            seen.push((r.algorithm, r.generation, r.population.len()));
        },
    )
    .unwrap();
    assert_eq!(seen, vec![("nsga2", 4, 20), ("nsga2", 5, 20)]);
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(24))]

    /// Any seed, batch size and tell order: the run equals the one told in index order.
    #[test]
    fn tell_order_never_changes_the_run(seed in 0u64..1000, batch in 1usize..=12, order_seed in 0u64..1000) {
        let p = TestProblem::Constr(Constr::default());
        let make = || {
            Moead::new(
                MoeadConfig {
                    population: 12,
                    neighbours: 4,
                    weights: WeightGeneration::LowDiscrepancy,
                    batch_size: batch,
                    ..MoeadConfig::default()
                },
                seed,
            )
        };
        let mut in_order = make();
        evolve(&mut in_order, &p, &Serial, 4, &mut NoObserver).unwrap();
        let mut shuffled = make();
        run_shuffled(&mut shuffled, &p, 4, order_seed);
        proptest::prop_assert_eq!(&in_order, &shuffled);
        let mut a = nsga2(12, seed);
        evolve(&mut a, &p, &Serial, 3, &mut NoObserver).unwrap();
        let mut b = nsga2(12, seed);
        run_shuffled(&mut b, &p, 3, order_seed);
        proptest::prop_assert_eq!(a, b);
    }
}
