//! Design-problem tests: small, fixed decisions; each flight is a real closed-loop run.

use super::*;
use crate::optim::{Problem, RealProblem};
use crate::scenario::{build_guidance, fly, parse_scenario, scenario_to_toml};

fn horus() -> ReentryProblem {
    DesignConfig::preset("horus-2b")
        .unwrap()
        .problem(std::path::Path::new("."))
        .unwrap()
}

/// A mid-box HORUS-2B decision: 6 free nodes from E = 0.9 down to 0.15.
fn horus_decision() -> Vec<f64> {
    let mut x = Vec::new();
    for (i, e) in [0.9, 0.75, 0.6, 0.45, 0.3, 0.15].into_iter().enumerate() {
        x.extend([e, 35.0 - 3.0 * i as f64, 40.0 + 5.0 * i as f64]);
    }
    x
}

/// The evaluation is the simulator's own result for the node table: the same flight through
/// `scenario::fly`, and the scenario written to TOML and parsed back flies to the same
/// evaluation (the front's scenario files fly as is).
#[test]
fn known_node_table_gives_the_simulators_own_result() {
    let p = horus();
    let x = horus_decision();
    assert_eq!(p.bounds().dim(), 18);
    let ev = p.evaluate(&x).unwrap();
    let sc = p.scenario_of(&x).unwrap();
    assert_eq!(sc.guidance.nodes.len(), 8);
    let s = fly(&sc, "test", &mut |_| {}).unwrap().result.summary;
    let pi = std::f64::consts::PI;
    assert_eq!(
        ev.objectives,
        vec![-s.flown_range_angle_rad / pi, s.heat_load_j_m2 / 1e9]
    );
    assert_eq!(
        ev.constraints,
        vec![
            s.peak_heat_flux_w_m2.value / 5e5 - 1.0,
            s.peak_g_load.value / 3.0 - 1.0,
            s.peak_g_load_rate_per_s.value / 0.5 - 1.0,
        ]
    );
    assert!(s.flown_range_angle_rad > 0.1, "{s:?}");
    let text = scenario_to_toml(&sc);
    let back = parse_scenario(&text, "front.toml", std::path::Path::new(".")).unwrap();
    assert_eq!(p.evaluate_scenario(&back), ev, "{text}");
}

/// `g <= 0` is feasible: a peak below its limit gives a negative value, above a positive one
/// (eq. 4.9-4.11: the violation starts at the limit).
#[test]
fn constraints_have_the_feasible_sign() {
    let p = horus();
    let sc = p.scenario_of(&horus_decision()).unwrap();
    let mut s = fly(&sc, "test", &mut |_| {}).unwrap().result.summary;
    let set = |s: &mut crate::sim::Summary, q: f64, g: f64, gd: f64| {
        s.peak_heat_flux_w_m2.value = q;
        s.peak_g_load.value = g;
        s.peak_g_load_rate_per_s.value = gd;
    };
    set(&mut s, 4e5, 2.4, 0.25);
    let ev = p.evaluation_of(&s);
    for (c, want) in ev.constraints.iter().zip([-0.2, -0.2, -0.5]) {
        assert!((c - want).abs() < 1e-12, "{:?}", ev.constraints);
    }
    set(&mut s, 6e5, 3.6, 1.0);
    let ev = p.evaluation_of(&s);
    for (c, want) in ev.constraints.iter().zip([0.2, 0.2, 1.0]) {
        assert!((c - want).abs() < 1e-12, "{:?}", ev.constraints);
    }
    s.termination = crate::sim::TerminationReason::MaxTime;
    assert!(p.evaluation_of(&s).objectives.iter().all(|v| v.is_nan()));
}

/// A variable-length individual (any number of free nodes, genes in any order, repeated
/// energies) maps to a valid node table with the fixed end nodes.
#[test]
fn variable_length_individuals_map_to_valid_tables() {
    let p = horus();
    let enc = p.encoding().clone();
    let planet = crate::env::Planet::earth();
    for k in 2..=6usize {
        let mut genes = Vec::new();
        for i in 0..k {
            // Unsorted energies, and a repeat for k >= 4.
            let e = if i == 3 {
                0.5
            } else {
                0.1 + 0.85 * ((i * 7 % k) as f64 + 0.5) / k as f64
            };
            genes.extend([e, 10.0 + i as f64, 80.0 - i as f64]);
        }
        if k >= 4 {
            genes[0] = 0.5;
        }
        let table = enc.table_of(&genes);
        assert_eq!(table[0], [1.0, 40f64.to_radians(), 0.0]);
        assert_eq!(table[table.len() - 1], [0.0, 0.0, 0.0]);
        assert!(table.windows(2).all(|w| w[0][0] > w[1][0]), "{table:?}");
        let expect = if k >= 4 { k + 1 } else { k + 2 };
        assert_eq!(table.len(), expect, "{table:?}");
        let sc = p.scenario_of_table(table, None);
        build_guidance(&sc, &planet, "test").unwrap();
    }
}

/// Bank-only SRM with the entry altitude as a variable: 6 x 2 genes + 1; the altitude moves
/// the entry radius; bad settings name their field.
#[test]
fn srm_altitude_encoding_and_setting_errors() {
    let cfg = DesignConfig::preset("srm-altitude").unwrap();
    let p = cfg.problem(std::path::Path::new(".")).unwrap();
    assert_eq!(p.bounds().dim(), 13);
    let mut x: Vec<f64> = (0..6).flat_map(|i| [0.9 - 0.15 * i as f64, 30.0]).collect();
    x.push(80.0);
    let sc = p.scenario_of(&x).unwrap();
    assert_eq!(sc.entry.radius_m, sc.environment.planet.radius_m + 80e3);
    assert!(sc.guidance.nodes.iter().all(|n| n[1] == 0.0));
    let mut bad = cfg.clone();
    bad.encoding.nodes = 2;
    let e = bad.problem(std::path::Path::new(".")).unwrap_err();
    assert!(e.to_string().contains("`encoding.nodes` = 2"), "{e}");
    let mut bad = cfg;
    bad.encoding.energy = [0.0, 0.95];
    let e = bad.problem(std::path::Path::new(".")).unwrap_err();
    assert!(e.to_string().contains("`encoding.energy`"), "{e}");
    let e = DesignConfig::preset("x38").unwrap_err();
    assert!(e.to_string().contains("unknown preset"), "{e}");
}

/// The SCEA problem: a 3-free-node chromosome (5 table nodes) flies the same table as the
/// fixed-length problem's, and a chromosome outside the 4-8 node layout is an error.
#[test]
fn variable_length_problem_flies_its_table() {
    use crate::optim::chromosome::{Chromosome, CountRange, StructuredProblem};
    let v = VariableReentry::new(horus(), [4, 8]).unwrap();
    assert_eq!(v.layout().nodes().min, 2);
    assert_eq!(v.layout().nodes().max, 6);
    let legs = vec![vec![
        vec![0.3, 30.0, 60.0],
        vec![0.8, 40.0, 20.0],
        vec![0.55, 35.0, 45.0],
    ]];
    let c = Chromosome {
        fixed: vec![],
        legs,
    };
    let (table, h) = v.table_of(&c).unwrap();
    assert_eq!(h, None);
    assert_eq!(table.len(), 5);
    assert_eq!(table[1][0], 0.8);
    let direct = v
        .inner()
        .evaluate_scenario(&v.inner().scenario_of_table(table, None));
    assert_eq!(v.evaluate(&c).unwrap(), direct);
    let short = Chromosome {
        fixed: vec![],
        legs: vec![vec![vec![0.5, 30.0, 40.0]]],
    };
    assert!(v.evaluate(&short).is_err());
    // One leg: the legs are not skip passes (the whole flight flies one energy-indexed
    // table), and the nodes carry no optional genes. A second leg is a dimension error.
    assert_eq!(v.layout().legs(), CountRange { min: 1, max: 1 });
    assert!(v.layout().optional().is_none());
    let two_legs = Chromosome {
        fixed: vec![],
        legs: vec![
            vec![vec![0.8, 40.0, 20.0]; 2],
            vec![vec![0.3, 30.0, 60.0]; 2],
        ],
    };
    assert!(matches!(
        v.evaluate(&two_legs),
        Err(crate::optim::EvalError::Dimension {
            expected: 1,
            got: 2
        })
    ));
}

/// The padded encoding: the bounds are the largest node count's genes, then the count; a
/// padded decision keeps only its first `count` nodes; a bad length or count is an error.
#[test]
fn padded_encoding_keeps_the_first_count_nodes() {
    let v = VariableReentry::new(horus(), [4, 8]).unwrap();
    let e = v.inner().encoding().clone();
    assert_eq!(v.nodes(), [4, 8]);
    assert_eq!(v.padded_dim(), 6 * 3 + 1);
    let (lo, hi) = v.padded_bounds();
    assert_eq!((lo.len(), hi.len()), (19, 19));
    assert_eq!(&lo[..3], &[e.energy[0], e.alpha_deg[0], e.sigma_deg[0]]);
    assert_eq!(&hi[15..18], &[e.energy[1], e.alpha_deg[1], e.sigma_deg[1]]);
    assert_eq!((lo[18], hi[18]), (2.0, 6.0));
    let b = e.bounds().unwrap();
    assert_eq!(b.lower(), &lo[..18]);
    assert_eq!(b.upper(), &hi[..18]);
    let mut x: Vec<f64> = (0..18).map(f64::from).collect();
    x.push(2.6);
    let c = v.chromosome_of_padded(&x).unwrap();
    assert!(c.fixed.is_empty());
    assert_eq!(
        c.legs,
        vec![vec![
            vec![0.0, 1.0, 2.0],
            vec![3.0, 4.0, 5.0],
            vec![6.0, 7.0, 8.0]
        ]]
    );
    x[18] = 6.6;
    let err = v.chromosome_of_padded(&x).unwrap_err().to_string();
    assert!(err.contains("= 6.6: must round to 2 ..= 6"), "{err}");
    x[18] = f64::NAN;
    assert!(v.chromosome_of_padded(&x).is_err());
    let err = v.chromosome_of_padded(&x[..5]).unwrap_err().to_string();
    assert!(err.contains("decision has 5 variables"), "{err}");
    assert!(v.chromosome_of_padded(&[]).is_err());
}

/// With a target range the first objective is the miss distance |theta - target| / pi of
/// the same flight, the heat load and constraints unchanged; a bad target names the field.
#[test]
fn target_range_makes_the_miss_distance_the_first_objective() {
    let x = horus_decision();
    let plain = horus().evaluate(&x).unwrap();
    let theta = -plain.objectives[0] * std::f64::consts::PI;
    for target_deg in [40.0, 120.0] {
        let mut c = DesignConfig::preset("horus-2b").unwrap();
        c.objectives.target_range_deg = Some(target_deg);
        let p = c.problem(std::path::Path::new(".")).unwrap();
        let ev = p.evaluate(&x).unwrap();
        let miss = (theta - f64::to_radians(target_deg)).abs() / std::f64::consts::PI;
        assert!((ev.objectives[0] - miss).abs() < 1e-12, "{ev:?} vs {miss}");
        assert!(ev.objectives[0] >= 0.0);
        assert_eq!(ev.objectives[1], plain.objectives[1]);
        assert_eq!(ev.constraints, plain.constraints);
        // The plots' axis names the miss, not the range.
        assert_eq!(
            c.objectives.labels()[0],
            "f_r = |theta - theta_target|/pi [-]"
        );
    }
    assert_eq!(
        DesignConfig::preset("horus-2b")
            .unwrap()
            .objectives
            .labels()[0],
        "f_r = -theta/pi [-]"
    );
    let mut c = DesignConfig::preset("horus-2b").unwrap();
    c.objectives.target_range_deg = Some(-5.0);
    let e = c
        .problem(std::path::Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(e.contains("objectives.target_range_deg"), "{e}");
}
