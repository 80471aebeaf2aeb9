//! Tests of the right-hand side's cache ([`super::RhsCache`]).

use super::*;
use crate::vehicle::horus2b;

/// The right-hand side's cache of the last point changes no bit: a derivative, the peak
/// monitors' values and the flight conditions served from it equal those of a fresh cache
/// and of [`Dynamics::conditions_at`], and another state or angle of attack is not served
/// from it.
#[test]
fn the_point_cache_serves_the_bits_of_a_fresh_evaluation() {
    let env = Environment::full();
    let vehicle = horus2b::vehicle().unwrap();
    let dynm = Dynamics::from_environment(&env, &vehicle);
    let s = SphericalState {
        radius_m: env.planet.radius_m + 60e3,
        longitude_rad: 0.3,
        latitude_rad: -0.2,
        speed_m_s: 5_500.0,
        flight_path_angle_rad: -0.01,
        heading_rad: 1.0,
    };
    let y = dynm.initial_state(&s, 12.0);
    let mut y2 = y;
    y2[5] += 1e-3;
    let att = |alpha_deg: f64| Command {
        alpha_rad: alpha_deg.to_radians(),
        sigma_rad: 0.4,
    };
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let fresh = |y: &[f64; STATE_LEN], a: Command<f64>| {
        let mut c = dynm.rhs_cache();
        (
            dynm.cartesian_derivative(y, a, &mut c),
            dynm.heat_flux_and_g_load(y, a, &mut dynm.rhs_cache()),
            dynm.conditions_at(y, a),
        )
    };
    let mut cache = dynm.rhs_cache();
    for (y, a) in [(&y, 20.0), (&y, 20.0), (&y, 30.0), (&y2, 30.0), (&y, 20.0)] {
        let (d, (q, g), fc) = fresh(y, att(a));
        // Order as in the loop: monitors, sample, then the next step's first stage.
        let (q_c, g_c) = dynm.heat_flux_and_g_load(y, att(a), &mut cache);
        assert_eq!((q_c.to_bits(), g_c.to_bits()), (q.to_bits(), g.to_bits()));
        assert_eq!(dynm.conditions_at_cached(y, att(a), &mut cache), fc);
        assert_eq!(fc.heat_flux_w_m2.to_bits(), q.to_bits());
        let d_c = dynm.cartesian_derivative(y, att(a), &mut cache);
        assert_eq!(bits(&d_c), bits(&d));
    }
    // The states differ in their air data, so a stale point would have been caught.
    assert_ne!(fresh(&y, att(20.0)).2, fresh(&y2, att(20.0)).2);
    assert_ne!(fresh(&y, att(20.0)).2, fresh(&y, att(30.0)).2);
}
