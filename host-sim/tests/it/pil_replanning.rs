//! PIL with onboard re-planning (issue 13 item 4): `examples/srm-glide-replanning.toml` (SRM
//! glide, dispersed entry, `[replanning]` to a flown-range target) uploaded as set-up frames,
//! re-planning items included, and flown on the Cortex-M4F (`ReplanningGuidance<f32>`) and on
//! the Cortex-M3 (fixed-point guidance tick, `f32` soft-float re-planner) under QEMU.
//!
//! Two checks per target:
//!
//! 1. The firmware is the core: the recorded nav frames replayed through the core's own
//!    set-up path on the host, in the firmware's scalars (`SetupBuilder<S, 16>` with the same
//!    items, `build_flight::<f32>()`), give every command frame bit for bit (bound 0: the same
//!    code and IEEE `f32` arithmetic; fixed point is exact).
//! 2. Against SIL (`ReplanningGuidance<f64>`) with a derived bound. The re-planner only
//!    guarantees its predicted range within `tolerance_m` of the target, so an `f32` solve and
//!    an `f64` solve from the same state may differ by up to `delta = 2 tol + e_R` in predicted
//!    range, with `e_R = 64 u R_t` the `f32` rounding of the range (u = 2^-24, `R_t` the
//!    target's total range). Outcome bound, as in `pil_scenarios.rs` "twice the SIL change
//!    that a perturbation of the size of the bound causes": `2 (S_target + S_att) + 1e-9 |x|`,
//!    `S_target` the largest SIL change of the outcome when the target moves by `+-delta`,
//!    `S_att` the largest SIL change under a constant attitude offset of `+-e` (the guidance
//!    path's rounding bound of `pil_scenarios.rs`). Outcomes: flown range angle, range angle,
//!    peak heat flux, final speed, latitude, longitude, flight time.

use std::path::Path;

use guidance_core::guidance::Command;
use guidance_core::link::CommandFrame;
use guidance_core::replan::RangeTarget;
use guidance_core::setup::{SetupBuilder, SetupGuidance};
use guidance_core::{Fixed, NavState, Scalar};
use host_sim::dynamics::Dynamics;
use host_sim::pil::{PilConfig, PilError, fly_scenario_pil, scenario_setup};
use host_sim::scenario::{Scenario, build_replanning_guidance, read_scenario};
use host_sim::sim::{self, GuidanceSource, SimResult};

use crate::pil_support::{Offset, check_pil_memory_budget, pil_elf};

const CAPACITY: usize = guidance_core::nodes::DEFAULT_NODE_CAPACITY;

fn scenario() -> Scenario {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/srm-glide-replanning.toml");
    read_scenario(&p).unwrap()
}

/// SIL (`ReplanningGuidance<f64>`), the target's total range moved by `dtarget_m`, the
/// attitude offset by `offset` rad. Also returns the re-plans applied.
fn sil(sc: &Scenario, dtarget_m: f64, offset: f64) -> (SimResult, u32) {
    let mut sc = sc.clone();
    let r = sc.environment.planet.radius_m;
    if let Some(rp) = sc.replanning.as_mut()
        && let RangeTarget::FlownRangeAngle { total_rad } = &mut rp.target
    {
        *total_rad += dtarget_m / r;
    }
    let env = sc.environment.build();
    let veh = sc.load_vehicle().unwrap();
    let g = build_replanning_guidance(&sc, &env, &veh, "(test)")
        .unwrap()
        .unwrap();
    let dynm = Dynamics::from_environment(&env, &veh);
    let (res, src) = sim::simulate(
        dynm,
        Offset(GuidanceSource::new(g), offset),
        &sc.sim_config(),
        &mut |_| {},
    )
    .unwrap();
    (res, src.0.guidance.counts().applied)
}

fn metrics(r: &SimResult) -> [f64; 7] {
    let last = r.samples.last().unwrap();
    [
        r.summary.flown_range_angle_rad,
        r.summary.range_angle_rad,
        r.summary.peak_heat_flux_w_m2.value,
        last.state.speed_m_s,
        last.state.latitude_rad,
        last.state.longitude_rad,
        r.summary.flight_time_s,
    ]
}

fn wide<S: Scalar>(c: Command<S>) -> Command<f64> {
    Command {
        alpha_rad: c.alpha_rad.to_f64(),
        sigma_rad: c.sigma_rad.to_f64(),
    }
}

/// Check 1: replay the recorded nav frames through the core in the firmware's scalar `S`
/// (re-planner `f32`); every command frame must match bit for bit. Returns the re-plans the
/// replay applied.
fn replay<S: Scalar>(sc: &Scenario, exchanges: &[host_sim::pil::Exchange]) -> u32 {
    let (items, _) = scenario_setup(sc, "(test)").unwrap();
    let mut b = SetupBuilder::<S, CAPACITY>::new();
    for it in items
        .iter()
        .filter(|i| **i != guidance_core::setup::SetupItem::Commit)
    {
        b.apply(it).unwrap();
    }
    let mut g = b.build_flight::<f32>().unwrap();
    assert!(matches!(g, SetupGuidance::Replanning(_)));
    for ex in exchanges {
        let n = &ex.nav;
        let nav = NavState {
            time_s: S::from_f64(n.time_s),
            radius_m: S::from_f64(n.radius_m),
            speed_m_s: S::from_f64(n.speed_m_s),
            flight_path_angle_rad: S::from_f64(n.flight_path_angle_rad),
            heading_rad: S::from_f64(n.heading_rad),
            latitude_rad: S::from_f64(n.latitude_rad),
            longitude_rad: S::from_f64(n.longitude_rad),
        };
        g.update(&nav).unwrap();
        let h = g.guidance();
        let tick = h.last_tick_s().unwrap();
        let c: CommandFrame = ex.reply.unwrap();
        assert_eq!(
            c.tick_time_s.to_bits(),
            tick.to_f64().to_bits(),
            "seq {}",
            ex.seq
        );
        assert_eq!(c.command, wide(h.command()), "seq {}", ex.seq);
        assert_eq!(c.ramp_start, wide(h.attitude_at(tick)), "seq {}", ex.seq);
    }
    match g {
        SetupGuidance::Replanning(r) => r.counts().applied,
        SetupGuidance::Stored(_) => 0,
    }
}

/// The guidance path's rounding bound of `pil_scenarios.rs` (energy-indexed table).
fn path_bound(sc: &Scenario, fixed: bool) -> f64 {
    let env = sc.environment.build();
    let g = host_sim::scenario::build_guidance(sc, &env.planet, "(test)").unwrap();
    let nodes = g.table().nodes();
    let (x0, x1) = (nodes.first().unwrap().x, nodes.last().unwrap().x);
    let interp = g.interpolator();
    let n = 20_000;
    let mut slope = 0.0f64;
    let mut prev = interp.evaluate(x0);
    for i in 1..=n {
        let x = x0 + (x1 - x0) * f64::from(i) / f64::from(n);
        let c = interp.evaluate(x);
        let dx = (x1 - x0).abs() / f64::from(n);
        slope = slope
            .max((c.alpha_rad - prev.alpha_rad).abs() / dx)
            .max((c.sigma_rad - prev.sigma_rad).abs() / dx);
        prev = c;
    }
    let u = f64::from(f32::EPSILON) / 2.0;
    let ua = if fixed {
        2f64.powi(-32)
    } else {
        u * std::f64::consts::FRAC_PI_2
    };
    let p = &env.planet;
    let m = p.mu_m3_s2 / p.radius_m + 0.5 * sc.entry.speed_m_s.powi(2);
    let span =
        0.5 * sc.entry.speed_m_s.powi(2) - p.mu_m3_s2 / sc.entry.radius_m + p.mu_m3_s2 / p.radius_m;
    let dx = if fixed {
        16.0 * 2f64.powi(-32) * (1.0 + m / span)
    } else {
        8.0 * u * m / span
    };
    64.0 * ua + 1.1 * slope * dx + 10.0 * ua
}

fn check(target: &str, fixed: bool) {
    let sc = scenario();
    let name = format!("{} on {target}", sc.name);
    let (run, record) = fly_scenario_pil(&sc, "(test)", PilConfig::new(pil_elf(target)));
    let (pil, stats) = match run {
        Ok(r) => r,
        Err(e @ (PilError::QemuMissing { .. } | PilError::ElfMissing(_)))
            if std::env::var_os("PIL_REQUIRED").is_none() =>
        {
            println!("SKIPPED {name}: {e}");
            return;
        }
        Err(e) => panic!("{name}: PIL run failed: {e}"),
    };
    let exchanges = record.exchanges();
    assert_eq!(exchanges.len() as u64, stats.frames, "{name}");
    // 1. The firmware computes what the core computes in its scalars, bit for bit.
    let replans = if fixed {
        replay::<Fixed>(&sc, &exchanges)
    } else {
        replay::<f32>(&sc, &exchanges)
    };
    println!(
        "{name}: {} frames replayed bit for bit; {replans} re-plans applied",
        exchanges.len()
    );
    assert!(replans > 0, "{name}: the firmware never re-planned");
    // The firmware's whole-run stack (painted), and the image's static RAM plus it, within
    // their budgets.
    let stack = stats
        .firmware_stack_bytes
        .expect("the firmware reports its stack");
    check_pil_memory_budget(&name, target, &pil_elf(target), stack);
    // 2. Against SIL with the derived bound.
    let (base, sil_replans) = sil(&sc, 0.0, 0.0);
    assert!(sil_replans > 0, "{name}: SIL never re-planned");
    assert_eq!(pil.summary.termination, base.summary.termination, "{name}");
    let rp = sc.replanning.unwrap();
    let RangeTarget::FlownRangeAngle { total_rad } = rp.target else {
        panic!("the example aims at a flown range");
    };
    let r_t = total_rad * sc.environment.planet.radius_m;
    let u = f64::from(f32::EPSILON) / 2.0;
    let delta = 2.0 * rp.tolerance_m + 64.0 * u * r_t;
    let e = path_bound(&sc, fixed);
    let mut s_target = [0.0f64; 7];
    let mut s_att = [0.0f64; 7];
    for (is_target, dt, off) in [
        (true, delta, 0.0),
        (true, -delta, 0.0),
        (false, 0.0, e),
        (false, 0.0, -e),
    ] {
        let sens = if is_target { &mut s_target } else { &mut s_att };
        for ((s, m), b) in sens
            .iter_mut()
            .zip(metrics(&sil(&sc, dt, off).0))
            .zip(metrics(&base))
        {
            *s = s.max((m - b).abs());
        }
    }
    let mut max_att = 0.0f64;
    for (a, b) in pil.samples.iter().zip(&base.samples) {
        max_att = max_att
            .max((a.attitude.alpha_rad - b.attitude.alpha_rad).abs())
            .max((a.attitude.sigma_rad - b.attitude.sigma_rad).abs());
    }
    println!(
        "{name}: delta {delta:.1} m, path bound {e:.2e} rad; max attitude difference PIL - SIL \
         {max_att:.3e} rad; ticks PIL {} SIL {}",
        pil.summary.ticks, base.summary.ticks
    );
    assert!(
        max_att > 0.0,
        "{name}: identical to f64: link not exercised?"
    );
    let labels = [
        "flown range angle",
        "range angle",
        "peak heat flux",
        "final speed",
        "latitude",
        "longitude",
        "flight time",
    ];
    for (i, ((p, s), (st, sa))) in metrics(&pil)
        .into_iter()
        .zip(metrics(&base))
        .zip(s_target.into_iter().zip(s_att))
        .enumerate()
    {
        let b = 2.0 * (st + sa) + 1e-9 * s.abs();
        let diff = (p - s).abs();
        println!(
            "  {:<17} PIL {p:.9e} SIL {s:.9e} |diff| {diff:.2e} bound {b:.2e}",
            labels[i]
        );
        assert!(
            diff <= b,
            "{name}: {}: |PIL - SIL| = {diff:e} > {b:e}",
            labels[i]
        );
    }
}

#[test]
fn pil_replanning_m4f_matches_core_and_sil() {
    check("thumbv7em-none-eabihf", false);
}

#[test]
fn pil_replanning_m3_fixed_point_matches_core_and_sil() {
    check("thumbv7m-none-eabi", true);
}
