//! [`ReplanSolver`]'s warm start: the guess and the secant steps that replace the bracketing
//! predictions at `f_min` and `f_max` (see the parent module's docs, "Warm start").

use super::super::BankShape;
use crate::scalar::Real;
use crate::vinh::predict::PeakMode;

use super::super::{ReplanCase, ReplanResult};
use super::{Phase, ReplanSolver, search};

/// Most secant steps of a warm start before the cold start takes over.
const WARM_SECANT_STEPS: u8 = 3;
/// Factor on the second and later secant steps of a warm start (> 1: they overshoot a
/// root the secant falls short of, so that the last two points bracket it).
const WARM_STEP_GROWTH: f64 = 1.5;

impl<S: Real> ReplanSolver<S> {
    /// This solver starting from the guess `f` \[-\] (e.g. the last solve's vertical fraction)
    /// with the range sensitivity `slope_m` \[m per unit vertical fraction\] (e.g. that
    /// solve's [`ReplanSolver::range_slope`]) instead of from the ends of `[f_min, f_max]`
    /// (module docs, "Warm start"). Ignored (a cold start) for a non-finite guess, a guess
    /// outside `[f_min, f_max]`, or a slope that is not finite and positive; also ignored by
    /// a solver that is already done.
    #[must_use]
    pub fn with_warm_start(mut self, f: S, slope_m: S) -> Self {
        let ok = f.is_finite()
            && f >= self.config.min_vertical_fraction
            && f <= self.config.max_vertical_fraction
            && slope_m.is_finite()
            && slope_m > S::ZERO;
        if ok && self.phase == Phase::EndLo {
            self.phase = Phase::Guess { f, slope: slope_m };
            self.warm = Some((f, slope_m));
        }
        self
    }

    /// This solver, if hybrid ([`super::super::PredictorMode::Hybrid`],
    /// [`super::super::PredictorMode::HybridSink`]), on the numerical predictor from its first
    /// prediction, as after a switch (e.g. when
    /// the last solve left the closed forms' domain; [`ReplanSolver::uses_numerical`]).
    #[must_use]
    pub fn numerical_from_start(mut self) -> Self {
        if self.hybrid_closed_form() && self.result().is_none() {
            self.numerical = true;
            self.glide = false;
            self.sink = false;
        }
        self
    }

    /// The secant slope of range against vertical fraction \[m\] between the solve's last two
    /// range-only predictions at distinct fractions, if it has made two and the slope is
    /// finite and positive (range grows with the vertical fraction).
    #[must_use]
    pub fn range_slope(&self) -> Option<S> {
        match self.evals {
            [Some((f1, m1)), Some((f0, m0))] if f1 != f0 => {
                let s = (m1 - m0) / (f1 - f0);
                (s.is_finite() && s > S::ZERO).then_some(s)
            }
            _ => None,
        }
    }

    /// Record a completed range-only prediction at `f` with miss `miss` \[m\].
    pub(super) fn record(&mut self, f: S, miss: S) {
        self.evals = [Some((f, miss)), self.evals[0]];
    }

    /// The range-only miss \[m\] at `f`: `None` while a numerical prediction is in progress,
    /// `Some(None)` (and the cold start next) if the prediction failed: the cold start then
    /// decides (ends, glide, switch).
    fn warm_miss(&mut self, f: S, shape: Option<&BankShape<S>>) -> Option<Option<S>> {
        let r = self.eval(f, PeakMode::RangeOnly, shape)?;
        match r {
            Ok(p) => {
                let miss = p.range_m - self.target_range_m;
                self.record(f, miss);
                Some(Some(miss))
            }
            Err(_) => {
                self.phase = Phase::EndLo;
                Some(None)
            }
        }
    }

    /// [`Phase::Guess`]: the prediction at the guess `f`, then the first secant step with the
    /// slope `slope` \[m\]. The guess is refined even within the tolerance (a guess accepted
    /// as it is would let the miss drift to the tolerance from one solve to the next).
    pub(super) fn step_guess(
        &mut self,
        f: S,
        slope: S,
        shape: Option<&BankShape<S>>,
    ) -> Option<ReplanResult<S>> {
        let miss = self.warm_miss(f, shape)??;
        self.phase = if miss == S::ZERO {
            Phase::Final {
                f,
                case: ReplanCase::Converged,
            }
        } else {
            let f1 = self.clamp_f(f - miss / slope);
            if f1 == f {
                // At a bound and still short or long: the cold start decides.
                Phase::EndLo
            } else {
                Phase::Secant {
                    f0: f,
                    m0: miss,
                    f: f1,
                    n: 1,
                }
            }
        };
        None
    }

    /// [`Phase::Secant`]: the prediction at `f`, the `n`-th secant step from `f0` (miss `m0`
    /// \[m\]); then the final prediction, Brent's search in the bracket, another step or the
    /// cold start.
    pub(super) fn step_secant(
        &mut self,
        f0: S,
        m0: S,
        f: S,
        n: u8,
        shape: Option<&BankShape<S>>,
    ) -> Option<ReplanResult<S>> {
        let miss = self.warm_miss(f, shape)??;
        self.phase = if miss.abs() <= self.config.tolerance_m {
            Phase::Final {
                f,
                case: ReplanCase::Converged,
            }
        } else if (miss > S::ZERO) != (m0 > S::ZERO) {
            // Bracketed by the last two points: Brent's search there.
            search((f0, m0), (f, miss)).unwrap_or(Phase::EndLo)
        } else if n < WARM_SECANT_STEPS && miss.abs() < m0.abs() {
            // Closer, not bracketed: another secant step, lengthened so that the next one
            // brackets the root when the range curves.
            let step = (f - f0) / (m0 - miss) * miss;
            let f2 = self.clamp_f(f + step * S::from_f64(WARM_STEP_GROWTH));
            if f2 == f {
                Phase::EndLo
            } else {
                Phase::Secant {
                    f0: f,
                    m0: miss,
                    f: f2,
                    n: n + 1,
                }
            }
        } else {
            // Not closing in: the cold start (both ends, then Brent).
            Phase::EndLo
        };
        None
    }
}
