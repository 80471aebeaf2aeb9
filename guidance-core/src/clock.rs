//! Fixed-period guidance clock with zero-order hold (thesis: 2.0 s guidance period).
//!
//! The clock starts at the first time it is polled (`t0`). Tick `k` happens at
//! `t0 + k * period`, computed from the integer counter `k` every time (one multiplication and
//! one addition, so no rounding error accumulates over a flight; in `f32` the tick times are
//! exact for `k < 2^24` when `t0` and the period are exact binary fractions, e.g. 2.0 s).
//!
//! A poll at time `t` reports a tick if `t` has reached the next tick time. If `t` has passed
//! several tick times (a gap in navigation data), it reports one tick at the *latest* tick time
//! `<= t` together with the number of tick instants that were passed; guidance recomputes once
//! (see [`crate::guidance`]). A time earlier than the last tick is rejected.
//!
//! The tick counter never saturates: once it reaches 2^31 the clock re-bases (`t0` moves to
//! the current tick, the counter restarts at 0; the tick times are unchanged up to one
//! rounding). Tick times never become infinite: they saturate at the scalar type's largest
//! value. [`crate::guidance::Guidance`] also rejects implausible time jumps before they reach
//! the clock ([`crate::plausibility`]).
//!
//! # Time range and resolution of each scalar type
//! Times are absolute seconds in the scalar type, so their resolution falls with magnitude:
//!
//! | type | resolution at 1e3 s | at 1e5 s | at 1e7 s | usable range |
//! |------|--------------------|----------|----------|--------------|
//! | `f64` | 1.1e-13 s | 1.5e-11 s | 1.9e-9 s | any finite time |
//! | `f32` | 6.1e-5 s | 7.8e-3 s | 1 s | tick times exact for `k < 2^24` with exact `t0` and period; sample-time rounding is visible beyond ~1e5 s (7.8 ms) |
//! | `Fixed` (I32F32) | 2.3e-10 s | 2.3e-10 s | 2.3e-10 s | +-2^31 s (68 years); beyond it saturates |
//!
//! A flight that counts time from entry (a few thousand seconds) is far inside every range; a
//! navigation system that stamps time since an old epoch should subtract the epoch before
//! guidance sees it, especially in `f32`.

use crate::error::GuidanceError;
use crate::scalar::Scalar;

/// Bound on the correction steps of the tick-index estimate in [`GuidanceClock::poll`].
const MAX_CORRECTIONS: u32 = 4;
/// Tick index at which the clock re-bases so the counter never saturates.
const REBASE_AT: u32 = 1 << 31;

/// What a poll of the clock found.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ClockEvent<S> {
    /// No tick due: hold the command.
    Hold,
    /// A tick is due.
    Tick {
        /// Index of the tick (0 for the first).
        index: u32,
        /// Time of the tick, `t0 + index * period`, in seconds.
        time_s: S,
        /// Tick instants reached since the previous tick (1 normally, more after a gap; 1 for
        /// the first tick).
        elapsed_ticks: u32,
    },
}

/// The guidance clock. `Copy`; polling does not change it: call [`GuidanceClock::commit`] with
/// the event once the tick has been processed, so that a failed update leaves the clock as it
/// was.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct GuidanceClock<S> {
    period_s: S,
    /// `t0` once started.
    start_s: Option<S>,
    /// Index of the last tick taken.
    last_index: u32,
}

impl<S: Scalar> GuidanceClock<S> {
    /// A clock with the given period in seconds (finite, > 0), not yet started.
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] for a non-finite or non-positive period.
    pub fn new(period_s: S) -> Result<Self, GuidanceError> {
        if !(period_s.is_finite() && period_s > S::ZERO) {
            return Err(GuidanceError::InvalidConfig);
        }
        Ok(Self {
            period_s,
            start_s: None,
            last_index: 0,
        })
    }

    /// Period \[s\].
    #[must_use]
    pub fn period_s(&self) -> S {
        self.period_s
    }

    /// Start time `t0` \[s\], once the first tick has been committed.
    #[must_use]
    pub fn start_s(&self) -> Option<S> {
        self.start_s
    }

    /// Time of tick `k` \[s\]: `t0 + k * period` (`t0` = 0 before the start), saturated at
    /// the scalar type's largest value (never infinite).
    #[must_use]
    pub fn tick_time_s(&self, k: u32) -> S {
        let t = self.start_s.unwrap_or(S::ZERO) + S::from_u32(k) * self.period_s;
        if t.is_finite() { t } else { S::MAX }
    }

    /// Time of the last tick taken \[s\] (`None` before the start).
    #[must_use]
    pub fn last_tick_s(&self) -> Option<S> {
        self.start_s.map(|_| self.tick_time_s(self.last_index))
    }

    /// Time of the next tick \[s\]. Before the first tick the clock ticks at the first poll;
    /// this then returns 0.
    #[must_use]
    pub fn next_tick_s(&self) -> S {
        match self.start_s {
            Some(_) => self.tick_time_s(self.last_index.saturating_add(1)),
            None => S::ZERO,
        }
    }

    /// Decide whether `time_s` \[s\] is a tick. Does not change the clock.
    ///
    /// # Errors
    /// [`GuidanceError::NonFiniteState`] for a non-finite time;
    /// [`GuidanceError::NonIncreasingTime`] for a time before the last tick.
    pub fn poll(&self, time_s: S) -> Result<ClockEvent<S>, GuidanceError> {
        if !time_s.is_finite() {
            return Err(GuidanceError::NonFiniteState);
        }
        let Some(t0) = self.start_s else {
            return Ok(ClockEvent::Tick {
                index: 0,
                time_s,
                elapsed_ticks: 1,
            });
        };
        let last = self.tick_time_s(self.last_index);
        if time_s < last {
            return Err(GuidanceError::NonIncreasingTime);
        }
        let next_index = self.last_index.saturating_add(1);
        if time_s < self.tick_time_s(next_index) || next_index == self.last_index {
            return Ok(ClockEvent::Hold);
        }
        // Latest k with tick_time(k) <= time: estimate by division (a non-negative f64, so the
        // saturating `as` cast floors it), then correct by comparing with the exact tick times.
        // The corrections are bounded (the estimate is off by at most one in the exact range;
        // beyond it, e.g. saturated fixed point or f32 times above 2^24 periods, tick times
        // are not distinct anyway), and the result never precedes `next_index` nor lies after
        // `time_s`.
        let estimate = ((time_s - t0) / self.period_s).to_f64();
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let mut k = (estimate as u32).max(next_index);
        for _ in 0..MAX_CORRECTIONS {
            if k > next_index && self.tick_time_s(k) > time_s {
                k -= 1;
            }
        }
        for _ in 0..MAX_CORRECTIONS {
            if k < u32::MAX && self.tick_time_s(k + 1) <= time_s {
                k += 1;
            }
        }
        if self.tick_time_s(k) > time_s {
            k = next_index;
        }
        if self.tick_time_s(k) <= last {
            // Tick times no longer distinct (saturated fixed point, or f32 far beyond 2^24
            // periods): hold rather than tick twice at the same instant.
            return Ok(ClockEvent::Hold);
        }
        Ok(ClockEvent::Tick {
            index: k,
            time_s: self.tick_time_s(k),
            elapsed_ticks: k - self.last_index,
        })
    }

    /// Record a tick returned by [`GuidanceClock::poll`] (a `Hold` changes nothing).
    pub fn commit(&mut self, event: ClockEvent<S>) {
        if let ClockEvent::Tick { index, time_s, .. } = event {
            if self.start_s.is_none() || index >= REBASE_AT {
                // First tick, or re-base before the counter could saturate.
                self.start_s = Some(time_s);
                self.last_index = 0;
            } else {
                self.last_index = index;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Fixed;

    fn step<S: Scalar>(c: &mut GuidanceClock<S>, t: f64) -> ClockEvent<S> {
        let e = c.poll(S::from_f64(t)).unwrap();
        c.commit(e);
        e
    }

    #[test]
    fn ticks_every_period_and_holds_between() {
        let mut c = GuidanceClock::new(2.0_f64).unwrap();
        assert!(matches!(
            step(&mut c, 10.0),
            ClockEvent::Tick { index: 0, .. }
        ));
        assert_eq!(c.next_tick_s(), 12.0);
        assert_eq!(step(&mut c, 11.9), ClockEvent::Hold);
        assert_eq!(
            step(&mut c, 12.0),
            ClockEvent::Tick {
                index: 1,
                time_s: 12.0,
                elapsed_ticks: 1
            }
        );
        assert_eq!(step(&mut c, 13.0), ClockEvent::Hold);
        // Gap: 12 -> 19.5 passes 14, 16, 18.
        assert_eq!(
            step(&mut c, 19.5),
            ClockEvent::Tick {
                index: 4,
                time_s: 18.0,
                elapsed_ticks: 3
            }
        );
        assert_eq!(c.poll(17.0), Err(GuidanceError::NonIncreasingTime));
        assert_eq!(c.poll(f64::NAN), Err(GuidanceError::NonFiniteState));
        assert!(GuidanceClock::new(0.0_f64).is_err());
        assert!(GuidanceClock::new(f64::INFINITY).is_err());
    }

    #[test]
    fn no_drift_over_long_flight_f32_and_fixed() {
        // 0.1 s samples (i / 10 is not exact in binary except at multiples of 0.5 s): tick k
        // must come exactly at sample 20k, in both types, with no drift.
        let mut c32 = GuidanceClock::new(2.0_f32).unwrap();
        let mut cx = GuidanceClock::new(Fixed::from_f64(2.0)).unwrap();
        let mut ticks = 0u32;
        for i in 0..20_000u32 {
            let t = f64::from(i) / 10.0;
            let e32 = step(&mut c32, t);
            let ex = step(&mut cx, t);
            if let ClockEvent::Tick { index, time_s, .. } = e32 {
                assert_eq!(index, ticks);
                assert_eq!(i, 20 * index);
                assert_eq!(f64::from(time_s), 2.0 * f64::from(index));
                ticks += 1;
            }
            assert_eq!(
                matches!(e32, ClockEvent::Tick { .. }),
                matches!(ex, ClockEvent::Tick { .. }),
                "t={t}"
            );
        }
        assert_eq!(ticks, 1000);
    }

    /// Issue 8.5: tick times never become infinite and the counter re-bases instead of
    /// saturating.
    #[test]
    fn next_tick_is_finite_and_counter_rebases() {
        let mut c = GuidanceClock::new(1e30_f32).unwrap();
        step(&mut c, 3e38);
        assert!(c.next_tick_s().is_finite());
        let mut c = GuidanceClock::new(2.0_f64).unwrap();
        step(&mut c, 0.0);
        let t = 2.0 * f64::from(REBASE_AT) + 1.0;
        let e = step(&mut c, t);
        assert!(matches!(e, ClockEvent::Tick { index, .. } if index == REBASE_AT));
        assert_eq!(c.last_tick_s(), Some(t - 1.0));
        assert_eq!(c.next_tick_s(), t + 1.0);
        assert!(matches!(
            step(&mut c, t + 1.0),
            ClockEvent::Tick { index: 1, .. }
        ));
    }

    /// Huge times (saturated fixed point, f32 beyond 2^24 periods) terminate promptly and
    /// give a tick at or before the sample time.
    #[test]
    fn huge_time_jumps_terminate() {
        let mut cx = GuidanceClock::new(Fixed::from_f64(2.0)).unwrap();
        step(&mut cx, 0.0);
        let e = step(&mut cx, 1e300);
        assert!(matches!(e, ClockEvent::Tick { time_s, .. } if time_s <= Fixed::MAX));
        assert_eq!(step(&mut cx, 1e300), ClockEvent::Hold);
        let mut c32 = GuidanceClock::new(2.0_f32).unwrap();
        step(&mut c32, 0.0);
        for t in [1e9, 3e9, 1e20, 1e38] {
            if let ClockEvent::Tick { time_s, .. } = step(&mut c32, t) {
                assert!(f64::from(time_s) <= t);
            }
        }
    }
}
