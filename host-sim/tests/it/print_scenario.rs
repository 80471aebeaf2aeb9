//! `simulate --print-scenario` prints the annotated template, and its output, saved anywhere,
//! flies the same as its input (a relative `vehicle_file` is printed absolute).

use std::path::Path;

use host_sim::scenario::{fly, read_scenario, scenario_to_toml};

/// A directory of its own under the system's temporary directory, removed when dropped.
struct TempDir(std::path::PathBuf);

impl TempDir {
    fn new(tag: &str) -> Self {
        let p = std::env::temp_dir().join(format!("host-sim-it-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&p);
        std::fs::create_dir_all(p.join("elsewhere")).unwrap();
        Self(p)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

#[test]
fn printed_scenario_saved_elsewhere_flies_the_same() {
    // Read by a path relative to the current directory (host-sim/ under cargo test), so its
    // vehicle_file resolves to a relative path too.
    let input = Path::new("../examples/betts-shuttle.toml");
    let mut sc = read_scenario(input).unwrap();
    let text = scenario_to_toml(&sc);
    assert!(text.starts_with("# host-sim scenario file"), "{text}");
    assert!(
        text.lines()
            .any(|l| l.starts_with("altitude_km = ") && l.contains("# [km], (0, 10000)")),
        "keys carry their unit and range:\n{text}"
    );
    let tmp = TempDir::new("print-scenario");
    let saved = tmp.0.join("elsewhere").join("copy.toml");
    std::fs::write(&saved, &text).unwrap();
    let mut back = read_scenario(&saved).unwrap();
    assert_eq!(scenario_to_toml(&back), text);
    // Fly both for their first 200 s: the same summary, bit for bit.
    sc.termination.max_time_s = 200.0;
    back.termination.max_time_s = 200.0;
    let a = fly(&sc, "input", &mut |_| {}).unwrap().result.summary;
    let b = fly(&back, "copy", &mut |_| {}).unwrap().result.summary;
    assert_eq!(format!("{a:?}"), format!("{b:?}"));
}
