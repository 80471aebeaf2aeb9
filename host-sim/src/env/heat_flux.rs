//! The Chapman stagnation-point heat-flux model (thesis eq. 2.2) with configurable constants:
//! `q = c* / sqrt(R_N) * sqrt(rho / rho_ref) * (V / V_ref)^m` \[W/m^2\].
//!
//! [`ChapmanHeatFlux::thesis`] holds `guidance-core`'s constants (c* = 1.1097e8
//! W/m^2 m^0.5 with the ERRATA, rho_ref = 1.225 kg/m^3, V_ref = 7905.4 m/s, m = 3.15); with them
//! [`ChapmanHeatFlux::heat_flux_w_m2`] equals the core's `monitor::chapman_heat_flux_w_m2` bit
//! for bit (same operations, routed through `guidance_core::math`). Other planets or vehicles
//! set their own constants in the scenario file (`[heat_flux]`).

use guidance_core::math;
use guidance_core::monitor::{
    CHAPMAN_C_STAR, CHAPMAN_RHO0_KG_M3, CHAPMAN_SPEED_EXPONENT, CHAPMAN_VC_M_S,
};

/// Constants of the Chapman heat-flux relation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChapmanHeatFlux {
    /// Coefficient c* \[W/m^2 * m^0.5\] (with the nose radius in metres).
    pub coefficient: f64,
    /// Reference density rho_ref \[kg/m^3\].
    pub reference_density_kg_m3: f64,
    /// Reference speed V_ref \[m/s\].
    pub reference_speed_m_s: f64,
    /// Speed exponent m \[-\].
    pub speed_exponent: f64,
}

/// A Chapman constant that is not finite and positive.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error(
    "heat-flux model: parameter `{parameter}` = {}: must be finite and positive",
    crate::num_fmt::Compact(*value)
)]
pub struct HeatFluxError {
    /// Parameter name.
    pub parameter: &'static str,
    /// The rejected value.
    pub value: f64,
}

impl Default for ChapmanHeatFlux {
    fn default() -> Self {
        Self::thesis()
    }
}

impl ChapmanHeatFlux {
    /// `guidance-core`'s constants (thesis eq. 2.2 with the ERRATA).
    #[must_use]
    pub fn thesis() -> Self {
        Self {
            coefficient: CHAPMAN_C_STAR,
            reference_density_kg_m3: CHAPMAN_RHO0_KG_M3,
            reference_speed_m_s: CHAPMAN_VC_M_S,
            speed_exponent: CHAPMAN_SPEED_EXPONENT,
        }
    }

    /// Check every constant is finite and positive.
    ///
    /// # Errors
    /// [`HeatFluxError`] naming the first bad constant.
    pub fn validate(&self) -> Result<(), HeatFluxError> {
        for (parameter, value) in [
            ("coefficient", self.coefficient),
            ("reference_density_kg_m3", self.reference_density_kg_m3),
            ("reference_speed_m_s", self.reference_speed_m_s),
            ("speed_exponent", self.speed_exponent),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(HeatFluxError { parameter, value });
            }
        }
        Ok(())
    }

    /// Stagnation-point heat flux \[W/m^2\] at density `density_kg_m3`, speed `speed_m_s` and
    /// nose radius `nose_radius_m`; 0 for non-finite, negative density or speed, or a
    /// non-positive nose radius (as the core's plain function).
    #[must_use]
    pub fn heat_flux_w_m2(&self, density_kg_m3: f64, speed_m_s: f64, nose_radius_m: f64) -> f64 {
        let finite =
            density_kg_m3.is_finite() && speed_m_s.is_finite() && nose_radius_m.is_finite();
        if !finite || density_kg_m3 < 0.0 || speed_m_s < 0.0 || nose_radius_m <= 0.0 {
            return 0.0;
        }
        // The core's Scalar::sqrt: 0 for non-positive input.
        let sqrt = |x: f64| if x > 0.0 { math::sqrt(x) } else { 0.0 };
        let rho_ratio = density_kg_m3 / self.reference_density_kg_m3;
        let v_ratio = speed_m_s / self.reference_speed_m_s;
        let q = self.coefficient / sqrt(nose_radius_m)
            * sqrt(rho_ratio)
            * math::pow(v_ratio, self.speed_exponent);
        if q.is_finite() { q } else { 0.0 }
    }

    /// The relation for one nose radius `nose_radius_m` \[m\] as the simulator's right-hand
    /// side evaluates it (thousands of times per flight): `c* / sqrt(R_N)` computed once and
    /// the power taken with the host's `powf` (see [`NoseHeatFlux`]).
    #[must_use]
    pub fn at_nose(&self, nose_radius_m: f64) -> NoseHeatFlux {
        let coefficient = (nose_radius_m.is_finite() && nose_radius_m > 0.0)
            .then(|| self.coefficient / math::sqrt(nose_radius_m));
        NoseHeatFlux {
            model: *self,
            coefficient,
        }
    }
}

/// [`ChapmanHeatFlux`] for one nose radius ([`ChapmanHeatFlux::at_nose`]), the integrand of
/// the simulated heat load. It takes `(V / V_ref)^m` from the host's `f64::powf` instead of
/// `libm`'s `pow` (which the core must use, `no_std`, and which cost a third of a flight's
/// CPU time), so it may differ from [`ChapmanHeatFlux::heat_flux_w_m2`] in the last bit or
/// two (test: within 3 ulp relative). The simulator reports these values too (its flight
/// conditions, samples and peaks), so what it integrates and what it reports agree bit for
/// bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NoseHeatFlux {
    model: ChapmanHeatFlux,
    /// `c* / sqrt(R_N)` \[W/m^2\]; `None` for a non-finite or non-positive nose radius.
    coefficient: Option<f64>,
}

impl NoseHeatFlux {
    /// Stagnation-point heat flux \[W/m^2\] at density `density_kg_m3` and speed `speed_m_s`;
    /// 0 for non-finite or negative input or a bad nose radius (as the core's plain function).
    #[must_use]
    pub fn heat_flux_w_m2(&self, density_kg_m3: f64, speed_m_s: f64) -> f64 {
        let Some(k) = self.coefficient else {
            return 0.0;
        };
        let finite = density_kg_m3.is_finite() && speed_m_s.is_finite();
        if !finite || density_kg_m3 < 0.0 || speed_m_s < 0.0 {
            return 0.0;
        }
        // The core's Scalar::sqrt: 0 for non-positive input.
        let sqrt = |x: f64| if x > 0.0 { math::sqrt(x) } else { 0.0 };
        let rho_ratio = density_kg_m3 / self.model.reference_density_kg_m3;
        let v_ratio = speed_m_s / self.model.reference_speed_m_s;
        let q = k * sqrt(rho_ratio) * v_ratio.powf(self.model.speed_exponent);
        if q.is_finite() { q } else { 0.0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// With the thesis constants the host model is the core's function, bit for bit.
    #[test]
    fn thesis_constants_reproduce_the_core_bit_for_bit() {
        let m = ChapmanHeatFlux::thesis();
        let mut n = 0;
        for i in 0..200 {
            let rho = 1e-9 * 1.13f64.powi(i);
            for j in 0..60 {
                let v = 1.0 + 150.0 * f64::from(j);
                for rn in [0.1, 0.3, 1.0, 2.5] {
                    let core = guidance_core::monitor::chapman_heat_flux_w_m2(rho, v, rn);
                    assert_eq!(m.heat_flux_w_m2(rho, v, rn).to_bits(), core.to_bits());
                    n += 1;
                }
            }
        }
        assert_eq!(n, 48_000);
        for (rho, v, rn) in [
            (f64::NAN, 1.0, 1.0),
            (-1.0, 1.0, 1.0),
            (1.0, -1.0, 1.0),
            (1.0, 1.0, 0.0),
        ] {
            assert_eq!(m.heat_flux_w_m2(rho, v, rn), 0.0);
            assert_eq!(
                guidance_core::monitor::chapman_heat_flux_w_m2(rho, v, rn),
                0.0
            );
        }
    }

    /// The right-hand side's variant (host `powf`) stays within 3 ulp of the core's value.
    #[test]
    fn nose_variant_agrees_with_the_core_to_a_few_ulp() {
        let m = ChapmanHeatFlux::thesis();
        let mut worst: f64 = 0.0;
        for rn in [0.1, 0.3, 1.0, 2.5] {
            let nose = m.at_nose(rn);
            for i in 0..200 {
                let rho = 1e-9 * 1.13f64.powi(i);
                for j in 0..60 {
                    let v = 1.0 + 150.0 * f64::from(j);
                    let core = guidance_core::monitor::chapman_heat_flux_w_m2(rho, v, rn);
                    let rel = (nose.heat_flux_w_m2(rho, v) - core).abs() / core;
                    worst = worst.max(rel);
                }
            }
        }
        assert!(
            worst <= 3.0 * f64::EPSILON,
            "worst relative difference {worst:e}"
        );
        let bad = m.at_nose(0.0);
        assert_eq!(bad.heat_flux_w_m2(1.0, 1.0), 0.0);
        assert_eq!(m.at_nose(1.0).heat_flux_w_m2(f64::NAN, 1.0), 0.0);
        assert_eq!(m.at_nose(1.0).heat_flux_w_m2(1.0, -1.0), 0.0);
    }

    #[test]
    fn constants_scale_the_flux() {
        let base = ChapmanHeatFlux::thesis();
        let double = ChapmanHeatFlux {
            coefficient: 2.0 * base.coefficient,
            ..base
        };
        let q = base.heat_flux_w_m2(1e-4, 7000.0, 0.5);
        assert!((double.heat_flux_w_m2(1e-4, 7000.0, 0.5) / q - 2.0).abs() < 1e-14);
        let cube = ChapmanHeatFlux {
            speed_exponent: 3.0,
            ..base
        };
        let expect = base.coefficient / 0.5f64.sqrt()
            * (1e-4f64 / 1.225).sqrt()
            * (7000.0f64 / 7905.4).powi(3);
        assert!((cube.heat_flux_w_m2(1e-4, 7000.0, 0.5) / expect - 1.0).abs() < 1e-14);
        assert!(
            ChapmanHeatFlux {
                speed_exponent: -1.0,
                ..base
            }
            .validate()
            .is_err()
        );
        assert!(base.validate().is_ok());
    }
}
