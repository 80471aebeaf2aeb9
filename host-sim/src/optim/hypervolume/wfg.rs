//! Five or more objectives: WFG (While, Bradstreet & Barone 2012) with the points sorted by
//! the last objective, worst first. Then every point's limit set (the later points clipped to
//! its box) shares the point's last coordinate, so its exclusive volume is a slab of height
//! `r_d - p_d` times a (d-1)-dimensional exclusive area: the recursion drops one dimension
//! per level and bottoms out in the O(n^2) 4-D sweep. Limit sets are reduced to their
//! non-dominated points before recursing; a point whose limit set contains itself (it is
//! weakly dominated by a later point) is skipped.

use std::cmp::Ordering;

/// Hypervolume of `n` points (stride `d >= 5`) strictly dominating `r`.
pub(super) fn hypervolume(pts: &[f64], d: usize, r: &[f64]) -> f64 {
    let n = pts.len() / d;
    let dm = d - 1;
    // Worst last coordinate first; ties broken so that a weakly dominating point comes after
    // the points it dominates (descending lexicographic order of the other coordinates).
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_unstable_by(|&a, &b| {
        let (pa, pb) = (&pts[d * a..d * a + d], &pts[d * b..d * b + d]);
        pb[dm]
            .total_cmp(&pa[dm])
            .then_with(|| lex(&pb[..dm], &pa[..dm]))
    });
    let mut sorted = Vec::with_capacity(pts.len());
    for &i in &order {
        sorted.extend_from_slice(&pts[d * i..d * i + d]);
    }
    let mut limited: Vec<f64> = Vec::with_capacity(n * dm);
    let mut total = 0.0;
    for k in 0..n {
        let p = &sorted[d * k..d * k + d];
        limited.clear();
        let mut dominated = false;
        for j in k + 1..n {
            let q = &sorted[d * j..d * j + dm];
            let mut same = true;
            for c in 0..dm {
                let v = p[c].max(q[c]);
                same &= v == p[c];
                limited.push(v);
            }
            if same {
                dominated = true;
                break;
            }
        }
        if dominated {
            continue;
        }
        let area: f64 = (0..dm).map(|c| r[c] - p[c]).product();
        let covered = if limited.is_empty() {
            0.0
        } else {
            let nd = nondominated(&limited, dm);
            super::hypervolume_of(&nd, dm, &r[..dm])
        };
        total += (r[dm] - p[dm]) * (area - covered).max(0.0);
    }
    total
}

/// Lexicographic order of two coordinate slices.
fn lex(a: &[f64], b: &[f64]) -> Ordering {
    for (x, y) in a.iter().zip(b) {
        match x.total_cmp(y) {
            Ordering::Equal => {}
            o => return o,
        }
    }
    Ordering::Equal
}

/// The points of `pts` (stride `d`) that no other point weakly dominates, one copy of each
/// duplicate kept. Sorting lexicographically first means a point can only be dominated by
/// points before it, so each is compared with the kept ones only.
pub(super) fn nondominated(pts: &[f64], d: usize) -> Vec<f64> {
    let n = pts.len() / d;
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_unstable_by(|&a, &b| lex(&pts[d * a..d * a + d], &pts[d * b..d * b + d]));
    let mut kept: Vec<f64> = Vec::with_capacity(pts.len());
    for &i in &order {
        let p = &pts[d * i..d * i + d];
        let dominated = kept
            .chunks_exact(d)
            .any(|q| q.iter().zip(p).all(|(a, b)| a <= b));
        if !dominated {
            kept.extend_from_slice(p);
        }
    }
    kept
}
