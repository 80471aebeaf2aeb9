//! Variable-length MHACO ([`VlMhaco`]): MHACO's archive, ranking, pheromone weights and
//! standard-deviation schedule over structured chromosomes ([`Chromosome`],
//! [`StructuredProblem`]), the thesis' recommendation (sec. 10.2: "MHACO might provide a
//! valuable algorithm for variable length individuals as it already stores a solution archive
//! and thus has historical data readily available").
//!
//! Everything but the ant construction is [`super::Mhaco`]'s (pagmo `maco`): the archive of
//! `ker` members is ranked by fronts and exclusive hypervolume contribution
//! ([`super::archive`]), the kernel of an ant is an archive member picked by the rank weights,
//! `q`, `threshold`, `gen_mark`, `evalstop` and `focus` mean the same. An ant around kernel `K`
//! is built highest level first:
//! 1. **fixed genes**: MHACO's Gaussian around `K`'s, with the per-variable standard deviations
//!    of the archive's fixed genes ([`super::kernel::sigmas`]);
//! 2. **counts** (the length): either dictated by the problem from the ant's fixed genes, or
//!    drawn from the archive as integer variables, as pagmo's ant colony optimisers treat
//!    integer variables: `round(c_K + sigma_c N(0, 1))`, redrawn until inside the layout's
//!    range, where `sigma_c = (D_max - D_min) / gen_mark` is MHACO's spread formula over the
//!    archive members' counts (the number of legs; per leg position `l`, the node counts of
//!    the members that have leg `l`). An archive of one length therefore proposes only that
//!    length (the colony has converged on it), an archive of several lengths proposes those
//!    and their neighbours, the more often the longer the counts spread;
//! 3. **node genes**, aligned by position `(l, k)` as in SCEA: a node the kernel has is
//!    sampled around the kernel's genes; a node it lacks (the ant is longer) is centred on the
//!    same node of the best-ranked archive member that has it (the historical data of the
//!    recommendation), and is uniformly random only when no archive member has it. The
//!    standard deviations of position `(l, k)` come from the archive members that have that
//!    node (at least two), else from all nodes of all archive members pooled;
//! 4. **optional node genes** ([`Layout::with_optional`]): whether node `(l, k)` carries the
//!    group is an integer variable in `{0, 1}` drawn like the counts, around the presence of
//!    the node its genes are centred on, with the spread of the presences of the archive
//!    members that have node `(l, k)`. A node that carries it samples the group around the
//!    centre node's group, or, when that node lacks it, around the group of the best-ranked
//!    archive member whose node `(l, k)` carries it (uniformly random when none does), with
//!    the deviations of the members carrying it there (at least two), else of all carried
//!    groups pooled (else zero). A uniformly random node carries the group with probability
//!    1/2. Without a group none of this draws a random number.
//!
//! Ask/tell, tell-order and thread invariance, checkpoints: as [`super::Mhaco`].

use serde::{Deserialize, Serialize};

use crate::optim::algorithm::{Algorithm, Batch, check_objectives};
use crate::optim::algorithms::scea::variation::{random_chromosome, random_count, random_node};
use crate::optim::chromosome::{Chromosome, CountRange, Layout, StructuredProblem};
use crate::optim::error::OptimError;
use crate::optim::operators::random_point;
use crate::optim::population::Individual;
use crate::optim::problem::{Bounds, Evaluation};
use crate::optim::rng::OptimRng;

use super::kernel::{MAX_REDRAWS, Normal, ant, cumulative_weights, pick, sigmas};
use super::{MhacoConfig, advance, archive, select};

const NAME: &str = "vl-mhaco";

/// Variable-length MHACO state (serialisable: checkpoint and resume give the bit-identical
/// run). Settings are [`MhacoConfig`]'s.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct VlMhaco {
    config: MhacoConfig,
    rng: OptimRng,
    normal: Normal,
    /// Archive (first `archive_len`, best first), then the rest of the last batch.
    population: Vec<Individual<Chromosome>>,
    archive_len: usize,
    q: f64,
    gen_mark: u64,
    stalls: u64,
    finished: bool,
    batch: Batch<Chromosome>,
    initialised: bool,
    generation: u64,
    evaluations: u64,
}

/// MHACO's spread `D_max - D_min` of a set of values (0 for fewer than two).
fn spread(values: &mut [f64]) -> f64 {
    if values.len() < 2 {
        return 0.0;
    }
    values.sort_by(f64::total_cmp);
    let d_max = values[values.len() - 1] - values[0];
    let d_min = values
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min);
    d_max - d_min
}

/// One integer draw `round(centre + sigma N)` inside `[min, max]` (see the module docs).
fn draw_count(
    centre: usize,
    sigma: f64,
    range: CountRange,
    normal: &mut Normal,
    rng: &mut OptimRng,
) -> usize {
    if sigma == 0.0 {
        return centre.clamp(range.min, range.max);
    }
    for _ in 0..MAX_REDRAWS {
        let v = (centre as f64 + sigma * normal.draw(rng)).round();
        if v >= range.min as f64 && v <= range.max as f64 {
            return v as usize;
        }
    }
    random_count(range, rng)
}

/// The per-generation standard deviations of the archive (see the module docs).
struct Spreads {
    fixed: Vec<f64>,
    legs: f64,
    /// Per leg position: the node-count spread.
    nodes: Vec<f64>,
    /// Per node position: base-gene deviations (`None`: fewer than two members have it).
    genes: Vec<Vec<Option<Vec<f64>>>>,
    pooled: Vec<f64>,
    /// Per node position: the spread of the optional group's presence (empty without one).
    presence: Vec<Vec<f64>>,
    /// Per node position: the optional genes' deviations (`None`: fewer than two carry it).
    optional: Vec<Vec<Option<Vec<f64>>>>,
    optional_pooled: Vec<f64>,
}

/// Deviations of `rows` (at least two) in the bounds, or `None`.
fn sigmas_of(
    rows: &[&[f64]],
    bounds: &Bounds,
    gen_mark: u64,
    focus: f64,
    generation: u64,
) -> Option<Vec<f64>> {
    (rows.len() >= 2).then(|| sigmas(rows, bounds, gen_mark, focus, generation))
}

impl Spreads {
    fn new(
        archive: &[&Chromosome],
        layout: &Layout,
        gen_mark: u64,
        focus: f64,
        generation: u64,
    ) -> Self {
        let g = gen_mark as f64;
        let node_dim = layout.node().dim();
        let fixed = layout.fixed().map_or_else(Vec::new, |b| {
            let rows: Vec<&[f64]> = archive.iter().map(|c| c.fixed.as_slice()).collect();
            sigmas(&rows, b, gen_mark, focus, generation)
        });
        let mut legs: Vec<f64> = archive.iter().map(|c| c.legs.len() as f64).collect();
        let legs = spread(&mut legs) / g;
        let max_legs = archive.iter().map(|c| c.legs.len()).max().unwrap_or(0);
        let mut nodes = Vec::with_capacity(max_legs);
        let mut genes: Vec<Vec<Option<Vec<f64>>>> = Vec::with_capacity(max_legs);
        for l in 0..max_legs {
            let mut counts: Vec<f64> = archive
                .iter()
                .filter_map(|c| c.legs.get(l).map(|leg| leg.len() as f64))
                .collect();
            nodes.push(spread(&mut counts) / g);
            let max_nodes = archive
                .iter()
                .filter_map(|c| c.legs.get(l).map(Vec::len))
                .max()
                .unwrap_or(0);
            let at = |k: usize| archive.iter().filter_map(move |c| c.legs.get(l)?.get(k));
            genes.push(
                (0..max_nodes)
                    .map(|k| {
                        let rows: Vec<&[f64]> = at(k).map(|n| &n[..node_dim]).collect();
                        sigmas_of(&rows, layout.node(), gen_mark, focus, generation)
                    })
                    .collect(),
            );
        }
        let all: Vec<&Vec<f64>> = archive
            .iter()
            .flat_map(|c| c.legs.iter().flatten())
            .collect();
        let base: Vec<&[f64]> = all.iter().map(|n| &n[..node_dim]).collect();
        let pooled = sigmas_of(&base, layout.node(), gen_mark, focus, generation)
            .unwrap_or_else(|| vec![0.0; node_dim]);
        let (mut presence, mut optional, mut optional_pooled) =
            (Vec::new(), Vec::new(), Vec::new());
        if let Some(bounds) = layout.optional() {
            for (l, row) in genes.iter().enumerate() {
                let at = |k: usize| archive.iter().filter_map(move |c| c.legs.get(l)?.get(k));
                let mut p_row = Vec::with_capacity(row.len());
                let mut o_row = Vec::with_capacity(row.len());
                for k in 0..row.len() {
                    let mut p: Vec<f64> = at(k)
                        .map(|n| f64::from(u8::from(layout.carries_optional(n))))
                        .collect();
                    p_row.push(spread(&mut p) / g);
                    let rows: Vec<&[f64]> =
                        at(k).filter_map(|n| layout.optional_genes(n)).collect();
                    o_row.push(sigmas_of(&rows, bounds, gen_mark, focus, generation));
                }
                presence.push(p_row);
                optional.push(o_row);
            }
            let carried: Vec<&[f64]> = all
                .iter()
                .filter_map(|n| layout.optional_genes(n))
                .collect();
            optional_pooled = sigmas_of(&carried, bounds, gen_mark, focus, generation)
                .unwrap_or_else(|| vec![0.0; bounds.dim()]);
        }
        Self {
            fixed,
            legs,
            nodes,
            genes,
            pooled,
            presence,
            optional,
            optional_pooled,
        }
    }

    fn at<T: Clone>(table: &[Vec<Option<T>>], l: usize, k: usize) -> Option<T> {
        table.get(l)?.get(k)?.clone()
    }
}

/// The ant sampler of one generation.
struct Colony<'a> {
    layout: &'a Layout,
    archive: Vec<&'a Chromosome>,
    spreads: Spreads,
}

impl Colony<'_> {
    /// The same node of the best-ranked archive member that has it.
    fn historical(&self, l: usize, k: usize) -> Option<&Vec<f64>> {
        self.archive.iter().find_map(|c| c.legs.get(l)?.get(k))
    }

    /// The counts of an ant around `kernel` (free counts).
    fn counts(&self, kernel: &Chromosome, normal: &mut Normal, rng: &mut OptimRng) -> Vec<usize> {
        let legs = draw_count(
            kernel.legs.len(),
            self.spreads.legs,
            self.layout.legs(),
            normal,
            rng,
        );
        (0..legs)
            .map(|l| {
                let centre = kernel.legs.get(l).map(Vec::len).or_else(|| {
                    self.archive
                        .iter()
                        .find_map(|c| c.legs.get(l).map(Vec::len))
                });
                match centre {
                    Some(c) => {
                        let s = self.spreads.nodes.get(l).copied().unwrap_or(0.0);
                        draw_count(c, s, self.layout.nodes(), normal, rng)
                    }
                    None => random_count(self.layout.nodes(), rng),
                }
            })
            .collect()
    }

    /// Node `(l, k)` of an ant around `kernel`.
    fn node(
        &self,
        kernel: &Chromosome,
        (l, k): (usize, usize),
        normal: &mut Normal,
        rng: &mut OptimRng,
    ) -> Vec<f64> {
        let layout = self.layout;
        let dim = layout.node().dim();
        let own = kernel.legs.get(l).and_then(|leg| leg.get(k));
        let centre = own.or_else(|| self.historical(l, k));
        let Some(centre) = centre else {
            return random_node(layout, rng);
        };
        let sigma =
            Spreads::at(&self.spreads.genes, l, k).unwrap_or_else(|| self.spreads.pooled.clone());
        let mut node = ant(&centre[..dim], &sigma, layout.node(), normal, rng);
        let Some(optional) = layout.optional() else {
            return node;
        };
        let carries = layout.carries_optional(centre);
        let s = self
            .spreads
            .presence
            .get(l)
            .and_then(|row| row.get(k))
            .copied()
            .unwrap_or(0.0);
        let range = CountRange { min: 0, max: 1 };
        if draw_count(usize::from(carries), s, range, normal, rng) == 0 {
            return node;
        }
        let group = if carries {
            Some(&centre[dim..])
        } else {
            self.archive
                .iter()
                .filter_map(|c| c.legs.get(l)?.get(k))
                .find_map(|n| layout.optional_genes(n))
        };
        match group {
            Some(g) => {
                let sigma = Spreads::at(&self.spreads.optional, l, k)
                    .unwrap_or_else(|| self.spreads.optional_pooled.clone());
                node.extend(ant(g, &sigma, optional, normal, rng));
            }
            None => node.extend(random_point(optional, rng)),
        }
        node
    }

    fn ant<P: StructuredProblem>(
        &self,
        problem: &P,
        kernel: &Chromosome,
        normal: &mut Normal,
        rng: &mut OptimRng,
    ) -> Chromosome {
        let fixed = match self.layout.fixed() {
            Some(b) => ant(&kernel.fixed, &self.spreads.fixed, b, normal, rng),
            None => Vec::new(),
        };
        let counts = problem
            .derived_nodes(&fixed)
            .unwrap_or_else(|| self.counts(kernel, normal, rng));
        let legs = counts
            .iter()
            .enumerate()
            .map(|(l, &n)| {
                (0..n)
                    .map(|k| self.node(kernel, (l, k), normal, rng))
                    .collect()
            })
            .collect();
        Chromosome { fixed, legs }
    }
}

impl VlMhaco {
    /// A new run with `config`, seeded with `seed`.
    #[must_use]
    pub fn new(config: MhacoConfig, seed: u64) -> Self {
        let q = config.q;
        Self {
            config,
            rng: OptimRng::new(seed),
            normal: Normal,
            population: Vec::new(),
            archive_len: 0,
            q,
            gen_mark: 1,
            stalls: 0,
            finished: false,
            batch: Batch::default(),
            initialised: false,
            generation: 0,
            evaluations: 0,
        }
    }

    /// The settings.
    #[must_use]
    pub fn config(&self) -> &MhacoConfig {
        &self.config
    }

    /// The solution archive, best first (empty before the initial population is told).
    #[must_use]
    pub fn archive(&self) -> &[Individual<Chromosome>] {
        &self.population[..self.archive_len]
    }

    /// Current `gen_mark` (divisor of the standard deviations).
    #[must_use]
    pub fn gen_mark(&self) -> u64 {
        self.gen_mark
    }

    fn make_ants<P: StructuredProblem>(&mut self, problem: &P) {
        let generation = self.generation + 1;
        if generation == self.config.threshold {
            self.q = 0.01;
        }
        let cumulative = cumulative_weights(self.archive_len, self.q);
        let archive: Vec<&Chromosome> = self.population[..self.archive_len]
            .iter()
            .map(|i| &i.decision)
            .collect();
        let layout = problem.layout();
        let spreads = Spreads::new(
            &archive,
            layout,
            self.gen_mark,
            self.config.focus,
            generation,
        );
        let colony = Colony {
            layout,
            archive,
            spreads,
        };
        let ants = (0..self.config.population)
            .map(|_| {
                let k = pick(&cumulative, self.rng.uniform());
                colony.ant(problem, colony.archive[k], &mut self.normal, &mut self.rng)
            })
            .collect();
        self.batch.open(ants);
    }
}

impl<P: StructuredProblem> Algorithm<P> for VlMhaco {
    fn name(&self) -> &'static str {
        NAME
    }

    fn ask(&mut self, problem: &P) -> Result<&[Chromosome], OptimError> {
        if self.finished {
            return Ok(&[]);
        }
        if !self.batch.is_open() {
            if self.initialised {
                self.make_ants(problem);
            } else {
                check_objectives(problem)?;
                self.config
                    .check(problem.objectives(), problem.constraints())?;
                let decisions = (0..self.config.population)
                    .map(|_| random_chromosome(problem, &mut self.rng))
                    .collect();
                self.batch.open(decisions);
            }
        }
        Ok(self.batch.decisions())
    }

    fn tell(
        &mut self,
        problem: &P,
        index: usize,
        evaluation: Evaluation,
    ) -> Result<(), OptimError> {
        let complete = self.batch.tell(
            index,
            evaluation,
            problem.objectives(),
            problem.constraints(),
        )?;
        self.evaluations += 1;
        if !complete {
            return Ok(());
        }
        let told = self.batch.take();
        let (merged, start, offset, improved) = if self.initialised {
            let handling = &self.config.constraints;
            let before = archive::progress_marker(self.archive(), handling);
            let mut merged = std::mem::take(&mut self.population);
            merged.truncate(self.archive_len);
            let start = merged.len();
            merged.extend(told);
            let after = archive::progress_marker(&merged, handling);
            self.generation += 1;
            (merged, start, 0.01, before != after)
        } else {
            self.initialised = true;
            (told, 0, 0.1, true)
        };
        self.finished |= advance(&self.config, improved, &mut self.stalls, &mut self.gen_mark);
        (self.population, self.archive_len) = select(&self.config, merged, start, offset);
        Ok(())
    }

    fn population(&self) -> &[Individual<Chromosome>] {
        &self.population
    }

    fn is_initialised(&self) -> bool {
        self.initialised
    }

    fn generation(&self) -> u64 {
        self.generation
    }

    fn evaluations(&self) -> u64 {
        self.evaluations
    }

    fn is_told(&self, index: usize) -> bool {
        self.batch.is_told(index)
    }

    fn is_finished(&self) -> bool {
        self.finished
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::optim::evaluate::{Rayon, Serial, evolve};
    use crate::optim::observe::NoObserver;
    use crate::optim::problems::{OptionalNodes, Vlmop};

    fn make(seed: u64) -> VlMhaco {
        VlMhaco::new(
            MhacoConfig {
                population: 20,
                ker: 10,
                threshold: 4,
                ..MhacoConfig::default()
            },
            seed,
        )
    }

    #[test]
    fn vl_mhaco_one_and_two_threads_and_resume_are_bit_identical() {
        let p = Vlmop::standard(1).unwrap();
        let pool = |n| {
            Arc::new(
                rayon::ThreadPoolBuilder::new()
                    .num_threads(n)
                    .build()
                    .unwrap(),
            )
        };
        let mut a = make(7);
        evolve(&mut a, &p, &Rayon::with_pool(pool(1)), 10, &mut NoObserver).unwrap();
        let mut b = make(7);
        evolve(&mut b, &p, &Rayon::with_pool(pool(2)), 10, &mut NoObserver).unwrap();
        assert_eq!(a, b);
        let mut part = make(7);
        evolve(&mut part, &p, &Serial, 4, &mut NoObserver).unwrap();
        let mut resumed: VlMhaco =
            serde_json::from_str(&serde_json::to_string(&part).unwrap()).unwrap();
        evolve(&mut resumed, &p, &Serial, 6, &mut NoObserver).unwrap();
        assert_eq!(resumed, a);
        for ind in <VlMhaco as Algorithm<Vlmop>>::population(&a) {
            assert_eq!(
                ind.decision.node_counts(),
                vec![p.length(&ind.decision.fixed)]
            );
        }
    }

    /// Seed survey on vlmop1..=3 (population 100, ker 63, n_gen_mark 15, 30 generations): the
    /// feasible-front hypervolume over the true front's, per seed 1..=8 (`cargo test --release -p
    /// host-sim --lib vl_mhaco_survey -- --ignored --nocapture`). No threshold is asserted yet.
    #[test]
    #[ignore = "survey: run in release"]
    fn vl_mhaco_survey() {
        use crate::optim::hypervolume::hypervolume;
        use crate::optim::population::feasible_front;
        for id in 1..=3u8 {
            let p = Vlmop::standard(id).unwrap();
            let r = p.reference_point();
            let truth = p.front_hypervolume(&r).unwrap();
            let ratios: Vec<String> = (1..=8)
                .map(|seed| {
                    let mut a = VlMhaco::new(
                        MhacoConfig {
                            n_gen_mark: 15,
                            ..MhacoConfig::default()
                        },
                        seed,
                    );
                    evolve(&mut a, &p, &Serial, 30, &mut NoObserver).unwrap();
                    let pop = <VlMhaco as Algorithm<Vlmop>>::population(&a);
                    format!(
                        "{:.4}",
                        hypervolume(&feasible_front(pop), &r).unwrap() / truth
                    )
                })
                .collect();
            println!("vl-mhaco vlmop{id}: {}", ratios.join(" "));
        }
    }

    /// Thresholds: the smallest ratio of `vl_mhaco_survey` over seeds 1..=8 (0.9581, 0.9713,
    /// 0.8438) less about 2 %, rounded down; the test runs seed 1.
    const VL_MHACO_VL: [f64; 3] = [0.93, 0.95, 0.82];

    #[test]
    fn vl_mhaco_converges_on_vlmop1_to_3() {
        use crate::optim::hypervolume::hypervolume;
        use crate::optim::population::feasible_front;
        for id in 1..=3u8 {
            let p = Vlmop::standard(id).unwrap();
            let r = p.reference_point();
            let mut a = VlMhaco::new(
                MhacoConfig {
                    n_gen_mark: 15,
                    ..MhacoConfig::default()
                },
                1,
            );
            evolve(&mut a, &p, &Serial, 30, &mut NoObserver).unwrap();
            let pop = <VlMhaco as Algorithm<Vlmop>>::population(&a);
            let ratio =
                hypervolume(&feasible_front(pop), &r).unwrap() / p.front_hypervolume(&r).unwrap();
            assert!(
                ratio > VL_MHACO_VL[usize::from(id) - 1],
                "vlmop{id}: {ratio}"
            );
        }
    }

    /// The hypervolume ratio of the archive on [`OptionalNodes`] and the share of its
    /// non-dominated members whose nodes carry the extra gene exactly where it is needed.
    fn optional_scores(p: &OptionalNodes, a: &VlMhaco) -> (f64, f64) {
        p.scores(<VlMhaco as Algorithm<OptionalNodes>>::population(a))
            .unwrap()
    }

    fn optional_run(seed: u64, gens: u64) -> VlMhaco {
        let p = OptionalNodes::standard().unwrap();
        let mut a = VlMhaco::new(
            MhacoConfig {
                n_gen_mark: 15,
                ..MhacoConfig::default()
            },
            seed,
        );
        evolve(&mut a, &p, &Serial, gens, &mut NoObserver).unwrap();
        a
    }

    /// Seed survey on [`OptionalNodes`] (population 100, ker 63, n_gen_mark 15): ratio and
    /// pattern share per seed 1..=8 (`cargo test -p host-sim --lib vl_mhaco_optional_survey
    /// -- --ignored --nocapture`).
    #[test]
    #[ignore = "survey"]
    fn vl_mhaco_optional_survey() {
        let p = OptionalNodes::standard().unwrap();
        for gens in [30, 100] {
            let rows: Vec<String> = (1..=8)
                .map(|seed| {
                    let (ratio, share) = optional_scores(&p, &optional_run(seed, gens));
                    format!("{ratio:.4}/{share:.2}")
                })
                .collect();
            println!("vl-mhaco optional {gens} gens: {}", rows.join(" "));
        }
    }

    /// Thresholds at 30 generations: the minima of `vl_mhaco_optional_survey` over seeds
    /// 1..=8 (ratio 0.8256, share 0.22; seed 1 0.9453/1.00) less about 2 % (ratio) or 0.05
    /// (share), rounded down; the test runs seed 1. Seeds 4 and 7 stall with shares 0.22-0.24
    /// (still 0.24 and 0.80 after 100 generations): once the archive members agree on a
    /// node's presence its spread is zero and the ants keep it, as they keep a converged
    /// length; SCEA (mutation of the presence) finds the pattern on every seed.
    const VL_MHACO_OPTIONAL: (f64, f64) = (0.80, 0.17);

    #[test]
    fn vl_mhaco_finds_the_optional_gene_pattern() {
        let p = OptionalNodes::standard().unwrap();
        let a = optional_run(1, 30);
        for ind in <VlMhaco as Algorithm<OptionalNodes>>::population(&a) {
            p.layout().check(&ind.decision, None).unwrap();
        }
        let (ratio, share) = optional_scores(&p, &a);
        assert!(ratio > VL_MHACO_OPTIONAL.0, "ratio {ratio}");
        assert!(share > VL_MHACO_OPTIONAL.1, "share {share}");
    }
}
