//! The run directory is whole or absent whatever step a writer dies or fails at.

use std::collections::BTreeMap;

use super::*;

type Tree = BTreeMap<String, Vec<u8>>;

fn scratch(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "host-sim-rundir-{tag}-{}-{}",
        std::process::id(),
        SEQ.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = fs::remove_dir_all(&d);
    fs::create_dir_all(&d).unwrap();
    d
}

/// Every regular file under `dir` (relative path -> contents), the marker excluded.
fn tree(dir: &Path) -> Option<Tree> {
    fn walk(root: &Path, dir: &Path, out: &mut Tree) {
        for e in fs::read_dir(dir).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                walk(root, &p, out);
            } else if e.file_name() != MARKER {
                let rel = p.strip_prefix(root).unwrap().to_string_lossy().into_owned();
                out.insert(rel, fs::read(&p).unwrap());
            }
        }
    }
    if !dir.exists() {
        return None;
    }
    let mut t = Tree::new();
    walk(dir, dir, &mut t);
    Some(t)
}

fn run_files(tag: &str) -> Vec<(String, Vec<u8>)> {
    [
        "trajectory.csv",
        "summary.json",
        "plots/a.svg",
        "plots/b.svg",
    ]
    .iter()
    .map(|n| (n.to_string(), format!("{tag} {n}\n").into_bytes()))
    .collect()
}

fn as_tree(files: &[(String, Vec<u8>)]) -> Tree {
    files.iter().cloned().collect()
}

fn write_all(target: &Path, files: &[(String, Vec<u8>)]) {
    let mut rd = RunDir::begin(target).unwrap();
    for (n, c) in files {
        rd.write(n, c).unwrap();
    }
    rd.commit().unwrap();
}

/// A process id that is certainly gone: a child that has been waited for.
fn dead_pid() -> u32 {
    let mut c = std::process::Command::new("true").spawn().unwrap();
    let pid = c.id();
    c.wait().unwrap();
    pid
}

/// Entries of `parent` other than the run directory `name`.
fn leftovers(parent: &Path, name: &str) -> Vec<String> {
    fs::read_dir(parent)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n != name)
        .collect()
}

/// Rename our own leftovers as if their process had died (a killed run's pid is gone).
fn orphan_leftovers(parent: &Path, name: &str, dead: u32) {
    for n in leftovers(parent, name) {
        for mark in [TMP_MARK, OLD_MARK] {
            if let Some((base, pid)) = leftover(&n, mark) {
                assert_eq!(pid, std::process::id());
                let to = parent.join(format!(".{base}{mark}{dead}-9{n}", n = n.len()));
                fs::rename(parent.join(&n), to).unwrap();
            }
        }
    }
}

#[test]
fn fault_at_every_step_leaves_the_previous_run_or_the_new_one_whole() {
    let dead = dead_pid();
    let new = run_files("new");
    // Steps: 0 = right after begin, k = after k files, then the commit's own steps.
    let file_steps = new.len() + 1;
    let commit_steps = [CommitStep::Synced, CommitStep::Swapped];
    for first_run in [false, true] {
        for step in 0..file_steps + commit_steps.len() {
            for fault in [Fault::Fail, Fault::Kill] {
                // A failure after the swap cannot happen (only best-effort removal is left).
                if fault == Fault::Fail && step == file_steps + 1 {
                    continue;
                }
                let parent = scratch("fault");
                let target = parent.join("run");
                let old = run_files("old");
                if !first_run {
                    write_all(&target, &old);
                }
                let before = tree(&target);
                let mut rd = RunDir::begin(&target).unwrap();
                for (n, c) in new.iter().take(step.min(new.len())) {
                    rd.write(n, c).unwrap();
                }
                let case = format!("first_run {first_run}, step {step}, {fault:?}");
                if step < file_steps {
                    match fault {
                        Fault::Fail => drop(rd),
                        Fault::Kill => rd.kill(),
                    }
                } else {
                    let at = commit_steps[step - file_steps];
                    let res = rd
                        .commit_injected(&mut |s| if s == at { Err(fault) } else { Ok(()) })
                        .map(|_| ());
                    assert!(res.is_err(), "{case}: the injected fault is reported");
                }
                let after = tree(&target);
                // The invariant: the previous run (or nothing) or the complete new run.
                assert!(
                    after == before || after == Some(as_tree(&new)),
                    "{case}: mixed run directory {after:?}"
                );
                if step <= file_steps {
                    assert_eq!(
                        after, before,
                        "{case}: the previous run is kept until the swap"
                    );
                }
                if fault == Fault::Fail {
                    assert!(
                        leftovers(&parent, "run").is_empty(),
                        "{case}: a failure cleans up: {:?}",
                        leftovers(&parent, "run")
                    );
                } else {
                    // A killed writer's leftovers are removed by the next run once its
                    // process is gone, and the run directory is not touched by that.
                    orphan_leftovers(&parent, "run", dead);
                    clean_stale(&parent);
                    assert!(
                        leftovers(&parent, "run").is_empty(),
                        "{case}: {:?}",
                        leftovers(&parent, "run")
                    );
                    assert_eq!(tree(&target), after, "{case}");
                }
                // The next run succeeds and is whole.
                write_all(&target, &new);
                assert_eq!(tree(&target), Some(as_tree(&new)), "{case}");
                assert!(leftovers(&parent, "run").is_empty(), "{case}");
                let _ = fs::remove_dir_all(&parent);
            }
        }
    }
}

#[test]
fn stale_leftovers_are_removed_only_when_their_process_is_gone() {
    let parent = scratch("stale");
    let dead = dead_pid();
    let me = std::process::id();
    let stale_dir = parent.join(format!(".run{TMP_MARK}{dead}-0"));
    let stale_file = parent.join(format!(".summary.json{TMP_MARK}{dead}-3"));
    let live = parent.join(format!(".run{TMP_MARK}{me}-999"));
    let other = parent.join(format!(".run.tmp-{dead}"));
    fs::create_dir_all(stale_dir.join("sub")).unwrap();
    fs::write(&stale_file, b"x").unwrap();
    fs::create_dir(&live).unwrap();
    fs::write(&other, b"not ours").unwrap();
    // A previous run moved aside by a run killed mid-swap comes back.
    let old = parent.join(format!(".run{OLD_MARK}{dead}-1"));
    fs::create_dir(&old).unwrap();
    fs::write(old.join("trajectory.csv"), b"old").unwrap();
    assert_eq!(clean_stale(&parent), 3);
    assert!(!stale_dir.exists() && !stale_file.exists() && !old.exists());
    assert!(live.exists(), "a live process's directory is kept");
    assert!(other.exists(), "names of other programs are not touched");
    assert_eq!(fs::read(parent.join("run/trajectory.csv")).unwrap(), b"old");
    let _ = fs::remove_dir_all(&parent);
}

#[test]
fn a_directory_that_is_not_a_run_is_never_replaced() {
    let parent = scratch("foreign");
    let target = parent.join("docs");
    fs::create_dir(&target).unwrap();
    fs::write(target.join("thesis.txt"), b"keep me").unwrap();
    let e = RunDir::begin(&target).unwrap_err().to_string();
    assert!(
        e.contains("docs") && e.contains("not a host-sim run directory"),
        "{e}"
    );
    assert_eq!(fs::read(target.join("thesis.txt")).unwrap(), b"keep me");
    // A file in the way, `..` and an escaping file name are errors naming the path.
    fs::write(parent.join("file"), b"f").unwrap();
    let e = RunDir::begin(&parent.join("file")).unwrap_err().to_string();
    assert!(e.contains("file") && e.contains("not a directory"), "{e}");
    assert!(RunDir::begin(&parent.join("..")).is_err());
    let mut rd = RunDir::begin(&parent.join("run")).unwrap();
    assert!(rd.write("../escape", b"x").is_err());
    drop(rd);
    // An empty directory is taken (and then marked as a run).
    let empty = parent.join("empty");
    fs::create_dir(&empty).unwrap();
    write_all(&empty, &run_files("a"));
    assert!(empty.join(MARKER).is_file());
    let _ = fs::remove_dir_all(&parent);
}

/// The race behind a temporary directory left by Ctrl-C: the handler exits at once when no
/// run is active, so a writer must count as active before its temporary directory exists,
/// and must not start between the handler's check and its exit (the handler holds
/// [`crate::sim::hold_new_runs`] for both).
#[test]
fn no_temporary_directory_appears_while_ctrl_c_decides_to_exit() {
    use std::sync::mpsc::channel;
    let parent = scratch("gate");
    let target = parent.join("run");
    let gate = crate::sim::hold_new_runs();
    let (begun, wait_begun) = channel();
    let (finish, wait_finish) = channel::<()>();
    let writer = {
        let target = target.clone();
        std::thread::spawn(move || {
            let run = RunDir::begin(&target).unwrap();
            begun.send(()).unwrap();
            wait_finish.recv().unwrap();
            drop(run);
        })
    };
    std::thread::sleep(std::time::Duration::from_millis(200));
    assert!(
        leftovers(&parent, "run").is_empty(),
        "a temporary directory appeared while new runs were held: {:?}",
        leftovers(&parent, "run")
    );
    drop(gate);
    wait_begun.recv().unwrap();
    assert_eq!(
        leftovers(&parent, "run").len(),
        1,
        "the writer's temporary directory"
    );
    assert!(
        crate::sim::runs_active(),
        "a writer did not count as an active run"
    );
    finish.send(()).unwrap();
    writer.join().unwrap();
    assert!(leftovers(&parent, "run").is_empty());
    let _ = fs::remove_dir_all(&parent);
}
