//! Any scenario in PIL: the stack the scenario flies in SIL ([`crate::scenario::fly`]) is
//! uploaded to the firmware as one set-up image (protocol v2, `guidance_core::setup::image`)
//! and flown beside its host twin (every command frame compared bit for bit,
//! [`super::TwinCheck`]):
//!
//! * a scenario with `[guidance.*]` layers: the campaign set-up's stack in its fullest mode
//!   ([`crate::scenario::stack_setup`]), flown as `simulate` flies it, the nominal case to the
//!   terminal interface ([`super::fly_case_pil`]'s flight), its outcome against the target
//!   included;
//! * without: the stored profile alone ([`build_stack`]: node table in either independent
//!   variable, any interpolation, bounds, period, rates, initial attitude, E-hat map), flown
//!   with the scenario's vehicle, environment, termination and settings.

use guidance_core::setup::image::{CHUNK_BYTES, chunks};
use guidance_core::stack::HostStackConfig;

use crate::campaign::CampaignSetup;
use crate::dynamics::Dynamics;
use crate::scenario::{Scenario, StackOutcome, build_stack, stack_setup};
use crate::sim::{self, SimResult};

use super::campaign::{fly_case_pil_run, stack_image, stack_limits, start_stack};
use super::{FrameLimits, PilConfig, PilError, PilRecord, PilStats, TwinCheck, unwrap_pil_error};

/// The stack a scenario flies: its stored profile alone, or its layers' campaign set-up.
enum ScenarioStack {
    /// No `[guidance.*]` layers.
    Profile(Box<HostStackConfig<f64>>),
    /// With layers: the set-up whose fullest mode is flown.
    Layers(Box<CampaignSetup>),
}

impl ScenarioStack {
    fn of(sc: &Scenario, file: &str) -> Result<Self, PilError> {
        Ok(if sc.layers.is_some() {
            Self::Layers(Box::new(stack_setup(sc, file)?))
        } else {
            let env = sc.environment.build();
            Self::Profile(Box::new(build_stack(sc, &env.planet, file)?))
        })
    }

    fn config(&self) -> HostStackConfig<f64> {
        match self {
            Self::Profile(c) => c.as_ref().clone(),
            Self::Layers(s) => s.stack_of(s.full_mode()),
        }
    }
}

/// The set-up image of the stack `sc` flies, in the chunks the image frames carry (in order),
/// and the limits its command frames must respect. `file` names the scenario in errors.
///
/// # Errors
/// [`PilError::Scenario`] if the scenario's stack does not build, [`PilError::Image`] if it has
/// no image for the firmware.
pub fn scenario_setup(
    sc: &Scenario,
    file: &str,
) -> Result<(Vec<[u8; CHUNK_BYTES]>, FrameLimits), PilError> {
    let config = ScenarioStack::of(sc, file)?.config();
    let image = stack_image(&config)?;
    let list = chunks(&image).map(|(_, _, data)| data).collect();
    Ok((list, stack_limits(&config)))
}

/// A scenario flown in PIL ([`fly_scenario_pil`]).
#[derive(Debug)]
pub struct ScenarioPil {
    /// The run.
    pub result: SimResult,
    /// The link counters and the firmware's summary (stack, ticks, overruns).
    pub stats: PilStats,
    /// Every command frame against the host twin.
    pub twin: TwinCheck,
    /// With guidance layers: the nominal case's record from the firmware's flight (reversals
    /// and re-plans from its command frames; fall-backs and the final estimate are not carried
    /// by the link: 0 and `None`) and the target (`None`: the stored profile alone).
    pub stack: Option<StackOutcome>,
    /// Bytes of the set-up image uploaded.
    pub image_bytes: usize,
}

/// Fly scenario `sc` in PIL: the stack it flies in SIL uploaded to the firmware `cfg.elf`,
/// which computes every command (`f32` on the Cortex-M4F, a fixed-point tick with `f32` layers
/// on the Cortex-M3), beside its host twin. Returns the run, the link counters and the twin
/// check, and the frame record (complete up to a failure, whose exchange is marked).
pub fn fly_scenario_pil(
    sc: &Scenario,
    file: &str,
    cfg: PilConfig,
) -> (Result<ScenarioPil, PilError>, PilRecord) {
    let mut record = PilRecord::default();
    let run = fly(sc, file, cfg, &mut record);
    (run, record)
}

fn fly(
    sc: &Scenario,
    file: &str,
    cfg: PilConfig,
    record: &mut PilRecord,
) -> Result<ScenarioPil, PilError> {
    match ScenarioStack::of(sc, file)? {
        ScenarioStack::Layers(setup) => {
            let mode = setup.full_mode();
            let (case, result) =
                fly_case_pil_run(&setup, None, mode, cfg, sc.output_interval_s, record)?;
            Ok(ScenarioPil {
                result,
                stats: case.stats,
                twin: case.twin,
                stack: Some(StackOutcome {
                    case: case.result,
                    target: setup.target(),
                }),
                image_bytes: case.image_bytes,
            })
        }
        ScenarioStack::Profile(config) => {
            let veh = sc.load_vehicle()?;
            let env = sc.environment.build();
            let (source, image_bytes) = start_stack(&config, cfg, file)?;
            *record = source.pil.record();
            let dynm = Dynamics::from_environment(&env, &veh);
            let (result, source) = sim::simulate(dynm, source, &sc.sim_config(), &mut |_| {})
                .map_err(unwrap_pil_error)?;
            let stats = source.pil.finish()?;
            Ok(ScenarioPil {
                result,
                stats,
                twin: source.check,
                stack: None,
                image_bytes,
            })
        }
    }
}
