//! Scenario file -> [`Scenario`]: the TOML is read into [`ScenarioFile`] (unknown fields
//! rejected), then every value is range-checked and converted to SI units and radians; every
//! error names the file, the field and the value. The keys describing the vehicle, the entry,
//! the guidance and the time limit are required (`required`); the others take the generic
//! defaults of [`Scenario::default`] (integrator, monitors, output, environment preset,
//! heat-flux constants); the `[guidance]` section is in
//! [`resolve_guidance`](super::resolve_guidance).

use std::path::Path;

use crate::num_fmt::compact;
use crate::toml_input::TomlInputError;

use super::fields::Fields;
use super::file::{
    EntryFile, IntegratorFile, MonitorsFile, OutputFile, ScenarioFile, TerminationFile,
};
use super::resolve_environment::{environment, heat_flux};
use super::resolve_guidance::guidance;
use super::{Scenario, ScenarioError, VehicleSpec};
use crate::sim::config::{
    MAX_EVENT_TIME_TOL_S, MAX_OUTPUT_SAMPLES, MAX_STEPS_LIMIT, MIN_OUTPUT_INTERVAL_S,
};
use crate::vehicle;

/// Read the file structs out of TOML text (the one TOML reading path,
/// [`crate::toml_input`]); errors name the file, the field and the value.
fn read_file(text: &str, file: &str) -> Result<ScenarioFile, ScenarioError> {
    match crate::toml_input::parse(text) {
        Ok((sf, _)) => Ok(sf),
        Err(TomlInputError::Syntax(source)) => Err(ScenarioError::Toml {
            file: file.to_string(),
            source,
        }),
        Err(TomlInputError::Field {
            field,
            value,
            reason,
        }) => Err(ScenarioError::Field {
            file: file.to_string(),
            field,
            value,
            reason,
        }),
    }
}

/// Read and resolve a scenario file (relative `vehicle_file` paths against its folder).
///
/// # Errors
/// [`ScenarioError`] naming the file, field and value.
pub fn read_scenario(path: &Path) -> Result<Scenario, ScenarioError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|source| ScenarioError::Read {
        file: file.clone(),
        source,
    })?;
    parse_scenario(&text, &file, path.parent().unwrap_or(Path::new(".")))
}

/// Parse a scenario from TOML text; `file` names it in error messages. Relative
/// `vehicle_file` paths are resolved against `base_dir`.
///
/// # Errors
/// [`ScenarioError`] naming file, field and value.
pub fn parse_scenario(text: &str, file: &str, base_dir: &Path) -> Result<Scenario, ScenarioError> {
    let sf = read_file(text, file)?;
    if let Some(t) = &sf.replanning {
        return Err(super::old_replanning::refuse(file, t));
    }
    let f = Fields { file };
    super::required::check(&f, &sf)?;
    // The generic defaults (integrator, monitors, output, environment preset, heat-flux
    // constants); every key describing the vehicle, the entry, the guidance or the run's end
    // is present (checked above) and replaces its value below. A file's layers are the ones
    // it writes (a layer absent is off).
    let mut sc = Scenario {
        layers: None,
        ..Scenario::default()
    };
    // Files may bank to either side (3-D); the built-in mission keeps the thesis bounds.
    sc.guidance.bounds = super::guidance_bounds();
    // The run ends where the file says (max_time_s, required) and on the ground.
    sc.termination = crate::sim::Termination {
        altitude_m: None,
        mach: None,
        normalized_energy: None,
        max_time_s: sc.termination.max_time_s,
    };
    sc.name = run_name(&f, sf.name)?;
    match (sf.vehicle, sf.vehicle_file) {
        (Some(_), Some(p)) => {
            return Err(f.err(
                "vehicle_file",
                &format!("{p:?}"),
                "give either `vehicle` or `vehicle_file`, not both",
            ));
        }
        (Some(n), None) => {
            if vehicle::by_name(&n).is_err() {
                return Err(f.err(
                    "vehicle",
                    &format!("{n:?}"),
                    &format!("unknown vehicle (known: {})", vehicle::list().join(", ")),
                ));
            }
            sc.vehicle = VehicleSpec::Name(n);
        }
        (None, Some(p)) => sc.vehicle = VehicleSpec::File(base_dir.join(p)),
        (None, None) => {}
    }
    if let Some(t) = sf.environment {
        environment(&f, t, base_dir, &mut sc)?;
    }
    if let Some(t) = sf.heat_flux {
        heat_flux(&f, t, &mut sc)?;
    }
    if let Some(t) = sf.entry {
        entry(&f, t, &mut sc)?;
    }
    if let Some(t) = sf.guidance {
        guidance(&f, t, &mut sc)?;
    }
    if let Some(t) = sf.termination {
        termination(&f, t, &mut sc)?;
    }
    let radius = sc.environment.planet.radius_m;
    if let Some(h) = sc.termination.altitude_m
        && h >= sc.entry.radius_m - radius
    {
        return Err(f.err(
            "termination.altitude_km",
            &compact(h / 1e3),
            "must be below the entry altitude",
        ));
    }
    if let Some(t) = sf.integrator {
        integrator(&f, t, &mut sc)?;
    }
    if let Some(t) = sf.monitors {
        monitors(&f, t, &mut sc)?;
    }
    if let Some(t) = sf.output {
        output(&f, t, &mut sc)?;
    }
    cross_checks(&f, &sc)?;
    Ok(sc)
}

/// The run name: `name` as written, or the file's stem (`capsule.toml` -> `capsule`).
fn run_name(f: &Fields<'_>, name: Option<String>) -> Result<String, ScenarioError> {
    let (n, shown_as) = match name {
        Some(n) => (n.clone(), format!("{n:?}")),
        None => {
            let stem = Path::new(f.file)
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            (stem.clone(), format!("(missing; file stem {stem:?})"))
        }
    };
    if let Err(reason) = crate::toml_input::check_name(&n) {
        return Err(f.err("name", &shown_as, reason));
    }
    if n.contains(['/', '\\']) || n == "." || n == ".." {
        return Err(f.err(
            "name",
            &shown_as,
            "must be a name without path separators (it names the run directory)",
        ));
    }
    Ok(n)
}

/// The `[entry]` section: the entry state (km and degrees in the file).
fn entry(f: &Fields<'_>, t: EntryFile, sc: &mut Scenario) -> Result<(), ScenarioError> {
    let radius = sc.environment.planet.radius_m;
    let e = &mut sc.entry;
    if let Some(h) = f.checked(
        "entry.altitude_km",
        t.altitude_km,
        |h| h > 0.0 && h < 10_000.0,
        "must be in (0, 10000) km",
    )? {
        e.radius_m = radius + h * 1e3;
    }
    if let Some(v) = f.checked(
        "entry.longitude_deg",
        t.longitude_deg,
        |v| v.abs() <= 360.0,
        "must be within [-360, 360] deg",
    )? {
        e.longitude_rad = v.to_radians();
    }
    if let Some(v) = f.checked(
        "entry.latitude_deg",
        t.latitude_deg,
        |v| v.abs() < 90.0,
        "must be within (-90, 90) deg",
    )? {
        e.latitude_rad = v.to_radians();
    }
    if let Some(v) = f.checked(
        "entry.speed_m_s",
        t.speed_m_s,
        |v| v > 0.0 && v < 20_000.0,
        "must be in (0, 20000) m/s",
    )? {
        e.speed_m_s = v;
    }
    if let Some(v) = f.checked(
        "entry.flight_path_angle_deg",
        t.flight_path_angle_deg,
        |v| v.abs() <= 90.0,
        "must be within [-90, 90] deg",
    )? {
        e.flight_path_angle_rad = v.to_radians();
    }
    if let Some(v) = f.checked(
        "entry.heading_deg",
        t.heading_deg,
        |v| v.abs() <= 360.0,
        "must be within [-360, 360] deg",
    )? {
        e.heading_rad = v.to_radians();
    }
    Ok(())
}

/// The `[termination]` section.
fn termination(f: &Fields<'_>, t: TerminationFile, sc: &mut Scenario) -> Result<(), ScenarioError> {
    let tm = &mut sc.termination;
    if let Some(v) = f.checked(
        "termination.altitude_km",
        t.altitude_km,
        |v| (0.0..10_000.0).contains(&v),
        "must be in [0, 10000) km",
    )? {
        tm.altitude_m = Some(v * 1e3);
    }
    if let Some(v) = f.checked("termination.mach", t.mach, |v| v > 0.0, "must be > 0")? {
        tm.mach = Some(v);
    }
    if let Some(v) = f.checked(
        "termination.normalized_energy",
        t.normalized_energy,
        |v| (0.0..1.0).contains(&v),
        "must be within [0, 1)",
    )? {
        tm.normalized_energy = Some(v);
    }
    if let Some(v) = f.checked(
        "termination.max_time_s",
        t.max_time_s,
        |v| v > 0.0 && v <= 1e6,
        "must be in (0, 1e6] s",
    )? {
        tm.max_time_s = v;
    }
    Ok(())
}

/// The `[integrator]` section: RKF4(5) tolerances and step limits.
fn integrator(f: &Fields<'_>, t: IntegratorFile, sc: &mut Scenario) -> Result<(), ScenarioError> {
    let tl = &mut sc.tolerances;
    if let Some(v) = f.checked(
        "integrator.rtol",
        t.rtol,
        |v| (1e-14..=1e-2).contains(&v),
        "must be within [1e-14, 1e-2]",
    )? {
        tl.rtol = v;
    }
    let step = |v: f64| v > 0.0 && v <= 1e4;
    let step_reason = "must be in (0, 1e4] s";
    if let Some(v) = f.checked("integrator.h_init_s", t.h_init_s, step, step_reason)? {
        tl.h_init = v;
    }
    if let Some(v) = f.checked("integrator.h_min_s", t.h_min_s, step, step_reason)? {
        tl.h_min = v;
    }
    if let Some(v) = f.checked("integrator.h_max_s", t.h_max_s, step, step_reason)? {
        tl.h_max = v;
    }
    if let Some(v) = f.checked(
        "integrator.max_steps",
        t.max_steps,
        |v| (1.0..=MAX_STEPS_LIMIT as f64).contains(&v) && v.fract() == 0.0,
        "must be an integer in [1, 1e8]",
    )? {
        tl.max_steps = v as u64;
    }
    if let Some(v) = f.checked(
        "integrator.event_time_tol_s",
        t.event_time_tol_s,
        |v| v > 0.0 && v <= MAX_EVENT_TIME_TOL_S,
        "must be in (0, 0.01] s",
    )? {
        tl.event_time_tol_s = v;
    }
    Ok(())
}

/// Checks across sections, once every section is read: each names the field and the range
/// it must be in, so a setting that would burn the run (millions of steps or samples) or
/// mislead the event location fails before the run.
fn cross_checks(f: &Fields<'_>, sc: &Scenario) -> Result<(), ScenarioError> {
    let tl = &sc.tolerances;
    let max_t = sc.termination.max_time_s;
    if tl.h_min > tl.h_max {
        return Err(f.err(
            "integrator.h_min_s",
            &compact(tl.h_min),
            &format!("must be <= integrator.h_max_s = {} s", compact(tl.h_max)),
        ));
    }
    let h_floor = max_t / tl.max_steps as f64;
    if tl.h_max < h_floor {
        return Err(f.err(
            "integrator.h_max_s",
            &compact(tl.h_max),
            &format!(
                "must be >= termination.max_time_s / integrator.max_steps = {} s \
                 (else the step budget runs out before the time limit)",
                compact(h_floor)
            ),
        ));
    }
    let period = sc.guidance.period_s;
    if tl.event_time_tol_s >= period {
        return Err(f.err(
            "integrator.event_time_tol_s",
            &compact(tl.event_time_tol_s),
            &format!(
                "must be < guidance.period_s = {} s (an event is located within one guidance period)",
                compact(period)
            ),
        ));
    }
    let dt = sc.output_interval_s;
    if dt > 0.0 && max_t / dt > MAX_OUTPUT_SAMPLES {
        return Err(f.err(
            "output.interval_s",
            &compact(dt),
            &format!(
                "must be >= termination.max_time_s / 1e7 = {} s (at most 10 million samples)",
                compact(max_t / MAX_OUTPUT_SAMPLES)
            ),
        ));
    }
    Ok(())
}

/// The `[monitors]` section: skip-detection interface and g-load-rate window.
fn monitors(f: &Fields<'_>, t: MonitorsFile, sc: &mut Scenario) -> Result<(), ScenarioError> {
    if let Some(v) = f.checked(
        "monitors.interface_altitude_km",
        t.interface_altitude_km,
        |v| v > 0.0 && v < 10_000.0,
        "must be in (0, 10000) km",
    )? {
        sc.interface_altitude_m = v * 1e3;
    }
    if let Some(v) = f.checked(
        "monitors.g_rate_window_s",
        t.g_rate_window_s,
        |v| v > 0.0 && v <= 100.0,
        "must be in (0, 100] s",
    )? {
        sc.g_rate_window_s = v;
    }
    Ok(())
}

/// The `[output]` section.
fn output(f: &Fields<'_>, t: OutputFile, sc: &mut Scenario) -> Result<(), ScenarioError> {
    if let Some(v) = f.checked(
        "output.interval_s",
        t.interval_s,
        |v| v == 0.0 || (MIN_OUTPUT_INTERVAL_S..=1e6).contains(&v),
        "must be 0 (one sample per guidance tick) or in [0.001, 1e6] s",
    )? {
        sc.output_interval_s = v;
    }
    Ok(())
}
