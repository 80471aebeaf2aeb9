//! `LiftSchedule`: the numerical predictor's lift parameter against speed (a stored
//! angle-of-attack profile that changes along the flight), in the predictor, the solver and
//! `ReplanningGuidance`; `ReplanningGuidance::with_start_energy`: no re-plan above an E-hat.

use crate::vinh_replan::{NO_LIMITS, glide_nav, rcfg, replanning};
use crate::vinh_support::inputs::{atmosphere, horus, planet};
use crate::vinh_support::vehicles::R_EARTH;
use guidance_core::GuidanceError;
use guidance_core::replan::{
    LiftSchedule, NumericalRun, PredictorMode, RangeTarget, ReplanCase, ReplanConfig, ReplanSolver,
    SCHEDULE_NODES, ScheduleNode,
};
use guidance_core::vinh::{EntryState, LiftControl, PeakMode, Prediction, PredictorConfig};

const DEG: f64 = std::f64::consts::PI / 180.0;

/// HORUS-2B-like: lambda 3.7 (alpha 40 deg) down to 4 km/s, then a ramp to 0.55 at 800 m/s.
fn horus_like() -> LiftSchedule<f64> {
    LiftSchedule::linear(4000.0, 3.7, 800.0, 0.55)
}

#[test]
fn lift_schedule_is_linear_in_speed_and_bounded() {
    let s = horus_like();
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
        LiftSchedule::linear(4000.0, 3.7, 4000.0, 0.55),
        LiftSchedule::linear(4000.0, 3.7, -1.0, 0.55),
        LiftSchedule::linear(4000.0, 3.7, 800.0, -0.1),
        LiftSchedule::linear(4000.0, f64::NAN, 800.0, 0.55),
        LiftSchedule::linear(f64::INFINITY, 3.7, 800.0, 0.55),
        LiftSchedule { len: 1, ..s },
        LiftSchedule { len: 99, ..s },
    ] {
        assert!(!bad.is_valid(), "{bad:?}");
        let l = bad.lambda_at(3000.0);
        let nan_node = bad.nodes.iter().any(|n| n.lambda.is_nan());
        assert!(!l.is_nan() || nan_node, "{bad:?}: {l}");
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
    let flat = LiftSchedule::linear(4000.0, 3.7, 800.0, 3.7);
    assert_eq!(predict(3.7, Some(flat)), predict(3.7, None));
    let invalid = LiftSchedule::linear(4000.0, 3.7, 9000.0, 0.55);
    assert_eq!(predict(3.7, Some(invalid)), predict(3.7, None));
    // The schedule replaces the constant (whatever it is).
    assert_eq!(
        predict(1.0, Some(horus_like())),
        predict(3.7, Some(horus_like()))
    );
    let held = predict(3.7, None).range_m;
    let ramp = predict(3.7, Some(horus_like())).range_m;
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
    let num_s = solve(PredictorMode::Numerical, Some(horus_like()));
    assert_eq!(num.case, ReplanCase::Converged, "{num:?}");
    assert_eq!(num_s.case, ReplanCase::Converged, "{num_s:?}");
    // Higher L/D at low speed: less vertical lift needed for the same range.
    assert!(
        num_s.vertical_fraction < num.vertical_fraction,
        "{num_s:?} {num:?}"
    );
    let glide = solve(PredictorMode::Glide, None);
    assert_eq!(solve(PredictorMode::Glide, Some(horus_like())), glide);
}

/// `ReplanningGuidance`: an invalid schedule or a non-finite start E-hat is refused; with a
/// start E-hat below the state's, the ticks fly the table without a re-plan.
#[test]
fn replanning_guidance_start_energy_and_schedule() {
    let target = RangeTarget::FlownRangeAngle { total_rad: 0.3 };
    let cfg = rcfg(target, 1, PredictorMode::Numerical);
    let bad = LiftSchedule::linear(4000.0, 3.7, 5000.0, 0.55);
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
        .with_lift_schedule(horus_like())
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

fn node(speed_m_s: f64, lambda: f64, drag_scale: f64) -> ScheduleNode<f64> {
    ScheduleNode {
        speed_m_s,
        lambda,
        drag_scale,
    }
}

/// A many-node schedule: the node values at the nodes, linear between them, the end values
/// beyond, within the neighbouring nodes' values for any speed; bad nodes are typed errors.
#[test]
fn aero_schedule_interpolates_its_nodes_and_is_bounded() {
    let nodes = [
        node(7000.0, 3.7, 1.0),
        node(4000.0, 3.7, 1.1),
        node(2000.0, 2.0, 1.4),
        node(800.0, 0.55, 2.0),
    ];
    let s = LiftSchedule::from_nodes(&nodes).unwrap();
    assert!(s.is_valid());
    assert_eq!(s.used(), &nodes[..]);
    for n in &nodes {
        assert_eq!(s.at(n.speed_m_s), (n.lambda, n.drag_scale));
    }
    assert_eq!(s.at(9000.0), (3.7, 1.0));
    assert_eq!(s.at(100.0), (0.55, 2.0));
    assert_eq!(s.at(f64::NAN), (0.55, 2.0));
    assert_eq!(s.at(f64::INFINITY), (3.7, 1.0));
    let (l, d) = s.at(3000.0);
    assert!(
        (l - 2.85).abs() < 1e-12 && (d - 1.25).abs() < 1e-12,
        "{l} {d}"
    );
    let (l, d) = s.at(1400.0);
    assert!(
        (l - 1.275).abs() < 1e-12 && (d - 1.7).abs() < 1e-12,
        "{l} {d}"
    );
    for i in 0..=800 {
        let v = 10.0 * f64::from(i);
        let (l, d) = s.at(v);
        assert!(
            (0.55..=3.7).contains(&l) && (1.0..=2.0).contains(&d),
            "{v}: {l} {d}"
        );
        // Between the two nodes around v.
        if let Some(w) = nodes
            .windows(2)
            .find(|w| v <= w[0].speed_m_s && v >= w[1].speed_m_s)
        {
            let inside = |x: f64, a: f64, b: f64| x >= a.min(b) && x <= a.max(b);
            assert!(inside(l, w[0].lambda, w[1].lambda), "{v}: {l}");
            assert!(inside(d, w[0].drag_scale, w[1].drag_scale), "{v}: {d}");
        }
    }
    assert_eq!(s.drag_scale_at(3000.0), s.at(3000.0).1);
    assert_eq!(s.lambda_at(3000.0), s.at(3000.0).0);
    use guidance_core::replan::LiftScheduleError::{InvalidNode, NodeCount};
    assert_eq!(LiftSchedule::from_nodes(&nodes[..1]).err(), Some(NodeCount));
    assert_eq!(
        LiftSchedule::from_nodes(&[node(1.0, 1.0, 1.0); SCHEDULE_NODES + 1]).err(),
        Some(NodeCount)
    );
    for bad in [
        [node(800.0, 3.7, 1.0), node(4000.0, 0.55, 1.0)],
        [node(4000.0, 3.7, 0.0), node(800.0, 0.55, 1.0)],
        [node(4000.0, 3.7, 1.0), node(800.0, 0.55, f64::NAN)],
        [node(4000.0, 3.7, 1.0), node(800.0, 0.55, f64::INFINITY)],
    ] {
        assert_eq!(LiftSchedule::from_nodes(&bad).err(), Some(InvalidNode));
    }
}

/// Drag scales of 1 and a flat lift parameter over all nodes are the constant-lambda
/// prediction bit for bit, and a two-node schedule from nodes is the linear one; more drag
/// (scale 1.3) or less lift (lambda scaled by 0.8) flies a shorter range.
#[test]
fn flat_aero_schedule_is_the_constant_bit_for_bit() {
    let flat: Vec<_> = (0..SCHEDULE_NODES)
        .map(|i| node(7500.0 - 600.0 * i as f64, 3.7, 1.0))
        .collect();
    let flat = LiftSchedule::from_nodes(&flat).unwrap();
    assert_eq!(predict(3.7, Some(flat)), predict(3.7, None));
    let two = LiftSchedule::from_nodes(&[node(4000.0, 3.7, 1.0), node(800.0, 0.55, 1.0)]).unwrap();
    assert_eq!(two, horus_like());
    assert_eq!(predict(3.7, Some(two)), predict(3.7, Some(horus_like())));
    let scaled = |lambda: f64, drag: f64| {
        let n: Vec<_> = (0..SCHEDULE_NODES)
            .map(|i| node(7500.0 - 600.0 * i as f64, lambda, drag))
            .collect();
        predict(3.7, Some(LiftSchedule::from_nodes(&n).unwrap())).range_m
    };
    let base = predict(3.7, None).range_m;
    assert!(scaled(3.7, 1.3) < 0.9 * base, "{} {base}", scaled(3.7, 1.3));
    // lambda 3.7 -> 2.96 with the drag of lambda 3.7: less lift at the same drag.
    let d37 = (1.0 + 3.7 * 3.7) / (1.0 + 2.96 * 2.96);
    assert!(
        scaled(2.96, d37) < 0.95 * base,
        "{} {base}",
        scaled(2.96, d37)
    );
}
