//! The guidance of a scenario: `guidance-core`'s flight [`Guidance`] in `f64`, or with a
//! `[replanning]` section its [`ReplanningGuidance`], as the closed loop's attitude source.

use guidance_core::energy::EnergyNormalizer;
use guidance_core::guidance::{Guidance, GuidanceConfig, HostGuidance, RateLimits};
use guidance_core::interp::Interpolation;
use guidance_core::nodes::{AngleBounds, HostNodeTable, Node};

use guidance_core::replan::{
    HostReplanningGuidance, ReplanConfig, ReplanLimits, ReplanningConfig, ReplanningGuidance,
};
use guidance_core::stack::{HostStackConfig, ProfileLayer, ReplanLayer, StackConfig};
use guidance_core::vinh::PredictorConfig;

use super::{InterpolationKind, Scenario, ScenarioError};
use crate::env::{Environment, ExponentialAtmosphere, Planet};
use crate::replan_loop::predictor_model;
use crate::vehicle::Vehicle;

/// Build the guidance of a scenario: `guidance-core`'s flight [`Guidance`] in `f64` (the
/// stored profile; [`build_replanning_guidance`] adds the scenario's re-planning).
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

/// The re-planning settings of a scenario (`None` without a `[replanning]` section): the
/// section's values, the vehicle's limits where the section sets none, and the predictor model
/// from `vehicle` (its polar at the section's Mach number), `env`'s planet and an exponential
/// fit of `env`'s atmosphere between [`PREDICTOR_FIT_ALTITUDES_M`].
///
/// # Errors
/// [`ScenarioError::Predictor`] if the predictor model cannot be built (no polar, or an
/// atmosphere that does not fit).
pub fn build_replanning(
    sc: &Scenario,
    env: &Environment,
    vehicle: &Vehicle,
    file: &str,
) -> Result<Option<ReplanningConfig<f64>>, ScenarioError> {
    let Some(r) = &sc.replanning else {
        return Ok(None);
    };
    let perr = |source| ScenarioError::Predictor {
        file: file.to_string(),
        source,
    };
    let (h1, h2) = PREDICTOR_FIT_ALTITUDES_M;
    let fit = ExponentialAtmosphere::fitted_to(env.atmosphere.as_ref(), h1, h2)
        .map_err(|e| perr(e.into()))?;
    let model = predictor_model(vehicle, &fit, &env.planet, r.polar_mach).map_err(perr)?;
    Ok(Some(ReplanningConfig {
        every_n_ticks: r.every_n_ticks,
        target: r.target,
        limits: ReplanLimits {
            heat_flux_w_m2: r
                .heat_flux_limit_w_m2
                .unwrap_or(vehicle.limits.heat_flux_w_m2),
            g_load: r.g_load_limit.unwrap_or(vehicle.limits.g_load),
        },
        solver: ReplanConfig {
            lambda: r.lambda,
            min_vertical_fraction: r.min_vertical_fraction,
            max_vertical_fraction: r.max_vertical_fraction,
            tolerance_m: r.tolerance_m,
            max_iterations: r.max_iterations,
            predictor: PredictorConfig {
                final_speed_m_s: r.final_speed_m_s,
                max_skips: r.max_skips,
            },
            mode: r.mode,
        },
        model,
        apply_out_of_reach: r.apply_out_of_reach,
        steps_per_tick: r.steps_per_tick,
    }))
}

/// The scenario's guidance with its re-planning: `guidance-core`'s [`ReplanningGuidance`] in
/// `f64` on the scenario's table (`None` without a `[replanning]` section).
///
/// # Errors
/// As [`build_guidance`] and [`build_replanning`]; [`ScenarioError::Replanning`] if the core
/// rejects the re-planning settings.
pub fn build_replanning_guidance(
    sc: &Scenario,
    env: &Environment,
    vehicle: &Vehicle,
    file: &str,
) -> Result<Option<HostReplanningGuidance<f64>>, ScenarioError> {
    let Some(config) = build_replanning(sc, env, vehicle, file)? else {
        return Ok(None);
    };
    let p = parts(sc, &env.planet, file)?;
    ReplanningGuidance::new(
        p.config,
        p.table,
        p.kind,
        p.energy,
        sc.guidance.initial,
        config,
    )
    .map(Some)
    .map_err(|source| ScenarioError::Replanning {
        file: file.to_string(),
        source,
    })
}

/// The onboard stack of a scenario (`guidance_core::stack::StackConfig`, the one description
/// every flight of the scenario flies): its stored profile and, with a `[replanning]` section,
/// the re-planner ([`build_replanning`]) aimed at the section's target.
///
/// # Errors
/// As [`build_guidance`] and [`build_replanning`].
pub fn build_stack(
    sc: &Scenario,
    env: &Environment,
    vehicle: &Vehicle,
    file: &str,
) -> Result<HostStackConfig<f64>, ScenarioError> {
    let p = parts(sc, &env.planet, file)?;
    let replan = build_replanning(sc, env, vehicle, file)?;
    Ok(StackConfig {
        profile: ProfileLayer {
            guidance: p.config,
            table: p.table,
            interpolation: p.kind,
            energy: p.energy,
            initial: sc.guidance.initial,
        },
        target: replan.map(|r| r.target),
        replan: replan.map(|r| ReplanLayer {
            every_n_ticks: r.every_n_ticks,
            limits: r.limits,
            solver: r.solver,
            model: r.model,
            apply_out_of_reach: r.apply_out_of_reach,
            steps_per_tick: r.steps_per_tick,
            lift_schedule: None,
            start_normalized_energy: None,
            numerical_rotation: false,
            final_energy_j_kg: None,
        }),
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
