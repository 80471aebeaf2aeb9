//! The barrier law of `PathBound` (`barrier_frequency_rad_s > 0`): the heat-flux and g-load
//! limits as altitude floors whose margin may not close faster than a damped second-order
//! response; the sensed accelerations in place of the model's; the bank cap it puts on
//! `Guidance` at every tick.

use crate::path_bound::{nav, predict};
use crate::vinh_replan::{glide_nav, glide_range_m, rcfg, replanning};
use crate::vinh_support::inputs::{atmosphere, horus, planet};
use crate::vinh_support::vehicles::R_EARTH;
use guidance_core::estimate::{SensedAero, expected_aero};
use guidance_core::nav::NavState;
use guidance_core::replan::{
    PathBound, PredictorMode, RangeTarget, ReplanLimits, SENSED_MIN_DRAG_M_S2,
};

fn barrier(q_w_m2: f64, g_load: f64, omega: f64, zeta: f64) -> PathBound<f64> {
    PathBound {
        limits: ReplanLimits {
            heat_flux_w_m2: q_w_m2,
            g_load,
        },
        descent_time_s: 0.0,
        barrier_frequency_rad_s: omega,
        barrier_damping: zeta,
    }
}

/// The barrier's fraction for HORUS-2B (lambda 3.7, the polar's drag) at `n`.
fn at(b: &PathBound<f64>, n: &NavState<f64>, sensed: Option<SensedAero<f64>>) -> f64 {
    b.barrier_vertical_fraction(&planet(), &atmosphere(), &horus(), (3.7, 1.0), n, sensed)
        .unwrap()
}

/// The model's lift and drag accelerations \[m/s^2\] of HORUS-2B at lambda 3.7 at `n`.
fn model_aero(n: &NavState<f64>) -> SensedAero<f64> {
    expected_aero(&atmosphere(), &horus(), 3.7, n.radius_m, n.speed_m_s).unwrap()
}

/// Far above both floors the barrier does not bind; in air denser than the heat-flux limit
/// allows it asks for lift-up; with the barrier off it is the equilibrium bound bit for bit.
#[test]
fn the_barrier_is_slack_far_from_the_limits_and_lift_up_beyond() {
    let b = barrier(500e3, 2.5, 0.15, 1.0);
    assert_eq!(at(&b, &nav(110.0, 7400.0, -1.0), None), 0.0);
    // 50 km at 6 km/s: far denser than the 500 kW/m^2 density at that speed.
    assert_eq!(at(&b, &nav(50.0, 6000.0, 0.0), None), 1.0);
    let off = barrier(500e3, 2.5, 0.0, 1.0);
    for n in [nav(70.0, 6500.0, -0.5), nav(40.0, 2500.0, -3.0)] {
        assert_eq!(
            off.barrier_vertical_fraction(&planet(), &atmosphere(), &horus(), (3.7, 1.0), &n, None),
            off.min_vertical_fraction(&planet(), &horus(), 3.7, &n)
        );
    }
}

/// Closer to a floor, or closing on it faster, needs more vertical lift; a higher frequency
/// lets the vehicle come closer before the barrier acts.
#[test]
fn the_barrier_reacts_to_the_margin_and_the_closing_rate() {
    // omega 0.05 rad/s: a band of a few km above the heat-flux floor at 6.5 km/s (about 71 km
    // for HORUS-2B in this model) where the bound is between 0 and 1.
    let b = barrier(500e3, 2.5, 0.05, 1.0);
    let alts = [74.0, 73.0, 72.5, 72.0, 71.5, 71.0];
    let f: Vec<f64> = alts
        .iter()
        .map(|&h| at(&b, &nav(h, 6500.0, -0.5), None))
        .collect();
    assert!(f.windows(2).all(|w| w[0] <= w[1]), "{f:?}");
    assert!(f.iter().any(|x| *x > 0.0 && *x < 1.0), "{f:?}");
    assert!(f[0] == 0.0 && f[5] == 1.0, "{f:?}");
    let dives: Vec<f64> = [0.5, 0.0, -0.5, -1.0, -2.0]
        .iter()
        .map(|&g| at(&b, &nav(76.0, 6500.0, g), None))
        .collect();
    assert!(dives.windows(2).all(|w| w[0] <= w[1]), "{dives:?}");
    assert!(dives[0] == 0.0 && dives[4] == 1.0, "{dives:?}");
    let n = nav(73.0, 6500.0, -1.0);
    let slow = at(&barrier(500e3, 2.5, 0.05, 1.0), &n, None);
    let fast = at(&barrier(500e3, 2.5, 0.3, 1.0), &n, None);
    assert!(fast < slow, "{fast} {slow}");
    for x in f.iter().chain(&dives) {
        assert!((0.0..=1.0).contains(x));
    }
}

/// Sensed accelerations replace the model's: more drag than modelled (denser air, a draggier
/// vehicle) needs more lift; a sensed drag below the floor, or an invalid one, is not used.
#[test]
fn the_barrier_uses_the_sensed_accelerations() {
    let b = barrier(500e3, 2.5, 0.05, 1.0);
    let n = nav(72.5, 6500.0, -0.5);
    let model = at(&b, &n, None);
    assert!(model > 0.0 && model < 1.0, "{model}");
    let m = model_aero(&n);
    let same = at(&b, &n, Some(m));
    assert!((same - model).abs() < 1e-9, "{same} {model}");
    let denser = SensedAero {
        lift_m_s2: 1.2 * m.lift_m_s2,
        drag_m_s2: 1.2 * m.drag_m_s2,
    };
    assert!(at(&b, &n, Some(denser)) > model);
    let thin = SensedAero {
        lift_m_s2: 0.1,
        drag_m_s2: 0.5 * SENSED_MIN_DRAG_M_S2,
    };
    let high = nav(90.0, 7400.0, -1.0);
    assert_eq!(at(&b, &high, Some(thin)), at(&b, &high, None));
    let bad = SensedAero {
        lift_m_s2: f64::NAN,
        drag_m_s2: 10.0,
    };
    assert_eq!(at(&b, &n, Some(bad)), model);
}

/// An invalid barrier (negative or non-finite frequency or damping) is no bound, never NaN.
#[test]
fn an_invalid_barrier_is_no_bound() {
    let n = nav(70.0, 6500.0, -0.5);
    for b in [
        barrier(500e3, 2.5, -0.1, 1.0),
        barrier(500e3, 2.5, f64::NAN, 1.0),
        barrier(500e3, 2.5, 0.1, -1.0),
        barrier(500e3, 2.5, 0.1, f64::INFINITY),
    ] {
        assert!(!b.is_valid());
        assert_eq!(
            b.barrier_vertical_fraction(&planet(), &atmosphere(), &horus(), (3.7, 1.0), &n, None),
            None
        );
    }
    let b = barrier(500e3, 2.5, 0.1, 1.0);
    assert_eq!(
        b.barrier_vertical_fraction(&planet(), &atmosphere(), &horus(), (3.7, 0.0), &n, None),
        None,
        "zero drag scale"
    );
}

/// Flown by the numerical predictor, the barrier holds a binding heat-flux limit and a
/// binding g-load limit (the plain flight breaks each by 25 %) within 1 %, and flies farther.
/// Measured: peaks 1.0012 and 1.0004 of the limits (the law is exact only for the model's
/// exponential atmosphere at a fixed polar and small flight-path angles; RK4 steps).
#[test]
fn a_predicted_flight_holds_the_limits_with_the_barrier() {
    let plain = predict(None);
    let q_lim = 0.8 * plain.peak_heat_flux_w_m2;
    let g_lim = 0.8 * plain.peak_g_load;
    let q = predict(Some(barrier(q_lim, 1e6, 0.15, 1.0)));
    let g = predict(Some(barrier(1e12, g_lim, 0.15, 1.0)));
    assert!(
        q.peak_heat_flux_w_m2 <= 1.01 * q_lim,
        "{} / {q_lim}",
        q.peak_heat_flux_w_m2
    );
    assert!(g.peak_g_load <= 1.01 * g_lim, "{} / {g_lim}", g.peak_g_load);
    assert!(q.range_m > plain.range_m && g.range_m > plain.range_m);
    // A loose barrier is the plain prediction bit for bit.
    assert_eq!(predict(Some(barrier(1e12, 1e6, 0.15, 1.0))), plain);
}

/// `ReplanningGuidance` with a barrier caps the bank at every guidance tick, between re-plans
/// too; the commanded bank moves to the cap at the rate limit, never in a step; the
/// equilibrium bound sets no cap.
#[test]
fn replanning_guidance_caps_the_bank_at_every_tick() {
    let total = glide_range_m(0.6) / R_EARTH;
    let cfg = rcfg(
        RangeTarget::FlownRangeAngle { total_rad: total },
        3,
        PredictorMode::Glide,
    );
    // The glide state is nearly circular: 1e-4 g at the limit needs lift-up (cap 0).
    let mut tight = replanning(cfg)
        .with_path_bound(barrier(1e12, 1e-4, 0.15, 1.0), false)
        .unwrap();
    let mut equilibrium = replanning(cfg)
        .with_path_bound(
            PathBound {
                barrier_frequency_rad_s: 0.0,
                ..barrier(1e12, 1e-4, 0.15, 1.0)
            },
            false,
        )
        .unwrap();
    let rate = guidance_core::guidance::GuidanceConfig::<f64>::thesis_default()
        .rates
        .sigma_rad_s;
    let mut last: Option<f64> = None;
    for k in 0..6 {
        let n = glide_nav(2.0 * f64::from(k));
        let out = tight.update(&n).unwrap();
        equilibrium.update(&n).unwrap();
        assert!(out.guidance.ticked);
        assert_eq!(tight.guidance().bank_cap(), Some(0.0), "tick {k}");
        assert_eq!(equilibrium.guidance().bank_cap(), None);
        let s = out.guidance.command.sigma_rad.abs();
        if let Some(p) = last {
            assert!(s <= p + 1e-12, "tick {k}: {s} after {p}");
            assert!(p - s <= rate * 2.0 + 1e-9, "tick {k}: a step {p} -> {s}");
        }
        last = Some(s);
    }
}

/// A barrier makes `ReplanningGuidance` use sensed accelerations without an estimator (it
/// measures its margins with them); sensing then validates the sample; without an estimator
/// or a barrier sensing does nothing.
#[test]
fn a_barrier_uses_sensed_accelerations_without_an_estimator() {
    let total = glide_range_m(0.6) / R_EARTH;
    let cfg = rcfg(
        RangeTarget::FlownRangeAngle { total_rad: total },
        3,
        PredictorMode::Glide,
    );
    let n = glide_nav(0.0);
    let bad = SensedAero {
        lift_m_s2: -1.0,
        drag_m_s2: 1.0,
    };
    let mut plain = replanning(cfg);
    assert!(!plain.uses_sensed());
    assert_eq!(plain.sense(&n, &bad), Ok(None));
    let mut with = replanning(cfg)
        .with_path_bound(barrier(1e12, 2.5, 0.15, 1.0), false)
        .unwrap();
    assert!(with.uses_sensed());
    assert!(with.sense(&n, &bad).is_err());
    let good = SensedAero {
        lift_m_s2: 1.0,
        drag_m_s2: 1.0,
    };
    assert_eq!(with.sense(&n, &good), Ok(None));
}
