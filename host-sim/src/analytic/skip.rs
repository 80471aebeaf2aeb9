//! Skip trajectory: the skip closed form ([`SkipSolution`]) sampled from entry to exit.

use guidance_core::vinh::{EntryState, NonDim, SkipSolution};

use super::samples::{Ctx, Planar};
use super::{
    AnalyticError, AnalyticRun, AnalyticVehicle, LiftSetting, Phase, Placement, check_points,
    evenly_spaced, planet, vinh_atmosphere, vinh_planet,
};
use crate::dynamics::SphericalState;
use crate::env::ExponentialAtmosphere;
use crate::sim::{SampleKind, TerminationReason};

/// Skip from `entry` (planet-relative; descending) to the return to the entry radius, with
/// constant lift `lift`, in the exponential atmosphere `atmosphere`; `points` samples evenly
/// spaced in range angle.
///
/// # Errors
/// [`AnalyticError::Domain`] with the closed form's typed error (e.g.
/// [`VinhError::NoAtmosphericExit`] when the vehicle is captured, [`VinhError::NotDescending`]),
/// [`AnalyticError::Setting`] for a bad sample count.
///
/// [`VinhError::NoAtmosphericExit`]: guidance_core::vinh::VinhError::NoAtmosphericExit
/// [`VinhError::NotDescending`]: guidance_core::vinh::VinhError::NotDescending
pub fn skip_trajectory(
    vehicle: &AnalyticVehicle,
    lift: &LiftSetting,
    atmosphere: &ExponentialAtmosphere,
    entry: &SphericalState,
    points: usize,
) -> Result<AnalyticRun, AnalyticError> {
    check_points(points)?;
    let dom = |error| AnalyticError::Domain {
        phase: "skip",
        error,
    };
    let planet = planet();
    let nd = NonDim::new(
        &vinh_planet(&planet),
        &vinh_atmosphere(atmosphere, &planet),
        &vehicle.params(),
        &vehicle.lift_control(lift)?,
        &EntryState {
            radius_m: entry.radius_m,
            speed_m_s: entry.speed_m_s,
            flight_path_angle_rad: entry.flight_path_angle_rad,
        },
    )
    .map_err(dom)?;
    let skip = SkipSolution::new(&nd).map_err(dom)?;
    let tau_exit = skip.tau_exit();
    let rows = (0..points)
        .map(|i| {
            skip.point_at_tau(evenly_spaced(0.0, tau_exit, i, points))
                .map(Planar::from)
        })
        .collect::<Result<Vec<_>, _>>()
        .map_err(dom)?;
    let peak_q = Planar::from(skip.peak_heat_flux().map_err(dom)?);
    let peak_g = Planar::from(skip.peak_g_load().map_err(dom)?);
    let deepest = skip.deepest_point().map_err(dom)?;
    let ctx = Ctx {
        vehicle,
        lifts: std::slice::from_ref(lift),
        atmosphere,
        planet,
        placement: Placement::of(entry),
    };
    let mut result = ctx.assemble(&rows, peak_q, peak_g, TerminationReason::Altitude);
    let t_exit = result.summary.flight_time_s;
    result.summary.exits = 1;
    result.summary.interface_crossings_s = vec![(t_exit, SampleKind::Exit)];
    Ok(AnalyticRun {
        result,
        phase: Phase::Skip,
        entry: *entry,
        deepest_altitude_m: deepest.radius_m - planet.radius_m,
        lift: *lift,
        atmosphere: *atmosphere,
    })
}
