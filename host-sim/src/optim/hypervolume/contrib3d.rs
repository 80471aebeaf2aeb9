//! Every point's exclusive contribution in three objectives in O(n log n): one sweep in z
//! (after Emmerich & Fonseca 2011, "Computing hypervolume contributions in low dimensions").
//!
//! At each height of the sweep, the points seen so far that no other seen point dominates in
//! (x, y) form the 2-D front. Only a front point has exclusive area at that height, and that
//! area lies in the vertical band `[q.x, next front x)`. Inside the band it is the region
//! `[q.y, H(x))`, where `H` is a non-increasing step function: the left neighbour's y, lowered
//! by the points that only `q` dominates. The bands tile the x-axis, so all the exclusive
//! areas are kept as one list of strips ordered by x. A strip starts at some point's x (its
//! slot is that point's rank in (x, y) order), ends where the next strip starts, and has a
//! height `H`, an owner and the z at which it was opened. A strip that changes is closed,
//! crediting `width * (H - owner.y) * (z - opened)` to its owner, and reopened. A new point
//! `p` at height `p.z`:
//! * dominated in (x, y) by two front points: changes nothing (it lies where two points
//!   already overlap), contributes 0;
//! * dominated by one front point `q` only: lowers `q`'s strips right of `p.x` to `p.y`
//!   (merging them into one), contributes 0;
//! * otherwise it joins the front: the front points it dominates leave (their strips close
//!   for good), its left neighbour's band ends at `p.x`, its right neighbour's strips are
//!   lowered to `p.y`, and `p`'s own strips step down at each point it removed.
//!
//! Each point opens O(1) strips plus one per point it removes, so the strip operations are
//! O(n) in all, each a few hierarchical bit-set queries ([`BitSet`]).

use super::hv3d::key;
use super::staircase::BitSet;

/// Exclusive contribution of each point (stride 3, all strictly dominating `r`), in input
/// order; 0 for weakly dominated points and for every copy of a duplicated point.
pub(super) fn contributions(pts: &[f64], r: &[f64]) -> Vec<f64> {
    let n = pts.len() / 3;
    let (rx, ry, rz) = (r[0], r[1], r[2]);
    // Ranks in (x, y) order.
    let mut keys: Vec<(u64, u64, u32)> = (0..n)
        .map(|i| (key(pts[3 * i]), key(pts[3 * i + 1]), i as u32))
        .collect();
    keys.sort_unstable();
    let orig: Vec<usize> = keys.iter().map(|&(_, _, i)| i as usize).collect();
    let x: Vec<f64> = orig.iter().map(|&i| pts[3 * i]).collect();
    let y: Vec<f64> = orig.iter().map(|&i| pts[3 * i + 1]).collect();
    let z: Vec<f64> = orig.iter().map(|&i| pts[3 * i + 2]).collect();
    let mut by_z: Vec<(u64, u32)> = z
        .iter()
        .enumerate()
        .map(|(k, &v)| (key(v), k as u32))
        .collect();
    by_z.sort_unstable();
    let mut sweep = Sweep {
        x: &x,
        y: &y,
        rx,
        ry,
        front: BitSet::new(n),
        strips: BitSet::new(n),
        h: vec![0.0; n],
        z0: vec![0.0; n],
        owner: vec![0; n],
        acc: vec![0.0; n],
        closed: Vec::new(),
    };
    for &(_, k) in &by_z {
        let k = k as usize;
        sweep.add(k, z[k]);
    }
    sweep.finish(rz);
    let mut out = vec![0.0; n];
    for (k, &i) in orig.iter().enumerate() {
        out[i] = super::num::nonneg(sweep.acc[k]);
    }
    out
}

/// The sweep's state; points and slots are ranks in (x, y) order.
struct Sweep<'a> {
    x: &'a [f64],
    y: &'a [f64],
    rx: f64,
    ry: f64,
    /// The 2-D front at the current height.
    front: BitSet,
    /// The strips, by the slot of their left edge.
    strips: BitSet,
    /// Per strip: upper edge H, the z it was opened at, and its owner.
    h: Vec<f64>,
    z0: Vec<f64>,
    owner: Vec<usize>,
    /// Exclusive contribution so far, per point.
    acc: Vec<f64>,
    /// Scratch: strips closed for good in one step.
    closed: Vec<usize>,
}

impl Sweep<'_> {
    /// Credit strip `s`'s volume from its opening to height `z` to its owner (the strip set
    /// must still be the one the strip was valid in: its right edge is the next strip).
    fn close(&mut self, s: usize, z: f64) {
        let right = self.strips.next_after(s).map_or(self.rx, |t| self.x[t]);
        let o = self.owner[s];
        self.acc[o] += (right - self.x[s]) * (self.h[s] - self.y[o]) * (z - self.z0[s]);
    }

    /// Open strip `s` at height `z`.
    fn open(&mut self, s: usize, h: f64, owner: usize, z: f64) {
        self.strips.insert(s);
        self.h[s] = h;
        self.owner[s] = owner;
        self.z0[s] = z;
    }

    /// Close the strips after `from` owned by `owner` with `H > limit`, in x order, and list
    /// them in `self.closed` (they are not removed yet).
    fn close_run(&mut self, from: usize, owner: usize, limit: f64, z: f64) {
        let mut t = self.strips.next_after(from);
        while let Some(s) = t {
            if self.owner[s] != owner || self.h[s] <= limit {
                break;
            }
            self.close(s, z);
            self.closed.push(s);
            t = self.strips.next_after(s);
        }
    }

    /// Sweep past point `k` at height `pz`.
    fn add(&mut self, k: usize, pz: f64) {
        let py = self.y[k];
        let q = self.front.prev_before(k);
        self.closed.clear();
        if let Some(q) = q.filter(|&q| self.y[q] <= py) {
            // p is dominated in (x, y) by q (so in 3-D: it contributes 0).
            if self.front.prev_before(q).is_some_and(|l| self.y[l] <= py) {
                return; // and by q's left neighbour: it only covers shared area
            }
            // Only q: q's strips right of p.x lose everything above p.y.
            let Some(s0) = self.strips.prev_before(k) else {
                return; // unreachable: q's band contains p.x
            };
            if self.h[s0] <= py {
                return; // H is non-increasing: nothing of q's lies above p
            }
            self.close(s0, pz);
            self.close_run(k, q, py, pz);
            for i in 0..self.closed.len() {
                self.strips.remove(self.closed[i]);
            }
            self.z0[s0] = pz;
            self.open(k, py, q, pz);
            return;
        }
        // p joins the front. a: its left neighbour (x < p.x, y > p.y), if any.
        let a = q;
        // The front points p dominates, and its right neighbour b.
        let mut removed_first = None;
        let mut b = self.front.next_after(k);
        while let Some(r) = b {
            if self.y[r] < py {
                break;
            }
            removed_first.get_or_insert(r);
            b = self.front.next_after(r);
        }
        let sa = a.and_then(|_| self.strips.prev_before(k));
        if let Some(sa) = sa {
            self.close(sa, pz);
        }
        // Every strip between p.x and b's band closes for good (a's beyond p.x and those of
        // the points p removes).
        let mut t = self.strips.next_after(k);
        while let Some(s) = t {
            if Some(s) == b {
                break;
            }
            self.close(s, pz);
            self.closed.push(s);
            t = self.strips.next_after(s);
        }
        let gone = self.closed.len();
        // b's strips above p.y merge into one at height p.y.
        let lower_b = b.filter(|&b| self.h[b] > py);
        if let Some(b) = lower_b {
            self.close(b, pz);
            self.close_run(b, b, py, pz);
        }
        for i in 0..self.closed.len() {
            self.strips.remove(self.closed[i]);
        }
        self.closed.truncate(gone);
        if let Some(b) = lower_b {
            self.h[b] = py;
            self.z0[b] = pz;
        }
        if let Some(sa) = sa {
            self.z0[sa] = pz;
        }
        // p's strips: from p.x under its left neighbour, then a step down at each removed
        // front point.
        let top = a.map_or(self.ry, |a| self.y[a]);
        self.open(k, top, k, pz);
        let mut r = removed_first;
        while let Some(s) = r {
            if Some(s) == b {
                break;
            }
            self.front.remove(s);
            let hs = self.y[s];
            self.open(s, hs, k, pz);
            r = self.front.next_after(s);
        }
        self.front.insert(k);
    }

    /// Close every strip at the reference height.
    fn finish(&mut self, rz: f64) {
        let mut t = self.strips.first();
        while let Some(s) = t {
            self.close(s, rz);
            t = self.strips.next_after(s);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contributions_3d_match_the_loss_on_removal_on_random_and_tied_sets() {
        let mut s: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        let r = [1.0, 1.0, 1.0];
        for case in 0..400 {
            let n = 1 + (next() % 60) as usize;
            let grid = case % 2 == 0; // ties, duplicates, dominated points
            let pts: Vec<f64> = (0..3 * n)
                .map(|_| {
                    let u = (next() >> 11) as f64 / (1u64 << 53) as f64;
                    if grid { (u * 5.0).floor() / 5.0 } else { u }
                })
                .collect();
            let all = crate::optim::hypervolume::hv3d::hypervolume(&pts, &r);
            let got = contributions(&pts, &r);
            for (i, &c) in got.iter().enumerate() {
                let mut rest = pts.clone();
                rest.drain(3 * i..3 * i + 3);
                let want = all - crate::optim::hypervolume::hv3d::hypervolume(&rest, &r);
                assert!(
                    (c - want).abs() <= 1e-12 * all,
                    "case {case}, n = {n}, point {i}: {c} vs {want}"
                );
            }
        }
    }
}
