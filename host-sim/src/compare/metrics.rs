//! The compared cases ([`Case`]) and quantities ([`Metric`]), their values read from an
//! analytical trajectory and from a numerical run, and the error measure between them
//! ([`metric_error`]).

use crate::analytic::{AnalyticRun, GlideEnd, Placement};
use crate::dynamics::SphericalState;
use crate::sim::{Sample, SampleKind, SimResult, TerminationReason};

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
        /// Entry altitude \[m\].
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

/// Error of `analytic` against `numerical` for `metric`: relative in % or absolute.
#[must_use]
pub fn metric_error(metric: &Metric, analytic: f64, numerical: f64) -> f64 {
    if metric.relative {
        100.0 * (analytic - numerical) / numerical
    } else {
        analytic - numerical
    }
}

pub(super) fn analytic_metrics(run: &AnalyticRun, case: &Case) -> Vec<f64> {
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

/// Why and when a run stopped, for the failure messages: `(stopped by Altitude at t = 12.3 s)`.
fn stopped_by(res: &SimResult) -> String {
    format!(
        "(stopped by {:?} at t = {:.1} s)",
        res.summary.termination, res.summary.flight_time_s
    )
}

fn lerp(a: f64, b: f64, f: f64) -> f64 {
    a + f * (b - a)
}

pub(super) fn numerical_metrics(
    res: &SimResult,
    case: &Case,
    v_end: f64,
) -> Result<Vec<f64>, String> {
    match case {
        Case::Skip { .. } => {
            let exit = res
                .samples
                .iter()
                .find(|s| s.kind == SampleKind::Exit)
                .ok_or_else(|| format!("no atmosphere exit {}", stopped_by(res)))?;
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
                    "did not reach {:.1} km {}",
                    altitude_m / 1e3,
                    stopped_by(res)
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
                    format!("speed did not fall to {v_end:.1} m/s {}", stopped_by(res))
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
