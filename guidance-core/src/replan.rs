//! Onboard re-planning: analytic predictor-corrector on the vertical lift fraction.
//!
//! From the current navigation state ([`NavState`]), a target range to go and the vehicle
//! limits, [`replan`] finds the vertical lift fraction `f = cos(sigma)` (hence the bank magnitude
//! `|sigma| = acos(f)`) whose analytically predicted trajectory ([`crate::vinh::predict()`]: skips,
//! Kepler arcs, final glide, constant lift) meets the range target, while the predicted peak heat
//! flux and g-load stay within the limits.
//!
//! # Algorithm (bounded)
//! 1. Predict at both ends `f_min`, `f_max` of the allowed interval (more vertical lift flies
//!    farther). A predictor domain error at either end, or a range that does not increase with
//!    `f`, is [`ReplanCase::FallBack`]: keep the stored profile.
//! 2. Target outside `[range(f_min), range(f_max)]`: the nearest end is taken
//!    ([`ReplanCase::TargetOutOfReach`]). Otherwise bisection on `f` until the predicted range is
//!    within `tolerance_m` or [`ReplanConfig::max_iterations`] halvings (a domain error inside
//!    the bracket is also a fall-back).
//! 3. Limits: if the prediction at that `f` exceeds the heat-flux or g-load limit, a fixed grid
//!    of [`LIMIT_GRID`] fractions over `[f_min, f_max]` is predicted and the feasible one whose
//!    range is closest to the target is returned as [`ReplanCase::LimitsBind`] (the loads are not
//!    monotone in `f`: more lift can turn a captured glide into a skip with a higher peak). No
//!    feasible grid point: [`ReplanCase::FallBack`] with [`ReplanFallBack::LimitsInfeasible`].
//!
//! # Worst-case cost
//! `max_iterations + 2 + LIMIT_GRID` predictor calls (at most `40 + 2 + 16 = 58`); each
//! predictor call is
//! at most [`crate::vinh::predict::MAX_SKIPS`] skips and arcs plus one glide (see
//! [`crate::vinh::predict()`]).

use crate::nav::NavState;
use crate::scalar::Real;
use crate::vinh::VinhError;
use crate::vinh::nondim::{EntryState, ExpAtmosphere, LiftControl, Planet, VehicleParams};
use crate::vinh::predict::{Prediction, PredictorConfig, predict};

/// Largest accepted [`ReplanConfig::max_iterations`].
pub const MAX_ITERATIONS: u8 = 40;

/// Fractions scanned when a limit binds.
pub const LIMIT_GRID: u8 = 16;

/// Vehicle limits checked on the prediction.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ReplanLimits<S> {
    /// Peak Chapman heat flux limit \[W/m^2\].
    pub heat_flux_w_m2: S,
    /// Peak g-load limit \[-\].
    pub g_load: S,
}

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
    /// Bisection halvings per search (at most [`MAX_ITERATIONS`]).
    pub max_iterations: u8,
    /// Predictor settings (final glide speed, skip budget).
    pub predictor: PredictorConfig<S>,
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

struct Ctx<'a, S> {
    planet: &'a Planet<S>,
    atmosphere: &'a ExpAtmosphere<S>,
    vehicle: &'a VehicleParams<S>,
    state: EntryState<S>,
    config: &'a ReplanConfig<S>,
    calls: u8,
}

impl<S: Real> Ctx<'_, S> {
    fn eval(&mut self, f: S) -> Result<Prediction<S>, VinhError> {
        self.calls = self.calls.saturating_add(1);
        let lift = LiftControl {
            lambda: self.config.lambda,
            vertical_fraction: f,
        };
        predict(
            self.planet,
            self.atmosphere,
            self.vehicle,
            &lift,
            &self.state,
            &self.config.predictor,
        )
    }
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

fn load_ratio<S: Real>(p: &Prediction<S>, l: &ReplanLimits<S>) -> S {
    (p.peak_heat_flux_w_m2 / l.heat_flux_w_m2).max(p.peak_g_load / l.g_load)
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
    let bad = |e| fall_back(ReplanFallBack::OutOfDomain(e), 0);
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
        return bad(VinhError::NonFiniteInput);
    }
    if !(config.min_vertical_fraction > S::ZERO
        && config.min_vertical_fraction <= config.max_vertical_fraction
        && config.max_vertical_fraction <= S::ONE
        && config.tolerance_m > S::ZERO
        && limits.heat_flux_w_m2 > S::ZERO
        && limits.g_load > S::ZERO
        && config.max_iterations <= MAX_ITERATIONS)
    {
        return bad(VinhError::InvalidConfig);
    }
    let mut ctx = Ctx {
        planet,
        atmosphere,
        vehicle,
        state: EntryState {
            radius_m: nav.radius_m,
            speed_m_s: nav.speed_m_s,
            flight_path_angle_rad: nav.flight_path_angle_rad,
        },
        config,
        calls: 0,
    };
    let (f_lo, f_hi) = (config.min_vertical_fraction, config.max_vertical_fraction);
    let p_lo = match ctx.eval(f_lo) {
        Ok(p) => p,
        Err(e) => return fall_back(ReplanFallBack::OutOfDomain(e), ctx.calls),
    };
    let p_hi = match ctx.eval(f_hi) {
        Ok(p) => p,
        Err(e) => return fall_back(ReplanFallBack::OutOfDomain(e), ctx.calls),
    };
    if p_hi.range_m < p_lo.range_m {
        return fall_back(ReplanFallBack::NotMonotone, ctx.calls);
    }
    // Range search.
    let (mut f, mut p, mut case) = if target_range_m <= p_lo.range_m {
        (f_lo, p_lo, ReplanCase::TargetOutOfReach)
    } else if target_range_m >= p_hi.range_m {
        (f_hi, p_hi, ReplanCase::TargetOutOfReach)
    } else {
        let (mut a, mut b) = (f_lo, f_hi);
        let (mut best_f, mut best_p) = (f_lo, p_lo);
        let mut i = 0;
        while i < config.max_iterations {
            let mid = (a + b).half();
            let pm = match ctx.eval(mid) {
                Ok(p) => p,
                Err(e) => return fall_back(ReplanFallBack::OutOfDomain(e), ctx.calls),
            };
            best_f = mid;
            best_p = pm;
            let miss = pm.range_m - target_range_m;
            if miss.abs() <= config.tolerance_m {
                break;
            }
            if miss < S::ZERO {
                a = mid;
            } else {
                b = mid;
            }
            i += 1;
        }
        (best_f, best_p, ReplanCase::Converged)
    };
    if (p.range_m - target_range_m).abs() > config.tolerance_m && case == ReplanCase::Converged {
        case = ReplanCase::TargetOutOfReach;
    }
    // Limits: the loads need not be monotone in f (more lift can turn a captured glide into a
    // skip with a higher peak), so scan a fixed grid and keep the feasible fraction whose range
    // is closest to the target.
    if load_ratio(&p, limits) > S::ONE {
        let mut best: Option<(S, Prediction<S>)> = None;
        let n: S = S::from_f64(f64::from(LIMIT_GRID - 1));
        let mut i = 0_u8;
        while i < LIMIT_GRID {
            let fi = f_lo + (f_hi - f_lo) * S::from_f64(f64::from(i)) / n;
            i += 1;
            let Ok(pi) = ctx.eval(fi) else { continue };
            if load_ratio(&pi, limits) > S::ONE {
                continue;
            }
            let miss = (pi.range_m - target_range_m).abs();
            let better = match &best {
                None => true,
                Some((_, pb)) => miss < (pb.range_m - target_range_m).abs(),
            };
            if better {
                best = Some((fi, pi));
            }
        }
        match best {
            None => return fall_back(ReplanFallBack::LimitsInfeasible, ctx.calls),
            Some((fb, pb)) => {
                f = fb;
                p = pb;
                case = ReplanCase::LimitsBind;
            }
        }
    }
    ReplanResult {
        case,
        vertical_fraction: f,
        bank_rad: f.clamp(-S::ONE, S::ONE).acos(),
        prediction: Some(p),
        predictor_calls: ctx.calls,
    }
}
