//! Run directories are whole or absent at the process level: `host-sim simulate` is killed
//! (SIGKILL) at spread-out moments while it replaces a previous run, and interrupted with
//! SIGINT (Ctrl-C); the output directory must always be exactly the previous run or exactly
//! the new one, and leftovers of killed runs are removed by the next run.

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

/// The files of a run directory (relative path -> contents), or `None` if it is absent.
fn tree(dir: &Path) -> Option<Tree> {
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
    dir.exists().then(|| {
        let mut t = Tree::new();
        walk(dir, dir, &mut t);
        t
    })
}

fn simulate(builtin: &str, out: &Path) -> Command {
    let mut c = bin();
    c.args(["simulate", "--quiet", "--builtin", builtin, "--out"])
        .arg(out)
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    c
}

/// Reference runs of the two missions (previous run: HORUS-2B; new run: SRM glide) and the
/// wall time of the new one.
fn references(root: &Path) -> (Tree, Tree, Duration) {
    let a = root.join("ref-horus");
    assert!(
        simulate("horus-2b-reference", &a)
            .status()
            .unwrap()
            .success()
    );
    let b = root.join("ref-srm");
    let t0 = Instant::now();
    assert!(simulate("srm-glide", &b).status().unwrap().success());
    (tree(&a).unwrap(), tree(&b).unwrap(), t0.elapsed())
}

/// Entries next to the run directory other than it (temporary directories of killed runs).
fn siblings(parent: &Path) -> Vec<String> {
    std::fs::read_dir(parent)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n != "run")
        .collect()
}

#[test]
fn sigkill_at_any_moment_leaves_the_previous_run_or_the_new_one_whole() {
    let root = temp_dir("kill");
    let (old, new, wall) = references(&root);
    assert_ne!(old, new);
    // Kill moments spread over 0..1.3 of the run's wall time (a fixed sequence: the
    // machine's load decides where each lands, the invariant must hold everywhere).
    let n = 24;
    let (mut absent, mut kept, mut replaced) = (0, 0, 0);
    for k in 0..n {
        let parent = root.join(format!("k{k}"));
        std::fs::create_dir_all(&parent).unwrap();
        let target = parent.join("run");
        let fresh = k % 3 == 2;
        if !fresh {
            assert!(
                simulate("horus-2b-reference", &target)
                    .status()
                    .unwrap()
                    .success()
            );
        }
        let mut child = simulate("srm-glide", &target).spawn().unwrap();
        std::thread::sleep(wall.mul_f64(1.3 * f64::from(k) / f64::from(n)));
        let _ = child.kill();
        let _ = child.wait();
        let after = tree(&target);
        match &after {
            None => {
                assert!(fresh, "kill {k}: the previous run disappeared");
                absent += 1;
            }
            Some(t) if *t == new => replaced += 1,
            Some(t) if *t == old && !fresh => kept += 1,
            Some(t) => panic!(
                "kill {k}: a mixed or partial run directory: {:?}",
                t.keys().collect::<Vec<_>>()
            ),
        }
        // The next run removes what the killed one left and is whole.
        assert!(simulate("srm-glide", &target).status().unwrap().success());
        assert_eq!(tree(&target).as_ref(), Some(&new), "kill {k}");
        assert!(
            siblings(&parent).is_empty(),
            "kill {k}: {:?}",
            siblings(&parent)
        );
    }
    eprintln!("{n} kills: {kept} kept the previous run, {replaced} replaced it, {absent} absent");
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn ctrl_c_stops_the_run_and_keeps_the_previous_one() {
    let root = temp_dir("sigint");
    let (old, new, wall) = references(&root);
    let target = root.join("run");
    assert!(
        simulate("horus-2b-reference", &target)
            .status()
            .unwrap()
            .success()
    );
    let mut interrupted = 0;
    for k in 1..=8 {
        let child = simulate("srm-glide", &target).spawn().unwrap();
        std::thread::sleep(wall.mul_f64(0.04 * f64::from(k)));
        let pid = child.id().to_string();
        let _ = Command::new("kill").args(["-INT", &pid]).status();
        let o = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&o.stderr);
        let after = tree(&target);
        match o.status.code() {
            Some(130) => {
                interrupted += 1;
                assert!(stderr.contains("interrupted"), "{stderr}");
                assert!(
                    after.as_ref() == Some(&old) || after.as_ref() == Some(&new),
                    "attempt {k}: mixed run directory"
                );
            }
            Some(0) => assert_eq!(after.as_ref(), Some(&new), "attempt {k}"),
            other => panic!("attempt {k}: exit {other:?}: {stderr}"),
        }
        if after.as_ref() == Some(&old) && o.status.code() == Some(130) {
            assert!(
                stderr.contains("no run directory written"),
                "attempt {k}: {stderr}"
            );
        }
        assert!(
            siblings(&root).iter().all(|n| n.starts_with("ref-")),
            "{:?}",
            siblings(&root)
        );
        // Back to the previous run for the next attempt.
        assert!(
            simulate("horus-2b-reference", &target)
                .status()
                .unwrap()
                .success()
        );
    }
    assert!(interrupted > 0, "no attempt was interrupted mid-run");
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn ctrl_c_stops_a_long_optimisation_without_writing() {
    let root = temp_dir("sigint-optimize");
    let out = root.join("opt");
    let child = bin()
        .args(["optimize", "--problem", "zdt1", "nsga2"])
        .args(["--generations", "100000000", "--out"])
        .arg(&out)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(300));
    let _ = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status();
    let o = child.wait_with_output().unwrap();
    assert_eq!(
        o.status.code(),
        Some(130),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn an_output_path_that_is_a_file_or_a_foreign_directory_is_left_alone() {
    let root = temp_dir("foreign-out");
    let file = root.join("notes.txt");
    std::fs::write(&file, b"mine").unwrap();
    let o = simulate("srm-glide", &file).output().unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("notes.txt"));
    assert_eq!(std::fs::read(&file).unwrap(), b"mine");
    let dir = root.join("home");
    std::fs::create_dir(&dir).unwrap();
    std::fs::write(dir.join("thesis.tex"), b"keep").unwrap();
    let o = simulate("srm-glide", &dir).output().unwrap();
    assert_eq!(o.status.code(), Some(1));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("not a host-sim run directory"), "{e}");
    assert_eq!(std::fs::read(dir.join("thesis.tex")).unwrap(), b"keep");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn compare_output_is_one_run_directory_replaced_whole() {
    let root = temp_dir("compare-whole");
    let out = root.join("cmp");
    let compare = |trajectories: bool| {
        let mut c = bin();
        c.args(["compare", "--phase", "glide", "--altitudes-km", "60"])
            .args([
                "--cl-vertical",
                "0.3",
                "--environments",
                "simplified",
                "--out",
            ])
            .arg(&out)
            .stdout(Stdio::null())
            .stderr(Stdio::null());
        if trajectories {
            c.arg("--trajectories");
        }
        assert!(c.status().unwrap().success());
        tree(&out).unwrap()
    };
    let with = compare(true);
    assert!(
        with.contains_key("point_0/analytic/trajectory.csv"),
        "{:?}",
        with.keys()
    );
    // A later run without trajectories replaces the directory: no stale point_0 beside the
    // new grid.
    let without = compare(false);
    assert!(
        without.keys().all(|k| !k.starts_with("point_")),
        "{:?}",
        without.keys()
    );
    assert_eq!(without.get("grid.csv"), with.get("grid.csv"));
    assert!(
        siblings(&root).iter().all(|n| n == "cmp"),
        "{:?}",
        siblings(&root)
    );
    let _ = std::fs::remove_dir_all(&root);
}
