//! Two objectives: sort by the first, sweep the second. O(n log n) for the hypervolume and
//! for every exclusive contribution.

/// Hypervolume of `n` points stored row-major in `pts` (stride 2), all strictly dominating
/// `r`.
pub(super) fn hypervolume(pts: &[f64], r: &[f64]) -> f64 {
    let n = pts.len() / 2;
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_unstable_by(|&a, &b| {
        pts[2 * a]
            .total_cmp(&pts[2 * b])
            .then(pts[2 * a + 1].total_cmp(&pts[2 * b + 1]))
    });
    let mut area = 0.0;
    let mut min_y = r[1];
    for &i in &order {
        let (x, y) = (pts[2 * i], pts[2 * i + 1]);
        if y < min_y {
            area += (r[0] - x) * (min_y - y);
            min_y = y;
        }
    }
    area
}

/// Exclusive contribution of each of the `n` points (stride 2, all strictly dominating `r`):
/// the area only it dominates, i.e. the hypervolume lost when it alone is removed. 0 for
/// weakly dominated points and for every copy of a duplicated point.
///
/// A front point `k` (front sorted by x, y decreasing) exclusively dominates its rectangle
/// `[x_k, x_{k+1}) x [y_k, y_{k-1})` less the quadrants of the dominated points that only it
/// dominates (they fall inside that rectangle, each in one rectangle only).
pub(super) fn contributions(pts: &[f64], r: &[f64]) -> Vec<f64> {
    let n = pts.len() / 2;
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_unstable_by(|&a, &b| {
        pts[2 * a]
            .total_cmp(&pts[2 * b])
            .then(pts[2 * a + 1].total_cmp(&pts[2 * b + 1]))
    });
    // Front points in x order (strictly decreasing y), and for each the area, inside its
    // rectangle, of the points it alone dominates (swept in x order like `hypervolume`).
    let mut front: Vec<usize> = Vec::with_capacity(n);
    // Per front point: (running minimum y of its dominated points, covered area so far).
    let mut inner: Vec<(f64, f64)> = Vec::with_capacity(n);
    let mut pending: Vec<(usize, f64, f64)> = Vec::new();
    for &i in &order {
        let (x, y) = (pts[2 * i], pts[2 * i + 1]);
        let b = front.len();
        if b == 0 || y < pts[2 * front[b - 1] + 1] {
            front.push(i);
            inner.push((f64::INFINITY, 0.0));
            continue;
        }
        // Dominated by front point b - 1 (the last with x <= this x); by it alone iff the
        // front point before it is higher than this point.
        let k = b - 1;
        if k == 0 || pts[2 * front[k - 1] + 1] > y {
            pending.push((k, x, y));
        }
    }
    // The rectangles' right edges are known only now: sweep each bucket (already in x order).
    let right = |k: usize| front.get(k + 1).map_or(r[0], |&j| pts[2 * j]);
    let top = |k: usize| {
        if k == 0 {
            r[1]
        } else {
            pts[2 * front[k - 1] + 1]
        }
    };
    for &(k, x, y) in &pending {
        let (min_y, covered) = &mut inner[k];
        let ceiling = min_y.min(top(k));
        if y < ceiling {
            *covered += (right(k) - x) * (ceiling - y);
            *min_y = y;
        }
    }
    let mut out = vec![0.0; n];
    for (k, &i) in front.iter().enumerate() {
        let rect = (right(k) - pts[2 * i]) * (top(k) - pts[2 * i + 1]);
        out[i] = super::num::nonneg(rect - inner[k].1);
    }
    out
}
