//! Every key of the scenario template and of the vehicle file format is read or refused
//! (issue 24 items 1 and 2): each key, changed to another valid-looking value, changes the
//! flight (its trajectory, summary, run or vehicle name) or is rejected with an error naming
//! it; each key a scenario must state, deleted, is an error naming the file and the key.

use std::path::{Path, PathBuf};

use host_sim::scenario::{Scenario, fly, parse_scenario, scenario_to_toml};
use toml::{Table, Value};

/// What a flight gave, for comparison: the whole result (samples, events, summary), the run
/// name and the vehicle name; or the error.
fn outcome(text: &str, dir: &Path) -> Result<String, String> {
    let sc = parse_scenario(text, "walk.toml", dir).map_err(|e| e.to_string())?;
    let f = fly(&sc, "walk.toml", &mut |_| {}).map_err(|e| e.to_string())?;
    let all = format!("{} {} {:?}", sc.name, f.vehicle.name, f.result);
    // Compared whole; shown as its summary when a change changed nothing.
    Ok(format!("{:?} #{}", f.result.summary, hash(&all)))
}

/// Set the dotted `path` of `t` to `v` (creating tables), or remove it with `None`.
fn set(t: &mut Table, path: &str, v: Option<Value>) {
    let (head, last) = path.rsplit_once('.').map_or(("", path), |(h, l)| (h, l));
    let mut cur = t;
    for k in head.split('.').filter(|k| !k.is_empty()) {
        cur = cur
            .entry(k.to_string())
            .or_insert_with(|| Value::Table(Table::new()))
            .as_table_mut()
            .unwrap();
    }
    match v {
        Some(v) => {
            cur.insert(last.to_string(), v);
        }
        None => {
            cur.remove(last);
        }
    }
}

/// Every leaf key of a table, dotted (arrays are leaves).
fn keys(t: &Table, prefix: &str, out: &mut Vec<String>) {
    for (k, v) in t {
        let p = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        match v {
            Value::Table(s) => keys(s, &p, out),
            _ => out.push(p),
        }
    }
}

fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("host-sim-keys-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn hash(s: &str) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    s.hash(&mut h);
    h.finish()
}

fn v(s: &str) -> Value {
    // A TOML value from its text.
    let t: Table = format!("x = {s}").parse().unwrap();
    t["x"].clone()
}

/// The changes walked over the scenario: each key of the template (`--print-scenario`) and
/// each optional key of the documented template; a key of the template missing here fails
/// the test, so a new key must be added to the walk.
fn scenario_changes() -> Vec<(&'static str, Value)> {
    vec![
        ("name", v("\"other-name\"")),
        ("vehicle", v("\"srm\"")),
        ("environment.atmosphere", v("\"exponential\"")),
        ("environment.gravity", v("\"central\"")),
        ("environment.rotating", v("false")),
        ("environment.planet.radius_m", v("6371000.0")),
        ("environment.planet.mu_m3_s2", v("3.9e14")),
        ("environment.planet.j2", v("2e-3")),
        ("environment.planet.rotation_rate_rad_s", v("1e-4")),
        ("heat_flux.coefficient", v("2e8")),
        ("heat_flux.reference_density_kg_m3", v("1.0")),
        ("heat_flux.reference_speed_m_s", v("7000.0")),
        ("heat_flux.speed_exponent", v("3.0")),
        ("heat_flux.nose_radius_m", v("2.0")),
        ("entry.altitude_km", v("121.0")),
        ("entry.longitude_deg", v("-100.0")),
        ("entry.latitude_deg", v("-20.0")),
        ("entry.speed_m_s", v("7400.0")),
        ("entry.flight_path_angle_deg", v("-1.5")),
        ("entry.heading_deg", v("80.0")),
        ("guidance.independent", v("\"energy\"")),
        ("guidance.interpolation", v("\"natural-cubic\"")),
        ("guidance.tension", v("0.5")),
        ("guidance.period_s", v("1.0")),
        ("guidance.alpha_rate_deg_s", v("1.0")),
        ("guidance.sigma_rate_deg_s", v("2.0")),
        ("guidance.initial_alpha_deg", v("30.0")),
        ("guidance.initial_sigma_deg", v("10.0")),
        (
            "guidance.nodes",
            v("[[0, 40, 0], [264, 40, 0], [290, 40, 70], [1319, 11.5, 54]]"),
        ),
        ("termination.altitude_km", v("60.0")),
        ("termination.mach", v("20.0")),
        ("termination.normalized_energy", v("0.5")),
        ("termination.max_time_s", v("500.0")),
        ("integrator.rtol", v("1e-6")),
        ("integrator.h_init_s", v("1.0")),
        ("integrator.h_min_s", v("1.0")),
        ("integrator.h_max_s", v("0.5")),
        ("integrator.max_steps", v("100")),
        // The largest event bracket: events are located to the integration tolerance, so at
        // this file's rtol any bracket up to the 0.01 s range limit gives the same flight; the
        // walk shows the key is read by its range check.
        ("integrator.event_time_tol_s", v("0.05")),
        ("monitors.interface_altitude_km", v("110.0")),
        ("monitors.g_rate_window_s", v("20.0")),
        ("output.interval_s", v("10.0")),
        ("environment.preset", v("\"simplified\"")),
        ("environment.planet.preset", v("\"mars\"")),
        ("environment.exponential.rho0_kg_m3", v("1.0")),
        ("environment.exponential.scale_height_m", v("7000.0")),
    ]
}

#[test]
fn every_scenario_key_changes_the_flight_or_is_refused() {
    let dir = temp_dir("scenario");
    // The stored profile alone: the layers' keys are walked by `guidance_layers`.
    let mut base: Table = scenario_to_toml(&Scenario::default()).parse().unwrap();
    crate::support::strip_layers(&mut base);
    let printed = toml::to_string(&base).unwrap();
    // A shorter flight (the walk flies once per key); every node is still flown.
    set(&mut base, "termination.max_time_s", Some(v("1400.0")));
    let base_text = toml::to_string(&base).unwrap();
    let reference = outcome(&base_text, &dir).expect("the base flies");
    let changes = scenario_changes();
    let mut template = Vec::new();
    keys(&printed.parse::<Table>().unwrap(), "", &mut template);
    for k in &template {
        assert!(
            changes.iter().any(|(c, _)| c == k),
            "template key `{k}` is not walked"
        );
    }
    let mut report = Vec::new();
    for (key, value) in changes {
        let mut t = base.clone();
        set(&mut t, key, Some(value.clone()));
        // Keys read only beside another: the exponential parameters with that atmosphere
        // (walked on their own below), energy nodes with energy indexing.
        if key.starts_with("environment.exponential.") {
            set(&mut t, "environment.atmosphere", Some(v("\"exponential\"")));
        }
        if key == "guidance.independent" {
            set(
                &mut t,
                "guidance.nodes",
                Some(v("[[1.0, 40, 0], [0.8, 40, 60], [0.0, 20, 50]]")),
            );
        }
        let text = toml::to_string(&t).unwrap();
        let got = outcome(&text, &dir);
        match &got {
            Err(e) => {
                let leaf = key.rsplit('.').next().unwrap();
                assert!(
                    e.contains(leaf) || e.contains("simulation failed"),
                    "`{key}` = {value}: the error does not name it: {e}"
                );
                report.push(format!("{key}: refused: {e}"));
            }
            Ok(o) => {
                assert_ne!(o, &reference, "`{key}` = {value} changed nothing");
                report.push(format!("{key}: changes the flight"));
            }
        }
    }
    // The exponential parameters change the exponential flight (not just its selection).
    let mut exp = base.clone();
    set(
        &mut exp,
        "environment.atmosphere",
        Some(v("\"exponential\"")),
    );
    let exp_ref = outcome(&toml::to_string(&exp).unwrap(), &dir).unwrap();
    for (key, value) in [
        ("environment.exponential.rho0_kg_m3", v("1.0")),
        ("environment.exponential.scale_height_m", v("7000.0")),
    ] {
        let mut t = exp.clone();
        set(&mut t, key, Some(value));
        assert_ne!(
            outcome(&toml::to_string(&t).unwrap(), &dir).unwrap(),
            exp_ref,
            "`{key}` changed nothing"
        );
    }
    // The tension changes a hermite flight; the presets change the flight where they set a
    // model the file does not.
    let mut herm = base.clone();
    set(&mut herm, "guidance.interpolation", Some(v("\"hermite\"")));
    set(&mut herm, "guidance.tension", Some(v("0.0")));
    let herm_ref = outcome(&toml::to_string(&herm).unwrap(), &dir).unwrap();
    set(&mut herm, "guidance.tension", Some(v("0.5")));
    assert_ne!(
        outcome(&toml::to_string(&herm).unwrap(), &dir).unwrap(),
        herm_ref
    );
    let mut pre = base.clone();
    set(&mut pre, "environment.atmosphere", None);
    let pre_ref = outcome(&toml::to_string(&pre).unwrap(), &dir).unwrap();
    set(&mut pre, "environment.preset", Some(v("\"simplified\"")));
    assert_ne!(
        outcome(&toml::to_string(&pre).unwrap(), &dir).unwrap(),
        pre_ref
    );
    let mut mars = base.clone();
    set(&mut mars, "environment.planet.j2", None);
    let mars_ref = outcome(&toml::to_string(&mars).unwrap(), &dir).unwrap();
    set(&mut mars, "environment.planet.preset", Some(v("\"mars\"")));
    assert_ne!(
        outcome(&toml::to_string(&mars).unwrap(), &dir).unwrap(),
        mars_ref
    );
    println!("{}", report.join("\n"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Deleting any key a scenario must state is an error naming the file and the key: the
/// vehicle, each entry-state and guidance key, the time limit (issue 24's reproducers:
/// a missing `speed_m_s` flew HORUS-2B's 7435.5 m/s, a missing `[guidance]` its profile).
#[test]
fn deleting_a_required_key_is_an_error_naming_it() {
    let mut base: Table = scenario_to_toml(&Scenario::default()).parse().unwrap();
    crate::support::strip_layers(&mut base);
    let mut required = vec![
        "vehicle".to_string(),
        "guidance".to_string(),
        "entry".into(),
    ];
    for section in ["entry", "guidance"] {
        let mut ks = Vec::new();
        keys(base[section].as_table().unwrap(), section, &mut ks);
        required.extend(ks);
    }
    required.push("termination.max_time_s".into());
    for key in &required {
        let mut t = base.clone();
        set(&mut t, key, None);
        let e = parse_scenario(&toml::to_string(&t).unwrap(), "cut.toml", Path::new("."))
            .expect_err(key)
            .to_string();
        assert!(
            e.starts_with("cut.toml: ")
                && e.contains(&format!("`{key}`"))
                && e.contains("required"),
            "{key}: {e}"
        );
    }
    // The generic defaults may be omitted: a file of the required keys only flies.
    let mut minimal = Table::new();
    for key in ["vehicle", "entry", "guidance"] {
        minimal.insert(key.into(), base[key].clone());
    }
    set(&mut minimal, "termination.max_time_s", Some(v("50.0")));
    let sc = parse_scenario(
        &toml::to_string(&minimal).unwrap(),
        "min.toml",
        Path::new("."),
    )
    .unwrap();
    assert_eq!(sc.name, "min");
    assert_eq!(
        sc.termination.altitude_m, None,
        "no HORUS-2B termination altitude"
    );
    fly(&sc, "min.toml", &mut |_| {}).unwrap();
}

/// The vehicle file keys walked (every key of the format, the kinds' keys included).
#[test]
fn every_vehicle_key_changes_the_flight_or_is_refused() {
    let dir = temp_dir("vehicle");
    let vehicle = |aero: &str, extra: &str| {
        format!(
            "name = \"walker\"\nmass_kg = 1200.0\nreference_area_m2 = 4.5\nnose_radius_m = 0.3\n{extra}\n\
             [limits]\nheat_flux_kw_m2 = 50.0\ng_load = 0.1\ng_load_rate_per_s = 0.001\n\
             alpha_rate_deg_s = 5.0\nsigma_rate_deg_s = 15.0\n[aero]\n{aero}\n"
        )
    };
    let scenario = |vfile: &str| {
        // The stored profile alone: the walk is over the vehicle's keys.
        let mut t: Table = scenario_to_toml(&Scenario::horus_2b_stored())
            .parse()
            .unwrap();
        t.remove("vehicle");
        t.insert("vehicle_file".into(), Value::String(vfile.into()));
        set(&mut t, "termination.max_time_s", Some(v("600.0")));
        toml::to_string(&t).unwrap()
    };
    let kinds: [(&str, Vec<(&str, &str)>); 4] = [
        (
            "kind = \"table\"\nmach = [2.0, 10.0]\nalpha_deg = [0.0, 20.0, 45.0]\n\
             cl = [[0.0, 0.4, 0.8], [0.0, 0.3, 0.6]]\ncd = [[0.1, 0.2, 0.5], [0.08, 0.15, 0.4]]",
            vec![
                ("mach", "mach = [2.0, 30.0]"),
                ("alpha_deg", "alpha_deg = [0.0, 30.0, 45.0]"),
                ("cl", "cl = [[0.0, 0.4, 0.8], [0.0, 0.3, 0.7]]"),
                ("cd", "cd = [[0.1, 0.2, 0.5], [0.08, 0.15, 0.5]]"),
            ],
        ),
        (
            "kind = \"polynomial\"\ncl = [0.0, 0.02]\ncd = [0.05, 0.0, 2e-4]\nalpha_min_deg = 0.0\nalpha_max_deg = 45.0",
            vec![
                ("cl", "cl = [0.0, 0.025]"),
                ("cd", "cd = [0.05, 0.0, 3e-4]"),
                ("alpha_min_deg", "alpha_min_deg = 41.0"),
                ("alpha_max_deg", "alpha_max_deg = 30.0"),
            ],
        ),
        (
            "kind = \"drag_polar\"\ncd0 = 0.05\nk = 0.5\ncl = [0.0, 0.02]",
            vec![
                ("cd0", "cd0 = 0.06"),
                ("k", "k = 0.6"),
                ("cl", "cl = [0.0, 0.025]"),
                ("alpha_min_deg", "alpha_min_deg = 41.0"),
                ("alpha_max_deg", "alpha_max_deg = 30.0"),
            ],
        ),
        (
            "kind = \"trim\"\ncl = 0.3\ncd = 0.9",
            vec![
                ("cl", "cl = 0.35"),
                ("cd", "cd = 1.0"),
                ("kind", "kind = \"table\""),
            ],
        ),
    ];
    let top: [(&str, &str, &str); 9] = [
        ("name", "name = \"walker\"", "name = \"other\""),
        ("mass_kg", "mass_kg = 1200.0", "mass_kg = 1300.0"),
        (
            "reference_area_m2",
            "reference_area_m2 = 4.5",
            "reference_area_m2 = 5.0",
        ),
        (
            "nose_radius_m",
            "nose_radius_m = 0.3",
            "nose_radius_m = 0.4",
        ),
        (
            "limits.heat_flux_kw_m2",
            "heat_flux_kw_m2 = 50.0",
            "heat_flux_kw_m2 = 60.0",
        ),
        ("limits.g_load", "g_load = 0.1", "g_load = 0.2"),
        (
            "limits.g_load_rate_per_s",
            "g_load_rate_per_s = 0.001",
            "g_load_rate_per_s = 0.002",
        ),
        // The vehicle's rate limits bound the guidance's (5 and 15 deg/s): lower is refused.
        (
            "limits.alpha_rate_deg_s",
            "alpha_rate_deg_s = 5.0",
            "alpha_rate_deg_s = 4.0",
        ),
        (
            "limits.sigma_rate_deg_s",
            "sigma_rate_deg_s = 15.0",
            "sigma_rate_deg_s = 1.0",
        ),
    ];
    let sc_text = scenario("v.toml");
    for (aero, changes) in &kinds {
        let base = vehicle(aero, "");
        std::fs::write(dir.join("v.toml"), &base).unwrap();
        let reference = outcome(&sc_text, &dir).unwrap_or_else(|e| panic!("{aero}: {e}"));
        let mut walked: Vec<(String, String)> = changes
            .iter()
            .map(|(k, line)| {
                let key = line.split(" = ").next().unwrap();
                let replaced = aero
                    .lines()
                    .map(|l| {
                        if l.starts_with(&format!("{key} =")) {
                            (*line).to_string()
                        } else {
                            l.to_string()
                        }
                    })
                    .collect::<Vec<_>>();
                let text = if replaced.iter().any(|l| l == line) {
                    replaced.join("\n")
                } else {
                    format!("{aero}\n{line}")
                };
                (format!("aero.{k}"), vehicle(&text, ""))
            })
            .collect();
        for (k, from, to) in top {
            walked.push((k.to_string(), base.replacen(from, to, 1)));
        }
        for (key, text) in walked {
            assert_ne!(text, base, "{key}: the change was not made");
            std::fs::write(dir.join("v.toml"), &text).unwrap();
            match outcome(&sc_text, &dir) {
                Err(e) => {
                    // Another kind asks for its own keys: the error names the first missing.
                    let leaf = if key == "aero.kind" {
                        "aero."
                    } else {
                        key.rsplit('.').next().unwrap()
                    };
                    assert!(e.contains(leaf), "{key}: the error does not name it: {e}");
                }
                Ok(o) => assert_ne!(o, reference, "{key} changed nothing ({aero})"),
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// What a flight with guidance layers gave: as [`outcome`], with the stack's record (mode,
/// miss, reversals, re-plans) and target; the record's copy of the settings left out (it
/// echoes every key, flown or not).
fn layer_outcome(text: &str, dir: &Path) -> Result<String, String> {
    let sc = parse_scenario(text, "walk.toml", dir).map_err(|e| e.to_string())?;
    let mut f = fly(&sc, "walk.toml", &mut |_| {}).map_err(|e| e.to_string())?;
    if let Some(s) = f.stack.as_mut() {
        s.case.guidance = None;
    }
    let all = format!("{:?} {:?}", f.result, f.stack);
    Ok(format!(
        "{:?} #{}",
        f.stack.map(|s| s.case.miss_m),
        hash(&all)
    ))
}

/// The layer keys walked: `(key, value, context)`; the change is flown against the base with
/// `context` set too (a key read only beside another: the glide sink by the closed forms, the
/// descent time without the barrier law, the constant lift parameter by the closed forms).
#[allow(clippy::type_complexity)]
fn layer_changes() -> Vec<(String, Value, Vec<(&'static str, Value)>)> {
    // With the hybrid predictor this mission flies no closed-form prediction: the closed forms.
    // The template's bank shape needs the numerical predictor: off beside the closed forms.
    let closed_form = || {
        vec![
            ("guidance.replanning.predictor", v("\"closed-form\"")),
            ("guidance.replanning.bank_shape", Value::Boolean(false)),
        ]
    };
    let mut c: Vec<(String, Value, Vec<(&'static str, Value)>)> = vec![];
    let mut add = |k: &str, val: &str, ctx: Vec<(&'static str, Value)>| {
        c.push((format!("guidance.{k}"), v(val), ctx));
    };
    add("lateral.corridor_width_entry_deg", "8.0", vec![]);
    add("lateral.corridor_width_final_deg", "1.0", vec![]);
    add("lateral.corridor_low_speed_fraction", "0.3", vec![]);
    add("lateral.hysteresis_deg", "10.0", vec![]);
    add("lateral.max_reversals", "2", vec![]);
    add("lateral.freeze_km", "200.0", vec![]);
    add("lateral.terminal_start_km", "600.0", vec![]);
    add("lateral.terminal_tolerance_km", "0.2", vec![]);
    add("lateral.terminal_reversal_lead_s", "30.0", vec![]);
    add("replanning.every_n_ticks", "2", vec![]);
    add("replanning.solver_steps_per_tick", "1", vec![]);
    add("replanning.tolerance_km", "20.0", vec![]);
    add("replanning.min_vertical_fraction", "0.5", vec![]);
    add("replanning.max_vertical_fraction", "0.6", vec![]);
    add("replanning.glide_sink", "false", closed_form());
    add(
        "replanning.predictor",
        "\"closed-form\"",
        vec![("guidance.replanning.bank_shape", Value::Boolean(false))],
    );
    add("replanning.lift_parameter", "2.0", closed_form());
    add("replanning.lift_profile", "false", vec![]);
    add("replanning.lift_profile_mach", "true", vec![]);
    add("replanning.start_normalized_energy", "0.8", vec![]);
    add("replanning.limit_scale", "[0.5, 0.5]", vec![]);
    add("replanning.numerical_rotation", "true", vec![]);
    add("replanning.bank_shape", "false", vec![]);
    add("estimator.lift_to_drag_gain", "0.9", vec![]);
    add("estimator.drag_gain", "0.9", vec![]);
    add("estimator.lift_to_drag_bounds", "[0.99, 1.01]", vec![]);
    add("estimator.drag_bounds", "[0.99, 1.01]", vec![]);
    add("estimator.min_drag_m_s2", "50.0", vec![]);
    add("barrier.limit_scale", "[0.5, 0.5]", vec![]);
    add(
        "barrier.descent_time_s",
        "60.0",
        vec![
            ("guidance.barrier.frequency_rad_s", Value::Boolean(false)),
            ("guidance.barrier.damping", Value::Boolean(false)),
        ],
    );
    add("barrier.frequency_rad_s", "0.02", vec![]);
    add("barrier.damping", "5.0", vec![]);
    add("barrier.predicted", "false", vec![]);
    add("target.interface_speed_m_s", "3000.0", vec![]);
    add("target.interface_altitude_m", "40000.0", vec![]);
    add("target.interface_normalized_energy", "0.05", vec![]);
    c
}

/// Every key of the `[guidance.<layer>]` sections ([`LAYER_KEYS`], `[guidance.target]`'s
/// [`TARGET_KEYS`]), changed, changes the stack's flight (trajectory, summary or record) or is
/// refused with an error naming it; `Boolean(false)` in a context removes that key. The base
/// is the reference mission's template (every layer on).
#[test]
fn every_layer_key_changes_the_flight_or_is_refused() {
    use host_sim::scenario::guidance_layers::{LAYER_KEYS, TARGET_KEYS};
    let dir = temp_dir("layers");
    let base: Table = scenario_to_toml(&Scenario::default()).parse().unwrap();
    let with = |t: &Table, ctx: &[(&str, Value)]| {
        let mut t = t.clone();
        for (k, val) in ctx {
            set(
                &mut t,
                k,
                (val != &Value::Boolean(false)).then(|| val.clone()),
            );
        }
        t
    };
    let fly_text = |t: &Table| layer_outcome(&toml::to_string(t).unwrap(), &dir);
    let reference = fly_text(&base).expect("the base flies");
    let mut changes = layer_changes();
    // The target's forms: a point, or downrange and crossrange, in place of `nominal`.
    let point = vec![
        ("guidance.target.nominal", Value::Boolean(false)),
        ("guidance.target.latitude_deg", v("30.0")),
        ("guidance.target.longitude_deg", v("-150.0")),
    ];
    let range = vec![
        ("guidance.target.nominal", Value::Boolean(false)),
        ("guidance.target.downrange_km", v("6000.0")),
        ("guidance.target.crossrange_km", v("100.0")),
    ];
    changes.push((
        "guidance.target.latitude_deg".into(),
        v("31.0"),
        point.clone(),
    ));
    changes.push(("guidance.target.longitude_deg".into(), v("-149.0"), point));
    changes.push((
        "guidance.target.downrange_km".into(),
        v("6500.0"),
        range.clone(),
    ));
    changes.push(("guidance.target.crossrange_km".into(), v("-100.0"), range));
    // `nominal` against a point form (with the point the nominal aim is not).
    changes.push((
        "guidance.target.nominal".into(),
        Value::Boolean(true),
        vec![
            ("guidance.target.nominal", Value::Boolean(false)),
            ("guidance.target.latitude_deg", v("30.0")),
            ("guidance.target.longitude_deg", v("-150.0")),
        ],
    ));
    for (_, section, key) in LAYER_KEYS {
        let k = format!("guidance.{section}.{key}");
        assert!(
            changes.iter().any(|(c, _, _)| *c == k),
            "layer key `{k}` is not walked"
        );
    }
    for key in TARGET_KEYS {
        let k = format!("guidance.target.{key}");
        assert!(
            changes.iter().any(|(c, _, _)| *c == k),
            "target key `{k}` is not walked"
        );
    }
    let mut report = Vec::new();
    for (key, value, ctx) in changes {
        let ctx_base = with(&base, &ctx);
        let ctx_ref = if ctx.is_empty() {
            reference.clone()
        } else {
            fly_text(&ctx_base).unwrap_or_else(|e| panic!("`{key}`: its context: {e}"))
        };
        let mut t = ctx_base.clone();
        if key == "guidance.target.nominal" {
            // `nominal = true` beside a point is refused (one form); alone it aims elsewhere.
            set(&mut t, "guidance.target.latitude_deg", None);
            set(&mut t, "guidance.target.longitude_deg", None);
        }
        set(&mut t, &key, Some(value.clone()));
        match fly_text(&t) {
            Err(e) => {
                let leaf = key.rsplit('.').next().unwrap();
                assert!(
                    e.contains(leaf),
                    "`{key}` = {value}: the error does not name it: {e}"
                );
                report.push(format!("{key}: refused: {e}"));
            }
            Ok(o) => {
                assert_ne!(o, ctx_ref, "`{key}` = {value} changed nothing");
                report.push(format!("{key}: changes the flight ({o} against {ctx_ref})"));
            }
        }
    }
    println!("{}", report.join("\n"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A layer key read only beside another, set away from its default where nothing reads it, is
/// refused naming it (each was flown as nothing before: the same flight, found by the walk
/// above); at its default it is accepted (the template writes every key).
#[test]
fn layer_keys_read_by_nothing_are_refused() {
    let base: Table = scenario_to_toml(&Scenario::default()).parse().unwrap();
    let parse = |t: &Table| {
        parse_scenario(&toml::to_string(t).unwrap(), "unread.toml", Path::new("."))
            .map(|_| ())
            .map_err(|e| e.to_string())
    };
    parse(&base).expect("the template parses");
    /// (key, context: keys set or removed, (value as the error shows it, value), default).
    type Case = (
        &'static str,
        Vec<(&'static str, Option<Value>)>,
        (&'static str, Value),
        Value,
    );
    let cases: [Case; 8] = [
        // The template flies the barrier law and the numerical predictor with the profile.
        (
            "barrier.descent_time_s",
            vec![],
            ("60", v("60.0")),
            v("0.0"),
        ),
        (
            "replanning.glide_sink",
            vec![],
            ("false", v("false")),
            v("true"),
        ),
        (
            "replanning.lift_parameter",
            vec![],
            ("2", v("2.0")),
            v("2.0"),
        ),
        (
            "replanning.lift_profile_mach",
            vec![("guidance.replanning.lift_profile", Some(v("false")))],
            ("true", v("true")),
            v("false"),
        ),
        (
            "lateral.terminal_tolerance_km",
            vec![("guidance.lateral.terminal_start_km", None)],
            ("0.2", v("0.2")),
            v("1.0"),
        ),
        (
            "lateral.terminal_reversal_lead_s",
            vec![
                ("guidance.lateral.terminal_start_km", None),
                ("guidance.lateral.terminal_tolerance_km", Some(v("1.0"))),
            ],
            ("30", v("30.0")),
            v("5.0"),
        ),
        (
            "replanning.glide_sink",
            vec![
                ("guidance.estimator", None),
                ("guidance.replanning.predictor", Some(v("\"hybrid\""))),
                ("guidance.replanning.bank_shape", Some(v("false"))),
            ],
            ("false", v("false")),
            v("true"),
        ),
        // The closed forms fly a constant bank: the shape is numerical only.
        (
            "replanning.bank_shape",
            vec![("guidance.replanning.predictor", Some(v("\"hybrid\"")))],
            ("true", v("true")),
            v("false"),
        ),
    ];
    for (key, ctx, (shown, value), default) in cases {
        let key = format!("guidance.{key}");
        let mut t = base.clone();
        for (k, val) in ctx {
            set(&mut t, k, val);
        }
        set(&mut t, &key, Some(value));
        let e = parse(&t).expect_err(&key);
        assert!(
            e.contains(&format!("`{key}`")) && e.contains(shown) && e.contains("unread.toml"),
            "{key}: {e}"
        );
        if key.ends_with("lift_parameter") {
            // No default value: absent is the only form.
            continue;
        }
        set(&mut t, &key, Some(default));
        parse(&t).unwrap_or_else(|e| panic!("{key} at its default: {e}"));
    }
}
