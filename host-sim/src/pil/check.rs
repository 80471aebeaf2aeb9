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

#[cfg(test)]
mod tests {
    //! Issue 8 item 3: every rule of [`FrameLimits::check`] rejects a frame that breaks it
    //! (the PIL reliability tests reproduce only the three frames, which fail on the
    //! bounds and the tick time) and accepts the firmware's legitimate frames.
    use super::*;

    const DEG: f64 = std::f64::consts::PI / 180.0;

    fn cmd(alpha_deg: f64, sigma_deg: f64) -> Command<f64> {
        Command {
            alpha_rad: alpha_deg * DEG,
            sigma_rad: sigma_deg * DEG,
        }
    }

    /// HORUS-2B-like configuration: alpha 0..45 deg, sigma -90..90 deg, 5 and 15 deg/s, 2 s.
    fn limits() -> FrameLimits {
        FrameLimits {
            bounds: AngleBounds {
                alpha_min_rad: 0.0,
                alpha_max_rad: 45.0 * DEG,
                sigma_min_rad: -90.0 * DEG,
                sigma_max_rad: 90.0 * DEG,
            },
            rates: RateLimits::thesis_default(),
            initial: cmd(40.0, 0.0),
            period_s: 2.0,
        }
    }

    /// A legitimate first answer at `t`: from the initial attitude, one rate-limited step.
    fn first(t: f64) -> CommandFrame {
        CommandFrame {
            seq: 0,
            status: guidance_core::link::LinkStatus::Ok,
            tick_time_s: t,
            command: cmd(35.0, 30.0),
            ramp_start: cmd(40.0, 0.0),
            rates: RateLimits::thesis_default(),
            reversals: 0,
            replans: 0,
        }
    }

    #[test]
    fn legitimate_frames_pass() {
        let l = limits();
        let a = first(0.0);
        l.check(&a, 0.0, None).unwrap();
        // The next tick starts where the previous ramp is (reached: 35, 30 deg) and steps again.
        let b = CommandFrame {
            seq: 1,
            tick_time_s: 2.0,
            ramp_start: a.attitude_at(2.0),
            command: cmd(30.0, 60.0),
            ..a
        };
        l.check(&b, 2.0, Some(&a)).unwrap();
        // The firmware's f32 rounding is tolerated: bounds, rates and times within the slack.
        let c = CommandFrame {
            seq: 2,
            tick_time_s: 4.0 * (1.0 + 0.5 * RELATIVE_SLACK),
            ramp_start: b.attitude_at(4.0),
            command: Command {
                alpha_rad: 30.0 * DEG,
                sigma_rad: 90.0 * DEG + 0.5 * ANGLE_SLACK_RAD,
            },
            rates: RateLimits {
                alpha_rad_s: 5.0 * DEG * (1.0 + 0.5 * RELATIVE_SLACK),
                sigma_rad_s: 15.0 * DEG,
            },
            ..b
        };
        l.check(&c, 4.0, Some(&b)).unwrap();
    }

    #[test]
    fn every_angle_is_checked_against_the_bounds() {
        let l = limits();
        let cases = [
            ("command alpha", Some(cmd(46.0, 0.0)), None),
            ("command sigma", Some(cmd(40.0, -91.0)), None),
            ("ramp-start alpha", None, Some(cmd(-1.0, 0.0))),
            ("ramp-start sigma", None, Some(cmd(40.0, 180.0))),
            ("command sigma", Some(cmd(40.0, f64::NAN)), None),
        ];
        for (what, command, ramp_start) in cases {
            let mut f = first(0.0);
            if let Some(c) = command {
                f.command = c;
            }
            if let Some(r) = ramp_start {
                f.ramp_start = r;
            }
            match l.check(&f, 0.0, None) {
                Err(FrameViolation::OutOfBounds { what: w, .. }) => assert_eq!(w, what),
                other => panic!("{what}: {other:?}"),
            }
        }
    }

    #[test]
    fn rates_other_than_the_configured_ones_are_rejected() {
        let l = limits();
        for rates in [
            RateLimits {
                alpha_rad_s: 5.0 * DEG,
                sigma_rad_s: 150.0 * DEG,
            },
            RateLimits {
                alpha_rad_s: 5.0 * DEG + 2.0 * RELATIVE_SLACK,
                sigma_rad_s: 15.0 * DEG,
            },
            RateLimits {
                alpha_rad_s: f64::INFINITY,
                sigma_rad_s: 15.0 * DEG,
            },
        ] {
            let f = CommandFrame {
                rates,
                ..first(0.0)
            };
            assert!(
                matches!(l.check(&f, 0.0, None), Err(FrameViolation::Rates { .. })),
                "{rates:?}"
            );
        }
    }

    #[test]
    fn a_tick_time_other_than_the_nav_samples_is_rejected() {
        let l = limits();
        for (tick_s, nav_s) in [
            (2.0, 0.0),
            (-2.0, 0.0),
            (1e300, 0.0),
            (100.0 * (1.0 + 4.0 * RELATIVE_SLACK), 100.0),
        ] {
            let f = first(tick_s);
            assert!(
                matches!(
                    l.check(&f, nav_s, None),
                    Err(FrameViolation::TickTime { .. })
                ),
                "tick {tick_s} for nav {nav_s}"
            );
        }
    }

    #[test]
    fn a_ramp_that_jumps_or_a_step_beyond_rate_times_period_is_rejected() {
        let l = limits();
        // The first ramp must start at the initial attitude.
        let jump = CommandFrame {
            ramp_start: cmd(40.0, 5.0),
            command: cmd(40.0, 5.0),
            ..first(0.0)
        };
        assert!(matches!(
            l.check(&jump, 0.0, None),
            Err(FrameViolation::RampJump { what: "sigma", .. })
        ));
        // Later ramps start where the previous one is at the tick (35 deg alpha reached).
        let a = first(0.0);
        let b = CommandFrame {
            seq: 1,
            tick_time_s: 2.0,
            ramp_start: cmd(40.0, 30.0),
            command: cmd(40.0, 30.0),
            ..a
        };
        assert!(matches!(
            l.check(&b, 2.0, Some(&a)),
            Err(FrameViolation::RampJump { what: "alpha", .. })
        ));
        // A held command more than rate x period (10 deg alpha, 30 deg sigma) away.
        for (command, what) in [(cmd(29.0, 0.0), "alpha"), (cmd(40.0, -31.0), "sigma")] {
            let f = CommandFrame {
                command,
                ..first(0.0)
            };
            match l.check(&f, 0.0, None) {
                Err(FrameViolation::RateExceeded { what: w, .. }) => assert_eq!(w, what),
                other => panic!("{command:?}: {other:?}"),
            }
        }
    }
}
