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
//!   the crossrange the terminal law accepts. The `f32` and fixed-point rounding changes where inside those
//!   accepted sets each flight ends, not the guidance's decisions (asserted by the counts);
//! * the firmware's whole-run stack and static RAM within `onboard-demo/size-budget.toml`.
//!
//! The reference (nominal) case and cases 0-4 of the default dispersions per vehicle run in
//! `cargo xtask pil` / `cargo xtask test` on the Cortex-M4F and on the Cortex-M3 (fixed-point
//! tick, `f32` layers), each with all three checks. 50 cases per vehicle:
//! `pil_campaign_50_cases` (ignored; docs/guides/pil.md has its figures).
//!
//! The comparison and the bound are the library's (`host_sim::pil::PilSilComparison`,
//! `host_sim::pil::miss_bound_m`), the ones `host-sim dispersions --pil ELF --pil-cases K`
//! prints; `pil_dispersions_cli_reference_mission_m4f` runs that command.

use host_sim::campaign::draw::draw_case;
use host_sim::campaign::flight::fly_case;
use host_sim::campaign::{CampaignSetup, CaseResult, DispersionSettings, Mode};
use host_sim::pil::{PilCase, PilConfig, PilError, PilSilComparison, fly_case_pil, miss_bound_m};
use host_sim::scenario::Scenario;

use crate::pil_support::{check_pil_memory_budget, pil_elf, pil_required};

const M4F: &str = "thumbv7em-none-eabihf";
const M3: &str = "thumbv7m-none-eabi";

fn setup(name: &str) -> CampaignSetup {
    let sc = Scenario::try_builtin(name).unwrap();
    CampaignSetup::new(&sc, &format!("builtin:{name}"), None).unwrap()
}

/// One case in PIL on `target`; `None` if QEMU or the ELF is missing (and not required).
fn pil_case(setup: &CampaignSetup, index: Option<u32>, target: &str) -> Option<PilCase> {
    let draw = index.map(|i| draw_case(&DispersionSettings::default(), i));
    let cfg = PilConfig::new(pil_elf(target));
    match fly_case_pil(setup, draw.as_ref(), Mode::ReplanEstimation, cfg) {
        Ok(r) => Some(r),
        Err(e @ (PilError::QemuMissing { .. } | PilError::ElfMissing(_))) if !pil_required() => {
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

/// The case against SIL (the library's comparison, `host_sim::pil::PilSilComparison`, the one
/// `host-sim dispersions --pil` prints), printed.
fn compare(label: &str, pil: &PilCase, sil: &CaseResult, bound_m: f64) -> PilSilComparison {
    let c = PilSilComparison::new(pil, sil, bound_m);
    println!(
        "{label}: image {} B; twin {}/{} ticks differ; PIL miss {:.3} km, {} reversals, {} re-plans; \
         SIL miss {:.3} km, {} reversals, {} re-plans; |miss diff| {:.3} km; stack {:?} B",
        c.image_bytes,
        c.twin.mismatches,
        c.twin.ticks,
        c.pil_miss_m / 1e3,
        c.pil_reversals,
        c.pil_replans,
        c.sil_miss_m / 1e3,
        c.sil_reversals,
        c.sil_replans,
        c.miss_diff_m / 1e3,
        c.firmware_stack_bytes,
    );
    c
}

/// The reference case and cases 0-4 of `vehicle` on `target`: the twin, the `f64` SIL
/// comparison and the memory budgets.
fn campaign_cases(vehicle: &str, target: &str) {
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
        let c = compare(&label, &pil, &sil, bound);
        assert_eq!(pil.twin.mismatches, 0, "{label}: {:?}", pil.twin.first);
        assert!(pil.twin.ticks > 100, "{label}: {} ticks", pil.twin.ticks);
        assert!(
            pil.result.reached_interface,
            "{label}: {}",
            pil.result.termination
        );
        assert!(
            c.same_counts,
            "{label}: reversal or re-plan count differs from SIL"
        );
        assert!(
            c.within_bound,
            "{label}: |miss PIL - SIL| {} m > {bound} m",
            c.miss_diff_m
        );
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
    campaign_cases("horus-2b-reference", M4F);
}

#[test]
fn pil_campaign_srm_m4f_matches_sil() {
    campaign_cases("srm-glide", M4F);
}

#[test]
fn pil_campaign_horus_m3_matches_sil() {
    campaign_cases("horus-2b-reference", M3);
}

#[test]
fn pil_campaign_srm_m3_matches_sil() {
    campaign_cases("srm-glide", M3);
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
            let c = compare(&format!("{vehicle} case {i}"), &pil, &sil, bound);
            twin_bad += u32::from(pil.twin.mismatches > 0);
            counts_bad += u32::from(!c.same_counts);
            over += u32::from(!c.within_bound);
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

/// `host-sim dispersions --pil ELF --pil-cases 2` on the reference mission (2 cases,
/// `replan-estimation`, the Cortex-M4F): exits 0, prints one line per flight (the nominal and
/// cases 0-1) and writes `pil-cases.csv`, whose SIL columns are the campaign's own records
/// (`cases/`) and whose PIL columns are `fly_case_pil`'s flight of the same case. Skipped
/// (with a message on stderr) without QEMU or the ELF, unless `PIL_REQUIRED` or `CI=true`.
#[test]
fn pil_dispersions_cli_reference_mission_m4f() {
    let elf = pil_elf(M4F);
    if let Err(e) = PilConfig::new(elf.clone()).check_tools() {
        assert!(
            !pil_required(),
            "PIL required (PIL_REQUIRED or CI=true): {e}"
        );
        eprintln!("SKIPPED pil_dispersions_cli_reference_mission_m4f: {e}");
        return;
    }
    let dir = std::env::temp_dir().join(format!("host-sim-it-pil-cli-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let t0 = std::time::Instant::now();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args([
            "dispersions",
            "-n",
            "2",
            "--modes",
            "replan-estimation",
            "--quiet",
        ])
        .arg("--pil")
        .arg(&elf)
        .args(["--pil-cases", "2", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    println!("{stdout}{}", String::from_utf8_lossy(&out.stderr));
    println!("dispersions --pil: {:.1} s", t0.elapsed().as_secs_f64());
    assert!(out.status.success(), "{}", out.status);
    assert!(
        stdout.contains("PIL: 3 of 3 flights within the tolerances"),
        "{stdout}"
    );
    let csv = std::fs::read_to_string(dir.join("pil-cases.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |row: &[&str], name: &str| -> String {
        let i = header.iter().position(|h| *h == name).unwrap();
        row[i].to_string()
    };
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 3, "{csv}");
    let setup = setup("horus-2b-reference");
    let settings = DispersionSettings {
        cases: 2,
        ..DispersionSettings::default()
    };
    for (row, index) in rows.iter().zip([None, Some(0), Some(1)]) {
        assert_eq!(row.len(), header.len(), "{csv}");
        let case = index.map_or_else(|| "nominal".to_string(), |i| i.to_string());
        assert_eq!(col(row, "case"), case);
        assert_eq!(col(row, "passed"), "true", "{csv}");
        assert_eq!(col(row, "twin_mismatches"), "0", "{csv}");
        assert_eq!(col(row, "bound_km"), "3", "{csv}");
        // The SIL columns are the campaign's record of the case, the PIL ones the firmware's
        // flight of it.
        let draw = index.map(|i| draw_case(&settings, i));
        let sil = fly_case(&setup, draw.as_ref(), Mode::ReplanEstimation).unwrap();
        assert_eq!(col(row, "sil_miss_km"), (sil.miss_m / 1e3).to_string());
        assert_eq!(col(row, "sil_reversals"), sil.reversals.to_string());
        let pil = fly_case_pil(
            &setup,
            draw.as_ref(),
            Mode::ReplanEstimation,
            PilConfig::new(elf.clone()),
        )
        .unwrap();
        assert_eq!(
            col(row, "pil_miss_km"),
            (pil.result.miss_m / 1e3).to_string()
        );
        assert_eq!(col(row, "pil_replans"), pil.result.replans.to_string());
    }
    // The SIL campaign wrote its records as without --pil.
    let records = dir.join("cases").join(Mode::ReplanEstimation.name());
    assert_eq!(
        records.read_dir().unwrap().count(),
        2,
        "{}",
        records.display()
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `dispersions --pil` refuses before flying: K = 0, K > n, a missing ELF (naming `--pil`
/// and the path), a campaign without a re-planning mode; and `--pil` without `--pil-cases`.
#[test]
fn pil_dispersions_cli_refuses_bad_arguments() {
    let elf = pil_elf(M4F);
    let run = |extra: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_host-sim"))
            .args(["dispersions", "-n", "2", "--quiet", "--out"])
            .arg(std::env::temp_dir().join(format!("host-sim-it-pil-bad-{}", std::process::id())))
            .args(extra)
            .output()
            .unwrap();
        assert!(!out.status.success(), "{extra:?} succeeded");
        String::from_utf8_lossy(&out.stderr).to_string()
    };
    let e = elf.to_str().unwrap();
    let msg = run(&["--pil", "/nonexistent/pil", "--pil-cases", "1"]);
    assert!(
        (msg.contains("`--pil` = /nonexistent/pil") && msg.contains("no such firmware ELF"))
            || msg.contains("QEMU"),
        "{msg}"
    );
    let msg = run(&["--pil", e]);
    assert!(msg.contains("--pil-cases"), "{msg}");
    if PilConfig::new(elf.clone()).check_tools().is_err() {
        assert!(!pil_required(), "PIL required: {}", elf.display());
        eprintln!("SKIPPED the rest of pil_dispersions_cli_refuses_bad_arguments: no QEMU or ELF");
        return;
    }
    for k in ["0", "3"] {
        let msg = run(&["--pil", e, "--pil-cases", k]);
        assert!(
            msg.contains(&format!("--pil-cases = {k}: fly 1 to 2 cases")),
            "{msg}"
        );
    }
    let msg = run(&[
        "--pil",
        e,
        "--pil-cases",
        "1",
        "--modes",
        "stored,stored-reversals",
    ]);
    assert!(
        msg.contains("modes = stored,stored-reversals") && msg.contains("re-planning mode"),
        "{msg}"
    );
}
