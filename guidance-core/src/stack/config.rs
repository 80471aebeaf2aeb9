//! [`StackConfig`]: the whole onboard guidance as data, one optional field per layer, and
//! [`Layers`], the mask that switches layers off.

use crate::energy::EnergyNormalizer;
use crate::estimate::EstimatorConfig;
use crate::guidance::{Command, GuidanceConfig};
use crate::interp::Interpolation;
use crate::lateral::{Corridor, TerminalLateral};
use crate::nodes::{DEFAULT_NODE_CAPACITY, NodeTable};
use crate::replan::{
    LiftSchedule, PathBound, PredictorMode, PredictorModel, RangeTarget, ReplanConfig,
    ReplanLimits, ReplanningConfig,
};

/// The stored profile: what [`crate::guidance::Guidance::new`] takes (guidance scalar `S`,
/// node capacity `N`).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ProfileLayer<S, const N: usize = DEFAULT_NODE_CAPACITY> {
    /// Guidance period \[s\] and attitude rate limits \[rad/s\].
    pub guidance: GuidanceConfig<S>,
    /// The node table (energy-indexed when the re-planner is on).
    pub table: NodeTable<S, N>,
    /// Interpolation between nodes.
    pub interpolation: Interpolation<S>,
    /// The E-hat map of the entry (onboard constant).
    pub energy: EnergyNormalizer<S>,
    /// Attitude before the first tick \[rad\].
    pub initial: Command<S>,
}

/// Onboard re-planning of the bank magnitude ([`crate::replan::ReplanningGuidance`]) except
/// its target, which is the stack's ([`StackConfig::target`]); predictor scalar `P`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ReplanLayer<P> {
    /// Re-plan on every N-th guidance tick \[ticks\], `>= 1`.
    pub every_n_ticks: u16,
    /// Peak heat flux \[W/m^2\] and g-load \[g0\] the solver checks on its predictions.
    pub limits: ReplanLimits<P>,
    /// Solver settings: lift parameter \[-\], vertical-fraction interval \[-\], tolerance \[m\],
    /// iterations, predictor final speed \[m/s\] and skips, predictor mode.
    pub solver: ReplanConfig<P>,
    /// The predictor's model of planet, atmosphere and vehicle (SI units).
    pub model: PredictorModel<P>,
    /// Apply the nearest end of the vertical-fraction interval when the target is out of reach.
    pub apply_out_of_reach: bool,
    /// Work budget per tick \[solver steps\] (0: a whole solve in its tick).
    pub steps_per_tick: u8,
    /// The lift parameter (and drag scale) against speed \[m/s\] of numerical predictions and of
    /// the estimator's model (`None`: the constant `solver.lambda`).
    pub lift_schedule: Option<LiftSchedule<P>>,
    /// No solve starts while E-hat is above this \[-\] (`None`: from the entry).
    pub start_normalized_energy: Option<P>,
    /// Numerical predictions model the planet's rotation in their equations of motion.
    pub numerical_rotation: bool,
    /// Numerical predictions fly the stored profile's bank shape shifted by one offset, and
    /// re-plans install that offset ([`crate::replan::ReplanningGuidance::with_bank_shape`]);
    /// `false`: a constant bank.
    pub bank_shape: bool,
    /// Numerical predictions end at this specific energy \[J/kg\] (`V^2/2 - mu/r` with the
    /// model planet's `mu`: the terminal interface the flight ends on;
    /// [`crate::replan::ReplanningGuidance::with_final_energy`]); `None`: at the final speed of
    /// `solver.predictor`.
    pub final_energy_j_kg: Option<P>,
}

/// Lateral guidance: bank reversals on a heading-error corridor
/// ([`crate::lateral::BankReversalLogic`]) aimed at the stack's target point, with the optional
/// terminal crossrange law.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LateralLayer<P> {
    /// Heading-error corridor (half-widths \[rad\] against speed \[m/s\] or E-hat \[-\]).
    pub corridor: Corridor<P>,
    /// Re-arm margin below the corridor half-width \[rad\], `>= 0`.
    pub hysteresis_rad: P,
    /// Most reversals per flight.
    pub max_reversals: u8,
    /// No reversal once the great-circle angle to the target is below this \[rad\], `>= 0`.
    pub freeze_angle_rad: P,
    /// The terminal crossrange law (`None`: the corridor to the end).
    pub terminal: Option<TerminalLateral<P>>,
}

/// The path-limit bound on the re-planned bank ([`PathBound`]: the quasi-equilibrium bound,
/// or the barrier law when its frequency is above 0, applied at every tick).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BarrierLayer<P> {
    /// The bound: limits \[W/m^2, g0\], descent time \[s\], barrier frequency \[rad/s\] and
    /// damping \[-\].
    pub bound: PathBound<P>,
    /// The re-planner's numerical predictions fly the bound too.
    pub predicted: bool,
}

/// The whole onboard guidance (guidance scalar `S`, node capacity `N`, predictor scalar `P`):
/// the stored profile and each optional layer. A layer `None` is off. Heapless; build a
/// [`super::FlightStack`] from it.
///
/// Rules ([`super::FlightStack::new`] checks them): the estimator and the barrier are parts of
/// the re-planner (they need `replan`); the re-planner needs a `target`; the lateral layer
/// needs a target point ([`RangeTarget::Point`]); with the re-planner the table is
/// energy-indexed.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StackConfig<S, const N: usize = DEFAULT_NODE_CAPACITY, P = S> {
    /// The stored profile (always on).
    pub profile: ProfileLayer<S, N>,
    /// Onboard re-planning of the bank magnitude.
    pub replan: Option<ReplanLayer<P>>,
    /// Bank reversals.
    pub lateral: Option<LateralLayer<P>>,
    /// Onboard estimation of the L/D and drag scales from sensed accelerations.
    pub estimator: Option<EstimatorConfig<P>>,
    /// The path-limit bound.
    pub barrier: Option<BarrierLayer<P>>,
    /// Where the re-planner and the lateral logic aim (latitude, longitude \[rad\] at the
    /// terminal interface, or a total range angle \[rad\] for the re-planner alone).
    pub target: Option<RangeTarget<P>>,
}

/// Which optional layers are on (a mask over a [`StackConfig`]; the profile is always on).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Layers {
    /// The re-planner.
    pub replan: bool,
    /// Bank reversals.
    pub lateral: bool,
    /// The onboard estimator.
    pub estimator: bool,
    /// The path-limit bound.
    pub barrier: bool,
}

impl Layers {
    /// Every layer.
    pub const ALL: Self = Self {
        replan: true,
        lateral: true,
        estimator: true,
        barrier: true,
    };
    /// The stored profile alone.
    pub const PROFILE: Self = Self {
        replan: false,
        lateral: false,
        estimator: false,
        barrier: false,
    };

    /// The layers on in both `self` and `other`.
    #[must_use]
    pub const fn and(self, other: Self) -> Self {
        Self {
            replan: self.replan && other.replan,
            lateral: self.lateral && other.lateral,
            estimator: self.estimator && other.estimator,
            barrier: self.barrier && other.barrier,
        }
    }
}

impl<S: Clone, const N: usize, P: Copy> StackConfig<S, N, P> {
    /// The layers this configuration has.
    #[must_use]
    pub fn layers(&self) -> Layers {
        Layers {
            replan: self.replan.is_some(),
            lateral: self.lateral.is_some(),
            estimator: self.estimator.is_some(),
            barrier: self.barrier.is_some(),
        }
    }

    /// The settings of the re-planner this configuration builds
    /// ([`crate::replan::ReplanningGuidance::new`]: the layer with the stack's target);
    /// `None` without the layer or without a target.
    #[must_use]
    pub fn replanning_config(&self) -> Option<ReplanningConfig<P>> {
        let (r, target) = (self.replan?, self.target?);
        Some(ReplanningConfig {
            every_n_ticks: r.every_n_ticks,
            target,
            limits: r.limits,
            solver: r.solver,
            model: r.model,
            apply_out_of_reach: r.apply_out_of_reach,
            steps_per_tick: r.steps_per_tick,
        })
    }

    /// This configuration with the layers off that `mask` leaves out (a layer absent here
    /// stays absent). Switching the re-planner off switches the estimator and the barrier off
    /// too (they are parts of it). When the estimator is switched off, a predictor mode with
    /// the glide's sink to its equilibrium ([`PredictorMode::AutoSink`],
    /// [`PredictorMode::HybridSink`]) becomes the same mode without it
    /// ([`PredictorMode::Auto`], [`PredictorMode::Hybrid`]): the sink models an offset from
    /// the equilibrium as a transient, which holds when the estimator's density scale removes
    /// the model error, not without it.
    #[must_use]
    pub fn masked(&self, mask: Layers) -> Self {
        let mut c = self.clone();
        let replan = mask.replan && c.replan.is_some();
        if !replan {
            c.replan = None;
        }
        if !mask.lateral {
            c.lateral = None;
        }
        if !(mask.estimator && replan) && c.estimator.is_some() {
            c.estimator = None;
            if let Some(r) = c.replan.as_mut() {
                r.solver.mode = match r.solver.mode {
                    PredictorMode::AutoSink => PredictorMode::Auto,
                    PredictorMode::HybridSink => PredictorMode::Hybrid,
                    m => m,
                };
            }
        }
        if !(mask.barrier && replan) {
            c.barrier = None;
        }
        c
    }
}
