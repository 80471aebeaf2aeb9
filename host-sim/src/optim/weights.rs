//! Weight vectors and decompositions for MOEA/D, as in pagmo (`decomposition_weights`,
//! `decompose_objectives`).

use serde::{Deserialize, Serialize};

use super::error::ConfigError;
use super::rng::OptimRng;

/// How the weight vectors are generated (`--weights`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum WeightGeneration {
    /// Uniform simplex lattice (Das-Dennis): only populations C(H + m - 1, m - 1).
    Grid,
    /// The m unit vectors, then a Halton sequence mapped onto the simplex.
    LowDiscrepancy,
    /// The m unit vectors, then uniformly random points of the simplex.
    Random,
}

/// How objectives are aggregated for one weight vector.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Decomposition {
    /// `max_i w_i |f_i - z_i|` (a zero weight counts as 1e-4, as in pagmo).
    Tchebycheff,
    /// `sum_i w_i f_i`.
    Weighted,
    /// Penalty-based boundary intersection with penalty theta = 5 (pagmo's "bi").
    Pbi,
}

fn binomial(n: usize, k: usize) -> usize {
    let k = k.min(n.saturating_sub(k));
    let mut r: u128 = 1;
    for i in 0..k {
        r = r * (n - i) as u128 / (i + 1) as u128;
        if r > usize::MAX as u128 {
            return usize::MAX;
        }
    }
    r as usize
}

/// Legal grid sizes around `n` for `m` objectives: (largest <= n, smallest >= n).
#[must_use]
pub fn grid_sizes_around(n: usize, m: usize) -> (usize, usize) {
    let mut below = 0;
    let mut h = 0;
    loop {
        let size = binomial(h + m - 1, m - 1);
        if size >= n {
            return (below, size);
        }
        below = size;
        h += 1;
    }
}

/// `n` weight vectors for `m >= 2` objectives.
///
/// # Errors
/// [`ConfigError::GridSize`] (naming the nearest legal sizes) for a grid that does not exist;
/// [`ConfigError::PopulationTooSmall`] when `n < m` for the other methods.
pub fn generate(
    n: usize,
    m: usize,
    kind: WeightGeneration,
    rng: &mut OptimRng,
) -> Result<Vec<Vec<f64>>, ConfigError> {
    match kind {
        WeightGeneration::Grid => {
            let (below, above) = grid_sizes_around(n, m);
            if above != n {
                return Err(ConfigError::GridSize {
                    population: n,
                    objectives: m,
                    below,
                    above,
                });
            }
            let mut h = 0;
            while binomial(h + m - 1, m - 1) < n {
                h += 1;
            }
            let mut out = Vec::with_capacity(n);
            let mut current = vec![0usize; m];
            lattice(&mut out, &mut current, 0, h, h);
            Ok(out)
        }
        WeightGeneration::LowDiscrepancy | WeightGeneration::Random => {
            if n < m {
                return Err(ConfigError::PopulationTooSmall {
                    algorithm: "moead (weights)",
                    population: n,
                    minimum: m,
                });
            }
            let mut out: Vec<Vec<f64>> = (0..m)
                .map(|i| (0..m).map(|j| if i == j { 1.0 } else { 0.0 }).collect())
                .collect();
            let mut count = m as u64;
            while out.len() < n {
                let u: Vec<f64> = if kind == WeightGeneration::Random {
                    (0..m - 1).map(|_| rng.uniform()).collect()
                } else {
                    // pagmo's Halton points start at index m (the point after the m unit
                    // vectors).
                    let u = (0..m - 1)
                        .map(|d| radical_inverse(count, PRIMES[d % PRIMES.len()]))
                        .collect();
                    count += 1;
                    u
                };
                out.push(simplex_from_unit_cube(u));
            }
            Ok(out)
        }
    }
}

fn lattice(out: &mut Vec<Vec<f64>>, current: &mut [usize], k: usize, left: usize, h: usize) {
    let m = current.len();
    if k == m - 1 {
        current[k] = left;
        out.push(current.iter().map(|&c| c as f64 / h as f64).collect());
        return;
    }
    for c in 0..=left {
        current[k] = c;
        lattice(out, current, k + 1, left - c, h);
    }
}

const PRIMES: [u64; 20] = [
    2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53, 59, 61, 67, 71,
];

fn radical_inverse(mut i: u64, base: u64) -> f64 {
    let mut f = 1.0;
    let mut r = 0.0;
    while i > 0 {
        f /= base as f64;
        r += f * (i % base) as f64;
        i /= base;
    }
    r
}

/// Map a point of the unit cube [0,1]^(m-1) to the unit simplex of dimension m (sorted
/// coordinates as cut points).
fn simplex_from_unit_cube(mut u: Vec<f64>) -> Vec<f64> {
    u.sort_by(f64::total_cmp);
    let mut out = Vec::with_capacity(u.len() + 1);
    let mut prev = 0.0;
    for &v in &u {
        out.push(v - prev);
        prev = v;
    }
    out.push(1.0 - prev);
    out
}

/// The decomposed (scalar) value of objectives `f` for weight `w` and ideal point `z`.
#[inline]
#[must_use]
pub fn decompose(kind: Decomposition, f: &[f64], w: &[f64], z: &[f64]) -> f64 {
    match kind {
        Decomposition::Tchebycheff => tchebycheff(f, w, z),
        Decomposition::Weighted => f.iter().zip(w).map(|(a, b)| a * b).sum(),
        Decomposition::Pbi => {
            const THETA: f64 = 5.0;
            let norm = w.iter().map(|v| v * v).sum::<f64>().sqrt();
            let d1: f64 = f
                .iter()
                .zip(z)
                .zip(w)
                .map(|((fi, zi), wi)| (fi - zi) * wi)
                .sum::<f64>()
                / norm;
            let d2 = f
                .iter()
                .zip(z)
                .zip(w)
                .map(|((fi, zi), wi)| {
                    let d = fi - (zi + d1 * wi / norm);
                    d * d
                })
                .sum::<f64>()
                .sqrt();
            d1 + THETA * d2
        }
    }
}

/// Tchebycheff value `max_i w_i |f_i - z_i|` (a zero weight counts as 1e-4, as in pagmo).
#[inline]
#[must_use]
pub fn tchebycheff(f: &[f64], w: &[f64], z: &[f64]) -> f64 {
    let mut r = f64::NEG_INFINITY;
    for ((&fi, &wi), &zi) in f.iter().zip(w).zip(z) {
        let wi = if wi == 0.0 { 1e-4 } else { wi };
        let t = wi * (fi - zi).abs();
        if t > r {
            r = t;
        }
    }
    r
}

/// For every weight, the indices of the `t` nearest *other* weights (Euclidean, nearest
/// first, ties by index): pagmo's `kNN`, which leaves a weight out of its own neighbourhood,
/// so a subproblem mates with and offers its child to `t` others.
#[must_use]
pub fn neighbourhoods(weights: &[Vec<f64>], t: usize) -> Vec<Vec<usize>> {
    weights
        .iter()
        .enumerate()
        .map(|(i, wi)| {
            let mut d: Vec<(f64, usize)> = weights
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .map(|(j, wj)| {
                    let d2: f64 = wi.iter().zip(wj).map(|(a, b)| (a - b) * (a - b)).sum();
                    (d2, j)
                })
                .collect();
            d.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            d.into_iter().take(t).map(|(_, j)| j).collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_sizes_and_errors() {
        let mut rng = OptimRng::new(0);
        let w = generate(100, 2, WeightGeneration::Grid, &mut rng).unwrap();
        assert_eq!(w.len(), 100);
        assert!(
            w.iter()
                .all(|v| (v.iter().sum::<f64>() - 1.0).abs() < 1e-12)
        );
        assert_eq!(
            generate(91, 3, WeightGeneration::Grid, &mut rng)
                .unwrap()
                .len(),
            91
        );
        let e = generate(100, 3, WeightGeneration::Grid, &mut rng).unwrap_err();
        assert_eq!(
            e,
            ConfigError::GridSize {
                population: 100,
                objectives: 3,
                below: 91,
                above: 105
            }
        );
        assert!(e.to_string().contains("91 and 105"), "{e}");
    }

    #[test]
    fn low_discrepancy_and_random_weights_lie_on_the_simplex() {
        let mut rng = OptimRng::new(1);
        for kind in [WeightGeneration::LowDiscrepancy, WeightGeneration::Random] {
            let w = generate(50, 3, kind, &mut rng).unwrap();
            assert_eq!(w.len(), 50);
            assert_eq!(w[0], vec![1.0, 0.0, 0.0]);
            for v in &w {
                assert!((v.iter().sum::<f64>() - 1.0).abs() < 1e-12);
                assert!(v.iter().all(|&x| x >= 0.0));
            }
            assert!(matches!(
                generate(2, 3, kind, &mut rng),
                Err(ConfigError::PopulationTooSmall { .. })
            ));
        }
    }

    #[test]
    fn decompositions_at_known_points() {
        let z = [0.0, 0.0];
        assert_eq!(
            decompose(Decomposition::Tchebycheff, &[1.0, 2.0], &[0.5, 0.5], &z),
            1.0
        );
        assert_eq!(
            decompose(Decomposition::Tchebycheff, &[1.0, 2.0], &[0.0, 1.0], &z),
            2.0
        );
        assert_eq!(
            decompose(Decomposition::Weighted, &[1.0, 2.0], &[0.25, 0.75], &z),
            1.75
        );
        // On the weight direction d2 = 0: PBI is the distance along it.
        let s = 0.5f64.sqrt();
        let v = decompose(Decomposition::Pbi, &[1.0, 1.0], &[s, s], &z);
        assert!((v - 2.0f64.sqrt()).abs() < 1e-12);
        let nb = neighbourhoods(
            &generate(5, 2, WeightGeneration::Grid, &mut OptimRng::new(0)).unwrap(),
            3,
        );
        assert_eq!(nb[0], vec![1, 2, 3]);
        assert_eq!(nb[2], vec![1, 3, 0]);
        assert_eq!(nb[4], vec![3, 2, 1]);
    }

    // pygmo 2.20: `pg.decomposition_weights(m, n, method, 1)` and `pg.decompose_objectives`.
    const GRID_3_15: &[&[f64]] = &[
        &[0.0, 0.0, 1.0],
        &[0.0, 0.25, 0.75],
        &[0.0, 0.5, 0.5],
        &[0.0, 0.75, 0.25],
        &[0.0, 1.0, 0.0],
        &[0.25, 0.0, 0.75],
        &[0.25, 0.25, 0.5],
        &[0.25, 0.5, 0.25],
        &[0.25, 0.75, 0.0],
        &[0.5, 0.0, 0.5],
        &[0.5, 0.25, 0.25],
        &[0.5, 0.5, 0.0],
        &[0.75, 0.0, 0.25],
        &[0.75, 0.25, 0.0],
        &[1.0, 0.0, 0.0],
    ];
    const LD_3_12: &[&[f64]] = &[
        &[1.0, 0.0, 0.0],
        &[0.0, 1.0, 0.0],
        &[0.0, 0.0, 1.0],
        &[0.1111111111111111, 0.6388888888888888, 0.25],
        &[0.125, 0.3194444444444444, 0.5555555555555556],
        &[0.625, 0.15277777777777768, 0.22222222222222232],
        &[0.2222222222222222, 0.1527777777777778, 0.625],
        &[0.5555555555555556, 0.3194444444444444, 0.125],
        &[0.0625, 0.8263888888888888, 0.11111111111111116],
        &[0.037037037037037035, 0.525462962962963, 0.4375],
        &[0.3125, 0.05787037037037035, 0.6296296296296297],
        &[0.7037037037037037, 0.10879629629629628, 0.1875],
    ];
    const LD_2_6: &[&[f64]] = &[
        &[1.0, 0.0],
        &[0.0, 1.0],
        &[0.25, 0.75],
        &[0.75, 0.25],
        &[0.125, 0.875],
        &[0.625, 0.375],
    ];
    const LD_4_9: &[&[f64]] = &[
        &[1.0, 0.0, 0.0, 0.0],
        &[0.0, 1.0, 0.0, 0.0],
        &[0.0, 0.0, 1.0, 0.0],
        &[0.0, 0.0, 0.0, 1.0],
        &[
            0.125,
            0.3194444444444444,
            0.3555555555555556,
            0.19999999999999996,
        ],
        &[0.04, 0.585, 0.15277777777777768, 0.22222222222222232],
        &[
            0.2222222222222222,
            0.01777777777777781,
            0.13499999999999998,
            0.625,
        ],
        &[0.44, 0.11555555555555558, 0.3194444444444444, 0.125],
        &[
            0.0625,
            0.5775000000000001,
            0.24888888888888872,
            0.11111111111111116,
        ],
    ];

    #[test]
    fn validate_pygmo_weights_and_decompositions() {
        let mut rng = OptimRng::new(0);
        for (n, m, kind, expected) in [
            (15, 3, WeightGeneration::Grid, GRID_3_15),
            (12, 3, WeightGeneration::LowDiscrepancy, LD_3_12),
            (6, 2, WeightGeneration::LowDiscrepancy, LD_2_6),
            (9, 4, WeightGeneration::LowDiscrepancy, LD_4_9),
        ] {
            let w = generate(n, m, kind, &mut rng).unwrap();
            assert_eq!(w.len(), expected.len());
            for (a, b) in w.iter().zip(expected) {
                for (x, y) in a.iter().zip(b.iter()) {
                    assert!((x - y).abs() < 1e-15, "{kind:?} {n}: {a:?} vs pygmo {b:?}");
                }
            }
        }
        type Case<'a> = (Decomposition, &'a [f64], &'a [f64], &'a [f64], f64);
        let cases: [Case; 6] = [
            (
                Decomposition::Tchebycheff,
                &[1.0, 2.0],
                &[0.5, 0.5],
                &[0.0, 0.0],
                1.0,
            ),
            (
                Decomposition::Tchebycheff,
                &[1.0, 2.0],
                &[0.0, 1.0],
                &[0.1, 0.2],
                1.8,
            ),
            (
                Decomposition::Weighted,
                &[1.0, 2.0, 3.0],
                &[0.2, 0.3, 0.5],
                &[0.0; 3],
                2.3,
            ),
            (
                Decomposition::Weighted,
                &[1.0, 2.0],
                &[0.5, 0.5],
                &[0.3, 0.1],
                1.5,
            ),
            (
                Decomposition::Pbi,
                &[1.0, 2.0],
                &[0.5, 0.5],
                &[0.0, 0.0],
                5.65685424949238,
            ),
            (
                Decomposition::Pbi,
                &[0.3, 0.9, 0.1],
                &[0.1, 0.6, 0.3],
                &[0.05, 0.1, 0.0],
                2.2910772514487983,
            ),
        ];
        for (kind, f, w, z, expected) in cases {
            let v = decompose(kind, f, w, z);
            assert!(
                (v - expected).abs() < 1e-12,
                "{kind:?}: {v} vs pygmo {expected}"
            );
        }
    }
}
