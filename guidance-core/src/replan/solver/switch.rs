//! [`ReplanSolver`]'s switches between predictors: the hybrid modes' move to the numerical
//! predictor and the `Auto` modes' move to the glide (see the parent module's docs).

use crate::scalar::Real;
use crate::vinh::VinhError;
use crate::vinh::predict::Prediction;
use crate::vinh::validity::Validity;

use super::super::{PredictorMode, ReplanFallBack, ReplanResult};
use super::{Phase, ReplanSolver};

impl<S: Real> ReplanSolver<S> {
    /// Whether the solve is hybrid and still on the closed forms.
    pub(super) fn hybrid_closed_form(&self) -> bool {
        matches!(
            self.config.mode,
            PredictorMode::Hybrid | PredictorMode::HybridSink
        ) && !self.numerical
    }

    /// Whether the prediction `p` to be flown sends a hybrid solve to the numerical predictor
    /// (out of the closed forms' validated domain).
    pub(super) fn leaves_domain(&self, p: &Prediction<S>) -> bool {
        self.hybrid_closed_form() && p.validity != Validity::InDomain
    }

    /// Restart the solve with the numerical predictor (hybrid modes).
    pub(super) fn switch_to_numerical(&mut self) -> Option<ReplanResult<S>> {
        self.numerical = true;
        self.glide = false;
        self.sink = false;
        self.run = None;
        self.phase = match self.warm {
            Some((f, slope)) => Phase::Guess { f, slope },
            None => Phase::EndLo,
        };
        None
    }

    /// A prediction at an end of the interval failed: in [`PredictorMode::Auto`] (or
    /// [`PredictorMode::AutoSink`], and the hybrid modes) redo the ends with the glide (once);
    /// in the hybrid modes then with the numerical predictor; else fall back.
    pub(super) fn end_failed(&mut self, e: VinhError) -> Option<ReplanResult<S>> {
        let auto = matches!(
            self.config.mode,
            PredictorMode::Auto
                | PredictorMode::AutoSink
                | PredictorMode::Hybrid
                | PredictorMode::HybridSink
        );
        if auto && !self.glide && !self.numerical {
            self.glide = true;
            self.phase = Phase::EndLo;
            None
        } else if self.hybrid_closed_form() {
            self.switch_to_numerical()
        } else {
            self.fail(ReplanFallBack::OutOfDomain(e))
        }
    }
}
