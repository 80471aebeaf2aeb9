//! SCEA tests: bad settings, determinism (tell order, threads), checkpoint/resume, free and
//! dictated chromosome lengths, convergence with fixed seeds on the variable-length problems
//! and on ZDT1/DTLZ2 as fixed-length chromosomes (thresholds from measured runs,
//! docs/reference/optimisers.md; heavy runs `#[ignore]`d).

use std::sync::Arc;

use super::*;
use crate::optim::algorithm::Algorithm;
use crate::optim::chromosome::{CountRange, FixedLength, Layout};
use crate::optim::error::OptimError;
use crate::optim::error::{ConfigError, EvalError};
use crate::optim::evaluate::{Rayon, Serial, evolve};
use crate::optim::hypervolume::hypervolume;
use crate::optim::observe::NoObserver;
use crate::optim::population::Individual;
use crate::optim::population::feasible_front;
use crate::optim::problem::Evaluation;
use crate::optim::problem::{Bounds, Problem};
use crate::optim::problems::{Dtlz, OptionalNodes, TestProblem, Vlmop, Zdt};
use crate::optim::rng::OptimRng;
use crate::optim::weights::WeightGeneration;

fn scea(population: usize, new_genes: NewGenes, seed: u64) -> Scea {
    Scea::new(
        SceaConfig {
            moead: MoeadConfig {
                population,
                neighbours: 20.min(population / 4).max(2),
                ..MoeadConfig::default()
            },
            new_genes,
            ..SceaConfig::default()
        },
        seed,
    )
}

fn run<P: StructuredProblem>(mut alg: Scea, p: &P, gens: u64) -> Scea {
    evolve(&mut alg, p, &Serial, gens, &mut NoObserver).unwrap();
    alg
}

/// Free counts: 1-3 legs of 1-4 one-gene nodes; `n` nodes in all (1..=12) and the mean
/// squared distance of the genes from 0.5 give `f1 = (n - 1) / 11`,
/// `f2 = (1 - f1)(1 + 10 d)`: twelve front points, one per total node count, at `d = 0`.
struct Nodes(Layout);

impl Nodes {
    fn new() -> Self {
        Self(
            Layout::new(
                None,
                CountRange { min: 1, max: 3 },
                CountRange { min: 1, max: 4 },
                Bounds::uniform(1, 0.0, 1.0).unwrap(),
            )
            .unwrap(),
        )
    }
}

impl Problem for Nodes {
    type Decision = Chromosome;
    fn objectives(&self) -> usize {
        2
    }
    fn evaluate(&self, c: &Chromosome) -> Result<Evaluation, EvalError> {
        self.0.check(c, None)?;
        let genes: Vec<f64> = c.legs.iter().flatten().map(|node| node[0]).collect();
        let n = genes.len();
        let d = genes.iter().map(|y| (y - 0.5).powi(2)).sum::<f64>() / n as f64;
        let f1 = (n - 1) as f64 / 11.0;
        Ok(Evaluation::new(vec![f1, (1.0 - f1) * (1.0 + 10.0 * d)]))
    }
}

impl StructuredProblem for Nodes {
    fn layout(&self) -> &Layout {
        &self.0
    }
}

/// Feasible-front hypervolume over the true front's.
fn vl_ratio(alg: &Scea, p: &Vlmop) -> f64 {
    let r = p.reference_point();
    let truth = p
        .front_hypervolume(&r)
        .unwrap_or_else(|| hypervolume(&p.pareto_front(600), &r).unwrap());
    hypervolume(&feasible_front(alg.population()), &r).unwrap() / truth
}

#[test]
fn scea_bad_settings_are_typed_errors() {
    let p = Vlmop::standard(4).unwrap();
    let mut a = scea(100, NewGenes::Random, 0);
    assert!(matches!(
        a.ask(&p),
        Err(OptimError::Config(ConfigError::GridSize { above: 105, .. }))
    ));
    let mut a = Scea::new(
        SceaConfig {
            count_mutation: 2.0,
            ..SceaConfig::default()
        },
        0,
    );
    assert!(matches!(
        a.ask(&Vlmop::standard(1).unwrap()),
        Err(OptimError::Config(ConfigError::Parameter {
            name: "count_mutation",
            ..
        }))
    ));
}

#[test]
fn scea_same_seed_same_run_whatever_tell_order_and_thread_count() {
    let p = Nodes::new();
    let pool = |n| {
        Arc::new(
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap(),
        )
    };
    let make = || {
        Scea::new(
            SceaConfig {
                moead: MoeadConfig {
                    population: 20,
                    neighbours: 5,
                    batch_size: 7,
                    ..MoeadConfig::default()
                },
                ..SceaConfig::default()
            },
            42,
        )
    };
    let mut a = make();
    evolve(&mut a, &p, &Rayon::with_pool(pool(1)), 6, &mut NoObserver).unwrap();
    let mut b = make();
    evolve(&mut b, &p, &Rayon::with_pool(pool(4)), 6, &mut NoObserver).unwrap();
    let mut c = make();
    let mut order_rng = OptimRng::new(9);
    while !(c.is_initialised() && c.generation() >= 6) {
        let batch = c.ask(&p).unwrap().to_vec();
        let mut order: Vec<usize> = (0..batch.len()).collect();
        order_rng.shuffle(&mut order);
        for i in order {
            c.tell(&p, i, p.evaluate(&batch[i]).unwrap()).unwrap();
        }
    }
    assert_eq!(a, b);
    assert_eq!(a, c);
    let other = run(scea(20, NewGenes::Population, 43), &p, 6);
    assert_ne!(a.population(), other.population());
}

#[test]
fn scea_checkpoint_and_resume_give_the_bit_identical_run() {
    let vl = Vlmop::standard(1).unwrap();
    let nodes = Nodes::new();
    for genes in [NewGenes::Random, NewGenes::Population] {
        let straight = run(scea(20, genes, 5), &vl, 10);
        let first = run(scea(20, genes, 5), &vl, 4);
        let json = serde_json::to_string(&first).unwrap();
        let resumed = run(serde_json::from_str(&json).unwrap(), &vl, 6);
        assert_eq!(straight, resumed);
        let straight = run(scea(20, genes, 6), &nodes, 10);
        let first = run(scea(20, genes, 6), &nodes, 4);
        let json = serde_json::to_string(&first).unwrap();
        let resumed = run(serde_json::from_str(&json).unwrap(), &nodes, 6);
        assert_eq!(straight, resumed);
    }
}

#[test]
fn scea_chromosomes_keep_their_layout_and_dictated_lengths() {
    let vl = Vlmop::standard(2).unwrap();
    let a = run(scea(30, NewGenes::Population, 1), &vl, 10);
    for ind in a.population() {
        let c = &ind.decision;
        assert_eq!(c.node_counts(), vec![vl.length(&c.fixed)]);
    }
    let nodes = Nodes::new();
    let a = run(scea(30, NewGenes::Random, 1), &nodes, 10);
    let mut totals: Vec<usize> = a
        .population()
        .iter()
        .map(|i| {
            nodes.layout().check(&i.decision, None).unwrap();
            i.decision.len()
        })
        .collect();
    totals.sort_unstable();
    totals.dedup();
    assert!(totals.len() >= 6, "lengths {totals:?}");
}

#[test]
fn scea_finds_every_length_of_the_free_count_problem() {
    // Twelve front points, one per total node count; both gene sources.
    let p = Nodes::new();
    let mut counts = Vec::new();
    for genes in [NewGenes::Random, NewGenes::Population] {
        let a = run(scea(50, genes, 3), &p, 100);
        let mut found: Vec<usize> = a
            .population()
            .iter()
            .filter(|i| i.objectives[1] <= (1.0 - i.objectives[0]) * 1.01)
            .map(|i| i.decision.len())
            .collect();
        found.sort_unstable();
        found.dedup();
        println!("scea {genes:?} nodes: lengths on the front {found:?}");
        counts.push(found.len());
    }
    assert!(counts[0] >= SCEA_NODES_LENGTHS[0], "random: {counts:?}");
    assert!(counts[1] >= SCEA_NODES_LENGTHS[1], "population: {counts:?}");
}

// Thresholds of the ratios: the smallest ratio measured over seeds 1..=8 with these settings
// (`scea_threshold_survey`, docs/reference/optimisers.md) less about 2 %, rounded down; the tests run
// seed 1. Free-count problem (seed 3's measured lengths): 10-11 nodes (three legs) are not
// reached in 100 generations.
const SCEA_NODES_LENGTHS: [usize; 2] = [9, 8];
/// [random genes, population genes][vlmop1..=5].
const SCEA_VL: [[f64; 5]; 2] = [
    [0.95, 0.96, 0.77, 0.88, 0.80],
    [0.95, 0.96, 0.78, 0.89, 0.78],
];
const SCEA_ZDT1: f64 = 0.92;
const SCEA_DTLZ2: f64 = 0.74;

/// Li & Deb's problems with the thesis' constraint: population 100 (91 for three objectives),
/// 30 generations (20 for three objectives), seed 1, both gene sources.
#[test]
fn scea_converges_on_the_variable_length_problems() {
    let mut failures = Vec::new();
    for (k, genes) in [NewGenes::Random, NewGenes::Population]
        .into_iter()
        .enumerate()
    {
        for id in 1..=5u8 {
            let p = Vlmop::standard(id).unwrap();
            let (pop, gens) = if id <= 3 { (100, 30) } else { (91, 20) };
            let a = run(scea(pop, genes, 1), &p, gens);
            let r = vl_ratio(&a, &p);
            println!("scea {genes:?} vlmop{id} ratio {r:.4}");
            if r <= SCEA_VL[k][usize::from(id) - 1] {
                failures.push(format!("vlmop{id} {genes:?}: {r}"));
            }
            assert!(a.population().iter().filter(|i| i.is_feasible()).count() > pop / 3);
        }
    }
    assert!(failures.is_empty(), "{failures:?}");
}

/// Every variable-length problem, both gene sources, seeds 1..=3 (release: `cargo test
/// --release -p host-sim --lib scea_table -- --ignored --nocapture`).
#[test]
#[ignore = "heavy: run in release"]
fn scea_table() {
    for id in 1..=5 {
        let p = Vlmop::standard(id).unwrap();
        let pop = if id <= 3 { 100 } else { 91 };
        for gens in [10, 20, 50] {
            let mut line = format!("vlmop{id} {gens:3} gens");
            for genes in [NewGenes::Random, NewGenes::Population] {
                for seed in 1..=3 {
                    let r = vl_ratio(&run(scea(pop, genes, seed), &p, gens), &p);
                    line += &format!(" {genes:?} {r:.4}");
                }
            }
            println!("{line}");
        }
    }
}

/// The settings of `scea_converges_on_the_variable_length_problems` (and the fixed-length
/// ZDT1 run) over seeds 1..=8: the thresholds above derive from these minima (release:
/// `cargo test --release -p host-sim --lib scea_threshold_survey -- --ignored --nocapture`).
#[test]
#[ignore = "survey: run in release"]
fn scea_threshold_survey() {
    for (k, genes) in [NewGenes::Random, NewGenes::Population]
        .into_iter()
        .enumerate()
    {
        for id in 1..=5u8 {
            let p = Vlmop::standard(id).unwrap();
            let (pop, gens) = if id <= 3 { (100, 30) } else { (91, 20) };
            let ratios: Vec<f64> = (1..=8)
                .map(|seed| vl_ratio(&run(scea(pop, genes, seed), &p, gens), &p))
                .collect();
            let min = ratios.iter().copied().fold(f64::INFINITY, f64::min);
            let shown: Vec<String> = ratios.iter().map(|r| format!("{r:.4}")).collect();
            println!(
                "scea {genes:?} vlmop{id}: {} (min {min:.4}, threshold {})",
                shown.join(" "),
                SCEA_VL[k][usize::from(id) - 1]
            );
        }
    }
    let zdt1 = FixedLength::new(TestProblem::Zdt(Zdt::standard(1).unwrap()));
    let r = [1.1, 1.1];
    let truth = zdt1.inner().front_hypervolume(&r, 2000).unwrap();
    let ratios: Vec<String> = (1..=8)
        .map(|seed| {
            let a = run(scea(100, NewGenes::Population, seed), &zdt1, 250);
            format!(
                "{:.4}",
                hypervolume(&feasible_front(a.population()), &r).unwrap() / truth
            )
        })
        .collect();
    println!(
        "scea zdt1 fixed length: {} (threshold {SCEA_ZDT1})",
        ratios.join(" ")
    );
    let dtlz2 = FixedLength::new(TestProblem::Dtlz(Dtlz::standard(2, 3).unwrap()));
    let r = dtlz2.inner().reference_point();
    let truth = dtlz2.inner().front_hypervolume(&r, 2000).unwrap();
    let ratios: Vec<String> = (1..=8)
        .map(|seed| {
            let a = run(fixed_dtlz2_scea(seed), &dtlz2, 100);
            format!(
                "{:.4}",
                hypervolume(&feasible_front(a.population()), &r).unwrap() / truth
            )
        })
        .collect();
    println!(
        "scea dtlz2 fixed length: {} (threshold {SCEA_DTLZ2})",
        ratios.join(" ")
    );
}

/// SCEA on DTLZ2 as a fixed-length chromosome: population 91 on the grid, MOEA/D defaults.
fn fixed_dtlz2_scea(seed: u64) -> Scea {
    Scea::new(
        SceaConfig {
            moead: MoeadConfig {
                population: 91,
                weights: WeightGeneration::Grid,
                ..MoeadConfig::default()
            },
            ..SceaConfig::default()
        },
        seed,
    )
}

#[test]
#[ignore = "heavy in debug builds: run in release"]
fn scea_converges_on_zdt1_and_dtlz2_as_fixed_length_chromosomes() {
    let zdt1 = FixedLength::new(TestProblem::Zdt(Zdt::standard(1).unwrap()));
    let a = run(scea(100, NewGenes::Population, 1), &zdt1, 250);
    let r = [1.1, 1.1];
    let ratio = hypervolume(&feasible_front(a.population()), &r).unwrap()
        / zdt1.inner().front_hypervolume(&r, 2000).unwrap();
    println!("scea zdt1 {ratio:.4}");
    assert!(ratio > SCEA_ZDT1, "zdt1 {ratio}");
    let dtlz2 = FixedLength::new(TestProblem::Dtlz(Dtlz::standard(2, 3).unwrap()));
    let a = run(fixed_dtlz2_scea(1), &dtlz2, 100);
    let r = dtlz2.inner().reference_point();
    let ratio = hypervolume(&feasible_front(a.population()), &r).unwrap()
        / dtlz2.inner().front_hypervolume(&r, 2000).unwrap();
    println!("scea dtlz2 {ratio:.4}");
    assert!(ratio > SCEA_DTLZ2, "dtlz2 {ratio}");
}

/// SCEA inherits MOEA/D's opt-in external archive: the population is unchanged, the archive
/// holds feasible mutually non-dominated chromosomes within its capacity and checkpoints.
#[test]
fn scea_external_archive_leaves_the_run_unchanged_and_checkpoints() {
    let p = Vlmop::standard(1).unwrap();
    let make = |archive| {
        Scea::new(
            SceaConfig {
                moead: MoeadConfig {
                    population: 20,
                    neighbours: 5,
                    archive,
                    ..MoeadConfig::default()
                },
                new_genes: NewGenes::Population,
                ..SceaConfig::default()
            },
            6,
        )
    };
    let plain = run(make(None), &p, 10);
    let with = run(make(Some(8)), &p, 10);
    let pop = |a: &Scea| <Scea as Algorithm<Vlmop>>::population(a).to_vec();
    assert_eq!(pop(&plain), pop(&with));
    assert!(<Scea as Algorithm<Vlmop>>::external_archive(&plain).is_none());
    let archive = <Scea as Algorithm<Vlmop>>::external_archive(&with).unwrap();
    assert!(!archive.is_empty() && archive.len() <= 8);
    assert!(archive.iter().all(|i| i.is_feasible()));
    assert_eq!(feasible_front(archive).len(), archive.len());
    let back: Scea = serde_json::from_str(&serde_json::to_string(&with).unwrap()).unwrap();
    assert_eq!(back, with);
}

fn optional_scores(p: &OptionalNodes, pop: &[Individual<Chromosome>]) -> (f64, f64) {
    p.scores(pop).unwrap()
}

#[test]
fn scea_optional_genes_keep_the_layout_and_both_presences_occur() {
    let p = OptionalNodes::standard().unwrap();
    for genes in [NewGenes::Random, NewGenes::Population] {
        let a = run(scea(30, genes, 2), &p, 10);
        let (mut with, mut without) = (0, 0);
        for ind in a.population() {
            p.layout().check(&ind.decision, None).unwrap();
            for node in ind.decision.legs.iter().flatten() {
                if p.layout().carries_optional(node) {
                    with += 1;
                } else {
                    without += 1;
                }
            }
        }
        assert!(
            with > 0 && without > 0,
            "{genes:?}: {with} with, {without} without"
        );
    }
}

/// Seed survey on [`OptionalNodes`] (population 100, 100 generations, both gene sources):
/// the hypervolume ratio and the share of front members with the optimal presence pattern,
/// per seed 1..=8 (`cargo test --release -p host-sim --lib scea_optional_survey -- --ignored
/// --nocapture`).
#[test]
#[ignore = "survey: run in release"]
fn scea_optional_survey() {
    let p = OptionalNodes::standard().unwrap();
    for gens in [20, 30, 100] {
        for genes in [NewGenes::Random, NewGenes::Population] {
            let rows: Vec<String> = (1..=8)
                .map(|seed| {
                    let a = run(scea(100, genes, seed), &p, gens);
                    let (ratio, share) = optional_scores(&p, a.population());
                    format!("{ratio:.4}/{share:.2}")
                })
                .collect();
            println!("scea {genes:?} optional {gens} gens: {}", rows.join(" "));
        }
    }
}

/// Thresholds at 30 generations: the smallest ratio and share of `scea_optional_survey` over
/// seeds 1..=8 (ratios 0.9662 random genes, 0.9612 population genes; shares 0.99 both; seed 1
/// 0.9721/1.00 and 0.9695/1.00) less about 2 % (ratio) or 0.05 (share), rounded down;
/// [random genes, population genes]. (At 20 generations the ratios are 0.89-0.97 and the
/// shares 0.92-1.00, at 100 generations 0.988-0.992 and 1.00.)
const SCEA_OPTIONAL: [(f64, f64); 2] = [(0.94, 0.94), (0.94, 0.94)];

#[test]
fn scea_finds_the_optional_gene_pattern() {
    let p = OptionalNodes::standard().unwrap();
    for (k, genes) in [NewGenes::Random, NewGenes::Population]
        .into_iter()
        .enumerate()
    {
        let a = run(scea(100, genes, 1), &p, 30);
        let (ratio, share) = optional_scores(&p, a.population());
        println!("scea {genes:?} optional: ratio {ratio:.4}, pattern share {share:.2}");
        let (min_ratio, min_share) = SCEA_OPTIONAL[k];
        assert!(ratio > min_ratio, "{genes:?}: ratio {ratio}");
        assert!(share > min_share, "{genes:?}: share {share}");
    }
}

/// The presence of the optional group follows the module documentation's rule: with CR = 1
/// the child takes parent `a`'s presence where the parents differ, the base's where they
/// agree; with `count_mutation` = 1 it flips; new groups come from a parent that has one.
#[test]
fn scea_presence_of_the_optional_group_follows_the_parents() {
    use super::variation::{Settings, child};
    let p = OptionalNodes::new(1).unwrap();
    let c = |x: f64, node: Vec<f64>| Chromosome {
        fixed: vec![x],
        legs: vec![vec![node]],
    };
    let settings = |cr: f64, count_mutation: f64| Settings {
        cr,
        f: 0.5,
        eta_m: 20.0,
        mutation_probability: Some(0.0),
        count_mutation,
        new_genes: NewGenes::Population,
    };
    let without = c(0.5, vec![0.3]);
    let with = c(0.5, vec![0.3, 0.8]);
    let mut rng = OptimRng::new(4);
    let carries = |ch: &Chromosome| p.layout().carries_optional(&ch.legs[0][0]);
    for _ in 0..20 {
        // Parents differ: a's presence.
        let k = child(&p, &without, &with, &without, &settings(1.0, 0.0), &mut rng);
        assert!(carries(&k));
        // The new group is the parent's (a and b both carry it: one of theirs).
        assert_eq!(k.legs[0][0][1], 0.8);
        let k = child(&p, &with, &without, &with, &settings(1.0, 0.0), &mut rng);
        assert!(!carries(&k));
        // Parents agree: the base's.
        let k = child(&p, &with, &without, &without, &settings(1.0, 0.0), &mut rng);
        assert!(carries(&k));
        assert_eq!(k.legs[0][0][1], 0.8, "kept from the base");
        let k = child(&p, &without, &with, &with, &settings(1.0, 0.0), &mut rng);
        assert!(!carries(&k));
        // No crossover: the base's; mutation 1: flipped.
        let k = child(&p, &without, &with, &without, &settings(0.0, 0.0), &mut rng);
        assert!(!carries(&k));
        let k = child(
            &p,
            &without,
            &without,
            &without,
            &settings(0.0, 1.0),
            &mut rng,
        );
        assert!(
            carries(&k),
            "flipped on, a random group (no parent has one)"
        );
        p.layout().check(&k, None).unwrap();
        let k = child(&p, &with, &with, &with, &settings(0.0, 1.0), &mut rng);
        assert!(!carries(&k));
    }
}

/// A variable number of legs with a known answer (the skip-entry structure, thesis Fig. 4.4:
/// one leg per atmospheric pass, later passes needing more nodes): 1-3 legs of 1-3 one-gene
/// nodes. With `L` legs, leg `l` (from 0) should have `l + 1` nodes whose genes all equal
/// `t = (l + 1) / (L + 1)` (the targets move with the number of legs, as the passes of a
/// skip trajectory do with the number of skips): `g = sum (y - t)^2 + 0.1 sum_l |n_l - (l +
/// 1)|`, `a = (L - 1) / 2`, `f = ((1 + g) a, (1 + g) (1 - a))`. The front is the three
/// points (0, 1), (0.5, 0.5), (1, 0), each reached only with its number of legs, those node
/// counts and those genes.
struct Legs(Layout);

impl Legs {
    fn new() -> Self {
        Self(
            Layout::new(
                None,
                CountRange { min: 1, max: 3 },
                CountRange { min: 1, max: 3 },
                Bounds::uniform(1, 0.0, 1.0).unwrap(),
            )
            .unwrap(),
        )
    }

    fn g(c: &Chromosome) -> f64 {
        let legs = c.legs.len() as f64;
        c.legs
            .iter()
            .enumerate()
            .map(|(l, leg)| {
                let t = (l + 1) as f64 / (legs + 1.0);
                let d: f64 = leg.iter().map(|n| (n[0] - t).powi(2)).sum();
                d + 0.1 * (leg.len() as f64 - (l + 1) as f64).abs()
            })
            .sum()
    }
}

impl Problem for Legs {
    type Decision = Chromosome;
    fn objectives(&self) -> usize {
        2
    }
    fn evaluate(&self, c: &Chromosome) -> Result<Evaluation, EvalError> {
        self.0.check(c, None)?;
        let g = Self::g(c);
        let a = (c.legs.len() - 1) as f64 / 2.0;
        Ok(Evaluation::new(vec![(1.0 + g) * a, (1.0 + g) * (1.0 - a)]))
    }
}

impl StructuredProblem for Legs {
    fn layout(&self) -> &Layout {
        &self.0
    }
}

/// Per number of legs 1..=3, the smallest `g` of the population's members with that many legs
/// (`INFINITY`: none).
fn legs_best_g(pop: &[Individual<Chromosome>]) -> [f64; 3] {
    let mut best = [f64::INFINITY; 3];
    for i in pop {
        let l = i.decision.legs.len() - 1;
        best[l] = best[l].min(Legs::g(&i.decision));
    }
    best
}

#[test]
fn legs_problem_has_the_known_answer() {
    let p = Legs::new();
    for legs in 1..=3usize {
        let c = Chromosome {
            fixed: Vec::new(),
            legs: (0..legs)
                .map(|l| vec![vec![(l + 1) as f64 / (legs + 1) as f64]; l + 1])
                .collect(),
        };
        let f = p.evaluate(&c).unwrap().objectives;
        let a = (legs - 1) as f64 / 2.0;
        assert_eq!(f, vec![a, 1.0 - a]);
        // A node more or less on the last leg, or a gene off its target, is worse.
        let mut count = c.clone();
        if legs < 3 {
            count.legs[legs - 1].push(vec![0.5]);
        } else {
            count.legs[legs - 1].pop();
        }
        let mut off = c.clone();
        off.legs[0][0][0] += 0.1;
        for worse in [count, off] {
            let e = p.evaluate(&worse).unwrap().objectives;
            assert!(Legs::g(&worse) >= 0.01 - 1e-12, "{worse:?}");
            assert!(
                e.iter().zip(&f).all(|(e, f)| e >= f) && e != f,
                "{e:?} {f:?}"
            );
        }
    }
}

/// Seed survey on [`Legs`] (population 30, 50 generations, both gene sources): `g` of the best
/// member with 1, 2 and 3 legs per seed 1..=8 (`cargo test -p host-sim --lib
/// scea_legs_survey -- --ignored --nocapture`).
#[test]
#[ignore = "survey"]
fn scea_legs_survey() {
    let p = Legs::new();
    for genes in [NewGenes::Random, NewGenes::Population] {
        let rows: Vec<String> = (1..=8)
            .map(|seed| {
                let a = run(scea(30, genes, seed), &p, 50);
                let b = legs_best_g(a.population());
                format!("{:.1e}/{:.1e}/{:.1e}", b[0], b[1], b[2])
            })
            .collect();
        println!("scea {genes:?} legs: {}", rows.join(" "));
    }
}

/// Thresholds on the best `g` per number of legs (seed 1, population 30, 50 generations):
/// the largest of `scea_legs_survey` over seeds 1..=8 (3.3e-3 random genes, 6.5e-4
/// population genes, both for three legs; seed 1 5.0e-4 and 3.2e-4), rounded up to a power
/// of ten; [random genes, population genes]. A wrong number of nodes on a leg costs 0.1.
const SCEA_LEGS_G: [f64; 2] = [1e-2, 1e-3];

#[test]
fn scea_finds_every_number_of_legs_of_the_legs_problem() {
    let p = Legs::new();
    for (k, genes) in [NewGenes::Random, NewGenes::Population]
        .into_iter()
        .enumerate()
    {
        let a = run(scea(30, genes, 1), &p, 50);
        for ind in a.population() {
            p.layout().check(&ind.decision, None).unwrap();
        }
        let best = legs_best_g(a.population());
        println!("scea {genes:?} legs: best g per leg count {best:?}");
        assert!(
            best.iter().all(|&g| g < SCEA_LEGS_G[k]),
            "{genes:?}: {best:?}"
        );
    }
}
