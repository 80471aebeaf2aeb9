//! Re-planning set-up items: the whole [`ReplanningConfig`] (schedule, target and limits,
//! corrector, predictor model) as five set-up items (codes 8 to 12), uploaded after the
//! guidance items when a scenario uses re-planning. The firmware collects them
//! ([`ReplanParts`]) and, at commit, builds a [`crate::replan::ReplanningGuidance`] whose
//! constructor runs the core's checks on them.

use super::{SetupError, small_int};
use crate::replan::{
    PredictorMode, PredictorModel, RangeTarget, ReplanConfig, ReplanLimits, ReplanningConfig,
    TargetPoint,
};
use crate::scalar::Real;
use crate::vinh::PredictorConfig;
use crate::vinh::nondim::{ExpAtmosphere, Planet, VehicleParams};

/// One re-planning set-up item (values SI, radians).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ReplanItem {
    /// Code 8: schedule and counts. Slots: every N ticks, predictor calls per tick (0: whole
    /// solve in its tick), apply out of reach (0 or 1), predictor mode (0 chain, 1 glide,
    /// 2 auto), corrector iterations, predictor skips.
    Schedule {
        /// [`ReplanningConfig::every_n_ticks`] \[ticks\].
        every_n_ticks: u16,
        /// [`ReplanningConfig::steps_per_tick`] \[predictor calls\].
        steps_per_tick: u8,
        /// [`ReplanningConfig::apply_out_of_reach`].
        apply_out_of_reach: bool,
        /// [`ReplanConfig::mode`].
        mode: PredictorMode,
        /// [`ReplanConfig::max_iterations`].
        max_iterations: u8,
        /// [`PredictorConfig::max_skips`].
        max_skips: u8,
    },
    /// Code 9: target and limits. Slots: target kind (0 point, 1 flown range angle), latitude
    /// \[rad\] or total range angle \[rad\], longitude \[rad\] (0 for a range angle), final speed
    /// \[m/s\], heat-flux limit \[W/m^2\], g-load limit \[-\].
    Target {
        /// What the re-planner aims at.
        target: RangeTarget<f64>,
        /// Predictor final speed \[m/s\].
        final_speed_m_s: f64,
        /// Peak heat-flux and g-load limits.
        limits: ReplanLimits<f64>,
    },
    /// Code 10: corrector. Slots: lambda \[-\], smallest and largest vertical lift fraction
    /// \[-\], range tolerance \[m\].
    Corrector {
        /// Total lift parameter \[-\].
        lambda: f64,
        /// Smallest vertical lift fraction \[-\].
        min_vertical_fraction: f64,
        /// Largest vertical lift fraction \[-\].
        max_vertical_fraction: f64,
        /// Accepted range miss \[m\].
        tolerance_m: f64,
    },
    /// Code 11: the predictor's planet and atmosphere. Slots: mu \[m^3/s^2\], radius \[m\],
    /// rho0 \[kg/m^3\], scale height \[m\], atmosphere reference radius \[m\], rotation rate
    /// \[rad/s\].
    World {
        /// Planet.
        planet: Planet<f64>,
        /// Exponential atmosphere.
        atmosphere: ExpAtmosphere<f64>,
        /// Rotation rate for the effective-gravity correction \[rad/s\].
        rotation_rate_rad_s: f64,
    },
    /// Code 12: the predictor's vehicle. Slots: mass \[kg\], reference area \[m^2\], `C_D0`
    /// \[-\], polar `K` \[-\], nose radius \[m\].
    Vehicle(VehicleParams<f64>),
}

fn flag(b: bool) -> f64 {
    if b { 1.0 } else { 0.0 }
}

impl ReplanItem {
    /// The seven payload slots (slot 0 the item code).
    #[must_use]
    pub fn to_slots(&self) -> [f64; 7] {
        match *self {
            ReplanItem::Schedule {
                every_n_ticks,
                steps_per_tick,
                apply_out_of_reach,
                mode,
                max_iterations,
                max_skips,
            } => [
                8.0,
                f64::from(every_n_ticks),
                f64::from(steps_per_tick),
                flag(apply_out_of_reach),
                match mode {
                    PredictorMode::Chain => 0.0,
                    PredictorMode::Glide => 1.0,
                    PredictorMode::Auto => 2.0,
                },
                f64::from(max_iterations),
                f64::from(max_skips),
            ],
            ReplanItem::Target {
                target,
                final_speed_m_s,
                limits,
            } => {
                let (kind, a, b) = match target {
                    RangeTarget::Point(p) => (0.0, p.latitude_rad, p.longitude_rad),
                    RangeTarget::FlownRangeAngle { total_rad } => (1.0, total_rad, 0.0),
                };
                [
                    9.0,
                    kind,
                    a,
                    b,
                    final_speed_m_s,
                    limits.heat_flux_w_m2,
                    limits.g_load,
                ]
            }
            ReplanItem::Corrector {
                lambda,
                min_vertical_fraction,
                max_vertical_fraction,
                tolerance_m,
            } => [
                10.0,
                lambda,
                min_vertical_fraction,
                max_vertical_fraction,
                tolerance_m,
                0.0,
                0.0,
            ],
            ReplanItem::World {
                planet,
                atmosphere,
                rotation_rate_rad_s,
            } => [
                11.0,
                planet.mu_m3_s2,
                planet.radius_m,
                atmosphere.rho0_kg_m3,
                atmosphere.scale_height_m,
                atmosphere.ref_radius_m,
                rotation_rate_rad_s,
            ],
            ReplanItem::Vehicle(v) => [
                12.0,
                v.mass_kg,
                v.reference_area_m2,
                v.cd0,
                v.k_polar,
                v.nose_radius_m,
                0.0,
            ],
        }
    }

    /// The item of code `code` (8 to 12) from its slots (not checked for canonical form here:
    /// see [`super::SetupItem::from_slots`]).
    pub(super) fn parse(code: u32, s: &[f64; 7]) -> Result<Self, SetupError> {
        let [_, a, b, c, d, e, f] = *s;
        let byte = |v: f64| -> Result<u8, SetupError> {
            u8::try_from(small_int(v, 255)?).map_err(|_| SetupError::BadItem)
        };
        Ok(match code {
            8 => ReplanItem::Schedule {
                every_n_ticks: u16::try_from(small_int(a, u32::from(u16::MAX))?)
                    .map_err(|_| SetupError::BadItem)?,
                steps_per_tick: byte(b)?,
                apply_out_of_reach: small_int(c, 1)? == 1,
                mode: match small_int(d, 2)? {
                    0 => PredictorMode::Chain,
                    1 => PredictorMode::Glide,
                    _ => PredictorMode::Auto,
                },
                max_iterations: byte(e)?,
                max_skips: byte(f)?,
            },
            9 => ReplanItem::Target {
                target: match small_int(a, 1)? {
                    0 => RangeTarget::Point(TargetPoint {
                        latitude_rad: b,
                        longitude_rad: c,
                    }),
                    _ => RangeTarget::FlownRangeAngle { total_rad: b },
                },
                final_speed_m_s: d,
                limits: ReplanLimits {
                    heat_flux_w_m2: e,
                    g_load: f,
                },
            },
            10 => ReplanItem::Corrector {
                lambda: a,
                min_vertical_fraction: b,
                max_vertical_fraction: c,
                tolerance_m: d,
            },
            11 => ReplanItem::World {
                planet: Planet {
                    mu_m3_s2: a,
                    radius_m: b,
                },
                atmosphere: ExpAtmosphere {
                    rho0_kg_m3: c,
                    scale_height_m: d,
                    ref_radius_m: e,
                },
                rotation_rate_rad_s: f,
            },
            12 => ReplanItem::Vehicle(VehicleParams {
                mass_kg: a,
                reference_area_m2: b,
                cd0: c,
                k_polar: d,
                nose_radius_m: e,
            }),
            _ => return Err(SetupError::BadItem),
        })
    }
}

/// The five items of `c`, in upload order.
#[must_use]
pub fn replan_items(c: &ReplanningConfig<f64>) -> [ReplanItem; 5] {
    [
        ReplanItem::Schedule {
            every_n_ticks: c.every_n_ticks,
            steps_per_tick: c.steps_per_tick,
            apply_out_of_reach: c.apply_out_of_reach,
            mode: c.solver.mode,
            max_iterations: c.solver.max_iterations,
            max_skips: c.solver.predictor.max_skips,
        },
        ReplanItem::Target {
            target: c.target,
            final_speed_m_s: c.solver.predictor.final_speed_m_s,
            limits: c.limits,
        },
        ReplanItem::Corrector {
            lambda: c.solver.lambda,
            min_vertical_fraction: c.solver.min_vertical_fraction,
            max_vertical_fraction: c.solver.max_vertical_fraction,
            tolerance_m: c.solver.tolerance_m,
        },
        ReplanItem::World {
            planet: c.model.planet,
            atmosphere: c.model.atmosphere,
            rotation_rate_rad_s: c.model.rotation_rate_rad_s,
        },
        ReplanItem::Vehicle(c.model.vehicle),
    ]
}

/// The re-planning items received so far (`f64` as on the wire).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct ReplanParts {
    schedule: Option<ReplanItem>,
    target: Option<ReplanItem>,
    corrector: Option<ReplanItem>,
    world: Option<ReplanItem>,
    vehicle: Option<ReplanItem>,
}

impl ReplanParts {
    /// Keep `item` (a later item of the same code replaces an earlier one).
    pub(super) fn apply(&mut self, item: ReplanItem) {
        let slot = match item {
            ReplanItem::Schedule { .. } => &mut self.schedule,
            ReplanItem::Target { .. } => &mut self.target,
            ReplanItem::Corrector { .. } => &mut self.corrector,
            ReplanItem::World { .. } => &mut self.world,
            ReplanItem::Vehicle(_) => &mut self.vehicle,
        };
        *slot = Some(item);
    }

    /// The configuration in the predictor scalar `P`: `Ok(None)` if no re-planning item was
    /// received (stored profile only).
    ///
    /// # Errors
    /// [`SetupError::Incomplete`] if some but not all five items arrived.
    pub(super) fn config<P: Real>(&self) -> Result<Option<ReplanningConfig<P>>, SetupError> {
        let p = P::from_f64;
        match (
            self.schedule,
            self.target,
            self.corrector,
            self.world,
            self.vehicle,
        ) {
            (None, None, None, None, None) => Ok(None),
            (
                Some(ReplanItem::Schedule {
                    every_n_ticks,
                    steps_per_tick,
                    apply_out_of_reach,
                    mode,
                    max_iterations,
                    max_skips,
                }),
                Some(ReplanItem::Target {
                    target,
                    final_speed_m_s,
                    limits,
                }),
                Some(ReplanItem::Corrector {
                    lambda,
                    min_vertical_fraction,
                    max_vertical_fraction,
                    tolerance_m,
                }),
                Some(ReplanItem::World {
                    planet,
                    atmosphere,
                    rotation_rate_rad_s,
                }),
                Some(ReplanItem::Vehicle(v)),
            ) => Ok(Some(ReplanningConfig {
                every_n_ticks,
                target: match target {
                    RangeTarget::Point(t) => RangeTarget::Point(TargetPoint {
                        latitude_rad: p(t.latitude_rad),
                        longitude_rad: p(t.longitude_rad),
                    }),
                    RangeTarget::FlownRangeAngle { total_rad } => RangeTarget::FlownRangeAngle {
                        total_rad: p(total_rad),
                    },
                },
                limits: ReplanLimits {
                    heat_flux_w_m2: p(limits.heat_flux_w_m2),
                    g_load: p(limits.g_load),
                },
                solver: ReplanConfig {
                    lambda: p(lambda),
                    min_vertical_fraction: p(min_vertical_fraction),
                    max_vertical_fraction: p(max_vertical_fraction),
                    tolerance_m: p(tolerance_m),
                    max_iterations,
                    predictor: PredictorConfig {
                        final_speed_m_s: p(final_speed_m_s),
                        max_skips,
                    },
                    mode,
                },
                model: PredictorModel {
                    planet: Planet {
                        mu_m3_s2: p(planet.mu_m3_s2),
                        radius_m: p(planet.radius_m),
                    },
                    atmosphere: ExpAtmosphere {
                        rho0_kg_m3: p(atmosphere.rho0_kg_m3),
                        scale_height_m: p(atmosphere.scale_height_m),
                        ref_radius_m: p(atmosphere.ref_radius_m),
                    },
                    vehicle: VehicleParams {
                        mass_kg: p(v.mass_kg),
                        reference_area_m2: p(v.reference_area_m2),
                        cd0: p(v.cd0),
                        k_polar: p(v.k_polar),
                        nose_radius_m: p(v.nose_radius_m),
                    },
                    rotation_rate_rad_s: p(rotation_rate_rad_s),
                },
                apply_out_of_reach,
                steps_per_tick,
            })),
            _ => Err(SetupError::Incomplete),
        }
    }
}
