//! Three objectives: the dimension sweep of Beume et al. / Fonseca et al. (HV3D) in
//! O(n log n). The exclusive contributions are [`super::contrib3d`]'s sweep.
//!
//! The 2-D staircase lives in slots indexed by each point's rank in (x, y) order, so the
//! sweep needs no balanced tree: see [`super::staircase`].

use super::staircase::Staircase;

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
    /// Ranks in increasing z.
    pub(super) by_z: Vec<usize>,
    /// Reference point (first three coordinates).
    pub(super) r: [f64; 3],
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
        self.x.clear();
        self.y.clear();
        self.z.clear();
        for &(_, _, i) in &self.keys {
            let i = i as usize;
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
        self.stair.fill(&self.x, r[0], r[1]);
        self.r = [r[0], r[1], r[2]];
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
}

/// Hypervolume of `n` points (stride 3) strictly dominating `r`.
pub(super) fn hypervolume(pts: &[f64], r: &[f64]) -> f64 {
    Sorted3::new(pts, 3, r).hypervolume()
}
