//! Re-entry design benchmarks (issue 11 item 8): one closed-loop evaluation of the HORUS-2B
//! design problem (a mid-box 8-node decision; flights per second = 1 / time), and a short
//! MOEA/D run (population 64, 4 generations = 320 flights, batches of 64 on a 2-thread rayon
//! pool) whose time per flight scales to the 64 x 128 run; one evaluation of a mid-box
//! SRM table, numerical (`srm`) and analytical (`srm-analytical`).

use std::hint::black_box;
use std::sync::Arc;

use criterion::{Criterion, criterion_group, criterion_main};
use host_sim::design::{DesignConfig, ReentryProblem};
use host_sim::optim::{Moead, MoeadConfig, NoObserver, Problem, Rayon, evolve};

fn problem() -> ReentryProblem {
    DesignConfig::preset("horus-2b")
        .expect("preset")
        .problem(std::path::Path::new("."))
        .expect("problem")
}

fn decision() -> Vec<f64> {
    let mut x = Vec::new();
    for (i, e) in [0.9, 0.75, 0.6, 0.45, 0.3, 0.15].into_iter().enumerate() {
        x.extend([e, 35.0 - 3.0 * i as f64, 40.0 + 5.0 * i as f64]);
    }
    x
}

fn bench(c: &mut Criterion) {
    let p = problem();
    let x = decision();
    c.bench_function("design/horus2b_evaluation", |b| {
        b.iter(|| black_box(p.evaluate(black_box(&x)).expect("evaluates")));
    });
    // The same mid-box SRM table on the numerical closed loop and on the analytical
    // simulator (the node-guided glide closed form).
    let srm_x: Vec<f64> = [0.9, 0.75, 0.6, 0.45, 0.3, 0.15]
        .into_iter()
        .enumerate()
        .flat_map(|(i, e)| [e, 20.0 + 8.0 * i as f64])
        .collect();
    for name in ["srm", "srm-analytical"] {
        let p = DesignConfig::preset(name)
            .expect("preset")
            .problem(std::path::Path::new("."))
            .expect("problem");
        c.bench_function(&format!("design/{name}_evaluation"), |b| {
            b.iter(|| black_box(p.evaluate(black_box(&srm_x)).expect("evaluates")));
        });
    }
    let pool = Arc::new(
        rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .expect("pool"),
    );
    let mut g = c.benchmark_group("design");
    g.sample_size(10);
    g.bench_function("horus2b_moead_pop64_gen4_2threads", |b| {
        b.iter(|| {
            let cfg = MoeadConfig {
                population: 64,
                limit: 1,
                mutation_probability: Some(1.0 / 64.0),
                batch_size: 64,
                ..MoeadConfig::default()
            };
            let mut a = Moead::new(cfg, 123);
            evolve(
                &mut a,
                &p,
                &Rayon::with_pool(Arc::clone(&pool)),
                4,
                &mut NoObserver,
            )
            .expect("runs");
            black_box(a.evaluations())
        });
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
