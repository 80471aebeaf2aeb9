//! Vehicles: mass properties, limits and aerodynamics.
//!
//! * [`horus2b`]: HORUS-2B winged vehicle, Mach x alpha tables (Mooij 1995) plus per-Mach
//!   drag polar (thesis table 8.1).
//! * [`srm`]: sample-return capsule, fixed trim coefficients, bank-angle control only.
//! * [`file`](mod@file): user vehicles from TOML files (table, polynomial, drag-polar or trim
//!   aerodynamics).
//! * Registry: [`by_name`], [`list`], and [`load`] (a registered name or a `.toml` path).

pub mod file;
pub mod horus2b;
pub mod models;
pub mod srm;
pub mod table;

pub use file::{from_toml_file, from_toml_str};
pub use models::{
    DragPolar, DragPolarTable, PolarAerodynamics, PolynomialAerodynamics, TableAerodynamics,
    TrimAerodynamics,
};
pub use table::{CoefficientTable, GapFill, TableError};

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

/// Names of the built-in vehicles.
const NAMES: [&str; 2] = ["horus-2b", "srm"];

/// Names of the built-in vehicles, for `--vehicle` help and listings.
#[must_use]
pub fn list() -> &'static [&'static str] {
    &NAMES
}

/// A built-in vehicle by name (case-insensitive; `horus2b` and `horus` are accepted for
/// `horus-2b`).
///
/// # Errors
/// [`VehicleFileError::Unknown`] for an unknown name.
pub fn by_name(name: &str) -> Result<Vehicle, VehicleFileError> {
    match name.trim().to_ascii_lowercase().as_str() {
        "horus-2b" | "horus2b" | "horus" => horus2b::vehicle(),
        "srm" => Ok(srm::vehicle()),
        _ => Err(VehicleFileError::Unknown {
            name: name.to_string(),
            known: NAMES.join(", "),
        }),
    }
}

/// A built-in vehicle by name, or a vehicle TOML file if `name_or_path` ends in `.toml`.
///
/// # Errors
/// As [`by_name`] or [`from_toml_file`].
pub fn load(name_or_path: &str) -> Result<Vehicle, VehicleFileError> {
    if name_or_path.to_ascii_lowercase().ends_with(".toml") {
        from_toml_file(std::path::Path::new(name_or_path))
    } else {
        by_name(name_or_path)
    }
}
