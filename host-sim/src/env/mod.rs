//! Environment models: atmosphere, gravity, planet.
//!
//! The traits here are the seams between the environment and the dynamics; implementations
//! live in the submodules.

pub mod atmosphere;
pub mod gravity;
pub mod planet;

pub use atmosphere::{Atmosphere, AtmosphereState};
pub use gravity::Gravity;
pub use planet::Planet;
