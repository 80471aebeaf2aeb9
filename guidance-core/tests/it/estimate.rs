//! Onboard aerodynamic estimation: convergence to the true scales from sensed accelerations
//! along a descent, the threshold, the scaled predictor model, and hostile inputs (finite,
//! bounded outputs, typed errors).

use guidance_core::GuidanceError;
use guidance_core::energy::EARTH_RADIUS_M;
use guidance_core::estimate::{
    AeroEstimator, AeroScales, EstimateError, EstimateStatus, EstimatorConfig, SensedAero,
    expected_aero,
};
use guidance_core::vinh::{ExpAtmosphere, VehicleParams};
use proptest::prelude::*;

fn config() -> EstimatorConfig<f64> {
    EstimatorConfig {
        lift_to_drag_gain: 0.1,
        drag_gain: 0.2,
        lift_to_drag_bounds: (0.5, 2.0),
        drag_bounds: (0.3, 3.0),
        min_drag_m_s2: 0.5,
    }
}

/// A capsule-like polar (E* = 1 / (2 sqrt(K C_D0)) = 0.5 / sqrt(0.9 * 0.6)).
fn vehicle() -> VehicleParams<f64> {
    VehicleParams {
        mass_kg: 1500.0,
        reference_area_m2: 3.0,
        cd0: 0.6,
        k_polar: 0.9,
        nose_radius_m: 0.5,
    }
}

/// The world differs from the model: L/D x1.08, drag x1.25 (e.g. density +25 %); a
/// deterministic +-3 % sensor error on lift and drag that does not average to a bias over a
/// window. Sensed along a descent from 90 km to 40 km at 6 km/s -> 3 km/s.
#[test]
fn estimator_converges_to_the_true_scales_on_a_dispersed_case() {
    let (atm, veh) = (ExpAtmosphere::<f64>::earth(), vehicle());
    let (true_ld, true_drag) = (1.08, 1.25);
    let mut est = AeroEstimator::new(config()).unwrap();
    let mut updated = 0;
    for i in 0..200 {
        let f = f64::from(i) / 199.0;
        let (h, v) = (90e3 - 50e3 * f, 6000.0 - 3000.0 * f);
        let e = expected_aero(&atm, &veh, 1.0, EARTH_RADIUS_M + h, v).unwrap();
        let noise = |k: i32| 1.0 + 0.03 * f64::from((i * k) % 7 - 3) / 3.0;
        let sensed = SensedAero {
            lift_m_s2: e.lift_m_s2 * true_drag * true_ld * noise(3),
            drag_m_s2: e.drag_m_s2 * true_drag * noise(5),
        };
        if est.update(&sensed, &e).unwrap() == EstimateStatus::Updated {
            updated += 1;
        }
    }
    assert!(updated > 100, "{updated} updates");
    let s = est.scales();
    assert!(
        (s.lift_to_drag - true_ld).abs() < 0.02,
        "L/D scale {} (true {true_ld})",
        s.lift_to_drag
    );
    assert!(
        (s.drag - true_drag).abs() < 0.03,
        "drag scale {} (true {true_drag})",
        s.drag
    );
    // Exact sensing converges to the exact value (geometric: 0.9^k).
    let e = expected_aero(&atm, &veh, 1.0, EARTH_RADIUS_M + 50e3, 5000.0).unwrap();
    for _ in 0..300 {
        est.update(
            &SensedAero {
                lift_m_s2: e.lift_m_s2 * true_drag * true_ld,
                drag_m_s2: e.drag_m_s2 * true_drag,
            },
            &e,
        )
        .unwrap();
    }
    let s = est.scales();
    assert!((s.lift_to_drag - true_ld).abs() < 1e-9);
    assert!((s.drag - true_drag).abs() < 1e-9);
}

/// In thin air (sensed drag under the threshold) nothing changes; a measurement outside the
/// bounds moves the estimate only towards the bound.
#[test]
fn threshold_and_bounds() {
    let mut est = AeroEstimator::new(config()).unwrap();
    let e = SensedAero {
        lift_m_s2: 0.2,
        drag_m_s2: 0.4,
    };
    let thin = SensedAero {
        lift_m_s2: 0.4,
        drag_m_s2: 0.45,
    };
    assert_eq!(est.update(&thin, &e), Ok(EstimateStatus::BelowThreshold));
    assert_eq!(est.scales(), AeroScales::nominal());
    assert_eq!(est.updates(), 0);
    let wild = SensedAero {
        lift_m_s2: 1e6,
        drag_m_s2: 100.0,
    };
    for _ in 0..500 {
        assert_eq!(est.update(&wild, &e), Ok(EstimateStatus::Updated));
    }
    let s = est.scales();
    assert!(s.lift_to_drag <= 2.0 && s.lift_to_drag > 1.99, "{s:?}");
    assert!(s.drag <= 3.0 && s.drag > 2.99, "{s:?}");
    // The model expects no drag (e.g. density underflow): nothing changes.
    let none = SensedAero {
        lift_m_s2: 0.0,
        drag_m_s2: 0.0,
    };
    assert_eq!(est.update(&e, &none), Ok(EstimateStatus::BelowThreshold));
    assert_eq!(est.update(&wild, &none), Ok(EstimateStatus::NoModel));
    assert_eq!(est.scales(), s);
}

/// Bad settings are `InvalidConfig`.
#[test]
fn bad_configs_are_rejected() {
    let bad = [
        EstimatorConfig {
            lift_to_drag_gain: 0.0,
            ..config()
        },
        EstimatorConfig {
            drag_gain: 1.5,
            ..config()
        },
        EstimatorConfig {
            drag_gain: f64::NAN,
            ..config()
        },
        EstimatorConfig {
            lift_to_drag_bounds: (1.1, 2.0),
            ..config()
        },
        EstimatorConfig {
            drag_bounds: (0.0, 2.0),
            ..config()
        },
        EstimatorConfig {
            drag_bounds: (0.5, 0.9),
            ..config()
        },
        EstimatorConfig {
            lift_to_drag_bounds: (0.5, f64::INFINITY),
            ..config()
        },
        EstimatorConfig {
            min_drag_m_s2: -1.0,
            ..config()
        },
    ];
    for c in bad {
        assert_eq!(
            AeroEstimator::new(c),
            Err(GuidanceError::InvalidConfig),
            "{c:?}"
        );
    }
}

/// The scaled model: at scales 1 the model is returned bit for bit; the L/D scale scales the
/// model's E* and lift at a given lambda and keeps its drag; the drag scale scales both.
#[test]
fn scaled_model_has_the_estimated_aerodynamics() {
    let (atm, veh) = (ExpAtmosphere::<f64>::earth(), vehicle());
    assert_eq!(AeroScales::nominal().apply(&atm, &veh), Some((atm, veh)));
    let s = AeroScales {
        lift_to_drag: 1.1,
        drag: 0.8,
    };
    let (a2, v2) = s.apply(&atm, &veh).unwrap();
    let e1 = veh.max_lift_to_drag().unwrap();
    let e2 = v2.max_lift_to_drag().unwrap();
    assert!((e2 / e1 - 1.1).abs() < 1e-12);
    let r = EARTH_RADIUS_M + 60e3;
    for lambda in [0.5, 1.0, 1.7] {
        let x1 = expected_aero(&atm, &veh, lambda, r, 5000.0).unwrap();
        let x2 = expected_aero(&a2, &v2, lambda, r, 5000.0).unwrap();
        assert!((x2.drag_m_s2 / x1.drag_m_s2 - 0.8).abs() < 1e-12);
        assert!((x2.lift_m_s2 / x1.lift_m_s2 - 0.8 * 1.1).abs() < 1e-12);
    }
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let b = AeroScales {
            lift_to_drag: bad,
            drag: 1.0,
        };
        assert_eq!(b.apply(&atm, &veh), None);
    }
}

fn hostile() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-0.0),
        Just(f64::MIN_POSITIVE),
        Just(5e-324),
        Just(f64::MAX),
        -1e3..1e3f64,
        0.0..1e-300f64,
        1e300..f64::MAX,
        any::<f64>(),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    /// Whatever it is fed, the estimate stays finite and inside its bounds, a non-finite or
    /// negative input is a typed error that changes nothing, and `expected_aero` is finite or
    /// `None`, in `f64` and `f32`.
    #[test]
    fn estimator_outputs_are_finite_and_bounded_for_hostile_inputs(
        samples in prop::collection::vec((hostile(), hostile(), hostile(), hostile()), 1..40),
        lo in 0.01f64..=1.0, hi in 1.0f64..10.0, g in 0.001f64..=1.0,
        state in (hostile(), hostile(), hostile()),
    ) {
        let c = EstimatorConfig {
            lift_to_drag_gain: g,
            drag_gain: g,
            lift_to_drag_bounds: (lo, hi),
            drag_bounds: (lo, hi),
            min_drag_m_s2: 0.0,
        };
        let mut est = AeroEstimator::new(c).unwrap();
        #[allow(clippy::cast_possible_truncation)]
        let c32 = EstimatorConfig {
            lift_to_drag_gain: g as f32,
            drag_gain: g as f32,
            lift_to_drag_bounds: (lo as f32, hi as f32),
            drag_bounds: (lo as f32, hi as f32),
            min_drag_m_s2: 0.0,
        };
        let mut est32 = AeroEstimator::new(c32).ok();
        for (a, b, x, y) in samples {
            let sensed = SensedAero { lift_m_s2: a, drag_m_s2: b };
            let expected = SensedAero { lift_m_s2: x, drag_m_s2: y };
            let before = est.scales();
            match est.update(&sensed, &expected) {
                Ok(_) => {}
                Err(e) => {
                    let all = [a, b, x, y];
                    if all.iter().any(|v| !v.is_finite()) {
                        prop_assert_eq!(e, EstimateError::NonFinite);
                    } else {
                        prop_assert_eq!(e, EstimateError::Negative);
                    }
                    prop_assert_eq!(est.scales(), before);
                }
            }
            let s = est.scales();
            for (v, (l, h)) in [(s.lift_to_drag, (lo, hi)), (s.drag, (lo, hi))] {
                prop_assert!(v.is_finite() && v >= l && v <= h, "{s:?}");
            }
            if let Some(e32) = est32.as_mut() {
                #[allow(clippy::cast_possible_truncation)]
                let f = |v: f64| v as f32;
                let _ = e32.update(
                    &SensedAero { lift_m_s2: f(a), drag_m_s2: f(b) },
                    &SensedAero { lift_m_s2: f(x), drag_m_s2: f(y) },
                );
                let s = e32.scales();
                for (v, (l, h)) in [(s.lift_to_drag, c32.drag_bounds), (s.drag, c32.drag_bounds)] {
                    prop_assert!(v.is_finite() && v >= l && v <= h, "{s:?}");
                }
                if let Some((atm, veh)) = s.apply(&ExpAtmosphere::earth(), &VehicleParams {
                    mass_kg: 1500.0, reference_area_m2: 3.0, cd0: 0.6, k_polar: 0.9,
                    nose_radius_m: 0.5,
                }) {
                    prop_assert!(atm.rho0_kg_m3.is_finite() && veh.k_polar.is_finite());
                }
            }
        }
        let (r, v, lambda) = state;
        if let Some(e) = expected_aero(&ExpAtmosphere::earth(), &vehicle(), lambda, r, v) {
            prop_assert!(e.lift_m_s2.is_finite() && e.drag_m_s2.is_finite());
            prop_assert!(e.lift_m_s2 >= 0.0 && e.drag_m_s2 >= 0.0);
        }
    }
}

/// In `ReplanningGuidance`: an estimator that has not been fed changes nothing (bit for bit);
/// once fed (gain 1: one sample), the solve is that of a guidance whose model *is* the scaled
/// one, and it differs from the unscaled solve.
#[test]
fn replanning_predicts_with_the_estimated_aerodynamics() {
    use crate::vinh_replan::{glide_nav, glide_range_m, model, rcfg, replanning};
    use guidance_core::replan::{PredictorMode, RangeTarget};
    let cfg = rcfg(
        RangeTarget::FlownRangeAngle {
            total_rad: glide_range_m(0.6) / EARTH_RADIUS_M,
        },
        3,
        PredictorMode::Glide,
    );
    // Gain 1, and no threshold (at 100 km the drag is below the 0.5 m/s^2 one).
    let one = EstimatorConfig {
        lift_to_drag_gain: 1.0,
        drag_gain: 1.0,
        min_drag_m_s2: 0.0,
        ..config()
    };
    let nav = glide_nav(0.0);
    let plain = replanning(cfg).update(&nav).unwrap().replan.unwrap();
    let mut unfed = replanning(cfg).with_estimator(AeroEstimator::new(one).unwrap());
    assert_eq!(unfed.aero_scales(), Some(AeroScales::nominal()));
    assert_eq!(unfed.update(&nav).unwrap().replan.unwrap(), plain);

    let m = model();
    let e = expected_aero(&m.atmosphere, &m.vehicle, 1.0, nav.radius_m, nav.speed_m_s).unwrap();
    let (s_ld, s_d) = (0.93, 1.15);
    let sensed = SensedAero {
        lift_m_s2: e.lift_m_s2 * s_ld * s_d,
        drag_m_s2: e.drag_m_s2 * s_d,
    };
    let mut fed = replanning(cfg).with_estimator(AeroEstimator::new(one).unwrap());
    assert_eq!(
        fed.sense(&nav, &sensed).unwrap(),
        Some(EstimateStatus::Updated)
    );
    let est = fed.aero_scales().unwrap();
    assert!((est.lift_to_drag - s_ld).abs() < 1e-12 && (est.drag - s_d).abs() < 1e-12);
    let got = fed.update(&nav).unwrap().replan.unwrap();
    let (atm, veh) = est.apply(&m.atmosphere, &m.vehicle).unwrap();
    let mut scaled_cfg = cfg;
    scaled_cfg.model.atmosphere = atm;
    scaled_cfg.model.vehicle = veh;
    let want = replanning(scaled_cfg).update(&nav).unwrap().replan.unwrap();
    assert_eq!(got, want);
    assert!(
        (got.bank_rad - plain.bank_rad).abs() > 1e-3,
        "{} vs {}",
        got.bank_rad,
        plain.bank_rad
    );
    // Hostile sensed values are typed errors and leave the estimate alone; without an
    // estimator `sense` does nothing.
    let bad = SensedAero {
        lift_m_s2: f64::NAN,
        drag_m_s2: 1.0,
    };
    assert_eq!(fed.sense(&nav, &bad), Err(EstimateError::NonFinite));
    assert_eq!(fed.aero_scales(), Some(est));
    assert_eq!(replanning(cfg).sense(&nav, &sensed), Ok(None));
}
