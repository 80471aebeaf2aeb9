//! The guidance-core integration-test binary (one per crate). Each module is one topic.

mod guidance_props;
mod navconv;
mod node_capacity;
mod vinh_props;
mod vinh_replan;
mod vinh_support;
mod vinh_validation;
