//! The re-planning benchmarks of `insn-bench` (`f32` on both targets): re-planning solves,
//! the largest guidance tick of `ReplanningGuidance` when a solve is spread over ticks, and the
//! onboard aerodynamic estimator fed at every tick.

use cortex_m_semihosting::hprintln;
use guidance_core::NavState;
use guidance_core::energy::{EARTH_MU_M3_S2, EARTH_RADIUS_M, EnergyNormalizer};
use guidance_core::estimate::{
    AeroEstimator, EstimateStatus, EstimatorConfig, SensedAero, expected_aero,
};
use guidance_core::guidance::{Command, GuidanceConfig};
use guidance_core::interp::Interpolation;
use guidance_core::nodes::{AngleBounds, Independent, NodeTable};
use guidance_core::replan::{
    PredictorMode, PredictorModel, RangeTarget, ReplanConfig, ReplanLimits, ReplanningConfig,
    ReplanningGuidance, replan,
};
use guidance_core::vinh::nondim::{EntryState, ExpAtmosphere, LiftControl, Planet};
use guidance_core::vinh::predict::{PredictorConfig, predict};
use onboard_demo::insn::InsnCounter;

use crate::firmware::{INSN_PER_TICK, REPS, srm};

/// Re-planning solves in `f32` (the case of guidance-core's `closed_forms` bench): one that
/// converges, the solver's worst case (tolerance never met, heat-flux limit below every
/// prediction: 58 predictor calls) and a glide-mode solve.
pub(crate) fn bench_replan(c: &mut InsnCounter) -> bool {
    let planet = Planet::<f32>::earth();
    let atm = ExpAtmosphere::<f32>::earth();
    let veh = srm();
    let deg = core::f32::consts::PI / 180.0;
    let nav = |h: f32, v: f32, g_deg: f32| NavState {
        time_s: 0.0,
        radius_m: 6_378_137.0 + h,
        speed_m_s: v,
        flight_path_angle_rad: g_deg * deg,
        heading_rad: 0.0,
        latitude_rad: 0.0,
        longitude_rad: 0.0,
    };
    let predictor = PredictorConfig {
        final_speed_m_s: 2_500.0,
        max_skips: 4,
    };
    let solver = ReplanConfig {
        lambda: 1.0,
        min_vertical_fraction: 0.3,
        max_vertical_fraction: 1.0,
        tolerance_m: 1_000.0,
        max_iterations: 40,
        predictor,
        mode: PredictorMode::Chain,
    };
    let limits = ReplanLimits {
        heat_flux_w_m2: 1e9,
        g_load: 1e3,
    };
    let start = nav(122e3, 7_000.0, -4.0);
    let state = EntryState {
        radius_m: start.radius_m,
        speed_m_s: start.speed_m_s,
        flight_path_angle_rad: start.flight_path_angle_rad,
    };
    let lift = LiftControl {
        lambda: 1.0,
        vertical_fraction: 0.7,
    };
    let Ok(target) = predict(&planet, &atm, &veh, &lift, &state, &predictor).map(|p| p.range_m)
    else {
        return false;
    };
    let mut calls = [0u8; 3];
    let converged = c.ticks(|| {
        let r = replan(
            &planet,
            &atm,
            &veh,
            &core::hint::black_box(start),
            target,
            &limits,
            &solver,
        );
        calls[0] = r.predictor_calls;
    });
    let worst_solver = ReplanConfig {
        tolerance_m: 1e-6,
        ..solver
    };
    let worst_limits = ReplanLimits {
        heat_flux_w_m2: 1.0,
        g_load: 1e3,
    };
    let worst = c.ticks(|| {
        let r = replan(
            &planet,
            &atm,
            &veh,
            &core::hint::black_box(start),
            target,
            &worst_limits,
            &worst_solver,
        );
        calls[1] = r.predictor_calls;
    });
    let glide_solver = ReplanConfig {
        mode: PredictorMode::Glide,
        min_vertical_fraction: 0.05,
        ..solver
    };
    let glide = c.ticks(|| {
        let r = replan(
            &planet,
            &atm,
            &veh,
            &core::hint::black_box(nav(100e3, 7_658.34, -0.056)),
            12_000e3,
            &limits,
            &glide_solver,
        );
        calls[2] = r.predictor_calls;
    });
    hprintln!(
        "bench replan_converged_f32: {} insn/call ({} predictor calls)",
        converged * INSN_PER_TICK,
        calls[0]
    );
    hprintln!(
        "bench replan_worst_case_f32: {} insn/call ({} predictor calls)",
        worst * INSN_PER_TICK,
        calls[1]
    );
    hprintln!(
        "bench replan_glide_mode_f32: {} insn/call ({} predictor calls)",
        glide * INSN_PER_TICK,
        calls[2]
    );
    calls.iter().all(|&n| n > 0)
}

/// The SRM state of the tick benchmarks (122 km, 7 km/s, -4 deg) at mission time `t_s` \[s\].
fn srm_nav(t_s: f32) -> NavState<f32> {
    NavState {
        time_s: t_s,
        radius_m: 6_378_137.0 + 122e3,
        speed_m_s: 7_000.0,
        flight_path_angle_rad: -4.0_f32.to_radians(),
        heading_rad: 0.0,
        latitude_rad: 0.0,
        longitude_rad: 0.0,
    }
}

/// The chain-mode solver of the tick benchmarks (converging to 1 km).
fn tick_solver() -> ReplanConfig<f32> {
    ReplanConfig {
        lambda: 1.0,
        min_vertical_fraction: 0.3,
        max_vertical_fraction: 1.0,
        tolerance_m: 1_000.0,
        max_iterations: 40,
        predictor: PredictorConfig {
            final_speed_m_s: 2_500.0,
            max_skips: 4,
        },
        mode: PredictorMode::Chain,
    }
}

/// `ReplanningGuidance` (f32) of the SRM on a three-node energy table, re-planning at its
/// first tick (one predictor call per tick) with `solver` towards the flown range angle
/// `target_rad` \[rad\] under the heat-flux limit `heat_flux_w_m2` \[W/m^2\]; `None` if a
/// setting is rejected.
pub(crate) fn srm_replanning_guidance(
    solver: ReplanConfig<f32>,
    heat_flux_w_m2: f32,
    target_rad: f32,
) -> Option<ReplanningGuidance<f32>> {
    let bounds = AngleBounds::<f32>::from_deg(0.0, 45.0, -90.0, 90.0).ok()?;
    let rows = [(1.0, 20.0, 0.0), (0.5, 20.0, 45.0), (0.0, 20.0, 45.0)];
    let table = NodeTable::<f32>::from_deg(Independent::NormalizedEnergy, &rows, bounds).ok()?;
    let energy = EnergyNormalizer::<f32>::new(
        EARTH_MU_M3_S2,
        EARTH_RADIUS_M,
        EARTH_RADIUS_M + 122_000.0,
        7_500.0,
    )
    .ok()?;
    let config = ReplanningConfig {
        every_n_ticks: 1000,
        target: RangeTarget::FlownRangeAngle {
            total_rad: target_rad,
        },
        limits: ReplanLimits {
            heat_flux_w_m2,
            g_load: 1e3,
        },
        solver,
        model: PredictorModel {
            planet: Planet::<f32>::earth(),
            atmosphere: ExpAtmosphere::<f32>::earth(),
            vehicle: srm(),
            rotation_rate_rad_s: 0.0,
        },
        apply_out_of_reach: false,
        steps_per_tick: 1,
    };
    let initial = Command {
        alpha_rad: 20.0_f32.to_radians(),
        sigma_rad: 0.0,
    };
    ReplanningGuidance::new(
        GuidanceConfig::thesis_default(),
        table,
        Interpolation::Linear,
        energy,
        initial,
        config,
    )
    .ok()
}

/// Guidance ticks with re-planning spread over ticks (`steps_per_tick = 1`, f32): the largest
/// instruction count of one tick (guidance update plus at most one predictor call) over the
/// whole solve, for the converged and the worst-case solve of [`bench_replan`]; the tick that
/// runs the prediction with peaks is the most expensive.
pub(crate) fn bench_replanning_tick(c: &mut InsnCounter) -> bool {
    let start = srm_nav(0.0);
    let state = EntryState {
        radius_m: start.radius_m,
        speed_m_s: start.speed_m_s,
        flight_path_angle_rad: start.flight_path_angle_rad,
    };
    let lift = LiftControl {
        lambda: 1.0,
        vertical_fraction: 0.7,
    };
    let solver = tick_solver();
    let (planet, atm, veh) = (Planet::<f32>::earth(), ExpAtmosphere::<f32>::earth(), srm());
    let Ok(target) =
        predict(&planet, &atm, &veh, &lift, &state, &solver.predictor).map(|p| p.range_m)
    else {
        return false;
    };
    let cases = [
        (solver, 1e9_f32, "converged"),
        (
            ReplanConfig {
                tolerance_m: 1e-6,
                ..solver
            },
            1.0,
            "worst_case",
        ),
    ];
    let mut ok = true;
    let mut worst = 0_u32;
    for (solver, heat, name) in cases {
        let Some(mut g) = srm_replanning_guidance(solver, heat, target / 6_378_137.0) else {
            return false;
        };
        let mut max = 0_u32;
        let mut done = None;
        let mut k = 0_u16;
        while k < 100 && done.is_none() {
            let n = srm_nav(2.0 * f32::from(k));
            let mut out = None;
            let t = c.ticks(|| out = Some(g.update(&core::hint::black_box(n))));
            max = max.max(t * INSN_PER_TICK);
            match out {
                Some(Ok(o)) => done = o.replan.map(|r| (k, r.predictor_calls)),
                _ => ok = false,
            }
            k += 1;
        }
        let Some((k_done, calls)) = done else {
            return false;
        };
        hprintln!(
            "bench replanning_tick_max_{}_f32: {} insn/call ({} ticks, {} predictor calls)",
            name,
            max,
            k_done + 1,
            calls
        );
        worst = worst.max(max);
    }
    hprintln!("bench replanning_tick_max_f32: {} insn/call", worst);
    ok
}

/// Onboard aerodynamic estimation (f32): one `ReplanningGuidance::sense`, what a guidance tick
/// with an estimator adds (the model's lift and drag at the navigated radius and speed, one
/// exponential and one square root, and the fading-memory update of the L/D and drag scales;
/// the campaigns' default estimator settings). Mean over [`REPS`] samples of a descent from 70
/// to 50 km at 6 to 5 km/s whose sensed accelerations differ from the model (L/D x 1.08,
/// drag x 1.2), built before the measurement, so every sample updates the estimate.
pub(crate) fn bench_estimator(c: &mut InsnCounter) -> bool {
    let config = EstimatorConfig {
        lift_to_drag_gain: 0.1,
        drag_gain: 0.2,
        lift_to_drag_bounds: (0.5, 2.0),
        drag_bounds: (0.3, 3.0),
        min_drag_m_s2: 0.5,
    };
    let (Ok(estimator), Some(g)) = (
        AeroEstimator::new(config),
        srm_replanning_guidance(tick_solver(), 1e9, 0.1),
    ) else {
        return false;
    };
    let mut g = g.with_estimator(estimator);
    let (atm, veh) = (ExpAtmosphere::<f32>::earth(), srm());
    let none = SensedAero {
        lift_m_s2: 0.0,
        drag_m_s2: 0.0,
    };
    let mut samples = [(srm_nav(0.0), none); REPS as usize];
    for (k, s) in (0_u16..).zip(samples.iter_mut()) {
        let f = f32::from(k) / REPS as f32;
        let nav = NavState {
            time_s: 2.0 * f32::from(k),
            radius_m: 6_378_137.0 + 70e3 - 20e3 * f,
            speed_m_s: 6_000.0 - 1_000.0 * f,
            ..srm_nav(0.0)
        };
        let Some(model) = expected_aero(&atm, &veh, 1.0, nav.radius_m, nav.speed_m_s) else {
            return false;
        };
        let sensed = SensedAero {
            lift_m_s2: 1.08 * 1.2 * model.lift_m_s2,
            drag_m_s2: 1.2 * model.drag_m_s2,
        };
        *s = (nav, sensed);
    }
    let mut ok = true;
    let ticks = c.ticks(|| {
        for (nav, sensed) in &samples {
            let r = g.sense(core::hint::black_box(nav), core::hint::black_box(sensed));
            ok &= matches!(r, Ok(Some(EstimateStatus::Updated)));
        }
    });
    let overhead = c.ticks(|| {
        for s in &samples {
            core::hint::black_box(s);
        }
    });
    let per_call = ticks.saturating_sub(overhead) * INSN_PER_TICK / REPS;
    hprintln!("bench estimator_sense_f32: {} insn/call", per_call);
    // The estimate moved towards the sensed world (both scales above 1).
    ok && g
        .aero_scales()
        .is_some_and(|s| s.lift_to_drag > 1.0 && s.drag > 1.0)
}
