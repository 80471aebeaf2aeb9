//! One scenario with every guidance layer on (`examples/horus-2b-stack.toml` over the complete HORUS-2B
//! scenario: re-planning,
//! lateral with the terminal law, estimator, barrier, target) flown three ways: `simulate`
//! (`scenario::fly`, the library call), a 1-case campaign with every dispersion zero, and the
//! `--case` replay of that case (`campaign::run::replay_case`, what `host-sim dispersions
//! ... --case ID` calls). They fly one stack built in one place, so the records agree bit for
//! bit. In PIL (`pil_flies_the_one_file_stack_on_both_targets`): `simulate --pil`'s flight on
//! the Cortex-M4F and the Cortex-M3, and the 1-case campaign's PIL leg (`dispersions --pil
//! ELF --pil-cases 1`) on the M4F, against their twin and the SIL flights above. The Python
//! leg (`reentry.fly` and a 1-case `DispersionCampaign` of the same file) is
//! `python/tests/test_flight.py::test_the_one_stack_file_flies_in_python_as_in_simulate_and_a_one_case_campaign`.

use host_sim::campaign::run::{Replay, RunOptions, replay_case};
use host_sim::campaign::{CampaignSetup, DispersionSettings, Mode, run_campaign};
use host_sim::pil::{PilConfig, fly_campaign_pil, fly_scenario_pil};
use host_sim::scenario::{Scenario, fly, parse_scenario};

use crate::pil_support::{pil_elf, pil_required};

const FILE: &str = "horus-2b-stack.toml";

/// `examples/horus-2b-stack.toml` over the complete HORUS-2B scenario.
fn scenario() -> Scenario {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/horus-2b-stack.toml"
    );
    let text = crate::support::complete_scenario(&std::fs::read_to_string(path).unwrap());
    parse_scenario(&text, FILE, std::path::Path::new(".")).unwrap()
}

fn zero_dispersions() -> DispersionSettings {
    let text = "[dispersions]\ncases = 1\nseed = 11\n\
        altitude_km = { distribution = \"normal\", three_sigma = 0.0 }\nspeed_m_s = { distribution = \"normal\", three_sigma = 0.0 }\n\
        flight_path_angle_deg = { distribution = \"normal\", three_sigma = 0.0 }\nheading_deg = { distribution = \"normal\", three_sigma = 0.0 }\n\
        latitude_deg = { distribution = \"normal\", three_sigma = 0.0 }\nlongitude_deg = { distribution = \"normal\", three_sigma = 0.0 }\n\
        density_bias = { distribution = \"normal\", three_sigma = 0.0 }\ndensity_wave = { distribution = \"normal\", three_sigma = 0.0 }\n\
        lift = { distribution = \"normal\", three_sigma = 0.0 }\ndrag = { distribution = \"normal\", three_sigma = 0.0 }\nmass = { distribution = \"normal\", three_sigma = 0.0 }\n\
        imu_bias_m_s2 = { distribution = \"normal\", three_sigma = 0.0 }\nimu_scale_factor = { distribution = \"normal\", three_sigma = 0.0 }\n\
        imu_noise_m_s2 = 0.0\n";
    host_sim::campaign::parse_settings(text, "zero.toml").unwrap()
}

#[test]
fn simulate_a_one_case_campaign_and_its_replay_fly_the_same_stack() {
    let file = FILE;
    let sc = scenario();
    let l = sc.layers.as_ref().unwrap().layers;
    assert_eq!(l, guidance_core::stack::Layers::ALL, "every layer on");
    assert_eq!(
        sc.output_interval_s, 0.0,
        "samples at the ticks, as a campaign"
    );

    // simulate: the library call behind `host-sim simulate --scenario`.
    let flight = fly(&sc, file, &mut |_| {}).unwrap();
    let stack = flight.stack.as_ref().unwrap();
    assert_eq!(stack.case.mode, Mode::ReplanEstimation);
    assert!(stack.case.reached_interface);
    assert!(
        stack.case.replans > 10 && stack.case.reversals > 0,
        "{stack:?}"
    );
    let summary = flight.summary(&sc, &sc.name);
    let t = summary.target.as_ref().unwrap();
    assert_eq!(t.miss_km, stack.case.miss_m / 1e3);
    assert!(t.miss_km < 10.0, "nominal miss {} km", t.miss_km);
    let end = flight.result.samples.last().unwrap().state;
    assert_eq!(end.latitude_rad, stack.case.final_latitude_rad);
    assert_eq!(end.speed_m_s, stack.case.final_speed_m_s);

    // A 1-case campaign of the same scenario, every dispersion zero.
    let settings = zero_dispersions();
    let setup = CampaignSetup::new(&sc, file, None).unwrap();
    let dir = std::env::temp_dir().join(format!("host-sim-it-stack-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let out = run_campaign(
        &setup,
        &settings,
        &RunOptions {
            modes: vec![Mode::ReplanEstimation],
            out_dir: Some(dir.clone()),
            threads: Some(1),
            progress: false,
        },
    )
    .unwrap();
    // Its nominal flight is simulate's, record for record.
    assert_eq!(out.nominal, vec![stack.case.clone()]);
    // Its one case (undispersed) flies the same flight: only the index and the draw differ.
    let (_, cases) = &out.cases[0];
    let case = &cases[0];
    let mut as_nominal = case.clone();
    as_nominal.index = stack.case.index;
    as_nominal.draw = None;
    assert_eq!(as_nominal, stack.case);

    // The `--case` replay reproduces the campaign's record byte for byte.
    let (replayed, replay) =
        replay_case(&setup, &settings, Mode::ReplanEstimation, 0, Some(&dir)).unwrap();
    assert_eq!(replay, Replay::Same);
    assert_eq!(&replayed, case);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The same file in PIL. `simulate --pil` (`fly_scenario_pil`) on the Cortex-M4F (`f32`) and
/// the Cortex-M3 (fixed-point tick, `f32` layers): every command frame equals the host twin.
/// On the M4F, against the `f64` flights: the 1-case campaign's PIL leg (`fly_campaign_pil`,
/// what `dispersions --pil ELF --pil-cases 1` runs) passes its tolerances for the nominal
/// flight and the undispersed case 0 (same counts, same ending, miss within the bound), and
/// its nominal PIL flight is `simulate --pil`'s, bit for bit. The M3 against the `f64` SIL is
/// printed, not asserted (as in `pil_campaign.rs`: its counts can differ, docs/guides/pil.md).
#[test]
fn pil_flies_the_one_file_stack_on_both_targets() {
    let sc = scenario();
    let sil = fly(&sc, FILE, &mut |_| {}).unwrap();
    let sil = &sil.stack.as_ref().unwrap().case;
    for target in ["thumbv7em-none-eabihf", "thumbv7m-none-eabi"] {
        let cfg = PilConfig::new(pil_elf(target));
        if let Err(e) = cfg.check_tools() {
            assert!(
                !pil_required(),
                "PIL required (PIL_REQUIRED or CI=true): {e}"
            );
            eprintln!("SKIPPED pil_flies_the_one_file_stack_on_both_targets on {target}: {e}");
            continue;
        }
        let t0 = std::time::Instant::now();
        let (run, _record) = fly_scenario_pil(&sc, FILE, cfg.clone());
        let pil = run.unwrap_or_else(|e| panic!("{target}: {e}"));
        let p = &pil.stack.as_ref().unwrap().case;
        println!(
            "{target}: simulate --pil in {:.1} s: twin {}/{} ticks differ; PIL miss {:.3} km, {} \
             reversals, {} re-plans; SIL miss {:.3} km, {} reversals, {} re-plans",
            t0.elapsed().as_secs_f64(),
            pil.twin.mismatches,
            pil.twin.ticks,
            p.miss_m / 1e3,
            p.reversals,
            p.replans,
            sil.miss_m / 1e3,
            sil.reversals,
            sil.replans
        );
        assert_eq!(pil.twin.mismatches, 0, "{target}: {:?}", pil.twin.first);
        assert!(pil.twin.ticks > 100, "{target}: {} ticks", pil.twin.ticks);
        assert_eq!(p.mode, Mode::ReplanEstimation, "{target}");
        if target != "thumbv7em-none-eabihf" {
            continue;
        }
        // The 1-case campaign (every dispersion zero) and its PIL leg.
        let settings = zero_dispersions();
        let setup = CampaignSetup::new(&sc, FILE, None).unwrap();
        let out = run_campaign(
            &setup,
            &settings,
            &RunOptions {
                modes: vec![Mode::ReplanEstimation],
                out_dir: None,
                threads: Some(1),
                progress: false,
            },
        )
        .unwrap();
        let checks =
            fly_campaign_pil(&setup, &settings, &out, Mode::ReplanEstimation, 1, &cfg).unwrap();
        assert_eq!(checks.len(), 2);
        for c in &checks {
            let s = c.outcome.as_ref().unwrap();
            println!("{target}: campaign PIL leg {:?}: {s:?}", c.index);
            assert!(c.passed(), "{target} {:?}: {s:?}", c.index);
            // The campaign's PIL flights are `simulate --pil`'s, and its SIL records
            // `simulate`'s (the case is undispersed).
            assert_eq!(s.pil_miss_m.to_bits(), p.miss_m.to_bits(), "{:?}", c.index);
            assert_eq!((s.pil_reversals, s.pil_replans), (p.reversals, p.replans));
            assert_eq!(
                s.sil_miss_m.to_bits(),
                sil.miss_m.to_bits(),
                "{:?}",
                c.index
            );
            assert_eq!(s.twin.ticks, pil.twin.ticks);
        }
    }
}

/// A scenario whose layers make no campaign mode (re-planning without bank reversals) is
/// refused by `simulate`, naming the missing section: it never flies less than it writes.
#[test]
fn simulate_refuses_layers_that_make_no_mode() {
    let text = crate::support::complete_scenario(
        "[guidance.replanning]\n[guidance.target]\nnominal = true\n",
    );
    let sc = parse_scenario(&text, "r.toml", std::path::Path::new(".")).unwrap();
    let e = fly(&sc, "r.toml", &mut |_| {}).unwrap_err().to_string();
    assert!(
        e.contains("r.toml") && e.contains("guidance.lateral"),
        "{e}"
    );
}

/// A `[replanning]` section (here beside the guidance layers; without them too:
/// `scenario_files::old_replanning_section_is_refused`) is refused, naming the new key of each
/// old one it holds (one set of names per setting).
#[test]
fn replanning_beside_the_layers_names_the_new_keys() {
    let text = crate::support::complete_scenario(
        "[guidance.lateral]\n[guidance.replanning]\n[guidance.target]\nnominal = true\n\
         [replanning]\nevery_n_ticks = 5\ntolerance_m = 500\nrange_km = 9000\nfinal_speed_m_s = 2500\n",
    );
    let e = parse_scenario(&text, "both.toml", std::path::Path::new("."))
        .unwrap_err()
        .to_string();
    for part in [
        "both.toml",
        "`replanning`",
        "replanning.every_n_ticks -> [guidance.replanning] every_n_ticks",
        "replanning.tolerance_m -> [guidance.replanning] tolerance_km",
        "replanning.range_km -> [guidance.target] downrange_km",
        "replanning.final_speed_m_s -> [guidance.target] interface_speed_m_s",
    ] {
        assert!(e.contains(part), "`{part}` not in {e}");
    }
    assert!(!e.contains("max_skips"), "{e}");
    // Every old key has its entry.
    assert_eq!(host_sim::scenario::old_replanning::OLD_KEYS.len(), 17);
}
