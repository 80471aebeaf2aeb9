//! The full-stack benchmarks of `insn-bench`: each vehicle's campaign stack
//! (`guidance_core::stack::FlightStack`, every layer on: re-planner with the estimator, bank
//! reversals with the terminal law, the barrier where the vehicle flies it) decoded from the
//! set-up image the host uploads in PIL and ticked over a recorded flight, and the per-tick
//! cost of its lateral, estimator and barrier layers over the same flight.
//!
//! The flights (`onboard_demo::flights`) are the nominal SIL flights of
//! the campaign stacks in their PIL mode: every guidance tick's navigation state and sensed
//! lift and drag. The firmware replays them open loop in its scalars (`f32` on the M4F; the
//! fixed-point tick with `f32` layers on the M3, as in PIL), so the stack sees the states of a
//! real flight: its re-plan ticks, reversals, terminal phase and barrier activity. Each tick
//! is timed alone; a benchmark's figure is the largest tick of the flight (mean and count on
//! the same line for context).

use cortex_m_semihosting::hprintln;
use guidance_core::estimate::AeroEstimator;
use guidance_core::lateral::{BankReversalLogic, LateralConfig};
use guidance_core::nodes::DEFAULT_NODE_CAPACITY;
use guidance_core::replan::{RangeTarget, ReplanningGuidance};
use guidance_core::setup::image::decode;
use guidance_core::stack::{FlightStack, Layers, StackConfig};
use guidance_core::{NavState, Real};
use onboard_demo::flights::{Recorded, VEHICLES};
use onboard_demo::insn::InsnCounter;

use crate::firmware::{INSN_PER_TICK, Num};

/// The configuration of the firmware's stack (its node capacity, `f32` layers).
type Config = StackConfig<Num, DEFAULT_NODE_CAPACITY, f32>;

/// Largest, sum and count of the timed calls of one benchmark.
#[derive(Default)]
struct Worst {
    max: u32,
    max_at: u32,
    sum: u64,
    n: u32,
}

impl Worst {
    /// One call of `insn` instructions at recorded tick `k`.
    fn add(&mut self, insn: u32, k: u32) {
        if insn > self.max {
            self.max = insn;
            self.max_at = k;
        }
        self.sum += u64::from(insn);
        self.n += 1;
    }

    fn mean(&self) -> u64 {
        self.sum / u64::from(self.n.max(1))
    }

    fn print(&self, name: &str, vehicle: &str) {
        hprintln!(
            "bench {}_{}: {} insn/call (largest of {} ticks, at tick {}; mean {})",
            name,
            vehicle,
            self.max,
            self.n,
            self.max_at,
            self.mean()
        );
    }
}

/// The stack over the flight: every tick (`<name>`), the ticks without predictor work (no
/// prediction completed, no integration step: `<name>_no_predictor`), the re-plans and reversals made; false if a tick failed or the
/// flight made no re-plan.
fn full_stack(
    c: &mut InsnCounter,
    config: &Config,
    f: &Recorded,
    name: (&str, &str),
    vehicle: &str,
) -> bool {
    let Ok(mut stack) = FlightStack::new(config) else {
        return false;
    };
    let (mut all, mut quiet) = (Worst::default(), Worst::default());
    let mut most_calls = 0_u8;
    let mut ok = true;
    for (k, (nav64, sensed)) in (0_u32..).zip(f.ticks()) {
        let nav: NavState<Num> = nav64.to_scalar();
        let mut out = None;
        let t = c.ticks(|| {
            out = Some(stack.tick(
                core::hint::black_box(&nav),
                core::hint::black_box(sensed.as_ref()),
            ));
        });
        let insn = t * INSN_PER_TICK;
        all.add(insn, k);
        match out {
            Some(Ok(o)) => {
                most_calls = most_calls.max(o.predictor_calls);
                if o.predictor_calls == 0 && o.integration_steps == 0 {
                    quiet.add(insn, k);
                }
            }
            _ => ok = false,
        }
    }
    all.print(name.0, vehicle);
    quiet.print(name.1, vehicle);
    let replans = stack.replan_counts().map_or(0, |n| n.replans);
    hprintln!(
        "{} {}: {} re-plans, {} reversals, at most {} predictor calls in a tick",
        name.0,
        vehicle,
        replans,
        stack.reversals(),
        most_calls
    );
    ok && replans > 0
}

/// The lateral logic of the stack alone (`BankReversalLogic::update`, the terminal law
/// included) at every tick.
fn lateral(c: &mut InsnCounter, config: &Config, f: &Recorded, vehicle: &str) -> bool {
    let (Some(l), Some(RangeTarget::Point(target))) = (config.lateral, config.target) else {
        return false;
    };
    let built = BankReversalLogic::new(LateralConfig {
        target,
        corridor: l.corridor,
        hysteresis_rad: l.hysteresis_rad,
        max_reversals: l.max_reversals,
        freeze_angle_rad: l.freeze_angle_rad,
    })
    .and_then(|g| match l.terminal {
        Some(t) => g.with_terminal(t),
        None => Ok(g),
    });
    let Ok(mut logic) = built else {
        return false;
    };
    let mut w = Worst::default();
    let mut ok = true;
    for (k, (nav64, _)) in (0_u32..).zip(f.ticks()) {
        let nav: NavState<f32> = nav64.to_scalar();
        let mut r = None;
        let t = c.ticks(|| r = Some(logic.update(core::hint::black_box(&nav))));
        ok &= matches!(r, Some(Ok(_)));
        w.add(t * INSN_PER_TICK, k);
    }
    w.print("lateral_tick_max", vehicle);
    ok
}

/// The estimator alone (`ReplanningGuidance::sense` with the stack's estimator and lift
/// schedule, no barrier: the model's expected lift and drag and the estimator's update) at
/// every tick with a measurement.
fn estimator(c: &mut InsnCounter, config: &Config, f: &Recorded, vehicle: &str) -> bool {
    let (Some(r), Some(e), Some(replanning)) =
        (config.replan, config.estimator, config.replanning_config())
    else {
        return false;
    };
    let p = &config.profile;
    let Ok(est) = AeroEstimator::new(e) else {
        return false;
    };
    let built = ReplanningGuidance::new(
        p.guidance,
        p.table.clone(),
        p.interpolation,
        p.energy,
        p.initial,
        replanning,
    )
    .map(|g| g.with_estimator(est));
    let built = match (built, r.lift_schedule) {
        (Ok(g), Some(s)) => g.with_lift_schedule(s),
        (g, _) => g,
    };
    let Ok(mut g) = built else {
        return false;
    };
    let mut w = Worst::default();
    let mut ok = true;
    for (k, (nav64, sensed)) in (0_u32..).zip(f.ticks()) {
        let Some(s) = sensed else { continue };
        let nav: NavState<Num> = nav64.to_scalar();
        let mut out = None;
        let t = c.ticks(|| {
            out = Some(g.sense(core::hint::black_box(&nav), core::hint::black_box(&s)));
        });
        ok &= matches!(out, Some(Ok(Some(_))));
        w.add(t * INSN_PER_TICK, k);
    }
    w.print("estimator_tick_max", vehicle);
    ok && w.n > 0
}

/// The barrier alone at every tick with a measurement: what the re-planner adds to each tick
/// with a barrier bound (`PathBound::barrier_vertical_fraction` of the model at the tick's
/// state and sensed accelerations, with the lift schedule's lift parameter and drag scale,
/// then the bank cap `acos` of the fraction within the solver's interval). `None` when the
/// vehicle's stack has no barrier law.
fn barrier(c: &mut InsnCounter, config: &Config, f: &Recorded, vehicle: &str) -> Option<bool> {
    let b = config.barrier.filter(|b| b.bound.is_barrier())?;
    let r = config.replan?;
    let m = r.model;
    let solver = r.solver;
    let mut w = Worst::default();
    let mut ok = true;
    for (k, (nav64, sensed)) in (0_u32..).zip(f.ticks()) {
        let nav: NavState<f32> = nav64.to_scalar();
        let mut cap = None;
        let t = c.ticks(|| {
            let nav = core::hint::black_box(&nav);
            let aero = match &r.lift_schedule {
                Some(s) => s.at(nav.speed_m_s),
                None => (solver.lambda, 1.0),
            };
            cap = b
                .bound
                .barrier_vertical_fraction(
                    &m.planet,
                    &m.atmosphere,
                    &m.vehicle,
                    aero,
                    nav,
                    core::hint::black_box(sensed),
                )
                .map(|f| {
                    f.clamp(solver.min_vertical_fraction, solver.max_vertical_fraction)
                        .clamp(0.0, 1.0)
                        .acos()
                });
        });
        ok &= cap.is_some_and(f32::is_finite);
        w.add(t * INSN_PER_TICK, k);
    }
    w.print("barrier_tick_max", vehicle);
    Some(ok)
}

/// The full-stack and layer benchmarks of both vehicles; false if a flight file does not
/// parse, its image does not decode or build, or a benchmark fails.
pub(crate) fn bench_flight_stacks(c: &mut InsnCounter) -> bool {
    let mut ok = true;
    for (vehicle, bytes) in VEHICLES {
        let Some(f) = Recorded::parse(bytes) else {
            hprintln!("flight {}: bad file", vehicle);
            ok = false;
            continue;
        };
        let Ok(config) = decode::<Num, DEFAULT_NODE_CAPACITY, f32>(f.image, Layers::ALL) else {
            hprintln!("flight {}: image does not decode", vehicle);
            ok = false;
            continue;
        };
        hprintln!(
            "flight {}: {} ticks, layers {:?}",
            vehicle,
            f.len(),
            config.layers()
        );
        let names = ("stack_tick_max", "stack_tick_max_no_predictor");
        ok &= full_stack(c, &config, &f, names, vehicle);
        // The same stack with its solves spread, one solver step per tick.
        let mut spread = config.clone();
        if let Some(r) = spread.replan.as_mut() {
            r.steps_per_tick = 1;
        }
        let names = (
            "stack_tick_max_spread",
            "stack_tick_max_spread_no_predictor",
        );
        ok &= full_stack(c, &spread, &f, names, vehicle);
        ok &= lateral(c, &config, &f, vehicle);
        ok &= estimator(c, &config, &f, vehicle);
        match barrier(c, &config, &f, vehicle) {
            Some(b) => ok &= b,
            None => hprintln!("flight {}: no barrier law in this stack", vehicle),
        }
    }
    ok
}
