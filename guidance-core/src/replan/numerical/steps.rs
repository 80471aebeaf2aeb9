//! The step rule's constants of the numerical predictor (the rule itself: the parent module's
//! "Step rule"), in a leaf module so that the integrator's dynamics and the run read them
//! without importing each other; re-exported as `replan::numerical::{MAX_STEP_S, ...}`.

/// Largest time step \[s\].
pub const MAX_STEP_S: f64 = 20.0;
/// Largest altitude change per step, in density scale heights \[-\].
pub const VERTICAL_STEP_FRACTION: f64 = 0.5;
/// Largest relative speed change per step by drag \[-\].
pub const SPEED_STEP_FRACTION: f64 = 0.05;
/// Largest phugoid phase per step \[rad\].
pub const PHUGOID_STEP_RAD: f64 = 0.5;
