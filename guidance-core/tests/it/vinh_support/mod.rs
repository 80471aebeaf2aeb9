//! Test-side support for the Vinh validation: an adaptive Dormand-Prince 5(4) integrator with
//! event location, the reference vehicles of the thesis, and reference dynamics written from the
//! governing equations (independent of `guidance_core::vinh`).

pub mod dynamics;
pub mod inputs;
pub mod ode;
pub mod vehicles;
