//! Re-planning set-up items: the whole [`ReplanningConfig`] (schedule, target and limits,
//! corrector, predictor model) as five set-up items (codes 8 to 12), uploaded after the
//! guidance items when a scenario uses re-planning. The firmware collects them
//! (`SetupBuilder`) and, at commit, builds a [`crate::replan::ReplanningGuidance`] whose
//! constructor runs the core's checks on them.

use super::error::{SetupError, small_int};
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
    /// Code 8: schedule and counts. Slots: every N ticks, solver steps per tick (0: whole
    /// solve in its tick), apply out of reach (0 or 1), predictor mode (0 chain, 1 glide,
    /// 2 auto, 3 auto-sink, 4 numerical, 5 hybrid, 6 hybrid-sink), corrector iterations,
    /// predictor skips.
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
                    PredictorMode::AutoSink => 3.0,
                    PredictorMode::Numerical => 4.0,
                    PredictorMode::Hybrid => 5.0,
                    PredictorMode::HybridSink => 6.0,
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
                mode: match small_int(d, 6)? {
                    0 => PredictorMode::Chain,
                    1 => PredictorMode::Glide,
                    2 => PredictorMode::Auto,
                    3 => PredictorMode::AutoSink,
                    4 => PredictorMode::Numerical,
                    5 => PredictorMode::Hybrid,
                    _ => PredictorMode::HybridSink,
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

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::panic)]
mod tests {
    use super::*;
    use crate::guidance::{Command, GuidanceConfig};
    use crate::interp::Interpolation;
    use crate::nodes::{AngleBounds, Independent, Node, NodeTable};
    use crate::setup::{SetupBuilder, SetupGuidance, SetupItem, items};
    use crate::{Fixed, NavState, Scalar};

    fn config(target: RangeTarget<f64>, mode: PredictorMode) -> ReplanningConfig<f64> {
        ReplanningConfig {
            every_n_ticks: 5,
            target,
            limits: ReplanLimits {
                heat_flux_w_m2: 5e5,
                g_load: 3.0,
            },
            solver: ReplanConfig {
                lambda: 1.0,
                min_vertical_fraction: 0.05,
                max_vertical_fraction: 1.0,
                tolerance_m: 1000.0,
                max_iterations: 20,
                predictor: PredictorConfig {
                    final_speed_m_s: 2500.0,
                    max_skips: 4,
                },
                mode,
            },
            model: PredictorModel {
                planet: Planet::earth(),
                atmosphere: ExpAtmosphere::earth(),
                vehicle: VehicleParams {
                    mass_kg: 38.77,
                    reference_area_m2: 0.441,
                    cd0: 0.2576,
                    k_polar: 0.1879,
                    nose_radius_m: 0.9,
                },
                rotation_rate_rad_s: 7.292_115e-5,
            },
            apply_out_of_reach: true,
            steps_per_tick: 3,
        }
    }

    fn targets() -> [RangeTarget<f64>; 2] {
        [
            RangeTarget::Point(TargetPoint {
                latitude_rad: -0.4,
                longitude_rad: 2.5,
            }),
            RangeTarget::FlownRangeAngle { total_rad: 2.8 },
        ]
    }

    fn table() -> NodeTable<f64> {
        let d = core::f64::consts::PI / 180.0;
        let n = |x: f64, s: f64| Node {
            x,
            alpha_rad: 0.0,
            sigma_rad: s * d,
        };
        NodeTable::new(
            Independent::NormalizedEnergy,
            &[n(1.0, 0.0), n(0.8, 40.0), n(0.4, 60.0), n(0.0, 0.0)],
            AngleBounds {
                alpha_min_rad: 0.0,
                alpha_max_rad: 45.0 * d,
                sigma_min_rad: -90.0 * d,
                sigma_max_rad: 90.0 * d,
            },
        )
        .unwrap()
    }

    fn all_items(rc: Option<&ReplanningConfig<f64>>) -> ([SetupItem; 32], usize) {
        let t = table();
        let energy = (3.986_004_418e14, 6_378_137.0, 6_478_137.0, 7658.34);
        let mut out = [SetupItem::Commit; 32];
        let mut n = 0;
        for (slot, it) in out.iter_mut().zip(items(
            &t,
            Interpolation::Linear,
            GuidanceConfig::thesis_default(),
            Command::from_deg(0.0, 0.0).unwrap(),
            energy,
            rc,
        )) {
            *slot = it;
            n += 1;
        }
        (out, n)
    }

    /// Every re-planning item survives its slots, and the whole configuration survives the
    /// builder (for `f64`: exactly).
    #[test]
    fn replanning_items_round_trip() {
        for target in targets() {
            for mode in [
                PredictorMode::Chain,
                PredictorMode::Glide,
                PredictorMode::Auto,
                PredictorMode::AutoSink,
                PredictorMode::Numerical,
                PredictorMode::Hybrid,
                PredictorMode::HybridSink,
            ] {
                let rc = config(target, mode);
                for it in replan_items(&rc) {
                    let slots = SetupItem::Replan(it).to_slots();
                    assert_eq!(SetupItem::from_slots(&slots), Ok(SetupItem::Replan(it)));
                }
                let mut parts = ReplanParts::default();
                for it in replan_items(&rc) {
                    parts.apply(it);
                }
                assert_eq!(parts.config::<f64>(), Ok(Some(rc)));
            }
        }
    }

    /// Malformed integer or enumeration slots and unknown codes are `BadItem`.
    #[test]
    fn malformed_replanning_items_are_rejected() {
        let rc = config(targets()[1], PredictorMode::Auto);
        let schedule = SetupItem::Replan(replan_items(&rc)[0]).to_slots();
        for (slot, value) in [
            (1, 1.5),
            (1, 70_000.0),
            (2, 256.0),
            (3, 2.0),
            (4, 7.0),
            (5, -1.0),
        ] {
            let mut s = schedule;
            s[slot] = value;
            assert_eq!(
                SetupItem::from_slots(&s),
                Err(SetupError::BadItem),
                "{slot}"
            );
        }
        let mut target = SetupItem::Replan(replan_items(&rc)[1]).to_slots();
        target[1] = 2.0;
        assert_eq!(SetupItem::from_slots(&target), Err(SetupError::BadItem));
        // A flown-range target carries no longitude: a non-zero one is not canonical.
        target[1] = 1.0;
        target[3] = 0.5;
        assert_eq!(SetupItem::from_slots(&target), Err(SetupError::BadItem));
        let mut unknown = schedule;
        unknown[0] = 13.0;
        assert_eq!(SetupItem::from_slots(&unknown), Err(SetupError::BadItem));
    }

    fn builder<S: crate::Scalar>(list: &[SetupItem]) -> SetupBuilder<S, 16> {
        let mut b = SetupBuilder::<S, 16>::new();
        for it in list.iter().filter(|i| **i != SetupItem::Commit) {
            b.apply(it).unwrap();
        }
        b
    }

    /// With all five items the builder makes `ReplanningGuidance` (f32, and fixed point with an
    /// f32 re-planner); with some missing it is `Incomplete`; the core's checks reject a bad
    /// configuration; `build` refuses re-planning items; without them it is the stored profile.
    #[test]
    fn builder_makes_replanning_guidance_with_the_core_checks() {
        let rc = config(targets()[1], PredictorMode::Auto);
        let (list, n) = all_items(Some(&rc));
        let b = builder::<f32>(&list[..n]);
        assert!(matches!(
            b.build_flight::<f32>(),
            Ok(SetupGuidance::Replanning(_))
        ));
        assert_eq!(b.build().err(), Some(SetupError::BadItem));
        let bf = builder::<Fixed>(&list[..n]);
        assert!(matches!(
            bf.build_flight::<f32>(),
            Ok(SetupGuidance::Replanning(_))
        ));
        // One item short.
        let short: [SetupItem; 31] = core::array::from_fn(|i| {
            if i + 2 == n {
                SetupItem::Commit
            } else {
                list[i]
            }
        });
        assert_eq!(
            builder::<f32>(&short[..n - 1]).build_flight::<f32>().err(),
            Some(SetupError::Incomplete)
        );
        // The core rejects a vertical-fraction interval outside (0, 1] and a bad model.
        let mut bad = rc;
        bad.solver.min_vertical_fraction = 0.0;
        let (list, n) = all_items(Some(&bad));
        assert_eq!(
            builder::<f32>(&list[..n]).build_flight::<f32>().err(),
            Some(SetupError::Guidance(crate::GuidanceError::InvalidConfig))
        );
        let mut bad = rc;
        bad.model.vehicle.mass_kg = -1.0;
        let (list, n) = all_items(Some(&bad));
        assert_eq!(
            builder::<f32>(&list[..n]).build_flight::<f32>().err(),
            Some(SetupError::Guidance(crate::GuidanceError::InvalidConfig))
        );
        let (list, n) = all_items(None);
        assert!(matches!(
            builder::<f32>(&list[..n]).build_flight::<f32>(),
            Ok(SetupGuidance::Stored(_))
        ));
        assert!(builder::<f32>(&list[..n]).build().is_ok());
    }

    /// Fixed-point guidance with an f32 re-planner re-plans where f32 guidance does, to the
    /// same bank (the predictor sees the same f32 state up to the fixed-point rounding of the
    /// navigation values), and its commands stay within the table's bounds.
    #[test]
    fn fixed_point_tick_with_f32_replanner_follows_f32() {
        let mut rc = config(
            RangeTarget::FlownRangeAngle { total_rad: 2.83 },
            PredictorMode::Auto,
        );
        rc.model.rotation_rate_rad_s = 0.0;
        let (list, n) = all_items(Some(&rc));
        let (SetupGuidance::Replanning(mut g32), SetupGuidance::Replanning(mut gfx)) = (
            builder::<f32>(&list[..n]).build_flight::<f32>().unwrap(),
            builder::<Fixed>(&list[..n]).build_flight::<f32>().unwrap(),
        ) else {
            panic!("not re-planning");
        };
        let mut applied = 0;
        for k in 0..12u8 {
            let t = 2.0 * f64::from(k);
            let nav = NavState {
                time_s: t,
                radius_m: 6_478_137.0 - 50.0 * t,
                speed_m_s: 7658.34 - 0.5 * t,
                flight_path_angle_rad: -0.004_47,
                heading_rad: 1.5,
                latitude_rad: 0.0,
                longitude_rad: 1.2e-3 * t,
            };
            let a = g32.update(&nav.to_scalar::<f32>()).unwrap();
            let b = gfx.update(&nav.to_scalar::<Fixed>()).unwrap();
            assert_eq!(a.replan.is_some(), b.replan.is_some(), "tick {k}");
            if let (Some(ra), Some(rb)) = (a.replan, b.replan) {
                assert_eq!(ra.case, rb.case);
                assert!((ra.bank_rad - rb.bank_rad).abs() < 1e-3, "{ra:?} {rb:?}");
                applied += u32::from(rb.applied);
            }
            let (ca, cb) = (a.guidance.command, b.guidance.command);
            assert!((f64::from(ca.sigma_rad) - cb.sigma_rad.to_f64()).abs() < 1e-3);
        }
        assert!(applied > 0, "{:?}", g32.last_replan());
    }
}
