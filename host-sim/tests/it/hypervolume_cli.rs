//! `host-sim hypervolume` (issue 9 item 14): values, contributions, `--repeat`, and errors
//! naming the file and line. Library calls through `host_sim::cli::run`, plus one run of the
//! binary for the exit code.

use std::ops::Deref;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

use host_sim::cli::run;

/// A front file named `name` in a directory of its own (tests run in parallel in one process),
/// removed with its directory when dropped.
struct TempFile {
    dir: PathBuf,
    path: PathBuf,
}

impl Deref for TempFile {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.path
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

fn temp_file(name: &str, text: &str) -> TempFile {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("host-sim-it-hv-{}-{n}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    TempFile { dir, path }
}

/// Run the CLI in-process; Ok(stdout) or Err(error message).
fn cli(args: &[&str]) -> Result<String, String> {
    let mut out = Vec::new();
    let mut full = vec!["host-sim", "hypervolume"];
    full.extend_from_slice(args);
    run(full, &mut out)
        .map(|()| String::from_utf8(out).unwrap())
        .map_err(|e| e.to_string())
}

fn value(out: &str, key: &str) -> f64 {
    out.lines()
        .find_map(|l| l.strip_prefix(key))
        .unwrap_or_else(|| panic!("no {key} in {out}"))
        .trim()
        .parse()
        .unwrap()
}

#[test]
fn hypervolume_cli_prints_the_exact_value_and_contributions() {
    // Header, a comment, a dominated point and one outside the reference point.
    let f = temp_file(
        "front2.csv",
        "f1,f2\n# comment\n0.0,0.7\n0.5,0.5\n0.9,0.0\n0.6,0.6\n1.2,0.1\n\n",
    );
    let path = f.to_str().unwrap();
    let out = cli(&[path, "--ref", "1,1"]).unwrap();
    // [0,1)x[0.7,1) + [0.5,1)x[0.5,0.7) + [0.9,1)x[0,0.5) = 0.3 + 0.1 + 0.05
    assert!((value(&out, "hypervolume:") - 0.45).abs() < 1e-15, "{out}");
    assert_eq!(value(&out, "points:"), 5.0);
    assert!(!out.contains("median_time_s"));
    let out = cli(&[path, "--ref", "1,1", "--contributions"]).unwrap();
    let rows: Vec<&str> = out
        .lines()
        .skip_while(|l| *l != "index,contribution")
        .skip(1)
        .collect();
    assert_eq!(rows.len(), 5, "{out}");
    let c: Vec<f64> = rows
        .iter()
        .map(|r| r.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    // (0.5,0.5) alone: [0.5,0.9)x[0.5,0.7) less (0.6,0.6)'s [0.6,0.9)x[0.6,0.7) = 0.08 - 0.03.
    let want = [0.15, 0.05, 0.05, 0.0, 0.0];
    for (g, w) in c.iter().zip(want) {
        assert!((g - w).abs() < 1e-15, "{c:?}");
    }
}

#[test]
fn hypervolume_cli_repeat_prints_a_median_time() {
    let f = temp_file("front3.csv", "0.1,0.5,0.9\n0.5,0.5,0.5\n0.9,0.1,0.1\n");
    let out = cli(&[f.to_str().unwrap(), "--ref", "1,1,1", "--repeat", "5"]).unwrap();
    assert_eq!(value(&out, "repeats:"), 5.0);
    let t = value(&out, "median_time_s:");
    assert!(t > 0.0 && t < 1.0, "{out}");
    assert!(cli(&[f.to_str().unwrap(), "--ref", "1,1,1", "--repeat", "0"]).is_err());
}

#[test]
fn hypervolume_cli_errors_name_file_and_line() {
    let cases = [
        (
            "bad1.csv",
            "0.1,0.2\n0.3,x\n",
            "bad1.csv:2: field 2 = \"x\": not a number",
        ),
        (
            "bad2.csv",
            "0.1,0.2\n\n0.3,inf\n",
            "bad2.csv:3: field 2 = \"inf\": must be finite",
        ),
        (
            "bad3.csv",
            "0.1,0.2\n0.3,NaN\n",
            "bad3.csv:2: field 2 = \"NaN\": must be finite",
        ),
        (
            "bad4.csv",
            "0.1,0.2\n0.3,0.1,0.5\n",
            "bad4.csv:2: 3 fields, but the reference point has 2",
        ),
        (
            "bad5.csv",
            "0.1,0.2\n0.3,\n",
            "bad5.csv:2: field 2 = \"\": not a number",
        ),
        // A one-line text file is no front (it used to give 0 with exit 0).
        (
            "bad6.csv",
            "hello world\n",
            "bad6.csv:1: 1 fields, but the reference point has 2",
        ),
    ];
    for (name, text, want) in cases {
        let f = temp_file(name, text);
        let e = cli(&[f.to_str().unwrap(), "--ref", "1,1"]).unwrap_err();
        assert!(e.contains(want), "{name}: {e}");
    }
    // A reference point of the wrong dimension: the first data line names the mismatch.
    let f = temp_file("ok.csv", "a,b\n0.1,0.2\n");
    let e = cli(&[f.to_str().unwrap(), "--ref", "1,1,1"]).unwrap_err();
    assert!(
        e.contains("ok.csv:2: 2 fields, but the reference point has 3"),
        "{e}"
    );
    let e = cli(&[f.to_str().unwrap(), "--ref", "1,nan"]).unwrap_err();
    assert!(
        e.contains("--ref \"1,nan\": coordinate 2: must be finite"),
        "{e}"
    );
    let e = cli(&[f.to_str().unwrap(), "--ref", "1,,"]).unwrap_err();
    assert!(e.contains("coordinate 2: not a number"), "{e}");
    let e = cli(&["/nonexistent/front.csv", "--ref", "1,1"]).unwrap_err();
    assert!(e.starts_with("/nonexistent/front.csv: cannot read"), "{e}");
    // The binary exits non-zero and says so on stderr.
    let o = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["hypervolume", "/nonexistent/front.csv", "--ref", "1,1"])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("front.csv: cannot read"));
}
