//! Dispersion campaigns: lateral guidance hits the target in the nominal closed loop, a small
//! campaign is bit-identical across thread counts and resumes, bad settings name the field.

use host_sim::campaign::run::RunOptions;
use host_sim::campaign::settings::Dispersion;
use host_sim::campaign::{
    CampaignError, CampaignSetup, DispersionSettings, Mode, parse_settings, run_campaign,
};
use host_sim::scenario::guidance_layers::{LAYER_KEYS, scenario_key};
use host_sim::scenario::{Scenario, TerminalInterface};

/// The guidance layers' settings of `flat` (lines `field = value` in the settings' field names,
/// [`LAYER_KEYS`]) written as a scenario's `[guidance.<layer>]` sections (an unknown field
/// goes to `[guidance.replanning]`), parsed as a scenario file `file`; a scenario error as a
/// [`CampaignError::Setting`] (field, value, reason), so `field_of` reads both.
fn parse_layers(flat: &str, file: &str) -> Result<Layered, CampaignError> {
    let mut sections: std::collections::BTreeMap<&str, String> = std::collections::BTreeMap::new();
    for line in flat.lines().filter(|l| !l.trim().is_empty()) {
        let (field, value) = line.split_once('=').unwrap();
        let (field, value) = (field.trim(), value.trim());
        let keys: Vec<_> = LAYER_KEYS.iter().filter(|(f, _, _)| *f == field).collect();
        match keys.as_slice() {
            [] => sections
                .entry("replanning")
                .or_default()
                .push_str(&format!("{line}\n")),
            [(_, sec, key)] => sections
                .entry(sec)
                .or_default()
                .push_str(&format!("{key} = {value}\n")),
            // path_bound_barrier = [w, z]: two keys.
            [(_, sec, k1), (_, _, k2)] => {
                let v = value.trim_start_matches('[').trim_end_matches(']');
                let (w, z) = v.split_once(',').unwrap();
                sections.entry(sec).or_default().push_str(&format!(
                    "{k1} = {}\n{k2} = {}\n",
                    w.trim(),
                    z.trim()
                ));
            }
            _ => unreachable!(),
        }
    }
    // Every layer on (the setting of a layer not written reaches the campaign's full stack).
    let mut text = String::from("[guidance.target]\nnominal = true\n");
    for sec in ["lateral", "replanning", "estimator", "barrier"] {
        if sec == "barrier" && !sections.contains_key("barrier") {
            continue;
        }
        text.push_str(&format!(
            "[guidance.{sec}]\n{}",
            sections.get(sec).cloned().unwrap_or_default()
        ));
    }
    match host_sim::scenario::parse_scenario(
        &crate::support::complete_scenario(&text),
        file,
        std::path::Path::new("."),
    ) {
        Ok(sc) => Ok(Layered {
            guidance: sc.layers.unwrap().settings,
        }),
        Err(host_sim::scenario::ScenarioError::Field {
            file,
            field,
            value,
            reason,
        }) => Err(CampaignError::Setting {
            file,
            field,
            value,
            reason,
        }),
        Err(e) => panic!("{e}"),
    }
}

/// What [`parse_layers`] gives.
#[derive(Debug)]
struct Layered {
    guidance: host_sim::campaign::CampaignGuidance,
}

/// The SRM glide with its terminal interface at 2.5 km/s (start of the terminal area).
fn srm_setup() -> CampaignSetup {
    CampaignSetup::new(&Scenario::srm_glide(), "builtin:srm-glide", Some(2500.0)).unwrap()
}

/// Nominal closed loop (no dispersion): bank reversals steer the stored profile to the target
/// point 18 000 km downrange within 5 km, where the constant-sign profile misses by thousands
/// of km; the re-planner with reversals also arrives within 5 km.
#[test]
fn nominal_flight_with_reversals_hits_its_target() {
    let setup = srm_setup();
    let fly = |m| host_sim::campaign::flight::fly_case(&setup, None, m).unwrap();
    let stored = fly(Mode::Stored);
    let rev = fly(Mode::StoredReversals);
    let replan = fly(Mode::ReplanReversals);
    assert!(rev.reached_interface && replan.reached_interface);
    assert!(rev.miss_m < 5e3, "stored + reversals miss {} m", rev.miss_m);
    assert!(
        replan.miss_m < 5e3,
        "re-planning + reversals miss {} m",
        replan.miss_m
    );
    assert!(
        stored.miss_m > 1e6,
        "constant sign miss {} m",
        stored.miss_m
    );
    assert!(rev.reversals >= 2 && replan.replans > 100);
    assert!(rev.crossrange_error_m.abs() < 5e3);
}

fn small(cases: u32) -> DispersionSettings {
    DispersionSettings {
        cases,
        seed: 7,
        interface_speed_m_s: Some(2500.0),
        ..DispersionSettings::default()
    }
}

/// 20 flights on 1 and on 2 threads give bit-identical results; a second run into the same
/// directory reuses every case and gives the same statistics.
#[test]
fn campaign_is_bit_identical_across_thread_counts_and_resumes() {
    let setup = srm_setup();
    let s = small(20);
    let opts = |threads, out_dir| RunOptions {
        modes: vec![Mode::StoredReversals],
        out_dir,
        threads: Some(threads),
        progress: false,
    };
    let one = run_campaign(&setup, &s, &opts(1, None)).unwrap();
    let two = run_campaign(&setup, &s, &opts(2, None)).unwrap();
    let bits = |o: &host_sim::campaign::CampaignOutput| -> Vec<u64> {
        o.cases[0]
            .1
            .iter()
            .flat_map(|c| {
                [
                    c.miss_m.to_bits(),
                    c.peak_g_load.to_bits(),
                    c.flight_time_s.to_bits(),
                ]
            })
            .collect()
    };
    assert_eq!(one.cases[0].1.len(), 20);
    assert_eq!(bits(&one), bits(&two));
    assert_eq!(one.cases[0].1, two.cases[0].1);
    // Dispersed cases differ from each other.
    assert_ne!(one.cases[0].1[0].miss_m, one.cases[0].1[1].miss_m);
    // Resume: a first run writes the cases, the second reuses all of them.
    let dir = std::env::temp_dir().join(format!("host-sim-campaign-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let s4 = small(4);
    let first = run_campaign(&setup, &s4, &opts(2, Some(dir.clone()))).unwrap();
    let again = run_campaign(&setup, &s4, &opts(1, Some(dir.clone()))).unwrap();
    assert_eq!((first.resumed, again.resumed), (0, 4));
    assert_eq!(first.cases, again.cases);
    assert_eq!(first.cases[0].1[..], one.cases[0].1[..4]);
    let _ = std::fs::remove_dir_all(&dir);
}

fn field_of(e: CampaignError) -> String {
    match e {
        CampaignError::Setting { field, .. } => field,
        other => panic!("not a setting error: {other}"),
    }
}

#[test]
fn bad_dispersion_settings_name_the_field() {
    let bad = |text: &str| field_of(parse_settings(text, "d.toml").unwrap_err());
    assert_eq!(bad("[dispersions]\ncases = 0\n"), "dispersions.cases");
    assert_eq!(
        bad("[dispersions]\nspeed_m_s = { distribution = \"normal\", three_sigma = -1.0 }\n"),
        "dispersions.speed_m_s.three_sigma"
    );
    assert_eq!(
        bad("[dispersions]\nmass = { distribution = \"lognormal\", three_sigma = 0.1 }\n"),
        "dispersions.mass.distribution"
    );
    assert_eq!(
        bad("[dispersions]\nspeeed_m_s = 3\n"),
        "dispersions.speeed_m_s"
    );
    assert_eq!(
        bad("[dispersions]\nimu_noise_m_s2 = -0.1\n"),
        "dispersions.imu_noise_m_s2"
    );
    assert_eq!(
        bad("[dispersions]\nimu_bias_m_s2 = { distribution = \"cauchy\", three_sigma = 0.1 }\n"),
        "dispersions.imu_bias_m_s2.distribution"
    );
    let e = parse_settings("[dispersions]\ncases = 0\n", "d.toml").unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.contains("d.toml") && msg.contains("cases") && msg.contains('0'),
        "{msg}"
    );
    // Defaults are valid; a file without the section gives them.
    assert_eq!(
        parse_settings("", "d.toml").unwrap(),
        DispersionSettings::default()
    );
    let s = DispersionSettings {
        drag: Dispersion {
            distribution: "uniform".into(),
            three_sigma: 0.06,
        },
        ..DispersionSettings::default()
    };
    assert!(s.validate("x").is_ok());
}

/// A case whose flight fails (here: an entry altitude dispersion that puts some entries below
/// the surface) is recorded with its error, and the other cases are flown and counted.
#[test]
fn a_failed_case_is_recorded_and_the_campaign_goes_on() {
    let setup = srm_setup();
    let s = DispersionSettings {
        altitude_km: Dispersion {
            distribution: "uniform".into(),
            three_sigma: 300.0,
        },
        ..small(10)
    };
    let opts = RunOptions {
        modes: vec![Mode::StoredReversals],
        out_dir: None,
        threads: Some(2),
        progress: false,
    };
    let out = run_campaign(&setup, &s, &opts).unwrap();
    let flown = out.cases[0].1.len();
    assert!(
        !out.failed.is_empty() && flown > 0,
        "{} failed",
        out.failed.len()
    );
    assert_eq!(flown + out.failed.len(), 10);
    assert_eq!(out.stats[0].failed, out.failed.len());
    assert_eq!(out.stats[0].cases, flown);
    for f in &out.failed {
        assert!(f.draw.altitude_m < -100e3, "{f:?}");
        assert!(f.error.contains("entry.altitude_m"), "{}", f.error);
        assert!(out.cases[0].1.iter().all(|c| c.index != f.index));
    }
}

/// Onboard estimation in the closed loop (SRM, re-planning with reversals): the L/D-scale
/// estimate converges to the true (1 + dC_L)/(1 + dC_D) of a dispersed case, and stays at 1
/// in the nominal world; the drag scale sees the density bias. With it the re-planner lands
/// closer than without.
#[test]
fn onboard_estimation_converges_to_the_true_scale_in_the_closed_loop() {
    use host_sim::campaign::draw::CaseDraw;
    let setup = srm_setup();
    let fly = |d: Option<&CaseDraw>, m| host_sim::campaign::flight::fly_case(&setup, d, m).unwrap();
    let nominal = fly(None, Mode::ReplanEstimation);
    let [ld, _] = nominal.estimated_scales.unwrap();
    assert!((ld - 1.0).abs() < 1e-3, "nominal L/D scale {ld}");
    let draw = CaseDraw {
        index: 0,
        altitude_m: 300.0,
        speed_m_s: -5.0,
        flight_path_angle_rad: 0.0,
        heading_rad: 0.0,
        latitude_rad: 0.0,
        longitude_rad: 0.0,
        density_bias: 0.08,
        density_wave: 0.0,
        density_phase_rad: 0.0,
        density_wavelength_m: 20e3,
        lift: -0.05,
        drag: 0.03,
        mass: 0.0,
        ..CaseDraw::default()
    };
    let est = fly(Some(&draw), Mode::ReplanEstimation);
    let without = fly(Some(&draw), Mode::ReplanReversals);
    assert!(without.estimated_scales.is_none());
    let [ld, drag] = est.estimated_scales.unwrap();
    let true_ld = 0.95 / 1.03;
    assert!(
        (ld - true_ld).abs() < 2e-3,
        "L/D scale {ld}, true {true_ld}"
    );
    // Density +8 % and C_D +3 % at the end of the flight (the exponential model's own error at
    // the final altitude is in the drag scale too, so only the direction is checked).
    assert!(drag > 1.0, "drag scale {drag}");
    assert!(est.reached_interface);
    assert!(
        est.miss_m < without.miss_m && est.miss_m < 5e3,
        "miss with estimation {} m, without {} m",
        est.miss_m,
        without.miss_m
    );
}

/// The simulated IMU (bias, scale factor, white noise; defaults on) is drawn per case and
/// seeded: flights with onboard estimation are bit-identical on 1 and 2 threads, and the noise
/// reaches the estimate (the final L/D scale differs from an exact IMU's, by less than 1 %).
#[test]
fn imu_noise_is_seeded_and_reaches_the_estimate() {
    let setup = srm_setup();
    let opts = |threads| RunOptions {
        modes: vec![Mode::ReplanEstimation],
        out_dir: None,
        threads: Some(threads),
        progress: false,
    };
    let noisy = small(3);
    assert!(noisy.imu_noise_m_s2 > 0.0 && noisy.imu_bias_m_s2.three_sigma > 0.0);
    let exact = DispersionSettings {
        imu_noise_m_s2: 0.0,
        imu_bias_m_s2: Dispersion {
            distribution: "normal".into(),
            three_sigma: 0.0,
        },
        imu_scale_factor: Dispersion {
            distribution: "normal".into(),
            three_sigma: 0.0,
        },
        ..small(3)
    };
    let one = run_campaign(&setup, &noisy, &opts(1)).unwrap();
    let two = run_campaign(&setup, &noisy, &opts(2)).unwrap();
    assert_eq!(one.cases[0].1, two.cases[0].1);
    let off = run_campaign(&setup, &exact, &opts(2)).unwrap();
    for (n, e) in one.cases[0].1.iter().zip(&off.cases[0].1) {
        let [ln, _] = n.estimated_scales.unwrap();
        let [le, _] = e.estimated_scales.unwrap();
        assert_ne!(ln, le);
        assert!(
            (ln / le - 1.0).abs() < 0.01,
            "L/D scale {ln} noisy, {le} exact"
        );
    }
}

/// The scenario's `[guidance.<layer>]` settings: bad values name the field; other settings
/// change the flights, and
/// cases stored by a run with other settings are not reused.
#[test]
fn guidance_settings_are_configurable_and_checked() {
    assert_eq!(
        field_of(parse_layers("replan_every_n_ticks = 0", "d.toml").unwrap_err()),
        scenario_key("replan_every_n_ticks")
    );
    assert_eq!(
        field_of(parse_layers("estimator_drag_gain = 1.5", "d.toml").unwrap_err()),
        scenario_key("estimator_drag_gain")
    );
    assert_eq!(
        field_of(parse_layers("estimator_lift_to_drag_bounds = [1.2, 2.0]", "d.toml").unwrap_err()),
        scenario_key("estimator_lift_to_drag_bounds")
    );
    assert_eq!(
        field_of(parse_layers("corridor_width_final_deg = -3", "d.toml").unwrap_err()),
        scenario_key("corridor_width_final_deg")
    );
    assert_eq!(
        field_of(parse_layers("replan_every = 2", "d.toml").unwrap_err()),
        "guidance.replanning.replan_every"
    );
    // The old settings table is refused, naming the new key of each of its settings.
    let e = parse_settings(
        "[dispersions.guidance]\nmax_reversals = 2\npath_bound_barrier = [0.2, 1.0]\n",
        "g.toml",
    )
    .unwrap_err()
    .to_string();
    for w in [
        "g.toml",
        "dispersions.guidance",
        "max_reversals -> [guidance.lateral] max_reversals",
        "path_bound_barrier -> [guidance.barrier] frequency_rad_s",
    ] {
        assert!(e.contains(w), "`{e}` lacks `{w}`");
    }
    let s = parse_settings(
        "[dispersions]\ncases = 3\nseed = 7\ninterface_speed_m_s = 2500.0\n",
        "g.toml",
    )
    .unwrap();
    let mut sc = Scenario::srm_glide();
    sc.layers.as_mut().unwrap().settings.max_reversals = 2;
    let other = CampaignSetup::new(&sc, "builtin:srm-glide", Some(2500.0)).unwrap();
    let default = srm_setup();
    let dir = std::env::temp_dir().join(format!("host-sim-campaign-g-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let opts = RunOptions {
        modes: vec![Mode::StoredReversals],
        out_dir: Some(dir.clone()),
        threads: Some(2),
        progress: false,
    };
    let a = run_campaign(&default, &small(3), &opts).unwrap();
    // Into the same directory: refused (its cases are of other settings), naming the field.
    match run_campaign(&other, &s, &opts) {
        Err(CampaignError::ResumeMismatch {
            field, old, new, ..
        }) => assert!(
            field == "scenario.layers"
                && old.contains("max_reversals: 12")
                && new.contains("max_reversals: 2"),
            "{field}: {old} -> {new}"
        ),
        r => panic!("resumed into a directory of other settings: {r:?}"),
    }
    let b = run_campaign(
        &other,
        &s,
        &RunOptions {
            out_dir: None,
            ..opts
        },
    )
    .unwrap();
    assert!(b.cases[0].1.iter().all(|c| c.reversals <= 2));
    assert_ne!(a.cases[0].1, b.cases[0].1);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `[guidance.replanning] predictor`: each name picks the re-planner's predictor of both
/// re-planning modes (the sink only with onboard estimation and `glide_sink`; the default
/// predictor is the hybrid); the closed forms end at the interface speed and the numerical
/// predictions at the interface energy (no offset); a bad name is an error naming the file,
/// field and value, and the removed `final_speed_offset_m_s` is refused naming the key that
/// replaces it.
#[test]
fn campaign_predictor_setting_picks_the_replanner_mode() {
    use guidance_core::replan::PredictorMode as P;
    use host_sim::campaign::CampaignPredictor;
    let parse = |text: &str| parse_layers(text, "p.toml").unwrap().guidance;
    assert_eq!(parse("").predictor, CampaignPredictor::Hybrid, "default");
    for (text, predictor, estimation, reversals) in [
        ("", CampaignPredictor::Hybrid, P::HybridSink, P::Hybrid),
        (
            "predictor = \"closed-form\"",
            CampaignPredictor::ClosedForm,
            P::AutoSink,
            P::Auto,
        ),
        (
            "predictor = \"closed-form\"\nglide_sink = false",
            CampaignPredictor::ClosedForm,
            P::Auto,
            P::Auto,
        ),
        (
            "predictor = \"numerical\"",
            CampaignPredictor::Numerical,
            P::Numerical,
            P::Numerical,
        ),
        (
            "predictor = \"hybrid\"",
            CampaignPredictor::Hybrid,
            P::HybridSink,
            P::Hybrid,
        ),
        (
            "predictor = \"hybrid\"\nglide_sink = false",
            CampaignPredictor::Hybrid,
            P::Hybrid,
            P::Hybrid,
        ),
    ] {
        let g = parse(text);
        assert_eq!(g.predictor, predictor, "{text}");
        assert_eq!(g.predictor.mode(g.glide_sink), estimation, "{text}");
        assert_eq!(g.predictor.mode(false), reversals, "{text}");
    }
    // The setting reaches the flights' re-planner (one set-up: nominal flights are not cheap).
    let g = parse("predictor = \"hybrid\"");
    let setup = CampaignSetup::with_guidance(
        &Scenario::srm_glide(),
        "builtin:srm-glide",
        Some(TerminalInterface::Speed { speed_m_s: 2500.0 }),
        &g,
    )
    .unwrap();
    assert_eq!(
        setup
            .stack_of(Mode::ReplanEstimation)
            .replan
            .unwrap()
            .solver
            .mode,
        P::HybridSink
    );
    let replan = setup.stack_of(Mode::ReplanReversals).replan.unwrap();
    assert_eq!(replan.solver.mode, P::Hybrid);
    assert_eq!(
        replan.solver.predictor.final_speed_m_s,
        setup.interface_speed_m_s
    );
    assert_eq!(replan.final_energy_j_kg, Some(setup.interface_energy_j_kg));
    assert_eq!(
        setup.guidance_key(),
        None,
        "the defaults are stored as none"
    );
    // The removed offset: refused, naming the key of the interface.
    let e = parse_layers("final_speed_offset_m_s = 25.0", "p.toml").unwrap_err();
    let msg = e.to_string();
    assert_eq!(
        field_of(e),
        "guidance.replanning.final_speed_offset_m_s",
        "{msg}"
    );
    for w in [
        "p.toml",
        "25",
        "removed",
        "[guidance.target] interface_speed_m_s",
    ] {
        assert!(msg.contains(w), "`{msg}` lacks `{w}`");
    }
    for (text, field, value) in [("predictor = \"fast\"", "predictor", "fast")] {
        let e = parse_layers(text, "p.toml").unwrap_err();
        let msg = e.to_string();
        assert_eq!(field_of(e), scenario_key(field), "{text}");
        for w in ["p.toml", value] {
            assert!(msg.contains(w), "`{msg}` lacks `{w}`");
        }
    }
}

/// Resume is safe: a run into a directory whose fingerprint differs in any input that changes
/// a flight and is not in a case's draw (interface speed, the scenario's integrator and
/// environment, the seed) is refused before anything is written, naming the field with its
/// old and new value; removing the fingerprint of a directory holding cases makes it
/// unverifiable (refused); identical inputs reuse every case with identical results and
/// files, more cases and another mode extend the directory.
#[test]
fn resume_refuses_other_inputs_and_reuses_identical_ones() {
    use host_sim::campaign::output::write_campaign;
    let setup = srm_setup();
    let dir = std::env::temp_dir().join(format!("host-sim-campaign-r-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let opts = |modes: Vec<Mode>| RunOptions {
        modes,
        out_dir: Some(dir.clone()),
        threads: Some(2),
        progress: false,
    };
    let stored = || opts(vec![Mode::Stored]);
    let s = small(2);
    let first = run_campaign(&setup, &s, &stored()).unwrap();
    write_campaign(&dir, &setup, &s, &first).unwrap();
    let files = |d: &std::path::Path| -> Vec<(String, Vec<u8>)> {
        let mut v: Vec<_> = std::fs::read_dir(d)
            .unwrap()
            .flatten()
            .filter(|e| e.path().is_file())
            .map(|e| {
                (
                    e.file_name().to_string_lossy().into_owned(),
                    std::fs::read(e.path()).unwrap(),
                )
            })
            .collect();
        v.sort();
        v
    };
    let before = files(&dir);
    let case_file = dir.join("cases/stored/000000.json");
    let case_bytes = std::fs::read(&case_file).unwrap();
    let refused = |setup: &CampaignSetup, s: &DispersionSettings| -> (String, String, String) {
        match run_campaign(setup, s, &stored()) {
            Err(e @ CampaignError::ResumeMismatch { .. }) => {
                let msg = e.to_string();
                assert!(
                    msg.contains(&dir.display().to_string()) && msg.contains("--out"),
                    "{msg}"
                );
                let CampaignError::ResumeMismatch {
                    field, old, new, ..
                } = e
                else {
                    unreachable!()
                };
                (field, old, new)
            }
            r => panic!("resumed into a directory of other inputs: {r:?}"),
        }
    };
    let other_speed = DispersionSettings {
        interface_speed_m_s: Some(2400.0),
        ..s.clone()
    };
    assert_eq!(
        refused(&setup, &other_speed),
        (
            "dispersions.interface_speed_m_s".into(),
            "2500.0".into(),
            "2400.0".into()
        )
    );
    let other_seed = DispersionSettings {
        seed: 8,
        ..s.clone()
    };
    assert_eq!(
        refused(&setup, &other_seed),
        ("dispersions.seed".into(), "7".into(), "8".into())
    );
    // The integrator's step settings and the environment are in no draw.
    let mut steps = setup.clone();
    steps.scenario.tolerances.h_max *= 0.5;
    let (field, old, new) = refused(&steps, &s);
    assert_eq!(field, "scenario.tolerances");
    assert!(old.contains("h_max") && old != new, "{old} / {new}");
    let mut env = setup.clone();
    env.scenario.environment.rotating = !env.scenario.environment.rotating;
    assert_eq!(refused(&env, &s).0, "scenario.environment.rotating");
    // Refused runs wrote nothing.
    assert_eq!(files(&dir), before);
    assert_eq!(std::fs::read(&case_file).unwrap(), case_bytes);
    // Identical inputs: every case reused, identical results and files.
    let again = run_campaign(&setup, &s, &stored()).unwrap();
    assert_eq!(again.resumed, 2);
    assert_eq!(again.cases, first.cases);
    assert_eq!(again.nominal, first.nominal);
    write_campaign(&dir, &setup, &s, &again).unwrap();
    assert_eq!(files(&dir), before);
    // More cases and another mode extend the campaign; the first mode still resumes.
    let both = run_campaign(
        &setup,
        &small(3),
        &opts(vec![Mode::Stored, Mode::StoredReversals]),
    )
    .unwrap();
    assert_eq!(both.resumed, 2);
    assert_eq!(both.cases[0].1[..2], first.cases[0].1[..]);
    assert_eq!(run_campaign(&setup, &s, &stored()).unwrap().resumed, 2);
    // Case results without a fingerprint (an earlier version's run) cannot be checked.
    std::fs::remove_file(dir.join("fingerprint.json")).unwrap();
    match run_campaign(&setup, &s, &stored()) {
        Err(CampaignError::ResumeUnverified { dir: d }) => assert_eq!(d, dir),
        r => panic!("resumed into an unverifiable directory: {r:?}"),
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The predictor's lift parameter: `profile_lift_parameter` gives 1 for the trim-only SRM
/// capsule (its polar's trim point is at maximum L/D) and, for HORUS-2B, the range-weighted
/// `C_L(alpha)/C_L*` of its stored profile (alpha 40 deg over most of the range: `C_L` 0.77
/// at Mach 20 against `C_L*` 0.206, lambda 3.73; 11.5 deg at the end, lambda 0.47), between
/// them; `[dispersions.guidance] predictor_lift_parameter` reaches the solver (default 1) and a
/// bad value names the field.
#[test]
fn predictor_lift_parameter_of_the_stored_profile() {
    use host_sim::campaign::flight::fly_plain;
    use host_sim::campaign::setup::{
        PREDICTOR_POLAR_MACH, profile_lift_parameter, profile_lift_schedule,
    };
    use host_sim::replan_loop::predictor_model;
    use host_sim::scenario::build_guidance;
    let lambda_of = |sc: &Scenario| {
        let vehicle = sc.load_vehicle().unwrap();
        let env = sc.environment.build();
        let g = build_guidance(sc, &env.planet, "t").unwrap();
        let nominal = fly_plain(sc, &env, &vehicle, g).unwrap();
        let fit =
            host_sim::env::ExponentialAtmosphere::fitted_to(env.atmosphere.as_ref(), 50e3, 100e3)
                .unwrap();
        let model = predictor_model(&vehicle, &fit, &env.planet, PREDICTOR_POLAR_MACH).unwrap();
        let end = nominal.samples.last().unwrap().state.speed_m_s;
        (
            profile_lift_parameter(&vehicle, &model, &nominal, "t").unwrap(),
            profile_lift_schedule(&vehicle, &model, &nominal, end),
        )
    };
    assert_eq!(lambda_of(&Scenario::srm_glide()), (1.0, None));
    let (horus, schedule) = lambda_of(&Scenario::default());
    assert!((3.4..3.73).contains(&horus), "HORUS-2B lambda {horus}");
    // 40 deg (lambda 3.73) until the ramp starts near 4 km/s, 11.5 deg (0.55) at the end.
    let s = schedule.unwrap();
    let [hi, lo] = s.used() else { panic!("{s:?}") };
    assert!((hi.lambda - 3.733).abs() < 0.01, "{s:?}");
    assert!((lo.lambda - 0.552).abs() < 0.01, "{s:?}");
    assert!((3500.0..4500.0).contains(&hi.speed_m_s), "{s:?}");
    assert!((700.0..900.0).contains(&lo.speed_m_s), "{s:?}");
    let parse = |text: &str| parse_layers(text, "l.toml");
    assert_eq!(parse("").unwrap().guidance.predictor_lift_parameter, None);
    let g = parse("predictor_lift_parameter = 3.5").unwrap().guidance;
    let setup = CampaignSetup::with_guidance(
        &Scenario::srm_glide(),
        "builtin:srm-glide",
        Some(TerminalInterface::Speed { speed_m_s: 2500.0 }),
        &g,
    )
    .unwrap();
    assert_eq!(setup.stack.replan.unwrap().solver.lambda, 3.5);
    assert_eq!(srm_setup().stack.replan.unwrap().solver.lambda, 1.0);
    for v in ["0.0", "-1.0", "25.0", "nan"] {
        let e = parse(&format!("predictor_lift_parameter = {v}")).unwrap_err();
        assert_eq!(field_of(e), scenario_key("predictor_lift_parameter"), "{v}");
    }
}

/// `[dispersions.guidance] path_bound_limit_scale`, `path_bound_descent_time_s` and
/// `path_bound_barrier` reach the set-up as a `PathBound` on the vehicle's limits (none by
/// default); bad values name the field.
#[test]
fn path_bound_settings_reach_the_setup() {
    let parse = |text: &str| parse_layers(text, "p.toml");
    assert_eq!(srm_setup().stack.barrier, None);
    let g = parse("path_bound_limit_scale = [100, 0.9]\npath_bound_descent_time_s = 20")
        .unwrap()
        .guidance;
    let setup = CampaignSetup::with_guidance(
        &Scenario::srm_glide(),
        "builtin:srm-glide",
        Some(TerminalInterface::Speed { speed_m_s: 2500.0 }),
        &g,
    )
    .unwrap();
    let b = setup.stack.barrier.unwrap().bound;
    let own = setup.scenario.load_vehicle().unwrap().limits;
    assert_eq!(b.limits.heat_flux_w_m2, own.heat_flux_w_m2 * 100.0);
    assert_eq!(b.limits.g_load, own.g_load * 0.9);
    assert_eq!(b.descent_time_s, 20.0);
    for v in ["[0, 1]", "[1, -1]", "[1, 101]", "[nan, 1]"] {
        let e = parse(&format!("path_bound_limit_scale = {v}")).unwrap_err();
        assert_eq!(field_of(e), scenario_key("path_bound_limit_scale"), "{v}");
    }
    for v in ["-1.0", "1001.0", "nan"] {
        let e = parse(&format!("path_bound_descent_time_s = {v}")).unwrap_err();
        assert_eq!(
            field_of(e),
            scenario_key("path_bound_descent_time_s"),
            "{v}"
        );
    }
    // The barrier law: off (0, 0) by default, [omega, zeta] when set.
    assert_eq!((b.barrier_frequency_rad_s, b.barrier_damping), (0.0, 0.0));
    let g = parse("path_bound_limit_scale = [1, 1]\npath_bound_barrier = [0.15, 0.8]")
        .unwrap()
        .guidance;
    let setup = CampaignSetup::with_guidance(
        &Scenario::srm_glide(),
        "builtin:srm-glide",
        Some(TerminalInterface::Speed { speed_m_s: 2500.0 }),
        &g,
    )
    .unwrap();
    let b = setup.stack.barrier.unwrap().bound;
    assert!(b.is_barrier());
    assert_eq!((b.barrier_frequency_rad_s, b.barrier_damping), (0.15, 0.8));
    for v in [
        "[0, 1]",
        "[-0.1, 1]",
        "[1.5, 1]",
        "[0.1, -1]",
        "[0.1, 11]",
        "[nan, 1]",
    ] {
        let e = parse(&format!("path_bound_barrier = {v}")).unwrap_err();
        assert_eq!(field_of(e), scenario_key("path_bound_barrier"), "{v}");
    }
}

/// `[dispersions.guidance] predictor_rotation` (default off) is read with a numerical or hybrid
/// predictor and refused, naming the file, field and value, with the closed forms.
#[test]
fn predictor_rotation_setting_needs_numerical_predictions() {
    let parse = |text: &str| parse_layers(text, "p.toml");
    assert!(!parse("").unwrap().guidance.predictor_rotation);
    for p in ["numerical", "hybrid"] {
        let g = parse(&format!("predictor = \"{p}\"\npredictor_rotation = true"))
            .unwrap()
            .guidance;
        assert!(g.predictor_rotation, "{p}");
    }
    let e = parse("predictor = \"closed-form\"\npredictor_rotation = true").unwrap_err();
    let text = e.to_string();
    assert!(text.contains("p.toml") && text.contains("true"), "{text}");
    assert_eq!(field_of(e), scenario_key("predictor_rotation"));
}

/// `[dispersions.guidance] terminal_lateral_km` (default off) builds the lateral logic's
/// terminal law in SI units; bad values of it and of its tolerance and lead are errors naming
/// the file, field and value.
#[test]
fn terminal_lateral_settings_are_read_and_checked() {
    let parse = |text: &str| parse_layers(text, "p.toml");
    let g = parse("").unwrap().guidance;
    assert_eq!(g.terminal_lateral_km, None);
    assert_eq!(
        (g.terminal_tolerance_km, g.terminal_reversal_lead_s),
        (1.0, 5.0)
    );
    let g = parse("terminal_lateral_km = 200.0\nfreeze_km = 5.0\nterminal_tolerance_km = 0.5")
        .unwrap()
        .guidance;
    let setup = CampaignSetup::with_guidance(
        &Scenario::srm_glide(),
        "builtin:srm-glide",
        Some(TerminalInterface::Speed { speed_m_s: 2500.0 }),
        &g,
    )
    .unwrap();
    let t = setup.stack.lateral.unwrap().terminal.unwrap();
    let r = setup.planet_radius_m;
    assert!((t.start_angle_rad * r - 200e3).abs() < 1e-6);
    assert!((t.tolerance_rad * r - 500.0).abs() < 1e-9);
    assert_eq!(t.reversal_lead_s, 5.0);
    for (text, field, value) in [
        ("terminal_lateral_km = 20.0", "terminal_lateral_km", "20"),
        ("terminal_lateral_km = nan", "terminal_lateral_km", "NaN"),
        (
            "terminal_lateral_km = 3000.0",
            "terminal_lateral_km",
            "3000",
        ),
        ("terminal_tolerance_km = 0.0", "terminal_tolerance_km", "0"),
        (
            "terminal_tolerance_km = -1.0",
            "terminal_tolerance_km",
            "-1",
        ),
        (
            "terminal_reversal_lead_s = -1.0",
            "terminal_reversal_lead_s",
            "-1",
        ),
        (
            "terminal_reversal_lead_s = 61.0",
            "terminal_reversal_lead_s",
            "61",
        ),
    ] {
        let e = parse(text).unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.contains("p.toml") && msg.contains(value),
            "{text}: {msg}"
        );
        assert_eq!(field_of(e), scenario_key(field), "{text}");
    }
}

/// The report's traced replays: the replayed record is the campaign's bit for bit, the worst
/// flights come largest miss first, and each error history ends (time to go 0) at the
/// flight's footprint point and starts at the longest time to go both flights share.
#[test]
fn report_replays_the_worst_flights_with_their_error_histories() {
    use host_sim::campaign::report::mode_report;
    use host_sim::campaign::run::replay_case_traced;
    let setup = srm_setup();
    let s = small(4);
    let opts = RunOptions {
        modes: vec![Mode::StoredReversals],
        out_dir: None,
        threads: Some(2),
        progress: false,
    };
    let out = run_campaign(&setup, &s, &opts).unwrap();
    let cases = &out.cases[0].1;
    let (again, sim) = replay_case_traced(&setup, &s, Mode::StoredReversals, Some(2)).unwrap();
    assert_eq!(&again, &cases[2]);
    assert!(sim.samples.len() > 100, "{} samples", sim.samples.len());
    let r = mode_report(&setup, &s, &out, Mode::StoredReversals).unwrap();
    assert_eq!(r.flights.len(), 4);
    assert_eq!(r.traces.len(), 4);
    let misses: Vec<f64> = r.traces.iter().map(|t| t.miss_km).collect();
    assert!(misses.windows(2).all(|w| w[0] >= w[1]), "{misses:?}");
    for t in &r.traces {
        let c = cases.iter().find(|c| c.index == t.id).unwrap();
        let end = t.points.last().unwrap();
        assert_eq!(end.time_to_go_s, 0.0);
        assert!(
            (end.downrange_km - c.downrange_error_m / 1e3).abs() < 1e-6
                && (end.crossrange_km - c.crossrange_error_m / 1e3).abs() < 1e-6,
            "case {}: ends at {end:?}, footprint ({}, {}) km",
            t.id,
            c.downrange_error_m / 1e3,
            c.crossrange_error_m / 1e3
        );
        let first = t.points.first().unwrap().time_to_go_s;
        let nominal = out.nominal[0].flight_time_s;
        assert!(first <= nominal.min(c.flight_time_s) + 1e-9, "{first}");
        assert!(first > 0.9 * nominal.min(c.flight_time_s), "{first}");
    }
}
