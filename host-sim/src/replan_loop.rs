//! Closed loop with onboard re-planning: `guidance-core`'s [`ReplanningGuidance`] (the flight
//! [`guidance_core::guidance::Guidance`] plus the analytic predictor-corrector of
//! `guidance_core::replan`) as an attitude source of [`crate::sim::simulate`], at the
//! guidance's own 2 s clock, through the same adapter as [`crate::sim::CoreGuidance`]
//! ([`GuidanceSource`]).
//!
//! Every re-plan report is recorded ([`GuidanceSource::reports`]) so a run can be checked for
//! the re-planning rate, the cases that happened and the predictor calls used.
//!
//! [`predictor_model`] builds the predictor's model of the world from a simulator vehicle and an
//! exponential atmosphere, with the same conventions as the analytical simulator
//! ([`crate::analytic::AnalyticVehicle`]): a tabulated polar at one Mach number, or for a
//! trim-only vehicle (the SRM capsule) the polar with the trim point at maximum L/D
//! (`lambda = 1`, steered by bank only).

use guidance_core::replan::{PredictorModel, ReplanningGuidance};
use guidance_core::vinh::{ExpAtmosphere, Planet as VinhPlanet};

use crate::analytic::{AnalyticError, AnalyticVehicle};
use crate::env::{ExponentialAtmosphere, Planet};
use crate::sim::GuidanceSource;
use crate::vehicle::Vehicle;

/// [`ReplanningGuidance`] in the closed loop (the simulator's one guidance adapter), with the
/// re-plan reports of the run in [`GuidanceSource::reports`].
pub type ReplanLoop = GuidanceSource<ReplanningGuidance<f64>>;

/// The predictor's model: `planet`'s `mu`, radius and rotation rate (the closed forms assume no
/// rotation; the rate feeds the effective-gravity correction of
/// [`PredictorModel::rotation_rate_rad_s`]),
/// `atmosphere` (an exponential atmosphere; for US76 use e.g.
/// [`crate::analytic::fit_us76`]) and the vehicle's polar at Mach `polar_mach`.
///
/// # Errors
/// [`AnalyticError`] if the vehicle has no polar or trim coefficients (see
/// [`AnalyticVehicle::from_vehicle`]).
pub fn predictor_model(
    vehicle: &Vehicle,
    atmosphere: &ExponentialAtmosphere,
    planet: &Planet,
    polar_mach: f64,
) -> Result<PredictorModel<f64>, AnalyticError> {
    let av = AnalyticVehicle::from_vehicle(vehicle, polar_mach)?;
    Ok(PredictorModel {
        planet: VinhPlanet {
            mu_m3_s2: planet.mu_m3_s2,
            radius_m: planet.radius_m,
        },
        atmosphere: ExpAtmosphere {
            rho0_kg_m3: atmosphere.rho0_kg_m3(),
            scale_height_m: atmosphere.scale_height_m(),
            ref_radius_m: planet.radius_m + atmosphere.reference_altitude_m(),
        },
        vehicle: av.params(),
        rotation_rate_rad_s: planet.rotation_rate_rad_s,
    })
}
