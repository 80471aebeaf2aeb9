//! Bounded work per tick (issue 10 item 3): the resumable solver (`ReplanSolver`, one
//! predictor call per step) gives exactly the one-shot `replan` answer, and
//! `ReplanningGuidance` with a per-tick step budget never makes more predictor calls in one
//! tick than the budget, flies the table in use until the solve completes, then applies the
//! same bank as the one-shot re-plan from the same start state. The same for the numerical
//! modes (`Numerical`, `Hybrid`, `HybridSink`: a bounded chunk of integration per step) in
//! `numerical_replan.rs`.

use crate::vinh_replan::{
    DEG, NO_LIMITS, config, energy_table, glide_nav, glide_range_m, glide_solver, nav, range_at,
    rcfg, replanning,
};
use crate::vinh_support::vehicles::{H_S, MU, R_EARTH, RHO0};
use guidance_core::guidance::{Command, Guidance, GuidanceConfig};
use guidance_core::interp::Interpolation;
use guidance_core::replan::{
    MAX_PREDICTOR_CALLS, PredictorMode, RangeTarget, ReplanCase, ReplanConfig, ReplanLimits,
    ReplanSolver, replan,
};
use guidance_core::vinh::{ExpAtmosphere, Planet};
use guidance_core::{NavState, energy::EnergyNormalizer};

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

/// Cases covering every path of the solver: converged (chain and glide), out of reach at
/// both ends, limits binding, limits infeasible with a tolerance never met (the worst case),
/// a fall-back, and the automatic switch from the chain to the glide.
/// One solve: state, target range \[m\], limits, solver settings.
type Case = (NavState<f64>, f64, ReplanLimits<f64>, ReplanConfig<f64>);

fn cases() -> Vec<Case> {
    let n = nav(7000.0, -4.0);
    let t = range_at(&n, 0.7).range_m;
    let tight = ReplanLimits {
        heat_flux_w_m2: 1.0,
        g_load: 1e3,
    };
    let some = ReplanLimits {
        heat_flux_w_m2: range_at(&n, 0.5).peak_heat_flux_w_m2,
        g_load: 1e3,
    };
    let worst = ReplanConfig {
        tolerance_m: 1e-6,
        ..config()
    };
    let glide_target = glide_range_m(0.6);
    vec![
        (n, t, NO_LIMITS, config()),
        (n, 1e9, NO_LIMITS, config()),
        (n, 0.0, NO_LIMITS, config()),
        (n, t, some, config()),
        (n, t, tight, worst),
        (
            glide_nav(0.0),
            glide_target,
            NO_LIMITS,
            glide_solver(PredictorMode::Glide),
        ),
        (
            glide_nav(0.0),
            glide_target,
            NO_LIMITS,
            glide_solver(PredictorMode::Auto),
        ),
        (
            glide_nav(0.0),
            glide_target,
            NO_LIMITS,
            glide_solver(PredictorMode::Chain),
        ),
    ]
}

/// Stepping the solver one predictor call at a time gives bit for bit the one-shot result,
/// every step makes at most one call, and the number of steps is the call count.
#[test]
fn resumable_solver_gives_the_one_shot_answer() {
    let mut seen = std::collections::BTreeSet::new();
    for (n, target, limits, cfg) in cases() {
        let one_shot = replan(
            &planet(),
            &atmosphere(),
            &crate::vinh_replan::srm(),
            &n,
            target,
            &limits,
            &cfg,
        );
        let mut s = ReplanSolver::new(
            &planet(),
            &atmosphere(),
            &crate::vinh_replan::srm(),
            &n,
            target,
            &limits,
            &cfg,
        );
        let mut steps = 0_u32;
        let r = loop {
            let before = s.predictor_calls();
            let done = s.step();
            assert!(s.predictor_calls() - before <= 1);
            steps += 1;
            if let Some(r) = done {
                break r;
            }
            assert!(steps <= u32::from(MAX_PREDICTOR_CALLS));
        };
        assert_eq!(r, one_shot);
        assert!(steps <= u32::from(r.predictor_calls) + 1);
        assert_eq!(s.result(), Some(r));
        seen.insert(format!("{:?}", r.case));
    }
    // Every outcome was exercised.
    for c in [
        "Converged",
        "TargetOutOfReach",
        "LimitsBind",
        "FallBack(LimitsInfeasible)",
    ] {
        assert!(seen.contains(c), "{c} not exercised: {seen:?}");
    }
}

/// `ReplanningGuidance` with budgets of 1 and 3 predictor calls per tick: no tick exceeds the
/// budget; until the solve completes the command is the stored profile's (a plain `Guidance`
/// with the same table); the completed re-plan reports its start tick and applies the bank of
/// the one-shot re-plan of the same start state.
#[test]
fn replanning_with_a_step_budget_matches_one_shot_and_stays_in_budget() {
    let total = glide_range_m(0.6) / R_EARTH;
    let target = RangeTarget::FlownRangeAngle { total_rad: total };
    let mut one_shot = replanning(rcfg(target, 1000, PredictorMode::Glide));
    let reference = one_shot.update(&glide_nav(0.0)).unwrap().replan.unwrap();
    assert_eq!(reference.case, ReplanCase::Converged);
    assert!(reference.predictor_calls > 3, "{reference:?}");
    for budget in [1_u8, 3] {
        let mut cfg = rcfg(target, 1000, PredictorMode::Glide);
        cfg.steps_per_tick = budget;
        let mut g = replanning(cfg);
        let mut stored = Guidance::new(
            GuidanceConfig::thesis_default(),
            energy_table(),
            Interpolation::Linear,
            EnergyNormalizer::new(MU, R_EARTH, R_EARTH + 100e3, 7700.0).unwrap(),
            Command::from_deg(5.0, 10.0).unwrap(),
        )
        .unwrap();
        let mut done = None;
        let mut total_calls = 0_u32;
        for k in 0..40 {
            let t = 2.0 * f64::from(k);
            let out = g.update(&glide_nav(t)).unwrap();
            let plain = stored.update(&glide_nav(t)).unwrap();
            assert!(
                out.predictor_calls <= budget,
                "{} > {budget}",
                out.predictor_calls
            );
            total_calls += u32::from(out.predictor_calls);
            if done.is_none() {
                match out.replan {
                    None => assert_eq!(out.guidance.command, plain.command, "tick {k}"),
                    Some(r) => done = Some((k, r)),
                }
            }
        }
        let (k, r) = done.expect("the solve completes");
        assert_eq!(r.start_tick, 0);
        assert_eq!(r.tick, k);
        assert_eq!(r.case, reference.case);
        assert_eq!(r.bank_rad, reference.bank_rad);
        assert_eq!(r.predictor_calls, reference.predictor_calls);
        assert!(r.applied);
        let want_ticks = u32::from(reference.predictor_calls).div_ceil(u32::from(budget));
        assert_eq!(k + 1, want_ticks, "budget {budget}");
        assert_eq!(total_calls, u32::from(reference.predictor_calls));
        assert!((r.bank_rad - 0.6f64.acos()).abs() < 0.5 * DEG);
    }
}
