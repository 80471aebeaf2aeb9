//! The navigation interface (`guidance_core::navconv`): hostile Cartesian states (zero vectors,
//! positions on the spin axis, vertical and zero planet-relative velocity, NaN, infinities,
//! extremes), inertial and planet-fixed, in `f64` and `f32`. Never a panic; an accepted state
//! gives finite outputs in their documented ranges.

use guidance_core::nav::NavState;
use guidance_core::navconv::{CartesianNav, InertialFrame, from_inertial, from_planet_fixed};
use nalgebra::Vector3;
use rand::{Rng, RngExt};

use crate::hostile::value;

const OMEGA: f64 = 7.292_115e-5;

pub fn run<R: Rng>(rng: &mut R) -> Result<(), String> {
    let p = 0.05;
    let mut pos = Vector3::new(
        value(rng, -1e7, 1e7, p),
        value(rng, -1e7, 1e7, p),
        value(rng, -1e7, 1e7, p),
    );
    let mut vel = Vector3::new(
        value(rng, -1e4, 1e4, p),
        value(rng, -1e4, 1e4, p),
        value(rng, -1e4, 1e4, p),
    );
    match rng.random_range(0..8) {
        0 => pos = Vector3::zeros(),
        // On or next to the spin axis (a pole).
        1 => {
            pos.x = value(rng, -1e-6, 1e-6, 0.3);
            pos.y = 0.0;
        }
        // Vertical flight: velocity along the position.
        2 => vel = pos * value(rng, -1e-3, 1e-3, 0.1),
        // Zero planet-relative velocity (inertial: v = omega x r).
        3 => vel = Vector3::new(-OMEGA * pos.y, OMEGA * pos.x, 0.0),
        4 => vel = Vector3::zeros(),
        _ => {}
    }
    let time_s = value(rng, 0.0, 1e4, p);
    let frame = InertialFrame {
        rotation_rate_rad_s: if rng.random_bool(0.9) {
            OMEGA
        } else {
            value(rng, -1.0, 1.0, 0.5)
        },
        angle_at_zero_rad: value(rng, -10.0, 10.0, p),
    };
    let nav64 = CartesianNav {
        time_s,
        position_m: pos,
        velocity_m_s: vel,
    };
    let nav32 = CartesianNav {
        time_s: time_s as f32,
        position_m: pos.map(|x| x as f32),
        velocity_m_s: vel.map(|x| x as f32),
    };
    let frame32 = InertialFrame {
        rotation_rate_rad_s: frame.rotation_rate_rad_s as f32,
        angle_at_zero_rad: frame.angle_at_zero_rad as f32,
    };
    let ctx = || format!("pos {pos:?} vel {vel:?} t {time_s:e} frame {frame:?}");
    if let Ok(n) = from_inertial(&nav64, &frame) {
        check(&n, std::f64::consts::PI).map_err(|e| format!("f64 inertial: {e}: {}", ctx()))?;
    }
    if let Ok(n) = from_planet_fixed(&nav64) {
        check(&n, std::f64::consts::PI).map_err(|e| format!("f64 fixed: {e}: {}", ctx()))?;
    }
    if let Ok(n) = from_inertial(&nav32, &frame32) {
        check(&widen(&n), f64::from(std::f32::consts::PI))
            .map_err(|e| format!("f32 inertial: {e}: {}", ctx()))?;
    }
    if let Ok(n) = from_planet_fixed(&nav32) {
        check(&widen(&n), f64::from(std::f32::consts::PI))
            .map_err(|e| format!("f32 fixed: {e}: {}", ctx()))?;
    }
    Ok(())
}

fn widen(n: &NavState<f32>) -> NavState<f64> {
    NavState {
        time_s: f64::from(n.time_s),
        radius_m: f64::from(n.radius_m),
        speed_m_s: f64::from(n.speed_m_s),
        flight_path_angle_rad: f64::from(n.flight_path_angle_rad),
        heading_rad: f64::from(n.heading_rad),
        latitude_rad: f64::from(n.latitude_rad),
        longitude_rad: f64::from(n.longitude_rad),
    }
}

/// Finite, radius and speed > 0, angles in their ranges (`pi` of the scalar type).
fn check(n: &NavState<f64>, pi: f64) -> Result<(), String> {
    let all = [
        n.time_s,
        n.radius_m,
        n.speed_m_s,
        n.flight_path_angle_rad,
        n.heading_rad,
        n.latitude_rad,
        n.longitude_rad,
    ];
    if all.iter().any(|x| !x.is_finite()) {
        return Err(format!("non-finite output {n:?}"));
    }
    let half = pi / 2.0;
    let ok = n.radius_m > 0.0
        && n.speed_m_s > 0.0
        && (-half..=half).contains(&n.flight_path_angle_rad)
        && (-half..=half).contains(&n.latitude_rad)
        && (0.0..2.0 * pi).contains(&n.heading_rad)
        && n.longitude_rad > -pi
        && n.longitude_rad <= pi;
    if ok {
        Ok(())
    } else {
        Err(format!("output out of range {n:?}"))
    }
}
