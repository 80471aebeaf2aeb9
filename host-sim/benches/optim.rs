//! Optimiser benchmarks (single thread, serial evaluation): ZDT1 with 30 variables,
//! population 100, 250 generations (25,100 evaluations), MOEA/D and NSGA-II with pagmo's
//! defaults, seeds 1..=10 in turn (one run per iteration). The median hypervolume over the
//! ten seeds (reference point (1.1, 1.1); true front 0.8767) is printed once per algorithm.
//! The `-archive100` variants keep the opt-in external archive of capacity 100 (Zhang & Li's
//! EP, `archive: Some(100)`) and report its front. `moead-dra` is MOEA/D-DRA's resource
//! allocation (Zhang, Liu & Li 2009): 100 / 5 = 20 children per generation, so 1250
//! generations for the same 25,100 evaluations; `moead-sbx` is Zhang & Li's (2007) SBX
//! variation (250 generations).
//! Peer figures (pygmo 2.20): `scripts/compare_pygmo.py`, docs/reference/performance.md.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use host_sim::optim::hypervolume::hypervolume;
use host_sim::optim::population::feasible_front;
use host_sim::optim::problems::Zdt;
use host_sim::optim::{
    Algorithm, Individual, Mhaco, MhacoConfig, Moead, MoeadConfig, MoeadSbx, NoObserver, Nsga2,
    Nsga2Config, ResourceAllocation, SbxVariation, Serial, evolve,
};

const GENERATIONS: u64 = 250;
const SEEDS: u64 = 10;

fn run_moead(problem: &Zdt, seed: u64) -> Vec<Individual<Vec<f64>>> {
    let mut a = Moead::new(MoeadConfig::default(), seed);
    evolve(&mut a, problem, &Serial, GENERATIONS, &mut NoObserver).expect("moead runs");
    a.population().to_vec()
}

fn run_nsga2(problem: &Zdt, seed: u64) -> Vec<Individual<Vec<f64>>> {
    let mut a = Nsga2::new(Nsga2Config::default(), seed);
    evolve(&mut a, problem, &Serial, GENERATIONS, &mut NoObserver).expect("nsga2 runs");
    a.population().to_vec()
}

/// The archive's capacity of the `-archive100` variants (pygmo's output size: the population).
const ARCHIVE: Option<usize> = Some(100);

fn run_moead_archive(problem: &Zdt, seed: u64) -> Vec<Individual<Vec<f64>>> {
    let config = MoeadConfig {
        archive: ARCHIVE,
        ..MoeadConfig::default()
    };
    let mut a = Moead::new(config, seed);
    evolve(&mut a, problem, &Serial, GENERATIONS, &mut NoObserver).expect("moead runs");
    Algorithm::<Zdt>::result(&a).to_vec()
}

fn run_nsga2_archive(problem: &Zdt, seed: u64) -> Vec<Individual<Vec<f64>>> {
    let config = Nsga2Config {
        archive: ARCHIVE,
        ..Nsga2Config::default()
    };
    let mut a = Nsga2::new(config, seed);
    evolve(&mut a, problem, &Serial, GENERATIONS, &mut NoObserver).expect("nsga2 runs");
    Algorithm::<Zdt>::result(&a).to_vec()
}

/// MOEA/D-DRA generations for 25,100 evaluations: (25,100 - 100) / (100 / 5).
const DRA_GENERATIONS: u64 = 1250;

fn run_moead_dra(problem: &Zdt, seed: u64, archive: Option<usize>) -> Vec<Individual<Vec<f64>>> {
    let config = MoeadConfig {
        archive,
        resource_allocation: Some(ResourceAllocation::default()),
        ..MoeadConfig::default()
    };
    let mut a = Moead::new(config, seed);
    evolve(&mut a, problem, &Serial, DRA_GENERATIONS, &mut NoObserver).expect("moead-dra runs");
    assert_eq!(Algorithm::<Zdt>::evaluations(&a), 25_100);
    Algorithm::<Zdt>::result(&a).to_vec()
}

fn run_moead_sbx(problem: &Zdt, seed: u64) -> Vec<Individual<Vec<f64>>> {
    let mut a = MoeadSbx::sbx(MoeadConfig::default(), SbxVariation::default(), seed);
    evolve(&mut a, problem, &Serial, GENERATIONS, &mut NoObserver).expect("moead-sbx runs");
    a.population().to_vec()
}

fn median_hypervolume(run: fn(&Zdt, u64) -> Vec<Individual<Vec<f64>>>, problem: &Zdt) -> Vec<f64> {
    let mut hv: Vec<f64> = (1..=SEEDS)
        .map(|s| hypervolume(&feasible_front(&run(problem, s)), &[1.1, 1.1]).expect("hypervolume"))
        .collect();
    hv.sort_by(f64::total_cmp);
    hv
}

fn bench(c: &mut Criterion) {
    let problem = Zdt::standard(1).expect("zdt1");
    type Run = fn(&Zdt, u64) -> Vec<Individual<Vec<f64>>>;
    let algorithms: [(&str, Run); 7] = [
        ("moead", run_moead),
        ("nsga2", run_nsga2),
        ("moead-archive100", run_moead_archive),
        ("nsga2-archive100", run_nsga2_archive),
        ("moead-dra", |p, s| run_moead_dra(p, s, None)),
        ("moead-dra-archive100", |p, s| run_moead_dra(p, s, ARCHIVE)),
        ("moead-sbx", run_moead_sbx),
    ];
    for (name, run) in algorithms {
        let hv = median_hypervolume(run, &problem);
        println!(
            "{name} zdt1: hypervolume over seeds 1..={SEEDS}: median {:.4}, min {:.4}, max {:.4}",
            0.5 * (hv[4] + hv[5]),
            hv[0],
            hv[9]
        );
        let mut seed = 0;
        c.bench_function(&format!("optim/zdt1-30var-pop100-250gen/{name}"), |b| {
            b.iter(|| {
                seed = seed % SEEDS + 1;
                black_box(run(black_box(&problem), seed).len())
            });
        });
    }
}

/// MHACO on the same setting: pagmo's defaults (ker 63, q 1, threshold 1, n_gen_mark 7) and
/// the recommended n_gen_mark 15 (docs/reference/optimisers.md).
fn bench_mhaco(c: &mut Criterion) {
    let problem = Zdt::standard(1).expect("zdt1");
    for (name, n_gen_mark) in [("mhaco-pagmo-defaults", 7), ("mhaco-n_gen_mark-15", 15)] {
        let config = MhacoConfig {
            n_gen_mark,
            ..MhacoConfig::default()
        };
        let run = |seed: u64| {
            let mut a = Mhaco::new(config.clone(), seed);
            evolve(&mut a, &problem, &Serial, GENERATIONS, &mut NoObserver).expect("mhaco runs");
            a.population().to_vec()
        };
        let mut hv: Vec<f64> = (1..=SEEDS)
            .map(|s| hypervolume(&feasible_front(&run(s)), &[1.1, 1.1]).expect("hypervolume"))
            .collect();
        hv.sort_by(f64::total_cmp);
        println!(
            "{name} zdt1: hypervolume over seeds 1..={SEEDS}: median {:.4}, min {:.4}, max {:.4}",
            0.5 * (hv[4] + hv[5]),
            hv[0],
            hv[9]
        );
        let mut seed = 0;
        c.bench_function(&format!("optim/zdt1-30var-pop100-250gen/{name}"), |b| {
            b.iter(|| {
                seed = seed % SEEDS + 1;
                black_box(run(seed).len())
            });
        });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30);
    targets = bench, bench_mhaco
}
criterion_main!(benches);
