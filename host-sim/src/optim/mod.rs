//! Generic multi-objective optimisation (issue 9): problems, ask/tell algorithms (MOEA/D,
//! NSGA-II; MHACO and SCEA build on the same framework), Pareto utilities, exact hypervolume
//! and standard test problems.
//!
//! Layering rule: this module imports nothing else of `host-sim` (no simulator, no CLI); a test
//! enforces it. The re-entry problems live outside it and implement its `Problem` trait.
//!
//! * [`problem`]: [`Problem`] (associated decision type, objectives minimised, constraints
//!   `g <= 0`), [`RealProblem`] (box [`Bounds`]), [`Evaluation`];
//! * [`algorithm`]: the ask/tell [`Algorithm`] trait; [`evaluate`]: [`evolve`] with a
//!   [`Serial`] or [`Rayon`] evaluator; [`observe`]: per-generation [`Observer`]s;
//! * [`population`]: evaluated [`Individual`]s, constraint violation, feasible fronts;
//! * [`pareto`]: dominance, non-dominated sorting, crowding distance; [`rng`]: the one seeded,
//!   serialisable generator of a run;
//! * [`hypervolume`]: exact hypervolume, contributions, least contributor.
//!
//! See docs/OPTIMISERS.md for the semantics and the measured convergence.

pub mod algorithm;
pub mod algorithms;
pub mod chromosome;
pub mod error;
pub mod evaluate;
pub mod hypervolume;
pub mod observe;
pub mod operators;
pub mod pareto;
pub mod population;
pub mod problem;
pub mod problems;
pub mod rng;
pub mod weights;

pub use algorithm::{Algorithm, Batch};
pub use algorithms::{
    ConstraintHandling, Mhaco, MhacoConfig, Moead, MoeadConfig, NewGenes, Nsga2, Nsga2Config, Scea,
    SceaConfig,
};
pub use error::{BoundsError, ConfigError, EvalError, OptimError, TellError};
pub use evaluate::{Evaluator, Rayon, Serial, evolve};
pub use observe::{GenerationRecord, GenerationReport, History, NoObserver, Observer};
pub use population::Individual;
pub use problem::{Bounds, Decision, Evaluation, Problem, RealProblem};
pub use rng::OptimRng;
pub use weights::{Decomposition, WeightGeneration};

#[cfg(test)]
mod layering {
    use std::path::Path;

    fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                rust_files(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }

    /// The line without the contents of string literals.
    fn strip_strings(line: &str) -> String {
        let mut inside = false;
        line.chars()
            .filter(|&c| {
                if c == '"' {
                    inside = !inside;
                }
                !inside
            })
            .collect()
    }

    /// The optimisers know nothing of re-entry: no `crate::` path outside `crate::optim`,
    /// no `host_sim::` path, no climbing out with `super::` from `optim/mod.rs`.
    #[test]
    fn optim_imports_nothing_else_of_host_sim() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/optim");
        let mut files = Vec::new();
        rust_files(&root, &mut files);
        assert!(
            files.len() > 5,
            "found {} files under {}",
            files.len(),
            root.display()
        );
        for file in files {
            let text = std::fs::read_to_string(&file).unwrap();
            for (n, line) in text.lines().enumerate() {
                let code = strip_strings(line.split("//").next().unwrap_or(""));
                let code = code.as_str();
                for (pos, _) in code.match_indices("crate::") {
                    let rest = &code[pos + "crate::".len()..];
                    assert!(
                        rest.starts_with("optim"),
                        "{}:{}: imports outside optim: {line}",
                        file.display(),
                        n + 1
                    );
                }
                assert!(
                    !code.contains("host_sim::"),
                    "{}:{}: {line}",
                    file.display(),
                    n + 1
                );
                if file.ends_with("optim/mod.rs") {
                    assert!(
                        !code.contains("super::"),
                        "{}:{}: {line}",
                        file.display(),
                        n + 1
                    );
                }
            }
        }
    }
}
