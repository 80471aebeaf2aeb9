//! MOEA/D with a custom variation on a variable-length decision type (what SCEA builds on):
//! the rest of MOEA/D (weights, Lampinen's rules, ask/tell, checkpoints) works unchanged.

use serde::{Deserialize, Serialize};

use super::*;
use crate::optim::algorithms::{MoeadVariation, MoeadWith};

/// A chromosome with 1 to 5 real genes in [0, 1].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct Chromosome {
    genes: Vec<f64>,
}

/// f1 = g0, f2 = 1 - sqrt(g0) + |len - 3| + sum of the other genes squared; constraint
/// g0 >= 0.1. Front: three genes, the others 0, f2 = 1 - sqrt(f1) for f1 in [0.1, 1].
struct VarLen;

impl Problem for VarLen {
    type Decision = Chromosome;
    fn objectives(&self) -> usize {
        2
    }
    fn constraints(&self) -> usize {
        1
    }
    fn evaluate(&self, x: &Chromosome) -> Result<Evaluation, EvalError> {
        let g = &x.genes;
        if g.is_empty() || g.len() > 5 {
            return Err(EvalError::Dimension {
                expected: 3,
                got: g.len(),
            });
        }
        let tail: f64 = g[1..].iter().map(|v| v * v).sum();
        let f2 = 1.0 - g[0].sqrt() + (g.len() as f64 - 3.0).abs() + tail;
        Ok(Evaluation::with_constraints(
            vec![g[0], f2],
            vec![0.1 - g[0]],
        ))
    }
}

/// Length from one parent, changed by one with probability 0.2 (genes appended at random or
/// dropped); genes crossed with the DE step where all three parents have them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct LengthVariation;

impl MoeadVariation<VarLen> for LengthVariation {
    fn random(&self, _p: &VarLen, rng: &mut OptimRng) -> Chromosome {
        let len = 1 + rng.below(5);
        Chromosome {
            genes: (0..len).map(|_| rng.uniform()).collect(),
        }
    }

    fn child(
        &self,
        _p: &VarLen,
        config: &MoeadConfig,
        x: &Chromosome,
        a: &Chromosome,
        b: &Chromosome,
        _reuse: Option<Chromosome>,
        rng: &mut OptimRng,
    ) -> Chromosome {
        let mut genes = x.genes.clone();
        if rng.uniform() < 0.2 {
            if rng.uniform() < 0.5 && genes.len() < 5 {
                genes.push(rng.uniform());
            } else if genes.len() > 1 {
                genes.pop();
            }
        }
        for (k, v) in genes.iter_mut().enumerate() {
            if let (Some(ak), Some(bk)) = (a.genes.get(k), b.genes.get(k)) {
                *v = (*v + config.f * (ak - bk)).clamp(0.0, 1.0);
            }
            if rng.uniform() < 0.2 {
                *v = (*v + 0.1 * (rng.uniform() - 0.5)).clamp(0.0, 1.0);
            }
        }
        Chromosome { genes }
    }
}

fn scea_like(seed: u64) -> MoeadWith<Chromosome, LengthVariation> {
    MoeadWith::with_variation(
        MoeadConfig {
            population: 30,
            neighbours: 6,
            ..MoeadConfig::default()
        },
        LengthVariation,
        seed,
    )
}

#[test]
fn moead_with_a_variable_length_variation_finds_the_right_length() {
    let mut a = scea_like(1);
    evolve(&mut a, &VarLen, &Serial, 60, &mut NoObserver).unwrap();
    let pop = a.population();
    assert!(pop.iter().all(|i| i.is_feasible()));
    let right_length = pop.iter().filter(|i| i.decision.genes.len() == 3).count();
    assert!(right_length >= 27, "{right_length} of 30 have three genes");
    // Close to the front f2 = 1 - sqrt(f1).
    let worst = pop
        .iter()
        .map(|i| i.objectives[1] - (1.0 - i.objectives[0].sqrt()))
        .fold(0.0, f64::max);
    assert!(worst < 0.05, "largest distance above the front {worst}");

    // Checkpoint/resume and tell-order invariance hold for any decision type.
    let mut straight = scea_like(2);
    evolve(&mut straight, &VarLen, &Serial, 8, &mut NoObserver).unwrap();
    let mut part = scea_like(2);
    evolve(&mut part, &VarLen, &Serial, 3, &mut NoObserver).unwrap();
    let mut resumed: MoeadWith<Chromosome, LengthVariation> =
        serde_json::from_str(&serde_json::to_string(&part).unwrap()).unwrap();
    evolve(&mut resumed, &VarLen, &Serial, 5, &mut NoObserver).unwrap();
    assert_eq!(resumed, straight);
}
