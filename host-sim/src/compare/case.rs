//! One compared case: the closed form, then the numerical runs of the requested environments,
//! with their outcomes.

use guidance_core::vinh::VinhError;

use super::metrics::{Case, analytic_metrics, numerical_metrics};
use super::numerical::energy_below_speed;
use super::{CompareError, NumericalSettings, Preset, numerical_run};
use crate::analytic::{self, AnalyticError, AnalyticRun, AnalyticVehicle, GlideEnd, LiftSetting};
use crate::env::ExponentialAtmosphere;
use crate::sim::{SimResult, Termination, TerminationReason};

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

    pub(super) fn status(&self) -> String {
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

    pub(super) fn status(&self) -> String {
        match self {
            AnalyticOutcome::Values(_) => "ok".into(),
            AnalyticOutcome::OutOfDomain(e) => format!("out_of_domain: {e}"),
            AnalyticOutcome::Failed(m) => format!("failed: {}", m.replace(',', ";")),
        }
    }
}

/// The runs of one compared case (for writing trajectories with [`write_case`]).
///
/// [`write_case`]: super::write_case
#[derive(Clone, Debug)]
pub struct CaseRuns {
    /// The analytical trajectory (`Err`: out of domain or failed).
    pub analytic: Result<AnalyticRun, String>,
    /// Analytical metrics.
    pub analytic_outcome: AnalyticOutcome,
    /// Numerical runs: simplified, full (`None`: not flown).
    pub numerical: [(Preset, Option<SimResult>, Outcome); 2],
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
    fidelities: &[Preset],
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
            (Preset::Simplified, None, Outcome::NotRun),
            (Preset::Full, None, Outcome::NotRun),
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
    let fly = |fidelity: Preset| -> (Option<SimResult>, Outcome) {
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
