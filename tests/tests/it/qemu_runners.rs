//! `.cargo/config.toml` cannot read the QEMU machine table of `onboard_spec::machines`, so
//! its runners are written out by hand; this test keeps them equal to the table (and the
//! table is what xtask and host-sim's PIL use).

use std::path::Path;

use onboard_spec::machines::{MACHINES, by_target, runner};

fn cargo_config() -> toml::Table {
    config_in(&Path::new(env!("CARGO_MANIFEST_DIR")).join(".."))
}

/// `DIR/.cargo/config.toml`, parsed.
fn config_in(dir: &Path) -> toml::Table {
    let path = dir.join(".cargo").join("config.toml");
    let text = std::fs::read_to_string(&path).expect(".cargo/config.toml is readable");
    text.parse().expect(".cargo/config.toml is valid TOML")
}

/// The runner of `[target.<triple>]` as words (cargo accepts a string or an array).
fn runner_words(config: &toml::Table, triple: &str) -> Option<Vec<String>> {
    let value = config.get("target")?.get(triple)?.get("runner")?;
    match value {
        toml::Value::String(s) => Some(s.split_whitespace().map(str::to_owned).collect()),
        toml::Value::Array(a) => a.iter().map(|v| v.as_str().map(str::to_owned)).collect(),
        _ => None,
    }
}

#[test]
fn cargo_runners_match_the_qemu_machine_table() {
    let config = cargo_config();
    for m in &MACHINES {
        let want: Vec<String> = runner(m).iter().map(|w| (*w).to_owned()).collect();
        let got = runner_words(&config, m.target).unwrap_or_else(|| {
            panic!("[target.{}] runner missing in .cargo/config.toml", m.target)
        });
        assert_eq!(
            got, want,
            ".cargo/config.toml runner of {} differs from onboard_spec::machines",
            m.target
        );
    }
    // And no runner for a target the table does not know.
    let targets = config.get("target").and_then(toml::Value::as_table);
    for (triple, section) in targets.into_iter().flatten() {
        if section.get("runner").is_some() {
            assert!(
                by_target(triple).is_some(),
                "[target.{triple}] has a runner but no QEMU machine in onboard_spec::machines"
            );
        }
    }
}

/// The board example (a crate of its own, `examples/board-firmware/`) runs on the Cortex-M4F
/// machine of the table too.
#[test]
fn board_example_runner_matches_the_qemu_machine_table() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("examples")
        .join("board-firmware");
    let config = config_in(&dir);
    let m = onboard_spec::machines::CORTEX_M4F;
    let want: Vec<String> = runner(&m).iter().map(|w| (*w).to_owned()).collect();
    assert_eq!(runner_words(&config, m.target), Some(want));
}

/// The check fails on a runner that disagrees (so the test above can fail).
#[test]
fn runner_check_sees_a_difference() {
    let bad: toml::Table =
        "[target.thumbv7m-none-eabi]\nrunner = \"qemu-system-arm -cpu cortex-m4\"\n"
            .parse()
            .unwrap();
    let want: Vec<String> = runner(&MACHINES[1])
        .iter()
        .map(|w| (*w).to_owned())
        .collect();
    assert_ne!(runner_words(&bad, "thumbv7m-none-eabi"), Some(want));
}
