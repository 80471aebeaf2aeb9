//! Campaign cases in PIL (issue 19 items 4 and 5): each vehicle's campaign stack in its best
//! mode (re-planning with the estimator, reversals with the terminal law, and the barrier
//! where the vehicle flies it) uploaded to the firmware as one set-up image
//! (`guidance_core::setup::image`) and flown in the case's dispersed world, with the case's
//! IMU readings in the nav frames (`host_sim::pil::fly_case_pil`).
//!
//! What is asserted, per case:
//! * the firmware equals its host twin (the same image decoded on the host in the firmware's
//!   scalars, fed the same narrowed inputs) bit for bit at every tick: held command, ramp
//!   start, tick time, reversal and re-plan counts. The command tolerance against the stack in
//!   the target's arithmetic is therefore 0;
//! * against the `f64` SIL flight of the same case (`campaign::flight::fly_case`): the same
//!   number of bank reversals and of re-plans, and the miss within
//!   `tolerance_m + R tolerance_rad`: the range error the re-planner's corrector accepts plus
//!   the crossrange the terminal law accepts. The `f32` rounding changes where inside those
//!   accepted sets each flight ends, not the guidance's decisions (asserted by the counts);
//! * the firmware's whole-run stack and static RAM within `onboard-demo/size-budget.toml`.
//!
//! The reference (nominal) case and cases 0-4 of the default dispersions per vehicle run in
//! `cargo xtask pil` / `cargo xtask test` on the Cortex-M4F; the Cortex-M3 (fixed-point tick,
//! `f32` layers) checks the twin and the budgets on the same cases. 50 cases per vehicle:
//! `pil_campaign_50_cases` (ignored; docs/guides/pil.md has its figures).

use host_sim::campaign::draw::draw_case;
use host_sim::campaign::flight::fly_case;
use host_sim::campaign::{CampaignSetup, CaseResult, DispersionSettings, Mode};
use host_sim::pil::{PilCase, PilConfig, PilError, fly_case_pil};
use host_sim::scenario::Scenario;

use crate::pil_support::{check_pil_memory_budget, pil_elf};

const M4F: &str = "thumbv7em-none-eabihf";
const M3: &str = "thumbv7m-none-eabi";

fn setup(name: &str) -> CampaignSetup {
    let sc = Scenario::try_builtin(name).unwrap();
    CampaignSetup::new(&sc, &format!("builtin:{name}"), None).unwrap()
}

/// The miss bound of the module docs \[m\]: the corrector's range tolerance plus the terminal
/// law's crossrange tolerance (0 without the law).
fn miss_bound_m(setup: &CampaignSetup, mode: Mode) -> f64 {
    let c = setup.stack_of(mode);
    let range = c.replan.map_or(0.0, |r| r.solver.tolerance_m);
    let cross = c.lateral.and_then(|l| l.terminal).map_or(0.0, |t| {
        t.tolerance_rad * c.replan.map_or(0.0, |r| r.model.planet.radius_m)
    });
    range + cross
}

/// One case in PIL on `target`; `None` if QEMU or the ELF is missing (and not required).
fn pil_case(setup: &CampaignSetup, index: Option<u32>, target: &str) -> Option<PilCase> {
    let draw = index.map(|i| draw_case(&DispersionSettings::default(), i));
    let cfg = PilConfig::new(pil_elf(target));
    match fly_case_pil(setup, draw.as_ref(), Mode::ReplanEstimation, cfg) {
        Ok(r) => Some(r),
        Err(e @ (PilError::QemuMissing { .. } | PilError::ElfMissing(_)))
            if std::env::var_os("PIL_REQUIRED").is_none() =>
        {
            println!("SKIPPED {} case {index:?} on {target}: {e}", setup.file);
            None
        }
        Err(e) => panic!("{} case {index:?} on {target}: {e}", setup.file),
    }
}

fn sil_case(setup: &CampaignSetup, index: Option<u32>) -> CaseResult {
    let draw = index.map(|i| draw_case(&DispersionSettings::default(), i));
    fly_case(setup, draw.as_ref(), Mode::ReplanEstimation).unwrap()
}

/// What one case gives against SIL: (same counts, |miss difference| \[m\]).
struct Compared {
    same_counts: bool,
    miss_diff_m: f64,
}

fn compare(label: &str, pil: &PilCase, sil: &CaseResult) -> Compared {
    let p = &pil.result;
    let miss_diff_m = (p.miss_m - sil.miss_m).abs();
    println!(
        "{label}: image {} B; twin {}/{} ticks differ; PIL miss {:.3} km, {} reversals, {} re-plans; \
         SIL miss {:.3} km, {} reversals, {} re-plans; |miss diff| {:.3} km; stack {:?} B",
        pil.image_bytes,
        pil.twin.mismatches,
        pil.twin.ticks,
        p.miss_m / 1e3,
        p.reversals,
        p.replans,
        sil.miss_m / 1e3,
        sil.reversals,
        sil.replans,
        miss_diff_m / 1e3,
        pil.stats.firmware_stack_bytes,
    );
    Compared {
        same_counts: p.reversals == sil.reversals && p.replans == sil.replans,
        miss_diff_m,
    }
}

/// The reference case and cases 0-4 of `vehicle` on `target`; `against_sil`: also assert the
/// `f64` SIL comparison.
fn campaign_cases(vehicle: &str, target: &str, against_sil: bool) {
    let setup = setup(vehicle);
    let bound = miss_bound_m(&setup, Mode::ReplanEstimation);
    assert!(bound > 0.0);
    let mut deepest = 0;
    for index in [None, Some(0), Some(1), Some(2), Some(3), Some(4)] {
        let label = format!("{vehicle} case {index:?} on {target}");
        let Some(pil) = pil_case(&setup, index, target) else {
            return;
        };
        let sil = sil_case(&setup, index);
        let c = compare(&label, &pil, &sil);
        assert_eq!(pil.twin.mismatches, 0, "{label}: {:?}", pil.twin.first);
        assert!(pil.twin.ticks > 100, "{label}: {} ticks", pil.twin.ticks);
        assert!(
            pil.result.reached_interface,
            "{label}: {}",
            pil.result.termination
        );
        if against_sil {
            assert!(
                c.same_counts,
                "{label}: reversal or re-plan count differs from SIL"
            );
            assert!(
                c.miss_diff_m <= bound,
                "{label}: |miss PIL - SIL| {} m > {bound} m",
                c.miss_diff_m
            );
        }
        deepest = deepest.max(pil.stats.firmware_stack_bytes.expect("stack reported"));
    }
    println!("{vehicle} on {target}: miss bound {bound} m; deepest stack {deepest} B");
    check_pil_memory_budget(
        &format!("{vehicle} campaign"),
        target,
        &pil_elf(target),
        deepest,
    );
}

#[test]
fn pil_campaign_horus_m4f_matches_sil() {
    campaign_cases("horus-2b-reference", M4F, true);
}

#[test]
fn pil_campaign_srm_m4f_matches_sil() {
    campaign_cases("srm-glide", M4F, true);
}

#[test]
fn pil_campaign_horus_m3_matches_its_twin() {
    campaign_cases("horus-2b-reference", M3, false);
}

#[test]
fn pil_campaign_srm_m3_matches_its_twin() {
    campaign_cases("srm-glide", M3, false);
}

/// The M3's fixed-point tick against the `f64` SIL: the counts and the miss bound of the
/// M4F's test. Ignored: it fails (docs/guides/pil.md has the measured cases).
#[test]
#[ignore = "fails: the fixed-point tick changes the SRM nominal case's reversals (docs/guides/pil.md)"]
fn pil_campaign_m3_against_f64_sil() {
    campaign_cases("srm-glide", M3, true);
    campaign_cases("horus-2b-reference", M3, true);
}

/// 50 cases per vehicle on the Cortex-M4F (or the target `PIL_TARGET` names, e.g.
/// `thumbv7m-none-eabi`), measured once (docs/guides/pil.md):
/// `PIL_CASES=50 cargo test -p host-sim --test it pil_campaign_50_cases -- --ignored --nocapture`.
#[test]
#[ignore = "measurement: 100 PIL flights"]
fn pil_campaign_50_cases() {
    let n: u32 = std::env::var("PIL_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(50);
    let target = std::env::var("PIL_TARGET").unwrap_or_else(|_| M4F.to_string());
    for vehicle in ["horus-2b-reference", "srm-glide"] {
        let setup = setup(vehicle);
        let bound = miss_bound_m(&setup, Mode::ReplanEstimation);
        let (mut twin_bad, mut counts_bad, mut worst, mut over) = (0, 0, 0.0f64, 0);
        for i in 0..n {
            let Some(pil) = pil_case(&setup, Some(i), &target) else {
                return;
            };
            let sil = sil_case(&setup, Some(i));
            let c = compare(&format!("{vehicle} case {i}"), &pil, &sil);
            twin_bad += u32::from(pil.twin.mismatches > 0);
            counts_bad += u32::from(!c.same_counts);
            over += u32::from(c.miss_diff_m > bound);
            worst = worst.max(c.miss_diff_m);
        }
        println!(
            "{vehicle}: {n} cases on {target}: twin differs in {twin_bad}; counts differ in {counts_bad}; \
             largest |miss diff| {:.3} km; over the {:.3} km bound in {over}",
            worst / 1e3,
            bound / 1e3
        );
    }
}
