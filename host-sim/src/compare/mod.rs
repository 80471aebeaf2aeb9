//! Analytical against numerical: the closed-form trajectory of [`crate::analytic`] against the
//! numerical simulator ([`crate::sim::simulate`]) for the same vehicle, entry state and constant
//! lift, in two environments, over a grid of (entry speed or entry altitude) x (vertical lift
//! coefficient), as in thesis fig. 8.5 (glide: final range-angle error over entry altitude and
//! `C_L`, SRM capsule, simplified environment) and sec. 8.2.1 (skip).
//!
//! * [`Preset::Simplified`]: non-rotating sphere, central gravity and the *same* exponential
//!   atmosphere as the closed forms ([`crate::env::Environment::simplified`]): the closed forms'
//!   own assumptions, so the error is that of the approximations alone (thesis sec. 8.1.3).
//! * [`Preset::Full`]: rotating Earth, US76, J2 ([`crate::env::Environment::full`]).
//!
//! In both, the numerical vehicle is the analytical one: its drag polar at constant `C_L`
//! ([`AnalyticVehicle::constant_lift_vehicle`]), flown at constant bank through the simulator's
//! constant-attitude source [`FixedAttitude`] (no guidance ticks, no rate limits). The full run
//! therefore measures the environment's effect, not that of an aerodynamic table (for the SRM,
//! whose aerodynamics are trim coefficients, the polar vehicle is the vehicle).
//!
//! Metrics and their errors (analytical minus numerical):
//! * skip (entry -> return to the entry altitude): exit speed [%], exit flight-path angle
//!   \[deg\], deepest altitude \[km\], peak heat flux [%], range angle to the exit [%];
//! * glide (imposed entry -> end): range angle [%], final speed [%] (end at an altitude) or final
//!   altitude \[km\] (end at a speed), peak heat flux [%].
//!
//! The range angle of both is the flown range angle `integral V cos(gamma)/r dt` (eq. 3.15),
//! the quantity the closed forms give. Points where the closed form is out of its domain are
//! kept and marked with its typed error (and the numerical runs are not flown: the glide's entry
//! state comes from the closed form). Numerical runs that do not reach the comparison point (no
//! exit, end not reached) are marked as failed with the reason.
//!
//! [`AnalyticVehicle::constant_lift_vehicle`]: crate::analytic::AnalyticVehicle::constant_lift_vehicle
//! [`FixedAttitude`]: crate::sim::FixedAttitude

mod case;
mod csv;
mod grid;
mod heatmap;
mod metrics;
mod numerical;
mod output;

use crate::analytic::AnalyticError;
use crate::env::Preset;
use crate::report::ReportError;

pub use case::{AnalyticOutcome, CaseRuns, Outcome, compare_case};
pub use csv::grid_csv;
pub use grid::{
    CompareConfig, CompareGrid, GridKind, GridPoint, PointHook, run_grid, run_grid_with,
};
pub use heatmap::heat_map_svg;
pub use metrics::{
    Case, GLIDE_METRICS_ALTITUDE_END, GLIDE_METRICS_SPEED_END, Metric, SKIP_METRICS, metric_error,
};
pub use numerical::numerical_run;
pub use output::{write_case, write_case_into, write_grid, write_grid_into};

/// Numerical-run settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NumericalSettings {
    /// RKF4(5) relative tolerance [-].
    pub rtol: f64,
    /// Sample interval \[s\] (the deepest altitude and speed crossings are read from samples).
    pub output_interval_s: f64,
    /// Time limit of a glide run \[s\].
    pub max_time_s: f64,
}

impl Default for NumericalSettings {
    /// rtol 1e-8, samples every 1 s, 8000 s limit.
    fn default() -> Self {
        Self {
            rtol: 1e-8,
            output_interval_s: 1.0,
            max_time_s: 8000.0,
        }
    }
}

/// Comparison failures that stop the whole grid (per-point problems are marked instead).
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    /// A setting is out of range.
    #[error("invalid setting `{field}` = {value}: {reason}")]
    Setting {
        /// Setting name with unit.
        field: &'static str,
        /// Its value.
        value: String,
        /// What is required.
        reason: &'static str,
    },
    /// Analytical set-up failure that is not a domain error.
    #[error(transparent)]
    Analytic(#[from] AnalyticError),
    /// Output could not be written.
    #[error(transparent)]
    Report(#[from] ReportError),
    /// The vehicle could not be loaded.
    #[error(transparent)]
    Vehicle(#[from] crate::vehicle::VehicleFileError),
    /// Writing to the console failed.
    #[error("cannot write output: {0}")]
    Io(#[from] std::io::Error),
}

impl CompareError {
    /// A [`CompareError::Setting`] naming `field`, `value` and `reason`.
    pub fn setting(field: &'static str, value: impl ToString, reason: &'static str) -> Self {
        Self::Setting {
            field,
            value: value.to_string(),
            reason,
        }
    }
}

fn setting(field: &'static str, value: impl ToString, reason: &'static str) -> CompareError {
    CompareError::setting(field, value, reason)
}
