//! Second-order closed-form solutions of Vinh, Kim & Greenwood (1993) as used in the thesis
//! sec. 3.5 (skip, glide, ballistic arc), with the corrections of `ERRATA.md`, and an analytic
//! range/constraint predictor chaining them.
//!
//! * [`nondim`]: non-dimensional set-up (eq. 3.16-3.28).
//! * [`skip`]: atmospheric skip, second order (eq. 3.39-3.61).
//! * [`glide`]: atmospheric glide, second order (eq. 3.62-3.79).
//! * [`ballistic`]: Kepler arc from exit to re-entry (eq. 3.80-3.82, corrected).
//! * [`predict`]: skip -> arc -> ... -> final glide chain: range, peak heat flux and g-load.
//!
//! Everything is generic over [`crate::Real`] (`f32`, `f64`), `no_std`, allocation-free and
//! panic-free; every iteration is bounded. Inputs outside the domain of a solution return a
//! [`VinhError`]; no function returns NaN or an infinite value.

pub mod ballistic;
pub mod error;
pub mod glide;
pub mod nondim;
mod num;
pub mod predict;
pub mod skip;

pub use ballistic::{ArcPoint, BallisticArc};
pub use error::VinhError;
pub use glide::{GlidePoint, GlideSolution};
pub use nondim::{
    Constants, EntryState, ExpAtmosphere, LiftControl, NonDim, Planet, VehicleParams,
};
pub use predict::{Prediction, PredictorConfig, predict};
pub use skip::{Leg, SkipOptions, SkipPoint, SkipSolution};
