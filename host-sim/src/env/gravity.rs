//! Gravity models: central field ([`CentralGravity`]) and central field plus the J2 zonal
//! harmonic ([`J2Gravity`]); thesis sec. 3.6.5.
//!
//! # J2 derivation (checked against thesis eq. 3.100)
//!
//! Potential (sign convention: acceleration = -grad U):
//!
//! U = -mu/r [1 - J2 (R/r)^2 P2(sin phi)],  P2(s) = (3 s^2 - 1)/2,  sin phi = z/r,
//!
//! so U = -mu/r + (mu J2 R^2 / 2) (3 z^2 r^-5 - r^-3). Taking -grad U:
//!
//! a = -mu r_vec / r^3 + (mu J2 R^2 / 2) r^-5 [ (15 z^2/r^2 - 3) r_vec - 6 z e_z ],
//!
//! i.e. the textbook components a_x = -(3/2) J2 mu R^2 x / r^5 (1 - 5 z^2/r^2) (same for y)
//! and a_z = -(3/2) J2 mu R^2 z / r^5 (3 - 5 z^2/r^2). Projected on the local vertical and on
//! the local north direction:
//!
//! * radial (positive towards the centre): g_r = mu/r^2 [1 - (3/2) J2 (R/r)^2 (3 sin^2 phi - 1)],
//! * northward: g_phi = -3 mu/r^2 J2 (R/r)^2 sin phi cos phi (pointing towards the equator),
//!
//! which is thesis eq. 3.100 with g_r taken positive downward and g_delta positive north: the
//! printed equation is correct. The longitudinal component is zero (axisymmetric field).
//! Tests: `validate_j2_*` in `tests/it/env_validation.rs` (closed forms at pole/equator and
//! finite-difference gradient of [`J2Gravity::potential_m2_s2`]).

use super::planet::Planet;
use nalgebra::Vector3;

/// A gravity model in the planet-centred frame (inertial or rotating: the field is
/// axisymmetric about the z axis, so it is the same in both).
pub trait Gravity: Send + Sync {
    /// Gravitational acceleration [m/s^2] at position `r_m` \[m\] (z axis = rotation axis).
    fn acceleration(&self, r_m: &Vector3<f64>) -> Vector3<f64>;
    /// Gravitational potential U [m^2/s^2] with acceleration = -grad U (zero at infinity).
    /// Default: not provided (NaN); both models here implement it.
    fn potential_m2_s2(&self, r_m: &Vector3<f64>) -> f64 {
        let _ = r_m;
        f64::NAN
    }
    /// Short model name for reports (`"central"`, `"j2"`).
    fn name(&self) -> &'static str {
        "gravity"
    }
}

/// Point-mass (central) field, a = -mu r / |r|^3 (thesis eq. 3.97-3.98).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CentralGravity {
    /// Gravitational parameter mu [m^3/s^2].
    pub mu_m3_s2: f64,
}

impl CentralGravity {
    /// Central field of gravitational parameter `mu_m3_s2`.
    #[must_use]
    pub fn new(mu_m3_s2: f64) -> Self {
        Self { mu_m3_s2 }
    }

    /// Central field of `planet`.
    #[must_use]
    pub fn from_planet(planet: &Planet) -> Self {
        Self::new(planet.mu_m3_s2)
    }
}

impl Gravity for CentralGravity {
    fn acceleration(&self, r_m: &Vector3<f64>) -> Vector3<f64> {
        let r2 = r_m.norm_squared();
        let r = r2.sqrt();
        -r_m * (self.mu_m3_s2 / (r2 * r))
    }

    fn potential_m2_s2(&self, r_m: &Vector3<f64>) -> f64 {
        -self.mu_m3_s2 / r_m.norm()
    }

    fn name(&self) -> &'static str {
        "central"
    }
}

/// Central field plus the J2 zonal term (see the module documentation for the derivation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct J2Gravity {
    /// Gravitational parameter mu [m^3/s^2].
    pub mu_m3_s2: f64,
    /// Reference (equatorial) radius R of the J2 coefficient \[m\].
    pub reference_radius_m: f64,
    /// Second zonal harmonic J2 [-].
    pub j2: f64,
}

impl J2Gravity {
    /// J2 field with the given constants.
    #[must_use]
    pub fn new(mu_m3_s2: f64, reference_radius_m: f64, j2: f64) -> Self {
        Self {
            mu_m3_s2,
            reference_radius_m,
            j2,
        }
    }

    /// J2 field of `planet` (its mu, radius and J2).
    #[must_use]
    pub fn from_planet(planet: &Planet) -> Self {
        Self::new(planet.mu_m3_s2, planet.radius_m, planet.j2)
    }

    /// Radial (positive towards the centre) and northward components [m/s^2] at radius
    /// `r_m` \[m\] and geocentric latitude `latitude_rad` (thesis eq. 3.100: g_r, g_delta).
    #[must_use]
    pub fn radial_and_north_components(&self, r_m: f64, latitude_rad: f64) -> (f64, f64) {
        let g0 = self.mu_m3_s2 / (r_m * r_m);
        let q = self.j2 * (self.reference_radius_m / r_m).powi(2);
        let (s, c) = latitude_rad.sin_cos();
        let g_r = g0 * (1.0 - 1.5 * q * (3.0 * s * s - 1.0));
        let g_north = -3.0 * g0 * q * s * c;
        (g_r, g_north)
    }
}

impl Gravity for J2Gravity {
    fn acceleration(&self, r_m: &Vector3<f64>) -> Vector3<f64> {
        let r2 = r_m.norm_squared();
        let r = r2.sqrt();
        let central = -r_m * (self.mu_m3_s2 / (r2 * r));
        let z = r_m.z;
        let c = 0.5 * self.mu_m3_s2 * self.j2 * self.reference_radius_m * self.reference_radius_m
            / (r2 * r2 * r);
        let radial_factor = 15.0 * z * z / r2 - 3.0;
        let j2 = Vector3::new(
            c * radial_factor * r_m.x,
            c * radial_factor * r_m.y,
            c * (radial_factor * z - 6.0 * z),
        );
        central + j2
    }

    fn potential_m2_s2(&self, r_m: &Vector3<f64>) -> f64 {
        let r = r_m.norm();
        let s = r_m.z / r;
        let p2 = 0.5 * (3.0 * s * s - 1.0);
        -self.mu_m3_s2 / r * (1.0 - self.j2 * (self.reference_radius_m / r).powi(2) * p2)
    }

    fn name(&self) -> &'static str {
        "j2"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_j2_equals_central() {
        let p = Planet::earth();
        let c = CentralGravity::from_planet(&p);
        let j = J2Gravity::new(p.mu_m3_s2, p.radius_m, 0.0);
        let r = Vector3::new(3.0e6, -4.0e6, 2.5e6);
        assert!((c.acceleration(&r) - j.acceleration(&r)).norm() < 1e-15);
    }

    #[test]
    fn cartesian_matches_eq_3_100_projection_at_mid_latitude() {
        let g = J2Gravity::from_planet(&Planet::earth());
        let (lat, lon, r) = (0.7_f64, -1.2_f64, 6.5e6);
        let pos = Vector3::new(
            r * lat.cos() * lon.cos(),
            r * lat.cos() * lon.sin(),
            r * lat.sin(),
        );
        let a = g.acceleration(&pos);
        let up = pos / r;
        let north = Vector3::new(-lat.sin() * lon.cos(), -lat.sin() * lon.sin(), lat.cos());
        let east = Vector3::new(-lon.sin(), lon.cos(), 0.0);
        let (g_r, g_n) = g.radial_and_north_components(r, lat);
        assert!((-a.dot(&up) - g_r).abs() < 1e-12);
        assert!((a.dot(&north) - g_n).abs() < 1e-12);
        assert!(a.dot(&east).abs() < 1e-12);
    }
}
