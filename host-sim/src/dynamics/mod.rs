//! 3-DOF translational dynamics of an unpowered entry vehicle over a rotating spherical planet
//! (thesis sec. 3.3-3.4).
//!
//! Two formulations of the same physics:
//! * [`Dynamics::cartesian_rhs`]: inertial planet-centred Cartesian position and velocity,
//!   `F = m a` (eq. 3.12). This is what the simulator integrates. The atmosphere co-rotates
//!   with the planet, so the aerodynamic forces use the air-relative velocity
//!   `v_rel = v_I - omega x r`.
//! * [`Dynamics::spherical_rhs`]: planet-relative spherical state `(r, tau, delta, V, gamma,
//!   chi)` with Coriolis and centripetal terms (eq. 3.13 after Mooij, with the ERRATA fixes:
//!   the first line is the longitude rate `tau-dot`, and the centripetal term of the
//!   gamma equation has `r`, not `R`). Gravity enters through its radial and northward
//!   components, so J2 is included exactly. Used as an independent cross-check.
//!
//! Frames: the inertial frame I and the planet-fixed frame R share the z axis (rotation
//! axis) and coincide at t = 0; at time t, R is rotated by `omega t` about z. Heading `chi` is
//! measured clockwise from north, flight-path angle `gamma` positive up, bank angle `sigma`
//! positive turns the velocity to the right (towards increasing heading).
//!
//! The integrated state (see [`STATE_LEN`]) is position (3), velocity (3), heat load
//! `Q = integral q dt` [J/m^2] and flown range angle `theta = integral V cos(gamma)/r dt`
//! \[rad\] (eq. 3.15).

use guidance_core::guidance::Command;
use nalgebra::Vector3;

use crate::env::{Atmosphere, ChapmanHeatFlux, Environment, Gravity, NoseHeatFlux, Planet};
use crate::vehicle::Vehicle;

mod frames;

use frames::local_axes;
pub use frames::{
    CartesianState, FLOWN_RANGE_SLOT, HEAT_LOAD_SLOT, STATE_LEN, SphericalState, cartesian_of,
    cartesian_to_spherical, spherical_to_cartesian,
};

/// Standard gravity g0 [m/s^2] used to express g-loads (eq. 2.1); `guidance-core`'s value.
pub const G0_M_S2: f64 = guidance_core::monitor::G0_M_S2;

/// Everything the forces model computes at one instant (inputs to the RHS and to outputs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlightConditions {
    /// Altitude above the sphere \[m\].
    pub altitude_m: f64,
    /// Air density [kg/m^3].
    pub density_kg_m3: f64,
    /// Air-relative (planet-relative) speed [m/s].
    pub airspeed_m_s: f64,
    /// Mach number [-] (airspeed over the local speed of sound; 0 where the model has no
    /// speed of sound).
    pub mach: f64,
    /// Dynamic pressure \[Pa\].
    pub dynamic_pressure_pa: f64,
    /// Lift coefficient [-].
    pub cl: f64,
    /// Drag coefficient [-].
    pub cd: f64,
    /// Lift \[N\].
    pub lift_n: f64,
    /// Drag \[N\].
    pub drag_n: f64,
    /// Chapman stagnation heat flux [W/m^2].
    pub heat_flux_w_m2: f64,
    /// Aerodynamic load factor sqrt(L^2 + D^2) / (m g0) [-] (eq. 2.1).
    pub g_load: f64,
}

/// Forces model: planet, atmosphere, gravity and vehicle.
#[derive(Clone, Copy)]
pub struct Dynamics<'a> {
    /// Planet constants (radius, rotation rate).
    pub planet: Planet,
    /// Atmosphere model (co-rotating).
    pub atmosphere: &'a dyn Atmosphere,
    /// Gravity model.
    pub gravity: &'a dyn Gravity,
    /// Vehicle.
    pub vehicle: &'a Vehicle,
    /// Chapman heat-flux constants.
    pub heat_flux: ChapmanHeatFlux,
}

impl std::fmt::Debug for Dynamics<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Dynamics")
            .field("planet", &self.planet)
            .field("vehicle", &self.vehicle.name)
            .finish_non_exhaustive()
    }
}

/// Unit lift direction for air-relative velocity direction `vhat` at position direction
/// `rhat` and bank angle `sigma`: `cos(sigma) e_gamma + sin(sigma) (vhat x e_gamma)`, where
/// `e_gamma` is the unit vector in the vertical plane perpendicular to `vhat` pointing up.
/// For vertical flight (undefined vertical plane) `e_gamma` falls back to the direction of
/// `z x vhat` (or `x x vhat`), a documented arbitrary choice.
#[must_use]
pub fn lift_direction(rhat: &Vector3<f64>, vhat: &Vector3<f64>, sigma_rad: f64) -> Vector3<f64> {
    lift_direction_sc(rhat, vhat, sigma_rad.sin_cos())
}

/// [`lift_direction`] with the sine and cosine of the bank angle given (the right-hand side
/// keeps them while the bank angle holds).
fn lift_direction_sc(
    rhat: &Vector3<f64>,
    vhat: &Vector3<f64>,
    sin_cos: (f64, f64),
) -> Vector3<f64> {
    let mut e_up = rhat - vhat * rhat.dot(vhat);
    if e_up.norm() < 1e-12 {
        e_up = Vector3::z().cross(vhat);
        if e_up.norm() < 1e-12 {
            e_up = Vector3::x().cross(vhat);
        }
    }
    let e_up = e_up.normalize();
    let (s, c) = sin_cos;
    e_up * c + vhat.cross(&e_up) * s
}

/// What the simulator's right-hand side ([`Dynamics::cartesian_derivative`]) keeps between
/// calls: the heat-flux relation at the vehicle's nose radius, the sine and cosine of the
/// last bank angle, and the air data, forces and heat flux of the last point evaluated. Made
/// by [`Dynamics::rhs_cache`] for one `Dynamics`.
///
/// The last point is what makes an accepted step's end cheap: the loop's peak monitors
/// ([`Dynamics::heat_flux_and_g_load`]), an output sample ([`Dynamics::conditions_at_cached`])
/// and the next step's first stage all evaluate the same state under the same angle of
/// attack; only the first computes the atmosphere, the aerodynamic coefficients and the heat
/// flux, the others reuse them (the same values, bit for bit).
#[derive(Clone, Copy, Debug)]
pub struct RhsCache {
    heat_flux: NoseHeatFlux,
    sigma_rad: f64,
    sin_cos: (f64, f64),
    /// Which point `last` is ([`point_key`]); `None` before the first evaluation.
    last_key: Option<[u64; 7]>,
    last: PointAero,
}

/// Air data and aerodynamic forces at one instant (what the right-hand side needs).
#[derive(Clone, Copy, Debug)]
struct Aero {
    rho: f64,
    mach: f64,
    q_dyn: f64,
    cl: f64,
    cd: f64,
    lift: f64,
    drag: f64,
}

/// [`Aero`], the airspeed and the heat flux at one point (position, velocity and angle of
/// attack).
#[derive(Clone, Copy, Debug)]
struct PointAero {
    airspeed_m_s: f64,
    aero: Aero,
    heat_flux_w_m2: f64,
}

/// The bits that determine [`PointAero`]: position and velocity of `y`, and `alpha_rad`
/// (the bank angle, time, heat load and range do not enter the air data).
fn point_key(y: &[f64; STATE_LEN], alpha_rad: f64) -> [u64; 7] {
    [
        y[0].to_bits(),
        y[1].to_bits(),
        y[2].to_bits(),
        y[3].to_bits(),
        y[4].to_bits(),
        y[5].to_bits(),
        alpha_rad.to_bits(),
    ]
}

impl<'a> Dynamics<'a> {
    /// Dynamics from an environment bundle and a vehicle.
    #[must_use]
    pub fn from_environment(env: &'a Environment, vehicle: &'a Vehicle) -> Self {
        Self {
            planet: env.planet,
            atmosphere: env.atmosphere.as_ref(),
            gravity: env.gravity.as_ref(),
            vehicle,
            heat_flux: env.heat_flux,
        }
    }

    fn omega(&self) -> Vector3<f64> {
        Vector3::new(0.0, 0.0, self.planet.rotation_rate_rad_s)
    }

    /// Altitude \[m\] and airspeed (relative to the co-rotating air) \[m/s\] at an
    /// integrated state `y`.
    fn altitude_airspeed(&self, y: &[f64; STATE_LEN]) -> (f64, f64) {
        let r = Vector3::new(y[0], y[1], y[2]);
        let v = Vector3::new(y[3], y[4], y[5]);
        (
            r.norm() - self.planet.radius_m,
            (v - self.omega().cross(&r)).norm(),
        )
    }

    /// Air data and forces at altitude `altitude_m` and airspeed `v_m_s` (one atmosphere call,
    /// one aerodynamic lookup).
    fn aero(&self, altitude_m: f64, v_m_s: f64, alpha_rad: f64) -> Aero {
        let atm = self.atmosphere.state(altitude_m);
        let rho = atm.density_kg_m3.max(0.0);
        let mach = if atm.speed_of_sound_m_s > 0.0 {
            v_m_s / atm.speed_of_sound_m_s
        } else {
            0.0
        };
        let q_dyn = 0.5 * rho * v_m_s * v_m_s;
        let (cl, cd, lift, drag) = if q_dyn > 0.0 {
            let c = self.vehicle.aero.coefficients(mach, alpha_rad);
            let qs = q_dyn * self.vehicle.reference_area_m2;
            (c.cl, c.cd, c.cl * qs, c.cd * qs)
        } else {
            (0.0, 0.0, 0.0, 0.0)
        };
        Aero {
            rho,
            mach,
            q_dyn,
            cl,
            cd,
            lift,
            drag,
        }
    }

    /// Aerodynamic and heating quantities at altitude `altitude_m` and airspeed `v_m_s` (the
    /// heat flux as the right-hand side integrates it, [`crate::env::NoseHeatFlux`]).
    #[must_use]
    pub fn conditions(&self, altitude_m: f64, v_m_s: f64, att: Command<f64>) -> FlightConditions {
        let a = self.aero(altitude_m, v_m_s, att.alpha_rad);
        FlightConditions {
            altitude_m,
            density_kg_m3: a.rho,
            airspeed_m_s: v_m_s,
            mach: a.mach,
            dynamic_pressure_pa: a.q_dyn,
            cl: a.cl,
            cd: a.cd,
            lift_n: a.lift,
            drag_n: a.drag,
            heat_flux_w_m2: self
                .heat_flux
                .at_nose(self.vehicle.nose_radius_m)
                .heat_flux_w_m2(a.rho, v_m_s),
            g_load: guidance_core::monitor::g_load(a.lift, a.drag, self.vehicle.mass_kg),
        }
    }

    /// Conditions at an integrated Cartesian state `y` (see [`STATE_LEN`]).
    #[must_use]
    pub fn conditions_at(&self, y: &[f64; STATE_LEN], att: Command<f64>) -> FlightConditions {
        let (altitude_m, airspeed_m_s) = self.altitude_airspeed(y);
        self.conditions(altitude_m, airspeed_m_s, att)
    }

    /// Magnitudes of the lift and drag accelerations \[m/s^2\] at an integrated state `y`
    /// under `att` (what an IMU senses): `|lift| / m` and `|drag| / m` of
    /// [`Dynamics::conditions_at`], bit for bit, without its heat flux and g-load.
    #[must_use]
    pub fn aero_accelerations_at(&self, y: &[f64; STATE_LEN], att: Command<f64>) -> (f64, f64) {
        let (altitude_m, airspeed_m_s) = self.altitude_airspeed(y);
        let a = self.aero(altitude_m, airspeed_m_s, att.alpha_rad);
        let m = self.vehicle.mass_kg;
        (a.lift.abs() / m, a.drag.abs() / m)
    }

    /// Time derivative of the Cartesian state `[r, v, Q, theta]` (inertial frame) under
    /// attitude `att`. Returns the derivative and the flight conditions used.
    #[must_use]
    pub fn cartesian_rhs(
        &self,
        y: &[f64; STATE_LEN],
        att: Command<f64>,
    ) -> ([f64; STATE_LEN], FlightConditions) {
        let fc = self.conditions_at(y, att);
        (self.cartesian_derivative(y, att, &mut self.rhs_cache()), fc)
    }

    /// Air data, forces and heat flux at an integrated state `y` under angle of attack
    /// `alpha_rad`: the cache's last point if it is this one, else computed (as
    /// [`Dynamics::conditions_at`] computes them) and kept as the last point.
    #[inline]
    fn point<'c>(
        &self,
        y: &[f64; STATE_LEN],
        alpha_rad: f64,
        cache: &'c mut RhsCache,
    ) -> &'c PointAero {
        let key = point_key(y, alpha_rad);
        // Branch-free word comparison (an array comparison calls `memcmp`).
        let hit = cache
            .last_key
            .is_some_and(|k| k.iter().zip(&key).fold(0, |d, (a, b)| d | (a ^ b)) == 0);
        if !hit {
            let (altitude_m, vr) = self.altitude_airspeed(y);
            let aero = self.aero(altitude_m, vr, alpha_rad);
            cache.last = PointAero {
                airspeed_m_s: vr,
                aero,
                heat_flux_w_m2: cache.heat_flux.heat_flux_w_m2(aero.rho, vr),
            };
            cache.last_key = Some(key);
        }
        &cache.last
    }

    /// Stagnation heat flux \[W/m^2\] (as the right-hand side computes it,
    /// [`crate::env::NoseHeatFlux`]) and g-load \[-\] at an integrated state `y` under `att`:
    /// what the loop's peak monitors need after every step, without the rest of
    /// [`Dynamics::conditions_at`]. The g-load is that of `conditions_at`, bit for bit.
    /// `cache` must come from [`Dynamics::rhs_cache`] of this `Dynamics`.
    #[must_use]
    pub fn heat_flux_and_g_load(
        &self,
        y: &[f64; STATE_LEN],
        att: Command<f64>,
        cache: &mut RhsCache,
    ) -> (f64, f64) {
        let p = self.point(y, att.alpha_rad, cache);
        (
            p.heat_flux_w_m2,
            guidance_core::monitor::g_load(p.aero.lift, p.aero.drag, self.vehicle.mass_kg),
        )
    }

    /// [`Dynamics::conditions_at`] through the right-hand side's cache (the same values, bit
    /// for bit; computed only if the cache's last point is another one). `cache` must come
    /// from [`Dynamics::rhs_cache`] of this `Dynamics`.
    #[must_use]
    pub fn conditions_at_cached(
        &self,
        y: &[f64; STATE_LEN],
        att: Command<f64>,
        cache: &mut RhsCache,
    ) -> FlightConditions {
        let p = *self.point(y, att.alpha_rad, cache);
        let a = p.aero;
        FlightConditions {
            altitude_m: Vector3::new(y[0], y[1], y[2]).norm() - self.planet.radius_m,
            density_kg_m3: a.rho,
            airspeed_m_s: p.airspeed_m_s,
            mach: a.mach,
            dynamic_pressure_pa: a.q_dyn,
            cl: a.cl,
            cd: a.cd,
            lift_n: a.lift,
            drag_n: a.drag,
            heat_flux_w_m2: p.heat_flux_w_m2,
            g_load: guidance_core::monitor::g_load(a.lift, a.drag, self.vehicle.mass_kg),
        }
    }

    /// The constants and the caches of [`Dynamics::cartesian_derivative`].
    #[must_use]
    pub fn rhs_cache(&self) -> RhsCache {
        RhsCache {
            heat_flux: self.heat_flux.at_nose(self.vehicle.nose_radius_m),
            sigma_rad: 0.0,
            sin_cos: (0.0, 1.0),
            last_key: None,
            last: PointAero {
                airspeed_m_s: f64::NAN,
                aero: Aero {
                    rho: f64::NAN,
                    mach: f64::NAN,
                    q_dyn: f64::NAN,
                    cl: f64::NAN,
                    cd: f64::NAN,
                    lift: f64::NAN,
                    drag: f64::NAN,
                },
                heat_flux_w_m2: f64::NAN,
            },
        }
    }

    /// Time derivative of the Cartesian state `[r, v, Q, theta]` (inertial frame) under
    /// attitude `att`: what the simulator integrates ([`Dynamics::cartesian_rhs`] without
    /// the flight conditions, which it does not need). The heat-load rate comes from
    /// [`crate::env::NoseHeatFlux`] (host `powf`, within a few ulp of the core's Chapman
    /// value). `cache` must come from [`Dynamics::rhs_cache`] of this `Dynamics`.
    #[must_use]
    pub fn cartesian_derivative(
        &self,
        y: &[f64; STATE_LEN],
        att: Command<f64>,
        cache: &mut RhsCache,
    ) -> [f64; STATE_LEN] {
        let (vr, q_dyn, lift, drag, q) = {
            let p = self.point(y, att.alpha_rad, cache);
            let a = &p.aero;
            (p.airspeed_m_s, a.q_dyn, a.lift, a.drag, p.heat_flux_w_m2)
        };
        let r = Vector3::new(y[0], y[1], y[2]);
        let v = Vector3::new(y[3], y[4], y[5]);
        let rn = r.norm();
        let rhat = r / rn;
        let v_rel = v - self.omega().cross(&r);
        let mut a = self.gravity.acceleration(&r);
        let mut theta_dot = 0.0;
        if vr > 0.0 {
            let vhat = v_rel / vr;
            let m = self.vehicle.mass_kg;
            if q_dyn > 0.0 {
                if att.sigma_rad.to_bits() != cache.sigma_rad.to_bits() {
                    cache.sigma_rad = att.sigma_rad;
                    cache.sin_cos = att.sigma_rad.sin_cos();
                }
                a +=
                    lift_direction_sc(&rhat, &vhat, cache.sin_cos) * (lift / m) - vhat * (drag / m);
            }
            // Horizontal planet-relative speed over r.
            theta_dot = (v_rel - rhat * v_rel.dot(&rhat)).norm() / rn;
        }
        [v.x, v.y, v.z, a.x, a.y, a.z, q, theta_dot]
    }

    /// Time derivative of the planet-relative spherical state `[r, tau, delta, V, gamma, chi]`
    /// (eq. 3.13 with the ERRATA fixes, gravity split into radial and northward components).
    #[must_use]
    pub fn spherical_rhs(&self, s: &[f64; 6], att: Command<f64>) -> [f64; 6] {
        let [r, tau, delta, v, gamma, chi] = *s;
        let w = self.planet.rotation_rate_rad_s;
        let (up, _east, north) = local_axes(tau, delta);
        let g = self.gravity.acceleration(&(up * r));
        let g_r = -g.dot(&up); // positive towards the centre
        let g_n = g.dot(&north); // positive northwards
        let fc = self.conditions(r - self.planet.radius_m, v, att);
        let m = self.vehicle.mass_kg;
        let (l, d) = (fc.lift_n / m, fc.drag_n / m);
        let (sg, cg) = gamma.sin_cos();
        let (sc, cc) = chi.sin_cos();
        let (sd, cd) = delta.sin_cos();
        let (ss, cs) = att.sigma_rad.sin_cos();
        let r_dot = v * sg;
        let tau_dot = v * cg * sc / (r * cd);
        let delta_dot = v * cg * cc / r;
        let v_dot = -d - g_r * sg + g_n * cg * cc + w * w * r * cd * (sg * cd - cg * sd * cc);
        let gamma_dot = (l * cs - g_r * cg - g_n * sg * cc
            + 2.0 * w * v * cd * sc
            + v * v / r * cg
            + w * w * r * cd * (cd * cg + sg * sd * cc))
            / v;
        let chi_dot = (l * ss - g_n * sc
            + 2.0 * w * v * (sd * cg - cd * sg * cc)
            + v * v / r * cg * cg * sd / cd * sc
            + w * w * r * cd * sd * sc)
            / (v * cg);
        [r_dot, tau_dot, delta_dot, v_dot, gamma_dot, chi_dot]
    }

    /// Initial integrated state `[r, v, 0, 0]` from a planet-relative spherical state at
    /// time `t_s`.
    #[must_use]
    pub fn initial_state(&self, s: &SphericalState, t_s: f64) -> [f64; STATE_LEN] {
        let c = spherical_to_cartesian(s, &self.planet, t_s);
        [
            c.position_m.x,
            c.position_m.y,
            c.position_m.z,
            c.velocity_m_s.x,
            c.velocity_m_s.y,
            c.velocity_m_s.z,
            0.0,
            0.0,
        ]
    }

    /// Planet-relative spherical state of an integrated state `y` at time `t_s`.
    #[must_use]
    pub fn spherical_of(&self, y: &[f64; STATE_LEN], t_s: f64) -> SphericalState {
        cartesian_to_spherical(&cartesian_of(y), &self.planet, t_s)
    }
}

#[cfg(test)]
mod tests;
