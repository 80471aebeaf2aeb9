//! Scenario file -> [`Scenario`]: the TOML is read into [`ScenarioFile`] (unknown fields
//! rejected), then every value is range-checked and converted to SI units and radians; every
//! error names the file, the field and the value. Defaults are the HORUS-2B reference mission
//! ([`Scenario::default`]); the `[guidance]` section is in
//! [`resolve_guidance`](super::resolve_guidance).

use std::path::Path;

use crate::toml_input::TomlInputError;

use super::file::{
    EntryFile, IntegratorFile, MonitorsFile, Num, OutputFile, ScenarioFile, TerminationFile,
};
use super::resolve_environment::{environment, heat_flux};
use super::resolve_guidance::guidance;
use super::{Scenario, ScenarioError, VehicleSpec};
use crate::vehicle;

/// Names the file in errors and range-checks numbers.
pub(super) struct Fields<'a> {
    pub(super) file: &'a str,
}

impl Fields<'_> {
    /// The error naming this file, `field`, `value` and `reason`.
    pub(super) fn err(&self, field: &str, value: &str, reason: &str) -> ScenarioError {
        ScenarioError::Field {
            file: self.file.to_string(),
            field: field.to_string(),
            value: value.to_string(),
            reason: reason.to_string(),
        }
    }

    /// A number of field `field` that must be finite and satisfy `ok`.
    pub(super) fn checked(
        &self,
        field: &str,
        v: Option<Num>,
        ok: impl Fn(f64) -> bool,
        reason: &str,
    ) -> Result<Option<f64>, ScenarioError> {
        match v {
            None => Ok(None),
            Some(Num(x)) if !x.is_finite() => {
                Err(self.err(field, &x.to_string(), "must be finite"))
            }
            Some(Num(x)) if !ok(x) => Err(self.err(field, &x.to_string(), reason)),
            Some(Num(x)) => Ok(Some(x)),
        }
    }
}

/// Read the file structs out of TOML text (the one TOML reading path,
/// [`crate::toml_input`]); errors name the file, the field and the value.
fn read_file(text: &str, file: &str) -> Result<ScenarioFile, ScenarioError> {
    match crate::toml_input::parse(text) {
        Ok((sf, _)) => Ok(sf),
        Err(TomlInputError::Syntax(message)) => Err(ScenarioError::Toml {
            file: file.to_string(),
            message,
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
    let f = Fields { file };
    let mut sc = Scenario::default();
    // Files may bank to either side (3-D); the built-in mission keeps the thesis bounds.
    sc.guidance.bounds = super::guidance_bounds();
    if let Some(n) = sf.name {
        if n.is_empty() || n.contains(['/', '\\']) || n == "." || n == ".." {
            return Err(f.err(
                "name",
                &format!("{n:?}"),
                "must be a non-empty name without path separators",
            ));
        }
        sc.name = n;
    }
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
            &(h / 1e3).to_string(),
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
    Ok(sc)
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
        |v| v >= 0.0,
        "must be >= 0",
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
    let pos = |v: f64| v > 0.0;
    if let Some(v) = f.checked("integrator.h_init_s", t.h_init_s, pos, "must be > 0")? {
        tl.h_init = v;
    }
    if let Some(v) = f.checked("integrator.h_min_s", t.h_min_s, pos, "must be > 0")? {
        tl.h_min = v;
    }
    if let Some(v) = f.checked("integrator.h_max_s", t.h_max_s, pos, "must be > 0")? {
        tl.h_max = v;
    }
    if let Some(v) = f.checked(
        "integrator.max_steps",
        t.max_steps,
        |v| v >= 1.0 && v.fract() == 0.0,
        "must be a positive integer",
    )? {
        tl.max_steps = v as u64;
    }
    if let Some(v) = f.checked(
        "integrator.event_time_tol_s",
        t.event_time_tol_s,
        pos,
        "must be > 0",
    )? {
        tl.event_time_tol_s = v;
    }
    if tl.h_min > tl.h_max {
        return Err(f.err(
            "integrator.h_min_s",
            &tl.h_min.to_string(),
            &format!("must be <= h_max_s = {}", tl.h_max),
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
        |v| v >= 0.0,
        "must be >= 0",
    )? {
        sc.output_interval_s = v;
    }
    Ok(())
}
