//! The `[replanning]` section: onboard re-planning of the bank-angle magnitude
//! (`guidance_core::replan::ReplanningGuidance`) on the scenario's energy-indexed table.
//! Degrees, km and kW/m^2 in the file; SI and radians in [`ReplanningSpec`].

use guidance_core::nodes::Independent;
use guidance_core::replan::{
    DEFAULT_EVERY_N_TICKS, DEFAULT_LAMBDA, DEFAULT_MAX_VERTICAL_FRACTION, MAX_EVERY_N_TICKS,
    MAX_ITERATIONS, PredictorMode, RangeTarget, TargetPoint,
};
use guidance_core::vinh::predict::MAX_SKIPS;

use super::file::{Num, PredictorFile, ReplanningFile};
use super::resolve::Fields;
use super::{ReplanningSpec, Scenario, ScenarioError};
use crate::num_fmt::compact;

/// Defaults of the optional keys (those of the dispersion campaigns' re-planner).
const DEFAULT_MIN_VERTICAL_FRACTION: f64 = 0.05;
const DEFAULT_TOLERANCE_M: f64 = 1000.0;
const DEFAULT_MAX_ITERATIONS: u8 = 20;
const DEFAULT_MAX_SKIPS: u8 = 4;
const DEFAULT_POLAR_MACH: f64 = 20.0;

/// An integer field in `[0, max]`.
fn int(
    f: &Fields<'_>,
    field: &str,
    v: Option<Num>,
    min: u32,
    max: u32,
) -> Result<Option<u32>, ScenarioError> {
    let reason = format!("must be an integer in [{min}, {max}]");
    Ok(f.checked(
        field,
        v,
        |x| x.fract() == 0.0 && x >= f64::from(min) && x <= f64::from(max),
        &reason,
    )?
    .map(|x| {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let n = x as u32;
        n
    }))
}

/// Resolve `[replanning]` into `sc.replanning` (after `[guidance]` and `[environment]`).
pub(super) fn replanning(
    f: &Fields<'_>,
    t: ReplanningFile,
    sc: &mut Scenario,
) -> Result<(), ScenarioError> {
    if sc.guidance.independent != Independent::NormalizedEnergy {
        return Err(f.err(
            "guidance.independent",
            "\"time\"",
            "re-planning ([replanning]) needs an energy-indexed table: independent = \"energy\"",
        ));
    }
    let small = |field: &str, v, min, max: u8| -> Result<Option<u8>, ScenarioError> {
        Ok(int(f, field, v, min, u32::from(max))?.and_then(|n| u8::try_from(n).ok()))
    };
    let every = int(
        f,
        "replanning.every_n_ticks",
        t.every_n_ticks,
        1,
        u32::from(MAX_EVERY_N_TICKS),
    )?
    .and_then(|n| u16::try_from(n).ok())
    .unwrap_or(DEFAULT_EVERY_N_TICKS);
    let steps = small("replanning.steps_per_tick", t.steps_per_tick, 0, u8::MAX)?.unwrap_or(0);
    let deg = |field, v| {
        f.checked(
            field,
            v,
            |x: f64| (-360.0..=360.0).contains(&x),
            "must be in [-360, 360] deg",
        )
    };
    let lat = deg("replanning.target_latitude_deg", t.target_latitude_deg)?;
    let lon = deg("replanning.target_longitude_deg", t.target_longitude_deg)?;
    let range = f.checked(
        "replanning.range_km",
        t.range_km,
        |x| x > 0.0 && x <= 1e5,
        "must be in (0, 1e5] km",
    )?;
    let target = match (lat, lon, range) {
        (Some(la), Some(lo), None) if la.abs() <= 90.0 => RangeTarget::Point(TargetPoint {
            latitude_rad: la.to_radians(),
            longitude_rad: lo.to_radians(),
        }),
        (Some(la), Some(_), None) => {
            return Err(f.err(
                "replanning.target_latitude_deg",
                &compact(la),
                "must be in [-90, 90] deg",
            ));
        }
        (None, None, Some(r)) => RangeTarget::FlownRangeAngle {
            total_rad: r * 1e3 / sc.environment.planet.radius_m,
        },
        _ => {
            return Err(f.err(
                "replanning.range_km",
                &range.map_or_else(|| "(missing)".into(), compact),
                "give either range_km or both target_latitude_deg and target_longitude_deg",
            ));
        }
    };
    let final_speed_m_s = f
        .checked(
            "replanning.final_speed_m_s",
            t.final_speed_m_s,
            |x| x > 0.0 && x < sc.entry.speed_m_s,
            "must be in (0, entry speed) m/s",
        )?
        .ok_or_else(|| {
            f.err(
                "replanning.final_speed_m_s",
                "(missing)",
                "the predictor's final speed is required",
            )
        })?;
    let positive = |field, v| f.checked(field, v, |x: f64| x > 0.0, "must be > 0");
    let heat = positive("replanning.heat_flux_limit_kw_m2", t.heat_flux_limit_kw_m2)?;
    let g_load_limit = positive("replanning.g_load_limit", t.g_load_limit)?;
    let lambda = f
        .checked(
            "replanning.lambda",
            t.lambda,
            |x| (0.0..=10.0).contains(&x),
            "must be in [0, 10]",
        )?
        .unwrap_or(DEFAULT_LAMBDA);
    let fraction =
        |field, v| f.checked(field, v, |x: f64| x > 0.0 && x <= 1.0, "must be in (0, 1]");
    let fmin = fraction("replanning.min_vertical_fraction", t.min_vertical_fraction)?
        .unwrap_or(DEFAULT_MIN_VERTICAL_FRACTION);
    let fmax = fraction("replanning.max_vertical_fraction", t.max_vertical_fraction)?
        .unwrap_or(DEFAULT_MAX_VERTICAL_FRACTION);
    if fmin > fmax {
        return Err(f.err(
            "replanning.min_vertical_fraction",
            &compact(fmin),
            "must not exceed max_vertical_fraction",
        ));
    }
    let tolerance_m =
        positive("replanning.tolerance_m", t.tolerance_m)?.unwrap_or(DEFAULT_TOLERANCE_M);
    let max_iterations = small(
        "replanning.max_iterations",
        t.max_iterations,
        1,
        MAX_ITERATIONS,
    )?
    .unwrap_or(DEFAULT_MAX_ITERATIONS);
    let max_skips =
        small("replanning.max_skips", t.max_skips, 0, MAX_SKIPS)?.unwrap_or(DEFAULT_MAX_SKIPS);
    let polar_mach = f
        .checked(
            "replanning.polar_mach",
            t.polar_mach,
            |x| x > 0.0 && x <= 100.0,
            "must be in (0, 100]",
        )?
        .unwrap_or(DEFAULT_POLAR_MACH);
    sc.replanning = Some(ReplanningSpec {
        every_n_ticks: every,
        steps_per_tick: steps,
        target,
        final_speed_m_s,
        heat_flux_limit_w_m2: heat.map(|q| q * 1e3),
        g_load_limit,
        lambda,
        min_vertical_fraction: fmin,
        max_vertical_fraction: fmax,
        tolerance_m,
        max_iterations,
        max_skips,
        mode: match t.predictor.unwrap_or(PredictorFile::Hybrid) {
            PredictorFile::Chain => PredictorMode::Chain,
            PredictorFile::Glide => PredictorMode::Glide,
            PredictorFile::Auto => PredictorMode::Auto,
            PredictorFile::AutoSink => PredictorMode::AutoSink,
            PredictorFile::Numerical => PredictorMode::Numerical,
            PredictorFile::Hybrid => PredictorMode::Hybrid,
            PredictorFile::HybridSink => PredictorMode::HybridSink,
        },
        apply_out_of_reach: t.apply_out_of_reach.unwrap_or(true),
        polar_mach,
    });
    Ok(())
}
