//! The guidance-core integration-test binary (one per crate). Each module is one topic.

mod bank_shape;
mod estimate;
mod guidance_props;
mod lateral;
mod lateral_terminal;
mod lift_down;
mod lift_schedule;
mod navconv;
mod node_capacity;
mod numerical_predictor;
mod numerical_replan;
mod numerical_rotation;
mod path_barrier;
mod path_bound;
mod setup_image;
mod stack;
mod vinh_error_map;
mod vinh_oracle;
mod vinh_peaks;
mod vinh_props;
mod vinh_replan;
mod vinh_replan_budget;
mod vinh_skip_map;
mod vinh_support;
mod vinh_validation;
mod vinh_validity;
