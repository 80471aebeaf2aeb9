//! The onboard navigation interface (`guidance_core::navconv`) against the simulator's own
//! conversion (`dynamics::cartesian_to_spherical`), over re-entry states on the rotating Earth:
//! `f64` to a few ulp, `f32` within the stated bounds below.

use guidance_core::nav::NavState;
use guidance_core::navconv::{CartesianNav, InertialFrame, from_inertial, from_planet_fixed};
use host_sim::dynamics::{SphericalState, cartesian_to_spherical, spherical_to_cartesian};
use host_sim::env::Planet;
use nalgebra::Vector3;

/// A deterministic spread of re-entry states: altitude 20-130 km, speed 100-8000 m/s,
/// flight-path angle -30..+30 deg, any heading, latitude -85..85 deg, any longitude, time
/// 0-4000 s (splitmix64 stream, fixed seed).
fn states(n: usize) -> Vec<(f64, SphericalState)> {
    let mut s = 0x2026_1130_u64;
    let mut u = move || {
        s = s.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = s;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        (z ^ (z >> 31)) as f64 / u64::MAX as f64
    };
    let p = Planet::earth();
    (0..n)
        .map(|_| {
            let t = 4000.0 * u();
            let st = SphericalState {
                radius_m: p.radius_m + 20e3 + 110e3 * u(),
                speed_m_s: 100.0 + 7900.0 * u(),
                flight_path_angle_rad: (-30.0 + 60.0 * u()).to_radians(),
                heading_rad: 360f64.to_radians() * u(),
                latitude_rad: (-85.0 + 170.0 * u()).to_radians(),
                longitude_rad: (-180.0 + 360.0 * u()).to_radians(),
            };
            (t, st)
        })
        .collect()
}

fn frame(p: &Planet) -> InertialFrame<f64> {
    InertialFrame {
        rotation_rate_rad_s: p.rotation_rate_rad_s,
        angle_at_zero_rad: 0.0,
    }
}

fn ang(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    d.min(std::f64::consts::TAU - d)
}

/// `f64`: the same operations in the same order, but libm's sin/cos/atan2 (the core's routing)
/// against the platform's and sqrt(x^2 + y^2) for hypot: radius and speed within 4 epsilon
/// relative, angles within 4 ulp of pi.
#[test]
fn navconv_f64_matches_the_simulator_conversion() {
    let p = Planet::earth();
    let (mut worst, mut worst_rel) = (0.0f64, 0.0f64);
    for (t, s) in states(20_000) {
        let c = spherical_to_cartesian(&s, &p, t);
        let sim = cartesian_to_spherical(&c, &p, t);
        let nav = CartesianNav {
            time_s: t,
            position_m: c.position_m,
            velocity_m_s: c.velocity_m_s,
        };
        let core = from_inertial(&nav, &frame(&p)).unwrap();
        for (a, b) in [
            (core.radius_m, sim.radius_m),
            (core.speed_m_s, sim.speed_m_s),
        ] {
            worst_rel = worst_rel.max((a - b).abs() / b);
        }
        for (a, b) in [
            (core.flight_path_angle_rad, sim.flight_path_angle_rad),
            (core.heading_rad, sim.heading_rad),
            (core.latitude_rad, sim.latitude_rad),
            (core.longitude_rad, sim.longitude_rad),
        ] {
            worst = worst.max(ang(a, b));
        }
    }
    println!(
        "f64 navconv vs simulator: largest angle difference {worst:.2e} rad, radius/speed {worst_rel:.2e} relative"
    );
    assert!(
        worst <= 4.0 * f64::EPSILON * std::f64::consts::PI,
        "{worst:e}"
    );
    assert!(worst_rel <= 4.0 * f64::EPSILON, "{worst_rel:e}");
}

/// `f32` (the Cortex-M4F), inputs rounded to `f32`, against the simulator's `f64` conversion
/// of the unrounded state. Bounds, with u = 2^-24 (f32 unit round-off), |r| the radius, |v| the
/// inertial speed, V the planet-relative speed:
/// * radius: 4 u |r| (three rounded inputs, one sum of squares, one square root);
/// * position angles (latitude, longitude): 8 u (1 + |theta|) rad (inputs, rotation angle
///   theta = omega t rounded, atan2);
/// * speed: 8 u (|v| + omega |r|) (rounded inputs and the rotation subtracting omega x r, whose
///   errors are absolute, not relative to V);
/// * velocity angles (flight-path angle, heading): that speed error over V plus 8 u rad.
#[test]
fn navconv_f32_within_stated_bounds() {
    let p = Planet::earth();
    let u = f64::from(f32::EPSILON) / 2.0;
    let mut worst = [0.0f64; 6];
    for (t, s) in states(20_000) {
        let c = spherical_to_cartesian(&s, &p, t);
        let sim = cartesian_to_spherical(&c, &p, t);
        let nav = CartesianNav {
            time_s: t as f32,
            position_m: c.position_m.map(|x| x as f32),
            velocity_m_s: c.velocity_m_s.map(|x| x as f32),
        };
        let fr = InertialFrame {
            rotation_rate_rad_s: p.rotation_rate_rad_s as f32,
            angle_at_zero_rad: 0.0f32,
        };
        let n = from_inertial(&nav, &fr).unwrap();
        let theta = p.rotation_rate_rad_s * t;
        let vin = c.velocity_m_s.norm();
        let dv = 8.0 * u * (vin + p.rotation_rate_rad_s * sim.radius_m);
        let bounds = [
            4.0 * u * sim.radius_m,
            dv,
            dv / sim.speed_m_s + 8.0 * u,
            // Heading: horizontal speed error over the horizontal speed.
            dv / (sim.speed_m_s * sim.flight_path_angle_rad.cos()) + 8.0 * u,
            8.0 * u * (1.0 + theta.abs()),
            8.0 * u * (1.0 + theta.abs()),
        ];
        let errs = [
            (f64::from(n.radius_m) - sim.radius_m).abs(),
            (f64::from(n.speed_m_s) - sim.speed_m_s).abs(),
            ang(
                f64::from(n.flight_path_angle_rad),
                sim.flight_path_angle_rad,
            ),
            ang(f64::from(n.heading_rad), sim.heading_rad),
            ang(f64::from(n.latitude_rad), sim.latitude_rad),
            ang(f64::from(n.longitude_rad), sim.longitude_rad),
        ];
        for ((w, e), b) in worst.iter_mut().zip(errs).zip(bounds) {
            *w = w.max(e / b);
        }
    }
    let names = [
        "radius",
        "speed",
        "gamma",
        "heading",
        "latitude",
        "longitude",
    ];
    for (name, w) in names.iter().zip(worst) {
        println!("f32 navconv {name}: largest error / bound = {w:.3}");
    }
    assert!(worst.iter().all(|w| *w <= 1.0), "{worst:?}");
}

/// A planet-fixed input (velocity planet-relative) gives the same variables as the inertial
/// one at rotation angle 0.
#[test]
fn navconv_planet_fixed_equals_inertial_at_angle_zero() {
    let p = Planet::earth();
    for (_, s) in states(1000) {
        let c = spherical_to_cartesian(&s, &p, 0.0);
        let w = Vector3::new(0.0, 0.0, p.rotation_rate_rad_s);
        let fixed = CartesianNav {
            time_s: 0.0,
            position_m: c.position_m,
            velocity_m_s: c.velocity_m_s - w.cross(&c.position_m),
        };
        let a: NavState<f64> = from_planet_fixed(&fixed).unwrap();
        let b = cartesian_to_spherical(&c, &p, 0.0);
        assert!((a.speed_m_s - b.speed_m_s).abs() < 1e-9 * b.speed_m_s);
        assert!(ang(a.heading_rad, b.heading_rad) < 1e-12);
        assert!(ang(a.flight_path_angle_rad, b.flight_path_angle_rad) < 1e-12);
    }
}
