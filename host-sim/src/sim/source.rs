//! The guidance seam of the closed loop: [`AttitudeSource`], a constant attitude
//! ([`FixedAttitude`]) and the one adapter that flies `guidance-core`'s guidance, plain
//! ([`CoreGuidance`]) or with onboard re-planning (`crate::replan_loop::ReplanLoop`), at the
//! guidance's own clock ([`GuidanceSource`]).

use guidance_core::estimate::{AeroScales, EstimateError, SensedAero};
use guidance_core::guidance::{BankSign, Command, Guidance, HostGuidance};
use guidance_core::replan::{ReplanReport, ReplanningGuidance};
use guidance_core::{GuidanceError, NavState};

/// A source of commanded attitude: the guidance seam of the closed loop.
pub trait AttitudeSource {
    /// What a failed tick reports (carried by [`super::SimError::Guidance`] as its source).
    type Error: std::error::Error + Send + Sync + 'static;
    /// Called at every guidance tick (first at t = 0) with the navigation state.
    ///
    /// # Errors
    /// [`AttitudeSource::Error`] when the guidance rejects the state or cannot answer.
    fn tick(&mut self, nav: &NavState<f64>) -> Result<(), Self::Error>;
    /// Called at every guidance tick just before [`AttitudeSource::tick`] with the same
    /// navigation state and the aerodynamic accelerations an IMU senses there (lift and drag
    /// of the simulated vehicle in the simulated atmosphere at the attitude flown at that
    /// instant). Called only when [`AttitudeSource::senses`]. Default: ignored.
    ///
    /// # Errors
    /// [`AttitudeSource::Error`] when the source rejects the measurement.
    fn sense(&mut self, nav: &NavState<f64>, sensed: &SensedAero<f64>) -> Result<(), Self::Error> {
        let _ = (nav, sensed);
        Ok(())
    }
    /// Whether [`AttitudeSource::sense`] uses its measurements (the loop computes them at a
    /// tick only then). Default: no.
    fn senses(&self) -> bool {
        false
    }
    /// Attitude at time `time_s` \[s\] between ticks (continuous) \[rad\].
    fn attitude_at(&self, time_s: f64) -> Command<f64>;
    /// Time of the next tick \[s\]; `f64::INFINITY` for none.
    fn next_tick_s(&self) -> f64;
    /// The next time after `time_s` at which [`AttitudeSource::attitude_at`] has a kink (a
    /// rate-limited ramp reaching the held command) \[s\]; `f64::INFINITY` for none. The loop
    /// makes these breakpoints, so no integration step straddles a kink (which would cost
    /// rejected steps and accuracy).
    fn next_kink_s(&self, time_s: f64) -> f64 {
        let _ = time_s;
        f64::INFINITY
    }
}

/// Constant attitude, never ticks (open loop).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FixedAttitude(pub Command<f64>);

impl AttitudeSource for FixedAttitude {
    type Error = std::convert::Infallible;
    fn tick(&mut self, _nav: &NavState<f64>) -> Result<(), Self::Error> {
        Ok(())
    }
    fn attitude_at(&self, _time_s: f64) -> Command<f64> {
        self.0
    }
    fn next_tick_s(&self) -> f64 {
        f64::INFINITY
    }
}

/// A `guidance-core` guidance the closed loop can fly: [`Guidance`] itself, or
/// [`ReplanningGuidance`] (the same clocked guidance plus the predictor-corrector).
pub trait FlightGuidance {
    /// What a tick may report besides the command (a re-plan report; nothing for plain
    /// guidance).
    type Report;
    /// One guidance update at `nav`: whether the guidance ticked, and the tick's report.
    ///
    /// # Errors
    /// The core's [`GuidanceError`].
    fn update(
        &mut self,
        nav: &NavState<f64>,
    ) -> Result<(bool, Option<Self::Report>), GuidanceError>;
    /// The clocked guidance's attitude at `time_s` ([`Guidance::attitude_at`]) \[rad\].
    fn attitude_at(&self, time_s: f64) -> Command<f64>;
    /// The clocked guidance's next tick ([`Guidance::next_tick_s`]) \[s\].
    fn next_tick_s(&self) -> f64;
    /// The next end of a ramp after `time_s` ([`Guidance::next_ramp_kink_s`]) \[s\].
    fn next_ramp_kink_s(&self, time_s: f64) -> Option<f64>;
    /// Impose the bank sign from the next tick on ([`Guidance::set_bank_sign`]; lateral
    /// guidance, `guidance_core::lateral`).
    fn set_bank_sign(&mut self, sign: Option<BankSign>);
    /// Feed the sensed aerodynamic accelerations at `nav` to onboard estimation
    /// ([`ReplanningGuidance::sense`]); default: ignored.
    ///
    /// # Errors
    /// The core's [`EstimateError`].
    fn sense(
        &mut self,
        nav: &NavState<f64>,
        sensed: &SensedAero<f64>,
    ) -> Result<(), EstimateError> {
        let _ = (nav, sensed);
        Ok(())
    }
    /// Whether [`FlightGuidance::sense`] uses its measurements (an onboard estimator or a
    /// barrier bound is running); default: no.
    fn senses(&self) -> bool {
        false
    }
    /// The onboard aerodynamic estimate the next solve would start from
    /// ([`ReplanningGuidance::aero_scales`]); default: none.
    fn aero_scales(&self) -> Option<AeroScales<f64>> {
        None
    }
}

/// The clocked-guidance part of [`FlightGuidance`], the same for every wrapper of a
/// `Guidance<f64, N>` (any node capacity `N`).
/// `$($to)*` is the path from `self` to the wrapped `Guidance` (empty for `Guidance` itself,
/// whose inherent methods take precedence over the trait's).
macro_rules! clocked_guidance {
    ($($to:tt)*) => {
        fn attitude_at(&self, time_s: f64) -> Command<f64> {
            self$($to)*.attitude_at(time_s)
        }
        fn next_tick_s(&self) -> f64 {
            self$($to)*.next_tick_s()
        }
        fn next_ramp_kink_s(&self, time_s: f64) -> Option<f64> {
            self$($to)*.next_ramp_kink_s(time_s)
        }
    };
}

impl<const N: usize> FlightGuidance for Guidance<f64, N> {
    type Report = std::convert::Infallible;
    fn update(
        &mut self,
        nav: &NavState<f64>,
    ) -> Result<(bool, Option<Self::Report>), GuidanceError> {
        Ok((Guidance::update(self, nav)?.ticked, None))
    }
    fn set_bank_sign(&mut self, sign: Option<BankSign>) {
        Guidance::set_bank_sign(self, sign);
    }
    clocked_guidance!();
}

impl<const N: usize> FlightGuidance for ReplanningGuidance<f64, N> {
    type Report = ReplanReport<f64>;
    fn update(
        &mut self,
        nav: &NavState<f64>,
    ) -> Result<(bool, Option<Self::Report>), GuidanceError> {
        let out = ReplanningGuidance::update(self, nav)?;
        Ok((out.guidance.ticked, out.replan))
    }
    fn set_bank_sign(&mut self, sign: Option<BankSign>) {
        ReplanningGuidance::set_bank_sign(self, sign);
    }
    fn sense(
        &mut self,
        nav: &NavState<f64>,
        sensed: &SensedAero<f64>,
    ) -> Result<(), EstimateError> {
        ReplanningGuidance::sense(self, nav, sensed).map(|_| ())
    }
    fn senses(&self) -> bool {
        ReplanningGuidance::uses_sensed(self)
    }
    fn aero_scales(&self) -> Option<AeroScales<f64>> {
        ReplanningGuidance::aero_scales(self)
    }
    clocked_guidance!(.guidance());
}

/// Why a tick of a [`GuidanceSource`] failed.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum TickError {
    /// The core rejected the navigation state or its configuration.
    #[error(transparent)]
    Guidance(#[from] GuidanceError),
    /// Onboard estimation rejected the sensed accelerations.
    #[error("onboard estimation: {0}")]
    Estimate(#[from] EstimateError),
    /// The loop called at a time that is not a guidance tick.
    #[error("guidance did not tick at t = {time_s} s (next tick {next_tick_s} s)")]
    NoTick {
        /// Mission time of the call \[s\].
        time_s: f64,
        /// The guidance's next tick \[s\].
        next_tick_s: f64,
    },
}

/// What the guidance had in hand at the tick that completed a report: the navigation state
/// and the onboard aerodynamic estimate (with a whole solve per tick,
/// `ReplanningConfig::steps_per_tick = 0`, these are the solve's inputs: the predictor's state
/// and the scales applied to its model). Kept so a run's predictions can be recomputed and
/// checked (docs/validation/vinh-numerical.md, the re-planning domain).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReportContext {
    /// Navigation state of the tick \[SI, rad\].
    pub nav: NavState<f64>,
    /// Onboard aerodynamic estimate at the tick (`None` without estimation).
    pub aero_scales: Option<AeroScales<f64>>,
}

/// A `guidance-core` guidance as the attitude source of the closed loop: called at every
/// tick with the navigation state; the attitude between ticks is its rate-limited ramp
/// ([`Guidance::attitude_at`]). Every report a tick makes is kept in
/// [`GuidanceSource::reports`] (the re-plans of a run), with its [`ReportContext`] in
/// [`GuidanceSource::contexts`].
#[derive(Clone, Debug)]
pub struct GuidanceSource<G: FlightGuidance> {
    /// The flight guidance.
    pub guidance: G,
    /// Every report of the run, in order.
    pub reports: Vec<G::Report>,
    /// The context of each report (same index).
    pub contexts: Vec<ReportContext>,
}

/// `guidance-core`'s [`Guidance`] in the loop, with a host-sized node table (up to
/// [`guidance_core::nodes::HOST_NODE_CAPACITY`] nodes).
pub type CoreGuidance = GuidanceSource<HostGuidance<f64>>;

impl<G: FlightGuidance> GuidanceSource<G> {
    /// Wrap a configured guidance.
    #[must_use]
    pub fn new(guidance: G) -> Self {
        Self {
            guidance,
            reports: Vec::new(),
            contexts: Vec::new(),
        }
    }
}

impl<G: FlightGuidance> AttitudeSource for GuidanceSource<G> {
    type Error = TickError;
    fn tick(&mut self, nav: &NavState<f64>) -> Result<(), TickError> {
        // The estimate the solve of this tick starts from (before the update).
        let aero_scales = self.guidance.aero_scales();
        let (ticked, report) = self.guidance.update(nav)?;
        if let Some(r) = report {
            self.reports.push(r);
            self.contexts.push(ReportContext {
                nav: *nav,
                aero_scales,
            });
        }
        if ticked {
            Ok(())
        } else {
            Err(TickError::NoTick {
                time_s: nav.time_s,
                next_tick_s: self.guidance.next_tick_s(),
            })
        }
    }
    fn sense(&mut self, nav: &NavState<f64>, sensed: &SensedAero<f64>) -> Result<(), TickError> {
        Ok(self.guidance.sense(nav, sensed)?)
    }
    fn senses(&self) -> bool {
        self.guidance.senses()
    }
    fn attitude_at(&self, time_s: f64) -> Command<f64> {
        self.guidance.attitude_at(time_s)
    }
    fn next_tick_s(&self) -> f64 {
        self.guidance.next_tick_s()
    }
    fn next_kink_s(&self, time_s: f64) -> f64 {
        self.guidance
            .next_ramp_kink_s(time_s)
            .unwrap_or(f64::INFINITY)
    }
}
