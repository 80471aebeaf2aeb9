//! The keys a scenario file must state: what it flies. The vehicle, the entry state, the
//! guidance and the end of the run have no default (a missing one would otherwise become
//! another mission's value); the keys with a documented generic default (environment preset,
//! heat-flux constants, integrator, monitors, output, run name) may be omitted. Every missing
//! key is an error naming the file and the key (`docs/reference/inputs.md`).

use super::ScenarioError;
use super::fields::Fields;
use super::file::{InterpolationFile, ScenarioFile};

/// Why a required key is required, for the message.
const WHY: &str = "required: a scenario states what it flies (no default)";

/// The required keys of `[entry]`.
pub(super) const ENTRY_KEYS: [&str; 6] = [
    "altitude_km",
    "longitude_deg",
    "latitude_deg",
    "speed_m_s",
    "flight_path_angle_deg",
    "heading_deg",
];

/// The required keys of `[guidance]` (and `tension` with `interpolation = "hermite"`).
pub(super) const GUIDANCE_KEYS: [&str; 8] = [
    "independent",
    "interpolation",
    "period_s",
    "alpha_rate_deg_s",
    "sigma_rate_deg_s",
    "initial_alpha_deg",
    "initial_sigma_deg",
    "nodes",
];

/// Is `section.key` a key every scenario file must state (the vehicle keys aside)?
pub(super) fn is_required(section: &str, key: &str) -> bool {
    match section {
        "" => key == "vehicle",
        "entry" => ENTRY_KEYS.contains(&key),
        "guidance" => GUIDANCE_KEYS.contains(&key) || key == "tension",
        "termination" => key == "max_time_s",
        _ => false,
    }
}

/// The first required key `sf` lacks, as an error naming the file and the key.
pub(super) fn check(f: &Fields<'_>, sf: &ScenarioFile) -> Result<(), ScenarioError> {
    let missing = |field: &str, what: &str| f.err(field, "(missing)", &format!("{WHY}: {what}"));
    if sf.vehicle.is_none() && sf.vehicle_file.is_none() {
        return Err(missing(
            "vehicle",
            "a built-in vehicle name (`vehicle`) or a vehicle file (`vehicle_file`)",
        ));
    }
    let Some(e) = &sf.entry else {
        return Err(missing("entry", "the entry state section `[entry]`"));
    };
    for (key, there) in ENTRY_KEYS.into_iter().zip([
        e.altitude_km.is_some(),
        e.longitude_deg.is_some(),
        e.latitude_deg.is_some(),
        e.speed_m_s.is_some(),
        e.flight_path_angle_deg.is_some(),
        e.heading_deg.is_some(),
    ]) {
        if !there {
            return Err(missing(&format!("entry.{key}"), "the entry state"));
        }
    }
    let Some(g) = &sf.guidance else {
        return Err(missing("guidance", "the guidance section `[guidance]`"));
    };
    for (key, there) in GUIDANCE_KEYS.into_iter().zip([
        g.independent.is_some(),
        g.interpolation.is_some(),
        g.period_s.is_some(),
        g.alpha_rate_deg_s.is_some(),
        g.sigma_rate_deg_s.is_some(),
        g.initial_alpha_deg.is_some(),
        g.initial_sigma_deg.is_some(),
        g.nodes.is_some(),
    ]) {
        if !there {
            return Err(missing(&format!("guidance.{key}"), "the guidance"));
        }
    }
    let hermite = g.interpolation == Some(InterpolationFile::Hermite);
    match (hermite, &g.tension) {
        (true, None) => {
            return Err(missing(
                "guidance.tension",
                "the tension of the hermite interpolation",
            ));
        }
        (false, Some(t)) => {
            return Err(f.err(
                "guidance.tension",
                &crate::num_fmt::compact(t.0),
                "is read only with interpolation = \"hermite\" (remove it)",
            ));
        }
        _ => {}
    }
    match &sf.termination {
        Some(t) if t.max_time_s.is_some() => Ok(()),
        _ => Err(missing(
            "termination.max_time_s",
            "the time limit of the run (altitude_km, mach and normalized_energy are optional \
             end conditions; the ground always ends it)",
        )),
    }
}
