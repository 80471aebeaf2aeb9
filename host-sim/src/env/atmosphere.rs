//! Atmosphere models: the [`Atmosphere`] trait, the U.S. Standard Atmosphere 1976 from 0 to
//! 1000 km ([`Us76`]) and the exponential atmosphere of the analytical solutions
//! ([`ExponentialAtmosphere`]); thesis sec. 3.6.2.

pub mod exponential;
pub mod table;
pub mod us76;

pub use exponential::{ExponentialAtmosphere, ExponentialAtmosphereError};
pub use table::{TableAtmosphereError, TabulatedAtmosphere};
pub use us76::Us76;

/// Atmospheric state at one altitude.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AtmosphereState {
    /// Kinetic temperature \[K\].
    pub temperature_k: f64,
    /// Pressure \[Pa\].
    pub pressure_pa: f64,
    /// Density [kg/m^3].
    pub density_kg_m3: f64,
    /// Speed of sound [m/s].
    pub speed_of_sound_m_s: f64,
}

/// An atmosphere model: properties as a function of geometric altitude above the sphere.
pub trait Atmosphere: Send + Sync {
    /// Properties at geometric altitude `altitude_m` \[m\]. Below 0 m the model holds its 0 m
    /// values; above its top it returns zero density and pressure.
    fn state(&self, altitude_m: f64) -> AtmosphereState;
    /// Density only [kg/m^3] (may be faster than [`Atmosphere::state`]).
    fn density_kg_m3(&self, altitude_m: f64) -> f64 {
        self.state(altitude_m).density_kg_m3
    }
    /// Short model name for reports (e.g. `"us76"`, `"exponential"`).
    fn name(&self) -> &'static str {
        "atmosphere"
    }
}
