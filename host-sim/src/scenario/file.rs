//! The scenario file as written: serde structs, every section and key an `Option` (so a
//! missing required key is reported as such by `required`), unknown keys rejected
//! (`deny_unknown_fields`). Units are those in the key names (km, deg, deg/s); the
//! resolver ([`super::parse_scenario`]) range-checks them and converts to SI and radians.

use serde::Deserialize;

use super::{AtmosphereKind, GravityKind};
use crate::env::Preset;
pub use crate::toml_input::Num;

/// The whole file.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScenarioFile {
    /// Run name (output directory runs/\<name\>/).
    pub name: Option<String>,
    /// Built-in vehicle name.
    pub vehicle: Option<String>,
    /// Vehicle TOML file, relative to the scenario file.
    pub vehicle_file: Option<String>,
    /// `[environment]`.
    pub environment: Option<EnvironmentFile>,
    /// `[entry]`.
    pub entry: Option<EntryFile>,
    /// `[guidance]`.
    pub guidance: Option<GuidanceFile>,
    /// `[termination]`.
    pub termination: Option<TerminationFile>,
    /// `[integrator]`.
    pub integrator: Option<IntegratorFile>,
    /// `[monitors]`.
    pub monitors: Option<MonitorsFile>,
    /// `[output]`.
    pub output: Option<OutputFile>,
    /// `[heat_flux]`.
    pub heat_flux: Option<HeatFluxFile>,
    /// `[replanning]`: the former re-planning section, refused (any keys: the error names
    /// the layer key of each, `super::old_replanning`).
    pub replanning: Option<toml::Table>,
}

/// `[environment]`: a preset, then single models.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvironmentFile {
    /// `"full"` or `"simplified"`.
    pub preset: Option<Preset>,
    /// `"us76"` or `"exponential"`.
    pub atmosphere: Option<AtmosphereKind>,
    /// `"j2"` or `"central"`.
    pub gravity: Option<GravityKind>,
    /// Rotating planet.
    pub rotating: Option<bool>,
    /// `[environment.planet]`.
    pub planet: Option<PlanetFile>,
    /// `[environment.exponential]`: parameters of the exponential atmosphere.
    pub exponential: Option<ExponentialFile>,
    /// `[environment.table]`: the tabulated atmosphere.
    pub table: Option<TableFile>,
}

/// Planet presets.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PlanetPreset {
    /// Spherical Earth ([`crate::env::Planet::earth`]).
    Earth,
    /// Spherical Mars ([`crate::env::Planet::mars`]).
    Mars,
}

/// `[environment.planet]`: a preset, then single constants.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanetFile {
    /// Preset the constants start from (default: Earth).
    pub preset: Option<PlanetPreset>,
    /// Sphere radius \[m\].
    pub radius_m: Option<Num>,
    /// Gravitational parameter \[m^3/s^2\].
    pub mu_m3_s2: Option<Num>,
    /// Second zonal harmonic \[-\].
    pub j2: Option<Num>,
    /// Rotation rate \[rad/s\] (used when `rotating = true`).
    pub rotation_rate_rad_s: Option<Num>,
}

/// `[environment.exponential]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExponentialFile {
    /// Density at the reference altitude \[kg/m^3\].
    pub rho0_kg_m3: Option<Num>,
    /// Scale height \[m\].
    pub scale_height_m: Option<Num>,
}

/// `[environment.table]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TableFile {
    /// CSV file, relative to the scenario file.
    pub file: String,
    /// Gas constant \[J/(kg K)\] (default: air, 287.05).
    pub gas_constant_j_kg_k: Option<Num>,
    /// Heat-capacity ratio \[-\] (default 1.4).
    pub heat_capacity_ratio: Option<Num>,
}

/// `[heat_flux]`: Chapman constants and the nose radius.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HeatFluxFile {
    /// Coefficient c* \[W/m^2 * m^0.5\].
    pub coefficient: Option<Num>,
    /// Reference density \[kg/m^3\].
    pub reference_density_kg_m3: Option<Num>,
    /// Reference speed \[m/s\].
    pub reference_speed_m_s: Option<Num>,
    /// Speed exponent \[-\].
    pub speed_exponent: Option<Num>,
    /// Nose radius \[m\] (replaces the vehicle's).
    pub nose_radius_m: Option<Num>,
}

/// `[entry]`: the entry state.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EntryFile {
    /// Altitude \[km\].
    pub altitude_km: Option<Num>,
    /// Longitude \[deg\].
    pub longitude_deg: Option<Num>,
    /// Latitude \[deg\].
    pub latitude_deg: Option<Num>,
    /// Planet-relative speed \[m/s\].
    pub speed_m_s: Option<Num>,
    /// Flight-path angle \[deg\].
    pub flight_path_angle_deg: Option<Num>,
    /// Heading \[deg\], clockwise from north.
    pub heading_deg: Option<Num>,
}

/// Node independent variable as written.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum IndependentFile {
    /// Mission time \[s\].
    Time,
    /// Normalised energy \[-\].
    #[serde(alias = "normalized-energy", alias = "normalized_energy")]
    Energy,
}

/// Interpolation as written.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum InterpolationFile {
    /// Piecewise linear.
    Linear,
    /// Natural cubic spline.
    #[serde(alias = "cubic")]
    NaturalCubic,
    /// Cardinal Hermite with `tension`.
    Hermite,
}

/// `[guidance]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GuidanceFile {
    /// Node independent variable.
    pub independent: Option<IndependentFile>,
    /// Interpolation.
    pub interpolation: Option<InterpolationFile>,
    /// Hermite tension \[-\].
    pub tension: Option<Num>,
    /// Guidance period \[s\].
    pub period_s: Option<Num>,
    /// Angle-of-attack rate limit \[deg/s\].
    pub alpha_rate_deg_s: Option<Num>,
    /// Bank-angle rate limit \[deg/s\].
    pub sigma_rate_deg_s: Option<Num>,
    /// Initial angle of attack \[deg\].
    pub initial_alpha_deg: Option<Num>,
    /// Initial bank angle \[deg\].
    pub initial_sigma_deg: Option<Num>,
    /// Nodes `[x, alpha_deg, sigma_deg]` in flight order.
    pub nodes: Option<Vec<Vec<Num>>>,
    /// `[guidance.lateral]`: bank reversals (absent: off).
    pub lateral: Option<super::resolve_layers::LateralFile>,
    /// `[guidance.replanning]`: the re-planner of the campaigns' stack (absent: off).
    pub replanning: Option<super::resolve_layers::ReplanFile>,
    /// `[guidance.estimator]`: onboard estimation (absent: off).
    pub estimator: Option<super::resolve_layers::EstimatorFile>,
    /// `[guidance.barrier]`: the path-limit bound (absent: off).
    pub barrier: Option<super::resolve_layers::BarrierFile>,
    /// `[guidance.target]`: where the layers aim.
    pub target: Option<super::resolve_layers::TargetFile>,
}

/// `[termination]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TerminationFile {
    /// Altitude \[km\].
    pub altitude_km: Option<Num>,
    /// Mach number \[-\].
    pub mach: Option<Num>,
    /// Normalised energy \[-\].
    pub normalized_energy: Option<Num>,
    /// Time limit \[s\].
    pub max_time_s: Option<Num>,
}

/// `[integrator]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IntegratorFile {
    /// Relative tolerance \[-\].
    pub rtol: Option<Num>,
    /// Initial step \[s\].
    pub h_init_s: Option<Num>,
    /// Smallest step \[s\].
    pub h_min_s: Option<Num>,
    /// Largest step \[s\].
    pub h_max_s: Option<Num>,
    /// Step budget.
    pub max_steps: Option<Num>,
    /// Event-location time tolerance \[s\].
    pub event_time_tol_s: Option<Num>,
}

/// `[monitors]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MonitorsFile {
    /// Exit/re-entry interface altitude \[km\].
    pub interface_altitude_km: Option<Num>,
    /// Minimum g-load-rate window \[s\].
    pub g_rate_window_s: Option<Num>,
}

/// `[output]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputFile {
    /// Sample interval \[s\] (0: per tick).
    pub interval_s: Option<Num>,
}
