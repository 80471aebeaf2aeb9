//! The mission definition: vehicle, environment, entry state, guidance, termination,
//! integrator, monitors and output.
//!
//! A scenario file (TOML) is read into the serde structs of [`file`](mod@file) (unknown fields
//! rejected), then resolved into a [`Scenario`] (SI units, radians, typed choices) with every
//! value range-checked; every error names the file, the field and the value
//! ([`ScenarioError`]). [`Scenario::default`] is the HORUS-2B reference mission and
//! [`Scenario::builtin`] names the built-in scenarios (`simulate --builtin NAME`). [`fly`]
//! flies a scenario with `guidance-core`'s guidance and [`simulate_scenario`] also writes its
//! run directory; [`Warning`]s tell of exceeded vehicle limits and likely unit mistakes.
//!
//! A scenario file states what it flies: the keys marked REQUIRED below (the vehicle, the
//! entry state, the guidance, the time limit) have no default and their absence is an error
//! naming the file and the key; the others have the generic defaults shown (the name defaults
//! to the file's stem). docs/reference/inputs.md has the rules. `host-sim simulate
//! --print-scenario` prints a complete file (the HORUS-2B reference mission, thesis eq. 2.3
//! and table 2.1):
//!
//! ```toml
//! name = "horus-2b-reference"   # 1-100 characters, no control characters or / \
//! vehicle = "horus-2b"            # REQUIRED: built-in name, or vehicle_file = "my.toml"
//!
//! [environment]                   # default: preset = "full"
//! preset = "full"                 # full: US76, J2, rotating; simplified: exponential, central
//!                                 # (refused if atmosphere, gravity and rotating all given)
//! # atmosphere = "us76" | "exponential" | "table"; gravity = "j2" | "central"; rotating = true
//!
//! [environment.planet]            # optional: preset = "earth" | "mars", then constants
//! radius_m = 6378137.0            # [1e3, 1e9] m
//! mu_m3_s2 = 3.986004418e14       # [1e3, 1e21] m^3/s^2
//! j2 = 1.0826267e-3
//! rotation_rate_rad_s = 7.292115e-5   # used when rotating = true
//!
//! # [environment.exponential]     # with atmosphere = "exponential"
//! # rho0_kg_m3 = 1.225
//! # scale_height_m = 7200.0
//! # [environment.table]           # with atmosphere = "table": CSV altitude, density,
//! # file = "atmosphere.csv"       # temperature or speed of sound (see env::TabulatedAtmosphere)
//! # gas_constant_j_kg_k = 287.05
//! # heat_capacity_ratio = 1.4
//!
//! [heat_flux]                     # Chapman q = c*/sqrt(R_N) sqrt(rho/rho_ref) (V/V_ref)^m
//! coefficient = 1.1097e8          # c* [W/m^2 m^0.5]
//! reference_density_kg_m3 = 1.225
//! reference_speed_m_s = 7905.4
//! speed_exponent = 3.15
//! # nose_radius_m = 0.8           # replaces the vehicle's
//!
//! [entry]                         # REQUIRED: every key
//! altitude_km = 122.0
//! longitude_deg = -106.7
//! latitude_deg = -22.3
//! speed_m_s = 7435.5              # planet-relative
//! flight_path_angle_deg = -1.43
//! heading_deg = 70.75
//!
//! [guidance]                      # REQUIRED: every key (tension with "hermite" only)
//! independent = "time"            # or "energy" (normalised energy, 1 at entry)
//! interpolation = "linear"        # or "natural-cubic", "hermite" (with tension in [0, 1])
//! period_s = 2.0                # [0.01, 100] s
//! alpha_rate_deg_s = 5.0          # [0.001, 1000] deg/s, <= the vehicle's limits.alpha_rate_deg_s
//! sigma_rate_deg_s = 15.0         # [0.001, 1000] deg/s, <= the vehicle's limits.sigma_rate_deg_s
//! initial_alpha_deg = 40.0        # [0, 45] deg
//! initial_sigma_deg = 0.0         # (-180, 180] deg; |sigma| > 90 deg: lift down
//! nodes = [[0, 40, 0], [264, 40, 0], [290, 40, 79.6], ...]   # [x, alpha_deg, sigma_deg]
//!                                 # alpha [0, 45] deg, sigma (-180, 180] deg
//!
//! [termination]
//! altitude_km = 25.0              # [0, 10000) km; and/or mach = 2.5, normalized_energy = 0.01
//!                                 # (optional; not written: not used; the ground always ends it)
//! max_time_s = 2500.0             # REQUIRED: (0, 1e6] s
//!
//! [integrator]
//! rtol = 1e-9
//! h_init_s = 0.1                  # steps: (0, 1e4] s
//! h_min_s = 1e-9                  # <= h_max_s
//! h_max_s = 20.0                  # >= termination.max_time_s / max_steps
//! max_steps = 2000000             # integer in [1, 1e8]
//! event_time_tol_s = 1e-6         # largest event bracket (narrowed to rtol): (0, 0.01] s, < period_s
//!
//! [monitors]
//! interface_altitude_km = 100.0   # exit/re-entry (skip) detection
//! g_rate_window_s = 0.1           # minimum window of the g-load-rate difference
//!
//! [output]
//! interval_s = 0.0                # 0: one sample per guidance tick; else [0.001, 1e6] s
//!                                 # and >= termination.max_time_s / 1e7 (10 million samples)
//! ```
//!
//! The onboard layers beyond the stored profile (re-planner, bank reversals, estimator,
//! path-limit barrier) and their target are the `[guidance.lateral]`, `[guidance.replanning]`,
//! `[guidance.estimator]`, `[guidance.barrier]` and `[guidance.target]` sections
//! ([`GuidanceLayers`]; keys: [`guidance_layers::LAYER_KEYS`], docs/reference/guidance-stack.md).
//! The former top-level `[replanning]` section is refused, naming for each of its keys the
//! layer key that replaced it ([`old_replanning::OLD_KEYS`]).
//!
//! Ranges are checked before the run (the cross-field ones once every section is read), so a
//! setting that would only fail after millions of integrator steps or samples ("maximum
//! number of steps exceeded", growing memory) fails at once, naming the field, its value and
//! the range. Values in messages are printed compactly ([`crate::num_fmt`]: `1e308`,
//! `5e-324`). Why these ranges: a guidance cycle under 10 ms is faster than any re-entry
//! guidance and only multiplies the integrator's breakpoints; the step budget must cover the
//! time limit at the largest step; an event is located well within one guidance period; a
//! run records at most 10 million samples.

mod annotate;
mod builtin;
mod error;
mod fields;
pub mod file;
mod flight;
mod guidance;
pub mod guidance_layers;
pub mod old_replanning;
mod required;
mod resolve;
mod resolve_environment;
mod resolve_guidance;
mod resolve_layers;
mod to_toml;
pub mod warnings;

use std::path::PathBuf;
use std::sync::Arc;

use guidance_core::guidance::Command;

use crate::dynamics::SphericalState;
use crate::env::{
    Atmosphere, CentralGravity, ChapmanHeatFlux, Environment, ExponentialAtmosphere, Gravity,
    J2Gravity, Planet, Preset, TabulatedAtmosphere, Us76,
};
use crate::integrate::Tolerances;
use crate::sim::{SimConfig, Termination};

pub use builtin::{horus_stack, srm_stack};
pub use error::ScenarioError;
pub use flight::{
    Flight, RunOutput, StackOutcome, fly, simulate_scenario, stack_setup, write_flight,
};
pub use guidance::{PREDICTOR_FIT_ALTITUDES_M, build_guidance, build_stack, guidance_bounds};
pub use resolve::{parse_scenario, read_scenario};
pub use to_toml::scenario_to_toml;
pub use warnings::{Limit, Warning, flight_warnings, input_warnings};

/// Interpolation between nodes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum InterpolationKind {
    /// Piecewise linear.
    Linear,
    /// Natural cubic spline.
    NaturalCubic,
    /// Cardinal Hermite spline with tension.
    Hermite {
        /// Tension \[-\].
        tension: f64,
    },
}

/// Guidance settings of a scenario (SI units, radians).
#[derive(Clone, Debug, PartialEq)]
pub struct GuidanceSpec {
    /// Node independent variable (the core's).
    pub independent: guidance_core::nodes::Independent,
    /// Interpolation.
    pub interpolation: InterpolationKind,
    /// Guidance period \[s\].
    pub period_s: f64,
    /// Angle-of-attack rate limit \[rad/s\].
    pub alpha_rate_rad_s: f64,
    /// Bank-angle rate limit \[rad/s\].
    pub sigma_rate_rad_s: f64,
    /// Attitude at t = 0 \[rad\].
    pub initial: Command<f64>,
    /// Nodes `[x, alpha_rad, sigma_rad]` in flight order.
    pub nodes: Vec<[f64; 3]>,
    /// Angle bounds the nodes and commands are held to \[rad\]: the mission's for the
    /// built-in reference scenario, [`guidance_bounds`] (banking to either side) for a
    /// scenario file and the SRM glide.
    pub bounds: guidance_core::nodes::AngleBounds<f64>,
}

/// Atmosphere model of a scenario.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AtmosphereKind {
    /// U.S. Standard Atmosphere 1976.
    Us76,
    /// Exponential atmosphere (default rho0 = 1.225 kg/m^3, H = 7.2 km).
    Exponential,
    /// Tabulated atmosphere from a CSV file.
    Table,
}

impl AtmosphereKind {
    /// Name as written in scenario files.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Us76 => "us76",
            Self::Exponential => "exponential",
            Self::Table => "table",
        }
    }
}

/// Gravity model of a scenario.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum GravityKind {
    /// Central field plus J2.
    J2,
    /// Central field.
    Central,
}

impl GravityKind {
    /// Name as written in scenario files.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Self::J2 => "j2",
            Self::Central => "central",
        }
    }
}

/// A tabulated atmosphere of a scenario: the file it came from and the table.
#[derive(Clone, Debug, PartialEq)]
pub struct AtmosphereTable {
    /// CSV file (as resolved against the scenario file's folder).
    pub file: PathBuf,
    /// The table.
    pub model: Arc<TabulatedAtmosphere>,
}

/// The atmosphere of a scenario, with its parameters.
#[derive(Clone, Debug, PartialEq)]
pub enum AtmosphereSpec {
    /// U.S. Standard Atmosphere 1976.
    Us76,
    /// Exponential atmosphere.
    Exponential(ExponentialAtmosphere),
    /// Tabulated atmosphere.
    Table(AtmosphereTable),
}

impl AtmosphereSpec {
    /// The kind, as named in scenario files.
    #[must_use]
    pub fn kind(&self) -> AtmosphereKind {
        match self {
            Self::Us76 => AtmosphereKind::Us76,
            Self::Exponential(_) => AtmosphereKind::Exponential,
            Self::Table(_) => AtmosphereKind::Table,
        }
    }
}

/// Environment of a scenario: planet, atmosphere, gravity, rotation, heat-flux constants.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvSpec {
    /// Planet constants (its rotation rate is used when [`EnvSpec::rotating`]).
    pub planet: Planet,
    /// Atmosphere model.
    pub atmosphere: AtmosphereSpec,
    /// Gravity model.
    pub gravity: GravityKind,
    /// Rotating planet.
    pub rotating: bool,
    /// Chapman heat-flux constants.
    pub heat_flux: ChapmanHeatFlux,
}

impl EnvSpec {
    /// The models of an environment preset (Earth, thesis heat-flux constants).
    #[must_use]
    pub fn preset(p: Preset) -> Self {
        let (atmosphere, gravity, rotating) = match p {
            Preset::Full => (AtmosphereSpec::Us76, GravityKind::J2, true),
            Preset::Simplified => (
                AtmosphereSpec::Exponential(ExponentialAtmosphere::earth()),
                GravityKind::Central,
                false,
            ),
        };
        Self {
            planet: Planet::earth(),
            atmosphere,
            gravity,
            rotating,
            heat_flux: ChapmanHeatFlux::thesis(),
        }
    }

    /// The planet flown: [`EnvSpec::planet`], without rotation unless [`EnvSpec::rotating`].
    #[must_use]
    pub fn effective_planet(&self) -> Planet {
        if self.rotating {
            self.planet
        } else {
            self.planet.without_rotation()
        }
    }

    /// Build the environment.
    #[must_use]
    pub fn build(&self) -> Environment {
        let planet = self.effective_planet();
        let atmosphere: Box<dyn Atmosphere> = match &self.atmosphere {
            AtmosphereSpec::Us76 => Box::new(Us76::new()),
            AtmosphereSpec::Exponential(e) => Box::new(*e),
            AtmosphereSpec::Table(t) => Box::new(t.model.as_ref().clone()),
        };
        let gravity: Box<dyn Gravity> = match self.gravity {
            GravityKind::Central => Box::new(CentralGravity::from_planet(&planet)),
            GravityKind::J2 => Box::new(J2Gravity::from_planet(&planet)),
        };
        let mut env = Environment::new(planet, atmosphere, gravity);
        env.heat_flux = self.heat_flux;
        env
    }

    /// One-line description for reports.
    #[must_use]
    pub fn describe(&self) -> String {
        let body = if self.planet == Planet::earth() {
            "Earth".to_string()
        } else {
            format!("planet (R = {} km)", self.planet.radius_m / 1e3)
        };
        format!(
            "{} atmosphere, {} gravity, {} spherical {body}",
            self.atmosphere.kind().as_str(),
            self.gravity.as_str(),
            if self.rotating {
                "rotating"
            } else {
                "non-rotating"
            }
        )
    }
}

/// Vehicle choice.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum VehicleSpec {
    /// Built-in name.
    Name(String),
    /// Vehicle TOML file.
    File(PathBuf),
}

impl VehicleSpec {
    /// The vehicle for messages: `vehicle "srm"` or `vehicle_file "capsule.toml"`.
    #[must_use]
    pub fn describe(&self) -> String {
        match self {
            Self::Name(n) => format!("vehicle {n:?}"),
            Self::File(p) => format!("vehicle_file {:?}", p.display().to_string()),
        }
    }

    /// Load the vehicle (the vehicle module's one loader).
    ///
    /// # Errors
    /// [`crate::vehicle::VehicleFileError`] naming the file or name.
    pub fn load(&self) -> Result<crate::vehicle::Vehicle, crate::vehicle::VehicleFileError> {
        match self {
            Self::Name(n) => crate::vehicle::by_name(n),
            Self::File(p) => crate::vehicle::from_toml_file(p),
        }
    }
}

/// A resolved scenario (SI units, radians).
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    /// Name (default output directory runs/\<name\>/).
    pub name: String,
    /// Vehicle.
    pub vehicle: VehicleSpec,
    /// Environment.
    pub environment: EnvSpec,
    /// Entry state.
    pub entry: SphericalState,
    /// Guidance.
    pub guidance: GuidanceSpec,
    /// Termination.
    pub termination: Termination,
    /// Integrator.
    pub tolerances: Tolerances,
    /// Output interval \[s\] (0: per tick).
    pub output_interval_s: f64,
    /// Atmospheric interface for exit/re-entry (skip) detection \[m\] (thesis: 100 km).
    pub interface_altitude_m: f64,
    /// Minimum window of the g-load-rate finite difference \[s\].
    pub g_rate_window_s: f64,
    /// Nose radius replacing the vehicle's \[m\] (`[heat_flux] nose_radius_m`).
    pub nose_radius_m: Option<f64>,
    /// The onboard layers beyond the stored profile that campaigns fly
    /// (`[guidance.lateral]`, `[guidance.replanning]`, `[guidance.estimator]`,
    /// `[guidance.barrier]`; `None`: the stored profile alone).
    pub layers: Option<GuidanceLayers>,
}

/// The scenario's layers beyond the stored profile: which are on, and their settings (the
/// defaults for a layer written without keys; a layer off keeps the defaults, unused).
#[derive(Clone, Debug, PartialEq)]
pub struct GuidanceLayers {
    /// The settings of every layer.
    pub settings: guidance_layers::CampaignGuidance,
    /// The layers on (a mask over the campaigns' full stack).
    pub layers: guidance_core::stack::Layers,
    /// Where the re-planner and the lateral logic aim (`[guidance.target]`).
    pub target: TargetSpec,
    /// The terminal interface (`[guidance.target] interface_speed_m_s`,
    /// `interface_altitude_m` or `interface_normalized_energy`; `None`: the scenario's own
    /// end). A campaign's `[dispersions] interface_speed_m_s` or `--interface-speed` overrides
    /// it.
    pub interface: Option<TerminalInterface>,
}

/// The terminal interface of the scenario's layers (`[guidance.target]`): the state where the
/// nominal flight (the scenario flown with its own stored profile) first crosses the value
/// given, linearly between its output samples. The flights end on that state's specific
/// energy `V^2/2 - mu/r`, the re-planner's predictions too (`CampaignSetup::new`).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TerminalInterface {
    /// Where the nominal flight first slows to this speed (`interface_speed_m_s`).
    Speed {
        /// Planet-relative speed \[m/s\], in (0, entry speed).
        speed_m_s: f64,
    },
    /// Where the nominal flight first descends to this altitude (`interface_altitude_m`).
    Altitude {
        /// Altitude above the planet's sphere \[m\], in (0, entry altitude).
        altitude_m: f64,
    },
    /// Where the nominal flight's normalised energy first falls to this value
    /// (`interface_normalized_energy`).
    NormalizedEnergy {
        /// E-hat of the nominal entry \[-\], in (0, 1): 1 at the entry state, 0 at standstill
        /// on the surface (`guidance_core::energy`).
        normalized_energy: f64,
    },
}

impl TerminalInterface {
    /// The `[guidance.target]` key that gives this interface.
    #[must_use]
    pub fn key(&self) -> &'static str {
        match self {
            Self::Speed { .. } => "interface_speed_m_s",
            Self::Altitude { .. } => "interface_altitude_m",
            Self::NormalizedEnergy { .. } => "interface_normalized_energy",
        }
    }

    /// The value given (in the key's unit).
    #[must_use]
    pub fn value(&self) -> f64 {
        match *self {
            Self::Speed { speed_m_s: v }
            | Self::Altitude { altitude_m: v }
            | Self::NormalizedEnergy {
                normalized_energy: v,
            } => v,
        }
    }
}

/// The target of the scenario's layers at the terminal interface (`[guidance.target]`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TargetSpec {
    /// Where the nominal stored profile flown with bank reversals ends, on the entry great
    /// circle (the campaign set-up finds it by nominal flights; `nominal = true`).
    Nominal,
    /// A point: geocentric latitude and longitude \[rad\].
    Point {
        /// Latitude \[rad\].
        latitude_rad: f64,
        /// Longitude \[rad\].
        longitude_rad: f64,
    },
    /// From the entry point: downrange along the entry heading's great circle and crossrange
    /// off it (positive: right) \[rad\] (great-circle angles).
    Range {
        /// Downrange \[rad\], > 0.
        downrange_rad: f64,
        /// Crossrange \[rad\].
        crossrange_rad: f64,
    },
}

impl Scenario {
    /// The scenario's vehicle: loaded through [`VehicleSpec::load`], with the scenario's
    /// nose radius if it sets one, and checked against the scenario's guidance: the vehicle's
    /// attitude-rate limits (`[limits] alpha_rate_deg_s`, `sigma_rate_deg_s`) bound the
    /// guidance's rate limiter (`[guidance] alpha_rate_deg_s`, `sigma_rate_deg_s`). Every
    /// flight of a scenario (SIL, PIL, campaigns, design problems) loads its vehicle here.
    ///
    /// # Errors
    /// [`ScenarioError::Vehicle`] naming the file or name; [`ScenarioError::RateLimit`] when a
    /// guidance rate exceeds the vehicle's.
    pub fn load_vehicle(&self) -> Result<crate::vehicle::Vehicle, ScenarioError> {
        let mut v = self.vehicle.load()?;
        if let Some(rn) = self.nose_radius_m {
            v.nose_radius_m = rn;
        }
        let g = &self.guidance;
        for (axis, guidance, vehicle) in [
            ("alpha", g.alpha_rate_rad_s, v.limits.alpha_rate_rad_s),
            ("sigma", g.sigma_rate_rad_s, v.limits.sigma_rate_rad_s),
        ] {
            // 1e-12 relative: the same deg/s value converted to rad/s by two routes.
            if guidance > vehicle * (1.0 + 1e-12) {
                return Err(ScenarioError::RateLimit {
                    scenario: self.name.clone(),
                    vehicle: self.vehicle.describe(),
                    axis,
                    guidance_deg_s: guidance.to_degrees(),
                    vehicle_deg_s: vehicle.to_degrees(),
                });
            }
        }
        Ok(v)
    }

    /// The simulator settings this scenario asks for (entry state, termination, tolerances,
    /// output interval, interface altitude, g-load-rate window).
    #[must_use]
    pub fn sim_config(&self) -> SimConfig {
        let mut cfg = SimConfig::new(self.entry);
        cfg.termination = self.termination;
        cfg.tolerances = self.tolerances;
        cfg.output_interval_s = self.output_interval_s;
        cfg.interface_altitude_m = self.interface_altitude_m;
        cfg.g_rate_window_s = self.g_rate_window_s;
        cfg
    }
}

/// A guidance node from file units `[x, alpha_deg, sigma_deg]` to `[x, alpha_rad, sigma_rad]`.
pub(crate) fn node_to_rad(n: &[f64; 3]) -> [f64; 3] {
    [n[0], n[1].to_radians(), n[2].to_radians()]
}
