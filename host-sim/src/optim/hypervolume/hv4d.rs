//! Four objectives: sweep the fourth coordinate upwards, keeping the 3-D hypervolume of the
//! points seen so far up to date by adding each new point's exclusive 3-D contribution
//! ([`Sorted3::exclusive`], O(n) after one sort). O(n^2) overall, like HV4D (Guerreiro,
//! Fonseca & Emmerich 2012). Points dominated in the first three coordinates by a later
//! (higher w) point are dropped from the sweep's set when that point comes in, which keeps
//! the set at the size of the 3-D non-dominated prefix (about a third of n on random fronts).

use super::hv3d::{Sorted3, key};
use super::staircase::BitSet;

/// Hypervolume of `n` points (stride 4) strictly dominating `r`.
pub(super) fn hypervolume(pts: &[f64], r: &[f64]) -> f64 {
    Hv4::default().hypervolume(pts, r)
}

/// The 4-D sweep's buffers, reusable across calls (the >= 5-D recursion makes many).
#[derive(Debug, Clone, Default)]
pub(super) struct Hv4 {
    s: Sorted3,
    w: Vec<f64>,
    by_w: Vec<usize>,
    in_x: BitSet,
    in_z: BitSet,
    wkeys: Vec<(u64, u32)>,
}

impl Hv4 {
    /// Hypervolume of `n` points (stride 4) strictly dominating `r`.
    pub(super) fn hypervolume(&mut self, pts: &[f64], r: &[f64]) -> f64 {
        let n = pts.len() / 4;
        if n == 0 {
            return 0.0;
        }
        let Self {
            s,
            w,
            by_w,
            in_x,
            in_z,
            wkeys,
        } = self;
        s.fill(pts, 4, r);
        // Ranks in increasing w.
        w.clear();
        w.extend(s.original.iter().map(|&i| pts[4 * i + 3]));
        wkeys.clear();
        wkeys.extend(w.iter().enumerate().map(|(k, &v)| (key(v), k as u32)));
        wkeys.sort_unstable();
        by_w.clear();
        by_w.extend(wkeys.iter().map(|&(_, k)| k as usize));
        in_x.reset(n);
        in_z.reset(n);
        let mut v3 = 0.0;
        let mut vol = 0.0;
        for (p, &k) in by_w.iter().enumerate() {
            let c = s.exclusive(k, in_x, in_z);
            if c > 0.0 {
                v3 += c;
                in_x.insert(k);
                in_z.insert(s.z_pos[k]);
                // Members k dominates in 3-D add nothing to any later union: drop them.
                for &j in &s.dominated {
                    in_x.remove(j);
                    in_z.remove(s.z_pos[j]);
                }
            }
            let w_next = by_w.get(p + 1).map_or(r[3], |&j| w[j]);
            vol += v3 * (w_next - w[k]);
        }
        vol
    }
}
