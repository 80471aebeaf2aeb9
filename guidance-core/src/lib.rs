#![doc = include_str!("../README.md")]
//!
//! ## Modules
//!
//! The flow is: navigation state ([`NavState`]) -> normalised energy ([`energy`]) ->
//! node table lookup ([`nodes`]) -> interpolation ([`interp`]) -> attitude-rate limiting
//! ([`rate`]) -> fixed 2 s guidance clock with zero-order hold ([`clock`], [`guidance`]) ->
//! command (angle of attack, bank angle). Constraint monitors live in [`monitor`]; the
//! second-order closed forms of Vinh, Kim & Greenwood (1993) in [`vinh`]; onboard re-planning
//! (an analytic predictor-corrector on the bank-angle nodes) in `replan`.
//!
//! Units: SI and radians everywhere. Degrees appear only in `*_deg` constructors/constants.
//! Units in docs are written in brackets, e.g. \[m/s\].
//!
//! Numerics: everything on the guidance path is generic over [`Scalar`] (implemented for `f32`,
//! `f64` and the fixed-point [`Fixed`]); closed forms need transcendental functions and are
//! generic over [`Real`] (`f32`, `f64`). All float math goes through [`math`].
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]
#![deny(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing
)]
// `!(x > 0.0)` is the NaN-rejecting form of `x <= 0.0`: flight code relies on it on purpose.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod clock;
pub mod command;
pub mod energy;
pub mod error;
pub mod estimate;
pub mod geo;
pub mod guidance;
pub mod interp;
pub mod lateral;
pub mod link;
pub mod math;
pub mod missions;
pub mod monitor;
pub mod nav;
pub mod navconv;
pub mod nodes;
pub mod plausibility;
pub mod rate;
pub mod replan;
pub mod scalar;
pub mod setup;
pub mod stack;
pub mod vinh;

pub use command::Command;
pub use error::GuidanceError;
pub use nav::NavState;
pub use scalar::{Fixed, Real, Scalar};
