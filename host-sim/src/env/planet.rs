//! Planet constants: a spherical planet, rotating or not (thesis sec. 3.6.4: spherical Earth).
//!
//! Earth constants ([`Planet::earth`]): mu = 3.986004418e14 m^3/s^2 and R = 6 378 137 m (the
//! same values as `guidance_core::energy`, so E-hat agrees between the core and the
//! simulator), omega = 7.292115e-5 rad/s (WGS84/IERS), J2 = 1.0826267e-3 (EGM96/EGM2008
//! value). The thesis prints only J2 = 0.00108263 (eq. 3.101, from Wertz 2001), which is this
//! value rounded to six digits; it does not print mu, R or omega (they came from the Tudat
//! toolbox defaults).

/// A spherical planet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Planet {
    /// Gravitational parameter mu [m^3/s^2].
    pub mu_m3_s2: f64,
    /// Radius of the sphere \[m\]; altitude is measured from it.
    pub radius_m: f64,
    /// Rotation rate about +z [rad/s]; 0 for a non-rotating planet.
    pub rotation_rate_rad_s: f64,
    /// Second zonal harmonic J2 [-] (used only by the J2 gravity model).
    pub j2: f64,
}

/// Earth's rotation rate [rad/s] (the core's constant).
pub use guidance_core::energy::EARTH_ROTATION_RATE_RAD_S;
/// Earth's second zonal harmonic J2 [-].
pub const EARTH_J2: f64 = 1.082_626_7e-3;

impl Planet {
    /// Rotating spherical Earth (constants in the module documentation).
    #[must_use]
    pub fn earth() -> Self {
        Self {
            mu_m3_s2: guidance_core::energy::EARTH_MU_M3_S2,
            radius_m: guidance_core::energy::EARTH_RADIUS_M,
            rotation_rate_rad_s: EARTH_ROTATION_RATE_RAD_S,
            j2: EARTH_J2,
        }
    }

    /// Rotating spherical Mars (NASA Mars fact sheet): mu = 4.2828e13 m^3/s^2, volumetric
    /// mean radius 3389.5 km, J2 = 1.96045e-3, sidereal day 24.6229 h (omega = 7.0882e-5
    /// rad/s).
    #[must_use]
    pub fn mars() -> Self {
        Self {
            mu_m3_s2: 4.282_8e13,
            radius_m: 3_389_500.0,
            rotation_rate_rad_s: std::f64::consts::TAU / (24.6229 * 3600.0),
            j2: 1.960_45e-3,
        }
    }

    /// Non-rotating spherical Earth (same mu, R and J2; omega = 0), as in the analytical
    /// solutions and the thesis' "simplified" numerical environment (sec. 8.1.3).
    #[must_use]
    pub fn earth_non_rotating() -> Self {
        Self {
            rotation_rate_rad_s: 0.0,
            ..Self::earth()
        }
    }

    /// The same planet without rotation.
    #[must_use]
    pub fn without_rotation(self) -> Self {
        Self {
            rotation_rate_rad_s: 0.0,
            ..self
        }
    }

    /// Whether the planet rotates.
    #[must_use]
    pub fn is_rotating(&self) -> bool {
        self.rotation_rate_rad_s != 0.0
    }

    /// Radial distance \[m\] of a point at `altitude_m` above the sphere.
    #[must_use]
    pub fn radius_at_altitude_m(&self, altitude_m: f64) -> f64 {
        self.radius_m + altitude_m
    }

    /// Altitude \[m\] above the sphere of a point at radial distance `r_m`.
    #[must_use]
    pub fn altitude_m(&self, r_m: f64) -> f64 {
        r_m - self.radius_m
    }

    /// Surface gravity of the central field mu/R^2 [m/s^2].
    #[must_use]
    pub fn surface_gravity_m_s2(&self) -> f64 {
        self.mu_m3_s2 / (self.radius_m * self.radius_m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets() {
        let e = Planet::earth();
        assert!(e.is_rotating());
        assert_eq!(e.radius_m, 6_378_137.0);
        assert_eq!(e.mu_m3_s2, 3.986_004_418e14);
        // Thesis eq. 3.101 value to its printed precision.
        assert!((e.j2 - 0.001_082_63).abs() < 5e-9);
        let n = Planet::earth_non_rotating();
        assert!(!n.is_rotating());
        assert_eq!(n.radius_m, e.radius_m);
        assert_eq!(e.without_rotation(), n);
        assert!((e.altitude_m(e.radius_at_altitude_m(122_000.0)) - 122_000.0).abs() < 1e-6);
        assert!((e.surface_gravity_m_s2() - 9.798).abs() < 1e-3);
    }
}
