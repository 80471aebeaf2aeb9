//! Dispersion campaigns (Monte Carlo): N closed-loop flights of one scenario with dispersed
//! entry state, atmosphere, aerodynamics and mass, flown with three guidance modes on the same
//! cases, with statistics and a report of figures per mode (docs/reference/campaigns.md).
//!
//! * [`settings`]: the `[dispersions]` TOML section, defaults, validation naming the field;
//! * [`draw`]: the dispersed values of case `i`, from a generator seeded by (seed, i) only;
//! * [`models`]: the dispersed atmosphere (altitude-varying, bounded density scale) and aero;
//! * [`setup`]: what the cases share (terminal interface, target, stored profile, settings of
//!   the lateral logic and the re-planner), from nominal flights of the scenario;
//! * [`flight`]: one flight in one mode -> [`flight::CaseResult`];
//! * [`run`]: the campaign (rayon, bit-identical whatever the thread count, resumable per case
//!   with atomic writes, progress bar);
//! * [`fingerprint`]: the resolved inputs of a campaign, stored with its cases, so a run
//!   resumes only into a directory of the same inputs;
//! * [`stats`]: the statistics of each mode;
//! * [`report`]: the report's figures per mode ([`crate::report::campaign`]), the worst
//!   flights replayed with their trajectories.

pub mod draw;
pub mod fingerprint;
pub mod flight;
pub mod imu;
pub mod models;
pub mod output;
pub mod report;
pub mod run;
pub mod settings;
pub mod setup;
pub mod stats;

use guidance_core::stack::Layers;
use serde::{Deserialize, Serialize};

pub use crate::scenario::guidance_layers::{CampaignGuidance, CampaignPredictor};
pub use flight::CaseResult;
pub use run::{CampaignOutput, run_campaign};
pub use settings::{Dispersion, DispersionSettings, parse_settings};
pub use setup::CampaignSetup;
pub use stats::{ModeStats, Stats};

/// A guidance mode of the comparison.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Mode {
    /// The stored profile with its own (constant) bank sign.
    Stored,
    /// The stored profile's magnitude with bank reversals.
    StoredReversals,
    /// Re-planned magnitude (predictor-corrector on the target's range to go) with reversals.
    ReplanReversals,
    /// As [`Mode::ReplanReversals`], the predictor flying the model scaled by the onboard
    /// estimate of L/D and drag scale from sensed accelerations (`guidance_core::estimate`).
    ReplanEstimation,
}

impl Mode {
    /// Every mode, in report order.
    pub const ALL: [Mode; 4] = [
        Mode::Stored,
        Mode::StoredReversals,
        Mode::ReplanReversals,
        Mode::ReplanEstimation,
    ];

    /// The layers of the campaign's stack this mode flies (a mask over the one stack:
    /// `guidance_core::stack::StackConfig::masked`).
    #[must_use]
    pub fn layers(self) -> Layers {
        match self {
            Mode::Stored => Layers::PROFILE,
            Mode::StoredReversals => Layers {
                lateral: true,
                ..Layers::PROFILE
            },
            Mode::ReplanReversals => Layers {
                estimator: false,
                ..Layers::ALL
            },
            Mode::ReplanEstimation => Layers::ALL,
        }
    }

    /// Whether a stack with `layers` can fly this mode: it has the layers that make the mode
    /// (the barrier is flown where present, not required).
    #[must_use]
    pub fn flies_with(self, layers: Layers) -> bool {
        let need = Layers {
            barrier: false,
            ..self.layers()
        };
        need.and(layers) == need
    }

    /// Short name (file and directory names).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Mode::Stored => "stored",
            Mode::StoredReversals => "stored-reversals",
            Mode::ReplanReversals => "replan-reversals",
            Mode::ReplanEstimation => "replan-estimation",
        }
    }
}

/// Why a campaign failed.
#[derive(Debug, thiserror::Error)]
pub enum CampaignError {
    /// A bad setting.
    #[error("{file}: {field} = {value}: {reason}")]
    Setting {
        /// Settings file.
        file: String,
        /// Dotted field name.
        field: String,
        /// The value as written.
        value: String,
        /// What is wrong.
        reason: String,
    },
    /// Malformed TOML.
    #[error("{file}: {source}")]
    Toml {
        /// Settings file.
        file: String,
        /// The parser's error.
        source: crate::toml_input::TomlSyntax,
    },
    /// The scenario could not be loaded or flown.
    #[error("{file}: scenario: {source}")]
    Scenario {
        /// Scenario file.
        file: String,
        /// The cause.
        source: Box<crate::scenario::ScenarioError>,
    },
    /// Guidance could not be set up.
    #[error("{file}: {field}: {source}")]
    Guidance {
        /// Scenario file.
        file: String,
        /// What was being built.
        field: &'static str,
        /// The core's error.
        source: guidance_core::GuidanceError,
    },
    /// The onboard stack could not be built.
    #[error("{file}: guidance stack: {source}")]
    Stack {
        /// Scenario file.
        file: String,
        /// The core's error.
        source: guidance_core::stack::StackBuildError,
    },
    /// The predictor model could not be built.
    #[error("{file}: predictor model: {source}")]
    Predictor {
        /// Scenario file.
        file: String,
        /// The cause.
        source: crate::analytic::AnalyticError,
    },
    /// A flight failed.
    #[error("flight {index:?}: {source}")]
    Sim {
        /// Case index (`None`: nominal).
        index: Option<u32>,
        /// The simulator's error.
        source: crate::sim::SimError,
    },
    /// A flight produced no sample.
    #[error("a flight produced no sample")]
    EmptyFlight,
    /// Writing results failed.
    #[error(transparent)]
    Report(#[from] crate::report::ReportError),
    /// A stored case result could not be read.
    #[error("{path}: cannot read case result: {source}")]
    CaseFile {
        /// The file.
        path: std::path::PathBuf,
        /// The cause.
        source: serde_json::Error,
    },
    /// A stored case file holds a value no flight gives (edited or corrupt): it is not reused.
    #[error("{}: field `{field}` = {value}: {reason}; remove the file to fly the case again", path.display())]
    CaseValue {
        /// The file.
        path: std::path::PathBuf,
        /// The field.
        field: String,
        /// Its value.
        value: String,
        /// What it must be.
        reason: String,
    },
    /// The output directory holds case results of a campaign with other inputs: resuming
    /// would mix them.
    #[error(
        "{dir}: holds the case results of a campaign with other inputs ({file}: {field} was {old}, \
         now {new}); resuming would mix them: choose another output directory (--out) or remove \
         this one",
        file = fingerprint::FINGERPRINT_FILE
    )]
    ResumeMismatch {
        /// The output directory.
        dir: std::path::PathBuf,
        /// The first input that differs (dotted, as in `fingerprint.json`).
        field: String,
        /// Its value in the stored fingerprint (cut around the difference).
        old: String,
        /// Its value in this campaign.
        new: String,
    },
    /// The output directory holds case results but no fingerprint (a run of an earlier
    /// version): they cannot be checked against this campaign's inputs.
    #[error(
        "{dir}: holds case results but no {file} (an earlier version's run), so they cannot be \
         checked against this campaign's inputs: choose another output directory (--out) or \
         remove this one",
        file = fingerprint::FINGERPRINT_FILE
    )]
    ResumeUnverified {
        /// The output directory.
        dir: std::path::PathBuf,
    },
    /// A stored fingerprint could not be read.
    #[error("{path}: cannot read the campaign fingerprint: {source}")]
    FingerprintFile {
        /// The file.
        path: std::path::PathBuf,
        /// The cause.
        source: serde_json::Error,
    },
    /// The thread pool could not be built.
    #[error("thread pool: {0}")]
    Pool(#[from] rayon::ThreadPoolBuildError),
    /// A stop was requested (Ctrl-C): the flights completed so far are kept as case files
    /// (a run into the same directory resumes them), and no statistics of the partial
    /// campaign are made.
    #[error(
        "interrupted after {done} of {total} flights; no summary of a partial campaign \
         (the finished cases are kept in the output directory: the same command resumes them)"
    )]
    Interrupted {
        /// Flights finished (flown or reused).
        done: usize,
        /// Flights of the campaign.
        total: usize,
    },
}
