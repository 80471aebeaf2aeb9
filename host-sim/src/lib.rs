#![doc = include_str!("../README.md")]
//!
//! ## Modules
//!
//! Host-side (std) re-entry simulation around `guidance-core`:
//! environment models ([`env`](mod@env): atmosphere, gravity, planet), vehicles ([`vehicle`]),
//! 3-DOF dynamics ([`dynamics`]), integrators ([`integrate`]), the closed-loop harness that
//! flies the core's own `Guidance` at its fixed 2 s clock ([`sim`]), the analytical simulator
//! ([`analytic`]), the mission definition ([`scenario`]), reports ([`report`]) and the CLI
//! ([`cli`], which nothing else in the library imports).
//!
//! Units: SI and radians inside; degrees and km only at the edges (CLI, files, plots).
#![deny(missing_docs)]
#![forbid(unsafe_code)]

pub mod analytic;
pub mod campaign;
pub mod cli;
pub mod compare;
pub mod design;
pub mod dynamics;
pub mod env;
pub mod integrate;
pub mod num_fmt;
pub mod optim;
pub mod pil;
pub mod replan_loop;
pub mod report;
pub mod scenario;
pub mod sim;
pub mod stack_loop;
pub mod toml_input;
pub mod vehicle;
