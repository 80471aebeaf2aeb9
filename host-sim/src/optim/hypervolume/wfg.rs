//! Five or more objectives: WFG (While, Bradstreet & Barone 2012) with the points sorted by
//! the last objective. A point's exclusive volume is taken against the points better in the
//! last objective; clipped to its box they all share its last coordinate, so that volume is a
//! slab of height `r_d - p_d` times a (d-1)-dimensional `vol(box) - HV(limit set)`. The
//! recursion drops one dimension per level and bottoms out in the O(n^2) 4-D sweep.
//!
//! The points are taken from the best last coordinate up, keeping the non-dominated ones seen
//! so far (in the first d-1 coordinates): only those can shape a limit set. Limit sets are
//! filtered to (nearly) their non-dominated points by [`limit_set`]; a point weakly dominated
//! by a seen one has no exclusive volume and is skipped.
//!
//! The module also holds the dimension dispatch [`hypervolume_of`] (the 1-D to 4-D kernels,
//! WFG above), which the recursion calls for its limit sets: with it here, no kernel imports
//! the facade that calls them.

use std::cmp::Ordering;

use super::num::nonneg;

/// Hypervolume of the points `pts` (row-major, stride `d = r.len()`), every one strictly
/// dominating `r`: the dimension dispatch of the facade and of the exclusive contributions,
/// called by the WFG recursion for its limit sets (one dimension down).
pub(super) fn hypervolume_of(pts: &[f64], d: usize, r: &[f64]) -> f64 {
    match (pts.len() / d, d) {
        (0, _) => 0.0,
        (1, _) => pts.iter().zip(r).map(|(p, r)| r - p).product(),
        (_, 1) => r[0] - pts.iter().copied().fold(f64::INFINITY, f64::min),
        (_, 2) => super::hv2d::hypervolume(pts, r),
        (_, 3) => super::hv3d::hypervolume(pts, r),
        (_, 4) => super::hv4d::hypervolume(pts, r),
        _ => hypervolume(pts, d, r),
    }
}

/// Hypervolume of `n` points (stride `d >= 5`) strictly dominating `r`.
fn hypervolume(pts: &[f64], d: usize, r: &[f64]) -> f64 {
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
    // Processed from the best last coordinate up, so the "later" points of point k are the
    // ones already seen; of those only the non-dominated ones in the first d-1 coordinates
    // (`seen`) can matter to a limit set.
    let mut seen: Vec<f64> = Vec::with_capacity(n * dm);
    let mut limited: Vec<f64> = Vec::with_capacity(n * dm);
    let mut scratch = LimitScratch::default();
    let mut hv4 = super::hv4d::Hv4::default();
    let mut rc = vec![0.0; dm];
    let mut total = 0.0;
    for &i in order.iter().rev() {
        let p = &pts[d * i..d * i + d];
        let pm = &p[..dm];
        rc.copy_from_slice(&r[..dm]);
        if !limit_set_any(pm, &seen, &mut scratch, &mut limited, &mut rc) {
            continue; // weakly dominated by a point already seen: no exclusive volume
        }
        let area: f64 = (0..dm).map(|c| rc[c] - p[c]).product();
        let covered = if dm == 4 && limited.len() > dm {
            hv4.hypervolume(&limited, &rc)
        } else {
            hypervolume_of(&limited, dm, &rc)
        };
        total += (r[dm] - p[dm]) * nonneg(area - covered);
        // p joins the seen set; the seen points it weakly dominates leave it.
        let mut w = 0;
        for (r, &gone) in scratch.dominated.iter().enumerate() {
            if !gone {
                if w != r {
                    seen.copy_within(r * dm..r * dm + dm, w * dm);
                }
                w += 1;
            }
        }
        seen.truncate(w * dm);
        seen.extend_from_slice(pm);
    }
    total
}

/// Scratch space of [`limit_set`], reused across calls.
#[derive(Default)]
pub(super) struct LimitScratch {
    /// Seen points exceeding `p` in two or more coordinates: (mask, index). The mask has bit
    /// c set where the point exceeds `p` in coordinate c (beyond 64 coordinates bits alias,
    /// which keeps the filter exact but weaker).
    multi: Vec<(u64, u32)>,
    /// Per seen point: whether `p` weakly dominates it.
    dominated: Vec<bool>,
    /// Seen points left by the single-coordinate filter, after their masks (up to
    /// [`GROUPED`] coordinates, taken by mask size) or their mask sizes (beyond).
    survivors: Vec<(u32, u32)>,
    /// Kept clipped points with two or more exceeding coordinates, row-major.
    kept: Vec<f64>,
    /// Their masks.
    kept_mask: Vec<u64>,
    /// One clipped point.
    q: Vec<f64>,
    /// For up to [`GROUPED`] coordinates: the kept clipped points by mask, row-major.
    groups: Vec<Vec<f64>>,
    /// The masks whose group is non-empty.
    used: Vec<u64>,
}

/// Up to this many coordinates the kept points are grouped by mask (2^GROUPED groups), so a
/// point is compared only with the groups of its mask's subsets.
const GROUPED: usize = 6;

/// [`limit_set`] for `p.len()` coordinates, monomorphised for the common small counts.
fn limit_set_any(
    p: &[f64],
    seen: &[f64],
    sc: &mut LimitScratch,
    out: &mut Vec<f64>,
    rc: &mut [f64],
) -> bool {
    match p.len() {
        4 => limit_set::<4>(p, seen, sc, out, rc),
        5 => limit_set::<5>(p, seen, sc, out, rc),
        6 => limit_set::<6>(p, seen, sc, out, rc),
        _ => limit_set::<0>(p, seen, sc, out, rc),
    }
}

/// The points of `{max(p, s) : s in seen}` that no other one weakly dominates, into `out`
/// (a few dominated ones may remain; the hypervolume does not care), with the reference
/// point `rc` (the caller's, on entry) lowered to the points that exceed `p` in a single
/// coordinate, which then need no volume computation: `p`'s exclusive volume is
/// `vol([p, rc)) - HV(out, rc)`, and every point of `out` strictly dominates `rc`. Returns
/// false, leaving `out` and `rc` partial, when some `s <= p` (then `p` has no exclusive
/// volume). `N` is the number of coordinates, or 0 for "read it from `p`".
///
/// A clipped point `q = max(p, s)` equals `p` except on its mask `M(s) = {c : s_c > p_c}`,
/// and `max(p, t) <= max(p, s)` iff `M(t)` is a subset of `M(s)` and `t <= s` on `M(t)`. So
/// the points with a single-coordinate mask reduce to one minimum per coordinate, which
/// filter all the others at once; the rest are taken by increasing mask size and compared
/// only with kept points whose mask is a subset of their own (grouped by mask up to
/// [`GROUPED`] coordinates, one AND per pair beyond).
fn limit_set<const N: usize>(
    p: &[f64],
    seen: &[f64],
    sc: &mut LimitScratch,
    out: &mut Vec<f64>,
    rc: &mut [f64],
) -> bool {
    let dm = if N == 0 { p.len() } else { N };
    let p = &p[..dm];
    let track = dm <= 64;
    out.clear();
    sc.dominated.clear();
    sc.multi.clear();
    // best[c]: the lowest single-coordinate point in coordinate c; slot 64 is a sink.
    let mut best = [f64::INFINITY; 65];
    if N > 0 && N < 64 {
        // Few coordinates: branch-free, every multi-coordinate point is filtered at the end.
        let count = seen.len() / dm;
        sc.dominated.resize(count, false);
        sc.multi.resize(count, (0, 0));
        let mut k = 0;
        for (i, s) in seen.chunks_exact(dm).enumerate() {
            let s = &s[..dm];
            let mut m = 0u64;
            let mut below = true;
            for c in 0..dm {
                m |= u64::from(s[c] > p[c]) << c;
                below &= p[c] <= s[c];
            }
            if m == 0 {
                return false;
            }
            sc.dominated[i] = below;
            let single = m & (m - 1) == 0;
            let v = s[m.trailing_zeros() as usize];
            let slot = if single {
                m.trailing_zeros() as usize
            } else {
                64
            };
            let b = best[slot];
            best[slot] = if v < b { v } else { b };
            sc.multi[k] = (m, i as u32);
            k += usize::from(!single);
        }
        sc.multi.truncate(k);
    } else {
        for (i, s) in seen.chunks_exact(dm).enumerate() {
            let s = &s[..dm];
            let mut m = 0u64;
            let mut below = true;
            for c in 0..dm {
                m |= u64::from(s[c] > p[c]) << (c & 63);
                below &= p[c] <= s[c];
            }
            if m == 0 {
                return false;
            }
            sc.dominated.push(below);
            if track && m & (m - 1) == 0 {
                let c = m.trailing_zeros() as usize;
                if s[c] < best[c] {
                    best[c] = s[c];
                }
            } else if !(track && filtered(m, s, &best)) {
                // Not dominated by the single-coordinate points so far: check again at the
                // end.
                sc.multi.push((m, i as u32));
            }
        }
    }
    if track {
        // The single-coordinate points together cover every x with some x_c >= best[c]:
        // what is left of the box is [p, rc).
        for (c, &b) in best.iter().enumerate().take(dm) {
            rc[c] = rc[c].min(b);
        }
    }
    sc.survivors.clear();
    if dm <= GROUPED {
        // Few mask sizes: a counting sort by size (stable), straight from `multi`.
        let mut start = [0usize; GROUPED + 2];
        let mut kept = 0;
        for j in 0..sc.multi.len() {
            let (m, i) = sc.multi[j];
            let s = &seen[i as usize * dm..i as usize * dm + dm];
            if track && filtered(m, s, &best) {
                continue;
            }
            start[popcount_small(m) + 1] += 1;
            sc.multi[kept] = (m, i);
            kept += 1;
        }
        sc.multi.truncate(kept);
        for k in 1..start.len() {
            start[k] += start[k - 1];
        }
        sc.survivors.resize(kept, (0, 0));
        for &(m, i) in &sc.multi {
            let k = popcount_small(m);
            // The mask itself (it fits: at most GROUPED bits), so the loop below need not
            // recompute it.
            sc.survivors[start[k]] = (m as u32, i);
            start[k] += 1;
        }
    } else {
        for &(m, i) in &sc.multi {
            if track && filtered(m, &seen[i as usize * dm..i as usize * dm + dm], &best) {
                continue;
            }
            sc.survivors.push((m.count_ones(), i));
        }
        sc.survivors.sort_unstable();
    }
    sc.q.clear();
    sc.q.extend_from_slice(p);
    // Bit m set: the group of mask m is not empty (masks < 2^GROUPED <= 64).
    let mut nonempty = 0u64;
    if dm <= GROUPED {
        if sc.groups.len() < 1 << GROUPED {
            sc.groups.resize(1 << GROUPED, Vec::new());
        }
        for &m in &sc.used {
            sc.groups[m as usize].clear();
        }
        sc.used.clear();
    } else {
        sc.kept.clear();
        sc.kept_mask.clear();
    }
    for &(key, i) in &sc.survivors {
        let i = i as usize;
        let s = &seen[i * dm..i * dm + dm];
        let m = if dm <= GROUPED {
            u64::from(key)
        } else {
            let mut m = 0u64;
            for c in 0..dm {
                m |= u64::from(s[c] > p[c]) << (c & 63);
            }
            m
        };
        let q = &mut sc.q[..dm];
        for c in 0..dm {
            q[c] = p[c].max(s[c]);
        }
        let q = &sc.q[..dm];
        // Branch-free per point: the comparisons rarely all hold.
        let covers = |t: &[f64]| {
            let t = &t[..dm];
            (0..dm).fold(true, |acc, c| acc & (t[c] <= q[c]))
        };
        if dm <= GROUPED {
            // Every non-empty group whose mask is a subset of m (single-coordinate masks
            // were filtered already).
            let mut dominated = false;
            let mut sub = m;
            while sub != 0 && !dominated {
                if (nonempty >> sub) & 1 == 1 {
                    dominated = sc.groups[sub as usize].chunks_exact(dm).any(covers);
                }
                sub = (sub - 1) & m;
            }
            if !dominated {
                let g = &mut sc.groups[m as usize];
                if g.is_empty() {
                    sc.used.push(m);
                    nonempty |= 1u64 << m;
                }
                g.extend_from_slice(q);
            }
        } else {
            let dominated = sc
                .kept_mask
                .iter()
                .zip(sc.kept.chunks_exact(dm))
                .any(|(&km, t)| km & !m == 0 && covers(t));
            if !dominated {
                sc.kept.extend_from_slice(q);
                sc.kept_mask.push(m);
            }
        }
    }
    if dm <= GROUPED {
        for &m in &sc.used {
            out.extend_from_slice(&sc.groups[m as usize]);
        }
    } else {
        out.extend_from_slice(&sc.kept);
    }
    true
}

/// The number of set bits of a mask below 2^[`GROUPED`], by table: the baseline x86-64
/// target has no `popcnt` instruction, and `count_ones` is a dozen operations there.
#[inline]
fn popcount_small(m: u64) -> usize {
    const POP: [u8; 1 << GROUPED] = {
        let mut t = [0u8; 1 << GROUPED];
        let mut i = 1;
        while i < t.len() {
            t[i] = t[i >> 1] + (i & 1) as u8;
            i += 1;
        }
        t
    };
    usize::from(POP[m as usize & ((1 << GROUPED) - 1)])
}

/// Whether the clipped point of `s` (mask `m`, at most 64 coordinates) is weakly dominated
/// by one of the single-coordinate points `best` (coordinate c at `best[c]`, the rest at p).
#[inline]
fn filtered(m: u64, s: &[f64], best: &[f64; 65]) -> bool {
    let mut dominated = false;
    for (c, (&v, &b)) in s.iter().zip(best).enumerate() {
        dominated |= ((m >> c) & 1 == 1) & (b <= v);
    }
    dominated
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
