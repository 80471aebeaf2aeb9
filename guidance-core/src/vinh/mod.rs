//! Second-order closed-form solutions of Vinh, Kim & Greenwood (1993) as used in the thesis
//! sec. 3.5 (skip, glide, ballistic arc), with the corrections of `ERRATA.md`, and an analytic
//! range/constraint predictor chaining them.
//!
//! * [`nondim`]: non-dimensional set-up (eq. 3.16-3.28).
//! * [`skip`]: atmospheric skip, second order (eq. 3.39-3.61).
//! * [`glide`]: atmospheric glide, second order (eq. 3.62-3.79).
//! * [`ballistic`]: Kepler arc from exit to re-entry (eq. 3.80-3.82, corrected).
//! * [`mod@predict`]: skip -> arc -> ... -> final glide chain: range, peak heat flux and g-load.
//! * [`validity`]: whether a prediction lies in the validated region ([`Validity`]).
//!
//! Everything is generic over [`crate::Real`] (`f32`, `f64`), `no_std`, allocation-free and
//! panic-free; every iteration is bounded (roots: a short scan for the bracket, then Brent's
//! method to the working precision of the scalar type, at most 128 evaluations; skip peaks: an
//! 8-interval scan and Brent maximisation, at most 64 evaluations; glide peaks: Brent on the
//! analytic derivative; Kepler's equation: 120 safeguarded Newton steps; predictor: at most 8
//! skips). Predictions can skip the peak searches ([`PeakMode::RangeOnly`]) or stop at the first
//! phase proven to exceed a load limit ([`PeakMode::Limits`]). Inputs outside the domain of a
//! solution return a [`VinhError`], detected before the operation that would produce a complex
//! number, NaN or infinity; every output is checked finite.
//!
//! # Domains of validity (details in each module)
//! * Environment: planar, non-rotating spherical planet, inverse-square gravity, exponential
//!   atmosphere. Reference speeds up to [`nondim::MAX_ENTRY_SPEED_M_S`], `C_D0 > 0`.
//! * Skip: descending reference state, a real deepest point above the surface, `a1 < 0`,
//!   `|eta v| <= 0.7`; exits only if `phi^2 >= 0` where `x` returns to 0.
//! * Glide: upward lift, `1 - u_E >= 0.01` (not near circular), `0 < u <= u_E`, altitude above
//!   the surface.
//! * Arc: `0 < gamma0 < 90 deg`, elliptic, re-entry radius between periapsis and apoapsis.
//!
//! # Accuracy
//! Bounds against integration of the exact equations in the same environment: skip exit speed <= 0.8 %,
//! deepest altitude <= 0.25 km, peak heat flux <= 1.7 %, peak g-load <= 3.3 %, exit flight-path
//! angle <= 0.36 deg (SRM) / 1.1 deg (HORUS-2B), range angle <= 11.2 %; glide final range angle
//! <= 2.5 % at 70-110 km (thesis: <= 3 %), 3.2 % for final speeds of 0.3 `V_E`; Kepler arc to
//! 1e-8 against two-body propagation (the tables and their commands:
//! docs/validation/vinh-numerical.md).
//!
//! `f32` against `f64` (bounds of `vinh_f32_agrees_with_f64`): skip exit speed 1e-5 relative,
//! exit flight-path angle 1e-6 rad, range angle 1e-4, peak heat flux 5e-4; glide range angle
//! 1e-3; Kepler range angle and flight time 1e-4 (default libm back end).

pub mod ballistic;
pub mod error;
pub mod glide;
pub mod nondim;
pub(crate) mod num;
pub mod predict;
pub mod skip;
pub mod validity;

pub use ballistic::{ArcPoint, BallisticArc};
pub use error::VinhError;
pub use glide::{GlidePoint, GlideSolution};
pub use nondim::{
    Constants, EntryState, ExpAtmosphere, LiftControl, NonDim, Planet, VehicleParams,
};
pub use predict::{
    LoadLimits, PeakMode, PeakStatus, Prediction, PredictorConfig, predict, predict_with,
};
pub use predict::{skip_validity, validity_of};
pub use skip::{Leg, SkipOptions, SkipPoint, SkipSolution};
pub use validity::{Extrapolation, Validity};
