//! Re-entry mission design (issue 11): the thesis' guidance problems (sec. 4.2) for the
//! generic optimisers of [`crate::optim`], whose `Problem` trait they implement. An evaluation
//! flies the closed loop (guidance-core's `Guidance` at its 2 s clock in the numerical
//! simulator), or for an analytical problem the glide closed form along the node table
//! ([`analytical`]).
//!
//! * [`encoding`]: decision vector <-> node table (fixed end nodes, free energy nodes, the
//!   entry altitude as an optional variable);
//! * [`problem`]: [`ReentryProblem`] (objectives, constraints with `g <= 0` feasible);
//! * [`robust`]: [`RobustProblem`] (each candidate judged by a dispersion campaign of the
//!   base scenario's guidance stack);
//! * [`config`]: the problem as a file section and the thesis presets;
//! * [`analytical`]: which simulator evaluates (numerical closed loop or the analytical
//!   node-guided glide);
//! * [`run`]: a recorded, resumable optimisation run of a problem (run file, checkpoint,
//!   records, run directory).

pub mod analytical;
#[cfg(test)]
mod analytical_tests;
pub mod config;
pub mod encoding;
pub mod problem;
pub mod robust;
pub mod robust_settings;
#[cfg(test)]
mod robust_tests;
pub mod run;
pub mod sample;
#[cfg(test)]
mod tests;
pub mod variable;

pub use analytical::{AnalyticalModel, Simulator};
pub use config::{DesignConfig, PRESETS};
pub use encoding::{Encoding, FixedNode};
pub use problem::{Limits, Objectives, ReentryProblem};
pub use robust::{RobustConfig, RobustProblem, Statistic};
pub use robust_settings::SettingVariable;
pub use sample::latin_hypercube;
pub use variable::VariableReentry;

use crate::analytic::AnalyticError;
use crate::optim::BoundsError;
use crate::scenario::ScenarioError;

/// Why the re-entry problems refuse the algorithm flags they fix (`run::fixed_on_reentry`:
/// the CLI's and `run::ReentryRunConfig::of_flags`' message).
pub const FIXED_ON_REENTRY: &str = "fixed on the re-entry problems (MOEA/D's DE without \
     resource allocation, MHACO ker = min(63, population) and n_gen_mark 7, the budget in \
     --generations); drop it";

/// Design-problem failures; each names the field and what to change.
#[derive(Debug, thiserror::Error)]
pub enum DesignError {
    /// A setting out of range.
    #[error("problem: field `{field}` = {value}: {reason}")]
    Setting {
        /// Dotted field path.
        field: &'static str,
        /// The value given.
        value: String,
        /// What to change.
        reason: &'static str,
    },
    /// Not a preset name or scenario file.
    #[error(
        "problem: field `base` = {name:?}: unknown preset; use one of horus-2b, srm, srm-altitude, srm-analytical, srm-analytical-altitude, or a scenario file"
    )]
    UnknownPreset {
        /// The name given.
        name: String,
    },
    /// An algorithm setting the re-entry problems fix (`run::fixed_on_reentry`).
    #[error("{flag} does not apply to the re-entry problems: {FIXED_ON_REENTRY}")]
    FixedOnReentry {
        /// The flag given (`--resource-allocation`, `--ker`, ...).
        flag: &'static str,
    },
    /// A decision of the wrong length.
    #[error("decision has {got} variables, the encoding expects {expected}")]
    Dimension {
        /// Expected variables.
        expected: usize,
        /// Given.
        got: usize,
    },
    /// The free-node count of a padded decision (its last variable) out of range.
    #[error("free-node count (last variable) = {value}: must round to {min} ..= {max}")]
    PaddedCount {
        /// The value given.
        value: f64,
        /// Fewest free nodes.
        min: usize,
        /// Most free nodes.
        max: usize,
    },
    /// Invalid decision bounds.
    #[error("problem: encoding bounds: {0}")]
    Bounds(#[from] BoundsError),
    /// The analytical simulator cannot fly the base (e.g. no usable drag polar).
    #[error("problem: analytical simulator: {0}")]
    Analytic(#[from] AnalyticError),
    /// A `[robust]` setting that cannot be flown ([`robust::RobustProblem`]).
    #[error("robust problem: field `{field}` = {value}: {reason}")]
    Robust {
        /// Dotted field path (`robust.objectives`, `robust.dispersions.cases`, ...).
        field: String,
        /// The value given.
        value: String,
        /// What to change.
        reason: String,
    },
    /// A run file's text that is not TOML, or tables of the wrong shape.
    #[error("{label}: {message}")]
    Toml {
        /// The file or `(TOML string)`.
        label: String,
        /// What is wrong (with the field).
        message: String,
    },
    /// The base scenario's campaign cannot be set up (its nominal flight fails).
    #[error("robust problem: the base scenario's campaign: {0}")]
    RobustBase(#[source] Box<crate::campaign::CampaignError>),
    /// The base scenario could not be read or built.
    #[error("problem: base scenario: {0}")]
    Scenario(#[from] ScenarioError),
}
