//! Exact hypervolume benchmarks (issue 9): random fronts with every point on the unit sphere
//! (non-negative orthant) or on the unit simplex, reference point 1.1 in every objective,
//! the sizes of the peer measurements (3-D n = 2000, 4-D and 5-D n = 1000; 6-D
//! n = 300, 7-D n = 100 and 8-D n = 50, sizes at which moocore takes well under a second), plus
//! all exclusive contributions in 2-D and 3-D (n = 2000), 4-D (n = 1000) and 5-D (n = 300).
//! The side-by-side comparison with moocore and pygmo on identical fronts is
//! scripts/compare_hypervolume.py (docs/validation/hypervolume.md).

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use host_sim::optim::hypervolume::{contributions, hypervolume};

/// splitmix64: a small seeded generator so the fronts are the same on every run.
struct SplitMix(u64);
impl SplitMix {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in (0, 1).
    fn uniform(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    fn normal(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }
}

/// `n` points uniformly on the sphere (|x| = 1, x >= 0) or the simplex (sum x = 1, x >= 0).
fn front(kind: &str, d: usize, n: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = SplitMix(seed);
    (0..n)
        .map(|_| {
            let v: Vec<f64> = match kind {
                "sphere" => (0..d).map(|_| rng.normal().abs()).collect(),
                _ => (0..d).map(|_| -rng.uniform().ln()).collect(),
            };
            let norm = if kind == "sphere" {
                v.iter().map(|x| x * x).sum::<f64>().sqrt()
            } else {
                v.iter().sum::<f64>()
            };
            v.iter().map(|x| x / norm).collect()
        })
        .collect()
}

fn hypervolumes(c: &mut Criterion) {
    for (d, n) in [(3, 2000), (4, 1000), (5, 1000), (6, 300), (7, 100), (8, 50)] {
        for kind in ["sphere", "simplex"] {
            let pts = front(kind, d, n, 42);
            let r = vec![1.1; d];
            c.bench_function(&format!("hypervolume/{d}d/{kind}/n{n}"), |b| {
                b.iter(|| hypervolume(black_box(&pts), black_box(&r)).expect("valid front"));
            });
        }
    }
    for (d, n) in [(2, 2000), (3, 2000), (4, 1000), (5, 300)] {
        for kind in ["sphere", "simplex"] {
            let pts = front(kind, d, n, 7);
            let r = vec![1.1; d];
            c.bench_function(&format!("contributions/{d}d/{kind}/n{n}"), |b| {
                b.iter(|| contributions(black_box(&pts), black_box(&r)).expect("valid front"));
            });
        }
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = hypervolumes
}
criterion_main!(benches);
