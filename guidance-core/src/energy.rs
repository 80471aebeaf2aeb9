//! Specific energy and normalised specific energy (thesis sec. 3.7, corrected per ERRATA).
//!
//! E = V^2/2 - mu/r \[J/kg\] (negative for a bound vehicle), and
//! E-hat = (E - E_0) / (E_entry - E_0) with E_0 = -mu/R, the energy of standstill on the
//! surface. E-hat is 1 at entry and 0 at standstill on the surface.
//!
//! For fixed-point use the computation is done in planet units: speed over the surface
//! circular speed `V_c = sqrt(mu/R)` and radius over `R`, so that
//! E-hat = (v^2/2 + 1 - 1/rho) / span with v = V/V_c, rho = r/R and
//! span = (E_entry - E_0)/(mu/R). No quantity larger than a radius in metres is formed.

use crate::error::GuidanceError;
use crate::scalar::Scalar;

/// Earth's gravitational parameter \[m^3/s^2\] (as in the thesis, EGM96/WGS84 value).
pub const EARTH_MU_M3_S2: f64 = 3.986_004_418e14;
/// Earth's mean equatorial radius \[m\] used by the thesis' spherical Earth.
pub const EARTH_RADIUS_M: f64 = 6_378_137.0;
/// Earth rotation rate \[rad/s\] (sidereal; WGS84/IERS), for the re-planner's
/// rotating-planet corrections.
pub const EARTH_ROTATION_RATE_RAD_S: f64 = 7.292_115e-5;

/// Specific mechanical energy E = V^2/2 - mu/r \[J/kg\], in `f64`.
#[must_use]
pub fn specific_energy(mu_m3_s2: f64, radius_m: f64, speed_m_s: f64) -> f64 {
    0.5 * speed_m_s * speed_m_s - mu_m3_s2 / radius_m
}

/// Maps (radius, speed) to normalised energy E-hat, precomputed for one planet and one entry
/// state. Works in any [`Scalar`], including [`crate::Fixed`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct EnergyNormalizer<S> {
    /// Surface circular speed sqrt(mu/R) \[m/s\].
    circular_speed_m_s: S,
    /// Planet radius R \[m\].
    planet_radius_m: S,
    /// 1 / span, span = (E_entry - E_0)/(mu/R) \[-\].
    inv_span: S,
}

impl<S: Scalar> EnergyNormalizer<S> {
    /// Build from planet constants and the entry state that defines E-hat = 1.
    ///
    /// * `mu_m3_s2`: gravitational parameter \[m^3/s^2\]; `planet_radius_m`: R \[m\];
    /// * `entry_radius_m` \[m\], `entry_speed_m_s` \[m/s\].
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] if any input is non-finite or non-positive, the entry
    /// energy is not above the surface standstill energy, or a constant does not fit `S`.
    pub fn new(
        mu_m3_s2: f64,
        planet_radius_m: f64,
        entry_radius_m: f64,
        entry_speed_m_s: f64,
    ) -> Result<Self, GuidanceError> {
        let inputs = [mu_m3_s2, planet_radius_m, entry_radius_m, entry_speed_m_s];
        if inputs.iter().any(|v| !v.is_finite() || *v <= 0.0) {
            return Err(GuidanceError::InvalidConfig);
        }
        let vc2 = mu_m3_s2 / planet_radius_m;
        let span = (specific_energy(mu_m3_s2, entry_radius_m, entry_speed_m_s) + vc2) / vc2;
        if !(span.is_finite() && span > 0.0) {
            return Err(GuidanceError::InvalidConfig);
        }
        Ok(Self {
            circular_speed_m_s: S::from_f64_checked(crate::math::sqrt(vc2))
                .ok_or(GuidanceError::InvalidConfig)?,
            planet_radius_m: S::from_f64_checked(planet_radius_m)
                .ok_or(GuidanceError::InvalidConfig)?,
            inv_span: S::from_f64_checked(1.0 / span).ok_or(GuidanceError::InvalidConfig)?,
        })
    }

    /// The precomputed constants: surface circular speed `sqrt(mu/R)` \[m/s\], planet radius
    /// `R` \[m\], and the inverse energy span \[-\] (what [`EnergyNormalizer::from_parts`]
    /// takes; the set-up image carries them, [`crate::setup::image`]).
    #[must_use]
    pub fn parts(&self) -> [S; 3] {
        [self.circular_speed_m_s, self.planet_radius_m, self.inv_span]
    }

    /// The normaliser of [`EnergyNormalizer::parts`] given in `f64` (each rounded to `S`, as
    /// [`EnergyNormalizer::new`] rounds them: the same normaliser bit for bit).
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] if a part is non-finite, not positive, or does not
    /// fit `S`.
    pub fn from_parts(parts: [f64; 3]) -> Result<Self, GuidanceError> {
        let [c, r, i] = parts;
        let conv = |v: f64| {
            if v.is_finite() && v > 0.0 {
                S::from_f64_checked(v).ok_or(GuidanceError::InvalidConfig)
            } else {
                Err(GuidanceError::InvalidConfig)
            }
        };
        Ok(Self {
            circular_speed_m_s: conv(c)?,
            planet_radius_m: conv(r)?,
            inv_span: conv(i)?,
        })
    }

    /// Normalised energy E-hat \[-\] at `radius_m` \[m\] and `speed_m_s` \[m/s\]. 1 at entry, 0 at
    /// standstill on the surface; not clamped (it can exceed 1 or go below 0).
    ///
    /// # Errors
    /// [`GuidanceError::NonFiniteState`] for non-finite input, [`GuidanceError::UnphysicalState`]
    /// for a non-positive radius.
    pub fn normalized(&self, radius_m: S, speed_m_s: S) -> Result<S, GuidanceError> {
        if !(radius_m.is_finite() && speed_m_s.is_finite()) {
            return Err(GuidanceError::NonFiniteState);
        }
        if radius_m <= S::ZERO {
            return Err(GuidanceError::UnphysicalState);
        }
        let v = speed_m_s / self.circular_speed_m_s;
        let rho = radius_m / self.planet_radius_m;
        let e = (v * v).half() + S::ONE - S::ONE / rho;
        let out = e * self.inv_span;
        if out.is_finite() {
            Ok(out)
        } else {
            Err(GuidanceError::NonFiniteState)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Fixed;

    const R_E: f64 = EARTH_RADIUS_M + 122_000.0;
    const V_E: f64 = 7435.5;

    fn reference(r: f64, v: f64) -> f64 {
        let e0 = -EARTH_MU_M3_S2 / EARTH_RADIUS_M;
        (specific_energy(EARTH_MU_M3_S2, r, v) - e0)
            / (specific_energy(EARTH_MU_M3_S2, R_E, V_E) - e0)
    }

    #[test]
    fn one_at_entry_zero_at_surface_standstill() {
        let n = EnergyNormalizer::<f64>::new(EARTH_MU_M3_S2, EARTH_RADIUS_M, R_E, V_E).unwrap();
        assert!((n.normalized(R_E, V_E).unwrap() - 1.0).abs() < 1e-12);
        assert!(n.normalized(EARTH_RADIUS_M, 0.0).unwrap().abs() < 1e-12);
    }

    #[test]
    fn f32_and_fixed_agree_with_f64_definition() {
        let nf = EnergyNormalizer::<f32>::new(EARTH_MU_M3_S2, EARTH_RADIUS_M, R_E, V_E).unwrap();
        let nx = EnergyNormalizer::<Fixed>::new(EARTH_MU_M3_S2, EARTH_RADIUS_M, R_E, V_E).unwrap();
        for i in 0..=50 {
            let h = 122_000.0 * f64::from(i) / 50.0;
            let v = V_E * f64::from(i) / 50.0;
            let r = EARTH_RADIUS_M + h;
            let want = reference(r, v);
            let got32 = f64::from(nf.normalized(r as f32, v as f32).unwrap());
            let gotx = nx
                .normalized(Fixed::from_f64(r), Fixed::from_f64(v))
                .unwrap()
                .to_f64();
            // f32: radius carries ~0.5 m of rounding, giving |dE-hat| ~ g*0.5/(span*mu/R) ~ 2e-7;
            // the 1 - 1/rho cancellation costs another few ulp of 1.
            assert!(
                (got32 - want).abs() < 2e-6,
                "f32 at h={h}: {got32} vs {want}"
            );
            assert!(
                (gotx - want).abs() < 1e-8,
                "fixed at h={h}: {gotx} vs {want}"
            );
        }
    }

    #[test]
    fn rejects_bad_config_and_state() {
        assert!(EnergyNormalizer::<f64>::new(f64::NAN, 1.0, 1.0, 1.0).is_err());
        assert!(EnergyNormalizer::<f64>::new(EARTH_MU_M3_S2, EARTH_RADIUS_M, 1.0, 0.0).is_err());
        let n = EnergyNormalizer::<f64>::new(EARTH_MU_M3_S2, EARTH_RADIUS_M, R_E, V_E).unwrap();
        assert_eq!(
            n.normalized(f64::NAN, 1.0),
            Err(GuidanceError::NonFiniteState)
        );
        assert_eq!(n.normalized(0.0, 1.0), Err(GuidanceError::UnphysicalState));
    }
}
