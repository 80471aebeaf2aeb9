//! The flight-guidance stack: every onboard layer, assembled once.
//!
//! [`StackConfig`] is the whole onboard guidance as data: the stored profile
//! ([`ProfileLayer`]) and, each optional, the re-planner ([`ReplanLayer`]), bank reversals
//! ([`LateralLayer`], with the terminal crossrange law), the onboard estimator
//! ([`crate::estimate::EstimatorConfig`]), the path-limit bound ([`BarrierLayer`]) and the
//! target. [`FlightStack::new`] checks it and builds the layers; [`FlightStack::tick`] is the
//! one entry a flight loop calls with every navigation sample (the host simulator, the
//! firmware and the fuzz harness call the same function).
//!
//! # One tick
//! [`FlightStack::tick`]`(nav, sensed)`, on a sample that is a guidance tick (the first sample,
//! or `nav.time_s` at or after [`FlightStack::next_tick_s`]):
//!
//! 1. `sensed` (the lift and drag accelerations \[m/s^2\] an IMU measured at `nav`) goes to the
//!    estimator and the barrier ([`crate::replan::ReplanningGuidance::sense`]) when a layer
//!    uses it ([`FlightStack::uses_sensed`]); an invalid measurement is not used and is
//!    reported ([`StackOutput::sensed_rejected`]), the tick goes on;
//! 2. the lateral logic decides the bank sign ([`crate::lateral::BankReversalLogic::update`])
//!    and imposes it on the guidance;
//! 3. the guidance updates: the stored profile ([`Guidance::update`]) or the re-planner
//!    ([`ReplanningGuidance::update`]: a re-plan on its ticks, the barrier's cap, then the
//!    profile's interpolation, rate limit and hold).
//!
//! Between ticks only step 3 runs (it holds the command). A non-finite or unphysical state is
//! refused before step 1 and changes nothing; on an error of step 2 or 3 (a time the guidance
//! refuses) the lateral logic and the bank sign are as before the call (an accepted
//! measurement of step 1 stays).
//! The command is always finite and within the table's bounds (those of [`Guidance`]).
//!
//! # Scalars
//! `S` is the guidance scalar (any [`Scalar`], fixed point included), `P` the scalar of the
//! re-planner, the estimator, the barrier and the lateral logic (a [`Real`]; by default `S`).
//! With `P != S` the navigation state goes to `P` through `f64`.
//!
//! # Cost
//! The sum of the layers' own (each documented with its module); no allocation, no panics.

mod config;

pub use config::{BarrierLayer, LateralLayer, Layers, ProfileLayer, ReplanLayer, StackConfig};

use crate::error::GuidanceError;
use crate::estimate::{AeroEstimator, AeroScales, EstimateError, EstimateStatus, SensedAero};
use crate::guidance::{Command, Guidance};
use crate::lateral::{BankReversalLogic, LateralConfig, LateralStatus};
use crate::nav::NavState;
use crate::nodes::{DEFAULT_NODE_CAPACITY, HOST_NODE_CAPACITY};
use crate::replan::{RangeTarget, ReplanCounts, ReplanReport, ReplanningGuidance};
use crate::scalar::{Real, Scalar};

/// A layer of the stack (for errors and telemetry).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Layer {
    /// The stored profile.
    Profile,
    /// The re-planner.
    Replan,
    /// The lateral logic.
    Lateral,
    /// The onboard estimator.
    Estimator,
    /// The path-limit bound.
    Barrier,
    /// The target.
    Target,
}

/// Why a [`StackConfig`] cannot be flown.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum StackBuildError {
    /// The layer's own check rejected its settings.
    Rejected {
        /// The layer.
        layer: Layer,
        /// The core's error.
        source: GuidanceError,
    },
    /// The layer (estimator or barrier) is part of the re-planner, which is off.
    NeedsReplan(Layer),
    /// The layer (re-planner or lateral logic) needs a target, and there is none, or (lateral
    /// logic) the target is not a point.
    NeedsTarget(Layer),
}

impl core::fmt::Display for StackBuildError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Rejected { layer, source } => write!(f, "{layer:?} layer: {source}"),
            Self::NeedsReplan(l) => write!(f, "{l:?} layer needs the re-planner"),
            Self::NeedsTarget(l) => write!(f, "{l:?} layer needs a target point"),
        }
    }
}

impl core::error::Error for StackBuildError {}

/// What one [`FlightStack::tick`] did (guidance scalar `S`, predictor scalar `P`).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StackOutput<S, P = S> {
    /// The held command after this sample \[rad\].
    pub command: Command<S>,
    /// True if this sample was a guidance tick (the command was recomputed).
    pub ticked: bool,
    /// The table's independent variable at this sample: E-hat \[-\] or time \[s\].
    pub independent_value: S,
    /// The lateral decision of this tick (`None` without the layer or between ticks).
    pub lateral: Option<LateralStatus<P>>,
    /// The re-plan completed at this sample.
    pub replan: Option<ReplanReport<P>>,
    /// Predictor calls made during this sample.
    pub predictor_calls: u8,
    /// Integration steps of numerical predictions made during this sample.
    pub integration_steps: u32,
    /// What the estimator did with this sample's measurement (`None`: no estimator, no
    /// measurement, or between ticks).
    pub estimate: Option<EstimateStatus>,
    /// Why this sample's measurement was not used (it was invalid).
    pub sensed_rejected: Option<EstimateError>,
    /// The onboard estimate after this sample's measurement, before the update: the scales a
    /// solve started at this sample uses (`None` without an estimator).
    pub aero_scales: Option<AeroScales<P>>,
}

/// The guidance layer: the stored profile alone, or with the re-planner.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
// One per flight, held statically by the firmware: no allocation either way.
#[allow(clippy::large_enum_variant)]
enum Core<S, const N: usize, P> {
    Profile(Guidance<S, N>),
    Replan(ReplanningGuidance<S, N, P>),
}

/// The assembled onboard guidance (module docs).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FlightStack<S, const N: usize = DEFAULT_NODE_CAPACITY, P = S> {
    core: Core<S, N, P>,
    lateral: Option<BankReversalLogic<P>>,
    layers: Layers,
}

/// `x` in the scalar `P` (through `f64`).
fn to_p<S: Scalar, P: Real>(x: S) -> P {
    P::from_f64(x.to_f64())
}

/// `nav` in the scalar `P`.
fn nav_to_p<S: Scalar, P: Real>(nav: &NavState<S>) -> NavState<P> {
    NavState {
        time_s: to_p(nav.time_s),
        radius_m: to_p(nav.radius_m),
        speed_m_s: to_p(nav.speed_m_s),
        flight_path_angle_rad: to_p(nav.flight_path_angle_rad),
        heading_rad: to_p(nav.heading_rad),
        latitude_rad: to_p(nav.latitude_rad),
        longitude_rad: to_p(nav.longitude_rad),
    }
}

impl<S: Scalar, const N: usize, P: Real> FlightStack<S, N, P> {
    /// Check `config` and build its layers with their own checks.
    ///
    /// # Errors
    /// [`StackBuildError::NeedsReplan`] for an estimator or barrier without the re-planner;
    /// [`StackBuildError::NeedsTarget`] for a re-planner without a target or a lateral layer
    /// without a target point; [`StackBuildError::Rejected`] naming the layer whose settings
    /// its constructor rejects.
    pub fn new(config: &StackConfig<S, N, P>) -> Result<Self, StackBuildError> {
        let rejected = |layer| move |source| StackBuildError::Rejected { layer, source };
        if config.replan.is_none() {
            if config.estimator.is_some() {
                return Err(StackBuildError::NeedsReplan(Layer::Estimator));
            }
            if config.barrier.is_some() {
                return Err(StackBuildError::NeedsReplan(Layer::Barrier));
            }
        }
        let lateral = match &config.lateral {
            None => None,
            Some(l) => {
                let Some(RangeTarget::Point(target)) = config.target else {
                    return Err(StackBuildError::NeedsTarget(Layer::Lateral));
                };
                let logic = BankReversalLogic::new(LateralConfig {
                    target,
                    corridor: l.corridor,
                    hysteresis_rad: l.hysteresis_rad,
                    max_reversals: l.max_reversals,
                    freeze_angle_rad: l.freeze_angle_rad,
                })
                .map_err(rejected(Layer::Lateral))?;
                Some(match l.terminal {
                    Some(t) => logic.with_terminal(t).map_err(rejected(Layer::Lateral))?,
                    None => logic,
                })
            }
        };
        let p = &config.profile;
        let core = match &config.replan {
            None => Core::Profile(
                Guidance::new(
                    p.guidance,
                    p.table.clone(),
                    p.interpolation,
                    p.energy,
                    p.initial,
                )
                .map_err(rejected(Layer::Profile))?,
            ),
            Some(r) => {
                let replanning = config
                    .replanning_config()
                    .ok_or(StackBuildError::NeedsTarget(Layer::Replan))?;
                // The profile's own check first, so that its errors name it.
                Guidance::new(
                    p.guidance,
                    p.table.clone(),
                    p.interpolation,
                    p.energy,
                    p.initial,
                )
                .map_err(rejected(Layer::Profile))?;
                let estimator = match config.estimator {
                    Some(e) => Some(AeroEstimator::new(e).map_err(rejected(Layer::Estimator))?),
                    None => None,
                };
                // Built once and configured in place: every by-value builder step would be
                // another copy of the guidance on the stack (the board counts it).
                let mut core = Core::Replan(
                    ReplanningGuidance::new(
                        p.guidance,
                        p.table.clone(),
                        p.interpolation,
                        p.energy,
                        p.initial,
                        replanning,
                    )
                    .map_err(rejected(Layer::Replan))?,
                );
                if let Core::Replan(g) = &mut core {
                    g.set_estimator_and_rotation(estimator, r.numerical_rotation);
                    if let Some(s) = r.lift_schedule {
                        g.set_lift_schedule(s).map_err(rejected(Layer::Replan))?;
                    }
                    if let Some(e) = r.start_normalized_energy {
                        g.set_start_energy(S::from_f64(e.to_f64()))
                            .map_err(rejected(Layer::Replan))?;
                    }
                    if let Some(b) = config.barrier {
                        g.set_path_bound(b.bound, b.predicted)
                            .map_err(rejected(Layer::Barrier))?;
                    }
                    if let Some(e) = r.final_energy_j_kg {
                        g.set_final_energy(e).map_err(rejected(Layer::Replan))?;
                    }
                    if r.bank_shape {
                        g.set_bank_shape().map_err(rejected(Layer::Replan))?;
                    }
                }
                core
            }
        };
        Ok(Self {
            core,
            lateral,
            layers: config.layers(),
        })
    }

    /// One navigation sample (module docs, "One tick"); `sensed`: the lift and drag
    /// accelerations \[m/s^2\] measured at `nav` (`None`: no measurement; used only by the
    /// estimator and the barrier).
    ///
    /// # Errors
    /// The guidance's or the lateral logic's [`GuidanceError`] for a bad navigation state or
    /// time; the held command and the ramp stay valid, the lateral logic and the bank sign
    /// unchanged.
    pub fn tick(
        &mut self,
        nav: &NavState<S>,
        sensed: Option<&SensedAero<P>>,
    ) -> Result<StackOutput<S, P>, GuidanceError> {
        nav.validate()?;
        let g = self.guidance();
        let will_tick = g.last_tick_s().is_none() || nav.time_s >= g.next_tick_s();
        let sign_before = g.bank_sign();
        let (mut estimate, mut sensed_rejected) = (None, None);
        if let (true, Some(s), Core::Replan(r)) = (will_tick, sensed, &mut self.core) {
            match r.sense(nav, s) {
                Ok(e) => estimate = e,
                Err(e) => sensed_rejected = Some(e),
            }
        }
        let aero_scales = self.aero_scales();
        let lateral_before = self.lateral;
        let mut lateral = None;
        if let (true, Some(logic)) = (will_tick, self.lateral.as_mut()) {
            let status = logic.update(&nav_to_p(nav))?;
            self.set_bank_sign(Some(status.sign));
            lateral = Some(status);
        }
        let out = match &mut self.core {
            Core::Profile(g) => g.update(nav).map(|o| (o, None, 0, 0)),
            Core::Replan(r) => r
                .update(nav)
                .map(|o| (o.guidance, o.replan, o.predictor_calls, o.integration_steps)),
        };
        let (out, replan, predictor_calls, integration_steps) = match out {
            Ok(o) => o,
            Err(e) => {
                self.lateral = lateral_before;
                self.set_bank_sign(sign_before);
                return Err(e);
            }
        };
        Ok(StackOutput {
            command: out.command,
            ticked: out.ticked,
            independent_value: out.independent_value,
            lateral,
            replan,
            predictor_calls,
            integration_steps,
            estimate,
            sensed_rejected,
            aero_scales,
        })
    }

    fn set_bank_sign(&mut self, sign: Option<crate::guidance::BankSign>) {
        match &mut self.core {
            Core::Profile(g) => g.set_bank_sign(sign),
            Core::Replan(r) => r.set_bank_sign(sign),
        }
    }

    /// The clocked profile guidance (held command, ramp, clock, table in use).
    #[must_use]
    pub fn guidance(&self) -> &Guidance<S, N> {
        match &self.core {
            Core::Profile(g) => g,
            Core::Replan(r) => r.guidance(),
        }
    }

    /// The re-planner (`None` without the layer).
    #[must_use]
    pub fn replanning(&self) -> Option<&ReplanningGuidance<S, N, P>> {
        match &self.core {
            Core::Profile(_) => None,
            Core::Replan(r) => Some(r),
        }
    }

    /// The lateral logic (`None` without the layer).
    #[must_use]
    pub fn lateral(&self) -> Option<&BankReversalLogic<P>> {
        self.lateral.as_ref()
    }

    /// The layers this stack flies.
    #[must_use]
    pub fn layers(&self) -> Layers {
        self.layers
    }

    /// Bank reversals made (0 without the lateral layer).
    #[must_use]
    pub fn reversals(&self) -> u8 {
        self.lateral
            .as_ref()
            .map_or(0, BankReversalLogic::reversals)
    }

    /// Re-plan outcome counts (`None` without the re-planner).
    #[must_use]
    pub fn replan_counts(&self) -> Option<ReplanCounts> {
        self.replanning().map(ReplanningGuidance::counts)
    }

    /// The onboard estimate (`None` without the estimator).
    #[must_use]
    pub fn aero_scales(&self) -> Option<AeroScales<P>> {
        self.replanning().and_then(ReplanningGuidance::aero_scales)
    }

    /// Whether a layer uses the sensed accelerations of [`FlightStack::tick`] (the estimator,
    /// or the barrier law).
    #[must_use]
    pub fn uses_sensed(&self) -> bool {
        self.replanning()
            .is_some_and(ReplanningGuidance::uses_sensed)
    }

    /// The held command \[rad\].
    #[must_use]
    pub fn command(&self) -> Command<S> {
        self.guidance().command()
    }

    /// The attitude at `time_s` \[s\] on the rate-limited ramp ([`Guidance::attitude_at`])
    /// \[rad\].
    #[must_use]
    pub fn attitude_at(&self, time_s: S) -> Command<S> {
        self.guidance().attitude_at(time_s)
    }

    /// Time of the next guidance tick \[s\].
    #[must_use]
    pub fn next_tick_s(&self) -> S {
        self.guidance().next_tick_s()
    }

    /// The next end of a ramp after `time_s` \[s\] ([`Guidance::next_ramp_kink_s`]).
    #[must_use]
    pub fn next_ramp_kink_s(&self, time_s: S) -> Option<S> {
        self.guidance().next_ramp_kink_s(time_s)
    }
}

/// [`StackConfig`] over a host-sized node table ([`HOST_NODE_CAPACITY`] nodes).
pub type HostStackConfig<S> = StackConfig<S, HOST_NODE_CAPACITY>;

/// [`FlightStack`] over a host-sized node table ([`HOST_NODE_CAPACITY`] nodes).
pub type HostFlightStack<S> = FlightStack<S, HOST_NODE_CAPACITY>;
