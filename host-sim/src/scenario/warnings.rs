//! Warnings a GNC engineer wants from a run that otherwise succeeded: a vehicle limit the
//! flight exceeded (which, by how much, when), and entry values that are probably a unit
//! mistake (a speed in km/s, a flight-path angle in radians, an altitude in m read as km...).
//! They are not errors: the scenario is flown as written. [`Warning`] is the one type; the
//! library returns them ([`input_warnings`], [`flight_warnings`], [`super::RunOutput`]) and
//! the CLI prints them.

use crate::num_fmt::compact;
use crate::sim::SimResult;
use crate::vehicle::VehicleLimits;

use super::Scenario;

/// Entry speeds below this are probably given in km/s \[m/s\].
pub const MIN_PLAUSIBLE_ENTRY_SPEED_M_S: f64 = 1000.0;
/// Flight-path angles steeper than this are probably radians read as degrees, or a typo
/// \[deg\].
pub const MAX_PLAUSIBLE_FLIGHT_PATH_ANGLE_DEG: f64 = 30.0;
/// Entry altitudes below this are probably metres divided by the wrong power \[km\].
pub const MIN_PLAUSIBLE_ENTRY_ALTITUDE_KM: f64 = 20.0;

/// A vehicle limit of the path constraints (thesis eq. 4.9-4.11).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Limit {
    /// Stagnation-point heat flux (`[limits] heat_flux_kw_m2`).
    HeatFlux,
    /// g-load (`[limits] g_load`).
    GLoad,
    /// g-load rate (`[limits] g_load_rate_per_s`).
    GLoadRate,
}

impl Limit {
    /// The vehicle file's key of this limit.
    #[must_use]
    pub fn field(self) -> &'static str {
        match self {
            Self::HeatFlux => "limits.heat_flux_kw_m2",
            Self::GLoad => "limits.g_load",
            Self::GLoadRate => "limits.g_load_rate_per_s",
        }
    }
}

/// Something to tell the user about a run that is flown anyway.
#[derive(Clone, Debug, PartialEq)]
pub enum Warning {
    /// The flight's peak exceeded a vehicle limit.
    LimitExceeded {
        /// Which limit.
        limit: Limit,
        /// The peak, in the file's units (kW/m^2, g, 1/s).
        peak: f64,
        /// The limit, in the same units.
        limit_value: f64,
        /// When the peak occurred \[s\].
        peak_time_s: f64,
        /// First and last output sample above the limit \[s\] (`None` for the g-load rate,
        /// which is not sampled, or when only the peak itself was over).
        over_s: Option<(f64, f64)>,
    },
    /// An input value is probably in the wrong unit.
    LikelyUnitMistake {
        /// Dotted scenario field.
        field: &'static str,
        /// The value as the file gives it (its units).
        value: f64,
        /// Why it looks wrong.
        reason: &'static str,
    },
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::LimitExceeded {
                limit,
                peak,
                limit_value,
                peak_time_s,
                over_s,
            } => {
                let unit = match limit {
                    Limit::HeatFlux => " kW/m^2",
                    Limit::GLoad => " g",
                    Limit::GLoadRate => " 1/s",
                };
                write!(
                    f,
                    "vehicle limit `{}` exceeded: peak {}{unit} against {}{unit} ({:.1} % over) at t = {:.1} s",
                    limit.field(),
                    compact_4(*peak),
                    compact(*limit_value),
                    (peak / limit_value - 1.0) * 100.0,
                    peak_time_s
                )?;
                if let Some((a, b)) = over_s {
                    write!(f, "; over the limit from t = {a:.1} s to {b:.1} s")?;
                }
                Ok(())
            }
            Self::LikelyUnitMistake {
                field,
                value,
                reason,
            } => write!(
                f,
                "field `{field}` = {}: {reason} (flown as written)",
                compact(*value)
            ),
        }
    }
}

/// Four significant digits for peaks (511.3, not 511.26724730614).
fn compact_4(x: f64) -> String {
    compact(format!("{x:.4e}").parse().unwrap_or(x))
}

/// Warnings about the scenario's inputs: likely unit mistakes in the entry state.
#[must_use]
pub fn input_warnings(sc: &Scenario) -> Vec<Warning> {
    let e = &sc.entry;
    let mut out = Vec::new();
    if e.speed_m_s < MIN_PLAUSIBLE_ENTRY_SPEED_M_S {
        out.push(Warning::LikelyUnitMistake {
            field: "entry.speed_m_s",
            value: e.speed_m_s,
            reason: "an entry speed below 1 km/s: given in km/s?",
        });
    }
    let gamma_deg = e.flight_path_angle_rad.to_degrees();
    if gamma_deg.abs() > MAX_PLAUSIBLE_FLIGHT_PATH_ANGLE_DEG {
        out.push(Warning::LikelyUnitMistake {
            field: "entry.flight_path_angle_deg",
            value: gamma_deg,
            reason: "a flight-path angle steeper than 30 deg: given in radians, or a typo?",
        });
    }
    let h_km = (e.radius_m - sc.environment.planet.radius_m) / 1e3;
    if h_km < MIN_PLAUSIBLE_ENTRY_ALTITUDE_KM {
        out.push(Warning::LikelyUnitMistake {
            field: "entry.altitude_km",
            value: h_km,
            reason: "an entry altitude below 20 km: given in another unit?",
        });
    }
    out
}

/// Warnings about a flown trajectory: each vehicle limit its peak exceeded.
#[must_use]
pub fn flight_warnings(result: &SimResult, limits: &VehicleLimits) -> Vec<Warning> {
    let s = &result.summary;
    let over = |value: &dyn Fn(&crate::sim::Sample) -> f64, limit: f64| {
        let mut times = result
            .samples
            .iter()
            .filter(|x| value(x) > limit)
            .map(|x| x.time_s);
        let first = times.next()?;
        Some((first, times.last().unwrap_or(first)))
    };
    let mut out = Vec::new();
    let cases = [
        (
            Limit::HeatFlux,
            s.peak_heat_flux_w_m2.value / 1e3,
            limits.heat_flux_w_m2 / 1e3,
            s.peak_heat_flux_w_m2.time_s,
            over(&|x| x.conditions.heat_flux_w_m2, limits.heat_flux_w_m2),
        ),
        (
            Limit::GLoad,
            s.peak_g_load.value,
            limits.g_load,
            s.peak_g_load.time_s,
            over(&|x| x.conditions.g_load, limits.g_load),
        ),
        (
            Limit::GLoadRate,
            s.peak_g_load_rate_per_s.value,
            limits.g_load_rate_per_s,
            s.peak_g_load_rate_per_s.time_s,
            None,
        ),
    ];
    for (limit, peak, limit_value, peak_time_s, over_s) in cases {
        if peak > limit_value {
            out.push(Warning::LimitExceeded {
                limit,
                peak,
                limit_value,
                peak_time_s,
                over_s,
            });
        }
    }
    out
}
