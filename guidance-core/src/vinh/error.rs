//! Typed domain errors of the Vinh closed forms, the Kepler arc and the predictor.
//!
//! Every failure mode reported in thesis sec. 8.2.1 / 8.1.6 (complex numbers for `x` beyond the
//! deepest point, `C_D0 <= 0`, entry speeds above about 11 km/s, near-circular glide entry, no
//! real root for the deepest point) maps to a variant here and is detected *before* a square
//! root of a negative number, a division by zero or a logarithm of a non-positive number could
//! be formed. No function of [`crate::vinh`] returns NaN or an infinite value: results are
//! checked and [`VinhError::NonFiniteResult`] is returned if a check ever fails.

/// Errors of [`crate::vinh`]. Small, `Copy`, no string payloads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum VinhError {
    /// An input was NaN or infinite.
    NonFiniteInput,
    /// Planet constants not positive, or the planet radius is larger than the state radius.
    InvalidPlanet,
    /// Exponential atmosphere with non-positive density or scale height.
    InvalidAtmosphere,
    /// Vehicle mass, reference area, drag-polar factor `K` or nose radius not positive.
    InvalidVehicle,
    /// Zero-lift drag coefficient `C_D0 <= 0`: `E* = 1/(2 sqrt(K C_D0))` and
    /// `B ~ sqrt(C_D0/K)` are not real (thesis sec. 8.2.1, second case).
    NonPositiveZeroLiftDrag,
    /// Lift setting out of range: `lambda < 0` or vertical fraction outside `[-1, 1]`.
    InvalidLiftControl,
    /// `|k1|` (vertical-lift parameter `B lambda cos(sigma)`) below the smallest value for which
    /// the closed forms, which divide by `k1`, are well conditioned in the chosen float type.
    VerticalLiftTooSmall,
    /// The state lies at or below the planet surface, or the speed is not positive.
    UnphysicalState,
    /// Entry speed above the validated limit ([`crate::vinh::nondim::MAX_ENTRY_SPEED_M_S`],
    /// thesis sec. 8.2.1: "initial velocities above 11000 m/s" give complex numbers).
    EntrySpeedTooHigh,
    /// The skip solution needs a descending entry (`gamma_E < 0`, `phi_E > 0`).
    NotDescending,
    /// `|gamma| >= 90 deg`, or `|phi| > sqrt(r_E/H_s)` so that `gamma = asin(-phi/sqrt(r_E/H_s))`
    /// would not be real.
    FlightPathAngleOutOfDomain,
    /// `phi^2(x) = 0` has no real root above the planet surface: the vehicle does not pull up
    /// (thesis: "no real root of the deepest point").
    NoDeepestPoint,
    /// The quadratic fit `phi_a^2 = a1 x^2 + a2 x + a3` is not oscillatory (`a1 >= 0`), so
    /// `sqrt(-a1)` in eq. 3.43 would be complex.
    NotOscillatory,
    /// The second-order `phi^2` (eq. 3.50) is negative by more than the consistency tolerance at
    /// a point of the skip: the point would be beyond the deepest point (complex `phi`).
    BeyondDeepestPoint,
    /// Skip: the second-order `phi^2` is negative where `x(tau)` returns to 0, so the vehicle does
    /// not climb back to the reference radius (captured; a glide follows).
    NoAtmosphericExit,
    /// A requested range angle or depth lies outside the skip (`tau` outside `[0, tau_exit]`,
    /// `x` outside `[0, x1]`).
    OutsideSkip,
    /// The second-order speed expansion `exp(eta v) ~ 1 + eta v` is outside its validated range
    /// (`|eta v|` above [`crate::vinh::skip::MAX_ETA_V`]).
    SpeedExpansionInvalid,
    /// Glide: `1 - u_E` below [`crate::vinh::glide::MIN_ONE_MINUS_U_E`]: near-circular entry,
    /// the range-angle step of eq. 3.77 blows up (thesis sec. 8.1.6).
    GlideNearCircular,
    /// Glide: the requested speed is outside `(0, V_E]` of the glide, or its altitude from the
    /// second-order `y1` lies below the planet surface.
    GlideSpeedOutOfDomain,
    /// Glide: the vertical lift-to-drag ratio `E` is not positive (no equilibrium glide).
    GlideNoLift,
    /// Ballistic arc: the exit flight-path angle is not positive (the vehicle is not leaving).
    NotAscending,
    /// Ballistic arc: the conic is not elliptic (`e >= 1`); the vehicle escapes.
    EscapeTrajectory,
    /// Ballistic arc: the conic does not reach the requested re-entry radius (apoapsis below it or
    /// periapsis above it).
    NoReentry,
    /// A requested time is outside the ballistic arc.
    OutsideArc,
    /// Predictor or re-planner configuration out of range (non-positive final speed, too many
    /// phases or iterations, inconsistent limits).
    InvalidConfig,
    /// Predictor: the phase budget was used up before the final glide.
    PhaseLimit,
    /// A bounded iteration ended without meeting its tolerance.
    NoConvergence,
    /// A computed output was not finite (defensive check; should not happen for validated input).
    NonFiniteResult,
    /// Numerical predictor: the trajectory reaches the planet surface before the final speed.
    GroundImpact,
    /// Numerical predictor: the step budget ([`crate::replan::numerical::MAX_STEPS`]) is used
    /// up before the final speed (a very long skip arc).
    StepLimit,
    /// Numerical predictor: the state's speed is not above the final speed.
    BelowFinalSpeed,
}

impl core::fmt::Display for VinhError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let s = match self {
            VinhError::NonFiniteInput => "non-finite input",
            VinhError::InvalidPlanet => "invalid planet constants",
            VinhError::InvalidAtmosphere => "invalid exponential atmosphere",
            VinhError::InvalidVehicle => "invalid vehicle parameters",
            VinhError::NonPositiveZeroLiftDrag => "zero-lift drag coefficient C_D0 <= 0",
            VinhError::InvalidLiftControl => "lift setting out of range",
            VinhError::VerticalLiftTooSmall => "vertical lift parameter k1 too small",
            VinhError::UnphysicalState => "state below the surface or speed not positive",
            VinhError::EntrySpeedTooHigh => "entry speed above the validated limit",
            VinhError::NotDescending => "skip entry is not descending",
            VinhError::FlightPathAngleOutOfDomain => "flight-path angle out of domain",
            VinhError::NoDeepestPoint => "no real deepest point above the surface",
            VinhError::NotOscillatory => "quadratic fit of phi^2 is not oscillatory",
            VinhError::BeyondDeepestPoint => "point beyond the deepest point (complex phi)",
            VinhError::NoAtmosphericExit => "skip does not return to the reference radius",
            VinhError::OutsideSkip => "point outside the skip",
            VinhError::SpeedExpansionInvalid => "exp(eta v) expansion out of its valid range",
            VinhError::GlideNearCircular => "glide entry too close to circular speed",
            VinhError::GlideSpeedOutOfDomain => "glide speed out of domain",
            VinhError::GlideNoLift => "glide needs a positive vertical L/D",
            VinhError::NotAscending => "ballistic exit is not ascending",
            VinhError::EscapeTrajectory => "ballistic arc is not elliptic",
            VinhError::NoReentry => "ballistic arc does not reach the re-entry radius",
            VinhError::OutsideArc => "time outside the ballistic arc",
            VinhError::InvalidConfig => "invalid predictor configuration",
            VinhError::PhaseLimit => "predictor phase budget used up",
            VinhError::NoConvergence => "bounded iteration did not converge",
            VinhError::NonFiniteResult => "non-finite result",
            VinhError::GroundImpact => "trajectory reaches the surface before the final speed",
            VinhError::StepLimit => "numerical predictor step budget used up",
            VinhError::BelowFinalSpeed => "state speed not above the final speed",
        };
        f.write_str(s)
    }
}

impl core::error::Error for VinhError {}
