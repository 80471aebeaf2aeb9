//! The host-sim integration-test binary (one per crate). Each module is one topic.

mod aero_schedule;
mod analytic_validation;
mod campaign;
mod cli;
mod closed_loop;
mod dynamics_validation;
mod env_validation;
mod hypervolume;
mod hypervolume_cli;
mod hypervolume_pagmo2;
mod input_ranges;
mod integrator_reuse;
mod interrupt;
mod layering;
mod navconv;
mod pil;
mod pil_faults;
mod pil_reliability;
mod pil_replanning;
mod pil_scenarios;
mod pil_support;
mod replan_domain;
mod replan_loop;
mod run_dir_kill;
mod scenario_files;
mod support;
