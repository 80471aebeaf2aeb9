//! Resume and run-directory robustness of re-entry `optimize` (issue 24 item 5): generations
//! with no feasible member (NaN best and mean), the front directory written whole, fronts
//! without repeated members, the run marker.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::cli::run as cli_run;

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("host-sim-resume-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn optimize(extra: &[&str]) -> Result<String, crate::cli::CliError> {
    let mut args = vec!["host-sim", "optimize"];
    args.extend_from_slice(extra);
    let mut out = Vec::new();
    cli_run(args, &mut out)?;
    Ok(String::from_utf8(out).unwrap_or_default())
}

/// Every file under `dir` (relative path -> contents), the checkpoint and config aside.
fn tree(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    fn walk(root: &Path, d: &Path, out: &mut BTreeMap<String, Vec<u8>>) {
        for e in std::fs::read_dir(d).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                walk(root, &p, out);
            } else {
                let rel = p.strip_prefix(root).unwrap().display().to_string();
                out.insert(rel, std::fs::read(&p).unwrap());
            }
        }
    }
    let mut m = BTreeMap::new();
    walk(dir, dir, &mut m);
    m.remove("checkpoint.json");
    m.remove("config.toml");
    m
}

/// The SRM analytical problem (fast) with a g-load limit of 1.2: with seed 3 (SCEA: 8) no
/// member of generations 0 and 1 is feasible (best and mean NaN), later ones are.
fn infeasible_start_config(dir: &Path, algorithm: &str, generations: u64) -> PathBuf {
    let mut c = super::optimize_reentry::ReentryRunConfig::thesis("srm-analytical").unwrap();
    c.algorithm = algorithm.into();
    c.population = 8;
    c.generations = generations;
    c.seed = if algorithm == "scea" { 8 } else { 3 };
    c.neighbours = 4;
    c.mutation_probability = None;
    c.problem.limits.g_load = 1.2;
    std::fs::create_dir_all(dir).unwrap();
    let p = dir.join(format!("{algorithm}-{generations}.toml"));
    std::fs::write(&p, toml::to_string(&c).unwrap()).unwrap();
    p
}

/// Every algorithm: a run whose first generations have no feasible member, interrupted after
/// generation 1 and resumed to 5, writes the uninterrupted run's files, byte for byte,
/// and no other file (the front directory of the 1-generation run is replaced whole).
#[test]
fn resume_after_infeasible_generations_gives_the_uninterrupted_run() {
    let base = tmp("nan");
    for algorithm in ["moead", "nsga2", "mhaco", "mhaco-objectives", "scea"] {
        let (a, b) = (
            base.join(format!("{algorithm}-a")),
            base.join(format!("{algorithm}-b")),
        );
        let full = infeasible_start_config(&base, algorithm, 5);
        let short = infeasible_start_config(&base, algorithm, 1);
        optimize(&[
            "--config",
            full.to_str().unwrap(),
            "--out",
            a.to_str().unwrap(),
        ])
        .unwrap();
        optimize(&[
            "--config",
            short.to_str().unwrap(),
            "--out",
            b.to_str().unwrap(),
        ])
        .unwrap();
        let first = std::fs::read_to_string(b.join("generations.csv")).unwrap();
        assert!(
            first.contains("NaN"),
            "{algorithm}: no infeasible generation:\n{first}"
        );
        optimize(&["--resume", b.to_str().unwrap(), "--generations", "5"])
            .unwrap_or_else(|e| panic!("{algorithm}: resume failed: {e}"));
        let (ta, tb) = (tree(&a), tree(&b));
        assert_eq!(
            ta.keys().collect::<Vec<_>>(),
            tb.keys().collect::<Vec<_>>(),
            "{algorithm}: the resumed run's files"
        );
        for (k, v) in &ta {
            assert!(tb[k] == *v, "{algorithm}: {k} differs");
        }
        let json = std::fs::read_to_string(a.join("generations.json")).unwrap();
        assert!(json.contains("\"NaN\""), "{algorithm}: {json}");
    }
    std::fs::remove_dir_all(&base).unwrap();
}

/// `optimize --out` on a re-entry problem keeps the run marker's promise: a directory that is
/// not a run is refused and left as it was; a new run into an old run's directory leaves none
/// of the old run's files (populations of later generations, front members).
#[test]
fn a_new_run_respects_the_marker_and_replaces_an_old_run_whole() {
    let base = tmp("marker");
    let foreign = base.join("mine");
    std::fs::create_dir_all(&foreign).unwrap();
    std::fs::write(foreign.join("notes.txt"), "keep me").unwrap();
    let cfg = infeasible_start_config(&base, "moead", 5);
    let e = optimize(&[
        "--config",
        cfg.to_str().unwrap(),
        "--out",
        foreign.to_str().unwrap(),
    ])
    .unwrap_err()
    .to_string();
    assert!(e.contains("not a host-sim run directory"), "{e}");
    assert_eq!(
        std::fs::read_to_string(foreign.join("notes.txt")).unwrap(),
        "keep me"
    );
    assert_eq!(std::fs::read_dir(&foreign).unwrap().count(), 1);
    let run = base.join("run");
    optimize(&[
        "--config",
        cfg.to_str().unwrap(),
        "--out",
        run.to_str().unwrap(),
    ])
    .unwrap();
    assert!(run.join("population/gen_0005.csv").is_file());
    let short = infeasible_start_config(&base, "nsga2", 1);
    optimize(&[
        "--config",
        short.to_str().unwrap(),
        "--out",
        run.to_str().unwrap(),
    ])
    .unwrap();
    let fresh = base.join("fresh");
    optimize(&[
        "--config",
        short.to_str().unwrap(),
        "--out",
        fresh.to_str().unwrap(),
    ])
    .unwrap();
    let (t_run, t_fresh) = (tree(&run), tree(&fresh));
    assert_eq!(
        t_run.keys().collect::<Vec<_>>(),
        t_fresh.keys().collect::<Vec<_>>()
    );
    std::fs::remove_dir_all(&base).unwrap();
}

/// front.csv and the recorded fronts hold each member once, even when the population holds
/// copies of one individual.
#[test]
fn fronts_have_no_repeated_members() {
    use crate::optim::Individual;
    let ind = |x: f64, f: [f64; 2]| Individual {
        decision: vec![x],
        objectives: f.to_vec(),
        constraints: vec![-1.0],
        violation: 0.0,
    };
    let pop = vec![
        ind(0.1, [0.0, 1.0]),
        ind(0.1, [0.0, 1.0]),
        ind(0.2, [1.0, 0.0]),
        ind(0.3, [1.0, 0.0]),
        ind(0.2, [1.0, 0.0]),
    ];
    let r = crate::optim::run::record_of(0, 5, &pop, &pop, &[2.0, 2.0]);
    assert_eq!(r.front, vec![vec![0.0, 1.0], vec![1.0, 0.0]]);
    let dir = tmp("dedup");
    std::fs::create_dir_all(&dir).unwrap();
    let c = super::optimize_reentry::ReentryRunConfig::thesis("srm-analytical").unwrap();
    let scenarios = vec![None; pop.len()];
    crate::design::run::files::write_final(
        &dir,
        &scenarios,
        &pop,
        &pop,
        &[r],
        &c.problem.base,
        &crate::design::run::files::MemberFlights {
            analytical: None,
            robust: None,
            objectives: &crate::design::Objectives::default(),
            threads: &crate::optim::Threads::serial(),
            nominal_front: &[],
        },
    )
    .unwrap();
    let front = std::fs::read_to_string(dir.join("front.csv")).unwrap();
    let rows: Vec<&str> = front.lines().skip(1).collect();
    assert_eq!(rows.len(), 3, "{front}");
    let unique: std::collections::BTreeSet<&&str> = rows.iter().collect();
    assert_eq!(unique.len(), rows.len(), "{front}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A seeded corruption of a JSON value: one leaf or container replaced by a hostile value,
/// an array shortened or lengthened, or a key removed.
fn corrupt(v: &mut serde_json::Value, rng: &mut u64) {
    use serde_json::{Value, json};
    let mut next = |n: usize| {
        *rng ^= *rng << 13;
        *rng ^= *rng >> 7;
        *rng ^= *rng << 17;
        (*rng % n as u64) as usize
    };
    // Collect the paths of every node, then pick one.
    fn paths(v: &Value, at: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
        out.push(at.clone());
        match v {
            Value::Object(m) => {
                for (k, x) in m {
                    at.push(k.clone());
                    paths(x, at, out);
                    at.pop();
                }
            }
            Value::Array(a) => {
                for (i, x) in a.iter().enumerate() {
                    at.push(i.to_string());
                    paths(x, at, out);
                    at.pop();
                }
            }
            _ => {}
        }
    }
    let mut all = Vec::new();
    paths(v, &mut Vec::new(), &mut all);
    let path = all[1 + next(all.len() - 1)].clone();
    let (last, parent) = path.split_last().unwrap();
    let mut p = &mut *v;
    for k in parent {
        p = match p {
            Value::Object(m) => m.get_mut(k).unwrap(),
            Value::Array(a) => &mut a[k.parse::<usize>().unwrap()],
            _ => unreachable!(),
        };
    }
    let hostile = [
        json!(0),
        json!(-1),
        json!(999),
        json!(1_000_000),
        json!(1e300),
        json!(-1e300),
        json!(0.5),
        json!("NaN"),
        json!("inf"),
        json!("x"),
        Value::Null,
        json!([]),
        json!({}),
        json!(true),
    ];
    let pick = next(hostile.len() + 3);
    match p {
        Value::Object(m) if pick == hostile.len() => {
            m.remove(last);
        }
        Value::Array(a) if pick >= hostile.len() => {
            let i: usize = last.parse().unwrap();
            if pick == hostile.len() {
                a.remove(i);
            } else {
                let x = a[i].clone();
                a.insert(i, x);
            }
        }
        Value::Object(m) => {
            m.insert(last.clone(), hostile[pick % hostile.len()].clone());
        }
        Value::Array(a) => {
            a[last.parse::<usize>().unwrap()] = hostile[pick % hostile.len()].clone();
        }
        _ => unreachable!(),
    }
}

/// Integers too large for `serde_json::Value` (the generator's `u128` state) as strings
/// `"BIG<digits>"`, so that a corruption elsewhere leaves them exact.
fn protect_big(text: &str) -> String {
    let mut out = String::new();
    let mut digits = String::new();
    let flush = |digits: &mut String, out: &mut String| {
        if digits.len() > 18 {
            out.push_str(&format!("\"BIG{digits}\""));
        } else {
            out.push_str(digits);
        }
        digits.clear();
    };
    let mut prev = ' ';
    for ch in text.chars() {
        if ch.is_ascii_digit() && (!digits.is_empty() || matches!(prev, ':' | ',' | '[')) {
            digits.push(ch);
        } else {
            if !digits.is_empty() {
                if matches!(ch, '.' | 'e' | 'E') {
                    out.push_str(&digits);
                    digits.clear();
                } else {
                    flush(&mut digits, &mut out);
                }
            }
            out.push(ch);
        }
        prev = ch;
    }
    flush(&mut digits, &mut out);
    out
}

/// The inverse of [`protect_big`].
fn restore_big(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(at) = rest.find("\"BIG") {
        out.push_str(&rest[..at]);
        let tail = &rest[at + 4..];
        let end = tail.find('"').unwrap();
        out.push_str(&tail[..end]);
        rest = &tail[end + 1..];
    }
    out.push_str(rest);
    out
}

/// 100 seeded corruptions of real checkpoints (MOEA/D with batches of 3, NSGA-II, MHACO,
/// SCEA): `--resume` never panics or hangs; it resumes, or its error names the checkpoint
/// and a field.
#[test]
fn corrupt_checkpoints_give_an_error_naming_a_field_or_a_valid_resume() {
    let base = tmp("corrupt");
    let mut sources = Vec::new();
    for algorithm in ["moead", "nsga2", "mhaco", "scea"] {
        let cfg = infeasible_start_config(&base, algorithm, 1);
        let mut text = std::fs::read_to_string(&cfg).unwrap();
        if algorithm == "moead" {
            text = text.replace("batch_size = 1", "batch_size = 3");
            std::fs::write(&cfg, &text).unwrap();
        }
        let dir = base.join(format!("src-{algorithm}"));
        optimize(&[
            "--config",
            cfg.to_str().unwrap(),
            "--out",
            dir.to_str().unwrap(),
        ])
        .unwrap();
        let text = std::fs::read_to_string(dir.join("checkpoint.json")).unwrap();
        let ck: serde_json::Value = serde_json::from_str(&protect_big(&text)).unwrap();
        sources.push((dir, ck));
    }
    let (mut resumed, mut refused) = (0, 0);
    let mut rng = 0x9E37_79B9_7F4A_7C15_u64;
    for case in 0..100 {
        let (src, ck) = &sources[case % sources.len()];
        let mut bad = ck.clone();
        corrupt(&mut bad, &mut rng);
        let dir = base.join(format!("case{case}"));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::copy(src.join("config.toml"), dir.join("config.toml")).unwrap();
        std::fs::write(dir.join("checkpoint.json"), restore_big(&bad.to_string())).unwrap();
        let d = dir.clone();
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let r = std::panic::catch_unwind(|| {
                optimize(&["--resume", d.to_str().unwrap(), "--generations", "2"])
                    .map_err(|e| e.to_string())
            });
            let _ = tx.send(r);
        });
        let r = rx
            .recv_timeout(std::time::Duration::from_secs(120))
            .unwrap_or_else(|_| panic!("case {case}: no answer in 120 s (hang)"));
        match r {
            Err(_) => panic!("case {case}: panicked"),
            Ok(Ok(_)) => resumed += 1,
            Ok(Err(e)) => {
                assert!(
                    e.contains("checkpoint.json") && e.contains("field `"),
                    "case {case}: {e}"
                );
                refused += 1;
            }
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
    assert!(refused > 50, "{refused} refused, {resumed} resumed");
    std::fs::remove_dir_all(&base).unwrap();
}

fn cli(args: &[&str]) -> Result<String, String> {
    let mut out = Vec::new();
    cli_run(args.iter().copied(), &mut out).map_err(|e| e.to_string())?;
    Ok(String::from_utf8(out).unwrap_or_default())
}

/// Sizes without bounds are refused with an error naming the option, before anything is
/// allocated (they used to abort on allocation or hang building a thread pool), and a small
/// MOEA/D population runs without `--neighbours` (the default adapts).
#[test]
fn sizes_without_bounds_are_refused_naming_the_option() {
    let base = tmp("sizes");
    let out = base.join("o");
    let o = out.to_str().unwrap();
    let csv = base.join("s.csv");
    for (args, name) in [
        (
            vec![
                "host-sim",
                "optimize",
                "--problem",
                "srm-analytical",
                "--population",
                "1000000000",
                "--out",
                o,
            ],
            "population",
        ),
        (
            vec![
                "host-sim",
                "optimize",
                "--problem",
                "zdt1",
                "--population",
                "1000000000",
                "--out",
                o,
            ],
            "population",
        ),
        (
            vec![
                "host-sim",
                "optimize",
                "--problem",
                "zdt1",
                "--threads",
                "100000",
                "--out",
                o,
            ],
            "--threads",
        ),
        (
            vec![
                "host-sim",
                "sample",
                "--problem",
                "srm",
                "--threads",
                "100000",
                "--out",
                csv.to_str().unwrap(),
            ],
            "--threads",
        ),
        (
            vec![
                "host-sim",
                "sample",
                "--problem",
                "srm",
                "--count",
                "1000000000",
                "--out",
                csv.to_str().unwrap(),
            ],
            "--count",
        ),
        (
            vec![
                "host-sim",
                "dispersions",
                "--builtin",
                "srm-glide",
                "-n",
                "1000000000",
                "--quiet",
                "--out",
                o,
            ],
            "cases",
        ),
        (
            vec![
                "host-sim",
                "dispersions",
                "--builtin",
                "srm-glide",
                "-n",
                "2",
                "--threads",
                "100000",
                "--quiet",
                "--out",
                o,
            ],
            "threads",
        ),
    ] {
        let e = cli(&args).unwrap_err();
        assert!(e.contains(name), "{args:?}: {e}");
        assert!(!csv.exists(), "{args:?}");
    }
    let said = cli(&[
        "host-sim",
        "optimize",
        "--problem",
        "srm-analytical",
        "--population",
        "8",
        "--generations",
        "1",
        "--out",
        o,
    ])
    .unwrap();
    assert!(said.contains("generation 1"), "{said}");
    assert!(
        std::fs::read_to_string(out.join("config.toml"))
            .unwrap()
            .contains("neighbours = 7")
    );
    let e = cli(&[
        "host-sim",
        "optimize",
        "--problem",
        "srm-analytical",
        "--population",
        "8",
        "moead",
        "--neighbours",
        "20",
        "--generations",
        "1",
        "--out",
        o,
    ])
    .unwrap_err();
    assert!(e.contains("--neighbours"), "{e}");
    let _ = std::fs::remove_dir_all(&base);
}

/// `--resume` with other flags is refused naming them (they used to be ignored silently): the
/// common flags by clap, an algorithm subcommand because the run file decides;
/// `--generations` extends the run.
#[test]
fn resume_with_other_flags_names_them() {
    let base = tmp("resume-flags");
    let cfg = infeasible_start_config(&base, "moead", 1);
    let run = base.join("r");
    let r = run.to_str().unwrap();
    optimize(&["--config", cfg.to_str().unwrap(), "--out", r]).unwrap();
    for (flags, named) in [
        (
            &["--population", "16", "--seed", "9"][..],
            &["--population <POPULATION>", "--seed <SEED>"][..],
        ),
        (&["--out", "elsewhere"][..], &["--out <DIR>"][..]),
    ] {
        let mut v = vec!["--resume", r];
        v.extend(flags);
        let e = optimize(&v).unwrap_err();
        let crate::cli::CliError::Usage(c) = &e else {
            panic!("{e}")
        };
        assert_eq!(c.exit_code(), 2);
        let e = e.to_string();
        assert!(e.contains("'--resume <DIR>' cannot be used with"), "{e}");
        for flag in named {
            assert!(e.contains(flag), "{e}");
        }
    }
    let e = optimize(&["--resume", r, "moead", "--neighbours", "3"])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("`optimize moead` with --config or --resume: the run file decides"),
        "{e}"
    );
    optimize(&["--resume", r, "--generations", "2"]).unwrap();
    std::fs::remove_dir_all(&base).unwrap();
}

/// `dispersions`: a stored case file with a value no flight gives is refused naming the file
/// and the field (a miss of -1e300 gave `std: null`), and a settings file without
/// `[dispersions]` is refused instead of running the defaults.
#[test]
fn dispersions_refuse_bad_stored_cases_and_settings_without_the_section() {
    let base = tmp("disp");
    let out = base.join("c");
    let o = out.to_str().unwrap();
    let args = [
        "host-sim",
        "dispersions",
        "--builtin",
        "srm-glide",
        "-n",
        "2",
        "--interface-speed",
        "2500",
        "--modes",
        "stored",
        "--threads",
        "1",
        "--quiet",
        "--out",
        o,
    ];
    cli(&args).unwrap();
    let case = out.join("cases/stored/000001.json");
    let text = std::fs::read_to_string(&case).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["miss_m"] = serde_json::json!(-1e300);
    std::fs::write(&case, v.to_string()).unwrap();
    let e = cli(&args).unwrap_err();
    assert!(
        e.contains("000001.json") && e.contains("field `miss_m` = -1e300"),
        "{e}"
    );
    let settings = base.join("s.toml");
    std::fs::write(&settings, "[dispersion]\ncases = 3\n").unwrap();
    let e = cli(&[
        "host-sim",
        "dispersions",
        "--builtin",
        "srm-glide",
        "--settings",
        settings.to_str().unwrap(),
        "--quiet",
        "--out",
        base.join("d").to_str().unwrap(),
    ])
    .unwrap_err();
    assert!(e.contains("dispersion"), "{e}");
    std::fs::write(&settings, "seed = 3\n").unwrap();
    let e = cli(&[
        "host-sim",
        "dispersions",
        "--builtin",
        "srm-glide",
        "--settings",
        settings.to_str().unwrap(),
        "--quiet",
        "--out",
        base.join("d").to_str().unwrap(),
    ])
    .unwrap_err();
    assert!(e.contains("no [dispersions] section"), "{e}");
    // An absurd but finite spread is refused with its range, the value written compactly.
    std::fs::write(
        &settings,
        "[dispersions.speed_m_s]\ndistribution = \"normal\"\nthree_sigma = 1e300\n",
    )
    .unwrap();
    let e = cli(&[
        "host-sim",
        "dispersions",
        "--builtin",
        "srm-glide",
        "--settings",
        settings.to_str().unwrap(),
        "--quiet",
        "--out",
        base.join("d").to_str().unwrap(),
    ])
    .unwrap_err();
    assert!(
        e.contains("speed_m_s.three_sigma = 1e300") && e.contains("[0, 5000]"),
        "{e}"
    );
    assert!(!e.contains("00000000000"), "{e}");
    let _ = std::fs::remove_dir_all(&base);
}
