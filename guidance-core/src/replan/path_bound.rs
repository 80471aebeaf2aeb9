//! [`PathBound`]: the heat-flux and g-load limits as a lower bound on the vertical lift
//! fraction `f = cos(sigma)` at the current state (an upper bound on the bank magnitude), the
//! way flight-proven entry guidance enforces path constraints (Shuttle drag-velocity corridor,
//! FNPEG's quasi-equilibrium-glide bank limit), instead of demanding them over the whole
//! remaining flight at one constant bank.
//!
//! # Bound
//! At the limit the density is a function of speed alone: the g-load limit `n` holds at
//! `rho_g(V)` where the aerodynamic acceleration is `n g0`, whose lift part is
//! `L_g = n g0 (L/D) / sqrt(1 + (L/D)^2)` (independent of the density model and the
//! vehicle's size); the heat-flux limit `q` (Chapman, [`crate::monitor`]) holds at
//! `rho_q(V) = rho_0 (q sqrt(R_N) / (c* (V / V_c)^3.15))^2`, where the lift acceleration is
//! `L_q = rho_q V^2 S C_L / (2 m)`. The quasi-equilibrium glide `L f = g - V^2 / r` at that
//! density needs `f_qeg = (g - V^2 / r) / min(L_g, L_q)`: with less vertical lift the
//! equilibrium lies in denser air than the limit. A descending vehicle (`h' = V sin(gamma) <
//! 0`) is not in equilibrium: to stop the descent within `tau` seconds it needs the extra
//! vertical acceleration `-h' / tau`, so
//!
//! `f_min = (g - V^2 / r - min(h', 0) / tau) / min(L_g, L_q)`, clamped to `[0, 1]`,
//!
//! with the limits of [`PathBound::limits`] (the vehicle's, or less for a margin; `tau` =
//! [`PathBound::descent_time_s`], 0 turns the descent term off). `L/D` and `C_L` are the predictor model's
//! (`C_L = lambda sqrt(C_D0 / K)`, `C_D = C_D0 (1 + lambda^2)`).
//!
//! # Barrier law (`barrier_frequency_rad_s > 0`)
//! The descent term above asks *every* descent to stop, also far from a limit, so it lofts the
//! vehicle. The barrier law instead keeps the distance to each limit from closing faster than
//! a damped second-order response. With an exponential atmosphere of scale height `H` a limit
//! of the form `rho V^k <= c` (heat flux: `k = 2 * 3.15`; g-load at a fixed polar: `k = 2`) is
//! an altitude floor `h_lim(V)`, and the margin `e = h - h_lim = H ln(rho_lim(V) / rho)` (`> 0`
//! inside the limit) is computed from the current density: `rho_lim / rho = (q_lim / q)^2` for
//! the heat flux, `n_lim / n` for the g-load. The floor moves with the speed:
//! `h_lim' = k H V' / V`, `h_lim'' = k H (V'/V)'`, with `V' = -D - g sin(gamma)` and
//! `(V'/V)' = D (h' / H - 2 V' / V) / V - (V' / V)^2`. Asking
//! `e'' >= -2 zeta omega e' - omega^2 e` (`omega` = [`PathBound::barrier_frequency_rad_s`],
//! `zeta` = [`PathBound::barrier_damping`]) of `h'' = V' sin(gamma) + cos(gamma) (L f - (g -
//! V^2/r) cos(gamma))` gives, for each limit,
//!
//! `f_i = ((h_lim'' - 2 zeta omega (h' - h_lim') - omega^2 e - V' sin(gamma)) / cos(gamma) + (g
//! - V^2/r) cos(gamma)) / L`,
//!
//! with `L`, `D` the lift and drag accelerations at the current density, and `f_min = max_i
//! f_i` clamped to `[0, 1]`: no bound far from the limits (`e` large), the equilibrium glide on
//! a limit (`e = e' = 0`), lift-up beyond it. The density is the model atmosphere's
//! ([`PathBound::barrier_vertical_fraction`]). [`crate::replan::ReplanningGuidance`] applies
//! a barrier bound at every guidance tick, not only at re-plans.

use crate::estimate::{SensedAero, expected_aero};
use crate::monitor::{CHAPMAN_C_STAR, CHAPMAN_RHO0_KG_M3, CHAPMAN_SPEED_EXPONENT, CHAPMAN_VC_M_S};
use crate::nav::NavState;
use crate::scalar::Real;
use crate::vinh::nondim::{ExpAtmosphere, G0_M_S2, Planet, VehicleParams};

use super::ReplanLimits;

/// Smallest sensed drag acceleration \[m/s^2\] the barrier law uses in place of the model's
/// ([`PathBound::barrier_vertical_fraction`]).
pub const SENSED_MIN_DRAG_M_S2: f64 = 0.5;

/// The limit-driven bound on the vertical lift fraction (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PathBound<S> {
    /// The limits the bound holds: stagnation-point heat flux \[W/m^2\] and g-load \[g0\]
    /// (the vehicle's times a margin; a very large one leaves that limit out).
    pub limits: ReplanLimits<S>,
    /// Time in which the bound asks a descent to be stopped \[s\], `>= 0`; 0: no descent term
    /// (the plain quasi-equilibrium-glide bound).
    pub descent_time_s: S,
    /// Natural frequency `omega` of the barrier law \[rad/s\], `>= 0` (module docs); 0: off
    /// (the equilibrium bound with its descent term). With a barrier, `descent_time_s` is
    /// not used.
    pub barrier_frequency_rad_s: S,
    /// Damping ratio `zeta` of the barrier law \[-\], `>= 0` (module docs).
    pub barrier_damping: S,
}

/// The point at which the barrier law is evaluated (module docs), in SI units.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BarrierPoint<S> {
    /// Gravitational parameter \[m^3/s^2\].
    pub mu_m3_s2: S,
    /// Radius \[m\].
    pub r: S,
    /// Speed \[m/s\].
    pub v: S,
    /// Sine and cosine of the flight-path angle \[-\].
    pub sin_gamma: S,
    /// See `sin_gamma`.
    pub cos_gamma: S,
    /// Density \[kg/m^3\].
    pub rho: S,
    /// The atmosphere's scale height \[m\].
    pub scale_height_m: S,
    /// Lift and drag accelerations at `rho` \[m/s^2\].
    pub lift: S,
    /// See `lift`.
    pub drag: S,
}

/// Default [`PathBound::barrier_frequency_rad_s`] of [`PathBound::barrier`] \[rad/s\] (chosen
/// on HORUS-2B dispersion campaigns: docs/reference/path-limits.md).
pub const DEFAULT_BARRIER_FREQUENCY_RAD_S: f64 = 0.2;
/// Default [`PathBound::barrier_damping`] of [`PathBound::barrier`] \[-\] (critical damping).
pub const DEFAULT_BARRIER_DAMPING: f64 = 1.0;

impl<S: Real> PathBound<S> {
    /// The barrier law holding `limits` (heat flux \[W/m^2\], g-load \[-\]) with natural
    /// frequency [`DEFAULT_BARRIER_FREQUENCY_RAD_S`] and damping [`DEFAULT_BARRIER_DAMPING`]
    /// (module docs, "Barrier law").
    ///
    /// ```
    /// use guidance_core::missions::HORUS2B_LIMITS;
    /// use guidance_core::replan::PathBound;
    /// let bound = PathBound::<f32>::barrier(HORUS2B_LIMITS.load_limits());
    /// assert!(bound.is_valid());
    /// ```
    #[must_use]
    pub fn barrier(limits: ReplanLimits<S>) -> Self {
        Self {
            limits,
            descent_time_s: S::ZERO,
            barrier_frequency_rad_s: S::from_f64(DEFAULT_BARRIER_FREQUENCY_RAD_S),
            barrier_damping: S::from_f64(DEFAULT_BARRIER_DAMPING),
        }
    }

    /// The quasi-equilibrium-glide bound holding `limits`, asking a descent to stop within
    /// `descent_time_s` \[s\] (`>= 0`; 0: no descent term; module docs, "Bound").
    #[must_use]
    pub fn equilibrium(limits: ReplanLimits<S>, descent_time_s: S) -> Self {
        Self {
            limits,
            descent_time_s,
            barrier_frequency_rad_s: S::ZERO,
            barrier_damping: S::ZERO,
        }
    }

    /// Whether the bound is usable: finite, positive limits, `descent_time_s >= 0`.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        let all = [
            self.limits.heat_flux_w_m2,
            self.limits.g_load,
            self.descent_time_s,
            self.barrier_frequency_rad_s,
            self.barrier_damping,
        ];
        all.iter().all(|v| v.is_finite())
            && self.limits.heat_flux_w_m2 > S::ZERO
            && self.limits.g_load > S::ZERO
            && self.descent_time_s >= S::ZERO
            && self.barrier_frequency_rad_s >= S::ZERO
            && self.barrier_damping >= S::ZERO
    }

    /// Whether the bound and the inputs the two laws share are usable (module docs).
    fn inputs_ok(
        &self,
        planet: &Planet<S>,
        vehicle: &VehicleParams<S>,
        lambda: S,
        nav: &NavState<S>,
    ) -> bool {
        let pos = |v: S| v.is_finite() && v > S::ZERO;
        self.is_valid()
            && pos(planet.mu_m3_s2)
            && pos(nav.radius_m)
            && pos(nav.speed_m_s)
            && nav.flight_path_angle_rad.is_finite()
            && pos(vehicle.mass_kg)
            && pos(vehicle.reference_area_m2)
            && pos(vehicle.cd0)
            && pos(vehicle.k_polar)
            && pos(vehicle.nose_radius_m)
            && lambda.is_finite()
            && lambda >= S::ZERO
    }

    /// Whether the barrier law is on (`barrier_frequency_rad_s > 0`).
    #[must_use]
    pub fn is_barrier(&self) -> bool {
        self.barrier_frequency_rad_s > S::ZERO
    }

    /// The barrier law's smallest vertical lift fraction \[-\] at `nav` (module docs), in
    /// `[0, 1]`, for a vehicle flying the lift parameter `lambda` \[-\] of `vehicle`'s polar
    /// with its drag coefficient times `drag_scale` \[-\], in `atmosphere` on `planet`. With
    /// the barrier off it is [`PathBound::min_vertical_fraction`]. `None` for an invalid bound,
    /// non-finite or out-of-domain input (as there, plus a non-positive `drag_scale`, density
    /// or scale height) or a non-finite result.
    ///
    /// With `sensed` (the lift and drag accelerations measured at `nav`, e.g. by the IMU) the
    /// law uses them instead of the model's, and the density the measured drag implies
    /// (`rho_model D_sensed / D_model`): the margins are then those of the flown vehicle in the
    /// flown atmosphere. A sensed drag below [`SENSED_MIN_DRAG_M_S2`] (thin air, where the
    /// measurement is mostly noise) or an invalid one is not used.
    #[must_use]
    pub fn barrier_vertical_fraction(
        &self,
        planet: &Planet<S>,
        atmosphere: &ExpAtmosphere<S>,
        vehicle: &VehicleParams<S>,
        (lambda, drag_scale): (S, S),
        nav: &NavState<S>,
        sensed: Option<SensedAero<S>>,
    ) -> Option<S> {
        if !self.is_barrier() {
            return self.min_vertical_fraction(planet, vehicle, lambda, nav);
        }
        let pos = |v: S| v.is_finite() && v > S::ZERO;
        let ok = self.inputs_ok(planet, vehicle, lambda, nav)
            && pos(drag_scale)
            && pos(atmosphere.rho0_kg_m3)
            && pos(atmosphere.scale_height_m)
            && atmosphere.ref_radius_m.is_finite();
        if !ok {
            return None;
        }
        let r = nav.radius_m;
        let v = nav.speed_m_s;
        let rho = atmosphere.density_unchecked(r);
        // The model's accelerations, as the onboard estimator expects them.
        let model = expected_aero(atmosphere, vehicle, lambda, r, v)?;
        let (lift, drag) = (model.lift_m_s2, model.drag_m_s2 * drag_scale);
        let min_drag = S::from_f64(SENSED_MIN_DRAG_M_S2);
        let (rho, lift, drag) = match sensed {
            Some(a) if a.validate().is_ok() && a.drag_m_s2 >= min_drag && drag > S::ZERO => {
                (rho * (a.drag_m_s2 / drag), a.lift_m_s2, a.drag_m_s2)
            }
            _ => (rho, lift, drag),
        };
        let gamma = nav.flight_path_angle_rad;
        let point = BarrierPoint {
            mu_m3_s2: planet.mu_m3_s2,
            r,
            v,
            sin_gamma: gamma.sin(),
            cos_gamma: gamma.cos(),
            rho,
            scale_height_m: atmosphere.scale_height_m,
            lift,
            drag,
        };
        self.barrier_fraction(&point, vehicle.nose_radius_m)
    }

    /// The barrier law at `p` (module docs) without the input checks, for a vehicle of nose
    /// radius `nose_radius_m` \[m\]; `None` if not computable (no density, no lift and a
    /// positive need is lift-up).
    pub(crate) fn barrier_fraction(&self, p: &BarrierPoint<S>, nose_radius_m: S) -> Option<S> {
        if !(p.rho > S::ZERO && p.v > S::ZERO && p.scale_height_m > S::ZERO) {
            return None;
        }
        let h = p.scale_height_m;
        let g = p.mu_m3_s2 / (p.r * p.r);
        let c = g - p.v * p.v / p.r;
        let hdot = p.v * p.sin_gamma;
        let vdot = -p.drag - g * p.sin_gamma;
        let a = vdot / p.v;
        let adot = p.drag * (hdot / h - a - a) / p.v - a * a;
        // Margins (altitude above each limit's floor) from the current density.
        let rho_q = chapman_limit_density(self.limits.heat_flux_w_m2, nose_radius_m, p.v);
        let e_q = h * (rho_q / p.rho).ln();
        let accel = (p.lift * p.lift + p.drag * p.drag).sqrt_raw();
        let n = self.limits.g_load * S::from_f64(G0_M_S2);
        let e_g = h * (n / accel).ln();
        let w = self.barrier_frequency_rad_s;
        let two_zw = (self.barrier_damping + self.barrier_damping) * w;
        let k_q = S::from_f64(2.0 * CHAPMAN_SPEED_EXPONENT);
        let k_g = S::from_f64(2.0);
        let need = |kk: S, e: S| {
            let floor_rate = kk * h * a;
            let floor_accel = kk * h * adot;
            let hdd = floor_accel - two_zw * (hdot - floor_rate) - w * w * e;
            (hdd - vdot * p.sin_gamma) / p.cos_gamma + c * p.cos_gamma
        };
        let need = need(k_q, e_q).max(need(k_g, e_g));
        let f = need / p.lift;
        if !f.is_finite() {
            return if p.lift == S::ZERO && need.is_finite() {
                Some(if need > S::ZERO { S::ONE } else { S::ZERO })
            } else {
                None
            };
        }
        Some(f.clamp(S::ZERO, S::ONE))
    }

    /// The smallest vertical lift fraction \[-\] that keeps the quasi-equilibrium glide at
    /// `nav`'s speed within [`PathBound::limits`] (module docs), in `[0, 1]`; for a vehicle
    /// flying the lift parameter `lambda` \[-\] of `vehicle`'s polar on `planet`. `None` for
    /// an invalid bound, non-finite or out-of-domain input (non-positive radius, speed, mass,
    /// area, `C_D0`, `K`, nose radius; negative `lambda`) or a non-finite result.
    #[must_use]
    pub fn min_vertical_fraction(
        &self,
        planet: &Planet<S>,
        vehicle: &VehicleParams<S>,
        lambda: S,
        nav: &NavState<S>,
    ) -> Option<S> {
        if !self.inputs_ok(planet, vehicle, lambda, nav) {
            return None;
        }
        let cl = lambda * (vehicle.cd0 / vehicle.k_polar).sqrt_raw();
        let cd = vehicle.cd0 * (S::ONE + lambda * lambda);
        self.fraction(
            planet.mu_m3_s2,
            nav.radius_m,
            nav.speed_m_s,
            nav.flight_path_angle_rad.sin(),
            cl,
            cd,
            vehicle,
        )
    }

    /// [`PathBound::min_vertical_fraction`] without the input checks, from the gravitational
    /// parameter \[m^3/s^2\], radius \[m\], speed \[m/s\], sine of the flight-path angle,
    /// `C_L` and `C_D` \[-\] (for the numerical predictor, whose inputs are validated once).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn fraction(
        &self,
        mu_m3_s2: S,
        r: S,
        v: S,
        sin_gamma: S,
        cl: S,
        cd: S,
        vehicle: &VehicleParams<S>,
    ) -> Option<S> {
        // g-load limit: lift part of n g0 at the polar's L/D.
        let n = self.limits.g_load * S::from_f64(G0_M_S2);
        let lift_g = n * cl / (cl * cl + cd * cd).sqrt_raw();
        // Heat-flux limit: the Chapman density at this speed, and the lift there.
        let rho_q = chapman_limit_density(self.limits.heat_flux_w_m2, vehicle.nose_radius_m, v);
        let lift_q = rho_q * v * v * vehicle.reference_area_m2.half() * cl / vehicle.mass_kg;
        let lift = lift_g.min(lift_q);
        // Vertical acceleration needed: gravity less centrifugal, plus stopping the descent.
        let mut need = mu_m3_s2 / (r * r) - v * v / r;
        if self.descent_time_s > S::ZERO {
            let sink = v * sin_gamma;
            if sink < S::ZERO {
                need = need - sink / self.descent_time_s;
            }
        }
        let f = need / lift;
        if !f.is_finite() {
            // Zero lift (lambda 0) with a positive need: the bound is lift-up; else none.
            return if lift == S::ZERO && need.is_finite() {
                Some(if need > S::ZERO { S::ONE } else { S::ZERO })
            } else {
                None
            };
        }
        Some(f.clamp(S::ZERO, S::ONE))
    }
}

/// The density \[kg/m^3\] at which the Chapman stagnation heat flux ([`crate::monitor`]) of a
/// nose of radius `nose_radius_m` \[m\] at speed `v` \[m/s\] is `q_w_m2` \[W/m^2\].
#[inline]
fn chapman_limit_density<S: Real>(q_w_m2: S, nose_radius_m: S, v: S) -> S {
    let v_ratio = v / S::from_f64(CHAPMAN_VC_M_S);
    let root = q_w_m2 * nose_radius_m.sqrt_raw()
        / (S::from_f64(CHAPMAN_C_STAR) * v_ratio.powf(S::from_f64(CHAPMAN_SPEED_EXPONENT)));
    S::from_f64(CHAPMAN_RHO0_KG_M3) * root * root
}
