//! Dispersion campaigns: lateral guidance hits the target in the nominal closed loop, a small
//! campaign is bit-identical across thread counts and resumes, bad settings name the field.

use host_sim::campaign::run::RunOptions;
use host_sim::campaign::settings::Dispersion;
use host_sim::campaign::{
    CampaignError, CampaignSetup, DispersionSettings, Mode, parse_settings, run_campaign,
};
use host_sim::scenario::Scenario;

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
