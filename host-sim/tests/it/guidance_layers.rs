//! The scenario's guidance layers (`[guidance.lateral]`, `[guidance.replanning]`,
//! `[guidance.estimator]`, `[guidance.barrier]`): a layer absent is off, the built-ins carry
//! their stacks and round-trip through the printed scenario, errors name file, field, value
//! and range, an old `[dispersions.guidance]` gets the new key of each setting, and the key
//! list, the printed template and the docs' key table agree key by key.

use guidance_core::stack::Layers;
use host_sim::campaign::{CampaignSetup, Mode, parse_settings};
use host_sim::scenario::guidance_layers::{LAYER_KEYS, TARGET_KEYS};
use host_sim::scenario::{Scenario, ScenarioError, parse_scenario, scenario_to_toml};

/// `text` over a complete scenario with no layer (the stored profile alone).
fn parse(text: &str) -> Result<Scenario, ScenarioError> {
    parse_scenario(
        &crate::support::complete_scenario(text),
        "s.toml",
        std::path::Path::new("."),
    )
}

/// A file's layers are the sections it writes; none: the stored profile alone (even though
/// the built-in mission it starts from has every layer).
#[test]
fn a_layer_absent_is_off() {
    assert_eq!(parse("").unwrap().layers, None);
    let sc = parse("[guidance.lateral]\n[guidance.target]\nnominal = true\n").unwrap();
    let l = sc.layers.unwrap();
    assert_eq!(
        l.layers,
        Layers {
            lateral: true,
            ..Layers::PROFILE
        }
    );
    assert_eq!(l.settings, host_sim::campaign::CampaignGuidance::default());
    let sc = parse(
        "[guidance.replanning]\n[guidance.estimator]\n[guidance.lateral]\n\
         [guidance.target]\nnominal = true\n",
    )
    .unwrap();
    assert_eq!(
        sc.layers.unwrap().layers,
        Layers {
            barrier: false,
            ..Layers::ALL
        }
    );
    assert_eq!(Scenario::default().layers.unwrap().layers, Layers::ALL);
    assert_eq!(Scenario::horus_2b_stored().layers, None);
}

/// The built-ins print with their layers and parse back to themselves; the example file is
/// the built-in reference mission's stack.
#[test]
fn builtin_stacks_round_trip_and_match_the_example() {
    for name in Scenario::BUILTIN {
        let sc = Scenario::try_builtin(name).unwrap();
        let back = parse(&scenario_to_toml(&sc)).unwrap();
        assert_eq!(back.layers, sc.layers, "{name}");
    }
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/horus-2b-stack.toml"
    );
    let text = std::fs::read_to_string(path).unwrap();
    assert_eq!(parse(&text).unwrap().layers, Scenario::default().layers);
}

/// Bad values name the file, the scenario key, the value and the range; layers that are parts
/// of the re-planner need it.
#[test]
fn bad_layer_settings_name_file_field_value_and_range() {
    for (text, field, words) in [
        (
            "[guidance.replanning]\nevery_n_ticks = 0\n",
            "guidance.replanning.every_n_ticks",
            &["0", ">= 1"][..],
        ),
        (
            "[guidance.replanning]\nevery_n_ticks = 2.5\n",
            "guidance.replanning.every_n_ticks",
            &["2.5", "integer"],
        ),
        (
            "[guidance.replanning]\nsolver_steps_per_tick = 256\n",
            "guidance.replanning.solver_steps_per_tick",
            &["256", "[0, 255]"],
        ),
        (
            "[guidance.replanning]\nsolver_steps_per_tick = 1.5\n",
            "guidance.replanning.solver_steps_per_tick",
            &["1.5", "integer"],
        ),
        (
            "[guidance.lateral]\nterminal_start_km = 5000\n",
            "guidance.lateral.terminal_start_km",
            &["5000", "2000"],
        ),
        (
            "[guidance.replanning]\n[guidance.estimator]\ndrag_gain = 1.5\n",
            "guidance.estimator.drag_gain",
            &["1.5", "(0, 1]"],
        ),
        (
            "[guidance.replanning]\n[guidance.barrier]\nfrequency_rad_s = 0.2\n",
            "guidance.barrier.frequency_rad_s",
            &["0.2", "damping"],
        ),
        (
            "[guidance.replanning]\n[guidance.barrier]\nfrequency_rad_s = 2\ndamping = 1\n",
            "guidance.barrier.frequency_rad_s",
            &["2", "(0, 1]"],
        ),
        (
            "[guidance.estimator]\n",
            "guidance.estimator",
            &["[guidance.replanning]"],
        ),
        (
            "[guidance.replanning]\nreplan_every_n_ticks = 3\n",
            "guidance.replanning.replan_every_n_ticks",
            &["unknown"],
        ),
    ] {
        match parse(text) {
            Err(e @ ScenarioError::Field { .. }) => {
                let msg = e.to_string();
                let ScenarioError::Field { field: f, .. } = e else {
                    unreachable!()
                };
                assert_eq!(f, field, "{text}");
                for w in words.iter().chain(&["s.toml"]) {
                    assert!(msg.contains(w), "{text}: `{msg}` lacks `{w}`");
                }
            }
            r => panic!("{text}: {r:?}"),
        }
    }
}

/// A campaign flies the modes its scenario's layers make, refuses the others, and a settings
/// file's old `[dispersions.guidance]` names the new key of each setting.
#[test]
fn campaign_modes_are_masks_of_the_scenario_layers() {
    let sc = parse(
        "[guidance]\nindependent = \"energy\"\nnodes = [[1, 0, 0], [0.8, 0, 40], [0.4, 0, 60], \
         [0, 0, 0]]\n[guidance.lateral]\n[guidance.target]\nnominal = true\n",
    );
    // The reference mission's time-indexed nodes replaced by an energy table: lateral only.
    let sc = sc.unwrap();
    let setup = CampaignSetup::new(&sc, "s.toml", None).unwrap();
    assert_eq!(setup.modes(), vec![Mode::Stored, Mode::StoredReversals]);
    assert!(setup.check_modes(&[Mode::StoredReversals]).is_ok());
    let e = setup
        .check_modes(&[Mode::ReplanReversals])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("replan-reversals") && e.contains("s.toml"),
        "{e}"
    );
    let e = parse_settings(
        "[dispersions.guidance]\nterminal_lateral_km = 250.0\npredictor_aero_mach = true\n",
        "d.toml",
    )
    .unwrap_err()
    .to_string();
    for w in [
        "d.toml",
        "terminal_lateral_km -> [guidance.lateral] terminal_start_km",
        "predictor_aero_mach -> [guidance.replanning] lift_profile_mach",
    ] {
        assert!(e.contains(w), "`{e}` lacks `{w}`");
    }
}

/// One name per setting: every key of [`LAYER_KEYS`] is in the printed template of the
/// reference mission (which has every layer) under its section, parses, and has a row in the
/// docs' key table (docs/reference/guidance-stack.md); the template and the table have no
/// other layer key.
#[test]
fn key_list_template_and_docs_agree() {
    let template = scenario_to_toml(&Scenario::default());
    let doc = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../docs/reference/guidance-stack.md"
    ))
    .unwrap();
    let mut listed = std::collections::BTreeSet::new();
    for (_, section, key) in LAYER_KEYS {
        listed.insert(format!("{section}.{key}"));
    }
    for key in TARGET_KEYS {
        listed.insert(format!("target.{key}"));
    }
    // The template: keys under each [guidance.<section>] table.
    let mut in_template = std::collections::BTreeSet::new();
    let table: toml::Table = template.parse().unwrap();
    for (section, value) in table["guidance"].as_table().unwrap() {
        if let Some(t) = value.as_table() {
            for k in t.keys() {
                in_template.insert(format!("{section}.{k}"));
            }
        }
    }
    // The reference mission leaves the estimator's and terminal law's optional keys at their
    // defaults; every key with a value is printed, the optional ones unset are not.
    for k in &in_template {
        assert!(listed.contains(k), "template key {k} not in LAYER_KEYS");
    }
    // Unset optional keys, and the target's other forms (the reference aims at `nominal`).
    let unset = [
        "replanning.lift_parameter",
        "target.latitude_deg",
        "target.longitude_deg",
        "target.downrange_km",
        "target.crossrange_km",
        "target.interface_speed_m_s",
        "target.interface_altitude_m",
        "target.interface_normalized_energy",
    ];
    for k in &listed {
        assert!(
            in_template.contains(k) || unset.contains(&k.as_str()),
            "{k} not in the template"
        );
    }
    // The docs: a row `| \`[guidance.<section>] <key>\` |` per key.
    let mut in_doc = std::collections::BTreeSet::new();
    for line in doc.lines() {
        if let Some(r) = line.strip_prefix("| `[guidance.")
            && let Some((s, rest)) = r.split_once("] ")
            && let Some((k, _)) = rest.split_once('`')
        {
            in_doc.insert(format!("{s}.{k}"));
        }
    }
    assert_eq!(in_doc, listed, "docs key table vs LAYER_KEYS");
}

/// A recorded case flown alone reproduces its record bit for bit (`host-sim dispersions ...
/// --case ID`), and a changed record is reported as different (exit status non-zero).
#[test]
fn a_recorded_case_flown_alone_reproduces_its_record() {
    let dir = std::env::temp_dir().join(format!("host-sim-it-replay-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let run = |extra: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_host-sim"))
            .args([
                "dispersions",
                "--builtin",
                "srm-glide",
                "-n",
                "3",
                "--seed",
                "5",
                "--interface-speed",
                "2500",
                "--modes",
                "stored-reversals,replan-estimation",
                "--threads",
                "2",
                "--quiet",
                "--out",
            ])
            .arg(&dir)
            .args(extra)
            .output()
            .unwrap()
    };
    assert!(run(&[]).status.success());
    let o = run(&["--case", "2"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{text}");
    assert_eq!(
        text.matches("reproduces its record bit for bit").count(),
        2,
        "{text}"
    );
    // A record edited by one digit is not reproduced.
    let p = dir.join("cases/replan-estimation/000002.json");
    let json = std::fs::read_to_string(&p).unwrap();
    let i = json.find("\"miss_m\": ").unwrap() + 10;
    let mut edited = json.clone();
    let d = if &json[i..=i] == "9" { "8" } else { "9" };
    edited.replace_range(i..=i, d);
    std::fs::write(&p, edited).unwrap();
    let o = run(&["--case", "2"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(!o.status.success());
    assert!(
        text.contains("replan-estimation: miss") && text.contains("DIFFERS"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The scenario's target: required by the aiming layers, one form only, checked; a campaign
/// flies it (a point, or downrange and crossrange from the entry), `nominal` keeps the
/// derived one.
#[test]
fn the_campaign_flies_the_scenarios_target() {
    use host_sim::campaign::setup::downrange_crossrange;
    use host_sim::scenario::TargetSpec;
    for (text, field) in [
        ("[guidance.lateral]\n", "guidance.target"),
        (
            "[guidance.lateral]\n[guidance.target]\nlatitude_deg = 10\n",
            "guidance.target",
        ),
        (
            "[guidance.lateral]\n[guidance.target]\nnominal = true\ndownrange_km = 100\ncrossrange_km = 0\n",
            "guidance.target",
        ),
        (
            "[guidance.lateral]\n[guidance.target]\nlatitude_deg = 95\nlongitude_deg = 0\n",
            "guidance.target.latitude_deg",
        ),
        (
            "[guidance.lateral]\n[guidance.target]\ndownrange_km = -5\ncrossrange_km = 0\n",
            "guidance.target.downrange_km",
        ),
        ("[guidance.target]\nnominal = true\n", "guidance.target"),
        (
            "[guidance.lateral]\n[guidance.target]\nnominal = true\ninterface_speed_m_s = 9000\n",
            "guidance.target.interface_speed_m_s",
        ),
    ] {
        match parse(text) {
            Err(ScenarioError::Field { field: f, file, .. }) => {
                assert_eq!((f.as_str(), file.as_str()), (field, "s.toml"), "{text}");
            }
            r => panic!("{text}: {r:?}"),
        }
    }
    // Downrange and crossrange: the point's along- and cross-track on the entry heading's
    // great circle are the values given.
    let sc = Scenario::srm_glide();
    let e = sc.entry;
    let r = sc.environment.planet.radius_m;
    let (d, c) = (2000e3 / r, -150e3 / r);
    let t = downrange_crossrange(&e, d, c);
    let ahead = downrange_crossrange(&e, 1.0, 0.0);
    let (at, xt) = guidance_core::geo::along_cross_track(
        (e.latitude_rad, e.longitude_rad),
        (ahead.latitude_rad, ahead.longitude_rad),
        (t.latitude_rad, t.longitude_rad),
    )
    .unwrap();
    assert!(
        (at - d).abs() * r < 1.0 && (xt - c).abs() * r < 1.0,
        "{at} {xt}"
    );
    // The SRM campaign aimed at it: the set-up's target is that point, and the nominal
    // flight with the full stack ends near it.
    let mut sc = sc;
    sc.layers.as_mut().unwrap().target = TargetSpec::Range {
        downrange_rad: 17_500e3 / r,
        crossrange_rad: 100e3 / r,
    };
    let setup = CampaignSetup::new(&sc, "s.toml", Some(2500.0)).unwrap();
    let want = downrange_crossrange(&sc.entry, 17_500e3 / r, 100e3 / r);
    assert_eq!(setup.target(), want);
    let f = host_sim::campaign::flight::fly_case(&setup, None, Mode::ReplanEstimation).unwrap();
    assert!(
        f.reached_interface && f.miss_m < 20e3,
        "miss {} km",
        f.miss_m / 1e3
    );
    let nominal = CampaignSetup::new(&Scenario::srm_glide(), "s.toml", None).unwrap();
    assert_ne!(nominal.target(), want);
    // The built-in's own terminal interface: 2.5 km/s.
    assert_eq!(nominal.interface_speed_m_s, 2500.0);
}
