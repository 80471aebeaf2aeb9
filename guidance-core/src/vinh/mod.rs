//! Second-order closed-form solutions of Vinh, Kim & Greenwood (1993) as used in the thesis
//! sec. 3.5 (skip, glide, ballistic arc), with the corrections of `ERRATA.md`, and an analytic
//! range/constraint predictor chaining them.
//!
//! * [`nondim`]: non-dimensional set-up (eq. 3.16-3.28).
//! * [`skip`]: atmospheric skip, second order (eq. 3.39-3.61).
//!
//! Everything is generic over [`crate::Real`] (`f32`, `f64`), `no_std`, allocation-free and
//! panic-free; every iteration is bounded. Inputs outside the domain of a solution return a
//! [`VinhError`]; no function returns NaN or an infinite value.

pub mod error;
pub mod nondim;
mod num;
pub mod skip;

pub use error::VinhError;
pub use nondim::{
    Constants, EntryState, ExpAtmosphere, LiftControl, NonDim, Planet, VehicleParams,
};
pub use skip::{Leg, SkipOptions, SkipPoint, SkipSolution};
