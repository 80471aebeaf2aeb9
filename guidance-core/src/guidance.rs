//! The guidance loop: navigation state -> independent variable -> interpolated command ->
//! rate limit -> 2 s zero-order hold, plus the continuous attitude ramp between ticks.
//!
//! # Timing
//! [`Guidance::update`] is called with every navigation sample. The first call is a tick and
//! starts the clock at `t0 = nav.time_s`; later ticks are at `t0 + k * 2 s` (integer counter,
//! see [`crate::clock`]). At a tick at time `t_k`:
//!
//! 1. `target = interpolate(x)`, with `x` the normalised energy of the sample (or its time, for
//!    time-indexed tables); clamped into the angle bounds;
//! 2. `start = attitude_at(t_s)`, the attitude the previous ramp has reached at the sample time
//!    `t_s` (`t_s = t_k` when samples arrive on the ticks, as in the simulator and PIL);
//! 3. `command = start + clamp(target - start, +-rate * period)` (see [`crate::rate`]). The
//!    commanded change per period is thus limited relative to the attitude at the sample time,
//!    which is the previous command whenever the previous ramp had completed (always so when
//!    samples arrive on their tick instants).
//!
//! Between ticks the command is held. [`Guidance::attitude_at`] gives the attitude the vehicle
//! is commanded to fly: from `start` at the sample time `t_s` ([`Guidance::ramp_start_s`]) it
//! moves towards the held command at the rate limits and reaches it no later than
//! `t_s + period`. The new ramp starts where the old one was at `t_s`, so the attitude is
//! continuous in time even when a sample arrives late (after its tick instant), and it never
//! exceeds the rate limits, so a g-load rate computed from the simulated attitude sees no
//! artificial steps.
//!
//! # Gaps and errors
//! * If the sample time has passed several tick instants (a navigation gap), guidance
//!   recomputes **once**, at the latest tick instant `<= nav.time_s`, with the *normal* per-
//!   period step `rate * period`: missed ticks are not made up, the command converges over the
//!   following ticks. The ramp starts at the sample time from the attitude reached there, so
//!   both guarantees above hold (rate never exceeded, command reached within one period of the
//!   ramp start, attitude continuous).
//! * A sample that is non-finite, unphysical (radius <= 0, speed < 0) or earlier than the last
//!   tick is rejected with an error; nothing changes (the clock does not advance, the held
//!   command and the ramp stay valid).
//!
//! # Guarantees
//! Every command and attitude that comes out is finite and inside the table's angle bounds.
//!
//! # Precision of `f32` and fixed point relative to `f64`
//! Let `e_k` be the difference between the commands of two runs (say `f32` and `f64`) fed the
//! same navigation samples, with tick instants that coincide (sample times exactly
//! representable in both types, e.g. multiples of 0.25 s below 2^22 s). The rate limiter is
//! 1-Lipschitz in the max norm (see [`crate::rate`]) and returns the target exactly when it is
//! within reach, so per tick
//!
//! * `e_k <= e_target` when neither run is rate-limited at tick `k`;
//! * `e_k <= max(e_{k-1}, e_target) + r` otherwise, with `r` the rounding of one addition
//!   (one ulp of an angle <= pi/2 in `f32`: 1.2e-7 rad; 2^-32 rad in fixed point);
//!
//! hence `e_k <= e_0 + e_target + L_k * r`, with `L_k` the length of the current run of ticks
//! in which either run was limited. The target error is
//! `e_target <= Lip * dx + C * u * A`: `Lip` the largest slope of the interpolant [rad per
//! unit x], `dx` the error of the independent variable (time: 0, exact; E-hat: 2e-6 in `f32`,
//! 1e-8 in fixed point, the bounds asserted by [`crate::energy`]'s tests), `u` the unit
//! roundoff (2^-24 for `f32`, an absolute 2^-32 for fixed point), `A` the magnitude of the
//! quantities in one evaluation (angles and tangents, a few radians) and `C` a count of rounded
//! operations (node conversion, `t`, the Hermite sum, the tangent solve: C = 64 is used). The
//! test `guidance_props::f32_and_fixed_agree_with_f64` measures `Lip` by sampling the `f64`
//! interpolant and `L_k` from the runs, and checks this bound.

use crate::clock::{ClockEvent, GuidanceClock};
use crate::energy::EnergyNormalizer;
use crate::error::GuidanceError;
use crate::interp::{Interpolation, Interpolator};
use crate::nav::NavState;
use crate::nodes::{DEFAULT_NODE_CAPACITY, HOST_NODE_CAPACITY, Independent, NodeTable};
use crate::plausibility::{TimeGate, TimeVerdict, TimeWindow};
use crate::rate::{RampEnd, limit_command, ramp_end};
use crate::scalar::Scalar;

pub use crate::command::{BankSign, Command};
pub use crate::rate::RateLimits;

/// Guidance configuration.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct GuidanceConfig<S> {
    /// Guidance period \[s\] (thesis: 2.0 s, zero-order hold).
    pub period_s: S,
    /// Attitude rate limits.
    pub rates: RateLimits<S>,
}

impl<S: Scalar> GuidanceConfig<S> {
    /// Thesis values: 2.0 s period, 5 deg/s and 15 deg/s rate limits.
    #[must_use]
    pub fn thesis_default() -> Self {
        Self {
            period_s: S::from_f64(2.0),
            rates: RateLimits::thesis_default(),
        }
    }

    /// Period finite and > 0, rates finite and > 0.
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] otherwise.
    pub fn validate(&self) -> Result<(), GuidanceError> {
        if !(self.period_s.is_finite() && self.period_s > S::ZERO) {
            return Err(GuidanceError::InvalidConfig);
        }
        self.rates.validate()
    }
}

impl<S: Scalar> Default for GuidanceConfig<S> {
    fn default() -> Self {
        Self::thesis_default()
    }
}

/// [`Guidance`] over a host-sized node table ([`HOST_NODE_CAPACITY`] nodes).
pub type HostGuidance<S> = Guidance<S, HOST_NODE_CAPACITY>;

/// Result of one [`Guidance::update`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct GuidanceOutput<S> {
    /// The held command after this update \[rad\].
    pub command: Command<S>,
    /// True if this sample was a tick (the command was recomputed).
    pub ticked: bool,
    /// The independent variable of this sample: E-hat \[-\] or time \[s\].
    pub independent_value: S,
}

/// The guidance function (see the module docs), over a node table of capacity `N`
/// ([`crate::nodes`]: 16 by default, [`HostGuidance`] for the host's 256).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Guidance<S, const N: usize = DEFAULT_NODE_CAPACITY> {
    config: GuidanceConfig<S>,
    table: NodeTable<S, N>,
    interp: Interpolator<S, N>,
    energy: EnergyNormalizer<S>,
    clock: GuidanceClock<S>,
    /// Held (rate-limited) command.
    command: Command<S>,
    /// Last interpolated (un-limited) command.
    target: Command<S>,
    /// Attitude at the last tick.
    ramp_start: Command<S>,
    /// Time of the last tick \[s\] (`None` before the first).
    ramp_start_s: Option<S>,
    /// Plausibility check of the sample times.
    time_gate: TimeGate<S>,
    /// Number of time-base re-synchronisations so far.
    time_resyncs: u32,
    /// Bank sign imposed by a lateral logic (`None`: the table's own sign).
    bank_sign: Option<BankSign>,
    /// Largest bank magnitude \[rad\] imposed by a path-limit bound (`None`: the table's).
    bank_cap: Option<S>,
}

impl<S: Scalar, const N: usize> Guidance<S, N> {
    /// Set up guidance. `energy` maps (r, V) to E-hat (used for energy-indexed tables);
    /// `initial` is the attitude at start \[rad\] (clamped into the table's bounds). The first
    /// call to [`Guidance::update`] is a tick.
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] for an invalid config or tension, or a non-finite
    /// `initial`.
    ///
    /// ```
    /// use guidance_core::energy::{EARTH_MU_M3_S2, EARTH_RADIUS_M, EnergyNormalizer};
    /// use guidance_core::guidance::{Command, Guidance, GuidanceConfig, RateLimits};
    /// use guidance_core::interp::Interpolation;
    /// use guidance_core::nodes::{AngleBounds, Independent, NodeTable};
    /// // Energy-indexed nodes (E-hat, alpha [deg], sigma [deg]), thesis bounds.
    /// let table = NodeTable::<f32>::from_deg(
    ///     Independent::NormalizedEnergy,
    ///     &[(1.0, 40.0, 0.0), (0.5, 30.0, 60.0), (0.0, 10.0, 30.0)],
    ///     AngleBounds::thesis_default(),
    /// )?;
    /// // E-hat = 1 at the entry interface: 122 km, 7435.5 m/s.
    /// let energy = EnergyNormalizer::new(
    ///     EARTH_MU_M3_S2,
    ///     EARTH_RADIUS_M,
    ///     EARTH_RADIUS_M + 122e3,
    ///     7435.5,
    /// )?;
    /// let config = GuidanceConfig { period_s: 2.0, rates: RateLimits::thesis_default() };
    /// let initial = Command { alpha_rad: 0.698, sigma_rad: 0.0 };
    /// let guidance = Guidance::new(config, table, Interpolation::Linear, energy, initial)?;
    /// assert_eq!(guidance.command(), initial);
    /// # Ok::<(), guidance_core::GuidanceError>(())
    /// ```
    pub fn new(
        config: GuidanceConfig<S>,
        table: NodeTable<S, N>,
        kind: Interpolation<S>,
        energy: EnergyNormalizer<S>,
        initial: Command<S>,
    ) -> Result<Self, GuidanceError> {
        config.validate()?;
        if !initial.is_finite() {
            return Err(GuidanceError::InvalidConfig);
        }
        let clock = GuidanceClock::new(config.period_s)?;
        let interp = Interpolator::new(&table, kind)?;
        let bounds = table.bounds();
        let initial = Command {
            alpha_rad: bounds.clamp_alpha(initial.alpha_rad),
            sigma_rad: bounds.clamp_sigma(initial.sigma_rad),
        };
        Ok(Self {
            config,
            table,
            interp,
            energy,
            clock,
            command: initial,
            target: initial,
            ramp_start: initial,
            ramp_start_s: None,
            time_gate: TimeGate::new(TimeWindow::for_period(config.period_s)),
            time_resyncs: 0,
            bank_sign: None,
            bank_cap: None,
        })
    }

    /// Process one navigation sample. Recomputes the command only when `nav.time_s` has
    /// reached the next tick (`t0 + k * period`); otherwise returns the held command.
    ///
    /// A sample whose time lies outside the plausibility window around the last accepted
    /// sample ([`Guidance::time_window`], see [`crate::plausibility`]) is rejected and does not
    /// become the time reference, so guidance recovers at the next good sample; a run of
    /// consistent such samples re-synchronises the clock to the new time base (the new ramp then
    /// starts from the held command).
    ///
    /// # Errors
    /// [`GuidanceError::NonFiniteState`], [`GuidanceError::UnphysicalState`] (radius <= 0 or
    /// speed < 0), [`GuidanceError::ImplausibleTime`] (outside the plausibility window) or
    /// [`GuidanceError::NonIncreasingTime`] (time before the last tick). On error the held
    /// command and the ramp remain valid and nothing changes, except that an implausible time
    /// is counted towards a re-synchronisation.
    ///
    /// One flight of the HORUS-2B reference mission's first minute, a sample every 0.5 s: the
    /// command changes at the 2 s ticks only and never faster than the rate limits.
    ///
    /// ```
    /// use guidance_core::missions::horus2b_reference;
    /// use guidance_core::NavState;
    /// let mission = horus2b_reference::<f32>()?;
    /// let mut guidance = mission.guidance(mission.earth_energy_normalizer()?)?;
    /// let mut ticks = 0;
    /// for i in 0..120 {
    ///     let nav = NavState {
    ///         time_s: 0.5 * i as f32,
    ///         radius_m: 6_378_137.0 + 122e3 - 100.0 * i as f32,
    ///         speed_m_s: 7435.5,
    ///         flight_path_angle_rad: -0.025,
    ///         heading_rad: 1.235,
    ///         latitude_rad: -0.389,
    ///         longitude_rad: -1.862,
    ///     };
    ///     let out = guidance.update(&nav)?;
    ///     ticks += usize::from(out.ticked);
    ///     assert!(out.command.alpha_rad.is_finite() && out.command.sigma_rad.is_finite());
    /// }
    /// assert_eq!(ticks, 30); // one tick per 2 s
    /// # Ok::<(), guidance_core::GuidanceError>(())
    /// ```
    pub fn update(&mut self, nav: &NavState<S>) -> Result<GuidanceOutput<S>, GuidanceError> {
        nav.validate()?;
        let x = match self.table.independent() {
            Independent::NormalizedEnergy => self.energy.normalized(nav.radius_m, nav.speed_m_s)?,
            Independent::TimeS => nav.time_s,
        };
        let verdict = self.time_gate.screen(nav.time_s)?;
        let clock = match verdict {
            TimeVerdict::Accept => self.clock,
            TimeVerdict::Resync => GuidanceClock::new(self.config.period_s)?,
        };
        let mut clock = clock;
        let event = clock.poll(nav.time_s)?;
        let ClockEvent::Tick { .. } = event else {
            self.time_gate.accept(nav.time_s);
            return Ok(GuidanceOutput {
                command: self.command,
                ticked: false,
                independent_value: x,
            });
        };
        // Start the new ramp where the current one is at the sample time: a late sample (after
        // its tick instant) must not back-date the ramp, which would make the attitude jump.
        let start = match verdict {
            TimeVerdict::Accept => self.attitude_at(nav.time_s),
            // The old ramp's times mean nothing in the new time base: start from its end.
            TimeVerdict::Resync => self.command,
        };
        let bounds = self.table.bounds();
        let target = self.interp.evaluate(x);
        // A lateral logic's sign applies to the interpolated target, *before* the rate limit,
        // so that a bank reversal is flown as a rate-limited ramp, never a step.
        let target = match self.bank_sign {
            Some(sign) => Command {
                alpha_rad: target.alpha_rad,
                sigma_rad: bounds.clamp_sigma(sign.apply(target.sigma_rad)),
            },
            None => target,
        };
        // A path-limit cap on the magnitude, also before the rate limit.
        let target = match self.bank_cap {
            Some(cap) if target.sigma_rad.abs() > cap => Command {
                alpha_rad: target.alpha_rad,
                sigma_rad: bounds.clamp_sigma(if target.sigma_rad < S::ZERO {
                    -cap
                } else {
                    cap
                }),
            },
            _ => target,
        };
        let limited = limit_command(start, target, self.config.rates, self.config.period_s);
        let command = Command {
            alpha_rad: bounds.clamp_alpha(limited.alpha_rad),
            sigma_rad: bounds.clamp_sigma(limited.sigma_rad),
        };
        if !(command.is_finite() && target.is_finite()) {
            // Unreachable with validated inputs; kept so that nothing non-finite is ever stored.
            return Err(GuidanceError::NonFiniteState);
        }
        clock.commit(event);
        self.clock = clock;
        self.time_gate.accept(nav.time_s);
        if verdict == TimeVerdict::Resync {
            self.time_resyncs = self.time_resyncs.saturating_add(1);
        }
        self.ramp_start = start;
        self.ramp_start_s = Some(nav.time_s);
        self.command = command;
        self.target = target;
        Ok(GuidanceOutput {
            command,
            ticked: true,
            independent_value: x,
        })
    }

    /// Attitude at `time_s` \[s\]: from the attitude at the ramp start `t_s`
    /// ([`Guidance::ramp_start_s`]) it moves towards the held command at the rate limits (a
    /// ramp) and equals the command from one period after `t_s` on (for a ramp that started on
    /// its tick, also from [`Guidance::next_tick_s`] on, whichever comes first in floating
    /// point). Before `t_s` it returns the attitude at `t_s`; before the first update, the
    /// initial attitude; for a NaN time, the held command.
    #[must_use]
    pub fn attitude_at(&self, time_s: S) -> Command<S> {
        let Some(t_k) = self.ramp_start_s else {
            return self.command;
        };
        if !time_s.is_finite() {
            return self.command;
        }
        let dt = time_s - t_k;
        if dt <= S::ZERO {
            self.ramp_start
        } else if dt >= self.config.period_s
            || time_s >= t_k + self.config.period_s
            || (Some(t_k) == self.clock.last_tick_s() && time_s >= self.clock.next_tick_s())
        {
            // Complete one period after the ramp start, however the caller rounds that instant
            // (`t_k + period` may exceed `t_k` by a hair less than `period`).
            self.command
        } else {
            limit_command(self.ramp_start, self.command, self.config.rates, dt)
        }
    }

    /// Time of the next tick \[s\]; 0 before the first update (which is always a tick).
    #[must_use]
    pub fn next_tick_s(&self) -> S {
        self.clock.next_tick_s()
    }

    /// Time of the last tick \[s\] (`None` before the first update).
    #[must_use]
    pub fn last_tick_s(&self) -> Option<S> {
        self.clock.last_tick_s()
    }

    /// Start time of the current attitude ramp \[s\]: the sample time of the last tick update
    /// (equal to [`Guidance::last_tick_s`] when samples arrive on the ticks; later for a late
    /// sample). `None` before the first update.
    #[must_use]
    pub fn ramp_start_s(&self) -> Option<S> {
        self.ramp_start_s
    }

    /// The time plausibility window in use (default [`TimeWindow::for_period`]).
    #[must_use]
    pub fn time_window(&self) -> TimeWindow<S> {
        self.time_gate.window()
    }

    /// Set the time plausibility window (see [`crate::plausibility`]).
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] as [`TimeWindow::validate`]; the old window stays.
    pub fn set_time_window(&mut self, window: TimeWindow<S>) -> Result<(), GuidanceError> {
        window.validate(self.config.period_s)?;
        self.time_gate.set_window(window);
        Ok(())
    }

    /// Number of re-synchronisations to a new time base so far.
    #[must_use]
    pub fn time_resyncs(&self) -> u32 {
        self.time_resyncs
    }

    /// When the current attitude ramp reaches the held command, per angle \[s\]: from the
    /// ramp start `t_s` ([`Guidance::ramp_start_s`]), `t_s + |command - start| / rate`
    /// ([`crate::rate::ramp_end`]). [`Guidance::attitude_at`] also completes the ramp one period
    /// after `t_s`; the two agree up to rounding, since a command never moves more than one
    /// period's step. `None` before the first update.
    ///
    /// A simulator makes these instants integration breakpoints (the attitude history has a
    /// kink there) instead of re-deriving the ramp; see also [`Guidance::next_ramp_kink_s`].
    #[must_use]
    pub fn ramp_end_s(&self) -> Option<RampEnd<S>> {
        let t_s = self.ramp_start_s?;
        Some(ramp_end(
            self.ramp_start,
            self.command,
            self.config.rates,
            t_s,
        ))
    }

    /// The earliest end of a per-angle ramp strictly after `time_s` \[s\] (where one angle of
    /// [`Guidance::attitude_at`] stops moving); `None` if there is none (before the first
    /// update, or the ramp is complete by `time_s`).
    #[must_use]
    pub fn next_ramp_kink_s(&self, time_s: S) -> Option<S> {
        self.ramp_end_s()?.next_after(time_s)
    }

    /// The held (rate-limited) command \[rad\].
    #[must_use]
    pub fn command(&self) -> Command<S> {
        self.command
    }

    /// The interpolated command of the last tick before rate limiting \[rad\] (equal to
    /// [`Guidance::command`] when the limiter did not act).
    #[must_use]
    pub fn target(&self) -> Command<S> {
        self.target
    }

    /// The node table in use.
    #[must_use]
    pub fn table(&self) -> &NodeTable<S, N> {
        &self.table
    }

    /// The configuration.
    #[must_use]
    pub fn config(&self) -> GuidanceConfig<S> {
        self.config
    }

    /// The interpolator in use.
    #[must_use]
    pub fn interpolator(&self) -> &Interpolator<S, N> {
        &self.interp
    }

    /// Impose the sign of the bank angle from the next tick on (`None`: the table's own sign),
    /// keeping the interpolated magnitude; the signed target is clamped into the table's bounds
    /// and then rate-limited like any command, so a reversal is a ramp at the bank-rate limit.
    /// The table's bounds must allow both signs (`sigma_min_rad <= -sigma_max_rad` for a full
    /// reversal), else the reversed bank is clamped (with thesis bounds 0..90 deg: to 0).
    pub fn set_bank_sign(&mut self, sign: Option<BankSign>) {
        self.bank_sign = sign;
    }

    /// Cap the bank magnitude at `cap` \[rad\] from the next tick on (`None`: no cap), keeping
    /// the sign: a path-limit bound ([`crate::replan::PathBound`]). Like the sign, it applies
    /// to the interpolated target before the rate limiter, so the attitude never jumps. A
    /// negative or non-finite cap is ignored (`None`).
    pub fn set_bank_cap(&mut self, cap: Option<S>) {
        self.bank_cap = cap.filter(|c| c.is_finite() && *c >= S::ZERO);
    }

    /// The imposed bank-magnitude cap \[rad\] (`None`: none).
    #[must_use]
    pub fn bank_cap(&self) -> Option<S> {
        self.bank_cap
    }

    /// The imposed bank sign (`None`: the table's own).
    #[must_use]
    pub fn bank_sign(&self) -> Option<BankSign> {
        self.bank_sign
    }

    /// Replace the node table (onboard re-planning), keeping the interpolation kind. Takes
    /// effect at the next tick; the held command and ramp are kept. If the new table's bounds
    /// exclude the current attitude, the next command is clamped into the new bounds, which
    /// can step faster than the rate limit (keep the bounds when re-planning).
    ///
    /// # Errors
    /// As [`Interpolator::new`]; on error the old table stays in use.
    pub fn replace_table(&mut self, table: NodeTable<S, N>) -> Result<(), GuidanceError> {
        let interp = Interpolator::new(&table, self.interp.kind())?;
        self.interp = interp;
        self.table = table;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::energy::{EARTH_MU_M3_S2, EARTH_RADIUS_M};
    use crate::scalar::Fixed;

    const DEG: f64 = core::f64::consts::PI / 180.0;

    fn energy<S: Scalar>() -> EnergyNormalizer<S> {
        EnergyNormalizer::new(
            EARTH_MU_M3_S2,
            EARTH_RADIUS_M,
            EARTH_RADIUS_M + 122_000.0,
            7435.5,
        )
        .unwrap()
    }

    fn nav<S: Scalar>(t: f64) -> NavState<S> {
        NavState {
            time_s: S::from_f64(t),
            radius_m: S::from_f64(EARTH_RADIUS_M + 80_000.0),
            speed_m_s: S::from_f64(7000.0),
            flight_path_angle_rad: S::ZERO,
            heading_rad: S::ZERO,
            latitude_rad: S::ZERO,
            longitude_rad: S::ZERO,
        }
    }

    fn reference<S: Scalar>() -> Guidance<S> {
        Guidance::new(
            GuidanceConfig::thesis_default(),
            crate::missions::horus2b_reference().unwrap().table,
            Interpolation::Linear,
            energy(),
            Command::from_deg(40.0, 0.0).unwrap(),
        )
        .unwrap()
    }

    /// Across the 0 -> 79.6 deg bank step of the reference mission (264 s -> 290 s, 3.06 deg/s,
    /// below the 15 deg/s limit) the command follows the linear interpolation at each tick.
    #[test]
    fn reference_mission_bank_step() {
        let mut g = reference::<f64>();
        let out = g.update(&nav(264.0)).unwrap();
        assert!(out.ticked);
        assert!(out.command.sigma_rad.abs() < 1e-12);
        assert!(!g.update(&nav(265.0)).unwrap().ticked);
        let out = g.update(&nav(266.0)).unwrap();
        assert!(out.ticked);
        assert!((out.command.sigma_rad - 79.6 * DEG * 2.0 / 26.0).abs() < 1e-12);
        assert!((out.command.alpha_rad - 40.0 * DEG).abs() < 1e-12);
        assert_eq!(out.independent_value, 266.0);
    }

    /// Starting at 0 deg bank in the middle of the plateau (59.8 deg), the limiter steps
    /// 15 deg/s * 2 s = 30 deg per tick: 30, 59.8.
    #[test]
    fn rate_limit_binds_and_ramp_is_continuous() {
        let mut g = Guidance::<f64>::new(
            GuidanceConfig::thesis_default(),
            crate::missions::horus2b_reference().unwrap().table,
            Interpolation::Linear,
            energy(),
            Command::from_deg(40.0, 0.0).unwrap(),
        )
        .unwrap();
        g.update(&nav(600.0)).unwrap();
        assert!((g.command().sigma_rad - 30.0 * DEG).abs() < 1e-12);
        assert!((g.target().sigma_rad - 59.8 * DEG).abs() < 1e-12);
        assert!((g.attitude_at(601.0).sigma_rad - 15.0 * DEG).abs() < 1e-12);
        assert_eq!(g.attitude_at(602.0), g.command());
        assert_eq!(g.attitude_at(599.0).sigma_rad, 0.0);
        // A late sample (0.5 s after the 602 s tick): the new ramp starts where the attitude is
        // at the sample time (30 deg, the old ramp was complete), not back-dated to 602 s.
        let before = g.attitude_at(602.5);
        g.update(&nav(602.5)).unwrap();
        assert_eq!(g.attitude_at(602.5), before);
        assert!((g.command().sigma_rad - 59.8 * DEG).abs() < 1e-12);
        assert!((g.attitude_at(603.0).sigma_rad - 37.5 * DEG).abs() < 1e-12);
        assert_eq!(g.last_tick_s(), Some(602.0));
        assert_eq!(g.ramp_start_s(), Some(602.5));
        assert_eq!(g.next_tick_s(), 604.0);
        // The ramp is still running at the 604 s tick (37.5 + 15 * 1.5 = 52.5 deg): the next
        // update continues from there, so the attitude stays continuous across that tick too.
        let at_tick = g.attitude_at(604.0);
        assert!((at_tick.sigma_rad - 52.5 * DEG).abs() < 1e-12);
        g.update(&nav(604.0)).unwrap();
        assert_eq!(g.attitude_at(604.0), at_tick);
    }

    /// A bank cap (path-limit bound) lowers the target's magnitude, keeps its sign and is
    /// flown through the rate limiter (59.8 -> 20 deg at 15 deg/s: 29.8, 20); an invalid cap
    /// clears it; without it the target is the table's again.
    #[test]
    fn bank_cap_is_rate_limited_and_keeps_the_sign() {
        let mut g = reference::<f64>();
        g.update(&nav(600.0)).unwrap();
        g.update(&nav(602.0)).unwrap();
        assert!((g.command().sigma_rad - 59.8 * DEG).abs() < 1e-12);
        g.set_bank_cap(Some(20.0 * DEG));
        assert_eq!(g.bank_cap(), Some(20.0 * DEG));
        g.update(&nav(604.0)).unwrap();
        assert!((g.command().sigma_rad - 29.8 * DEG).abs() < 1e-12);
        g.update(&nav(606.0)).unwrap();
        assert!((g.command().sigma_rad - 20.0 * DEG).abs() < 1e-12);
        // The reference table's bounds are 0..90 deg: a negative sign clamps to 0, within the cap.
        g.set_bank_sign(Some(BankSign::Negative));
        g.update(&nav(608.0)).unwrap();
        assert!(g.target().sigma_rad <= 0.0 && g.target().sigma_rad > -20.0 * DEG - 1e-12);
        for bad in [-1.0, f64::NAN, f64::INFINITY] {
            g.set_bank_cap(Some(bad));
            assert_eq!(g.bank_cap(), None);
        }
        g.set_bank_sign(None);
        g.update(&nav(610.0)).unwrap();
        assert!((g.target().sigma_rad - 59.8 * DEG).abs() < 1e-12);
    }

    /// The ramp end is where `attitude_at` reaches the command, per angle.
    #[test]
    fn ramp_end_matches_attitude_at() {
        let mut g = reference::<f64>();
        assert_eq!(g.ramp_end_s(), None);
        assert_eq!(g.next_ramp_kink_s(0.0), None);
        g.update(&nav(600.0)).unwrap();
        // Bank 0 -> 30 deg at 15 deg/s: 2 s; alpha does not move (ends at the ramp start).
        let end = g.ramp_end_s().unwrap();
        assert_eq!(end.alpha_s, 600.0);
        assert!((end.sigma_s - 602.0).abs() < 1e-12);
        assert_eq!(g.next_ramp_kink_s(600.0), Some(end.sigma_s));
        assert_eq!(g.next_ramp_kink_s(602.0), None);
        assert!(g.attitude_at(end.sigma_s - 1e-6).sigma_rad < g.command().sigma_rad);
        assert_eq!(g.attitude_at(end.sigma_s), g.command());
        // A late sample: the ramp (30 -> 59.8 deg, 1.987 s) starts at the sample time.
        g.update(&nav(602.5)).unwrap();
        let end = g.ramp_end_s().unwrap();
        assert!((end.sigma_s - (602.5 + 29.8 / 15.0)).abs() < 1e-12);
        assert_eq!(end.latest(), end.sigma_s);
    }

    /// Regression (review finding): a sample arriving late after a tick instant used to
    /// back-date the ramp to the tick, so the attitude jumped at the sample time.
    #[test]
    fn late_sample_keeps_the_attitude_continuous() {
        let mut g = reference::<f64>();
        for &t in &[270.0, 272.0] {
            g.update(&nav(t)).unwrap();
        }
        let before = g.attitude_at(275.9);
        g.update(&nav(275.9)).unwrap();
        let after = g.attitude_at(275.9);
        assert!(
            (after.sigma_rad - before.sigma_rad).abs() < 1e-12,
            "{before:?} -> {after:?}"
        );
        assert!((after.alpha_rad - before.alpha_rad).abs() < 1e-12);
        // and the ramp from there respects the bank rate
        let later = g.attitude_at(276.4);
        assert!((later.sigma_rad - after.sigma_rad).abs() <= 15.0 * DEG * 0.5 + 1e-12);
    }

    #[test]
    fn bad_samples_change_nothing() {
        let mut g = reference::<f64>();
        g.update(&nav(600.0)).unwrap();
        let before = g.clone();
        let mut bad = nav::<f64>(602.0);
        bad.speed_m_s = f64::NAN;
        assert_eq!(g.update(&bad), Err(GuidanceError::NonFiniteState));
        bad.speed_m_s = -1.0;
        assert_eq!(g.update(&bad), Err(GuidanceError::UnphysicalState));
        assert_eq!(g.update(&nav(598.0)), Err(GuidanceError::NonIncreasingTime));
        assert_eq!(g, before);
        // Fixed point has no NaN: 0/0 saturates to 0, a zero radius, which is unphysical.
        let mut gx = reference::<Fixed>();
        let mut bad = nav::<Fixed>(0.0);
        bad.radius_m = Fixed::ZERO / Fixed::ZERO;
        assert_eq!(gx.update(&bad), Err(GuidanceError::UnphysicalState));
    }

    /// Issue 8.5 (reproduced defect): one finite but wrong time stamp used to become the time
    /// reference, so every later correct sample was rejected as `NonIncreasingTime` and the
    /// command computed at the glitch was held for the rest of the flight.
    fn glitch_then_recovery<S: Scalar>(glitch: f64) {
        let mut g = reference::<S>();
        for k in 0..5 {
            g.update(&nav(264.0 + 2.0 * f64::from(k))).unwrap();
        }
        let before = g.clone();
        assert_eq!(
            g.update(&nav(glitch)),
            Err(GuidanceError::ImplausibleTime),
            "glitch {glitch}"
        );
        assert_eq!(g.command(), before.command());
        assert_eq!(g.last_tick_s(), before.last_tick_s());
        // The next good samples tick on the old clock and follow the profile.
        for k in 5..20 {
            let t = 264.0 + 2.0 * f64::from(k);
            let out = g.update(&nav(t)).unwrap();
            assert!(out.ticked, "t {t}");
            assert_eq!(g.last_tick_s(), Some(S::from_f64(t)));
        }
        assert!(g.next_tick_s().is_finite());
        assert_eq!(g.time_resyncs(), 0);
    }

    #[test]
    fn time_glitch_does_not_freeze_guidance() {
        for glitch in [1e4, 1e12, -1e12] {
            glitch_then_recovery::<f64>(glitch);
            glitch_then_recovery::<f32>(glitch);
        }
        glitch_then_recovery::<f64>(f64::MAX);
        glitch_then_recovery::<f32>(f64::from(f32::MAX));
        // Fixed point saturates at +-2^31 s; a glitch of 1e4 s is representable.
        glitch_then_recovery::<Fixed>(1e4);
        glitch_then_recovery::<Fixed>(1e12);
    }

    /// A real change of time base (a run of consistent samples far from the old one) is taken
    /// after `resync_samples` samples; the attitude starts from the held command (no jump).
    #[test]
    fn consistent_new_time_base_resynchronises() {
        let mut g = reference::<f64>();
        g.update(&nav(600.0)).unwrap();
        g.update(&nav(602.0)).unwrap();
        let held = g.command();
        assert_eq!(g.update(&nav(5e4)), Err(GuidanceError::ImplausibleTime));
        assert_eq!(
            g.update(&nav(5e4 + 2.0)),
            Err(GuidanceError::ImplausibleTime)
        );
        let out = g.update(&nav(5e4 + 4.0)).unwrap();
        assert!(out.ticked);
        assert_eq!(g.time_resyncs(), 1);
        assert_eq!(g.attitude_at(5e4 + 4.0), held);
        assert_eq!(g.next_tick_s(), 5e4 + 6.0);
        assert!(g.update(&nav(5e4 + 6.0)).unwrap().ticked);
        // The window is configurable and validated.
        let w = TimeWindow {
            max_step_s: 1.0,
            resync_samples: 3,
        };
        assert_eq!(g.set_time_window(w), Err(GuidanceError::InvalidConfig));
        let w = TimeWindow {
            max_step_s: 1e5,
            resync_samples: 1,
        };
        g.set_time_window(w).unwrap();
        assert_eq!(g.time_window(), w);
        assert!(g.update(&nav(9e4)).unwrap().ticked);
    }

    #[test]
    fn gap_recomputes_once_at_latest_tick() {
        let mut g = reference::<f64>();
        g.update(&nav(600.0)).unwrap();
        let out = g.update(&nav(611.0)).unwrap();
        assert!(out.ticked);
        assert_eq!(g.last_tick_s(), Some(610.0));
        // One normal step only: 30 -> 59.8 deg (step 29.8 <= 30).
        assert!((g.command().sigma_rad - 59.8 * DEG).abs() < 1e-12);
        // The ramp starts at the sample time from the attitude reached there (30 deg).
        assert!((g.attitude_at(611.0).sigma_rad - 30.0 * DEG).abs() < 1e-12);
        assert!((g.attitude_at(612.0).sigma_rad - 45.0 * DEG).abs() < 1e-12);
    }

    /// A replaced table takes effect at the next tick; the held command is kept until then.
    #[test]
    fn replace_table_takes_effect_at_next_tick() {
        let mut g = reference::<f64>();
        g.update(&nav(600.0)).unwrap();
        let held = g.command();
        let mut t = g.table().clone();
        for i in 0..t.len() {
            t.set_sigma(i, 10.0 * DEG).unwrap();
        }
        g.replace_table(t).unwrap();
        assert_eq!(g.command(), held);
        assert_eq!(g.update(&nav(601.0)).unwrap().command, held);
        g.update(&nav(602.0)).unwrap();
        assert!((g.target().sigma_rad - 10.0 * DEG).abs() < 1e-12);
        assert!((g.command().sigma_rad - 10.0 * DEG).abs() < 1e-12);
    }

    #[test]
    fn rejects_bad_config() {
        let mk = |c: GuidanceConfig<f64>, init: Command<f64>| {
            Guidance::new(
                c,
                crate::missions::horus2b_reference::<f64>().unwrap().table,
                Interpolation::Linear,
                energy(),
                init,
            )
        };
        let ok = Command::from_deg(40.0, 0.0).unwrap();
        let mut c = GuidanceConfig::thesis_default();
        c.period_s = 0.0;
        assert_eq!(mk(c, ok).unwrap_err(), GuidanceError::InvalidConfig);
        let mut c = GuidanceConfig::thesis_default();
        c.rates.sigma_rad_s = f64::INFINITY;
        assert_eq!(mk(c, ok).unwrap_err(), GuidanceError::InvalidConfig);
        let bad = Command {
            alpha_rad: f64::NAN,
            sigma_rad: 0.0,
        };
        assert_eq!(
            mk(GuidanceConfig::thesis_default(), bad).unwrap_err(),
            GuidanceError::InvalidConfig
        );
        // Out-of-bounds initial attitude is clamped.
        let g = mk(
            GuidanceConfig::thesis_default(),
            Command::from_deg(60.0, -5.0).unwrap(),
        )
        .unwrap();
        assert!((g.command().alpha_rad - 45.0 * DEG).abs() < 1e-15);
        assert_eq!(g.command().sigma_rad, 0.0);
    }
}
