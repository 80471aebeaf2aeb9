//! Building a campaign's [`CampaignSetup`] from a scenario: the nominal flight (the terminal
//! interface), the energy-indexed stored profile, the settings of the lateral logic and the
//! re-planner, then the target re-aimed with nominal flights of the stored profile with bank
//! reversals ([`super::flight`], which flies the set-up this builds).

use guidance_core::energy::EnergyNormalizer;
use guidance_core::guidance::{GuidanceConfig, RateLimits};
use guidance_core::interp::Interpolation;
use guidance_core::lateral::{Corridor, CorridorAxis, TerminalLateral};
use guidance_core::replan::{PathBound, RangeTarget, ReplanConfig, ReplanLimits, TargetPoint};
use guidance_core::stack::{
    BarrierLayer, LateralLayer, Layers, ProfileLayer, ReplanLayer, StackConfig,
};
use guidance_core::vinh::PredictorConfig;

use super::setup::{
    CampaignSetup, DEG, PREDICTOR_POLAR_MACH, RETARGET_ITERATIONS, along_heading,
    downrange_crossrange, energy_table, profile_aero_schedule, profile_lift_parameter,
    profile_lift_schedule,
};
use super::{CampaignError, Mode};
use crate::dynamics::SphericalState;
use crate::env::Planet;
use crate::env::{Environment, ExponentialAtmosphere};
use crate::replan_loop::predictor_model;
use crate::scenario::guidance_layers::CampaignGuidance;
use crate::scenario::{
    PREDICTOR_FIT_ALTITUDES_M, Scenario, TargetSpec, TerminalInterface, build_guidance,
};
use crate::sim::SimResult;

impl CampaignSetup {
    /// Build from `sc` with the scenario's layers ([`Scenario::layers`]; none: the stored
    /// profile alone) aimed at the scenario's target (`TargetSpec::Nominal`: as below): fly it
    /// nominally with its own guidance (the stored profile), take the
    /// end as the terminal interface, build the energy-indexed two-sided table, then place the
    /// target on the entry great circle at the downrange that the stored profile flown with
    /// bank reversals reaches (at most [`RETARGET_ITERATIONS`] nominal flights, until the
    /// downrange error is below 100 m), so the nominal case is on target. The terminal
    /// interface is where the nominal flight first slows to `interface_speed_m_s` (a
    /// campaign's override) if given, else the scenario's own interface
    /// ([`crate::scenario::GuidanceLayers::interface`]: a speed, an altitude or a normalised
    /// energy), else the nominal end.
    ///
    /// # Errors
    /// [`CampaignError`] if the scenario cannot be flown or its guidance built.
    pub fn new(
        sc: &Scenario,
        file: &str,
        interface_speed_m_s: Option<f64>,
    ) -> Result<Self, CampaignError> {
        let Some(l) = &sc.layers else {
            let mut s = Self::with_guidance(
                sc,
                file,
                interface_speed_m_s.map(|speed_m_s| TerminalInterface::Speed { speed_m_s }),
                &CampaignGuidance::default(),
            )?;
            s.stack = s.stack.masked(Layers::PROFILE);
            return Ok(s);
        };
        let interface = interface_speed_m_s
            .map(|speed_m_s| TerminalInterface::Speed { speed_m_s })
            .or(l.interface);
        // A fixed target is aimed at directly: the re-aiming flights of `with_guidance` would
        // only place a target that `aim_at` replaces.
        let mut s = match l.target {
            TargetSpec::Nominal => Self::with_guidance(sc, file, interface, &l.settings)?,
            _ => Self::unaimed(sc, file, interface, &l.settings)?,
        };
        s.stack = s.stack.masked(l.layers);
        match l.target {
            TargetSpec::Nominal => {}
            TargetSpec::Point {
                latitude_rad,
                longitude_rad,
            } => s.aim_at(TargetPoint {
                latitude_rad,
                longitude_rad,
            }),
            TargetSpec::Range {
                downrange_rad,
                crossrange_rad,
            } => s.aim_at(downrange_crossrange(
                &sc.entry,
                downrange_rad,
                crossrange_rad,
            )),
        }
        Ok(s)
    }

    /// [`CampaignSetup::new`] with every layer on, with the settings `gs` (whatever the
    /// scenario's own layers), ending at the terminal interface `interface` (`None`: the
    /// nominal end).
    ///
    /// # Errors
    /// As [`CampaignSetup::new`]; [`CampaignError::Setting`] for a bad `gs` or an interface
    /// the nominal flight never reaches.
    pub fn with_guidance(
        sc: &Scenario,
        file: &str,
        interface: Option<TerminalInterface>,
        gs: &CampaignGuidance,
    ) -> Result<Self, CampaignError> {
        let mut setup = Self::unaimed(sc, file, interface, gs)?;
        // Re-aim at where the stored profile with reversals ends, on the entry great circle
        // (a fixed-point iteration: the reversals depend on the target).
        for _ in 0..RETARGET_ITERATIONS {
            let f = super::flight::fly_case(&setup, None, Mode::StoredReversals)?;
            if f.downrange_error_m.abs() < 100.0 {
                break;
            }
            let radius = setup.planet_radius_m;
            setup.retarget(setup.target_downrange_rad + f.downrange_error_m / radius);
        }
        Ok(setup)
    }

    /// [`CampaignSetup::with_guidance`] without the re-aiming flights: the target where the
    /// nominal flight of the stored profile (without reversals) ends.
    fn unaimed(
        sc: &Scenario,
        file: &str,
        interface: Option<TerminalInterface>,
        gs: &CampaignGuidance,
    ) -> Result<Self, CampaignError> {
        gs.validate(file)?;
        let scen = |source| CampaignError::Scenario {
            file: file.into(),
            source: Box::new(source),
        };
        let vehicle = sc.load_vehicle().map_err(scen)?;
        let env: Environment = sc.environment.build();
        let planet = env.planet;
        let g0 = build_guidance(sc, &planet, file).map_err(scen)?;
        let nominal = super::flight::fly_plain(sc, &env, &vehicle, g0)?;
        let last = nominal
            .samples
            .last()
            .map(|s| s.state)
            .ok_or(CampaignError::EmptyFlight)?;
        let end = match interface {
            Some(i) => interface_crossing(&nominal, i, &planet, &sc.entry).ok_or_else(|| {
                let (field, reason) = match i {
                    TerminalInterface::Speed { .. } => (
                        "dispersions.interface_speed_m_s".to_string(),
                        "the nominal flight never slows down to it",
                    ),
                    _ => (
                        format!("guidance.target.{}", i.key()),
                        "the nominal flight never reaches it",
                    ),
                };
                CampaignError::Setting {
                    file: file.into(),
                    field,
                    value: i.value().to_string(),
                    reason: reason.into(),
                }
            })?,
            None => last,
        };
        let energy = EnergyNormalizer::new(
            planet.mu_m3_s2,
            planet.radius_m,
            sc.entry.radius_m,
            sc.entry.speed_m_s,
        )
        .map_err(|source| CampaignError::Guidance {
            file: file.into(),
            field: "entry",
            source,
        })?;
        let table = energy_table(sc, &nominal, file)?;
        let g = &sc.guidance;
        let guidance_config = GuidanceConfig {
            period_s: g.period_s,
            rates: RateLimits {
                alpha_rad_s: g.alpha_rate_rad_s,
                sigma_rad_s: g.sigma_rate_rad_s,
            },
        };
        let v_e = sc.entry.speed_m_s;
        let v_f = end.speed_m_s;
        let target = along_heading(&sc.entry, nominal.summary.range_angle_rad);
        let lateral = LateralLayer {
            corridor: Corridor {
                axis: CorridorAxis::Speed,
                x_high: v_e,
                width_high_rad: gs.corridor_width_entry_deg * DEG,
                x_low: v_f + gs.corridor_low_speed_fraction * (v_e - v_f),
                width_low_rad: gs.corridor_width_final_deg * DEG,
            },
            hysteresis_rad: gs.hysteresis_deg * DEG,
            max_reversals: gs.max_reversals,
            freeze_angle_rad: gs.freeze_km * 1e3 / planet.radius_m,
            terminal: gs.terminal_lateral_km.map(|k| TerminalLateral {
                start_angle_rad: k * 1e3 / planet.radius_m,
                tolerance_rad: gs.terminal_tolerance_km * 1e3 / planet.radius_m,
                reversal_lead_s: gs.terminal_reversal_lead_s,
            }),
        };
        let (h1, h2) = PREDICTOR_FIT_ALTITUDES_M;
        let fit =
            ExponentialAtmosphere::fitted_to(env.atmosphere.as_ref(), h1, h2).map_err(|e| {
                CampaignError::Predictor {
                    file: file.into(),
                    source: e.into(),
                }
            })?;
        let model =
            predictor_model(&vehicle, &fit, &planet, PREDICTOR_POLAR_MACH).map_err(|source| {
                CampaignError::Predictor {
                    file: file.into(),
                    source,
                }
            })?;
        let replan = ReplanLayer {
            every_n_ticks: gs.replan_every_n_ticks,
            limits: ReplanLimits {
                heat_flux_w_m2: vehicle.limits.heat_flux_w_m2 * gs.replan_limit_scale[0],
                g_load: vehicle.limits.g_load * gs.replan_limit_scale[1],
            },
            solver: ReplanConfig {
                // 1: the polar's maximum L/D (the trim point of a trim vehicle).
                lambda: match (gs.predictor_lift_parameter, gs.predictor_lift_profile) {
                    (Some(l), _) => l,
                    (None, true) => profile_lift_parameter(&vehicle, &model, &nominal, file)?,
                    (None, false) => 1.0,
                },
                min_vertical_fraction: gs.min_vertical_fraction,
                max_vertical_fraction: gs.max_vertical_fraction,
                tolerance_m: gs.replan_tolerance_km * 1e3,
                max_iterations: guidance_core::replan::DEFAULT_MAX_ITERATIONS,
                // The closed forms end at the interface speed; the numerical predictions at
                // the interface energy (`final_energy_j_kg` below).
                predictor: PredictorConfig {
                    final_speed_m_s: v_f,
                    max_skips: guidance_core::replan::DEFAULT_MAX_SKIPS,
                },
                // The mode of `replan-estimation`; masking the estimator off drops the sink
                // (`StackConfig::masked`).
                mode: gs.predictor.mode(gs.glide_sink),
            },
            model,
            apply_out_of_reach: true,
            steps_per_tick: gs.replan_solver_steps_per_tick,
            lift_schedule: match (gs.predictor_lift_profile, gs.predictor_aero_mach) {
                (true, true) => profile_aero_schedule(&vehicle, &model, &nominal, v_f),
                (true, false) => profile_lift_schedule(&vehicle, &model, &nominal, v_f),
                (false, _) => None,
            },
            start_normalized_energy: gs.replan_start_normalized_energy,
            numerical_rotation: gs.predictor_rotation,
            bank_shape: gs.bank_shape,
            // The terminal interface the flights end on: the nominal flight's energy where it
            // crosses the interface.
            final_energy_j_kg: Some(0.5 * v_f * v_f - planet.mu_m3_s2 / end.radius_m),
        };
        let barrier = gs.path_bound_limit_scale.map(|[q, g]| BarrierLayer {
            bound: PathBound {
                limits: ReplanLimits {
                    heat_flux_w_m2: vehicle.limits.heat_flux_w_m2 * q,
                    g_load: vehicle.limits.g_load * g,
                },
                descent_time_s: gs.path_bound_descent_time_s,
                barrier_frequency_rad_s: gs.path_bound_barrier.map_or(0.0, |[w, _]| w),
                barrier_damping: gs.path_bound_barrier.map_or(0.0, |[_, z]| z),
            },
            predicted: gs.path_bound_predicted,
        });
        let stack = StackConfig {
            profile: ProfileLayer {
                guidance: guidance_config,
                table,
                interpolation: Interpolation::Linear,
                energy,
                initial: sc.guidance.initial,
            },
            replan: Some(replan),
            lateral: Some(lateral),
            estimator: Some(gs.estimator()),
            barrier,
            target: Some(RangeTarget::Point(target)),
        };
        let r_f = end.radius_m;
        Ok(Self {
            scenario: sc.clone(),
            file: file.into(),
            interface_energy_j_kg: 0.5 * v_f * v_f - planet.mu_m3_s2 / r_f,
            interface_speed_m_s: v_f,
            interface,
            floor_altitude_m: (r_f - planet.radius_m - 10e3).max(1e3),
            planet_radius_m: planet.radius_m,
            target_downrange_rad: nominal.summary.range_angle_rad,
            stack,
            guidance: gs.clone(),
        })
    }
}

/// The terminal interface `interface` on the nominal flight `nominal` (entry state `entry`,
/// planet `planet`): the state of the first output sample interval where the flight crosses
/// it downwards, at the crossing (linear in the crossed quantity between the two samples),
/// the other fields those of the interval's first sample. Speed: the speed is the one given,
/// the radius interpolated. Altitude (above the planet's sphere): the radius is the one given,
/// the speed interpolated. Normalised energy (E-hat of the nominal entry): the specific energy
/// is the one given, the radius interpolated and the speed the one of that energy at that
/// radius. `None` if the flight never crosses it.
fn interface_crossing(
    nominal: &SimResult,
    interface: TerminalInterface,
    planet: &Planet,
    entry: &SphericalState,
) -> Option<SphericalState> {
    let mu = planet.mu_m3_s2;
    let energy = |s: &SphericalState| 0.5 * s.speed_m_s * s.speed_m_s - mu / s.radius_m;
    // The crossed quantity of a state, and its value at the interface.
    let value = |s: &SphericalState| match interface {
        TerminalInterface::Speed { .. } => s.speed_m_s,
        TerminalInterface::Altitude { .. } => s.radius_m - planet.radius_m,
        TerminalInterface::NormalizedEnergy { .. } => energy(s),
    };
    let at = match interface {
        TerminalInterface::Speed { speed_m_s } => speed_m_s,
        TerminalInterface::Altitude { altitude_m } => altitude_m,
        TerminalInterface::NormalizedEnergy { normalized_energy } => {
            // E-hat = (E - E_0) / (E_entry - E_0), E_0 = -mu/R (guidance_core::energy).
            let e0 = -mu / planet.radius_m;
            e0 + normalized_energy * (energy(entry) - e0)
        }
    };
    nominal.samples.windows(2).find_map(|w| match w {
        [a, b] if value(&a.state) > at && value(&b.state) <= at => {
            let (a, b) = (&a.state, &b.state);
            let f = (value(a) - at) / (value(a) - value(b));
            let mut s = *a;
            match interface {
                TerminalInterface::Speed { speed_m_s } => {
                    s.radius_m += f * (b.radius_m - a.radius_m);
                    s.speed_m_s = speed_m_s;
                }
                TerminalInterface::Altitude { altitude_m } => {
                    s.radius_m = planet.radius_m + altitude_m;
                    s.speed_m_s += f * (b.speed_m_s - a.speed_m_s);
                }
                TerminalInterface::NormalizedEnergy { .. } => {
                    s.radius_m += f * (b.radius_m - a.radius_m);
                    s.speed_m_s = (2.0 * (at + mu / s.radius_m)).max(0.0).sqrt();
                }
            }
            Some(s)
        }
        _ => None,
    })
}
