//! [`BankReversalLogic`]: the sign of the bank angle from the heading error to the target.

use crate::command::BankSign;
use crate::error::GuidanceError;
use crate::geo::{central_angle, initial_bearing, wrap_pi};
use crate::nav::NavState;
use crate::replan::TargetPoint;
use crate::scalar::Real;

use super::corridor::Corridor;

/// Settings of [`BankReversalLogic`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LateralConfig<S> {
    /// The target point (latitude, longitude at the terminal interface) \[rad\].
    pub target: TargetPoint<S>,
    /// Heading-error corridor.
    pub corridor: Corridor<S>,
    /// Re-arm margin below the corridor half-width \[rad\], `>= 0` (module docs).
    pub hysteresis_rad: S,
    /// Largest number of reversals (0: the first sign is kept).
    pub max_reversals: u8,
    /// No reversal once the great-circle angle to the target is below this \[rad\], `>= 0`
    /// (near the target the bearing, hence the heading error, is ill-defined).
    pub freeze_angle_rad: S,
}

/// What one [`BankReversalLogic::update`] decided.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LateralStatus<S> {
    /// Bank sign to fly.
    pub sign: BankSign,
    /// Heading error `wrap(heading - bearing to target)` \[rad\] (positive: right of target).
    pub heading_error_rad: S,
    /// Corridor half-width at this state \[rad\].
    pub corridor_rad: S,
    /// Great-circle angle to the target \[rad\].
    pub range_angle_rad: S,
    /// Reversals made so far (this one included).
    pub reversals: u8,
    /// True if this call reversed the sign.
    pub reversed: bool,
}

/// Bank-reversal logic on a heading-error corridor (module docs of [`crate::lateral`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BankReversalLogic<S> {
    config: LateralConfig<S>,
    sign: Option<BankSign>,
    reversals: u8,
    armed: bool,
}

impl<S: Real> BankReversalLogic<S> {
    /// Set up.
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] for an invalid corridor, a non-finite target, a
    /// negative or non-finite hysteresis or freeze angle.
    pub fn new(config: LateralConfig<S>) -> Result<Self, GuidanceError> {
        config.corridor.validate()?;
        let t = config.target;
        let ok = t.latitude_rad.is_finite()
            && t.longitude_rad.is_finite()
            && config.hysteresis_rad.is_finite()
            && config.hysteresis_rad >= S::ZERO
            && config.freeze_angle_rad.is_finite()
            && config.freeze_angle_rad >= S::ZERO;
        if !ok {
            return Err(GuidanceError::InvalidConfig);
        }
        Ok(Self {
            config,
            sign: None,
            reversals: 0,
            armed: true,
        })
    }

    /// Decide the bank sign at `nav` (call at each guidance tick, before the guidance update).
    ///
    /// # Errors
    /// [`GuidanceError::NonFiniteState`] / [`GuidanceError::UnphysicalState`] for a bad
    /// navigation state; nothing changes then.
    pub fn update(&mut self, nav: &NavState<S>) -> Result<LateralStatus<S>, GuidanceError> {
        nav.validate()?;
        let t = self.config.target;
        let x = self.config.corridor.variable(nav)?;
        let (lat, lon) = (nav.latitude_rad, nav.longitude_rad);
        let theta = central_angle(lat, lon, t.latitude_rad, t.longitude_rad)
            .ok_or(GuidanceError::NonFiniteState)?;
        let bearing = initial_bearing(lat, lon, t.latitude_rad, t.longitude_rad)
            .ok_or(GuidanceError::NonFiniteState)?;
        let dpsi = wrap_pi(nav.heading_rad - bearing).ok_or(GuidanceError::NonFiniteState)?;
        let width = self.config.corridor.width_rad(x);
        let positive_error = dpsi > S::ZERO;
        let mut reversed = false;
        let sign = match self.sign {
            None => {
                if positive_error {
                    BankSign::Negative
                } else {
                    BankSign::Positive
                }
            }
            Some(sign) => {
                if !self.armed && dpsi.abs() < width - self.config.hysteresis_rad {
                    self.armed = true;
                }
                let diverging = match sign {
                    BankSign::Positive => dpsi > S::ZERO,
                    BankSign::Negative => dpsi < S::ZERO,
                };
                if diverging
                    && self.armed
                    && dpsi.abs() > width
                    && self.reversals < self.config.max_reversals
                    && theta > self.config.freeze_angle_rad
                {
                    reversed = true;
                    self.reversals = self.reversals.saturating_add(1);
                    self.armed = false;
                    sign.reversed()
                } else {
                    sign
                }
            }
        };
        self.sign = Some(sign);
        Ok(LateralStatus {
            sign,
            heading_error_rad: dpsi,
            corridor_rad: width,
            range_angle_rad: theta,
            reversals: self.reversals,
            reversed,
        })
    }

    /// The sign in force (`None` before the first update).
    #[must_use]
    pub fn sign(&self) -> Option<BankSign> {
        self.sign
    }

    /// Reversals made so far.
    #[must_use]
    pub fn reversals(&self) -> u8 {
        self.reversals
    }

    /// The settings.
    #[must_use]
    pub fn config(&self) -> &LateralConfig<S> {
        &self.config
    }
}
