//! The vehicle types the built-ins, the file reader and the registry share: [`Vehicle`], its
//! [`VehicleLimits`] and [`Aerodynamics`], and [`VehicleFileError`], and the [`DragPolar`] an aerodynamic model may have.

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
    /// Coefficients at Mach `mach` [-] and angle of attack `alpha_rad` \[rad\]. Outside the
    /// tabulated range the model clamps to its edges (documented per model).
    fn coefficients(&self, mach: f64, alpha_rad: f64) -> AeroCoefficients;

    /// Parabolic drag polar C_D = C_D0 + K C_L^2 at Mach `mach` for the analytical methods,
    /// if the model has one (HORUS-2B: thesis table 8.1; TOML `drag_polar` vehicles).
    fn drag_polar(&self, mach: f64) -> Option<DragPolar> {
        let _ = mach;
        None
    }

    /// Whether the angle of attack is a control (false for trim-only vehicles such as the
    /// SRM capsule, which are steered by bank angle alone).
    fn controls_alpha(&self) -> bool {
        true
    }
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
    /// Mass \[kg\].
    pub mass_kg: f64,
    /// Aerodynamic reference area [m^2].
    pub reference_area_m2: f64,
    /// Nose radius \[m\] (Chapman heat flux).
    pub nose_radius_m: f64,
    /// Operational limits.
    pub limits: VehicleLimits,
    /// Aerodynamic model.
    pub aero: Box<dyn Aerodynamics>,
}

/// Errors from loading a vehicle. Messages name the file, the field and the value.
#[derive(Debug, thiserror::Error)]
pub enum VehicleFileError {
    /// The file could not be read.
    #[error("{file}: cannot read: {source}")]
    Io {
        /// File name as given.
        file: String,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The file is not valid TOML (the message gives line, column and the offending text).
    #[error("{file}: invalid TOML: {source}")]
    Toml {
        /// File name as given.
        file: String,
        /// The parser's error.
        source: crate::toml_input::TomlSyntax,
    },
    /// A field is missing, mistyped, out of range or unknown.
    #[error("{file}: field `{field}` = {value}: {reason}")]
    Field {
        /// File name as given.
        file: String,
        /// Dotted field path, e.g. `limits.g_load` or `aero.cl[1]`.
        field: String,
        /// The offending value as written (TOML syntax), or `(missing)`.
        value: String,
        /// What is required.
        reason: String,
    },
    /// Not a registered vehicle name (and not a `.toml` path).
    #[error(
        "unknown vehicle `{name}`: known vehicles are {known} (or give a path to a .toml file)"
    )]
    Unknown {
        /// The name asked for.
        name: String,
        /// Comma-separated registered names.
        known: String,
    },
}

/// Parabolic drag polar C_D = C_D0 + K C_L^2 (thesis eq. 3.19).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DragPolar {
    /// Zero-lift drag coefficient C_D0 [-].
    pub cd0: f64,
    /// Induced-drag factor K [-].
    pub k: f64,
}

impl DragPolar {
    /// C_D at lift coefficient `cl`.
    #[must_use]
    pub fn cd(&self, cl: f64) -> f64 {
        self.cd0 + self.k * cl * cl
    }

    /// Maximum lift-to-drag ratio E* = 1 / (2 sqrt(K C_D0)) (thesis eq. 3.18).
    #[must_use]
    pub fn max_lift_to_drag(&self) -> f64 {
        0.5 / (self.k * self.cd0).sqrt()
    }

    /// Lift coefficient of maximum L/D, C_L* = sqrt(C_D0 / K) (denominator of eq. 3.21).
    #[must_use]
    pub fn cl_at_max_lift_to_drag(&self) -> f64 {
        (self.cd0 / self.k).sqrt()
    }
}
