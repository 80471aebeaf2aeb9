//! Onboard re-planning: analytic predictor-corrector on the vertical lift fraction.
//!
//! From the current navigation state ([`NavState`]), a target range to go and the vehicle
//! limits, [`replan`] finds the vertical lift fraction `f = cos(sigma)` (hence the bank magnitude
//! `|sigma| = acos(f)`) whose analytically predicted trajectory (constant lift; the chain
//! [`crate::vinh::predict()`] of skips, Kepler arcs and a final glide, or the glide alone, see
//! [`PredictorMode`]) meets the range target, while the predicted peak heat flux and g-load stay
//! within the limits.
//!
//! # Algorithm (bounded; [`ReplanSolver`], one predictor call per step)
//! 1. Range-only predictions ([`crate::vinh::PeakMode::RangeOnly`]: no peak search) at both
//!    ends `f_min`, `f_max` of the allowed interval (more vertical lift flies farther). A
//!    predictor domain error at either end (in [`PredictorMode::Auto`]: of the chain and then of
//!    the glide), or a range that does not increase with `f`, is [`ReplanCase::FallBack`]: keep
//!    the stored profile.
//! 2. Target outside `[range(f_min), range(f_max)]`: the nearest end is taken
//!    ([`ReplanCase::TargetOutOfReach`]). Otherwise Brent's method on `range(f) - target`
//!    (secant and inverse quadratic interpolation, bisection when they stall), range-only,
//!    until the miss is within `tolerance_m`, the bracket reaches the working precision of the
//!    scalar type, or [`ReplanConfig::max_iterations`] predictions (a domain error inside the
//!    bracket is also a fall-back). Not within tolerance at the end:
//!    [`ReplanCase::TargetOutOfReach`] at the best fraction.
//! 3. One prediction with peaks at that `f` ([`crate::vinh::PeakMode::Limits`]).
//! 4. Limits: if it exceeds the heat-flux or g-load limit, a fixed grid of [`LIMIT_GRID`]
//!    fractions over `[f_min, f_max]` is predicted (each stops at the first phase proven to
//!    exceed a limit) and the feasible one whose range is closest to the target is returned as
//!    [`ReplanCase::LimitsBind`] (the loads are not monotone in `f`: more lift can turn a
//!    captured glide into a skip with a higher peak). No feasible grid point:
//!    [`ReplanCase::FallBack`] with [`ReplanFallBack::LimitsInfeasible`].
//!
//! Every fraction evaluated or returned is clamped into `[f_min, f_max]`: the output is never
//! outside its bounds, not even by rounding (issue 8, item 6).
//!
//! # In the guidance loop
//! [`ReplanningGuidance`] wraps [`crate::guidance::Guidance`] and runs [`replan`] on every N-th
//! tick of the 2 s clock towards a target ([`RangeTarget`]: a point, or a total range along the
//! path), replacing the bank angle of the remaining energy nodes when the solver succeeds (see
//! [`ReplanningGuidance`]).
//!
//! # Predictor
//! [`ReplanConfig::mode`] selects the full chain ([`crate::vinh::predict()`]), a glide-only
//! prediction from the current speed ([`predict_glide`], for a vehicle already in its glide,
//! where the skip closed form is out of domain), or the chain with an automatic switch to the
//! glide when the chain is out of domain ([`PredictorMode::Auto`]), or the numerical
//! integration of the model from the navigated state ([`numerical`],
//! [`PredictorMode::Numerical`]), or the closed forms where the prediction they would fly is in
//! their validated domain and the integration elsewhere ([`PredictorMode::Hybrid`]). A
//! numerical prediction spans several solver steps of at most
//! [`numerical::STEPS_PER_SOLVER_STEP`] integration steps each.
//!
//! # Worst-case cost
//! `max_iterations + 7 + LIMIT_GRID` predictor calls in [`PredictorMode::AutoSink`], `+ 5` in
//! [`PredictorMode::Auto`], `+ 3` in [`PredictorMode::Chain`], [`PredictorMode::Glide`] and
//! [`PredictorMode::Numerical`]; a hybrid solve that leaves the closed forms adds a numerical
//! solve to its closed-form one (at most [`MAX_PREDICTOR_CALLS`]`= 2 (40 + 16) + 18 = 130`,
//! with a warm start's guess and secant steps before each);
//! each chain call is at most [`crate::vinh::predict::MAX_SKIPS`]
//! skips and arcs plus one glide (see [`crate::vinh::predict()`]), each glide call one glide;
//! all but the last and the limit grid are range-only. In practice Brent's method converges in
//! a handful of predictions and stops at the scalar type's working precision (the worst-case
//! benchmark with an unreachable 1e-6 m tolerance: 29 calls in `f32`). Measured on the
//! Cortex-M4F in `f32` (docs/reference/performance.md, `cargo xtask bench-firmware`): predictor chain
//! 81 k instructions, converged re-plan 0.44 M, worst case 1.1 M; spread over ticks with one
//! predictor call per tick ([`ReplanningConfig::steps_per_tick`]) the largest guidance tick is
//! 115 k instructions.

mod bank_shape;
mod lift_schedule;
pub mod numerical;
mod path_bound;
mod replanning;
mod solver;

pub use bank_shape::{BankShape, SHAPE_CAPACITY};
pub use lift_schedule::{LiftSchedule, LiftScheduleError, SCHEDULE_NODES, ScheduleNode};
pub use numerical::{NumericalRun, predict_numerical};
pub use path_bound::{
    DEFAULT_BARRIER_DAMPING, DEFAULT_BARRIER_FREQUENCY_RAD_S, PathBound, SENSED_MIN_DRAG_M_S2,
};
pub use replanning::{
    DEFAULT_EVERY_N_TICKS, HostReplanningGuidance, MAX_EVERY_N_TICKS, NODE_EDGE_E_HAT,
    PredictorModel, RangeTarget, ReplanCounts, ReplanReport, ReplanningConfig, ReplanningGuidance,
    ReplanningOutput, TargetPoint, range_to_go_m,
};
pub use solver::ReplanSolver;

use crate::nav::NavState;
use crate::scalar::Real;
use crate::vinh::VinhError;
use crate::vinh::glide::GlideSolution;
use crate::vinh::nondim::{EntryState, ExpAtmosphere, LiftControl, Planet, VehicleParams};
use crate::vinh::predict::{
    PeakMode, PeakStatus, Prediction, PredictorConfig, glide_start_radius, glide_start_validity,
    glide_validity,
};
use crate::vinh::validity::Validity;

/// Largest accepted [`ReplanConfig::max_iterations`].
pub const MAX_ITERATIONS: u8 = 40;

/// Fractions scanned when a limit binds.
pub const LIMIT_GRID: u8 = 16;

/// Worst-case predictor calls of one solve: `2 (MAX_ITERATIONS + LIMIT_GRID) + 18`, the
/// hybrid modes' worst case: a closed-form solve ([`PredictorMode::HybridSink`]: two end points
/// of a failed chain attempt, two of the glide attempt, two more of the glide without the sink
/// when the range with it is not monotone, the range search, one prediction with peaks at the
/// result, the limit grid: `MAX_ITERATIONS + 7 + LIMIT_GRID`) whose result is out of the
/// validated domain, then the numerical solve (`MAX_ITERATIONS + 3 + LIMIT_GRID`). Every other
/// mode needs at most `MAX_ITERATIONS + 7 + LIMIT_GRID`. A warm start
/// ([`ReplanSolver::with_warm_start`]) adds its guess and at most three secant steps before
/// each of the two solves (8; [`replan`] itself starts cold: at most `+ 10`). A numerical
/// prediction counts once, however many solver steps it spans.
pub const MAX_PREDICTOR_CALLS: u8 = 2 * (MAX_ITERATIONS + LIMIT_GRID) + 18;

/// How far above the current radius a glide-mode prediction may start \[m\]. A vehicle given
/// more lift than its equilibrium glide needs climbs to a higher equilibrium: in an
/// exponential atmosphere the equilibrium density at a given speed scales as `1/cos(sigma)`,
/// so the interval `[f_min, 1]` spans `H_s ln(1/f_min)` of altitude (21.6 km for `f_min = 0.05`
/// and `H_s = 7.2 km`); 40 km covers `f_min` down to 0.004.
pub const GLIDE_CLIMB_MARGIN_M: f64 = 40_000.0;

/// Which analytic prediction the solver uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum PredictorMode {
    /// The full chain [`crate::vinh::predict()`] (skips, arcs, final glide) from the state.
    Chain,
    /// Equilibrium glide only, from the current speed: the glide closed form started at the
    /// radius (at most [`GLIDE_CLIMB_MARGIN_M`] above the current one) where its imposed speed
    /// (eq. 3.78) equals the current speed, run to the final speed. The current flight-path
    /// angle is not used (the glide imposes its own). For a vehicle already gliding, where the
    /// skip closed form of the chain is out of its domain (e.g. `NotOscillatory` for a shallow
    /// state deep in the atmosphere).
    Glide,
    /// [`PredictorMode::Chain`]; if it is out of domain at either end of the interval, the
    /// whole solve is redone in [`PredictorMode::Glide`] (never mixing the two in one solve,
    /// so the bracketing stays consistent).
    Auto,
    /// [`PredictorMode::Auto`] whose glide adds the range of the sink from the current radius
    /// to the glide start radius ([`predict_glide_with_sink`]): a vehicle above the
    /// equilibrium of the commanded lift (after a bank reversal has lofted it, or a bank
    /// decrease) flies farther than the glide started at its equilibrium. Meant for a
    /// re-planner whose model is corrected onboard ([`crate::estimate`]): with the model's own
    /// density error uncorrected, an offset from the equilibrium is mostly model error, not a
    /// sink to come ([`predict_glide_with_sink`]). Measured in the dispersion campaigns
    /// (docs/reference/campaigns.md).
    AutoSink,
    /// Numerical integration of the predictor model's planar equations of motion from the
    /// navigated state (its flight-path angle included) with constant lift, to the final speed:
    /// valid wherever the model is, at the cost of many right-hand sides per prediction (spread
    /// over several solver steps). See docs/reference/vinh.md, "Numerical predictor".
    Numerical,
    /// The closed forms as in `Auto` when both ends of the interval are in their validated
    /// domain (validity `InDomain`); otherwise the whole solve is redone with `Numerical`
    /// (never mixing the two in one solve).
    Hybrid,
    /// `Hybrid` whose closed-form part is `AutoSink`.
    HybridSink,
}

/// Vehicle limits checked on the prediction (the predictor's [`crate::vinh::LoadLimits`]).
pub use crate::vinh::predict::LoadLimits as ReplanLimits;

/// Re-planner settings.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ReplanConfig<S> {
    /// Total lift parameter `lambda = C_L / C_L*` set by the angle of attack \[-\].
    pub lambda: S,
    /// Smallest allowed vertical lift fraction `cos(sigma)` \[-\], in `(0, 1]`.
    pub min_vertical_fraction: S,
    /// Largest allowed vertical lift fraction \[-\], in `[min, 1]`.
    pub max_vertical_fraction: S,
    /// Accepted range miss \[m\].
    pub tolerance_m: S,
    /// Corrector predictions per range search (Brent steps; at most [`MAX_ITERATIONS`]).
    pub max_iterations: u8,
    /// Predictor settings (final glide speed, skip budget).
    pub predictor: PredictorConfig<S>,
    /// Which prediction to use.
    pub mode: PredictorMode,
}

/// Default [`ReplanConfig::lambda`]: the angle of attack of maximum L/D \[-\].
pub const DEFAULT_LAMBDA: f64 = 1.0;
/// Default [`ReplanConfig::min_vertical_fraction`] \[-\] (a bank of at most 87.1 deg).
pub const DEFAULT_MIN_VERTICAL_FRACTION: f64 = 0.05;
/// Default [`ReplanConfig::max_vertical_fraction`] \[-\] (lift up allowed).
pub const DEFAULT_MAX_VERTICAL_FRACTION: f64 = 1.0;
/// Default [`ReplanConfig::tolerance_m`] \[m\].
pub const DEFAULT_TOLERANCE_M: f64 = 1000.0;
/// Default [`ReplanConfig::max_iterations`] \[predictions\].
pub const DEFAULT_MAX_ITERATIONS: u8 = 20;
/// Default [`PredictorConfig::max_skips`] of [`ReplanConfig::new`].
pub const DEFAULT_MAX_SKIPS: u8 = 4;

impl<S: Real> ReplanConfig<S> {
    /// The re-planner's default settings for a prediction that ends at `final_speed_m_s`
    /// \[m/s\] (the terminal interface speed, `> 0`): lambda [`DEFAULT_LAMBDA`], vertical
    /// fraction in [[`DEFAULT_MIN_VERTICAL_FRACTION`], [`DEFAULT_MAX_VERTICAL_FRACTION`]],
    /// tolerance [`DEFAULT_TOLERANCE_M`], [`DEFAULT_MAX_ITERATIONS`] iterations,
    /// [`DEFAULT_MAX_SKIPS`] skips, [`PredictorMode::Hybrid`] (the closed forms where their
    /// prediction is in the validated domain, else the numerical predictor). These are the
    /// defaults of host-sim's `[guidance.replanning]` layer (scenarios and campaigns).
    ///
    /// ```
    /// use guidance_core::replan::{PredictorMode, ReplanConfig};
    /// let c = ReplanConfig::<f32>::new(2500.0);
    /// assert_eq!(c.predictor.final_speed_m_s, 2500.0);
    /// assert_eq!(c.mode, PredictorMode::Hybrid);
    /// assert_eq!((c.min_vertical_fraction, c.tolerance_m), (0.05, 1000.0));
    /// ```
    #[must_use]
    pub fn new(final_speed_m_s: S) -> Self {
        Self {
            lambda: S::from_f64(DEFAULT_LAMBDA),
            min_vertical_fraction: S::from_f64(DEFAULT_MIN_VERTICAL_FRACTION),
            max_vertical_fraction: S::from_f64(DEFAULT_MAX_VERTICAL_FRACTION),
            tolerance_m: S::from_f64(DEFAULT_TOLERANCE_M),
            max_iterations: DEFAULT_MAX_ITERATIONS,
            predictor: PredictorConfig {
                final_speed_m_s,
                max_skips: DEFAULT_MAX_SKIPS,
            },
            mode: PredictorMode::Hybrid,
        }
    }
}

/// Why the re-planner fell back to the stored profile.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum ReplanFallBack {
    /// The analytic predictor is out of its domain (or an input is invalid).
    OutOfDomain(VinhError),
    /// The predicted range does not increase with the vertical lift fraction.
    NotMonotone,
    /// Even the largest vertical lift fraction violates a limit.
    LimitsInfeasible,
}

/// What happened.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ReplanCase {
    /// The range target is met within tolerance and the limits hold.
    Converged,
    /// The target lies outside the reachable range; the nearest end is returned.
    TargetOutOfReach,
    /// The limits bind: the returned fraction satisfies them, the range misses the target.
    LimitsBind,
    /// Out of domain: keep the stored profile.
    FallBack(ReplanFallBack),
}

/// Result of [`replan`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ReplanResult<S> {
    /// What happened.
    pub case: ReplanCase,
    /// Commanded vertical lift fraction `cos(sigma)` \[-\] (meaningless for a fall-back).
    pub vertical_fraction: S,
    /// Bank-angle magnitude `acos(vertical_fraction)` \[rad\].
    pub bank_rad: S,
    /// Prediction at the returned fraction (`None` for a fall-back).
    pub prediction: Option<Prediction<S>>,
    /// Predictor calls made.
    pub predictor_calls: u8,
}

/// Glide-only prediction ([`PredictorMode::Glide`]) from `state` with constant `lift`, with
/// peaks ([`predict_glide_with`] and [`PeakMode::Full`]).
///
/// # Errors
/// As [`predict_glide_with`].
pub fn predict_glide<S: Real>(
    planet: &Planet<S>,
    atmosphere: &ExpAtmosphere<S>,
    vehicle: &VehicleParams<S>,
    lift: &LiftControl<S>,
    state: &EntryState<S>,
    config: &PredictorConfig<S>,
) -> Result<Prediction<S>, VinhError> {
    predict_glide_with(
        planet,
        atmosphere,
        vehicle,
        lift,
        state,
        config,
        PeakMode::Full,
    )
}

/// Glide-only prediction from `state` with constant `lift`, peaks as `peaks` asks: the glide
/// closed form started at the radius where its imposed speed equals the state's speed, the
/// descent from the state to that radius not modelled (zero range). The re-planner's
/// [`PredictorMode::Glide`]; see [`predict_glide_with_sink`] for the variant that models the
/// sink.
///
/// # Errors
/// Input validation errors, and the domain errors of [`glide_start_radius`] and
/// [`GlideSolution`] (e.g. [`VinhError::GlideNearCircular`] when the speed is above the imposed
/// speed even [`GLIDE_CLIMB_MARGIN_M`] above the state).
pub fn predict_glide_with<S: Real>(
    planet: &Planet<S>,
    atmosphere: &ExpAtmosphere<S>,
    vehicle: &VehicleParams<S>,
    lift: &LiftControl<S>,
    state: &EntryState<S>,
    config: &PredictorConfig<S>,
    peaks: PeakMode<S>,
) -> Result<Prediction<S>, VinhError> {
    glide_prediction(
        planet, atmosphere, vehicle, lift, state, config, peaks, false,
    )
}

/// As [`predict_glide_with`], plus the range of the sink from the state to the glide start
/// radius ([`sink_range_angle_within`], the deficit acting for at most the glide's time to go
/// at the mean of the current and final speeds; on long glides the same as
/// [`sink_range_angle`]; nothing for a state below the glide start radius): a state above the equilibrium of the commanded lift (after a
/// bank change) sinks to it in a phugoid and flies farther than the glide started at its
/// equilibrium. Against integration (glide range-error map, docs/validation/vinh-numerical.md) every start of the
/// map with vertical L/D 0.6-2.5 and a glide start radius at 70-110 km is within 2.9 % (without
/// the sink: up to -12.7 %), so its validity accepts start offsets up to
/// [`crate::vinh::validity::GLIDE_MAX_START_OFFSET_M`] (without the sink: [`crate::vinh::validity::GLIDE_MAX_START_OFFSET_PER_LD_M`] per unit
/// of total L/D).
///
/// The re-planner uses it only in [`PredictorMode::AutoSink`] (with the time-to-go cap), meant
/// for a model corrected onboard: with an uncorrected model a state above the predicted glide
/// start radius is mostly model error (a denser atmosphere than the predictor's raises the real
/// equilibrium), not a sink to come, and the sink term then adds range that is never flown
/// (SRM glide with density x 1.1: final range error -6.4 km against +2.8 km without it;
/// docs/validation/vinh-numerical.md).
///
/// # Errors
/// As [`predict_glide_with`].
pub fn predict_glide_with_sink<S: Real>(
    planet: &Planet<S>,
    atmosphere: &ExpAtmosphere<S>,
    vehicle: &VehicleParams<S>,
    lift: &LiftControl<S>,
    state: &EntryState<S>,
    config: &PredictorConfig<S>,
    peaks: PeakMode<S>,
) -> Result<Prediction<S>, VinhError> {
    glide_prediction(
        planet, atmosphere, vehicle, lift, state, config, peaks, true,
    )
}

/// The glide prediction of [`predict_glide_with`] (`sink` false) and
/// [`predict_glide_with_sink`] (`sink` true).
#[allow(clippy::too_many_arguments)]
pub(crate) fn glide_prediction<S: Real>(
    planet: &Planet<S>,
    atmosphere: &ExpAtmosphere<S>,
    vehicle: &VehicleParams<S>,
    lift: &LiftControl<S>,
    state: &EntryState<S>,
    config: &PredictorConfig<S>,
    peaks: PeakMode<S>,
    sink: bool,
) -> Result<Prediction<S>, VinhError> {
    if !(config.final_speed_m_s.is_finite()
        && state.radius_m.is_finite()
        && state.speed_m_s.is_finite()
        && state.flight_path_angle_rad.is_finite())
    {
        return Err(VinhError::NonFiniteInput);
    }
    if !(config.final_speed_m_s > S::ZERO) {
        return Err(VinhError::InvalidConfig);
    }
    // Validates every input (as the chain does).
    crate::vinh::NonDim::new(planet, atmosphere, vehicle, lift, state)?;
    let r_max = state.radius_m + S::from_f64(GLIDE_CLIMB_MARGIN_M);
    let r_g = glide_start_radius(planet, atmosphere, vehicle, lift, state.speed_m_s, r_max)?;
    let glide = GlideSolution::new(planet, atmosphere, vehicle, lift, r_g)?;
    let end = glide.point_at_speed(config.final_speed_m_s)?;
    let theta = if sink {
        // The sink cannot last longer than the flight: time to go at the mean of the current
        // and final speeds along the glide's range.
        let v_mean = (state.speed_m_s + config.final_speed_m_s).half();
        let t_go = end.range_angle_rad * r_g / v_mean;
        // Only a sink: a state below the glide start radius (a climb to come) adds nothing
        // (the symmetric negative term is not validated, and it makes the range fall with `f`
        // near the end, where a bracket could then close on a root at almost full lift).
        let sink_rad = sink_range_angle_within(planet, atmosphere, state, r_g, t_go);
        end.range_angle_rad + sink_rad.max(S::ZERO)
    } else {
        end.range_angle_rad
    };
    let range = theta * planet.radius_m;
    let (q, n, status) = match peaks {
        PeakMode::RangeOnly => (S::ZERO, S::ZERO, PeakStatus::NotComputed),
        PeakMode::Full | PeakMode::Limits(_) => {
            let start = glide.point_at_u(glide.u_entry())?;
            let (qb, nb) = (
                start.heat_flux_w_m2.max(end.heat_flux_w_m2),
                start.g_load.max(end.g_load),
            );
            match peaks {
                PeakMode::Limits(l) if qb > l.heat_flux_w_m2 || nb > l.g_load => {
                    (qb, nb, PeakStatus::LimitExceeded)
                }
                _ => {
                    let q = glide.peak_heat_flux(config.final_speed_m_s)?.heat_flux_w_m2;
                    let n = glide.peak_g_load(config.final_speed_m_s)?.g_load;
                    let over = match peaks {
                        PeakMode::Limits(l) => q > l.heat_flux_w_m2 || n > l.g_load,
                        _ => false,
                    };
                    let status = if over {
                        PeakStatus::LimitExceeded
                    } else {
                        PeakStatus::Computed
                    };
                    (q, n, status)
                }
            }
        }
    };
    let all = [theta, range, q, n];
    if all.iter().any(|v| !v.is_finite()) {
        return Err(VinhError::NonFiniteResult);
    }
    Ok(Prediction {
        range_angle_rad: theta,
        range_m: range,
        peak_heat_flux_w_m2: q,
        peak_g_load: n,
        skips: 0,
        arcs: 0,
        glide_start_radius_m: r_g,
        glide_range_angle_rad: end.range_angle_rad,
        peak_status: status,
        validity: glide_start_validity(
            glide_validity(
                Validity::InDomain,
                &glide,
                planet,
                r_g,
                config.final_speed_m_s,
            ),
            &glide,
            planet,
            atmosphere,
            state,
            lift,
            end.range_angle_rad,
            sink,
        ),
    })
}

/// Range angle \[rad\] the glide-mode prediction adds for the sink from the state at
/// `state.radius_m` to the glide start radius `r_g` (the equilibrium of the commanded lift at
/// the state's speed), which the glide closed form, started at `r_g`, does not contain.
///
/// Model (docs/validation/vinh-numerical.md, "sink to the equilibrium glide"): above its new equilibrium by
/// `dh = r - r_g` the vehicle meets `exp(-dh/H)` of the equilibrium density, so its drag falls
/// short of the glide's by `1 - exp(-dh/H)`; it sinks to the equilibrium and oscillates about
/// it (a phugoid of angular frequency `w = sqrt(a/H)`, `a = mu/r^2 - V^2/r` the net downward
/// acceleration the lift balances), and the range per unit of excess lift,
/// `V/(r a)`, drops quickly as the vehicle slows near circular speed, so the first swing is not
/// given back by the later ones. The range gained is taken as the range flown during one
/// radian of phugoid phase at the initial drag deficit: `(V/r) (1 - exp(-dh/H)) / w`. No
/// fitted constant; validated against integration by the glide range-error map
/// ([`predict_glide_with_sink`]; docs/validation/vinh-numerical.md). A state below `r_g` gives the symmetric
/// (negative) term, not validated. Zero when `a <= 0` (at or above circular speed, where the glide closed
/// form is out of domain anyway) or for non-finite values.
#[must_use]
pub fn sink_range_angle<S: Real>(
    planet: &Planet<S>,
    atmosphere: &ExpAtmosphere<S>,
    state: &EntryState<S>,
    r_g: S,
) -> S {
    sink_range_angle_within(planet, atmosphere, state, r_g, S::MAX)
}

/// [`sink_range_angle`] when only `time_to_go_s` \[s\] of flight is left: the drag deficit
/// acts for `min(1/w, time_to_go_s)` instead of one radian of phugoid phase `1/w` (near the end
/// of the flight there is no time for the sink to pay out; the same as
/// [`sink_range_angle`] when `time_to_go_s >= 1/w`). A non-finite or negative time counts as
/// unbounded.
#[must_use]
pub fn sink_range_angle_within<S: Real>(
    planet: &Planet<S>,
    atmosphere: &ExpAtmosphere<S>,
    state: &EntryState<S>,
    r_g: S,
    time_to_go_s: S,
) -> S {
    let r = state.radius_m;
    let v = state.speed_m_s;
    let h_s = atmosphere.scale_height_m;
    let a = planet.mu_m3_s2 / (r * r) - v * v / r;
    if !(a > S::ZERO && h_s > S::ZERO && r > S::ZERO) {
        return S::ZERO;
    }
    let deficit = S::ONE - (-(r - r_g) / h_s).exp();
    let w = (a / h_s).sqrt_raw();
    let one_radian_s = S::ONE / w;
    let acting_s = if time_to_go_s.is_finite() && time_to_go_s >= S::ZERO {
        one_radian_s.min(time_to_go_s)
    } else {
        one_radian_s
    };
    let d = v / r * deficit * acting_s;
    if d.is_finite() { d } else { S::ZERO }
}

/// Re-plan the vertical lift fraction for `target_range_m` \[m\] of surface range to go from `nav`.
///
/// Never panics; every outcome, including invalid input, is a [`ReplanResult`].
#[must_use]
pub fn replan<S: Real>(
    planet: &Planet<S>,
    atmosphere: &ExpAtmosphere<S>,
    vehicle: &VehicleParams<S>,
    nav: &NavState<S>,
    target_range_m: S,
    limits: &ReplanLimits<S>,
    config: &ReplanConfig<S>,
) -> ReplanResult<S> {
    let mut solver = ReplanSolver::new(
        planet,
        atmosphere,
        vehicle,
        nav,
        target_range_m,
        limits,
        config,
    );
    // Each step makes at most one predictor call (a numerical one spans at most
    // numerical::MAX_STEPS / STEPS_PER_SOLVER_STEP + 1 steps) and the solver stops at
    // MAX_PREDICTOR_CALLS, so this loop ends.
    loop {
        if let Some(r) = solver.step() {
            return r;
        }
    }
}
