//! [`ReplanSolver`]'s predictions: one closed-form call, or a bounded chunk of a numerical
//! prediction held in the solver (see the parent module's docs).

use crate::scalar::Real;
use crate::vinh::VinhError;
use crate::vinh::nondim::LiftControl;
use crate::vinh::predict::{PeakMode, Prediction, predict_with};

use super::super::BankShape;
use super::super::glide_prediction;
use super::super::numerical::NumericalRun;
use super::ReplanSolver;

impl<S: Real> ReplanSolver<S> {
    /// The prediction at `f`: `None` while a numerical prediction is in progress (call again
    /// with the same `f` and `peaks` at the next step).
    pub(super) fn eval(
        &mut self,
        f: S,
        peaks: PeakMode<S>,
        shape: Option<&BankShape<S>>,
    ) -> Option<Result<Prediction<S>, VinhError>> {
        let lift = LiftControl {
            lambda: self.config.lambda,
            vertical_fraction: f,
        };
        if self.numerical {
            return self.eval_numerical(&lift, peaks, shape);
        }
        self.calls = self.calls.saturating_add(1);
        Some(self.eval_closed_form(&lift, peaks))
    }

    /// Advance (or start) the numerical prediction with `lift`: `None` while in progress.
    /// Not inlined: keeps the closed-form path of [`ReplanSolver::step`] as lean as before.
    #[inline(never)]
    pub(super) fn eval_numerical(
        &mut self,
        lift: &LiftControl<S>,
        peaks: PeakMode<S>,
        shape: Option<&BankShape<S>>,
    ) -> Option<Result<Prediction<S>, VinhError>> {
        {
            let mut run = match self.run.take() {
                Some(r) => r,
                None => match NumericalRun::new(
                    match &self.rotation {
                        Some(w) => &w.planet,
                        None => &self.planet,
                    },
                    &self.atmosphere,
                    &self.vehicle,
                    lift,
                    &self.state,
                    &self.config.predictor,
                    peaks,
                ) {
                    Ok(r) => {
                        let r = match self.lift_schedule {
                            Some(s) => r.with_lift_schedule(s),
                            None => r,
                        };
                        let r = match self.path_bound {
                            Some(b) => r.with_path_bound(b),
                            None => r,
                        };
                        let r = match &self.rotation {
                            Some(w) => {
                                r.with_rotation(w.omega_rad_s, w.latitude_rad, w.heading_rad)
                            }
                            None => r,
                        };
                        let mut r = match self.final_energy {
                            Some((mu, e)) => r.with_final_energy(mu, e),
                            None => r,
                        };
                        // In place: one more by-value step would be another copy of the run
                        // on the stack.
                        if let Some(s) = shape {
                            r.set_bank_shape(s);
                        }
                        r
                    }
                    Err(e) => {
                        self.calls = self.calls.saturating_add(1);
                        return Some(Err(e));
                    }
                },
            };
            let before = run.steps();
            let out = run.advance_shaped(self.chunk, shape);
            self.integration_steps = self
                .integration_steps
                .saturating_add(u32::from(run.steps().saturating_sub(before)));
            if out.is_none() {
                self.run = Some(run);
            } else {
                self.calls = self.calls.saturating_add(1);
            }
            out
        }
    }

    /// One closed-form prediction with `lift`.
    pub(super) fn eval_closed_form(
        &self,
        lift: &LiftControl<S>,
        peaks: PeakMode<S>,
    ) -> Result<Prediction<S>, VinhError> {
        if self.glide {
            glide_prediction(
                &self.planet,
                &self.atmosphere,
                &self.vehicle,
                lift,
                &self.state,
                &self.config.predictor,
                peaks,
                self.sink,
            )
        } else {
            predict_with(
                &self.planet,
                &self.atmosphere,
                &self.vehicle,
                lift,
                &self.state,
                &self.config.predictor,
                peaks,
            )
        }
    }
}
