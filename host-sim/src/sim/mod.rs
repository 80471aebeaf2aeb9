//! Closed-loop trajectory simulation: dynamics + RKF4(5) + an attitude source (guidance).
//!
//! The attitude source is called at every guidance tick with the navigation state
//! (planet-relative spherical quantities); the integrator lands on every tick exactly, and
//! between ticks the right-hand side uses the source's continuous attitude
//! ([`AttitudeSource::attitude_at`], the rate-limited ramp towards the held command).
//!
//! Events located inside steps ([`Event`]): atmosphere exit and re-entry at the interface
//! altitude (100 km), and termination on altitude, Mach number or normalised energy (all
//! falling), plus ground impact. A skip is an exit followed by a re-entry.
//!
//! Outputs: trajectory samples at the output interval, at ticks when no interval is set,
//! and at every event; a [`Summary`] with range angle, heat load (integrated as a state),
//! peak heat flux, g-load and g-load rate (from every accepted step), flight time, skips,
//! constraint violations (eq. 4.9-4.11) and the termination reason.
//!
//! Modules: [`source`] (the attitude-source seam and the one adapter of `guidance-core`'s
//! guidance, with or without re-planning), [`config`] (settings and their validation),
//! [`events`], [`results`], [`error`] and the run loop ([`simulate`]).

pub mod config;
pub mod error;
pub mod events;
pub mod results;
mod run;
pub mod source;
pub mod stop;

pub use config::{SimConfig, Termination, state_atol, validate_config};
pub use error::SimError;
pub use events::Event;
pub use results::{
    Peak, Sample, SampleKind, SimResult, Summary, TerminationReason, great_circle, violations,
};
pub use run::{Progress, simulate};
pub use source::{
    AttitudeSource, CoreGuidance, FixedAttitude, FlightGuidance, GuidanceSource, ReportContext,
    TickError,
};
pub(crate) use stop::ActiveRun;
pub use stop::{hold_new_runs, request_stop, runs_active, stop_requested};
