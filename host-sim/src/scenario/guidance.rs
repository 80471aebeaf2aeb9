//! The guidance of a scenario: `guidance-core`'s flight [`Guidance`] in `f64`, as the closed
//! loop's attitude source.

use guidance_core::energy::EnergyNormalizer;
use guidance_core::guidance::{Guidance, GuidanceConfig, HostGuidance, RateLimits};
use guidance_core::interp::Interpolation;
use guidance_core::nodes::{AngleBounds, HostNodeTable, Node};

use super::{InterpolationKind, Scenario, ScenarioError};
use crate::env::Planet;

/// Build the guidance of a scenario: `guidance-core`'s flight [`Guidance`] in `f64`.
///
/// # Errors
/// [`ScenarioError::Guidance`] or [`ScenarioError::Entry`] when the core rejects the
/// configuration (`file` names the scenario).
pub fn build_guidance(
    sc: &Scenario,
    planet: &Planet,
    file: &str,
) -> Result<HostGuidance<f64>, ScenarioError> {
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
    let gerr =
        |field: &'static str, source: guidance_core::GuidanceError| ScenarioError::Guidance {
            file: file.to_string(),
            field,
            source,
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
    let table =
        HostNodeTable::new(g.independent, &nodes, g.bounds).map_err(|e| gerr("nodes", e.into()))?;
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
    Guidance::new(config, table, kind, energy, g.initial).map_err(|e| gerr("interpolation", e))
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
