//! PIL reliability (issue 8 items 2-4): each test reproduces a defect that was found.
//!
//! * QEMU is stopped on every exit path (error, panic, Ctrl-C, SIGKILL of host-sim), even when
//!   it ignores SIGTERM (as QEMU blocked in a FIFO open does), and the FIFO directory is
//!   removed; a directory of a run whose owner died is removed (its QEMU killed) by the next;
//! * a leftover directory of a dead process with the same pid does not block a run;
//! * every command frame is checked against the configured bounds, rates and tick timing
//!   (alpha 1e300 rad, alpha 90 deg with sigma 180 deg, tick time 1e300 s were flown before);
//! * a bad ELF reports QEMU's exit status and stderr at once, not a 10 s timeout;
//! * a FIFO directory with a space or a path over the firmware's 256 bytes works.
//!
//! The stand-in for QEMU is a shell script (`PilConfig::qemu`, `REENTRY_PIL_QEMU` for the CLI)
//! that ignores SIGTERM/SIGINT and records its pid. Tests that need the real QEMU and firmware
//! skip (pass with a message) when they are absent, unless `PIL_REQUIRED` is set or `CI=true`.

use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use guidance_core::guidance::{Command, RateLimits};
use guidance_core::link::{CommandFrame, FRAME_LEN, Frame, LinkStatus, encode};
use host_sim::pil::{
    FIFO_DIR_PREFIX, FrameViolation, OWNER_FILE, PilConfig, PilError, PilGuidance,
    fly_reference_pil,
};

fn target_dir() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR").map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../target"),
        PathBuf::from,
    )
}

fn pil_elf() -> PathBuf {
    std::env::var_os("PIL_ELF").map_or_else(
        || target_dir().join("thumbv7em-none-eabihf/firmware/pil"),
        PathBuf::from,
    )
}

/// A fresh, empty directory for one test.
fn fresh(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("host-sim-pilrel-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// FIFO directories left in `parent`.
fn leftovers(parent: &Path) -> Vec<String> {
    std::fs::read_dir(parent)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(FIFO_DIR_PREFIX))
        .collect()
}

/// Whether process `pid` still runs (a zombie counts as gone).
fn alive(pid: u32) -> bool {
    std::fs::read_to_string(format!("/proc/{pid}/stat")).is_ok_and(|s| {
        !s.rsplit(')')
            .next()
            .unwrap_or("")
            .trim_start()
            .starts_with('Z')
    })
}

fn wait_for(what: &str, secs: f64, mut f: impl FnMut() -> bool) {
    let t0 = Instant::now();
    while !f() {
        assert!(
            t0.elapsed().as_secs_f64() < secs,
            "timed out waiting for {what}"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// A fake QEMU in `dir`: answers `--version`, writes its pid to `dir/pid`, ignores SIGTERM and
/// SIGINT, then runs `body` (shell, in the FIFO directory) and sleeps.
fn fake_qemu(dir: &Path, body: &str) -> (String, PathBuf) {
    use std::os::unix::fs::PermissionsExt;
    let script = dir.join("fake-qemu.sh");
    let pidfile = dir.join("pid");
    std::fs::write(
        &script,
        format!(
            "#!/bin/sh\n[ \"$1\" = --version ] && exit 0\ntrap '' TERM INT HUP\necho $$ > '{}'\n{body}\nexec sleep 300\n",
            pidfile.display()
        ),
    )
    .unwrap();
    std::fs::set_permissions(&script, std::fs::Permissions::from_mode(0o755)).unwrap();
    (script.display().to_string(), pidfile)
}

fn pid_of(pidfile: &Path) -> u32 {
    wait_for("the fake QEMU's pid", 5.0, || {
        std::fs::read_to_string(pidfile).is_ok_and(|s| s.trim().parse::<u32>().is_ok())
    });
    std::fs::read_to_string(pidfile)
        .unwrap()
        .trim()
        .parse()
        .unwrap()
}

fn config(dir: &Path, qemu: String) -> PilConfig {
    let mut cfg = PilConfig::new(dir.join("fake-qemu.sh"));
    cfg.qemu = qemu;
    cfg.fifo_parent = dir.to_path_buf();
    cfg.reply_timeout = Duration::from_secs(1);
    cfg
}

/// The firmware never opens the link and QEMU ignores SIGTERM: the run times out within the
/// configured time, and QEMU is killed (it was left running before) and the directory removed.
#[test]
fn pil_error_path_kills_qemu_that_ignores_sigterm() {
    let dir = fresh("error");
    let (qemu, pidfile) = fake_qemu(&dir, "");
    let t0 = Instant::now();
    match PilGuidance::start(config(&dir, qemu)) {
        Err(PilError::Timeout(_, what)) => assert!(what.contains("FIFO"), "{what}"),
        Err(e) => panic!("expected a timeout, got {e}"),
        Ok(_) => panic!("expected a timeout, got a link"),
    }
    assert!(t0.elapsed() < Duration::from_secs(5));
    let pid = pid_of(&pidfile);
    wait_for("QEMU to be killed", 3.0, || !alive(pid));
    assert!(leftovers(&dir).is_empty(), "{:?}", leftovers(&dir));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A panic while the link is up (unwinding drops the PIL source): QEMU killed, directory gone.
#[test]
fn pil_panic_path_kills_qemu_and_removes_the_fifos() {
    let dir = fresh("panic");
    let (qemu, pidfile) = fake_qemu(&dir, "exec 3<nav 4>cmd");
    let cfg = config(&dir, qemu);
    let r = std::panic::catch_unwind(move || {
        let pil = PilGuidance::start(cfg).unwrap();
        assert!(pil.fifo_dir().join("nav").exists());
        panic!("deliberate panic with the link up");
    });
    assert!(r.is_err());
    let pid = pid_of(&pidfile);
    wait_for("QEMU to be killed", 3.0, || !alive(pid));
    assert!(leftovers(&dir).is_empty(), "{:?}", leftovers(&dir));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Ctrl-C during `host-sim simulate --pil`: exit 130 at once, QEMU (own process group, ignores
/// SIGINT/SIGTERM) killed, FIFO directory removed, no run directory written.
#[test]
fn pil_ctrl_c_stops_qemu_and_cleans_up() {
    let dir = fresh("ctrlc");
    let (qemu, pidfile) = fake_qemu(&dir, "exec 3<nav 4>cmd");
    let out = dir.join("run");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["simulate", "--quiet", "--pil"])
        .arg(dir.join("fake-qemu.sh"))
        .arg("--out")
        .arg(&out)
        .env("REENTRY_PIL_QEMU", &qemu)
        .env("TMPDIR", &dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let pid = pid_of(&pidfile);
    wait_for("the FIFO directory", 5.0, || !leftovers(&dir).is_empty());
    std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    let t0 = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        assert!(
            t0.elapsed() < Duration::from_secs(10),
            "host-sim ignored Ctrl-C"
        );
        std::thread::sleep(Duration::from_millis(10));
    };
    assert_eq!(status.code(), Some(130));
    wait_for("QEMU to be killed", 3.0, || !alive(pid));
    assert!(leftovers(&dir).is_empty(), "{:?}", leftovers(&dir));
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// SIGKILL of `host-sim simulate --pil` mid-run (no handler runs): its watchdog kills QEMU
/// (which ignores SIGTERM/SIGINT) within seconds and removes the FIFO directory. Before, QEMU
/// stayed blocked for the 600 s wall-time limit and the directory stayed on disk.
#[test]
fn pil_sigkill_of_the_host_stops_qemu_and_cleans_up() {
    let dir = fresh("sigkill");
    let (qemu, pidfile) = fake_qemu(&dir, "exec 3<nav 4>cmd");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["simulate", "--quiet", "--pil"])
        .arg(dir.join("fake-qemu.sh"))
        .arg("--out")
        .arg(dir.join("run"))
        .env("REENTRY_PIL_QEMU", &qemu)
        .env("TMPDIR", &dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let pid = pid_of(&pidfile);
    wait_for("the FIFO directory", 5.0, || !leftovers(&dir).is_empty());
    child.kill().unwrap();
    child.wait().unwrap();
    wait_for("QEMU to be killed", 5.0, || !alive(pid));
    wait_for("the FIFO directory to be removed", 5.0, || {
        leftovers(&dir).is_empty()
    });
    let _ = std::fs::remove_dir_all(&dir);
}

/// Start time of process `pid` (field 22 of `/proc/<pid>/stat`).
fn start_time(pid: u32) -> u64 {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap();
    let rest = stat.rsplit_once(')').unwrap().1;
    rest.split_whitespace().nth(19).unwrap().parse().unwrap()
}

/// A FIFO directory in `parent` with an owner record (the format of `OWNER_FILE`'s docs).
fn owned_dir(parent: &Path, name: &str, host: (u32, u64), watchdog: Option<(u32, u64)>) -> PathBuf {
    let boot = std::fs::read_to_string("/proc/sys/kernel/random/boot_id").unwrap();
    let d = parent.join(format!("{FIFO_DIR_PREFIX}{name}"));
    std::fs::create_dir(&d).unwrap();
    let mut text = format!("boot {}\nhost {} {}\n", boot.trim(), host.0, host.1);
    if let Some((p, s)) = watchdog {
        text.push_str(&format!("watchdog {p} {s}\n"));
    }
    std::fs::write(d.join(OWNER_FILE), text).unwrap();
    std::fs::write(d.join("nav"), b"").unwrap();
    d
}

/// A directory left by a run whose host-sim and watchdog both died (SIGKILL to both), with its
/// QEMU still running in its process group (ignoring SIGTERM): the next run in the same parent
/// kills that QEMU and removes the directory. A directory whose owner runs is left alone, and
/// so is one whose owner pid is now another process (start time differs), but its recorded
/// QEMU pid, now another process too, is not killed. Before, nothing removed them.
#[test]
fn pil_next_run_removes_directories_of_dead_owners() {
    let dir = fresh("stale");
    // A dead host: a process that ran and was reaped.
    let mut gone = std::process::Command::new("true").spawn().unwrap();
    let dead = gone.id();
    gone.wait().unwrap();
    // The stale run's QEMU: its own process group, ignores SIGTERM.
    let mut stale_qemu = std::process::Command::new("sh")
        .args(["-c", "trap '' TERM INT HUP; exec sleep 300"])
        .process_group(0)
        .spawn()
        .unwrap();
    let q = stale_qemu.id();
    wait_for("the stale QEMU to start", 5.0, || {
        std::fs::read_to_string(format!("/proc/{q}/cmdline")).is_ok_and(|c| c.contains("sleep"))
    });
    let stale = owned_dir(
        &dir,
        &format!("{dead}-0"),
        (dead, 1),
        Some((q, start_time(q))),
    );
    // This process's own directory (its owner runs): kept.
    let me = std::process::id();
    let mine = owned_dir(&dir, "mine", (me, start_time(me)), None);
    // An innocent process with the recorded QEMU's pid but another start time: not killed.
    let mut innocent = std::process::Command::new("sleep")
        .arg("300")
        .spawn()
        .unwrap();
    let i = innocent.id();
    let reused = owned_dir(&dir, "reused", (dead, 1), Some((i, start_time(i) + 1)));
    let (qemu, _pidfile) = fake_qemu(&dir, "exec 3<nav 4>cmd");
    let pil = PilGuidance::start(config(&dir, qemu)).unwrap();
    drop(pil);
    let reaped = || stale_qemu.try_wait().unwrap().is_some();
    wait_for("the stale QEMU to be killed", 5.0, reaped);
    assert!(!stale.exists(), "the stale directory is left");
    assert!(!reused.exists(), "the directory of a reused pid is left");
    assert!(mine.exists(), "a live owner's directory was removed");
    assert!(
        alive(i),
        "a process with a recorded pid but another start time was killed"
    );
    innocent.kill().unwrap();
    innocent.wait().unwrap();
    assert_eq!(leftovers(&dir), vec![format!("{FIFO_DIR_PREFIX}mine")]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Leftover directories of a dead process whose pid this process now has do not block a run
/// (it failed with "File exists" before); they are left alone.
#[test]
fn pil_fifo_directory_names_skip_leftovers() {
    let dir = fresh("leftover");
    for n in 0..64 {
        std::fs::create_dir(dir.join(format!("{FIFO_DIR_PREFIX}{}-{n}", std::process::id())))
            .unwrap();
    }
    let (qemu, _pidfile) = fake_qemu(&dir, "exec 3<nav 4>cmd");
    let pil = PilGuidance::start(config(&dir, qemu)).unwrap();
    assert!(pil.fifo_dir().join("cmd").exists());
    drop(pil);
    assert_eq!(leftovers(&dir).len(), 64);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A frame that decodes (valid CRC, status Ok, right sequence) but breaks the configuration.
fn bad_frame(tick_time_s: f64, alpha_rad: f64, sigma_rad: f64) -> [u8; FRAME_LEN] {
    let c = Command {
        alpha_rad,
        sigma_rad,
    };
    let f = CommandFrame {
        seq: 0,
        status: LinkStatus::Ok,
        tick_time_s,
        command: c,
        ramp_start: Command {
            alpha_rad: 40f64.to_radians(),
            sigma_rad: 0.0,
        },
        rates: RateLimits::thesis_default(),
        reversals: 0,
        replans: 0,
    };
    let mut b = [0u8; FRAME_LEN];
    encode(&Frame::Command(f), &mut b).unwrap();
    b
}

/// The frames (alpha 1e300 rad; alpha 90 deg with sigma 180 deg; tick time 1e300 s)
/// each end the run with a typed error; the record keeps the frame, marked.
#[test]
fn pil_rejects_command_frames_outside_the_configuration() {
    let cases = [
        ("alpha1e300", bad_frame(0.0, 1e300, 0.0), "command alpha"),
        (
            "alpha90sigma180",
            bad_frame(0.0, 90f64.to_radians(), 180f64.to_radians()),
            "command alpha",
        ),
        (
            "tick1e300",
            bad_frame(1e300, 40f64.to_radians(), 0.0),
            "tick",
        ),
    ];
    for (name, frame, _) in &cases {
        let dir = fresh(&format!("bad-{name}"));
        let fpath = dir.join("frame.bin");
        std::fs::write(&fpath, frame).unwrap();
        let (qemu, _pid) = fake_qemu(
            &dir,
            &format!("exec 3<nav 4>cmd\ncat '{}' >&4", fpath.display()),
        );
        // The compiled-in reference mission (no set-up): the fake answers the first nav frame.
        let mut pil = PilGuidance::start(config(&dir, qemu)).unwrap();
        let record = pil.record();
        let nav = guidance_core::NavState {
            time_s: 0.0,
            radius_m: 6.5e6,
            speed_m_s: 7500.0,
            flight_path_angle_rad: -0.02,
            heading_rad: 1.0,
            latitude_rad: 0.1,
            longitude_rad: 0.2,
        };
        let r = pil.exchange(&nav);
        drop(pil);
        match r {
            Err(PilError::BadCommand { seq, violation, .. }) => {
                assert_eq!(seq, 0);
                match (name, violation) {
                    (&"tick1e300", FrameViolation::TickTime { tick_time_s, .. }) => {
                        assert_eq!(tick_time_s, 1e300);
                    }
                    (&"tick1e300", v) => panic!("{name}: {v}"),
                    (_, FrameViolation::OutOfBounds { what, .. }) => {
                        assert_eq!(what, "command alpha");
                    }
                    (_, v) => panic!("{name}: {v}"),
                }
            }
            Err(e) => panic!("{name}: expected BadCommand, got {e}"),
            Ok(_) => panic!("{name}: a bad frame was accepted"),
        }
        let ex = record.exchanges();
        assert_eq!(ex.len(), 1);
        assert!(ex[0].reply.is_some());
        assert!(
            ex[0]
                .failure
                .as_deref()
                .is_some_and(|f| f.contains("rejected"))
        );
        assert!(record.to_csv().lines().nth(1).unwrap().contains("rejected"));
        assert!(leftovers(&dir).is_empty());
        let _ = std::fs::remove_dir_all(&dir);
    }
}

fn qemu_present() -> bool {
    std::process::Command::new(onboard_spec::machines::QEMU_SYSTEM)
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

fn skip(test: &str, why: &str) -> bool {
    assert!(
        !crate::pil_support::pil_required(),
        "{test}: {why} (PIL required: PIL_REQUIRED or CI=true)"
    );
    println!("SKIPPED {test}: {why}");
    true
}

/// A bad ELF (`/bin/true`, an empty file, the instruction-count firmware that never opens the
/// link): QEMU's exit status and output are reported at once (it waited 10 s before).
#[test]
fn pil_bad_elf_reports_qemu_exit_at_once() {
    if !qemu_present() && skip("pil_bad_elf_reports_qemu_exit_at_once", "no QEMU") {
        return;
    }
    let dir = fresh("badelf");
    let empty = dir.join("empty.elf");
    std::fs::write(&empty, b"").unwrap();
    let bench = pil_elf().with_file_name("insn-bench");
    let mut elves = vec![PathBuf::from("/bin/true"), empty];
    if bench.is_file() {
        elves.push(bench);
    }
    for elf in elves {
        let mut cfg = PilConfig::new(elf.clone());
        cfg.fifo_parent = dir.clone();
        let t0 = Instant::now();
        match fly_reference_pil(cfg) {
            Err(PilError::QemuExited(e)) => {
                println!("{}: {e}", elf.display());
                assert!(!e.stderr.is_empty() || !e.stdout.is_empty(), "{e}");
            }
            other => panic!("{}: expected QemuExited, got {other:?}", elf.display()),
        }
        assert!(t0.elapsed() < Duration::from_secs(5), "{:?}", t0.elapsed());
        assert!(leftovers(&dir).is_empty());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The reference mission in PIL with a FIFO directory whose path has a space and one longer
/// than the firmware's 256-byte path limit (both failed before).
#[test]
fn pil_fifo_directory_with_space_or_long_path() {
    if !(qemu_present() && pil_elf().is_file())
        && skip(
            "pil_fifo_directory_with_space_or_long_path",
            "no QEMU or PIL ELF",
        )
    {
        return;
    }
    let dir = fresh("paths");
    let spaced = dir.join("with a space");
    let long = dir.join("l".repeat(200)).join("m".repeat(100));
    for parent in [spaced, long] {
        std::fs::create_dir_all(&parent).unwrap();
        let mut cfg = PilConfig::new(pil_elf());
        cfg.fifo_parent = parent.clone();
        let (res, stats) = fly_reference_pil(cfg).unwrap_or_else(|e| {
            panic!(
                "{} ({} bytes): {e}",
                parent.display(),
                parent.as_os_str().len()
            )
        });
        assert!(stats.frames > 600);
        assert!(res.summary.flight_time_s > 1000.0);
        assert!(leftovers(&parent).is_empty());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 13 item 5, "nothing lost from the record", through the CLI: a PIL run that fails
/// mid-flight (the fake firmware accepts the set-up, then answers the first nav frame with a
/// command outside the configuration) exits with the error, writes no run directory, and keeps
/// the frames exchanged up to the failure beside it as `<out>.failed-pil-record.csv`, the
/// failing row marked.
#[test]
fn pil_cli_keeps_the_record_of_a_failed_run() {
    let dir = fresh("cli-record");
    let (items, _) =
        host_sim::pil::scenario_setup(&host_sim::scenario::Scenario::default(), "(test)").unwrap();
    let mut answers = Vec::new();
    for seq in 0..items.len() {
        let ok = CommandFrame {
            seq: u32::try_from(seq).unwrap(),
            status: LinkStatus::Ok,
            tick_time_s: 0.0,
            command: Command {
                alpha_rad: 0.0,
                sigma_rad: 0.0,
            },
            ramp_start: Command {
                alpha_rad: 0.0,
                sigma_rad: 0.0,
            },
            rates: RateLimits::thesis_default(),
            reversals: 0,
            replans: 0,
        };
        let mut b = [0u8; FRAME_LEN];
        encode(&Frame::Command(ok), &mut b).unwrap();
        answers.extend_from_slice(&b);
    }
    let mut bad = bad_frame(0.0, 1e300, 0.0);
    // The nav frame's sequence number follows the set-up's (re-sealed by re-encoding).
    let Frame::Command(mut c) = guidance_core::link::decode(&bad).unwrap() else {
        panic!("bad_frame is a command frame");
    };
    c.seq = u32::try_from(items.len()).unwrap();
    encode(&Frame::Command(c), &mut bad).unwrap();
    answers.extend_from_slice(&bad);
    let answers_path = dir.join("answers.bin");
    std::fs::write(&answers_path, &answers).unwrap();
    let (qemu, _pid) = fake_qemu(
        &dir,
        &format!("exec 3<nav 4>cmd\ncat '{}' >&4", answers_path.display()),
    );
    let out_dir = dir.join("run");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["simulate", "--pil"])
        .arg(dir.join("fake-qemu.sh"))
        .arg("--out")
        .arg(&out_dir)
        .env("REENTRY_PIL_QEMU", &qemu)
        .env("TMPDIR", &dir)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{stdout}{stderr}");
    assert!(stderr.contains("rejected"), "{stderr}");
    assert!(stdout.contains("failed-pil-record.csv"), "{stdout}");
    assert!(!out_dir.exists(), "no run directory for a failed run");
    let csv = std::fs::read_to_string(dir.join("run.failed-pil-record.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows.len(), 2, "{csv}");
    assert!(rows[0].starts_with("seq,time_s,"), "{csv}");
    assert!(
        rows[1].starts_with(&format!("{},", items.len())) && rows[1].contains("rejected"),
        "{csv}"
    );
    assert!(leftovers(&dir).is_empty());
    let _ = std::fs::remove_dir_all(&dir);
}
