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
