//! The navigation interface's degenerate inputs: typed errors or the documented limit, never
//! NaN (`f64` and `f32`). Accuracy against the simulator: host-sim `tests/it/navconv.rs`.

use guidance_core::navconv::{
    CartesianNav, InertialFrame, NavConvError, from_inertial, from_planet_fixed,
};
use nalgebra::Vector3;
use proptest::prelude::*;

const RE: f64 = 6_378_137.0;
const OMEGA: f64 = 7.292_115e-5;

fn nav(p: [f64; 3], v: [f64; 3]) -> CartesianNav<f64> {
    CartesianNav {
        time_s: 10.0,
        position_m: Vector3::from(p),
        velocity_m_s: Vector3::from(v),
    }
}

fn nav32(n: &CartesianNav<f64>) -> CartesianNav<f32> {
    CartesianNav {
        time_s: n.time_s as f32,
        position_m: n.position_m.map(|x| x as f32),
        velocity_m_s: n.velocity_m_s.map(|x| x as f32),
    }
}

const EARTH: InertialFrame<f64> = InertialFrame {
    rotation_rate_rad_s: OMEGA,
    angle_at_zero_rad: 0.0,
};
const EARTH32: InertialFrame<f32> = InertialFrame {
    rotation_rate_rad_s: OMEGA as f32,
    angle_at_zero_rad: 0.0,
};

fn both(n: &CartesianNav<f64>) -> (Result<(), NavConvError>, Result<(), NavConvError>) {
    (
        from_planet_fixed(n).map(|_| ()),
        from_planet_fixed(&nav32(n)).map(|_| ()),
    )
}

#[test]
fn navconv_zero_position_is_an_error() {
    let n = nav([0.0; 3], [7000.0, 0.0, 0.0]);
    assert_eq!(
        both(&n),
        (
            Err(NavConvError::ZeroPosition),
            Err(NavConvError::ZeroPosition)
        )
    );
}

#[test]
fn navconv_pole_is_an_error() {
    for z in [RE, -RE] {
        let n = nav([0.0, 0.0, z], [7000.0, 0.0, 0.0]);
        assert_eq!(both(&n), (Err(NavConvError::Pole), Err(NavConvError::Pole)));
        // A metre off the axis is not a pole in f64; in f32 (4 eps |r| = 3 m) it is.
        let n = nav([1.0, 0.0, z], [7000.0, 0.0, 0.0]);
        assert!(from_planet_fixed(&n).is_ok());
        assert_eq!(
            from_planet_fixed(&nav32(&n)).map(|_| ()),
            Err(NavConvError::Pole)
        );
    }
}

#[test]
fn navconv_zero_relative_velocity_is_an_error() {
    let n = nav([RE, 0.0, 0.0], [0.0; 3]);
    assert_eq!(
        both(&n),
        (
            Err(NavConvError::ZeroVelocity),
            Err(NavConvError::ZeroVelocity)
        )
    );
    // Inertial velocity = omega x r: at rest on the rotating planet (at time 0).
    let mut n = nav([RE, 0.0, 0.0], [0.0, OMEGA * RE, 0.0]);
    n.time_s = 0.0;
    assert_eq!(from_inertial(&n, &EARTH), Err(NavConvError::ZeroVelocity));
}

/// Documented limit: vertical flight has heading 0 and flight-path angle +-pi/2.
#[test]
fn navconv_vertical_flight_heading_is_zero() {
    for (vx, gamma) in [
        (-3000.0, -std::f64::consts::FRAC_PI_2),
        (50.0, std::f64::consts::FRAC_PI_2),
    ] {
        let n = nav([RE + 1e5, 0.0, 0.0], [vx, 0.0, 0.0]);
        let a = from_planet_fixed(&n).unwrap();
        assert_eq!(a.heading_rad, 0.0);
        assert_eq!(a.flight_path_angle_rad, gamma);
        let b = from_planet_fixed(&nav32(&n)).unwrap();
        assert_eq!(b.heading_rad, 0.0);
        assert!((f64::from(b.flight_path_angle_rad) - gamma).abs() < 1e-6);
    }
}

#[test]
fn navconv_non_finite_and_overflow_are_errors() {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let n = nav([RE, bad, 0.0], [7000.0, 0.0, 0.0]);
        assert_eq!(
            both(&n),
            (Err(NavConvError::NonFinite), Err(NavConvError::NonFinite))
        );
        let mut n = nav([RE, 0.0, 0.0], [7000.0, 0.0, 0.0]);
        n.time_s = bad;
        assert_eq!(from_inertial(&n, &EARTH), Err(NavConvError::NonFinite));
    }
    // 1e20 m is finite in f32 but its square is not.
    let n = nav([1e20, 0.0, 0.0], [0.0, 7000.0, 0.0]);
    assert!(from_planet_fixed(&n).is_ok());
    assert_eq!(
        from_planet_fixed(&nav32(&n)).map(|_| ()),
        Err(NavConvError::OutOfRange)
    );
}

fn any_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -1e7..1e7f64,
        1 => Just(0.0),
        1 => prop::num::f64::ANY,
    ]
}

proptest! {
    /// Any input: an error, or finite outputs in their documented ranges (f64 and f32,
    /// inertial and planet-fixed).
    #[test]
    fn navconv_never_nan(p in prop::array::uniform3(any_f64()), v in prop::array::uniform3(any_f64()),
                         t in any_f64()) {
        let mut n = nav(p, v);
        n.time_s = t;
        let pi = std::f64::consts::PI;
        for r in [from_inertial(&n, &EARTH), from_planet_fixed(&n)].into_iter().flatten() {
            prop_assert!(r.radius_m > 0.0 && r.radius_m.is_finite());
            prop_assert!(r.speed_m_s > 0.0 && r.speed_m_s.is_finite());
            prop_assert!(r.flight_path_angle_rad.abs() <= pi / 2.0);
            prop_assert!(r.latitude_rad.abs() <= pi / 2.0);
            prop_assert!((0.0..2.0 * pi).contains(&r.heading_rad));
            prop_assert!(r.longitude_rad > -pi && r.longitude_rad <= pi);
        }
        let n32 = nav32(&n);
        let pi32 = std::f32::consts::PI;
        for r in [from_inertial(&n32, &EARTH32), from_planet_fixed(&n32)].into_iter().flatten() {
            prop_assert!(r.radius_m > 0.0 && r.radius_m.is_finite());
            prop_assert!(r.speed_m_s > 0.0 && r.speed_m_s.is_finite());
            prop_assert!(r.flight_path_angle_rad.abs() <= pi32 / 2.0);
            prop_assert!(r.latitude_rad.abs() <= pi32 / 2.0);
            prop_assert!((0.0..2.0 * pi32).contains(&r.heading_rad));
            prop_assert!(r.longitude_rad >= -pi32 && r.longitude_rad <= pi32);
        }
    }
}
