//! Planet constants (interface; presets in progress).

/// A spherical planet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Planet {
    /// Gravitational parameter mu [m^3/s^2].
    pub mu_m3_s2: f64,
    /// Radius of the sphere [m]; altitude is measured from it.
    pub radius_m: f64,
    /// Rotation rate about +z [rad/s]; 0 for a non-rotating planet.
    pub rotation_rate_rad_s: f64,
    /// Second zonal harmonic J2 [-] (used only by the J2 gravity model).
    pub j2: f64,
}
