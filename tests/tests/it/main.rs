//! The workspace-level integration-test binary. Each module is one topic.

mod firmware_golden;
