//! Flying a scenario: load its vehicle, build its environment and guidance, run the closed
//! loop, and (for [`simulate_scenario`]) write the run directory.

use std::path::{Path, PathBuf};

use guidance_core::replan::TargetPoint;
use guidance_core::stack::{FlightStack, StackBuildError};

use super::{Scenario, ScenarioError, build_stack};
use crate::campaign::flight::{CaseResult, fly_case_run};
use crate::campaign::{CampaignError, CampaignSetup};
use crate::dynamics::Dynamics;
use crate::env::Environment;
use crate::report;
use crate::sim;
use crate::stack_loop::StackSource;
use crate::vehicle::Vehicle;

/// Result of [`simulate_scenario`].
#[derive(Debug)]
pub struct RunOutput {
    /// The run.
    pub result: sim::SimResult,
    /// The summary written to summary.json.
    pub summary: report::SummaryReport,
    /// Files written.
    pub files: Vec<PathBuf>,
    /// What the user should know: likely unit mistakes in the inputs, then each vehicle limit
    /// the flight exceeded ([`super::Warning`]).
    pub warnings: Vec<super::Warning>,
    /// The stack's outcome ([`Flight::stack`]).
    pub stack: Option<StackOutcome>,
}

/// A flown scenario with the models it used.
pub struct Flight {
    /// The run.
    pub result: sim::SimResult,
    /// The vehicle flown.
    pub vehicle: Vehicle,
    /// The environment flown in.
    pub environment: Environment,
    /// With guidance layers: the flight as a campaign records its nominal case (mode, miss
    /// against the target, reversals, re-plans) and the target (`None`: the stored profile
    /// alone, no target).
    pub stack: Option<StackOutcome>,
}

/// The outcome of a scenario's guidance stack flown by [`fly`]: the campaign's record of the
/// nominal case in the campaign's fullest mode (`CampaignSetup::full_mode`) and the target it
/// aimed at.
#[derive(Clone, Debug, PartialEq)]
pub struct StackOutcome {
    /// The nominal case's record, as a campaign of this scenario writes it.
    pub case: CaseResult,
    /// The target at the terminal interface (geocentric latitude, longitude \[rad\]).
    pub target: TargetPoint<f64>,
}

impl Flight {
    /// The summary of this flight of `sc` under the name `run_name` (what summary.json holds,
    /// PIL counters aside): the run's, and with guidance layers the outcome against the target
    /// (`target`).
    #[must_use]
    pub fn summary(&self, sc: &Scenario, run_name: &str) -> report::SummaryReport {
        let mut summary = report::summary_report(
            &self.result,
            run_name,
            &self.vehicle.name,
            &sc.environment.describe(),
            self.environment.planet.radius_m,
        );
        summary.target = self.stack.as_ref().map(target_out);
        summary
    }

    /// The warnings of this flight of `sc`: likely unit mistakes in its inputs, then each
    /// vehicle limit the flight exceeded.
    #[must_use]
    pub fn warnings(&self, sc: &Scenario) -> Vec<super::Warning> {
        let mut w = super::input_warnings(sc);
        w.extend(super::flight_warnings(&self.result, &self.vehicle.limits));
        w
    }
}

impl std::fmt::Debug for Flight {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Flight")
            .field("summary", &self.result.summary)
            .field("vehicle", &self.vehicle.name)
            .finish_non_exhaustive()
    }
}

/// Fly a scenario closed-loop with `guidance-core`'s flight stack (no files written), through
/// `guidance_core::stack::FlightStack::tick`:
///
/// * with guidance layers (`[guidance.lateral]`, `[guidance.replanning]`, ...: [`Scenario::layers`])
///   the stack a campaign of the scenario builds ([`CampaignSetup::new`], the one builder of
///   the layers), flown as the campaign flies its nominal case in the fullest mode
///   ([`CampaignSetup::full_mode`], [`fly_case_run`]): aimed at `[guidance.target]`, ended at
///   the terminal interface (or the campaign's altitude floor), with the scenario's output
///   interval; [`Flight::stack`] holds the record (miss against the target included);
/// * without, the stored profile as written ([`build_stack`]), ended by `[termination]`.
///
/// `crate::pil::fly_scenario_pil` flies the same stack on the firmware.
///
/// # Errors
/// [`ScenarioError`] for vehicle, guidance or simulation failures.
///
/// ```
/// use host_sim::scenario::{Scenario, fly};
/// use host_sim::sim::TerminationReason;
/// // The HORUS-2B reference mission's stored profile alone (full environment), ended at
/// // 25 km altitude.
/// let flight = fly(&Scenario::horus_2b_stored(), "(built-in)", &mut |_| {})?;
/// let s = &flight.result.summary;
/// assert_eq!(s.termination, TerminationReason::Altitude);
/// assert!(s.range_angle_rad.to_degrees() > 10.0);
/// assert!(flight.stack.is_none());
/// // The SRM glide with its stack (re-planning, reversals, estimator) to its target.
/// let flight = fly(&Scenario::srm_glide(), "(built-in)", &mut |_| {})?;
/// assert_eq!(flight.result.summary.termination, TerminationReason::NormalizedEnergy);
/// assert!(flight.stack.as_ref().is_some_and(|s| s.case.miss_m < 10e3));
/// # Ok::<(), host_sim::scenario::ScenarioError>(())
/// ```
pub fn fly(
    sc: &Scenario,
    file: &str,
    progress: &mut dyn FnMut(sim::Progress),
) -> Result<Flight, ScenarioError> {
    if sc.layers.is_some() {
        return fly_layers(sc, file, progress);
    }
    let vehicle = sc.load_vehicle()?;
    let environment = sc.environment.build();
    let dynm = Dynamics::from_environment(&environment, &vehicle);
    let config = build_stack(sc, &environment.planet, file)?;
    let stack = FlightStack::new(&config).map_err(|e| stack_error(e, file))?;
    let source = StackSource::new(stack);
    let result = sim::simulate(dynm, source, &sc.sim_config(), progress)?.0;
    Ok(Flight {
        result,
        vehicle,
        environment,
        stack: None,
    })
}

/// The campaign set-up of a scenario with guidance layers (`CampaignSetup::new`, the one
/// builder of the layers) whose fullest mode (`CampaignSetup::full_mode`) flies every layer
/// written: what [`fly`] flies in SIL and `crate::pil::fly_scenario_pil` uploads to the
/// firmware, as the nominal case in that mode.
///
/// # Errors
/// The set-up's errors as scenario errors; [`ScenarioError::Field`] naming
/// `guidance.lateral` when the layers make no campaign mode (re-planning flies with bank
/// reversals): every layer written flies, or the flight is refused (never silently less).
pub fn stack_setup(sc: &Scenario, file: &str) -> Result<CampaignSetup, ScenarioError> {
    let setup = CampaignSetup::new(sc, file, None).map_err(|e| campaign_error(e, file))?;
    if setup.stack_of(setup.full_mode()).layers() != setup.stack.layers() {
        return Err(ScenarioError::Field {
            file: file.to_string(),
            field: "guidance.lateral".into(),
            value: "(missing)".into(),
            reason: format!(
                "the layers {:?} make no campaign mode (re-planning flies with bank reversals): \
                 add [guidance.lateral]",
                setup.stack.layers()
            ),
        });
    }
    Ok(setup)
}

/// [`fly`] of a scenario with guidance layers: the campaign's nominal case in its fullest mode.
fn fly_layers(
    sc: &Scenario,
    file: &str,
    progress: &mut dyn FnMut(sim::Progress),
) -> Result<Flight, ScenarioError> {
    let setup = stack_setup(sc, file)?;
    let mode = setup.full_mode();
    let run = fly_case_run(&setup, None, mode, sc.output_interval_s, progress)
        .map_err(|e| campaign_error(e, file))?;
    Ok(Flight {
        result: run.result,
        vehicle: sc.load_vehicle()?,
        environment: sc.environment.build(),
        stack: Some(StackOutcome {
            case: run.case,
            target: setup.target(),
        }),
    })
}

/// The summary's part of a stack's outcome (km, deg).
fn target_out(s: &StackOutcome) -> report::TargetOut {
    let c = &s.case;
    report::TargetOut {
        mode: c.mode.name().to_string(),
        latitude_deg: s.target.latitude_rad.to_degrees(),
        longitude_deg: s.target.longitude_rad.to_degrees(),
        reached_interface: c.reached_interface,
        miss_km: c.miss_m / 1e3,
        downrange_error_km: c.downrange_error_m / 1e3,
        crossrange_error_km: c.crossrange_error_m / 1e3,
        reversals: c.reversals,
        replans: c.replans,
        fall_backs: c.fall_backs,
    }
}

/// A campaign error as a scenario error (a scenario error inside it as itself).
fn campaign_error(e: CampaignError, file: &str) -> ScenarioError {
    match e {
        CampaignError::Scenario { source, .. } => *source,
        CampaignError::Sim {
            source: sim::SimError::Interrupted { time_s },
            ..
        } => ScenarioError::Sim(sim::SimError::Interrupted { time_s }),
        other => ScenarioError::Stack {
            file: file.to_string(),
            source: Box::new(other),
        },
    }
}

/// The scenario error of a stored-profile stack ([`build_stack`]) the core refuses, as a
/// `[guidance]` error (it has no other layer).
fn stack_error(e: StackBuildError, file: &str) -> ScenarioError {
    let source = match e {
        StackBuildError::Rejected { source, .. } => source,
        StackBuildError::NeedsReplan(_) | StackBuildError::NeedsTarget(_) => {
            guidance_core::GuidanceError::InvalidConfig
        }
    };
    ScenarioError::Guidance {
        file: file.to_string(),
        field: "interpolation",
        source,
    }
}

/// Fly a scenario and write its run directory.
///
/// # Errors
/// [`ScenarioError`] for vehicle, guidance, simulation or output failures.
pub fn simulate_scenario(
    sc: &Scenario,
    file: &str,
    out_dir: &Path,
    progress: &mut dyn FnMut(sim::Progress),
) -> Result<RunOutput, ScenarioError> {
    let flight = fly(sc, file, progress)?;
    write_flight(sc, &sc.name, flight, None, out_dir)
}

/// Write the run directory of a flown scenario (`run_name` labels the summary; `pil`, for a
/// processor-in-the-loop run, goes into summary.json).
///
/// # Errors
/// [`ScenarioError::Report`] if the files cannot be written.
pub fn write_flight(
    sc: &Scenario,
    run_name: &str,
    flight: Flight,
    pil: Option<report::PilOut>,
    out_dir: &Path,
) -> Result<RunOutput, ScenarioError> {
    let mut summary = flight.summary(sc, run_name);
    summary.pil = pil;
    let Flight {
        result,
        vehicle: veh,
        stack,
        ..
    } = flight;
    // The rate limits drawn are the guidance's (what its rate limiter flies), the target the
    // stack's if it aims at one.
    let limits = report::PlotLimits {
        alpha_rate_rad_s: sc.guidance.alpha_rate_rad_s,
        sigma_rate_rad_s: sc.guidance.sigma_rate_rad_s,
        target: stack
            .as_ref()
            .map(|s| (s.target.latitude_rad, s.target.longitude_rad)),
        ..report::PlotLimits::of_vehicle(&veh.limits)
    };
    let files = report::write_run(out_dir, &result, &summary, &limits)?;
    let mut warnings = super::input_warnings(sc);
    warnings.extend(super::flight_warnings(&result, &veh.limits));
    Ok(RunOutput {
        result,
        summary,
        files,
        warnings,
        stack,
    })
}
