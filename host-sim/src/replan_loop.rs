//! Closed loop with onboard re-planning: `guidance-core`'s [`ReplanningGuidance`] (the flight
//! [`guidance_core::guidance::Guidance`] plus the analytic predictor-corrector of
//! `guidance_core::replan`) as an [`AttitudeSource`] of [`crate::sim::simulate`], at the
//! guidance's own 2 s clock, like [`crate::sim::CoreGuidance`].
//!
//! Every re-plan report is recorded ([`ReplanLoop::reports`]) so a run can be checked for the
//! re-planning rate, the cases that happened and the predictor calls used.
//!
//! [`predictor_model`] builds the predictor's model of the world from a simulator vehicle and an
//! exponential atmosphere, with the same conventions as the analytical simulator
//! ([`crate::analytic::AnalyticVehicle`]): a tabulated polar at one Mach number, or for a
//! trim-only vehicle (the SRM capsule) the polar with the trim point at maximum L/D
//! (`lambda = 1`, steered by bank only).

use guidance_core::NavState;
use guidance_core::guidance::Command;
use guidance_core::replan::{PredictorModel, ReplanReport, ReplanningGuidance};
use guidance_core::vinh::{ExpAtmosphere, Planet as VinhPlanet};

use crate::analytic::{AnalyticError, AnalyticVehicle};
use crate::env::{ExponentialAtmosphere, Planet};
use crate::sim::{AttitudeSource, ramp_kink};
use crate::vehicle::Vehicle;

/// [`ReplanningGuidance`] in the closed loop, with the re-plan reports of the run.
#[derive(Clone, Debug)]
pub struct ReplanLoop {
    /// The flight guidance with re-planning.
    pub guidance: ReplanningGuidance<f64>,
    /// Every re-plan of the run, in order.
    pub reports: Vec<ReplanReport<f64>>,
}

impl ReplanLoop {
    /// Wrap a configured [`ReplanningGuidance`].
    #[must_use]
    pub fn new(guidance: ReplanningGuidance<f64>) -> Self {
        Self {
            guidance,
            reports: Vec::new(),
        }
    }
}

fn attitude_of(c: Command<f64>) -> Command<f64> {
    Command {
        alpha_rad: c.alpha_rad,
        sigma_rad: c.sigma_rad,
    }
}

impl AttitudeSource for ReplanLoop {
    fn tick(&mut self, nav: &NavState<f64>) -> Result<(), String> {
        let out = self.guidance.update(nav).map_err(|e| e.to_string())?;
        if let Some(r) = out.replan {
            self.reports.push(r);
        }
        if out.guidance.ticked {
            Ok(())
        } else {
            Err(format!(
                "guidance did not tick at t = {} s (next tick {} s)",
                nav.time_s,
                self.guidance.next_tick_s()
            ))
        }
    }
    fn attitude_at(&self, time_s: f64) -> Command<f64> {
        attitude_of(self.guidance.attitude_at(time_s))
    }
    fn next_tick_s(&self) -> f64 {
        self.guidance.next_tick_s()
    }
    fn next_kink_s(&self, time_s: f64) -> f64 {
        let g = self.guidance.guidance();
        let Some(t_k) = g.ramp_start_s() else {
            return f64::INFINITY;
        };
        let rates = g.config().rates;
        ramp_kink(
            time_s,
            t_k,
            attitude_of(g.attitude_at(t_k)),
            attitude_of(g.command()),
            (rates.alpha_rad_s, rates.sigma_rad_s),
        )
    }
}

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
