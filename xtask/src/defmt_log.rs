//! `cargo xtask defmt`: the smoke firmware built with feature `defmt` (defmt over semihosting,
//! `DEFMT_LOG=info`) on each QEMU machine, its output decoded with `defmt-print` (installed
//! from crates.io with `cargo install defmt-print` if missing); passes when the decoded log
//! has the firmware's success line. Built in its own target directory (`<target>/defmt`) so
//! the plain firmware images are not replaced.

use std::io::Write as _;
use std::process::{Command, Stdio};

use onboard_spec::machines::MACHINES;

use crate::{cargo, have, qemu, run, target_dir};

/// The line the firmware logs when its outputs match the golden values.
const SUCCESS: &str = "guidance outputs match the host golden values";

pub fn defmt_log() -> Result<(), String> {
    if !have("defmt-print", "--version") {
        let mut c = cargo();
        c.args(["install", "defmt-print", "--locked"]);
        run(c, "install defmt-print")?;
    }
    let dir = target_dir().join("defmt");
    for m in &MACHINES {
        let mut c = cargo();
        c.args([
            "build",
            "-p",
            "onboard-demo",
            "--profile",
            "firmware",
            "--target",
            m.target,
            "--features",
            "defmt",
            "--bin",
            "onboard-demo",
        ])
        .env("CARGO_TARGET_DIR", &dir)
        .env("DEFMT_LOG", "info");
        run(c, &format!("build defmt firmware for {}", m.target))?;
        let elf = dir.join(m.target).join("firmware").join("onboard-demo");
        let out = qemu(m, &elf, false)
            .output()
            .map_err(|e| format!("cannot run QEMU on {}: {e}", elf.display()))?;
        if !out.status.success() {
            return Err(format!(
                "defmt firmware on {} failed ({})",
                m.description, out.status
            ));
        }
        let mut dp = Command::new("defmt-print")
            .arg("-e")
            .arg(&elf)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| format!("cannot start defmt-print: {e}"))?;
        if let Some(mut stdin) = dp.stdin.take() {
            stdin
                .write_all(&out.stdout)
                .map_err(|e| format!("defmt-print stdin: {e}"))?;
        }
        let decoded = dp
            .wait_with_output()
            .map_err(|e| format!("defmt-print: {e}"))?;
        let text = String::from_utf8_lossy(&decoded.stdout);
        println!(
            "xtask: defmt log on {}:\n{}",
            m.description,
            text.trim_end()
        );
        if !text.contains(SUCCESS) {
            return Err(format!(
                "defmt log on {} lacks {SUCCESS:?}: {}{}",
                m.description,
                text,
                String::from_utf8_lossy(&decoded.stderr)
            ));
        }
    }
    Ok(())
}
