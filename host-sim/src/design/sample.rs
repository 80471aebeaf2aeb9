//! Space-filling designs of the decision space (thesis sec. 9.2-9.3 sampled 4000 individuals
//! at random): a Latin hypercube, a pure function of the seed.

use crate::optim::{Bounds, OptimRng};

/// `n` points of a Latin hypercube in `bounds`: each variable's range is cut into `n` equal
/// strata, each stratum holds exactly one point (at a uniform position inside it), and the
/// strata are paired across variables by independent random permutations.
#[must_use]
pub fn latin_hypercube(bounds: &Bounds, n: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = OptimRng::new(seed);
    let d = bounds.dim();
    let mut pts = vec![vec![0.0; d]; n];
    for j in 0..d {
        let (lo, hi) = (bounds.lower()[j], bounds.upper()[j]);
        let mut strata: Vec<usize> = (0..n).collect();
        rng.shuffle(&mut strata);
        for (p, s) in pts.iter_mut().zip(strata) {
            let u = (s as f64 + rng.uniform()) / n as f64;
            p[j] = (lo + u * (hi - lo)).clamp(lo, hi);
        }
    }
    pts
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every variable has exactly one point per stratum, inside the bounds; the same seed
    /// gives the same design.
    #[test]
    fn latin_hypercube_fills_every_stratum_once() {
        let b = Bounds::new(vec![0.1, 0.0, 50.0], vec![0.95, 45.0, 110.0]).unwrap();
        let n = 37;
        let pts = latin_hypercube(&b, n, 5);
        assert_eq!(pts, latin_hypercube(&b, n, 5));
        assert_ne!(pts, latin_hypercube(&b, n, 6));
        for j in 0..3 {
            let (lo, hi) = (b.lower()[j], b.upper()[j]);
            let mut seen = vec![0; n];
            for p in &pts {
                assert!(p[j] >= lo && p[j] <= hi);
                let s = (((p[j] - lo) / (hi - lo)) * n as f64).floor() as usize;
                seen[s.min(n - 1)] += 1;
            }
            assert!(seen.iter().all(|&c| c == 1), "{j}: {seen:?}");
        }
    }
}
