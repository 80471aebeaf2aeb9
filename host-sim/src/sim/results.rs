//! What a run produces: trajectory [`Sample`]s, the [`Summary`] and why the run stopped.

use guidance_core::guidance::Command;
use guidance_core::monitor::{ConstraintLimits, Violations, violation};
use serde::Serialize;

use crate::dynamics::{FlightConditions, SphericalState};
use crate::vehicle::VehicleLimits;

/// Why the simulation stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TerminationReason {
    /// Altitude fell below the termination altitude.
    Altitude,
    /// Mach number fell below the termination Mach.
    Mach,
    /// Normalised energy fell below the termination value.
    NormalizedEnergy,
    /// The time limit was reached.
    MaxTime,
    /// The vehicle reached the surface (altitude 0).
    Ground,
}

/// One trajectory sample (SI units, radians).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Mission time \[s\].
    pub time_s: f64,
    /// Planet-relative spherical state.
    pub state: SphericalState,
    /// Attitude \[rad\].
    pub attitude: Command<f64>,
    /// Flight conditions (altitude, density, Mach, forces, heat flux, g-load).
    pub conditions: FlightConditions,
    /// Heat load so far [J/m^2].
    pub heat_load_j_m2: f64,
    /// Flown range angle so far \[rad\].
    pub flown_range_rad: f64,
    /// Normalised energy [-].
    pub normalized_energy: f64,
    /// Why this sample was taken.
    pub kind: SampleKind,
}

/// Why a sample was recorded.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SampleKind {
    /// Initial state.
    Start,
    /// Output interval or guidance tick.
    Output,
    /// Atmosphere exit (rising through the interface).
    Exit,
    /// Re-entry (falling through the interface).
    Entry,
    /// Final state.
    End,
}

/// A value with the time it occurred: the core's one peak type.
pub type Peak = guidance_core::monitor::TimedPeak<f64>;

/// Run summary.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// Why the run stopped.
    pub termination: TerminationReason,
    /// Flight time \[s\].
    pub flight_time_s: f64,
    /// Great-circle angle between entry and final position (planet-fixed) \[rad\].
    pub range_angle_rad: f64,
    /// Integral of V cos(gamma) / r dt (eq. 3.15) \[rad\].
    pub flown_range_angle_rad: f64,
    /// Heat load, integral of the Chapman heat flux [J/m^2].
    pub heat_load_j_m2: f64,
    /// Peak heat flux [W/m^2].
    pub peak_heat_flux_w_m2: Peak,
    /// Peak g-load [-].
    pub peak_g_load: Peak,
    /// Peak |g-load rate| [1/s]: finite differences (core `GLoadRateMonitor`) of the g-load
    /// at accepted steps at least [`SimConfig::g_rate_window_s`](super::SimConfig::g_rate_window_s) apart. Steps end on every
    /// tick and ramp end, so the short attitude ramps after each tick are resolved.
    pub peak_g_load_rate_per_s: Peak,
    /// Atmosphere exits (rising through the interface).
    pub exits: u32,
    /// Skips: exits followed by a re-entry.
    pub skips: u32,
    /// Times of exits and re-entries \[s\].
    pub interface_crossings_s: Vec<(f64, SampleKind)>,
    /// Constraint violations (eq. 4.9-4.11): 0 if within the limit, else peak / limit.
    pub violations: Violations<f64>,
    /// Integrator work.
    pub rhs_evals: u64,
    /// Accepted integrator steps.
    pub accepted_steps: u64,
    /// Rejected integrator steps.
    pub rejected_steps: u64,
    /// Guidance ticks.
    pub ticks: u64,
}

/// Constraint violations of timed peaks (eq. 4.9-4.11, `guidance-core`'s monitor): 0 if
/// within the vehicle's limit, else peak / limit.
#[must_use]
pub fn violations(
    heat_flux: Peak,
    g_load: Peak,
    g_load_rate: Peak,
    limits: &VehicleLimits,
) -> Violations<f64> {
    let limits = ConstraintLimits {
        heat_flux_w_m2: limits.heat_flux_w_m2,
        g_load: limits.g_load,
        g_load_rate_per_s: limits.g_load_rate_per_s,
    };
    Violations {
        heat_flux: violation(heat_flux.value, limits.heat_flux_w_m2),
        g_load: violation(g_load.value, limits.g_load),
        g_load_rate: violation(g_load_rate.value, limits.g_load_rate_per_s),
    }
}

/// Result of a run.
#[derive(Clone, Debug)]
pub struct SimResult {
    /// Trajectory samples.
    pub samples: Vec<Sample>,
    /// Summary.
    pub summary: Summary,
}

/// Great-circle angle between two positions \[rad\].
#[must_use]
pub fn great_circle(a: &SphericalState, b: &SphericalState) -> f64 {
    let (sa, ca) = a.latitude_rad.sin_cos();
    let (sb, cb) = b.latitude_rad.sin_cos();
    let dl = b.longitude_rad - a.longitude_rad;
    let x = sa * sb + ca * cb * dl.cos();
    let yv = ((cb * dl.sin()).powi(2) + (ca * sb - sa * cb * dl.cos()).powi(2)).sqrt();
    yv.atan2(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(lat_deg: f64, lon_deg: f64) -> SphericalState {
        SphericalState {
            radius_m: 1.0,
            longitude_rad: lon_deg.to_radians(),
            latitude_rad: lat_deg.to_radians(),
            speed_m_s: 0.0,
            flight_path_angle_rad: 0.0,
            heading_rad: 0.0,
        }
    }

    #[test]
    fn great_circle_angles() {
        let d = |a: f64, b: f64| (a - b).abs() < 1e-12;
        assert!(d(
            great_circle(&at(0.0, 0.0), &at(0.0, 90.0)),
            std::f64::consts::FRAC_PI_2
        ));
        assert!(d(
            great_circle(&at(0.0, 0.0), &at(90.0, 0.0)),
            std::f64::consts::FRAC_PI_2
        ));
        assert!(d(great_circle(&at(10.0, 20.0), &at(10.0, 20.0)), 0.0));
        assert!(d(
            great_circle(&at(0.0, -170.0), &at(0.0, 170.0)),
            20f64.to_radians()
        ));
        assert!(d(
            great_circle(&at(0.0, 0.0), &at(0.0, 180.0)),
            std::f64::consts::PI
        ));
    }
}
