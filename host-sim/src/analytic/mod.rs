//! Analytical simulator: trajectories from the Vinh, Kim & Greenwood second-order closed forms of
//! `guidance_core::vinh` (thesis sec. 3.5), returned in the numerical simulator's own output
//! types ([`SimResult`]: [`Sample`] rows and a [`Summary`]), so [`crate::report`] writes the
//! same trajectory CSV, summary JSON and SVG plots for both.
//!
//! The closed forms are only *called* here (skip: [`SkipSolution`], glide: [`GlideSolution`]);
//! this module converts their planar points into samples:
//!
//! * Placement: the closed forms are planar (range angle `theta` only). The trajectory is laid
//!   on the great circle through the entry position in the entry heading ([`Placement`]), so
//!   latitude, longitude and heading are defined; the planet does not rotate (the closed forms'
//!   assumption).
//! * Time: the closed forms have no time. It is the quadrature `t = integral r / (V cos gamma)
//!   d theta` (from `d theta / dt = V cos gamma / r`, eq. 3.15) by the trapezoidal rule over
//!   the samples; the heat load is the trapezoidal integral of the heat flux over that time.
//! * Peaks: peak heat flux and g-load are the closed forms' own maximisations
//!   ([`SkipSolution::peak_heat_flux`], [`GlideSolution::peak_heat_flux`], ...); their times
//!   are interpolated in range angle. The g-load rate is the largest finite difference between
//!   samples (the closed forms are smooth, so this is a lower bound of a real vehicle's).
//! * Attitude: the samples carry the bank angle; the angle of attack is 0 (the closed forms,
//!   and the constant-`C_L` polar vehicle of the comparison runs, are parameterised by `C_L`).
//! * Termination: the glide ends at an altitude or a speed ([`GlideEnd`]) and is reported as
//!   [`TerminationReason::Altitude`] or [`TerminationReason::Mach`] (the speed of sound of the
//!   isothermal exponential atmosphere is constant, so a speed is a Mach number). The skip ends
//!   where it climbs back through its entry radius; `sim::TerminationReason` has no
//!   "atmosphere exit" reason, so it is reported as [`TerminationReason::Altitude`] with one
//!   exit recorded in [`Summary::exits`] and [`Summary::interface_crossings_s`].
//!
//! # Vehicle model ([`AnalyticVehicle`])
//! The closed forms need a parabolic drag polar `C_D = C_D0 + K C_L^2`:
//! * vehicles with a polar ([`crate::vehicle::Aerodynamics::drag_polar`], e.g. HORUS-2B, thesis
//!   table 8.1) use it at one representative Mach number (default [`DEFAULT_POLAR_MACH`],
//!   hypersonic), and are steered by the lift coefficient (`lambda = C_L / C_L*`) and bank;
//! * trim-only vehicles (the SRM capsule, which has no polar) get the polar on which their trim
//!   point is the maximum-L/D point: `C_D0 = C_D,trim / 2`, `K = C_D0 / C_L,trim^2`, so
//!   `lambda = 1`, `E* = (L/D)_trim` and the polar reproduces the trim `C_D` exactly. They are
//!   steered by bank only: vertical lift coefficient `C_L,trim cos(sigma)`. For the SRM this
//!   gives C_D0 = 0.2816, K = 0.1722 (E* = 2.27); guidance-core's Vinh validation uses the polar
//!   back-derived from thesis sec. 9.2 instead (C_D0 = 0.2576, K = 0.1879, same E*), on which
//!   the trim point C_L = 1.2786 lies within 0.3 % in C_D. Both fly the same trim lift and drag.
//!
//! # Atmosphere
//! The closed forms assume an isothermal exponential atmosphere. [`fit_us76`] gives the one
//! through the US76 densities at two altitudes of the flight band (default
//! [`DEFAULT_FIT_ALTITUDES_M`]); the same [`ExponentialAtmosphere`] drives the simplified
//! numerical environment in [`crate::compare`], so that comparison isolates the closed forms'
//! own approximations.
//!
//! [`Sample`]: crate::sim::Sample
//! [`Summary`]: crate::sim::Summary
//! [`Summary::exits`]: crate::sim::Summary::exits
//! [`Summary::interface_crossings_s`]: crate::sim::Summary::interface_crossings_s
//! [`TerminationReason::Altitude`]: crate::sim::TerminationReason::Altitude
//! [`TerminationReason::Mach`]: crate::sim::TerminationReason::Mach
//! [`SkipSolution`]: guidance_core::vinh::SkipSolution
//! [`SkipSolution::peak_heat_flux`]: guidance_core::vinh::SkipSolution::peak_heat_flux
//! [`GlideSolution`]: guidance_core::vinh::GlideSolution
//! [`GlideSolution::peak_heat_flux`]: guidance_core::vinh::GlideSolution::peak_heat_flux

mod glide;
mod guided;
mod placement;
mod samples;
mod skip;
mod vehicle;

use guidance_core::vinh::{self, ExpAtmosphere, VinhError};

use crate::dynamics::SphericalState;
use crate::env::{ExponentialAtmosphere, Planet, Us76, atmosphere::ExponentialAtmosphereError};
use crate::sim::SimResult;

pub use glide::glide_trajectory;
pub use guided::{GuidedGlide, SEGMENT_POINTS, guided_glide};
pub use placement::Placement;
pub use skip::skip_trajectory;
pub use vehicle::{AnalyticVehicle, LiftSetting};

/// Mach number at which a tabulated drag polar is taken by default (hypersonic; HORUS-2B's
/// table 8.1 polar at Mach 20).
pub const DEFAULT_POLAR_MACH: f64 = 20.0;
/// Default altitudes \[m\] through which the exponential atmosphere is fitted to US76 (the band
/// of a capsule glide or skip from 100 km).
pub const DEFAULT_FIT_ALTITUDES_M: (f64, f64) = (50_000.0, 100_000.0);
/// Default number of trajectory samples.
pub const DEFAULT_POINTS: usize = 201;
/// Smallest and largest accepted number of samples.
pub const POINTS_RANGE: (usize, usize) = (3, 100_000);

/// Why a vehicle has no usable drag polar for the closed forms.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NoPolar {
    /// It has neither a drag polar nor fixed trim coefficients.
    Missing,
    /// Its trim coefficients are not finite and positive.
    BadTrim {
        /// Trim lift coefficient \[-\].
        cl: f64,
        /// Trim drag coefficient \[-\].
        cd: f64,
    },
    /// Its drag polar at the Mach number asked for is not finite and positive.
    BadPolar {
        /// Mach number of the polar \[-\].
        mach: f64,
        /// Zero-lift drag coefficient \[-\].
        cd0: f64,
        /// Induced-drag factor \[-\].
        k: f64,
    },
}

impl std::fmt::Display for NoPolar {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            NoPolar::Missing => {
                f.write_str("no drag polar (give one in the vehicle file: aero kind `drag_polar`)")
            }
            NoPolar::BadTrim { cl, cd } => write!(
                f,
                "trim coefficients C_L = {cl}, C_D = {cd} must be finite and positive"
            ),
            NoPolar::BadPolar { mach, cd0, k } => write!(
                f,
                "drag polar at Mach {mach}: C_D0 = {cd0}, K = {k} must be finite and positive"
            ),
        }
    }
}

/// Analytical-simulator failures.
#[derive(Debug, thiserror::Error)]
pub enum AnalyticError {
    /// The vehicle cannot be described by a drag polar.
    #[error("vehicle `{vehicle}`: {reason}")]
    Vehicle {
        /// Vehicle name.
        vehicle: String,
        /// Why.
        reason: NoPolar,
    },
    /// A setting is out of range.
    #[error("invalid setting `{field}` = {}: {reason}", crate::num_fmt::Compact(*value))]
    Setting {
        /// Setting name (with unit).
        field: &'static str,
        /// Its value.
        value: f64,
        /// What is required.
        reason: &'static str,
    },
    /// The closed form is outside its domain of validity (typed, from guidance-core).
    #[error("{phase} closed form out of domain: {error}")]
    Domain {
        /// `"skip"` or `"glide"`.
        phase: &'static str,
        /// The closed form's error.
        error: VinhError,
    },
    /// A node-guided glide needs a vehicle steered by bank only (trim coefficients).
    #[error(
        "vehicle `{vehicle}`: the node-guided glide flies bank-only vehicles (trim coefficients, e.g. the SRM capsule); this one is steered by the angle of attack"
    )]
    NotBankOnly {
        /// Vehicle name.
        vehicle: String,
    },
    /// The exponential atmosphere could not be built.
    #[error(transparent)]
    Atmosphere(#[from] ExponentialAtmosphereError),
}

fn setting(field: &'static str, value: f64, reason: &'static str) -> AnalyticError {
    AnalyticError::Setting {
        field,
        value,
        reason,
    }
}

/// The exponential atmosphere through the US76 densities at `h1_m` and `h2_m` \[m\].
///
/// # Errors
/// As [`ExponentialAtmosphere::fitted_to`] (e.g. equal altitudes, non-positive density).
pub fn fit_us76(h1_m: f64, h2_m: f64) -> Result<ExponentialAtmosphere, AnalyticError> {
    Ok(ExponentialAtmosphere::fitted_to(&Us76::new(), h1_m, h2_m)?)
}

/// The closed forms' planet: Earth's `mu` and radius, no rotation.
#[must_use]
pub fn planet() -> Planet {
    Planet::earth_non_rotating()
}

fn vinh_planet(p: &Planet) -> vinh::Planet<f64> {
    vinh::Planet {
        mu_m3_s2: p.mu_m3_s2,
        radius_m: p.radius_m,
    }
}

fn vinh_atmosphere(a: &ExponentialAtmosphere, p: &Planet) -> ExpAtmosphere<f64> {
    ExpAtmosphere {
        rho0_kg_m3: a.rho0_kg_m3(),
        scale_height_m: a.scale_height_m(),
        ref_radius_m: p.radius_m + a.reference_altitude_m(),
    }
}

/// How a glide ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GlideEnd {
    /// At this altitude \[m\] (below the glide start).
    Altitude {
        /// Final altitude \[m\].
        altitude_m: f64,
    },
    /// At this fraction of the imposed entry speed [-], in (0, 1).
    SpeedFraction {
        /// Final speed over entry speed [-].
        fraction: f64,
    },
}

/// Which closed form produced a trajectory.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Phase {
    /// Atmospheric skip, entry to exit (thesis sec. 3.5.1).
    Skip,
    /// Equilibrium glide (thesis sec. 3.5.2).
    Glide,
}

/// An analytical trajectory.
#[derive(Clone, Debug)]
pub struct AnalyticRun {
    /// Samples and summary, in the numerical simulator's types.
    pub result: SimResult,
    /// Which closed form.
    pub phase: Phase,
    /// Entry state (for the glide: the state imposed by eq. 3.78/3.79).
    pub entry: SphericalState,
    /// Lowest altitude \[m\] (skip: the closed form's deepest point; glide: the end).
    pub deepest_altitude_m: f64,
    /// Lift setting flown.
    pub lift: LiftSetting,
    /// The exponential atmosphere of the closed forms.
    pub atmosphere: ExponentialAtmosphere,
}

fn check_points(points: usize) -> Result<(), AnalyticError> {
    if (POINTS_RANGE.0..=POINTS_RANGE.1).contains(&points) {
        Ok(())
    } else {
        Err(setting(
            "points",
            points as f64,
            "must be within [3, 100000]",
        ))
    }
}

/// Sample `i` of `points` evenly spaced from `start` to `end` (both ends exact).
fn evenly_spaced(start: f64, end: f64, i: usize, points: usize) -> f64 {
    if i == 0 {
        start
    } else if i + 1 == points {
        end
    } else {
        start + (end - start) * i as f64 / (points - 1) as f64
    }
}

/// Environment description of the analytical simulator for [`crate::report::summary_report`].
#[must_use]
pub fn environment_label(atmosphere: &ExponentialAtmosphere) -> String {
    format!(
        "analytical (Vinh second order): non-rotating sphere, central gravity, exponential \
         atmosphere rho0 = {:.4e} kg/m^3 at {:.1} km, H_s = {:.1} m",
        atmosphere.rho0_kg_m3(),
        atmosphere.reference_altitude_m() / 1e3,
        atmosphere.scale_height_m()
    )
}
