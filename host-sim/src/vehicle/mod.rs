//! Vehicles: mass properties, limits and aerodynamics (interface; HORUS-2B, SRM and TOML
//! vehicles in progress).

/// Lift and drag coefficients at one flight condition.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AeroCoefficients {
    /// Lift coefficient C_L [-].
    pub cl: f64,
    /// Drag coefficient C_D [-].
    pub cd: f64,
}

/// Aerodynamic model: coefficients against Mach number and angle of attack.
pub trait Aerodynamics: Send + Sync + std::fmt::Debug {
    /// Coefficients at Mach `mach` [-] and angle of attack `alpha_rad` [rad]. Outside the
    /// tabulated range the model clamps to its edges (documented per model).
    fn coefficients(&self, mach: f64, alpha_rad: f64) -> AeroCoefficients;
}

/// Operational limits of a vehicle (thesis table 2.1 for HORUS-2B).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VehicleLimits {
    /// Maximum stagnation-point heat flux [W/m^2].
    pub heat_flux_w_m2: f64,
    /// Maximum g-load [-] (multiples of g0 = 9.80665 m/s^2).
    pub g_load: f64,
    /// Maximum g-load rate [1/s].
    pub g_load_rate_per_s: f64,
    /// Maximum angle-of-attack rate [rad/s].
    pub alpha_rate_rad_s: f64,
    /// Maximum bank-angle rate [rad/s].
    pub sigma_rate_rad_s: f64,
}

/// A re-entry vehicle.
#[derive(Debug)]
pub struct Vehicle {
    /// Name used on the command line and in reports.
    pub name: String,
    /// Mass [kg].
    pub mass_kg: f64,
    /// Aerodynamic reference area [m^2].
    pub reference_area_m2: f64,
    /// Nose radius [m] (Chapman heat flux).
    pub nose_radius_m: f64,
    /// Operational limits.
    pub limits: VehicleLimits,
    /// Aerodynamic model.
    pub aero: Box<dyn Aerodynamics>,
}
