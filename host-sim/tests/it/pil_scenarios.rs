//! PIL for any scenario's stored profile (a scenario without `[guidance.*]` layers): the HORUS-2B
//! reference mission (time-indexed, linear) and the SRM glide (energy-indexed) uploaded as a
//! set-up image of their profile-only stack and flown on the Cortex-M4F (`f32`) and on the
//! Cortex-M3 (fixed point), each against its host twin (bit for bit) and against SIL (`f64`
//! in-process) with a derived bound. A scenario with layers: `pil_replanning.rs`.
//!
//! Attitude bound (per run, from the scenario's own numbers):
//!   e <= C u A + L dx + R r,
//! * C u A: the guidance path's own rounding, C = 64 rounded operations of unit round-off u on
//!   angles of size A = pi/2 (u = 2^-24 for f32; fixed point: absolute resolution 2^-32, i.e.
//!   u A := 2^-32);
//! * L dx: L the largest slope |d angle / dx| of the table's interpolant (sampled densely on the
//!   SIL interpolator, times 1.1), dx the error of the independent variable on the firmware:
//!   time: 2 u t_max (f32; fixed: 2 * 2^-32 s); E-hat: 8 u M / span with M = mu/R + V_e^2/2 the
//!   largest energy term and span = E_entry + mu/R (f32), fixed point 16 * 2^-32 * (1 + M/span)
//!   (normalised units);
//! * R r: a rate-limited run of R = 10 ticks, each adding one rounding r = u A.
//!
//! Outcomes (range angle, peak heat flux, final speed and position, flight time): within twice
//! the SIL change that a constant attitude offset of the bound causes, scaled to the observed
//! attitude difference, plus 1e-9 relative (the integrator tolerance), as in `pil.rs`.

use guidance_core::nodes::Independent;
use host_sim::dynamics::Dynamics;
use host_sim::pil::{PilConfig, PilError, fly_scenario_pil};
use host_sim::scenario::{Scenario, build_guidance};
use host_sim::sim::{self, CoreGuidance, SimResult};

use crate::pil_support::{Offset, check_pil_memory_budget, pil_elf, pil_required};

fn sil(sc: &Scenario, offset: f64) -> SimResult {
    let env = sc.environment.build();
    let veh = sc.load_vehicle().unwrap();
    let g = build_guidance(sc, &env.planet, "(test)").unwrap();
    let dynm = Dynamics::from_environment(&env, &veh);
    sim::simulate(
        dynm,
        Offset(CoreGuidance::new(g), offset),
        &sc.sim_config(),
        &mut |_| {},
    )
    .unwrap()
    .0
}

fn metrics(r: &SimResult) -> [f64; 6] {
    let last = r.samples.last().unwrap();
    [
        r.summary.range_angle_rad,
        r.summary.peak_heat_flux_w_m2.value,
        last.state.speed_m_s,
        last.state.latitude_rad,
        last.state.longitude_rad,
        r.summary.flight_time_s,
    ]
}

/// The derived attitude bound of the module docs.
fn attitude_bound(sc: &Scenario, fixed: bool) -> f64 {
    let env = sc.environment.build();
    let g = build_guidance(sc, &env.planet, "(test)").unwrap();
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
    let l = 1.1 * slope;
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
    let dx = match (g.table().independent(), fixed) {
        (Independent::TimeS, false) => 2.0 * u * sc.termination.max_time_s,
        (Independent::TimeS, true) => 2.0 * 2f64.powi(-32),
        (Independent::NormalizedEnergy, false) => 8.0 * u * m / span,
        (Independent::NormalizedEnergy, true) => 16.0 * 2f64.powi(-32) * (1.0 + m / span),
    };
    64.0 * ua + l * dx + 10.0 * ua
}

fn check(sc: &Scenario, target: &str, fixed: bool) {
    let name = format!("{} on {target}", sc.name);
    let elf = pil_elf(target);
    let run = match fly_scenario_pil(sc, "(test)", PilConfig::new(elf.clone())).0 {
        Ok(r) => r,
        Err(e @ (PilError::QemuMissing { .. } | PilError::ElfMissing(_))) if !pil_required() => {
            println!("SKIPPED {name}: {e}");
            return;
        }
        Err(e) => panic!("{name}: PIL run failed: {e}"),
    };
    assert!(
        run.stack.is_none(),
        "{name}: a stored profile has no target"
    );
    // The firmware computes what its host twin (the image in its scalars) computes.
    assert_eq!(run.twin.mismatches, 0, "{name}: {:?}", run.twin.first);
    assert_eq!(u64::from(run.twin.ticks), run.stats.frames, "{name}");
    let (pil, stats) = (run.result, run.stats);
    // The firmware's whole-run stack (painted), and the image's static RAM plus it, within
    // their budgets.
    let stack = stats
        .firmware_stack_bytes
        .expect("the firmware reports its stack");
    check_pil_memory_budget(&name, target, &elf, stack);
    let base = sil(sc, 0.0);
    assert_eq!(pil.summary.termination, base.summary.termination, "{name}");
    assert_eq!(pil.summary.ticks, base.summary.ticks, "{name}");
    assert_eq!(stats.frames, base.summary.ticks, "{name}");
    assert_eq!(pil.samples.len(), base.samples.len(), "{name}");
    let bound = attitude_bound(sc, fixed);
    let mut max_att = 0.0f64;
    for (a, b) in pil.samples.iter().zip(&base.samples) {
        assert_eq!(a.kind, b.kind, "{name}");
        assert!(
            (a.time_s - b.time_s).abs() < 1e-4,
            "{name}: {} vs {}",
            a.time_s,
            b.time_s
        );
        max_att = max_att
            .max((a.attitude.alpha_rad - b.attitude.alpha_rad).abs())
            .max((a.attitude.sigma_rad - b.attitude.sigma_rad).abs());
    }
    println!("{name}: max attitude difference PIL - SIL {max_att:.3e} rad (bound {bound:.3e})");
    assert!(
        max_att > 0.0,
        "{name}: identical to f64: link not exercised?"
    );
    assert!(max_att <= bound, "{name}: {max_att:e} > {bound:e}");
    let mut sens = [0.0f64; 6];
    for delta in [bound, -bound] {
        for ((s, m), b) in sens
            .iter_mut()
            .zip(metrics(&sil(sc, delta)))
            .zip(metrics(&base))
        {
            *s = s.max((m - b).abs());
        }
    }
    for ((p, s), sens) in metrics(&pil).into_iter().zip(metrics(&base)).zip(sens) {
        let b = 2.0 * sens * (max_att / bound) + 1e-9 * s.abs();
        let diff = (p - s).abs();
        println!("  PIL {p:.9e} SIL {s:.9e} |diff| {diff:.2e} bound {b:.2e}");
        assert!(diff <= b, "{name}: |PIL - SIL| = {diff:e} > {b:e}");
    }
}

/// The SRM glide's stored profile alone (the built-in without its layers).
fn srm_glide_stored() -> Scenario {
    Scenario {
        layers: None,
        ..Scenario::srm_glide()
    }
}

#[test]
fn pil_srm_glide_m4f_matches_sil() {
    check(&srm_glide_stored(), "thumbv7em-none-eabihf", false);
}

#[test]
fn pil_srm_glide_m3_fixed_point_matches_sil() {
    check(&srm_glide_stored(), "thumbv7m-none-eabi", true);
}

#[test]
fn pil_reference_mission_m3_fixed_point_matches_sil() {
    check(&Scenario::horus_2b_stored(), "thumbv7m-none-eabi", true);
}
