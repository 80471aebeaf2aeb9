//! Trajectory benchmarks (single thread): one HORUS-2B reference trajectory (US76, J2,
//! rotating Earth, time nodes of thesis eq. 2.3) and one SRM glide (simplified environment,
//! energy nodes), both closed-loop with guidance-core's `Guidance` at 2 s. The number of
//! right-hand-side evaluations per trajectory is printed once per benchmark.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use host_sim::scenario::{Scenario, fly};

fn bench_scenario(c: &mut Criterion, sc: &Scenario) {
    let once = fly(sc, "bench", &mut |_| {}).expect("scenario flies");
    let s = &once.result.summary;
    println!(
        "{}: {} RHS evaluations per trajectory ({} accepted, {} rejected steps, {} ticks, {:.1} s flight)",
        sc.name, s.rhs_evals, s.accepted_steps, s.rejected_steps, s.ticks, s.flight_time_s
    );
    c.bench_function(&format!("trajectory/{}", sc.name), |b| {
        b.iter(|| {
            let f = fly(black_box(sc), "bench", &mut |_| {}).expect("scenario flies");
            black_box(f.result.summary.heat_load_j_m2)
        });
    });
}

fn trajectories(c: &mut Criterion) {
    // One closed-loop flight of each stored profile (the built-ins without their layers:
    // `simulate` of a scenario with layers flies a campaign set-up first).
    for sc in [Scenario::default(), Scenario::srm_glide()] {
        bench_scenario(c, &Scenario { layers: None, ..sc });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = trajectories
}
criterion_main!(benches);
