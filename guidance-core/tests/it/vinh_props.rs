//! Property tests of `guidance_core::vinh`: random inputs, in and out of the domain, give a
//! value with every field finite or a typed `VinhError`; never NaN, never a panic.

use guidance_core::vinh::{
    BallisticArc, EntryState, ExpAtmosphere, GlideSolution, Leg, LiftControl, NonDim, Planet,
    PredictorConfig, SkipSolution, VehicleParams, predict,
};
use proptest::prelude::*;

/// Mostly plausible values, sometimes hostile ones.
fn wild(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    prop_oneof![
        40 => lo..hi,
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(-1.0),
        1 => Just(0.0),
        1 => any::<f64>(),
    ]
}

fn vehicle() -> impl Strategy<Value = VehicleParams<f64>> {
    (
        wild(1.0, 1e5),
        wild(0.1, 200.0),
        wild(-0.05, 1.0),
        wild(0.05, 2.0),
        wild(0.1, 2.0),
    )
        .prop_map(|(m, s, cd0, k, rn)| VehicleParams {
            mass_kg: m,
            reference_area_m2: s,
            cd0,
            k_polar: k,
            nose_radius_m: rn,
        })
}

fn lift() -> impl Strategy<Value = LiftControl<f64>> {
    (wild(0.0, 2.0), wild(-1.0, 1.0)).prop_map(|(l, v)| LiftControl {
        lambda: l,
        vertical_fraction: v,
    })
}

fn entry() -> impl Strategy<Value = EntryState<f64>> {
    (
        wild(6_378_137.0 - 1e3, 6_378_137.0 + 200e3),
        wild(500.0, 15_000.0),
        wild(-0.5, 0.3),
    )
        .prop_map(|(r, v, g)| EntryState {
            radius_m: r,
            speed_m_s: v,
            flight_path_angle_rad: g,
        })
}

fn all_finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 192, ..ProptestConfig::default() })]

    #[test]
    fn skip_never_nan_never_panics(veh in vehicle(), l in lift(), e in entry(), f in 0.0..1.0f64, fx in 0.0..1.2f64) {
        let planet = Planet::<f64>::earth();
        let atm = ExpAtmosphere::<f64>::earth();
        if let Ok(nd) = NonDim::new(&planet, &atm, &veh, &l, &e) {
            let c = nd.constants();
            prop_assert!(all_finite(&[c.e_star, c.b, c.k1, c.eta, c.k, c.alpha, c.s, c.c, c.e_vertical]));
            if let Ok(s) = SkipSolution::new(&nd) {
                let ex = s.exit();
                prop_assert!(all_finite(&[ex.speed_m_s, ex.flight_path_angle_rad, ex.range_angle_rad, ex.heat_flux_w_m2, ex.g_load]));
                prop_assert!(ex.speed_m_s > 0.0 && ex.flight_path_angle_rad >= 0.0);
                for p in [s.point_at_tau(f * s.tau_exit()), s.point_at_depth(fx * s.x1(), Leg::Descending), s.point_at_depth(fx * s.x1(), Leg::Ascending), s.peak_heat_flux(), s.peak_g_load()].into_iter().flatten() {
                    prop_assert!(all_finite(&[p.tau, p.x, p.phi, p.eta_v, p.radius_m, p.speed_m_s, p.flight_path_angle_rad, p.heat_flux_w_m2, p.drag_acc_m_s2, p.lift_acc_m_s2, p.g_load]));
                }
            }
        }
    }

    #[test]
    fn glide_never_nan_never_panics(veh in vehicle(), l in lift(), h in wild(-1e3, 130e3), f in wild(0.0, 1.1)) {
        let planet = Planet::<f64>::earth();
        let atm = ExpAtmosphere::<f64>::earth();
        if let Ok(g) = GlideSolution::new(&planet, &atm, &veh, &l, 6_378_137.0 + h) {
            let e = g.imposed_entry();
            prop_assert!(all_finite(&[e.speed_m_s, e.flight_path_angle_rad, g.u_entry()]));
            for p in [g.point_at_u(f * g.u_entry()), g.point_at_speed(f * e.speed_m_s), g.peak_heat_flux(0.5 * e.speed_m_s), g.peak_g_load(0.5 * e.speed_m_s)].into_iter().flatten() {
                prop_assert!(all_finite(&[p.u, p.speed_m_s, p.range_angle_rad, p.density_ratio, p.radius_m, p.phi, p.flight_path_angle_rad, p.heat_flux_w_m2, p.drag_acc_m_s2, p.lift_acc_m_s2, p.g_load]));
                prop_assert!(p.range_angle_rad >= 0.0);
            }
        }
    }

    #[test]
    fn kepler_never_nan_never_panics(e in entry(), g in wild(-0.2, 1.7), dr in wild(-20e3, 20e3), t in 0.0..1.0f64) {
        let planet = Planet::<f64>::earth();
        let exit = EntryState { flight_path_angle_rad: g, ..e };
        if let Ok(a) = BallisticArc::new(&planet, &exit, e.radius_m + dr) {
            prop_assert!(all_finite(&[a.range_angle_rad(), a.flight_time_s(), a.eccentricity(), a.exit_true_anomaly_rad()]));
            prop_assert!(a.range_angle_rad() > 0.0 && a.flight_time_s() > 0.0 && a.eccentricity() < 1.0);
            let p = a.state_at_time(t * a.flight_time_s());
            prop_assert!(p.is_ok());
            let p = p.unwrap();
            prop_assert!(all_finite(&[p.radius_m, p.speed_m_s, p.flight_path_angle_rad, p.range_angle_rad]));
        }
    }

    #[test]
    fn predictor_never_nan_never_panics(veh in vehicle(), l in lift(), e in entry(), vf in wild(100.0, 8000.0), n in 0u8..10) {
        let planet = Planet::<f64>::earth();
        let atm = ExpAtmosphere::<f64>::earth();
        if let Ok(p) = predict(&planet, &atm, &veh, &l, &e, &PredictorConfig { final_speed_m_s: vf, max_skips: n }) {
            prop_assert!(all_finite(&[p.range_angle_rad, p.range_m, p.peak_heat_flux_w_m2, p.peak_g_load, p.glide_start_radius_m]));
            prop_assert!(p.range_angle_rad >= 0.0 && p.skips <= n);
        }
    }

    #[test]
    fn f32_skip_and_glide_never_nan(m in 1.0f32..1e5, s in 0.1f32..200.0, cd0 in -0.05f32..1.0, k in 0.05f32..2.0,
                                    lam in 0.0f32..2.0, vfrac in -1.0f32..1.0, h in 0.0f32..200e3, v in 500.0f32..15000.0, g in -0.5f32..0.3) {
        let planet = Planet::<f32>::earth();
        let atm = ExpAtmosphere::<f32>::earth();
        let veh = VehicleParams { mass_kg: m, reference_area_m2: s, cd0, k_polar: k, nose_radius_m: 0.5 };
        let l = LiftControl { lambda: lam, vertical_fraction: vfrac };
        let e = EntryState { radius_m: 6_378_137.0 + h, speed_m_s: v, flight_path_angle_rad: g };
        if let Ok(nd) = NonDim::new(&planet, &atm, &veh, &l, &e)
            && let Ok(sk) = SkipSolution::new(&nd)
        {
            let ex = sk.exit();
            prop_assert!(ex.speed_m_s.is_finite() && ex.flight_path_angle_rad.is_finite() && ex.range_angle_rad.is_finite());
            if let Ok(p) = sk.peak_heat_flux() {
                prop_assert!(p.heat_flux_w_m2.is_finite());
            }
        }
        if let Ok(gl) = GlideSolution::new(&planet, &atm, &veh, &l, 6_378_137.0 + h)
            && let Ok(p) = gl.point_at_u(0.5 * gl.u_entry())
        {
            prop_assert!(p.range_angle_rad.is_finite() && p.radius_m.is_finite() && p.heat_flux_w_m2.is_finite());
        }
    }
}

/// Coverage check of the property tests: near the thesis vehicles a good share of random
/// cases is in domain, so the finiteness properties above are exercised on real solutions.
#[test]
fn property_inputs_reach_the_domain() {
    let planet = Planet::<f64>::earth();
    let atm = ExpAtmosphere::<f64>::earth();
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut uniform = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut skips, mut glides) = (0, 0);
    for _ in 0..200 {
        let veh = VehicleParams {
            mass_kg: 20.0 + 30.0 * uniform(),
            reference_area_m2: 0.3 + 0.3 * uniform(),
            cd0: 0.1 + 0.3 * uniform(),
            k_polar: 0.1 + 0.2 * uniform(),
            nose_radius_m: 0.9,
        };
        let l = LiftControl {
            lambda: 0.3 + 0.7 * uniform(),
            vertical_fraction: 0.3 + 0.7 * uniform(),
        };
        let e = EntryState {
            radius_m: 6_378_137.0 + 122e3,
            speed_m_s: 7500.0 + 3000.0 * uniform(),
            flight_path_angle_rad: -(0.03 + 0.1 * uniform()),
        };
        if NonDim::new(&planet, &atm, &veh, &l, &e)
            .and_then(|nd| SkipSolution::new(&nd))
            .is_ok()
        {
            skips += 1;
        }
        if GlideSolution::new(
            &planet,
            &atm,
            &veh,
            &l,
            6_378_137.0 + 60e3 + 40e3 * uniform(),
        )
        .is_ok()
        {
            glides += 1;
        }
    }
    assert!(
        skips > 100 && glides > 100,
        "skips {skips}, glides {glides}"
    );
}
