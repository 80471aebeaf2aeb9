//! Analytical against numerical: the closed-form trajectory of [`crate::analytic`] against the
//! numerical simulator ([`crate::sim::simulate`]) for the same vehicle, entry state and constant
//! lift, in two environments, over a grid of (entry speed or entry altitude) x (vertical lift
//! coefficient), as in thesis fig. 8.5 (glide: final range-angle error over entry altitude and
//! `C_L`, SRM capsule, simplified environment) and sec. 8.2.1 (skip).
//!
//! * [`Fidelity::Simplified`]: non-rotating sphere, central gravity and the *same* exponential
//!   atmosphere as the closed forms ([`crate::env::Environment::simplified`]): the closed forms'
//!   own assumptions, so the error is that of the approximations alone (thesis sec. 8.1.3).
//! * [`Fidelity::Full`]: rotating Earth, US76, J2 ([`crate::env::Environment::full`]).
//!
//! In both, the numerical vehicle is the analytical one: its drag polar at constant `C_L`
//! ([`AnalyticVehicle::constant_lift_vehicle`]), flown at constant bank through the simulator's
//! constant-attitude source [`FixedAttitude`] (no guidance ticks, no rate limits). The full run
//! therefore measures the environment's effect, not that of an aerodynamic table (for the SRM,
//! whose aerodynamics are trim coefficients, the polar vehicle is the vehicle).
//!
//! Metrics and their errors (analytical minus numerical):
//! * skip (entry -> return to the entry altitude): exit speed [%], exit flight-path angle
//!   [deg], deepest altitude [km], peak heat flux [%], range angle to the exit [%];
//! * glide (imposed entry -> end): range angle [%], final speed [%] (end at an altitude) or final
//!   altitude [km] (end at a speed), peak heat flux [%].
//!
//! The range angle of both is the flown range angle `integral V cos(gamma)/r dt` (eq. 3.15),
//! the quantity the closed forms give. Points where the closed form is out of its domain are
//! kept and marked with its typed error (and the numerical runs are not flown: the glide's entry
//! state comes from the closed form). Numerical runs that do not reach the comparison point (no
//! exit, end not reached) are marked as failed with the reason.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use guidance_core::energy::EnergyNormalizer;
use guidance_core::vinh::VinhError;

use crate::analytic::{
    self, AnalyticError, AnalyticRun, AnalyticVehicle, GlideEnd, LiftSetting, Phase, Placement,
};
use crate::dynamics::{Attitude, Dynamics, SphericalState};
use crate::env::{Environment, ExponentialAtmosphere};
use crate::integrate::Tolerances;
use crate::report::{self, ReportError};
use crate::sim::{
    FixedAttitude, Sample, SampleKind, SimConfig, SimError, SimResult, Termination,
    TerminationReason, simulate,
};

/// Which numerical environment.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Fidelity {
    /// Non-rotating sphere, central gravity, the closed forms' exponential atmosphere.
    Simplified,
    /// Rotating sphere, US76, central + J2 gravity.
    Full,
}

impl Fidelity {
    /// Short name for files and columns.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Fidelity::Simplified => "simplified",
            Fidelity::Full => "full",
        }
    }
}

/// Numerical-run settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NumericalSettings {
    /// RKF4(5) relative tolerance [-].
    pub rtol: f64,
    /// Sample interval [s] (the deepest altitude and speed crossings are read from samples).
    pub output_interval_s: f64,
    /// Time limit of a glide run [s].
    pub max_time_s: f64,
}

impl Default for NumericalSettings {
    /// rtol 1e-8, samples every 1 s, 8000 s limit.
    fn default() -> Self {
        Self {
            rtol: 1e-8,
            output_interval_s: 1.0,
            max_time_s: 8000.0,
        }
    }
}

/// Comparison failures that stop the whole grid (per-point problems are marked instead).
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    /// A setting is out of range.
    #[error("invalid setting `{field}` = {value}: {reason}")]
    Setting {
        /// Setting name with unit.
        field: &'static str,
        /// Its value.
        value: String,
        /// What is required.
        reason: &'static str,
    },
    /// Analytical set-up failure that is not a domain error.
    #[error(transparent)]
    Analytic(#[from] AnalyticError),
    /// Output could not be written.
    #[error(transparent)]
    Report(#[from] ReportError),
    /// The vehicle could not be loaded.
    #[error(transparent)]
    Vehicle(#[from] crate::vehicle::VehicleFileError),
    /// Writing to the console failed.
    #[error("cannot write output: {0}")]
    Io(#[from] std::io::Error),
}

fn setting(field: &'static str, value: impl ToString, reason: &'static str) -> CompareError {
    CompareError::Setting {
        field,
        value: value.to_string(),
        reason,
    }
}

/// Fly `vehicle` at constant lift `lift` from `entry` in the given environment.
///
/// # Errors
/// [`SimError`] for bad settings or an integrator failure.
#[allow(clippy::too_many_arguments)]
pub fn numerical_run(
    vehicle: &AnalyticVehicle,
    lift: &LiftSetting,
    fidelity: Fidelity,
    atmosphere: &ExponentialAtmosphere,
    entry: &SphericalState,
    termination: Termination,
    interface_altitude_m: f64,
    settings: &NumericalSettings,
) -> Result<SimResult, SimError> {
    let env = match fidelity {
        Fidelity::Simplified => Environment::simplified(*atmosphere),
        Fidelity::Full => Environment::full(),
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
    let source = FixedAttitude(Attitude {
        alpha_rad: 0.0,
        sigma_rad: lift.bank_rad,
    });
    let (res, _) = simulate(dynm, source, &cfg, &mut |_, _| {})?;
    Ok(res)
}

/// A compared quantity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Metric {
    /// Column name with unit, e.g. `exit_speed_m_s`.
    pub name: &'static str,
    /// Whether the error is relative (in %) or absolute (in the metric's unit).
    pub relative: bool,
    /// Unit of the absolute error (column suffix).
    pub error_unit: &'static str,
}

const fn rel(name: &'static str) -> Metric {
    Metric {
        name,
        relative: true,
        error_unit: "pct",
    }
}

const fn abs(name: &'static str, error_unit: &'static str) -> Metric {
    Metric {
        name,
        relative: false,
        error_unit,
    }
}

/// Skip metrics, in this order.
pub const SKIP_METRICS: [Metric; 5] = [
    rel("exit_speed_m_s"),
    abs("exit_gamma_deg", "deg"),
    abs("deepest_altitude_km", "km"),
    rel("peak_heat_flux_kw_m2"),
    rel("range_angle_deg"),
];

/// Glide metrics for a glide ending at an altitude, in this order.
pub const GLIDE_METRICS_ALTITUDE_END: [Metric; 3] = [
    rel("range_angle_deg"),
    rel("final_speed_m_s"),
    rel("peak_heat_flux_kw_m2"),
];

/// Glide metrics for a glide ending at a speed, in this order.
pub const GLIDE_METRICS_SPEED_END: [Metric; 3] = [
    rel("range_angle_deg"),
    abs("final_altitude_km", "km"),
    rel("peak_heat_flux_kw_m2"),
];

/// The compared case of one run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Case {
    /// Skip from this entry state (descending) to the return to its altitude.
    Skip {
        /// Planet-relative entry state.
        entry: SphericalState,
    },
    /// Glide from this altitude (entry speed and flight-path angle imposed) to `end`.
    Glide {
        /// Entry altitude [m].
        entry_altitude_m: f64,
        /// Where the trajectory starts on the sphere.
        placement: Placement,
        /// End of the glide.
        end: GlideEnd,
    },
}

impl Case {
    /// The metrics of this case.
    #[must_use]
    pub fn metrics(&self) -> &'static [Metric] {
        match self {
            Case::Skip { .. } => &SKIP_METRICS,
            Case::Glide {
                end: GlideEnd::Altitude { .. },
                ..
            } => &GLIDE_METRICS_ALTITUDE_END,
            Case::Glide {
                end: GlideEnd::SpeedFraction { .. },
                ..
            } => &GLIDE_METRICS_SPEED_END,
        }
    }
}

/// Numerical outcome of one environment.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    /// Metric values (order of [`Case::metrics`]).
    Values(Vec<f64>),
    /// The run failed or did not reach the comparison point.
    Failed(String),
    /// Not flown (out-of-domain closed form, or environment not requested).
    NotRun,
}

impl Outcome {
    /// The values, if any.
    #[must_use]
    pub fn values(&self) -> Option<&[f64]> {
        match self {
            Outcome::Values(v) => Some(v),
            _ => None,
        }
    }

    fn status(&self) -> String {
        match self {
            Outcome::Values(_) => "ok".into(),
            Outcome::Failed(m) => format!("failed: {}", m.replace(',', ";")),
            Outcome::NotRun => "not_run".into(),
        }
    }
}

/// Analytical outcome of one case.
#[derive(Clone, Debug, PartialEq)]
pub enum AnalyticOutcome {
    /// Metric values (order of [`Case::metrics`]).
    Values(Vec<f64>),
    /// The closed form is outside its domain (typed error of guidance-core).
    OutOfDomain(VinhError),
    /// Another analytical failure (bad setting).
    Failed(String),
}

impl AnalyticOutcome {
    /// The values, if any.
    #[must_use]
    pub fn values(&self) -> Option<&[f64]> {
        match self {
            AnalyticOutcome::Values(v) => Some(v),
            _ => None,
        }
    }

    fn status(&self) -> String {
        match self {
            AnalyticOutcome::Values(_) => "ok".into(),
            AnalyticOutcome::OutOfDomain(e) => format!("out_of_domain: {e}"),
            AnalyticOutcome::Failed(m) => format!("failed: {}", m.replace(',', ";")),
        }
    }
}

/// The runs of one compared case (for writing trajectories with [`write_case`]).
#[derive(Clone, Debug)]
pub struct CaseRuns {
    /// The analytical trajectory (`Err`: out of domain or failed).
    pub analytic: Result<AnalyticRun, String>,
    /// Analytical metrics.
    pub analytic_outcome: AnalyticOutcome,
    /// Numerical runs: simplified, full (`None`: not flown).
    pub numerical: [(Fidelity, Option<SimResult>, Outcome); 2],
}

fn analytic_metrics(run: &AnalyticRun, case: &Case) -> Vec<f64> {
    let s = &run.result.summary;
    let last = run.result.samples.last();
    let speed = last.map_or(f64::NAN, |p| p.state.speed_m_s);
    let range_deg = s.flown_range_angle_rad.to_degrees();
    let q_kw = s.peak_heat_flux_w_m2.value / 1e3;
    match case {
        Case::Skip { .. } => vec![
            speed,
            last.map_or(f64::NAN, |p| p.state.flight_path_angle_rad.to_degrees()),
            run.deepest_altitude_m / 1e3,
            q_kw,
            range_deg,
        ],
        Case::Glide {
            end: GlideEnd::Altitude { .. },
            ..
        } => vec![range_deg, speed, q_kw],
        Case::Glide {
            end: GlideEnd::SpeedFraction { .. },
            ..
        } => vec![
            range_deg,
            last.map_or(f64::NAN, |p| p.conditions.altitude_m / 1e3),
            q_kw,
        ],
    }
}

/// Peak heat flux [W/m^2] up to `t_end`: the run's exact peak if it happened by then, else the
/// largest sampled value.
fn peak_heat_until(res: &SimResult, t_end: f64) -> f64 {
    let p = res.summary.peak_heat_flux_w_m2;
    if p.time_s <= t_end {
        p.value
    } else {
        res.samples
            .iter()
            .filter(|s| s.time_s <= t_end)
            .map(|s| s.conditions.heat_flux_w_m2)
            .fold(0.0, f64::max)
    }
}

/// Lowest sampled altitude [m] up to `t_end`, refined by the parabola through it and its
/// neighbours.
fn deepest_altitude_until(samples: &[Sample], t_end: f64) -> f64 {
    let pts: Vec<(f64, f64)> = samples
        .iter()
        .filter(|s| s.time_s <= t_end)
        .map(|s| (s.time_s, s.conditions.altitude_m))
        .collect();
    let Some((i, &(_, h_min))) = pts
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.1.total_cmp(&b.1.1))
    else {
        return f64::NAN;
    };
    if let (Some(&(t0, h0)), Some(&(t1, h1)), Some(&(t2, h2))) = (
        i.checked_sub(1).and_then(|j| pts.get(j)),
        pts.get(i),
        pts.get(i + 1),
    ) {
        // Vertex of the parabola through three points.
        let d01 = (h1 - h0) / (t1 - t0);
        let d12 = (h2 - h1) / (t2 - t1);
        let a = (d12 - d01) / (t2 - t0);
        if a > 0.0 {
            let b = d01 - a * (t0 + t1);
            let tv = (-b / (2.0 * a)).clamp(t0, t2);
            let hv = h0 + d01 * (tv - t0) + a * (tv - t0) * (tv - t1);
            if hv.is_finite() && hv <= h_min {
                return hv;
            }
        }
    }
    h_min
}

/// Linear interpolation of a sample quantity where `key` first falls to `target`.
fn first_fall_to(
    samples: &[Sample],
    key: impl Fn(&Sample) -> f64,
    target: f64,
) -> Option<(f64, &Sample, &Sample)> {
    samples.windows(2).find_map(|w| match w {
        [a, b] if key(a) > target && key(b) <= target => {
            let f = (key(a) - target) / (key(a) - key(b));
            Some((f, a, b))
        }
        _ => None,
    })
}

fn lerp(a: f64, b: f64, f: f64) -> f64 {
    a + f * (b - a)
}

fn numerical_metrics(res: &SimResult, case: &Case, v_end: f64) -> Result<Vec<f64>, String> {
    match case {
        Case::Skip { .. } => {
            let exit = res
                .samples
                .iter()
                .find(|s| s.kind == SampleKind::Exit)
                .ok_or_else(|| {
                    format!(
                        "no atmosphere exit (stopped by {:?} at t = {:.1} s)",
                        res.summary.termination, res.summary.flight_time_s
                    )
                })?;
            Ok(vec![
                exit.state.speed_m_s,
                exit.state.flight_path_angle_rad.to_degrees(),
                deepest_altitude_until(&res.samples, exit.time_s) / 1e3,
                peak_heat_until(res, exit.time_s) / 1e3,
                exit.flown_range_rad.to_degrees(),
            ])
        }
        Case::Glide {
            end: GlideEnd::Altitude { altitude_m },
            ..
        } => {
            let end = res
                .samples
                .last()
                .filter(|_| res.summary.termination == TerminationReason::Altitude);
            let end = end.ok_or_else(|| {
                format!(
                    "did not reach {:.1} km (stopped by {:?} at t = {:.1} s)",
                    altitude_m / 1e3,
                    res.summary.termination,
                    res.summary.flight_time_s
                )
            })?;
            Ok(vec![
                end.flown_range_rad.to_degrees(),
                end.state.speed_m_s,
                res.summary.peak_heat_flux_w_m2.value / 1e3,
            ])
        }
        Case::Glide {
            end: GlideEnd::SpeedFraction { .. },
            ..
        } => {
            let (f, a, b) =
                first_fall_to(&res.samples, |s| s.state.speed_m_s, v_end).ok_or_else(|| {
                    format!(
                        "speed did not fall to {v_end:.1} m/s (stopped by {:?} at t = {:.1} s)",
                        res.summary.termination, res.summary.flight_time_s
                    )
                })?;
            let t = lerp(a.time_s, b.time_s, f);
            Ok(vec![
                lerp(a.flown_range_rad, b.flown_range_rad, f).to_degrees(),
                lerp(a.conditions.altitude_m, b.conditions.altitude_m, f) / 1e3,
                peak_heat_until(res, t) / 1e3,
            ])
        }
    }
}

/// Normalised energy (as the simulator computes it from `entry`) of standstill-height speed
/// `speed_m_s` on the surface: once the energy has fallen to it, the speed is at most
/// `speed_m_s` at any altitude, so a run stopped there has passed that speed.
fn energy_below_speed(entry: &SphericalState, speed_m_s: f64) -> Option<f64> {
    let p = analytic::planet();
    EnergyNormalizer::<f64>::new(p.mu_m3_s2, p.radius_m, entry.radius_m, entry.speed_m_s)
        .and_then(|e| e.normalized(p.radius_m, speed_m_s))
        .ok()
}

/// Run one case: the closed form, then (if it is in domain) the numerical runs requested.
///
/// # Errors
/// [`CompareError::Analytic`] only for set-up failures that are not domain errors (a bad lift
/// setting or sample count); domain errors are returned as [`AnalyticOutcome::OutOfDomain`].
pub fn compare_case(
    vehicle: &AnalyticVehicle,
    lift: &LiftSetting,
    atmosphere: &ExponentialAtmosphere,
    case: &Case,
    fidelities: &[Fidelity],
    settings: &NumericalSettings,
    points: usize,
) -> Result<CaseRuns, CompareError> {
    let run = match case {
        Case::Skip { entry } => analytic::skip_trajectory(vehicle, lift, atmosphere, entry, points),
        Case::Glide {
            entry_altitude_m,
            placement,
            end,
        } => analytic::glide_trajectory(
            vehicle,
            lift,
            atmosphere,
            *entry_altitude_m,
            placement,
            *end,
            points,
        ),
    };
    let not_run = || {
        [
            (Fidelity::Simplified, None, Outcome::NotRun),
            (Fidelity::Full, None, Outcome::NotRun),
        ]
    };
    let run = match run {
        Ok(r) => r,
        Err(AnalyticError::Domain { error, .. }) => {
            return Ok(CaseRuns {
                analytic: Err(error.to_string()),
                analytic_outcome: AnalyticOutcome::OutOfDomain(error),
                numerical: not_run(),
            });
        }
        Err(e @ AnalyticError::Setting { .. }) => return Err(e.into()),
        Err(e) => {
            return Ok(CaseRuns {
                analytic: Err(e.to_string()),
                analytic_outcome: AnalyticOutcome::Failed(e.to_string()),
                numerical: not_run(),
            });
        }
    };
    let a_values = analytic_metrics(&run, case);
    let entry = run.entry;
    let h_entry = entry.radius_m - analytic::planet().radius_m;
    let v_end = match case {
        Case::Glide {
            end: GlideEnd::SpeedFraction { fraction },
            ..
        } => entry.speed_m_s * fraction,
        _ => 0.0,
    };
    let fly = |fidelity: Fidelity| -> (Option<SimResult>, Outcome) {
        let attempt = |termination: Termination| {
            numerical_run(
                vehicle,
                lift,
                fidelity,
                atmosphere,
                &entry,
                termination,
                h_entry,
                settings,
            )
        };
        let res = match case {
            Case::Skip { .. } => {
                // Stop well after the analytical exit time; fly once more, longer, if the
                // numerical exit had not come by then.
                let t_a = run.result.summary.flight_time_s;
                let mut term = Termination {
                    altitude_m: Some(10_000.0),
                    mach: None,
                    normalized_energy: None,
                    max_time_s: 1.5 * t_a + 120.0,
                };
                match attempt(term) {
                    Ok(r)
                        if r.summary.exits == 0
                            && r.summary.termination == TerminationReason::MaxTime =>
                    {
                        term.max_time_s *= 4.0;
                        attempt(term)
                    }
                    other => other,
                }
            }
            Case::Glide {
                end: GlideEnd::Altitude { altitude_m },
                ..
            } => attempt(Termination {
                altitude_m: Some(*altitude_m),
                mach: None,
                normalized_energy: None,
                max_time_s: settings.max_time_s,
            }),
            Case::Glide {
                end: GlideEnd::SpeedFraction { .. },
                ..
            } => attempt(Termination {
                altitude_m: Some(5_000.0),
                mach: None,
                normalized_energy: energy_below_speed(&entry, 0.95 * v_end),
                max_time_s: settings.max_time_s,
            }),
        };
        match res {
            Ok(r) => {
                let outcome = match numerical_metrics(&r, case, v_end) {
                    Ok(v) => Outcome::Values(v),
                    Err(m) => Outcome::Failed(m),
                };
                (Some(r), outcome)
            }
            Err(e) => (None, Outcome::Failed(e.to_string())),
        }
    };
    let mut numerical = not_run();
    for slot in &mut numerical {
        if fidelities.contains(&slot.0) {
            let (r, o) = fly(slot.0);
            slot.1 = r;
            slot.2 = o;
        }
    }
    Ok(CaseRuns {
        analytic: Ok(run),
        analytic_outcome: AnalyticOutcome::Values(a_values),
        numerical,
    })
}

/// Error of `analytic` against `numerical` for `metric`: relative in % or absolute.
#[must_use]
pub fn metric_error(metric: &Metric, analytic: f64, numerical: f64) -> f64 {
    if metric.relative {
        100.0 * (analytic - numerical) / numerical
    } else {
        analytic - numerical
    }
}

/// What the grid varies besides the vertical lift coefficient.
#[derive(Clone, Debug, PartialEq)]
pub enum GridKind {
    /// Skips at a fixed entry altitude and flight-path angle over entry speeds.
    Skip {
        /// Entry altitude [m] (also the exit altitude).
        entry_altitude_m: f64,
        /// Entry flight-path angle [rad] (negative).
        flight_path_angle_rad: f64,
        /// Entry speeds [m/s] (grid x axis).
        entry_speeds_m_s: Vec<f64>,
    },
    /// Glides over entry altitudes (grid x axis); speed and angle are imposed by the method.
    Glide {
        /// Entry altitudes [m].
        entry_altitudes_m: Vec<f64>,
        /// End of each glide.
        end: GlideEnd,
    },
}

/// A comparison grid.
#[derive(Clone, Debug, PartialEq)]
pub struct CompareConfig {
    /// The vehicle (drag polar).
    pub vehicle: AnalyticVehicle,
    /// Grid x axis and case.
    pub kind: GridKind,
    /// Vertical lift coefficients `C_L cos(sigma)` [-] (grid y axis).
    pub cl_vertical: Vec<f64>,
    /// Exponential atmosphere of the closed forms and of the simplified environment.
    pub atmosphere: ExponentialAtmosphere,
    /// Start position and heading.
    pub placement: Placement,
    /// Numerical environments to fly.
    pub fidelities: Vec<Fidelity>,
    /// Numerical settings.
    pub numerical: NumericalSettings,
    /// Samples per analytical trajectory.
    pub points: usize,
}

/// One grid point.
#[derive(Clone, Debug, PartialEq)]
pub struct GridPoint {
    /// Grid x value (entry speed [m/s] or entry altitude [m]).
    pub x: f64,
    /// Vertical lift coefficient [-].
    pub cl_vertical: f64,
    /// Lift setting flown.
    pub lift: LiftSetting,
    /// `lambda = C_L / C_L*` [-].
    pub lambda: f64,
    /// Entry speed [m/s] and flight-path angle [rad] flown (glide: imposed; NaN out of domain).
    pub entry_speed_m_s: f64,
    /// Entry flight-path angle [rad].
    pub entry_gamma_rad: f64,
    /// Closed form.
    pub analytic: AnalyticOutcome,
    /// Simplified environment.
    pub simplified: Outcome,
    /// Full environment.
    pub full: Outcome,
}

impl GridPoint {
    /// Outcome of one environment.
    #[must_use]
    pub fn outcome(&self, fidelity: Fidelity) -> &Outcome {
        match fidelity {
            Fidelity::Simplified => &self.simplified,
            Fidelity::Full => &self.full,
        }
    }
}

/// A computed grid.
#[derive(Clone, Debug, PartialEq)]
pub struct CompareGrid {
    /// Skip or glide.
    pub phase: Phase,
    /// Metrics, in value order.
    pub metrics: Vec<Metric>,
    /// Grid x values (entry speeds [m/s] or altitudes [m]).
    pub xs: Vec<f64>,
    /// Vertical lift coefficients [-].
    pub cl_vertical: Vec<f64>,
    /// Points, x major (`points[ix * cl_vertical.len() + iy]`).
    pub points: Vec<GridPoint>,
    /// Vehicle name.
    pub vehicle: String,
    /// Exponential atmosphere used.
    pub atmosphere: ExponentialAtmosphere,
}

impl CompareGrid {
    /// Error of metric `m` at `point` against `fidelity`, if both sides have values.
    #[must_use]
    pub fn error(&self, point: &GridPoint, m: usize, fidelity: Fidelity) -> Option<f64> {
        let metric = self.metrics.get(m)?;
        let a = *point.analytic.values()?.get(m)?;
        let n = *point.outcome(fidelity).values()?.get(m)?;
        Some(metric_error(metric, a, n))
    }

    /// Largest |error| of metric `m` against `fidelity` over the compared points.
    #[must_use]
    pub fn max_abs_error(&self, m: usize, fidelity: Fidelity) -> Option<f64> {
        self.points
            .iter()
            .filter_map(|p| self.error(p, m, fidelity))
            .map(f64::abs)
            .reduce(f64::max)
    }

    /// Name of the x axis with unit (CSV column and plot label).
    #[must_use]
    pub fn x_name(&self) -> &'static str {
        match self.phase {
            Phase::Skip => "entry_speed_m_s",
            Phase::Glide => "entry_altitude_km",
        }
    }

    fn x_value(&self, x: f64) -> f64 {
        match self.phase {
            Phase::Skip => x,
            Phase::Glide => x / 1e3,
        }
    }
}

fn check_axis(field: &'static str, v: &[f64]) -> Result<(), CompareError> {
    if v.is_empty() {
        return Err(setting(field, "[]", "needs at least one value"));
    }
    if let Some(bad) = v.iter().find(|x| !x.is_finite()) {
        return Err(setting(field, bad, "must be finite"));
    }
    Ok(())
}

/// Run the grid; `progress(done, total)` after each point.
///
/// # Errors
/// [`CompareError::Setting`] for an empty or non-finite axis or a bad lift coefficient,
/// [`CompareError::Analytic`] for set-up failures (domain errors are marked per point).
pub fn run_grid(
    cfg: &CompareConfig,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<CompareGrid, CompareError> {
    run_grid_with(cfg, &mut |done, total, _, _| {
        progress(done, total);
        Ok(())
    })
}

/// Per-point callback of [`run_grid_with`]: `(done, total, point, runs)`.
pub type PointHook<'a> =
    dyn FnMut(usize, usize, &GridPoint, &CaseRuns) -> Result<(), CompareError> + 'a;

/// [`run_grid`] handing every point's runs to `on_point(done, total, point, runs)` (e.g. to
/// write its trajectories with [`write_case`]); an error from it stops the grid.
///
/// # Errors
/// As [`run_grid`], and `on_point`'s errors.
pub fn run_grid_with(
    cfg: &CompareConfig,
    on_point: &mut PointHook<'_>,
) -> Result<CompareGrid, CompareError> {
    check_axis("cl_vertical", &cfg.cl_vertical)?;
    let (phase, xs) = match &cfg.kind {
        GridKind::Skip {
            entry_speeds_m_s, ..
        } => {
            check_axis("entry_speeds_m_s", entry_speeds_m_s)?;
            (Phase::Skip, entry_speeds_m_s.clone())
        }
        GridKind::Glide {
            entry_altitudes_m, ..
        } => {
            check_axis("entry_altitudes_m", entry_altitudes_m)?;
            (Phase::Glide, entry_altitudes_m.clone())
        }
    };
    if !(cfg.numerical.rtol.is_finite() && cfg.numerical.rtol > 0.0) {
        return Err(setting(
            "rtol",
            cfg.numerical.rtol,
            "must be finite and > 0",
        ));
    }
    let total = xs.len() * cfg.cl_vertical.len();
    let mut points = Vec::with_capacity(total);
    let mut metrics = Vec::new();
    for &x in &xs {
        for &clv in &cfg.cl_vertical {
            let lift = cfg.vehicle.lift_for_vertical_cl(clv)?;
            let case = match &cfg.kind {
                GridKind::Skip {
                    entry_altitude_m,
                    flight_path_angle_rad,
                    ..
                } => Case::Skip {
                    entry: SphericalState {
                        radius_m: analytic::planet().radius_m + entry_altitude_m,
                        longitude_rad: cfg.placement.longitude_rad,
                        latitude_rad: cfg.placement.latitude_rad,
                        speed_m_s: x,
                        flight_path_angle_rad: *flight_path_angle_rad,
                        heading_rad: cfg.placement.heading_rad,
                    },
                },
                GridKind::Glide { end, .. } => Case::Glide {
                    entry_altitude_m: x,
                    placement: cfg.placement,
                    end: *end,
                },
            };
            metrics = case.metrics().to_vec();
            let runs = compare_case(
                &cfg.vehicle,
                &lift,
                &cfg.atmosphere,
                &case,
                &cfg.fidelities,
                &cfg.numerical,
                cfg.points,
            )?;
            let (v_e, g_e) = runs.analytic.as_ref().map_or((f64::NAN, f64::NAN), |r| {
                (r.entry.speed_m_s, r.entry.flight_path_angle_rad)
            });
            let point = GridPoint {
                x,
                cl_vertical: clv,
                lift,
                lambda: lift.cl / cfg.vehicle.polar.cl_at_max_lift_to_drag(),
                entry_speed_m_s: v_e,
                entry_gamma_rad: g_e,
                analytic: runs.analytic_outcome.clone(),
                simplified: runs.numerical[0].2.clone(),
                full: runs.numerical[1].2.clone(),
            };
            on_point(points.len() + 1, total, &point, &runs)?;
            points.push(point);
        }
    }
    Ok(CompareGrid {
        phase,
        metrics,
        xs,
        cl_vertical: cfg.cl_vertical.clone(),
        points,
        vehicle: cfg.vehicle.name.clone(),
        atmosphere: cfg.atmosphere,
    })
}

fn cell(v: Option<f64>) -> String {
    match v {
        Some(x) if x.is_finite() => format!("{x:.6}"),
        _ => String::new(),
    }
}

/// The grid as CSV: one row per point; empty cells where a value does not exist.
#[must_use]
pub fn grid_csv(grid: &CompareGrid) -> String {
    let mut s = format!(
        "{},cl_vertical,cl,bank_deg,lambda,flown_entry_speed_m_s,flown_entry_gamma_deg,analytic_status,\
         simplified_status,full_status",
        grid.x_name()
    );
    for m in &grid.metrics {
        let _ = write!(
            s,
            ",{n}_analytic,{n}_simplified,{n}_full,{n}_err_simplified_{u},{n}_err_full_{u}",
            n = m.name,
            u = m.error_unit
        );
    }
    s.push('\n');
    for p in &grid.points {
        let _ = write!(
            s,
            "{},{},{},{:.6},{:.6},{},{},{},{},{}",
            grid.x_value(p.x),
            p.cl_vertical,
            p.lift.cl,
            p.lift.bank_rad.to_degrees(),
            p.lambda,
            cell(Some(p.entry_speed_m_s)),
            cell(Some(p.entry_gamma_rad.to_degrees())),
            p.analytic.status().replace(',', ";"),
            p.simplified.status(),
            p.full.status()
        );
        for (i, _) in grid.metrics.iter().enumerate() {
            let a = p.analytic.values().and_then(|v| v.get(i).copied());
            let ns = p.simplified.values().and_then(|v| v.get(i).copied());
            let nf = p.full.values().and_then(|v| v.get(i).copied());
            let _ = write!(
                s,
                ",{},{},{},{},{}",
                cell(a),
                cell(ns),
                cell(nf),
                cell(grid.error(p, i, Fidelity::Simplified)),
                cell(grid.error(p, i, Fidelity::Full))
            );
        }
        s.push('\n');
    }
    s
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Heat map of the error of metric `m` against `fidelity` over the grid, as a standalone SVG:
/// x = grid x values, y = vertical lift coefficient, colour = |error| (white to red, scaled to
/// the largest |error| of the map), value printed in each cell. Out-of-domain points are grey
/// and marked "out of domain"; failed numerical runs are hatched yellow and marked "n/a".
#[must_use]
pub fn heat_map_svg(grid: &CompareGrid, m: usize, fidelity: Fidelity) -> String {
    let Some(metric) = grid.metrics.get(m) else {
        return String::new();
    };
    let nx = grid.xs.len().max(1);
    let ny = grid.cl_vertical.len().max(1);
    let (cw, ch) = (96.0, 44.0);
    let (ml, mt, mr, mb) = (90.0, 56.0, 150.0, 60.0);
    let pw = cw * nx as f64;
    let ph = ch * ny as f64;
    let (w, h) = (ml + pw + mr, mt + ph + mb);
    let scale = grid.max_abs_error(m, fidelity).unwrap_or(0.0).max(1e-12);
    let unit = if metric.relative {
        "%"
    } else {
        metric.error_unit
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="11">"#
    );
    let _ = writeln!(
        s,
        r##"<defs><pattern id="hatch" width="6" height="6" patternUnits="userSpaceOnUse" patternTransform="rotate(45)"><rect width="6" height="6" fill="#fff3b0"/><line x1="0" y1="0" x2="0" y2="6" stroke="#c8a800" stroke-width="2"/></pattern></defs>"##
    );
    let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
    let title = format!(
        "{} {}: error of {} (analytical - numerical, {} environment) [{unit}]",
        grid.vehicle,
        match grid.phase {
            Phase::Skip => "skip",
            Phase::Glide => "glide",
        },
        metric.name,
        fidelity.name()
    );
    let _ = writeln!(
        s,
        r#"<text x="{:.1}" y="22" text-anchor="middle" font-size="13">{}</text>"#,
        w / 2.0,
        xml_escape(&title)
    );
    for (iy, clv) in grid.cl_vertical.iter().enumerate() {
        // Highest C_L at the top.
        let y = mt + ph - ch * (iy as f64 + 1.0);
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="end">{clv}</text>"#,
            ml - 6.0,
            y + ch / 2.0 + 4.0
        );
    }
    for (ix, x) in grid.xs.iter().enumerate() {
        let xp = ml + cw * ix as f64;
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
            xp + cw / 2.0,
            mt + ph + 16.0,
            grid.x_value(*x)
        );
    }
    for (k, p) in grid.points.iter().enumerate() {
        let (ix, iy) = (k / ny, k % ny);
        let x = ml + cw * ix as f64;
        let y = mt + ph - ch * (iy as f64 + 1.0);
        let (fill, label) = match (&p.analytic, grid.error(p, m, fidelity)) {
            (AnalyticOutcome::OutOfDomain(_), _) | (AnalyticOutcome::Failed(_), _) => {
                ("#bdbdbd".to_string(), "out of domain".to_string())
            }
            (_, Some(e)) => {
                let f = (e.abs() / scale).clamp(0.0, 1.0);
                let gb = (255.0 * (1.0 - 0.85 * f)).round() as u8;
                (format!("rgb(255,{gb},{gb})"), format!("{e:+.2}"))
            }
            (_, None) => ("url(#hatch)".to_string(), "n/a".to_string()),
        };
        let _ = writeln!(
            s,
            r##"<rect x="{x:.1}" y="{y:.1}" width="{cw}" height="{ch}" fill="{fill}" stroke="#555"/><text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"##,
            x + cw / 2.0,
            y + ch / 2.0 + 4.0,
            xml_escape(&label)
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
        ml + pw / 2.0,
        h - 18.0,
        match grid.phase {
            Phase::Skip => "entry speed [m/s]",
            Phase::Glide => "entry altitude [km]",
        }
    );
    let _ = writeln!(
        s,
        r#"<text x="18" y="{:.1}" text-anchor="middle" transform="rotate(-90 18 {:.1})">vertical lift coefficient C_L cos(sigma) [-]</text>"#,
        mt + ph / 2.0,
        mt + ph / 2.0
    );
    // Legend.
    let lx = ml + pw + 20.0;
    let steps = 5;
    for i in 0..=steps {
        let f = f64::from(i) / f64::from(steps);
        let gb = (255.0 * (1.0 - 0.85 * f)).round() as u8;
        let ly = mt + 18.0 * f64::from(i);
        let _ = writeln!(
            s,
            r##"<rect x="{lx:.1}" y="{ly:.1}" width="16" height="16" fill="rgb(255,{gb},{gb})" stroke="#555"/><text x="{:.1}" y="{:.1}">|err| {:.3} {unit}</text>"##,
            lx + 22.0,
            ly + 12.0,
            f * scale
        );
    }
    let ly = mt + 18.0 * f64::from(steps + 1) + 8.0;
    let _ = writeln!(
        s,
        r##"<rect x="{lx:.1}" y="{ly:.1}" width="16" height="16" fill="#bdbdbd" stroke="#555"/><text x="{:.1}" y="{:.1}">out of domain</text>"##,
        lx + 22.0,
        ly + 12.0
    );
    let _ = writeln!(
        s,
        r##"<rect x="{lx:.1}" y="{:.1}" width="16" height="16" fill="url(#hatch)" stroke="#555"/><text x="{:.1}" y="{:.1}">numerical n/a</text>"##,
        ly + 22.0,
        lx + 22.0,
        ly + 34.0
    );
    s.push_str("</svg>\n");
    s
}

/// Write `grid.csv` and one heat map per metric and environment flown
/// (`<metric>_err_<environment>.svg`) into `dir` (created if needed), atomically.
///
/// # Errors
/// [`ReportError`] naming the path.
pub fn write_grid(
    dir: &Path,
    grid: &CompareGrid,
    fidelities: &[Fidelity],
) -> Result<Vec<PathBuf>, ReportError> {
    std::fs::create_dir_all(dir).map_err(|source| ReportError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut written = Vec::new();
    let csv = dir.join("grid.csv");
    report::write_atomic(&csv, grid_csv(grid).as_bytes())?;
    written.push(csv);
    for (m, metric) in grid.metrics.iter().enumerate() {
        for &f in fidelities {
            let p = dir.join(format!("{}_err_{}.svg", metric.name, f.name()));
            report::write_atomic(&p, heat_map_svg(grid, m, f).as_bytes())?;
            written.push(p);
        }
    }
    Ok(written)
}

/// Write the trajectories of one case as run directories `analytic/`, `simplified/`, `full/`
/// (whichever exist) under `dir`, each with the numerical simulator's report files.
///
/// # Errors
/// [`ReportError`] naming the path.
pub fn write_case(
    dir: &Path,
    runs: &CaseRuns,
    vehicle: &AnalyticVehicle,
    scenario: &str,
) -> Result<Vec<PathBuf>, ReportError> {
    let lim = vehicle.limits;
    let mut written = Vec::new();
    let planet_r = analytic::planet().radius_m;
    if let Ok(a) = &runs.analytic {
        let summary = report::summary_report(
            &a.result,
            scenario,
            &vehicle.name,
            &analytic::environment_label(&a.atmosphere),
            planet_r,
        );
        written.extend(report::write_run(
            &dir.join("analytic"),
            &a.result,
            &summary,
            lim.heat_flux_w_m2,
            lim.g_load,
        )?);
    }
    for (f, res, _) in &runs.numerical {
        if let Some(res) = res {
            let env = match f {
                Fidelity::Simplified => "numerical: non-rotating sphere, central gravity, \
                                         exponential atmosphere of the closed forms"
                    .to_string(),
                Fidelity::Full => "numerical: rotating sphere, US76, J2".to_string(),
            };
            let summary = report::summary_report(res, scenario, &vehicle.name, &env, planet_r);
            written.extend(report::write_run(
                &dir.join(f.name()),
                res,
                &summary,
                lim.heat_flux_w_m2,
                lim.g_load,
            )?);
        }
    }
    Ok(written)
}

/// Which closed form the `compare` subcommand maps.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum CliPhase {
    /// Skip from a fixed entry altitude and flight-path angle over entry speeds.
    Skip,
    /// Glide over entry altitudes (entry speed and angle imposed by the method).
    Glide,
}

/// Arguments of `host-sim compare` (SI units or the unit in the name).
#[derive(Debug, Clone, clap::Args)]
pub struct CompareCliArgs {
    /// Vehicle: a built-in name (srm, horus-2b) or a vehicle TOML file.
    #[arg(long, default_value = "srm")]
    pub vehicle: String,
    /// Closed form to compare.
    #[arg(long, value_enum, default_value = "glide")]
    pub phase: CliPhase,
    /// Glide: entry altitudes [km] (grid x axis), comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "70,80,90,100,110")]
    pub altitudes_km: Vec<f64>,
    /// Skip: entry speeds [m/s] (grid x axis), comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "7000,7500,8000,9000,10000"
    )]
    pub speeds_m_s: Vec<f64>,
    /// Skip: entry altitude [km] (also the exit altitude).
    #[arg(long, default_value_t = 100.0)]
    pub altitude_km: f64,
    /// Skip: entry flight-path angle [deg] (negative: descending).
    #[arg(long, default_value_t = -3.0, allow_negative_numbers = true)]
    pub gamma_deg: f64,
    /// Vertical lift coefficients C_L cos(sigma) [-] (grid y axis), comma-separated. Bank-only
    /// vehicles fly their trim C_L banked; others fly C_L = this value, lift up. Default: five
    /// values from 0.3 to 1 times the maximum (trim C_L, or C_L at maximum L/D).
    #[arg(long, value_delimiter = ',')]
    pub cl_vertical: Vec<f64>,
    /// Glide: end at this altitude [km] instead of a speed.
    #[arg(long, conflicts_with = "end_speed_fraction")]
    pub end_altitude_km: Option<f64>,
    /// Glide: end at this fraction of the imposed entry speed [-].
    #[arg(long, default_value_t = 0.5)]
    pub end_speed_fraction: f64,
    /// Mach number at which a tabulated drag polar is taken [-].
    #[arg(long, default_value_t = crate::analytic::DEFAULT_POLAR_MACH)]
    pub polar_mach: f64,
    /// Two altitudes [km] through which the exponential atmosphere is fitted to US76.
    #[arg(long, value_delimiter = ',', num_args = 1, default_value = "50,100")]
    pub fit_altitudes_km: Vec<f64>,
    /// Numerical environments to fly, comma-separated.
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "simplified,full"
    )]
    pub environments: Vec<Fidelity>,
    /// Start latitude [deg].
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub latitude_deg: f64,
    /// Start longitude [deg].
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub longitude_deg: f64,
    /// Start heading [deg], clockwise from north.
    #[arg(long, default_value_t = 90.0, allow_negative_numbers = true)]
    pub heading_deg: f64,
    /// Integrator relative tolerance [-].
    #[arg(long, default_value_t = 1e-8)]
    pub rtol: f64,
    /// Numerical sample interval [s].
    #[arg(long, default_value_t = 1.0)]
    pub output_interval_s: f64,
    /// Samples per analytical trajectory.
    #[arg(long, default_value_t = crate::analytic::DEFAULT_POINTS)]
    pub points: usize,
    /// Also write every point's trajectories (analytic/, simplified/, full/ run directories
    /// under point_<i>/).
    #[arg(long)]
    pub trajectories: bool,
    /// Output directory (default: runs/compare-<vehicle>-<phase>/).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

fn finite_arg(field: &'static str, v: f64) -> Result<f64, CompareError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(setting(field, v, "must be finite"))
    }
}

/// The grid of a `compare` command line.
///
/// # Errors
/// [`CompareError`] naming the argument and value (or the vehicle file, field and value).
pub fn config_from_args(a: &CompareCliArgs) -> Result<CompareConfig, CompareError> {
    let veh = crate::vehicle::load(&a.vehicle)?;
    let vehicle = AnalyticVehicle::from_vehicle(&veh, a.polar_mach)?;
    let [h1, h2] = a.fit_altitudes_km[..] else {
        return Err(setting(
            "--fit-altitudes-km",
            format!("{:?}", a.fit_altitudes_km),
            "needs exactly two altitudes",
        ));
    };
    let atmosphere = analytic::fit_us76(
        finite_arg("--fit-altitudes-km", h1)? * 1e3,
        finite_arg("--fit-altitudes-km", h2)? * 1e3,
    )?;
    let cl_max = vehicle
        .trim_cl
        .unwrap_or_else(|| vehicle.polar.cl_at_max_lift_to_drag());
    let cl_vertical = if a.cl_vertical.is_empty() {
        [0.3, 0.475, 0.65, 0.825, 1.0]
            .iter()
            .map(|f| (f * cl_max * 1e4).round() / 1e4)
            .collect()
    } else {
        a.cl_vertical.clone()
    };
    let km = |v: &[f64]| v.iter().map(|x| x * 1e3).collect::<Vec<_>>();
    let kind = match a.phase {
        CliPhase::Skip => GridKind::Skip {
            entry_altitude_m: finite_arg("--altitude-km", a.altitude_km)? * 1e3,
            flight_path_angle_rad: finite_arg("--gamma-deg", a.gamma_deg)?.to_radians(),
            entry_speeds_m_s: a.speeds_m_s.clone(),
        },
        CliPhase::Glide => GridKind::Glide {
            entry_altitudes_m: km(&a.altitudes_km),
            end: match a.end_altitude_km {
                Some(h) => GlideEnd::Altitude {
                    altitude_m: finite_arg("--end-altitude-km", h)? * 1e3,
                },
                None => GlideEnd::SpeedFraction {
                    fraction: a.end_speed_fraction,
                },
            },
        },
    };
    if !(a.output_interval_s.is_finite() && a.output_interval_s > 0.0) {
        return Err(setting(
            "--output-interval-s",
            a.output_interval_s,
            "must be finite and > 0",
        ));
    }
    if a.environments.is_empty() {
        return Err(setting("--environments", "[]", "needs at least one"));
    }
    Ok(CompareConfig {
        vehicle,
        kind,
        cl_vertical,
        atmosphere,
        placement: Placement {
            latitude_rad: finite_arg("--latitude-deg", a.latitude_deg)?.to_radians(),
            longitude_rad: finite_arg("--longitude-deg", a.longitude_deg)?.to_radians(),
            heading_rad: finite_arg("--heading-deg", a.heading_deg)?.to_radians(),
        },
        fidelities: a.environments.clone(),
        numerical: NumericalSettings {
            rtol: a.rtol,
            output_interval_s: a.output_interval_s,
            ..NumericalSettings::default()
        },
        points: a.points,
    })
}

/// `host-sim compare`: run the grid, write `grid.csv`, the heat maps and (with
/// `--trajectories`) every point's run directories, and print a summary to `out`. Returns the
/// files written.
///
/// # Errors
/// [`CompareError`] naming the argument and value, or the path that could not be written.
pub fn run_cli(
    a: &CompareCliArgs,
    out: &mut dyn std::io::Write,
) -> Result<Vec<PathBuf>, CompareError> {
    let cfg = config_from_args(a)?;
    let phase = match a.phase {
        CliPhase::Skip => "skip",
        CliPhase::Glide => "glide",
    };
    let dir = a.out.clone().unwrap_or_else(|| {
        PathBuf::from("runs").join(format!(
            "compare-{}-{phase}",
            cfg.vehicle.name.replace([' ', '/', '\\'], "_")
        ))
    });
    let mut files = Vec::new();
    let scenario = format!("compare {} {phase}", cfg.vehicle.name);
    let grid = run_grid_with(&cfg, &mut |done, total, _, runs| {
        if a.trajectories {
            let sub = dir.join(format!("point_{}", done - 1));
            files.extend(write_case(&sub, runs, &cfg.vehicle, &scenario)?);
        }
        eprint!("\rcompare: {done}/{total} points");
        Ok(())
    })?;
    eprintln!();
    files.extend(write_grid(&dir, &grid, &cfg.fidelities)?);
    writeln!(
        out,
        "{} {phase}: {} points, {} out of the closed form's domain; exponential atmosphere \
         H_s = {:.1} m",
        grid.vehicle,
        grid.points.len(),
        grid.points
            .iter()
            .filter(|p| matches!(p.analytic, AnalyticOutcome::OutOfDomain(_)))
            .count(),
        grid.atmosphere.scale_height_m()
    )?;
    for (i, m) in grid.metrics.iter().enumerate() {
        for &f in &cfg.fidelities {
            let compared = grid
                .points
                .iter()
                .filter(|p| grid.error(p, i, f).is_some())
                .count();
            match grid.max_abs_error(i, f) {
                Some(e) => writeln!(
                    out,
                    "  {:<24} {:<10} max |error| {e:.3} {} over {compared} points",
                    m.name,
                    f.name(),
                    if m.relative { "%" } else { m.error_unit }
                )?,
                None => writeln!(out, "  {:<24} {:<10} no point compared", m.name, f.name())?,
            }
        }
    }
    writeln!(out, "wrote {}", dir.display())?;
    Ok(files)
}
