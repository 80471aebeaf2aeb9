//! The comparison grid: (entry speed or entry altitude) x vertical lift coefficient, its
//! definition ([`CompareConfig`]), running ([`run_grid`]) and result ([`CompareGrid`]).

use super::{
    AnalyticOutcome, Case, CaseRuns, CompareError, Metric, NumericalSettings, Outcome, Preset,
    compare_case, metric_error, setting,
};
use crate::analytic::{self, AnalyticVehicle, GlideEnd, LiftSetting, Phase, Placement};
use crate::dynamics::SphericalState;
use crate::env::ExponentialAtmosphere;

/// What the grid varies besides the vertical lift coefficient.
#[derive(Clone, Debug, PartialEq)]
pub enum GridKind {
    /// Skips at a fixed entry altitude and flight-path angle over entry speeds.
    Skip {
        /// Entry altitude \[m\] (also the exit altitude).
        entry_altitude_m: f64,
        /// Entry flight-path angle \[rad\] (negative).
        flight_path_angle_rad: f64,
        /// Entry speeds [m/s] (grid x axis).
        entry_speeds_m_s: Vec<f64>,
    },
    /// Glides over entry altitudes (grid x axis); speed and angle are imposed by the method.
    Glide {
        /// Entry altitudes \[m\].
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
    pub fidelities: Vec<Preset>,
    /// Numerical settings.
    pub numerical: NumericalSettings,
    /// Samples per analytical trajectory.
    pub points: usize,
}

/// One grid point.
#[derive(Clone, Debug, PartialEq)]
pub struct GridPoint {
    /// Grid x value (entry speed [m/s] or entry altitude \[m\]).
    pub x: f64,
    /// Vertical lift coefficient [-].
    pub cl_vertical: f64,
    /// Lift setting flown.
    pub lift: LiftSetting,
    /// `lambda = C_L / C_L*` [-].
    pub lambda: f64,
    /// Entry speed [m/s] and flight-path angle \[rad\] flown (glide: imposed; NaN out of domain).
    pub entry_speed_m_s: f64,
    /// Entry flight-path angle \[rad\].
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
    pub fn outcome(&self, fidelity: Preset) -> &Outcome {
        match fidelity {
            Preset::Simplified => &self.simplified,
            Preset::Full => &self.full,
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
    /// Grid x values (entry speeds [m/s] or altitudes \[m\]).
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
    pub fn error(&self, point: &GridPoint, m: usize, fidelity: Preset) -> Option<f64> {
        let metric = self.metrics.get(m)?;
        let a = *point.analytic.values()?.get(m)?;
        let n = *point.outcome(fidelity).values()?.get(m)?;
        Some(metric_error(metric, a, n))
    }

    /// Largest |error| of metric `m` against `fidelity` over the compared points.
    #[must_use]
    pub fn max_abs_error(&self, m: usize, fidelity: Preset) -> Option<f64> {
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

    pub(super) fn x_value(&self, x: f64) -> f64 {
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
///
/// [`write_case`]: super::write_case
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
