//! Issue 8 items 8-10: settings that used to burn the run (tiny periods, intervals, steps),
//! misplaced or unreadable error messages, absurd vehicles and names are rejected before the
//! run, each error naming the field, its value (printed compactly) and the range.

use std::path::Path;

use host_sim::scenario::parse_scenario;
use host_sim::vehicle::from_toml_str;

use crate::support::complete_scenario;

/// The error of a scenario made of `toml` (the reference mission's keys otherwise).
fn scenario_err(toml: &str) -> String {
    match parse_scenario(&complete_scenario(toml), "s.toml", Path::new(".")) {
        Ok(_) => panic!("accepted:\n{toml}"),
        Err(e) => e.to_string(),
    }
}

fn assert_names(msg: &str, parts: &[&str]) {
    for p in parts {
        assert!(msg.contains(p), "`{p}` missing from: {msg}");
    }
}

#[test]
fn tiny_periods_intervals_and_steps_are_rejected_before_the_run() {
    let cases: &[(&str, &[&str])] = &[
        (
            "[guidance]\nperiod_s = 1e-6",
            &["guidance.period_s", "1e-6", "[0.01, 100] s"],
        ),
        (
            "[output]\ninterval_s = 1e-9",
            &[
                "output.interval_s",
                "1e-9",
                "0 (one sample per guidance tick) or in [0.001",
            ],
        ),
        (
            "[integrator]\nh_max_s = 1e-6",
            &[
                "integrator.h_max_s",
                "1e-6",
                "termination.max_time_s / integrator.max_steps",
            ],
        ),
        (
            "[integrator]\nh_max_s = 1e-3\nh_min_s = 1e-2",
            &[
                "integrator.h_min_s",
                "0.01",
                "must be <= integrator.h_max_s = 0.001 s",
            ],
        ),
        (
            "[integrator]\nevent_time_tol_s = 1.0",
            &["integrator.event_time_tol_s", "= 1:", "(0, 0.01] s"],
        ),
        (
            "[guidance]\nperiod_s = 0.01\n[integrator]\nevent_time_tol_s = 0.01",
            &[
                "integrator.event_time_tol_s",
                "must be < guidance.period_s = 0.01 s",
            ],
        ),
        (
            "[integrator]\nmax_steps = 1e12",
            &["integrator.max_steps", "1e12", "[1, 1e8]"],
        ),
        (
            "[termination]\nmax_time_s = 1e6\n[output]\ninterval_s = 0.01",
            &[
                "output.interval_s",
                "0.01",
                "termination.max_time_s / 1e7 = 0.1 s",
            ],
        ),
    ];
    for (toml, parts) in cases {
        assert_names(&scenario_err(toml), parts);
    }
    // The bounds themselves are accepted.
    for ok in [
        "[guidance]\nperiod_s = 0.01",
        "[output]\ninterval_s = 0.001",
        "[output]\ninterval_s = 0.0",
        "[integrator]\nevent_time_tol_s = 0.01",
    ] {
        parse_scenario(&complete_scenario(ok), "s.toml", Path::new(".")).unwrap();
    }
}

#[test]
fn errors_blame_the_field_given_and_print_extremes_compactly() {
    // Was blamed on `guidance.interpolation` with no value.
    assert_names(
        &scenario_err("[guidance]\nalpha_rate_deg_s = 5e-324"),
        &[
            "guidance.alpha_rate_deg_s",
            "= 5e-324",
            "[0.001, 1000] deg/s",
        ],
    );
    assert_names(
        &scenario_err("[guidance]\nsigma_rate_deg_s = 1e308"),
        &["guidance.sigma_rate_deg_s", "= 1e308:"],
    );
    // Was printed as `inf` (km -> m overflow) or as a 309-digit integer.
    for toml in [
        "[termination]\naltitude_km = 1e308",
        "[termination]\nmax_time_s = 1e308",
        "[entry]\nspeed_m_s = 1e308",
        "[integrator]\nh_max_s = 1e308",
    ] {
        let e = scenario_err(toml);
        assert!(e.contains("= 1e308:"), "{e}");
        assert!(!e.contains("inf") && !e.contains("00000000"), "{e}");
    }
}

#[test]
fn names_with_control_characters_or_300_characters_are_rejected_up_front() {
    let long = "x".repeat(300);
    for (name, why) in [
        ("a\\u0000b", "control characters"),
        ("run\\nname", "control characters"),
        (long.as_str(), "at most 100 characters"),
        ("   ", "non-empty"),
    ] {
        let e = scenario_err(&format!("name = \"{name}\""));
        assert_names(&e, &["s.toml", "`name`", why]);
    }
    parse_scenario(
        &complete_scenario(&format!("name = \"{}\"", "y".repeat(100))),
        "s.toml",
        Path::new("."),
    )
    .unwrap();
}

const VEHICLE: &str = r#"
mass_kg = 1200.0
reference_area_m2 = 4.5
nose_radius_m = 0.3

[limits]
heat_flux_kw_m2 = 800.0
g_load = 4.0
g_load_rate_per_s = 1.0
alpha_rate_deg_s = 5.0
sigma_rate_deg_s = 10.0
"#;

fn vehicle_err(extra: &str, aero: &str) -> String {
    let text = format!("{extra}{VEHICLE}\n[aero]\n{aero}");
    match from_toml_str(&text, "v.toml") {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

const TABLE: &str = "kind = \"table\"\nmach = [2.0, 10.0]\nalpha_deg = [0.0, 40.0]\n\
                     cl = [[0.0, 0.8], [0.0, 0.6]]\n";

#[test]
fn vehicles_with_zero_or_negative_drag_or_absurd_sizes_are_rejected() {
    // Table: every tabulated drag coefficient positive.
    assert_names(
        &vehicle_err("", &format!("{TABLE}cd = [[0.1, 0.2], [0.08, -0.4]]")),
        &["v.toml", "aero.cd[1][1]", "-0.4", "positive"],
    );
    assert_names(
        &vehicle_err("", &format!("{TABLE}cd = [[0.0, 0.2], [0.08, 0.4]]")),
        &["aero.cd[0][0]", "= 0:"],
    );
    // Polynomial: positive over the declared alpha range (here it crosses zero at 20 deg).
    assert_names(
        &vehicle_err(
            "",
            "kind = \"polynomial\"\ncl = [0.0, 0.02]\ncd = [0.2, -0.01]\nalpha_max_deg = 40.0",
        ),
        &["aero.cd", "positive over alpha in [0, 40] deg"],
    );
    // ... but only there: the same polynomial clamped to 0..10 deg is fine.
    let ok = format!(
        "{VEHICLE}\n[aero]\nkind = \"polynomial\"\ncl = [0.0, 0.02]\ncd = [0.2, -0.01]\n\
         alpha_max_deg = 10.0"
    );
    from_toml_str(&ok, "v.toml").unwrap();
    let good = format!("{TABLE}cd = [[0.1, 0.2], [0.08, 0.4]]");
    from_toml_str(&format!("{VEHICLE}\n[aero]\n{good}"), "v.toml").unwrap();
    // Absurd sizes name the field, the value and the range.
    for (field, bad, range) in [
        ("nose_radius_m", "5e-324", "[0.001, 100] m"),
        ("mass_kg", "-3.0", "[1, 10000000] kg"),
        ("mass_kg", "1e300", "[1, 10000000] kg"),
        ("reference_area_m2", "0.0", "[0.001, 10000] m^2"),
    ] {
        let text = format!("{VEHICLE}\n[aero]\n{good}").replacen(
            &format!("{field} = "),
            &format!("{field} = {bad}\n#"),
            1,
        );
        let e = match from_toml_str(&text, "v.toml") {
            Ok(_) => panic!("{field} = {bad} accepted"),
            Err(e) => e.to_string(),
        };
        let shown = bad.trim_end_matches(".0");
        assert_names(&e, &[field, shown, range]);
    }
    assert_names(
        &vehicle_err("name = \"a\\nb\"\n", &good),
        &["`name`", "control characters"],
    );
}
