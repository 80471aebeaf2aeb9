//! The one random-number generator of a run: PCG64 (128-bit LCG, XSL-RR output) from
//! `rand_pcg`, seeded from a `u64`, with its full state serialisable (serde), and the few
//! derived draws the algorithms need, written here so that their bit patterns never depend on
//! a distribution crate's version.

use rand_core::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use serde::{Deserialize, Serialize};

/// Seeded, serialisable RNG; the same seed gives the same stream on every platform.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct OptimRng {
    pcg: Pcg64,
}

impl OptimRng {
    /// Generator for `seed` (seed expanded with PCG32 as in `rand_core::SeedableRng`).
    #[must_use]
    pub fn new(seed: u64) -> Self {
        Self {
            pcg: Pcg64::seed_from_u64(seed),
        }
    }

    /// Next raw 64 bits.
    #[inline]
    pub fn next_u64(&mut self) -> u64 {
        self.pcg.next_u64()
    }

    /// Uniform in [0, 1) with 53 random bits.
    #[inline]
    pub fn uniform(&mut self) -> f64 {
        // 2^-53
        const SCALE: f64 = 1.0 / 9_007_199_254_740_992.0;
        (self.next_u64() >> 11) as f64 * SCALE
    }

    /// Uniform in [lo, hi).
    #[inline]
    pub fn uniform_in(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.uniform()
    }

    /// Uniform integer in 0..n (unbiased, Lemire's multiply-and-reject); 0 when `n == 0`.
    #[inline]
    pub fn below(&mut self, n: usize) -> usize {
        if n <= 1 {
            return 0;
        }
        let n = n as u64;
        loop {
            let m = u128::from(self.next_u64()) * u128::from(n);
            let low = m as u64;
            // Reject the few values that would bias the result; the threshold (a division) is
            // only needed when `low < n`, which is rare.
            if low >= n || low >= n.wrapping_neg() % n {
                return (m >> 64) as usize;
            }
        }
    }

    /// Fisher-Yates shuffle (unbiased). Slices shorter than 2^32 take their indices from
    /// 32-bit halves of the generator's output (Lemire's multiply-and-reject on 32 bits), two
    /// per draw.
    pub fn shuffle<T>(&mut self, items: &mut [T]) {
        if items.len() > u32::MAX as usize {
            for i in (1..items.len()).rev() {
                let j = self.below(i + 1);
                items.swap(i, j);
            }
            return;
        }
        let mut spare: Option<u32> = None;
        let mut next32 = |rng: &mut Self| -> u32 {
            match spare.take() {
                Some(v) => v,
                None => {
                    let r = rng.next_u64();
                    spare = Some(r as u32);
                    (r >> 32) as u32
                }
            }
        };
        for i in (1..items.len()).rev() {
            let n = (i + 1) as u32;
            let j = loop {
                let m = u64::from(next32(self)) * u64::from(n);
                let low = m as u32;
                if low >= n || low >= n.wrapping_neg() % n {
                    break (m >> 32) as usize;
                }
            };
            items.swap(i, j);
        }
    }

    /// A seed for a child generator (for algorithms that need independent streams).
    pub fn fork_seed(&mut self) -> u64 {
        self.next_u64()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_seed_same_stream_and_serde_round_trip() {
        let mut a = OptimRng::new(7);
        let mut b = OptimRng::new(7);
        for _ in 0..10 {
            assert_eq!(a.next_u64(), b.next_u64());
        }
        let json = serde_json::to_string(&a).unwrap();
        let mut c: OptimRng = serde_json::from_str(&json).unwrap();
        for _ in 0..10 {
            assert_eq!(a.next_u64(), c.next_u64());
        }
        assert_ne!(OptimRng::new(8).next_u64(), OptimRng::new(7).next_u64());
    }

    #[test]
    fn shuffle_is_a_uniform_permutation() {
        let mut r = OptimRng::new(2);
        // Position of element 0 after shuffling 5 elements: uniform over 0..5.
        let mut counts = [0usize; 5];
        for _ in 0..10_000 {
            let mut v = [0, 1, 2, 3, 4];
            r.shuffle(&mut v);
            let mut sorted = v;
            sorted.sort_unstable();
            assert_eq!(sorted, [0, 1, 2, 3, 4]);
            counts[v.iter().position(|&x| x == 0).unwrap()] += 1;
        }
        for c in counts {
            assert!((1800..2200).contains(&c), "{counts:?}");
        }
    }

    #[test]
    fn uniform_and_below_stay_in_range() {
        let mut r = OptimRng::new(1);
        let mut counts = [0usize; 5];
        for _ in 0..10_000 {
            let u = r.uniform();
            assert!((0.0..1.0).contains(&u));
            counts[r.below(5)] += 1;
        }
        // Each bucket expects 2000; 5 sigma is about 200.
        for c in counts {
            assert!((1800..2200).contains(&c), "{counts:?}");
        }
        assert_eq!(r.below(0), 0);
        assert_eq!(r.below(1), 0);
    }
}
