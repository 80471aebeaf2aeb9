//! The terminal interface given as a speed, an altitude or a normalised energy
//! (`[guidance.target] interface_speed_m_s`, `interface_altitude_m`,
//! `interface_normalized_energy`): each is where the nominal flight first crosses it, so the
//! three forms of one crossing give the same interface; the flights end on its energy; at
//! most one form is given, each within its range; the printed scenario reads back.

use std::path::Path;

use host_sim::campaign::run::{RunOptions, run_campaign};
use host_sim::campaign::{CampaignError, CampaignSetup, DispersionSettings, Mode, flight};
use host_sim::scenario::{
    Scenario, ScenarioError, TerminalInterface, parse_scenario, scenario_to_toml,
};

fn srm_with(i: TerminalInterface) -> Scenario {
    let mut sc = Scenario::srm_glide();
    sc.layers.as_mut().unwrap().interface = Some(i);
    sc
}

fn setup(i: TerminalInterface) -> CampaignSetup {
    CampaignSetup::new(&srm_with(i), "s.toml", None).unwrap()
}

/// The speed interface of the SRM glide (2.5 km/s), its altitude and its E-hat on the
/// nominal flight give the same interface: the crossing of each form is linear between the
/// nominal flight's output samples in its own quantity, so they agree to that interpolation's
/// accuracy (measured: the altitude form 1e-11 m/s off the speed, the energy form 7e-5 m/s
/// and 0.02 m off; asserted: 0.01 m/s, 1 m, 1e-6 of the energy), and the crossed quantity
/// itself is the value given.
#[test]
fn altitude_and_energy_of_the_speed_crossing_give_the_same_interface() {
    let by_speed = setup(TerminalInterface::Speed { speed_m_s: 2500.0 });
    assert_eq!(by_speed.interface_speed_m_s, 2500.0);
    let h = by_speed.interface_altitude_m();
    let e = by_speed.interface_normalized_energy();
    assert!(
        h > 25e3 && h < 100e3 && e > 0.0 && e < 1.0,
        "{h} m, E-hat {e}"
    );
    let by_altitude = setup(TerminalInterface::Altitude { altitude_m: h });
    let by_energy = setup(TerminalInterface::NormalizedEnergy {
        normalized_energy: e,
    });
    println!(
        "speed 2500 m/s: altitude {h} m, E-hat {e}; altitude form: {} m/s, {} J/kg; \
         energy form: {} m/s, {} m; energies {} / {} / {} J/kg; downranges {} / {} / {} km",
        by_altitude.interface_speed_m_s,
        by_altitude.interface_energy_j_kg,
        by_energy.interface_speed_m_s,
        by_energy.interface_altitude_m(),
        by_speed.interface_energy_j_kg,
        by_altitude.interface_energy_j_kg,
        by_energy.interface_energy_j_kg,
        by_speed.target_downrange_rad * by_speed.planet_radius_m / 1e3,
        by_altitude.target_downrange_rad * by_speed.planet_radius_m / 1e3,
        by_energy.target_downrange_rad * by_speed.planet_radius_m / 1e3,
    );
    assert!((by_altitude.interface_altitude_m() - h).abs() < 1e-6);
    assert!((by_energy.interface_normalized_energy() - e).abs() < 1e-12);
    for s in [&by_altitude, &by_energy] {
        assert!(
            (s.interface_speed_m_s - 2500.0).abs() < 0.01,
            "{}",
            s.interface_speed_m_s
        );
        assert!((s.interface_altitude_m() - h).abs() < 1.0);
        let de = s.interface_energy_j_kg - by_speed.interface_energy_j_kg;
        assert!(
            de.abs() < 1e-6 * by_speed.interface_energy_j_kg.abs(),
            "{de}"
        );
        // The same target (the nominal flights with reversals end within 100 m of it).
        let dd = (s.target_downrange_rad - by_speed.target_downrange_rad) * s.planet_radius_m;
        assert!(dd.abs() < 200.0, "{dd} m");
    }
    assert_eq!(
        by_altitude.interface,
        Some(TerminalInterface::Altitude { altitude_m: h })
    );
}

/// A flight ends at the interface: every case ends on its energy (the termination event), so
/// a flight given an E-hat ends at that E-hat (measured: within 4e-11, every mode); the stored
/// profile flown nominally ends at the altitude given, where the nominal flight crossed it
/// (measured: 0.07 m above 40 km).
#[test]
fn flights_end_at_the_interface_given() {
    let h = 40e3;
    let by_altitude = setup(TerminalInterface::Altitude { altitude_m: h });
    let f = flight::fly_case(&by_altitude, None, Mode::Stored).unwrap();
    println!(
        "altitude interface {h} m: stored ends at {} m, {} m/s (interface speed {} m/s)",
        f.final_altitude_m, f.final_speed_m_s, by_altitude.interface_speed_m_s
    );
    assert!(f.reached_interface, "{}", f.termination);
    assert!(
        (f.final_altitude_m - h).abs() < 5.0,
        "{}",
        f.final_altitude_m
    );
    let e = 0.05;
    let by_energy = setup(TerminalInterface::NormalizedEnergy {
        normalized_energy: e,
    });
    let norm = by_energy.stack.profile.energy;
    for mode in [Mode::Stored, Mode::ReplanEstimation] {
        let f = flight::fly_case(&by_energy, None, mode).unwrap();
        let r = by_energy.planet_radius_m + f.final_altitude_m;
        let end = norm.normalized(r, f.final_speed_m_s).unwrap();
        println!(
            "E-hat interface {e}, {}: ends at E-hat {end}, {} m, miss {} km",
            mode.name(),
            f.final_altitude_m,
            f.miss_m / 1e3
        );
        assert!(f.reached_interface, "{}", f.termination);
        assert!((end - e).abs() < 1e-8, "{}: {end}", mode.name());
    }
}

/// The srm-glide template with its `interface_speed_m_s = 2500.0` line replaced by `lines`.
fn srm_text(lines: &str) -> String {
    let text = scenario_to_toml(&Scenario::srm_glide());
    assert!(text.contains("\ninterface_speed_m_s = 2500.0"), "{text}");
    text.lines()
        .map(|l| {
            if l.starts_with("interface_speed_m_s = ") {
                lines.to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn parse(lines: &str) -> Result<Scenario, ScenarioError> {
    parse_scenario(&srm_text(lines), "s.toml", Path::new("."))
}

/// At most one form, each in its range: two or more are refused naming the second key and
/// its value; an altitude outside (0, entry altitude) or an E-hat outside (0, 1) is refused;
/// an interface the nominal flight never reaches is refused when the campaign is set up.
#[test]
fn interface_keys_are_checked() {
    for (lines, field, value) in [
        (
            "interface_speed_m_s = 2500.0\ninterface_altitude_m = 40000.0",
            "guidance.target.interface_altitude_m",
            "40000",
        ),
        (
            "interface_altitude_m = 40000.0\ninterface_normalized_energy = 0.05",
            "guidance.target.interface_normalized_energy",
            "0.05",
        ),
        (
            "interface_speed_m_s = 2500.0\ninterface_altitude_m = 40000.0\n\
             interface_normalized_energy = 0.05",
            "guidance.target.interface_altitude_m",
            "40000",
        ),
        (
            "interface_altitude_m = 0.0",
            "guidance.target.interface_altitude_m",
            "0",
        ),
        (
            "interface_altitude_m = 100000.0",
            "guidance.target.interface_altitude_m",
            "100000",
        ),
        (
            "interface_normalized_energy = 1.0",
            "guidance.target.interface_normalized_energy",
            "1",
        ),
        (
            "interface_normalized_energy = 0.0",
            "guidance.target.interface_normalized_energy",
            "0",
        ),
        (
            "interface_normalized_energy = -0.2",
            "guidance.target.interface_normalized_energy",
            "-0.2",
        ),
    ] {
        match parse(lines) {
            Err(e @ ScenarioError::Field { .. }) => {
                let ScenarioError::Field {
                    file,
                    field: f,
                    value: v,
                    ..
                } = &e
                else {
                    unreachable!()
                };
                assert_eq!(
                    (file.as_str(), f.as_str(), v.as_str()),
                    ("s.toml", field, value),
                    "{lines}: {e}"
                );
                if lines.contains('\n') {
                    assert!(e.to_string().contains("one terminal interface only"), "{e}");
                }
            }
            r => panic!("{lines}: {r:?}"),
        }
    }
    // In range but below the nominal flight's end (25 km): refused by the set-up.
    let sc = parse("interface_altitude_m = 10000.0").unwrap();
    match CampaignSetup::new(&sc, "s.toml", None) {
        Err(CampaignError::Setting {
            file, field, value, ..
        }) => assert_eq!(
            (file.as_str(), field.as_str(), value.as_str()),
            ("s.toml", "guidance.target.interface_altitude_m", "10000")
        ),
        r => panic!("{r:?}"),
    }
}

/// The printed scenario of each form reads back as the same scenario and prints the same.
#[test]
fn printed_interfaces_read_back() {
    for i in [
        TerminalInterface::Speed { speed_m_s: 2500.0 },
        TerminalInterface::Altitude {
            altitude_m: 40_123.5,
        },
        TerminalInterface::NormalizedEnergy {
            normalized_energy: 0.051_234_567_890_123,
        },
    ] {
        let sc = srm_with(i);
        let text = scenario_to_toml(&sc);
        assert!(
            text.contains(&format!("\n{} = {:?}", i.key(), i.value())),
            "{text}"
        );
        let back = parse_scenario(&text, "printed.toml", Path::new(".")).unwrap();
        assert_eq!(back.layers, sc.layers);
        assert_eq!(scenario_to_toml(&back), text);
    }
}

/// A campaign directory of one interface is not resumed with another (the fingerprint names
/// the scenario's layers), and its summary records the interface.
#[test]
fn a_campaign_with_another_interface_is_not_resumed() {
    let dir = std::env::temp_dir().join(format!("host-sim-it-interface-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let opts = RunOptions {
        modes: vec![Mode::Stored],
        out_dir: Some(dir.clone()),
        threads: Some(1),
        progress: false,
    };
    let settings = DispersionSettings {
        cases: 1,
        seed: 7,
        ..DispersionSettings::default()
    };
    let by_speed = setup(TerminalInterface::Speed { speed_m_s: 2500.0 });
    let out = run_campaign(&by_speed, &settings, &opts).unwrap();
    host_sim::campaign::output::write_campaign(&dir, &by_speed, &settings, &out).unwrap();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["interface"]["speed"]["speed_m_s"], 2500.0);
    assert_eq!(summary["interface_speed_m_s"], 2500.0);
    let h = summary["interface_altitude_m"].as_f64().unwrap();
    assert!((h - by_speed.interface_altitude_m()).abs() < 1e-6, "{h}");
    let by_altitude = setup(TerminalInterface::Altitude { altitude_m: h });
    match run_campaign(&by_altitude, &settings, &opts) {
        Err(CampaignError::ResumeMismatch {
            field, old, new, ..
        }) => assert!(
            field == "scenario.layers" && old.contains("Speed") && new.contains("Altitude"),
            "{field}: {old} -> {new}"
        ),
        r => panic!("resumed into a directory of another interface: {r:?}"),
    }
    let _ = std::fs::remove_dir_all(&dir);
}
