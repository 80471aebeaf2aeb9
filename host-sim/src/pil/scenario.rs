//! Any scenario in PIL: the scenario's guidance (node table in either independent variable, any
//! interpolation, bounds, period, rates, initial attitude, E-hat map and, with a
//! `[replanning]` section, the re-planner's target and configuration with the predictor model
//! SIL uses) is uploaded to the firmware as set-up frames, then flown with the same vehicle,
//! environment and settings as SIL.

use guidance_core::setup::{SetupItem, items};

use crate::dynamics::Dynamics;
use crate::scenario::{Scenario, build_guidance, build_replanning};
use crate::sim::{self, SimResult};

use super::reference::unwrap_pil_error;
use super::{FrameLimits, PilConfig, PilError, PilGuidance, PilRecord, PilStats};

/// The set-up items of `sc`'s guidance (as SIL builds it, `f64`) and the limits its command
/// frames must respect. `file` names the scenario in errors.
///
/// # Errors
/// [`PilError::Scenario`] if the scenario's guidance or vehicle does not build.
pub fn scenario_setup(
    sc: &Scenario,
    file: &str,
) -> Result<(Vec<SetupItem>, FrameLimits), PilError> {
    let env = sc.environment.build();
    let g = build_guidance(sc, &env.planet, file)?;
    let replanning = match &sc.replanning {
        Some(_) => {
            let veh = sc.load_vehicle()?;
            build_replanning(sc, &env, &veh, file)?
        }
        None => None,
    };
    let config = g.config();
    let initial = g.command();
    let energy = (
        env.planet.mu_m3_s2,
        env.planet.radius_m,
        sc.entry.radius_m,
        sc.entry.speed_m_s,
    );
    let list = items(
        g.table(),
        g.interpolator().kind(),
        config,
        initial,
        energy,
        replanning.as_ref(),
    )
    .collect();
    let limits = FrameLimits {
        bounds: g.table().bounds(),
        rates: config.rates,
        initial,
        period_s: config.period_s,
    };
    Ok((list, limits))
}

/// Fly scenario `sc` in PIL: its guidance uploaded to the firmware `cfg.elf`, which computes
/// every command (`f32` on the Cortex-M4F, fixed point on the Cortex-M3). Returns the run and
/// the link counters, and the frame record (complete up to a failure, whose exchange is
/// marked).
pub fn fly_scenario_pil(
    sc: &Scenario,
    file: &str,
    cfg: PilConfig,
) -> (Result<(SimResult, PilStats), PilError>, PilRecord) {
    let record = std::cell::RefCell::new(PilRecord::default());
    let run = || -> Result<(SimResult, PilStats), PilError> {
        let (setup, limits) = scenario_setup(sc, file)?;
        let veh = sc.load_vehicle()?;
        let env = sc.environment.build();
        let source = PilGuidance::start_with(cfg, limits, &setup)?;
        record.replace(source.record());
        let dynm = Dynamics::from_environment(&env, &veh);
        let (result, source) =
            sim::simulate(dynm, source, &sc.sim_config(), &mut |_| {}).map_err(unwrap_pil_error)?;
        let stats = source.finish()?;
        Ok((result, stats))
    };
    let r = run();
    (r, record.into_inner())
}
