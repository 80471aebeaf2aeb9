//! Variation operators on real vectors inside box bounds, with pagmo's formulas: uniform
//! sampling, MOEA/D's differential-evolution step with its bound repair, simulated binary
//! crossover (SBX) and polynomial mutation (Deb). Every random draw comes from the run's
//! [`OptimRng`], in a fixed order.

use super::problem::Bounds;
use super::rng::OptimRng;
use super::root::Root;

/// `x^e`: by repeated squaring when `e` is a whole number up to 64 in magnitude (the usual
/// distribution indices; portable and about ten times cheaper than `powf`), else `powf`.
#[inline]
#[must_use]
pub fn pow(x: f64, e: f64) -> f64 {
    if e.fract() == 0.0 && e.abs() <= 64.0 {
        let mut n = e.abs() as u32;
        let mut base = x;
        let mut acc = 1.0;
        while n > 0 {
            if n & 1 == 1 {
                acc *= base;
            }
            base *= base;
            n >>= 1;
        }
        if e < 0.0 { 1.0 / acc } else { acc }
    } else {
        x.powf(e)
    }
}

/// A uniformly random point inside the bounds.
#[must_use]
pub fn random_point(bounds: &Bounds, rng: &mut OptimRng) -> Vec<f64> {
    bounds
        .lower()
        .iter()
        .zip(bounds.upper())
        .map(|(&lo, &hi)| rng.uniform_in(lo, hi))
        .collect()
}

/// MOEA/D-DE step (pagmo `moead`): per variable with probability `cr`,
/// `child = x + f (a - b)`; a value outside the bounds is redrawn uniformly between the bound
/// and the parent's value; otherwise the parent's value is kept.
#[allow(clippy::too_many_arguments)] // the DE step has exactly these inputs
pub fn de_step(
    x: &[f64],
    a: &[f64],
    b: &[f64],
    f: f64,
    cr: f64,
    bounds: &Bounds,
    rng: &mut OptimRng,
    child: &mut Vec<f64>,
) {
    child.clear();
    if cr >= 1.0 {
        // Every variable crosses, no draw needed (same distribution): the step vectorises,
        // and the rare repairs follow in variable order (the same draws as the loop below).
        child.extend(
            x.iter()
                .zip(a)
                .zip(b)
                .map(|((&xk, &ak), &bk)| xk + f * (ak - bk)),
        );
        let vars = child
            .iter_mut()
            .zip(x)
            .zip(bounds.lower())
            .zip(bounds.upper());
        for (((v, &xk), &lo), &hi) in vars {
            if *v < lo {
                *v = lo + rng.uniform() * (xk - lo);
            }
            if *v > hi {
                *v = hi - rng.uniform() * (hi - xk);
            }
        }
        return;
    }
    let vars = x
        .iter()
        .zip(a)
        .zip(b)
        .zip(bounds.lower())
        .zip(bounds.upper());
    for ((((&xk, &ak), &bk), &lo), &hi) in vars {
        let mut v = xk;
        if rng.uniform() < cr {
            v = xk + f * (ak - bk);
            if v < lo {
                v = lo + rng.uniform() * (xk - lo);
            }
            if v > hi {
                v = hi - rng.uniform() * (hi - xk);
            }
        }
        child.push(v);
    }
}

/// Polynomial mutation (Deb & Goyal; pagmo's form): each variable mutates with probability
/// `rate` with distribution index `eta`; results are clamped to the bounds.
///
/// The mutated variables are found by geometric skipping (the gap to the next mutated
/// variable is drawn, `P(gap = j) = (1 - rate)^j rate`), which selects them with exactly the
/// per-variable Bernoulli(`rate`) law but draws one number per mutation instead of one per
/// variable.
pub fn polynomial_mutation(
    x: &mut [f64],
    bounds: &Bounds,
    rate: f64,
    eta: f64,
    rng: &mut OptimRng,
) {
    if rate <= 0.0 {
        return;
    }
    let mut_pow = 1.0 / (eta + 1.0);
    let log_q = (1.0 - rate).ln();
    let gap = |rng: &mut OptimRng| -> usize {
        if rate >= 1.0 {
            0
        } else {
            // 1 - u lies in (0, 1]; the quotient is >= 0 and saturates on conversion.
            ((1.0 - rng.uniform()).ln() / log_q).floor() as usize
        }
    };
    let mut k = gap(rng);
    while k < x.len() {
        let (yl, yu) = (bounds.lower()[k], bounds.upper()[k]);
        let y = &mut x[k];
        let span = yu - yl;
        let delta1 = (*y - yl) / span;
        let delta2 = (yu - *y) / span;
        let rnd = rng.uniform();
        let deltaq = if rnd < 0.5 {
            let xy = 1.0 - delta1;
            let val = 2.0 * rnd + (1.0 - 2.0 * rnd) * pow(xy, eta + 1.0);
            val.powf(mut_pow) - 1.0
        } else {
            let xy = 1.0 - delta2;
            let val = 2.0 * (1.0 - rnd) + 2.0 * (rnd - 0.5) * pow(xy, eta + 1.0);
            1.0 - val.powf(mut_pow)
        };
        *y = (*y + deltaq * span).clamp(yl, yu);
        k = k.saturating_add(1).saturating_add(gap(rng));
    }
}

/// Simulated binary crossover (Deb & Agrawal; pagmo's bounded form since its PR #439, as in
/// pygmo 2.20): with probability `cr` the pair is crossed, each variable with probability 1/2
/// when the parents differ by more than 1e-14, with distribution index `eta`; one uniform
/// number per variable, the lower child's spread from the distance to the lower bound and the
/// upper child's from the distance to the upper bound; children are clamped to the bounds and
/// swapped with probability 1/2 per variable. Returns the two children.
#[must_use]
pub fn sbx(
    p1: &[f64],
    p2: &[f64],
    bounds: &Bounds,
    cr: f64,
    eta: f64,
    rng: &mut OptimRng,
) -> (Vec<f64>, Vec<f64>) {
    let mut c1 = p1.to_vec();
    let mut c2 = p2.to_vec();
    if rng.uniform() >= cr {
        return (c1, c2);
    }
    let root = 1.0 / (eta + 1.0);
    for k in 0..p1.len() {
        if rng.uniform() >= 0.5 || (p1[k] - p2[k]).abs() <= 1e-14 {
            continue;
        }
        let (y1, y2) = if p1[k] < p2[k] {
            (p1[k], p2[k])
        } else {
            (p2[k], p1[k])
        };
        let (yl, yu) = (bounds.lower()[k], bounds.upper()[k]);
        let rand = rng.uniform();
        let betaq = |beta: f64| {
            let alpha = 2.0 - pow(beta, -(eta + 1.0));
            if rand < 1.0 / alpha {
                (rand * alpha).powf(root)
            } else {
                (1.0 / (2.0 - rand * alpha)).powf(root)
            }
        };
        let b1 = betaq(1.0 + 2.0 * (y1 - yl) / (y2 - y1));
        let v1 = (0.5 * ((y1 + y2) - b1 * (y2 - y1))).clamp(yl, yu);
        let b2 = betaq(1.0 + 2.0 * (yu - y2) / (y2 - y1));
        let v2 = (0.5 * ((y1 + y2) + b2 * (y2 - y1))).clamp(yl, yu);
        if rng.uniform() < 0.5 {
            c1[k] = v2;
            c2[k] = v1;
        } else {
            c1[k] = v1;
            c2[k] = v2;
        }
    }
    (c1, c2)
}

/// One child of simulated binary crossover, written into `child` (its allocation reused):
/// the distribution of [`sbx`]'s first child (each variable crossed with probability 1/2 when
/// the parents differ by more than 1e-14; the child takes the lower or the upper spread with
/// probability 1/2, from the distance to its bound; clamped to the bounds), drawing and
/// computing only the kept side. MOEA/D's SBX variation (Zhang & Li 2007), which keeps one
/// child. Cheaper than [`sbx`]: the crossing and side coins are bits of one 64-bit draw per 32
/// variables, and the root `u^(1 / (eta + 1))` is [`Root`]'s table method for a whole
/// `eta + 1` up to 101 (relative error below 1e-13 against `powf`, no `ln`/`exp`), `powf`
/// otherwise.
#[allow(clippy::too_many_arguments)] // the operator has exactly these inputs
pub fn sbx_child(
    p1: &[f64],
    p2: &[f64],
    bounds: &Bounds,
    cr: f64,
    eta: f64,
    rng: &mut OptimRng,
    child: &mut Vec<f64>,
) {
    child.clear();
    child.extend_from_slice(p1);
    if rng.uniform() >= cr {
        return;
    }
    let root = Root::new(eta + 1.0);
    let (lower, upper) = (bounds.lower(), bounds.upper());
    for (chunk, start) in child.chunks_mut(32).zip((0..).step_by(32)) {
        let bits = rng.next_u64();
        // Low 32 bits: cross variable k; high 32 bits: take the upper spread.
        let mut cross = (bits as u32) & (u32::MAX >> (32 - chunk.len()));
        // First the draws, in variable order (the generator is serial)...
        let (mut picked, mut draws, mut m) = ([0_u8; 32], [0.0_f64; 32], 0);
        while cross != 0 {
            let j = cross.trailing_zeros();
            cross &= cross - 1;
            let k = start + j as usize;
            if (p1[k] - p2[k]).abs() > 1e-14 {
                picked[m] = j as u8;
                draws[m] = rng.uniform();
                m += 1;
            }
        }
        // ... then the arithmetic, independent from one variable to the next and without
        // branches on the data (the side and the root's sign are coin flips: selects, not
        // branches), so that the processor overlaps consecutive variables.
        for (&j, &u) in picked[..m].iter().zip(&draws[..m]) {
            let j = usize::from(j);
            let k = start + j;
            let (a, b) = (p1[k], p2[k]);
            let up = ((bits >> (32 + j)) & 1) as usize;
            let (y1, y2) = (a.min(b), a.max(b));
            let (yl, yu) = (lower[k], upper[k]);
            let spread = y2 - y1;
            let gap = [y1 - yl, yu - y2][up];
            // 1 / beta^(eta + 1) with beta = 1 + 2 gap / spread, one division.
            let alpha = 2.0 - pow(spread / (spread + 2.0 * gap), eta + 1.0);
            let ra = u * alpha;
            // betaq = ra^root below 1, else (1 / (2 - ra))^root = (2 - ra)^-root.
            let high = ra >= 1.0;
            let betaq = root.signed([ra, 2.0 - ra][usize::from(high)], high);
            let half = 0.5 * betaq * spread;
            let mid = 0.5 * (y1 + y2);
            // mid + half on the upper side, mid - half on the lower.
            let v = mid + f64::from_bits(half.to_bits() ^ (((up as u64) ^ 1) << 63));
            chunk[j] = v.clamp(yl, yu);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn operators_stay_inside_bounds() {
        let bounds = Bounds::new(vec![-1.0, 0.0, 5.0], vec![1.0, 0.001, 6.0]).unwrap();
        let mut rng = OptimRng::new(11);
        let mut child = Vec::new();
        for _ in 0..2000 {
            let x = random_point(&bounds, &mut rng);
            let a = random_point(&bounds, &mut rng);
            let b = random_point(&bounds, &mut rng);
            de_step(&x, &a, &b, 0.9, 1.0, &bounds, &mut rng, &mut child);
            polynomial_mutation(&mut child, &bounds, 1.0, 20.0, &mut rng);
            let (c1, c2) = sbx(&x, &a, &bounds, 1.0, 2.0, &mut rng);
            for v in [&x, &child, &c1, &c2] {
                for k in 0..3 {
                    assert!(
                        v[k] >= bounds.lower()[k] && v[k] <= bounds.upper()[k],
                        "{v:?}"
                    );
                }
            }
        }
    }

    /// `sbx_child`: inside the bounds; half of the variables crossed; far from the bounds the
    /// crossed values are centred on the parents' mean, spread on both sides (the first child
    /// of `sbx`, in distribution).
    #[test]
    fn sbx_child_crosses_half_the_variables_centred_on_the_parents() {
        let n = 40;
        let bounds = Bounds::uniform(n, -100.0, 100.0).unwrap();
        let (p1, p2) = (vec![0.3; n], vec![0.7; n]);
        let mut rng = OptimRng::new(8);
        let mut child = Vec::new();
        let (mut crossed, mut sum, mut above) = (0usize, 0.0, 0usize);
        let trials = 4000;
        for _ in 0..trials {
            sbx_child(&p1, &p2, &bounds, 1.0, 20.0, &mut rng, &mut child);
            for &c in &child {
                assert!((-100.0..=100.0).contains(&c));
                if c != 0.3 {
                    crossed += 1;
                    sum += c;
                    above += usize::from(c > 0.5);
                }
            }
        }
        let frac = crossed as f64 / (trials * n) as f64;
        assert!((frac - 0.5).abs() < 0.01, "{frac}");
        let mean = sum / crossed as f64;
        assert!((mean - 0.5).abs() < 0.002, "{mean}");
        let up = above as f64 / crossed as f64;
        assert!((up - 0.5).abs() < 0.01, "{up}");
        // Probability 0: the first parent unchanged; near a bound: inside it.
        sbx_child(&p1, &p2, &bounds, 0.0, 20.0, &mut rng, &mut child);
        assert_eq!(child, p1);
        let tight = Bounds::uniform(3, 0.0, 1.0).unwrap();
        for _ in 0..1000 {
            sbx_child(
                &[0.0, 1.0, 0.5],
                &[1e-9, 0.999, 0.0],
                &tight,
                1.0,
                2.0,
                &mut rng,
                &mut child,
            );
            assert!(child.iter().all(|c| (0.0..=1.0).contains(c)), "{child:?}");
        }
    }

    #[test]
    fn sbx_children_are_centred_on_the_parents() {
        // SBX preserves the mean of the two parents (before clamping).
        let bounds = Bounds::uniform(1, -100.0, 100.0).unwrap();
        let mut rng = OptimRng::new(5);
        for _ in 0..200 {
            let (c1, c2) = sbx(&[0.3], &[0.7], &bounds, 1.0, 15.0, &mut rng);
            assert!((c1[0] + c2[0] - 1.0).abs() < 1e-12, "{c1:?} {c2:?}");
        }
    }

    #[test]
    fn integer_pow_matches_powf() {
        for &x in &[0.0, 1e-3, 0.37, 1.0, 1.7, 12.5] {
            for e in [
                -21.0, -11.0, -1.0, 0.0, 1.0, 2.0, 11.0, 21.0, 51.0, 0.5, 2.5,
            ] {
                let (a, b): (f64, f64) = (pow(x, e), x.powf(e));
                assert!(a == b || ((a - b) / b).abs() < 1e-13, "{x}^{e}: {a} {b}");
            }
        }
    }

    #[test]
    fn geometric_skipping_mutates_each_variable_with_the_given_rate() {
        let bounds = Bounds::uniform(50, 0.0, 1.0).unwrap();
        let mut rng = OptimRng::new(8);
        for rate in [0.02, 0.3, 1.0] {
            let mut counts = [0usize; 50];
            let trials = 4000;
            for _ in 0..trials {
                let mut x = vec![0.5; 50];
                polynomial_mutation(&mut x, &bounds, rate, 20.0, &mut rng);
                for (c, v) in counts.iter_mut().zip(&x) {
                    *c += usize::from(*v != 0.5);
                }
            }
            let total: usize = counts.iter().sum();
            let expected = rate * (50 * trials) as f64;
            let sigma = (expected * (1.0 - rate)).sqrt().max(1.0);
            assert!(
                (total as f64 - expected).abs() < 5.0 * sigma,
                "rate {rate}: {total} vs {expected}"
            );
            // Uniform over positions: first and last ten variables mutate equally often.
            let head: usize = counts[..10].iter().sum();
            let tail: usize = counts[40..].iter().sum();
            let e = rate * (10 * trials) as f64;
            let s = (e * (1.0 - rate)).sqrt().max(1.0);
            assert!(
                (head as f64 - e).abs() < 5.0 * s && (tail as f64 - e).abs() < 5.0 * s,
                "{head} {tail} {e}"
            );
        }
    }

    #[test]
    fn mutation_with_rate_zero_is_identity() {
        let bounds = Bounds::uniform(4, 0.0, 1.0).unwrap();
        let mut rng = OptimRng::new(2);
        let mut x = vec![0.1, 0.2, 0.3, 0.4];
        polynomial_mutation(&mut x, &bounds, 0.0, 20.0, &mut rng);
        assert_eq!(x, vec![0.1, 0.2, 0.3, 0.4]);
    }
}
