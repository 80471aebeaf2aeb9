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
    /// `[replanning]`: onboard re-planning of the bank-angle magnitude.
    pub replanning: Option<ReplanningFile>,
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

/// Predictor of the re-planner.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PredictorFile {
    /// The full chain (skips, arcs, final glide).
    Chain,
    /// Equilibrium glide only.
    Glide,
    /// The chain, the glide when the chain is out of its domain.
    Auto,
    /// As `auto`, the glide with the sink to its equilibrium (`"auto-sink"`).
    #[serde(rename = "auto-sink")]
    AutoSink,
    /// Numerical integration of the predictor model from the navigated state (`"numerical"`).
    Numerical,
    /// The closed forms as `auto` where both ends are in their validated domain, else
    /// `numerical` for the whole solve (`"hybrid"`).
    Hybrid,
    /// As `hybrid`, with `auto-sink` as its closed-form part (`"hybrid-sink"`).
    #[serde(rename = "hybrid-sink")]
    HybridSink,
}

/// `[replanning]`: `guidance_core::replan::ReplanningGuidance` on the scenario's (energy-indexed)
/// table.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReplanningFile {
    /// Re-plan every N guidance ticks.
    pub every_n_ticks: Option<Num>,
    /// Predictor calls per tick (0: the whole solve in its tick).
    pub steps_per_tick: Option<Num>,
    /// Target point latitude \[deg\] (with `target_longitude_deg`).
    pub target_latitude_deg: Option<Num>,
    /// Target point longitude \[deg\].
    pub target_longitude_deg: Option<Num>,
    /// Or: total range along the path from the entry \[km\].
    pub range_km: Option<Num>,
    /// Predictor final speed \[m/s\].
    pub final_speed_m_s: Option<Num>,
    /// Peak heat-flux limit \[kW/m^2\] (default: the vehicle's).
    pub heat_flux_limit_kw_m2: Option<Num>,
    /// Peak g-load limit \[g\] (default: the vehicle's).
    pub g_load_limit: Option<Num>,
    /// Total lift parameter \[-\].
    pub lambda: Option<Num>,
    /// Smallest vertical lift fraction \[-\].
    pub min_vertical_fraction: Option<Num>,
    /// Largest vertical lift fraction \[-\].
    pub max_vertical_fraction: Option<Num>,
    /// Accepted range miss \[m\].
    pub tolerance_m: Option<Num>,
    /// Corrector iterations.
    pub max_iterations: Option<Num>,
    /// Predictor skip budget.
    pub max_skips: Option<Num>,
    /// `"chain"`, `"glide"`, `"auto"`, `"auto-sink"`, `"numerical"`, `"hybrid"` or
    /// `"hybrid-sink"` (default `"hybrid"`).
    pub predictor: Option<PredictorFile>,
    /// Apply the nearest end when the target is out of reach.
    pub apply_out_of_reach: Option<bool>,
    /// Mach number of the vehicle polar the predictor uses \[-\].
    pub polar_mach: Option<Num>,
}
