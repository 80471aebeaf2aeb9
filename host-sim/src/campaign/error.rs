//! [`CampaignError`]: why a campaign could not be set up, flown, resumed or written.

/// File name of the fingerprint in a campaign's output directory (written and checked by
/// [`super::fingerprint`]; named by the resume errors).
pub const FINGERPRINT_FILE: &str = "fingerprint.json";

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
    /// A job that is not one of the campaign's, given twice, or missing.
    #[error("case {index} of mode {mode}: {reason}")]
    Job {
        /// The job's mode.
        mode: &'static str,
        /// The job's case index.
        index: u32,
        /// What is wrong.
        reason: String,
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
        file = FINGERPRINT_FILE
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
        file = FINGERPRINT_FILE
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
