//! Small test-local environment and vehicle models shared by the dynamics and closed-loop
//! tests (written independently of `host_sim::env` so these tests check the integrators and
//! equations of motion, not the environment implementations).

use host_sim::env::{Atmosphere, AtmosphereState, Gravity, Planet};
use host_sim::vehicle::{AeroCoefficients, Aerodynamics, Vehicle, VehicleLimits};
use nalgebra::Vector3;

pub const MU: f64 = 3.986_004_418e14;
pub const RE: f64 = 6_378_137.0;
pub const OMEGA_E: f64 = 7.292_115e-5;
pub const J2: f64 = 1.082_63e-3;

/// Exponential atmosphere rho0 exp(-h/H), isothermal speed of sound; zero above `top_m`.
pub struct ExpAtmo {
    pub rho0: f64,
    pub h_s: f64,
    pub top_m: f64,
}

impl Atmosphere for ExpAtmo {
    fn state(&self, h: f64) -> AtmosphereState {
        let rho = if h > self.top_m {
            0.0
        } else {
            self.rho0 * (-h.max(0.0) / self.h_s).exp()
        };
        AtmosphereState {
            temperature_k: 250.0,
            pressure_pa: rho * 287.05 * 250.0,
            density_kg_m3: rho,
            speed_of_sound_m_s: (1.4_f64 * 287.05 * 250.0).sqrt(),
        }
    }
}

pub struct Central;
impl Gravity for Central {
    fn acceleration(&self, r: &Vector3<f64>) -> Vector3<f64> {
        -r * (MU / r.norm().powi(3))
    }
}

/// J2 gravity from the gradient of U = -mu/r [1 - J2 (R/r)^2 P2(z/r)].
pub struct J2Grav;
impl Gravity for J2Grav {
    fn acceleration(&self, r: &Vector3<f64>) -> Vector3<f64> {
        let rn = r.norm();
        let zr2 = (r.z / rn).powi(2);
        let k = 1.5 * J2 * (RE / rn).powi(2);
        let f = -MU / rn.powi(3);
        Vector3::new(
            f * r.x * (1.0 + k * (1.0 - 5.0 * zr2)),
            f * r.y * (1.0 + k * (1.0 - 5.0 * zr2)),
            f * r.z * (1.0 + k * (3.0 - 5.0 * zr2)),
        )
    }
}

#[derive(Debug)]
pub struct ConstAero {
    pub cl_per_rad: f64,
    pub cd: f64,
}
impl Aerodynamics for ConstAero {
    fn coefficients(&self, _mach: f64, alpha: f64) -> AeroCoefficients {
        AeroCoefficients {
            cl: self.cl_per_rad * alpha,
            cd: self.cd,
        }
    }
}

pub fn vehicle(mass: f64, area: f64, cl_per_rad: f64, cd: f64) -> Vehicle {
    Vehicle {
        name: "test".into(),
        mass_kg: mass,
        reference_area_m2: area,
        nose_radius_m: 0.8,
        limits: VehicleLimits {
            heat_flux_w_m2: 5e5,
            g_load: 3.0,
            g_load_rate_per_s: 0.5,
            alpha_rate_rad_s: 5f64.to_radians(),
            sigma_rate_rad_s: 15f64.to_radians(),
        },
        aero: Box::new(ConstAero { cl_per_rad, cd }),
    }
}

pub fn planet(rotating: bool) -> Planet {
    Planet {
        mu_m3_s2: MU,
        radius_m: RE,
        rotation_rate_rad_s: if rotating { OMEGA_E } else { 0.0 },
        j2: J2,
    }
}
