//! MHACO tests: bad settings, determinism (tell order, threads), checkpoint/resume, non-finite
//! objectives, `evalstop`, both constraint modes, and convergence with fixed seeds (thresholds
//! from measured runs, docs/reference/optimisers.md; the heavy runs are `#[ignore]`d).

use std::sync::Arc;

use super::*;
use crate::optim::error::EvalError;
use crate::optim::evaluate::{Rayon, Serial, evolve};
use crate::optim::hypervolume::hypervolume;
use crate::optim::observe::{History, NoObserver};
use crate::optim::population::feasible_front;
use crate::optim::problem::{Bounds, Problem};
use crate::optim::problems::{Constr, Dtlz, TestProblem, Zdt};

fn mhaco(population: usize, ker: usize, seed: u64) -> Mhaco {
    Mhaco::new(
        MhacoConfig {
            population,
            ker,
            ..MhacoConfig::default()
        },
        seed,
    )
}

/// The settings used for the convergence figures (docs/reference/optimisers.md): pagmo's defaults with
/// a longer standard-deviation period, n_gen_mark 15.
pub(crate) fn recommended(population: usize, ker: usize, seed: u64) -> Mhaco {
    Mhaco::new(
        MhacoConfig {
            population,
            ker,
            n_gen_mark: 15,
            ..MhacoConfig::default()
        },
        seed,
    )
}

fn hv_ratio(alg: &Mhaco, p: &TestProblem) -> f64 {
    let r = p.reference_point();
    let front = feasible_front(alg.population());
    hypervolume(&front, &r).unwrap() / p.front_hypervolume(&r, 2000).unwrap()
}

fn run(mut alg: Mhaco, p: &TestProblem, gens: u64) -> Mhaco {
    evolve(&mut alg, p, &Serial, gens, &mut NoObserver).unwrap();
    alg
}

/// Drive ask/tell by hand, telling each batch in a shuffled order.
fn run_shuffled<P: Problem<Decision = Vec<f64>> + RealProblem>(
    alg: &mut Mhaco,
    p: &P,
    gens: u64,
    seed: u64,
) {
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
fn mhaco_bad_settings_are_typed_errors() {
    let zdt = TestProblem::Zdt(Zdt::standard(1).unwrap());
    let err = |mut a: Mhaco| match a.ask(&zdt) {
        Err(OptimError::Config(c)) => c,
        other => panic!("expected a config error, got {other:?}"),
    };
    let e = err(mhaco(50, 63, 0));
    assert!(
        matches!(
            e,
            ConfigError::Count {
                value: 63,
                range: "[2, population]",
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("ker"), "{e}");
    assert!(matches!(
        err(mhaco(50, 1, 0)),
        ConfigError::Count { value: 1, .. }
    ));
    let with = |f: fn(&mut MhacoConfig)| {
        let mut c = MhacoConfig::default();
        f(&mut c);
        Mhaco::new(c, 0)
    };
    assert!(matches!(
        err(with(|c| c.q = 0.0)),
        ConfigError::Parameter { name: "q", .. }
    ));
    assert!(matches!(
        err(with(|c| c.threshold = 0)),
        ConfigError::Count {
            name: "threshold",
            ..
        }
    ));
    assert!(matches!(
        err(with(|c| c.focus = -1.0)),
        ConfigError::Parameter { name: "focus", .. }
    ));
    let constr = TestProblem::Constr(Constr::default());
    let mut a = with(|c| {
        c.constraints = ConstraintHandling::AsObjectives {
            scales: Some(vec![1.0]),
            cap: 2.0,
            penalty: 0.5,
        }
    });
    assert!(matches!(
        a.ask(&constr),
        Err(OptimError::Config(ConfigError::Count { value: 1, .. }))
    ));
}

#[test]
fn mhaco_same_seed_same_run_whatever_tell_order_and_thread_count() {
    let p = TestProblem::Zdt(Zdt::new(1, 8).unwrap());
    let pool = |n| {
        Arc::new(
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap(),
        )
    };
    let mut a = mhaco(20, 10, 42);
    evolve(&mut a, &p, &Rayon::with_pool(pool(1)), 8, &mut NoObserver).unwrap();
    let mut b = mhaco(20, 10, 42);
    evolve(&mut b, &p, &Rayon::with_pool(pool(4)), 8, &mut NoObserver).unwrap();
    let mut c = mhaco(20, 10, 42);
    run_shuffled(&mut c, &p, 8, 9);
    assert_eq!(a, b);
    assert_eq!(a, c);
    assert_eq!(a.evaluations(), 20 * 9);
    let mut other = mhaco(20, 10, 43);
    evolve(&mut other, &p, &Serial, 8, &mut NoObserver).unwrap();
    assert_ne!(a.archive(), other.archive());
}

#[test]
fn mhaco_checkpoint_and_resume_give_the_bit_identical_run() {
    let zdt = TestProblem::Zdt(Zdt::new(2, 6).unwrap());
    let constr = TestProblem::Constr(Constr::default());
    for (p, handling) in [
        (&zdt, ConstraintHandling::FeasibilityFirst),
        (&constr, ConstraintHandling::FeasibilityFirst),
        (&constr, ConstraintHandling::thesis_objectives()),
    ] {
        let make = || {
            Mhaco::new(
                MhacoConfig {
                    population: 16,
                    ker: 8,
                    threshold: 5,
                    constraints: handling.clone(),
                    ..MhacoConfig::default()
                },
                5,
            )
        };
        let straight = run(make(), p, 10);
        let first = run(make(), p, 4);
        let json = serde_json::to_string(&first).unwrap();
        let resumed: Mhaco = serde_json::from_str(&json).unwrap();
        let resumed = run(resumed, p, 6);
        assert_eq!(straight, resumed);
        assert_eq!(
            serde_json::to_string(&straight).unwrap(),
            serde_json::to_string(&resumed).unwrap()
        );
    }
    // Mid-batch.
    let mut straight = mhaco(16, 8, 3);
    run_shuffled(&mut straight, &zdt, 3, 1);
    let mut part = mhaco(16, 8, 3);
    run_shuffled(&mut part, &zdt, 2, 1);
    let batch = part.ask(&zdt).unwrap().to_vec();
    for (i, x) in batch.iter().enumerate().take(5) {
        part.tell(&zdt, i, zdt.evaluate(x).unwrap()).unwrap();
    }
    let mut resumed: Mhaco = serde_json::from_str(&serde_json::to_string(&part).unwrap()).unwrap();
    assert_eq!(resumed.ask(&zdt).unwrap(), batch.as_slice());
    for (i, x) in batch.iter().enumerate().skip(5) {
        resumed.tell(&zdt, i, zdt.evaluate(x).unwrap()).unwrap();
    }
    assert_eq!(resumed, straight);
    // Mid-batch through `evolve`: only the untold decisions are evaluated.
    let mut part = mhaco(16, 8, 3);
    run_shuffled(&mut part, &zdt, 2, 1);
    let batch = part.ask(&zdt).unwrap().to_vec();
    for (i, x) in batch.iter().enumerate().skip(9) {
        part.tell(&zdt, i, zdt.evaluate(x).unwrap()).unwrap();
    }
    let mut resumed: Mhaco = serde_json::from_str(&serde_json::to_string(&part).unwrap()).unwrap();
    evolve(&mut resumed, &zdt, &Serial, 1, &mut NoObserver).unwrap();
    assert_eq!(resumed.evaluations(), straight.evaluations());
    assert_eq!(resumed, straight);
}

/// ZDT1 whose objectives turn NaN or infinite in part of the space (issue 9 reports pygmo's
/// `maco` crashing on such values; see docs/reference/optimisers.md for what a check found).
struct Holes(Zdt);
impl Problem for Holes {
    type Decision = Vec<f64>;
    fn objectives(&self) -> usize {
        2
    }
    fn evaluate(&self, x: &Vec<f64>) -> Result<Evaluation, EvalError> {
        let mut e = self.0.evaluate(x)?;
        if x[1] > 0.6 {
            e.objectives[1] = f64::NAN;
        } else if x[2] > 0.6 {
            e.objectives[0] = f64::INFINITY;
        }
        Ok(e)
    }
}
impl RealProblem for Holes {
    fn bounds(&self) -> &Bounds {
        self.0.bounds()
    }
}

#[test]
fn mhaco_survives_non_finite_objectives_and_keeps_them_out_of_the_hypervolume() {
    let p = Holes(Zdt::new(1, 6).unwrap());
    for handling in [
        ConstraintHandling::FeasibilityFirst,
        ConstraintHandling::thesis_objectives(),
    ] {
        let mut a = Mhaco::new(
            MhacoConfig {
                population: 30,
                ker: 20,
                constraints: handling,
                ..MhacoConfig::default()
            },
            2,
        );
        let mut hist = History::with_reference(vec![1.1, 1.1]);
        evolve(&mut a, &p, &Serial, 20, &mut hist).unwrap();
        assert_eq!(hist.records.len(), 21);
        assert!(
            hist.records
                .iter()
                .all(|r| r.hypervolume.is_some_and(|h| h.is_finite() && h >= 0.0))
        );
        // The archive holds only finite individuals and improved on the initial population.
        assert!(a.archive().iter().all(|i| !i.is_failed()));
        assert!(hist.records[20].hypervolume > hist.records[0].hypervolume);
    }
}

/// Constant objectives: the ideal point never improves, so `evalstop` generations later the
/// run stops and `evolve` returns early.
struct Flat(Bounds);
impl Problem for Flat {
    type Decision = Vec<f64>;
    fn objectives(&self) -> usize {
        2
    }
    fn evaluate(&self, _: &Vec<f64>) -> Result<Evaluation, EvalError> {
        Ok(Evaluation::new(vec![1.0, 1.0]))
    }
}
impl RealProblem for Flat {
    fn bounds(&self) -> &Bounds {
        &self.0
    }
}

#[test]
fn mhaco_evalstop_ends_a_stalled_run() {
    let p = Flat(Bounds::uniform(3, 0.0, 1.0).unwrap());
    let mut a = Mhaco::new(
        MhacoConfig {
            population: 10,
            ker: 5,
            evalstop: 4,
            ..MhacoConfig::default()
        },
        1,
    );
    evolve(&mut a, &p, &Serial, 100, &mut NoObserver).unwrap();
    assert!(a.is_finished());
    assert_eq!(a.generation(), 4);
    assert_eq!(a.stalls(), 4);
    assert!(a.ask(&p).unwrap().is_empty());
    // gen_mark: 1 -> 2 (initial), then stalls 1, 2 keep it, stalls 3, 4 advance it.
    assert_eq!(a.gen_mark(), 4);
}

fn constr_ratio(handling: ConstraintHandling) -> f64 {
    let p = TestProblem::Constr(Constr::default());
    let a = run(
        Mhaco::new(
            MhacoConfig {
                population: 40,
                ker: 20,
                n_gen_mark: 15,
                constraints: handling.clone(),
                ..MhacoConfig::default()
            },
            2,
        ),
        &p,
        100,
    );
    let r = hv_ratio(&a, &p);
    println!("mhaco {handling:?} constr hypervolume ratio {r:.4}");
    assert!(
        a.archive().iter().take(10).all(|i| i.is_feasible()),
        "{handling:?}"
    );
    r
}

#[test]
fn mhaco_feasibility_first_ends_feasible_near_the_constr_front() {
    let r = constr_ratio(ConstraintHandling::FeasibilityFirst);
    assert!(r > MHACO_CONSTR_FEASIBILITY_FIRST, "ratio {r}");
}

/// The thesis' constraints-as-objectives mode on CONSTR (unit scales): the normalised
/// constraint objectives reward feasible points deep inside the feasible region, which pulls
/// the archive away from the front; the feasibility-first archive does much better (the
/// thesis' sec. 10.2 expectation). Heavy in debug builds: the ranking works in 4-D.
#[test]
#[ignore = "heavy in debug builds: run in release"]
fn mhaco_constraints_as_objectives_on_constr_trail_feasibility_first() {
    let r = constr_ratio(ConstraintHandling::thesis_objectives());
    assert!(r > MHACO_CONSTR_AS_OBJECTIVES, "ratio {r}");
    assert!(r < constr_ratio(ConstraintHandling::FeasibilityFirst));
}

// Thresholds: the measured ratio of these seeds (docs/reference/optimisers.md) less about 2 %.
const MHACO_CONSTR_FEASIBILITY_FIRST: f64 = 0.93;
const MHACO_CONSTR_AS_OBJECTIVES: f64 = 0.17;
const MHACO_ZDT1: f64 = 0.96;
const MHACO_DTLZ2: f64 = 0.83;

#[test]
fn mhaco_converges_on_zdt1() {
    let zdt1 = TestProblem::Zdt(Zdt::standard(1).unwrap());
    let r = hv_ratio(&run(recommended(100, 63, 1), &zdt1, 250), &zdt1);
    println!("mhaco zdt1 {r:.4}");
    assert!(r > MHACO_ZDT1, "zdt1 {r}");
}

#[test]
#[ignore = "heavy in debug builds: run in release"]
fn mhaco_converges_on_dtlz2() {
    let dtlz2 = TestProblem::Dtlz(Dtlz::standard(2, 3).unwrap());
    let r = hv_ratio(&run(recommended(92, 63, 1), &dtlz2, 250), &dtlz2);
    println!("mhaco dtlz2 {r:.4}");
    assert!(r > MHACO_DTLZ2, "dtlz2 {r}");
}

/// ZDT1 (30 variables), population 100, 250 generations, seeds 1..=10, for several settings:
/// median/min/max hypervolume w.r.t. (1.1, 1.1) (release: `cargo test --release -p host-sim
/// --lib mhaco_zdt1_table -- --ignored --nocapture`).
#[test]
#[ignore = "heavy: run in release"]
fn mhaco_zdt1_table() {
    let p = TestProblem::Zdt(Zdt::standard(1).unwrap());
    let settings: Vec<(&str, MhacoConfig)> = {
        let base = MhacoConfig::default();
        let mut v = vec![("pagmo defaults", base.clone())];
        for (ker, threshold, n_gen_mark) in [
            (63, 1, 15),
            (63, 1, 20),
            (63, 240, 15),
            (63, 240, 20),
            (63, 250, 15),
            (63, 200, 15),
            (50, 240, 15),
        ] {
            v.push((
                "tuned",
                MhacoConfig {
                    ker,
                    threshold,
                    n_gen_mark,
                    ..base.clone()
                },
            ));
        }
        v
    };
    for (name, config) in settings {
        let start = std::time::Instant::now();
        let mut hv: Vec<f64> = (1..=10)
            .map(|seed| {
                let a = run(Mhaco::new(config.clone(), seed), &p, 250);
                hypervolume(&feasible_front(a.population()), &[1.1, 1.1]).unwrap()
            })
            .collect();
        let per_run = start.elapsed().as_secs_f64() / 10.0;
        hv.sort_by(f64::total_cmp);
        println!(
            "{name:15} ker {:3} threshold {:3} n_gen_mark {:2}: median {:.4} min {:.4} max {:.4} ({:.1} ms/run)",
            config.ker,
            config.threshold,
            config.n_gen_mark,
            0.5 * (hv[4] + hv[5]),
            hv[0],
            hv[9],
            per_run * 1e3
        );
    }
}

/// Every fixed-length test problem, population 100 (92 for three objectives), ker 63,
/// n_gen_mark 15, 250 generations, seeds 1..=3: hypervolume ratios (release: `cargo test
/// --release -p host-sim --lib mhaco_convergence_table -- --ignored --nocapture`).
#[test]
#[ignore = "heavy: run in release"]
fn mhaco_convergence_table() {
    for name in crate::optim::problems::NAMES {
        let p = TestProblem::by_name(name, 3).unwrap().unwrap();
        let pop = if p.objectives() == 2 { 100 } else { 92 };
        let mut line = format!("{name:8}");
        for seed in 1..=3 {
            let r = hv_ratio(&run(recommended(pop, 63, seed), &p, 250), &p);
            line += &format!("  {r:.4}");
        }
        println!("{line}");
    }
}
