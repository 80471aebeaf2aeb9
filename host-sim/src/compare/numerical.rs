//! The numerical side of a comparison: the simulator flying the closed forms' vehicle at
//! constant lift and bank.

use guidance_core::energy::EnergyNormalizer;
use guidance_core::guidance::Command;

use super::{NumericalSettings, Preset};
use crate::analytic::{self, AnalyticVehicle, LiftSetting};
use crate::dynamics::{Dynamics, SphericalState};
use crate::env::{Environment, ExponentialAtmosphere};
use crate::integrate::Tolerances;
use crate::sim::{FixedAttitude, SimConfig, SimError, SimResult, Termination, simulate};

/// Fly `vehicle` at constant lift `lift` from `entry` in the given environment.
///
/// # Errors
/// [`SimError`] for bad settings or an integrator failure.
#[allow(clippy::too_many_arguments)]
pub fn numerical_run(
    vehicle: &AnalyticVehicle,
    lift: &LiftSetting,
    fidelity: Preset,
    atmosphere: &ExponentialAtmosphere,
    entry: &SphericalState,
    termination: Termination,
    interface_altitude_m: f64,
    settings: &NumericalSettings,
) -> Result<SimResult, SimError> {
    let env = match fidelity {
        Preset::Simplified => Environment::simplified(*atmosphere),
        Preset::Full => Environment::full(),
    };
    let veh = vehicle.constant_lift_vehicle(lift);
    let dynm = Dynamics::from_environment(&env, &veh);
    let mut cfg = SimConfig::new(*entry);
    cfg.termination = termination;
    cfg.tolerances = Tolerances {
        rtol: settings.rtol,
        ..cfg.tolerances
    };
    cfg.output_interval_s = settings.output_interval_s;
    cfg.interface_altitude_m = interface_altitude_m;
    let source = FixedAttitude(Command {
        alpha_rad: 0.0,
        sigma_rad: lift.bank_rad,
    });
    let (res, _) = simulate(dynm, source, &cfg, &mut |_| {})?;
    Ok(res)
}

/// Normalised energy (as the simulator computes it from `entry`) of standstill-height speed
/// `speed_m_s` on the surface: once the energy has fallen to it, the speed is at most
/// `speed_m_s` at any altitude, so a run stopped there has passed that speed.
pub(super) fn energy_below_speed(entry: &SphericalState, speed_m_s: f64) -> Option<f64> {
    let p = analytic::planet();
    EnergyNormalizer::<f64>::new(p.mu_m3_s2, p.radius_m, entry.radius_m, entry.speed_m_s)
        .and_then(|e| e.normalized(p.radius_m, speed_m_s))
        .ok()
}
