//! Attitude-rate limiting (thesis sec. 4.2.3, table 2.1: alpha-dot <= 5 deg/s,
//! sigma-dot <= 15 deg/s).
//!
//! The limit is applied to the commanded change over one guidance period:
//! `new = previous + clamp(target - previous, -rate * dt, +rate * dt)`. If the target is within
//! reach it is returned *exactly* (no rounding), otherwise `previous +- rate * dt` (one rounded
//! addition, so in floating point `|new - previous|` can exceed `rate * dt` by at most half an
//! ulp of `new`).
//!
//! The limiter is monotone in both arguments and commutes with adding a constant to both, so it
//! is 1-Lipschitz in the max norm: `|f(p, t) - f(p', t')| <= max(|p - p'|, |t - t'|)`. The
//! precision analysis of [`crate::guidance`] relies on this.

use crate::command::Command;
use crate::error::GuidanceError;
use crate::scalar::Scalar;

/// Degrees to radians.
const DEG_TO_RAD: f64 = core::f64::consts::PI / 180.0;

/// Largest attitude rates \[rad/s\].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RateLimits<S> {
    /// Largest |alpha-dot| \[rad/s\].
    pub alpha_rad_s: S,
    /// Largest |sigma-dot| \[rad/s\].
    pub sigma_rad_s: S,
}

impl<S: Scalar> RateLimits<S> {
    /// HORUS-2B limits of thesis table 2.1: 5 deg/s and 15 deg/s (in rad/s).
    #[must_use]
    pub fn thesis_default() -> Self {
        Self {
            alpha_rad_s: S::from_f64(5.0 * DEG_TO_RAD),
            sigma_rad_s: S::from_f64(15.0 * DEG_TO_RAD),
        }
    }

    /// Limits from degrees per second (converted to rad/s and validated).
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] for non-finite or non-positive rates.
    pub fn from_deg_s(alpha_deg_s: f64, sigma_deg_s: f64) -> Result<Self, GuidanceError> {
        let c = |v: f64| S::from_f64_checked(v * DEG_TO_RAD).ok_or(GuidanceError::InvalidConfig);
        let r = Self {
            alpha_rad_s: c(alpha_deg_s)?,
            sigma_rad_s: c(sigma_deg_s)?,
        };
        r.validate()?;
        Ok(r)
    }

    /// Both rates must be finite and strictly positive.
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] otherwise.
    pub fn validate(&self) -> Result<(), GuidanceError> {
        let ok = |v: S| v.is_finite() && v > S::ZERO;
        if ok(self.alpha_rad_s) && ok(self.sigma_rad_s) {
            Ok(())
        } else {
            Err(GuidanceError::InvalidConfig)
        }
    }
}

impl<S: Scalar> Default for RateLimits<S> {
    fn default() -> Self {
        Self::thesis_default()
    }
}

/// Move from `previous` towards `target` by at most `max_step` (>= 0): returns `target` if
/// `|target - previous| <= max_step`, else `previous + max_step * sign(target - previous)`.
/// A negative `max_step` is treated as zero. Callers pass finite values.
#[must_use]
pub fn limit_step<S: Scalar>(previous: S, target: S, max_step: S) -> S {
    let step = max_step.max(S::ZERO);
    let delta = target - previous;
    if delta > step {
        previous + step
    } else if delta < -step {
        previous - step
    } else {
        target
    }
}

/// Rate-limit a whole command over `dt_s` \[s\] (>= 0): each angle moves towards `target` by at
/// most `rate * dt_s`.
#[must_use]
pub fn limit_command<S: Scalar>(
    previous: Command<S>,
    target: Command<S>,
    rates: RateLimits<S>,
    dt_s: S,
) -> Command<S> {
    Command {
        alpha_rad: limit_step(
            previous.alpha_rad,
            target.alpha_rad,
            rates.alpha_rad_s * dt_s,
        ),
        sigma_rad: limit_step(
            previous.sigma_rad,
            target.sigma_rad,
            rates.sigma_rad_s * dt_s,
        ),
    }
}

/// When a rate-limited ramp reaches its target, per angle \[s\] (see [`ramp_end`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RampEnd<S> {
    /// Time the angle of attack reaches the command \[s\] (the ramp start if it does not move).
    pub alpha_s: S,
    /// Time the bank angle reaches the command \[s\] (the ramp start if it does not move).
    pub sigma_s: S,
}

impl<S: Scalar> RampEnd<S> {
    /// The later of the two: from then on the attitude equals the command \[s\].
    #[must_use]
    pub fn latest(&self) -> S {
        self.alpha_s.max(self.sigma_s)
    }

    /// The earliest per-angle end strictly after `time_s` \[s\] (a kink of the attitude
    /// history: one angle stops moving); `None` if both ends are at or before `time_s` (or
    /// non-finite).
    #[must_use]
    pub fn next_after(&self, time_s: S) -> Option<S> {
        let mut best: Option<S> = None;
        for end in [self.alpha_s, self.sigma_s] {
            if end.is_finite() && end > time_s {
                best = Some(match best {
                    Some(b) => b.min(end),
                    None => end,
                });
            }
        }
        best
    }
}

/// End of the ramp that starts at `start_s` \[s\] from `start` and moves towards `target` at
/// `rates` (the ramp of [`limit_command`] over a growing `dt`): per angle,
/// `start_s + |target - start| / rate`. Where the change is within one period's step (always,
/// for a guidance command) this is at most one period after `start_s`, up to rounding.
#[must_use]
pub fn ramp_end<S: Scalar>(
    start: Command<S>,
    target: Command<S>,
    rates: RateLimits<S>,
    start_s: S,
) -> RampEnd<S> {
    RampEnd {
        alpha_s: start_s + (target.alpha_rad - start.alpha_rad).abs() / rates.alpha_rad_s,
        sigma_s: start_s + (target.sigma_rad - start.sigma_rad).abs() / rates.sigma_rad_s,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Fixed;

    #[test]
    fn limits_and_passes_through() {
        assert_eq!(limit_step(0.0, 1.0, 0.25), 0.25);
        assert_eq!(limit_step(0.0, -1.0, 0.25), -0.25);
        assert_eq!(limit_step(0.0, 0.1, 0.25), 0.1);
        assert_eq!(limit_step(0.3, 0.1, -5.0), 0.3);
        let f = |v: f64| Fixed::from_f64(v);
        assert_eq!(limit_step(f(1.0), f(3.0), f(0.5)), f(1.5));
    }

    #[test]
    fn ramp_end_per_angle_and_next_kink() {
        let rates = RateLimits::<f64> {
            alpha_rad_s: 0.5,
            sigma_rad_s: 1.0,
        };
        let start = Command {
            alpha_rad: 0.0,
            sigma_rad: 0.0,
        };
        let target = Command {
            alpha_rad: 0.1,
            sigma_rad: -0.3,
        };
        let end = ramp_end(start, target, rates, 10.0);
        assert_eq!(
            end,
            RampEnd {
                alpha_s: 10.2,
                sigma_s: 10.3
            }
        );
        assert_eq!(end.latest(), 10.3);
        assert_eq!(end.next_after(10.0), Some(10.2));
        assert_eq!(end.next_after(10.25), Some(10.3));
        assert_eq!(end.next_after(10.3), None);
        // The ramp of limit_command reaches each angle exactly there.
        let at = |dt: f64| limit_command(start, target, rates, dt);
        assert!((at(0.19).alpha_rad - 0.095).abs() < 1e-15);
        assert_eq!(at(0.2 + 1e-12).alpha_rad, 0.1);
        assert_eq!(at(0.3 + 1e-12).sigma_rad, -0.3);
        // An angle that does not move ends at the ramp start (never "after" it).
        let still = ramp_end(start, start, rates, 4.0);
        assert_eq!(still.latest(), 4.0);
        assert_eq!(still.next_after(4.0), None);
        // Fixed point works the same way.
        let f = |v: f64| Fixed::from_f64(v);
        let rf = RateLimits {
            alpha_rad_s: f(0.5),
            sigma_rad_s: f(1.0),
        };
        let tf = Command {
            alpha_rad: f(0.25),
            sigma_rad: f(0.5),
        };
        let sf = Command {
            alpha_rad: f(0.0),
            sigma_rad: f(0.0),
        };
        let e = ramp_end(sf, tf, rf, f(2.0));
        assert_eq!((e.alpha_s, e.sigma_s), (f(2.5), f(2.5)));
    }

    #[test]
    fn default_rates_are_thesis_values() {
        let r = RateLimits::<f64>::default();
        assert!((r.alpha_rad_s - 5.0_f64.to_radians()).abs() < 1e-15);
        assert!((r.sigma_rad_s - 15.0_f64.to_radians()).abs() < 1e-15);
        assert!(r.validate().is_ok());
        assert!(RateLimits::<f64>::from_deg_s(0.0, 1.0).is_err());
        assert!(RateLimits::<f64>::from_deg_s(f64::NAN, 1.0).is_err());
        assert!(RateLimits::<f64>::from_deg_s(2.0, 1.0).is_ok());
    }
}
