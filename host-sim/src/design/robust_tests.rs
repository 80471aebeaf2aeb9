//! Robust-problem tests: the SRM capsule on `examples/srm-glide-replanning.toml` (fixed
//! target, re-planning and bank reversals), a few dispersed flights per candidate.

use std::path::{Path, PathBuf};

use super::*;
use crate::campaign::{Campaign, JobOutcome, Mode, ModeStats};
use crate::design::SettingVariable;
use crate::optim::{Problem, RealProblem};

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples")
}

/// The SRM preset's encoding on the example scenario with its stack.
fn config(cases: u32, mode: Option<&str>) -> (DesignConfig, RobustConfig) {
    let mut d = DesignConfig::preset("srm").unwrap();
    d.base = "srm-glide-replanning.toml".into();
    let mut r = RobustConfig {
        mode: mode.map(str::to_string),
        ..RobustConfig::default()
    };
    r.dispersions.cases = cases;
    r.dispersions.seed = 7;
    (d, r)
}

fn problem(cases: u32, mode: Option<&str>) -> RobustProblem {
    let (d, r) = config(cases, mode);
    let inner = d.problem(&examples()).unwrap();
    let stack = d.stack_scenario(&examples()).unwrap();
    RobustProblem::new(inner, stack, r, &d.base).unwrap()
}

/// Close to the example's own stored profile: 6 free nodes `[E-hat, sigma_deg]`.
fn decision() -> Vec<f64> {
    vec![
        0.9, 20.0, 0.75, 42.0, 0.6, 50.0, 0.45, 57.0, 0.3, 45.0, 0.15, 22.0,
    ]
}

/// The evaluation is the campaign's own report: the same scenario flown as a campaign by
/// `Campaign::run_local` (on threads) gives the statistics the objectives are taken from,
/// and the constraint counts its flights that fail, miss the interface or exceed a limit.
#[test]
fn robust_evaluation_is_the_campaigns_own_statistics() {
    let p = problem(4, Some("stored-reversals"));
    assert_eq!(p.mode(), Mode::StoredReversals);
    assert_eq!((p.objectives(), p.constraints()), (2, 1));
    let x = decision();
    assert_eq!(p.bounds().dim(), 12);
    let ev = p.evaluate(&x).unwrap();
    let sc = p.scenario_of(&x).unwrap();
    assert!(sc.layers.is_some(), "the candidate flies the base's stack");
    let c = Campaign::new(
        &sc,
        "test",
        p.config().dispersions.clone(),
        "test",
        vec![Mode::StoredReversals],
    )
    .unwrap();
    let outcomes = c.run_local(Some(2)).unwrap();
    assert_eq!(outcomes.len(), 4);
    let flown: Vec<_> = outcomes
        .iter()
        .filter_map(|o| match o {
            JobOutcome::Flown(c) => Some(c.clone()),
            JobOutcome::Failed(_) => None,
        })
        .collect();
    let stats = ModeStats::of(Mode::StoredReversals, &flown, outcomes.len() - flown.len());
    assert_eq!(
        ev.objectives,
        vec![stats.miss_km.p99, stats.heat_flux_ratio.p99]
    );
    let bad = outcomes.len() - flown.len()
        + flown
            .iter()
            .filter(|c| !c.reached_interface || c.limit_ratios.iter().any(|r| *r > 1.0))
            .count();
    assert_eq!(ev.constraints, vec![bad as f64 / 4.0]);
    assert!(stats.miss_km.p99 > 0.0 && stats.miss_km.p99.is_finite());
    // Deterministic: the same decision evaluates bit-identically.
    assert_eq!(p.evaluate(&x).unwrap(), ev);
}

/// Common random numbers: every candidate's case `i` flies the same dispersions, so two
/// profiles differ in their campaigns only by the profile.
#[test]
fn robust_candidates_share_their_draws() {
    let p = problem(3, Some("stored"));
    let x = decision();
    let mut y = x.clone();
    y[3] = 30.0;
    let draws = |x: &[f64]| -> Vec<_> {
        let sc = p.scenario_of(x).unwrap();
        let c = Campaign::new(
            &sc,
            "t",
            p.config().dispersions.clone(),
            "t",
            vec![p.mode()],
        )
        .unwrap();
        c.run_local(Some(1))
            .unwrap()
            .into_iter()
            .map(|o| match o {
                JobOutcome::Flown(c) => (c.index, format!("{:?}", c.draw), c.miss_m),
                JobOutcome::Failed(f) => (f.index, format!("{:?}", Some(f.draw)), f64::NAN),
            })
            .collect()
    };
    let (a, b) = (draws(&x), draws(&y));
    for (ca, cb) in a.iter().zip(&b) {
        assert_eq!((ca.0, &ca.1), (cb.0, &cb.1));
    }
    assert_ne!(a, b, "the profiles differ, so the flights do");
    assert_ne!(p.evaluate(&x).unwrap(), p.evaluate(&y).unwrap());
}

/// What cannot be flown is refused, naming the `robust.` or `problem.` field.
#[test]
fn robust_settings_are_checked_naming_the_field() {
    let err = |d: &DesignConfig, r: RobustConfig| {
        let inner = d.problem(&examples()).unwrap();
        let stack = d.stack_scenario(&examples()).unwrap();
        RobustProblem::new(inner, stack, r, &d.base)
            .unwrap_err()
            .to_string()
    };
    let (d, r) = config(2, None);
    // A preset aims at its nominal end: no fixed target.
    let preset = DesignConfig::preset("srm").unwrap();
    let e = err(&preset, r.clone());
    assert!(
        e.contains("`problem.base`") && e.contains("fixed target"),
        "{e}"
    );
    let e = err(
        &d,
        RobustConfig {
            objectives: vec![],
            ..r.clone()
        },
    );
    assert!(e.contains("`robust.objectives`"), "{e}");
    let e = err(
        &d,
        RobustConfig {
            objectives: vec![Statistic::MissP99Km, Statistic::MissP99Km],
            ..r.clone()
        },
    );
    assert!(e.contains("distinct"), "{e}");
    let e = err(
        &d,
        RobustConfig {
            max_violation_fraction: 1.0,
            ..r.clone()
        },
    );
    assert!(e.contains("`robust.max_violation_fraction` = 1"), "{e}");
    let e = err(
        &d,
        RobustConfig {
            mode: Some("glide".into()),
            ..r.clone()
        },
    );
    assert!(e.contains("`robust.mode` = glide"), "{e}");
    let mut zero = r.clone();
    zero.dispersions.cases = 0;
    let e = err(&d, zero);
    assert!(e.contains("`robust.dispersions.cases` = 0"), "{e}");
}

/// A robust run through the run file: config.toml keeps the `[robust]` section (read back
/// equal), and the front's member scenarios carry the base's stack, so `simulate` and PIL fly
/// the member as the campaign did.
#[test]
fn robust_run_writes_its_section_and_stack_members() {
    use crate::design::run::{ReentryRunConfig, parse_toml, run};
    let (d, r) = config(2, Some("stored"));
    let mut c = ReentryRunConfig::thesis("srm").unwrap();
    c.problem = d;
    c.robust = Some(r);
    c.population = 4;
    c.neighbours = 3;
    c.generations = 1;
    c.threads = 2;
    c.reference = vec![5000.0, 2.0];
    let dir = std::env::temp_dir().join(format!("host-sim-robust-run-{}", std::process::id()));
    // A nominal front to compare with: one member, the decision near the example's profile
    // (its objectives in the file are not read).
    let nominal = std::env::temp_dir().join(format!(
        "host-sim-robust-nominal-{}.csv",
        std::process::id()
    ));
    let x = decision();
    let row: Vec<String> = x.iter().map(|v| format!("{v:e}")).collect();
    let head: Vec<String> = (1..=x.len()).map(|k| format!("x{k}")).collect();
    std::fs::write(
        &nominal,
        format!(
            "{},f1,f2,g1,violation\n{},0e0,0e0,0e0,0e0\n",
            head.join(","),
            row.join(",")
        ),
    )
    .unwrap();
    c.robust.as_mut().unwrap().nominal_front = Some(nominal.display().to_string());
    let done = run(&c, "test", &dir, false, &examples(), &mut (), None).unwrap();
    let last = done.last.unwrap();
    assert_eq!((last.generation, last.evaluations), (1, 8));
    // config.toml names the base scenario and the nominal front by absolute paths (the run
    // resumes from any working directory), the rest as given.
    let mut anchored = c.clone();
    anchored.problem = c.problem.anchored(&examples());
    assert!(Path::new(&anchored.problem.base).is_absolute());
    anchored.robust.as_mut().unwrap().nominal_front = Some(nominal.display().to_string());
    assert_eq!(parse_toml(&dir.join("config.toml")).unwrap(), anchored);
    let text = std::fs::read_to_string(dir.join("config.toml")).unwrap();
    assert!(
        text.contains("[robust]") && text.contains("[robust.dispersions]"),
        "{text}"
    );
    let members: Vec<_> = std::fs::read_dir(dir.join("front"))
        .unwrap()
        .filter_map(|e| {
            let p = e.unwrap().path();
            (p.extension().is_some_and(|x| x == "toml")).then_some(p)
        })
        .collect();
    assert!(!members.is_empty(), "{last:?}");
    assert_eq!(
        members.len(),
        last.front.len(),
        "one scenario per front member"
    );
    for m in &members {
        let t = std::fs::read_to_string(m).unwrap();
        assert!(
            t.contains("[guidance.target]") && t.contains("[guidance.lateral]"),
            "{t}"
        );
    }
    // The first front member's campaign report is the training campaign flown again: its
    // statistics are the member's objectives in front.csv, bit for bit, and its figures are
    // there (footprint, miss CDF, limit ratios).
    let front = std::fs::read_to_string(dir.join("front.csv")).unwrap();
    let mut rows = front.lines();
    let header: Vec<&str> = rows.next().unwrap().split(',').collect();
    let row: Vec<f64> = rows
        .next()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let col = |name: &str| row[header.iter().position(|h| *h == name).unwrap()];
    let report = dir.join("front/member_00/campaign");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(report.join("summary.json")).unwrap())
            .unwrap();
    let stats = &summary["stats"][0];
    assert_eq!(stats["mode"], "Stored", "{stats}");
    assert_eq!(stats["miss_km"]["p99"].as_f64().unwrap(), col("f1"));
    assert_eq!(stats["heat_flux_ratio"]["p99"].as_f64().unwrap(), col("f2"));
    for stem in crate::report::campaign::figure_stems("stored") {
        assert!(report.join(format!("{stem}.svg")).is_file(), "{stem}");
    }
    assert!(report.join("cases-stored.csv").is_file());
    let fronts = std::fs::read_to_string(dir.join("fronts.svg")).unwrap();
    assert!(
        fronts.contains("p99 miss [km]") && fronts.contains("p99 heat flux / limit [-]"),
        "the front's axes name the robust statistics"
    );
    // The nominal member flown in the same campaign: its robust objectives and constraint,
    // the problem's own evaluation of it.
    let ev = problem(2, Some("stored")).evaluate(&x).unwrap();
    let flown = std::fs::read_to_string(dir.join("nominal-front.csv")).unwrap();
    let (rows, dims) = crate::optim::rows::read_population(&flown).unwrap();
    assert_eq!((rows.len(), dims), (1, [12, 2, 1]), "{flown}");
    let f: Vec<f64> = rows[0].f.iter().map(|e| e.0).collect();
    let g: Vec<f64> = rows[0].g.iter().map(|e| e.0).collect();
    assert_eq!((f, g), (ev.objectives, ev.constraints));
    let svg = std::fs::read_to_string(dir.join("robust-vs-nominal.svg")).unwrap();
    assert!(svg.contains("robust front") && svg.contains("p99 miss [km]"));
    // A nominal front of another encoding is refused, naming the key and the file, before
    // the run directory is touched.
    std::fs::write(
        &nominal,
        "x1,x2,f1,f2,g1,violation\n1e0,2e0,0e0,0e0,0e0,0e0\n",
    )
    .unwrap();
    let e = run(&c, "run.toml", &dir, false, &examples(), &mut (), None).unwrap_err();
    assert!(
        e.to_string().contains("field `robust.nominal_front`")
            && e.to_string().contains(&nominal.display().to_string())
            && e.to_string().contains("2 genes"),
        "{e}"
    );
    assert!(dir.join("nominal-front.csv").is_file());
    std::fs::remove_file(&nominal).unwrap();
    // A robust run refuses what it would not use.
    let mut bad = c.clone();
    bad.problem.limits.g_load = 4.0;
    let e = run(&bad, "run.toml", &dir, false, &examples(), &mut (), None).unwrap_err();
    assert!(e.to_string().contains("field `problem.limits`"), "{e}");
    // Refused before the run directory is touched: the previous run is still there.
    assert_eq!(parse_toml(&dir.join("config.toml")).unwrap(), anchored);
    let mut bad = c.clone();
    bad.algorithm = "scea".into();
    let e = run(&bad, "run.toml", &dir, false, &examples(), &mut (), None).unwrap_err();
    assert!(e.to_string().contains("field `algorithm` = scea"), "{e}");
    let mut bad = c;
    bad.reference = vec![1.0];
    let e = run(&bad, "run.toml", &dir, false, &examples(), &mut (), None).unwrap_err();
    assert!(e.to_string().contains("give 2 finite values"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A candidate's evaluation split over flights: its cases flown in parts, in any order (as
/// workers would, each setting the campaign up again), and sent as JSON, give the whole
/// evaluation bit for bit; a part missing, repeated or of another campaign is refused.
#[test]
fn robust_evaluation_split_over_flights_is_the_whole_one() {
    let p = problem(4, Some("stored-reversals"));
    let x = decision();
    let sc = p.scenario_of(&x).unwrap();
    let whole = p.evaluate(&x).unwrap();
    let mut parts = Vec::new();
    for chunk in [[2_u32, 3], [0, 1]] {
        let json = serde_json::to_string(&p.fly_cases(&sc, chunk).unwrap()).unwrap();
        parts.extend(serde_json::from_str::<Vec<JobOutcome>>(&json).unwrap());
    }
    let o = p.outcome_of(parts.clone()).unwrap();
    assert_eq!(p.evaluation_of(&o), whole);
    let e = p.outcome_of(parts[1..].to_vec()).unwrap_err();
    assert!(e.to_string().contains("missing"), "{e}");
    let mut twice = parts.clone();
    twice.push(parts[0].clone());
    let e = p.outcome_of(twice).unwrap_err();
    assert!(e.to_string().contains("given twice"), "{e}");
    assert!(p.fly_cases(&sc, [4]).is_err(), "case 4 of 4");
}

/// `[[robust.settings]]` of the example's stack: the lateral corridor's final width, the
/// re-planning period in ticks (an integer key) and the re-planner's accepted miss.
fn settings() -> Vec<SettingVariable> {
    [
        ("guidance.lateral.corridor_width_final_deg", [1.0, 10.0]),
        ("guidance.replanning.every_n_ticks", [1.0, 10.0]),
        ("guidance.replanning.tolerance_km", [0.5, 5.0]),
    ]
    .into_iter()
    .map(|(f, r)| SettingVariable {
        field: f.into(),
        range: r,
    })
    .collect()
}

fn problem_with(cases: u32, mode: Option<&str>, s: Vec<SettingVariable>) -> RobustProblem {
    let (d, mut r) = config(cases, mode);
    r.settings = s;
    let inner = d.problem(&examples()).unwrap();
    let stack = d.stack_scenario(&examples()).unwrap();
    RobustProblem::new(inner, stack, r, &d.base).unwrap()
}

/// The member scenario file of a scenario read back (`front/member_NN.toml`).
fn member_round_trip(sc: &crate::scenario::Scenario) -> crate::scenario::Scenario {
    let text = crate::scenario::scenario_to_toml(sc);
    crate::scenario::parse_scenario(&text, "member_00.toml", Path::new(".")).unwrap()
}

/// A decision's setting genes are written into its scenario's stack (read back from the
/// scenario and from its member scenario file); the bounds are the encoding's and then the
/// ranges; a decision of the encoding alone completed with the base's values flies the base.
#[test]
fn robust_setting_genes_are_the_candidates_stack_settings() {
    let p = problem_with(2, Some("stored-reversals"), settings());
    assert_eq!(p.bounds().dim(), 15);
    assert_eq!(&p.bounds().lower()[12..], &[1.0, 1.0, 0.5]);
    assert_eq!(&p.bounds().upper()[12..], &[10.0, 10.0, 5.0]);
    let mut x = decision();
    x.extend([4.5, 3.4, 2.25]);
    let sc = p.scenario_of(&x).unwrap();
    let g = &sc.layers.as_ref().unwrap().settings;
    assert_eq!(g.corridor_width_final_deg, 4.5);
    assert_eq!(
        g.replan_every_n_ticks, 3,
        "an integer key takes its gene rounded"
    );
    assert_eq!(g.replan_tolerance_km, 2.25);
    // The rest of the stack is the base's.
    let base = problem(2, Some("stored-reversals"))
        .scenario_of(&decision())
        .unwrap();
    let mut expected = base.layers.clone().unwrap();
    expected.settings.corridor_width_final_deg = 4.5;
    expected.settings.replan_every_n_ticks = 3;
    expected.settings.replan_tolerance_km = 2.25;
    assert_eq!(sc.layers.as_ref(), Some(&expected));
    assert_eq!(sc.guidance.nodes, base.guidance.nodes);
    // The member scenario file carries them.
    let back = member_round_trip(&sc);
    assert_eq!(back.layers.unwrap().settings, expected.settings);
    // The base's own values (3 deg, 5 ticks, 1 km: the example's) complete a nominal decision.
    assert_eq!(p.base_setting_values(), &[3.0, 5.0, 1.0]);
    let nominal = p.with_base_settings(&decision());
    assert_eq!(nominal.len(), 15);
    assert_eq!(
        p.scenario_of(&nominal).unwrap().layers,
        base.layers,
        "the base's values fly the base's stack"
    );
    assert!(p.scenario_of(&decision()).is_err(), "12 genes of 15");
}

/// An element of a pair-valued key (`limit_scale[0]`: the re-planner's heat-flux limit as a
/// multiple of the vehicle's) is a setting gene: it is written into that element, the other
/// keeping the base's value, and read back from the member file; a bad element is refused.
#[test]
fn robust_setting_gene_may_be_an_element_of_a_pair() {
    let field = |f: &str| SettingVariable {
        field: f.into(),
        range: [0.5, 1.0],
    };
    let p = problem_with(
        2,
        Some("stored-reversals"),
        vec![field("guidance.replanning.limit_scale[0]")],
    );
    let mut x = decision();
    x.push(0.8);
    let sc = member_round_trip(&p.scenario_of(&x).unwrap());
    let layers = sc.layers.as_ref().unwrap();
    assert_eq!(layers.settings.replan_limit_scale, [0.8, 1.0]);
    for (f, why) in [
        (
            "guidance.replanning.limit_scale[2]",
            "name [0] or [1] of a pair",
        ),
        (
            "guidance.replanning.tolerance_km[0]",
            "not an element of the base scenario's",
        ),
        (
            "guidance.replanning.limit_scale[x]",
            "name [0] or [1] of a pair",
        ),
    ] {
        let (d, mut r) = config(2, Some("stored-reversals"));
        r.settings = vec![field(f)];
        let inner = d.problem(&examples()).unwrap();
        let stack = d.stack_scenario(&examples()).unwrap();
        let e = RobustProblem::new(inner, stack, r, &d.base)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`robust.settings[0].field`") && e.contains(why),
            "{f}: {e}"
        );
    }
}

/// A setting that is not a number of the base's stack, named twice, or with a range the
/// scenario refuses is refused when the problem is built, naming the entry and the value.
#[test]
fn robust_settings_are_refused_naming_the_entry() {
    let err = |s: Vec<(&str, [f64; 2])>| {
        let (d, mut r) = config(2, Some("stored"));
        r.settings = s
            .into_iter()
            .map(|(f, range)| SettingVariable {
                field: f.into(),
                range,
            })
            .collect();
        let inner = d.problem(&examples()).unwrap();
        let stack = d.stack_scenario(&examples()).unwrap();
        RobustProblem::new(inner, stack, r, &d.base)
            .unwrap_err()
            .to_string()
    };
    let ok = ("guidance.replanning.tolerance_km", [0.5, 5.0]);
    let e = err(vec![ok, ("guidance.lateral.corridor_width", [1.0, 2.0])]);
    assert!(
        e.contains("`robust.settings[1].field` = \"guidance.lateral.corridor_width\"")
            && e.contains("not a guidance layer setting"),
        "{e}"
    );
    let e = err(vec![("guidance.period_s", [1.0, 2.0])]);
    assert!(e.contains("`robust.settings[0].field`"), "{e}");
    let e = err(vec![("guidance.barrier.damping", [0.5, 2.0])]);
    assert!(
        e.contains("`robust.settings[0].field` = \"guidance.barrier.damping\"")
            && e.contains("no [guidance.barrier] layer")
            && e.contains("srm-glide-replanning.toml"),
        "{e}"
    );
    let e = err(vec![("guidance.lateral.terminal_start_km", [100.0, 500.0])]);
    assert!(e.contains("does not set it"), "{e}");
    let e = err(vec![("guidance.replanning.predictor", [0.0, 1.0])]);
    assert!(
        e.contains("`robust.settings[0].field` = \"guidance.replanning.predictor\"")
            && e.contains("not a number")
            && e.contains("\"hybrid\""),
        "{e}"
    );
    let e = err(vec![ok, ok]);
    assert!(
        e.contains("`robust.settings[1].field`")
            && e.contains("named twice (also robust.settings[0].field)"),
        "{e}"
    );
    let e = err(vec![("guidance.replanning.tolerance_km", [-1.0, 5.0])]);
    assert!(
        e.contains("`robust.settings[0].range` = [-1, 5]")
            && e.contains("guidance.replanning.tolerance_km = -1 is refused by the scenario")
            && e.contains("field `guidance.replanning.tolerance_km`"),
        "{e}"
    );
    let e = err(vec![("guidance.lateral.max_reversals", [1.0, 300.0])]);
    assert!(
        e.contains("`robust.settings[0].range` = [1, 300]")
            && e.contains("must be an integer in [0, 255]"),
        "{e}"
    );
    let e = err(vec![("guidance.replanning.tolerance_km", [5.0, 0.5])]);
    assert!(
        e.contains("`robust.settings[0].range` = [5, 0.5]") && e.contains("lower < upper"),
        "{e}"
    );
}

/// A setting gene changes the flights: the corridor's final width (the heading error at
/// which the lateral logic reverses the bank) gives two different campaigns at its two ends,
/// and each evaluation is the campaign the dispersions code flies on the member scenario
/// file, bit for bit.
#[test]
fn robust_setting_gene_is_flown_as_the_member_scenario() {
    let s = vec![SettingVariable {
        field: "guidance.lateral.corridor_width_final_deg".into(),
        range: [1.0, 10.0],
    }];
    let p = problem_with(2, Some("stored-reversals"), s);
    let eval = |w: f64| {
        let mut x = decision();
        x.push(w);
        let ev = p.evaluate(&x).unwrap();
        let member = member_round_trip(&p.scenario_of(&x).unwrap());
        assert_eq!(
            member
                .layers
                .as_ref()
                .unwrap()
                .settings
                .corridor_width_final_deg,
            w
        );
        let c = Campaign::new(
            &member,
            "member_00.toml",
            p.config().dispersions.clone(),
            "test",
            vec![Mode::StoredReversals],
        )
        .unwrap();
        let outcomes = c.run_local(Some(2)).unwrap();
        let flown: Vec<_> = outcomes
            .iter()
            .filter_map(|o| match o {
                JobOutcome::Flown(c) => Some(c.clone()),
                JobOutcome::Failed(_) => None,
            })
            .collect();
        let stats = ModeStats::of(Mode::StoredReversals, &flown, outcomes.len() - flown.len());
        assert_eq!(
            ev.objectives,
            vec![stats.miss_km.p99, stats.heat_flux_ratio.p99],
            "width {w}"
        );
        ev
    };
    let (narrow, wide) = (eval(1.0), eval(10.0));
    assert_ne!(narrow.objectives, wide.objectives);
}

/// A robust run with a setting: front.csv names the setting's gene after the encoding's
/// (x13), each member scenario file carries the member's value, and the member's campaign
/// report is its objectives; a bad setting is refused naming the run file before the run
/// directory is touched.
#[test]
fn robust_run_with_a_setting_writes_it_into_the_members() {
    use crate::design::run::{ReentryRunConfig, run};
    let (d, mut r) = config(2, Some("stored-reversals"));
    r.settings = vec![SettingVariable {
        field: "guidance.lateral.corridor_width_final_deg".into(),
        range: [1.0, 10.0],
    }];
    let mut c = ReentryRunConfig::thesis("srm").unwrap();
    c.problem = d;
    c.robust = Some(r);
    c.population = 4;
    c.neighbours = 3;
    c.generations = 1;
    c.threads = 2;
    c.reference = vec![5000.0, 2.0];
    let dir = std::env::temp_dir().join(format!(
        "host-sim-robust-settings-run-{}",
        std::process::id()
    ));
    run(&c, "test", &dir, false, &examples(), &mut (), None).unwrap();
    let front = std::fs::read_to_string(dir.join("front.csv")).unwrap();
    let mut rows = front.lines();
    let header: Vec<&str> = rows.next().unwrap().split(',').collect();
    assert_eq!(&header[11..14], &["x12", "x13", "f1"], "{front}");
    let row: Vec<f64> = rows
        .next()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let member = crate::scenario::read_scenario(&dir.join("front/member_00.toml")).unwrap();
    assert_eq!(
        member.layers.unwrap().settings.corridor_width_final_deg,
        row[12]
    );
    let summary: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("front/member_00/campaign/summary.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(
        summary["stats"][0]["miss_km"]["p99"].as_f64().unwrap(),
        row[13]
    );
    let config_text = std::fs::read_to_string(dir.join("config.toml")).unwrap();
    assert!(config_text.contains("[[robust.settings]]"), "{config_text}");
    let mut bad = c;
    bad.robust.as_mut().unwrap().settings[0].range = [0.0, 10.0];
    bad.generations = 5;
    let e = run(&bad, "run.toml", &dir, false, &examples(), &mut (), None)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("run.toml: ")
            && e.contains("`robust.settings[0].range` = [0, 10]")
            && e.contains("corridor_width_final_deg = 0"),
        "{e}"
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("config.toml")).unwrap(),
        config_text,
        "the run directory is untouched"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The run file's check reads `[[robust.settings]]` and refuses a bad one naming the file,
/// the entry and the value (without flying the base's campaign).
#[test]
fn robust_settings_in_a_run_file_are_checked_naming_it() {
    use crate::design::run::check_run_config;
    let text = std::fs::read_to_string(examples().join("optimize-robust-srm.toml")).unwrap();
    let path = examples().join("robust-settings.toml");
    let with = |s: &str| format!("{text}\n[[robust.settings]]\n{s}\n");
    let c = check_run_config(
        &with("field = \"guidance.replanning.every_n_ticks\"\nrange = [2.0, 10.0]"),
        &path,
    )
    .unwrap();
    assert_eq!(
        c.robust.unwrap().settings,
        vec![SettingVariable {
            field: "guidance.replanning.every_n_ticks".into(),
            range: [2.0, 10.0],
        }]
    );
    let e = check_run_config(
        &with("field = \"guidance.replanning.every_n_ticks\"\nrange = [0.0, 10.0]"),
        &path,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("robust-settings.toml")
            && e.contains("`robust.settings[0].range` = [0, 10]")
            && e.contains("every_n_ticks = 0 is refused by the scenario"),
        "{e}"
    );
    let e = check_run_config(
        &with("field = \"guidance.replanning.period_s\"\nrange = [4.0, 20.0]"),
        &path,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("robust-settings.toml")
            && e.contains("`robust.settings[0].field` = \"guidance.replanning.period_s\""),
        "{e}"
    );
}
