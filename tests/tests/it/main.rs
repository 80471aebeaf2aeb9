//! The workspace-level integration-test binary. Each module is one topic.

mod core_layering;
mod doc_links;
mod firmware_golden;
mod qemu_runners;
