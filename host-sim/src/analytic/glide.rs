//! Equilibrium glide trajectory: the glide closed form ([`GlideSolution`]) sampled from the
//! imposed entry state to the end of the glide.

use guidance_core::vinh::{GlideSolution, VinhError};

use super::samples::{Ctx, Planar};
use super::{
    AnalyticError, AnalyticRun, AnalyticVehicle, GlideEnd, LiftSetting, Phase, Placement,
    check_points, evenly_spaced, planet, setting, vinh_atmosphere, vinh_planet,
};
use crate::dynamics::SphericalState;
use crate::env::ExponentialAtmosphere;
use crate::sim::TerminationReason;

/// Equilibrium glide starting at `entry_altitude_m` \[m\] at `placement`, with the entry speed and
/// flight-path angle imposed by the method (eq. 3.78/3.79), constant lift `lift`, to `end`;
/// `points` samples evenly spaced in `u = V^2/(g_E r_E)`.
///
/// # Errors
/// [`AnalyticError::Domain`] with the closed form's typed error (e.g.
/// [`VinhError::GlideNearCircular`], [`VinhError::GlideSpeedOutOfDomain`] when the end is not
/// reached inside the method's domain), [`AnalyticError::Setting`] for a bad end or sample count.
pub fn glide_trajectory(
    vehicle: &AnalyticVehicle,
    lift: &LiftSetting,
    atmosphere: &ExponentialAtmosphere,
    entry_altitude_m: f64,
    placement: &Placement,
    end: GlideEnd,
    points: usize,
) -> Result<AnalyticRun, AnalyticError> {
    check_points(points)?;
    let dom = |error| AnalyticError::Domain {
        phase: "glide",
        error,
    };
    if !entry_altitude_m.is_finite() {
        return Err(setting(
            "entry_altitude_m",
            entry_altitude_m,
            "must be finite",
        ));
    }
    let planet = planet();
    let glide = GlideSolution::new(
        &vinh_planet(&planet),
        &vinh_atmosphere(atmosphere, &planet),
        &vehicle.params(),
        &vehicle.lift_control(lift)?,
        planet.radius_m + entry_altitude_m,
    )
    .map_err(dom)?;
    let e = glide.imposed_entry();
    let u_e = glide.u_entry();
    let u_end = match end {
        GlideEnd::SpeedFraction { fraction } => {
            if !(fraction.is_finite() && fraction > 0.0 && fraction < 1.0) {
                return Err(setting(
                    "end.speed_fraction",
                    fraction,
                    "must be within (0, 1)",
                ));
            }
            glide.u_from_speed(e.speed_m_s * fraction)
        }
        GlideEnd::Altitude { altitude_m } => {
            if !(altitude_m.is_finite() && altitude_m >= 0.0 && altitude_m < entry_altitude_m) {
                return Err(setting(
                    "end.altitude_m",
                    altitude_m,
                    "must be finite, >= 0 and below the entry altitude",
                ));
            }
            u_at_radius(&glide, planet.radius_m + altitude_m, 3).map_err(dom)?
        }
    };
    let rows = (0..points)
        .map(|i| {
            glide
                .point_at_u(evenly_spaced(u_e, u_end, i, points))
                .map(Planar::from)
        })
        .collect::<Result<Vec<_>, _>>()
        .map_err(dom)?;
    let v_end = rows.last().map_or(e.speed_m_s, |p| p.speed);
    let peak_q = Planar::from(glide.peak_heat_flux(v_end).map_err(dom)?);
    let peak_g = Planar::from(glide.peak_g_load(v_end).map_err(dom)?);
    let entry = SphericalState {
        radius_m: e.radius_m,
        longitude_rad: placement.longitude_rad,
        latitude_rad: placement.latitude_rad,
        speed_m_s: e.speed_m_s,
        flight_path_angle_rad: e.flight_path_angle_rad,
        heading_rad: placement.heading_rad,
    };
    let ctx = Ctx {
        vehicle,
        lifts: std::slice::from_ref(lift),
        atmosphere,
        planet,
        placement: *placement,
    };
    let reason = match end {
        GlideEnd::Altitude { .. } => TerminationReason::Altitude,
        GlideEnd::SpeedFraction { .. } => TerminationReason::Mach,
    };
    let result = ctx.assemble(&rows, peak_q, peak_g, reason);
    let deepest = rows.iter().map(|p| p.radius).fold(f64::INFINITY, f64::min) - planet.radius_m;
    Ok(AnalyticRun {
        result,
        phase: Phase::Glide,
        entry,
        deepest_altitude_m: deepest,
        lift: *lift,
        atmosphere: *atmosphere,
    })
}

/// `u` in `(0, u_E)` where the glide's second-order radius is `radius_m`: scan down from `u_E`
/// (`85 decades + 1` geometric steps to `10^-decades u_E`; 3 decades: 256 steps), then bisect
/// (bounded).
pub(super) fn u_at_radius(
    glide: &GlideSolution<f64>,
    radius_m: f64,
    decades: u32,
) -> Result<f64, VinhError> {
    let u_e = glide.u_entry();
    let below = |u: f64| glide.point_at_u(u).map(|p| p.radius_m < radius_m);
    let mut hi = u_e;
    let mut lo = None;
    let steps = 85 * decades + 1;
    for k in 1..=steps {
        let u = u_e * 10f64.powf(-f64::from(decades) * f64::from(k) / f64::from(steps));
        if below(u)? {
            lo = Some(u);
            break;
        }
        hi = u;
    }
    let Some(mut lo) = lo else {
        return Err(VinhError::GlideSpeedOutOfDomain);
    };
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if below(mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}
