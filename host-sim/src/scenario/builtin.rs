//! Built-in scenarios: the HORUS-2B reference mission (the default) and the SRM glide.

use guidance_core::guidance::Command;
use guidance_core::nodes::Independent;

use super::{
    EnvSpec, GuidanceSpec, InterpolationKind, Scenario, ScenarioError, VehicleSpec, node_to_rad,
};
use crate::dynamics::SphericalState;
use crate::env::{Planet, Preset};
use crate::sim::{SimConfig, Termination};

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
        let entry = SphericalState {
            radius_m: planet.radius_m + 122_000.0,
            longitude_rad: (-106.7f64).to_radians(),
            latitude_rad: (-22.3f64).to_radians(),
            speed_m_s: 7435.5,
            flight_path_angle_rad: (-1.43f64).to_radians(),
            heading_rad: 70.75f64.to_radians(),
        };
        // Integrator, output and monitor settings: the simulator's defaults.
        let sim = SimConfig::new(entry);
        Self {
            name: "horus-2b-reference".into(),
            vehicle: VehicleSpec::Name("horus-2b".into()),
            environment: EnvSpec::preset(Preset::Full),
            entry,
            guidance: GuidanceSpec {
                independent: Independent::TimeS,
                interpolation: InterpolationKind::Linear,
                period_s: 2.0,
                alpha_rate_rad_s: 5f64.to_radians(),
                sigma_rate_rad_s: 15f64.to_radians(),
                initial: Command {
                    alpha_rad: 40f64.to_radians(),
                    sigma_rad: 0.0,
                },
                nodes: HORUS_REFERENCE_NODES.iter().map(node_to_rad).collect(),
            },
            termination: Termination {
                altitude_m: Some(25_000.0),
                mach: None,
                normalized_energy: None,
                max_time_s: 2500.0,
            },
            tolerances: sim.tolerances,
            output_interval_s: sim.output_interval_s,
            interface_altitude_m: sim.interface_altitude_m,
            g_rate_window_s: sim.g_rate_window_s,
            nose_radius_m: None,
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

    /// A built-in scenario by name, or an error listing the known names.
    ///
    /// # Errors
    /// [`ScenarioError::UnknownBuiltin`].
    pub fn try_builtin(name: &str) -> Result<Self, ScenarioError> {
        Self::builtin(name).ok_or_else(|| ScenarioError::UnknownBuiltin {
            name: name.to_string(),
            known: Self::BUILTIN.join(", "),
        })
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
            environment: EnvSpec::preset(Preset::Simplified),
            entry: SphericalState {
                radius_m: planet.radius_m + 100_000.0,
                longitude_rad: 0.0,
                latitude_rad: 0.0,
                speed_m_s: 7658.34,
                flight_path_angle_rad: -0.056 * d,
                heading_rad: 90.0 * d,
            },
            guidance: GuidanceSpec {
                independent: Independent::NormalizedEnergy,
                interpolation: InterpolationKind::Linear,
                period_s: 2.0,
                alpha_rate_rad_s: 5.0 * d,
                sigma_rate_rad_s: 15.0 * d,
                initial: Command {
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
