//! The former simulate-only `[replanning]` section against the scenario's guidance layers: a
//! scenario with `[guidance.*]` layers writes its re-planner in `[guidance.replanning]` and
//! its target in `[guidance.target]`, so a `[replanning]` section beside them (a second set of
//! names and defaults for the same settings) is refused, with the new key of each old one it
//! holds ([`OLD_KEYS`]). A scenario without layers still flies `[replanning]` (`simulate`, and
//! PIL, whose upload carries it).

use super::ScenarioError;
use super::file::ReplanningFile;
use super::resolve::Fields;

/// Each `[replanning]` key and where its setting is written in the guidance layers.
pub const OLD_KEYS: [(&str, &str); 17] = [
    ("every_n_ticks", "[guidance.replanning] every_n_ticks"),
    (
        "steps_per_tick",
        "none: [guidance.replanning] solves in its tick",
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

/// The keys `t` holds, in [`OLD_KEYS`] order.
fn present(t: &ReplanningFile) -> Vec<&'static str> {
    let has = [
        t.every_n_ticks.is_some(),
        t.steps_per_tick.is_some(),
        t.target_latitude_deg.is_some(),
        t.target_longitude_deg.is_some(),
        t.range_km.is_some(),
        t.final_speed_m_s.is_some(),
        t.heat_flux_limit_kw_m2.is_some(),
        t.g_load_limit.is_some(),
        t.lambda.is_some(),
        t.min_vertical_fraction.is_some(),
        t.max_vertical_fraction.is_some(),
        t.tolerance_m.is_some(),
        t.max_iterations.is_some(),
        t.max_skips.is_some(),
        t.predictor.is_some(),
        t.apply_out_of_reach.is_some(),
        t.polar_mach.is_some(),
    ];
    OLD_KEYS
        .iter()
        .zip(has)
        .filter_map(|(&(k, _), h)| h.then_some(k))
        .collect()
}

/// The error of a `[replanning]` section `t` in a scenario with guidance layers: names the
/// section and, for each key it holds, the new key.
pub(super) fn refuse(f: &Fields<'_>, t: &ReplanningFile) -> ScenarioError {
    let moves: Vec<String> = present(t)
        .into_iter()
        .filter_map(|k| {
            OLD_KEYS
                .iter()
                .find(|(o, _)| *o == k)
                .map(|(o, n)| format!("replanning.{o} -> {n}"))
        })
        .collect();
    let moves = if moves.is_empty() {
        String::new()
    } else {
        format!(": {}", moves.join("; "))
    };
    f.err(
        "replanning",
        "(section)",
        &format!(
            "a scenario with [guidance.*] layers writes its re-planner in [guidance.replanning] \
             and its target in [guidance.target]; remove [replanning]{moves}"
        ),
    )
}
