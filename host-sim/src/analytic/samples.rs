//! Conversion of planar closed-form points into the numerical simulator's samples and summary
//! (time and heat load by quadrature over range angle, peak times interpolated in range angle).

use guidance_core::energy::EnergyNormalizer;
use guidance_core::guidance::Command;
use guidance_core::vinh;

use super::{AnalyticVehicle, LiftSetting, Placement};
use crate::dynamics::{FlightConditions, SphericalState};
use crate::env::{Atmosphere, ExponentialAtmosphere, Planet};
use crate::sim::{
    Peak, Sample, SampleKind, SimResult, Summary, TerminationReason, great_circle, violations,
};

/// One planar point of a closed form.
#[derive(Clone, Copy, Debug)]
pub(super) struct Planar {
    pub(super) theta: f64,
    pub(super) radius: f64,
    pub(super) speed: f64,
    pub(super) gamma: f64,
    pub(super) heat_flux: f64,
    pub(super) drag_acc: f64,
    pub(super) lift_acc: f64,
    pub(super) g_load: f64,
    /// Index of the lift setting flown here in [`Ctx::lifts`] (0 for a single glide or skip).
    pub(super) segment: usize,
}

/// `From` for the skip's and the glide's point types, which carry the same fields.
macro_rules! planar_from {
    ($($point:ty),+) => {$(
        impl From<$point> for Planar {
            fn from(p: $point) -> Self {
                Self {
                    theta: p.range_angle_rad,
                    radius: p.radius_m,
                    speed: p.speed_m_s,
                    gamma: p.flight_path_angle_rad,
                    heat_flux: p.heat_flux_w_m2,
                    drag_acc: p.drag_acc_m_s2,
                    lift_acc: p.lift_acc_m_s2,
                    g_load: p.g_load,
                    segment: 0,
                }
            }
        }
    )+};
}

planar_from!(vinh::SkipPoint<f64>, vinh::GlidePoint<f64>);

/// Shared conversion from planar closed-form points to simulator samples.
pub(super) struct Ctx<'a> {
    pub(super) vehicle: &'a AnalyticVehicle,
    /// The lift settings flown, indexed by [`Planar::segment`] (one for a single closed form;
    /// one per segment of a node-guided glide).
    pub(super) lifts: &'a [LiftSetting],
    pub(super) atmosphere: &'a ExponentialAtmosphere,
    pub(super) planet: Planet,
    pub(super) placement: Placement,
}

impl Ctx<'_> {
    fn state(&self, p: &Planar) -> SphericalState {
        let (lat, lon, heading) = self.placement.along(p.theta);
        SphericalState {
            radius_m: p.radius,
            longitude_rad: lon,
            latitude_rad: lat,
            speed_m_s: p.speed,
            flight_path_angle_rad: p.gamma,
            heading_rad: heading,
        }
    }

    fn lift(&self, p: &Planar) -> LiftSetting {
        self.lifts
            .get(p.segment)
            .or_else(|| self.lifts.last())
            .copied()
            .unwrap_or(LiftSetting {
                cl: 0.0,
                bank_rad: 0.0,
            })
    }

    fn conditions(&self, p: &Planar) -> FlightConditions {
        let lift = self.lift(p);
        let altitude_m = p.radius - self.planet.radius_m;
        let atm = self.atmosphere.state(altitude_m);
        let m = self.vehicle.mass_kg;
        FlightConditions {
            altitude_m,
            density_kg_m3: atm.density_kg_m3,
            airspeed_m_s: p.speed,
            mach: p.speed / atm.speed_of_sound_m_s,
            dynamic_pressure_pa: 0.5 * atm.density_kg_m3 * p.speed * p.speed,
            cl: lift.cl,
            cd: self.vehicle.polar.cd(lift.cl),
            lift_n: m * p.lift_acc,
            drag_n: m * p.drag_acc,
            heat_flux_w_m2: p.heat_flux,
            g_load: p.g_load,
        }
    }

    /// Samples (time by quadrature) and summary.
    pub(super) fn assemble(
        &self,
        rows: &[Planar],
        peak_q: Planar,
        peak_g: Planar,
        termination: TerminationReason,
    ) -> SimResult {
        let first = rows.first().copied().unwrap_or(peak_q);
        let energy = EnergyNormalizer::<f64>::new(
            self.planet.mu_m3_s2,
            self.planet.radius_m,
            first.radius,
            first.speed,
        )
        .ok();
        let pace = |p: &Planar| p.radius / (p.speed * p.gamma.cos());
        let mut samples: Vec<Sample> = Vec::with_capacity(rows.len());
        let (mut t, mut heat) = (0.0, 0.0);
        let mut g_rate = Peak::default();
        for (i, p) in rows.iter().enumerate() {
            if let Some(prev) = i.checked_sub(1).and_then(|j| rows.get(j)) {
                let dt = (p.theta - prev.theta) * 0.5 * (pace(prev) + pace(p));
                heat += 0.5 * (prev.heat_flux + p.heat_flux) * dt;
                t += dt;
                if dt > 0.0 {
                    let rate = ((p.g_load - prev.g_load) / dt).abs();
                    if rate > g_rate.value {
                        g_rate = Peak {
                            value: rate,
                            time_s: t,
                        };
                    }
                }
            }
            let state = self.state(p);
            let kind = if i == 0 {
                SampleKind::Start
            } else if i + 1 == rows.len() {
                SampleKind::End
            } else {
                SampleKind::Output
            };
            samples.push(Sample {
                time_s: t,
                state,
                attitude: Command {
                    alpha_rad: 0.0,
                    sigma_rad: self.lift(p).bank_rad,
                },
                conditions: self.conditions(p),
                heat_load_j_m2: heat,
                flown_range_rad: p.theta,
                normalized_energy: energy
                    .as_ref()
                    .and_then(|e| e.normalized(p.radius, p.speed).ok())
                    .unwrap_or(f64::NAN),
                kind,
            });
        }
        let time_at = |theta: f64| -> f64 {
            samples
                .windows(2)
                .find_map(|w| match w {
                    [a, b] if theta <= b.flown_range_rad => {
                        let span = b.flown_range_rad - a.flown_range_rad;
                        let f = if span > 0.0 {
                            ((theta - a.flown_range_rad) / span).clamp(0.0, 1.0)
                        } else {
                            0.0
                        };
                        Some(a.time_s + f * (b.time_s - a.time_s))
                    }
                    _ => None,
                })
                .unwrap_or(t)
        };
        let peak_heat = Peak {
            value: peak_q.heat_flux,
            time_s: time_at(peak_q.theta),
        };
        let peak_g_load = Peak {
            value: peak_g.g_load,
            time_s: time_at(peak_g.theta),
        };
        let range = match (samples.first(), samples.last()) {
            (Some(a), Some(b)) => great_circle(&a.state, &b.state),
            _ => 0.0,
        };
        let lim = &self.vehicle.limits;
        let summary = Summary {
            termination,
            flight_time_s: t,
            range_angle_rad: range,
            flown_range_angle_rad: rows.last().map_or(0.0, |p| p.theta),
            heat_load_j_m2: heat,
            peak_heat_flux_w_m2: peak_heat,
            peak_g_load,
            peak_g_load_rate_per_s: g_rate,
            exits: 0,
            skips: 0,
            interface_crossings_s: Vec::new(),
            violations: violations(peak_heat, peak_g_load, g_rate, lim),
            rhs_evals: 0,
            accepted_steps: 0,
            rejected_steps: 0,
            ticks: 0,
        };
        SimResult { samples, summary }
    }
}
