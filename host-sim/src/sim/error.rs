//! [`SimError`]: why a closed-loop run failed.

use guidance_core::GuidanceError;

use crate::integrate::{IntegrateError, ToleranceError};

/// Simulation failures.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// An invalid setting.
    #[error("invalid setting `{field}` = {}: {reason}", crate::num_fmt::Compact(*value))]
    Config {
        /// Setting name.
        field: &'static str,
        /// Its value.
        value: f64,
        /// Why it is rejected.
        reason: &'static str,
    },
    /// An integrator setting out of range.
    #[error(transparent)]
    Tolerances(#[from] ToleranceError),
    /// The entry state defines no normalised energy (the core's error).
    #[error("invalid entry state: {0}")]
    Entry(GuidanceError),
    /// The integrator failed.
    #[error("integration failed: {0}")]
    Integration(#[from] IntegrateError),
    /// The attitude source (guidance) failed at a tick; its error is the source.
    #[error("guidance failed at t = {} s: {source}", crate::num_fmt::Compact(*time_s))]
    Guidance {
        /// Mission time \[s\].
        time_s: f64,
        /// The attitude source's error.
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// The attitude source asked for a tick that is not after the current time.
    #[error(
        "guidance at t = {} s: next tick {} s is not after the current time",
        crate::num_fmt::Compact(*time_s),
        crate::num_fmt::Compact(*next_tick_s)
    )]
    TickNotAfter {
        /// Mission time \[s\].
        time_s: f64,
        /// The next tick the source reported \[s\].
        next_tick_s: f64,
    },
    /// The run was stopped on request (Ctrl-C: [`super::request_stop`]).
    #[error("interrupted at t = {} s", crate::num_fmt::Compact(*time_s))]
    Interrupted {
        /// Mission time \[s\].
        time_s: f64,
    },
    /// The integrator reported an event the loop does not define.
    #[error("integrator reported unknown event index {0}")]
    UnknownEvent(usize),
}
