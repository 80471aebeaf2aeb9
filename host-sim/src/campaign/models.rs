//! The dispersed world of one case: a density scale that varies with altitude (bounded,
//! reproducible) over the scenario's atmosphere, and scaled aerodynamic coefficients.

use crate::env::{Atmosphere, AtmosphereState};
use crate::vehicle::{AeroCoefficients, Aerodynamics, DragPolar};

/// Smallest and largest density scale \[-\].
pub const DENSITY_SCALE_BOUNDS: (f64, f64) = (0.5, 1.5);

/// `rho(h) = k(h) rho_nominal(h)`, `k(h) = clamp(1 + bias + wave sin(2 pi h / lambda + phase),
/// 0.5, 1.5)`: a bias plus an altitude wave, deterministic in its parameters.
pub struct DispersedAtmosphere<'a> {
    /// The scenario's atmosphere.
    pub nominal: &'a dyn Atmosphere,
    /// Density bias (fraction).
    pub bias: f64,
    /// Wave amplitude (fraction).
    pub wave: f64,
    /// Wavelength \[m\].
    pub wavelength_m: f64,
    /// Phase \[rad\].
    pub phase_rad: f64,
}

impl DispersedAtmosphere<'_> {
    /// The density scale at `altitude_m` \[m\], within [`DENSITY_SCALE_BOUNDS`].
    #[must_use]
    pub fn scale(&self, altitude_m: f64) -> f64 {
        let k = 1.0
            + self.bias
            + self.wave
                * (std::f64::consts::TAU * altitude_m / self.wavelength_m + self.phase_rad).sin();
        if k.is_finite() {
            k.clamp(DENSITY_SCALE_BOUNDS.0, DENSITY_SCALE_BOUNDS.1)
        } else {
            1.0
        }
    }
}

impl Atmosphere for DispersedAtmosphere<'_> {
    fn state(&self, altitude_m: f64) -> AtmosphereState {
        let mut s = self.nominal.state(altitude_m);
        s.density_kg_m3 *= self.scale(altitude_m);
        s
    }
    fn density_kg_m3(&self, altitude_m: f64) -> f64 {
        self.nominal.density_kg_m3(altitude_m) * self.scale(altitude_m)
    }
    fn name(&self) -> &'static str {
        "dispersed"
    }
}

/// Lift and drag coefficients scaled by `1 + lift` and `1 + drag`.
#[derive(Debug)]
pub struct DispersedAero {
    /// The vehicle's model.
    pub nominal: Box<dyn Aerodynamics>,
    /// Lift scale `1 + dCL/CL` \[-\].
    pub lift_scale: f64,
    /// Drag scale `1 + dCD/CD` \[-\].
    pub drag_scale: f64,
}

impl Aerodynamics for DispersedAero {
    fn coefficients(&self, mach: f64, alpha_rad: f64) -> AeroCoefficients {
        let c = self.nominal.coefficients(mach, alpha_rad);
        AeroCoefficients {
            cl: c.cl * self.lift_scale,
            cd: c.cd * self.drag_scale,
        }
    }
    fn drag_polar(&self, mach: f64) -> Option<DragPolar> {
        // The guidance's model is the nominal one (onboard knowledge), not the dispersed one.
        self.nominal.drag_polar(mach)
    }
    fn controls_alpha(&self) -> bool {
        self.nominal.controls_alpha()
    }
}
