//! [`BankReversalLogic`]: the sign of the bank angle from the heading error to the target.

use crate::command::BankSign;
use crate::error::GuidanceError;
use crate::geo::{central_angle, initial_bearing, wrap_pi};
use crate::nav::NavState;
use crate::replan::TargetPoint;
use crate::scalar::Real;

use super::corridor::Corridor;
use super::terminal::{TerminalLateral, reverse_now};

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

/// Default [`LateralConfig::hysteresis_rad`] \[deg\].
pub const DEFAULT_HYSTERESIS_DEG: f64 = 1.0;
/// Default [`LateralConfig::max_reversals`].
pub const DEFAULT_MAX_REVERSALS: u8 = 12;
/// Default freeze distance \[m\]: no reversal within 30 km of the target.
pub const DEFAULT_FREEZE_DISTANCE_M: f64 = 30_000.0;

impl<S: Real> LateralConfig<S> {
    /// The default logic for `target` with `corridor` (e.g.
    /// [`Corridor::narrowing_with_speed`]) on a planet of radius `planet_radius_m` \[m\]:
    /// hysteresis [`DEFAULT_HYSTERESIS_DEG`], at most [`DEFAULT_MAX_REVERSALS`] reversals, no
    /// reversal within [`DEFAULT_FREEZE_DISTANCE_M`] of the target (the dispersion
    /// campaigns' defaults).
    ///
    /// ```
    /// use guidance_core::lateral::{BankReversalLogic, Corridor, LateralConfig};
    /// use guidance_core::replan::TargetPoint;
    /// let target = TargetPoint { latitude_rad: 0.1_f64, longitude_rad: 1.2 };
    /// let corridor = Corridor::narrowing_with_speed(7600.0, 2500.0)?;
    /// let logic = BankReversalLogic::new(LateralConfig::new(target, corridor, 6_378_137.0))?;
    /// assert_eq!(logic.reversals(), 0);
    /// # Ok::<(), guidance_core::GuidanceError>(())
    /// ```
    #[must_use]
    pub fn new(target: TargetPoint<S>, corridor: Corridor<S>, planet_radius_m: S) -> Self {
        let deg = S::PI / S::from_f64(180.0);
        Self {
            target,
            corridor,
            hysteresis_rad: S::from_f64(DEFAULT_HYSTERESIS_DEG) * deg,
            max_reversals: DEFAULT_MAX_REVERSALS,
            freeze_angle_rad: S::from_f64(DEFAULT_FREEZE_DISTANCE_M) / planet_radius_m,
        }
    }
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
    terminal: Option<TerminalLateral<S>>,
    /// Latitude and longitude at the previous call \[rad\] (the measured turn).
    previous: Option<(S, S)>,
    /// Time of the last reversal \[s\].
    last_reversal_s: Option<S>,
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
            terminal: None,
            previous: None,
            last_reversal_s: None,
        })
    }

    /// Decide the last reversals with the terminal crossrange law once the target is closer
    /// than `terminal.start_angle_rad` ([`TerminalLateral`]; without: the corridor to the end).
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] for invalid terminal settings.
    pub fn with_terminal(mut self, terminal: TerminalLateral<S>) -> Result<Self, GuidanceError> {
        terminal.validate()?;
        self.terminal = Some(terminal);
        Ok(self)
    }

    /// The terminal law's settings (`None`: off).
    #[must_use]
    pub fn terminal(&self) -> Option<&TerminalLateral<S>> {
        self.terminal.as_ref()
    }

    /// The terminal law's decision at `nav` for `sign` in force, heading error `dpsi` and
    /// range angle `theta` \[rad\]: `Some(reverse?)` inside the terminal range, `None`
    /// outside it (the corridor decides).
    fn terminal_reverses(
        &self,
        nav: &NavState<S>,
        sign: BankSign,
        dpsi: S,
        theta: S,
    ) -> Option<bool> {
        let t = self.terminal?;
        if theta >= t.start_angle_rad {
            return None;
        }
        let c = match sign {
            BankSign::Positive => S::ONE,
            BankSign::Negative => -S::ONE,
        };
        let Some((kappa, step)) = self.measured_turn(nav) else {
            return Some(false);
        };
        let two = S::ONE + S::ONE;
        // The target behind (passed): the end is no longer ahead, nothing to null.
        if dpsi.abs() > S::PI / two {
            return Some(false);
        }
        let settled = self
            .last_reversal_s
            .is_none_or(|t0| nav.time_s - t0 >= two * t.reversal_lead_s);
        if !(c * kappa > S::ZERO && settled) {
            return Some(false);
        }
        let ground_rate = nav.speed_m_s * nav.flight_path_angle_rad.cos() / nav.radius_m;
        let d = t.reversal_lead_s * ground_rate;
        Some(reverse_now(theta, dpsi, kappa, c, d, step, t.tolerance_rad))
    }

    /// The heading's turn per angle flown since the previous call \[rad/rad\] (positive:
    /// clockwise) and that angle \[rad\], `None` without a previous position or with no
    /// motion.
    fn measured_turn(&self, nav: &NavState<S>) -> Option<(S, S)> {
        let (lat0, lon0) = self.previous?;
        let (lat, lon) = (nav.latitude_rad, nav.longitude_rad);
        let delta = central_angle(lat0, lon0, lat, lon)?;
        if !(delta > S::EPSILON) {
            return None;
        }
        // The chord's direction at the current point, from the bearing back to the previous
        // point; on a circular arc the heading is turned from it by half the arc's turn.
        let back = initial_bearing(lat, lon, lat0, lon0)?;
        let half_turn = wrap_pi(nav.heading_rad - (back + S::PI))?;
        let kappa = (half_turn + half_turn) / delta;
        kappa.is_finite().then_some((kappa, delta))
    }

    /// Decide the bank sign at `nav` (call at each guidance tick, before the guidance update).
    ///
    /// # Errors
    /// [`GuidanceError::NonFiniteState`] / [`GuidanceError::UnphysicalState`] for a bad
    /// navigation state; nothing changes then.
    ///
    /// ```
    /// use guidance_core::guidance::BankSign;
    /// use guidance_core::lateral::{BankReversalLogic, Corridor, LateralConfig};
    /// use guidance_core::replan::TargetPoint;
    /// use guidance_core::NavState;
    /// // Target due east on the equator; the vehicle heads 20 deg left of it (north of east).
    /// let target = TargetPoint { latitude_rad: 0.0_f64, longitude_rad: 0.5 };
    /// let corridor = Corridor::narrowing_with_speed(7600.0, 2500.0)?;
    /// let mut logic = BankReversalLogic::new(LateralConfig::new(target, corridor, 6_378_137.0))?;
    /// let nav = NavState {
    ///     time_s: 0.0,
    ///     radius_m: 6_378_137.0 + 80e3,
    ///     speed_m_s: 7000.0,
    ///     flight_path_angle_rad: -0.01,
    ///     heading_rad: 70.0_f64.to_radians(),
    ///     latitude_rad: 0.0,
    ///     longitude_rad: 0.0,
    /// };
    /// let first = logic.update(&nav)?; // the sign that reduces the heading error: right
    /// assert!((first.heading_error_rad.to_degrees() + 20.0).abs() < 0.1);
    /// assert_eq!((first.sign, first.reversed), (BankSign::Positive, false));
    /// // Later the bank has turned the vehicle 20 deg right of the target, outside the
    /// // 15 deg corridor: the sign reverses.
    /// let later = NavState { time_s: 60.0, heading_rad: 110.0_f64.to_radians(), ..nav };
    /// let status = logic.update(&later)?;
    /// assert_eq!((status.sign, status.reversed), (BankSign::Negative, true));
    /// # Ok::<(), guidance_core::GuidanceError>(())
    /// ```
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
                let wanted = match self.terminal_reverses(nav, sign, dpsi, theta) {
                    Some(terminal) => terminal,
                    None => diverging && self.armed && dpsi.abs() > width,
                };
                if wanted
                    && self.reversals < self.config.max_reversals
                    && theta > self.config.freeze_angle_rad
                {
                    reversed = true;
                    self.reversals = self.reversals.saturating_add(1);
                    self.armed = false;
                    self.last_reversal_s = Some(nav.time_s);
                    sign.reversed()
                } else {
                    sign
                }
            }
        };
        self.sign = Some(sign);
        self.previous = Some((lat, lon));
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
