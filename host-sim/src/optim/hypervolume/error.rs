//! Typed errors of the hypervolume functions.

/// Why a hypervolume could not be computed. Every variant names the offending point index
/// and/or coordinate, so the caller can report it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum HypervolumeError {
    /// The reference point has no coordinates: a hypervolume needs at least one objective.
    #[error("the reference point has zero coordinates: at least one objective is needed")]
    ZeroDimension,
    /// A coordinate of the reference point is NaN or infinite.
    #[error("reference point coordinate {coordinate} is {value}: it must be finite")]
    NonFiniteReference {
        /// Coordinate (objective) index, from 0.
        coordinate: usize,
        /// The offending value.
        value: f64,
    },
    /// A point has a different number of coordinates than the reference point.
    #[error(
        "point {index} has {found} coordinates but the reference point has {expected}: \
         every point needs one coordinate per objective"
    )]
    DimensionMismatch {
        /// Point index, from 0, in the order given.
        index: usize,
        /// Number of coordinates of the reference point.
        expected: usize,
        /// Number of coordinates of the point.
        found: usize,
    },
    /// A coordinate of a point is NaN or infinite.
    #[error("point {index} coordinate {coordinate} is {value}: it must be finite")]
    NonFinitePoint {
        /// Point index, from 0, in the order given.
        index: usize,
        /// Coordinate (objective) index, from 0.
        coordinate: usize,
        /// The offending value.
        value: f64,
    },
    /// The least contributor of an empty set was asked for.
    #[error("the point set is empty: it has no least contributor")]
    EmptySet,
    /// The result is not representable (the coordinates are finite but the volume overflows
    /// `f64`); scale the objectives.
    #[error("the hypervolume overflows f64 ({value}): scale the objectives")]
    Overflow {
        /// The non-finite intermediate result.
        value: f64,
    },
}
