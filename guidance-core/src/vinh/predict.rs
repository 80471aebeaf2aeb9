//! Analytic trajectory predictor: skip -> ballistic arc -> next skip ... -> final glide.
//!
//! From a planar state, a vehicle and a constant lift setting, [`predict`] chains the closed
//! forms of this module and returns the predicted range angle (and surface range), the peak
//! Chapman heat flux and the peak g-load:
//!
//! 1. The radius of the initial state is the *interface radius* of the whole prediction: every
//!    skip starts and ends there and every ballistic arc leaves and re-enters there.
//! 2. Descending state: a second-order skip ([`SkipSolution`]). If it exits, a Kepler arc
//!    ([`BallisticArc`]) carries the vehicle to re-entry at the interface radius, with the exit
//!    speed and the mirrored flight-path angle, and the next phase starts there. If the skip does
//!    not return to the interface radius ([`VinhError::NoAtmosphericExit`]: captured), or exits
//!    too shallow for a resolvable arc, the final glide follows.
//! 3. Ascending state (e.g. in the upper part of a skip): the remainder is treated as a Kepler
//!    arc to the descending crossing of the same radius.
//! 4. Final glide: the glide method imposes its entry speed for a given altitude
//!    (eq. 3.78), so the glide is started at the reference radius `r_g` below the interface
//!    where the imposed speed equals the current speed (bracketed root, bounded), and runs to
//!    [`PredictorConfig::final_speed_m_s`]. The descent from the interface to `r_g` is not
//!    modelled: its range angle is taken as zero and its heating is not included (a documented
//!    approximation; the glide peaks normally dominate).
//!
//! The number of phases is bounded by [`PredictorConfig::max_skips`] (at most [`MAX_SKIPS`]);
//! a chain that is still skipping after it returns [`VinhError::PhaseLimit`].
//!
//! # Domain of validity
//! The union of the domains of the phases (see [`super::skip`], [`super::ballistic`],
//! [`super::glide`]); any phase's domain error is returned unchanged, so the caller can fall
//! back to a stored profile.

use super::ballistic::BallisticArc;
use super::error::VinhError;
use super::glide::GlideSolution;
use super::nondim::{EntryState, ExpAtmosphere, LiftControl, NonDim, Planet, VehicleParams};
use super::num::{brent, finite, k};
use super::skip::SkipSolution;
use super::validity::{
    Extrapolation, GLIDE_ALTITUDE_RANGE_M, GLIDE_MAX_FLIGHT_PATH_ANGLE_OFFSET_RAD,
    GLIDE_MAX_START_ABOVE_STATE_M, GLIDE_MAX_START_OFFSET_M, GLIDE_MAX_START_OFFSET_PER_LD_M,
    GLIDE_MAX_TRANSIENT_FRACTION, GLIDE_MIN_FINAL_SPEED_RATIO, GLIDE_MIN_SUBCIRCULAR_MARGIN,
    GLIDE_VERTICAL_LD_RANGE, SKIP_FPA_RANGE_RAD, SKIP_MAX_EXIT_ETA_V, SKIP_MIN_VERTICAL_LD,
    SKIP_SPEED_RANGE_M_S, Validity,
};
use crate::scalar::Real;

/// Largest accepted [`PredictorConfig::max_skips`].
pub const MAX_SKIPS: u8 = 8;

/// Predictor settings.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PredictorConfig<S> {
    /// Speed at which the final glide ends \[m/s\] (must be below the glide start speed).
    pub final_speed_m_s: S,
    /// Maximum number of skips before the final glide (at most [`MAX_SKIPS`]).
    pub max_skips: u8,
}

/// Peak heat-flux and g-load limits (re-planner and [`PeakMode::Limits`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LoadLimits<S> {
    /// Peak Chapman heat flux limit \[W/m^2\].
    pub heat_flux_w_m2: S,
    /// Peak g-load limit \[-\].
    pub g_load: S,
}

impl<S: Real> LoadLimits<S> {
    /// Whether a heat flux \[W/m^2\] or g-load \[-\] exceeds a limit.
    fn exceeded(&self, heat_flux_w_m2: S, g_load: S) -> bool {
        heat_flux_w_m2 > self.heat_flux_w_m2 || g_load > self.g_load
    }
}

/// Which peak loads a prediction computes (the range is always computed, except after a
/// [`PeakStatus::LimitExceeded`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum PeakMode<S> {
    /// Range only: no peak search (the corrector's predictions).
    RangeOnly,
    /// Peak heat flux and g-load of every phase.
    Full,
    /// As [`PeakMode::Full`], but stop at the first phase whose loads are proven to exceed a
    /// limit: first from a point the phase computes anyway (the skip's deepest point, the
    /// glide's ends; a peak is at least as large), then from its peaks.
    Limits(LoadLimits<S>),
}

/// What the peak fields of a [`Prediction`] hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum PeakStatus {
    /// Not computed ([`PeakMode::RangeOnly`]): the peak fields are 0.
    NotComputed,
    /// The peaks over all modelled phases.
    Computed,
    /// [`PeakMode::Limits`]: a phase exceeded a limit and the prediction stopped there; the
    /// peak fields hold the loads that exceeded, the range fields only the phases before.
    LimitExceeded,
}

/// How the predicted trajectory ended.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Prediction<S> {
    /// Total predicted range angle \[rad\].
    pub range_angle_rad: S,
    /// Total predicted surface range `R theta` \[m\].
    pub range_m: S,
    /// Peak Chapman heat flux over all modelled phases \[W/m^2\].
    pub peak_heat_flux_w_m2: S,
    /// Peak g-load over all modelled phases \[-\].
    pub peak_g_load: S,
    /// Number of skips that exited the atmosphere.
    pub skips: u8,
    /// Number of ballistic arcs flown.
    pub arcs: u8,
    /// Reference radius where the final glide starts \[m\].
    pub glide_start_radius_m: S,
    /// Range angle of the final glide \[rad\].
    pub glide_range_angle_rad: S,
    /// What the peak fields hold.
    pub peak_status: PeakStatus,
    /// Whether every phase lies in the validated region ([`super::validity`]).
    pub validity: Validity,
}

/// Predict range and peak loads from `state` with constant lift `lift`
/// ([`predict_with`] and [`PeakMode::Full`]).
///
/// # Errors
/// As [`predict_with`].
pub fn predict<S: Real>(
    planet: &Planet<S>,
    atmosphere: &ExpAtmosphere<S>,
    vehicle: &VehicleParams<S>,
    lift: &LiftControl<S>,
    state: &EntryState<S>,
    config: &PredictorConfig<S>,
) -> Result<Prediction<S>, VinhError> {
    predict_with(
        planet,
        atmosphere,
        vehicle,
        lift,
        state,
        config,
        PeakMode::Full,
    )
}

/// Predict the range and, as `peaks` asks, the peak loads from `state` with constant lift
/// `lift`.
///
/// Cost: at most `max_skips` skips and arcs, plus one glide and one Brent search for the glide
/// start radius; [`PeakMode::RangeOnly`] skips every peak search.
///
/// # Errors
/// Input validation errors, [`VinhError::PhaseLimit`], and any domain error of a phase
/// (e.g. [`VinhError::EscapeTrajectory`], [`VinhError::GlideNearCircular`],
/// [`VinhError::GlideSpeedOutOfDomain`], [`VinhError::NoDeepestPoint`]).
pub fn predict_with<S: Real>(
    planet: &Planet<S>,
    atmosphere: &ExpAtmosphere<S>,
    vehicle: &VehicleParams<S>,
    lift: &LiftControl<S>,
    state: &EntryState<S>,
    config: &PredictorConfig<S>,
    peaks: PeakMode<S>,
) -> Result<Prediction<S>, VinhError> {
    if !config.final_speed_m_s.is_finite() {
        return Err(VinhError::NonFiniteInput);
    }
    if config.max_skips > MAX_SKIPS || !(config.final_speed_m_s > S::ZERO) {
        return Err(VinhError::InvalidConfig);
    }
    // Validates every input.
    NonDim::new(planet, atmosphere, vehicle, lift, state)?;
    let mut cur = *state;
    let mut theta = S::ZERO;
    let mut q_max = S::ZERO;
    let mut n_max = S::ZERO;
    let mut skips = 0_u8;
    let mut arcs = 0_u8;
    let r_i = state.radius_m;
    let mut phase = 0_u8;
    let mut validity = Validity::InDomain;
    // Each pass is a skip (descending) or an arc (ascending); at most 2 max_skips + 1 passes.
    let max_phases = config.max_skips.saturating_mul(2).saturating_add(1);
    loop {
        if phase > max_phases {
            return Err(VinhError::PhaseLimit);
        }
        phase += 1;
        if cur.flight_path_angle_rad > S::ZERO {
            let arc = match BallisticArc::new(planet, &cur, r_i) {
                Ok(a) => a,
                // Exit too shallow to resolve an arc: the vehicle stays at the interface
                // radius, treated as captured.
                Err(VinhError::NotAscending) if arcs < skips => break,
                Err(e) => return Err(e),
            };
            theta = theta + arc.range_angle_rad();
            let re = arc.reentry();
            cur = EntryState {
                radius_m: r_i,
                speed_m_s: re.speed_m_s,
                flight_path_angle_rad: re.flight_path_angle_rad,
            };
            arcs += 1;
            continue;
        }
        if skips >= config.max_skips {
            // Budget used up: only a captured trajectory may go on to the glide.
            let nd = NonDim::new(planet, atmosphere, vehicle, lift, &cur)?;
            match SkipSolution::new(&nd) {
                Err(VinhError::NoAtmosphericExit) => break,
                Err(e) => return Err(e),
                Ok(_) => return Err(VinhError::PhaseLimit),
            }
        }
        let nd = NonDim::new(planet, atmosphere, vehicle, lift, &cur)?;
        match SkipSolution::new(&nd) {
            Ok(skip) => {
                let ex = skip.exit();
                validity = skip_validity_and(validity, &cur, &skip);
                if let PeakMode::Limits(l) = peaks {
                    let b = skip.deepest_point()?;
                    if l.exceeded(b.heat_flux_w_m2, b.g_load) {
                        return Ok(exceeded(theta, planet, b.heat_flux_w_m2, b.g_load));
                    }
                }
                if peaks != PeakMode::RangeOnly {
                    let (q, g) = skip.peaks()?;
                    q_max = q_max.max(q.heat_flux_w_m2);
                    n_max = n_max.max(g.g_load);
                    if let PeakMode::Limits(l) = peaks
                        && l.exceeded(q_max, n_max)
                    {
                        return Ok(exceeded(theta, planet, q_max, n_max));
                    }
                }
                theta = theta + ex.range_angle_rad;
                cur = EntryState {
                    radius_m: r_i,
                    speed_m_s: ex.speed_m_s,
                    flight_path_angle_rad: ex.flight_path_angle_rad,
                };
                skips += 1;
                if !(cur.flight_path_angle_rad > S::ZERO) {
                    // Exit at zero flight-path angle: captured.
                    break;
                }
            }
            Err(VinhError::NoAtmosphericExit) => break,
            Err(e) => return Err(e),
        }
    }
    // Final glide from the captured state. The capture itself (the descent from the interface
    // to the glide start radius) is not modelled: the chain error map (docs/validation/vinh-numerical.md) measured
    // range errors of -62 to +1117 % for chains captured after a skip or an arc, which are never
    // in domain. Captured in the first skip from a descending state, the chain is the glide
    // started from the state (as the glide mode): checked as one (re-planning domain).
    let first_capture = skips == 0 && arcs == 0;
    validity = validity.and(!first_capture, Extrapolation::CaptureTransition);
    let r_g = glide_start_radius(planet, atmosphere, vehicle, lift, cur.speed_m_s, r_i)?;
    let glide = GlideSolution::new(planet, atmosphere, vehicle, lift, r_g)?;
    let end = glide.point_at_speed(config.final_speed_m_s)?;
    validity = glide_validity(validity, &glide, planet, r_g, config.final_speed_m_s);
    if first_capture {
        validity = glide_start_validity(
            validity,
            &glide,
            planet,
            atmosphere,
            state,
            lift,
            end.range_angle_rad,
            false,
        );
    }
    if let PeakMode::Limits(l) = peaks {
        let start = glide.point_at_u(glide.u_entry())?;
        let (qb, nb) = (
            start.heat_flux_w_m2.max(end.heat_flux_w_m2),
            start.g_load.max(end.g_load),
        );
        if l.exceeded(qb, nb) {
            return Ok(exceeded(theta, planet, qb, nb));
        }
    }
    if peaks != PeakMode::RangeOnly {
        let q = glide.peak_heat_flux(config.final_speed_m_s)?;
        let g = glide.peak_g_load(config.final_speed_m_s)?;
        q_max = q_max.max(q.heat_flux_w_m2);
        n_max = n_max.max(g.g_load);
        if let PeakMode::Limits(l) = peaks
            && l.exceeded(q_max, n_max)
        {
            return Ok(exceeded(theta, planet, q_max, n_max));
        }
    }
    theta = theta + end.range_angle_rad;
    Ok(Prediction {
        range_angle_rad: finite(theta)?,
        range_m: finite(theta * planet.radius_m)?,
        peak_heat_flux_w_m2: finite(q_max)?,
        peak_g_load: finite(n_max)?,
        skips,
        arcs,
        glide_start_radius_m: r_g,
        glide_range_angle_rad: end.range_angle_rad,
        peak_status: if peaks == PeakMode::RangeOnly {
            PeakStatus::NotComputed
        } else {
            PeakStatus::Computed
        },
        validity,
    })
}

/// `v` updated with a skip of `skip` from `entry` (see [`skip_validity`]).
fn skip_validity_and<S: Real>(
    v: Validity,
    entry: &EntryState<S>,
    skip: &SkipSolution<S>,
) -> Validity {
    match skip_validity(entry, skip) {
        Validity::Extrapolated(reason) => v.and(true, reason),
        _ => v,
    }
}

/// Validity of one skip `skip` from `entry`: `InDomain` inside the region validated against
/// integration (docs/validation/vinh-numerical.md: the validation grid and the skip error map), else the first
/// reason: entry speed outside [`SKIP_SPEED_RANGE_M_S`], entry flight-path angle outside
/// [`SKIP_FPA_RANGE_RAD`], vertical L/D below [`SKIP_MIN_VERTICAL_LD`], exit `|eta v|` above
/// [`SKIP_MAX_EXIT_ETA_V`].
pub fn skip_validity<S: Real>(entry: &EntryState<S>, skip: &SkipSolution<S>) -> Validity {
    let inside = |x: S, (lo, hi): (f64, f64)| x >= k(lo) && x <= k(hi);
    Validity::InDomain
        .and(
            !inside(entry.speed_m_s, SKIP_SPEED_RANGE_M_S),
            Extrapolation::SkipEntrySpeed,
        )
        .and(
            !inside(entry.flight_path_angle_rad.abs(), SKIP_FPA_RANGE_RAD),
            Extrapolation::SkipFlightPathAngle,
        )
        .and(
            !(skip.nondim().constants().e_vertical >= k(SKIP_MIN_VERTICAL_LD)),
            Extrapolation::SkipVerticalLiftToDrag,
        )
        .and(
            !(skip.exit().eta_v.abs() <= k(SKIP_MAX_EXIT_ETA_V)),
            Extrapolation::SkipSpeedExpansion,
        )
}

/// `v` updated with a glide started at `r_g` \[m\] and run to `final_speed_m_s` \[m/s\].
pub(crate) fn glide_validity<S: Real>(
    v: Validity,
    glide: &GlideSolution<S>,
    planet: &Planet<S>,
    r_g: S,
    final_speed_m_s: S,
) -> Validity {
    let inside = |x: S, (lo, hi): (f64, f64)| x >= k(lo) && x <= k(hi);
    let e = glide.nondim().constants().e_vertical;
    let start = glide.imposed_entry();
    let ratio = final_speed_m_s / start.speed_m_s;
    v.and(
        !inside(r_g - planet.radius_m, GLIDE_ALTITUDE_RANGE_M),
        Extrapolation::GlideAltitude,
    )
    .and(
        !inside(e, GLIDE_VERTICAL_LD_RANGE),
        Extrapolation::GlideVerticalLiftToDrag,
    )
    .and(
        !(ratio >= k(GLIDE_MIN_FINAL_SPEED_RATIO)),
        Extrapolation::GlideFinalSpeedRatio,
    )
    .and(
        !(S::ONE - start.speed_m_s * start.speed_m_s * start.radius_m / planet.mu_m3_s2
            >= k(GLIDE_MIN_SUBCIRCULAR_MARGIN)),
        Extrapolation::GlideCircularMargin,
    )
}

/// `v` updated with the checks of a glide started at `glide`'s radius `r_g` from `state` (the
/// glide mode, [`crate::replan::predict_glide_with`], or a chain captured in its first skip):
/// the distance from the state to `r_g` ([`GLIDE_MAX_START_OFFSET_PER_LD_M`] per unit of total
/// L/D, or [`GLIDE_MAX_START_OFFSET_M`] with the sink modelled), the state at most
/// [`GLIDE_MAX_START_ABOVE_STATE_M`] below `r_g`, its flight-path angle within
/// [`GLIDE_MAX_FLIGHT_PATH_ANGLE_OFFSET_RAD`] of the glide's imposed one, and the estimated
/// start transient within [`GLIDE_MAX_TRANSIENT_FRACTION`] of the glide's range angle
/// `glide_range_angle_rad` \[rad\] (see [`glide_transient_rad`]).
#[allow(clippy::too_many_arguments)]
pub(crate) fn glide_start_validity<S: Real>(
    v: Validity,
    glide: &GlideSolution<S>,
    planet: &Planet<S>,
    atmosphere: &ExpAtmosphere<S>,
    state: &EntryState<S>,
    lift: &LiftControl<S>,
    glide_range_angle_rad: S,
    sink: bool,
) -> Validity {
    let start = glide.imposed_entry();
    let r_g = start.radius_m;
    let offset = if sink {
        !((r_g - state.radius_m).abs() <= k(GLIDE_MAX_START_OFFSET_M))
    } else {
        // Total L/D = vertical L/D / vertical fraction (> 0 for a glide).
        !((r_g - state.radius_m).abs() * lift.vertical_fraction
            <= k::<S>(GLIDE_MAX_START_OFFSET_PER_LD_M) * glide.nondim().constants().e_vertical)
    };
    v.and(offset, Extrapolation::GlideStartOffset)
        .and(
            !(r_g - state.radius_m <= k(GLIDE_MAX_START_ABOVE_STATE_M)),
            Extrapolation::GlideBelowEquilibrium,
        )
        .and(
            !((state.flight_path_angle_rad - start.flight_path_angle_rad).abs()
                <= k(GLIDE_MAX_FLIGHT_PATH_ANGLE_OFFSET_RAD)),
            Extrapolation::GlideFlightPathAngle,
        )
        .and(
            !(glide_transient_rad(planet, atmosphere, state, &start).is_some_and(|t| {
                t <= k::<S>(GLIDE_MAX_TRANSIENT_FRACTION) * glide_range_angle_rad
            })),
            Extrapolation::GlideTransient,
        )
}

/// Estimated range angle \[rad\] of the start transient of a glide whose imposed start is
/// `start` flown from `state` (see [`GLIDE_MAX_TRANSIENT_FRACTION`]): `(V/r) (1 - exp(-A/H)) / w`
/// with `w = sqrt(a / H)`, `a = mu/r^2 - V^2/r`, `A = sqrt(dh^2 + (V dgamma / w)^2)`. `None`
/// when it cannot be estimated (`a <= 0`: at or above circular speed; non-finite values).
fn glide_transient_rad<S: Real>(
    planet: &Planet<S>,
    atmosphere: &ExpAtmosphere<S>,
    state: &EntryState<S>,
    start: &EntryState<S>,
) -> Option<S> {
    let r = state.radius_m;
    let v = state.speed_m_s;
    let h_s = atmosphere.scale_height_m;
    let a = planet.mu_m3_s2 / (r * r) - v * v / r;
    if !(a > S::ZERO && h_s > S::ZERO && r > S::ZERO) {
        return None;
    }
    let w = (a / h_s).sqrt_raw();
    let dh = r - start.radius_m;
    let dz = v * (state.flight_path_angle_rad - start.flight_path_angle_rad) / w;
    let amplitude = (dh * dh + dz * dz).sqrt_raw();
    let t = v / r * (S::ONE - (-amplitude / h_s).exp()) / w;
    t.is_finite().then_some(t)
}

/// A prediction stopped by [`PeakMode::Limits`] (range so far; the loads that exceeded).
fn exceeded<S: Real>(theta: S, planet: &Planet<S>, q: S, n: S) -> Prediction<S> {
    Prediction {
        range_angle_rad: theta,
        range_m: theta * planet.radius_m,
        peak_heat_flux_w_m2: q,
        peak_g_load: n,
        skips: 0,
        arcs: 0,
        glide_start_radius_m: S::ZERO,
        glide_range_angle_rad: S::ZERO,
        peak_status: PeakStatus::LimitExceeded,
        validity: Validity::InDomain,
    }
}

/// Imposed glide entry speed (eq. 3.78) at reference radius `r` \[m/s\].
fn imposed_speed<S: Real>(
    planet: &Planet<S>,
    atmosphere: &ExpAtmosphere<S>,
    vehicle: &VehicleParams<S>,
    lift: &LiftControl<S>,
    r: S,
) -> Result<S, VinhError> {
    let rho = atmosphere.density_kg_m3(r)?;
    let cl_star = vehicle.cl_max_ld()?;
    let k1 = rho * vehicle.reference_area_m2 * r / (k::<S>(2.0) * vehicle.mass_kg)
        * cl_star
        * lift.lambda
        * lift.vertical_fraction;
    finite((planet.mu_m3_s2 / r / (S::ONE + k1)).sqrt_raw())
}

/// Reference radius in `(R, r_max]` where the imposed glide speed equals `speed_m_s`.
///
/// # Errors
/// [`VinhError::GlideNoLift`] without upward lift, [`VinhError::GlideNearCircular`] if the
/// speed is above the imposed speed at `r_max`, [`VinhError::GlideSpeedOutOfDomain`] if it is
/// below the imposed speed 1 m above the surface.
pub fn glide_start_radius<S: Real>(
    planet: &Planet<S>,
    atmosphere: &ExpAtmosphere<S>,
    vehicle: &VehicleParams<S>,
    lift: &LiftControl<S>,
    speed_m_s: S,
    r_max: S,
) -> Result<S, VinhError> {
    lift.validate()?;
    if !(lift.lambda * lift.vertical_fraction > S::ZERO) {
        return Err(VinhError::GlideNoLift);
    }
    if !(speed_m_s.is_finite() && r_max.is_finite()) {
        return Err(VinhError::NonFiniteInput);
    }
    let lo = planet.radius_m + S::ONE;
    if !(r_max > lo) {
        return Err(VinhError::UnphysicalState);
    }
    let f = |r: S| -> Result<S, VinhError> {
        Ok(imposed_speed(planet, atmosphere, vehicle, lift, r)? - speed_m_s)
    };
    let f_hi = f(r_max)?;
    let f_lo = f(lo)?;
    if f_hi < S::ZERO {
        return Err(VinhError::GlideNearCircular);
    }
    if f_lo > S::ZERO {
        return Err(VinhError::GlideSpeedOutOfDomain);
    }
    brent(f, lo, r_max, f_lo, f_hi, S::ZERO)
}

/// The validity of a predictor result: its [`Prediction::validity`], or out of domain with
/// the error.
#[must_use]
pub fn validity_of<S>(result: &Result<Prediction<S>, VinhError>) -> Validity {
    match result {
        Ok(p) => p.validity,
        Err(e) => Validity::OutOfDomain(*e),
    }
}
