//! How far a prediction can be trusted: [`Validity`] of every prediction (`super::Prediction`).
//!
//! The closed forms return a typed [`VinhError`] outside their mathematical domain (out of
//! domain). Inside it, a prediction is [`Validity::InDomain`] only inside the region checked
//! against numerical integration of the same equations, and otherwise computed but
//! *extrapolated* (the first reason, [`Extrapolation`]).
//!
//! **Guarantee**: every range prediction called `InDomain` (the chain [`super::predict_with`],
//! the glide mode `replan::predict_glide_with` and its sink variant, hence every closed-form
//! re-plan the hybrid re-planner applies) is within 3 % of an integration of the predictor's
//! own model (planar, non-rotating, inverse-square gravity, the exponential atmosphere, the
//! parabolic polar at constant lift) from the same state to the same final speed. Checked by a
//! seeded random oracle over the whole accepted domain (`tests/it/vinh_oracle.rs`: uniform
//! draws of vehicle, lift, glide start, state offset and final speed, RK4 of the model;
//! docs/validation/vinh-numerical.md, "Random oracle of the domain"). A chain that skips or
//! flies an arc is always [`Extrapolation::CaptureTransition`], so only glides (glide mode, or a
//! chain captured in its first skip) end in an `InDomain` range prediction; [`super::skip_validity`]
//! of a single skip carries the skip error map's accuracy (exit speed <= 0.8 %, range angle
//! <= 11.2 %), not the range guarantee.
//!
//! The glide checks: start altitude [`GLIDE_ALTITUDE_RANGE_M`], vertical L/D
//! [`GLIDE_VERTICAL_LD_RANGE`], final speed ratio [`GLIDE_MIN_FINAL_SPEED_RATIO`], distance
//! from circular speed [`GLIDE_MIN_SUBCIRCULAR_MARGIN`]; for a glide
//! started from the state, its distance from the glide start radius
//! ([`GLIDE_MAX_START_OFFSET_PER_LD_M`], [`GLIDE_MAX_START_OFFSET_M`] with the sink,
//! [`GLIDE_MAX_START_ABOVE_STATE_M`] below it), its flight-path angle
//! ([`GLIDE_MAX_FLIGHT_PATH_ANGLE_OFFSET_RAD`]) and the estimated start transient against the
//! glide's range ([`GLIDE_MAX_TRANSIENT_FRACTION`]): the offset allowed shrinks with the glide's
//! range, so as the vertical L/D falls and as the final speed nears the start speed.

use super::error::VinhError;

/// Skip entry speeds validated against integration \[m/s\] (`validate_vinh_skip_*`: 7435.5 to
/// 10 500 m/s). The lower end was 7 400 m/s until the skip error map found a skip at exactly
/// 7 400 m/s (L/D 2.5, vertical fraction 0.5, -4 deg) that the closed form lets exit while the
/// integration is captured: now the validated grid's edge.
pub const SKIP_SPEED_RANGE_M_S: (f64, f64) = (7_435.0, 10_500.0);
/// Skip entry flight-path angles validated \[rad\] (-7 to -2 deg, as magnitudes).
pub const SKIP_FPA_RANGE_RAD: (f64, f64) = (
    2.0 * core::f64::consts::PI / 180.0 - 1e-9,
    7.0 * core::f64::consts::PI / 180.0 + 1e-9,
);
/// Smallest vertical lift-to-drag ratio of a validated skip (skip error map, docs/validation/vinh-numerical.md:
/// at 0.36 an in-grid skip was 18.6 % short in range and 1.4 deg off in exit flight-path
/// angle, at 0.5 its exit speed 1.9 % high; the validation grids start at 1.2).
pub const SKIP_MIN_VERTICAL_LD: f64 = 0.6;
/// Largest `|eta v|` at a validated skip exit (measured 0.33; the exit errors grow with it).
pub const SKIP_MAX_EXIT_ETA_V: f64 = 0.35;
/// Glide start altitudes inside the domain \[m\] (80 to 110 km). The validation grids start
/// at 70 km, but the random oracle (`tests/it/vinh_oracle.rs`) found glides started at
/// 70-75 km with little vertical lift up to 4 % short with every other check met, and at
/// 75-77 km (light vehicles, 4.5-5.1 km/s) up to -3.00 %; at 50 km the range error reached
/// 8-12 %.
pub const GLIDE_ALTITUDE_RANGE_M: (f64, f64) = (80_000.0, 110_000.0);
/// Vertical lift-to-drag ratios inside the domain (0.72 to 2.5: the error map's validated
/// range, <= 2.8 % from 0.72 to 2.5; it measured -4.4 % at 0.5, and the random oracle up to
/// -3.6 % at 0.66).
pub const GLIDE_VERTICAL_LD_RANGE: (f64, f64) = (0.72, 2.5);
/// Largest estimated start transient of a glide started from the state, as a fraction of the
/// glide's range angle \[-\] (1 %). The glide closed form starts at its own equilibrium radius
/// and flight-path angle; a state off them oscillates about the glide (a phugoid of angular
/// frequency `w = sqrt(a / H)`, `a = mu/r^2 - V^2/r`, `H` the scale height) with an altitude
/// amplitude `A = sqrt(dh^2 + (V dgamma / w)^2)` (`dh` the state's height above the glide start
/// radius, `dgamma` its flight-path angle minus the glide's), and its drag is off the glide's
/// by up to `1 - exp(-A/H)`. The transient's range is estimated as one radian of phugoid phase
/// at that drag offset, `(V/r) (1 - exp(-A/H)) / w` (the sink model of
/// `replan::sink_range_angle`, with the flight-path angle folded into the amplitude). The glide
/// range is long against it only if it is at most this fraction of the glide's range angle: a
/// start offset allowed shrinks with the glide range, hence as the vertical L/D falls or the
/// final speed nears the start speed. Random oracle, docs/validation/vinh-numerical.md: within
/// this budget and the other checks every glide-mode, sink and chain prediction was within
/// 3 % of the integration.
pub const GLIDE_MAX_TRANSIENT_FRACTION: f64 = 0.01;
/// Smallest ratio of final to glide start speed inside the domain (0.34: just below the glide
/// error map's final speed of 0.35, which its start-speed root meets only to rounding; at 0.3
/// the validation grid measured 3.2 % and the random oracle up to -3.6 % at 0.32-0.33 for
/// glides started at 75-77 km).
pub const GLIDE_MIN_FINAL_SPEED_RATIO: f64 = 0.34;
/// Smallest `1 - u_E` of a glide inside the domain (`u_E = V_E^2 r_E / mu`, the start speed
/// squared over the circular speed squared at the glide start radius) \[-\]: 0.03. The glide's
/// mathematical domain ends at 0.01 ([`super::VinhError::GlideNearCircular`]); the random oracle
/// found glides started at 1 - u_E of about 0.012 (7.8 km/s at 96-109 km) up to 3.3 % long.
pub const GLIDE_MIN_SUBCIRCULAR_MARGIN: f64 = 0.03;
/// Largest distance between the state and the glide start radius of a glide-mode prediction,
/// per unit of total L/D \[m\]: `0.56 (1.9)^2 = 2` % of added error (error map).
pub const GLIDE_MAX_START_OFFSET_PER_LD_M: f64 = 1_900.0;
/// Largest distance between the state and the glide start radius of a glide-mode prediction
/// with the sink modelled (`replan::predict_glide_with_sink`) \[m\]: the largest start offset of
/// the glide range-error map (8.7 km: an equilibrium start of full lift flown at a vertical
/// fraction of 0.3), over which that prediction is within 2.9 % for vertical L/D 0.6 to 2.5
/// (docs/validation/vinh-numerical.md). The transient budget [`GLIDE_MAX_TRANSIENT_FRACTION`]
/// binds first on most states.
pub const GLIDE_MAX_START_OFFSET_M: f64 = 9_000.0;
/// Largest distance a glide-mode prediction may start *above* the state \[m\] (the state below
/// the equilibrium of the commanded lift at its speed). The glide error map starts every glide
/// at or below the state; the re-planning domain (the re-plans of host-sim's closed-loop
/// scenarios and campaigns recomputed against integration, docs/validation/vinh-numerical.md) found states up to
/// 5 km below their glide start radius, descending at up to 0.8 deg, whose prediction was up to
/// 5.8 % long; up to 1 km below it every in-domain prediction was within 2.5 %.
pub const GLIDE_MAX_START_ABOVE_STATE_M: f64 = 1_000.0;
/// Largest difference between the state's flight-path angle and the one the glide imposes at
/// its start radius (eq. 3.79) for a glide started from the state \[rad\] (0.2 deg). The glide
/// does not use the state's flight-path angle; in the re-planning domain (docs/validation/vinh-numerical.md) states
/// descending 0.2-0.3 deg steeper than the glide were up to 3.9 % long, within 0.2 deg every
/// prediction that met the other glide checks was within 2.7 %.
pub const GLIDE_MAX_FLIGHT_PATH_ANGLE_OFFSET_RAD: f64 = 0.2 * core::f64::consts::PI / 180.0;

/// Why a prediction is extrapolated (the first phase and quantity outside the validated grid).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Extrapolation {
    /// A skip entry speed outside [`SKIP_SPEED_RANGE_M_S`].
    SkipEntrySpeed,
    /// A skip entry flight-path angle outside [`SKIP_FPA_RANGE_RAD`].
    SkipFlightPathAngle,
    /// A skip exit with `|eta v|` above [`SKIP_MAX_EXIT_ETA_V`].
    SkipSpeedExpansion,
    /// A skip with vertical L/D below [`SKIP_MIN_VERTICAL_LD`].
    SkipVerticalLiftToDrag,
    /// A chain reaching its final glide through a capture after a skip or an arc (a skip that
    /// does not exit, or an exit too shallow for an arc): the descent from the interface radius
    /// to the glide start radius is not modelled (zero range), and the chain error map shows
    /// errors far beyond the phases' own (docs/validation/vinh-numerical.md). A chain captured in its first skip
    /// from a descending state is the glide started from the state and is checked as one
    /// instead (start offset, flight-path angle).
    CaptureTransition,
    /// Glide start altitude outside [`GLIDE_ALTITUDE_RANGE_M`].
    GlideAltitude,
    /// Glide vertical L/D outside [`GLIDE_VERTICAL_LD_RANGE`].
    GlideVerticalLiftToDrag,
    /// Final speed below [`GLIDE_MIN_FINAL_SPEED_RATIO`] of the glide start speed.
    GlideFinalSpeedRatio,
    /// Glide start speed so near the circular speed that `1 - u_E` is below
    /// [`GLIDE_MIN_SUBCIRCULAR_MARGIN`] (the error [`super::VinhError::GlideNearCircular`]
    /// starts at 0.01).
    GlideCircularMargin,
    /// Glide-mode start radius more than [`GLIDE_MAX_START_OFFSET_PER_LD_M`] times the total
    /// L/D from the state ([`GLIDE_MAX_START_OFFSET_M`] with the sink modelled).
    GlideStartOffset,
    /// Glide-mode start radius more than [`GLIDE_MAX_START_ABOVE_STATE_M`] above the state (the
    /// state below the equilibrium of the commanded lift; not validated).
    GlideBelowEquilibrium,
    /// The state's flight-path angle more than [`GLIDE_MAX_FLIGHT_PATH_ANGLE_OFFSET_RAD`] from
    /// the one the glide imposes at its start (a glide started from the state: glide mode, or a
    /// chain captured in its first skip).
    GlideFlightPathAngle,
    /// The estimated start transient of a glide started from the state (its offset from the
    /// glide's start radius and flight-path angle) above [`GLIDE_MAX_TRANSIENT_FRACTION`] of the
    /// glide's range angle, or not estimable (at or above circular speed).
    GlideTransient,
}

/// Validity of a prediction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Validity {
    /// Every phase inside the validated region: the documented accuracy applies.
    InDomain,
    /// Computed, but a phase lies outside the validated region (the first reason).
    Extrapolated(Extrapolation),
    /// Not computed: outside the closed forms' domain (the predictor's error).
    OutOfDomain(VinhError),
}

impl Validity {
    /// Keep the first reason: `self` if already extrapolated, else `Extrapolated(reason)` when
    /// `outside`.
    #[must_use]
    pub(crate) fn and(self, outside: bool, reason: Extrapolation) -> Self {
        match self {
            Validity::InDomain if outside => Validity::Extrapolated(reason),
            v => v,
        }
    }
}
