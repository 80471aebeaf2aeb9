//! Built-in scenarios: the HORUS-2B reference mission (the default, with its onboard stack),
//! its stored profile alone, and the SRM glide (with its stack).

use guidance_core::guidance::Command;
use guidance_core::interp::Interpolation;
use guidance_core::missions::{Mission, horus2b_reference};
use guidance_core::nodes::Independent;

use guidance_core::stack::Layers;

use super::guidance_layers::{CampaignGuidance, CampaignPredictor};
use super::{
    EnvSpec, GuidanceLayers, GuidanceSpec, InterpolationKind, Scenario, ScenarioError, VehicleSpec,
    guidance_bounds,
};
use super::{TargetSpec, TerminalInterface};
use crate::dynamics::SphericalState;
use crate::env::{Planet, Preset};
use crate::sim::{SimConfig, Termination};

/// The guidance of a core mission as a scenario's guidance settings (same values, SI).
fn guidance_of(m: &Mission<f64>) -> GuidanceSpec {
    GuidanceSpec {
        independent: m.table.independent(),
        interpolation: match m.interpolation {
            Interpolation::Linear => InterpolationKind::Linear,
            Interpolation::NaturalCubic => InterpolationKind::NaturalCubic,
            Interpolation::CardinalHermite { tension } => InterpolationKind::Hermite { tension },
        },
        period_s: m.config.period_s,
        alpha_rate_rad_s: m.config.rates.alpha_rad_s,
        sigma_rate_rad_s: m.config.rates.sigma_rad_s,
        initial: m.initial,
        nodes: m
            .table
            .nodes()
            .iter()
            .map(|n| [n.x, n.alpha_rad, n.sigma_rad])
            .collect(),
        bounds: m.table.bounds(),
    }
}

impl Default for Scenario {
    /// The HORUS-2B reference mission (thesis sec. 2.2 and 7.4): its guidance and entry
    /// interface from `guidance_core::missions::horus2b_reference` (time nodes of eq. 2.3,
    /// linear interpolation, thesis bounds, period and rates; entry state of table 2.1), full
    /// environment, terminated at 25 km altitude.
    fn default() -> Self {
        let planet = Planet::earth();
        // f64 represents every value of the mission: this cannot fail (tested).
        #[allow(clippy::expect_used)]
        let mission = horus2b_reference::<f64>().expect("HORUS-2B reference mission in f64");
        let e = mission.entry;
        let entry = SphericalState {
            radius_m: planet.radius_m + e.altitude_m,
            longitude_rad: e.longitude_rad,
            latitude_rad: e.latitude_rad,
            speed_m_s: e.speed_m_s,
            flight_path_angle_rad: e.flight_path_angle_rad,
            heading_rad: e.heading_rad,
        };
        // Integrator, output and monitor settings: the simulator's defaults.
        let sim = SimConfig::new(entry);
        Self {
            name: mission.name.into(),
            vehicle: VehicleSpec::Name("horus-2b".into()),
            environment: EnvSpec::preset(Preset::Full),
            entry,
            guidance: guidance_of(&mission),
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
            layers: Some(horus_stack()),
        }
    }
}

/// The HORUS-2B reference mission's onboard stack: every layer, with the settings of the
/// documented accuracy (CHANGELOG.md, issue 12; chosen on tuning seeds 1 and 2): the
/// numerical predictor with the stored angle-of-attack profile's lift from E-hat 0.96 (after
/// the entry pull-out), flying the stored profile's bank shape (docs/reference/guidance-stack.md,
/// "Bank shape"), its whole-flight limit check off (scale 100), the numerical predictions
/// ending at the terminal interface's energy, largest vertical fraction 0.9 (a bank of at
/// least 25.8 deg for turning authority); the barrier law (0.2 rad/s, damping 1) at the vehicle's limits, flown by the
/// predictions too; the terminal crossrange law inside 250 km (tolerance 2 km), no reversal
/// in the last 10 km.
#[must_use]
pub fn horus_stack() -> GuidanceLayers {
    GuidanceLayers {
        settings: CampaignGuidance {
            predictor: CampaignPredictor::Numerical,
            predictor_lift_profile: true,
            bank_shape: true,
            replan_start_normalized_energy: Some(0.96),
            replan_limit_scale: [100.0, 100.0],
            path_bound_limit_scale: Some([1.0, 1.0]),
            path_bound_barrier: Some([0.2, 1.0]),
            path_bound_predicted: true,
            terminal_lateral_km: Some(250.0),
            terminal_tolerance_km: 2.0,
            freeze_km: 10.0,
            max_vertical_fraction: 0.9,
            ..CampaignGuidance::default()
        },
        layers: Layers::ALL,
        target: TargetSpec::Nominal,
        interface: None,
    }
}

/// The SRM glide's onboard stack: the re-planner (hybrid predictor), bank reversals and the
/// onboard estimator with the default settings, no path-limit bound; the terminal interface
/// at 2.5 km/s (the start of the terminal area: the documented accuracy's interface).
#[must_use]
pub fn srm_stack() -> GuidanceLayers {
    GuidanceLayers {
        settings: CampaignGuidance::default(),
        layers: Layers {
            barrier: false,
            ..Layers::ALL
        },
        target: TargetSpec::Nominal,
        interface: Some(TerminalInterface::Speed { speed_m_s: 2500.0 }),
    }
}

impl Scenario {
    /// Built-in scenarios by name: `horus-2b-reference` (the default: the reference mission
    /// with its full onboard stack, [`horus_stack`]), `horus-2b-stored` (the same mission's
    /// stored profile alone) and `srm-glide`.
    #[must_use]
    pub fn builtin(name: &str) -> Option<Self> {
        match name {
            "horus-2b-reference" => Some(Self::default()),
            "horus-2b-stored" => Some(Self::horus_2b_stored()),
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
    pub const BUILTIN: [&'static str; 3] = ["horus-2b-reference", "horus-2b-stored", "srm-glide"];

    /// The HORUS-2B reference mission's stored profile alone (no layer beyond it).
    #[must_use]
    pub fn horus_2b_stored() -> Self {
        Self {
            name: "horus-2b-stored".into(),
            layers: None,
            ..Self::default()
        }
    }

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
                bounds: guidance_bounds(),
            },
            termination: Termination {
                altitude_m: Some(25_000.0),
                mach: None,
                normalized_energy: None,
                max_time_s: 5000.0,
            },
            layers: Some(srm_stack()),
            ..Self::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The built-in reference scenario is the core's mission, thesis bounds included; the
    /// SRM glide and scenario files keep the host's two-sided bank bounds.
    #[test]
    fn default_scenario_is_the_core_mission() {
        let m = horus2b_reference::<f64>().unwrap();
        let sc = Scenario::default();
        assert_eq!(sc.name, m.name);
        assert_eq!(sc.guidance, guidance_of(&m));
        assert_eq!(sc.guidance.bounds, m.table.bounds());
        assert_eq!(sc.guidance.bounds.sigma_min_rad, 0.0);
        assert_eq!(sc.guidance.nodes.len(), 7);
        assert_eq!(
            sc.guidance.nodes[2],
            [290.0, 40f64.to_radians(), 79.6f64.to_radians()]
        );
        assert_eq!(sc.entry.speed_m_s, 7435.5);
        assert_eq!(sc.entry.radius_m, Planet::earth().radius_m + 122_000.0);
        assert_eq!(Scenario::srm_glide().guidance.bounds, guidance_bounds());
        let printed = super::super::scenario_to_toml(&sc);
        let parsed = super::super::parse_scenario(&printed, "p.toml", std::path::Path::new("."));
        assert_eq!(parsed.unwrap().guidance.bounds, guidance_bounds());
    }
}
