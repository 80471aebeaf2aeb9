//! Typed errors of the optimisation framework: bad bounds, bad algorithm settings, failed or
//! malformed evaluations. Every message says what to change.

use thiserror::Error;

/// Bad box bounds of a real-vector problem.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum BoundsError {
    /// No decision variables at all.
    #[error("bounds: no decision variables (give at least one lower/upper pair)")]
    Empty,
    /// `lower` and `upper` differ in length.
    #[error("bounds: lower has {lower} entries but upper has {upper}; give one pair per variable")]
    LengthMismatch {
        /// Entries in `lower`.
        lower: usize,
        /// Entries in `upper`.
        upper: usize,
    },
    /// A bound is NaN or infinite.
    #[error("bounds: variable {index}: {which} bound {value} is not finite; give a finite value")]
    NonFinite {
        /// Variable index (0-based).
        index: usize,
        /// "lower" or "upper".
        which: &'static str,
        /// The value given.
        value: f64,
    },
    /// `lower >= upper`.
    #[error("bounds: variable {index}: lower {lower} must be less than upper {upper}")]
    Inverted {
        /// Variable index (0-based).
        index: usize,
        /// Lower bound given.
        lower: f64,
        /// Upper bound given.
        upper: f64,
    },
}

/// Bad settings of an algorithm for a given problem (pagmo throws in these cases).
#[derive(Clone, Debug, PartialEq, Error)]
pub enum ConfigError {
    /// The problem declares no objectives.
    #[error("the problem has zero objectives; an optimiser needs at least one")]
    ZeroObjectives,
    /// The algorithm is multi-objective only.
    #[error("{algorithm} needs at least 2 objectives, the problem has {objectives}")]
    TooFewObjectives {
        /// Algorithm name.
        algorithm: &'static str,
        /// Objectives of the problem.
        objectives: usize,
    },
    /// The population is smaller than the algorithm needs.
    #[error("{algorithm}: population {population} is too small; use at least {minimum}")]
    PopulationTooSmall {
        /// Algorithm name.
        algorithm: &'static str,
        /// Population size given.
        population: usize,
        /// Smallest legal size.
        minimum: usize,
    },
    /// The population must be a multiple of some number (NSGA-II: 4).
    #[error(
        "{algorithm}: population {population} is not a multiple of {multiple}; use {below} or {above}"
    )]
    PopulationNotMultiple {
        /// Algorithm name.
        algorithm: &'static str,
        /// Population size given.
        population: usize,
        /// Required divisor.
        multiple: usize,
        /// Nearest legal size below (0 if none).
        below: usize,
        /// Nearest legal size above.
        above: usize,
    },
    /// Grid weights exist only for populations C(H + m - 1, m - 1).
    #[error(
        "population {population} is not a legal size for grid weights with {objectives} objectives; \
         the nearest legal sizes are {below} and {above} (or use low-discrepancy or random weights)"
    )]
    GridSize {
        /// Population size given.
        population: usize,
        /// Objectives of the problem.
        objectives: usize,
        /// Nearest legal size below (0 if none).
        below: usize,
        /// Nearest legal size above.
        above: usize,
    },
    /// More neighbours than other individuals.
    #[error(
        "neighbours (MOEA/D neighbourhood size, --neighbours) {neighbours} is too large for \
         population {population}; use at most {max}, or leave it out (default: \
         min(20, population - 1))",
        max = population.saturating_sub(1)
    )]
    TooManyNeighbours {
        /// Neighbourhood size given.
        neighbours: usize,
        /// Population size.
        population: usize,
    },
    /// A real parameter outside its range.
    #[error("{algorithm}: parameter {name} = {value} is outside {range}")]
    Parameter {
        /// Algorithm name.
        algorithm: &'static str,
        /// Parameter name.
        name: &'static str,
        /// Value given.
        value: f64,
        /// The legal range, e.g. "[0, 1]".
        range: &'static str,
    },
    /// An integer parameter outside its range.
    #[error("{algorithm}: parameter {name} = {value} is outside {range}")]
    Count {
        /// Algorithm name.
        algorithm: &'static str,
        /// Parameter name.
        name: &'static str,
        /// Value given.
        value: usize,
        /// The legal range.
        range: &'static str,
    },
}

/// A problem could not evaluate a decision.
#[derive(Debug, Error)]
pub enum EvalError {
    /// The decision has the wrong number of variables.
    #[error("decision has {got} variables, the problem expects {expected}")]
    Dimension {
        /// Expected number of variables.
        expected: usize,
        /// Variables given.
        got: usize,
    },
    /// The problem's own failure (e.g. a simulation that did not finish), with its cause.
    #[error("evaluation failed: {0}")]
    Failed(#[source] Box<dyn std::error::Error + Send + Sync>),
    /// The evaluation was stopped on request (Ctrl-C): it is no result, and the run stops
    /// without telling it.
    #[error("evaluation interrupted (stop requested): not a result")]
    Interrupted,
}

/// Misuse of the ask/tell protocol.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum TellError {
    /// `tell` without a batch handed out by `ask`.
    #[error("tell without an open batch: call ask first")]
    NoBatch,
    /// Index outside the batch.
    #[error("tell: index {index} is outside the batch of {batch}")]
    IndexOutOfRange {
        /// Index given.
        index: usize,
        /// Batch size.
        batch: usize,
    },
    /// The same index told twice.
    #[error("tell: index {index} was already told")]
    AlreadyTold {
        /// Index given.
        index: usize,
    },
    /// Wrong number of objectives.
    #[error("tell: index {index} has {got} objectives, the problem declares {expected}")]
    Objectives {
        /// Index.
        index: usize,
        /// Declared objectives.
        expected: usize,
        /// Objectives given.
        got: usize,
    },
    /// Wrong number of constraints.
    #[error("tell: index {index} has {got} constraints, the problem declares {expected}")]
    Constraints {
        /// Index.
        index: usize,
        /// Declared constraints.
        expected: usize,
        /// Constraints given.
        got: usize,
    },
}

/// Any failure of an optimisation run.
#[derive(Debug, Error)]
pub enum OptimError {
    /// Bad bounds.
    #[error(transparent)]
    Bounds(#[from] BoundsError),
    /// Bad algorithm settings for this problem.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// Misuse of ask/tell.
    #[error(transparent)]
    Tell(#[from] TellError),
    /// An evaluation failed (in [`crate::optim::evolve`]); `index` is its place in the batch.
    #[error("evaluation {index} of generation {generation}: {source}")]
    Evaluation {
        /// Index in the batch.
        index: usize,
        /// Generation being built.
        generation: u64,
        /// The problem's error.
        #[source]
        source: EvalError,
    },
    /// A restored state that does not hold together (a corrupt or edited checkpoint).
    #[error(transparent)]
    State(#[from] StateError),
}

/// A restored state that does not hold together: its field (dotted path), the value and what
/// is wrong.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("restored state: field `{field}` = {value}: {reason}")]
pub struct StateError {
    /// Dotted path of the field, with indices (`population[3].objectives`).
    pub field: String,
    /// The value found (shortened).
    pub value: String,
    /// What it must be.
    pub reason: String,
}
