//! The guidance of a scenario's stored profile: `guidance-core`'s flight [`Guidance`] in `f64`
//! and the profile-only stack ([`build_stack`]); the layers beyond it are built by the
//! campaign set-up (`crate::campaign::CampaignSetup::new`).

use guidance_core::energy::EnergyNormalizer;
use guidance_core::guidance::{Guidance, GuidanceConfig, HostGuidance, RateLimits};
use guidance_core::interp::Interpolation;
use guidance_core::nodes::{AngleBounds, HostNodeTable, Node};
use guidance_core::stack::{HostStackConfig, ProfileLayer, StackConfig};

use super::{InterpolationKind, Scenario, ScenarioError};
use crate::env::Planet;

/// Build the guidance of a scenario: `guidance-core`'s flight [`Guidance`] in `f64` (the
/// stored profile).
///
/// # Errors
/// [`ScenarioError::Guidance`] or [`ScenarioError::Entry`] when the core rejects the
/// configuration (`file` names the scenario).
pub fn build_guidance(
    sc: &Scenario,
    planet: &Planet,
    file: &str,
) -> Result<HostGuidance<f64>, ScenarioError> {
    let p = parts(sc, planet, file)?;
    Guidance::new(p.config, p.table, p.kind, p.energy, sc.guidance.initial).map_err(|source| {
        ScenarioError::Guidance {
            file: file.to_string(),
            field: "interpolation",
            source,
        }
    })
}

/// The pieces of a scenario's guidance, checked by the core.
struct Parts {
    config: GuidanceConfig<f64>,
    table: HostNodeTable<f64>,
    kind: Interpolation<f64>,
    energy: EnergyNormalizer<f64>,
}

fn parts(sc: &Scenario, planet: &Planet, file: &str) -> Result<Parts, ScenarioError> {
    let g = &sc.guidance;
    let energy = EnergyNormalizer::<f64>::new(
        planet.mu_m3_s2,
        planet.radius_m,
        sc.entry.radius_m,
        sc.entry.speed_m_s,
    )
    .map_err(|source| ScenarioError::Entry {
        file: file.to_string(),
        source,
    })?;
    let nodes: Vec<Node<f64>> = g
        .nodes
        .iter()
        .map(|n| Node {
            x: n[0],
            alpha_rad: n[1],
            sigma_rad: n[2],
        })
        .collect();
    let table = HostNodeTable::new(g.independent, &nodes, g.bounds).map_err(|e| {
        ScenarioError::Guidance {
            file: file.to_string(),
            field: "nodes",
            source: e.into(),
        }
    })?;
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
    Ok(Parts {
        config,
        table,
        kind,
        energy,
    })
}

/// Lower and upper altitude of the exponential fit of the environment's atmosphere that the
/// re-planner's predictor uses \[m\] (as the dispersion campaigns).
pub const PREDICTOR_FIT_ALTITUDES_M: (f64, f64) = (50e3, 100e3);

/// The onboard stack of a scenario's stored profile alone (`guidance_core::stack::StackConfig`
/// with no layer beyond the profile): what a scenario without `[guidance.*]` layers flies, in
/// SIL ([`super::fly`]) and in PIL (its set-up image, `crate::pil::fly_scenario_pil`). A
/// scenario with layers flies the campaign set-up's stack (`CampaignSetup::stack_of`).
///
/// # Errors
/// As [`build_guidance`].
pub fn build_stack(
    sc: &Scenario,
    planet: &Planet,
    file: &str,
) -> Result<HostStackConfig<f64>, ScenarioError> {
    let p = parts(sc, planet, file)?;
    Ok(StackConfig {
        profile: ProfileLayer {
            guidance: p.config,
            table: p.table,
            interpolation: p.kind,
            energy: p.energy,
            initial: sc.guidance.initial,
        },
        target: None,
        replan: None,
        lateral: None,
        estimator: None,
        barrier: None,
    })
}

/// Angle bounds of scenario guidance: alpha 0..45 deg (thesis sec. 4.2.1), sigma -180..180 deg
/// (banking to either side, lift down included: |sigma| > 90 deg points the lift's vertical
/// component down, as an Apollo-style capsule flies). Files give banks in (-180, 180] deg; the
/// bound -180 deg is reached only by reversing a 180 deg bank (the same attitude). A bank
/// change is a rate-limited ramp in sigma, not wrapped through 180 deg: a reversal of a
/// lift-down bank rolls through lift up (0 deg).
#[must_use]
pub fn guidance_bounds() -> AngleBounds<f64> {
    let d = std::f64::consts::PI / 180.0;
    AngleBounds {
        alpha_min_rad: 0.0,
        alpha_max_rad: 45.0 * d,
        sigma_min_rad: -180.0 * d,
        sigma_max_rad: 180.0 * d,
    }
}
