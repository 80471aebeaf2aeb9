//! TOML scenario file -> [`Scenario`]: unknown fields rejected, every value range-checked, and
//! every error naming the file, the field and the value. Defaults are the HORUS-2B reference
//! mission ([`Scenario::default`]); the `[guidance]` section is in
//! [`parse_guidance`](super::parse_guidance).

use std::path::Path;

use toml::Table;

use super::fields::Fields;
use super::parse_guidance::guidance;
use super::{CliError, EnvSpec, Scenario, VehicleSpec};
use crate::env::Planet;
use crate::vehicle;

/// Parse a scenario from TOML text; `file` names it in error messages. Relative
/// `vehicle_file` paths are resolved against `base_dir`.
///
/// # Errors
/// [`CliError::Scenario`] naming file, field and value.
pub fn parse_scenario(text: &str, file: &str, base_dir: &Path) -> Result<Scenario, CliError> {
    let doc: Table = text.parse().map_err(|e: toml::de::Error| {
        CliError::Scenario(format!(
            "{file}: malformed TOML: {}",
            e.to_string().trim_end()
        ))
    })?;
    let f = Fields { file };
    f.reject_unknown(
        &doc,
        "",
        &[
            "name",
            "vehicle",
            "vehicle_file",
            "environment",
            "entry",
            "guidance",
            "termination",
            "integrator",
            "output",
            "monitors",
        ],
    )?;
    let mut sc = Scenario::default();
    // Files may bank to either side (3-D); the built-in mission keeps the thesis bounds.
    sc.guidance.bounds = super::guidance_bounds();
    if let Some(n) = f.string(&doc, "", "name")? {
        if n.is_empty() || n.contains(['/', '\\']) || n == "." || n == ".." {
            return Err(f.err(
                "name",
                &format!("{n:?}"),
                "must be a non-empty name without path separators",
            ));
        }
        sc.name = n;
    }
    match (
        f.string(&doc, "", "vehicle")?,
        f.string(&doc, "", "vehicle_file")?,
    ) {
        (Some(_), Some(p)) => {
            return Err(f.err(
                "vehicle_file",
                &format!("{p:?}"),
                "give either `vehicle` or `vehicle_file`, not both",
            ));
        }
        (Some(n), None) => {
            if !vehicle::list()
                .iter()
                .any(|k| k.eq_ignore_ascii_case(n.trim()))
                && vehicle::by_name(&n).is_err()
            {
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

    if let Some(t) = f.table(&doc, "environment")? {
        environment(&f, t, &mut sc)?;
    }

    if let Some(t) = f.table(&doc, "entry")? {
        entry(&f, t, &mut sc)?;
    }

    if let Some(t) = f.table(&doc, "guidance")? {
        guidance(&f, t, &mut sc)?;
    }

    if let Some(t) = f.table(&doc, "termination")? {
        termination(&f, t, &mut sc)?;
    }
    let radius = Planet::earth().radius_m;
    if sc
        .termination
        .altitude_m
        .is_some_and(|h| h >= sc.entry.radius_m - radius)
    {
        return Err(f.err(
            "termination.altitude_km",
            &(sc.termination.altitude_m.unwrap_or(0.0) / 1e3).to_string(),
            "must be below the entry altitude",
        ));
    }

    if let Some(t) = f.table(&doc, "integrator")? {
        integrator(&f, t, &mut sc)?;
    }
    if let Some(t) = f.table(&doc, "monitors")? {
        monitors(&f, t, &mut sc)?;
    }
    if let Some(t) = f.table(&doc, "output")? {
        output(&f, t, &mut sc)?;
    }
    Ok(sc)
}

/// The `[environment]` section: a preset, then single models.
fn environment(f: &Fields<'_>, t: &Table, sc: &mut Scenario) -> Result<(), CliError> {
    let p = "environment";
    f.reject_unknown(t, p, &["preset", "atmosphere", "gravity", "rotating"])?;
    if let Some(preset) = f.string(t, p, "preset")? {
        sc.environment = match preset.as_str() {
            "full" => EnvSpec::full(),
            "simplified" => EnvSpec::simplified(),
            _ => {
                return Err(f.err(
                    "environment.preset",
                    &format!("{preset:?}"),
                    "must be \"full\" or \"simplified\"",
                ));
            }
        };
    }
    if let Some(a) = f.string(t, p, "atmosphere")? {
        if a != "us76" && a != "exponential" {
            return Err(f.err(
                "environment.atmosphere",
                &format!("{a:?}"),
                "must be \"us76\" or \"exponential\"",
            ));
        }
        sc.environment.atmosphere = a;
    }
    if let Some(g) = f.string(t, p, "gravity")? {
        if g != "j2" && g != "central" {
            return Err(f.err(
                "environment.gravity",
                &format!("{g:?}"),
                "must be \"j2\" or \"central\"",
            ));
        }
        sc.environment.gravity = g;
    }
    if let Some(r) = f.boolean(t, p, "rotating")? {
        sc.environment.rotating = r;
    }
    Ok(())
}

/// The `[entry]` section: the entry state (km and degrees in the file).
fn entry(f: &Fields<'_>, t: &Table, sc: &mut Scenario) -> Result<(), CliError> {
    let radius = Planet::earth().radius_m;
    let p = "entry";
    f.reject_unknown(
        t,
        p,
        &[
            "altitude_km",
            "longitude_deg",
            "latitude_deg",
            "speed_m_s",
            "flight_path_angle_deg",
            "heading_deg",
        ],
    )?;
    let e = &mut sc.entry;
    if let Some(h) = f.checked(
        t,
        p,
        "altitude_km",
        |h| h > 0.0 && h < 10_000.0,
        "must be in (0, 10000) km",
    )? {
        e.radius_m = radius + h * 1e3;
    }
    if let Some(v) = f.checked(
        t,
        p,
        "longitude_deg",
        |v| v.abs() <= 360.0,
        "must be within [-360, 360] deg",
    )? {
        e.longitude_rad = v.to_radians();
    }
    if let Some(v) = f.checked(
        t,
        p,
        "latitude_deg",
        |v| v.abs() < 90.0,
        "must be within (-90, 90) deg",
    )? {
        e.latitude_rad = v.to_radians();
    }
    if let Some(v) = f.checked(
        t,
        p,
        "speed_m_s",
        |v| v > 0.0 && v < 20_000.0,
        "must be in (0, 20000) m/s",
    )? {
        e.speed_m_s = v;
    }
    if let Some(v) = f.checked(
        t,
        p,
        "flight_path_angle_deg",
        |v| v.abs() <= 90.0,
        "must be within [-90, 90] deg",
    )? {
        e.flight_path_angle_rad = v.to_radians();
    }
    if let Some(v) = f.checked(
        t,
        p,
        "heading_deg",
        |v| v.abs() <= 360.0,
        "must be within [-360, 360] deg",
    )? {
        e.heading_rad = v.to_radians();
    }
    Ok(())
}

/// The `[termination]` section.
fn termination(f: &Fields<'_>, t: &Table, sc: &mut Scenario) -> Result<(), CliError> {
    let p = "termination";
    f.reject_unknown(
        t,
        p,
        &["altitude_km", "mach", "normalized_energy", "max_time_s"],
    )?;
    let tm = &mut sc.termination;
    if let Some(v) = f.checked(t, p, "altitude_km", |v| v >= 0.0, "must be >= 0")? {
        tm.altitude_m = Some(v * 1e3);
    }
    if let Some(v) = f.checked(t, p, "mach", |v| v > 0.0, "must be > 0")? {
        tm.mach = Some(v);
    }
    if let Some(v) = f.checked(
        t,
        p,
        "normalized_energy",
        |v| (0.0..1.0).contains(&v),
        "must be within [0, 1)",
    )? {
        tm.normalized_energy = Some(v);
    }
    if let Some(v) = f.checked(
        t,
        p,
        "max_time_s",
        |v| v > 0.0 && v <= 1e6,
        "must be in (0, 1e6] s",
    )? {
        tm.max_time_s = v;
    }
    Ok(())
}

/// The `[integrator]` section: RKF4(5) tolerances and step limits.
fn integrator(f: &Fields<'_>, t: &Table, sc: &mut Scenario) -> Result<(), CliError> {
    let p = "integrator";
    f.reject_unknown(
        t,
        p,
        &[
            "rtol",
            "h_init_s",
            "h_min_s",
            "h_max_s",
            "max_steps",
            "event_time_tol_s",
        ],
    )?;
    let tl = &mut sc.tolerances;
    if let Some(v) = f.checked(
        t,
        p,
        "rtol",
        |v| (1e-14..=1e-2).contains(&v),
        "must be within [1e-14, 1e-2]",
    )? {
        tl.rtol = v;
    }
    if let Some(v) = f.checked(t, p, "h_init_s", |v| v > 0.0, "must be > 0")? {
        tl.h_init = v;
    }
    if let Some(v) = f.checked(t, p, "h_min_s", |v| v > 0.0, "must be > 0")? {
        tl.h_min = v;
    }
    if let Some(v) = f.checked(t, p, "h_max_s", |v| v > 0.0, "must be > 0")? {
        tl.h_max = v;
    }
    if let Some(v) = f.checked(
        t,
        p,
        "max_steps",
        |v| v >= 1.0 && v.fract() == 0.0,
        "must be a positive integer",
    )? {
        tl.max_steps = v as u64;
    }
    if let Some(v) = f.checked(t, p, "event_time_tol_s", |v| v > 0.0, "must be > 0")? {
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
fn monitors(f: &Fields<'_>, t: &Table, sc: &mut Scenario) -> Result<(), CliError> {
    let p = "monitors";
    f.reject_unknown(t, p, &["interface_altitude_km", "g_rate_window_s"])?;
    if let Some(v) = f.checked(
        t,
        p,
        "interface_altitude_km",
        |v| v > 0.0 && v < 10_000.0,
        "must be in (0, 10000) km",
    )? {
        sc.interface_altitude_m = v * 1e3;
    }
    if let Some(v) = f.checked(
        t,
        p,
        "g_rate_window_s",
        |v| v > 0.0 && v <= 100.0,
        "must be in (0, 100] s",
    )? {
        sc.g_rate_window_s = v;
    }
    Ok(())
}

/// The `[output]` section.
fn output(f: &Fields<'_>, t: &Table, sc: &mut Scenario) -> Result<(), CliError> {
    f.reject_unknown(t, "output", &["interval_s"])?;
    if let Some(v) = f.checked(t, "output", "interval_s", |v| v >= 0.0, "must be >= 0")? {
        sc.output_interval_s = v;
    }
    Ok(())
}
