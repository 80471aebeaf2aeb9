//! Isothermal exponential atmosphere, rho = rho_0 exp(-(h - h_ref)/H_s) (thesis eq. 3.89,
//! generalised with a reference altitude). This is the atmosphere of the analytical (Vinh)
//! solutions.
//!
//! The temperature is the isothermal temperature consistent with the scale height,
//! T = g0 H_s / R_air (R_air = R*/M0 = 287.05 J/(kg K)); for H_s = 7.2 km that is 246.0 K.
//! Pressure is p = rho R_air T and the speed of sound a = sqrt(1.4 R_air T).
//! The model has no top: density decays without bound. Below 0 m the 0 m values are held
//! (as the [`Atmosphere`] contract says); a NaN altitude gives a NaN state.

use super::us76::{G0_M_S2, GAMMA_AIR, M0_KG_KMOL, R_STAR_J_KMOL_K};
use super::{Atmosphere, AtmosphereState};

/// Specific gas constant of air R*/M0 [J/(kg K)].
pub const R_AIR_J_KG_K: f64 = R_STAR_J_KMOL_K / M0_KG_KMOL;
/// Default sea-level density [kg/m^3] (the US76 sea-level value, also the thesis' rho_0 in
/// the Chapman heat-flux relation).
pub const DEFAULT_RHO0_KG_M3: f64 = 1.225;
/// Default scale height \[m\]. The thesis does not print its H_s; 7.2 km is the common Earth
/// value (e.g. the default exponential Earth atmosphere of the Tudat toolbox the thesis used).
pub const DEFAULT_SCALE_HEIGHT_M: f64 = 7_200.0;

/// A parameter of [`ExponentialAtmosphere::new`] that is not finite and positive (or, for
/// the reference altitude, not finite).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error(
    "exponential atmosphere: parameter `{parameter}` = {}: {reason}",
    crate::num_fmt::Compact(*value)
)]
pub struct ExponentialAtmosphereError {
    /// Parameter name (`rho0_kg_m3`, `scale_height_m`, `reference_altitude_m`).
    pub parameter: &'static str,
    /// The rejected value.
    pub value: f64,
    /// What is required.
    pub reason: &'static str,
}

/// Isothermal exponential atmosphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExponentialAtmosphere {
    rho0_kg_m3: f64,
    scale_height_m: f64,
    reference_altitude_m: f64,
}

impl ExponentialAtmosphere {
    /// rho(h) = `rho0_kg_m3` exp(-(h - `reference_altitude_m`) / `scale_height_m`).
    ///
    /// # Errors
    /// If `rho0_kg_m3` or `scale_height_m` is not finite and positive, or
    /// `reference_altitude_m` is not finite.
    pub fn new(
        rho0_kg_m3: f64,
        scale_height_m: f64,
        reference_altitude_m: f64,
    ) -> Result<Self, ExponentialAtmosphereError> {
        let positive = |parameter, value: f64| {
            if value.is_finite() && value > 0.0 {
                Ok(())
            } else {
                Err(ExponentialAtmosphereError {
                    parameter,
                    value,
                    reason: "must be finite and positive",
                })
            }
        };
        positive("rho0_kg_m3", rho0_kg_m3)?;
        positive("scale_height_m", scale_height_m)?;
        if !reference_altitude_m.is_finite() {
            return Err(ExponentialAtmosphereError {
                parameter: "reference_altitude_m",
                value: reference_altitude_m,
                reason: "must be finite",
            });
        }
        Ok(Self {
            rho0_kg_m3,
            scale_height_m,
            reference_altitude_m,
        })
    }

    /// Earth default: rho_0 = 1.225 kg/m^3 at 0 m, H_s = 7.2 km.
    #[must_use]
    pub fn earth() -> Self {
        Self {
            rho0_kg_m3: DEFAULT_RHO0_KG_M3,
            scale_height_m: DEFAULT_SCALE_HEIGHT_M,
            reference_altitude_m: 0.0,
        }
    }

    /// The exponential atmosphere through two (altitude, density) points: H_s =
    /// (h2 - h1) / ln(rho1/rho2), reference altitude h1, rho_0 = rho1. Useful to match another
    /// model (e.g. US76) over the altitude band an analytical solution covers.
    ///
    /// # Errors
    /// If a density is not finite and positive, or the points do not give a finite positive
    /// scale height (density must decrease with altitude).
    pub fn through_points(
        (h1_m, rho1_kg_m3): (f64, f64),
        (h2_m, rho2_kg_m3): (f64, f64),
    ) -> Result<Self, ExponentialAtmosphereError> {
        for (parameter, value) in [("rho1_kg_m3", rho1_kg_m3), ("rho2_kg_m3", rho2_kg_m3)] {
            if !(value.is_finite() && value > 0.0) {
                return Err(ExponentialAtmosphereError {
                    parameter,
                    value,
                    reason: "must be finite and positive",
                });
            }
        }
        let scale_height_m = (h2_m - h1_m) / (rho1_kg_m3 / rho2_kg_m3).ln();
        Self::new(rho1_kg_m3, scale_height_m, h1_m)
    }

    /// The exponential atmosphere matching `atmosphere`'s density at `h1_m` and `h2_m` \[m\]
    /// (see [`ExponentialAtmosphere::through_points`]).
    ///
    /// # Errors
    /// As [`ExponentialAtmosphere::through_points`].
    pub fn fitted_to(
        atmosphere: &dyn Atmosphere,
        h1_m: f64,
        h2_m: f64,
    ) -> Result<Self, ExponentialAtmosphereError> {
        Self::through_points(
            (h1_m, atmosphere.density_kg_m3(h1_m)),
            (h2_m, atmosphere.density_kg_m3(h2_m)),
        )
    }

    /// Density at the reference altitude [kg/m^3].
    #[must_use]
    pub fn rho0_kg_m3(&self) -> f64 {
        self.rho0_kg_m3
    }

    /// Scale height H_s \[m\].
    #[must_use]
    pub fn scale_height_m(&self) -> f64 {
        self.scale_height_m
    }

    /// Reference altitude \[m\] at which the density is rho_0.
    #[must_use]
    pub fn reference_altitude_m(&self) -> f64 {
        self.reference_altitude_m
    }

    /// Isothermal temperature consistent with the scale height, g0 H_s / R_air \[K\].
    #[must_use]
    pub fn temperature_k(&self) -> f64 {
        G0_M_S2 * self.scale_height_m / R_AIR_J_KG_K
    }
}

impl Default for ExponentialAtmosphere {
    fn default() -> Self {
        Self::earth()
    }
}

impl Atmosphere for ExponentialAtmosphere {
    fn state(&self, altitude_m: f64) -> AtmosphereState {
        let rho = self.density_kg_m3(altitude_m);
        let t = self.temperature_k();
        AtmosphereState {
            temperature_k: t,
            pressure_pa: rho * R_AIR_J_KG_K * t,
            density_kg_m3: rho,
            speed_of_sound_m_s: (GAMMA_AIR * R_AIR_J_KG_K * t).sqrt(),
        }
    }

    fn density_kg_m3(&self, altitude_m: f64) -> f64 {
        // f64::max(NaN, 0) would return 0: keep NaN visible instead.
        let h = if altitude_m.is_nan() {
            altitude_m
        } else {
            altitude_m.max(0.0)
        };
        self.rho0_kg_m3 * (-(h - self.reference_altitude_m) / self.scale_height_m).exp()
    }

    fn name(&self) -> &'static str {
        "exponential"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn density_follows_the_exponential_law() {
        let atm = ExponentialAtmosphere::new(2.0e-4, 6_500.0, 60_000.0).unwrap();
        assert_eq!(atm.density_kg_m3(60_000.0), 2.0e-4);
        let r = atm.density_kg_m3(66_500.0) / atm.density_kg_m3(60_000.0);
        assert!((r - (-1.0f64).exp()).abs() < 1e-14);
        // Below the reference altitude the density grows.
        assert!(atm.density_kg_m3(50_000.0) > 2.0e-4);
    }

    #[test]
    fn isothermal_temperature_matches_scale_height() {
        let atm = ExponentialAtmosphere::earth();
        // Hydrostatic isothermal: H = R T / g0  ->  T = 246.0 K for H = 7.2 km.
        assert!((atm.temperature_k() - 245.98).abs() < 0.05);
        let s = atm.state(10_000.0);
        assert!(
            (s.pressure_pa / (s.density_kg_m3 * R_AIR_J_KG_K * s.temperature_k) - 1.0).abs()
                < 1e-12
        );
    }

    #[test]
    fn rejects_bad_parameters_naming_them() {
        let e = ExponentialAtmosphere::new(1.2, -7.0, 0.0).unwrap_err();
        assert_eq!(e.parameter, "scale_height_m");
        assert!(e.to_string().contains("`scale_height_m` = -7"), "{e}");
        assert!(ExponentialAtmosphere::new(f64::NAN, 7.0, 0.0).is_err());
        assert!(ExponentialAtmosphere::new(1.2, 7.0, f64::INFINITY).is_err());
    }

    #[test]
    fn through_points_and_fit_to_us76() {
        let a =
            ExponentialAtmosphere::through_points((0.0, 1.0), (7_000.0, (-1.0f64).exp())).unwrap();
        assert!((a.scale_height_m() - 7_000.0).abs() < 1e-9);
        let us76 = super::super::Us76::new();
        let fit = ExponentialAtmosphere::fitted_to(&us76, 60_000.0, 80_000.0).unwrap();
        for h in [60_000.0, 80_000.0] {
            let r = fit.density_kg_m3(h) / us76.density_kg_m3(h);
            assert!((r - 1.0).abs() < 1e-12, "{h}");
        }
        // Density increasing with altitude gives a negative scale height: rejected.
        assert!(ExponentialAtmosphere::through_points((0.0, 1.0), (1.0, 2.0)).is_err());
        assert!(ExponentialAtmosphere::through_points((0.0, 0.0), (1.0, 2.0)).is_err());
    }

    #[test]
    fn below_zero_holds_zero_and_nan_propagates() {
        let atm = ExponentialAtmosphere::earth();
        assert_eq!(atm.density_kg_m3(-50.0), atm.density_kg_m3(0.0));
        assert!(atm.density_kg_m3(f64::NAN).is_nan());
    }
}
