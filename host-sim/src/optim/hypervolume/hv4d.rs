//! Four objectives: sweep the fourth coordinate (w) upwards, keeping the 3-D hypervolume of
//! the points seen so far up to date by adding each new point's exclusive 3-D contribution.
//! O(n^2) overall, like HV4D and HV4D+ (Guerreiro, Fonseca & Emmerich 2012; Guerreiro &
//! Fonseca 2018), with the work per new point kept local to its neighbourhood.
//!
//! The 3-D set ("members") is kept dense, as a structure of arrays sorted by x rank. The new
//! point `p`'s exclusive volume is the part of its box `[p, r)` no member covers:
//! * members with `x <= p.x` (a prefix of the array) act on the box as a "wall" at `p.x`:
//!   two branch-free passes give the wall's height at `p.z` (the lowest `y` of those with
//!   `z <= p.z`), the first `z` above `p.z` at which one covers `p` in x and y (the box is
//!   covered from there: the sweep stops), whether one dominates `p` (no volume at all),
//!   and the ones that lower the wall in between;
//! * members with `x > p.x` are scanned in x order only until the first one with
//!   `z <= p.z` and `y <= p.y`: it and everything beyond it in x is covered at `p.z` already.
//!   Those with `z <= p.z` form the staircase at `p.z`; those above `p.z` that are not yet
//!   covered are kept;
//! * the kept members are sorted by z and inserted into the staircase, slab by slab.
//!
//! On random fronts this visits a few dozen members per point in branchy code (instead of
//! every member), plus one branch-free pass over the members. A member that `p` dominates in
//! (x, y, z) adds nothing to any later union and leaves the set when `p` comes in.

use super::hv3d::key;
use super::staircase::Staircase;

/// Hypervolume of `n` points (stride 4) strictly dominating `r`.
pub(super) fn hypervolume(pts: &[f64], r: &[f64]) -> f64 {
    Hv4::default().hypervolume(pts, r)
}

/// The 4-D sweep's buffers, reusable across calls (the >= 5-D recursion makes many).
#[derive(Debug, Clone, Default)]
pub(super) struct Hv4 {
    /// Sort buffer: (x key, y key, point index).
    keys: Vec<(u64, u64, u32)>,
    /// Sort buffer: (w key, x rank).
    wkeys: Vec<(u64, u32)>,
    /// The points by x rank: x, y, z, w.
    px: Vec<f64>,
    py: Vec<f64>,
    pz: Vec<f64>,
    pw: Vec<f64>,
    /// Staircase over the x ranks (slot `rank + 1`; slot 0 is the wall).
    stair: Staircase,
    /// The 3-D set, sorted by rank.
    mem: Members,
    /// Per call: the members above `p.z` to insert (their positions in `mem`).
    cand: Vec<u32>,
    /// Per call: (z key, position) of the candidates, for sorting.
    cand_z: Vec<(u64, u32)>,
    /// Per call: positions of the members `p` dominates.
    gone: Vec<u32>,
}

/// The members of the 3-D set, dense, sorted by x rank.
#[derive(Debug, Clone, Default)]
struct Members {
    rank: Vec<u32>,
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
}

impl Members {
    fn clear(&mut self) {
        self.rank.clear();
        self.x.clear();
        self.y.clear();
        self.z.clear();
    }

    fn len(&self) -> usize {
        self.rank.len()
    }

    /// Insert at the position of `rank`.
    fn insert(&mut self, rank: u32, x: f64, y: f64, z: f64) {
        let at = self.rank.partition_point(|&q| q < rank);
        self.rank.insert(at, rank);
        self.x.insert(at, x);
        self.y.insert(at, y);
        self.z.insert(at, z);
    }

    /// Remove the members at `positions` (increasing).
    fn remove(&mut self, positions: &[u32]) {
        let Some(&first) = positions.first() else {
            return;
        };
        let mut w = first as usize;
        let mut next = positions.iter().copied().peekable();
        for j in first as usize..self.len() {
            if next.peek() == Some(&(j as u32)) {
                next.next();
                continue;
            }
            self.rank[w] = self.rank[j];
            self.x[w] = self.x[j];
            self.y[w] = self.y[j];
            self.z[w] = self.z[j];
            w += 1;
        }
        self.rank.truncate(w);
        self.x.truncate(w);
        self.y.truncate(w);
        self.z.truncate(w);
    }
}

impl Hv4 {
    /// Hypervolume of `n` points (stride 4) strictly dominating `r`.
    pub(super) fn hypervolume(&mut self, pts: &[f64], r: &[f64]) -> f64 {
        let n = pts.len() / 4;
        if n == 0 {
            return 0.0;
        }
        // Ranks in (x, y) order; the staircase's slots follow them.
        self.keys.clear();
        self.keys
            .extend((0..n).map(|i| (key(pts[4 * i]), key(pts[4 * i + 1]), i as u32)));
        self.keys.sort_unstable();
        self.px.clear();
        self.py.clear();
        self.pz.clear();
        self.pw.clear();
        for &(_, _, i) in &self.keys {
            let p = &pts[4 * i as usize..4 * i as usize + 4];
            self.px.push(p[0]);
            self.py.push(p[1]);
            self.pz.push(p[2]);
            self.pw.push(p[3]);
        }
        self.wkeys.clear();
        self.wkeys
            .extend(self.pw.iter().enumerate().map(|(k, &v)| (key(v), k as u32)));
        self.wkeys.sort_unstable();
        self.stair.fill(&self.px, r[0], r[1]);
        self.mem.clear();
        let r3 = [r[0], r[1], r[2]];
        let mut v3 = 0.0;
        let mut vol = 0.0;
        for t in 0..n {
            let k = self.wkeys[t].1;
            let ku = k as usize;
            let p = [self.px[ku], self.py[ku], self.pz[ku]];
            let c = self.exclusive(k, p, r3);
            if c > 0.0 {
                v3 += c;
                self.mem.remove(&self.gone);
                self.mem.insert(k, p[0], p[1], p[2]);
            }
            let w_next = self
                .wkeys
                .get(t + 1)
                .map_or(r[3], |&(_, j)| self.pw[j as usize]);
            vol += v3 * (w_next - self.pw[ku]);
        }
        vol
    }

    /// The volume of the box `[p, r)` (p of x rank `k`, not a member) that no member covers.
    /// Leaves in `self.gone` the positions of the members `p` dominates (those it found; a
    /// missed one only costs time), valid when the result is positive.
    fn exclusive(&mut self, k: u32, p: [f64; 3], r: [f64; 3]) -> f64 {
        let [px, py, pz] = p;
        let [rx, ry, rz] = r;
        let m = &self.mem;
        let len = m.len();
        self.gone.clear();
        self.cand.clear();
        // Members with x <= px: those of lower rank and the ties of higher rank.
        let mut e = m.rank.partition_point(|&q| q < k);
        while e < len && m.x[e] <= px {
            e += 1;
        }
        // Pass 1: the wall height at pz and the z from which the box is covered, four
        // independent lanes (no loop-carried dependency, vectorisable).
        let (ys, zs) = (&m.y[..e], &m.z[..e]);
        let mut wy4 = [ry; 4];
        let mut zc4 = [rz; 4];
        let (yc, zc) = (ys.chunks_exact(4), zs.chunks_exact(4));
        let (yr, zr) = (yc.remainder(), zc.remainder());
        for (y, z) in yc.zip(zc) {
            for l in 0..4 {
                wy4[l] = if z[l] <= pz && y[l] < wy4[l] {
                    y[l]
                } else {
                    wy4[l]
                };
                zc4[l] = if y[l] <= py && z[l] < zc4[l] {
                    z[l]
                } else {
                    zc4[l]
                };
            }
        }
        for (&y, &z) in yr.iter().zip(zr) {
            wy4[0] = if z <= pz && y < wy4[0] { y } else { wy4[0] };
            zc4[0] = if y <= py && z < zc4[0] { z } else { zc4[0] };
        }
        let wy = wy4.iter().fold(ry, |a, &b| if b < a { b } else { a });
        let zcap = zc4.iter().fold(rz, |a, &b| if b < a { b } else { a });
        if wy <= py {
            return 0.0; // a member weakly dominates p
        }
        // Pass 2: the wall members above pz that lower the wall before zcap.
        self.cand.resize(e, 0);
        let mut nc = 0;
        for (j, (&y, &z)) in ys.iter().zip(zs).enumerate() {
            self.cand[nc] = j as u32;
            nc += usize::from((z > pz) & (z < zcap) & (y < wy));
        }
        self.cand.truncate(nc);
        // The members with x > px in x order, up to the first covering the rest at pz.
        self.stair.reset(px);
        if wy < ry {
            self.stair.place(0, wy);
        }
        let mut covered = 0.0;
        let mut last_x = px;
        let mut last_y = wy;
        let mut j = e;
        while j < len {
            let (x, y, z) = (m.x[j], m.y[j], m.z[j]);
            if z <= pz {
                if y < last_y {
                    let yc = y.max(py);
                    covered += (x - last_x) * (ry - last_y);
                    self.stair.place(m.rank[j] as usize + 1, yc);
                    last_x = x;
                    last_y = yc;
                    if y <= py {
                        j += 1;
                        break;
                    }
                }
            } else {
                if z < zcap && y < last_y {
                    self.cand.push(j as u32);
                }
                if y >= py {
                    self.gone.push(j as u32);
                }
            }
            j += 1;
        }
        // Beyond it, only the members p dominates are of interest.
        let ng = self.gone.len();
        self.gone.resize(ng + (len - j), 0);
        let mut ng2 = ng;
        for (j, (&y, &z)) in m.y[j..]
            .iter()
            .zip(&m.z[j..])
            .enumerate()
            .map(|(i, v)| (i + j, v))
        {
            self.gone[ng2] = j as u32;
            ng2 += usize::from((z > pz) & (y >= py));
        }
        self.gone.truncate(ng2);
        covered += (rx - last_x) * (ry - last_y);
        let mut uncovered = super::num::nonneg((rx - px) * (ry - py) - covered);
        // Above pz: the candidates in z order, up to zcap.
        self.cand_z.clear();
        self.cand_z
            .extend(self.cand.iter().map(|&j| (key(m.z[j as usize]), j)));
        self.cand_z.sort_unstable();
        let mut vol = 0.0;
        let mut z_prev = pz;
        for &(_, j) in &self.cand_z {
            let j = j as usize;
            let (x, y, z) = (m.x[j], m.y[j], m.z[j]);
            vol += (z - z_prev) * uncovered;
            z_prev = z;
            let added = if x <= px {
                self.stair.insert(0, y)
            } else {
                self.stair.insert(m.rank[j] as usize + 1, y.max(py))
            };
            uncovered = super::num::nonneg(uncovered - added);
        }
        vol + (zcap - z_prev) * uncovered
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 4-D hypervolume by slicing w: the sum of the 3-D hypervolumes (HV3D sweep) of the
    /// points below each slab, an independent O(n^2 log n) path.
    fn sliced(pts: &[f64], r: &[f64]) -> f64 {
        let n = pts.len() / 4;
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| pts[4 * a + 3].total_cmp(&pts[4 * b + 3]));
        let mut below: Vec<f64> = Vec::new();
        let mut vol = 0.0;
        for (t, &i) in order.iter().enumerate() {
            below.extend_from_slice(&pts[4 * i..4 * i + 3]);
            let w_next = order.get(t + 1).map_or(r[3], |&j| pts[4 * j + 3]);
            vol +=
                crate::optim::hypervolume::hv3d::hypervolume(&below, r) * (w_next - pts[4 * i + 3]);
        }
        vol
    }

    #[test]
    fn hv4d_matches_slicing_on_random_and_tied_sets() {
        let mut s: u64 = 0x2545_f491_4f6c_dd1d;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        let r = [1.0, 1.0, 1.0, 1.0];
        let mut hv = Hv4::default();
        for case in 0..300 {
            let n = 2 + (next() % 120) as usize;
            let grid = case % 2 == 0; // coarse grid: ties, duplicates, dominated points
            let pts: Vec<f64> = (0..4 * n)
                .map(|_| {
                    let u = (next() >> 11) as f64 / (1u64 << 53) as f64;
                    if grid { (u * 6.0).floor() / 6.0 } else { u }
                })
                .collect();
            let want = sliced(&pts, &r);
            let got = hv.hypervolume(&pts, &r);
            assert!(
                (got - want).abs() <= 1e-12 * want.abs().max(1e-300),
                "case {case}, n = {n}: {got} vs {want}"
            );
        }
    }
}
