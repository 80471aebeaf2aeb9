//! The reference environment and vehicles of `vehicles` as guidance-core inputs: the one home of
//! the `Planet`, `ExpAtmosphere`, `VehicleParams` and lambda = 1 `LiftControl` every integration test hands to the core.

use super::vehicles::{self, H_S, MU, R_EARTH, RHO0, Vehicle};
use guidance_core::vinh::{ExpAtmosphere, LiftControl, Planet, VehicleParams};

/// The thesis' spherical Earth (`MU`, `R_EARTH`).
pub fn planet() -> Planet<f64> {
    Planet {
        mu_m3_s2: MU,
        radius_m: R_EARTH,
    }
}

/// The exponential atmosphere of the validation (`RHO0`, `H_S`), referenced to `R_EARTH`.
pub fn atmosphere() -> ExpAtmosphere<f64> {
    ExpAtmosphere {
        rho0_kg_m3: RHO0,
        scale_height_m: H_S,
        ref_radius_m: R_EARTH,
    }
}

/// Constant lift at the maximum-L/D lift coefficient (lambda = 1) with vertical fraction `f`
/// (cos(bank)).
pub fn lift(f: f64) -> LiftControl<f64> {
    LiftControl {
        lambda: 1.0,
        vertical_fraction: f,
    }
}

/// A test-side vehicle as the core's vehicle parameters.
pub fn params(v: &Vehicle) -> VehicleParams<f64> {
    VehicleParams {
        mass_kg: v.mass_kg,
        reference_area_m2: v.area_m2,
        cd0: v.cd0,
        k_polar: v.k,
        nose_radius_m: v.nose_radius_m,
    }
}

/// The SRM capsule (`vehicles::srm`) as the core's vehicle parameters.
pub fn srm() -> VehicleParams<f64> {
    params(&vehicles::srm())
}

/// HORUS-2B with its Mach 20 polar (`vehicles::horus(20.0)`) as the core's vehicle parameters.
pub fn horus() -> VehicleParams<f64> {
    params(&vehicles::horus(20.0))
}
