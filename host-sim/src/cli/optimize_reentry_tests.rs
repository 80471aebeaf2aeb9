//! Re-entry `optimize` runs: small SRM runs (4 individuals, 2 generations) with a fixed seed.

use std::path::{Path, PathBuf};

use crate::cli::ReentryError;
use crate::cli::run as cli_run;

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("host-sim-reentry-{name}-{}", std::process::id()));
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

fn read(dir: &Path, f: &str) -> String {
    std::fs::read_to_string(dir.join(f)).unwrap()
}

/// MHACO in both constraint modes on a re-entry problem: an interrupted run resumed gives
/// the uninterrupted run's files, and the two modes are different runs.
#[test]
fn mhaco_runs_both_modes_and_resumes() {
    let common = ["--problem", "srm", "--population", "4", "--seed", "7"];
    let run = |dir: &Path, g: &str, extra: &[&str]| {
        let mut v = common.to_vec();
        let d = dir.to_str().unwrap();
        v.extend(["--generations", g, "--out", d]);
        v.extend(extra);
        optimize(&v).unwrap()
    };
    let (a, b) = (tmp("mhaco_a"), tmp("mhaco_b"));
    run(&a, "2", &["mhaco"]);
    run(&b, "1", &["mhaco"]);
    optimize(&["--resume", b.to_str().unwrap(), "--generations", "2"]).unwrap();
    for f in ["generations.json", "population.csv", "front.csv"] {
        assert_eq!(read(&a, f), read(&b, f), "{f}");
    }
    assert!(read(&a, "config.toml").contains("algorithm = \"mhaco\""));
    // The constraints-as-objectives mode from a config file.
    let c = tmp("mhaco_c");
    std::fs::create_dir_all(&c).unwrap();
    let text = read(&a, "config.toml")
        .replace("algorithm = \"mhaco\"", "algorithm = \"mhaco-objectives\"");
    let cfg = c.join("run.toml");
    std::fs::write(&cfg, text).unwrap();
    let out = c.join("run");
    optimize(&[
        "--config",
        cfg.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ])
    .unwrap();
    assert!(read(&out, "config.toml").contains("mhaco-objectives"));
    assert_eq!(read(&out, "generations.csv").lines().count(), 4);
    assert_ne!(read(&a, "population.csv"), read(&out, "population.csv"));
    // The same mode from the flag: the same run as from the file.
    let f = tmp("mhaco_f");
    run(&f, "2", &["mhaco", "--mhaco-constraints", "objectives"]);
    assert!(read(&f, "config.toml").contains("algorithm = \"mhaco-objectives\""));
    assert_eq!(read(&f, "population.csv"), read(&out, "population.csv"));
    // Flags the re-entry problems fix are refused, not ignored.
    for extra in [["--ker", "3"], ["--n-gen-mark", "2"]] {
        let mut v = common.to_vec();
        v.extend(["mhaco", "--generations", "1"]);
        v.extend(extra);
        let e = optimize(&v).unwrap_err().to_string();
        assert!(e.contains("fixed on the re-entry problems"), "{e}");
    }
}

/// Interrupting after one generation (a run of 1 generation) and resuming to 2 gives the
/// bit-identical records, population and front of an uninterrupted 2-generation run; the
/// front's scenario files fly to the front's objectives.
#[test]
fn resume_gives_the_uninterrupted_run() {
    let (a, b) = (tmp("a"), tmp("b"));
    let common = [
        "--problem",
        "srm",
        "--population",
        "4",
        "moead",
        "--neighbours",
        "3",
        "--seed",
        "7",
    ];
    let run = |dir: &Path, g: &str| {
        let mut v = common.to_vec();
        let d = dir.to_str().unwrap();
        v.extend(["--generations", g, "--out", d]);
        optimize(&v).unwrap()
    };
    run(&a, "2");
    run(&b, "1");
    assert_eq!(read(&b, "generations.csv").lines().count(), 3);
    optimize(&["--resume", b.to_str().unwrap(), "--generations", "2"]).unwrap();
    for f in [
        "generations.json",
        "population.csv",
        "front.csv",
        "population/gen_0002.csv",
    ] {
        assert_eq!(read(&a, f), read(&b, f), "{f}");
    }
    let front = read(&a, "front.csv");
    assert!(front.lines().count() >= 2, "{front}");
    // The first member's scenario file flies as is to its objectives (to the round-off of
    // the degree values written in the file).
    let sc = crate::scenario::read_scenario(&a.join("front/member_00.toml")).unwrap();
    let s = crate::scenario::fly(&sc, "member", &mut |_| {})
        .unwrap()
        .result
        .summary;
    let row: Vec<f64> = front
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let n = row.len();
    let (f1, f2) = (row[n - 6], row[n - 5]);
    assert!(
        (f1 + s.flown_range_angle_rad / std::f64::consts::PI).abs() < 1e-9,
        "{f1} {s:?}"
    );
    assert!((f2 - s.heat_load_j_m2 / 1e9).abs() < 1e-9, "{f2} {s:?}");
    for f in [
        "fronts.svg",
        "hypervolume.svg",
        "feasible.svg",
        "objectives.svg",
        "config.toml",
    ] {
        assert!(a.join(f).is_file(), "{f}");
    }
    std::fs::remove_dir_all(&a).unwrap();
    std::fs::remove_dir_all(&b).unwrap();
}

/// SCEA on the variable-length SRM problem (4-8 nodes): resumed equals uninterrupted, and
/// the ragged decision rows are padded so the objective columns line up.
#[test]
fn scea_resume_gives_the_uninterrupted_run() {
    let (a, b) = (tmp("scea-a"), tmp("scea-b"));
    let common = [
        "--problem",
        "srm",
        "scea",
        "--population",
        "4",
        "--neighbours",
        "3",
        "--seed",
        "11",
    ];
    let run = |dir: &Path, g: &str| {
        let mut v = common.to_vec();
        let d = dir.to_str().unwrap();
        v.extend(["--generations", g, "--out", d]);
        optimize(&v).unwrap()
    };
    assert!(run(&a, "2").starts_with("scea on srm"));
    run(&b, "1");
    optimize(&["--resume", b.to_str().unwrap(), "--generations", "2"]).unwrap();
    for f in ["generations.json", "population.csv", "front.csv"] {
        assert_eq!(read(&a, f), read(&b, f), "{f}");
    }
    let pop = read(&a, "population.csv");
    let cols = pop.lines().next().unwrap().split(',').count();
    // Up to 6 free nodes x (E, sigma), padded to the longest present.
    let genes = cols - (2 + 3 + 1);
    assert!(
        genes.is_multiple_of(2) && (4..=12).contains(&genes),
        "{pop}"
    );
    assert!(pop.lines().all(|l| l.split(',').count() == cols), "{pop}");
    std::fs::remove_dir_all(&a).unwrap();
    std::fs::remove_dir_all(&b).unwrap();
}

/// `--print-config` prints a template that `--config` reads back; bad settings name their
/// field and what to change.
#[test]
fn config_template_and_errors_name_the_field() {
    let text = optimize(&["--problem", "horus-2b", "--print-config"]).unwrap();
    let c: crate::cli::ReentryRunConfig = toml::from_str(&text).unwrap();
    assert_eq!(c.problem.encoding.nodes, 8);
    assert_eq!(c.problem.limits.heat_flux_kw_m2, 500.0);
    let dir = tmp("cfg");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("run.toml");
    std::fs::write(
        &file,
        text.replace("algorithm = \"moead\"", "algorithm = \"pso\""),
    )
    .unwrap();
    let e = optimize(&["--config", file.to_str().unwrap()]).unwrap_err();
    assert!(
        e.to_string()
            .contains("field `algorithm` = pso: use moead, nsga2, scea, mhaco or mhaco-objectives"),
        "{e}"
    );
    std::fs::write(&file, text.replace("nodes = 8", "nodes = 1")).unwrap();
    let e = optimize(&["--config", file.to_str().unwrap()]).unwrap_err();
    assert!(
        e.to_string()
            .contains("`encoding.nodes` = 1: use at least 3"),
        "{e}"
    );
    std::fs::write(&file, text.replace("[problem]", "[problem]\nspeed = 1")).unwrap();
    let e = optimize(&["--config", file.to_str().unwrap()]).unwrap_err();
    assert!(e.to_string().contains("speed"), "{e}");
    // Issue 7 item 2: the file is read through the one TOML reading path, so a mistyped or
    // unknown field is named with its dotted path and its value as written, and bad TOML
    // gives the parser's line.
    let bad_seed = text
        .lines()
        .map(|l| {
            if l.starts_with("seed = ") {
                "seed = \"abc\""
            } else {
                l
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    assert!(bad_seed.contains("seed = \"abc\""), "{text}");
    std::fs::write(&file, bad_seed).unwrap();
    let e = optimize(&["--config", file.to_str().unwrap()]).unwrap_err();
    assert!(
        matches!(
            e,
            crate::cli::CliError::Optimize(super::optimize_cmd::OptimizeError::Reentry(
                ReentryError::Field { .. }
            ))
        ),
        "{e:?}"
    );
    assert!(
        e.to_string().contains("run.toml: field `seed` = \"abc\": "),
        "{e}"
    );
    std::fs::write(&file, text.replace("[problem]", "[problem]\nspeed = 1")).unwrap();
    let e = optimize(&["--config", file.to_str().unwrap()]).unwrap_err();
    assert!(
        e.to_string()
            .contains("field `problem.speed` = 1: unknown field"),
        "{e}"
    );
    std::fs::write(&file, "algorithm = \"moead\"\nseed = = 3\n").unwrap();
    let e = optimize(&["--config", file.to_str().unwrap()]).unwrap_err();
    assert!(
        matches!(
            e,
            crate::cli::CliError::Optimize(super::optimize_cmd::OptimizeError::Reentry(
                ReentryError::Toml { .. }
            ))
        ),
        "{e:?}"
    );
    assert!(e.to_string().contains("line 2"), "{e}");
    let e = optimize(&["--problem", "srm", "--ref", "1,2,3"]).unwrap_err();
    assert!(e.to_string().contains("field `reference`"), "{e}");
    // An unwritable run directory (a file stands where it should be).
    let e = optimize(&["--problem", "srm", "--out", file.to_str().unwrap()]).unwrap_err();
    assert!(e.to_string().contains("choose a writable --out"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `sample` writes one row per Latin-hypercube point, the same file for 1 and 2 threads.
#[test]
fn sample_is_the_same_for_any_thread_count() {
    let dir = tmp("sample");
    std::fs::create_dir_all(&dir).unwrap();
    let run = |t: &str| {
        let f = dir.join(format!("s{t}.csv"));
        let args = [
            "host-sim",
            "sample",
            "--problem",
            "srm",
            "--count",
            "3",
            "--threads",
            t,
        ];
        let mut v: Vec<&str> = args.to_vec();
        let fs = f.to_str().unwrap().to_string();
        v.extend(["--out", &fs]);
        cli_run(v, &mut Vec::new()).unwrap();
        std::fs::read_to_string(&f).unwrap()
    };
    let one = run("1");
    assert_eq!(one.lines().count(), 4);
    assert!(one.starts_with("x1,x2,"));
    assert_eq!(one, run("2"));
    let e = cli_run(["host-sim", "sample", "--count", "0"], &mut Vec::new()).unwrap_err();
    assert!(e.to_string().contains("--count"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The analytical SRM problems from `--problem`: a short seeded run gives bit-identical files
/// on one and on two threads, records the analytical simulator in config.toml, writes the
/// chosen front members' analytical trajectories, and the entry-altitude variant carries
/// its 13th variable.
#[test]
fn srm_analytical_seeded_run_is_reproducible() {
    let run = |dir: &Path, problem: &str, threads: &str| {
        let d = dir.to_str().unwrap();
        optimize(&[
            "--problem",
            problem,
            "--population",
            "8",
            "moead",
            "--neighbours",
            "4",
            "--batch-size",
            "8",
            "--generations",
            "3",
            "--seed",
            "5",
            "--threads",
            threads,
            "--out",
            d,
        ])
        .unwrap()
    };
    let (a, b) = (tmp("ana-a"), tmp("ana-b"));
    assert!(run(&a, "srm-analytical", "1").starts_with("moead on srm-analytical"));
    run(&b, "srm-analytical", "2");
    for f in ["generations.json", "population.csv", "front.csv"] {
        assert_eq!(read(&a, f), read(&b, f), "{f}");
    }
    let cfg = read(&a, "config.toml");
    assert!(cfg.contains("simulator = \"analytical\""), "{cfg}");
    let summary = read(&a, "front/member_00/summary.json");
    assert!(
        summary.contains("analytical (Vinh second order)"),
        "{summary}"
    );
    // The run's evaluations are the problem's: the first front member re-evaluated.
    let front = read(&a, "front.csv");
    let row: Vec<f64> = front
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let p = crate::design::DesignConfig::preset("srm-analytical")
        .unwrap()
        .problem(Path::new("."))
        .unwrap();
    let ev = crate::optim::Problem::evaluate(&p, &row[..12].to_vec()).unwrap();
    assert_eq!(ev.objectives, row[12..14].to_vec(), "{front}");
    let c = tmp("ana-c");
    run(&c, "srm-analytical-altitude", "1");
    let pop = read(&c, "population.csv");
    let header = pop.lines().next().unwrap();
    assert_eq!(header.split(',').count(), 13 + 2 + 3 + 1, "{header}");
    for d in [a, b, c] {
        std::fs::remove_dir_all(&d).unwrap();
    }
}

/// `--scea-genes` selects SCEA's gene source: written to config.toml (the `--print-config`
/// template too), read back by `--resume`, and the random and history-based sources give
/// different runs from the same seed (on the analytical SRM problem: fast).
#[test]
fn scea_gene_source_from_the_command_line() {
    let text = optimize(&[
        "--problem",
        "srm",
        "scea",
        "--scea-genes",
        "random",
        "--print-config",
    ])
    .unwrap();
    assert!(text.contains("scea_genes = \"random\""), "{text}");
    let text = optimize(&["--problem", "srm", "--print-config"]).unwrap();
    assert!(text.contains("scea_genes = \"population\""), "{text}");
    let run = |dir: &Path, genes: &str, g: &str| {
        let d = dir.to_str().unwrap();
        optimize(&[
            "--problem",
            "srm-analytical",
            "scea",
            "--population",
            "6",
            "--neighbours",
            "3",
            "--seed",
            "3",
            "--generations",
            g,
            "--scea-genes",
            genes,
            "--out",
            d,
        ])
        .unwrap()
    };
    let (r, h, r1) = (tmp("genes-r"), tmp("genes-h"), tmp("genes-r1"));
    run(&r, "random", "3");
    run(&h, "history", "3");
    assert!(read(&r, "config.toml").contains("scea_genes = \"random\""));
    assert!(read(&h, "config.toml").contains("scea_genes = \"population\""));
    assert_ne!(read(&r, "population.csv"), read(&h, "population.csv"));
    // Resume keeps the source of the file.
    run(&r1, "random", "1");
    optimize(&["--resume", r1.to_str().unwrap(), "--generations", "3"]).unwrap();
    assert_eq!(read(&r, "population.csv"), read(&r1, "population.csv"));
    let e = optimize(&["--problem", "srm", "scea", "--scea-genes", "parents"]).unwrap_err();
    assert!(e.to_string().contains("scea-genes"), "{e}");
    // Refused by clap, not ignored, for another algorithm.
    for alg in [&[][..], &["nsga2"][..]] {
        let mut v = vec!["--problem", "srm"];
        v.extend(alg);
        v.extend(["--scea-genes", "random"]);
        let e = optimize(&v).unwrap_err();
        let crate::cli::CliError::Usage(c) = &e else {
            panic!("{e}")
        };
        assert_eq!(c.exit_code(), 2);
        assert!(
            e.to_string().contains("unexpected argument '--scea-genes'"),
            "{e}"
        );
    }
    for d in [r, h, r1] {
        std::fs::remove_dir_all(&d).unwrap();
    }
}

/// `sample` counts a failed evaluation (an analytical table outside the closed form's domain:
/// NaN objectives) as infeasible with an infinite violation, not as feasible.
#[test]
fn sample_counts_failed_evaluations_as_infeasible() {
    let dir = tmp("sample-fail");
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("s.csv");
    let mut out = Vec::new();
    let args = [
        "host-sim",
        "sample",
        "--problem",
        "srm-analytical",
        "--count",
        "40",
    ];
    let mut v: Vec<&str> = args.to_vec();
    let fs = f.to_str().unwrap().to_string();
    v.extend(["--out", &fs]);
    cli_run(v, &mut out).unwrap();
    let text = std::fs::read_to_string(&f).unwrap();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    let failed = rows.iter().filter(|r| r[12].is_nan()).count();
    assert!(failed > 0 && failed < 40, "{text}");
    assert!(
        rows.iter()
            .filter(|r| r[12].is_nan())
            .all(|r| r[17] == f64::INFINITY)
    );
    let feasible = rows
        .iter()
        .filter(|r| r[12].is_finite() && r[14..17].iter().all(|g| *g <= 0.0))
        .count();
    let said = String::from_utf8(out).unwrap();
    assert!(said.contains(&format!(": {feasible} feasible;")), "{said}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The external archive on a re-entry run (`--archive`, `archive` in config.toml): the
/// population is the plain run's, the front comes from the archive (feasible, within its
/// capacity), a resumed run gives the uninterrupted run's files,
/// and bad values name the field.
#[test]
fn archive_on_a_reentry_run_resumes_and_writes_the_archive_front() {
    let common = [
        "--problem",
        "srm",
        "--population",
        "4",
        "moead",
        "--neighbours",
        "3",
        "--seed",
        "7",
    ];
    let run = |dir: &Path, g: &str, extra: &[&str]| {
        let mut v = common.to_vec();
        let d = dir.to_str().unwrap();
        v.extend(["--generations", g, "--out", d]);
        v.extend(extra);
        optimize(&v).unwrap()
    };
    let (a, b, p) = (tmp("archive_a"), tmp("archive_b"), tmp("archive_p"));
    let text = run(&a, "2", &["--archive", "3"]);
    assert!(text.contains("(external archive of 3)"), "{text}");
    run(&b, "1", &["--archive", "3"]);
    optimize(&["--resume", b.to_str().unwrap(), "--generations", "2"]).unwrap();
    for f in ["generations.json", "population.csv", "front.csv"] {
        assert_eq!(read(&a, f), read(&b, f), "{f}");
    }
    assert!(read(&a, "config.toml").contains("archive = 3"));
    run(&p, "2", &[]);
    assert!(!read(&p, "config.toml").contains("archive"));
    assert_eq!(read(&a, "population.csv"), read(&p, "population.csv"));
    let rows = read(&a, "front.csv").lines().count() - 1;
    assert!((1..=3).contains(&rows), "{rows}");
    // Every front row is feasible (violation, the last column, 0).
    for row in read(&a, "front.csv").lines().skip(1) {
        assert_eq!(
            row.rsplit(',').next().unwrap().parse::<f64>().unwrap(),
            0.0,
            "{row}"
        );
    }
    // A config file with archive = 0 or with MHACO names the field.
    let c = tmp("archive_c");
    std::fs::create_dir_all(&c).unwrap();
    for (from, to) in [
        ("archive = 3", "archive = 0"),
        ("algorithm = \"moead\"", "algorithm = \"mhaco\""),
    ] {
        let cfg = c.join("run.toml");
        std::fs::write(&cfg, read(&a, "config.toml").replace(from, to)).unwrap();
        let e = optimize(&[
            "--config",
            cfg.to_str().unwrap(),
            "--out",
            c.join("r").to_str().unwrap(),
        ])
        .unwrap_err()
        .to_string();
        assert!(e.contains("field `archive`"), "{e}");
    }
    for d in [a, b, p, c] {
        let _ = std::fs::remove_dir_all(d);
    }
}
