//! [`ReplanSolver`]: the re-planning predictor-corrector as a resumable state machine, one
//! predictor call per [`ReplanSolver::step`], so a solve can be spread over several guidance
//! ticks with a bounded amount of work in each. [`super::replan`] runs it to completion.
//!
//! # Steps
//! 1. Range-only predictions ([`PeakMode::RangeOnly`]) at both ends `f_min`, `f_max` (in
//!    [`PredictorMode::Auto`], a chain failure at either end restarts with the glide).
//! 2. Target inside `[range(f_min), range(f_max)]`: Brent's method on `range(f) - target`
//!    ([`crate::vinh`]'s `Zeroin`: secant and inverse quadratic steps, bisection when they are
//!    slow), range-only, until the miss is within `tolerance_m`, the bracket is at the working
//!    precision of the scalar type, or [`ReplanConfig::max_iterations`] predictions.
//! 3. One prediction with peaks at the chosen fraction ([`PeakMode::Limits`]: it stops as soon
//!    as a phase is proven to exceed a limit).
//! 4. Only if that exceeds a limit: the [`LIMIT_GRID`] fractions, each with
//!    [`PeakMode::Limits`] (most infeasible ones stop at the first skip's deepest point).
//!
//! Every fraction evaluated or returned is clamped into `[f_min, f_max]` (no rounding can put
//! the output an ulp outside its bounds).
//!
//! # Warm start
//! [`ReplanSolver::with_warm_start`] (a guess `f0` and a range slope `s`) replaces step 1:
//! range-only predictions at `f0`, then at secant steps (the first `f0 - miss / s`, the next
//! ones from the last two points, lengthened by `WARM_STEP_GROWTH` = 1.5 so that a range
//! curving away is bracketed), at most `WARM_SECANT_STEPS` = 3 of them. A step within the
//! tolerance goes to step 3; two points on either side of the target go to Brent's method
//! between them (step 2); a step that does not reduce the miss, a step stuck at a bound or a
//! failed prediction goes to the cold start (step 1). The guess is always refined by one step,
//! also within the tolerance: a guess accepted as it is lets the miss drift to the tolerance
//! from one solve to the next. A hybrid solve's switch to the numerical predictor starts from
//! the same guess; [`ReplanSolver::numerical_from_start`] makes a hybrid solve numerical from
//! its first prediction (the re-planner's spread solves after one that went numerical). [`ReplanSolver::range_slope`] gives the slope the solve's last two
//! range-only predictions measured, for the next warm start.
//!
//! # Numerical predictions
//! In [`PredictorMode::Numerical`] (and [`PredictorMode::Hybrid`] /
//! [`PredictorMode::HybridSink`] once switched) a prediction is a [`NumericalRun`] held in the
//! solver and advanced by at most [`super::numerical::STEPS_PER_SOLVER_STEP`] integration
//! steps per [`ReplanSolver::step`]: a step either advances the prediction in progress (and returns
//! `None` with the phase unchanged) or completes it and acts on it as for a closed-form
//! prediction. [`ReplanSolver::predictor_calls`] counts completed predictions,
//! [`ReplanSolver::integration_steps`] the integration steps.
//!
//! # Hybrid
//! [`PredictorMode::Hybrid`] solves as [`PredictorMode::Auto`] ([`PredictorMode::AutoSink`]
//! for [`PredictorMode::HybridSink`]) and trusts the result only if the prediction it would fly,
//! the one with peaks at the chosen fraction, is
//! [`crate::vinh::validity::Validity::InDomain`]. Otherwise (that
//! prediction extrapolated, a closed form failing at a search point, or both closed forms
//! failing at an end) the whole solve restarts with the numerical predictor. The ends' own
//! validity does not decide: the bracketing predictions are far from the solution (at
//! `f_min = 0.05` the glide is nearly always extrapolated) and only their position relative to
//! the target is used.

use crate::nav::NavState;
use crate::scalar::Real;
use crate::vinh::VinhError;
use crate::vinh::nondim::{EntryState, ExpAtmosphere, Planet, VehicleParams};
use crate::vinh::num::{Zeroin, ZeroinStep};
use crate::vinh::predict::{PeakMode, PeakStatus, Prediction};

use super::numerical::{NumericalRun, STEPS_PER_SOLVER_STEP};
use super::{BankShape, LiftSchedule, PathBound};
use super::{
    LIMIT_GRID, MAX_ITERATIONS, MAX_PREDICTOR_CALLS, PredictorMode, ReplanCase, ReplanConfig,
    ReplanFallBack, ReplanLimits, ReplanResult,
};

mod eval;
mod switch;
mod warm;

/// Where the solver is.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
enum Phase<S> {
    /// Next: the range at the warm start's guess `f` ([`ReplanSolver::with_warm_start`]).
    Guess { f: S, slope: S },
    /// Next: the range at `f`, the `n`-th secant step from the last point `f0` (miss `m0`).
    Secant { f0: S, m0: S, f: S, n: u8 },
    /// Next: the range at `f_min`.
    EndLo,
    /// Next: the range at `f_max` (`range(f_min)` known).
    EndHi { range_lo: S },
    /// Brent's search on the fraction.
    Search {
        z: Zeroin<S>,
        best_f: S,
        best_miss: S,
        iterations: u8,
    },
    /// Next: the prediction with peaks at `f`.
    Final { f: S, case: ReplanCase },
    /// Limit grid: next index `i`, best feasible fraction so far.
    Grid {
        i: u8,
        best: Option<(S, Prediction<S>)>,
    },
    /// Finished.
    Done(ReplanResult<S>),
}

/// Resumable re-planning solve (see the module docs). Holds copies of its inputs (a few hundred
/// bytes), so it can live across guidance ticks.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ReplanSolver<S> {
    planet: Planet<S>,
    atmosphere: ExpAtmosphere<S>,
    vehicle: VehicleParams<S>,
    state: EntryState<S>,
    target_range_m: S,
    limits: ReplanLimits<S>,
    config: ReplanConfig<S>,
    glide: bool,
    /// The glide predicts the sink ([`PredictorMode::AutoSink`], until a non-monotone range
    /// turns it off for the rest of the solve).
    sink: bool,
    /// Predictions are numerical ([`PredictorMode::Numerical`], or a switched hybrid).
    numerical: bool,
    /// The numerical prediction in progress.
    run: Option<NumericalRun<S>>,
    /// Integration steps taken by numerical predictions.
    integration_steps: u32,
    /// The lift parameter of numerical predictions against speed (else `config.lambda`).
    lift_schedule: Option<LiftSchedule<S>>,
    /// The path bound numerical predictions fly ([`NumericalRun::with_path_bound`]).
    path_bound: Option<PathBound<S>>,
    /// The rotating planet of numerical predictions ([`ReplanSolver::with_rotation`]).
    rotation: Option<SolverRotation<S>>,
    /// The terminal energy of numerical predictions: the gravitational parameter it is
    /// measured with \[m^3/s^2\] and the energy \[J/kg\] ([`ReplanSolver::with_final_energy`]).
    final_energy: Option<(S, S)>,
    calls: u8,
    phase: Phase<S>,
    /// The last two range-only evaluations `(f, miss)`, newest first (the secant slope a
    /// later warm start uses: [`ReplanSolver::range_slope`]).
    evals: [Option<(S, S)>; 2],
    /// The warm start's guess and slope ([`ReplanSolver::with_warm_start`]): a hybrid
    /// solve's switch to the numerical predictor starts from it again.
    warm: Option<(S, S)>,
    /// Integration steps the numerical prediction in progress may take in this step
    /// ([`ReplanSolver::run`]).
    chunk: u16,
}

/// The rotating planet of numerical predictions: the planet without a rotation correction,
/// the rate \[rad/s\], latitude \[rad\] and heading \[rad, clockwise from north\] of the
/// start state.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
struct SolverRotation<S> {
    planet: Planet<S>,
    omega_rad_s: S,
    latitude_rad: S,
    heading_rad: S,
}

/// Whether the solver settings are in their domain (finite values checked separately):
/// `0 < f_min <= f_max <= 1`, a positive tolerance and positive limits, at most
/// [`MAX_ITERATIONS`] iterations.
pub(crate) fn settings_valid<S: Real>(limits: &ReplanLimits<S>, config: &ReplanConfig<S>) -> bool {
    config.min_vertical_fraction > S::ZERO
        && config.min_vertical_fraction <= config.max_vertical_fraction
        && config.max_vertical_fraction <= S::ONE
        && config.tolerance_m > S::ZERO
        && limits.heat_flux_w_m2 > S::ZERO
        && limits.g_load > S::ZERO
        && config.max_iterations <= MAX_ITERATIONS
}

/// Brent's search between the evaluations `(f, miss)` `a` and `b` (misses of opposite signs),
/// the better of the two as the best so far.
fn search<S: Real>(a: (S, S), b: (S, S)) -> Result<Phase<S>, VinhError> {
    let ((f_a, m_a), (f_b, m_b)) = if a.0 < b.0 { (a, b) } else { (b, a) };
    let (best_f, best_miss) = if m_b.abs() < m_a.abs() {
        (f_b, m_b)
    } else {
        (f_a, m_a)
    };
    Zeroin::new(f_a, m_a, f_b, m_b, S::ZERO).map(|z| Phase::Search {
        z,
        best_f,
        best_miss,
        iterations: 0,
    })
}

fn fall_back<S: Real>(reason: ReplanFallBack, calls: u8) -> ReplanResult<S> {
    ReplanResult {
        case: ReplanCase::FallBack(reason),
        vertical_fraction: S::ONE,
        bank_rad: S::ZERO,
        prediction: None,
        predictor_calls: calls,
    }
}

impl<S: Real> ReplanSolver<S> {
    /// Set up a solve for `target_range_m` \[m\] of surface range to go from `nav` (arguments as
    /// [`super::replan`]). Invalid input gives a solver that is already done with a
    /// [`ReplanCase::FallBack`].
    #[must_use]
    pub fn new(
        planet: &Planet<S>,
        atmosphere: &ExpAtmosphere<S>,
        vehicle: &VehicleParams<S>,
        nav: &NavState<S>,
        target_range_m: S,
        limits: &ReplanLimits<S>,
        config: &ReplanConfig<S>,
    ) -> Self {
        let mut s = Self {
            planet: *planet,
            atmosphere: *atmosphere,
            vehicle: *vehicle,
            state: EntryState {
                radius_m: nav.radius_m,
                speed_m_s: nav.speed_m_s,
                flight_path_angle_rad: nav.flight_path_angle_rad,
            },
            target_range_m,
            limits: *limits,
            config: *config,
            glide: config.mode == PredictorMode::Glide,
            sink: matches!(
                config.mode,
                PredictorMode::AutoSink | PredictorMode::HybridSink
            ),
            numerical: config.mode == PredictorMode::Numerical,
            run: None,
            integration_steps: 0,
            lift_schedule: None,
            path_bound: None,
            rotation: None,
            final_energy: None,
            calls: 0,
            phase: Phase::EndLo,
            evals: [None, None],
            chunk: STEPS_PER_SOLVER_STEP,
            warm: None,
        };
        let scalars = [
            target_range_m,
            limits.heat_flux_w_m2,
            limits.g_load,
            config.lambda,
            config.min_vertical_fraction,
            config.max_vertical_fraction,
            config.tolerance_m,
        ];
        if scalars.iter().any(|v| !v.is_finite()) || nav.validate().is_err() {
            s.phase = Phase::Done(fall_back(
                ReplanFallBack::OutOfDomain(VinhError::NonFiniteInput),
                0,
            ));
        } else if !settings_valid(limits, config) {
            s.phase = Phase::Done(fall_back(
                ReplanFallBack::OutOfDomain(VinhError::InvalidConfig),
                0,
            ));
        }
        s
    }

    /// This solver with its numerical predictions flying the lift parameter of `schedule`
    /// against the speed ([`NumericalRun::with_lift_schedule`]; closed-form predictions keep
    /// [`ReplanConfig::lambda`]). An invalid schedule is ignored.
    #[must_use]
    pub fn with_lift_schedule(mut self, schedule: LiftSchedule<S>) -> Self {
        if schedule.is_valid() {
            self.lift_schedule = Some(schedule);
        }
        self
    }

    /// This solver with its numerical predictions flying at least the vertical lift fraction
    /// of `bound` at every state ([`NumericalRun::with_path_bound`]; closed-form predictions
    /// keep the constant fraction). An invalid bound is ignored.
    #[must_use]
    pub fn with_path_bound(mut self, bound: PathBound<S>) -> Self {
        if bound.is_valid() {
            self.path_bound = Some(bound);
        }
        self
    }

    /// This solver with its numerical predictions on `planet` (give it the planet WITHOUT a
    /// rotation correction of `mu`) rotating at `omega_rad_s` \[rad/s\], the latitude and
    /// heading of `nav` held ([`NumericalRun::with_rotation`]); closed-form predictions keep
    /// the planet of [`ReplanSolver::new`]. A zero or non-finite rate, or a planet that is not
    /// valid, is ignored.
    #[must_use]
    pub fn with_rotation(mut self, planet: &Planet<S>, omega_rad_s: S, nav: &NavState<S>) -> Self {
        if omega_rad_s != S::ZERO && omega_rad_s.is_finite() && planet.validate().is_ok() {
            self.rotation = Some(SolverRotation {
                planet: *planet,
                omega_rad_s,
                latitude_rad: nav.latitude_rad,
                heading_rad: nav.heading_rad,
            });
        }
        self
    }

    /// This solver with its numerical predictions ending at the specific energy
    /// `final_energy_j_kg` \[J/kg\] (`V^2/2 - mu/r`, measured with `mu_m3_s2` \[m^3/s^2\]:
    /// the planet's own) instead of the final speed of [`ReplanConfig::predictor`]
    /// ([`NumericalRun::with_final_energy`]; closed-form predictions keep the final speed). A
    /// non-finite energy or a non-finite or non-positive `mu_m3_s2` is ignored.
    #[must_use]
    pub fn with_final_energy(mut self, mu_m3_s2: S, final_energy_j_kg: S) -> Self {
        if mu_m3_s2.is_finite() && mu_m3_s2 > S::ZERO && final_energy_j_kg.is_finite() {
            self.final_energy = Some((mu_m3_s2, final_energy_j_kg));
        }
        self
    }

    /// This solver, finished as a fall-back for `e` (out of domain) without a predictor call.
    #[must_use]
    pub(crate) fn fallen_back(mut self, e: VinhError) -> Self {
        self.phase = Phase::Done(fall_back(ReplanFallBack::OutOfDomain(e), 0));
        self
    }

    /// The result, once the solve is done.
    #[must_use]
    pub fn result(&self) -> Option<ReplanResult<S>> {
        match self.phase {
            Phase::Done(r) => Some(r),
            _ => None,
        }
    }

    /// Predictor calls made so far (at most [`MAX_PREDICTOR_CALLS`]; a numerical prediction
    /// counts once, when it completes).
    #[must_use]
    pub fn predictor_calls(&self) -> u8 {
        self.calls
    }

    /// Integration steps taken so far by numerical predictions (0 with the closed forms).
    #[must_use]
    pub fn integration_steps(&self) -> u32 {
        self.integration_steps
    }

    /// Whether the solve uses the numerical predictor ([`PredictorMode::Numerical`], or a
    /// [`PredictorMode::Hybrid`] / [`PredictorMode::HybridSink`] solve out of the closed forms'
    /// validated domain).
    #[must_use]
    pub fn uses_numerical(&self) -> bool {
        self.numerical
    }

    /// Advance by at most `max_steps` solver steps of work; the result if the solve is done.
    ///
    /// A solver step of work is one closed-form prediction or
    /// [`super::numerical::STEPS_PER_SOLVER_STEP`] integration steps of numerical predictions:
    /// the integration steps of one call are shared by as many numerical predictions as they
    /// complete (a short prediction near the end of the flight leaves the rest of the budget
    /// to the next one). `u8::MAX` runs the solve to completion.
    pub fn run(&mut self, max_steps: u8) -> Option<ReplanResult<S>> {
        self.run_shaped(max_steps, None)
    }

    /// [`ReplanSolver::run`] with numerical predictions flying `shape` from the vertical
    /// fraction they are asked for at the start ([`NumericalRun::with_bank_shape`];
    /// closed-form predictions keep a constant bank). Pass the same shape on every call of a
    /// solve (it is borrowed, not held: the solver stays small).
    pub fn run_shaped(
        &mut self,
        max_steps: u8,
        shape: Option<&BankShape<S>>,
    ) -> Option<ReplanResult<S>> {
        if max_steps == u8::MAX {
            loop {
                if let Some(r) = self.step_shaped(shape) {
                    return Some(r);
                }
            }
        }
        let per = u32::from(STEPS_PER_SOLVER_STEP);
        let budget = u32::from(max_steps) * per;
        let mut used = 0_u32;
        while used < budget {
            let (calls, steps) = (self.calls, self.integration_steps);
            // The integration steps left to this call (at most `budget`: fits in u16).
            self.chunk = u16::try_from(budget - used).unwrap_or(STEPS_PER_SOLVER_STEP);
            let done = self.step_shaped(shape);
            self.chunk = STEPS_PER_SOLVER_STEP;
            if let Some(r) = done {
                return Some(r);
            }
            let taken = self.integration_steps.saturating_sub(steps);
            // A closed-form call (no integration step) costs a whole solver step; every
            // step costs at least one unit, so the loop ends.
            used += if taken == 0 && self.calls != calls {
                per
            } else {
                taken.max(1)
            };
        }
        self.result()
    }

    fn clamp_f(&self, f: S) -> S {
        f.clamp(
            self.config.min_vertical_fraction,
            self.config.max_vertical_fraction,
        )
    }

    fn finish(&mut self, r: ReplanResult<S>) -> Option<ReplanResult<S>> {
        self.phase = Phase::Done(r);
        Some(r)
    }

    fn fail(&mut self, reason: ReplanFallBack) -> Option<ReplanResult<S>> {
        let r = fall_back(reason, self.calls);
        self.finish(r)
    }

    fn success(&mut self, case: ReplanCase, f: S, p: Prediction<S>) -> Option<ReplanResult<S>> {
        let f = self.clamp_f(f);
        let r = ReplanResult {
            case,
            vertical_fraction: f,
            bank_rad: f.clamp(-S::ONE, S::ONE).acos(),
            prediction: Some(p),
            predictor_calls: self.calls,
        };
        self.finish(r)
    }

    /// End of the search at the best fraction found.
    fn enter_final(&mut self, best_f: S, best_miss: S) {
        let case = if best_miss.abs() <= self.config.tolerance_m {
            ReplanCase::Converged
        } else {
            ReplanCase::TargetOutOfReach
        };
        self.phase = Phase::Final { f: best_f, case };
    }

    /// Make exactly one predictor call (or finish without one); the result when done.
    pub fn step(&mut self) -> Option<ReplanResult<S>> {
        self.step_shaped(None)
    }

    /// [`ReplanSolver::step`] with numerical predictions flying `shape` (as
    /// [`ReplanSolver::run_shaped`]).
    pub fn step_shaped(&mut self, shape: Option<&BankShape<S>>) -> Option<ReplanResult<S>> {
        let (f_lo, f_hi) = (
            self.config.min_vertical_fraction,
            self.config.max_vertical_fraction,
        );
        let target = self.target_range_m;
        // Transitions that need no predictor call are taken in this loop (bounded: each
        // pass either calls the predictor and returns, or moves to a later phase; the search
        // ends within MAX_BRENT_EVALS `next()` calls that each return an evaluation).
        let mut guard = 0_u8;
        loop {
            guard = guard.saturating_add(1);
            if guard > 8 || self.calls >= MAX_PREDICTOR_CALLS {
                return match self.phase {
                    Phase::Done(r) => Some(r),
                    _ => self.fail(ReplanFallBack::OutOfDomain(VinhError::NoConvergence)),
                };
            }
            match self.phase {
                Phase::Done(r) => return Some(r),
                Phase::Guess { f, slope } => return self.step_guess(f, slope, shape),
                Phase::Secant { f0, m0, f, n } => return self.step_secant(f0, m0, f, n, shape),
                Phase::EndLo => {
                    // None: a numerical prediction in progress (this step ends).
                    let r = self.eval(f_lo, PeakMode::RangeOnly, shape)?;
                    return match r {
                        Ok(p) => {
                            self.record(f_lo, p.range_m - target);
                            self.phase = Phase::EndHi {
                                range_lo: p.range_m,
                            };
                            None
                        }
                        Err(e) => self.end_failed(e),
                    };
                }
                Phase::EndHi { range_lo } => {
                    // None: a numerical prediction in progress (this step ends).
                    let r = self.eval(f_hi, PeakMode::RangeOnly, shape)?;
                    let range_hi = match r {
                        Ok(p) => p.range_m,
                        Err(e) => return self.end_failed(e),
                    };
                    self.record(f_hi, range_hi - target);
                    if range_hi < range_lo {
                        if self.glide && self.sink {
                            // PredictorMode::AutoSink: near the end the sink term (falling
                            // with f) outweighs the glide's range; redo without it (once).
                            self.sink = false;
                            self.phase = Phase::EndLo;
                            continue;
                        }
                        return self.fail(ReplanFallBack::NotMonotone);
                    }
                    self.phase = if target <= range_lo {
                        Phase::Final {
                            f: f_lo,
                            case: ReplanCase::TargetOutOfReach,
                        }
                    } else if target >= range_hi {
                        Phase::Final {
                            f: f_hi,
                            case: ReplanCase::TargetOutOfReach,
                        }
                    } else {
                        match search((f_lo, range_lo - target), (f_hi, range_hi - target)) {
                            Ok(p) => p,
                            Err(e) => return self.fail(ReplanFallBack::OutOfDomain(e)),
                        }
                    };
                    return None;
                }
                Phase::Search {
                    mut z,
                    mut best_f,
                    mut best_miss,
                    iterations,
                } => {
                    if iterations >= self.config.max_iterations {
                        self.enter_final(best_f, best_miss);
                        continue;
                    }
                    let f = match z.next() {
                        ZeroinStep::Done(_) => {
                            self.enter_final(best_f, best_miss);
                            continue;
                        }
                        ZeroinStep::Eval(f) => self.clamp_f(f),
                    };
                    // None: a numerical prediction in progress (this step ends).
                    let r = self.eval(f, PeakMode::RangeOnly, shape)?;
                    let miss = match r {
                        Ok(p) => p.range_m - target,
                        Err(_) if self.hybrid_closed_form() => return self.switch_to_numerical(),
                        Err(e) => return self.fail(ReplanFallBack::OutOfDomain(e)),
                    };
                    self.record(f, miss);
                    if miss.abs() < best_miss.abs() {
                        best_f = f;
                        best_miss = miss;
                    }
                    if miss.abs() <= self.config.tolerance_m {
                        self.phase = Phase::Final {
                            f,
                            case: ReplanCase::Converged,
                        };
                        return None;
                    }
                    z.supply(miss);
                    self.phase = Phase::Search {
                        z,
                        best_f,
                        best_miss,
                        iterations: iterations + 1,
                    };
                    return None;
                }
                Phase::Final { f, case } => {
                    let limits = self.limits;
                    // None: a numerical prediction in progress (this step ends).
                    let r = self.eval(f, PeakMode::Limits(limits), shape)?;
                    return match r {
                        Ok(p) if self.leaves_domain(&p) => self.switch_to_numerical(),
                        Ok(p) if p.peak_status == PeakStatus::Computed => self.success(case, f, p),
                        Ok(_) => {
                            self.phase = Phase::Grid { i: 0, best: None };
                            None
                        }
                        Err(_) if self.hybrid_closed_form() => self.switch_to_numerical(),
                        Err(e) => self.fail(ReplanFallBack::OutOfDomain(e)),
                    };
                }
                Phase::Grid { i, best } => {
                    if i >= LIMIT_GRID {
                        return match best {
                            Some((_, p)) if self.leaves_domain(&p) => self.switch_to_numerical(),
                            None if self.hybrid_closed_form() => self.switch_to_numerical(),
                            None => self.fail(ReplanFallBack::LimitsInfeasible),
                            Some((f, p)) => self.success(ReplanCase::LimitsBind, f, p),
                        };
                    }
                    let n = S::from_f64(f64::from(LIMIT_GRID - 1));
                    let fi = self.clamp_f(f_lo + (f_hi - f_lo) * S::from_f64(f64::from(i)) / n);
                    let limits = self.limits;
                    let mut best = best;
                    // None: a numerical prediction in progress (this step ends).
                    let r = self.eval(fi, PeakMode::Limits(limits), shape)?;
                    if let Ok(p) = r
                        && p.peak_status == PeakStatus::Computed
                    {
                        let miss = (p.range_m - target).abs();
                        if best.is_none_or(|(_, pb)| miss < (pb.range_m - target).abs()) {
                            best = Some((fi, p));
                        }
                    }
                    self.phase = Phase::Grid { i: i + 1, best };
                    if i + 1 >= LIMIT_GRID {
                        continue;
                    }
                    return None;
                }
            }
        }
    }
}
