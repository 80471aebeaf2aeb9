//! Command-line interface (`host-sim simulate | atmosphere | vehicles`) and the TOML scenario
//! format behind it.
//!
//! Every error names the file, the field and the offending value; nothing panics on bad
//! input. The library entry point is [`run`], which `main` calls; tests call it directly.
//!
//! Scenario file (all sections and keys optional; defaults are the HORUS-2B reference
//! mission, thesis eq. 2.3 and table 2.1). `host-sim simulate --print-scenario` prints it:
//!
//! ```toml
//! name = "horus-2b-reference"
//! vehicle = "horus-2b"            # built-in name, or vehicle_file = "my.toml"
//!
//! [environment]
//! preset = "full"                 # full: US76, J2, rotating; simplified: exponential, central
//! # atmosphere = "us76" | "exponential"; gravity = "j2" | "central"; rotating = true
//!
//! [entry]
//! altitude_km = 122.0
//! longitude_deg = -106.7
//! latitude_deg = -22.3
//! speed_m_s = 7435.5              # planet-relative
//! flight_path_angle_deg = -1.43
//! heading_deg = 70.75
//!
//! [guidance]
//! independent = "time"            # or "energy" (normalised energy, 1 at entry)
//! interpolation = "linear"        # or "natural-cubic", "hermite" (with tension)
//! period_s = 2.0
//! alpha_rate_deg_s = 5.0
//! sigma_rate_deg_s = 15.0
//! initial_alpha_deg = 40.0
//! initial_sigma_deg = 0.0
//! nodes = [[0, 40, 0], [264, 40, 0], [290, 40, 79.6], ...]   # [x, alpha_deg, sigma_deg]
//!
//! [termination]
//! altitude_km = 25.0              # and/or mach = 2.5, normalized_energy = 0.01
//! max_time_s = 2500.0
//!
//! [integrator]
//! rtol = 1e-9
//! h_init_s = 0.1
//! h_min_s = 1e-9
//! h_max_s = 20.0
//! max_steps = 2000000
//! event_time_tol_s = 1e-6
//!
//! [monitors]
//! interface_altitude_km = 100.0   # exit/re-entry (skip) detection
//! g_rate_window_s = 0.1           # minimum window of the g-load-rate difference
//!
//! [output]
//! interval_s = 0.0                # 0: one sample per guidance tick
//! ```

use std::ffi::OsString;
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};

use clap::{Parser, Subcommand, ValueEnum};
use guidance_core::energy::EnergyNormalizer;
use toml::{Table, Value};

use crate::dynamics::{Attitude, Dynamics, SphericalState};
use crate::env::{
    Atmosphere, CentralGravity, Environment, ExponentialAtmosphere, Gravity, J2Gravity, Planet,
    Us76,
};
use crate::integrate::Tolerances;
use crate::report;
use crate::sim::{self, AttitudeSource, SimConfig, Termination};
use crate::vehicle::{self, Vehicle};
use guidance_core::guidance::{Command as CoreCommand, Guidance, GuidanceConfig, RateLimits};
use guidance_core::interp::Interpolation;
use guidance_core::nodes::{AngleBounds, Independent as CoreIndependent, Node, NodeTable};

/// `host-sim`: 3-DOF re-entry simulator flying guidance-core's guidance closed-loop.
#[derive(Debug, Parser)]
#[command(name = "host-sim", version, about, long_about = None)]
pub struct Cli {
    /// Subcommand.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Fly a scenario closed-loop (default: the HORUS-2B reference mission) and write a run
    /// directory with trajectory.csv, summary.json and SVG plots.
    Simulate(SimulateArgs),
    /// Query an atmosphere model at altitudes given in km.
    Atmosphere(AtmosphereArgs),
    /// List the built-in vehicles.
    Vehicles,
    /// Analytical (Vinh closed forms) against numerical simulation over a grid of entry
    /// altitude or speed x vertical lift coefficient (thesis fig. 8.5): grid.csv + SVG heat maps.
    Compare(crate::compare::CompareCliArgs),
}

/// Arguments of `simulate`.
#[derive(Debug, clap::Args)]
pub struct SimulateArgs {
    /// Scenario TOML file (default: built-in HORUS-2B reference mission).
    #[arg(long, value_name = "FILE")]
    pub scenario: Option<PathBuf>,
    /// Output directory (default: runs/<scenario-name>/).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Built-in scenario instead of a file: horus-2b-reference (default) or srm-glide.
    #[arg(long, value_name = "NAME", conflicts_with = "scenario")]
    pub builtin: Option<String>,
    /// Print the scenario (default or loaded) as TOML and exit without simulating.
    #[arg(long)]
    pub print_scenario: bool,
    /// Do not show a progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// Atmosphere model choice.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum AtmosphereModel {
    /// U.S. Standard Atmosphere 1976.
    Us76,
    /// Exponential, rho0 = 1.225 kg/m^3, H = 7.2 km.
    Exponential,
}

/// Arguments of `atmosphere`.
#[derive(Debug, clap::Args)]
pub struct AtmosphereArgs {
    /// Model.
    #[arg(long, value_enum, default_value = "us76")]
    pub model: AtmosphereModel,
    /// Altitudes [km] (default 0, 10, ..., 120).
    #[arg(value_name = "ALTITUDE_KM", allow_negative_numbers = true)]
    pub altitudes_km: Vec<f64>,
}

/// CLI failures; the message names file, field and value where there is one.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// Command-line usage error (also `--help`/`--version`, which are not failures).
    #[error("{0}")]
    Usage(#[from] clap::Error),
    /// Bad scenario file or value.
    #[error("{0}")]
    Scenario(String),
    /// Vehicle could not be loaded.
    #[error("{0}")]
    Vehicle(#[from] vehicle::VehicleFileError),
    /// Simulation failed.
    #[error("simulation failed: {0}")]
    Sim(#[from] sim::SimError),
    /// Output could not be written.
    #[error("{0}")]
    Report(#[from] report::ReportError),
    /// Analytical-vs-numerical comparison failed.
    #[error("{0}")]
    Compare(#[from] crate::compare::CompareError),
    /// Writing to the console failed.
    #[error("cannot write output: {0}")]
    Io(#[from] std::io::Error),
}

/// Which node independent variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Independent {
    /// Time [s].
    Time,
    /// Normalised energy [-].
    Energy,
}

/// Interpolation between nodes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum InterpolationKind {
    /// Piecewise linear.
    Linear,
    /// Natural cubic spline.
    NaturalCubic,
    /// Cardinal Hermite spline with tension.
    Hermite {
        /// Tension [-].
        tension: f64,
    },
}

/// Guidance settings of a scenario (SI units, radians).
#[derive(Clone, Debug, PartialEq)]
pub struct GuidanceSpec {
    /// Node independent variable.
    pub independent: Independent,
    /// Interpolation.
    pub interpolation: InterpolationKind,
    /// Guidance period [s].
    pub period_s: f64,
    /// Angle-of-attack rate limit [rad/s].
    pub alpha_rate_rad_s: f64,
    /// Bank-angle rate limit [rad/s].
    pub sigma_rate_rad_s: f64,
    /// Attitude at t = 0.
    pub initial: Attitude,
    /// Nodes `[x, alpha_rad, sigma_rad]` in flight order.
    pub nodes: Vec<[f64; 3]>,
}

/// Environment choice.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EnvSpec {
    /// `"us76"` or `"exponential"`.
    pub atmosphere: String,
    /// `"j2"` or `"central"`.
    pub gravity: String,
    /// Rotating planet.
    pub rotating: bool,
}

impl EnvSpec {
    /// Build the environment.
    #[must_use]
    pub fn build(&self) -> Environment {
        let planet = if self.rotating {
            Planet::earth()
        } else {
            Planet::earth_non_rotating()
        };
        let atmosphere: Box<dyn Atmosphere> = if self.atmosphere == "exponential" {
            Box::new(ExponentialAtmosphere::earth())
        } else {
            Box::new(Us76::new())
        };
        let gravity: Box<dyn Gravity> = if self.gravity == "central" {
            Box::new(CentralGravity::from_planet(&planet))
        } else {
            Box::new(J2Gravity::from_planet(&planet))
        };
        Environment::new(planet, atmosphere, gravity)
    }

    fn describe(&self) -> String {
        format!(
            "{} atmosphere, {} gravity, {} spherical Earth",
            self.atmosphere,
            self.gravity,
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

/// A resolved scenario (SI units, radians).
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    /// Name (default output directory runs/<name>/).
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
    /// Output interval [s] (0: per tick).
    pub output_interval_s: f64,
    /// Atmospheric interface for exit/re-entry (skip) detection [m] (thesis: 100 km).
    pub interface_altitude_m: f64,
    /// Minimum window of the g-load-rate finite difference [s].
    pub g_rate_window_s: f64,
}

/// HORUS-2B reference guidance nodes (thesis eq. 2.3): `[t_s, alpha_deg, sigma_deg]`.
pub const HORUS_REFERENCE_NODES: [[f64; 3]; 7] = [
    [0.0, 40.0, 0.0],
    [264.0, 40.0, 0.0],
    [290.0, 40.0, 79.6],
    [554.0, 40.0, 59.8],
    [686.0, 40.0, 59.8],
    [924.0, 40.0, 59.8],
    [1319.0, 11.5, 54.0],
];

impl Default for Scenario {
    /// The HORUS-2B reference mission (thesis sec. 2.2 and 7.4): full environment, time
    /// nodes of eq. 2.3 with linear interpolation, entry state of table 2.1, terminated at
    /// 25 km altitude.
    fn default() -> Self {
        let planet = Planet::earth();
        Self {
            name: "horus-2b-reference".into(),
            vehicle: VehicleSpec::Name("horus-2b".into()),
            environment: EnvSpec {
                atmosphere: "us76".into(),
                gravity: "j2".into(),
                rotating: true,
            },
            entry: SphericalState {
                radius_m: planet.radius_m + 122_000.0,
                longitude_rad: (-106.7f64).to_radians(),
                latitude_rad: (-22.3f64).to_radians(),
                speed_m_s: 7435.5,
                flight_path_angle_rad: (-1.43f64).to_radians(),
                heading_rad: 70.75f64.to_radians(),
            },
            guidance: GuidanceSpec {
                independent: Independent::Time,
                interpolation: InterpolationKind::Linear,
                period_s: 2.0,
                alpha_rate_rad_s: 5f64.to_radians(),
                sigma_rate_rad_s: 15f64.to_radians(),
                initial: Attitude {
                    alpha_rad: 40f64.to_radians(),
                    sigma_rad: 0.0,
                },
                nodes: HORUS_REFERENCE_NODES
                    .iter()
                    .map(|n| [n[0], n[1].to_radians(), n[2].to_radians()])
                    .collect(),
            },
            termination: Termination {
                altitude_m: Some(25_000.0),
                mach: None,
                normalized_energy: None,
                max_time_s: 2500.0,
            },
            tolerances: SimConfig::new(SphericalState {
                radius_m: 1.0,
                longitude_rad: 0.0,
                latitude_rad: 0.0,
                speed_m_s: 1.0,
                flight_path_angle_rad: 0.0,
                heading_rad: 0.0,
            })
            .tolerances,
            output_interval_s: 0.0,
            interface_altitude_m: 100_000.0,
            g_rate_window_s: 0.1,
        }
    }
}

impl Scenario {
    /// Built-in scenarios by name: `horus-2b-reference` (the default) and `srm-glide`.
    #[must_use]
    pub fn builtin(name: &str) -> Option<Self> {
        match name {
            "horus-2b-reference" => Some(Self::default()),
            "srm-glide" => Some(Self::srm_glide()),
            _ => None,
        }
    }

    /// Names accepted by [`Scenario::builtin`].
    pub const BUILTIN: [&'static str; 2] = ["horus-2b-reference", "srm-glide"];

    /// SRM capsule glide in the simplified environment from the thesis' sec. 9.2 entry
    /// state (100 km, 7658.34 m/s, -0.056 deg); bank-angle-only energy-indexed guidance
    /// (illustrative nodes, the thesis' optimised ones are not printed), ended at 25 km.
    #[must_use]
    pub fn srm_glide() -> Self {
        let planet = Planet::earth_non_rotating();
        let d = std::f64::consts::PI / 180.0;
        Self {
            name: "srm-glide".into(),
            vehicle: VehicleSpec::Name("srm".into()),
            environment: EnvSpec {
                atmosphere: "exponential".into(),
                gravity: "central".into(),
                rotating: false,
            },
            entry: SphericalState {
                radius_m: planet.radius_m + 100_000.0,
                longitude_rad: 0.0,
                latitude_rad: 0.0,
                speed_m_s: 7658.34,
                flight_path_angle_rad: -0.056 * d,
                heading_rad: 90.0 * d,
            },
            guidance: GuidanceSpec {
                independent: Independent::Energy,
                interpolation: InterpolationKind::Linear,
                period_s: 2.0,
                alpha_rate_rad_s: 5.0 * d,
                sigma_rate_rad_s: 15.0 * d,
                initial: Attitude {
                    alpha_rad: 0.0,
                    sigma_rad: 0.0,
                },
                nodes: vec![
                    [1.0, 0.0, 0.0],
                    [0.8, 0.0, 40.0 * d],
                    [0.4, 0.0, 60.0 * d],
                    [0.0, 0.0, 0.0],
                ],
            },
            termination: Termination {
                altitude_m: Some(25_000.0),
                mach: None,
                normalized_energy: None,
                max_time_s: 5000.0,
            },
            ..Self::default()
        }
    }
}

fn fmt_value(v: &Value) -> String {
    match v {
        Value::String(s) => format!("{s:?}"),
        other => other.to_string(),
    }
}

/// Reads typed fields out of a TOML table, naming file, field and value on errors.
struct Fields<'a> {
    file: &'a str,
}

impl Fields<'_> {
    fn err(&self, field: &str, value: &str, reason: &str) -> CliError {
        CliError::Scenario(format!(
            "{}: field `{field}` = {value}: {reason}",
            self.file
        ))
    }

    fn reject_unknown(&self, t: &Table, prefix: &str, allowed: &[&str]) -> Result<(), CliError> {
        for (k, v) in t {
            if !allowed.contains(&k.as_str()) {
                let field = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                return Err(self.err(
                    &field,
                    &fmt_value(v),
                    &format!("unknown field (expected one of: {})", allowed.join(", ")),
                ));
            }
        }
        Ok(())
    }

    fn table<'t>(&self, t: &'t Table, key: &str) -> Result<Option<&'t Table>, CliError> {
        match t.get(key) {
            None => Ok(None),
            Some(Value::Table(tt)) => Ok(Some(tt)),
            Some(v) => Err(self.err(key, &fmt_value(v), "must be a table ([section])")),
        }
    }

    fn num(&self, t: &Table, prefix: &str, key: &str) -> Result<Option<f64>, CliError> {
        let field = format!("{prefix}.{key}");
        match t.get(key) {
            None => Ok(None),
            Some(Value::Float(f)) if f.is_finite() => Ok(Some(*f)),
            Some(Value::Integer(i)) => Ok(Some(*i as f64)),
            Some(v @ Value::Float(_)) => Err(self.err(&field, &fmt_value(v), "must be finite")),
            Some(v) => Err(self.err(&field, &fmt_value(v), "must be a number")),
        }
    }

    fn string(&self, t: &Table, prefix: &str, key: &str) -> Result<Option<String>, CliError> {
        let field = if prefix.is_empty() {
            key.to_string()
        } else {
            format!("{prefix}.{key}")
        };
        match t.get(key) {
            None => Ok(None),
            Some(Value::String(s)) => Ok(Some(s.clone())),
            Some(v) => Err(self.err(&field, &fmt_value(v), "must be a string")),
        }
    }

    fn boolean(&self, t: &Table, prefix: &str, key: &str) -> Result<Option<bool>, CliError> {
        match t.get(key) {
            None => Ok(None),
            Some(Value::Boolean(b)) => Ok(Some(*b)),
            Some(v) => Err(self.err(
                &format!("{prefix}.{key}"),
                &fmt_value(v),
                "must be true or false",
            )),
        }
    }

    /// A number that must satisfy `ok`.
    fn checked(
        &self,
        t: &Table,
        prefix: &str,
        key: &str,
        ok: impl Fn(f64) -> bool,
        reason: &str,
    ) -> Result<Option<f64>, CliError> {
        let v = self.num(t, prefix, key)?;
        if let Some(x) = v
            && !ok(x)
        {
            return Err(self.err(&format!("{prefix}.{key}"), &x.to_string(), reason));
        }
        Ok(v)
    }
}

/// Parse a scenario from TOML text; `file` names it in error messages. Relative
/// `vehicle_file` paths are resolved against `base_dir`.
///
/// # Errors
/// [`CliError::Scenario`] naming file, field and value.
#[allow(clippy::too_many_lines)]
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
        let p = "environment";
        f.reject_unknown(t, p, &["preset", "atmosphere", "gravity", "rotating"])?;
        if let Some(preset) = f.string(t, p, "preset")? {
            sc.environment = match preset.as_str() {
                "full" => EnvSpec {
                    atmosphere: "us76".into(),
                    gravity: "j2".into(),
                    rotating: true,
                },
                "simplified" => EnvSpec {
                    atmosphere: "exponential".into(),
                    gravity: "central".into(),
                    rotating: false,
                },
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
    }

    let radius = Planet::earth().radius_m;
    if let Some(t) = f.table(&doc, "entry")? {
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
    }

    if let Some(t) = f.table(&doc, "guidance")? {
        let p = "guidance";
        f.reject_unknown(
            t,
            p,
            &[
                "independent",
                "interpolation",
                "tension",
                "period_s",
                "alpha_rate_deg_s",
                "sigma_rate_deg_s",
                "initial_alpha_deg",
                "initial_sigma_deg",
                "nodes",
            ],
        )?;
        let g = &mut sc.guidance;
        if let Some(s) = f.string(t, p, "independent")? {
            g.independent = match s.as_str() {
                "time" => Independent::Time,
                "energy" | "normalized-energy" | "normalized_energy" => Independent::Energy,
                _ => {
                    return Err(f.err(
                        "guidance.independent",
                        &format!("{s:?}"),
                        "must be \"time\" or \"energy\"",
                    ));
                }
            };
        }
        let tension = f.checked(
            t,
            p,
            "tension",
            |v| (0.0..=1.0).contains(&v),
            "must be within [0, 1]",
        )?;
        if let Some(s) = f.string(t, p, "interpolation")? {
            g.interpolation = match s.as_str() {
                "linear" => InterpolationKind::Linear,
                "natural-cubic" | "cubic" => InterpolationKind::NaturalCubic,
                "hermite" => InterpolationKind::Hermite {
                    tension: tension.unwrap_or(0.0),
                },
                _ => {
                    return Err(f.err(
                        "guidance.interpolation",
                        &format!("{s:?}"),
                        "must be \"linear\", \"natural-cubic\" or \"hermite\"",
                    ));
                }
            };
        }
        if let Some(v) = f.checked(
            t,
            p,
            "period_s",
            |v| v > 0.0 && v <= 100.0,
            "must be in (0, 100] s",
        )? {
            g.period_s = v;
        }
        if let Some(v) = f.checked(t, p, "alpha_rate_deg_s", |v| v > 0.0, "must be > 0")? {
            g.alpha_rate_rad_s = v.to_radians();
        }
        if let Some(v) = f.checked(t, p, "sigma_rate_deg_s", |v| v > 0.0, "must be > 0")? {
            g.sigma_rate_rad_s = v.to_radians();
        }
        if let Some(v) = f.checked(
            t,
            p,
            "initial_alpha_deg",
            |v| (0.0..=45.0).contains(&v),
            "must be within [0, 45] deg",
        )? {
            g.initial.alpha_rad = v.to_radians();
        }
        if let Some(v) = f.checked(
            t,
            p,
            "initial_sigma_deg",
            |v| (-90.0..=90.0).contains(&v),
            "must be within [-90, 90] deg",
        )? {
            g.initial.sigma_rad = v.to_radians();
        }
        if let Some(v) = t.get("nodes") {
            g.nodes = parse_nodes(&f, v, g.independent)?;
        } else if g.independent == Independent::Energy {
            return Err(f.err(
                "guidance.nodes",
                "(missing)",
                "energy-indexed guidance needs its own node table",
            ));
        }
    }

    if let Some(t) = f.table(&doc, "termination")? {
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
    }
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
    }
    if let Some(t) = f.table(&doc, "monitors")? {
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
    }
    if let Some(t) = f.table(&doc, "output")? {
        f.reject_unknown(t, "output", &["interval_s"])?;
        if let Some(v) = f.checked(t, "output", "interval_s", |v| v >= 0.0, "must be >= 0")? {
            sc.output_interval_s = v;
        }
    }
    Ok(sc)
}

fn parse_nodes(f: &Fields<'_>, v: &Value, ind: Independent) -> Result<Vec<[f64; 3]>, CliError> {
    let field = "guidance.nodes";
    let Value::Array(rows) = v else {
        return Err(f.err(
            field,
            &fmt_value(v),
            "must be an array of [x, alpha_deg, sigma_deg]",
        ));
    };
    if rows.len() < 2 || rows.len() > 16 {
        return Err(f.err(
            field,
            &format!("({} nodes)", rows.len()),
            "needs 2 to 16 nodes",
        ));
    }
    let mut out: Vec<[f64; 3]> = Vec::with_capacity(rows.len());
    for (i, row) in rows.iter().enumerate() {
        let fi = format!("{field}[{i}]");
        let Value::Array(cols) = row else {
            return Err(f.err(&fi, &fmt_value(row), "must be [x, alpha_deg, sigma_deg]"));
        };
        if cols.len() != 3 {
            return Err(f.err(
                &fi,
                &fmt_value(row),
                "must have exactly 3 numbers [x, alpha_deg, sigma_deg]",
            ));
        }
        let mut n = [0.0; 3];
        for (j, c) in cols.iter().enumerate() {
            n[j] = match c {
                Value::Float(x) if x.is_finite() => *x,
                Value::Integer(x) => *x as f64,
                _ => return Err(f.err(&fi, &fmt_value(row), "entries must be finite numbers")),
            };
        }
        if !(0.0..=45.0).contains(&n[1]) {
            return Err(f.err(
                &fi,
                &fmt_value(row),
                "alpha must be within [0, 45] deg (thesis 4.2.1)",
            ));
        }
        if !(-90.0..=90.0).contains(&n[2]) {
            return Err(f.err(&fi, &fmt_value(row), "sigma must be within [-90, 90] deg"));
        }
        if let Some(prev) = out.last() {
            let ok = match ind {
                Independent::Time => n[0] > prev[0],
                Independent::Energy => n[0] < prev[0],
            };
            if !ok {
                return Err(f.err(
                    &fi,
                    &fmt_value(row),
                    match ind {
                        Independent::Time => "node times must increase strictly",
                        Independent::Energy => {
                            "node energies must decrease strictly (flight order)"
                        }
                    },
                ));
            }
        }
        out.push([n[0], n[1].to_radians(), n[2].to_radians()]);
    }
    Ok(out)
}

/// Rounding to 10 decimals for printing degree values (keeps 40.0 from printing as
/// 39.99999999999999 after a radian round trip).
trait Round10 {
    fn r10(self) -> f64;
}

impl Round10 for f64 {
    fn r10(self) -> f64 {
        (self * 1e10).round() / 1e10
    }
}

/// The scenario as TOML text (parses back to the same scenario, angles to 1e-10 deg).
#[must_use]
pub fn scenario_to_toml(sc: &Scenario) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let r = Planet::earth().radius_m;
    let _ = writeln!(s, "name = {:?}", sc.name);
    match &sc.vehicle {
        VehicleSpec::Name(n) => {
            let _ = writeln!(s, "vehicle = {n:?}");
        }
        VehicleSpec::File(p) => {
            let _ = writeln!(s, "vehicle_file = {:?}", p.display().to_string());
        }
    }
    let e = &sc.environment;
    let _ = writeln!(
        s,
        "\n[environment]\natmosphere = {:?}\ngravity = {:?}\nrotating = {}",
        e.atmosphere, e.gravity, e.rotating
    );
    let en = &sc.entry;
    let _ = writeln!(
        s,
        "\n[entry]\naltitude_km = {:?}\nlongitude_deg = {:?}\nlatitude_deg = {:?}\nspeed_m_s = {:?}\nflight_path_angle_deg = {:?}\nheading_deg = {:?}",
        ((en.radius_m - r) / 1e3).r10(),
        en.longitude_rad.to_degrees().r10(),
        en.latitude_rad.to_degrees().r10(),
        en.speed_m_s,
        en.flight_path_angle_rad.to_degrees().r10(),
        en.heading_rad.to_degrees().r10()
    );
    let g = &sc.guidance;
    let (interp, tension) = match g.interpolation {
        InterpolationKind::Linear => ("linear", None),
        InterpolationKind::NaturalCubic => ("natural-cubic", None),
        InterpolationKind::Hermite { tension } => ("hermite", Some(tension)),
    };
    let _ = writeln!(
        s,
        "\n[guidance]\nindependent = {:?}\ninterpolation = {interp:?}",
        match g.independent {
            Independent::Time => "time",
            Independent::Energy => "energy",
        }
    );
    if let Some(t) = tension {
        let _ = writeln!(s, "tension = {t:?}");
    }
    let _ = writeln!(
        s,
        "period_s = {:?}\nalpha_rate_deg_s = {:?}\nsigma_rate_deg_s = {:?}\ninitial_alpha_deg = {:?}\ninitial_sigma_deg = {:?}\nnodes = [",
        g.period_s,
        g.alpha_rate_rad_s.to_degrees().r10(),
        g.sigma_rate_rad_s.to_degrees().r10(),
        g.initial.alpha_rad.to_degrees().r10(),
        g.initial.sigma_rad.to_degrees().r10()
    );
    for n in &g.nodes {
        let _ = writeln!(
            s,
            "  [{:?}, {:?}, {:?}],",
            n[0],
            n[1].to_degrees().r10(),
            n[2].to_degrees().r10()
        );
    }
    s.push_str("]\n\n[termination]\n");
    let t = &sc.termination;
    if let Some(h) = t.altitude_m {
        let _ = writeln!(s, "altitude_km = {:?}", h / 1e3);
    }
    if let Some(m) = t.mach {
        let _ = writeln!(s, "mach = {m:?}");
    }
    if let Some(e) = t.normalized_energy {
        let _ = writeln!(s, "normalized_energy = {e:?}");
    }
    let _ = writeln!(s, "max_time_s = {:?}", t.max_time_s);
    let tl = &sc.tolerances;
    let _ = writeln!(
        s,
        "\n[integrator]\nrtol = {:?}\nh_init_s = {:?}\nh_min_s = {:?}\nh_max_s = {:?}\nmax_steps = {}\nevent_time_tol_s = {:?}",
        tl.rtol, tl.h_init, tl.h_min, tl.h_max, tl.max_steps, tl.event_time_tol_s
    );
    let _ = writeln!(
        s,
        "\n[monitors]\ninterface_altitude_km = {:?}\ng_rate_window_s = {:?}",
        sc.interface_altitude_m / 1e3,
        sc.g_rate_window_s
    );
    let _ = writeln!(s, "\n[output]\ninterval_s = {:?}", sc.output_interval_s);
    s
}

/// Load the vehicle of a scenario.
///
/// # Errors
/// [`CliError::Vehicle`] naming the file or name.
pub fn load_vehicle(spec: &VehicleSpec) -> Result<Vehicle, CliError> {
    Ok(match spec {
        VehicleSpec::Name(n) => vehicle::by_name(n)?,
        VehicleSpec::File(p) => vehicle::from_toml_file(p)?,
    })
}

impl AttitudeSource for Box<dyn AttitudeSource> {
    fn tick(&mut self, nav: &guidance_core::NavState<f64>) -> Result<(), String> {
        (**self).tick(nav)
    }
    fn attitude_at(&self, time_s: f64) -> Attitude {
        (**self).attitude_at(time_s)
    }
    fn next_tick_s(&self) -> f64 {
        (**self).next_tick_s()
    }
    fn next_kink_s(&self, time_s: f64) -> f64 {
        (**self).next_kink_s(time_s)
    }
}

/// Build the guidance of a scenario: `guidance-core`'s flight [`Guidance`] in `f64`.
///
/// # Errors
/// [`CliError::Scenario`] when the guidance rejects its configuration.
pub fn build_guidance(
    sc: &Scenario,
    planet: &Planet,
    file: &str,
) -> Result<Box<dyn AttitudeSource>, CliError> {
    let g = &sc.guidance;
    let energy = EnergyNormalizer::<f64>::new(
        planet.mu_m3_s2,
        planet.radius_m,
        sc.entry.radius_m,
        sc.entry.speed_m_s,
    )
    .map_err(|e| CliError::Scenario(format!("{file}: entry state: {e}")))?;
    let gerr = |what: &str, e: guidance_core::GuidanceError| {
        CliError::Scenario(format!(
            "{file}: field `guidance.{what}`: rejected by guidance-core: {e}"
        ))
    };
    let nodes: Vec<Node<f64>> = g
        .nodes
        .iter()
        .map(|n| Node {
            x: n[0],
            alpha_rad: n[1],
            sigma_rad: n[2],
        })
        .collect();
    let independent = match g.independent {
        Independent::Time => CoreIndependent::TimeS,
        Independent::Energy => CoreIndependent::NormalizedEnergy,
    };
    let table = NodeTable::new(independent, &nodes, guidance_bounds())
        .map_err(|e| gerr("nodes", e.into()))?;
    let kind = match g.interpolation {
        InterpolationKind::Linear => Interpolation::Linear,
        InterpolationKind::NaturalCubic => Interpolation::NaturalCubic,
        InterpolationKind::Hermite { tension } => Interpolation::CardinalHermite { tension },
    };
    let config = GuidanceConfig {
        period_s: g.period_s,
        rates: RateLimits {
            alpha_rad_s: g.alpha_rate_rad_s,
            sigma_rad_s: g.sigma_rate_rad_s,
        },
    };
    let initial = CoreCommand {
        alpha_rad: g.initial.alpha_rad,
        sigma_rad: g.initial.sigma_rad,
    };
    let guidance = Guidance::new(config, table, kind, energy, initial)
        .map_err(|e| gerr("interpolation", e))?;
    Ok(Box::new(sim::CoreGuidance(guidance)))
}

/// Angle bounds of scenario guidance: alpha 0..45 deg (thesis sec. 4.2.1), sigma -90..90 deg
/// (the thesis' 0..90 deg with banking to either side allowed in 3-D).
#[must_use]
pub fn guidance_bounds() -> AngleBounds<f64> {
    let d = std::f64::consts::PI / 180.0;
    AngleBounds {
        alpha_min_rad: 0.0,
        alpha_max_rad: 45.0 * d,
        sigma_min_rad: -90.0 * d,
        sigma_max_rad: 90.0 * d,
    }
}

/// Result of [`simulate_scenario`].
#[derive(Debug)]
pub struct RunOutput {
    /// The run.
    pub result: sim::SimResult,
    /// The summary written to summary.json.
    pub summary: report::SummaryReport,
    /// Files written.
    pub files: Vec<PathBuf>,
}

/// A flown scenario with the models it used.
pub struct Flight {
    /// The run.
    pub result: sim::SimResult,
    /// The vehicle flown.
    pub vehicle: Vehicle,
    /// The environment flown in.
    pub environment: Environment,
}

impl std::fmt::Debug for Flight {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Flight")
            .field("summary", &self.result.summary)
            .field("vehicle", &self.vehicle.name)
            .finish_non_exhaustive()
    }
}

/// Fly a scenario closed-loop with `guidance-core`'s guidance (no files written).
///
/// # Errors
/// [`CliError`] for vehicle, guidance or simulation failures.
pub fn fly(
    sc: &Scenario,
    file: &str,
    progress: &mut dyn FnMut(f64, f64),
) -> Result<Flight, CliError> {
    let vehicle = load_vehicle(&sc.vehicle)?;
    let environment = sc.environment.build();
    let source = build_guidance(sc, &environment.planet, file)?;
    let mut cfg = SimConfig::new(sc.entry);
    cfg.termination = sc.termination;
    cfg.tolerances = sc.tolerances;
    cfg.output_interval_s = sc.output_interval_s;
    cfg.interface_altitude_m = sc.interface_altitude_m;
    cfg.g_rate_window_s = sc.g_rate_window_s;
    let dynm = Dynamics::from_environment(&environment, &vehicle);
    let (result, _) = sim::simulate(dynm, source, &cfg, progress)?;
    Ok(Flight {
        result,
        vehicle,
        environment,
    })
}

/// Fly a scenario and write its run directory.
///
/// # Errors
/// [`CliError`] for vehicle, guidance, simulation or output failures.
pub fn simulate_scenario(
    sc: &Scenario,
    file: &str,
    out_dir: &Path,
    progress: &mut dyn FnMut(f64, f64),
) -> Result<RunOutput, CliError> {
    let Flight {
        result,
        vehicle: veh,
        environment: env,
    } = fly(sc, file, progress)?;
    let summary = report::summary_report(
        &result,
        &sc.name,
        &veh.name,
        &sc.environment.describe(),
        env.planet.radius_m,
    );
    let files = report::write_run(
        out_dir,
        &result,
        &summary,
        veh.limits.heat_flux_w_m2,
        veh.limits.g_load,
    )?;
    Ok(RunOutput {
        result,
        summary,
        files,
    })
}

/// Run the CLI with `args` (including the program name), writing normal output to `out`.
///
/// # Errors
/// [`CliError`]; `CliError::Usage` also carries `--help`/`--version` output (see
/// [`clap::Error::exit`]).
pub fn run<I, T>(args: I, out: &mut dyn Write) -> Result<(), CliError>
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let cli = Cli::try_parse_from(args)?;
    match cli.command {
        Command::Simulate(a) => {
            let (sc, file) = match &a.scenario {
                Some(p) => {
                    let file = p.display().to_string();
                    let text = std::fs::read_to_string(p)
                        .map_err(|e| CliError::Scenario(format!("{file}: cannot read: {e}")))?;
                    let base = p.parent().unwrap_or(Path::new("."));
                    (parse_scenario(&text, &file, base)?, file)
                }
                None => {
                    let name = a.builtin.as_deref().unwrap_or("horus-2b-reference");
                    let sc = Scenario::builtin(name).ok_or_else(|| {
                        CliError::Scenario(format!(
                            "command line: option `--builtin` = {name:?}: unknown scenario (known: {})",
                            Scenario::BUILTIN.join(", ")
                        ))
                    })?;
                    (sc, format!("(built-in scenario {name})"))
                }
            };
            if a.print_scenario {
                out.write_all(scenario_to_toml(&sc).as_bytes())?;
                return Ok(());
            }
            let dir = a
                .out
                .clone()
                .unwrap_or_else(|| Path::new("runs").join(&sc.name));
            let show = !a.quiet && std::io::stderr().is_terminal();
            let bar = if show {
                indicatif::ProgressBar::new_spinner()
            } else {
                indicatif::ProgressBar::hidden()
            };
            let max_t = sc.termination.max_time_s;
            let mut progress = |t: f64, h: f64| {
                bar.set_message(format!(
                    "t = {t:7.1} s (max {max_t:.0} s), h = {:6.2} km",
                    h / 1e3
                ));
                bar.tick();
            };
            let res = simulate_scenario(&sc, &file, &dir, &mut progress);
            bar.finish_and_clear();
            let run = res?;
            let s = &run.summary;
            writeln!(
                out,
                "{}: {:?} after {:.1} s; range {:.2} deg ({:.0} km); heat load {:.1} MJ/m^2; peak q {:.1} kW/m^2; peak g {:.2}; peak g-dot {:.3} 1/s; skips {}; RHS evaluations {}",
                s.scenario,
                s.termination,
                s.flight_time_s,
                s.range_angle_deg,
                s.range_km,
                s.heat_load_mj_m2,
                s.peak_heat_flux_kw_m2.value,
                s.peak_g_load.value,
                s.peak_g_load_rate_per_s.value,
                s.skips,
                s.rhs_evals
            )?;
            writeln!(out, "wrote {}", dir.display())?;
            Ok(())
        }
        Command::Atmosphere(a) => {
            let model: Box<dyn Atmosphere> = match a.model {
                AtmosphereModel::Us76 => Box::new(Us76::new()),
                AtmosphereModel::Exponential => Box::new(ExponentialAtmosphere::earth()),
            };
            let alts = if a.altitudes_km.is_empty() {
                (0..=12).map(|k| f64::from(k) * 10.0).collect()
            } else {
                a.altitudes_km
            };
            writeln!(
                out,
                "altitude_km,temperature_k,pressure_pa,density_kg_m3,speed_of_sound_m_s"
            )?;
            for h in alts {
                if !h.is_finite() || !(-5.0..=1000.0).contains(&h) {
                    return Err(CliError::Scenario(format!(
                        "command line: argument `ALTITUDE_KM` = {h}: must be within [-5, 1000] km"
                    )));
                }
                let st = model.state(h * 1e3);
                writeln!(
                    out,
                    "{h},{:.4},{:.6e},{:.6e},{:.3}",
                    st.temperature_k, st.pressure_pa, st.density_kg_m3, st.speed_of_sound_m_s
                )?;
            }
            Ok(())
        }
        Command::Compare(a) => {
            crate::compare::run_cli(&a, out)?;
            Ok(())
        }
        Command::Vehicles => {
            writeln!(
                out,
                "name,mass_kg,reference_area_m2,nose_radius_m,max_heat_flux_kw_m2,max_g_load,max_g_load_rate_per_s"
            )?;
            for n in vehicle::list() {
                let v = vehicle::by_name(n)?;
                writeln!(
                    out,
                    "{},{},{},{},{},{},{}",
                    v.name,
                    v.mass_kg,
                    v.reference_area_m2,
                    v.nose_radius_m,
                    v.limits.heat_flux_w_m2 / 1e3,
                    v.limits.g_load,
                    v.limits.g_load_rate_per_s
                )?;
            }
            Ok(())
        }
    }
}
