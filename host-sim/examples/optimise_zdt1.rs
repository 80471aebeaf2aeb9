//! An optimiser through the library API: MOEA/D and NSGA-II on ZDT1 (30 variables), seeded,
//! with the exact hypervolume of each final population w.r.t. (1.1, 1.1) (the true front's is
//! 0.8767): `host_sim::optim::{evolve, hypervolume}`.
//!
//! ```sh
//! cargo run --release -p host-sim --example optimise_zdt1 -- 200   # generations (default 250)
//! ```

use host_sim::optim::hypervolume::hypervolume;
use host_sim::optim::problems::Zdt;
use host_sim::optim::{
    Algorithm, Moead, MoeadConfig, NoObserver, Nsga2, Nsga2Config, Rayon, evolve,
};

fn report<A: Algorithm<Zdt>>(name: &str, a: &A) -> Result<(), Box<dyn std::error::Error>> {
    let points: Vec<&[f64]> = a
        .population()
        .iter()
        .map(|i| i.objectives.as_slice())
        .collect();
    println!(
        "{name}: hypervolume {:.4}",
        hypervolume(&points, &[1.1, 1.1])?
    );
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let generations: u64 = match std::env::args().nth(1) {
        Some(g) => g.parse()?,
        None => 250,
    };
    let problem = Zdt::new(1, 30)?;
    let evaluator = Rayon::global();
    let mut moead = Moead::new(MoeadConfig::default(), 1);
    evolve(
        &mut moead,
        &problem,
        &evaluator,
        generations,
        &mut NoObserver,
    )?;
    report("MOEA/D (pagmo defaults, 100 members)", &moead)?;
    let mut nsga2 = Nsga2::new(Nsga2Config::default(), 1);
    evolve(
        &mut nsga2,
        &problem,
        &evaluator,
        generations,
        &mut NoObserver,
    )?;
    report("NSGA-II (100 members)", &nsga2)?;
    Ok(())
}
