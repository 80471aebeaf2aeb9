//! (in progress)

/// Why a node table was rejected (placeholder until the node module lands).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum NodeTableError {
    /// Fewer than two nodes.
    TooFewNodes,
}
