//! CPU time per closed-loop flight, for comparing builds on a shared machine (issue 11 item
//! 9): wall-clock benchmarks (criterion) inflate with the machine's load, the thread's own CPU
//! time much less. Flies the HORUS-2B reference mission and the SRM glide (their stored
//! profiles, without the guidance layers) `N` times each
//! (default 200) on one thread and prints the median CPU time per flight over 5 rounds, read
//! from `/proc/thread-self/schedstat` (Linux). A second argument flies only the built-in
//! scenario of that name (`horus-2b-reference` or `srm-glide`), or the scenario file of that
//! path when it ends in `.toml`, e.g. to count one scenario's instructions under
//! `valgrind --tool=callgrind`.
//!
//! ```sh
//! cargo run --release -p host-sim --example flight_cpu -- 200
//! cargo run --release -p host-sim --example flight_cpu -- 10 horus-2b-reference
//! cargo run --release -p host-sim --example flight_cpu -- 10 my-scenario.toml
//! ```

use host_sim::scenario::{Scenario, fly, read_scenario};

/// CPU time of this thread \[ns\] (first field of schedstat).
fn thread_cpu_ns() -> Result<u64, String> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat")
        .map_err(|e| format!("/proc/thread-self/schedstat: {e}"))?;
    s.split_whitespace()
        .next()
        .and_then(|f| f.parse().ok())
        .ok_or_else(|| format!("/proc/thread-self/schedstat: unexpected content {s:?}"))
}

fn main() -> Result<(), String> {
    let n: u32 = match std::env::args().nth(1) {
        Some(a) => a.parse().map_err(|e| format!("flight count {a:?}: {e}"))?,
        None => 200,
    };
    let scenarios = match std::env::args().nth(2) {
        Some(path) if path.ends_with(".toml") => {
            vec![read_scenario(std::path::Path::new(&path)).map_err(|e| e.to_string())?]
        }
        Some(name) => vec![Scenario::try_builtin(&name).map_err(|e| e.to_string())?],
        None => vec![Scenario::default(), Scenario::srm_glide()],
    };
    for sc in scenarios {
        // The stored profile alone: one closed-loop flight (with its layers `fly` would build
        // a campaign set-up first).
        let sc = Scenario { layers: None, ..sc };
        let once = fly(&sc, "cpu", &mut |_| {}).map_err(|e| e.to_string())?;
        let mut rounds = Vec::new();
        for _ in 0..5 {
            let c0 = thread_cpu_ns()?;
            for _ in 0..n {
                let f = fly(&sc, "cpu", &mut |_| {}).map_err(|e| e.to_string())?;
                std::hint::black_box(f.result.summary.heat_load_j_m2);
            }
            rounds.push((thread_cpu_ns()? - c0) as f64 / f64::from(n) / 1e6);
        }
        rounds.sort_by(f64::total_cmp);
        println!(
            "{}: {:.3} ms CPU per flight (median of 5 rounds of {n}; min {:.3}, max {:.3}), {} RHS evaluations",
            sc.name, rounds[2], rounds[0], rounds[4], once.result.summary.rhs_evals
        );
    }
    Ok(())
}
