//! The Vinh closed forms through the predictor chain (skip, ballistic arc, glide), the
//! glide-mode prediction with the sink modelled (`predict_glide_with_sink`), the numerical
//! predictor (`predict_numerical`, also with a `LiftSchedule`) and the re-planning solver
//! (every predictor mode, half the cases with a lift schedule), in `f64` and `f32`, from mostly plausible and sometimes hostile vehicles,
//! lift settings and entry states. Checks: no panic; a prediction is finite (range, peaks, glide
//! start) with non-negative peaks; a re-plan that commands a vertical fraction (any case but a
//! fall-back) keeps it exactly in its configured bounds, its bank angle is finite, and its
//! prediction (if any) is finite.

use guidance_core::NavState;
use guidance_core::replan::{
    LiftSchedule, NumericalRun, PredictorMode, ReplanCase, ReplanConfig, ReplanLimits,
    ReplanSolver, predict_glide_with_sink, predict_numerical, replan,
};
use guidance_core::scalar::Real;
use guidance_core::vinh::nondim::{EntryState, ExpAtmosphere, LiftControl, Planet, VehicleParams};
use guidance_core::vinh::predict::{PeakMode, Prediction, PredictorConfig, predict};
use rand::{Rng, RngExt};

use crate::hostile::value;

/// One case's inputs, in `f64`.
#[derive(Clone, Copy, Debug)]
struct Inputs {
    vehicle: [f64; 5],
    lift: [f64; 2],
    entry: [f64; 3],
    final_speed: f64,
    max_skips: u8,
    target_range_m: f64,
    fractions: [f64; 2],
    limits: [f64; 2],
    mode: u8,
    /// A lift schedule (`LiftSchedule`: speed high, lambda high, speed low, lambda low) for
    /// the numerical predictions, if any.
    schedule: Option<[f64; 4]>,
}

pub fn run<R: Rng>(rng: &mut R) -> Result<(), String> {
    // Most cases inside the envelope where the closed forms apply (so the solver and every
    // phase run), the rest over wide ranges with hostile values.
    let (p, wide) = if rng.random_bool(0.7) {
        (0.0, false)
    } else {
        (0.05, true)
    };
    let deg = core::f64::consts::PI / 180.0;
    let pick = |rng: &mut R, narrow: (f64, f64), broad: (f64, f64)| {
        let (a, b) = if wide { broad } else { narrow };
        value(rng, a, b, p)
    };
    let lo = pick(rng, (0.05, 0.6), (-0.2, 1.0));
    let inputs = Inputs {
        vehicle: [
            pick(rng, (20.0, 3e4), (10.0, 1e5)),
            pick(rng, (0.3, 150.0), (0.1, 500.0)),
            pick(rng, (0.03, 0.5), (0.01, 2.0)),
            pick(rng, (0.05, 1.0), (0.01, 2.0)),
            pick(rng, (0.2, 3.0), (0.05, 5.0)),
        ],
        lift: [
            pick(rng, (0.5, 1.0), (0.0, 1.5)),
            pick(rng, (0.1, 1.0), (-1.2, 1.2)),
        ],
        entry: [
            6_378_137.0 + pick(rng, (60e3, 130e3), (20e3, 200e3)),
            pick(rng, (5000.0, 8000.0), (500.0, 12_000.0)),
            pick(rng, (-6.0, 0.0), (-20.0, 5.0)) * deg,
        ],
        final_speed: pick(rng, (1000.0, 3000.0), (100.0, 4000.0)),
        max_skips: rng.random_range(0..10),
        target_range_m: pick(rng, (1e5, 1.2e7), (-1e6, 2e7)),
        fractions: [lo, lo + pick(rng, (0.0, 1.0 - lo), (0.0, 1.2))],
        limits: [
            pick(rng, (2e5, 5e6), (1e5, 1e7)),
            pick(rng, (2.0, 15.0), (1.0, 20.0)),
        ],
        mode: rng.random_range(0..7),
        schedule: None,
    };
    let inputs = Inputs {
        schedule: rng.random_bool(0.5).then(|| {
            [
                pick(rng, (2000.0, 6000.0), (-100.0, 12_000.0)),
                pick(rng, (0.5, 4.0), (-1.0, 20.0)),
                pick(rng, (300.0, 2000.0), (-100.0, 12_000.0)),
                pick(rng, (0.3, 2.0), (-1.0, 20.0)),
            ]
        }),
        ..inputs
    };
    check::<f64>(&inputs)?;
    check::<f32>(&inputs)
}

fn finite_prediction<S: Real>(p: &Prediction<S>) -> bool {
    let all = [
        p.range_angle_rad,
        p.range_m,
        p.peak_heat_flux_w_m2,
        p.peak_g_load,
        p.glide_start_radius_m,
        p.glide_range_angle_rad,
    ];
    all.iter().all(|v| v.is_finite())
        && p.peak_heat_flux_w_m2 >= S::ZERO
        && p.peak_g_load >= S::ZERO
}

fn check<S: Real>(i: &Inputs) -> Result<(), String> {
    let ty = core::any::type_name::<S>();
    let s = |v: f64| S::from_f64(v);
    let planet = Planet::<S>::earth();
    let atmosphere = ExpAtmosphere::<S>::earth();
    let [m, a, cd0, k, rn] = i.vehicle.map(s);
    let vehicle = VehicleParams {
        mass_kg: m,
        reference_area_m2: a,
        cd0,
        k_polar: k,
        nose_radius_m: rn,
    };
    let lift = LiftControl {
        lambda: s(i.lift[0]),
        vertical_fraction: s(i.lift[1]),
    };
    let entry = EntryState {
        radius_m: s(i.entry[0]),
        speed_m_s: s(i.entry[1]),
        flight_path_angle_rad: s(i.entry[2]),
    };
    let predictor = PredictorConfig {
        final_speed_m_s: s(i.final_speed),
        max_skips: i.max_skips,
    };
    if let Ok(p) = predict(&planet, &atmosphere, &vehicle, &lift, &entry, &predictor)
        && !finite_prediction(&p)
    {
        return Err(format!("{ty}: predict gave {p:?} for {i:?}"));
    }
    if let Ok(p) = predict_glide_with_sink(
        &planet,
        &atmosphere,
        &vehicle,
        &lift,
        &entry,
        &predictor,
        PeakMode::Full,
    ) && !finite_prediction(&p)
    {
        return Err(format!(
            "{ty}: predict_glide_with_sink gave {p:?} for {i:?}"
        ));
    }
    if let Ok(p) = predict_numerical(
        &planet,
        &atmosphere,
        &vehicle,
        &lift,
        &entry,
        &predictor,
        PeakMode::Full,
    ) && !finite_prediction(&p)
    {
        return Err(format!("{ty}: predict_numerical gave {p:?} for {i:?}"));
    }
    let schedule = i
        .schedule
        .map(|[a, b, c, d]| LiftSchedule::linear(s(a), s(b), s(c), s(d)));
    if let Some(sch) = schedule {
        // Within its bounds for any speed (NaN included), valid or not.
        for v in [-1.0, 0.0, 500.0, 3000.0, 9000.0, f64::NAN, f64::INFINITY] {
            let l = sch.lambda_at(s(v));
            let (a, b) = match sch.used() {
                [hi, lo] => (lo.lambda, hi.lambda),
                _ => return Err(format!("{ty}: a linear schedule without 2 nodes: {sch:?}")),
            };
            let inside = (l >= a.min(b) && l <= a.max(b)) || !(a.is_finite() && b.is_finite());
            if sch.is_valid() && !(l.is_finite() && inside) {
                return Err(format!("{ty}: lambda_at({v}) = {l:?} for {sch:?}"));
            }
        }
        if let Ok(run) = NumericalRun::new(
            &planet,
            &atmosphere,
            &vehicle,
            &lift,
            &entry,
            &predictor,
            PeakMode::Full,
        ) {
            let mut run = run.with_lift_schedule(sch);
            if let Some(Ok(p)) = run.advance(u16::MAX)
                && !finite_prediction(&p)
            {
                return Err(format!(
                    "{ty}: scheduled numerical prediction gave {p:?} for {i:?}"
                ));
            }
        }
    }
    let config = ReplanConfig {
        lambda: s(i.lift[0]),
        min_vertical_fraction: s(i.fractions[0]),
        max_vertical_fraction: s(i.fractions[1]),
        tolerance_m: s(1000.0),
        max_iterations: 40,
        predictor,
        mode: match i.mode {
            0 => PredictorMode::Chain,
            1 => PredictorMode::Glide,
            2 => PredictorMode::Auto,
            3 => PredictorMode::AutoSink,
            4 => PredictorMode::Numerical,
            5 => PredictorMode::Hybrid,
            _ => PredictorMode::HybridSink,
        },
    };
    let limits = ReplanLimits {
        heat_flux_w_m2: s(i.limits[0]),
        g_load: s(i.limits[1]),
    };
    let nav = NavState {
        time_s: S::ZERO,
        radius_m: entry.radius_m,
        speed_m_s: entry.speed_m_s,
        flight_path_angle_rad: entry.flight_path_angle_rad,
        heading_rad: S::ZERO,
        latitude_rad: S::ZERO,
        longitude_rad: S::ZERO,
    };
    let r = match schedule {
        None => replan(
            &planet,
            &atmosphere,
            &vehicle,
            &nav,
            s(i.target_range_m),
            &limits,
            &config,
        ),
        Some(sch) => {
            let mut solver = ReplanSolver::new(
                &planet,
                &atmosphere,
                &vehicle,
                &nav,
                s(i.target_range_m),
                &limits,
                &config,
            )
            .with_lift_schedule(sch);
            // As `replan`: each step makes at most one predictor call (a numerical one spans
            // at most MAX_STEPS / STEPS_PER_SOLVER_STEP + 1 steps), at most
            // MAX_PREDICTOR_CALLS calls: 65 * 65 steps bound the solve.
            let mut done = None;
            for _ in 0..(65 * 65) {
                done = solver.step();
                if done.is_some() {
                    break;
                }
            }
            match done {
                Some(r) => r,
                None => return Err(format!("{ty}: scheduled solve did not finish for {i:?}")),
            }
        }
    };
    let (lo, hi) = (config.min_vertical_fraction, config.max_vertical_fraction);
    // The solver's own rule for a usable interval (otherwise it falls back, typed).
    let bounds_valid = lo.is_finite() && hi.is_finite() && lo > S::ZERO && lo <= hi && hi <= S::ONE;
    // A fall-back's fraction is documented as meaningless (guidance keeps its table); every
    // other case commands it, so it must lie exactly in the configured interval.
    let commanded = !matches!(r.case, ReplanCase::FallBack(_));
    let in_bounds = r.vertical_fraction >= lo && r.vertical_fraction <= hi;
    if !r.bank_rad.is_finite()
        || !r.vertical_fraction.is_finite()
        || (bounds_valid && commanded && !in_bounds)
        || r.prediction.is_some_and(|p| !finite_prediction(&p))
    {
        return Err(format!("{ty}: replan gave {r:?} for {i:?}"));
    }
    Ok(())
}
