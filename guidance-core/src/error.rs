//! Typed errors of the flight core. Small, `Copy`, no string payloads.

pub use crate::nodes::NodeTableError;

/// Errors the guidance path can return.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum GuidanceError {
    /// A navigation-state field was NaN or infinite.
    NonFiniteState,
    /// Radius not positive or speed negative.
    UnphysicalState,
    /// A configuration value (planet constant, rate limit, period, bound) was non-finite,
    /// non-positive where it must be positive, or out of the scalar type's range.
    InvalidConfig,
    /// The node table was rejected.
    NodeTable(NodeTableError),
    /// A time stamp did not advance: navigation time earlier than the last guidance tick, or a
    /// monitor sample not later than the previous one.
    NonIncreasingTime,
    /// A navigation time stamp outside the plausibility window around the last accepted sample
    /// (see [`crate::plausibility`]); it did not become the time reference.
    ImplausibleTime,
}

impl From<NodeTableError> for GuidanceError {
    fn from(e: NodeTableError) -> Self {
        GuidanceError::NodeTable(e)
    }
}

impl core::fmt::Display for GuidanceError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            GuidanceError::NonFiniteState => f.write_str("navigation state is not finite"),
            GuidanceError::UnphysicalState => {
                f.write_str("navigation state is unphysical (radius <= 0 or speed < 0)")
            }
            GuidanceError::InvalidConfig => f.write_str("invalid guidance configuration"),
            GuidanceError::NodeTable(e) => write!(f, "node table rejected: {e:?}"),
            GuidanceError::NonIncreasingTime => f.write_str("time did not advance"),
            GuidanceError::ImplausibleTime => {
                f.write_str("navigation time outside the plausibility window")
            }
        }
    }
}

impl core::error::Error for GuidanceError {}
