//! The workspace-level integration-test binary. Each module is one topic.

mod core_layering;
mod doc_links;
mod firmware_golden;
#[path = "../../../host-sim/tests/it/module_graph.rs"]
mod module_graph;
mod qemu_runners;
