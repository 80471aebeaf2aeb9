//! The closed forms' vehicle: mass properties and a parabolic drag polar
//! ([`AnalyticVehicle`], module documentation of [`crate::analytic`]), and the constant lift
//! setting it flies ([`LiftSetting`]).

use guidance_core::vinh::{LiftControl, VehicleParams};

use super::{AnalyticError, NoPolar, setting};
use crate::vehicle::{DragPolar, PolarAerodynamics, Vehicle, VehicleLimits};

/// A vehicle as the closed forms see it: mass properties and a parabolic drag polar.
#[derive(Clone, Debug, PartialEq)]
pub struct AnalyticVehicle {
    /// Name (for reports).
    pub name: String,
    /// Mass \[kg\].
    pub mass_kg: f64,
    /// Reference area [m^2].
    pub reference_area_m2: f64,
    /// Nose radius \[m\].
    pub nose_radius_m: f64,
    /// Drag polar `C_D = C_D0 + K C_L^2`.
    pub polar: DragPolar,
    /// For trim-only vehicles: the fixed total lift coefficient (then steered by bank only).
    pub trim_cl: Option<f64>,
    /// Operational limits (for the violations of the summary).
    pub limits: VehicleLimits,
}

/// Constant lift setting: total lift coefficient and bank angle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LiftSetting {
    /// Total lift coefficient `C_L` [-].
    pub cl: f64,
    /// Bank angle `sigma` \[rad\] (0: lift up).
    pub bank_rad: f64,
}

impl LiftSetting {
    /// Vertical lift coefficient `C_L cos(sigma)` [-].
    #[must_use]
    pub fn vertical_cl(&self) -> f64 {
        self.cl * self.bank_rad.cos()
    }
}

impl AnalyticVehicle {
    /// From a simulator vehicle: its drag polar at Mach `polar_mach`, or for a trim-only vehicle
    /// the polar with the trim point at maximum L/D (module documentation).
    ///
    /// # Errors
    /// [`AnalyticError::Vehicle`] if the vehicle has neither a polar nor fixed trim
    /// coefficients, or they are not finite and positive.
    pub fn from_vehicle(vehicle: &Vehicle, polar_mach: f64) -> Result<Self, AnalyticError> {
        let err = |reason: NoPolar| AnalyticError::Vehicle {
            vehicle: vehicle.name.clone(),
            reason,
        };
        if !polar_mach.is_finite() || polar_mach <= 0.0 {
            return Err(setting(
                "polar_mach",
                polar_mach,
                "must be finite and positive",
            ));
        }
        let (polar, trim_cl) = if let Some(p) = vehicle.aero.drag_polar(polar_mach) {
            (p, None)
        } else if !vehicle.aero.controls_alpha() {
            let trim = vehicle.aero.coefficients(polar_mach, 0.0);
            if !(trim.cl.is_finite() && trim.cl > 0.0 && trim.cd.is_finite() && trim.cd > 0.0) {
                return Err(err(NoPolar::BadTrim {
                    cl: trim.cl,
                    cd: trim.cd,
                }));
            }
            let cd0 = trim.cd / 2.0;
            (
                DragPolar {
                    cd0,
                    k: cd0 / (trim.cl * trim.cl),
                },
                Some(trim.cl),
            )
        } else {
            return Err(err(NoPolar::Missing));
        };
        if !(polar.cd0.is_finite() && polar.cd0 > 0.0 && polar.k.is_finite() && polar.k > 0.0) {
            return Err(err(NoPolar::BadPolar {
                mach: polar_mach,
                cd0: polar.cd0,
                k: polar.k,
            }));
        }
        Ok(Self {
            name: vehicle.name.clone(),
            mass_kg: vehicle.mass_kg,
            reference_area_m2: vehicle.reference_area_m2,
            nose_radius_m: vehicle.nose_radius_m,
            polar,
            trim_cl,
            limits: vehicle.limits,
        })
    }

    /// The closed forms' vehicle constants.
    #[must_use]
    pub fn params(&self) -> VehicleParams<f64> {
        VehicleParams {
            mass_kg: self.mass_kg,
            reference_area_m2: self.reference_area_m2,
            cd0: self.polar.cd0,
            k_polar: self.polar.k,
            nose_radius_m: self.nose_radius_m,
        }
    }

    /// Lift setting giving vertical lift coefficient `cl_vertical` [-]: for trim-only vehicles
    /// the trim `C_L` banked to `acos(cl_vertical / C_L,trim)`, otherwise `C_L = cl_vertical`
    /// with the lift vector up.
    ///
    /// # Errors
    /// [`AnalyticError::Setting`] if `cl_vertical` is not finite, negative, or above the trim
    /// `C_L` of a trim-only vehicle.
    pub fn lift_for_vertical_cl(&self, cl_vertical: f64) -> Result<LiftSetting, AnalyticError> {
        if !(cl_vertical.is_finite() && cl_vertical >= 0.0) {
            return Err(setting(
                "cl_vertical",
                cl_vertical,
                "must be finite and >= 0",
            ));
        }
        match self.trim_cl {
            Some(trim) => {
                if cl_vertical > trim {
                    return Err(setting(
                        "cl_vertical",
                        cl_vertical,
                        "must not exceed the trim lift coefficient of a bank-only vehicle",
                    ));
                }
                Ok(LiftSetting {
                    cl: trim,
                    bank_rad: (cl_vertical / trim).acos(),
                })
            }
            None => Ok(LiftSetting {
                cl: cl_vertical,
                bank_rad: 0.0,
            }),
        }
    }

    /// The closed forms' lift control (`lambda = C_L / C_L*`, vertical fraction `cos(sigma)`).
    ///
    /// # Errors
    /// [`AnalyticError::Domain`] for an invalid setting (negative `C_L`, non-finite values).
    pub fn lift_control(&self, lift: &LiftSetting) -> Result<LiftControl<f64>, AnalyticError> {
        LiftControl::from_lift_coefficient(&self.params(), lift.cl, lift.bank_rad).map_err(
            |error| AnalyticError::Domain {
                phase: "lift setting",
                error,
            },
        )
    }

    /// A simulator vehicle flying this polar at constant `C_L = lift.cl` (Mach and angle of
    /// attack independent): what the closed forms assume, for the numerical comparison runs.
    #[must_use]
    pub fn constant_lift_vehicle(&self, lift: &LiftSetting) -> Vehicle {
        Vehicle {
            name: format!("{} (polar, C_L = {})", self.name, lift.cl),
            mass_kg: self.mass_kg,
            reference_area_m2: self.reference_area_m2,
            nose_radius_m: self.nose_radius_m,
            limits: self.limits,
            aero: Box::new(PolarAerodynamics {
                polar: self.polar,
                cl: vec![lift.cl],
                alpha_min_deg: None,
                alpha_max_deg: None,
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::DEFAULT_POLAR_MACH;

    #[test]
    fn trim_vehicle_polar_reproduces_trim_drag() {
        let srm = crate::vehicle::srm::vehicle();
        let av = AnalyticVehicle::from_vehicle(&srm, DEFAULT_POLAR_MACH).unwrap();
        let trim = crate::vehicle::srm::trim();
        assert!((av.polar.cd(trim.cl) - trim.cd).abs() < 1e-12);
        assert!((av.polar.cl_at_max_lift_to_drag() - trim.cl).abs() < 1e-12);
        let lift = av.lift_for_vertical_cl(0.5 * trim.cl).unwrap();
        assert!((lift.bank_rad.to_degrees() - 60.0).abs() < 1e-9);
        assert!((lift.vertical_cl() - 0.5 * trim.cl).abs() < 1e-12);
        assert!(av.lift_for_vertical_cl(2.0).is_err());
        assert!(av.lift_for_vertical_cl(f64::NAN).is_err());
    }
}
