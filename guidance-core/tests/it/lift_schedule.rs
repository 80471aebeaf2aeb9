//! `LiftSchedule`: the numerical predictor's lift parameter against speed (a stored
//! angle-of-attack profile that changes along the flight), in the predictor, the solver and
//! `ReplanningGuidance`; `ReplanningGuidance::with_start_energy`: no re-plan above an E-hat.

use crate::vinh_replan::{NO_LIMITS, glide_nav, rcfg, replanning};
use crate::vinh_support::inputs::{atmosphere, horus, planet};
use crate::vinh_support::vehicles::R_EARTH;
use guidance_core::GuidanceError;
use guidance_core::replan::{
    LiftSchedule, NumericalRun, PredictorMode, RangeTarget, ReplanCase, ReplanConfig, ReplanSolver,
};
use guidance_core::vinh::{EntryState, LiftControl, PeakMode, Prediction, PredictorConfig};

const DEG: f64 = std::f64::consts::PI / 180.0;

/// HORUS-2B-like: lambda 3.7 (alpha 40 deg) down to 4 km/s, then a ramp to 0.55 at 800 m/s.
const HORUS_LIKE: LiftSchedule<f64> = LiftSchedule {
    speed_high_m_s: 4000.0,
    lambda_high: 3.7,
    speed_low_m_s: 800.0,
    lambda_low: 0.55,
};

#[test]
fn lift_schedule_is_linear_in_speed_and_bounded() {
    let s = HORUS_LIKE;
    assert!(s.is_valid());
    assert_eq!(s.lambda_at(7000.0), 3.7);
    assert_eq!(s.lambda_at(4000.0), 3.7);
    assert_eq!(s.lambda_at(800.0), 0.55);
    assert_eq!(s.lambda_at(100.0), 0.55);
    let mid = s.lambda_at(2400.0);
    assert!((mid - 0.5 * (3.7 + 0.55)).abs() < 1e-12, "{mid}");
    assert_eq!(s.lambda_at(f64::NAN), 0.55);
    assert_eq!(s.lambda_at(f64::INFINITY), 3.7);
    assert_eq!(s.lambda_at(f64::NEG_INFINITY), 0.55);
    for bad in [
        LiftSchedule {
            speed_low_m_s: 4000.0,
            ..s
        },
        LiftSchedule {
            speed_low_m_s: -1.0,
            ..s
        },
        LiftSchedule {
            lambda_low: -0.1,
            ..s
        },
        LiftSchedule {
            lambda_high: f64::NAN,
            ..s
        },
        LiftSchedule {
            speed_high_m_s: f64::INFINITY,
            ..s
        },
    ] {
        assert!(!bad.is_valid(), "{bad:?}");
        let l = bad.lambda_at(3000.0);
        assert!(!l.is_nan() || bad.lambda_high.is_nan(), "{bad:?}: {l}");
    }
}

fn horus_entry() -> EntryState<f64> {
    EntryState {
        radius_m: R_EARTH + 75e3,
        speed_m_s: 7000.0,
        flight_path_angle_rad: -0.2 * DEG,
    }
}

fn predict(lambda: f64, schedule: Option<LiftSchedule<f64>>) -> Prediction<f64> {
    let run = NumericalRun::new(
        &planet(),
        &atmosphere(),
        &horus(),
        &LiftControl {
            lambda,
            vertical_fraction: 0.6,
        },
        &horus_entry(),
        &PredictorConfig {
            final_speed_m_s: 780.0,
            max_skips: 4,
        },
        PeakMode::Full,
    )
    .unwrap();
    let mut run = match schedule {
        Some(s) => run.with_lift_schedule(s),
        None => run,
    };
    run.advance(u16::MAX).unwrap().unwrap()
}

/// A flat schedule is the constant lambda bit for bit; an invalid one is ignored; the ramp to a
/// lift parameter nearer 1 (a higher L/D) at low speed flies farther than holding 3.7, and not
/// as far as holding the maximum L/D.
#[test]
fn numerical_prediction_follows_the_schedule() {
    let flat = LiftSchedule {
        lambda_high: 3.7,
        lambda_low: 3.7,
        ..HORUS_LIKE
    };
    assert_eq!(predict(3.7, Some(flat)), predict(3.7, None));
    let invalid = LiftSchedule {
        speed_low_m_s: 9000.0,
        ..HORUS_LIKE
    };
    assert_eq!(predict(3.7, Some(invalid)), predict(3.7, None));
    // The schedule replaces the constant (whatever it is).
    assert_eq!(
        predict(1.0, Some(HORUS_LIKE)),
        predict(3.7, Some(HORUS_LIKE))
    );
    let held = predict(3.7, None).range_m;
    let ramp = predict(3.7, Some(HORUS_LIKE)).range_m;
    let best = predict(1.0, None).range_m;
    assert!(held < ramp && ramp < best, "{held} {ramp} {best}");
    assert!(ramp - held > 50e3, "the ramp adds {} m", ramp - held);
}

/// The solver's numerical predictions follow the schedule; its closed-form ones do not.
#[test]
fn solver_applies_the_schedule_to_numerical_predictions_only() {
    let nav = glide_nav(0.0);
    let cfg = |mode| ReplanConfig {
        lambda: 3.7,
        min_vertical_fraction: 0.1,
        max_vertical_fraction: 1.0,
        tolerance_m: 1000.0,
        max_iterations: 30,
        predictor: PredictorConfig {
            final_speed_m_s: 780.0,
            max_skips: 4,
        },
        mode,
    };
    let solve = |mode, schedule: Option<LiftSchedule<f64>>| {
        let s = ReplanSolver::new(
            &planet(),
            &atmosphere(),
            &horus(),
            &nav,
            6000e3,
            &NO_LIMITS,
            &cfg(mode),
        );
        let mut s = match schedule {
            Some(l) => s.with_lift_schedule(l),
            None => s,
        };
        s.run(u8::MAX).unwrap()
    };
    let num = solve(PredictorMode::Numerical, None);
    let num_s = solve(PredictorMode::Numerical, Some(HORUS_LIKE));
    assert_eq!(num.case, ReplanCase::Converged, "{num:?}");
    assert_eq!(num_s.case, ReplanCase::Converged, "{num_s:?}");
    // Higher L/D at low speed: less vertical lift needed for the same range.
    assert!(
        num_s.vertical_fraction < num.vertical_fraction,
        "{num_s:?} {num:?}"
    );
    let glide = solve(PredictorMode::Glide, None);
    assert_eq!(solve(PredictorMode::Glide, Some(HORUS_LIKE)), glide);
}

/// `ReplanningGuidance`: an invalid schedule or a non-finite start E-hat is refused; with a
/// start E-hat below the state's, the ticks fly the table without a re-plan.
#[test]
fn replanning_guidance_start_energy_and_schedule() {
    let target = RangeTarget::FlownRangeAngle { total_rad: 0.3 };
    let cfg = rcfg(target, 1, PredictorMode::Numerical);
    let bad = LiftSchedule {
        speed_low_m_s: 5000.0,
        speed_high_m_s: 4000.0,
        ..HORUS_LIKE
    };
    assert_eq!(
        replanning(cfg).with_lift_schedule(bad).err(),
        Some(GuidanceError::InvalidConfig)
    );
    assert_eq!(
        replanning(cfg).with_start_energy(f64::NAN).err(),
        Some(GuidanceError::InvalidConfig)
    );
    let mut late = replanning(cfg).with_start_energy(0.5).unwrap();
    let mut now = replanning(cfg)
        .with_lift_schedule(HORUS_LIKE)
        .unwrap()
        .with_start_energy(1.0)
        .unwrap();
    for i in 0..3 {
        let nav = glide_nav(2.0 * f64::from(i));
        assert!(late.update(&nav).unwrap().replan.is_none(), "tick {i}");
        assert!(now.update(&nav).unwrap().replan.is_some(), "tick {i}");
    }
    assert_eq!(late.counts().replans, 0);
    assert_eq!(now.counts().replans, 3);
}
