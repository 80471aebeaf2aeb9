//! Processor-in-the-loop: the HORUS-2B reference mission flown with the firmware's `f32`
//! guidance in QEMU (`onboard-demo`'s `pil` binary) against the `f64` SIL run.
//!
//! Skipped (passes with a printed reason) when `qemu-system-arm` or the firmware ELF is absent,
//! unless `PIL_REQUIRED` is set (as `cargo xtask test` and `cargo xtask pil` do) or `CI=true`.
//! The ELF is `$PIL_ELF`, else `<target dir>/thumbv7em-none-eabihf/firmware/pil`; `cargo xtask
//! test` builds it before its host tests, which run this test.

use std::path::PathBuf;
use std::time::Instant;

use host_sim::pil::{
    PilConfig, PilError, fly_reference, fly_reference_pil, fly_reference_sil,
    reference_sil_guidance,
};
use host_sim::sim::SimResult;

use crate::pil_support::{Offset, check_pil_memory_budget, pil_required, reference_pil_elf};

/// (range angle [rad], peak heat flux [W/m^2], final speed [m/s], final latitude [rad],
/// final longitude [rad], flight time [s]).
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

const NAMES: [&str; 6] = [
    "range angle [rad]",
    "peak heat flux [W/m^2]",
    "final speed [m/s]",
    "final latitude [rad]",
    "final longitude [rad]",
    "flight time [s]",
];

/// Attitude bound of f32 against f64 guidance on a time-indexed table (guidance.rs docs,
/// "Precision"): e <= C u A + L r with C = 64 rounded operations, u = 2^-24, A = pi/2 rad
/// (6.0e-6 rad), plus L r for a rate-limited run of at most 10 ticks, r = 1.2e-7 rad
/// (1.2e-6 rad): 1e-5 rad after rounding up.
const ATTITUDE_BOUND_RAD: f64 = 1e-5;

/// The reference mission in PIL (f32 firmware guidance in QEMU) and in SIL (f64 in-process).
///
/// Bounds: (1) every sampled attitude within [`ATTITUDE_BOUND_RAD`] (derived above);
/// (2) each outcome within twice the larger change that a constant offset of +-1e-5 rad on
/// both angles causes in SIL (a first-order sensitivity measured here, the factor 2 covering
/// a time-varying perturbation of the same size), scaled down linearly to the largest
/// attitude difference actually observed, plus an integration floor of 1e-9 relative (rtol of
/// the run).
#[test]
fn pil_reference_mission_matches_sil() {
    let t0 = Instant::now();
    let (pil, stats) = match fly_reference_pil(PilConfig::new(reference_pil_elf())) {
        Ok(r) => r,
        Err(e @ (PilError::QemuMissing { .. } | PilError::ElfMissing(_))) if !pil_required() => {
            println!("SKIPPED pil_reference_mission_matches_sil: {e}");
            return;
        }
        Err(e) => panic!("PIL run failed: {e}"),
    };
    let wall = t0.elapsed().as_secs_f64();
    println!(
        "PIL: {} frames in {wall:.3} s wall ({:.0} frames/s overall; {:.1} us per round trip)",
        stats.frames,
        stats.frames as f64 / wall,
        1e6 * stats.link_s / stats.frames as f64
    );
    // The firmware's whole-run stack, and the image's static RAM plus it, within their budgets.
    let stack = stats
        .firmware_stack_bytes
        .expect("the firmware reports its stack");
    check_pil_memory_budget(
        "reference mission on thumbv7em-none-eabihf",
        "thumbv7em-none-eabihf",
        &reference_pil_elf(),
        stack,
    );
    // The firmware timed every tick with its SysTick tick timer (lockstep: every nav frame is
    // a tick); the durations are QEMU wall time, so only their presence is checked.
    println!(
        "firmware tick timing: {:?} ticks, {:?} overruns, longest {:?} us",
        stats.firmware_ticks, stats.firmware_overruns, stats.firmware_max_tick_us
    );
    assert_eq!(stats.firmware_ticks, Some(stats.frames));
    assert!(stats.firmware_overruns.is_some());
    assert!(
        stats.firmware_max_tick_us.is_some_and(|us| us > 0),
        "SysTick tick timer not running"
    );
    let sil = fly_reference_sil().unwrap();
    assert_eq!(pil.summary.termination, sil.summary.termination);
    assert_eq!(pil.summary.ticks, sil.summary.ticks);
    assert_eq!(stats.frames, sil.summary.ticks);
    assert_eq!(pil.summary.skips, sil.summary.skips);

    // Same samples: ticks at identical times, located events (interface crossing,
    // termination) within 1e-4 s.
    assert_eq!(pil.samples.len(), sil.samples.len());
    let mut max_att = 0.0f64;
    for (a, b) in pil.samples.iter().zip(&sil.samples) {
        assert_eq!(a.kind, b.kind);
        assert!(
            (a.time_s - b.time_s).abs() < 1e-4,
            "{} vs {}",
            a.time_s,
            b.time_s
        );
        max_att = max_att
            .max((a.attitude.alpha_rad - b.attitude.alpha_rad).abs())
            .max((a.attitude.sigma_rad - b.attitude.sigma_rad).abs());
    }
    println!("max attitude difference PIL - SIL: {max_att:.3e} rad (bound {ATTITUDE_BOUND_RAD:e})");
    assert!(
        max_att > 0.0,
        "f32 firmware identical to f64: link not exercised?"
    );
    assert!(max_att <= ATTITUDE_BOUND_RAD);

    let base = metrics(&sil);
    let mut sens = [0.0f64; 6];
    for delta in [ATTITUDE_BOUND_RAD, -ATTITUDE_BOUND_RAD] {
        let (r, _) = fly_reference(Offset(reference_sil_guidance().unwrap(), delta)).unwrap();
        for ((s, m), b) in sens.iter_mut().zip(metrics(&r)).zip(base) {
            *s = s.max((m - b).abs());
        }
    }
    for (((name, p), s), sens) in NAMES.iter().zip(metrics(&pil)).zip(base).zip(sens) {
        let bound = 2.0 * sens * (max_att / ATTITUDE_BOUND_RAD) + 1e-9 * s.abs();
        let diff = (p - s).abs();
        println!("{name}: PIL {p:.9e} SIL {s:.9e} |diff| {diff:.2e} bound {bound:.2e}");
        assert!(diff <= bound, "{name}: |PIL - SIL| = {diff:e} > {bound:e}");
    }
}

/// A fresh, empty directory for one test's FIFO directories.
fn fresh(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("host-sim-pil-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A missing ELF is reported as such (and no FIFO directory is left behind).
#[test]
fn pil_names_a_missing_reference_pil_elf() {
    let mut cfg = PilConfig::new(PathBuf::from("/nonexistent/pil-firmware.elf"));
    let dir = fresh("missing");
    cfg.fifo_parent = dir.clone();
    match fly_reference_pil(cfg) {
        Err(PilError::ElfMissing(p)) => assert!(p.ends_with("pil-firmware.elf")),
        Err(e @ PilError::QemuMissing { .. }) => println!("SKIPPED pil_names_a_missing_elf: {e}"),
        other => panic!("expected ElfMissing, got {other:?}"),
    }
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Firmware that never opens the link (the smoke binary `onboard-demo`, which runs its own
/// check and exits): the run fails at once with QEMU's exit and output (not after the reply
/// timeout), and cleans up its FIFOs.
#[test]
fn pil_reports_firmware_that_exits_without_opening_the_link() {
    let smoke = reference_pil_elf().with_file_name("onboard-demo");
    let mut cfg = PilConfig::new(smoke);
    let dir = fresh("smoke");
    cfg.fifo_parent = dir.clone();
    let t0 = Instant::now();
    match fly_reference_pil(cfg) {
        Err(PilError::QemuExited(e)) => {
            println!("{e}");
            assert!(!e.stdout.is_empty(), "{e}");
            assert!(t0.elapsed().as_secs_f64() < 5.0);
        }
        Err(e @ (PilError::QemuMissing { .. } | PilError::ElfMissing(_))) => {
            println!("SKIPPED pil_reports_firmware_that_exits_without_opening_the_link: {e}");
        }
        other => panic!("expected QemuExited, got {other:?}"),
    }
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 7 item 4: a vehicle that does not load is the scenario's error, reported before any
/// firmware is started (not a firmware or link error), naming the vehicle file.
#[test]
fn pil_vehicle_load_failure_is_a_scenario_error() {
    let sc = host_sim::scenario::Scenario {
        vehicle: host_sim::scenario::VehicleSpec::File(PathBuf::from("/nonexistent/vehicle.toml")),
        ..Default::default()
    };
    let dir = fresh("vehicle");
    let mut cfg = PilConfig::new(PathBuf::from("/nonexistent/pil-firmware.elf"));
    cfg.fifo_parent = dir.clone();
    let (run, record) = host_sim::pil::fly_scenario_pil(&sc, "(test)", cfg);
    match run {
        Err(e @ PilError::Scenario(_)) => {
            let text = e.to_string();
            assert!(text.contains("/nonexistent/vehicle.toml"), "{text}");
            assert!(!text.contains("firmware"), "{text}");
        }
        other => panic!("expected PilError::Scenario, got {other:?}"),
    }
    assert!(record.exchanges().is_empty());
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
    let _ = std::fs::remove_dir_all(&dir);
}
