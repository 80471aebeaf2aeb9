//! The algorithms, each an ask/tell [`crate::optim::Algorithm`] with serialisable state.

pub mod mhaco;
pub mod moead;
pub mod nsga2;
pub mod scea;

pub use mhaco::{ConstraintHandling, Mhaco, MhacoConfig, VlMhaco};
pub use moead::{
    DeVariation, Moead, MoeadConfig, MoeadSbx, MoeadVariation, MoeadWith, ResourceAllocation,
    SbxVariation,
};
pub use nsga2::{Nsga2, Nsga2Config};
pub use scea::{NewGenes, Scea, SceaConfig, SceaVariation};

use super::error::ConfigError;

/// Largest population (and archive) any algorithm accepts: larger sizes are refused with an
/// error naming the field instead of failing on allocation.
pub const MAX_POPULATION: usize = 100_000;

/// `value` of `name` at most [`MAX_POPULATION`].
pub(crate) fn check_size(
    algorithm: &'static str,
    name: &'static str,
    value: usize,
) -> Result<(), ConfigError> {
    if value > MAX_POPULATION {
        return Err(ConfigError::Count {
            algorithm,
            name,
            value,
            range: "at most 100000",
        });
    }
    Ok(())
}

/// Check `value` lies in `[lo, hi]`.
pub(crate) fn check_range(
    algorithm: &'static str,
    name: &'static str,
    value: f64,
    lo: f64,
    hi: f64,
    range: &'static str,
) -> Result<(), ConfigError> {
    if value >= lo && value <= hi {
        Ok(())
    } else {
        Err(ConfigError::Parameter {
            algorithm,
            name,
            value,
            range,
        })
    }
}

#[cfg(test)]
mod tests;
