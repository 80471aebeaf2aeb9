//! The error of a set-up payload and the exact-small-integer reading of its slots, shared by
//! the set-up items of the parent module and the re-planning items of [`super::replanning`]
//! (a leaf both import; re-exported as `setup::SetupError`).

use crate::error::{GuidanceError, NodeTableError};

/// Why a set-up payload is not an item.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SetupError {
    /// Unknown item code, or a code, count, index or enumeration slot that is not an exact
    /// small integer of the right range.
    BadItem,
    /// A node index outside the announced count, or nodes before the table item.
    BadIndex,
    /// Commit before every item arrived.
    Incomplete,
    /// The core rejected the configuration.
    Guidance(GuidanceError),
}

impl From<GuidanceError> for SetupError {
    fn from(e: GuidanceError) -> Self {
        Self::Guidance(e)
    }
}

impl From<NodeTableError> for SetupError {
    fn from(e: NodeTableError) -> Self {
        Self::Guidance(GuidanceError::NodeTable(e))
    }
}

pub(super) fn small_int(v: f64, max: u32) -> Result<u32, SetupError> {
    if v >= 0.0 && v <= f64::from(max) && (v - libm::floor(v)) == 0.0 {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        Ok(v as u32)
    } else {
        Err(SetupError::BadItem)
    }
}
