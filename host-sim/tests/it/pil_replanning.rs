//! PIL of a scenario with guidance layers, through `simulate --pil`'s path
//! (`host_sim::pil::fly_scenario_pil`): `examples/srm-glide-replanning.toml` (SRM glide,
//! dispersed entry, `[guidance.replanning]` with `[guidance.lateral]` to a downrange target)
//! has the stack it flies in SIL (`scenario::fly`: the campaign set-up's, fullest mode)
//! uploaded as one set-up image and flown on the Cortex-M4F (`f32`) and on the Cortex-M3
//! (fixed-point tick, `f32` layers) under QEMU.
//!
//! Asserted per target, with the bounds of `pil_campaign.rs` (no new tolerance):
//!
//! 1. The firmware is the core: every command frame equals the host twin's (the same image
//!    decoded on the host in the firmware's scalars, fed the same narrowed inputs) bit for bit
//!    (bound 0).
//! 2. Against the `f64` SIL flight of the scenario: the same termination, the same number of
//!    bank reversals and of re-plans, and the miss within the re-planner's range tolerance
//!    plus the terminal law's crossrange tolerance (the sets the stack accepts; the `f32`
//!    rounding changes where in them each flight ends, not the decisions).
//! 3. The firmware's whole-run stack and static RAM within `onboard-demo/size-budget.toml`.

use std::path::Path;

use host_sim::pil::{PilConfig, PilError, fly_scenario_pil, miss_bound_m};
use host_sim::scenario::{Scenario, fly, read_scenario, stack_setup};

use crate::pil_support::{check_pil_memory_budget, pil_elf, pil_required};

fn scenario() -> Scenario {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/srm-glide-replanning.toml");
    read_scenario(&p).unwrap()
}

fn check(target: &str) {
    let sc = scenario();
    let name = format!("{} on {target}", sc.name);
    let (run, record) = fly_scenario_pil(&sc, "(test)", PilConfig::new(pil_elf(target)));
    let pil = match run {
        Ok(r) => r,
        Err(e @ (PilError::QemuMissing { .. } | PilError::ElfMissing(_))) if !pil_required() => {
            println!("SKIPPED {name}: {e}");
            return;
        }
        Err(e) => panic!("{name}: PIL run failed: {e}"),
    };
    assert_eq!(record.exchanges().len() as u64, pil.stats.frames, "{name}");
    // 1. The firmware computes what the core computes in its scalars, bit for bit.
    assert_eq!(pil.twin.mismatches, 0, "{name}: {:?}", pil.twin.first);
    assert_eq!(u64::from(pil.twin.ticks), pil.stats.frames, "{name}");
    // 2. Against SIL.
    let sil = fly(&sc, "(test)", &mut |_| {}).unwrap();
    let (p, s) = (
        &pil.stack.as_ref().expect("the stack's outcome").case,
        &sil.stack.as_ref().expect("the stack's outcome").case,
    );
    // The bound of `pil_campaign.rs` (`host_sim::pil::miss_bound_m`), of the mode flown.
    let setup = stack_setup(&sc, "(test)").unwrap();
    let bound = miss_bound_m(&setup, setup.full_mode());
    let diff = (p.miss_m - s.miss_m).abs();
    println!(
        "{name}: image {} B, {} ticks bit for bit with the twin; PIL miss {:.3} km, {} reversals, \
         {} re-plans; SIL miss {:.3} km, {} reversals, {} re-plans; |miss diff| {:.3} km \
         (bound {:.3} km)",
        pil.image_bytes,
        pil.twin.ticks,
        p.miss_m / 1e3,
        p.reversals,
        p.replans,
        s.miss_m / 1e3,
        s.reversals,
        s.replans,
        diff / 1e3,
        bound / 1e3
    );
    assert!(p.replans > 0, "{name}: the firmware never re-planned");
    assert!(p.reached_interface, "{name}: {}", p.termination);
    assert_eq!(
        pil.result.summary.termination, sil.result.summary.termination,
        "{name}"
    );
    assert_eq!(
        (p.reversals, p.replans),
        (s.reversals, s.replans),
        "{name}: reversal or re-plan count differs from SIL"
    );
    assert!(bound > 0.0 && diff <= bound, "{name}: {diff} m > {bound} m");
    // 3. The firmware's whole-run stack (painted), and the image's static RAM plus it, within
    // their budgets.
    let stack = pil
        .stats
        .firmware_stack_bytes
        .expect("the firmware reports its stack");
    check_pil_memory_budget(&name, target, &pil_elf(target), stack);
}

#[test]
fn pil_replanning_m4f_matches_core_and_sil() {
    check("thumbv7em-none-eabihf");
}

#[test]
fn pil_replanning_m3_fixed_point_matches_core_and_sil() {
    check("thumbv7m-none-eabi");
}
