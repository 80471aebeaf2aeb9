//! Four objectives: sweep the fourth coordinate (w) upwards, keeping the 3-D hypervolume of
//! the points seen so far up to date by adding each new point's exclusive 3-D contribution.
//! O(n^2) overall, like HV4D and HV4D+ (Guerreiro, Fonseca & Emmerich 2012; Guerreiro &
//! Fonseca 2018), with the work per new point kept local to its neighbourhood.
//!
//! The 3-D set ("members") is kept dense, as a structure of arrays sorted by x. The new
//! point `p`'s exclusive volume is the part of its box `[p, r)` no member covers:
//! * members with `x <= p.x` (a prefix of the array) act on the box as a "wall" at `p.x`:
//!   two branch-free passes give the wall's height at `p.z` (the lowest `y` of those with
//!   `z <= p.z`), the first `z` above `p.z` at which one covers `p` in x and y (the box is
//!   covered from there: the sweep stops), whether one dominates `p` (no volume at all),
//!   and the ones that lower the wall in between (a bit mask per 64 members);
//! * members with `x > p.x` are scanned in x order only until the first one with
//!   `z <= p.z` and `y <= p.y`: it and everything beyond it in x is covered at `p.z` already
//!   (and `p` dominates none of those: that member would dominate it). Those with
//!   `z <= p.z` form the staircase at `p.z`; those above `p.z` that are not yet covered are
//!   kept. The scan is branch-free but for its exit: each outcome is a conditional write;
//! * the kept members are sorted by z and inserted into the staircase, slab by slab. The
//!   staircase in a box holds a handful of steps: a short array ([`Stair`]).
//!
//! On random fronts this visits a few dozen members per point in the scan (instead of
//! every member), plus the branch-free passes over the prefix. A member that `p` dominates
//! in (x, y, z) adds nothing to any later union and leaves the set when `p` comes in.

use super::hv3d::key;
use super::stair::{Stair, sort_short};

/// Hypervolume of `n` points (stride 4) strictly dominating `r`.
pub(super) fn hypervolume(pts: &[f64], r: &[f64]) -> f64 {
    Hv4::default().hypervolume(pts, r)
}

/// The 4-D sweep's buffers, reusable across calls (the >= 5-D recursion makes many). All
/// are sized once per call (`n` entries or a few more), so the per-point work indexes them
/// without growing any vector.
#[derive(Debug, Clone, Default)]
pub(super) struct Hv4 {
    /// Sort buffer: (w key, point index).
    wkeys: Vec<(u64, u32)>,
    /// The staircase of the box's (x, y) face at the current z.
    stair: Stair,
    /// The 3-D set, sorted by x.
    mem: Members,
    /// Per point: (z, position in `mem`) of the members above `p.z` to insert.
    cand: Vec<(f64, u32)>,
    /// Per point: positions of the members `p` dominates.
    gone: Vec<u32>,
}

/// The members of the 3-D set, dense, sorted by x: the first `len` entries of each array.
#[derive(Debug, Clone, Default)]
struct Members {
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    len: usize,
}

impl Members {
    /// Empty, with room for `n` members.
    fn reset(&mut self, n: usize) {
        for v in [&mut self.x, &mut self.y, &mut self.z] {
            v.clear();
            v.resize(n, 0.0);
        }
        self.len = 0;
    }

    /// Insert at position `at` (room for it is known).
    fn insert(&mut self, at: usize, x: f64, y: f64, z: f64) {
        let len = self.len;
        for (v, c) in [(&mut self.x, x), (&mut self.y, y), (&mut self.z, z)] {
            v.copy_within(at..len, at + 1);
            v[at] = c;
        }
        self.len = len + 1;
    }

    /// Remove the members at `positions` (increasing).
    fn remove(&mut self, positions: &[u32]) {
        let Some(&first) = positions.first() else {
            return;
        };
        let mut w = first as usize;
        let mut next = positions.iter().copied().peekable();
        for j in first as usize..self.len {
            if next.peek() == Some(&(j as u32)) {
                next.next();
                continue;
            }
            self.x[w] = self.x[j];
            self.y[w] = self.y[j];
            self.z[w] = self.z[j];
            w += 1;
        }
        self.len = w;
    }
}

impl Hv4 {
    /// Hypervolume of `n` points (stride 4) strictly dominating `r`.
    pub(super) fn hypervolume(&mut self, pts: &[f64], r: &[f64]) -> f64 {
        let n = pts.len() / 4;
        if n == 0 {
            return 0.0;
        }
        self.wkeys.clear();
        self.wkeys
            .extend((0..n).map(|i| (key(pts[4 * i + 3]), i as u32)));
        self.wkeys.sort_unstable();
        self.mem.reset(n);
        self.stair.resize(n + 2);
        self.cand.resize(n + 1, (0.0, 0));
        self.gone.resize(n + 1, 0);
        let r3 = [r[0], r[1], r[2]];
        let (t0, w0, mut v3) = self.first_slab(pts, r3);
        let mut vol = v3
            * (self
                .wkeys
                .get(t0)
                .map_or(r[3], |&(_, j)| pts[4 * j as usize + 3])
                - w0);
        for t in t0..n {
            let i = self.wkeys[t].1 as usize;
            let q = &pts[4 * i..4 * i + 4];
            let p = [q[0], q[1], q[2]];
            let (c, e, ng) = self.exclusive(p, r3);
            if c > 0.0 {
                v3 += c;
                self.mem.remove(&self.gone[..ng]);
                // The members p dominates all lie beyond its place e (their x is larger).
                self.mem.insert(e, p[0], p[1], p[2]);
            }
            let w_next = self
                .wkeys
                .get(t + 1)
                .map_or(r[3], |&(_, j)| pts[4 * j as usize + 3]);
            vol += v3 * (w_next - q[3]);
        }
        vol
    }

    /// The points sharing the lowest w (the first `t0` of `wkeys`) all enter the 3-D set at
    /// once: their 3-D hypervolume by a z sweep over a short staircase, and the members are
    /// those points sorted by x (a member another one dominates only costs time later).
    /// Returns `t0`, the lowest w and that hypervolume, or `(0, w, 0.0)` when a single point
    /// has the lowest w (it is left to the sweep). The limit sets of the >= 5-D recursion hold a dozen or
    /// more such points: all those whose w is clipped to the box corner.
    fn first_slab(&mut self, pts: &[f64], r: [f64; 3]) -> (usize, f64, f64) {
        let w0 = pts[4 * self.wkeys[0].1 as usize + 3];
        let t0 = self
            .wkeys
            .iter()
            .position(|&(_, j)| pts[4 * j as usize + 3] != w0)
            .unwrap_or(self.wkeys.len());
        if t0 < 2 {
            return (0, w0, 0.0);
        }
        let first = &mut self.cand[..t0];
        for (f, &(_, j)) in first.iter_mut().zip(&self.wkeys) {
            *f = (pts[4 * j as usize + 2], j);
        }
        sort_short(first);
        let stair = &mut self.stair;
        stair.reset(r[0], r[1]);
        let mut area = 0.0;
        let mut v3 = 0.0;
        for k in 0..t0 {
            let (z, j) = first[k];
            let q = &pts[4 * j as usize..4 * j as usize + 2];
            area += stair.insert(q[0], q[1]);
            let z_next = first.get(k + 1).map_or(r[2], |f| f.0);
            v3 += area * (z_next - z);
        }
        for f in first.iter_mut() {
            f.0 = pts[4 * f.1 as usize];
        }
        sort_short(first);
        let m = &mut self.mem;
        for (k, &(x, j)) in first.iter().enumerate() {
            m.x[k] = x;
            m.y[k] = pts[4 * j as usize + 1];
            m.z[k] = pts[4 * j as usize + 2];
        }
        m.len = t0;
        (t0, w0, v3)
    }

    /// The volume of the box `[p, r)` (p not a member) that no member covers; `p`'s place in
    /// the members (after those with `x <= p.x`); and the number of positions left at the
    /// start of `self.gone`: the members `p` dominates (those it found; a missed one only
    /// costs time), valid when the volume is positive.
    fn exclusive(&mut self, p: [f64; 3], r: [f64; 3]) -> (f64, usize, usize) {
        let [px, py, pz] = p;
        let [rx, ry, rz] = r;
        let m = &self.mem;
        let len = m.len;
        let (xs, ys, zs) = (&m.x[..len], &m.y[..len], &m.z[..len]);
        let cand = &mut self.cand[..len + 1];
        let gone = &mut self.gone[..len + 1];
        // Members with x <= px.
        // (Few members: a count, which has no chain of dependent loads.)
        let e = if len <= 32 {
            xs.iter().map(|&q| usize::from(q <= px)).sum()
        } else {
            xs.partition_point(|&q| q <= px)
        };
        // Pass 1: the wall height at pz and the z from which the box is covered, four
        // independent lanes (no loop-carried dependency, vectorisable).
        let (yp, zp) = (&ys[..e], &zs[..e]);
        let mut wy4 = [ry; 4];
        let mut zc4 = [rz; 4];
        let (yc, zc) = (yp.chunks_exact(4), zp.chunks_exact(4));
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
            return (0.0, e, 0); // a member weakly dominates p
        }
        // Pass 2: the wall members above pz that lower the wall before zcap, as bit masks
        // of 64 members (few bits are set).
        let mut nc = 0;
        for (base, (yc, zc)) in yp.chunks(64).zip(zp.chunks(64)).enumerate() {
            let mut bits = 0u64;
            for (l, (&y, &z)) in yc.iter().zip(zc).enumerate() {
                bits |= u64::from((z > pz) & (z < zcap) & (y < wy)) << l;
            }
            while bits != 0 {
                let j = 64 * base + bits.trailing_zeros() as usize;
                bits &= bits - 1;
                cand[nc] = (zp[j], j as u32);
                nc += 1;
            }
        }
        // The members with x > px in x order, up to the first covering the rest at pz.
        let stair = &mut self.stair;
        stair.reset(rx, ry);
        if wy < ry {
            stair.push(px, wy);
        }
        let mut covered = 0.0;
        let mut last_x = px;
        let mut last_y = wy;
        // Branch-free but for the exit: a new step, a candidate and a dominated member are
        // each a conditional write (the slot past the end takes the others).
        let mut ng = 0;
        let mut sl = stair.len;
        for j in e..len {
            let (x, y, z) = (xs[j], ys[j], zs[j]);
            let below = z <= pz;
            let step = below & (y < last_y);
            let yc = y.max(py);
            // A step at the x of the previous one (a tie) replaces it.
            let k = sl - usize::from(step & (x == last_x));
            stair.x[k] = x;
            stair.y[k] = yc;
            sl = k + usize::from(step);
            let area = (x - last_x) * (ry - last_y);
            covered += if step { area } else { 0.0 };
            cand[nc] = (z, j as u32);
            nc += usize::from(!below & (z < zcap) & (y < last_y));
            gone[ng] = j as u32;
            ng += usize::from(!below & (y >= py));
            last_x = if step { x } else { last_x };
            last_y = if step { yc } else { last_y };
            if step & (y <= py) {
                break;
            }
        }
        stair.len = sl;
        // Beyond the covering member c nothing matters: a member q there that p dominates
        // would have x >= c.x, y >= p.y >= c.y and z > p.z >= c.z, so c would dominate q,
        // and members do not dominate one another (up to ties, which only cost time).
        covered += (rx - last_x) * (ry - last_y);
        let mut uncovered = super::num::nonneg((rx - px) * (ry - py) - covered);
        // Above pz: the candidates in z order, up to zcap.
        let cand = &mut cand[..nc];
        sort_short(cand);
        let mut vol = 0.0;
        let mut z_prev = pz;
        for &(z, j) in cand.iter() {
            let j = j as usize;
            vol += (z - z_prev) * uncovered;
            z_prev = z;
            let added = stair.insert(xs[j].max(px), ys[j].max(py));
            uncovered = super::num::nonneg(uncovered - added);
        }
        (vol + (zcap - z_prev) * uncovered, e, ng)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Uniform numbers in [0, 1) from a xorshift stream seeded with `seed`.
    fn uniform(mut s: u64) -> impl FnMut() -> f64 {
        move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        }
    }

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

    /// Fronts large enough that the 3-D set outgrows the short paths (more than 32
    /// members: the binary search for a point's place; more than 64 in the prefix: several
    /// candidate bit masks), on the sphere and, rounded to a grid, with ties.
    #[test]
    fn hv4d_matches_slicing_on_large_fronts() {
        let mut next = uniform(0x9e37_79b9_7f4a_7c15);
        let r = [1.1; 4];
        let mut hv = Hv4::default();
        for (case, &n) in [300usize, 600, 600].iter().enumerate() {
            let mut pts = Vec::with_capacity(4 * n);
            for _ in 0..n {
                let v: Vec<f64> = (0..4).map(|_| next() + 1e-3).collect();
                let norm = v.iter().map(|a| a * a).sum::<f64>().sqrt();
                for a in v {
                    let u = a / norm;
                    pts.push(if case == 2 {
                        (u * 40.0).round() / 40.0
                    } else {
                        u
                    });
                }
            }
            let want = sliced(&pts, &r);
            let got = hv.hypervolume(&pts, &r);
            assert!(
                (got - want).abs() <= 1e-12 * want,
                "case {case}, n = {n}: {got} vs {want}"
            );
        }
    }

    /// Sets whose lowest w is shared by many points (as in the limit sets of the >= 5-D
    /// recursion, where every point not exceeding the box corner in w sits at the corner's
    /// w): the first slab enters at once. With duplicates, dominated points and ties in x,
    /// y and z (a coarse grid).
    #[test]
    fn hv4d_matches_slicing_when_many_points_share_the_lowest_w() {
        let mut next = uniform(0x51a7_e11d_c0ff_ee01);
        let r = [1.0; 4];
        let mut hv = Hv4::default();
        for case in 0..200 {
            let n = 2 + case % 70;
            let shared = 0.05 + 0.5 * next();
            let grid = case % 3 == 0;
            let mut pts = Vec::with_capacity(4 * n + 4);
            for k in 0..n {
                for _ in 0..3 {
                    let u = next();
                    pts.push(if grid { (u * 5.0).floor() / 5.0 } else { u });
                }
                // Two thirds of the points on the shared lowest w, the rest above it.
                pts.push(if k % 3 < 2 {
                    shared
                } else {
                    shared + (1.0 - shared) * next()
                });
            }
            // A duplicate of the first point (on the shared slab).
            let first: Vec<f64> = pts[..4].to_vec();
            pts.extend_from_slice(&first);
            let want = sliced(&pts, &r);
            let got = hv.hypervolume(&pts, &r);
            assert!(
                (got - want).abs() <= 1e-12 * want.abs().max(1e-300),
                "case {case}, n = {n}: {got} vs {want}"
            );
        }
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
