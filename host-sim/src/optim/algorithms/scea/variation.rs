//! SCEA's variation of structured chromosomes (thesis Algorithm 1), built on MOEA/D's DE step
//! and polynomial mutation ([`crate::optim::operators`]).
//!
//! Child of base `x_n` with parents `a`, `b`, highest level first:
//! 1. fixed genes: DE step and bound repair (`de_step`);
//! 2. integer genes: the number of legs, then the nodes of each leg: with probability `CR`
//!    `round(n + F (n_a - n_b))` (a parent without that leg counts as the base), then with
//!    probability `count_mutation` a step of +-1, clamped to the layout's range; or the counts
//!    the problem dictates from the child's fixed genes;
//! 3. structure: legs and nodes beyond the new counts are deleted from the end; missing ones
//!    are appended with new genes ([`NewGenes`]);
//! 4. real genes of every node the base had: DE step where both parents have that node too;
//! 5. polynomial mutation of all real genes.
//!
//! With an optional group of node genes ([`Layout::with_optional`]) every node the base had
//! also evolves whether it carries the group, a binary gene: with probability `CR`, where the
//! two parents differ at that node, the child takes parent `a`'s presence (the DE step
//! `p + F (p_a - p_b)` taken in the direction of the difference), then with probability
//! `count_mutation` it flips. The group's genes: DE step where the base and both parents
//! carry it, the base's where only the base does, new genes ([`NewGenes`]: a parent's group at
//! that node, else random) where the base did not. An appended node comes with the group of
//! the parent node it copies, or, random, carries it with probability 1/2. Without a group
//! none of this draws a random number: such runs are those of a layout without it.

use serde::{Deserialize, Serialize};

use crate::optim::chromosome::{Chromosome, CountRange, Layout, StructuredProblem};
use crate::optim::operators::{de_step, polynomial_mutation, random_point};
use crate::optim::rng::OptimRng;

/// Where the genes of an appended node come from (`--scea-genes`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum NewGenes {
    /// Uniformly random inside the node bounds (the thesis' SCEA).
    Random,
    /// From the population (the thesis' recommendation, sec. 10.2: "data taken from
    /// individuals in the population that use these nodes"): the same node (leg, position) of
    /// one of the two mating parents, population members from the child's neighbourhood
    /// (drawn between them when both have it); random when neither has it.
    #[value(alias = "history")]
    Population,
}

/// A uniformly random count in the range.
pub fn random_count(range: CountRange, rng: &mut OptimRng) -> usize {
    range.min + rng.below(range.max - range.min + 1)
}

/// A random node of the layout: genes inside the node bounds and, with an optional group,
/// with probability 1/2 that group's genes too.
pub fn random_node(layout: &Layout, rng: &mut OptimRng) -> Vec<f64> {
    let mut node = random_point(layout.node(), rng);
    if let Some(optional) = layout.optional()
        && rng.uniform() < 0.5
    {
        node.extend(random_point(optional, rng));
    }
    node
}

/// A random chromosome of the layout (counts dictated by the problem where it does so).
pub fn random_chromosome<P: StructuredProblem>(problem: &P, rng: &mut OptimRng) -> Chromosome {
    let layout = problem.layout();
    let fixed = layout
        .fixed()
        .map_or_else(Vec::new, |b| random_point(b, rng));
    let counts = problem.derived_nodes(&fixed).unwrap_or_else(|| {
        let legs = random_count(layout.legs(), rng);
        (0..legs)
            .map(|_| random_count(layout.nodes(), rng))
            .collect()
    });
    let legs = counts
        .iter()
        .map(|&n| (0..n).map(|_| random_node(layout, rng)).collect())
        .collect();
    Chromosome { fixed, legs }
}

/// Integer DE step with mutation, clamped to `range`.
fn evolve_count(
    base: usize,
    a: usize,
    b: usize,
    settings: &Settings,
    range: CountRange,
    rng: &mut OptimRng,
) -> usize {
    let mut n = base as f64;
    if rng.uniform() < settings.cr {
        n = (n + settings.f * (a as f64 - b as f64)).round();
    }
    if rng.uniform() < settings.count_mutation {
        n += if rng.uniform() < 0.5 { -1.0 } else { 1.0 };
    }
    n.clamp(range.min as f64, range.max as f64) as usize
}

/// The variation settings (from the SCEA configuration).
#[derive(Clone, Copy, Debug)]
pub struct Settings {
    /// DE crossover probability.
    pub cr: f64,
    /// DE weight.
    pub f: f64,
    /// Polynomial-mutation index.
    pub eta_m: f64,
    /// Per-gene mutation probability (`None`: 1 / number of real genes of the child).
    pub mutation_probability: Option<f64>,
    /// Probability of a +-1 step of each count gene.
    pub count_mutation: f64,
    /// Source of appended genes.
    pub new_genes: NewGenes,
}

/// Genes for node `(l, k)` of a child of parents `a`, `b`.
fn new_node(
    layout: &Layout,
    (l, k): (usize, usize),
    parents: [&Chromosome; 2],
    new_genes: NewGenes,
    rng: &mut OptimRng,
) -> Vec<f64> {
    if new_genes == NewGenes::Population {
        let node = |c: &Chromosome| c.legs.get(l).and_then(|leg| leg.get(k)).cloned();
        match (node(parents[0]), node(parents[1])) {
            (Some(x), Some(y)) => return if rng.uniform() < 0.5 { x } else { y },
            (Some(x), None) | (None, Some(x)) => return x,
            (None, None) => {}
        }
    }
    random_node(layout, rng)
}

/// Whether the child of a node carrying the optional group as `base`, `a`, `b` do (a parent
/// without the node counts as the base) carries it (see the module documentation).
fn evolve_presence(base: bool, a: bool, b: bool, settings: &Settings, rng: &mut OptimRng) -> bool {
    let mut p = base;
    if rng.uniform() < settings.cr && a != b {
        p = a;
    }
    if rng.uniform() < settings.count_mutation {
        p = !p;
    }
    p
}

/// The node of the child at `(l, k)` whose base had it (`x`; `pa`, `pb` the parents' same
/// node, if they have it; `scratch` is the DE step's buffer).
fn inherited_node<'a>(
    layout: &Layout,
    x: &[f64],
    pa: Option<&'a Vec<f64>>,
    pb: Option<&'a Vec<f64>>,
    settings: &Settings,
    rng: &mut OptimRng,
    scratch: &mut Vec<f64>,
) -> Vec<f64> {
    let d = layout.node().dim();
    let mut out = match (pa, pb) {
        (Some(pa), Some(pb)) => {
            de_step(
                &x[..d],
                &pa[..d],
                &pb[..d],
                settings.f,
                settings.cr,
                layout.node(),
                rng,
                scratch,
            );
            scratch.clone()
        }
        _ => x[..d].to_vec(),
    };
    let Some(optional) = layout.optional() else {
        return out;
    };
    let carries = |n: &[f64]| layout.carries_optional(n);
    let own = carries(x);
    let of = |p: Option<&Vec<f64>>| p.map_or(own, |n| carries(n));
    if !evolve_presence(own, of(pa), of(pb), settings, rng) {
        return out;
    }
    let group = |p: Option<&'a Vec<f64>>| p.and_then(|n| layout.optional_genes(n));
    match (own, group(pa), group(pb)) {
        (true, Some(ga), Some(gb)) => {
            de_step(
                &x[d..],
                ga,
                gb,
                settings.f,
                settings.cr,
                optional,
                rng,
                scratch,
            );
            out.extend_from_slice(scratch);
        }
        (true, _, _) => out.extend_from_slice(&x[d..]),
        (false, ga, gb) => {
            let from = if settings.new_genes == NewGenes::Population {
                match (ga, gb) {
                    (Some(ga), Some(gb)) => Some(if rng.uniform() < 0.5 { ga } else { gb }),
                    (g, None) | (None, g) => g,
                }
            } else {
                None
            };
            match from {
                Some(g) => out.extend_from_slice(g),
                None => out.extend(random_point(optional, rng)),
            }
        }
    }
    out
}

/// Polynomial mutation of a node's genes (its own, then the optional group if it has it).
fn mutate_node(layout: &Layout, node: &mut [f64], rate: f64, eta_m: f64, rng: &mut OptimRng) {
    let d = layout.node().dim();
    let (own, group) = node.split_at_mut(d.min(node.len()));
    polynomial_mutation(own, layout.node(), rate, eta_m, rng);
    if let (Some(optional), false) = (layout.optional(), group.is_empty()) {
        polynomial_mutation(group, optional, rate, eta_m, rng);
    }
}

/// The child of `base` with parents `a`, `b` (see the module documentation).
pub fn child<P: StructuredProblem>(
    problem: &P,
    base: &Chromosome,
    a: &Chromosome,
    b: &Chromosome,
    settings: &Settings,
    rng: &mut OptimRng,
) -> Chromosome {
    let layout = problem.layout();
    // 1. Fixed genes.
    let mut fixed = Vec::with_capacity(base.fixed.len());
    if let Some(bounds) = layout.fixed() {
        de_step(
            &base.fixed,
            &a.fixed,
            &b.fixed,
            settings.f,
            settings.cr,
            bounds,
            rng,
            &mut fixed,
        );
    }
    // 2. Integer genes, highest level first.
    let counts = problem.derived_nodes(&fixed).unwrap_or_else(|| {
        let legs = evolve_count(
            base.legs.len(),
            a.legs.len(),
            b.legs.len(),
            settings,
            layout.legs(),
            rng,
        );
        (0..legs)
            .map(|l| {
                let own = base.legs.get(l).map_or(0, Vec::len);
                let n_base = if own == 0 { layout.nodes().min } else { own };
                let of = |c: &Chromosome| c.legs.get(l).map_or(n_base, Vec::len);
                evolve_count(n_base, of(a), of(b), settings, layout.nodes(), rng)
            })
            .collect()
    });
    // 3. Structure, then 4. real genes.
    let mut legs: Vec<Vec<Vec<f64>>> = Vec::with_capacity(counts.len());
    let mut node = Vec::new();
    for (l, &n) in counts.iter().enumerate() {
        let mut leg = Vec::with_capacity(n);
        for k in 0..n {
            let inherited = base.legs.get(l).and_then(|leg| leg.get(k));
            let Some(x) = inherited else {
                leg.push(new_node(layout, (l, k), [a, b], settings.new_genes, rng));
                continue;
            };
            let pa = a.legs.get(l).and_then(|leg| leg.get(k));
            let pb = b.legs.get(l).and_then(|leg| leg.get(k));
            leg.push(inherited_node(layout, x, pa, pb, settings, rng, &mut node));
        }
        legs.push(leg);
    }
    let mut c = Chromosome { fixed, legs };
    // 5. Mutation.
    let rate = settings
        .mutation_probability
        .unwrap_or(1.0 / c.len().max(1) as f64);
    if let Some(bounds) = layout.fixed() {
        polynomial_mutation(&mut c.fixed, bounds, rate, settings.eta_m, rng);
    }
    for leg in &mut c.legs {
        for node in leg {
            mutate_node(layout, node, rate, settings.eta_m, rng);
        }
    }
    // A mutated fixed gene may change the dictated counts: re-shape (delete or append).
    if let Some(counts) = problem.derived_nodes(&c.fixed) {
        for (l, &n) in counts.iter().enumerate() {
            if c.legs.len() <= l {
                c.legs.push(Vec::new());
            }
            c.legs[l].truncate(n);
            for k in c.legs[l].len()..n {
                let node = new_node(layout, (l, k), [a, b], settings.new_genes, rng);
                c.legs[l].push(node);
            }
        }
        c.legs.truncate(counts.len());
    }
    c
}
