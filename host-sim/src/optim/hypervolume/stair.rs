//! The short 2-D staircase of the 4-D sweep's boxes, and the short sort of its candidates.
//! A box's staircase holds a handful of steps, so linear scans over two arrays beat the
//! bit-set [`super::staircase::Staircase`] there.

/// A small 2-D staircase (union of quadrants `[x, rx) x [y, ry)`): the first `len` entries
/// of two arrays, x strictly increasing and y strictly decreasing. The one in a point's box
/// holds a handful of steps, so a linear scan beats any search structure.
#[derive(Debug, Clone, Default)]
pub(super) struct Stair {
    /// The steps' x, strictly increasing (the first `len` entries).
    pub(super) x: Vec<f64>,
    /// The steps' y, strictly decreasing.
    pub(super) y: Vec<f64>,
    /// The number of steps.
    pub(super) len: usize,
    /// The bounding corner's x.
    rx: f64,
    /// The bounding corner's y.
    ry: f64,
}

impl Stair {
    /// Room for `n` steps.
    pub(super) fn resize(&mut self, n: usize) {
        self.x.resize(n, 0.0);
        self.y.resize(n, 0.0);
    }

    /// Empty the staircase, with bounding corner `(rx, ry)`.
    pub(super) fn reset(&mut self, rx: f64, ry: f64) {
        self.len = 0;
        self.rx = rx;
        self.ry = ry;
    }

    /// Append the step `(x, y)`: `x` at least the last step's, `y` below it (a scan in x
    /// order). A step at the same x as the last one replaces it.
    #[inline]
    pub(super) fn push(&mut self, x: f64, y: f64) {
        let mut k = self.len;
        if k > 0 && self.x[k - 1] == x {
            k -= 1;
        }
        self.x[k] = x;
        self.y[k] = y;
        self.len = k + 1;
    }

    /// Insert the step `(x, y)`; returns the area it adds to the union (0 if it is weakly
    /// dominated), removing the steps it dominates.
    #[inline(always)]
    pub(super) fn insert(&mut self, x: f64, y: f64) -> f64 {
        let n = self.len;
        let (sx, sy) = (&mut self.x[..n + 1], &mut self.y[..n + 1]);
        let mut i = 0;
        while i < n && sx[i] < x {
            i += 1;
        }
        let mut h = if i > 0 { sy[i - 1] } else { self.ry };
        if h <= y || (i < n && sx[i] == x && sy[i] <= y) {
            return 0.0;
        }
        let mut cur = x;
        let mut added = 0.0;
        let mut j = i;
        while j < n && sy[j] >= y {
            added += (sx[j] - cur) * (h - y);
            cur = sx[j];
            h = sy[j];
            j += 1;
        }
        let end = if j < n { sx[j] } else { self.rx };
        added += (end - cur) * (h - y);
        if j == i {
            sx.copy_within(i..n, i + 1);
            sy.copy_within(i..n, i + 1);
            self.len = n + 1;
        } else {
            sx.copy_within(j..n, i + 1);
            sy.copy_within(j..n, i + 1);
            self.len = n + 1 - (j - i);
        }
        sx[i] = x;
        sy[i] = y;
        added
    }
}

/// Sort short `(z, position)` lists by z (insertion sort: the lists hold a few entries).
#[inline]
pub(super) fn sort_short(v: &mut [(f64, u32)]) {
    for i in 1..v.len() {
        let item = v[i];
        let mut j = i;
        while j > 0 && v[j - 1].0 > item.0 {
            v[j] = v[j - 1];
            j -= 1;
        }
        v[j] = item;
    }
}
