//! The keys a scenario file must state: what it flies. The vehicle, the entry state, the
//! guidance and the end of the run have no default (a missing one would otherwise become
//! another mission's value); the keys with a documented generic default (environment preset,
//! heat-flux constants, integrator, monitors, output, run name) may be omitted. Every missing
//! key is an error naming the file and the key (`docs/reference/inputs.md`).

use super::ScenarioError;
use super::file::{InterpolationFile, ScenarioFile};
use super::resolve::Fields;

/// Why a required key is required, for the message.
const WHY: &str = "required: a scenario states what it flies (no default)";

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
    for (key, there) in [
        ("altitude_km", e.altitude_km.is_some()),
        ("longitude_deg", e.longitude_deg.is_some()),
        ("latitude_deg", e.latitude_deg.is_some()),
        ("speed_m_s", e.speed_m_s.is_some()),
        ("flight_path_angle_deg", e.flight_path_angle_deg.is_some()),
        ("heading_deg", e.heading_deg.is_some()),
    ] {
        if !there {
            return Err(missing(&format!("entry.{key}"), "the entry state"));
        }
    }
    let Some(g) = &sf.guidance else {
        return Err(missing("guidance", "the guidance section `[guidance]`"));
    };
    for (key, there) in [
        ("independent", g.independent.is_some()),
        ("interpolation", g.interpolation.is_some()),
        ("period_s", g.period_s.is_some()),
        ("alpha_rate_deg_s", g.alpha_rate_deg_s.is_some()),
        ("sigma_rate_deg_s", g.sigma_rate_deg_s.is_some()),
        ("initial_alpha_deg", g.initial_alpha_deg.is_some()),
        ("initial_sigma_deg", g.initial_sigma_deg.is_some()),
        ("nodes", g.nodes.is_some()),
    ] {
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
