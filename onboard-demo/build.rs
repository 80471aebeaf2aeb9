//! Puts the workspace-root `memory.x` on the linker search path and links with
//! cortex-m-rt's `link.x` (as `-Tlink.x` on every target kind, so tests link too), for
//! firmware targets (`target_os = "none"`) only: a host build of this package is empty.
use std::{env, fs, path::PathBuf};

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    if env::var("CARGO_CFG_TARGET_OS").as_deref() != Ok("none") {
        return;
    }
    let out = PathBuf::from(env::var_os("OUT_DIR").unwrap_or_default());
    let manifest = PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").unwrap_or_default());
    let memory = manifest.join("..").join("memory.x");
    match fs::read(&memory) {
        Ok(bytes) => {
            if let Err(e) = fs::write(out.join("memory.x"), bytes) {
                println!("cargo::error=cannot write memory.x to OUT_DIR: {e}");
            }
        }
        Err(e) => println!("cargo::error=cannot read {}: {e}", memory.display()),
    }
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed={}", memory.display());
    println!("cargo:rustc-link-arg=-Tlink.x");
    // defmt's interned strings (feature `defmt`).
    if env::var_os("CARGO_FEATURE_DEFMT").is_some() {
        println!("cargo:rustc-link-arg=-Tdefmt.x");
    }
}
