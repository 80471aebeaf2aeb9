//! Sample-return-mission (SRM) capsule (thesis sec. 2.3.2, table 2.3): a 19% scale Apollo
//! command module taken from Engelsma (2019).
//!
//! * Diameter 0.75 m, reference area 0.441 m^2, nose radius 0.90 m, mass 38.77 kg (table 2.3).
//! * Control: bank angle only (thesis sec. 4.2.1: "no data of the C_L with respect to alpha
//!   is available, and thus only the bank angle can be used"), so the aerodynamics are fixed
//!   trim coefficients and [`Aerodynamics::controls_alpha`](super::Aerodynamics::controls_alpha)
//!   is false.
//! * Coefficients. The thesis prints no C_D and no L/D table for the SRM; it gives
//!   "the maximum C_L of the SRM capsule of 1.2786" (sec. 8.1.5), used here as the trim C_L.
//!   The L/D is not printed but follows from the thesis' own glide entry state for the SRM at
//!   100 km (sec. 9.2: V_E = 7658.34 m/s, gamma_E = -0.056 deg): with Vinh's glide relations
//!   (sec. 8.1.1; sign of sin(gamma_E) per ERRATA) u_E = 1/(1+k1) fixes k1 = 0.0491 and then
//!   sin(gamma_E) = -2 k1 (1+k1) / (E [2 (1+k1)^2 + (r_E/H_s) k1]) gives E = C_L/C_D = 2.27
//!   for H_s = 7.2 km (2.21-2.36 for H_s between 7.0 and 7.5 km). Hence C_D = 1.2786/2.27 =
//!   0.563. This L/D is far above a real Apollo shape (about 0.3 in flight, Hillje 1967,
//!   NASA TN D-4185) and C_D is below its ~1.3; the values are kept because they reproduce
//!   the thesis' SRM results, which is what this vehicle is for. A user wanting a physical
//!   capsule can define one in a TOML file (`kind = "trim"`).
//! * Limits: the thesis uses the same constraint values for both vehicles (sec. 4.2.3): heat
//!   flux 500 kW/m^2, g-load 3.0, g-load rate 0.5 1/s, bank rate 15 deg/s; the alpha rate
//!   (5 deg/s) is unused for a bank-only vehicle.

use super::models::TrimAerodynamics;
use super::{AeroCoefficients, Vehicle, VehicleLimits};

/// Mass \[kg\] (thesis table 2.3).
pub const MASS_KG: f64 = 38.77;
/// Reference area [m^2] (thesis table 2.3).
pub const REFERENCE_AREA_M2: f64 = 0.441;
/// Nose radius \[m\] (thesis table 2.3).
pub const NOSE_RADIUS_M: f64 = 0.90;
/// Diameter \[m\] (thesis table 2.3).
pub const DIAMETER_M: f64 = 0.75;
/// Trim lift coefficient [-] (thesis sec. 8.1.5).
pub const TRIM_CL: f64 = 1.2786;
/// Trim lift-to-drag ratio [-] implied by the thesis' sec. 9.2 glide entry state (see module
/// documentation).
pub const TRIM_LIFT_TO_DRAG: f64 = 2.27;

/// The SRM trim coefficients.
#[must_use]
pub fn trim() -> AeroCoefficients {
    AeroCoefficients {
        cl: TRIM_CL,
        cd: TRIM_CL / TRIM_LIFT_TO_DRAG,
    }
}

/// The SRM capsule.
#[must_use]
pub fn vehicle() -> Vehicle {
    Vehicle {
        name: "srm".to_string(),
        mass_kg: MASS_KG,
        reference_area_m2: REFERENCE_AREA_M2,
        nose_radius_m: NOSE_RADIUS_M,
        limits: VehicleLimits {
            heat_flux_w_m2: 500.0e3,
            g_load: 3.0,
            g_load_rate_per_s: 0.5,
            alpha_rate_rad_s: 5.0_f64.to_radians(),
            sigma_rate_rad_s: 15.0_f64.to_radians(),
        },
        aero: Box::new(TrimAerodynamics { trim: trim() }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reference_area_is_the_disc_of_the_diameter() {
        let disc = std::f64::consts::PI * DIAMETER_M * DIAMETER_M / 4.0;
        assert!((disc - REFERENCE_AREA_M2).abs() < 1e-3);
        let t = trim();
        assert!((t.cl / t.cd - TRIM_LIFT_TO_DRAG).abs() < 1e-12);
    }
}
