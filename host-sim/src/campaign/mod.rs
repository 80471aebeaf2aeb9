//! Dispersion campaigns (Monte Carlo): N closed-loop flights of one scenario with dispersed
//! entry state, atmosphere, aerodynamics and mass, flown with three guidance modes on the same
//! cases, with statistics and a report of figures per mode (docs/reference/campaigns.md).
//!
//! * [`settings`]: the `[dispersions]` TOML section, defaults, validation naming the field;
//! * [`draw`]: the dispersed values of case `i`, from a generator seeded by (seed, i) only;
//! * [`models`]: the dispersed atmosphere (altitude-varying, bounded density scale) and aero;
//! * [`Mode`]: the guidance modes compared, each a mask over the layers of the one stack;
//! * [`setup`]: what the cases share (terminal interface, target, stored profile, settings of
//!   the lateral logic and the re-planner), built from nominal flights of the scenario
//!   ([`CampaignSetup::new`], in the private `build` module, above [`flight`], which it
//!   flies);
//! * [`flight`]: one flight in one mode -> [`flight::CaseResult`];
//! * [`run`]: the campaign (rayon, bit-identical whatever the thread count, resumable per case
//!   with atomic writes, progress bar);
//! * [`fingerprint`]: the resolved inputs of a campaign, stored with its cases, so a run
//!   resumes only into a directory of the same inputs;
//! * [`stats`]: the statistics of each mode;
//! * [`report`]: the report's figures per mode ([`crate::report::campaign`]), the worst
//!   flights replayed with their trajectories;
//! * [`CampaignError`]: why a campaign failed (it wraps a
//!   [`ScenarioError`](crate::scenario::ScenarioError); a scenario's stack error holds it as an
//!   error object, so the arrows point from campaign to scenario's error only).

mod build;
pub mod draw;
mod error;
pub mod fingerprint;
pub mod flight;
pub mod imu;
pub mod jobs;
mod mode;
pub mod models;
pub mod output;
pub mod report;
pub mod run;
pub mod settings;
pub mod setup;
pub mod stats;

pub use crate::scenario::guidance_layers::{CampaignGuidance, CampaignPredictor};
pub use error::CampaignError;
pub use flight::CaseResult;
pub use jobs::{Campaign, JobOutcome};
pub use mode::Mode;
pub use run::{CampaignOutput, run_campaign};
pub use settings::{Dispersion, DispersionSettings, parse_settings};
pub use setup::CampaignSetup;
pub use stats::{ModeStats, Stats};
