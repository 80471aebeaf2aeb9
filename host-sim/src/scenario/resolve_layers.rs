//! The scenario's onboard layers beyond the stored profile: the `[guidance.lateral]`,
//! `[guidance.replanning]`, `[guidance.estimator]` and `[guidance.barrier]` sections. A
//! section present switches its layer on (an empty one with the defaults); absent, the layer
//! is off. Each key is a field of [`CampaignGuidance`] under its scenario name
//! ([`LAYER_KEYS`]), checked by [`CampaignGuidance::validate`] (errors name
//! `guidance.<section>.<key>`, the value and the range).

use guidance_core::stack::Layers;
use serde::Deserialize;

use super::fields::Fields;
use super::file::Num;
use super::guidance_layers::{CampaignGuidance, CampaignPredictor};
use super::{GuidanceLayers, ScenarioError, TargetSpec, TerminalInterface};
use crate::campaign::CampaignError;

/// `[guidance.lateral]`: bank reversals on a heading-error corridor, the terminal law.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LateralFile {
    corridor_width_entry_deg: Option<Num>,
    corridor_width_final_deg: Option<Num>,
    corridor_low_speed_fraction: Option<Num>,
    hysteresis_deg: Option<Num>,
    max_reversals: Option<Num>,
    freeze_km: Option<Num>,
    terminal_start_km: Option<Num>,
    terminal_tolerance_km: Option<Num>,
    terminal_reversal_lead_s: Option<Num>,
}

/// `[guidance.replanning]`: the predictor-corrector on the bank magnitude.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReplanFile {
    every_n_ticks: Option<Num>,
    solver_steps_per_tick: Option<Num>,
    tolerance_km: Option<Num>,
    min_vertical_fraction: Option<Num>,
    max_vertical_fraction: Option<Num>,
    glide_sink: Option<bool>,
    predictor: Option<CampaignPredictor>,
    /// Removed (refused with the key that replaces it): the predictor ends at the terminal
    /// interface's energy.
    final_speed_offset_m_s: Option<Num>,
    lift_parameter: Option<Num>,
    lift_profile: Option<bool>,
    lift_profile_mach: Option<bool>,
    start_normalized_energy: Option<Num>,
    limit_scale: Option<[Num; 2]>,
    numerical_rotation: Option<bool>,
    bank_shape: Option<bool>,
}

/// `[guidance.estimator]`: onboard estimation of the L/D and drag scales.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EstimatorFile {
    lift_to_drag_gain: Option<Num>,
    drag_gain: Option<Num>,
    lift_to_drag_bounds: Option<[Num; 2]>,
    drag_bounds: Option<[Num; 2]>,
    min_drag_m_s2: Option<Num>,
}

/// `[guidance.barrier]`: the path-limit bound on the re-planned bank.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BarrierFile {
    limit_scale: Option<[Num; 2]>,
    descent_time_s: Option<Num>,
    frequency_rad_s: Option<Num>,
    damping: Option<Num>,
    predicted: Option<bool>,
}

/// `[guidance.target]`: where the re-planner and the lateral logic aim, at the terminal
/// interface: `latitude_deg` and `longitude_deg`, or `downrange_km` and `crossrange_km` from
/// the entry point (along and right of the entry heading's great circle), or
/// `nominal = true` (where the nominal stored profile with reversals ends); and the terminal
/// interface, at most one of `interface_speed_m_s`, `interface_altitude_m` and
/// `interface_normalized_energy` (absent: the scenario's end; [`TerminalInterface`]).
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TargetFile {
    latitude_deg: Option<Num>,
    longitude_deg: Option<Num>,
    downrange_km: Option<Num>,
    crossrange_km: Option<Num>,
    nominal: Option<bool>,
    interface_speed_m_s: Option<Num>,
    interface_altitude_m: Option<Num>,
    interface_normalized_energy: Option<Num>,
}

/// The four layer sections and the target as written.
#[derive(Debug, Default)]
pub struct LayerFiles {
    /// `[guidance.lateral]`.
    pub lateral: Option<LateralFile>,
    /// `[guidance.replanning]`.
    pub replanning: Option<ReplanFile>,
    /// `[guidance.estimator]`.
    pub estimator: Option<EstimatorFile>,
    /// `[guidance.barrier]`.
    pub barrier: Option<BarrierFile>,
    /// `[guidance.target]`.
    pub target: Option<TargetFile>,
}

/// The target of `t` (planet radius `radius_m` \[m\] for the distances).
fn target(
    f: &Fields<'_>,
    t: Option<TargetFile>,
    radius_m: f64,
) -> Result<TargetSpec, ScenarioError> {
    const HOW: &str = "give latitude_deg and longitude_deg, or downrange_km and crossrange_km, \
                       or nominal = true";
    let Some(t) = t else {
        return Err(f.err(
            "guidance.target",
            "(missing)",
            &format!("required by the re-planning and lateral layers: {HOW}"),
        ));
    };
    let lat = f.checked(
        "guidance.target.latitude_deg",
        t.latitude_deg,
        |v| v.abs() <= 90.0,
        "must be within [-90, 90] deg",
    )?;
    let lon = f.checked(
        "guidance.target.longitude_deg",
        t.longitude_deg,
        |v| v.abs() <= 360.0,
        "must be within [-360, 360] deg",
    )?;
    let half_circle_km = std::f64::consts::PI * radius_m / 1e3;
    let down = f.checked(
        "guidance.target.downrange_km",
        t.downrange_km,
        |v| v > 0.0 && v < half_circle_km,
        &format!(
            "must be in (0, {}) km (half the planet's circumference)",
            half_circle_km.round()
        ),
    )?;
    let cross = f.checked(
        "guidance.target.crossrange_km",
        t.crossrange_km,
        |v| v.abs() < 0.5 * half_circle_km,
        &format!(
            "must be within +-{} km (a quarter circumference)",
            (0.5 * half_circle_km).round()
        ),
    )?;
    let nominal = t.nominal == Some(true);
    match (lat, lon, down, cross, nominal) {
        (Some(la), Some(lo), None, None, false) => Ok(TargetSpec::Point {
            latitude_rad: la.to_radians(),
            longitude_rad: lo.to_radians(),
        }),
        (None, None, Some(d), Some(c), false) => Ok(TargetSpec::Range {
            downrange_rad: d * 1e3 / radius_m,
            crossrange_rad: c * 1e3 / radius_m,
        }),
        (None, None, None, None, true) => Ok(TargetSpec::Nominal),
        _ => Err(f.err(
            "guidance.target",
            "(keys)",
            &format!("one form only: {HOW}"),
        )),
    }
}

/// The terminal interface of `t` (at most one of its three keys), each key checked against its
/// range: a speed in (0, `entry_speed_m_s`), an altitude in (0, `entry_altitude_m`), an E-hat
/// in (0, 1) (1 at entry, 0 at standstill on the surface).
fn interface(
    f: &Fields<'_>,
    t: Option<&TargetFile>,
    entry_speed_m_s: f64,
    entry_altitude_m: f64,
) -> Result<Option<TerminalInterface>, ScenarioError> {
    let Some(t) = t else { return Ok(None) };
    let speed = f
        .checked(
            "guidance.target.interface_speed_m_s",
            t.interface_speed_m_s,
            |v| v > 0.0 && v < entry_speed_m_s,
            "must be in (0, entry speed) m/s",
        )?
        .map(|speed_m_s| TerminalInterface::Speed { speed_m_s });
    let altitude = f
        .checked(
            "guidance.target.interface_altitude_m",
            t.interface_altitude_m,
            |v| v > 0.0 && v < entry_altitude_m,
            &format!(
                "must be in (0, {}) m (the entry altitude)",
                crate::num_fmt::compact(entry_altitude_m)
            ),
        )?
        .map(|altitude_m| TerminalInterface::Altitude { altitude_m });
    let energy = f
        .checked(
            "guidance.target.interface_normalized_energy",
            t.interface_normalized_energy,
            |v| v > 0.0 && v < 1.0,
            "must be in (0, 1) (E-hat: 1 at entry, 0 at standstill on the surface)",
        )?
        .map(|normalized_energy| TerminalInterface::NormalizedEnergy { normalized_energy });
    let mut given = [speed, altitude, energy].into_iter().flatten();
    let first = given.next();
    match (first, given.next()) {
        (Some(a), Some(b)) => Err(f.err(
            &format!("guidance.target.{}", b.key()),
            &crate::num_fmt::compact(b.value()),
            &format!(
                "one terminal interface only: {} is given too (interface_speed_m_s, \
                 interface_altitude_m or interface_normalized_energy)",
                a.key()
            ),
        )),
        _ => Ok(first),
    }
}

fn pair(v: [Num; 2]) -> [f64; 2] {
    [v[0].0, v[1].0]
}

/// A whole number in `[0, max]` (`field` names it in the error).
fn whole(f: &Fields<'_>, field: &str, v: Num, max: f64) -> Result<f64, ScenarioError> {
    if v.0.fract() == 0.0 && (0.0..=max).contains(&v.0) {
        Ok(v.0)
    } else {
        Err(f.err(
            field,
            &crate::num_fmt::compact(v.0),
            &format!("must be an integer in [0, {max}]"),
        ))
    }
}

/// Resolve the layer sections (`None`: no layer beyond the stored profile).
///
/// # Errors
/// [`ScenarioError::Field`] naming `guidance.<section>.<key>`, the value and the range.
#[allow(clippy::too_many_lines)] // one assignment per key, in the order of the file structs
pub(super) fn layers(
    f: &Fields<'_>,
    t: LayerFiles,
    radius_m: f64,
    entry_speed_m_s: f64,
    entry_altitude_m: f64,
) -> Result<Option<GuidanceLayers>, ScenarioError> {
    let on = Layers {
        replan: t.replanning.is_some(),
        lateral: t.lateral.is_some(),
        estimator: t.estimator.is_some(),
        barrier: t.barrier.is_some(),
    };
    if on == Layers::PROFILE {
        if t.target.is_some() {
            return Err(f.err(
                "guidance.target",
                "(section)",
                "a target needs a layer that aims (add [guidance.replanning] or [guidance.lateral])",
            ));
        }
        return Ok(None);
    }
    let aim_file = t.target;
    let mut g = CampaignGuidance::default();
    if let Some(l) = t.lateral {
        set(&mut g.corridor_width_entry_deg, l.corridor_width_entry_deg);
        set(&mut g.corridor_width_final_deg, l.corridor_width_final_deg);
        set(
            &mut g.corridor_low_speed_fraction,
            l.corridor_low_speed_fraction,
        );
        set(&mut g.hysteresis_deg, l.hysteresis_deg);
        if let Some(v) = l.max_reversals {
            g.max_reversals = whole(f, "guidance.lateral.max_reversals", v, 255.0)? as u8;
        }
        set(&mut g.freeze_km, l.freeze_km);
        g.terminal_lateral_km = l.terminal_start_km.map(|v| v.0);
        set(&mut g.terminal_tolerance_km, l.terminal_tolerance_km);
        set(&mut g.terminal_reversal_lead_s, l.terminal_reversal_lead_s);
    }
    if let Some(r) = t.replanning {
        if let Some(v) = r.every_n_ticks {
            g.replan_every_n_ticks =
                whole(f, "guidance.replanning.every_n_ticks", v, 65535.0)? as u16;
        }
        if let Some(v) = r.solver_steps_per_tick {
            g.replan_solver_steps_per_tick =
                whole(f, "guidance.replanning.solver_steps_per_tick", v, 255.0)? as u8;
        }
        set(&mut g.replan_tolerance_km, r.tolerance_km);
        set(&mut g.min_vertical_fraction, r.min_vertical_fraction);
        set(&mut g.max_vertical_fraction, r.max_vertical_fraction);
        g.glide_sink = r.glide_sink.unwrap_or(g.glide_sink);
        g.predictor = r.predictor.unwrap_or(g.predictor);
        if let Some(v) = r.final_speed_offset_m_s {
            return Err(f.err(
                "guidance.replanning.final_speed_offset_m_s",
                &v.0.to_string(),
                "removed: the re-planner's numerical predictor ends at the terminal interface's \
                 energy, the one the flights end on (no tuned offset); the interface is \
                 [guidance.target] interface_speed_m_s, interface_altitude_m or \
                 interface_normalized_energy (docs/reference/guidance-stack.md)",
            ));
        }
        g.predictor_lift_parameter = r.lift_parameter.map(|v| v.0);
        g.predictor_lift_profile = r.lift_profile.unwrap_or(false);
        g.predictor_aero_mach = r.lift_profile_mach.unwrap_or(false);
        g.replan_start_normalized_energy = r.start_normalized_energy.map(|v| v.0);
        if let Some(v) = r.limit_scale {
            g.replan_limit_scale = pair(v);
        }
        g.predictor_rotation = r.numerical_rotation.unwrap_or(false);
        g.bank_shape = r.bank_shape.unwrap_or(false);
    }
    if let Some(e) = t.estimator {
        set(&mut g.estimator_lift_to_drag_gain, e.lift_to_drag_gain);
        set(&mut g.estimator_drag_gain, e.drag_gain);
        if let Some(v) = e.lift_to_drag_bounds {
            g.estimator_lift_to_drag_bounds = pair(v);
        }
        if let Some(v) = e.drag_bounds {
            g.estimator_drag_bounds = pair(v);
        }
        set(&mut g.estimator_min_drag_m_s2, e.min_drag_m_s2);
    }
    if let Some(b) = t.barrier {
        g.path_bound_limit_scale = Some(b.limit_scale.map_or([1.0, 1.0], pair));
        set(&mut g.path_bound_descent_time_s, b.descent_time_s);
        g.path_bound_barrier = match (b.frequency_rad_s, b.damping) {
            (Some(w), Some(z)) => Some([w.0, z.0]),
            (None, None) => None,
            (Some(w), None) => {
                return Err(f.err(
                    "guidance.barrier.frequency_rad_s",
                    &crate::num_fmt::compact(w.0),
                    "the barrier law needs `damping` too",
                ));
            }
            (None, Some(z)) => {
                return Err(f.err(
                    "guidance.barrier.damping",
                    &crate::num_fmt::compact(z.0),
                    "the barrier law needs `frequency_rad_s` too",
                ));
            }
        };
        g.path_bound_predicted = b.predicted.unwrap_or(false);
    }
    if on.estimator && !on.replan {
        return Err(f.err(
            "guidance.estimator",
            "(section)",
            "the estimator is part of the re-planner: add [guidance.replanning]",
        ));
    }
    if !on.estimator && !g.glide_sink {
        // The sink is flown in mode `replan-estimation` only (issue 24: no key read by nothing).
        return Err(f.err(
            "guidance.replanning.glide_sink",
            "false",
            "is read only with onboard estimation: add [guidance.estimator] or remove it",
        ));
    }
    if on.barrier && !on.replan {
        return Err(f.err(
            "guidance.barrier",
            "(section)",
            "the path-limit bound is part of the re-planner: add [guidance.replanning]",
        ));
    }
    g.validate(f.file).map_err(|e| match e {
        CampaignError::Setting {
            file,
            field,
            value,
            reason,
        } => ScenarioError::Field {
            file,
            field,
            value,
            reason,
        },
        other => f.err("guidance", "(layers)", &other.to_string()),
    })?;
    let interface = interface(f, aim_file.as_ref(), entry_speed_m_s, entry_altitude_m)?;
    let aim = target(f, aim_file, radius_m)?;
    Ok(Some(GuidanceLayers {
        settings: g,
        layers: on,
        target: aim,
        interface,
    }))
}

fn set(to: &mut f64, v: Option<Num>) {
    if let Some(v) = v {
        *to = v.0;
    }
}
