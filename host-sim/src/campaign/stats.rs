//! Campaign statistics: mean, standard deviation, 50th/90th/95th/99th/99.9th percentiles (nearest
//! rank, `report::campaign::cdf::nearest_rank`, the percentiles the miss CDF marks) and worst
//! case.

use serde::Serialize;

use super::{CaseResult, Mode};
use crate::report::campaign::cdf::{nearest_rank, sorted};

/// Statistics of one quantity over the cases.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Stats {
    /// Mean.
    pub mean: f64,
    /// Standard deviation (population).
    pub std: f64,
    /// Median (nearest rank: the `ceil(0.5 n)`-th smallest).
    pub p50: f64,
    /// 90th percentile (nearest rank: the `ceil(0.9 n)`-th smallest).
    pub p90: f64,
    /// 95th percentile (nearest rank: the `ceil(0.95 n)`-th smallest).
    pub p95: f64,
    /// 99th percentile (nearest rank: the `ceil(0.99 n)`-th smallest).
    pub p99: f64,
    /// 99.9th percentile (nearest rank: the `ceil(0.999 n)`-th smallest; with fewer than
    /// 1000 cases the largest value).
    pub p99_9: f64,
    /// Largest value.
    pub worst: f64,
}

impl Stats {
    /// Statistics of `values` (non-finite values count as +infinity for the percentiles and worst, and
    /// make the mean infinite); all zero for no value.
    #[must_use]
    pub fn of(values: &[f64]) -> Self {
        if values.is_empty() {
            return Self {
                mean: 0.0,
                std: 0.0,
                p50: 0.0,
                p90: 0.0,
                p95: 0.0,
                p99: 0.0,
                p99_9: 0.0,
                worst: 0.0,
            };
        }
        let v = sorted(values);
        let n = v.len() as f64;
        let mean = v.iter().sum::<f64>() / n;
        let var = v.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n;
        let pct = |p: f64| nearest_rank(&v, p).unwrap_or(f64::INFINITY);
        Self {
            mean,
            std: var.sqrt(),
            p50: pct(0.5),
            p90: pct(0.9),
            p95: pct(0.95),
            p99: pct(0.99),
            p99_9: pct(0.999),
            worst: v.last().copied().unwrap_or(f64::INFINITY),
        }
    }
}

/// The figures of one guidance mode.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ModeStats {
    /// The mode.
    pub mode: Mode,
    /// Flights (not counting failed ones).
    pub cases: usize,
    /// Cases whose flight failed (an error instead of a result; not in the statistics).
    pub failed: usize,
    /// Flights that reached the terminal interface.
    pub reached_interface: usize,
    /// Miss distance \[km\].
    pub miss_km: Stats,
    /// Downrange error \[km\] (signed; p99 and worst of the magnitude).
    pub downrange_km: Stats,
    /// Crossrange error \[km\] (signed).
    pub crossrange_km: Stats,
    /// Peak heat flux / limit \[-\].
    pub heat_flux_ratio: Stats,
    /// Peak g-load / limit \[-\].
    pub g_load_ratio: Stats,
    /// Peak g-load rate / limit \[-\].
    pub g_load_rate_ratio: Stats,
    /// Flights above a limit by more than 5 % (heat flux, g-load, g-load rate).
    pub over_limit_5pct: [usize; 3],
    /// Reversals per flight.
    pub reversals: Stats,
    /// Re-plans per flight.
    pub replans: Stats,
    /// Fall-backs per flight.
    pub fall_backs: Stats,
}

impl ModeStats {
    /// Figures of `cases` (all of one mode) and the number of `failed` cases of the mode.
    #[must_use]
    pub fn of(mode: Mode, cases: &[CaseResult], failed: usize) -> Self {
        let col = |f: &dyn Fn(&CaseResult) -> f64| cases.iter().map(f).collect::<Vec<_>>();
        let over = |i: usize| {
            cases
                .iter()
                .filter(|c| {
                    c.limit_ratios
                        .get(i)
                        .is_none_or(|r| r.is_nan() || *r > 1.05)
                })
                .count()
        };
        Self {
            mode,
            cases: cases.len(),
            failed,
            reached_interface: cases.iter().filter(|c| c.reached_interface).count(),
            miss_km: Stats::of(&col(&|c| c.miss_m / 1e3)),
            downrange_km: Stats::of(&col(&|c| c.downrange_error_m / 1e3)),
            crossrange_km: Stats::of(&col(&|c| c.crossrange_error_m / 1e3)),
            heat_flux_ratio: Stats::of(&col(&|c| c.limit_ratios[0])),
            g_load_ratio: Stats::of(&col(&|c| c.limit_ratios[1])),
            g_load_rate_ratio: Stats::of(&col(&|c| c.limit_ratios[2])),
            over_limit_5pct: [over(0), over(1), over(2)],
            reversals: Stats::of(&col(&|c| f64::from(c.reversals))),
            replans: Stats::of(&col(&|c| f64::from(c.replans))),
            fall_backs: Stats::of(&col(&|c| f64::from(c.fall_backs))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_of_known_values() {
        let v: Vec<f64> = (1..=200).map(f64::from).collect();
        let s = Stats::of(&v);
        assert_eq!(s.mean, 100.5);
        assert_eq!(s.p99, 198.0);
        assert_eq!(s.p95, 190.0);
        assert_eq!(s.p50, 100.0);
        assert_eq!(s.p90, 180.0);
        // 0.999 * 200 = 199.8: the 200th.
        assert_eq!(s.p99_9, 200.0);
        let k: Vec<f64> = (1..=1000).rev().map(f64::from).collect();
        assert_eq!(Stats::of(&k).p99_9, 999.0);
        assert_eq!(s.worst, 200.0);
        assert!((s.std - (((200.0f64 * 200.0) - 1.0) / 12.0).sqrt()).abs() < 1e-9);
        assert_eq!(Stats::of(&[1.0, f64::NAN]).worst, f64::INFINITY);
    }
}
