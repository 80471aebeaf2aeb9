//! The application's onboard clock: a monotonic microsecond tick timer ([`TickTimer`]) that
//! measures each guidance tick's execution time against the guidance period
//! ([`TickMonitor`]: overrun counter, longest tick), and the pacing mode ([`Pacing`]).
//!
//! Guidance *time* (what the guidance clock of `guidance_core::clock` ticks on) is always the
//! nav frame's time stamp, the navigation system's clock: in lockstep PIL that is the host's
//! simulated time, so runs stay deterministic and comparable bit for bit with SIL. The tick
//! timer only measures: how long the firmware took to answer a tick, and, when free-running,
//! how long to wait until the next period starts.
//!
//! * [`Pacing::Lockstep`] (QEMU `pil`): the host paces the run; the application answers each
//!   nav frame at once. Tick durations are measured (QEMU's SysTick, which runs on QEMU's
//!   virtual clock: host wall time without `-icount`), so they say how long the emulator took,
//!   not how long a real core would.
//! * [`Pacing::FreeRunning`] (`stm32f4-flight`): after answering a tick the application waits
//!   out the rest of the period with an embedded-hal [`DelayNs`], measured from the moment the
//!   nav frame arrived, so ticks start at most once per period in real time. The navigation
//!   system sends its next sample after receiving the command (the command frame is the
//!   request for it).
//!
//! Wrap-around: the timer is a free-running `u32` of microseconds (wrapping after 2^32 us,
//! 71.6 min); durations are `end.wrapping_sub(start)`, exact across one wrap, so any tick
//! shorter than 71.6 min is measured correctly.

use embedded_hal::delay::DelayNs;

/// A free-running monotonic microsecond counter.
pub trait TickTimer {
    /// The counter now \[us\], wrapping modulo 2^32 (differences with `wrapping_sub` are
    /// durations).
    fn now_us(&mut self) -> u32;
}

impl<T: TickTimer + ?Sized> TickTimer for &mut T {
    fn now_us(&mut self) -> u32 {
        (**self).now_us()
    }
}

/// No delay at all: the delay type of [`Pacing::Lockstep`] (uninhabited, never constructed).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NoDelay {}

impl DelayNs for NoDelay {
    fn delay_ns(&mut self, _ns: u32) {
        match *self {}
    }
}

/// How the application paces its ticks.
#[derive(Debug)]
pub enum Pacing<D> {
    /// The nav source paces the run (lockstep PIL): answer every frame at once.
    Lockstep,
    /// Free-running: after a tick, wait out the rest of the guidance period with this delay.
    FreeRunning(D),
}

/// Lockstep pacing (no delay type to name).
pub const LOCKSTEP: Pacing<NoDelay> = Pacing::Lockstep;

/// Tick timing counters of a run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TickStats {
    /// Guidance ticks measured \[-\].
    pub ticks: u32,
    /// Ticks whose execution took longer than the guidance period \[-\].
    pub overruns: u32,
    /// Longest tick execution \[us\].
    pub max_tick_us: u32,
    /// Last tick execution \[us\].
    pub last_tick_us: u32,
}

/// Measures guidance ticks against the period: counts overruns and keeps the longest tick.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TickMonitor {
    period_us: u32,
    stats: TickStats,
}

/// Guidance period \[s\] -> \[us\], saturating to `1..=u32::MAX` (a NaN or non-positive period
/// becomes 1 us: every tick then overruns, which is reported rather than hidden).
#[must_use]
pub fn period_us(period_s: f64) -> u32 {
    // `as` saturates and maps NaN to 0.
    // Rounded to the nearest microsecond (positive values; the rest saturates to 0).
    ((period_s * 1e6 + 0.5) as u32).max(1)
}

impl TickMonitor {
    /// A monitor for the guidance period `period_us` \[us\] (at least 1 us).
    #[must_use]
    pub const fn new(period_us: u32) -> Self {
        Self {
            period_us: if period_us == 0 { 1 } else { period_us },
            stats: TickStats {
                ticks: 0,
                overruns: 0,
                max_tick_us: 0,
                last_tick_us: 0,
            },
        }
    }

    /// The guidance period \[us\].
    #[must_use]
    pub const fn period_us(&self) -> u32 {
        self.period_us
    }

    /// Change the guidance period to `period_us` \[us\] (at least 1 us; e.g. after a set-up
    /// with another period); the counters are kept.
    pub fn set_period_us(&mut self, period_us: u32) {
        self.period_us = period_us.max(1);
    }

    /// Record one tick that started at `start_us` and ended at `end_us` (timer readings
    /// \[us\], wrap-safe); its duration \[us\]. A duration above the period is an overrun.
    pub fn record(&mut self, start_us: u32, end_us: u32) -> u32 {
        let d = end_us.wrapping_sub(start_us);
        let s = &mut self.stats;
        s.ticks = s.ticks.wrapping_add(1);
        s.last_tick_us = d;
        s.max_tick_us = s.max_tick_us.max(d);
        if d > self.period_us {
            s.overruns = s.overruns.wrapping_add(1);
        }
        d
    }

    /// Time left in the period that started at `start_us` when the timer reads `now_us`
    /// \[us\] (0 once the period is over).
    #[must_use]
    pub fn remaining_us(&self, start_us: u32, now_us: u32) -> u32 {
        self.period_us.saturating_sub(now_us.wrapping_sub(start_us))
    }

    /// The counters so far.
    #[must_use]
    pub const fn stats(&self) -> TickStats {
        self.stats
    }
}

/// Wait out the rest of the period that started at `start_us` (free-running pacing; nothing
/// in lockstep).
pub fn pace<T: TickTimer, D: DelayNs>(
    pacing: &mut Pacing<D>,
    timer: &mut T,
    monitor: &TickMonitor,
    start_us: u32,
) {
    if let Pacing::FreeRunning(delay) = pacing {
        let left = monitor.remaining_us(start_us, timer.now_us());
        if left > 0 {
            delay.delay_us(left);
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing)]
mod tests {
    use super::*;

    /// A fake timer: each reading advances by the next step of a script (wrapping).
    pub(crate) struct FakeTimer {
        pub now: u32,
        pub step: u32,
    }

    impl TickTimer for FakeTimer {
        fn now_us(&mut self) -> u32 {
            let t = self.now;
            self.now = self.now.wrapping_add(self.step);
            t
        }
    }

    #[test]
    fn durations_and_overruns_across_the_wrap() {
        let mut m = TickMonitor::new(2_000_000);
        // Within the period, straddling the u32 wrap.
        let start = u32::MAX - 499;
        assert_eq!(m.record(start, 1_000), 1_500);
        // Exactly the period: not an overrun.
        assert_eq!(m.record(10, 2_000_010), 2_000_000);
        assert_eq!(m.stats().overruns, 0);
        // One microsecond over, across the wrap: an overrun.
        let d = m.record(u32::MAX - 999_999, 1_000_001);
        assert_eq!(d, 2_000_001);
        let s = m.stats();
        assert_eq!(
            s,
            TickStats {
                ticks: 3,
                overruns: 1,
                max_tick_us: 2_000_001,
                last_tick_us: 2_000_001
            }
        );
        // A short tick after it keeps the maximum.
        m.record(5, 7);
        assert_eq!(m.stats().max_tick_us, 2_000_001);
        assert_eq!(m.stats().last_tick_us, 2);
    }

    #[test]
    fn remaining_time_in_the_period() {
        let m = TickMonitor::new(2_000_000);
        assert_eq!(m.remaining_us(u32::MAX - 99, 400), 1_999_500);
        assert_eq!(m.remaining_us(0, 2_000_000), 0);
        assert_eq!(m.remaining_us(0, 3_000_000), 0);
    }

    #[test]
    fn period_conversion_saturates() {
        assert_eq!(period_us(2.0), 2_000_000);
        assert_eq!(period_us(0.5e-6), 1);
        assert_eq!(period_us(f64::NAN), 1);
        assert_eq!(period_us(-3.0), 1);
        assert_eq!(period_us(1e12), u32::MAX);
        assert_eq!(TickMonitor::new(0).period_us(), 1);
    }

    /// Records every requested delay.
    struct FakeDelay(std::vec::Vec<u32>);

    impl DelayNs for FakeDelay {
        fn delay_ns(&mut self, ns: u32) {
            self.0.push(ns);
        }
        fn delay_us(&mut self, us: u32) {
            self.0.push(us.saturating_mul(1_000));
        }
    }

    #[test]
    fn free_running_waits_out_the_period_and_lockstep_does_not() {
        let m = TickMonitor::new(2_000_000);
        let mut timer = FakeTimer {
            now: u32::MAX - 100_000,
            step: 0,
        };
        let start = timer.now_us();
        timer.now = timer.now.wrapping_add(300_000);
        let mut free = Pacing::FreeRunning(FakeDelay(std::vec::Vec::new()));
        pace(&mut free, &mut timer, &m, start);
        let Pacing::FreeRunning(d) = &free else {
            panic!()
        };
        assert_eq!(d.0, [1_700_000_000]);
        // An overrun tick: no wait.
        timer.now = start.wrapping_add(2_500_000);
        pace(&mut free, &mut timer, &m, start);
        let Pacing::FreeRunning(d) = &free else {
            panic!()
        };
        assert_eq!(d.0.len(), 1);
        let mut lock = LOCKSTEP;
        pace(&mut lock, &mut timer, &m, start);
    }
}
