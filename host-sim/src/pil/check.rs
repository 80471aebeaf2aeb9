//! Every command frame from the firmware is checked against the configured angle bounds, rate
//! limits and tick timing before the host flies it (issue 8.3): a frame that fails ends the run
//! with a [`FrameViolation`].

use guidance_core::guidance::{Command, RateLimits};
use guidance_core::link::CommandFrame;
use guidance_core::nodes::AngleBounds;

/// Slack on angles for the firmware's own rounding \[rad\]: its bounds are the `f32` roundings
/// of the configured ones (at most 1 ulp of pi, 2.4e-7 rad) and a rate-limited step is one
/// `f32` product and sum (a few ulp of pi); 1e-6 rad covers both with a factor 4.
pub const ANGLE_SLACK_RAD: f64 = 1e-6;

/// Relative slack on times and rates for `f32` rounding on the firmware: 4 `f32` epsilons
/// (4.8e-7), times max(|t| \[s\], 1).
pub const RELATIVE_SLACK: f64 = 4.0 * f32::EPSILON as f64;

/// What a command frame violated.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum FrameViolation {
    /// An angle outside the configured bounds.
    #[error(
        "{what} = {value_rad:.6e} rad outside the configured bounds [{min_rad:.6e}, {max_rad:.6e}] rad"
    )]
    OutOfBounds {
        /// Which angle (`command alpha`, `ramp-start sigma`, ...).
        what: &'static str,
        /// Its value \[rad\].
        value_rad: f64,
        /// Lower bound \[rad\].
        min_rad: f64,
        /// Upper bound \[rad\].
        max_rad: f64,
    },
    /// The frame's rate limits differ from the configured ones.
    #[error(
        "rate limits ({alpha_rad_s:.6e}, {sigma_rad_s:.6e}) rad/s differ from the configured ones"
    )]
    Rates {
        /// Frame's alpha rate \[rad/s\].
        alpha_rad_s: f64,
        /// Frame's sigma rate \[rad/s\].
        sigma_rad_s: f64,
    },
    /// The tick time is not the time of the nav sample answered.
    #[error("tick time {tick_time_s:.9e} s is not the nav sample's time {nav_time_s:.9e} s")]
    TickTime {
        /// Frame's tick time \[s\].
        tick_time_s: f64,
        /// Time of the nav frame it answers \[s\].
        nav_time_s: f64,
    },
    /// The held command moved more than the rate limit allows over one period.
    #[error(
        "{what} moved {step_rad:.6e} rad in one tick, more than rate x period = {max_step_rad:.6e} rad"
    )]
    RateExceeded {
        /// Which angle.
        what: &'static str,
        /// |change| \[rad\].
        step_rad: f64,
        /// Rate limit times the time since the previous tick \[rad\].
        max_step_rad: f64,
    },
    /// The ramp does not start where the previous ramp was at the tick.
    #[error(
        "{what} ramp starts at {start_rad:.6e} rad, the previous ramp was at {expected_rad:.6e} rad"
    )]
    RampJump {
        /// Which angle.
        what: &'static str,
        /// Frame's ramp start \[rad\].
        start_rad: f64,
        /// The previous frame's attitude at this tick \[rad\].
        expected_rad: f64,
    },
}

/// The configuration a command frame must respect.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameLimits {
    /// Angle bounds \[rad\].
    pub bounds: AngleBounds<f64>,
    /// Rate limits \[rad/s\].
    pub rates: RateLimits<f64>,
    /// Attitude before the first tick \[rad\].
    pub initial: Command<f64>,
    /// Guidance period \[s\].
    pub period_s: f64,
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= RELATIVE_SLACK * scale.abs().max(1.0)
}

impl FrameLimits {
    /// Check `c`, the answer to a nav sample at `nav_time_s` \[s\], after `prev` (the last
    /// accepted frame, `None` before the first).
    ///
    /// # Errors
    /// The first [`FrameViolation`] found.
    pub fn check(
        &self,
        c: &CommandFrame,
        nav_time_s: f64,
        prev: Option<&CommandFrame>,
    ) -> Result<(), FrameViolation> {
        let b = &self.bounds;
        let angles = [
            (
                "command alpha",
                c.command.alpha_rad,
                b.alpha_min_rad,
                b.alpha_max_rad,
            ),
            (
                "command sigma",
                c.command.sigma_rad,
                b.sigma_min_rad,
                b.sigma_max_rad,
            ),
            (
                "ramp-start alpha",
                c.ramp_start.alpha_rad,
                b.alpha_min_rad,
                b.alpha_max_rad,
            ),
            (
                "ramp-start sigma",
                c.ramp_start.sigma_rad,
                b.sigma_min_rad,
                b.sigma_max_rad,
            ),
        ];
        for (what, value_rad, min_rad, max_rad) in angles {
            if !(value_rad >= min_rad - ANGLE_SLACK_RAD && value_rad <= max_rad + ANGLE_SLACK_RAD) {
                return Err(FrameViolation::OutOfBounds {
                    what,
                    value_rad,
                    min_rad,
                    max_rad,
                });
            }
        }
        if !(close(
            c.rates.alpha_rad_s,
            self.rates.alpha_rad_s,
            self.rates.alpha_rad_s,
        ) && close(
            c.rates.sigma_rad_s,
            self.rates.sigma_rad_s,
            self.rates.sigma_rad_s,
        )) {
            return Err(FrameViolation::Rates {
                alpha_rad_s: c.rates.alpha_rad_s,
                sigma_rad_s: c.rates.sigma_rad_s,
            });
        }
        if !close(c.tick_time_s, nav_time_s, nav_time_s) {
            return Err(FrameViolation::TickTime {
                tick_time_s: c.tick_time_s,
                nav_time_s,
            });
        }
        // The attitude the previous ramp had reached at this tick.
        let before = prev.map_or(self.initial, |p| p.attitude_at(c.tick_time_s));
        let pairs = [
            (
                "alpha",
                c.ramp_start.alpha_rad,
                before.alpha_rad,
                c.command.alpha_rad,
                self.rates.alpha_rad_s,
            ),
            (
                "sigma",
                c.ramp_start.sigma_rad,
                before.sigma_rad,
                c.command.sigma_rad,
                self.rates.sigma_rad_s,
            ),
        ];
        for (what, start, expected, command, rate) in pairs {
            if (start - expected).abs() > ANGLE_SLACK_RAD {
                return Err(FrameViolation::RampJump {
                    what,
                    start_rad: start,
                    expected_rad: expected,
                });
            }
            // The held command is at most one period's rate-limited step from the attitude at
            // the tick (the core limits the step over its period).
            let max_step_rad = rate * self.period_s;
            let step_rad = (command - start).abs();
            if step_rad > max_step_rad * (1.0 + RELATIVE_SLACK) + ANGLE_SLACK_RAD {
                return Err(FrameViolation::RateExceeded {
                    what,
                    step_rad,
                    max_step_rad,
                });
            }
        }
        Ok(())
    }
}
