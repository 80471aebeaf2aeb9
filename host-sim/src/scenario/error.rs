//! [`ScenarioError`]: what can be wrong with a scenario; every message names the file (or the
//! built-in scenario), the field and the value.

use guidance_core::GuidanceError;

use crate::sim::SimError;
use crate::vehicle::VehicleFileError;

/// A scenario that cannot be read, resolved or flown.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The scenario file could not be read.
    #[error("{file}: cannot read: {source}")]
    Read {
        /// File name as given.
        file: String,
        /// Operating-system error.
        source: std::io::Error,
    },
    /// The file is not valid TOML (the message gives line, column and the offending text).
    #[error("{file}: malformed TOML: {source}")]
    Toml {
        /// File name as given.
        file: String,
        /// The parser's error.
        source: crate::toml_input::TomlSyntax,
    },
    /// A field is unknown, mistyped or out of range.
    #[error("{file}: field `{field}` = {value}: {reason}")]
    Field {
        /// File name as given.
        file: String,
        /// Dotted field path, e.g. `entry.altitude_km` or `guidance.nodes[1]`.
        field: String,
        /// The offending value as written, or `(missing)`.
        value: String,
        /// What is required.
        reason: String,
    },
    /// Not a built-in scenario name.
    #[error("command line: option `--builtin` = {name:?}: unknown scenario (known: {known})")]
    UnknownBuiltin {
        /// The name asked for.
        name: String,
        /// Comma-separated known names.
        known: String,
    },
    /// `guidance-core` rejected the guidance configuration of the scenario.
    #[error("{file}: field `guidance.{field}`: rejected by guidance-core: {source}")]
    Guidance {
        /// File name (or built-in scenario).
        file: String,
        /// The guidance field concerned.
        field: &'static str,
        /// The core's error.
        source: GuidanceError,
    },
    /// The entry state does not define a normalised energy.
    #[error("{file}: field `entry` (with `environment.planet`): no normalised energy: {source}")]
    Entry {
        /// File name (or built-in scenario).
        file: String,
        /// The core's error.
        source: GuidanceError,
    },
    /// The tabulated atmosphere could not be read.
    #[error("{file}: field `environment.table.file`: {source}")]
    Atmosphere {
        /// Scenario file.
        file: String,
        /// The table's error (names the CSV file, line and value).
        source: crate::env::TableAtmosphereError,
    },
    /// A guidance attitude-rate limit exceeds the vehicle's (the vehicle's `[limits]` bound
    /// the guidance's rate limiter).
    #[error(
        "scenario `{scenario}`: field `guidance.{axis}_rate_deg_s` = {}: exceeds the vehicle's \
         `limits.{axis}_rate_deg_s` = {} deg/s ({vehicle}); the vehicle's rate limits bound \
         the guidance's",
        crate::num_fmt::compact(*guidance_deg_s),
        crate::num_fmt::compact(*vehicle_deg_s)
    )]
    RateLimit {
        /// Scenario name.
        scenario: String,
        /// The vehicle as the scenario names it.
        vehicle: String,
        /// `alpha` or `sigma`.
        axis: &'static str,
        /// The guidance's rate limit \[deg/s\].
        guidance_deg_s: f64,
        /// The vehicle's rate limit \[deg/s\].
        vehicle_deg_s: f64,
    },
    /// The scenario's guidance stack (its `[guidance.*]` layers) could not be built or flown
    /// (the campaign set-up's error: it names the file and the field).
    #[error("{file}: guidance stack: {source}")]
    Stack {
        /// File name (or built-in scenario).
        file: String,
        /// The set-up's error, a `campaign::CampaignError` (boxed as an error object: the
        /// campaign's error wraps this one, so this one does not name it; downcast to read it).
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// The vehicle could not be loaded.
    #[error(transparent)]
    Vehicle(#[from] VehicleFileError),
    /// The simulation failed.
    #[error("simulation failed: {0}")]
    Sim(#[from] SimError),
    /// The run directory could not be written.
    #[error(transparent)]
    Report(#[from] crate::report::ReportError),
}
