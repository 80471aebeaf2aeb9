//! The re-planner with the numerical predictor (`PredictorMode::Numerical`, `Hybrid`,
//! `HybridSink`): converges on the numerical range, the resumable solver and
//! `ReplanningGuidance` with a step budget give the one-shot answer with bounded work per step,
//! and the hybrid modes take the closed forms in their validated domain and the numerical
//! predictor elsewhere.

use crate::vinh_replan::{NO_LIMITS, glide_nav, rcfg, replanning, srm_equilibrium_glide_nav};
use crate::vinh_support::inputs::{atmosphere, horus, lift, planet, srm};
use crate::vinh_support::vehicles::R_EARTH;
use guidance_core::NavState;
use guidance_core::replan::numerical::{MAX_STEPS, STEPS_PER_SOLVER_STEP};
use guidance_core::replan::{
    MAX_PREDICTOR_CALLS, PredictorMode, RangeTarget, ReplanCase, ReplanConfig, ReplanLimits,
    ReplanResult, ReplanSolver, predict_glide_with, predict_glide_with_sink, predict_numerical,
    replan,
};
use guidance_core::vinh::{PeakMode, PredictorConfig, Validity, VehicleParams, predict_with};

const DEG: f64 = std::f64::consts::PI / 180.0;

fn state_nav(alt_km: f64, v: f64, fpa_deg: f64) -> NavState<f64> {
    NavState {
        time_s: 0.0,
        radius_m: R_EARTH + alt_km * 1e3,
        speed_m_s: v,
        flight_path_angle_rad: fpa_deg * DEG,
        heading_rad: 90.0 * DEG,
        latitude_rad: 0.0,
        longitude_rad: 0.0,
    }
}

fn solver_cfg(mode: PredictorMode, f_min: f64) -> ReplanConfig<f64> {
    ReplanConfig {
        lambda: 1.0,
        min_vertical_fraction: f_min,
        max_vertical_fraction: 1.0,
        tolerance_m: 1000.0,
        max_iterations: 30,
        // 2700 m/s: at least 0.34 of the glide start speeds below (the glide's final-speed
        // ratio bound, `vinh::validity::GLIDE_MIN_FINAL_SPEED_RATIO`).
        predictor: PredictorConfig {
            final_speed_m_s: 2700.0,
            max_skips: 4,
        },
        mode,
    }
}

/// Numerical range at fraction `f` from `n`.
fn numerical_range(v: &VehicleParams<f64>, n: &NavState<f64>, f: f64) -> f64 {
    predict_numerical(
        &planet(),
        &atmosphere(),
        v,
        &lift(f),
        &n.entry_state(),
        &solver_cfg(PredictorMode::Numerical, 0.1).predictor,
        PeakMode::RangeOnly,
    )
    .unwrap()
    .range_m
}

trait Entry {
    fn entry_state(&self) -> guidance_core::vinh::EntryState<f64>;
}
impl Entry for NavState<f64> {
    fn entry_state(&self) -> guidance_core::vinh::EntryState<f64> {
        guidance_core::vinh::EntryState {
            radius_m: self.radius_m,
            speed_m_s: self.speed_m_s,
            flight_path_angle_rad: self.flight_path_angle_rad,
        }
    }
}

/// One solve: vehicle, state, target \[m\], limits, settings.
type Case = (
    VehicleParams<f64>,
    NavState<f64>,
    f64,
    ReplanLimits<f64>,
    ReplanConfig<f64>,
);

fn cases() -> Vec<Case> {
    let srm_glide = glide_nav(0.0);
    let last = state_nav(66.0, 3800.0, -0.2);
    let skip = state_nav(122.0, 7400.0, -4.0);
    let horus_entry = state_nav(122.0, 7600.0, -1.2);
    let num = |f| solver_cfg(PredictorMode::Numerical, f);
    let some = ReplanLimits {
        heat_flux_w_m2: predict_numerical(
            &planet(),
            &atmosphere(),
            &srm(),
            &lift(0.5),
            &skip.entry_state(),
            &num(0.1).predictor,
            PeakMode::Full,
        )
        .unwrap()
        .peak_heat_flux_w_m2,
        g_load: 1e3,
    };
    // A case whose target is the numerical range at fraction `f`.
    let at = |v: VehicleParams<f64>, n: NavState<f64>, f, limits, cfg| {
        (v, n, numerical_range(&v, &n, f), limits, cfg)
    };
    vec![
        at(srm(), srm_glide, 0.6, NO_LIMITS, num(0.05)),
        at(srm(), last, 0.5, NO_LIMITS, num(0.1)),
        at(srm(), skip, 0.7, NO_LIMITS, num(0.3)),
        at(srm(), skip, 0.5, some, num(0.3)),
        at(horus(), horus_entry, 0.5, NO_LIMITS, num(0.1)),
        (srm(), last, 1e9, NO_LIMITS, num(0.1)),
        at(
            srm(),
            last,
            0.5,
            NO_LIMITS,
            solver_cfg(PredictorMode::Hybrid, 0.1),
        ),
        at(
            srm(),
            srm_glide,
            0.6,
            NO_LIMITS,
            solver_cfg(PredictorMode::HybridSink, 0.05),
        ),
    ]
}

fn one_shot(c: &Case) -> ReplanResult<f64> {
    let (v, n, target, limits, cfg) = c;
    replan(&planet(), &atmosphere(), v, n, *target, limits, cfg)
}

fn solver(c: &Case) -> ReplanSolver<f64> {
    let (v, n, target, limits, cfg) = c;
    ReplanSolver::new(&planet(), &atmosphere(), v, n, *target, limits, cfg)
}

/// The numerical re-planner converges on the numerical range within the tolerance: the
/// predicted range at the solved fraction meets the target (the numerical predictor's own
/// accuracy is validated in `numerical_predictor`).
#[test]
fn numerical_replan_converges_on_the_numerical_range() {
    for c in cases().into_iter().take(3) {
        let r = one_shot(&c);
        assert_eq!(r.case, ReplanCase::Converged, "{:?}: {r:?}", c.1);
        let p = r.prediction.unwrap();
        assert!(
            (p.range_m - c.2).abs() <= 1000.0,
            "{} vs {}",
            p.range_m,
            c.2
        );
        let again = numerical_range(&c.0, &c.1, r.vertical_fraction);
        assert_eq!(again, p.range_m);
        assert!(r.predictor_calls <= MAX_PREDICTOR_CALLS);
    }
}

/// Stepping the solver gives bit for bit the one-shot result; each step completes at most one
/// prediction and takes at most `STEPS_PER_SOLVER_STEP` integration steps; a numerical
/// prediction spans several steps; a hybrid solve switches to the numerical predictor when
/// the prediction it would fly is extrapolated (the SRM's last 500 km) and integrates nothing
/// when it is in domain.
#[test]
fn resumable_numerical_solver_gives_the_one_shot_answer() {
    let mut seen = std::collections::BTreeSet::new();
    let mut spanned = false;
    let mut hybrid_switched = false;
    for c in cases() {
        let want = one_shot(&c);
        let mut s = solver(&c);
        let mut steps = 0_u32;
        let max_steps_per_prediction = u32::from(MAX_STEPS / STEPS_PER_SOLVER_STEP) + 2;
        let r = loop {
            let (calls, work) = (s.predictor_calls(), s.integration_steps());
            let done = s.step();
            assert!(s.predictor_calls() - calls <= 1);
            assert!(s.integration_steps() - work <= u32::from(STEPS_PER_SOLVER_STEP));
            steps += 1;
            if let Some(r) = done {
                break r;
            }
            assert!(steps <= u32::from(MAX_PREDICTOR_CALLS) * max_steps_per_prediction);
        };
        assert_eq!(r, want, "{:?}", c.4.mode);
        if c.4.mode == PredictorMode::Numerical {
            assert!(s.uses_numerical());
        } else {
            hybrid_switched |= s.uses_numerical();
        }
        assert!(steps >= u32::from(r.predictor_calls));
        spanned |= steps > u32::from(r.predictor_calls);
        assert_eq!(s.integration_steps() > 0, s.uses_numerical());
        seen.insert(format!("{:?}", r.case));
    }
    assert!(spanned, "no numerical prediction spanned several steps");
    assert!(
        hybrid_switched,
        "no hybrid solve switched to the numerical predictor"
    );
    for c in ["Converged", "TargetOutOfReach", "LimitsBind"] {
        assert!(seen.contains(c), "{c} not exercised: {seen:?}");
    }
}

/// `ReplanningGuidance` in `Numerical` mode with `k` solver steps per tick: no tick exceeds
/// `k STEPS_PER_SOLVER_STEP` integration steps, the solve (the first: a cold start) completes
/// with the one-shot bank and calls, in no more ticks than one step of the stepped solver per
/// solver step of budget would take and no fewer than its integration steps need.
#[test]
fn replanning_numerical_with_a_step_budget_matches_one_shot() {
    let total = numerical_range(&srm(), &glide_nav(0.0), 0.6) / R_EARTH;
    let target = RangeTarget::FlownRangeAngle { total_rad: total };
    let mut one = replanning(rcfg(target, 1000, PredictorMode::Numerical));
    let reference = one.update(&glide_nav(0.0)).unwrap().replan.unwrap();
    assert_eq!(reference.case, ReplanCase::Converged);
    let mut s = ReplanSolver::new(
        &planet(),
        &atmosphere(),
        &srm(),
        &glide_nav(0.0),
        total * R_EARTH,
        &NO_LIMITS,
        &rcfg(target, 1000, PredictorMode::Numerical).solver,
    );
    let mut want_ticks = 0_u32;
    while s.step().is_none() {
        want_ticks += 1;
    }
    want_ticks += 1;
    for budget in [1_u8, 2] {
        let mut cfg = rcfg(target, 1000, PredictorMode::Numerical);
        cfg.steps_per_tick = budget;
        let mut g = replanning(cfg);
        let mut done = None;
        let mut work = 0_u32;
        for k in 0..400 {
            let out = g.update(&glide_nav(2.0 * f64::from(k))).unwrap();
            assert!(out.integration_steps <= u32::from(budget) * u32::from(STEPS_PER_SOLVER_STEP));
            work += out.integration_steps;
            if let Some(r) = out.replan {
                done = Some((k, r));
                break;
            }
        }
        let (k, r) = done.expect("the solve completes");
        let per_tick = u32::from(budget) * u32::from(STEPS_PER_SOLVER_STEP);
        let ticks = k + 1;
        assert!(
            ticks <= want_ticks.div_ceil(u32::from(budget)),
            "budget {budget}: {ticks} ticks"
        );
        assert!(
            ticks >= s.integration_steps().div_ceil(per_tick),
            "budget {budget}"
        );
        assert_eq!(r.bank_rad, reference.bank_rad);
        assert_eq!(r.predictor_calls, reference.predictor_calls);
        assert_eq!(work, s.integration_steps());
        assert!(r.applied);
    }
}

/// A warm start ([`ReplanSolver::with_warm_start`]) from a guess near the cold answer, with
/// the slope the cold solve measured, converges within the tolerance in fewer predictor calls
/// than the cold solve, and a guess far off (at a bound) still converges (secant steps, or the
/// cold start); an invalid guess or slope is a cold start, bit for bit.
#[test]
fn warm_start_converges_in_fewer_calls() {
    for c in cases().into_iter().take(3) {
        let mut cold = solver(&c);
        let want = cold.run(u8::MAX).unwrap();
        assert_eq!(want, one_shot(&c));
        assert_eq!(want.case, ReplanCase::Converged);
        let slope = cold.range_slope().expect("the cold solve measures a slope");
        let (f_min, f_max) = (c.4.min_vertical_fraction, c.4.max_vertical_fraction);
        for guess in [want.vertical_fraction * 0.97, f_min, f_max] {
            let mut warm = solver(&c).with_warm_start(guess.clamp(f_min, f_max), slope);
            let r = warm.run(u8::MAX).unwrap();
            assert_eq!(r.case, ReplanCase::Converged, "guess {guess}: {r:?}");
            let p = r.prediction.unwrap();
            assert!((p.range_m - c.2).abs() <= c.4.tolerance_m, "guess {guess}");
            if guess != f_min && guess != f_max {
                assert!(
                    r.predictor_calls < want.predictor_calls,
                    "guess {guess}: {} calls against {} cold",
                    r.predictor_calls,
                    want.predictor_calls
                );
            }
        }
        for (guess, slope) in [(f64::NAN, slope), (f_max + 0.1, slope), (0.5, -slope)] {
            let r = solver(&c)
                .with_warm_start(guess, slope)
                .run(u8::MAX)
                .unwrap();
            assert_eq!(r, want, "guess {guess}, slope {slope}");
        }
    }
}

/// `numerical_from_start` makes a hybrid solve the `Numerical` one bit for bit (it skips the
/// closed-form search a switch would discard) and changes nothing in `Numerical` mode.
#[test]
fn numerical_from_start_is_the_numerical_solve() {
    for c in cases() {
        let mut numerical = c;
        numerical.4.mode = PredictorMode::Numerical;
        let want = one_shot(&numerical);
        let mut s = solver(&c).numerical_from_start();
        let r = s.run(u8::MAX).unwrap();
        if matches!(c.4.mode, PredictorMode::Hybrid | PredictorMode::HybridSink) {
            assert_eq!(r, want, "{:?}", c.4.mode);
            assert!(s.uses_numerical());
        } else {
            assert_eq!(r, one_shot(&c));
        }
    }
}

/// Hybrid: in the closed forms' validated domain (both ends `InDomain`) the solve is the
/// `Auto` one bit for bit; out of it the `Numerical` one.
#[test]
fn hybrid_uses_closed_forms_in_domain_and_numerical_elsewhere() {
    // In domain: the SRM on its equilibrium glide of f = 1 at 90 km, f in [0.95, 1] (glide
    // starts at 89.6-90 km, the chain at f_min and the glide at both ends in domain; at
    // f = 0.7 the 2.6 km offset is a start transient beyond 1 % of the glide's range,
    // `GlideTransient`). Out of domain: the SRM's last 500 km (glide below 80 km) and
    // HORUS-2B's near-circular entry.
    let in_domain = srm_equilibrium_glide_nav(1.0, 90e3);
    let cases: Vec<(VehicleParams<f64>, NavState<f64>, f64, bool)> = vec![
        (srm(), in_domain, 0.95, false),
        (srm(), state_nav(66.0, 3800.0, -0.2), 0.1, true),
        (horus(), state_nav(122.0, 7600.0, -1.2), 0.1, true),
    ];
    for (v, n, f_min, numerical) in cases {
        for (hybrid, auto) in [
            (PredictorMode::Hybrid, PredictorMode::Auto),
            (PredictorMode::HybridSink, PredictorMode::AutoSink),
        ] {
            let target = numerical_range(&v, &n, 0.5 + f_min / 2.0);
            let mk = |mode| {
                ReplanSolver::new(
                    &planet(),
                    &atmosphere(),
                    &v,
                    &n,
                    target,
                    &NO_LIMITS,
                    &solver_cfg(mode, f_min),
                )
            };
            let mut s = mk(hybrid);
            let r = loop {
                if let Some(r) = s.step() {
                    break r;
                }
            };
            assert_eq!(s.uses_numerical(), numerical, "{hybrid:?} at {n:?}");
            let other = if numerical {
                PredictorMode::Numerical
            } else {
                auto
            };
            let mut o = mk(other);
            let ro = loop {
                if let Some(r) = o.step() {
                    break r;
                }
            };
            if numerical {
                // Redone from the start: the same fractions and ranges, more calls.
                assert_eq!(r.vertical_fraction, ro.vertical_fraction);
                assert_eq!(r.case, ro.case);
                assert_eq!(r.prediction, ro.prediction);
                assert!(r.predictor_calls > ro.predictor_calls);
            } else {
                assert_eq!(r, ro);
                // Both ends of the closed form in domain.
                for f in [f_min, 1.0] {
                    let lift = lift(f);
                    let cfg = solver_cfg(auto, f_min).predictor;
                    let state = n.entry_state();
                    // The chain, else the mode's glide (as `Auto`/`AutoSink` predict).
                    let glide = if auto == PredictorMode::Auto {
                        predict_glide_with::<f64>
                    } else {
                        predict_glide_with_sink::<f64>
                    };
                    let p = [predict_with::<f64>, glide]
                        .into_iter()
                        .find_map(|predictor| {
                            predictor(
                                &planet(),
                                &atmosphere(),
                                &v,
                                &lift,
                                &state,
                                &cfg,
                                PeakMode::RangeOnly,
                            )
                            .ok()
                        })
                        .unwrap();
                    assert_eq!(p.validity, Validity::InDomain, "{auto:?} f {f}");
                }
            }
            println!(
                "{hybrid:?} {:.0} m: {:?} ({} calls)",
                n.radius_m - R_EARTH,
                r.case,
                r.predictor_calls
            );
        }
    }
}
