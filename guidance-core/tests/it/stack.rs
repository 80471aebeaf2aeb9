//! The flight stack: [`FlightStack::tick`] flies exactly what the layers assembled by hand fly
//! (profile, re-planner, lateral logic, estimator, path bound), masks switch layers off, bad
//! configurations get a typed error naming the layer, and a failed tick leaves the lateral
//! state as it was.

use guidance_core::estimate::{EstimatorConfig, SensedAero};
use guidance_core::guidance::{Command, Guidance, GuidanceConfig};
use guidance_core::interp::Interpolation;
use guidance_core::lateral::{BankReversalLogic, Corridor, CorridorAxis, LateralConfig};
use guidance_core::replan::{
    PathBound, PredictorMode, RangeTarget, ReplanLimits, ReplanningConfig, TargetPoint,
};
use guidance_core::stack::{
    BarrierLayer, FlightStack, LateralLayer, Layer, Layers, ProfileLayer, ReplanLayer,
    StackBuildError, StackConfig,
};
use guidance_core::{GuidanceError, NavState};

use crate::vinh_replan::{energy_table, glide_nav, model, normalizer, rcfg};

const DEG: f64 = core::f64::consts::PI / 180.0;

fn target() -> TargetPoint<f64> {
    TargetPoint {
        latitude_rad: 2.0 * DEG,
        longitude_rad: 25.0 * DEG,
    }
}

fn lateral() -> LateralLayer<f64> {
    LateralLayer {
        corridor: Corridor {
            axis: CorridorAxis::Speed,
            x_high: 7700.0,
            width_high_rad: 6.0 * DEG,
            x_low: 3000.0,
            width_low_rad: 2.0 * DEG,
        },
        hysteresis_rad: 0.5 * DEG,
        max_reversals: 6,
        freeze_angle_rad: 0.2 * DEG,
        terminal: None,
    }
}

fn estimator() -> EstimatorConfig<f64> {
    EstimatorConfig {
        lift_to_drag_gain: 0.3,
        drag_gain: 0.3,
        lift_to_drag_bounds: (0.5, 2.0),
        drag_bounds: (0.3, 3.0),
        min_drag_m_s2: 0.0,
    }
}

fn bound() -> PathBound<f64> {
    PathBound {
        limits: ReplanLimits {
            heat_flux_w_m2: 2e6,
            g_load: 3.0,
        },
        descent_time_s: 0.0,
        barrier_frequency_rad_s: 0.15,
        barrier_damping: 0.8,
    }
}

/// The re-planner of `vinh_replan` aimed at [`target`] (every 3rd tick, the sink mode).
fn replanning() -> ReplanningConfig<f64> {
    rcfg(RangeTarget::Point(target()), 3, PredictorMode::AutoSink)
}

pub(crate) fn full() -> StackConfig<f64> {
    let r = replanning();
    StackConfig {
        profile: ProfileLayer {
            guidance: GuidanceConfig::thesis_default(),
            table: energy_table(),
            interpolation: Interpolation::Linear,
            energy: normalizer(),
            initial: Command::from_deg(5.0, 10.0).unwrap(),
        },
        replan: Some(ReplanLayer {
            every_n_ticks: r.every_n_ticks,
            limits: r.limits,
            solver: r.solver,
            model: r.model,
            apply_out_of_reach: r.apply_out_of_reach,
            steps_per_tick: r.steps_per_tick,
            lift_schedule: None,
            start_normalized_energy: None,
            numerical_rotation: false,
            bank_shape: false,
            final_energy_j_kg: None,
        }),
        lateral: Some(lateral()),
        estimator: Some(estimator()),
        barrier: Some(BarrierLayer {
            bound: bound(),
            predicted: false,
        }),
        target: Some(RangeTarget::Point(target())),
    }
}

/// A descent along the equator heading east, turning slowly left and right so that the
/// corridor reverses: one sample per 2 s tick.
pub(crate) fn samples() -> impl Iterator<Item = NavState<f64>> {
    (0..120).map(|k| {
        let t = 2.0 * f64::from(k);
        let mut n = glide_nav(t);
        n.radius_m -= 250.0 * t;
        n.speed_m_s -= 15.0 * t;
        n.longitude_rad = 0.0012 * t * DEG * 10.0;
        n.heading_rad = (90.0 + 12.0 * (t / 60.0).sin()) * DEG;
        n
    })
}

/// Sensed accelerations that differ from the model (not the model's own, so the estimate moves).
pub(crate) fn sensed(n: &NavState<f64>) -> SensedAero<f64> {
    let m = model();
    let e = guidance_core::estimate::expected_aero(
        &m.atmosphere,
        &m.vehicle,
        1.0,
        n.radius_m,
        n.speed_m_s,
    )
    .unwrap();
    SensedAero {
        lift_m_s2: e.lift_m_s2 * 1.2,
        drag_m_s2: e.drag_m_s2 * 1.1,
    }
}

/// The full stack is the layers assembled by hand (the assembly the host did before the
/// stack existed), bit for bit: commands, re-plans, reversals, estimate.
#[test]
fn full_stack_flies_exactly_the_hand_assembled_layers() {
    let cfg = full();
    let mut stack = FlightStack::new(&cfg).unwrap();
    let mut g = crate::vinh_replan::replanning(replanning())
        .with_estimator(guidance_core::estimate::AeroEstimator::new(estimator()).unwrap())
        .with_path_bound(bound(), false)
        .unwrap();
    let mut logic = BankReversalLogic::new(LateralConfig {
        target: target(),
        corridor: lateral().corridor,
        hysteresis_rad: lateral().hysteresis_rad,
        max_reversals: lateral().max_reversals,
        freeze_angle_rad: lateral().freeze_angle_rad,
    })
    .unwrap();
    let (mut replans, mut reversals) = (0, 0);
    for n in samples() {
        let s = sensed(&n);
        let out = stack.tick(&n, Some(&s)).unwrap();
        g.sense(&n, &s).unwrap();
        let status = logic.update(&n).unwrap();
        g.set_bank_sign(Some(status.sign));
        let hand = g.update(&n).unwrap();
        assert_eq!(out.command, hand.guidance.command, "t = {}", n.time_s);
        assert_eq!(out.replan, hand.replan);
        assert_eq!(out.lateral, Some(status));
        assert!(out.ticked);
        replans += usize::from(out.replan.is_some());
        reversals += usize::from(status.reversed);
    }
    assert_eq!(stack.aero_scales(), g.aero_scales());
    assert_eq!(stack.reversals(), logic.reversals());
    assert_eq!(stack.replan_counts(), Some(g.counts()));
    assert!(replans > 10, "{replans} re-plans");
    assert!(reversals >= 1, "{reversals} reversals");
    assert_ne!(stack.aero_scales().unwrap().drag, 1.0, "the estimate moved");
}

/// The profile alone is [`Guidance`] itself; the sensed accelerations are not used.
#[test]
fn profile_only_stack_is_the_stored_guidance() {
    let cfg = full().masked(Layers::PROFILE);
    assert_eq!(cfg.layers(), Layers::PROFILE);
    let mut stack = FlightStack::new(&cfg).unwrap();
    assert!(!stack.uses_sensed());
    let p = &cfg.profile;
    let mut g = Guidance::new(
        p.guidance,
        p.table.clone(),
        p.interpolation,
        p.energy,
        p.initial,
    )
    .unwrap();
    for n in samples() {
        let out = stack.tick(&n, Some(&sensed(&n))).unwrap();
        assert_eq!(out.command, g.update(&n).unwrap().command);
        assert_eq!(
            (out.replan, out.lateral, out.aero_scales),
            (None, None, None)
        );
    }
}

/// Masks: off layers are gone, the re-planner's parts go with it, and the sink is dropped
/// with the estimator.
#[test]
fn masks_switch_layers_off() {
    let c = full();
    assert_eq!(c.layers(), Layers::ALL);
    let no_est = c.masked(Layers {
        estimator: false,
        ..Layers::ALL
    });
    assert!(no_est.estimator.is_none() && no_est.barrier.is_some());
    assert_eq!(no_est.replan.unwrap().solver.mode, PredictorMode::Auto);
    assert_eq!(c.replan.unwrap().solver.mode, PredictorMode::AutoSink);
    let no_replan = c.masked(Layers {
        replan: false,
        ..Layers::ALL
    });
    assert_eq!(
        no_replan.layers(),
        Layers {
            lateral: true,
            ..Layers::PROFILE
        }
    );
    assert!(FlightStack::new(&no_replan).is_ok());
    // A layer absent stays absent.
    let lateral_only = no_replan.masked(Layers::ALL);
    assert_eq!(lateral_only, no_replan);
    assert_eq!(
        c.replanning_config().unwrap(),
        ReplanningConfig {
            target: RangeTarget::Point(target()),
            ..replanning()
        }
    );
}

/// Bad assemblies are refused with the layer named.
#[test]
fn bad_configurations_name_the_layer() {
    let mut c = full();
    c.replan = None;
    assert_eq!(
        FlightStack::new(&c).err(),
        Some(StackBuildError::NeedsReplan(Layer::Estimator))
    );
    c.estimator = None;
    assert_eq!(
        FlightStack::new(&c).err(),
        Some(StackBuildError::NeedsReplan(Layer::Barrier))
    );
    let mut c = full();
    c.target = None;
    assert_eq!(
        FlightStack::new(&c).err(),
        Some(StackBuildError::NeedsTarget(Layer::Lateral))
    );
    c.target = Some(RangeTarget::FlownRangeAngle { total_rad: 0.3 });
    assert_eq!(
        FlightStack::new(&c).err(),
        Some(StackBuildError::NeedsTarget(Layer::Lateral))
    );
    c.lateral = None;
    assert!(
        FlightStack::new(&c).is_ok(),
        "the re-planner alone flies a range"
    );
    c.target = None;
    assert_eq!(
        FlightStack::new(&c).err(),
        Some(StackBuildError::NeedsTarget(Layer::Replan))
    );
    let mut c = full();
    c.lateral.as_mut().unwrap().hysteresis_rad = f64::NAN;
    assert_eq!(
        FlightStack::new(&c).err(),
        Some(StackBuildError::Rejected {
            layer: Layer::Lateral,
            source: GuidanceError::InvalidConfig
        })
    );
    let mut c = full();
    c.estimator.as_mut().unwrap().drag_gain = 0.0;
    assert!(matches!(
        FlightStack::new(&c).err(),
        Some(StackBuildError::Rejected {
            layer: Layer::Estimator,
            ..
        })
    ));
    let mut c = full();
    c.barrier.as_mut().unwrap().bound.descent_time_s = -1.0;
    assert!(matches!(
        FlightStack::new(&c).err(),
        Some(StackBuildError::Rejected {
            layer: Layer::Barrier,
            ..
        })
    ));
    let mut c = full();
    c.profile.guidance.period_s = 0.0;
    assert!(matches!(
        FlightStack::new(&c).err(),
        Some(StackBuildError::Rejected {
            layer: Layer::Profile,
            ..
        })
    ));
}

/// A bad state is an error that changes nothing: the next good sample flies as if the bad one
/// never came; an invalid measurement is reported and not used, the tick goes on.
#[test]
fn a_failed_tick_changes_nothing_and_a_bad_measurement_is_not_used() {
    let mut a = FlightStack::new(&full()).unwrap();
    let mut b = a.clone();
    for (i, n) in samples().enumerate() {
        if i % 7 == 3 {
            let mut bad = n;
            bad.heading_rad = f64::NAN;
            assert_eq!(
                a.tick(&bad, Some(&sensed(&n))).err(),
                Some(GuidanceError::NonFiniteState)
            );
            assert_eq!(a, b);
            let nan = SensedAero {
                lift_m_s2: f64::NAN,
                drag_m_s2: 1.0,
            };
            let mut c = a.clone();
            let out = c.tick(&n, Some(&nan)).unwrap();
            assert!(out.sensed_rejected.is_some() && out.estimate.is_none());
            assert!(out.command.is_finite());
        }
        let s = sensed(&n);
        assert_eq!(a.tick(&n, Some(&s)), b.tick(&n, Some(&s)));
    }
}

/// Between ticks the stack holds its command; the lateral logic and the estimator run only
/// on ticks.
#[test]
fn between_ticks_only_the_hold_runs() {
    let mut s = FlightStack::new(&full()).unwrap();
    let n0 = glide_nav(0.0);
    assert!(s.tick(&n0, Some(&sensed(&n0))).unwrap().ticked);
    let scales = s.aero_scales();
    let mut n1 = n0;
    n1.time_s = 1.0;
    let out = s.tick(&n1, Some(&sensed(&n1))).unwrap();
    assert!(!out.ticked);
    assert_eq!((out.lateral, out.estimate), (None, None));
    assert_eq!(s.aero_scales(), scales);
    assert_eq!(out.command, s.command());
}
