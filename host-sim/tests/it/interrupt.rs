//! Ctrl-C (SIGINT) and SIGKILL of the commands that evaluate many flights (issue 24 item 7):
//! an interrupted evaluation is never a result. `optimize` on a re-entry problem stops at a
//! generation boundary, keeps its last checkpoint, writes no final file and exits 130, and
//! `--resume` then gives the uninterrupted run byte for byte (also after a SIGKILL);
//! `sample` writes nothing over the previous samples; `dispersions` writes no summary of a
//! partial campaign. Signals are sent at seeded moments spread over the command's run time.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

type Tree = BTreeMap<String, Vec<u8>>;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_host-sim"))
}

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("host-sim-it-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn tree(dir: &Path) -> Tree {
    fn walk(root: &Path, dir: &Path, out: &mut Tree) {
        for e in std::fs::read_dir(dir).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                walk(root, &p, out);
            } else {
                let rel = p.strip_prefix(root).unwrap().to_string_lossy().into_owned();
                out.insert(rel, std::fs::read(&p).unwrap());
            }
        }
    }
    let mut t = Tree::new();
    walk(dir, dir, &mut t);
    t
}

/// Seeded moments in `[lo, hi)` (xorshift64*).
fn moments(seed: u64, n: usize, lo: Duration, hi: Duration) -> Vec<Duration> {
    let mut s = seed;
    (0..n)
        .map(|_| {
            s ^= s >> 12;
            s ^= s << 25;
            s ^= s >> 27;
            let u = (s.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64;
            lo + (hi - lo).mul_f64(u)
        })
        .collect()
}

/// Start `cmd`, send `signal` after `at`, and return its exit code (`None`: killed).
fn signal_at(mut cmd: Command, at: Duration, signal: &str) -> (Option<i32>, String) {
    let mut child = cmd
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(at);
    let _ = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status();
    let start = Instant::now();
    loop {
        if let Some(_status) = child.try_wait().unwrap() {
            break;
        }
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "no exit within 120 s of {signal}"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    let out = child.wait_with_output().unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

const FINAL: [&str; 5] = [
    "generations.csv",
    "generations.json",
    "population.csv",
    "front.csv",
    "front",
];

fn optimize(out: &Path) -> Command {
    let mut c = bin();
    c.args([
        "optimize",
        "--problem",
        "srm",
        "--population",
        "4",
        "moead",
        "--neighbours",
        "3",
        "--generations",
        "4",
        "--seed",
        "7",
        "--threads",
        "2",
        "--batch-size",
        "2",
        "--out",
    ])
    .arg(out);
    c
}

fn resume(dir: &Path) {
    let out = bin()
        .arg("optimize")
        .arg("--resume")
        .arg(dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "resume: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// `optimize` on the SRM problem (closed-loop flights): SIGINT at 4 seeded moments and
/// SIGKILL at 3, each resumed to the uninterrupted run's files.
#[test]
fn optimize_interrupted_or_killed_resumes_to_the_uninterrupted_run() {
    let root = temp_dir("interrupt-optimize");
    let reference = root.join("ref");
    let t0 = Instant::now();
    assert!(optimize(&reference).status().unwrap().success());
    let wall = t0.elapsed();
    let want = tree(&reference);
    let ats = moments(20_261_201, 7, wall.mul_f64(0.05), wall.mul_f64(0.8));
    let mut stopped = 0;
    for (k, at) in ats.into_iter().enumerate() {
        let signal = if k < 4 { "-INT" } else { "-KILL" };
        let dir = root.join(format!("run{k}"));
        let (code, err) = signal_at(optimize(&dir), at, signal);
        if signal == "-INT" {
            if code == Some(0) {
                continue; // finished before the signal
            }
            assert_eq!(code, Some(130), "SIGINT at {at:?}: {err}");
            if err.contains("interrupted after the run was written") {
                // The signal came after the last file: the run is whole (a loaded machine).
                assert!(
                    tree(&dir) == want,
                    "SIGINT at {at:?} after the run: files differ"
                );
                continue;
            }
            stopped += 1;
            for f in FINAL {
                assert!(!dir.join(f).exists(), "SIGINT at {at:?} wrote {f}: {err}");
            }
        }
        let ck = dir.join("checkpoint.json");
        if ck.exists() {
            let text = std::fs::read_to_string(&ck).unwrap();
            assert!(text.starts_with('{') && text.ends_with('}'), "{ck:?}");
        }
        resume(&dir);
        let got = tree(&dir);
        assert_eq!(
            got.keys().collect::<Vec<_>>(),
            want.keys().collect::<Vec<_>>(),
            "{signal} at {at:?}: files"
        );
        for (f, v) in &want {
            assert!(got[f] == *v, "{signal} at {at:?}: {f} differs");
        }
    }
    assert!(
        stopped >= 2,
        "only {stopped} of 4 SIGINTs arrived during the run"
    );
    std::fs::remove_dir_all(&root).unwrap();
}

/// `sample` interrupted writes nothing: the previous samples.csv is kept as it was.
#[test]
fn sample_interrupted_keeps_the_previous_file() {
    let root = temp_dir("interrupt-sample");
    let out = root.join("samples.csv");
    let cmd = |out: &Path| {
        let mut c = bin();
        c.args([
            "sample",
            "--problem",
            "srm",
            "--count",
            "12",
            "--threads",
            "2",
            "--out",
        ])
        .arg(out);
        c
    };
    let t0 = Instant::now();
    assert!(cmd(&root.join("ref.csv")).status().unwrap().success());
    let wall = t0.elapsed();
    for at in moments(7, 3, wall.mul_f64(0.1), wall.mul_f64(0.8)) {
        std::fs::write(&out, "previous\n").unwrap();
        let (code, err) = signal_at(cmd(&out), at, "-INT");
        if code == Some(0) {
            continue;
        }
        assert_eq!(code, Some(130), "SIGINT at {at:?}: {err}");
        assert_eq!(
            std::fs::read_to_string(&out).unwrap(),
            "previous\n",
            "{at:?}"
        );
    }
    std::fs::remove_dir_all(&root).unwrap();
}

/// `dispersions` interrupted writes no summary (nor statistics files) of a partial campaign;
/// the finished cases are kept, and the same command then completes the campaign.
#[test]
fn dispersions_interrupted_writes_no_summary() {
    let root = temp_dir("interrupt-dispersions");
    let cmd = |out: &Path| {
        let mut c = bin();
        c.args([
            "dispersions",
            "--builtin",
            "srm-glide",
            "-n",
            "6",
            "--interface-speed",
            "2500",
            "--modes",
            "stored",
            "--threads",
            "2",
            "--quiet",
            "--out",
        ])
        .arg(out);
        c
    };
    let t0 = Instant::now();
    let reference = root.join("ref");
    assert!(cmd(&reference).status().unwrap().success());
    let wall = t0.elapsed();
    let summary = std::fs::read(reference.join("summary.json")).unwrap();
    for (k, at) in moments(11, 3, wall.mul_f64(0.1), wall.mul_f64(0.8))
        .into_iter()
        .enumerate()
    {
        let dir = root.join(format!("run{k}"));
        let (code, err) = signal_at(cmd(&dir), at, "-INT");
        if code == Some(0) {
            continue;
        }
        assert_eq!(code, Some(130), "SIGINT at {at:?}: {err}");
        if err.contains("interrupted after the run was written") {
            // The signal came after the last file: the run is whole (a loaded machine).
            assert_eq!(std::fs::read(dir.join("summary.json")).unwrap(), summary);
            continue;
        }
        assert!(!dir.join("summary.json").exists(), "{at:?}: {err}");
        assert!(!dir.join("cases-stored.csv").exists(), "{at:?}");
        assert!(cmd(&dir).status().unwrap().success());
        assert_eq!(std::fs::read(dir.join("summary.json")).unwrap(), summary);
    }
    std::fs::remove_dir_all(&root).unwrap();
}
