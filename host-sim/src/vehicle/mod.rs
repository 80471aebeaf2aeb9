//! Vehicles: mass properties, limits and aerodynamics.
//!
//! * [`horus2b`]: HORUS-2B winged vehicle, Mach x alpha tables (Mooij 1995) plus per-Mach
//!   drag polar (thesis table 8.1).
//! * [`srm`]: sample-return capsule, fixed trim coefficients, bank-angle control only.
//! * [`file`](mod@file): user vehicles from TOML files (table, polynomial, drag-polar or trim
//!   aerodynamics).
//! * Registry: [`by_name`], [`list`], and [`load`] (a registered name or a `.toml` path).
//! * The vehicle types ([`Vehicle`], [`Aerodynamics`], [`VehicleFileError`], ...) are defined
//!   in a leaf module the built-ins import, re-exported here.

pub mod file;
pub mod horus2b;
pub mod models;
pub mod srm;
pub mod table;
mod types;

pub use file::{from_toml_file, from_toml_str};
pub use models::{
    DragPolar, DragPolarTable, PolarAerodynamics, PolynomialAerodynamics, TableAerodynamics,
    TrimAerodynamics,
};
pub use table::{CoefficientTable, GapFill, TableError};
pub use types::{AeroCoefficients, Aerodynamics, Vehicle, VehicleFileError, VehicleLimits};

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
