//! `cargo xtask board-example` (also a step of `cargo xtask test`): build the standalone board
//! firmware of `examples/board-firmware/` (a crate of its own, outside the workspace, as a
//! user's firmware would be), check it with clippy, and run it in QEMU on the Cortex-M4F
//! (`mps2-an386`): it flies the core's re-planning guidance at its 2 s period and exits 0 only
//! if every command is finite and in bounds and the first tick re-planned.

use std::path::PathBuf;
use std::process::Command;

use onboard_spec::machines::CORTEX_M4F;

use super::{qemu, root, run, target_dir};

/// The example's folder.
fn example_dir() -> PathBuf {
    root().join("examples").join("board-firmware")
}

/// Cargo in the example's folder (so its `.cargo/config.toml`, target and linker flags
/// apply), its build output under the workspace's target directory.
fn cargo_in_example() -> Command {
    let mut c = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
    c.current_dir(example_dir())
        .env("CARGO_TARGET_DIR", target_dir().join("board-firmware"));
    c
}

/// Build, lint and run the example (module docs).
pub fn board_example() -> Result<(), String> {
    let mut c = cargo_in_example();
    c.args(["fmt", "--check"]);
    run(c, "board example: cargo fmt --check")?;
    let mut c = cargo_in_example();
    c.args(["clippy", "--release", "--", "-D", "warnings"]);
    run(c, "board example: clippy")?;
    let mut c = cargo_in_example();
    c.args(["build", "--release"]);
    run(c, "board example: build for thumbv7em-none-eabihf")?;
    let elf = target_dir()
        .join("board-firmware")
        .join(CORTEX_M4F.target)
        .join("release")
        .join("board-firmware");
    run(
        qemu(&CORTEX_M4F, &elf, false),
        &format!("board example in QEMU on {}", CORTEX_M4F.description),
    )
}
