//! Simulation settings ([`SimConfig`], [`Termination`]) and their validation.

use crate::dynamics::{STATE_LEN, SphericalState};
use crate::integrate::Tolerances;

use super::SimError;

/// Termination conditions (each optional except the time limit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Termination {
    /// Stop when the altitude falls below this \[m\].
    pub altitude_m: Option<f64>,
    /// Stop when the Mach number falls below this [-].
    pub mach: Option<f64>,
    /// Stop when the normalised energy falls below this [-].
    pub normalized_energy: Option<f64>,
    /// Stop at this mission time \[s\].
    pub max_time_s: f64,
}

impl Default for Termination {
    fn default() -> Self {
        Self {
            altitude_m: Some(25_000.0),
            mach: None,
            normalized_energy: None,
            max_time_s: 4000.0,
        }
    }
}

/// Simulation settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SimConfig {
    /// Entry state (planet-relative) at t = 0.
    pub entry: SphericalState,
    /// Termination conditions.
    pub termination: Termination,
    /// Integrator settings.
    pub tolerances: Tolerances,
    /// Trajectory output interval \[s\]; 0 records at guidance ticks (and events) only.
    pub output_interval_s: f64,
    /// Atmospheric interface altitude for exit/re-entry events \[m\] (thesis: 100 km).
    pub interface_altitude_m: f64,
    /// Minimum window for the finite-difference g-load rate \[s\].
    pub g_rate_window_s: f64,
}

impl SimConfig {
    /// Defaults around an entry state: 25 km / 4000 s termination, rtol 1e-9, output at
    /// ticks, interface at 100 km, 0.1 s g-rate window.
    #[must_use]
    pub fn new(entry: SphericalState) -> Self {
        Self {
            entry,
            termination: Termination::default(),
            tolerances: Tolerances {
                rtol: 1e-9,
                h_init: 0.1,
                h_min: 1e-9,
                h_max: 20.0,
                max_steps: 2_000_000,
                event_time_tol_s: 1e-6,
            },
            output_interval_s: 0.0,
            interface_altitude_m: 100_000.0,
            g_rate_window_s: 0.1,
        }
    }
}

/// Smallest non-zero output interval \[s\] (1 ms; 0 means one sample per guidance tick).
pub const MIN_OUTPUT_INTERVAL_S: f64 = 1e-3;
/// Most output samples a run may record (termination.max_time_s / output interval).
pub const MAX_OUTPUT_SAMPLES: f64 = 1e7;
/// Largest event-location time tolerance \[s\] (10 ms; it must also be below the guidance
/// period).
pub const MAX_EVENT_TIME_TOL_S: f64 = 1e-2;
/// Largest integrator step budget.
pub const MAX_STEPS_LIMIT: u64 = 100_000_000;

fn cfg_err(field: &'static str, value: f64, reason: &'static str) -> SimError {
    SimError::Config {
        field,
        value,
        reason,
    }
}

/// Validate a configuration against a planet.
///
/// # Errors
/// [`SimError::Config`] naming the field and value.
pub fn validate_config(cfg: &SimConfig, planet_radius_m: f64) -> Result<(), SimError> {
    let e = &cfg.entry;
    if !(e.radius_m.is_finite() && e.radius_m > planet_radius_m) {
        return Err(cfg_err(
            "entry.altitude_m",
            e.radius_m - planet_radius_m,
            "must be finite and > 0",
        ));
    }
    if !(e.speed_m_s.is_finite() && e.speed_m_s > 0.0) {
        return Err(cfg_err(
            "entry.speed_m_s",
            e.speed_m_s,
            "must be finite and > 0",
        ));
    }
    if !(e.flight_path_angle_rad.is_finite()
        && e.flight_path_angle_rad.abs() <= std::f64::consts::FRAC_PI_2)
    {
        return Err(cfg_err(
            "entry.flight_path_angle_rad",
            e.flight_path_angle_rad,
            "must be within [-90, 90] deg",
        ));
    }
    if !(e.latitude_rad.is_finite() && e.latitude_rad.abs() < std::f64::consts::FRAC_PI_2) {
        return Err(cfg_err(
            "entry.latitude_rad",
            e.latitude_rad,
            "must be within (-90, 90) deg",
        ));
    }
    for (f, v) in [
        ("entry.longitude_rad", e.longitude_rad),
        ("entry.heading_rad", e.heading_rad),
    ] {
        if !v.is_finite() {
            return Err(cfg_err(f, v, "must be finite"));
        }
    }
    let t = &cfg.termination;
    if !(t.max_time_s.is_finite() && t.max_time_s > 0.0) {
        return Err(cfg_err(
            "termination.max_time_s",
            t.max_time_s,
            "must be finite and > 0",
        ));
    }
    for (f, v) in [
        ("termination.altitude_m", t.altitude_m),
        ("termination.mach", t.mach),
        ("termination.normalized_energy", t.normalized_energy),
    ] {
        if let Some(v) = v
            && !v.is_finite()
        {
            return Err(cfg_err(f, v, "must be finite"));
        }
    }
    let dt = cfg.output_interval_s;
    if !(dt == 0.0 || (dt.is_finite() && dt >= MIN_OUTPUT_INTERVAL_S)) {
        return Err(cfg_err(
            "output.interval_s",
            dt,
            "must be 0 (one sample per guidance tick) or >= 0.001 s",
        ));
    }
    if dt > 0.0 && t.max_time_s / dt > MAX_OUTPUT_SAMPLES {
        return Err(cfg_err(
            "output.interval_s",
            dt,
            "must be >= termination.max_time_s / 1e7 (at most 10 million samples)",
        ));
    }
    if !(cfg.g_rate_window_s.is_finite() && cfg.g_rate_window_s > 0.0) {
        return Err(cfg_err(
            "g_rate_window_s",
            cfg.g_rate_window_s,
            "must be > 0",
        ));
    }
    if !cfg.interface_altitude_m.is_finite() {
        return Err(cfg_err(
            "interface_altitude_m",
            cfg.interface_altitude_m,
            "must be finite",
        ));
    }
    cfg.tolerances.validate()?;
    let tl = &cfg.tolerances;
    if tl.event_time_tol_s > MAX_EVENT_TIME_TOL_S {
        return Err(cfg_err(
            "integrator.event_time_tol_s",
            tl.event_time_tol_s,
            "must be <= 0.01 s",
        ));
    }
    if tl.max_steps > MAX_STEPS_LIMIT {
        return Err(cfg_err(
            "integrator.max_steps",
            tl.max_steps as f64,
            "must be <= 1e8",
        ));
    }
    if tl.h_max < t.max_time_s / tl.max_steps as f64 {
        return Err(cfg_err(
            "integrator.h_max_s",
            tl.h_max,
            "must be >= termination.max_time_s / integrator.max_steps \
             (else the step budget runs out before the time limit)",
        ));
    }
    Ok(())
}

/// Per-component absolute tolerances of the integrated state for relative tolerance
/// `rtol`: position 1e6 * rtol m, velocity 1e3 * rtol m/s, heat load 1e9 * rtol J/m^2,
/// range angle rtol rad (scales of the quantities during entry).
#[must_use]
pub fn state_atol(rtol: f64) -> [f64; STATE_LEN] {
    [
        1e6 * rtol,
        1e6 * rtol,
        1e6 * rtol,
        1e3 * rtol,
        1e3 * rtol,
        1e3 * rtol,
        1e9 * rtol,
        rtol,
    ]
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
    fn config_validation_names_fields() {
        let mut c = SimConfig::new(at(0.0, 0.0));
        c.entry.radius_m = 7e6;
        c.entry.speed_m_s = 7000.0;
        assert!(validate_config(&c, 6.4e6).is_ok());
        let mut bad = c;
        bad.entry.speed_m_s = f64::NAN;
        assert!(
            validate_config(&bad, 6.4e6)
                .unwrap_err()
                .to_string()
                .contains("entry.speed_m_s")
        );
        let mut bad = c;
        bad.termination.max_time_s = -1.0;
        assert!(
            validate_config(&bad, 6.4e6)
                .unwrap_err()
                .to_string()
                .contains("max_time_s")
        );
        let mut bad = c;
        bad.tolerances.rtol = 0.0;
        assert!(
            validate_config(&bad, 6.4e6)
                .unwrap_err()
                .to_string()
                .contains("rtol")
        );
    }
}
