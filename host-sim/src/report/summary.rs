//! The summary JSON document of a run, in report units.

use serde::Serialize;

use crate::sim::{Peak, SampleKind, SimResult, TerminationReason};

/// A peak with its time, in report units.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PeakOut {
    /// Value (unit in the field name of the owner).
    pub value: f64,
    /// Time of the peak \[s\].
    pub time_s: f64,
}

impl PeakOut {
    fn scaled(p: Peak, k: f64) -> Self {
        Self {
            value: p.value * k,
            time_s: p.time_s,
        }
    }
}

/// Constraint violations (eq. 4.9-4.11) as written to summary.json: `guidance-core`'s
/// [`Violations`](guidance_core::monitor::Violations), field for field.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ViolationsOut {
    /// Heat flux p_q.
    pub heat_flux: f64,
    /// g-load p_g.
    pub g_load: f64,
    /// g-load rate p_gdot.
    pub g_load_rate: f64,
}

impl From<guidance_core::monitor::Violations<f64>> for ViolationsOut {
    fn from(v: guidance_core::monitor::Violations<f64>) -> Self {
        Self {
            heat_flux: v.heat_flux,
            g_load: v.g_load,
            g_load_rate: v.g_load_rate,
        }
    }
}

/// Final state in report units.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct FinalState {
    /// Altitude \[km\].
    pub altitude_km: f64,
    /// Longitude \[deg\].
    pub longitude_deg: f64,
    /// Latitude \[deg\].
    pub latitude_deg: f64,
    /// Planet-relative speed [m/s].
    pub speed_m_s: f64,
    /// Flight-path angle \[deg\].
    pub gamma_deg: f64,
    /// Heading \[deg\].
    pub heading_deg: f64,
    /// Mach number [-].
    pub mach: f64,
    /// Normalised energy [-].
    pub normalized_energy: f64,
}

/// The summary JSON document.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SummaryReport {
    /// Scenario name.
    pub scenario: String,
    /// Vehicle name.
    pub vehicle: String,
    /// Environment description (atmosphere, gravity, rotating or not).
    pub environment: String,
    /// Why the run stopped.
    pub termination: TerminationReason,
    /// Flight time \[s\].
    pub flight_time_s: f64,
    /// Great-circle range angle entry -> end \[deg\].
    pub range_angle_deg: f64,
    /// Great-circle range over the sphere \[km\].
    pub range_km: f64,
    /// Integral of V cos(gamma)/r (eq. 3.15) \[deg\].
    pub flown_range_angle_deg: f64,
    /// Heat load [MJ/m^2].
    pub heat_load_mj_m2: f64,
    /// Peak heat flux [kW/m^2].
    pub peak_heat_flux_kw_m2: PeakOut,
    /// Peak g-load [-].
    pub peak_g_load: PeakOut,
    /// Peak g-load rate [1/s].
    pub peak_g_load_rate_per_s: PeakOut,
    /// Atmosphere exits above the interface.
    pub exits: u32,
    /// Skips (exit followed by re-entry).
    pub skips: u32,
    /// Interface crossing times \[s\] and kinds.
    pub interface_crossings: Vec<(f64, SampleKind)>,
    /// Constraint violations, eq. 4.9-4.11.
    pub violations: ViolationsOut,
    /// Final state.
    pub final_state: FinalState,
    /// RHS evaluations.
    pub rhs_evals: u64,
    /// Accepted steps.
    pub accepted_steps: u64,
    /// Rejected steps.
    pub rejected_steps: u64,
    /// Guidance ticks.
    pub guidance_ticks: u64,
    /// Processor-in-the-loop counters: only in the summary of a PIL run (absent otherwise, so
    /// a software-in-the-loop summary is unchanged).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pil: Option<PilOut>,
    /// The guidance stack's outcome against its target: only for a scenario with guidance
    /// layers (absent otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target: Option<TargetOut>,
}

/// A guidance stack's outcome against its target (`[guidance.target]`), as a campaign records
/// its nominal case.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TargetOut {
    /// The campaign mode flown (the scenario's fullest, e.g. `replan-estimation`).
    pub mode: String,
    /// Target latitude \[deg\] (geocentric).
    pub latitude_deg: f64,
    /// Target longitude \[deg\].
    pub longitude_deg: f64,
    /// True if the flight ended at the terminal interface (not the floor or the time limit).
    pub reached_interface: bool,
    /// Great-circle distance from the end to the target \[km\].
    pub miss_km: f64,
    /// Downrange error along the entry great circle (positive: long) \[km\].
    pub downrange_error_km: f64,
    /// Crossrange error (positive: right of the entry great circle) \[km\].
    pub crossrange_error_km: f64,
    /// Bank reversals.
    pub reversals: u32,
    /// Re-plans run.
    pub replans: u32,
    /// Re-plans that fell back to the table in use.
    pub fall_backs: u32,
}

/// The processor-in-the-loop part of a PIL run's summary.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PilOut {
    /// Nav/command round trips with the firmware.
    pub frames: u64,
    /// Deepest stack of the firmware's whole run, as it measured it \[bytes\] (`null`: not
    /// reported).
    pub firmware_stack_bytes: Option<u64>,
    /// Link faults injected by the host and their outcomes (`null`: no fault injection).
    pub link_faults: Option<LinkFaultsOut>,
}

/// Seeded link faults of a PIL run (`simulate --pil-fault-rate`) and their outcomes.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct LinkFaultsOut {
    /// Probability of a drop per transmission [-].
    pub p_drop: f64,
    /// Probability of a corruption per transmission [-].
    pub p_corrupt: f64,
    /// Probability of a delay past the tick per frame [-].
    pub p_delay: f64,
    /// Seed of the fault injector.
    pub seed: u64,
    /// Transmissions dropped.
    pub dropped: u64,
    /// Transmissions corrupted.
    pub corrupted: u64,
    /// Frames delayed past their tick.
    pub delayed: u64,
    /// Retransmissions.
    pub retries: u64,
    /// Ticks flown on the held command.
    pub missed_ticks: u64,
    /// Faults the firmware counted (rejected frames), as it reported them (`null`: not
    /// reported).
    pub firmware_counted: Option<u64>,
}

/// Build the summary document.
#[must_use]
pub fn summary_report(
    res: &SimResult,
    scenario: &str,
    vehicle: &str,
    environment: &str,
    planet_radius_m: f64,
) -> SummaryReport {
    let s = &res.summary;
    let last = res.samples.last();
    let final_state = last.map_or(
        FinalState {
            altitude_km: f64::NAN,
            longitude_deg: f64::NAN,
            latitude_deg: f64::NAN,
            speed_m_s: f64::NAN,
            gamma_deg: f64::NAN,
            heading_deg: f64::NAN,
            mach: f64::NAN,
            normalized_energy: f64::NAN,
        },
        |p| FinalState {
            altitude_km: p.conditions.altitude_m / 1e3,
            longitude_deg: p.state.longitude_rad.to_degrees(),
            latitude_deg: p.state.latitude_rad.to_degrees(),
            speed_m_s: p.state.speed_m_s,
            gamma_deg: p.state.flight_path_angle_rad.to_degrees(),
            heading_deg: p.state.heading_rad.to_degrees(),
            mach: p.conditions.mach,
            normalized_energy: p.normalized_energy,
        },
    );
    SummaryReport {
        scenario: scenario.into(),
        vehicle: vehicle.into(),
        environment: environment.into(),
        termination: s.termination,
        flight_time_s: s.flight_time_s,
        range_angle_deg: s.range_angle_rad.to_degrees(),
        range_km: s.range_angle_rad * planet_radius_m / 1e3,
        flown_range_angle_deg: s.flown_range_angle_rad.to_degrees(),
        heat_load_mj_m2: s.heat_load_j_m2 / 1e6,
        peak_heat_flux_kw_m2: PeakOut::scaled(s.peak_heat_flux_w_m2, 1e-3),
        peak_g_load: PeakOut::scaled(s.peak_g_load, 1.0),
        peak_g_load_rate_per_s: PeakOut::scaled(s.peak_g_load_rate_per_s, 1.0),
        exits: s.exits,
        skips: s.skips,
        interface_crossings: s.interface_crossings_s.clone(),
        violations: s.violations.into(),
        final_state,
        rhs_evals: s.rhs_evals,
        accepted_steps: s.accepted_steps,
        rejected_steps: s.rejected_steps,
        guidance_ticks: s.ticks,
        pil: None,
        target: None,
    }
}
