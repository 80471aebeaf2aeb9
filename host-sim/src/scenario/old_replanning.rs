//! The former top-level `[replanning]` section: a scenario writes its re-planner in
//! `[guidance.replanning]`, its target in `[guidance.target]` and flies it with bank reversals
//! (`[guidance.lateral]`), one set of names for the stack every flight of it flies (SIL, PIL,
//! campaigns). A `[replanning]` section is refused, with the new key of each old one it holds
//! ([`OLD_KEYS`]).

use super::ScenarioError;

/// Each `[replanning]` key and where its setting is written in the guidance layers.
pub const OLD_KEYS: [(&str, &str); 17] = [
    ("every_n_ticks", "[guidance.replanning] every_n_ticks"),
    (
        "steps_per_tick",
        "[guidance.replanning] solver_steps_per_tick",
    ),
    (
        "target_latitude_deg",
        "[guidance.target] latitude_deg (with longitude_deg)",
    ),
    ("target_longitude_deg", "[guidance.target] longitude_deg"),
    (
        "range_km",
        "[guidance.target] downrange_km (with crossrange_km; a great-circle distance, not the flown range)",
    ),
    ("final_speed_m_s", "[guidance.target] interface_speed_m_s"),
    (
        "heat_flux_limit_kw_m2",
        "[guidance.replanning] limit_scale (multiples of the vehicle's [heat flux, g-load])",
    ),
    ("g_load_limit", "[guidance.replanning] limit_scale"),
    ("lambda", "[guidance.replanning] lift_parameter"),
    (
        "min_vertical_fraction",
        "[guidance.replanning] min_vertical_fraction",
    ),
    (
        "max_vertical_fraction",
        "[guidance.replanning] max_vertical_fraction",
    ),
    ("tolerance_m", "[guidance.replanning] tolerance_km (in km)"),
    (
        "max_iterations",
        "none: guidance_core::replan::DEFAULT_MAX_ITERATIONS",
    ),
    (
        "max_skips",
        "none: guidance_core::replan::DEFAULT_MAX_SKIPS",
    ),
    (
        "predictor",
        "[guidance.replanning] predictor (\"closed-form\", \"numerical\" or \"hybrid\")",
    ),
    ("apply_out_of_reach", "none: always on"),
    (
        "polar_mach",
        "none: the campaign's PREDICTOR_POLAR_MACH (20)",
    ),
];

/// The error of a `[replanning]` section `t` in the scenario file `file`: names the section
/// and, for each key it holds (in [`OLD_KEYS`] order, then any other key), the new key.
pub(super) fn refuse(file: &str, t: &toml::Table) -> ScenarioError {
    let mut moves: Vec<String> = OLD_KEYS
        .iter()
        .filter(|(o, _)| t.contains_key(*o))
        .map(|(o, n)| format!("replanning.{o} -> {n}"))
        .collect();
    moves.extend(
        t.keys()
            .filter(|k| OLD_KEYS.iter().all(|(o, _)| o != k))
            .map(|k| format!("replanning.{k} -> none: not a key of the former section")),
    );
    let moves = if moves.is_empty() {
        String::new()
    } else {
        format!(": {}", moves.join("; "))
    };
    ScenarioError::Field {
        file: file.to_string(),
        field: "replanning".into(),
        value: "(section)".into(),
        reason: format!(
            "the section is gone: the re-planner is written in [guidance.replanning] (with \
             [guidance.lateral] for the bank reversals it flies with) and its target in \
             [guidance.target] (docs/reference/guidance-stack.md); remove [replanning]{moves}"
        ),
    }
}
