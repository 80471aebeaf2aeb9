//! Warnings (issue 24 item 4): `simulate` says when a vehicle limit was exceeded (which, by
//! how much, when) and flags likely unit mistakes, as warnings: the run is flown and written.
//! The library returns them typed; the CLI prints them.

use std::path::Path;
use std::process::Command;

use host_sim::scenario::{Limit, Scenario, Warning, fly, input_warnings, parse_scenario};

use crate::support::complete_scenario;

/// The reference mission peaks over its own 500 kW/m^2 heat-flux limit: one warning, with the
/// peak, the limit and the time of the summary, and the span of samples over the limit.
#[test]
fn reference_mission_warns_of_its_heat_flux_peak() {
    let sc = Scenario::horus_2b_stored();
    let f = fly(&sc, "(built-in)", &mut |_| {}).unwrap();
    let w = f.warnings(&sc);
    assert_eq!(w.len(), 1, "{w:?}");
    let Warning::LimitExceeded {
        limit,
        peak,
        limit_value,
        peak_time_s,
        over_s: Some((a, b)),
    } = w[0]
    else {
        panic!("{w:?}");
    };
    let s = &f.result.summary;
    assert_eq!(limit, Limit::HeatFlux);
    assert_eq!(limit_value, 500.0);
    assert_eq!(peak, s.peak_heat_flux_w_m2.value / 1e3);
    assert_eq!(peak_time_s, s.peak_heat_flux_w_m2.time_s);
    assert!((peak / limit_value - s.violations.heat_flux).abs() < 1e-12);
    assert!(
        a <= peak_time_s && peak_time_s <= b,
        "{a} {peak_time_s} {b}"
    );
    // Every sample outside the span is within the limit, every sample at its ends over it.
    for x in &f.result.samples {
        let over = x.conditions.heat_flux_w_m2 > 500e3;
        if x.time_s < a || x.time_s > b {
            assert!(!over, "{}", x.time_s);
        }
        if x.time_s == a || x.time_s == b {
            assert!(over);
        }
    }
    let text = w[0].to_string();
    for part in [
        "limits.heat_flux_kw_m2",
        "511.",
        "500 kW/m^2",
        "% over",
        "t = 380.0 s",
    ] {
        assert!(text.contains(part), "`{part}` not in {text}");
    }
    // Within every limit: no warning.
    let mut calm = Scenario::srm_glide();
    calm.layers = None;
    calm.termination.max_time_s = 300.0;
    let f = fly(&calm, "(built-in)", &mut |_| {}).unwrap();
    assert_eq!(f.warnings(&calm), vec![]);
}

/// Likely unit mistakes are warnings, not errors: the scenario still parses.
#[test]
fn likely_unit_mistakes_are_warned_not_refused() {
    for (snippet, field) in [
        ("[entry]\nspeed_m_s = 7.8", "entry.speed_m_s"),
        (
            "[entry]\nflight_path_angle_deg = -81.9",
            "entry.flight_path_angle_deg",
        ),
        (
            "[entry]\naltitude_km = 0.122\n[termination]\naltitude_km = 0.0",
            "entry.altitude_km",
        ),
    ] {
        let sc = parse_scenario(&complete_scenario(snippet), "u.toml", Path::new(".")).unwrap();
        let w = input_warnings(&sc);
        assert_eq!(w.len(), 1, "{snippet}: {w:?}");
        assert!(
            matches!(w[0], Warning::LikelyUnitMistake { field: f, .. } if f == field),
            "{w:?}"
        );
        assert!(w[0].to_string().contains(field));
    }
    assert_eq!(input_warnings(&Scenario::default()), vec![]);
}

/// The CLI prints the warnings and still writes the run (exit 0).
#[test]
fn simulate_prints_the_warnings() {
    let dir = std::env::temp_dir().join(format!("host-sim-it-warn-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("slow.toml");
    std::fs::write(
        &p,
        complete_scenario("[entry]\nspeed_m_s = 7.8\n[termination]\nmax_time_s = 20.0"),
    )
    .unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["simulate", "--quiet", "--scenario"])
        .arg(&p)
        .arg("--out")
        .arg(dir.join("run"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        stdout.contains("warning: field `entry.speed_m_s` = 7.8: an entry speed below 1 km/s"),
        "{stdout}"
    );
    assert!(dir.join("run/summary.json").exists());
    let o = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args([
            "simulate",
            "--quiet",
            "--builtin",
            "horus-2b-stored",
            "--out",
        ])
        .arg(dir.join("ref"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success());
    assert!(
        stdout.contains("warning: vehicle limit `limits.heat_flux_kw_m2` exceeded: peak 511."),
        "{stdout}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
