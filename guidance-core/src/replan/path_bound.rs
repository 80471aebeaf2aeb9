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

use crate::monitor::{CHAPMAN_C_STAR, CHAPMAN_RHO0_KG_M3, CHAPMAN_SPEED_EXPONENT, CHAPMAN_VC_M_S};
use crate::nav::NavState;
use crate::scalar::Real;
use crate::vinh::nondim::{G0_M_S2, Planet, VehicleParams};

use super::ReplanLimits;

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
}

impl<S: Real> PathBound<S> {
    /// Whether the bound is usable: finite, positive limits, `descent_time_s >= 0`.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        let all = [
            self.limits.heat_flux_w_m2,
            self.limits.g_load,
            self.descent_time_s,
        ];
        all.iter().all(|v| v.is_finite())
            && self.limits.heat_flux_w_m2 > S::ZERO
            && self.limits.g_load > S::ZERO
            && self.descent_time_s >= S::ZERO
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
        let pos = |v: S| v.is_finite() && v > S::ZERO;
        let ok = self.is_valid()
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
            && lambda >= S::ZERO;
        if !ok {
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
        let q = self.limits.heat_flux_w_m2;
        let v_ratio = v / S::from_f64(CHAPMAN_VC_M_S);
        let root = q * vehicle.nose_radius_m.sqrt_raw()
            / (S::from_f64(CHAPMAN_C_STAR) * v_ratio.powf(S::from_f64(CHAPMAN_SPEED_EXPONENT)));
        let rho_q = S::from_f64(CHAPMAN_RHO0_KG_M3) * root * root;
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
