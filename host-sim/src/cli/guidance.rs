//! The guidance of a scenario: `guidance-core`'s flight [`Guidance`] in `f64`, as the closed
//! loop's attitude source.

use guidance_core::energy::EnergyNormalizer;
use guidance_core::guidance::{Command as CoreCommand, Guidance, GuidanceConfig, RateLimits};
use guidance_core::interp::Interpolation;
use guidance_core::nodes::{AngleBounds, Independent as CoreIndependent, Node, NodeTable};

use super::{CliError, Independent, InterpolationKind, Scenario};
use crate::dynamics::Attitude;
use crate::env::Planet;
use crate::sim::{self, AttitudeSource};

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
    let table =
        NodeTable::new(independent, &nodes, g.bounds).map_err(|e| gerr("nodes", e.into()))?;
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

/// Angle bounds of scenario-file guidance: alpha 0..45 deg (thesis sec. 4.2.1), sigma
/// -90..90 deg (the thesis' 0..90 deg with banking to either side allowed in 3-D). The
/// built-in HORUS-2B mission keeps the thesis bounds of `guidance_core::missions`.
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
