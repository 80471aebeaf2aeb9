//! Exact hypervolume (`host_sim::optim::hypervolume`, issue 9 items 10 and 12): against
//! brute-force inclusion-exclusion on small random sets, against analytic fronts, edge cases
//! and errors, and property tests. The pagmo2 reference data: `hypervolume_pagmo2.rs`.

use host_sim::optim::hypervolume::{
    HypervolumeError, contributions, hypervolume, least_contributor,
};
use proptest::prelude::*;

/// Inclusion-exclusion over every non-empty subset: sum of (-1)^(|T|+1) vol(box(max T)).
fn brute_force(points: &[Vec<f64>], r: &[f64]) -> f64 {
    let n = points.len();
    let mut total = 0.0;
    for mask in 1u32..(1 << n) {
        let mut corner = vec![f64::NEG_INFINITY; r.len()];
        for (i, p) in points.iter().enumerate() {
            if mask & (1 << i) != 0 {
                for (c, v) in corner.iter_mut().zip(p) {
                    *c = c.max(*v);
                }
            }
        }
        let vol: f64 = corner
            .iter()
            .zip(r)
            .map(|(c, r)| (r - c).max(0.0))
            .product();
        if mask.count_ones() % 2 == 1 {
            total += vol;
        } else {
            total -= vol;
        }
    }
    total
}

/// A small deterministic generator (xorshift64*), so the random sets are reproducible.
struct Rng(u64);
impl Rng {
    fn next_f64(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()).max(1e-300) || (a - b).abs() < 1e-15
}

#[test]
fn hypervolume_matches_brute_force_on_random_sets_2d_to_6d() {
    let mut rng = Rng(0x1234_5678_9abc_def1);
    // 2-6 objectives thoroughly; 7, 8 and 66 (the >= 5-D code's grouped, ungrouped and
    // beyond-64-bit-mask paths) a few times.
    for d in [2, 3, 4, 5, 6, 7, 8, 66] {
        let cases = if d <= 6 { 60 } else { 12 };
        for case in 0..cases {
            let n = 1 + case % 9;
            // Half the sets on a coarse grid (ties, duplicates, dominated points), half
            // continuous; a few coordinates beyond the reference point.
            let coarse = case % 2 == 0;
            let points: Vec<Vec<f64>> = (0..n)
                .map(|_| {
                    (0..d)
                        .map(|_| {
                            let u = rng.next_f64();
                            if d > 8 {
                                // Keep the volume of a 66-D box representable.
                                0.3 + 0.69 * u
                            } else if coarse {
                                (u * 5.0).floor() / 4.0
                            } else {
                                u * 1.05
                            }
                        })
                        .collect()
                })
                .collect();
            let r = vec![1.0; d];
            let exact = brute_force(&points, &r);
            let hv = hypervolume(&points, &r).unwrap();
            assert!(
                close(hv, exact, 1e-12),
                "d={d} case={case}: {hv} vs {exact}"
            );
            let c = contributions(&points, &r).unwrap();
            for (i, ci) in c.iter().enumerate() {
                let rest: Vec<Vec<f64>> = points
                    .iter()
                    .enumerate()
                    .filter(|&(j, _)| j != i)
                    .map(|(_, p)| p.clone())
                    .collect();
                let want = exact - brute_force(&rest, &r);
                assert!(
                    (ci - want).abs() <= 1e-12 * exact.max(1e-300),
                    "d={d} case={case} point {i}: {ci} vs {want}"
                );
            }
        }
    }
}

/// The hypervolume by slicing the last objective: the (d-1)-D hypervolume of the points at
/// or below each distinct last coordinate times the slab up to the next one (an independent
/// decomposition of the WFG route, which takes each point's exclusive slab instead).
fn sliced(points: &[Vec<f64>], r: &[f64]) -> f64 {
    let d = r.len();
    let mut inside: Vec<&Vec<f64>> = points
        .iter()
        .filter(|p| p.iter().zip(r).all(|(a, b)| a < b))
        .collect();
    inside.sort_by(|a, b| a[d - 1].total_cmp(&b[d - 1]));
    let mut total = 0.0;
    for k in 0..inside.len() {
        let next = inside.get(k + 1).map_or(r[d - 1], |q| q[d - 1]);
        if next == inside[k][d - 1] {
            continue; // a tie: the slab starts at the last of the equal coordinates
        }
        let below: Vec<&[f64]> = inside[..=k].iter().map(|p| &p[..d - 1]).collect();
        total += hypervolume(&below, &r[..d - 1]).unwrap() * (next - inside[k][d - 1]);
    }
    total
}

/// 6-D to 8-D (and 5-D) fronts beyond brute force's reach (20-60 points) against slicing
/// the last objective, seeded: continuous fronts on the sphere, coarse-grid sets (ties,
/// duplicates, dominated points) and points beyond the reference point; also each
/// exclusive contribution against `HV(S) - HV(S minus p)` on the smaller sets.
#[test]
fn hypervolume_5d_to_8d_matches_slicing_on_random_sets_with_ties() {
    let mut rng = Rng(0x0bad_cafe_f00d_1234);
    for d in [5, 6, 7, 8] {
        for case in 0..8 {
            let n = 20 + 5 * case;
            let coarse = case % 2 == 1;
            let points: Vec<Vec<f64>> = (0..n)
                .map(|_| {
                    let v: Vec<f64> = (0..d).map(|_| rng.next_f64()).collect();
                    if coarse {
                        v.iter().map(|u| (u * 5.0).floor() / 4.0).collect()
                    } else {
                        // On the unit sphere; one in eight pushed past the reference in a
                        // coordinate.
                        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
                        let mut p: Vec<f64> = v.iter().map(|x| x / norm).collect();
                        if rng.next_f64() < 0.125 {
                            p[0] = 1.1 + rng.next_f64();
                        }
                        p
                    }
                })
                .collect();
            let r = vec![1.05; d];
            let want = sliced(&points, &r);
            let hv = hypervolume(&points, &r).unwrap();
            assert!(close(hv, want, 1e-12), "d={d} case={case}: {hv} vs {want}");
            if n <= 30 {
                let c = contributions(&points, &r).unwrap();
                for (i, ci) in c.iter().enumerate() {
                    let rest: Vec<&Vec<f64>> = points
                        .iter()
                        .enumerate()
                        .filter(|&(j, _)| j != i)
                        .map(|(_, p)| p)
                        .collect();
                    let without = hypervolume(&rest, &r).unwrap();
                    assert!(
                        (ci - (hv - without)).abs() <= 1e-12 * hv.max(1e-300),
                        "d={d} case={case} point {i}: {ci} vs {}",
                        hv - without
                    );
                }
            }
        }
    }
}

/// Binomial coefficient.
fn choose(n: u64, k: u64) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// Every non-negative integer vector of dimension `d` summing to `m`.
fn lattice(d: usize, m: usize) -> Vec<Vec<f64>> {
    if d == 1 {
        return vec![vec![m as f64]];
    }
    let mut out = Vec::new();
    for first in 0..=m {
        for mut rest in lattice(d - 1, m - first) {
            rest.insert(0, first as f64);
            out.push(rest);
        }
    }
    out
}

#[test]
fn hypervolume_of_the_integer_simplex_lattice_is_analytic() {
    // Points: the integer vectors >= 0 summing to m; reference (R, ..., R), R >= m. A unit
    // cell [a, a+1) is dominated iff sum(a) >= m, so HV = R^d - C(m + d - 1, d).
    for (d, m) in [(2, 30), (3, 12), (4, 7), (5, 5), (6, 4)] {
        let rr = m as f64 + 1.5;
        let pts = lattice(d, m);
        // Half-integer reference: the last partial cells add rr^d - (m+1)^d of volume that is
        // all dominated (every cell with a coordinate >= m has sum >= m).
        let want = rr.powi(d as i32) - choose((m + d - 1) as u64, d as u64);
        let hv = hypervolume(&pts, &vec![rr; d]).unwrap();
        assert!(close(hv, want, 1e-13), "d={d} m={m}: {hv} vs {want}");
        // Shuffled, with every point twice and a dominated copy shifted by +0.5: unchanged.
        let mut more = pts.clone();
        more.extend(pts.iter().rev().cloned());
        more.extend(
            pts.iter()
                .map(|p| p.iter().map(|v| v + 0.5).collect::<Vec<_>>()),
        );
        let hv2 = hypervolume(&more, &vec![rr; d]).unwrap();
        assert!(close(hv2, want, 1e-13), "d={d} m={m} with copies: {hv2}");
    }
}

#[test]
fn hypervolume_of_a_linear_2d_front_and_single_points_are_analytic() {
    // x_i = i/n, y_i = 1 - i/n, reference (1, 1): HV = (n - 1) / (2n).
    let n = 1000;
    let pts: Vec<[f64; 2]> = (0..=n)
        .map(|i| [i as f64 / n as f64, 1.0 - i as f64 / n as f64])
        .collect();
    let hv = hypervolume(&pts, &[1.0, 1.0]).unwrap();
    assert!(close(hv, (n - 1) as f64 / (2 * n) as f64, 1e-13), "{hv}");
    for d in 1..=7 {
        let p = vec![0.25; d];
        let r = vec![1.0; d];
        assert!(close(
            hypervolume(&[p], &r).unwrap(),
            0.75f64.powi(d as i32),
            1e-15
        ));
    }
}

#[test]
fn hypervolume_edge_cases_are_documented_values() {
    let none: [[f64; 3]; 0] = [];
    assert_eq!(hypervolume(&none, &[1.0, 1.0, 1.0]), Ok(0.0));
    assert_eq!(contributions(&none, &[1.0, 1.0, 1.0]), Ok(vec![]));
    assert_eq!(
        least_contributor(&none, &[1.0]),
        Err(HypervolumeError::EmptySet)
    );
    // Points on or beyond the reference point dominate nothing and contribute 0.
    let outside = [[1.0, 0.0], [0.0, 2.0], [0.5, 0.5]];
    assert_eq!(hypervolume(&outside, &[1.0, 1.0]), Ok(0.25));
    assert_eq!(
        contributions(&outside, &[1.0, 1.0]),
        Ok(vec![0.0, 0.0, 0.25])
    );
    assert_eq!(least_contributor(&outside, &[1.0, 1.0]), Ok(0));
    // Duplicates: each copy's exclusive contribution is 0, in every dimension.
    for d in 1..=5 {
        let p = vec![0.5; d];
        let c = contributions(&[p.clone(), p], &vec![1.0; d]).unwrap();
        assert_eq!(c, vec![0.0, 0.0], "d={d}");
    }
}

#[test]
fn hypervolume_bad_input_is_a_typed_error_naming_point_and_coordinate() {
    let r = [1.0, 1.0];
    assert_eq!(
        hypervolume(&[[0.5, 0.5]], &[]),
        Err(HypervolumeError::ZeroDimension)
    );
    let e = hypervolume(&[[0.5, 0.5]], &[1.0, f64::INFINITY]).unwrap_err();
    assert!(matches!(
        e,
        HypervolumeError::NonFiniteReference { coordinate: 1, .. }
    ));
    let pts = vec![vec![0.5, 0.5], vec![0.2, f64::NAN]];
    let e = contributions(&pts, &r).unwrap_err();
    assert!(matches!(
        e,
        HypervolumeError::NonFinitePoint {
            index: 1,
            coordinate: 1,
            ..
        }
    ));
    assert!(e.to_string().contains("point 1 coordinate 1"), "{e}");
    let pts = vec![vec![0.5, 0.5], vec![0.2, 0.1, 0.3]];
    assert_eq!(
        hypervolume(&pts, &r),
        Err(HypervolumeError::DimensionMismatch {
            index: 1,
            expected: 2,
            found: 3
        })
    );
    // Finite but overflowing volumes are an error, not inf or NaN.
    let big = [[-1e300, -1e300], [-2e300, 0.0]];
    assert!(matches!(
        hypervolume(&big, &r),
        Err(HypervolumeError::Overflow { .. })
    ));
    assert!(matches!(
        contributions(&big, &r),
        Err(HypervolumeError::Overflow { .. })
    ));
    // Boxes that overflow inside the higher-dimensional algorithms (inf - inf on the way)
    // are an error too, never a silently wrong finite value.
    for d in 3..=6 {
        let mut a = vec![0.0; d];
        a[0] = -1e300;
        a[1] = -1e300;
        let mut b = vec![0.0; d];
        b[1] = -1e300;
        b[2] = -1e300;
        let pts = [a, b, vec![0.5; d]];
        let r = vec![1.0; d];
        assert!(
            matches!(
                hypervolume(&pts, &r),
                Err(HypervolumeError::Overflow { .. })
            ),
            "d={d}: {:?}",
            hypervolume(&pts, &r)
        );
        assert!(
            matches!(
                contributions(&pts, &r),
                Err(HypervolumeError::Overflow { .. })
            ),
            "d={d}: {:?}",
            contributions(&pts, &r)
        );
    }
}

// ---- properties --------------------------------------------------------------------------

fn front_strategy() -> impl Strategy<Value = (usize, Vec<Vec<f64>>)> {
    (2usize..=5).prop_flat_map(|d| {
        (
            Just(d),
            prop::collection::vec(
                prop::collection::vec(
                    prop_oneof![0.0..1.0f64, (0u8..5).prop_map(|k| f64::from(k) / 4.0)],
                    d,
                ),
                1..24,
            ),
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn hypervolume_unchanged_by_a_dominated_point(
        (d, pts) in front_strategy(), pick in any::<prop::sample::Index>(),
        shift in prop::collection::vec(0.0..0.3f64, 5),
    ) {
        let r = vec![1.0; d];
        let base = hypervolume(&pts, &r).unwrap();
        let p = &pts[pick.index(pts.len())];
        let dominated: Vec<f64> = p.iter().zip(&shift).map(|(v, s)| v + s).collect();
        let mut more = pts.clone();
        more.push(dominated);
        let hv = hypervolume(&more, &r).unwrap();
        prop_assert!(close(hv, base, 1e-12), "{} vs {}", hv, base);
    }

    #[test]
    fn hypervolume_contribution_is_the_loss_on_removal(
        (d, pts) in front_strategy(), pick in any::<prop::sample::Index>(),
    ) {
        let r = vec![1.0; d];
        let all = hypervolume(&pts, &r).unwrap();
        let c = contributions(&pts, &r).unwrap();
        let i = pick.index(pts.len());
        let mut rest = pts.clone();
        rest.remove(i);
        let without = hypervolume(&rest, &r).unwrap();
        prop_assert!((all - without - c[i]).abs() <= 1e-12 * all.max(1e-300),
            "HV {} - HV without {} = {} but contribution {}", all, without, all - without, c[i]);
        let lc = least_contributor(&pts, &r).unwrap();
        prop_assert!(c.iter().all(|&v| v >= c[lc]));
    }

    #[test]
    fn hypervolume_invariant_to_point_order(
        (d, pts) in front_strategy(), seed in any::<u64>(),
    ) {
        let r = vec![1.0; d];
        let mut shuffled = pts.clone();
        let mut rng = Rng(seed | 1);
        for i in (1..shuffled.len()).rev() {
            let j = (rng.next_f64() * (i + 1) as f64) as usize;
            shuffled.swap(i, j.min(i));
        }
        let a = hypervolume(&pts, &r).unwrap();
        let b = hypervolume(&shuffled, &r).unwrap();
        prop_assert!(close(a, b, 1e-12), "{} vs {}", a, b);
        // Contributions follow their points.
        let ca = contributions(&pts, &r).unwrap();
        let cb = contributions(&shuffled, &r).unwrap();
        for (p, c) in pts.iter().zip(&ca) {
            let k = shuffled.iter().position(|q| q == p).unwrap();
            // Duplicated points share one value (0), so any copy matches.
            prop_assert!((c - cb[k]).abs() <= 1e-12 * a.max(1e-300));
        }
    }
}
