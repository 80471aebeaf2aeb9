//! [`ReplanningGuidance`]: the flight [`Guidance`] with the onboard re-planner in the loop.
//!
//! # What it does
//! [`ReplanningGuidance::update`] is called with every navigation sample, like
//! [`Guidance::update`]. On every `every_n_ticks`-th guidance tick (the 2 s clock; the first
//! tick is tick 0 and re-plans) and *before* the command of that tick is computed, it
//!
//! 1. computes the range to go to the target ([`RangeTarget`]: a point, see [`range_to_go_m`],
//!    or a total range angle along the path);
//! 2. runs the solver ([`super::replan`]) from the current [`NavState`] with the configured
//!    predictor model, limits and solver options;
//! 3. if the case is [`ReplanCase::Converged`] or [`ReplanCase::LimitsBind`] (a feasible
//!    fraction that satisfies the limits) — and, only if
//!    [`ReplanningConfig::apply_out_of_reach`] is set, [`ReplanCase::TargetOutOfReach`] —
//!    sets the bank angle of every *remaining* node (E-hat below the current E-hat plus
//!    [`NODE_EDGE_E_HAT`]: not yet passed) to the solved magnitude with the node's own sign
//!    (a node at 0 counts as positive), clamped into the table's bounds, keeps the angle of
//!    attack and the node positions, and installs the table with [`Guidance::replace_table`]. Because this happens
//!    before the tick's command is computed, the re-planned table is used at this tick;
//! 4. otherwise ([`ReplanCase::FallBack`], or out of reach without the option) keeps the table
//!    in use (the stored profile, or the last applied re-plan).
//!
//! Then the tick proceeds exactly as in [`Guidance::update`] (interpolation, rate limit, hold).
//! The command is therefore subject to the same guarantees: always finite and inside the
//! table's bounds. Between the last passed node and the first remaining one the interpolated
//! command moves from the passed node's (unchanged) bank towards the solved value; the
//! predictor-corrector loop absorbs this at the next re-plan.
//!
//! Ticks are counted as guidance ticks taken (a navigation gap that skips tick instants counts
//! once, as [`Guidance`] recomputes once).
//!
//! # Target
//! Two forms ([`RangeTarget`]); in both the range to go is recomputed onboard from navigation at
//! each re-plan, so a dispersion of the flown path is seen by the next re-plan:
//!
//! * a target point (geocentric latitude/longitude): the range to go is the great-circle angle
//!   from the current position to the target, times the predictor planet radius (the same
//!   `R theta` as [`crate::vinh::Prediction::range_m`]), *negative* when the target lies behind
//!   the vehicle (bearing to the target more than 90 deg from the heading): the solver then
//!   reports [`ReplanCase::TargetOutOfReach`] at the smallest vertical fraction. Suited when
//!   the path stays close to the great circle to the target (small bank, or bank reversals by
//!   a lateral logic that this module does not provide);
//! * a total range angle along the path: range to go = `(total - flown) R` with an onboard
//!   odometer. This is the quantity the planar predictor models; with a bank-only vehicle of
//!   high L/D and no bank reversals the heading turns by tens of degrees and only this form
//!   is consistent with the predictor.
//!
//! # Bounded work per tick
//! With [`ReplanningConfig::steps_per_tick`] `= 0` a re-plan runs to completion inside its tick.
//! With `k >= 1` the solve is a [`ReplanSolver`] kept across ticks: the re-planning tick starts
//! it (range to go, effective planet and state of that tick) and does at most `k` solver steps
//! of work ([`ReplanSolver::run`]); every following tick does at most `k` more, until it
//! completes. Meanwhile the table
//! in use (stored profile or last re-plan) flies unchanged and the command of every tick is
//! computed as without re-planning, so it is always on time. When the solve completes its
//! result is applied at that tick, to the nodes below that tick's E-hat, and reported
//! ([`ReplanReport::start_tick`], [`ReplanReport::tick`]). A new solve starts at the first
//! re-planning tick (multiple of `every_n_ticks`) after the previous one completed.
//!
//! A spread solve is warm-started ([`ReplanSolver::with_warm_start`]) from the vertical
//! fraction of the last converged solve and the range slope its last two predictions
//! measured ([`ReplanSolver::range_slope`]; a solve that measured none passes the previous
//! slope on): a guess and secant steps, then Brent's search once they bracket the target, the
//! cold start otherwise. In the hybrid modes a solve after one that went numerical starts
//! numerical ([`ReplanSolver::numerical_from_start`]): its closed-form search would be thrown
//! away at the switch, and each of its calls costs a solver step. Fewer predictions per solve
//! shorten the time a solve flies a stale table. Without a converged solve before it (the first, or after a fall-back or an
//! out-of-reach result) a solve starts cold; its answer is then bit for bit that of
//! [`super::replan`] from the start state (tested). A whole solve in its tick (`k = 0`)
//! always starts cold: measured on HORUS-2B (300 dispersed flights), a warm start there
//! raised the 99th-percentile miss from 4.4 to 7.1 km (docs/reference/guidance-stack.md,
//! "Spreading a re-plan over ticks").
//!
//! With the numerical predictor ([`super::PredictorMode::Numerical`], or a hybrid solve out of
//! the closed forms' domain) a tick's `k` solver steps are `k` times
//! [`super::numerical::STEPS_PER_SOLVER_STEP`] integration steps, shared by the predictions
//! they complete (a closed-form call costs one solver step), so a long numerical prediction
//! spans several ticks while the short ones near the end of the flight complete a whole solve
//! in one (docs/reference/vinh.md, "Numerical predictor").
//!
//! Measured on the Cortex-M4F (`f32`) with `k = 1`: the largest guidance tick of the
//! re-planner alone (numerical SRM glide) and of the SRM glide's whole stack stay below 200 k
//! instructions; HORUS-2B's whole stack does not (359 k: 64 RK4 steps with the barrier law at
//! every stage). The counts and their budgets: docs/reference/performance.md,
//! `onboard-demo/insn-budget.toml`.
//!
//! # Cost (worst case, bounded)
//! An update without a re-plan costs what [`Guidance::update`] costs plus one great-circle
//! angle (the odometer). An update with re-planning work adds: one E-hat evaluation, at the
//! start one range to go (a great-circle angle and a bearing: about 10 trig functions), the
//! predictor calls (all of a solve, at most [`super::MAX_PREDICTOR_CALLS`]` = 130`, or at most
//! `steps_per_tick`; each chain call at most [`crate::vinh::predict::MAX_SKIPS`] skips and
//! arcs plus one glide), and at completion a copy of the table (at most
//! `N` nodes, the table's capacity) and one interpolator rebuild. No allocation, no
//! recursion, no panics.
//!
//! # Rotating planet
//! The closed forms assume a non-rotating planet. [`PredictorModel::rotation_rate_rad_s`]
//! enables a first-order effective-gravity correction (see there).

use crate::energy::{EARTH_ROTATION_RATE_RAD_S, EnergyNormalizer};
use crate::error::GuidanceError;
use crate::estimate::{AeroEstimator, AeroScales, EstimateError, EstimateStatus, SensedAero};
use crate::geo::{central_angle, initial_bearing};
use crate::guidance::{BankSign, Command, Guidance, GuidanceConfig, GuidanceOutput};
use crate::interp::Interpolation;
use crate::nav::NavState;
use crate::nodes::{DEFAULT_NODE_CAPACITY, HOST_NODE_CAPACITY, Independent, NodeTable};
use crate::scalar::{Real, Scalar};
use crate::vinh::nondim::{ExpAtmosphere, Planet, VehicleParams};

use super::BankShape;
use super::{
    LiftSchedule, PathBound, ReplanCase, ReplanConfig, ReplanLimits, ReplanResult, ReplanSolver,
};
use crate::vinh::VinhError;

/// Largest accepted [`ReplanningConfig::every_n_ticks`] (one re-plan per 65535 ticks, about
/// 36 h at 2 s).
pub const MAX_EVERY_N_TICKS: u16 = u16::MAX;

/// Target point on the planet \[rad\].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TargetPoint<S> {
    /// Geocentric latitude \[rad\], in `[-pi/2, pi/2]`.
    pub latitude_rad: S,
    /// Longitude \[rad\], positive east.
    pub longitude_rad: S,
}

/// What the re-planner aims at.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RangeTarget<S> {
    /// A point: range to go = signed great-circle distance from the current position
    /// ([`range_to_go_m`]).
    Point(TargetPoint<S>),
    /// A total range angle to fly along the path, counted from the first accepted navigation
    /// sample \[rad\]: range to go = `(total_rad - flown) R`, with the flown range angle
    /// accumulated onboard from successive navigation positions (great-circle angle between
    /// samples; the chord error at 2 s samples is below 1e-9 relative). This is what the planar
    /// predictor models (range along the path), so it stays meaningful when the bank turns the
    /// vehicle far from the initial great circle.
    FlownRangeAngle {
        /// Total range angle along the path \[rad\].
        total_rad: S,
    },
}

/// The predictor's model of the world: planet, exponential atmosphere and vehicle polar.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PredictorModel<S> {
    /// Central-gravity, non-rotating planet; its radius also scales the range to go.
    pub planet: Planet<S>,
    /// Exponential atmosphere.
    pub atmosphere: ExpAtmosphere<S>,
    /// Vehicle constants (parabolic polar).
    pub vehicle: VehicleParams<S>,
    /// Planet rotation rate \[rad/s\] for the effective-gravity correction (0: none). The
    /// closed forms assume a non-rotating planet; with a rate `Omega` each re-plan lowers the
    /// gravitational parameter by the vertical apparent acceleration of the rotating frame
    /// (Coriolis at the mean of the current and final speeds, plus centrifugal) at the current
    /// position and heading: `mu_eff = mu - r^2 (2 Omega V_m cos(lat) sin(heading) cos(gamma) +
    /// Omega^2 r cos^2(lat))`. A first-order correction; it ignores the later turn of the
    /// heading by the bank and the change of latitude.
    pub rotation_rate_rad_s: S,
}

impl<S: Real> PredictorModel<S> {
    /// A model of `vehicle` (its parabolic polar) on a non-rotating `planet` with
    /// `atmosphere`.
    #[must_use]
    pub fn new(planet: Planet<S>, atmosphere: ExpAtmosphere<S>, vehicle: VehicleParams<S>) -> Self {
        Self {
            planet,
            atmosphere,
            vehicle,
            rotation_rate_rad_s: S::ZERO,
        }
    }

    /// A model of `vehicle` on the thesis' Earth ([`Planet::earth`], [`ExpAtmosphere::earth`]:
    /// `rho0 = 1.225 kg/m^3`, `H_s = 7200 m`) with the effective-gravity correction for the
    /// Earth's rotation ([`EARTH_ROTATION_RATE_RAD_S`]).
    ///
    /// ```
    /// use guidance_core::missions::horus2b_vehicle;
    /// use guidance_core::replan::PredictorModel;
    /// let model = PredictorModel::<f32>::earth(horus2b_vehicle());
    /// assert_eq!(model.planet.radius_m, 6_378_137.0);
    /// ```
    #[must_use]
    pub fn earth(vehicle: VehicleParams<S>) -> Self {
        Self {
            rotation_rate_rad_s: S::from_f64(EARTH_ROTATION_RATE_RAD_S),
            ..Self::new(Planet::earth(), ExpAtmosphere::earth(), vehicle)
        }
    }

    /// The planet the predictor uses at `nav` (see [`PredictorModel::rotation_rate_rad_s`]);
    /// the model planet if the correction is zero, non-finite or would make `mu` non-positive.
    #[must_use]
    pub fn effective_planet(&self, nav: &NavState<S>, final_speed_m_s: S) -> Planet<S> {
        let w = self.rotation_rate_rad_s;
        if w == S::ZERO || !w.is_finite() {
            return self.planet;
        }
        let r = nav.radius_m;
        let cl = nav.latitude_rad.cos();
        let v_mean = (nav.speed_m_s + final_speed_m_s.max(S::ZERO)).half();
        let two = S::ONE + S::ONE;
        let up = two * w * v_mean * cl * nav.heading_rad.sin() * nav.flight_path_angle_rad.cos()
            + w * w * r * cl * cl;
        let mu = self.planet.mu_m3_s2 - r * r * up;
        if mu.is_finite() && mu > S::ZERO {
            Planet {
                mu_m3_s2: mu,
                radius_m: self.planet.radius_m,
            }
        } else {
            self.planet
        }
    }
}

/// Settings of [`ReplanningGuidance`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ReplanningConfig<S> {
    /// Re-plan on every N-th guidance tick \[ticks\], `>= 1` (1: every 2 s tick).
    pub every_n_ticks: u16,
    /// Where the vehicle should arrive (at the predictor's final speed).
    pub target: RangeTarget<S>,
    /// Peak heat-flux and g-load limits checked on the prediction.
    pub limits: ReplanLimits<S>,
    /// Solver options (lambda, vertical-fraction interval, tolerance, iterations, predictor).
    pub solver: ReplanConfig<S>,
    /// Predictor model.
    pub model: PredictorModel<S>,
    /// Also apply the nearest end of the vertical-fraction interval when the target is out of
    /// reach (a saturated corrector). `false`: out of reach keeps the current table.
    pub apply_out_of_reach: bool,
    /// Work budget per guidance tick \[solver steps\]: 0 runs a whole re-plan inside its
    /// tick (at most [`super::MAX_PREDICTOR_CALLS`] calls), from a cold start; `k >= 1`
    /// spreads it over ticks, at most `k` solver steps of work per tick
    /// ([`super::ReplanSolver::run`]: one closed-form predictor call, or
    /// [`super::numerical::STEPS_PER_SOLVER_STEP`] integration steps shared by the numerical
    /// predictions they complete), the table in use flying until the solve completes, each
    /// solve warm-started from the last converged one (module docs, "Bounded work per tick").
    pub steps_per_tick: u8,
}

/// Default [`ReplanningConfig::every_n_ticks`] \[ticks\]: a re-plan every 10 s at the 2 s
/// guidance period.
pub const DEFAULT_EVERY_N_TICKS: u16 = 5;

/// A node at most this far above the current E-hat \[-\] counts as remaining when a re-plan
/// sets the nodes below E-hat (1e-6 of the energy span, about 0.004 m/s at orbital speed).
/// Without it a node at the current E-hat (a first node at E-hat 1 and a re-plan at entry)
/// is replaced or kept by the last bit of E-hat: `f64`, `f32` and fixed point round the same
/// state to either side of it and then fly different profiles. 1e-6 is above the rounding of
/// E-hat in each of them (`f32` 1.2e-7 at 1, fixed point 2.3e-10 per operation) and far below
/// a node spacing.
pub const NODE_EDGE_E_HAT: f64 = 1e-6;

impl<S: Real> ReplanningConfig<S> {
    /// The default re-planner aimed at `target`, its predictions ending at `final_speed_m_s`
    /// \[m/s\] and checked against `limits` (peak heat flux \[W/m^2\] and g-load), predicting
    /// with `model`: a re-plan every [`DEFAULT_EVERY_N_TICKS`] ticks, the solver settings of
    /// [`ReplanConfig::new`], the nearest end applied when the target is out of reach
    /// (`apply_out_of_reach = true`), the whole solve in its tick (`steps_per_tick = 0`; set
    /// it to 1 on a target with a per-tick budget). Every field stays public for changes;
    /// [`ReplanningGuidance::new`] checks them.
    ///
    /// ```
    /// use guidance_core::missions::{HORUS2B_LIMITS, horus2b_vehicle};
    /// use guidance_core::replan::{PredictorModel, RangeTarget, ReplanningConfig};
    /// let target = RangeTarget::FlownRangeAngle { total_rad: 0.9_f32 };
    /// let mut config = ReplanningConfig::new(
    ///     target,
    ///     2500.0,
    ///     HORUS2B_LIMITS.load_limits(),
    ///     PredictorModel::earth(horus2b_vehicle()),
    /// );
    /// config.steps_per_tick = 1; // spread each solve over ticks
    /// assert_eq!(config.every_n_ticks, 5);
    /// ```
    #[must_use]
    pub fn new(
        target: RangeTarget<S>,
        final_speed_m_s: S,
        limits: ReplanLimits<S>,
        model: PredictorModel<S>,
    ) -> Self {
        Self {
            every_n_ticks: DEFAULT_EVERY_N_TICKS,
            target,
            limits,
            solver: ReplanConfig::new(final_speed_m_s),
            model,
            apply_out_of_reach: true,
            steps_per_tick: 0,
        }
    }
}

/// What one re-plan did.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ReplanReport<S> {
    /// Index of the guidance tick (ticks taken, the first is 0).
    pub tick: u32,
    /// Navigation time of the re-plan \[s\].
    pub time_s: S,
    /// E-hat at the re-plan \[-\].
    pub normalized_energy: S,
    /// Signed range to go to the target \[m\] (negative: target behind).
    pub range_to_go_m: S,
    /// What the solver reported.
    pub case: ReplanCase,
    /// Predictor calls made by the whole solve (at most [`super::MAX_PREDICTOR_CALLS`]).
    pub predictor_calls: u8,
    /// Tick at which the solve started (equal to `tick` without a per-tick budget).
    pub start_tick: u32,
    /// Solved bank-angle magnitude \[rad\] (0 for a fall-back).
    pub bank_rad: S,
    /// Predicted range at the solved bank \[m\] (`None` for a fall-back).
    pub predicted_range_m: Option<S>,
    /// Predicted peak heat flux at the solved bank \[W/m^2\] (`None` for a fall-back).
    pub predicted_peak_heat_flux_w_m2: Option<S>,
    /// Predicted peak g-load at the solved bank \[-\] (`None` for a fall-back).
    pub predicted_peak_g_load: Option<S>,
    /// True if the table was replaced.
    pub applied: bool,
    /// Number of nodes whose bank angle was set (0 if not applied).
    pub nodes_replanned: u16,
    /// True if the installed bank is the [`PathBound`]'s, smaller than the solved `bank_rad`.
    pub path_bound_active: bool,
}

/// Counts of re-plan outcomes since start (saturating).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ReplanCounts {
    /// Re-plans run.
    pub replans: u32,
    /// [`ReplanCase::Converged`].
    pub converged: u32,
    /// [`ReplanCase::TargetOutOfReach`].
    pub out_of_reach: u32,
    /// [`ReplanCase::LimitsBind`].
    pub limits_bind: u32,
    /// [`ReplanCase::FallBack`] (any reason).
    pub fall_backs: u32,
    /// Re-plans whose table was installed.
    pub applied: u32,
    /// Installed re-plans whose bank the [`PathBound`] lowered.
    pub path_bound_active: u32,
    /// Largest predictor-call count of one re-plan.
    pub max_predictor_calls: u8,
}

impl ReplanCounts {
    fn record<S>(&mut self, r: &ReplanReport<S>) {
        let inc = |v: &mut u32| *v = v.saturating_add(1);
        inc(&mut self.replans);
        match r.case {
            ReplanCase::Converged => inc(&mut self.converged),
            ReplanCase::TargetOutOfReach => inc(&mut self.out_of_reach),
            ReplanCase::LimitsBind => inc(&mut self.limits_bind),
            ReplanCase::FallBack(_) => inc(&mut self.fall_backs),
        }
        if r.applied {
            inc(&mut self.applied);
        }
        if r.path_bound_active {
            inc(&mut self.path_bound_active);
        }
        self.max_predictor_calls = self.max_predictor_calls.max(r.predictor_calls);
    }
}

/// Result of one [`ReplanningGuidance::update`] (guidance scalar `S`, predictor scalar `P`).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ReplanningOutput<S, P = S> {
    /// The guidance output of this sample (held command, tick flag, E-hat).
    pub guidance: GuidanceOutput<S>,
    /// The re-plan completed at this sample, if any.
    pub replan: Option<ReplanReport<P>>,
    /// Predictor calls completed during this sample (0 without re-planning work; with
    /// [`ReplanningConfig::steps_per_tick`] `= k > 0`, at most `k` closed-form calls, or the
    /// numerical predictions that the sample's integration steps complete).
    pub predictor_calls: u8,
    /// Integration steps of numerical predictions made during this sample (0 with the closed
    /// forms; at most `steps_per_tick` times
    /// [`super::numerical::STEPS_PER_SOLVER_STEP`] when `steps_per_tick` is not 0).
    pub integration_steps: u32,
}

/// A re-plan in progress ([`ReplanningConfig::steps_per_tick`] `> 0`).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
struct Pending<S> {
    solver: ReplanSolver<S>,
    start_tick: u32,
    time_s: S,
    range_to_go_m: S,
}

/// [`ReplanningGuidance`] over a host-sized node table ([`HOST_NODE_CAPACITY`] nodes).
pub type HostReplanningGuidance<S> = ReplanningGuidance<S, HOST_NODE_CAPACITY>;

/// [`Guidance`] (energy-indexed table of capacity `N`, see [`crate::nodes`]) with periodic
/// onboard re-planning (module docs).
///
/// Two scalar types: `S` for the guidance path (any [`Scalar`], fixed point included: the
/// guidance tick of a Cortex-M3 without FPU) and `P` for the predictor-corrector, the odometer
/// and the re-planning settings (a [`Real`]: `f32` or `f64`; by default `S`). With `P != S` the
/// navigation state is converted to `P` (through `f64`) for the re-planner and the solved bank
/// magnitude back to `S` for the table; with `P == S` the conversions are exact.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ReplanningGuidance<S, const N: usize = DEFAULT_NODE_CAPACITY, P = S> {
    guidance: Guidance<S, N>,
    energy: EnergyNormalizer<S>,
    config: ReplanningConfig<P>,
    ticks: u32,
    last: Option<ReplanReport<P>>,
    counts: ReplanCounts,
    /// Flown range angle since the first accepted sample \[rad\].
    flown_rad: P,
    /// Position of the last accepted sample (latitude, longitude) \[rad\].
    last_position: Option<(P, P)>,
    /// The solve in progress.
    pending: Option<Pending<P>>,
    /// The last converged solve's vertical fraction \[-\], range slope \[m\] and whether it
    /// used the numerical predictor: the next spread solve's warm start.
    warm: Option<(P, P, bool)>,
    /// Onboard aerodynamic estimation (`None`: the predictor flies the model as is).
    estimator: Option<AeroEstimator<P>>,
    /// The lift parameter against speed of numerical predictions and of the estimator's model.
    lift_schedule: Option<LiftSchedule<P>>,
    /// No solve starts while E-hat is above this.
    start_energy: Option<S>,
    /// The limit-driven bound on the applied bank magnitude.
    path_bound: Option<PathBound<P>>,
    /// Numerical predictions fly the path bound too.
    path_bound_predicted: bool,
    /// Numerical predictions end at this specific energy \[J/kg\] (`None`: the final speed).
    final_energy_j_kg: Option<P>,
    /// Numerical predictions model the planet's rotation in their equations (with the
    /// model planet) instead of the effective planet.
    numerical_rotation: bool,
    /// The last sensed aerodynamic accelerations and their sample's time \[s\] (for the
    /// barrier bound).
    sensed: Option<(S, SensedAero<P>)>,
    /// The stored profile's bank against E-hat that numerical predictions fly and re-plans
    /// shift ([`ReplanningGuidance::with_bank_shape`]).
    shape: Option<BankShape<P>>,
}

/// `x` in the predictor scalar (through `f64`; exact when both are the same type).
fn to_p<S: Scalar, P: Real>(x: S) -> P {
    P::from_f64(x.to_f64())
}

/// `nav` in the predictor scalar.
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

/// Signed range to go \[m\] from `nav`'s position to `target` on a sphere of radius
/// `planet_radius_m` \[m\]: great-circle angle (haversine form, accurate for small and large
/// angles) times the radius, negative when the bearing to the target differs from the heading
/// by more than 90 deg. `None` for non-finite input or result.
#[must_use]
pub fn range_to_go_m<S: Real>(
    nav: &NavState<S>,
    target: &TargetPoint<S>,
    planet_radius_m: S,
) -> Option<S> {
    let all = [
        nav.latitude_rad,
        nav.longitude_rad,
        nav.heading_rad,
        target.latitude_rad,
        target.longitude_rad,
        planet_radius_m,
    ];
    if all.iter().any(|v| !v.is_finite()) {
        return None;
    }
    let (lat1, lat2) = (nav.latitude_rad, target.latitude_rad);
    let theta = central_angle(lat1, nav.longitude_rad, lat2, target.longitude_rad)?;
    // Initial bearing to the target, clockwise from north (0 when on the target: ahead).
    let bearing = initial_bearing(lat1, nav.longitude_rad, lat2, target.longitude_rad)?;
    let ahead = theta == S::ZERO || (bearing - nav.heading_rad).cos() >= S::ZERO;
    let r = theta * planet_radius_m;
    let r = if ahead { r } else { -r };
    r.is_finite().then_some(r)
}

impl<S: Scalar, const N: usize, P: Real> ReplanningGuidance<S, N, P> {
    /// Set up: the arguments up to `initial` are those of [`Guidance::new`] (the table must be
    /// energy-indexed); `config` the re-planning settings.
    ///
    /// # Errors
    /// As [`Guidance::new`]; [`GuidanceError::InvalidConfig`] for a time-indexed table,
    /// `every_n_ticks == 0`, a non-finite target, a predictor model the closed forms reject
    /// (planet, atmosphere, vehicle; non-finite rotation rate), or solver settings out of their
    /// domain (vertical-fraction interval not in `(0, 1]`, tolerance or limits not positive,
    /// more than [`super::MAX_ITERATIONS`] iterations or [`crate::vinh::predict::MAX_SKIPS`]
    /// skips, negative lambda, final speed not positive).
    ///
    /// The SRM glide of [`crate::missions::srm_glide`] re-planned to a flown range of 8000 km
    /// with the default settings ([`ReplanningConfig::new`]):
    ///
    /// ```
    /// use guidance_core::missions::{SRM_LIMITS, srm_glide, srm_vehicle};
    /// use guidance_core::replan::{PredictorModel, RangeTarget, ReplanningConfig, ReplanningGuidance};
    /// use guidance_core::NavState;
    /// let m = srm_glide::<f64>()?;
    /// let target = RangeTarget::FlownRangeAngle { total_rad: 8.0e6 / 6_378_137.0 };
    /// let mut model = PredictorModel::earth(srm_vehicle());
    /// model.rotation_rate_rad_s = 0.0; // the SRM glide's planet does not rotate
    /// let config = ReplanningConfig::new(target, 2500.0, SRM_LIMITS.load_limits(), model);
    /// let mut g = ReplanningGuidance::new(
    ///     m.config,
    ///     m.table.clone(),
    ///     m.interpolation,
    ///     m.earth_energy_normalizer()?,
    ///     m.initial,
    ///     config,
    /// )?;
    /// let nav = NavState {
    ///     time_s: 0.0,
    ///     radius_m: 6_378_137.0 + 100e3,
    ///     speed_m_s: 7658.34,
    ///     flight_path_angle_rad: -0.001,
    ///     heading_rad: core::f64::consts::FRAC_PI_2,
    ///     latitude_rad: 0.0,
    ///     longitude_rad: 0.0,
    /// };
    /// let out = g.update(&nav)?; // tick 0 re-plans
    /// let report = out.replan.expect("the first tick re-plans");
    /// assert!(report.predictor_calls > 0);
    /// assert!(out.guidance.command.sigma_rad.abs() <= core::f64::consts::FRAC_PI_2);
    /// # Ok::<(), guidance_core::GuidanceError>(())
    /// ```
    pub fn new(
        guidance_config: GuidanceConfig<S>,
        table: NodeTable<S, N>,
        kind: Interpolation<S>,
        energy: EnergyNormalizer<S>,
        initial: Command<S>,
        config: ReplanningConfig<P>,
    ) -> Result<Self, GuidanceError> {
        let target_ok = match config.target {
            RangeTarget::Point(p) => p.latitude_rad.is_finite() && p.longitude_rad.is_finite(),
            RangeTarget::FlownRangeAngle { total_rad } => total_rad.is_finite(),
        };
        let m = &config.model;
        let model_ok = m.planet.validate().is_ok()
            && m.atmosphere.validate().is_ok()
            && m.vehicle.validate().is_ok()
            && m.rotation_rate_rad_s.is_finite();
        let c = &config.solver;
        let solver_ok = [
            config.limits.heat_flux_w_m2,
            config.limits.g_load,
            c.lambda,
            c.min_vertical_fraction,
            c.max_vertical_fraction,
            c.tolerance_m,
            c.predictor.final_speed_m_s,
        ]
        .iter()
        .all(|v| v.is_finite())
            && super::solver::settings_valid(&config.limits, c)
            && c.lambda >= P::ZERO
            && c.predictor.final_speed_m_s > P::ZERO
            && c.predictor.max_skips <= crate::vinh::predict::MAX_SKIPS;
        if table.independent() != Independent::NormalizedEnergy
            || config.every_n_ticks == 0
            || !target_ok
            || !model_ok
            || !solver_ok
        {
            return Err(GuidanceError::InvalidConfig);
        }
        let guidance = Guidance::new(guidance_config, table, kind, energy, initial)?;
        Ok(Self {
            guidance,
            energy,
            config,
            ticks: 0,
            last: None,
            counts: ReplanCounts::default(),
            flown_rad: P::ZERO,
            last_position: None,
            pending: None,
            warm: None,
            estimator: None,
            lift_schedule: None,
            start_energy: None,
            path_bound: None,
            path_bound_predicted: false,
            final_energy_j_kg: None,
            numerical_rotation: false,
            sensed: None,
            shape: None,
        })
    }

    /// Enable onboard aerodynamic estimation ([`crate::estimate`]): from now on every solve
    /// that *starts* predicts with [`PredictorModel`] scaled by the estimate at its start
    /// ([`AeroScales::apply`]); the estimate is fed by [`ReplanningGuidance::sense`]. Until
    /// the first accepted sample the scales are 1 and the predictions are those without
    /// estimation, bit for bit.
    #[must_use]
    pub fn with_estimator(mut self, estimator: AeroEstimator<P>) -> Self {
        self.estimator = Some(estimator);
        self
    }

    /// Fly the lift parameter of `schedule` against the speed, instead of the constant
    /// [`super::ReplanConfig::lambda`], in every numerical prediction
    /// ([`super::ReplanSolver::with_lift_schedule`]) and in the estimator's model
    /// ([`ReplanningGuidance::sense`]): for a stored angle-of-attack profile that changes along
    /// the flight. Closed-form predictions keep the constant.
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] if the schedule is not valid
    /// ([`LiftSchedule::is_valid`]).
    pub fn with_lift_schedule(mut self, schedule: LiftSchedule<P>) -> Result<Self, GuidanceError> {
        self.set_lift_schedule(schedule)?;
        Ok(self)
    }

    /// [`Self::with_lift_schedule`] in place (no copy of the guidance: used by
    /// [`crate::stack::FlightStack::new`], whose stack depth counts on the board).
    pub(crate) fn set_lift_schedule(
        &mut self,
        schedule: LiftSchedule<P>,
    ) -> Result<(), GuidanceError> {
        if !schedule.is_valid() {
            return Err(GuidanceError::InvalidConfig);
        }
        self.lift_schedule = Some(schedule);
        Ok(())
    }

    /// Start no solve while E-hat is above `max_normalized_energy` \[-\]: the stored profile
    /// flies the entry until then (for example through the first pull-out, whose heat-flux
    /// peak a constant-bank prediction from the entry state does not represent). Re-planning
    /// ticks keep their cadence; a solve in progress is finished.
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] for a non-finite value.
    pub fn with_start_energy(mut self, max_normalized_energy: S) -> Result<Self, GuidanceError> {
        self.set_start_energy(max_normalized_energy)?;
        Ok(self)
    }

    /// [`Self::with_start_energy`] in place.
    pub(crate) fn set_start_energy(
        &mut self,
        max_normalized_energy: S,
    ) -> Result<(), GuidanceError> {
        if !max_normalized_energy.is_finite() {
            return Err(GuidanceError::InvalidConfig);
        }
        self.start_energy = Some(max_normalized_energy);
        Ok(())
    }

    /// Bound every installed re-planned bank magnitude by the heat-flux and g-load limits at
    /// the state where it is installed: the vertical lift fraction is at least
    /// [`PathBound::min_vertical_fraction`] of the predictor model (scaled by the onboard
    /// estimate, with the lift parameter of the schedule at the current speed, else
    /// [`super::ReplanConfig::lambda`]), within the solver's `[min, max]` vertical fraction.
    /// The solver's own limit checks ([`ReplanningConfig::limits`]) are unchanged: set them
    /// loose to leave the limits to the bound. With `predicted`, numerical predictions fly the
    /// bound too ([`ReplanSolver::with_path_bound`]: at every predicted state the fraction is
    /// at least the bound's), so the range is solved for the bounded flight.
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] if the bound is not valid ([`PathBound::is_valid`]).
    pub fn with_path_bound(
        mut self,
        bound: PathBound<P>,
        predicted: bool,
    ) -> Result<Self, GuidanceError> {
        self.set_path_bound(bound, predicted)?;
        Ok(self)
    }

    /// [`Self::with_path_bound`] in place.
    pub(crate) fn set_path_bound(
        &mut self,
        bound: PathBound<P>,
        predicted: bool,
    ) -> Result<(), GuidanceError> {
        if !bound.is_valid() {
            return Err(GuidanceError::InvalidConfig);
        }
        self.path_bound = Some(bound);
        self.path_bound_predicted = predicted;
        Ok(())
    }

    /// End every numerical prediction at the specific energy `final_energy_j_kg` \[J/kg\]
    /// (`E = V^2/2 - mu/r` with the model planet's `mu`, [`PredictorModel::planet`]): the
    /// terminal interface the flight ends on, instead of the predictor's final speed
    /// ([`super::ReplanSolver::with_final_energy`]). Closed-form predictions keep the final
    /// speed of [`super::ReplanConfig::predictor`] (set it to the interface speed). The energy
    /// falls monotonically along a flight, the speed need not: the final speed alone makes a
    /// prediction end where a dive or a pull-up first takes the speed through it, or miss a
    /// dip below it between two integration steps.
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] for a non-finite energy.
    pub fn with_final_energy(mut self, final_energy_j_kg: P) -> Result<Self, GuidanceError> {
        self.set_final_energy(final_energy_j_kg)?;
        Ok(self)
    }

    /// [`Self::with_final_energy`] in place.
    pub(crate) fn set_final_energy(&mut self, final_energy_j_kg: P) -> Result<(), GuidanceError> {
        if !final_energy_j_kg.is_finite() {
            return Err(GuidanceError::InvalidConfig);
        }
        self.final_energy_j_kg = Some(final_energy_j_kg);
        Ok(())
    }

    /// The estimator and the rotation flag set in place ([`Self::with_estimator`],
    /// [`Self::with_numerical_rotation`]).
    pub(crate) fn set_estimator_and_rotation(
        &mut self,
        estimator: Option<AeroEstimator<P>>,
        numerical_rotation: bool,
    ) {
        if estimator.is_some() {
            self.estimator = estimator;
        }
        self.numerical_rotation = numerical_rotation;
    }

    /// This guidance with its numerical predictions modelling the planet's rotation at
    /// [`PredictorModel::rotation_rate_rad_s`] in their equations of motion (the latitude and
    /// heading of the re-plan's start held: [`ReplanSolver::with_rotation`]) on the model
    /// planet, instead of the effective planet of [`PredictorModel::effective_planet`] (which
    /// closed-form predictions keep). `false` (the default): unchanged behaviour.
    #[must_use]
    pub fn with_numerical_rotation(mut self, on: bool) -> Self {
        self.numerical_rotation = on;
        self
    }

    /// This guidance with its numerical predictions flying the stored profile's bank shape
    /// ([`BankShape`]: the table's magnitudes against E-hat now, shifted by one offset) instead
    /// of a constant bank, and each re-plan installing the solved offset on the stored
    /// magnitudes of the nodes below E-hat and of the node that starts the segment being flown
    /// (what is flown is then what was predicted). Closed-form predictions keep a constant
    /// bank: use it with [`super::PredictorMode::Numerical`].
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] for a table of more than [`super::SHAPE_CAPACITY`] nodes or
    /// an energy map that does not convert to the predictor scalar.
    pub fn with_bank_shape(mut self) -> Result<Self, GuidanceError> {
        self.set_bank_shape()?;
        Ok(self)
    }

    /// [`Self::with_bank_shape`] in place (no copy of the guidance: used by
    /// [`crate::stack::FlightStack`]).
    ///
    /// # Errors
    /// As [`Self::with_bank_shape`]; nothing changes then.
    pub(crate) fn set_bank_shape(&mut self) -> Result<(), GuidanceError> {
        let [c, r, i] = self.energy.parts();
        let energy = EnergyNormalizer::<P>::from_parts([c.to_f64(), r.to_f64(), i.to_f64()])?;
        let s = &self.config.solver;
        let nodes = self
            .guidance
            .table()
            .nodes()
            .iter()
            .map(|n| (to_p::<S, P>(n.x), to_p::<S, P>(n.sigma_rad)));
        self.shape = Some(BankShape::new(
            energy,
            nodes,
            s.min_vertical_fraction,
            s.max_vertical_fraction,
        )?);
        Ok(())
    }

    /// The bank magnitude \[rad\] `bank_rad` lowered to the [`PathBound`] at `nav` (the
    /// model scaled by the current estimate), and whether the bound lowered it. Unchanged without a
    /// bound or where the bound is not computable.
    fn bounded_bank(&self, bank_rad: P, nav: &NavState<P>) -> (P, bool) {
        match self.bound_max_bank(nav) {
            Some(max_bank) if bank_rad > max_bank => (max_bank, true),
            _ => (bank_rad, false),
        }
    }

    /// The largest bank magnitude \[rad\] the [`PathBound`] allows at `nav` (the model scaled
    /// by the current estimate; the barrier law when the bound has one), within the solver's
    /// vertical-fraction interval. `None` without a bound or where it is not computable.
    fn bound_max_bank(&self, nav: &NavState<P>) -> Option<P> {
        let b = self.path_bound.as_ref()?;
        let m = &self.config.model;
        let (atmosphere, vehicle) = self
            .estimator
            .as_ref()
            .and_then(|e| e.scales().apply(&m.atmosphere, &m.vehicle))
            .unwrap_or((m.atmosphere, m.vehicle));
        let f = if b.is_barrier() {
            let aero = match &self.lift_schedule {
                Some(s) => s.at(nav.speed_m_s),
                None => (self.config.solver.lambda, P::ONE),
            };
            // The accelerations sensed at this sample, when there are some.
            let sensed = self
                .sensed
                .filter(|(t, _)| to_p::<S, P>(*t) == nav.time_s)
                .map(|(_, a)| a);
            b.barrier_vertical_fraction(&m.planet, &atmosphere, &vehicle, aero, nav, sensed)?
        } else {
            let lambda = match &self.lift_schedule {
                Some(s) => s.lambda_at(nav.speed_m_s),
                None => self.config.solver.lambda,
            };
            b.min_vertical_fraction(&m.planet, &vehicle, lambda, nav)?
        };
        let c = &self.config.solver;
        let f = f.clamp(c.min_vertical_fraction, c.max_vertical_fraction);
        Some(f.clamp(P::ZERO, P::ONE).acos())
    }

    /// Feed the sensed aerodynamic accelerations at `nav` (the IMU's lift and drag
    /// accelerations at the navigation sample's time) to the estimator, against the model's
    /// expectation at `nav`'s radius and speed with the solver's `lambda`
    /// ([`crate::estimate::expected_aero`]). Call it before [`ReplanningGuidance::update`]
    /// with the same sample. With a barrier bound the sample is also kept for the bound's
    /// margins at that sample's update. Without an estimator the result is `Ok(None)`; without
    /// an estimator and a barrier it does nothing.
    ///
    /// # Errors
    /// [`EstimateError`] for a non-finite or negative sensed acceleration (the estimate is
    /// unchanged).
    pub fn sense(
        &mut self,
        nav: &NavState<S>,
        sensed: &SensedAero<P>,
    ) -> Result<Option<EstimateStatus>, EstimateError> {
        if !self.uses_sensed() {
            return Ok(None);
        }
        sensed.validate()?;
        self.sensed = Some((nav.time_s, *sensed));
        let Some(est) = self.estimator.as_mut() else {
            return Ok(None);
        };
        let m = &self.config.model;
        let (lambda, drag_scale) = match &self.lift_schedule {
            Some(s) => s.at(to_p(nav.speed_m_s)),
            None => (self.config.solver.lambda, P::ONE),
        };
        let Some(mut expected) = crate::estimate::expected_aero(
            &m.atmosphere,
            &m.vehicle,
            lambda,
            to_p(nav.radius_m),
            to_p(nav.speed_m_s),
        ) else {
            return Ok(Some(EstimateStatus::NoModel));
        };
        // The schedule's drag (a valid schedule's scale is finite and positive).
        expected.drag_m_s2 = expected.drag_m_s2 * drag_scale;
        est.update(sensed, &expected).map(Some)
    }

    /// Whether this guidance uses sensed accelerations ([`ReplanningGuidance::sense`]): with
    /// an estimator, or with a barrier bound ([`PathBound`], which measures its margins with
    /// them).
    #[must_use]
    pub fn uses_sensed(&self) -> bool {
        self.estimator.is_some() || self.path_bound.is_some_and(|b| b.is_barrier())
    }

    /// The current aerodynamic estimate (`None` without estimation).
    #[must_use]
    pub fn aero_scales(&self) -> Option<AeroScales<P>> {
        self.estimator.as_ref().map(AeroEstimator::scales)
    }

    /// Process one navigation sample (see the module docs): re-plan if this sample is a
    /// re-planning tick, then [`Guidance::update`].
    ///
    /// # Errors
    /// As [`Guidance::update`]; on error nothing changes (a table installed by a re-plan at
    /// this sample is withdrawn).
    pub fn update(&mut self, nav: &NavState<S>) -> Result<ReplanningOutput<S, P>, GuidanceError> {
        nav.validate()?;
        let navp: NavState<P> = nav_to_p(nav);
        // Odometer (committed only if the update succeeds).
        let step = match self.last_position {
            Some((lat, lon)) => {
                central_angle(lat, lon, navp.latitude_rad, navp.longitude_rad).unwrap_or(P::ZERO)
            }
            None => P::ZERO,
        };
        let flown = self.flown_rad + step;
        let will_tick = match self.guidance.last_tick_s() {
            None => true,
            Some(_) => nav.time_s >= self.guidance.next_tick_s(),
        };
        let n = u32::from(self.config.every_n_ticks.max(1));
        let mut report = None;
        let mut previous = None;
        let pending_before = self.pending;
        let warm_before = self.warm;
        let mut calls = 0_u8;
        let mut steps = 0_u32;
        let started = self.pending.is_some()
            || match self.start_energy {
                None => true,
                Some(e0) => self
                    .energy
                    .normalized(nav.radius_m, nav.speed_m_s)
                    .is_ok_and(|e| e <= e0),
            };
        if will_tick && started && (self.pending.is_some() || self.ticks.is_multiple_of(n)) {
            let e_hat = self.energy.normalized(nav.radius_m, nav.speed_m_s)?;
            let mut p = match self.pending {
                Some(p) => p,
                None => self.start_solve(&navp, flown),
            };
            let before = p.solver.predictor_calls();
            let steps_before = p.solver.integration_steps();
            let done = match self.config.steps_per_tick {
                0 => p.solver.run_shaped(u8::MAX, self.shape.as_ref()),
                k => p.solver.run_shaped(k, self.shape.as_ref()),
            };
            calls = p.solver.predictor_calls().saturating_sub(before);
            steps = p.solver.integration_steps().saturating_sub(steps_before);
            match done {
                Some(res) => {
                    self.pending = None;
                    // A solve converged at its guess measured no slope: keep the last one.
                    let slope = p.solver.range_slope().or(self.warm.map(|w| w.1));
                    self.warm = match (res.case, slope) {
                        (ReplanCase::Converged, Some(slope)) => {
                            Some((res.vertical_fraction, slope, p.solver.uses_numerical()))
                        }
                        _ => None,
                    };
                    let (r, old) = self.apply(&p, &res, e_hat, &navp);
                    report = Some(r);
                    previous = old;
                }
                None => self.pending = Some(p),
            }
        }
        // A barrier bound caps the bank at every tick (not only at re-plans).
        let cap_before = self.guidance.bank_cap();
        if will_tick && self.path_bound.is_some_and(|b| b.is_barrier()) {
            let cap = self.bound_max_bank(&navp).map(|c| S::from_f64(c.to_f64()));
            self.guidance.set_bank_cap(cap);
        }
        let out = match self.guidance.update(nav) {
            Ok(o) => o,
            Err(e) => {
                if let Some(t) = previous {
                    // Restore the table in use before this sample (it was valid).
                    let _ = self.guidance.replace_table(t);
                }
                self.guidance.set_bank_cap(cap_before);
                self.pending = pending_before;
                self.warm = warm_before;
                return Err(e);
            }
        };
        if let Some(r) = &report {
            self.counts.record(r);
            self.last = Some(*r);
        }
        if out.ticked {
            self.ticks = self.ticks.saturating_add(1);
        }
        self.flown_rad = flown;
        self.last_position = Some((navp.latitude_rad, navp.longitude_rad));
        Ok(ReplanningOutput {
            guidance: out,
            replan: report,
            predictor_calls: calls,
            integration_steps: steps,
        })
    }

    /// Set up a solve from `nav` (range to go, effective planet): a solver that has not run.
    fn start_solve(&self, nav: &NavState<P>, flown_rad: P) -> Pending<P> {
        let cfg = &self.config;
        let m = &cfg.model;
        let rtg = match cfg.target {
            RangeTarget::Point(p) => range_to_go_m(nav, &p, m.planet.radius_m),
            RangeTarget::FlownRangeAngle { total_rad } => {
                let r = (total_rad - flown_rad) * m.planet.radius_m;
                r.is_finite().then_some(r)
            }
        };
        let planet = m.effective_planet(nav, cfg.solver.predictor.final_speed_m_s);
        // The model scaled by the onboard estimate (unchanged at scales 1 or without one).
        let (atmosphere, vehicle) = self
            .estimator
            .as_ref()
            .and_then(|e| e.scales().apply(&m.atmosphere, &m.vehicle))
            .unwrap_or((m.atmosphere, m.vehicle));
        let solver = ReplanSolver::new(
            &planet,
            &atmosphere,
            &vehicle,
            nav,
            rtg.unwrap_or(P::ZERO),
            &cfg.limits,
            &cfg.solver,
        );
        let solver = match self.lift_schedule {
            Some(s) => solver.with_lift_schedule(s),
            None => solver,
        };
        let solver = match self.path_bound {
            Some(b) if self.path_bound_predicted => solver.with_path_bound(b),
            _ => solver,
        };
        let solver = if self.numerical_rotation {
            solver.with_rotation(&m.planet, m.rotation_rate_rad_s, nav)
        } else {
            solver
        };
        let solver = match self.final_energy_j_kg {
            Some(e) => solver.with_final_energy(m.planet.mu_m3_s2, e),
            None => solver,
        };
        // Spread solves start from the last converged one (a whole solve in its tick keeps
        // the cold start: module docs, "Bounded work per tick").
        let solver = match self.warm {
            Some((f, slope, numerical)) if cfg.steps_per_tick > 0 => {
                let s = solver.with_warm_start(f, slope);
                if numerical {
                    s.numerical_from_start()
                } else {
                    s
                }
            }
            _ => solver,
        };
        Pending {
            // A non-finite range to go (non-finite model radius or target sum): out of domain.
            solver: if rtg.is_some() {
                solver
            } else {
                solver.fallen_back(VinhError::NonFiniteInput)
            },
            start_tick: self.ticks,
            time_s: nav.time_s,
            range_to_go_m: rtg.unwrap_or(P::ZERO),
        }
    }

    /// Report a finished solve and, if applicable, install the re-planned table (nodes below
    /// the current `e_hat`). Returns the report and the replaced table (to restore on a later
    /// error).
    fn apply(
        &mut self,
        p: &Pending<P>,
        res: &ReplanResult<P>,
        e_hat: S,
        nav: &NavState<P>,
    ) -> (ReplanReport<P>, Option<NodeTable<S, N>>) {
        let cfg = &self.config;
        let rtg = p.range_to_go_m;
        let apply = match res.case {
            ReplanCase::Converged | ReplanCase::LimitsBind => true,
            ReplanCase::TargetOutOfReach => cfg.apply_out_of_reach,
            ReplanCase::FallBack(_) => false,
        };
        let mut report = ReplanReport {
            tick: self.ticks,
            start_tick: p.start_tick,
            time_s: p.time_s,
            normalized_energy: to_p(e_hat),
            range_to_go_m: rtg,
            case: res.case,
            predictor_calls: res.predictor_calls,
            bank_rad: if res.bank_rad.is_finite() {
                res.bank_rad
            } else {
                P::ZERO
            },
            predicted_range_m: res.prediction.map(|p| p.range_m),
            predicted_peak_heat_flux_w_m2: res.prediction.map(|p| p.peak_heat_flux_w_m2),
            predicted_peak_g_load: res.prediction.map(|p| p.peak_g_load),
            applied: false,
            nodes_replanned: 0,
            path_bound_active: false,
        };
        if !apply || !res.bank_rad.is_finite() {
            return (report, None);
        }
        let (bank_p, bound) = self.bounded_bank(res.bank_rad, nav);
        report.path_bound_active = bound;
        // The (bounded) solved magnitude in the guidance scalar.
        let bank = S::from_f64(bank_p.to_f64());
        let mut table = self.guidance.table().clone();
        let bounds = table.bounds();
        // With a shape: the solved offset on the stored magnitudes, on the nodes below E-hat
        // and the one that starts the segment being flown (E-hat decreases: no later tick
        // reaches the nodes above it).
        let shaped = self.shape.as_ref().map(|sh| {
            let e = to_p::<S, P>(e_hat);
            let offset = sh.offset_for(e, bank_p.cos());
            (sh, offset)
        });
        // Nodes below `edge` are the remaining ones ([`NODE_EDGE_E_HAT`]).
        let edge = e_hat + S::from_f64(NODE_EDGE_E_HAT);
        let upper = match shaped {
            Some(_) => table.nodes().iter().rposition(|n| n.x >= edge),
            None => None,
        };
        let mut count = 0_u16;
        let mut i = 0_usize;
        while i < table.len() {
            let Some(node) = table.nodes().get(i).copied() else {
                break;
            };
            if node.x < edge || Some(i) == upper {
                let magnitude = match shaped {
                    Some((sh, offset)) => match sh.nodes().nth(i) {
                        Some((_, stored)) => S::from_f64(sh.clamp(stored + offset).to_f64()),
                        None => bank,
                    },
                    None => bank,
                };
                let signed = if node.sigma_rad < S::ZERO {
                    -magnitude
                } else {
                    magnitude
                };
                if table.set_sigma(i, bounds.clamp_sigma(signed)).is_ok() {
                    count = count.saturating_add(1);
                }
            }
            i += 1;
        }
        if count == 0 {
            return (report, None);
        }
        let old = self.guidance.table().clone();
        if self.guidance.replace_table(table).is_ok() {
            report.applied = true;
            report.nodes_replanned = count;
            (report, Some(old))
        } else {
            (report, None)
        }
    }

    /// Impose the bank sign (lateral logic, [`crate::lateral`]) from the next tick on; the
    /// magnitude stays the corrector's (see [`Guidance::set_bank_sign`]).
    pub fn set_bank_sign(&mut self, sign: Option<BankSign>) {
        self.guidance.set_bank_sign(sign);
    }

    /// The wrapped guidance (command, attitude ramp, table in use, clock).
    #[must_use]
    pub fn guidance(&self) -> &Guidance<S, N> {
        &self.guidance
    }

    /// The re-planning settings.
    #[must_use]
    pub fn config(&self) -> &ReplanningConfig<P> {
        &self.config
    }

    /// The last re-plan report (`None` before the first).
    #[must_use]
    pub fn last_replan(&self) -> Option<ReplanReport<P>> {
        self.last
    }

    /// Outcome counts since start.
    #[must_use]
    pub fn counts(&self) -> ReplanCounts {
        self.counts
    }

    /// Range angle flown since the first accepted sample \[rad\] (onboard odometer).
    #[must_use]
    pub fn flown_range_angle_rad(&self) -> P {
        self.flown_rad
    }

    /// Guidance ticks taken so far.
    #[must_use]
    pub fn ticks(&self) -> u32 {
        self.ticks
    }

    /// Attitude at `time_s` \[s\] (see [`Guidance::attitude_at`]).
    #[must_use]
    pub fn attitude_at(&self, time_s: S) -> Command<S> {
        self.guidance.attitude_at(time_s)
    }

    /// Time of the next tick \[s\] (see [`Guidance::next_tick_s`]).
    #[must_use]
    pub fn next_tick_s(&self) -> S {
        self.guidance.next_tick_s()
    }
}
