//! Scenario files beyond the defaults: the planet, exponential and tabulated atmospheres,
//! heat-flux constants, and the Betts Space Shuttle example (examples/betts-shuttle.toml).

use std::path::{Path, PathBuf};

use host_sim::env::Atmosphere;
use host_sim::scenario::{AtmosphereSpec, Scenario, fly, parse_scenario, read_scenario};
use host_sim::sim::TerminationReason;

use crate::support::complete_scenario;

const FT: f64 = 0.3048;
const SLUG_PER_FT3: f64 = 0.453_592_37 * 9.806_65 / FT / (FT * FT * FT);
const BTU_FT2_S: f64 = 1_055.055_852_62 / (FT * FT);

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples")
}

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// The Betts shuttle set-up, converted from Betts' English units here independently of the
/// file's comments: planet, atmosphere, aerodynamics, heating and entry state; then it flies
/// to Betts' terminal altitude turning north (negative bank).
#[test]
fn betts_shuttle_example_loads_and_flies() {
    let sc = read_scenario(&examples().join("betts-shuttle.toml")).unwrap();
    let e = &sc.environment;
    assert!(rel(e.planet.radius_m, 20_902_900.0 * FT) < 1e-15);
    assert!(rel(e.planet.mu_m3_s2, 0.140_765_39e17 * FT * FT * FT) < 1e-15);
    assert!(!e.rotating && e.planet.j2 == 0.0);
    let AtmosphereSpec::Exponential(atm) = e.atmosphere else {
        panic!("exponential atmosphere expected: {:?}", e.atmosphere);
    };
    assert!(rel(atm.rho0_kg_m3(), 0.002_378 * SLUG_PER_FT3) < 1e-12);
    assert!(rel(atm.scale_height_m(), 23_800.0 * FT) < 1e-12);
    assert!((atm.density_kg_m3(23_800.0 * FT) / atm.rho0_kg_m3() - (-1.0f64).exp()).abs() < 1e-12);
    // Entry state.
    assert!(rel(sc.entry.radius_m - e.planet.radius_m, 260_000.0 * FT) < 1e-12);
    assert!(rel(sc.entry.speed_m_s, 25_600.0 * FT) < 1e-15);
    assert!(rel(sc.entry.flight_path_angle_rad, (-1f64).to_radians()) < 1e-15);
    assert!(rel(sc.entry.heading_rad, 90f64.to_radians()) < 1e-15);
    // Vehicle: mass, area, polynomial aerodynamics in alpha_hat [deg].
    let veh = sc.load_vehicle().unwrap();
    assert!(rel(veh.mass_kg, 203_000.0 * 0.453_592_37) < 1e-12);
    assert!(rel(veh.reference_area_m2, 2690.0 * FT * FT) < 1e-12);
    let c = veh.aero.coefficients(10.0, 20f64.to_radians());
    assert!((c.cl - (-0.207_04 + 0.029_244 * 20.0)).abs() < 1e-12);
    assert!((c.cd - (0.078_54 - 0.615_92e-2 * 20.0 + 0.621_408e-3 * 400.0)).abs() < 1e-12);
    // Heating: Betts' q_r = 17700 sqrt(rho) (1e-4 V)^3.07 BTU/ft^2/s in English units.
    for (rho_si, v_si) in [(1e-4, 7000.0), (3e-6, 7800.0), (2e-3, 2500.0)] {
        let betts =
            17_700.0 * (rho_si / SLUG_PER_FT3).sqrt() * (1e-4 * v_si / FT).powf(3.07) * BTU_FT2_S;
        let q = e.heat_flux.heat_flux_w_m2(rho_si, v_si, veh.nose_radius_m);
        assert!(rel(q, betts) < 1e-12, "{q} vs {betts}");
    }
    // Flies to 80000 ft, turning north.
    let f = fly(&sc, "betts-shuttle.toml", &mut |_| {}).unwrap();
    let s = &f.result.summary;
    assert_eq!(s.termination, TerminationReason::Altitude);
    let end = f.result.samples.last().unwrap();
    assert!((end.conditions.altitude_m - 80_000.0 * FT).abs() < 1.0);
    assert!(
        (1500.0..3000.0).contains(&s.flight_time_s),
        "{}",
        s.flight_time_s
    );
    let lat = end.state.latitude_rad.to_degrees();
    assert!(lat > 20.0 && lat < 40.0, "final latitude {lat} deg");
    assert!(f.result.samples.iter().any(|x| x.attitude.sigma_rad < -0.5));
    assert!(s.heat_load_j_m2.is_finite() && s.peak_heat_flux_w_m2.value > 0.0);
}

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("host-sim-scn-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A tabulated atmosphere from a CSV next to the scenario, on another planet (Mars preset with
/// a changed radius): the entry altitude is kept, and the run uses the table.
#[test]
fn table_atmosphere_and_planet_preset() {
    let d = temp_dir("table");
    std::fs::write(
        d.join("mars.csv"),
        "altitude_km,density_kg_m3,speed_of_sound_m_s\n0,0.020,240\n40,0.0006,210\n80,1.0e-5,190\n130,1.0e-8,180\n",
    )
    .unwrap();
    let text = "vehicle = \"srm\"\n[environment]\natmosphere = \"table\"\ngravity = \"central\"\n\
                [environment.planet]\npreset = \"mars\"\n\
                [environment.table]\nfile = \"mars.csv\"\ngas_constant_j_kg_k = 188.9\nheat_capacity_ratio = 1.29\n\
                [guidance]\nindependent = \"energy\"\ninterpolation = \"linear\"\nperiod_s = 2.0\n\
                alpha_rate_deg_s = 5.0\nsigma_rate_deg_s = 15.0\ninitial_alpha_deg = 0.0\n\
                initial_sigma_deg = 0.0\nnodes = [[1, 0, 0], [0, 0, 30]]\n\
                [entry]\naltitude_km = 125\nspeed_m_s = 3300\nflight_path_angle_deg = -15\n\
                latitude_deg = -22.3\nlongitude_deg = -106.7\nheading_deg = 70.75\n\
                [termination]\naltitude_km = 10\nmax_time_s = 3000\n";
    let sc = parse_scenario(text, "mars.toml", &d).unwrap();
    let e = &sc.environment;
    assert_eq!(e.planet.radius_m, host_sim::env::Planet::mars().radius_m);
    assert!((sc.entry.radius_m - e.planet.radius_m - 125e3).abs() < 1e-6);
    let AtmosphereSpec::Table(t) = &e.atmosphere else {
        panic!("table expected");
    };
    assert!((t.model.state(0.0).speed_of_sound_m_s - 240.0).abs() < 1e-9);
    assert!(e.describe().contains("table atmosphere") && e.describe().contains("3389.5"));
    let f = fly(&sc, "mars.toml", &mut |_| {}).unwrap();
    assert_eq!(f.result.summary.termination, TerminationReason::Altitude);
    // The printed scenario parses back to the same environment.
    let back = parse_scenario(
        &host_sim::scenario::scenario_to_toml(&sc),
        "back.toml",
        Path::new("/"),
    )
    .unwrap();
    assert_eq!(back.environment, sc.environment);
    let _ = std::fs::remove_dir_all(&d);
}

/// Bad environment settings name the scenario file, the field and the value.
#[test]
fn bad_environment_settings_are_named() {
    let d = temp_dir("bad-env");
    std::fs::write(
        d.join("bad.csv"),
        "altitude_m,density_kg_m3,temperature_k\n0,1,300\n0,0.5,300\n",
    )
    .unwrap();
    let cases: &[(&str, &[&str])] = &[
        (
            "[environment]\natmosphere = \"us76\"\n[environment.exponential]\nrho0_kg_m3 = 1.0\n",
            &["s.toml", "environment.exponential", "exponential"],
        ),
        (
            "[environment]\natmosphere = \"exponential\"\n[environment.exponential]\nscale_height_m = -3\n",
            &["s.toml", "environment.exponential.scale_height_m", "-3"],
        ),
        (
            "[environment]\natmosphere = \"table\"\n",
            &["s.toml", "environment.table", "missing"],
        ),
        (
            "[environment]\natmosphere = \"table\"\n[environment.table]\nfile = \"bad.csv\"\n",
            &[
                "s.toml",
                "environment.table.file",
                "bad.csv",
                "line 3",
                "increase",
            ],
        ),
        (
            "[environment]\natmosphere = \"mars-ish\"\n",
            &[
                "s.toml",
                "environment.atmosphere",
                "mars-ish",
                "unknown variant",
            ],
        ),
        (
            "[environment.planet]\nradius_m = 0\n",
            &["s.toml", "environment.planet.radius_m", "0", "> 0"],
        ),
        (
            "[environment.planet]\nradus_m = 5\n",
            &["s.toml", "environment.planet.radus_m", "5", "unknown field"],
        ),
        (
            "[heat_flux]\nspeed_exponent = \"3\"\n",
            &["s.toml", "heat_flux.speed_exponent", "\"3\"", "number"],
        ),
        (
            "[heat_flux]\nnose_radius_m = -1\n",
            &["s.toml", "heat_flux.nose_radius_m", "-1"],
        ),
    ];
    for (text, needles) in cases {
        let e = parse_scenario(&complete_scenario(text), "s.toml", &d)
            .unwrap_err()
            .to_string();
        for n in *needles {
            assert!(e.contains(n), "`{n}` not in: {e}\n(for {text})");
        }
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// Heat-flux constants and the nose radius reach the run: doubling c* doubles the peak.
#[test]
fn heat_flux_constants_reach_the_dynamics() {
    let base = Scenario {
        layers: None,
        ..Scenario::srm_glide()
    };
    let text = "vehicle = \"srm\"\n[heat_flux]\ncoefficient = 2.2194e8\n";
    let mut doubled = parse_scenario(&complete_scenario(text), "h.toml", Path::new(".")).unwrap();
    doubled.entry = base.entry;
    doubled.guidance = base.guidance.clone();
    doubled.termination = base.termination;
    doubled.environment.atmosphere = base.environment.atmosphere.clone();
    doubled.environment.gravity = base.environment.gravity;
    doubled.environment.rotating = base.environment.rotating;
    let a = fly(&base, "base", &mut |_| {}).unwrap().result.summary;
    let b = fly(&doubled, "h.toml", &mut |_| {}).unwrap().result.summary;
    assert_eq!(
        a.flight_time_s, b.flight_time_s,
        "heat flux must not change the trajectory"
    );
    assert!(
        rel(
            b.peak_heat_flux_w_m2.value,
            2.0 * a.peak_heat_flux_w_m2.value
        ) < 1e-12
    );
    let text = "vehicle = \"srm\"\n[heat_flux]\nnose_radius_m = 4.0\n";
    let mut big_nose = parse_scenario(&complete_scenario(text), "n.toml", Path::new(".")).unwrap();
    big_nose.entry = base.entry;
    big_nose.guidance = base.guidance.clone();
    big_nose.termination = base.termination;
    big_nose.environment = base.environment.clone();
    let rn = base.load_vehicle().unwrap().nose_radius_m;
    let c = fly(&big_nose, "n.toml", &mut |_| {})
        .unwrap()
        .result
        .summary;
    assert!(
        rel(
            c.peak_heat_flux_w_m2.value,
            a.peak_heat_flux_w_m2.value * (rn / 4.0).sqrt()
        ) < 1e-12
    );
}

/// Issue 7.7: a scenario may carry a profile exported from an optimal-control solver as is:
/// 256 energy nodes fly, and the same bank profile sampled on 4 nodes gives the same flight to
/// interpolation accuracy; 257 nodes are rejected naming the field and the limit.
#[test]
fn host_scenarios_take_256_nodes() {
    let rows = |n: usize| -> String {
        (0..n)
            .map(|i| {
                #[allow(clippy::cast_precision_loss)]
                let e = 1.0 - i as f64 / (n - 1) as f64;
                // Linear bank profile 0 -> 60 deg: the same on any node grid.
                format!("[{e}, 0, {}]", 60.0 * (1.0 - e))
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    let scenario = |n: usize| {
        format!(
            "name = \"srm-{n}\"\nvehicle = \"srm\"\n[environment]\npreset = \"simplified\"\n\
             [entry]\naltitude_km = 100.0\nspeed_m_s = 7658.34\nflight_path_angle_deg = -0.056\n\
             heading_deg = 90.0\nlatitude_deg = 0.0\nlongitude_deg = 0.0\n\
             [guidance]\nindependent = \"energy\"\ninterpolation = \"linear\"\nperiod_s = 2.0\n\
             alpha_rate_deg_s = 5.0\nsigma_rate_deg_s = 15.0\ninitial_alpha_deg = 0.0\n\
             initial_sigma_deg = 0.0\nnodes = [{}]\n\
             [termination]\naltitude_km = 25.0\nmax_time_s = 2500.0\n",
            rows(n)
        )
    };
    let fine = parse_scenario(&scenario(256), "fine.toml", Path::new(".")).unwrap();
    assert_eq!(fine.guidance.nodes.len(), 256);
    let coarse = parse_scenario(&scenario(4), "coarse.toml", Path::new(".")).unwrap();
    let a = fly(&fine, "fine.toml", &mut |_| {}).unwrap().result.summary;
    let b = fly(&coarse, "coarse.toml", &mut |_| {})
        .unwrap()
        .result
        .summary;
    assert!(
        rel(a.range_angle_rad, b.range_angle_rad) < 1e-6,
        "{} vs {} rad",
        a.range_angle_rad,
        b.range_angle_rad
    );
    let e = parse_scenario(&scenario(257), "big.toml", Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(e.contains("guidance.nodes") && e.contains("256"), "{e}");
}

/// The re-planning example (`[guidance.replanning]` with `[guidance.lateral]`, aimed at a
/// downrange target): it parses into the layers, prints back to the same scenario, and flies
/// to its target: the stored profile alone ends hundreds of km short, the stack within 10 km.
#[test]
fn replanning_example_flies_to_its_target() {
    use host_sim::scenario::TargetSpec;
    let sc = read_scenario(&examples().join("srm-glide-replanning.toml")).unwrap();
    let l = sc.layers.as_ref().expect("guidance layers");
    assert!(l.layers.replan && l.layers.lateral && !l.layers.estimator && !l.layers.barrier);
    let radius = sc.environment.planet.radius_m;
    let TargetSpec::Range {
        downrange_rad,
        crossrange_rad,
    } = l.target
    else {
        panic!("downrange target expected: {:?}", l.target);
    };
    assert!(rel(downrange_rad * radius, 18_034.65e3) < 1e-15);
    assert_eq!(crossrange_rad, 0.0);
    assert_eq!(
        l.interface,
        Some(host_sim::scenario::TerminalInterface::Speed { speed_m_s: 2500.0 })
    );
    assert_eq!(l.settings.replan_every_n_ticks, 5);
    assert_eq!(
        l.settings.predictor,
        host_sim::scenario::guidance_layers::CampaignPredictor::Hybrid
    );
    let text = host_sim::scenario::scenario_to_toml(&sc);
    let back = parse_scenario(&text, "printed.toml", Path::new(".")).unwrap();
    assert_eq!(back.layers, sc.layers);
    let flight = fly(&sc, "(test)", &mut |_| {}).unwrap();
    let case = &flight.stack.as_ref().expect("the stack's outcome").case;
    let stored = Scenario {
        layers: None,
        ..sc.clone()
    };
    let s = fly(&stored, "(test)", &mut |_| {})
        .unwrap()
        .result
        .summary
        .range_angle_rad
        * radius;
    let target = downrange_rad * radius;
    println!(
        "miss: stored profile {:.1} km short, stack {:.2} km ({} reversals, {} re-plans)",
        (target - s) / 1e3,
        case.miss_m / 1e3,
        case.reversals,
        case.replans
    );
    assert!(target - s > 300e3);
    assert!(case.reached_interface, "{}", case.termination);
    assert!(case.miss_m < 10e3);
    assert!(case.replans > 0);
}

/// The former top-level `[replanning]` section is refused with or without layers, the error
/// naming the file, the section and, for each key it holds, the key that replaced it.
#[test]
fn old_replanning_section_is_refused() {
    let energy =
        "[guidance]\nindependent = \"energy\"\nnodes = [[1, 0, 0], [0.5, 0, 40], [0, 0, 0]]\n";
    let cases: &[(String, &[&str])] = &[
        (
            "[replanning]\nrange_km = 1000\nfinal_speed_m_s = 2500\n".into(),
            &[
                "s.toml",
                "`replanning`",
                "replanning.range_km -> [guidance.target] downrange_km",
                "replanning.final_speed_m_s -> [guidance.target] interface_speed_m_s",
            ],
        ),
        (
            format!("{energy}[replanning]\npredictor = \"auto\"\nevery = 3\n"),
            &[
                "s.toml",
                "replanning.predictor -> [guidance.replanning] predictor",
                "replanning.every -> none",
            ],
        ),
        (
            format!("{energy}[replanning]\n"),
            &["s.toml", "`replanning`", "[guidance.replanning]"],
        ),
    ];
    for (text, words) in cases {
        let e = parse_scenario(&complete_scenario(text), "s.toml", Path::new("."))
            .expect_err(text)
            .to_string();
        for w in *words {
            assert!(e.contains(w), "{text}: `{e}` lacks `{w}`");
        }
    }
}

/// Every scenario file under examples/ (top level and examples/validation/) reads on its own,
/// as `host-sim simulate --scenario FILE` and `dispersions --scenario FILE` read it: a file the
/// docs name as a scenario is complete, not an overlay. Vehicle and dispersion-settings files
/// are told apart by name; run files of `host-sim optimize --config` (`optimize-*.toml`) are
/// read and checked as `optimize` reads them.
#[test]
fn every_example_scenario_reads_on_its_own() {
    let mut read = 0;
    let mut runs = 0;
    for dir in [examples(), examples().join("validation")] {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            if path.extension().is_none_or(|e| e != "toml")
                || name.ends_with("-vehicle.toml")
                || name.starts_with("dispersions")
            {
                continue;
            }
            if name.starts_with("optimize-") {
                let text = std::fs::read_to_string(&path).unwrap();
                if let Err(e) = host_sim::design::run::check_run_config(&text, &path) {
                    panic!("{}: {e}", path.display());
                }
                runs += 1;
                continue;
            }
            if let Err(e) = read_scenario(&path) {
                panic!("{}: {e}", path.display());
            }
            read += 1;
        }
    }
    assert!(read >= 15, "{read} example scenarios read");
    assert!(runs >= 1, "{runs} example run files read");
}

/// The HORUS-2B profile designed with a 5 % margin on every limit
/// (examples/optimize-horus-2b-margin.toml, its member 00 in
/// examples/horus-2b-margin-profile.toml): flown undispersed with bank reversals it reaches its
/// target (within 2 km), stays within 0.95 of every limit of the vehicle, and takes less heat
/// than the reference profile, which exceeds the heat-flux limit with the same layers.
#[test]
fn margin_profile_example_holds_its_margin() {
    let sc = read_scenario(&examples().join("horus-2b-margin-profile.toml")).unwrap();
    let vehicle = sc.load_vehicle().unwrap();
    let lim = vehicle.limits;
    let flight = fly(&sc, "(test)", &mut |_| {}).unwrap();
    let case = &flight.stack.as_ref().expect("the stack's outcome").case;
    let s = &flight.result.summary;
    let ratios = [
        s.peak_heat_flux_w_m2.value / lim.heat_flux_w_m2,
        s.peak_g_load.value / lim.g_load,
        s.peak_g_load_rate_per_s.value / lim.g_load_rate_per_s,
    ];
    let flown_deg = s.flown_range_angle_rad.to_degrees();
    println!(
        "margin profile: miss {:.2} km, flown range {flown_deg:.3} deg, ratios {ratios:.3?}, \
         heat load {:.1} MJ/m^2",
        case.miss_m / 1e3,
        s.heat_load_j_m2 / 1e6
    );
    assert!(case.reached_interface, "{}", case.termination);
    assert!(case.miss_m < 2e3, "miss {} m", case.miss_m);
    assert!(ratios.iter().all(|r| *r <= 0.95), "{ratios:?}");
    let reference = Scenario {
        guidance: read_scenario(&examples().join("horus-2b-stack.toml"))
            .unwrap()
            .guidance,
        ..sc.clone()
    };
    let r = fly(&reference, "(test)", &mut |_| {})
        .unwrap()
        .result
        .summary;
    let r_q = r.peak_heat_flux_w_m2.value / lim.heat_flux_w_m2;
    println!(
        "reference profile, same layers: heat flux {r_q:.3} of the limit, heat load {:.1} MJ/m^2",
        r.heat_load_j_m2 / 1e6
    );
    assert!(r_q > 1.0);
    assert!(s.heat_load_j_m2 < r.heat_load_j_m2);
}
