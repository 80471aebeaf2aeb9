//! Flying a scenario: load its vehicle, build its environment and guidance, run the closed
//! loop, and (for [`simulate_scenario`]) write the run directory.

use std::path::{Path, PathBuf};

use guidance_core::replan::RangeTarget;
use guidance_core::stack::{FlightStack, Layer, StackBuildError};

use super::{Scenario, ScenarioError, build_stack};
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
}

/// A flown scenario with the models it used.
pub struct Flight {
    /// The run.
    pub result: sim::SimResult,
    /// The vehicle flown.
    pub vehicle: Vehicle,
    /// The environment flown in.
    pub environment: Environment,
}

impl Flight {
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

/// Fly a scenario closed-loop with `guidance-core`'s flight stack (no files written): the
/// scenario's stack ([`build_stack`]) through `guidance_core::stack::FlightStack::tick`.
///
/// # Errors
/// [`ScenarioError`] for vehicle, guidance or simulation failures.
///
/// ```
/// use host_sim::scenario::{Scenario, fly};
/// use host_sim::sim::TerminationReason;
/// // The HORUS-2B reference mission (full environment), ended at 25 km altitude.
/// let flight = fly(&Scenario::default(), "(built-in)", &mut |_| {})?;
/// let s = &flight.result.summary;
/// assert_eq!(s.termination, TerminationReason::Altitude);
/// assert!(s.range_angle_rad.to_degrees() > 10.0);
/// assert!(s.peak_heat_flux_w_m2.value > 0.0);
/// # Ok::<(), host_sim::scenario::ScenarioError>(())
/// ```
pub fn fly(
    sc: &Scenario,
    file: &str,
    progress: &mut dyn FnMut(sim::Progress),
) -> Result<Flight, ScenarioError> {
    let vehicle = sc.load_vehicle()?;
    let environment = sc.environment.build();
    let dynm = Dynamics::from_environment(&environment, &vehicle);
    let config = build_stack(sc, &environment, &vehicle, file)?;
    let stack = FlightStack::new(&config).map_err(|e| stack_error(e, file))?;
    let source = StackSource::new(stack);
    let result = sim::simulate(dynm, source, &sc.sim_config(), progress)?.0;
    Ok(Flight {
        result,
        vehicle,
        environment,
    })
}

/// The scenario error of a stack the core refuses: the profile's as a `[guidance]` error, any
/// other layer's as a `[replanning]` error.
fn stack_error(e: StackBuildError, file: &str) -> ScenarioError {
    match e {
        StackBuildError::Rejected {
            layer: Layer::Profile,
            source,
        } => ScenarioError::Guidance {
            file: file.to_string(),
            field: "interpolation",
            source,
        },
        StackBuildError::Rejected { source, .. } => ScenarioError::Replanning {
            file: file.to_string(),
            source,
        },
        StackBuildError::NeedsReplan(_) | StackBuildError::NeedsTarget(_) => {
            ScenarioError::Replanning {
                file: file.to_string(),
                source: guidance_core::GuidanceError::InvalidConfig,
            }
        }
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
    let Flight {
        result,
        vehicle: veh,
        environment: env,
    } = flight;
    let mut summary = report::summary_report(
        &result,
        run_name,
        &veh.name,
        &sc.environment.describe(),
        env.planet.radius_m,
    );
    summary.pil = pil;
    // The rate limits drawn are the guidance's (what its rate limiter flies), the target the
    // re-planner's point if it aims at one.
    let limits = report::PlotLimits {
        alpha_rate_rad_s: sc.guidance.alpha_rate_rad_s,
        sigma_rate_rad_s: sc.guidance.sigma_rate_rad_s,
        target: sc.replanning.as_ref().and_then(|r| match r.target {
            RangeTarget::Point(p) => Some((p.latitude_rad, p.longitude_rad)),
            RangeTarget::FlownRangeAngle { .. } => None,
        }),
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
    })
}
