//! Tests of the onboard re-planner (`guidance_core::replan`) built on the Vinh predictor.

use crate::vinh_support::vehicles::{self, H_S, MU, R_EARTH, RHO0};
use guidance_core::NavState;
use guidance_core::replan::{PredictorMode, ReplanCase, ReplanConfig, ReplanFallBack, ReplanLimits, replan};
use guidance_core::vinh::{
    EntryState, ExpAtmosphere, LiftControl, Planet, PredictorConfig, VehicleParams, VinhError,
    predict,
};
use proptest::prelude::*;

fn planet() -> Planet<f64> {
    Planet {
        mu_m3_s2: MU,
        radius_m: R_EARTH,
    }
}
fn atmosphere() -> ExpAtmosphere<f64> {
    ExpAtmosphere {
        rho0_kg_m3: RHO0,
        scale_height_m: H_S,
        ref_radius_m: R_EARTH,
    }
}
fn srm() -> VehicleParams<f64> {
    let v = vehicles::srm();
    VehicleParams {
        mass_kg: v.mass_kg,
        reference_area_m2: v.area_m2,
        cd0: v.cd0,
        k_polar: v.k,
        nose_radius_m: v.nose_radius_m,
    }
}
fn nav(v: f64, g_deg: f64) -> NavState<f64> {
    NavState {
        time_s: 0.0,
        radius_m: R_EARTH + 122e3,
        speed_m_s: v,
        flight_path_angle_rad: g_deg.to_radians(),
        heading_rad: 0.0,
        latitude_rad: 0.0,
        longitude_rad: 0.0,
    }
}
fn config() -> ReplanConfig<f64> {
    ReplanConfig {
        lambda: 1.0,
        min_vertical_fraction: 0.3,
        max_vertical_fraction: 1.0,
        tolerance_m: 1000.0,
        max_iterations: 40,
        predictor: PredictorConfig {
            final_speed_m_s: 2500.0,
            max_skips: 4,
        },
        mode: PredictorMode::Chain,
    }
}
fn range_at(n: &NavState<f64>, f: f64) -> guidance_core::vinh::Prediction<f64> {
    let lift = LiftControl {
        lambda: 1.0,
        vertical_fraction: f,
    };
    let s = EntryState {
        radius_m: n.radius_m,
        speed_m_s: n.speed_m_s,
        flight_path_angle_rad: n.flight_path_angle_rad,
    };
    predict(
        &planet(),
        &atmosphere(),
        &srm(),
        &lift,
        &s,
        &config().predictor,
    )
    .unwrap()
}
const NO_LIMITS: ReplanLimits<f64> = ReplanLimits {
    heat_flux_w_m2: 1e12,
    g_load: 1e6,
};

/// A target produced by the predictor at a known fraction is met within tolerance, with a
/// bounded number of predictor calls.
#[test]
fn replan_converges_on_a_reachable_target() {
    let n = nav(7000.0, -4.0);
    for &f_true in &[0.45, 0.7, 0.9] {
        let target = range_at(&n, f_true).range_m;
        let r = replan(
            &planet(),
            &atmosphere(),
            &srm(),
            &n,
            target,
            &NO_LIMITS,
            &config(),
        );
        assert_eq!(r.case, ReplanCase::Converged, "{r:?}");
        let p = r.prediction.unwrap();
        assert!(
            (p.range_m - target).abs() <= 1000.0,
            "{} vs {target}",
            p.range_m
        );
        assert!(r.predictor_calls <= 40 + 2 + 16);
        assert!((r.bank_rad.cos() - r.vertical_fraction).abs() < 1e-12);
    }
}

/// Targets beyond the reachable interval return the nearest end.
#[test]
fn replan_reports_target_out_of_reach() {
    let n = nav(7000.0, -4.0);
    let r = replan(
        &planet(),
        &atmosphere(),
        &srm(),
        &n,
        1e9,
        &NO_LIMITS,
        &config(),
    );
    assert_eq!(r.case, ReplanCase::TargetOutOfReach);
    assert_eq!(r.vertical_fraction, 1.0);
    let r = replan(
        &planet(),
        &atmosphere(),
        &srm(),
        &n,
        1.0,
        &NO_LIMITS,
        &config(),
    );
    assert_eq!(r.case, ReplanCase::TargetOutOfReach);
    assert_eq!(r.vertical_fraction, 0.3);
}

/// A heat-flux limit below the peak at the range solution makes the limits bind: the returned
/// fraction satisfies the limit. An unreachable limit falls back.
#[test]
fn replan_limits_bind() {
    let n = nav(7000.0, -4.0);
    let target = range_at(&n, 1.0).range_m;
    let free = replan(
        &planet(),
        &atmosphere(),
        &srm(),
        &n,
        target,
        &NO_LIMITS,
        &config(),
    );
    let q_free = free.prediction.unwrap().peak_heat_flux_w_m2;
    let q_min = (0..16)
        .map(|i| range_at(&n, 0.3 + 0.7 * f64::from(i) / 15.0).peak_heat_flux_w_m2)
        .fold(f64::INFINITY, f64::min);
    assert!(q_min < q_free, "{q_min} vs {q_free}");
    let lim = ReplanLimits {
        heat_flux_w_m2: 0.5 * (q_free + q_min),
        g_load: 1e6,
    };
    let r = replan(
        &planet(),
        &atmosphere(),
        &srm(),
        &n,
        target,
        &lim,
        &config(),
    );
    assert_eq!(r.case, ReplanCase::LimitsBind, "{r:?}");
    assert!(r.prediction.unwrap().peak_heat_flux_w_m2 <= lim.heat_flux_w_m2);
    let lim = ReplanLimits {
        heat_flux_w_m2: 0.5 * q_min,
        g_load: 1e6,
    };
    let r = replan(
        &planet(),
        &atmosphere(),
        &srm(),
        &n,
        target,
        &lim,
        &config(),
    );
    assert_eq!(
        r.case,
        ReplanCase::FallBack(ReplanFallBack::LimitsInfeasible)
    );
}

/// Out of the predictor's domain: fall back to the stored profile with the reason.
#[test]
fn replan_falls_back_out_of_domain() {
    let mut n = nav(7000.0, -4.0);
    n.speed_m_s = f64::NAN;
    let r = replan(
        &planet(),
        &atmosphere(),
        &srm(),
        &n,
        1e6,
        &NO_LIMITS,
        &config(),
    );
    assert_eq!(
        r.case,
        ReplanCase::FallBack(ReplanFallBack::OutOfDomain(VinhError::NonFiniteInput))
    );
    // Shallow entry above escape speed: the arc after the skip is hyperbolic.
    let n = nav(11_500.0, -2.0);
    let r = replan(
        &planet(),
        &atmosphere(),
        &srm(),
        &n,
        1e6,
        &NO_LIMITS,
        &config(),
    );
    assert_eq!(
        r.case,
        ReplanCase::FallBack(ReplanFallBack::OutOfDomain(VinhError::EscapeTrajectory)),
        "{r:?}"
    );
    assert!(r.prediction.is_none());
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]
    #[test]
    fn replan_never_panics(v in 3000.0..11000.0f64, g in -0.2..0.05f64, target in -1e6..3e7f64, fmin in -0.2..1.2f64, q in 1e4..1e7f64) {
        let mut n = nav(v, 0.0);
        n.flight_path_angle_rad = g;
        let cfg = ReplanConfig { min_vertical_fraction: fmin, ..config() };
        let r = replan(&planet(), &atmosphere(), &srm(), &n, target, &ReplanLimits { heat_flux_w_m2: q, g_load: 5.0 }, &cfg);
        prop_assert!(r.vertical_fraction.is_finite() && r.bank_rad.is_finite());
        prop_assert!(r.predictor_calls <= 58);
        if let Some(p) = r.prediction {
            prop_assert!(p.range_m.is_finite() && p.peak_heat_flux_w_m2.is_finite() && p.peak_g_load.is_finite());
        }
    }
}
