//! The HORUS-2B reference mission flown in SIL and in PIL (the same scenario, vehicle,
//! environment and settings).

use crate::dynamics::Dynamics;
use crate::env::Environment;
use crate::scenario::{Scenario, ScenarioError, build_guidance};
use crate::sim::{self, AttitudeSource, SimResult};
use crate::vehicle::Vehicle;

use super::{PilConfig, PilError, PilRecord, PilStats};

/// The HORUS-2B reference mission's stored profile (`Scenario::horus_2b_stored`: the default
/// scenario without its layers, full environment), as flown by SIL and PIL.
fn reference_setup() -> Result<(Scenario, Environment, Vehicle), ScenarioError> {
    let sc = Scenario::horus_2b_stored();
    let env = sc.environment.build();
    let veh = sc.load_vehicle()?;
    Ok((sc, env, veh))
}

/// The SIL guidance of the reference mission: `guidance-core`'s `Guidance<f64>` built from the
/// stored profile (the same table, rates, period and initial attitude as the firmware).
///
/// # Errors
/// [`ScenarioError`] if the reference mission cannot be set up.
pub fn reference_sil_guidance() -> Result<sim::CoreGuidance, ScenarioError> {
    let (sc, env, _) = reference_setup()?;
    Ok(sim::CoreGuidance::new(build_guidance(
        &sc,
        &env.planet,
        "(built-in)",
    )?))
}

/// Fly the HORUS-2B reference mission's stored profile (full environment, HORUS-2B vehicle,
/// its termination, tolerances and output settings) with any attitude source.
///
/// # Errors
/// [`ScenarioError`] naming the failure.
pub fn fly_reference<A: AttitudeSource>(source: A) -> Result<(SimResult, A), ScenarioError> {
    let (sc, env, veh) = reference_setup()?;
    let dynm = Dynamics::from_environment(&env, &veh);
    Ok(sim::simulate(dynm, source, &sc.sim_config(), &mut |_| {})?)
}

/// Fly the HORUS-2B reference mission in SIL (`f64` core guidance in-process).
///
/// # Errors
/// [`ScenarioError`] naming the failure.
pub fn fly_reference_sil() -> Result<SimResult, ScenarioError> {
    Ok(fly_reference(reference_sil_guidance()?)?.0)
}

/// Fly the HORUS-2B reference mission in PIL: the firmware (`cfg.elf`, with the same reference
/// table, rates, period and initial attitude compiled in) computes every command. Returns the
/// same [`SimResult`] as SIL, plus the link counters.
///
/// # Errors
/// [`PilError`] naming what failed; QEMU is stopped and the FIFOs are removed in every case.
pub fn fly_reference_pil(cfg: PilConfig) -> Result<(SimResult, PilStats), PilError> {
    fly_reference_pil_recorded(cfg).0
}

/// As [`fly_reference_pil`], also returning the record of the frames exchanged (complete up to
/// a failure, whose exchange is marked). The stored profile is uploaded as a set-up image,
/// like any scenario's stack ([`super::fly_scenario_pil`] of `Scenario::horus_2b_stored`).
pub fn fly_reference_pil_recorded(
    cfg: PilConfig,
) -> (Result<(SimResult, PilStats), PilError>, PilRecord) {
    let (run, record) = super::fly_scenario_pil(&Scenario::horus_2b_stored(), "(built-in)", cfg);
    (run.map(|r| (r.result, r.stats)), record)
}
