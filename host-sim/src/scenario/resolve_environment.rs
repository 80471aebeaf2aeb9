//! The `[environment]` section (planet, atmosphere and its parameters, gravity, rotation) and
//! the `[heat_flux]` section of a scenario file.

use std::path::Path;
use std::sync::Arc;

use super::fields::Fields;
use super::file::{
    EnvironmentFile, ExponentialFile, HeatFluxFile, PlanetFile, PlanetPreset, TableFile,
};
use super::{AtmosphereKind, AtmosphereSpec, AtmosphereTable, EnvSpec, Scenario, ScenarioError};
use crate::env::atmosphere::exponential::R_AIR_J_KG_K;
use crate::env::atmosphere::us76::GAMMA_AIR;
use crate::env::{ExponentialAtmosphere, Planet, TabulatedAtmosphere};
use crate::num_fmt::compact;

/// The `[environment]` section: a preset, then single models and their parameters. A
/// change of planet radius keeps the entry altitude.
pub(super) fn environment(
    f: &Fields<'_>,
    t: EnvironmentFile,
    base_dir: &Path,
    sc: &mut Scenario,
) -> Result<(), ScenarioError> {
    let old_radius = sc.environment.planet.radius_m;
    if let Some(p) = t.preset
        && t.atmosphere.is_some()
        && t.gravity.is_some()
        && t.rotating.is_some()
    {
        return Err(f.err(
            "environment.preset",
            &format!("{:?}", p.name()),
            "has no effect: atmosphere, gravity and rotating are all given (remove one or the preset)",
        ));
    }
    if let Some(p) = t.preset {
        sc.environment = EnvSpec::preset(p);
    }
    let kind = t.atmosphere.unwrap_or(sc.environment.atmosphere.kind());
    if t.exponential.is_some() && kind != AtmosphereKind::Exponential {
        return Err(f.err(
            "environment.exponential",
            "(section)",
            "applies to atmosphere = \"exponential\" only",
        ));
    }
    if t.table.is_some() && kind != AtmosphereKind::Table {
        return Err(f.err(
            "environment.table",
            "(section)",
            "applies to atmosphere = \"table\" only",
        ));
    }
    sc.environment.atmosphere = match kind {
        AtmosphereKind::Us76 => AtmosphereSpec::Us76,
        AtmosphereKind::Exponential => {
            let base = match &sc.environment.atmosphere {
                AtmosphereSpec::Exponential(e) => *e,
                _ => ExponentialAtmosphere::earth(),
            };
            AtmosphereSpec::Exponential(match t.exponential {
                Some(x) => exponential(f, x, base)?,
                None => base,
            })
        }
        AtmosphereKind::Table => match (t.table, &sc.environment.atmosphere) {
            (Some(x), _) => AtmosphereSpec::Table(table(f, x, base_dir)?),
            (None, AtmosphereSpec::Table(old)) => AtmosphereSpec::Table(old.clone()),
            (None, _) => {
                return Err(f.err(
                    "environment.table",
                    "(missing)",
                    "atmosphere = \"table\" needs [environment.table] with file = \"...csv\"",
                ));
            }
        },
    };
    if let Some(g) = t.gravity {
        sc.environment.gravity = g;
    }
    if let Some(r) = t.rotating {
        sc.environment.rotating = r;
    }
    if let Some(p) = t.planet {
        sc.environment.planet = planet(f, p)?;
    }
    if sc.environment.planet.radius_m != old_radius {
        sc.entry.radius_m = sc.environment.planet.radius_m + (sc.entry.radius_m - old_radius);
    }
    Ok(())
}

/// `[environment.planet]`: a preset, then single constants.
fn planet(f: &Fields<'_>, t: PlanetFile) -> Result<Planet, ScenarioError> {
    if let Some(preset) = t.preset
        && t.radius_m.is_some()
        && t.mu_m3_s2.is_some()
        && t.j2.is_some()
        && t.rotation_rate_rad_s.is_some()
    {
        return Err(f.err(
            "environment.planet.preset",
            &format!("{preset:?}").to_lowercase(),
            "has no effect: every planet constant is given (remove one or the preset)",
        ));
    }
    let mut p = match t.preset {
        None | Some(PlanetPreset::Earth) => Planet::earth(),
        Some(PlanetPreset::Mars) => Planet::mars(),
    };
    // From an asteroid (1 km, mu 1e3) to beyond the Sun (1e9 m, 1e21 m^3/s^2): outside, the
    // normalised energy and the closed forms' scales do not exist.
    if let Some(v) = f.checked(
        "environment.planet.radius_m",
        t.radius_m,
        |v| (1e3..=1e9).contains(&v),
        "must be > 0 and in [1e3, 1e9] m",
    )? {
        p.radius_m = v;
    }
    if let Some(v) = f.checked(
        "environment.planet.mu_m3_s2",
        t.mu_m3_s2,
        |v| (1e3..=1e21).contains(&v),
        "must be > 0 and in [1e3, 1e21] m^3/s^2",
    )? {
        p.mu_m3_s2 = v;
    }
    if let Some(v) = f.checked(
        "environment.planet.j2",
        t.j2,
        |v| v.abs() < 0.1,
        "must be within (-0.1, 0.1)",
    )? {
        p.j2 = v;
    }
    if let Some(v) = f.checked(
        "environment.planet.rotation_rate_rad_s",
        t.rotation_rate_rad_s,
        |v| v.abs() < 0.1,
        "must be within (-0.1, 0.1) rad/s",
    )? {
        p.rotation_rate_rad_s = v;
    }
    Ok(p)
}

/// `[environment.exponential]`: rho0 and scale height over `base`.
fn exponential(
    f: &Fields<'_>,
    t: ExponentialFile,
    base: ExponentialAtmosphere,
) -> Result<ExponentialAtmosphere, ScenarioError> {
    let pos = |v: f64| v > 0.0;
    let rho0 = f
        .checked(
            "environment.exponential.rho0_kg_m3",
            t.rho0_kg_m3,
            pos,
            "must be > 0",
        )?
        .unwrap_or(base.rho0_kg_m3());
    let h = f
        .checked(
            "environment.exponential.scale_height_m",
            t.scale_height_m,
            pos,
            "must be > 0",
        )?
        .unwrap_or(base.scale_height_m());
    ExponentialAtmosphere::new(rho0, h, base.reference_altitude_m()).map_err(|e| {
        f.err(
            &format!("environment.exponential.{}", e.parameter),
            &compact(e.value),
            e.reason,
        )
    })
}

/// `[environment.table]`: the CSV file (relative to the scenario file) and its gas constants.
fn table(f: &Fields<'_>, t: TableFile, base_dir: &Path) -> Result<AtmosphereTable, ScenarioError> {
    let pos = |v: f64| v > 0.0;
    let r = f
        .checked(
            "environment.table.gas_constant_j_kg_k",
            t.gas_constant_j_kg_k,
            pos,
            "must be > 0",
        )?
        .unwrap_or(R_AIR_J_KG_K);
    let gamma = f
        .checked(
            "environment.table.heat_capacity_ratio",
            t.heat_capacity_ratio,
            pos,
            "must be > 0",
        )?
        .unwrap_or(GAMMA_AIR);
    let file = base_dir.join(&t.file);
    let model = TabulatedAtmosphere::from_csv_file(&file, r, gamma).map_err(|source| {
        ScenarioError::Atmosphere {
            file: f.file.to_string(),
            source,
        }
    })?;
    Ok(AtmosphereTable {
        file,
        model: Arc::new(model),
    })
}

/// The `[heat_flux]` section: Chapman constants and the nose radius.
pub(super) fn heat_flux(
    f: &Fields<'_>,
    t: HeatFluxFile,
    sc: &mut Scenario,
) -> Result<(), ScenarioError> {
    let pos = |v: f64| v > 0.0;
    let hf = &mut sc.environment.heat_flux;
    for (field, v, slot) in [
        ("heat_flux.coefficient", t.coefficient, &mut hf.coefficient),
        (
            "heat_flux.reference_density_kg_m3",
            t.reference_density_kg_m3,
            &mut hf.reference_density_kg_m3,
        ),
        (
            "heat_flux.reference_speed_m_s",
            t.reference_speed_m_s,
            &mut hf.reference_speed_m_s,
        ),
        (
            "heat_flux.speed_exponent",
            t.speed_exponent,
            &mut hf.speed_exponent,
        ),
    ] {
        if let Some(x) = f.checked(field, v, pos, "must be > 0")? {
            *slot = x;
        }
    }
    if let Some(x) = f.checked(
        "heat_flux.nose_radius_m",
        t.nose_radius_m,
        pos,
        "must be > 0",
    )? {
        sc.nose_radius_m = Some(x);
    }
    Ok(())
}
