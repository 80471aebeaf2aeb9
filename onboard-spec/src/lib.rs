//! # onboard-spec
//!
//! The one home of what the onboard firmware (`onboard-demo`) runs on and is checked against,
//! shared as a crate (no `#[path]` includes) by the firmware, `xtask`, `host-sim`'s PIL and
//! the workspace tests:
//!
//! * [`machines`]: the QEMU machines (target triple, QEMU CPU and machine, description) the
//!   firmware boots on, and the QEMU command line for them; `.cargo/config.toml`'s runners
//!   are checked against this table by the workspace tests;
//! * [`scenario`]: the smoke scenario the firmware flies, run identically on the host;
//! * [`golden`]: its golden outputs, computed on the host by `cargo xtask golden`;
//! * [`footprint`]: the flash and static RAM of a firmware ELF and the budget-file values it
//!   is checked against (`cargo xtask size` / `stack`, `host-sim`'s PIL tests).
//!
//! `no_std`, no allocation, no unsafe code.
#![no_std]
#![forbid(unsafe_code)]
#![deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

pub mod footprint;
pub mod golden;
pub mod machines;
pub mod scenario;
