//! `host-sim optimize` with the opt-in MOEA/D variants (`--resource-allocation`,
//! `--moead-operator sbx`) and the `--evaluations` budget, parsed from real flags.

use super::optimize_cmd::{OptimizeArgs, OptimizeError, run};

/// `optimize` arguments parsed from `flags` (tests).
pub(super) fn parse_flags(flags: &[&str]) -> OptimizeArgs {
    use clap::Parser;
    let argv = ["host-sim", "optimize"].iter().chain(flags);
    match crate::cli::Cli::try_parse_from(argv).unwrap().command {
        crate::cli::Command::Optimize(a) => a,
        _ => unreachable!("optimize parses as optimize"),
    }
}

/// clap's refusal of `optimize flags` (exit code 2), as text (tests).
pub(super) fn refused(flags: &[&str]) -> String {
    use clap::Parser;
    let argv = ["host-sim", "optimize"].iter().chain(flags);
    let e = crate::cli::Cli::try_parse_from(argv).expect_err("clap refuses");
    assert_eq!(e.exit_code(), 2, "{e}");
    e.to_string()
}

/// `optimize ALGORITHM --problem PROBLEM` with population 20, 5 generations, seed 3 (MOEA/D
/// and SCEA: 5 neighbours), then `extra` (tests).
pub(super) fn small_args(problem: &str, algorithm: &str, extra: &[&str]) -> OptimizeArgs {
    let mut v = vec![algorithm, "--problem", problem, "--population", "20"];
    v.extend(["--generations", "5", "--seed", "3"]);
    if matches!(algorithm, "moead" | "scea") {
        v.extend(["--neighbours", "5"]);
    }
    v.extend(extra);
    parse_flags(&v)
}

fn parse(flags: &[&str]) -> OptimizeArgs {
    parse_flags(flags)
}

fn summary(flags: &[&str], tag: &str) -> serde_json::Value {
    let dir = std::env::temp_dir().join(format!(
        "host-sim-optimize-variants-{tag}-{}",
        std::process::id()
    ));
    let mut a = parse(flags);
    a.out = Some(dir.clone());
    run(&a, &mut Vec::new()).unwrap();
    let json = std::fs::read_to_string(dir.join("summary.json")).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    serde_json::from_str(&json).unwrap()
}

const SMALL: [&str; 5] = ["moead", "--population", "20", "--neighbours", "5"];

#[test]
fn evaluations_budget_counts_dra_generations_of_a_fifth_of_the_population() {
    let with = |extra: &[&str], tag| {
        let mut f = SMALL.to_vec();
        f.extend_from_slice(extra);
        summary(&f, tag)
    };
    // pagmo's MOEA/D: (100 - 20) / 20 = 4 generations.
    let s = with(&["--evaluations", "100"], "de");
    assert_eq!(
        (s["generations"].as_u64(), s["evaluations"].as_u64()),
        (Some(4), Some(100))
    );
    assert!(s.get("resource_allocation").is_none());
    assert!(s.get("moead_operator").is_none());
    // DRA: 20 / 5 = 4 children per generation, (100 - 20) / 4 = 20 generations.
    let s = with(&["--resource-allocation", "--evaluations", "100"], "dra");
    assert_eq!(
        (s["generations"].as_u64(), s["evaluations"].as_u64()),
        (Some(20), Some(100))
    );
    assert_eq!(s["resource_allocation"], true);
    // Rounded up to whole generations.
    let s = with(&["--resource-allocation", "--evaluations", "101"], "dra-up");
    assert_eq!(
        (s["generations"].as_u64(), s["evaluations"].as_u64()),
        (Some(21), Some(104))
    );
    // --generations counts DRA generations.
    let s = with(&["--resource-allocation", "--generations", "3"], "dra-gens");
    assert_eq!(s["evaluations"].as_u64(), Some(32));
    // SBX: same budget, another run.
    let s = with(&["--moead-operator", "sbx", "--evaluations", "100"], "sbx");
    assert_eq!(s["moead_operator"], "sbx");
    assert_eq!(s["evaluations"].as_u64(), Some(100));
    let s = summary(
        &["nsga2", "--population", "20", "--evaluations", "100"],
        "nsga2",
    );
    assert_eq!(s["generations"].as_u64(), Some(4));
}

#[test]
fn variant_flags_where_they_do_not_apply_say_what_to_change() {
    let err = |flags: &[&str]| run(&parse(flags), &mut Vec::new()).unwrap_err();
    // The algorithm's own flags: clap refuses them elsewhere.
    for (flags, flag) in [
        (
            &["nsga2", "--resource-allocation"][..],
            "--resource-allocation",
        ),
        (
            &["mhaco", "--resource-allocation"][..],
            "--resource-allocation",
        ),
        (&["scea", "--moead-operator", "sbx"][..], "--moead-operator"),
        (
            &["nsga2", "--moead-operator", "sbx"][..],
            "--moead-operator",
        ),
        (&["--resource-allocation"][..], "--resource-allocation"),
    ] {
        let e = refused(flags);
        assert!(e.contains(&format!("unexpected argument '{flag}'")), "{e}");
    }
    // What the problem does not take: one runtime refusal naming the flag and the problem.
    for (flags, flag) in [
        (
            &["moead", "--resource-allocation"][..],
            "--resource-allocation",
        ),
        (
            &["scea", "--resource-allocation"][..],
            "--resource-allocation",
        ),
        (
            &["moead", "--moead-operator", "sbx"][..],
            "--moead-operator sbx",
        ),
        (&["--evaluations", "1000"][..], "--evaluations"),
    ] {
        let mut v = vec!["--problem", "srm"];
        v.extend(flags);
        let e = err(&v);
        assert!(matches!(e, OptimizeError::NotForProblem { .. }), "{e}");
        let text = e.to_string();
        let want = format!("{flag} does not apply to --problem srm: fixed on the re-entry");
        assert!(text.contains(&want), "{text}");
    }
    for alg in ["mhaco", "scea"] {
        let e = err(&[alg, "--evaluations", "1000"]);
        assert!(
            e.to_string()
                .contains("--evaluations 1000: applies to the moead and nsga2"),
            "{e}"
        );
    }
    let e = err(&["--evaluations", "50"]);
    assert!(e.to_string().contains("use at least 100"), "{e}");
    // --evaluations and --generations together: clap refuses.
    let e = refused(&["--evaluations", "500", "--generations", "4"]);
    assert!(e.contains("'--evaluations <E>' cannot be used with"), "{e}");
}
