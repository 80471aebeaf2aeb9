//! The empirical distribution of a sample: nearest-rank percentiles (the ones the campaign's
//! statistics report) and the step curve of the empirical CDF.

/// The nearest-rank `p`-quantile (`0 < p <= 1`) of `sorted` (ascending): the `ceil(p n)`-th
/// smallest value (at least the first); `None` for an empty sample.
#[must_use]
pub fn nearest_rank(sorted: &[f64], p: f64) -> Option<f64> {
    let n = sorted.len();
    if n == 0 {
        return None;
    }
    // The rank is computed with a relative slack so that p n that is an integer in exact
    // arithmetic (0.999 * 1000) is not pushed to the next rank by rounding.
    let x = p * n as f64;
    let rank = (x - 1e-9 * x.abs().max(1.0)).ceil();
    let rank = (rank.max(1.0) as usize).min(n);
    sorted.get(rank - 1).copied()
}

/// `values` sorted ascending, non-finite ones as +infinity.
#[must_use]
pub fn sorted(values: &[f64]) -> Vec<f64> {
    let mut v: Vec<f64> = values
        .iter()
        .map(|x| if x.is_finite() { *x } else { f64::INFINITY })
        .collect();
    v.sort_by(f64::total_cmp);
    v
}

/// The empirical CDF of `sorted` (ascending) as a step curve from (first, 0) to (last, 1):
/// at each value the fraction of the sample at or below it. Infinite values are left off
/// (the curve then ends below 1).
#[must_use]
pub fn ecdf_steps(sorted: &[f64]) -> Vec<(f64, f64)> {
    let n = sorted.len() as f64;
    let mut out = Vec::with_capacity(2 * sorted.len());
    let mut below = 0.0;
    let mut i = 0;
    while let Some(&x) = sorted.get(i) {
        if !x.is_finite() {
            break;
        }
        // Equal values are one step.
        let mut j = i;
        while sorted.get(j) == Some(&x) {
            j += 1;
        }
        out.push((x, below));
        below = j as f64 / n;
        out.push((x, below));
        i = j;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Percentiles of 1..=1000: p50 500, p90 900, p99 990, p99.9 999; of 1..=200: p99.9 200
    /// (the 200th); a single value is every percentile.
    #[test]
    fn percentiles_of_a_known_sample() {
        let v: Vec<f64> = (1..=1000).map(f64::from).collect();
        let at = |p| nearest_rank(&v, p).unwrap();
        assert_eq!(at(0.5), 500.0);
        assert_eq!(at(0.9), 900.0);
        assert_eq!(at(0.99), 990.0);
        assert_eq!(at(0.999), 999.0);
        assert_eq!(at(1.0), 1000.0);
        let v: Vec<f64> = (1..=200).map(f64::from).collect();
        assert_eq!(nearest_rank(&v, 0.999), Some(200.0));
        assert_eq!(nearest_rank(&v, 0.99), Some(198.0));
        assert_eq!(nearest_rank(&[7.0], 0.5), Some(7.0));
        assert_eq!(nearest_rank(&[], 0.5), None);
        assert_eq!(sorted(&[3.0, f64::NAN, 1.0]), vec![1.0, 3.0, f64::INFINITY]);
    }

    /// The step curve rises by 1/n at each value (by k/n at k equal ones) and ends at 1.
    #[test]
    fn ecdf_steps_of_a_known_sample() {
        let s = ecdf_steps(&[1.0, 2.0, 2.0, 4.0]);
        assert_eq!(
            s,
            vec![
                (1.0, 0.0),
                (1.0, 0.25),
                (2.0, 0.25),
                (2.0, 0.75),
                (4.0, 0.75),
                (4.0, 1.0)
            ]
        );
        let s = ecdf_steps(&[1.0, f64::INFINITY]);
        assert_eq!(s.last(), Some(&(1.0, 0.5)));
    }
}
