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
//! * [`archive`]: [`ParetoArchive`], the bounded external archive of non-dominated solutions
//!   (Zhang & Li's EP; opt-in on MOEA/D, SCEA and NSGA-II);
//! * [`hypervolume`]: exact hypervolume, contributions, least contributor;
//! * [`spec`]: [`AlgorithmSpec`], one algorithm specification (serde-tagged, checked),
//!   [`RealAlgorithm`], the running algorithm every front end drives, and [`RunOptions`], the
//!   `host-sim optimize` flags that map onto a spec;
//! * [`run`]: a recorded run's per-generation records, checkpoint and population CSV, and a
//!   finished test-problem run's summary ([`run::run_report`]);
//! * [`nonfinite`]: serde of `f64`s that may be NaN or infinite (checkpoints, records).
//!
//! See docs/reference/optimisers.md for the semantics and the measured convergence.

pub mod algorithm;
pub mod algorithms;
pub mod archive;
pub mod chromosome;
pub mod error;
pub mod evaluate;
pub mod executor;
pub mod hypervolume;
pub mod nonfinite;
pub mod observe;
pub mod operators;
pub mod pareto;
pub mod population;
pub mod problem;
pub mod problems;
pub mod reference;
pub mod restore;
pub mod rng;
pub mod root;
pub mod rows;
pub mod run;
pub mod spec;
pub mod variable_length_run;
pub mod weights;

pub use algorithm::{Algorithm, Batch};
pub use algorithms::{
    ConstraintHandling, Mhaco, MhacoConfig, Moead, MoeadConfig, MoeadSbx, NewGenes, Nsga2,
    Nsga2Config, ResourceAllocation, SbxVariation, Scea, SceaConfig, VlMhaco,
};
pub use archive::ParetoArchive;
pub use error::{BoundsError, ConfigError, EvalError, OptimError, StateError, TellError};
pub use evaluate::{
    BatchEvaluator, Evaluator, External, Rayon, Serial, Threads, ThreadsError, evolve,
};
pub use executor::{Budget, Executor, Run, Stop};
pub use observe::{GenerationRecord, GenerationReport, History, NoObserver, Observer};
pub use population::Individual;
pub use problem::{Bounds, Decision, Evaluation, Problem, RealProblem};
pub use rng::OptimRng;
pub use spec::{
    AlgorithmSpec, BuiltAlgorithm, ChromosomeAlgorithm, RealAlgorithm, RunOptions, SPEC_NAMES,
};
pub use weights::{Decomposition, WeightGeneration};
