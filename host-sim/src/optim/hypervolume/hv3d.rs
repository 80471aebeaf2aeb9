//! Three objectives: the dimension sweep of Beume et al. / Fonseca et al. (HV3D) in
//! O(n log n), and each point's exclusive contribution in O(n) once the points are sorted
//! (O(n^2) for all of them). The 4-D sweep ([`super::hv4d`]) reuses the contribution routine.
//!
//! The 2-D staircase lives in slots indexed by each point's rank in (x, y) order, so the
//! sweep needs no balanced tree: see [`super::staircase`].

use super::staircase::{BitSet, Staircase};

/// The first three coordinates of `n` points (read with stride `d`) re-indexed by their
/// rank in (x, y) order, with their order in z, and the 2-D staircase over those ranks.
/// [`Sorted3::fill`] reuses the buffers, for callers solving many small problems.
#[derive(Debug, Clone, Default)]
pub(super) struct Sorted3 {
    /// x of the point of rank k.
    pub(super) x: Vec<f64>,
    /// y of the point of rank k.
    pub(super) y: Vec<f64>,
    /// z of the point of rank k.
    pub(super) z: Vec<f64>,
    /// Original index of the point of rank k.
    pub(super) original: Vec<usize>,
    /// Ranks in increasing z.
    pub(super) by_z: Vec<usize>,
    /// Position of rank k in `by_z`.
    pub(super) z_pos: Vec<usize>,
    /// Reference point (first three coordinates).
    pub(super) r: [f64; 3],
    /// After [`Sorted3::exclusive`] of point k: the members above k in z that k dominates
    /// in x and y (so in 3-D); the 4-D sweep drops them once k is in.
    pub(super) dominated: Vec<usize>,
    stair: Staircase,
    /// Sort buffers: (x key, y key, index) and (z key, rank).
    keys: Vec<(u64, u64, u32)>,
    zkeys: Vec<(u64, u32)>,
}

/// A `u64` whose order is that of the finite `f64` `v` (`total_cmp` order).
#[inline]
pub(super) fn key(v: f64) -> u64 {
    let b = v.to_bits();
    if b >> 63 == 1 { !b } else { b | (1 << 63) }
}

impl Sorted3 {
    /// Sort the first three coordinates of the points `pts` (stride `d >= 3`).
    pub(super) fn new(pts: &[f64], d: usize, r: &[f64]) -> Self {
        let mut s = Self::default();
        s.fill(pts, d, r);
        s
    }

    /// [`Sorted3::new`] into the existing buffers.
    pub(super) fn fill(&mut self, pts: &[f64], d: usize, r: &[f64]) {
        let n = pts.len() / d;
        // Sort integer keys (the order of finite f64 is that of these u64) with the index.
        self.keys.clear();
        self.keys
            .extend((0..n).map(|i| (key(pts[d * i]), key(pts[d * i + 1]), i as u32)));
        self.keys.sort_unstable();
        self.original.clear();
        self.x.clear();
        self.y.clear();
        self.z.clear();
        for &(_, _, i) in &self.keys {
            let i = i as usize;
            self.original.push(i);
            self.x.push(pts[d * i]);
            self.y.push(pts[d * i + 1]);
            self.z.push(pts[d * i + 2]);
        }
        self.zkeys.clear();
        self.zkeys
            .extend(self.z.iter().enumerate().map(|(k, &v)| (key(v), k as u32)));
        self.zkeys.sort_unstable();
        self.by_z.clear();
        self.by_z
            .extend(self.zkeys.iter().map(|&(_, k)| k as usize));
        self.z_pos.clear();
        self.z_pos.resize(n, 0);
        for (p, &k) in self.by_z.iter().enumerate() {
            self.z_pos[k] = p;
        }
        self.stair.fill(&self.x, r[0], r[1]);
        self.r = [r[0], r[1], r[2]];
        self.dominated.clear();
    }

    /// Number of points.
    pub(super) fn len(&self) -> usize {
        self.x.len()
    }

    /// The hypervolume of all the points: sweep z upwards, adding each point to the 2-D
    /// staircase and the slab below the next point to the volume.
    pub(super) fn hypervolume(&mut self) -> f64 {
        let n = self.len();
        self.stair.reset(f64::NEG_INFINITY);
        let mut area = 0.0;
        let mut vol = 0.0;
        for p in 0..n {
            let k = self.by_z[p];
            area += self.stair.insert(k + 1, self.y[k]);
            let z_next = if p + 1 < n {
                self.z[self.by_z[p + 1]]
            } else {
                self.r[2]
            };
            vol += area * (z_next - self.z[k]);
        }
        vol
    }

    /// The volume of the box `[point k, r)` that no member dominates. `in_x` holds the
    /// members by rank, `in_z` by position in z order (the same set); `k` must not be one.
    ///
    /// Below the point's z the members form a staircase built by one scan in x order;
    /// above it they are inserted in z order until one dominates the point in x and y.
    pub(super) fn exclusive(&mut self, k: usize, in_x: &BitSet, in_z: &BitSet) -> f64 {
        let (px, py, pz) = (self.x[k], self.y[k], self.z[k]);
        let [rx, ry, rz] = self.r;
        self.stair.reset(px);
        self.dominated.clear();
        // Phase 1: members with z <= pz, in x order, clipped to the box. The ones with
        // x <= px all fall on the wall (slot 0).
        let mut covered = 0.0;
        let mut last_x = px;
        let mut last_y = f64::INFINITY;
        for (wi, &word) in in_x.words().iter().enumerate() {
            let mut w = word;
            while w != 0 {
                let j = (wi << 6) | w.trailing_zeros() as usize;
                w &= w - 1;
                if self.z[j] > pz {
                    if self.x[j] >= px && self.y[j] >= py {
                        self.dominated.push(j);
                    }
                    continue;
                }
                let yj = self.y[j].max(py);
                if yj >= last_y {
                    continue;
                }
                let xj = self.x[j];
                if xj <= px {
                    if yj == py {
                        return 0.0; // weakly dominated
                    }
                    // Another wall point replaces the previous one at the same x: no width.
                    self.stair.place(0, yj);
                    last_y = yj;
                    continue;
                }
                if last_y.is_finite() {
                    covered += (xj - last_x) * (ry - last_y);
                }
                self.stair.place(j + 1, yj);
                last_x = xj;
                last_y = yj;
            }
        }
        if last_y.is_finite() {
            covered += (rx - last_x) * (ry - last_y);
        }
        let mut uncovered = super::nonneg((rx - px) * (ry - py) - covered);
        // Phase 2: members above pz in z order.
        let mut vol = 0.0;
        let mut z_prev = pz;
        let start = self.z_pos[k] + 1;
        let words = in_z.words();
        let mut wi = start >> 6;
        if wi < words.len() {
            let mut w = words[wi] & (!0u64 << (start & 63));
            loop {
                while w != 0 {
                    let p = (wi << 6) | w.trailing_zeros() as usize;
                    w &= w - 1;
                    let j = self.by_z[p];
                    let zj = self.z[j];
                    if zj <= pz {
                        continue;
                    }
                    vol += (zj - z_prev) * uncovered;
                    z_prev = zj;
                    let xj = self.x[j];
                    let yj = self.y[j].max(py);
                    if xj <= px {
                        if yj == py {
                            return vol; // the rest of the box is dominated
                        }
                        uncovered -= self.stair.insert(0, yj);
                    } else {
                        uncovered -= self.stair.insert(j + 1, yj);
                    }
                    uncovered = super::nonneg(uncovered);
                }
                wi += 1;
                if wi >= words.len() {
                    break;
                }
                w = words[wi];
            }
        }
        vol + (rz - z_prev) * uncovered
    }
}

/// Hypervolume of `n` points (stride 3) strictly dominating `r`.
pub(super) fn hypervolume(pts: &[f64], r: &[f64]) -> f64 {
    Sorted3::new(pts, 3, r).hypervolume()
}

/// Exclusive contribution of each point (stride 3, all strictly dominating `r`); 0 for
/// weakly dominated points and for every copy of a duplicated point.
pub(super) fn contributions(pts: &[f64], r: &[f64]) -> Vec<f64> {
    let mut s = Sorted3::new(pts, 3, r);
    let n = s.len();
    let mut in_x = BitSet::new(n);
    let mut in_z = BitSet::new(n);
    for k in 0..n {
        in_x.insert(k);
        in_z.insert(k);
    }
    let mut out = vec![0.0; n];
    for k in 0..n {
        in_x.remove(k);
        in_z.remove(s.z_pos[k]);
        out[s.original[k]] = s.exclusive(k, &in_x, &in_z);
        in_x.insert(k);
        in_z.insert(s.z_pos[k]);
    }
    out
}
