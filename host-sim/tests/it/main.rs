//! The host-sim integration-test binary (one per crate). Each module is one topic.

mod dynamics_validation;
mod env_validation;
