//! [`Mode`]: the guidance modes a campaign compares, each a selection of the layers of the one
//! stack (`guidance_core::stack::Layers`).

use guidance_core::stack::Layers;
use serde::{Deserialize, Serialize};

/// A guidance mode of the comparison.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Mode {
    /// The stored profile with its own (constant) bank sign.
    Stored,
    /// The stored profile's magnitude with bank reversals.
    StoredReversals,
    /// Re-planned magnitude (predictor-corrector on the target's range to go) with reversals.
    ReplanReversals,
    /// As [`Mode::ReplanReversals`], the predictor flying the model scaled by the onboard
    /// estimate of L/D and drag scale from sensed accelerations (`guidance_core::estimate`).
    ReplanEstimation,
}

impl Mode {
    /// Every mode, in report order.
    pub const ALL: [Mode; 4] = [
        Mode::Stored,
        Mode::StoredReversals,
        Mode::ReplanReversals,
        Mode::ReplanEstimation,
    ];

    /// The layers of the campaign's stack this mode flies (a mask over the one stack:
    /// `guidance_core::stack::StackConfig::masked`).
    #[must_use]
    pub fn layers(self) -> Layers {
        match self {
            Mode::Stored => Layers::PROFILE,
            Mode::StoredReversals => Layers {
                lateral: true,
                ..Layers::PROFILE
            },
            Mode::ReplanReversals => Layers {
                estimator: false,
                ..Layers::ALL
            },
            Mode::ReplanEstimation => Layers::ALL,
        }
    }

    /// Whether a stack with `layers` can fly this mode: it has the layers that make the mode
    /// (the barrier is flown where present, not required).
    #[must_use]
    pub fn flies_with(self, layers: Layers) -> bool {
        let need = Layers {
            barrier: false,
            ..self.layers()
        };
        need.and(layers) == need
    }

    /// Short name (file and directory names).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Mode::Stored => "stored",
            Mode::StoredReversals => "stored-reversals",
            Mode::ReplanReversals => "replan-reversals",
            Mode::ReplanEstimation => "replan-estimation",
        }
    }
}
