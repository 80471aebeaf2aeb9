//! MHACO's multi-kernel Gaussian sampling (pagmo `maco`): the pheromone weights of the archive
//! ranks, the per-variable standard deviations, and the new ants.
//!
//! * Weight of archive rank `l = 1..=ker`: `omega_l = exp(-(l-1)^2 / (2 q^2 ker^2)) /
//!   (q ker sqrt(2 pi))`; an ant picks its kernel (archive member) with probability
//!   `omega_l / sum omega`.
//! * Standard deviation of variable `h`: `(D_max - D_min) / gen_mark`, the largest and smallest
//!   distance between two archive members in that variable; with `focus != 0` it is capped at
//!   `(ub - lb) / focus` when `(D_max - D_min) / gen > (ub - lb) / focus` (pagmo's test).
//! * Each variable of an ant is the kernel's value plus `sigma_h` times a standard normal
//!   draw, redrawn until it lies inside the bounds (after [`MAX_REDRAWS`] failed draws, which
//!   only a tiny `focus` makes likely, it is drawn uniformly inside the bounds instead).
//!
//! Normal draws use a ziggurat on the run's [`OptimRng`] (written here, like the generator's
//! other draws, so that the bit patterns never depend on a distribution crate's version).

use serde::{Deserialize, Serialize};

use crate::optim::problem::Bounds;
use crate::optim::rng::OptimRng;

/// Redraws of one variable before falling back to a uniform draw inside the bounds.
pub const MAX_REDRAWS: usize = 1000;

/// Layers of the ziggurat.
const LAYERS: usize = 256;
/// Start of the tail (Marsaglia & Tsang 2000, 256 layers).
const ZIG_R: f64 = 3.654_152_885_361_009;
/// Area of each layer.
const ZIG_V: f64 = 0.004_928_673_233_99;

/// Ziggurat tables: layer right edges `x[0..=LAYERS]` (`x[0] = V / f(R)` is the base strip's
/// pseudo-width, `x[1] = R`, `x[LAYERS] = 0`) and the density at them.
struct Ziggurat {
    x: [f64; LAYERS + 1],
    f: [f64; LAYERS + 1],
}

fn ziggurat() -> &'static Ziggurat {
    static TABLES: std::sync::OnceLock<Ziggurat> = std::sync::OnceLock::new();
    TABLES.get_or_init(|| {
        let pdf = |x: f64| (-0.5 * x * x).exp();
        let mut x = [0.0; LAYERS + 1];
        x[0] = ZIG_V / pdf(ZIG_R);
        x[1] = ZIG_R;
        for i in 1..LAYERS - 1 {
            x[i + 1] = (-2.0 * (ZIG_V / x[i] + pdf(x[i])).ln()).sqrt();
        }
        x[LAYERS] = 0.0;
        let mut f = [0.0; LAYERS + 1];
        for i in 0..=LAYERS {
            f[i] = pdf(x[i]);
        }
        Ziggurat { x, f }
    })
}

/// Standard normal variates from the run's generator: Marsaglia & Tsang's ziggurat
/// (256 layers, one 64-bit draw in about 99 % of the cases; the tail by Marsaglia's method).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Normal;

impl Normal {
    /// One standard normal draw.
    #[inline]
    pub fn draw(&mut self, rng: &mut OptimRng) -> f64 {
        // 2^-53
        const SCALE: f64 = 1.0 / 9_007_199_254_740_992.0;
        let z = ziggurat();
        loop {
            let bits = rng.next_u64();
            let i = (bits & 0xff) as usize;
            // Uniform in [-1, 1) from the 53 high bits (disjoint from the layer bits).
            let u = 2.0 * ((bits >> 11) as f64 * SCALE) - 1.0;
            let x = u * z.x[i];
            if x.abs() < z.x[i + 1] {
                return x;
            }
            if i == 0 {
                // Tail beyond R.
                loop {
                    let a = (1.0 - rng.uniform()).ln() / ZIG_R;
                    let b = (1.0 - rng.uniform()).ln();
                    if -2.0 * b >= a * a {
                        return if u < 0.0 { a - ZIG_R } else { ZIG_R - a };
                    }
                }
            }
            if z.f[i + 1] + (z.f[i] - z.f[i + 1]) * rng.uniform() < (-0.5 * x * x).exp() {
                return x;
            }
        }
    }
}

/// Cumulative kernel probabilities of the archive ranks for convergence parameter `q`.
#[must_use]
pub fn cumulative_weights(ker: usize, q: f64) -> Vec<f64> {
    let k = ker as f64;
    let norm = 1.0 / (q * k * (2.0 * std::f64::consts::PI).sqrt());
    let omega: Vec<f64> = (0..ker)
        .map(|l| {
            let l = l as f64;
            norm * (-(l * l) / (2.0 * q * q * k * k)).exp()
        })
        .collect();
    let sum: f64 = omega.iter().sum();
    let mut acc = 0.0;
    omega
        .iter()
        .map(|w| {
            acc += w / sum;
            acc
        })
        .collect()
}

/// The archive rank chosen by a uniform draw `u` in [0, 1) (pagmo's search: the first rank
/// whose cumulative probability reaches `u`, the last rank beyond the second-to-last).
#[inline]
#[must_use]
pub fn pick(cumulative: &[f64], u: f64) -> usize {
    let k = cumulative.partition_point(|&c| c < u);
    k.min(cumulative.len().saturating_sub(1))
}

/// Per-variable standard deviations from the archive decisions (`ker >= 2`).
#[must_use]
pub fn sigmas(
    archive: &[&[f64]],
    bounds: &Bounds,
    gen_mark: u64,
    focus: f64,
    generation: u64,
) -> Vec<f64> {
    let n = bounds.dim();
    let ker = archive.len();
    // Column-major copy as order-preserving integer keys (sorting integers is several times
    // faster than sorting floats by `total_cmp`).
    let mut columns = vec![0u64; n * ker];
    for (k, x) in archive.iter().enumerate() {
        for (h, &v) in x.iter().enumerate() {
            columns[h * ker + k] = order_key(v);
        }
    }
    columns
        .chunks_exact_mut(ker)
        .enumerate()
        .map(|(h, column)| {
            column.sort_unstable();
            let value = |k: u64| from_order_key(k);
            let d_max = value(column[ker - 1]) - value(column[0]);
            let mut d_min = f64::INFINITY;
            let mut previous = value(column[0]);
            for &k in &column[1..] {
                let v = value(k);
                d_min = d_min.min(v - previous);
                previous = v;
            }
            let spread = d_max - d_min;
            let range = bounds.upper()[h] - bounds.lower()[h];
            if focus != 0.0 && spread / generation as f64 > range / focus {
                range / focus
            } else {
                spread / gen_mark as f64
            }
        })
        .collect()
}

/// A `u64` whose unsigned order is the numeric order of the finite `v` (`total_cmp`'s).
#[inline]
fn order_key(v: f64) -> u64 {
    let b = v.to_bits();
    if b >> 63 == 1 { !b } else { b | (1 << 63) }
}

/// Inverse of [`order_key`].
#[inline]
fn from_order_key(k: u64) -> f64 {
    f64::from_bits(if k >> 63 == 1 { k & !(1 << 63) } else { !k })
}

/// One new ant around `kernel` with standard deviations `sigma`.
pub fn ant(
    kernel: &[f64],
    sigma: &[f64],
    bounds: &Bounds,
    normal: &mut Normal,
    rng: &mut OptimRng,
) -> Vec<f64> {
    let (lower, upper) = (bounds.lower(), bounds.upper());
    kernel
        .iter()
        .zip(sigma)
        .enumerate()
        .map(|(h, (&centre, &s))| {
            for _ in 0..MAX_REDRAWS {
                let g = centre + s * normal.draw(rng);
                if g >= lower[h] && g <= upper[h] {
                    return g;
                }
            }
            rng.uniform_in(lower[h], upper[h])
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_are_pagmos() {
        // q = 1: nearly uniform over the archive; q = 0.01 (after the threshold): almost all
        // mass on the best rank.
        let c = cumulative_weights(63, 1.0);
        assert!((c[62] - 1.0).abs() < 1e-12);
        assert!(c[0] > 1.0 / 63.0 && c[0] < 1.4 / 63.0, "{}", c[0]);
        let c = cumulative_weights(63, 0.01);
        // omega_2 / omega_1 = exp(-1 / (2 * 0.0001 * 3969)).
        let r = (-1.0f64 / (2.0 * 1e-4 * 3969.0)).exp();
        assert!((c[0] - 1.0 / (1.0 + r + r.powi(4) + r.powi(9))).abs() < 1e-6);
        assert_eq!(pick(&c, 0.0), 0);
        assert_eq!(pick(&c, c[0]), 0);
        assert_eq!(pick(&c, c[0] + 1e-12), 1);
        assert_eq!(pick(&[0.5, 1.0], 0.9999), 1);
    }

    #[test]
    fn order_keys_sort_like_total_cmp() {
        let mut v = [3.5, -0.0, 0.0, -2.0, 1e-300, -1e300, 7.0, -7.0];
        let mut keys: Vec<u64> = v.iter().map(|&x| order_key(x)).collect();
        keys.sort_unstable();
        v.sort_by(f64::total_cmp);
        let back: Vec<f64> = keys.into_iter().map(from_order_key).collect();
        assert_eq!(
            back.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
            v.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
        );
    }

    #[test]
    fn sigmas_and_ants() {
        let bounds = Bounds::uniform(2, 0.0, 1.0).unwrap();
        let a = [0.1, 0.5];
        let b = [0.4, 0.5];
        let c = [0.3, 0.5];
        let archive: Vec<&[f64]> = vec![&a, &b, &c];
        // Variable 0: D_max 0.3, D_min 0.1 -> 0.2 / gen_mark; variable 1: 0.
        let s = sigmas(&archive, &bounds, 2, 0.0, 1);
        assert!((s[0] - 0.1).abs() < 1e-12 && s[1] == 0.0, "{s:?}");
        // focus 10: (0.2 / 1) > 1 / 10 -> capped at 0.1 for variable 0.
        let s = sigmas(&archive, &bounds, 1, 10.0, 1);
        assert!((s[0] - 0.1).abs() < 1e-12, "{s:?}");
        let mut rng = OptimRng::new(3);
        let mut normal = Normal;
        let (mut sum, mut sq) = (0.0, 0.0);
        let n = 20_000;
        for _ in 0..n {
            let z = normal.draw(&mut rng);
            sum += z;
            sq += z * z;
        }
        let mean = sum / f64::from(n);
        let var = sq / f64::from(n) - mean * mean;
        assert!(
            mean.abs() < 0.03 && (var - 1.0).abs() < 0.04,
            "{mean} {var}"
        );
        // Tail and shape: P(|z| > 1) = 0.3173, P(|z| > 2) = 0.0455, P(|z| > 3.6542) = 2.58e-4.
        let n = 400_000;
        let (mut c1, mut c2, mut c3) = (0, 0, 0);
        for _ in 0..n {
            let z = normal.draw(&mut rng).abs();
            c1 += usize::from(z > 1.0);
            c2 += usize::from(z > 2.0);
            c3 += usize::from(z > ZIG_R);
        }
        let frac = |c: usize| c as f64 / n as f64;
        assert!((frac(c1) - 0.3173).abs() < 0.004, "{}", frac(c1));
        assert!((frac(c2) - 0.0455).abs() < 0.0015, "{}", frac(c2));
        assert!((frac(c3) - 2.58e-4).abs() < 1.0e-4, "{}", frac(c3));
        for _ in 0..1000 {
            let x = ant(&[0.99, 0.5], &[5.0, 0.0], &bounds, &mut normal, &mut rng);
            assert!((0.0..=1.0).contains(&x[0]) && x[1] == 0.5, "{x:?}");
        }
    }
}
