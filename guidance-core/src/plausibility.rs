//! Plausibility of navigation time stamps (issue 8.5).
//!
//! A single finite but wrong time stamp (a glitch of 1e4 s, 1e12 s or `f64::MAX`) must not
//! become guidance's time reference: if it did, every later, correct sample would lie before
//! the glitch's tick and be rejected, freezing the command computed at the glitch for the rest
//! of the flight. So a sample whose time differs from the last accepted sample's by more than
//! [`TimeWindow::max_step_s`] (either way) is rejected with
//! [`GuidanceError::ImplausibleTime`] and does not become the reference; guidance recovers at
//! the next good sample.
//!
//! A real time discontinuity (navigation restarted with a new epoch, or a long outage) must not
//! freeze guidance either: when [`TimeWindow::resync_samples`] consecutive rejected samples are
//! consistent with each other (each later than the previous one by at most `max_step_s`),
//! guidance re-synchronises: the last of them is accepted as a first tick, the clock restarts
//! there ([`crate::clock`]), and the attitude ramp continues from where it is (no jump).
//!
//! Defaults ([`TimeWindow::for_period`]): a step of at most 30 guidance periods (60 s at the
//! thesis' 2 s), re-synchronisation after 3 consistent samples.

use crate::error::GuidanceError;
use crate::scalar::Scalar;

/// Default largest plausible step between accepted samples, in guidance periods.
const DEFAULT_MAX_STEP_PERIODS: f64 = 30.0;
/// Default number of consistent implausible samples that re-synchronise the clock.
const DEFAULT_RESYNC_SAMPLES: u8 = 3;
/// Largest step allowed, in guidance periods (keeps a tick jump far below `2^32` periods).
const MAX_STEP_PERIODS_LIMIT: f64 = 1_048_576.0;

/// The time plausibility window of [`crate::guidance::Guidance`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TimeWindow<S> {
    /// Largest plausible difference between a sample's time and the last accepted sample's
    /// time, forwards or backwards \[s\]. Finite, at least one guidance period and at most
    /// 2^20 periods.
    pub max_step_s: S,
    /// Consecutive, mutually consistent implausible samples after which guidance accepts the
    /// new time base (at least 1; 1 means every implausible sample is taken at once).
    pub resync_samples: u8,
}

impl<S: Scalar> TimeWindow<S> {
    /// The default window for a guidance period \[s\]: 30 periods, re-synchronisation after 3
    /// samples.
    #[must_use]
    pub fn for_period(period_s: S) -> Self {
        Self {
            max_step_s: period_s * S::from_f64(DEFAULT_MAX_STEP_PERIODS),
            resync_samples: DEFAULT_RESYNC_SAMPLES,
        }
    }

    /// Check the window against the guidance period \[s\].
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] if `max_step_s` is not finite, shorter than one period
    /// or longer than 2^20 periods, or `resync_samples` is 0.
    pub fn validate(&self, period_s: S) -> Result<(), GuidanceError> {
        let ok = self.max_step_s.is_finite()
            && self.max_step_s >= period_s
            && self.max_step_s <= period_s * S::from_f64(MAX_STEP_PERIODS_LIMIT)
            && self.resync_samples >= 1;
        if ok {
            Ok(())
        } else {
            Err(GuidanceError::InvalidConfig)
        }
    }
}

/// What the gate decided for a sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum TimeVerdict {
    /// Within the window (or the first sample): process normally.
    Accept,
    /// The last of `resync_samples` consistent implausible samples: restart the clock here.
    Resync,
}

/// State of the plausibility check: the last accepted time and the run of rejected ones.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct TimeGate<S> {
    window: TimeWindow<S>,
    /// Time of the last accepted sample \[s\].
    last_s: Option<S>,
    /// Time of the last rejected sample \[s\] and the length of the consistent run it ends.
    rejected: Option<(S, u8)>,
}

impl<S: Scalar> TimeGate<S> {
    /// A gate with no accepted sample yet.
    pub(crate) fn new(window: TimeWindow<S>) -> Self {
        Self {
            window,
            last_s: None,
            rejected: None,
        }
    }

    /// The window in use.
    pub(crate) fn window(&self) -> TimeWindow<S> {
        self.window
    }

    /// Change the window; the accepted time and the run of rejected samples are kept.
    pub(crate) fn set_window(&mut self, window: TimeWindow<S>) {
        self.window = window;
    }

    /// Screen a (finite) sample time \[s\]. An implausible sample extends the run of rejected
    /// samples (that is the only state it changes) and is an error unless it completes a run of
    /// `resync_samples`.
    ///
    /// # Errors
    /// [`GuidanceError::ImplausibleTime`] for a sample outside the window that does not yet
    /// re-synchronise.
    pub(crate) fn screen(&mut self, time_s: S) -> Result<TimeVerdict, GuidanceError> {
        let Some(last) = self.last_s else {
            return Ok(TimeVerdict::Accept);
        };
        if within(time_s, last, self.window.max_step_s) {
            return Ok(TimeVerdict::Accept);
        }
        let run = match self.rejected {
            Some((prev, n)) if time_s > prev && within(time_s, prev, self.window.max_step_s) => {
                n.saturating_add(1)
            }
            _ => 1,
        };
        self.rejected = Some((time_s, run));
        if run >= self.window.resync_samples {
            Ok(TimeVerdict::Resync)
        } else {
            Err(GuidanceError::ImplausibleTime)
        }
    }

    /// Record an accepted sample time \[s\] (after the update it belongs to succeeded).
    pub(crate) fn accept(&mut self, time_s: S) {
        self.last_s = Some(time_s);
        self.rejected = None;
    }
}

/// `|a - b| <= max`, written so that an overflowing difference (saturated fixed point, or
/// `inf` in floating point) counts as outside.
fn within<S: Scalar>(a: S, b: S, max: S) -> bool {
    let d = if a >= b { a - b } else { b - a };
    d.is_finite() && d <= max && d < S::MAX
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::scalar::Fixed;

    #[test]
    fn glitch_is_rejected_and_does_not_become_the_reference() {
        let mut g = TimeGate::new(TimeWindow::for_period(2.0_f64));
        assert_eq!(g.screen(10.0), Ok(TimeVerdict::Accept));
        g.accept(10.0);
        for glitch in [1e4, 1e12, f64::MAX, -1e12, -f64::MAX] {
            assert_eq!(g.screen(glitch), Err(GuidanceError::ImplausibleTime));
            assert_eq!(g.screen(12.0), Ok(TimeVerdict::Accept));
            g.accept(12.0);
        }
    }

    #[test]
    fn consistent_run_resynchronises() {
        let mut g = TimeGate::new(TimeWindow::for_period(2.0_f64));
        g.accept(10.0);
        assert_eq!(g.screen(1e4), Err(GuidanceError::ImplausibleTime));
        assert_eq!(g.screen(1e4 + 2.0), Err(GuidanceError::ImplausibleTime));
        // An inconsistent sample restarts the run.
        assert_eq!(g.screen(5e5), Err(GuidanceError::ImplausibleTime));
        assert_eq!(g.screen(5e5 + 2.0), Err(GuidanceError::ImplausibleTime));
        assert_eq!(g.screen(5e5 + 4.0), Ok(TimeVerdict::Resync));
        g.accept(5e5 + 4.0);
        assert_eq!(g.screen(5e5 + 6.0), Ok(TimeVerdict::Accept));
    }

    #[test]
    fn fixed_point_saturation_counts_as_outside() {
        let mut g = TimeGate::new(TimeWindow::for_period(Fixed::from_f64(2.0)));
        g.accept(Fixed::from_f64(-2.0e9));
        assert_eq!(
            g.screen(Fixed::from_f64(2.0e9)),
            Err(GuidanceError::ImplausibleTime)
        );
    }

    #[test]
    fn window_validation() {
        let p = 2.0_f32;
        assert!(TimeWindow::for_period(p).validate(p).is_ok());
        for bad in [
            TimeWindow {
                max_step_s: 1.0,
                resync_samples: 3,
            },
            TimeWindow {
                max_step_s: f32::INFINITY,
                resync_samples: 3,
            },
            TimeWindow {
                max_step_s: 1e30,
                resync_samples: 3,
            },
            TimeWindow {
                max_step_s: 60.0,
                resync_samples: 0,
            },
        ] {
            assert_eq!(bad.validate(p), Err(GuidanceError::InvalidConfig));
        }
    }
}
