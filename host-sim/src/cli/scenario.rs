//! The resolved scenario (SI units, radians) that the TOML scenario file describes: vehicle,
//! environment, entry state, guidance, termination, integrator, monitors and output.

use std::path::PathBuf;

use guidance_core::nodes::AngleBounds;

use crate::dynamics::{Attitude, SphericalState};
use crate::env::{
    Atmosphere, CentralGravity, Environment, ExponentialAtmosphere, Gravity, J2Gravity, Planet,
    Us76,
};
use crate::integrate::Tolerances;
use crate::sim::{SimConfig, Termination};

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
    /// Angle bounds the nodes and commands are held to \[rad\]: the mission's for a built-in
    /// scenario, [`super::guidance_bounds`] for a scenario file.
    pub bounds: AngleBounds<f64>,
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
    /// Preset `"full"`: US76 atmosphere, J2 gravity, rotating Earth.
    #[must_use]
    pub fn full() -> Self {
        Self {
            atmosphere: "us76".into(),
            gravity: "j2".into(),
            rotating: true,
        }
    }

    /// Preset `"simplified"`: exponential atmosphere, central gravity, non-rotating Earth.
    #[must_use]
    pub fn simplified() -> Self {
        Self {
            atmosphere: "exponential".into(),
            gravity: "central".into(),
            rotating: false,
        }
    }

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

    pub(super) fn describe(&self) -> String {
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

/// A guidance node from file units `[x, alpha_deg, sigma_deg]` to `[x, alpha_rad, sigma_rad]`.
pub(super) fn node_to_rad(n: &[f64; 3]) -> [f64; 3] {
    [n[0], n[1].to_radians(), n[2].to_radians()]
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

impl Scenario {
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
