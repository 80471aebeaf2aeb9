//! Gravity models (interface; central and J2 implementations in progress).

use nalgebra::Vector3;

/// A gravity model in the planet-centred frame (inertial or rotating: the field is
/// axisymmetric about the z axis, so it is the same in both).
pub trait Gravity: Send + Sync {
    /// Gravitational acceleration [m/s^2] at position `r_m` [m] (z axis = rotation axis).
    fn acceleration(&self, r_m: &Vector3<f64>) -> Vector3<f64>;
}
