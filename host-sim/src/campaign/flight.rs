//! One closed-loop flight of a campaign: a guidance mode over one dispersed case, and what it
//! gives at the terminal interface.

use guidance_core::energy::EnergyNormalizer;
use guidance_core::geo::along_cross_track;
use guidance_core::guidance::HostGuidance;
use guidance_core::replan::{ReplanCase, ReplanReport};
use guidance_core::stack::FlightStack;
use serde::{Deserialize, Serialize};

use super::draw::CaseDraw;
use super::imu::{ImuModel, ImuSource};
use super::models::{DispersedAero, DispersedAtmosphere};
use super::setup::CampaignSetup;
use super::{CampaignError, Mode};
use crate::dynamics::Dynamics;
use crate::env::Environment;
use crate::scenario::Scenario;
use crate::scenario::guidance_layers::CampaignGuidance;
use crate::sim::{
    GuidanceSource, ReportContext, SimConfig, SimResult, TerminationReason, simulate,
};
use crate::stack_loop::StackSource;
use crate::vehicle::Vehicle;

/// What one flight gives (SI units, radians).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CaseResult {
    /// Case index (`None`-like `u32::MAX` for the nominal flight).
    pub index: u32,
    /// Guidance mode.
    pub mode: Mode,
    /// The dispersed values (absent for the nominal flight).
    pub draw: Option<CaseDraw>,
    /// Why the flight ended (`"NormalizedEnergy"`: at the terminal interface).
    pub termination: String,
    /// True if the flight ended at the terminal interface (not the floor or the time limit).
    pub reached_interface: bool,
    /// Great-circle distance from the end to the target \[m\].
    pub miss_m: f64,
    /// Downrange error along the entry great circle (positive: long) \[m\].
    pub downrange_error_m: f64,
    /// Crossrange error (positive: right of the entry great circle) \[m\].
    pub crossrange_error_m: f64,
    /// Peak heat flux \[W/m^2\].
    pub peak_heat_flux_w_m2: f64,
    /// Peak g-load \[-\].
    pub peak_g_load: f64,
    /// Peak g-load rate \[1/s\].
    pub peak_g_load_rate_per_s: f64,
    /// Peak / limit of heat flux, g-load, g-load rate \[-\].
    pub limit_ratios: [f64; 3],
    /// Bank reversals.
    pub reversals: u32,
    /// Re-plans run.
    pub replans: u32,
    /// Re-plans that fell back to the table in use.
    pub fall_backs: u32,
    /// Onboard estimate at the end (L/D scale, drag scale) \[-\]
    /// ([`Mode::ReplanEstimation`] only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub estimated_scales: Option<[f64; 2]>,
    /// The campaign's guidance settings when they are not the defaults (a stored case is
    /// reused only by a campaign with the same settings).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub guidance: Option<CampaignGuidance>,
    /// Flight time \[s\].
    pub flight_time_s: f64,
    /// Final altitude \[m\].
    pub final_altitude_m: f64,
    /// Final speed \[m/s\].
    pub final_speed_m_s: f64,
    /// Final flight-path angle \[rad\].
    pub final_flight_path_angle_rad: f64,
    /// Final heading \[rad\].
    pub final_heading_rad: f64,
    /// Final latitude \[rad\].
    pub final_latitude_rad: f64,
    /// Final longitude \[rad\].
    pub final_longitude_rad: f64,
}

/// Fly `sc` nominally with `guidance` (no dispersion, no lateral logic).
///
/// # Errors
/// [`CampaignError::Sim`].
pub fn fly_plain(
    sc: &Scenario,
    env: &Environment,
    vehicle: &Vehicle,
    guidance: HostGuidance<f64>,
) -> Result<SimResult, CampaignError> {
    let dynm = Dynamics::from_environment(env, vehicle);
    let (r, _) = simulate(
        dynm,
        GuidanceSource::new(guidance),
        &sc.sim_config(),
        &mut |_| {},
    )
    .map_err(|source| CampaignError::Sim {
        index: None,
        source,
    })?;
    Ok(r)
}

/// Fly one case (`None`: the nominal world) in `mode`.
///
/// # Errors
/// [`CampaignError`] if the vehicle cannot be loaded, guidance cannot be built or the
/// simulation fails.
pub fn fly_case(
    setup: &CampaignSetup,
    draw: Option<&CaseDraw>,
    mode: Mode,
) -> Result<CaseResult, CampaignError> {
    fly_case_logged(setup, draw, mode).map(|(r, _)| r)
}

/// The re-plans of a flight: each report with the context of its tick (empty for the modes
/// without re-planning).
pub type ReplanLog = Vec<(ReplanReport<f64>, ReportContext)>;

/// What a campaign flight's guidance counted, read at the end of the flight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CaseCounts {
    /// Bank reversals.
    pub reversals: u32,
    /// Re-plans run.
    pub replans: u32,
    /// Re-plans that fell back to the table in use.
    pub fall_backs: u32,
    /// Onboard estimate at the end (L/D scale, drag scale) \[-\].
    pub estimated_scales: Option<[f64; 2]>,
}

/// The guidance of a campaign flight: the host's stack ([`StackSource`]) or, in PIL, the
/// firmware flying the same stack (`crate::pil::fly_case_pil`).
pub trait CaseSource: crate::sim::AttitudeSource {
    /// The counts at the end of the flight.
    fn counts(&self) -> CaseCounts;
}

impl CaseSource for StackSource {
    fn counts(&self) -> CaseCounts {
        let fall_backs = self
            .reports
            .iter()
            .filter(|r| matches!(r.case, ReplanCase::FallBack(_)))
            .count();
        CaseCounts {
            reversals: u32::from(self.reversals()),
            replans: self.stack.replan_counts().map_or(0, |c| c.replans),
            fall_backs: u32::try_from(fall_backs).unwrap_or(u32::MAX),
            estimated_scales: self.stack.aero_scales().map(|a| [a.lift_to_drag, a.drag]),
        }
    }
}

/// [`fly_case`], also returning the flight's re-plans ([`ReplanLog`]).
///
/// # Errors
/// As [`fly_case`].
pub fn fly_case_logged(
    setup: &CampaignSetup,
    draw: Option<&CaseDraw>,
    mode: Mode,
) -> Result<(CaseResult, ReplanLog), CampaignError> {
    fly_case_run(setup, draw, mode, 0.0, &mut |_| {}).map(|f| (f.case, f.log))
}

/// [`fly_case_logged`], also returning the flight's trajectory (a sample at every guidance
/// tick and event: the campaign's flights record at ticks). The record is the one
/// [`fly_case`] gives, bit for bit.
///
/// # Errors
/// As [`fly_case`].
pub fn fly_case_traced(
    setup: &CampaignSetup,
    draw: Option<&CaseDraw>,
    mode: Mode,
) -> Result<(CaseResult, ReplanLog, SimResult), CampaignError> {
    fly_case_run(setup, draw, mode, 0.0, &mut |_| {}).map(|f| (f.case, f.log, f.result))
}

/// A flown case with its trajectory ([`fly_case_run`]).
#[derive(Debug)]
pub struct CaseFlight {
    /// The case's record (as the campaign writes it).
    pub case: CaseResult,
    /// Its re-plans.
    pub log: ReplanLog,
    /// The run (samples every `output_interval_s`, or at the guidance ticks for 0).
    pub result: SimResult,
}

/// The one flight of a campaign case (`None`: the nominal world) in `mode` by the host's
/// stack, also returning the run: [`fly_case`] and [`fly_case_logged`] fly it with
/// `output_interval_s = 0` (samples at the guidance ticks) and no progress; `host-sim
/// simulate` of a scenario with guidance layers flies the nominal case in the best mode with
/// the scenario's output interval and a progress bar (`crate::scenario::fly`).
///
/// # Errors
/// As [`fly_case`].
pub fn fly_case_run(
    setup: &CampaignSetup,
    draw: Option<&CaseDraw>,
    mode: Mode,
    output_interval_s: f64,
    progress: &mut dyn FnMut(crate::sim::Progress),
) -> Result<CaseFlight, CampaignError> {
    let (case, s, result) =
        fly_case_with(setup, draw, mode, output_interval_s, progress, |config| {
            let stack = FlightStack::new(config).map_err(|source| CampaignError::Stack {
                file: setup.file.clone(),
                source,
            })?;
            Ok(StackSource::new(stack))
        })?;
    let log: ReplanLog = s
        .reports
        .iter()
        .copied()
        .zip(s.contexts.iter().copied())
        .collect();
    Ok(CaseFlight { case, log, result })
}

/// One case (`None`: the nominal world) in `mode`, flown by the guidance `source` makes of
/// the mode's stack ([`CampaignSetup::stack_of`]) behind the case's IMU: the world, the
/// terminal interface and the record exactly as [`fly_case`]. The run ends at the terminal
/// interface (the campaign's E-hat), at the altitude floor, or at the scenario's time limit
/// or the ground. Returns the record, the source after the flight and the run (samples
/// every `output_interval_s`, or at the guidance ticks for 0).
///
/// # Errors
/// As [`fly_case`], and `source`'s error.
pub fn fly_case_with<A: CaseSource>(
    setup: &CampaignSetup,
    draw: Option<&CaseDraw>,
    mode: Mode,
    output_interval_s: f64,
    progress: &mut dyn FnMut(crate::sim::Progress),
    source: impl FnOnce(&guidance_core::stack::HostStackConfig<f64>) -> Result<A, CampaignError>,
) -> Result<(CaseResult, A, SimResult), CampaignError>
where
    A::Error: std::error::Error + Send + Sync + 'static,
{
    let sc = &setup.scenario;
    let scen = |source| CampaignError::Scenario {
        file: setup.file.clone(),
        source: Box::new(source),
    };
    let mut vehicle = sc.load_vehicle().map_err(scen)?;
    let env = sc.environment.build();
    let zero = CaseDraw {
        index: u32::MAX,
        altitude_m: 0.0,
        speed_m_s: 0.0,
        flight_path_angle_rad: 0.0,
        heading_rad: 0.0,
        latitude_rad: 0.0,
        longitude_rad: 0.0,
        density_bias: 0.0,
        density_wave: 0.0,
        density_phase_rad: 0.0,
        density_wavelength_m: 20e3,
        lift: 0.0,
        drag: 0.0,
        mass: 0.0,
        imu_lift_bias_m_s2: 0.0,
        imu_drag_bias_m_s2: 0.0,
        imu_lift_scale: 0.0,
        imu_drag_scale: 0.0,
        imu_noise_m_s2: 0.0,
        imu_noise_seed: 0,
    };
    let d = draw.copied().unwrap_or(zero);
    vehicle.mass_kg *= 1.0 + d.mass;
    let nominal_aero = std::mem::replace(
        &mut vehicle.aero,
        Box::new(crate::vehicle::TrimAerodynamics {
            trim: crate::vehicle::AeroCoefficients { cl: 0.0, cd: 0.0 },
        }),
    );
    vehicle.aero = Box::new(DispersedAero {
        nominal: nominal_aero,
        lift_scale: 1.0 + d.lift,
        drag_scale: 1.0 + d.drag,
    });
    let atmosphere = DispersedAtmosphere {
        nominal: env.atmosphere.as_ref(),
        bias: d.density_bias,
        wave: d.density_wave,
        wavelength_m: d.density_wavelength_m,
        phase_rad: d.density_phase_rad,
    };
    let dynm = Dynamics {
        planet: env.planet,
        atmosphere: &atmosphere,
        gravity: env.gravity.as_ref(),
        vehicle: &vehicle,
        heat_flux: env.heat_flux,
    };
    let mut entry = sc.entry;
    entry.radius_m += d.altitude_m;
    entry.speed_m_s += d.speed_m_s;
    entry.flight_path_angle_rad += d.flight_path_angle_rad;
    entry.heading_rad += d.heading_rad;
    entry.latitude_rad += d.latitude_rad;
    entry.longitude_rad += d.longitude_rad;
    let mut cfg: SimConfig = sc.sim_config();
    cfg.entry = entry;
    cfg.output_interval_s = output_interval_s;
    // Terminal interface: the nominal end's energy, as E-hat of this case's entry.
    let case_energy = EnergyNormalizer::<f64>::new(
        env.planet.mu_m3_s2,
        env.planet.radius_m,
        entry.radius_m,
        entry.speed_m_s,
    )
    .map_err(|source| CampaignError::Guidance {
        file: setup.file.clone(),
        field: "entry (dispersed)",
        source,
    })?;
    let v_f = setup.interface_speed_m_s;
    let r_f = env.planet.mu_m3_s2 / (0.5 * v_f * v_f - setup.interface_energy_j_kg);
    let e_hat_f = case_energy
        .normalized(r_f, v_f)
        .map_err(|source| CampaignError::Guidance {
            file: setup.file.clone(),
            field: "terminal interface",
            source,
        })?;
    cfg.termination.normalized_energy = Some(e_hat_f);
    cfg.termination.altitude_m = Some(setup.floor_altitude_m);
    cfg.termination.mach = None;
    let source = ImuSource::new(source(&setup.stack_of(mode))?, ImuModel::of(&d));
    let (result, src) =
        simulate(dynm, source, &cfg, progress).map_err(|source| CampaignError::Sim {
            index: Some(d.index),
            source,
        })?;
    let CaseCounts {
        reversals,
        replans,
        fall_backs,
        estimated_scales,
    } = src.source.counts();
    let end = result
        .samples
        .last()
        .map(|s| s.state)
        .ok_or(CampaignError::EmptyFlight)?;
    let radius = env.planet.radius_m;
    let e0 = (sc.entry.latitude_rad, sc.entry.longitude_rad);
    let target = setup.target();
    let t = (target.latitude_rad, target.longitude_rad);
    let (at, xt) =
        along_cross_track(e0, t, (end.latitude_rad, end.longitude_rad)).unwrap_or((0.0, 0.0));
    let s = &result.summary;
    let lim = vehicle.limits;
    let case = CaseResult {
        index: d.index,
        mode,
        draw: draw.copied(),
        termination: format!("{:?}", s.termination),
        reached_interface: s.termination == TerminationReason::NormalizedEnergy,
        miss_m: setup.distance_to_target_m(end.latitude_rad, end.longitude_rad, radius),
        downrange_error_m: (at - setup.target_downrange_rad) * radius,
        crossrange_error_m: xt * radius,
        peak_heat_flux_w_m2: s.peak_heat_flux_w_m2.value,
        peak_g_load: s.peak_g_load.value,
        peak_g_load_rate_per_s: s.peak_g_load_rate_per_s.value,
        limit_ratios: [
            s.peak_heat_flux_w_m2.value / lim.heat_flux_w_m2,
            s.peak_g_load.value / lim.g_load,
            s.peak_g_load_rate_per_s.value / lim.g_load_rate_per_s,
        ],
        reversals,
        replans,
        fall_backs,
        estimated_scales,
        guidance: setup.guidance_key(),
        flight_time_s: s.flight_time_s,
        final_altitude_m: end.radius_m - radius,
        final_speed_m_s: end.speed_m_s,
        final_flight_path_angle_rad: end.flight_path_angle_rad,
        final_heading_rad: end.heading_rad,
        final_latitude_rad: end.latitude_rad,
        final_longitude_rad: end.longitude_rad,
    };
    Ok((case, src.source, result))
}
