//! Comments for the scenario TOML that [`scenario_to_toml`](super::scenario_to_toml) prints:
//! each key's meaning, unit, range and default, and a header naming the vehicle keys, so the
//! printout is the annotated template (`host-sim simulate --print-scenario`,
//! docs/reference/scenario.md). Defaults are read from the printout of
//! [`Scenario::default`](super::Scenario) itself, so they cannot drift from it; the ranges are
//! those the reader checks (`resolve*.rs`).

use std::collections::HashMap;
use std::fmt::Write as _;

/// The file's header comment.
const HEADER: &str = "\
# host-sim scenario file (docs/reference/scenario.md, docs/reference/inputs.md). A file states
# what it flies: the vehicle, every [entry] and [guidance] key and termination.max_time_s are
# required (marked \"required\"); the other keys have the generic default given beside them. A
# [guidance.<layer>] section turns that onboard layer on (absent: off; its keys, units and
# ranges: docs/reference/guidance-stack.md). Units are in the key names (SI; degrees and km at
# this edge); ranges are checked before the run.
# The vehicle: `vehicle` names a built-in one (horus-2b, srm; `host-sim vehicles`), or
# `vehicle_file = \"my-vehicle.toml\"` reads a vehicle file (mass, area, nose radius, limits,
# aerodynamics; docs/reference/scenario.md, \"Vehicle file\"), a relative path being relative
# to the folder of this file.
";

/// Comment after a section header.
const SECTIONS: &[(&str, &str)] = &[
    (
        "environment",
        "preset = \"full\" (US76, J2, rotating) or \"simplified\" (exponential, central, still) sets all three",
    ),
    (
        "environment.planet",
        "or preset = \"earth\" | \"mars\"; the constants below override it",
    ),
    (
        "environment.exponential",
        "with atmosphere = \"exponential\"",
    ),
    (
        "environment.table",
        "with atmosphere = \"table\": CSV of altitude, density, temperature or speed of sound",
    ),
    (
        "heat_flux",
        "Chapman: q = c* / sqrt(R_N) sqrt(rho / rho_ref) (V / V_ref)^m",
    ),
    ("entry", "the entry-interface state, planet-relative"),
    (
        "guidance",
        "guidance-core's node table, interpolation, period and rate limits",
    ),
    (
        "termination",
        "the first of altitude_km, mach, normalized_energy or max_time_s ends the flight",
    ),
    ("integrator", "RKF4(5), adaptive"),
    ("monitors", ""),
    ("output", ""),
    (
        "guidance.lateral",
        "layer on: bank reversals in a heading corridor, terminal crossrange law",
    ),
    (
        "guidance.replanning",
        "layer on: the stack's re-planner (predictor-corrector)",
    ),
    (
        "guidance.estimator",
        "layer on: onboard L/D and drag-scale estimation",
    ),
    (
        "guidance.barrier",
        "layer on: the path limits as a barrier on the bank",
    ),
    (
        "guidance.target",
        "where the layers aim, and the terminal interface (a speed, an altitude or an E-hat)",
    ),
];

/// `(section, key, note)`: what the key is, its unit and range; the default is added from the
/// default scenario where it sets the key, else it is in the note.
const KEYS: &[(&str, &str, &str)] = &[
    (
        "",
        "name",
        "run name (runs/<name>/): 1-100 characters, no control characters, / or \\",
    ),
    (
        "",
        "vehicle",
        "built-in vehicle: horus-2b or srm (or vehicle_file, header)",
    ),
    (
        "",
        "vehicle_file",
        "vehicle file, relative to this file's folder (header)",
    ),
    (
        "environment",
        "atmosphere",
        "\"us76\", \"exponential\" or \"table\"",
    ),
    ("environment", "gravity", "\"j2\" or \"central\""),
    (
        "environment",
        "rotating",
        "planet rotation on (true) or off",
    ),
    ("environment.planet", "radius_m", "sphere radius [m], > 0"),
    (
        "environment.planet",
        "mu_m3_s2",
        "gravitational parameter [m^3/s^2], > 0",
    ),
    (
        "environment.planet",
        "j2",
        "second zonal harmonic [-], (-0.1, 0.1)",
    ),
    (
        "environment.planet",
        "rotation_rate_rad_s",
        "[rad/s], (-0.1, 0.1); used when rotating = true",
    ),
    (
        "environment.exponential",
        "rho0_kg_m3",
        "density at altitude 0 [kg/m^3], > 0; default 1.225",
    ),
    (
        "environment.exponential",
        "scale_height_m",
        "[m], > 0; default 7200",
    ),
    (
        "environment.table",
        "file",
        "CSV file, relative to this file's folder (env::TabulatedAtmosphere)",
    ),
    (
        "environment.table",
        "gas_constant_j_kg_k",
        "[J/(kg K)], > 0; default 287.05",
    ),
    (
        "environment.table",
        "heat_capacity_ratio",
        "[-], > 0; default 1.4",
    ),
    ("heat_flux", "coefficient", "c* [W/m^2 m^0.5], > 0"),
    (
        "heat_flux",
        "reference_density_kg_m3",
        "rho_ref [kg/m^3], > 0",
    ),
    ("heat_flux", "reference_speed_m_s", "V_ref [m/s], > 0"),
    ("heat_flux", "speed_exponent", "m [-], > 0"),
    (
        "heat_flux",
        "nose_radius_m",
        "[m], > 0; default: the vehicle's",
    ),
    ("entry", "altitude_km", "[km], (0, 10000)"),
    ("entry", "longitude_deg", "[deg], [-360, 360]"),
    ("entry", "latitude_deg", "geocentric [deg], (-90, 90)"),
    ("entry", "speed_m_s", "planet-relative [m/s], (0, 20000)"),
    ("entry", "flight_path_angle_deg", "[deg], [-90, 90]"),
    (
        "entry",
        "heading_deg",
        "clockwise from north [deg], [-360, 360]",
    ),
    (
        "guidance",
        "independent",
        "node x: \"time\" [s] or \"energy\" (normalised energy, 1 at entry)",
    ),
    (
        "guidance",
        "interpolation",
        "\"linear\", \"natural-cubic\" or \"hermite\" (with tension)",
    ),
    (
        "guidance",
        "tension",
        "cardinal-Hermite tension [-], [0, 1]; default 0",
    ),
    ("guidance", "period_s", "guidance period [s], [0.01, 100]"),
    (
        "guidance",
        "alpha_rate_deg_s",
        "angle-of-attack rate limit [deg/s], [0.001, 1000]",
    ),
    (
        "guidance",
        "sigma_rate_deg_s",
        "bank rate limit [deg/s], [0.001, 1000]",
    ),
    (
        "guidance",
        "initial_alpha_deg",
        "attitude at entry [deg], [0, 45]",
    ),
    (
        "guidance",
        "initial_sigma_deg",
        "attitude at entry [deg], (-180, 180]",
    ),
    (
        "guidance",
        "nodes",
        "rows [x, alpha_deg, sigma_deg]: alpha in [0, 45], sigma in (-180, 180] deg",
    ),
    (
        "termination",
        "altitude_km",
        "[km], [0, 10000), below the entry altitude",
    ),
    ("termination", "mach", "[-], > 0; default: none"),
    (
        "termination",
        "normalized_energy",
        "[-], [0, 1); default: none",
    ),
    ("termination", "max_time_s", "time limit [s], (0, 1e6]"),
    (
        "integrator",
        "rtol",
        "relative tolerance [-], [1e-14, 1e-2]",
    ),
    ("integrator", "h_init_s", "first step [s], (0, 1e4]"),
    ("integrator", "h_min_s", "[s], (0, 1e4], <= h_max_s"),
    (
        "integrator",
        "h_max_s",
        "[s], (0, 1e4], >= termination.max_time_s / max_steps",
    ),
    ("integrator", "max_steps", "integer in [1, 1e8]"),
    (
        "integrator",
        "event_time_tol_s",
        "event-location tolerance [s], (0, 0.01], < period_s",
    ),
    (
        "monitors",
        "interface_altitude_km",
        "exit/re-entry (skip) detection [km], (0, 10000)",
    ),
    (
        "monitors",
        "g_rate_window_s",
        "window of the g-load-rate difference [s], (0, 100]",
    ),
    (
        "output",
        "interval_s",
        "[s]: 0 = one sample per guidance tick, else [0.001, 1e6]",
    ),
];

/// `section.key -> value` of the plain (unannotated) TOML `text` (first line of arrays).
fn values(text: &str) -> HashMap<String, String> {
    let mut out = HashMap::new();
    let mut section = String::new();
    for line in text.lines() {
        if let Some(s) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            section = s.to_string();
        } else if let Some((k, v)) = line.split_once(" = ")
            && !line.starts_with(' ')
            && !line.starts_with('#')
        {
            out.insert(format!("{section}.{k}"), v.to_string());
        }
    }
    out
}

/// The note of `key` in `section`, with the default scenario's value where it sets it.
fn note(section: &str, key: &str, defaults: &HashMap<String, String>) -> Option<String> {
    if let Some(layer) = section.strip_prefix("guidance.") {
        // The layers' keys: one table of names, units and ranges (docs/reference/guidance-stack.md).
        let known = crate::scenario::guidance_layers::LAYER_KEYS
            .iter()
            .any(|(_, s, k)| *s == layer && *k == key)
            || layer == "target";
        return known.then(|| {
            let d = defaults
                .get(&format!("{section}.{key}"))
                .map_or(String::new(), |d| format!("; built-in value {d}"));
            format!("[guidance.{layer}] key (docs/reference/guidance-stack.md){d}")
        });
    }
    let (_, _, text) = KEYS.iter().find(|(s, k, _)| *s == section && *k == key)?;
    if super::required::is_required(section, key) {
        return Some(format!("{text}; required"));
    }
    let default = defaults
        .get(&format!("{section}.{key}"))
        .filter(|_| key != "nodes" && key != "vehicle_file");
    Some(match default {
        Some(d) if !text.contains("default") => format!("{text}; default {d}"),
        _ => (*text).to_string(),
    })
}

/// Append `# note` to `line`, aligned at column 40 where the line is shorter.
fn with_note(out: &mut String, line: &str, note: &str) {
    if note.is_empty() {
        let _ = writeln!(out, "{line}");
    } else {
        let _ = writeln!(out, "{line:<39} # {note}");
    }
}

/// `plain` (a printed scenario) with the header and a note on every section and key;
/// `default_plain` is the printout of the default scenario (the defaults).
pub(super) fn annotate(plain: &str, default_plain: &str) -> String {
    let defaults = values(default_plain);
    let mut out = String::from(HEADER);
    out.push('\n');
    let mut section = String::new();
    for line in plain.lines() {
        if let Some(s) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            section = s.to_string();
            let n = SECTIONS
                .iter()
                .find(|(k, _)| *k == s)
                .map_or("", |(_, n)| n);
            with_note(&mut out, line, n);
        } else if let Some((k, _)) = line
            .split_once(" = ")
            .filter(|_| !line.starts_with(' ') && !line.starts_with('#'))
        {
            let n = note(&section, k, &defaults).unwrap_or_default();
            with_note(&mut out, line, &n);
        } else {
            let _ = writeln!(out, "{line}");
        }
    }
    out
}

/// Keys of `plain` that have no note (a key added to the printout needs one here).
#[cfg(test)]
pub(super) fn keys_without_notes(plain: &str) -> Vec<String> {
    let defaults = values(plain);
    let mut missing: Vec<String> = defaults
        .keys()
        .filter(|full| {
            let (section, key) = full.rsplit_once('.').unwrap_or(("", full));
            note(section, key, &defaults).is_none()
        })
        .cloned()
        .collect();
    missing.sort();
    missing
}
