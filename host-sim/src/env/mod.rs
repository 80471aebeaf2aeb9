//! Environment models: atmosphere, gravity, planet, and the [`Environment`] bundle the
//! dynamics use.
//!
//! The traits here are the seams between the environment and the dynamics; implementations
//! live in the submodules.
//!
//! * [`Environment::full`]: rotating spherical Earth, US76 atmosphere, central + J2 gravity
//!   (the thesis' high-fidelity environment, sec. 7.4).
//! * [`Environment::simplified`]: non-rotating spherical Earth, exponential atmosphere,
//!   central gravity: the environment of the analytical solutions (thesis sec. 8.1.3,
//!   "simplified numerical simulator").

pub mod atmosphere;
pub mod gravity;
pub mod heat_flux;
pub mod planet;

pub use atmosphere::{
    Atmosphere, AtmosphereState, ExponentialAtmosphere, TableAtmosphereError, TabulatedAtmosphere,
    Us76,
};
pub use gravity::{CentralGravity, Gravity, J2Gravity};
pub use heat_flux::{ChapmanHeatFlux, HeatFluxError, NoseHeatFlux};
pub use planet::Planet;

/// The environment presets: the one list, used by scenarios and by the analytical comparison.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Preset {
    /// Non-rotating sphere, central gravity, an exponential atmosphere (the closed forms'
    /// assumptions, thesis sec. 8.1.3).
    Simplified,
    /// Rotating sphere, US76, central + J2 gravity (thesis sec. 7.4).
    Full,
}

impl Preset {
    /// Short name for files, columns and scenario files.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Preset::Simplified => "simplified",
            Preset::Full => "full",
        }
    }
}

/// A complete environment: planet, atmosphere and gravity model.
pub struct Environment {
    /// Planet (radius, rotation, constants).
    pub planet: Planet,
    /// Atmosphere model.
    pub atmosphere: Box<dyn Atmosphere>,
    /// Gravity model.
    pub gravity: Box<dyn Gravity>,
    /// Chapman heat-flux constants (default: the thesis', [`ChapmanHeatFlux::thesis`]).
    pub heat_flux: ChapmanHeatFlux,
}

impl Environment {
    /// Rotating spherical Earth, US76, central + J2 gravity.
    #[must_use]
    pub fn full() -> Self {
        let planet = Planet::earth();
        Self {
            planet,
            atmosphere: Box::new(Us76::new()),
            gravity: Box::new(J2Gravity::from_planet(&planet)),
            heat_flux: ChapmanHeatFlux::thesis(),
        }
    }

    /// Non-rotating spherical Earth, the given exponential atmosphere, central gravity.
    #[must_use]
    pub fn simplified(atmosphere: ExponentialAtmosphere) -> Self {
        let planet = Planet::earth_non_rotating();
        Self {
            planet,
            atmosphere: Box::new(atmosphere),
            gravity: Box::new(CentralGravity::from_planet(&planet)),
            heat_flux: ChapmanHeatFlux::thesis(),
        }
    }

    /// [`Environment::simplified`] with the default Earth exponential atmosphere
    /// (rho_0 = 1.225 kg/m^3, H_s = 7.2 km).
    #[must_use]
    pub fn simplified_default() -> Self {
        Self::simplified(ExponentialAtmosphere::earth())
    }

    /// Any combination.
    #[must_use]
    pub fn new(planet: Planet, atmosphere: Box<dyn Atmosphere>, gravity: Box<dyn Gravity>) -> Self {
        Self {
            planet,
            atmosphere,
            gravity,
            heat_flux: ChapmanHeatFlux::thesis(),
        }
    }
}

impl std::fmt::Debug for Environment {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Environment")
            .field("planet", &self.planet)
            .field("atmosphere", &self.atmosphere.name())
            .field("gravity", &self.gravity.name())
            .finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn presets_bundle_the_right_models() {
        let full = Environment::full();
        assert!(full.planet.is_rotating());
        assert_eq!(full.atmosphere.name(), "us76");
        assert_eq!(full.gravity.name(), "j2");
        let simple = Environment::simplified_default();
        assert!(!simple.planet.is_rotating());
        assert_eq!(simple.atmosphere.name(), "exponential");
        assert_eq!(simple.gravity.name(), "central");
        // Central gravity magnitude mu/r^2 at the surface.
        let r = Vector3::new(0.0, simple.planet.radius_m, 0.0);
        let g = simple.gravity.acceleration(&r).norm();
        assert!((g - simple.planet.surface_gravity_m_s2()).abs() < 1e-12);
        assert!(format!("{full:?}").contains("us76"));
    }
}
