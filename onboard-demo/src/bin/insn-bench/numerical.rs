//! The numerical-predictor benchmarks of `insn-bench` (`f32` on both targets): one numerical
//! prediction of the SRM glide, a converged re-plan in `PredictorMode::Numerical`, and the
//! largest guidance tick of `ReplanningGuidance` in that mode with one solver step per tick.

use cortex_m_semihosting::hprintln;
use guidance_core::NavState;
use guidance_core::replan::numerical::NumericalRun;
use guidance_core::replan::{PredictorMode, ReplanConfig, ReplanLimits, replan};
use guidance_core::vinh::nondim::{EntryState, ExpAtmosphere, LiftControl, Planet};
use guidance_core::vinh::predict::{PeakMode, PredictorConfig};
use onboard_demo::insn::InsnCounter;

use crate::firmware::{INSN_PER_TICK, srm};
use crate::replanning::srm_replanning_guidance;

/// The SRM glide entry of thesis sec. 9.2 (100 km, 7658.34 m/s, -0.056 deg): the longest
/// numerical prediction of the re-planning set-ups (about 16 000 km to 2.5 km/s).
fn glide_nav() -> NavState<f32> {
    NavState {
        time_s: 0.0,
        radius_m: 6_378_137.0 + 100e3,
        speed_m_s: 7_658.34,
        flight_path_angle_rad: -0.056_f32.to_radians(),
        heading_rad: 0.0,
        latitude_rad: 0.0,
        longitude_rad: 0.0,
    }
}

fn entry(n: &NavState<f32>) -> EntryState<f32> {
    EntryState {
        radius_m: n.radius_m,
        speed_m_s: n.speed_m_s,
        flight_path_angle_rad: n.flight_path_angle_rad,
    }
}

fn predictor() -> PredictorConfig<f32> {
    PredictorConfig {
        final_speed_m_s: 2_500.0,
        max_skips: 4,
    }
}

/// Numerical range \[m\] and integration steps from `n` at vertical fraction `f`.
fn range(n: &NavState<f32>, f: f32, peaks: PeakMode<f32>) -> Option<(f32, u16)> {
    let lift = LiftControl {
        lambda: 1.0,
        vertical_fraction: f,
    };
    let mut run = NumericalRun::new(
        &Planet::earth(),
        &ExpAtmosphere::earth(),
        &srm(),
        &lift,
        &entry(n),
        &predictor(),
        peaks,
    )
    .ok()?;
    let p = run.advance(u16::MAX)?.ok()?;
    Some((p.range_m, run.steps()))
}

/// One numerical prediction with peaks (SRM glide, `f = 0.6`) and a converged re-plan in
/// `PredictorMode::Numerical` (target: the numerical range at `f = 0.6`, `f` in `[0.05, 1]`,
/// 1 km).
pub(crate) fn bench_numerical(c: &mut InsnCounter) -> bool {
    let n = glide_nav();
    let mut steps = 0_u16;
    let mut out = None;
    let one = c.ticks(|| out = range(&core::hint::black_box(n), 0.6, PeakMode::Full));
    if let Some((_, s)) = out {
        steps = s;
    }
    hprintln!(
        "bench numerical_prediction_f32: {} insn/call ({} integration steps)",
        one * INSN_PER_TICK,
        steps
    );
    let Some((target, _)) = range(&n, 0.6, PeakMode::RangeOnly) else {
        return false;
    };
    let solver = ReplanConfig {
        lambda: 1.0,
        min_vertical_fraction: 0.05,
        max_vertical_fraction: 1.0,
        tolerance_m: 1_000.0,
        max_iterations: 40,
        predictor: predictor(),
        mode: PredictorMode::Numerical,
    };
    let limits = ReplanLimits {
        heat_flux_w_m2: 1e9,
        g_load: 1e3,
    };
    let mut calls = 0_u8;
    let mut converged = false;
    let t = c.ticks(|| {
        let r = replan(
            &Planet::earth(),
            &ExpAtmosphere::earth(),
            &srm(),
            &core::hint::black_box(n),
            target,
            &limits,
            &solver,
        );
        calls = r.predictor_calls;
        converged = r.case == guidance_core::replan::ReplanCase::Converged;
    });
    hprintln!(
        "bench replan_numerical_converged_f32: {} insn/call ({} predictor calls)",
        t * INSN_PER_TICK,
        calls
    );
    out.is_some() && converged
}

/// `ReplanningGuidance` in `PredictorMode::Numerical` with one solver step per tick (at most
/// `STEPS_PER_SOLVER_STEP` integration steps): the largest instruction count of one tick over
/// the converged solve of the SRM glide.
pub(crate) fn bench_numerical_tick(c: &mut InsnCounter) -> bool {
    let n0 = glide_nav();
    let Some((target, _)) = range(&n0, 0.6, PeakMode::RangeOnly) else {
        return false;
    };
    let solver = ReplanConfig {
        lambda: 1.0,
        min_vertical_fraction: 0.05,
        max_vertical_fraction: 1.0,
        tolerance_m: 1_000.0,
        max_iterations: 40,
        predictor: predictor(),
        mode: PredictorMode::Numerical,
    };
    let Some(mut g) = srm_replanning_guidance(solver, 1e9, target / 6_378_137.0) else {
        return false;
    };
    let mut ok = true;
    let mut max = 0_u32;
    let mut done = None;
    let mut k = 0_u16;
    while k < 1000 && done.is_none() {
        let n = NavState {
            time_s: 2.0 * f32::from(k),
            ..n0
        };
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
        "bench replanning_tick_max_numerical_f32: {} insn/call ({} ticks, {} predictor calls)",
        max,
        k_done + 1,
        calls
    );
    ok
}
