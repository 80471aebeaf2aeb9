//! The design problems' simulators: the closed-loop numerical simulator (`scenario::fly`) or
//! the analytical simulator ([`crate::analytic::guided_glide`]: the glide closed form flown
//! segment by segment along the node table; thesis sec. 9.2's analytical SRM problem).
//!
//! An analytical evaluation takes from the scenario what the closed forms can use: the vehicle
//! (bank-only, its trim point as the maximum-L/D point of a parabolic polar, see
//! [`crate::analytic`]), the entry altitude (speed and flight-path angle are imposed by the
//! closed form for the first node's lift), the entry position and heading (placement only:
//! the planet does not rotate), the node table and the termination altitude. The atmosphere
//! is the scenario's own when it is exponential (the SRM presets' simplified environment, so
//! that the numerical and analytical problems fly the same atmosphere), otherwise the
//! exponential fit to US76 at [`DEFAULT_FIT_ALTITUDES_M`]. Everything else of the scenario
//! (guidance clock, rate limits, interpolation, integrator, J2, rotation) does not apply.

use serde::{Deserialize, Serialize};

use super::DesignError;
use crate::analytic::{
    AnalyticError, AnalyticRun, AnalyticVehicle, DEFAULT_FIT_ALTITUDES_M, DEFAULT_POLAR_MACH,
    GuidedGlide, Placement, fit_us76, guided_glide,
};
use crate::env::ExponentialAtmosphere;
use crate::scenario::{AtmosphereSpec, Scenario};

/// Which simulator evaluates a design problem.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Simulator {
    /// The closed loop in the numerical simulator (guidance-core's `Guidance` at its clock).
    #[default]
    Numerical,
    /// The analytical simulator: the glide closed form, one segment per node.
    Analytical,
}

impl Simulator {
    /// Whether this is the default (for `skip_serializing_if`).
    #[must_use]
    pub fn is_numerical(&self) -> bool {
        *self == Simulator::Numerical
    }
}

/// What the analytical simulator needs of a base scenario, built once per problem.
#[derive(Clone, Debug)]
pub struct AnalyticalModel {
    vehicle: AnalyticVehicle,
    atmosphere: ExponentialAtmosphere,
}

impl AnalyticalModel {
    /// The model of `base` (module documentation).
    ///
    /// # Errors
    /// [`DesignError::Setting`] naming the field when the base has no termination altitude or
    /// its vehicle is not steered by bank only; [`DesignError::Analytic`] when the vehicle
    /// has no usable polar.
    pub fn of(base: &Scenario) -> Result<Self, DesignError> {
        let v = base.load_vehicle().map_err(DesignError::Scenario)?;
        let vehicle = AnalyticVehicle::from_vehicle(&v, DEFAULT_POLAR_MACH)?;
        if vehicle.trim_cl.is_none() {
            return Err(DesignError::Setting {
                field: "base.vehicle",
                value: v.name.clone(),
                reason: "the analytical simulator flies bank-only vehicles (trim coefficients, \
                         e.g. srm); use simulator = \"numerical\"",
            });
        }
        if base.termination.altitude_m.is_none() {
            return Err(DesignError::Setting {
                field: "base.termination.altitude_km",
                value: "none".into(),
                reason: "the analytical simulator ends at an altitude: set one",
            });
        }
        let atmosphere = match &base.environment.atmosphere {
            AtmosphereSpec::Exponential(a) => *a,
            _ => fit_us76(DEFAULT_FIT_ALTITUDES_M.0, DEFAULT_FIT_ALTITUDES_M.1)?,
        };
        Ok(Self {
            vehicle,
            atmosphere,
        })
    }

    /// The closed forms' vehicle.
    #[must_use]
    pub fn vehicle(&self) -> &AnalyticVehicle {
        &self.vehicle
    }

    /// The exponential atmosphere flown.
    #[must_use]
    pub fn atmosphere(&self) -> &ExponentialAtmosphere {
        &self.atmosphere
    }

    /// Fly `sc` (a scenario of the problem: its node table and entry altitude) analytically.
    ///
    /// # Errors
    /// [`AnalyticError`] (a table outside the closed form's domain, a bad table).
    pub fn fly(&self, sc: &Scenario) -> Result<AnalyticRun, AnalyticError> {
        guided_glide(&GuidedGlide {
            vehicle: &self.vehicle,
            atmosphere: &self.atmosphere,
            entry_altitude_m: sc.entry.radius_m - sc.environment.planet.radius_m,
            placement: Placement::of(&sc.entry),
            nodes: &sc.guidance.nodes,
            end_altitude_m: sc.termination.altitude_m.unwrap_or(0.0),
        })
    }
}
