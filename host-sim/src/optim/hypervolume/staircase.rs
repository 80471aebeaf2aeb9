//! The 2-D building block of the 3-D sweeps: a staircase of mutually non-dominated
//! points kept in slots ordered by x (the x-ranks of the points, known in advance), stored in a
//! hierarchical bit set so that predecessor and successor queries cost O(log_64 n) word
//! operations instead of a balanced tree's pointer chasing.

/// A set of integers `0..n` as a hierarchy of 64-bit words: level 0 holds one bit per
/// element, level `l + 1` one bit per non-empty word of level `l`.
#[derive(Debug, Clone, Default)]
pub(super) struct BitSet {
    levels: Vec<Vec<u64>>,
}

impl BitSet {
    /// An empty set able to hold `0..n`.
    pub(super) fn new(n: usize) -> Self {
        let mut s = Self::default();
        s.reset(n);
        s
    }

    /// Make the set empty and able to hold `0..n`, reusing its buffers.
    pub(super) fn reset(&mut self, n: usize) {
        let mut len = n.div_ceil(64).max(1);
        let mut l = 0;
        loop {
            if l == self.levels.len() {
                self.levels.push(Vec::new());
            }
            let level = &mut self.levels[l];
            level.clear();
            level.resize(len, 0);
            l += 1;
            if len == 1 {
                break;
            }
            len = len.div_ceil(64);
        }
        self.levels.truncate(l);
    }

    /// Remove every element (cost proportional to `n / 64`).
    pub(super) fn clear(&mut self) {
        for l in &mut self.levels {
            l.fill(0);
        }
    }

    /// Whether `i` is in the set.
    #[inline]
    pub(super) fn contains(&self, i: usize) -> bool {
        self.levels[0][i >> 6] & (1u64 << (i & 63)) != 0
    }

    /// Add `i`.
    #[inline]
    pub(super) fn insert(&mut self, mut i: usize) {
        for level in &mut self.levels {
            let w = &mut level[i >> 6];
            let was = *w;
            *w |= 1u64 << (i & 63);
            if was != 0 {
                return;
            }
            i >>= 6;
        }
    }

    /// Remove `i`.
    #[inline]
    pub(super) fn remove(&mut self, mut i: usize) {
        for level in &mut self.levels {
            let w = &mut level[i >> 6];
            *w &= !(1u64 << (i & 63));
            if *w != 0 {
                return;
            }
            i >>= 6;
        }
    }

    /// The smallest element.
    #[inline]
    pub(super) fn first(&self) -> Option<usize> {
        if self.contains(0) {
            Some(0)
        } else {
            self.next_after(0)
        }
    }

    /// The smallest element greater than `i`.
    #[inline]
    pub(super) fn next_after(&self, i: usize) -> Option<usize> {
        let mut pos = i + 1;
        let mut l = 0;
        loop {
            let level = &self.levels[l];
            let w = pos >> 6;
            if w >= level.len() {
                return None;
            }
            let m = level[w] & (!0u64 << (pos & 63));
            if m != 0 {
                let mut idx = (w << 6) | m.trailing_zeros() as usize;
                while l > 0 {
                    l -= 1;
                    idx = (idx << 6) | self.levels[l][idx].trailing_zeros() as usize;
                }
                return Some(idx);
            }
            pos = w + 1;
            l += 1;
            if l == self.levels.len() {
                return None;
            }
        }
    }

    /// The largest element smaller than `i`.
    #[inline]
    pub(super) fn prev_before(&self, i: usize) -> Option<usize> {
        if i == 0 {
            return None;
        }
        let mut pos = i - 1;
        let mut l = 0;
        loop {
            let level = &self.levels[l];
            let w = pos >> 6;
            let bit = pos & 63;
            let mask = if bit == 63 {
                !0u64
            } else {
                (1u64 << (bit + 1)) - 1
            };
            let m = level[w] & mask;
            if m != 0 {
                let mut idx = (w << 6) | (63 - m.leading_zeros() as usize);
                while l > 0 {
                    l -= 1;
                    idx = (idx << 6) | (63 - self.levels[l][idx].leading_zeros() as usize);
                }
                return Some(idx);
            }
            if w == 0 {
                return None;
            }
            pos = w - 1;
            l += 1;
            if l == self.levels.len() {
                return None;
            }
        }
    }
}

/// The staircase (union of quadrants `[x, rx) x [y, ry)`) of points placed in slots whose x
/// coordinates are fixed and increase with the slot index (ties allowed). Slot 0 is the
/// "wall": its x is set on every [`Staircase::reset`] (the left edge of a box) and it may be
/// lowered repeatedly; the other slots each take one point at most.
#[derive(Debug, Clone, Default)]
pub(super) struct Staircase {
    set: BitSet,
    x: Vec<f64>,
    y: Vec<f64>,
    rx: f64,
    ry: f64,
}

impl Staircase {
    /// A staircase over slots `0..=xs.len()`: slot `k + 1` has x coordinate `xs[k]` (`xs`
    /// non-decreasing); the bounding corner is `(rx, ry)`.
    #[cfg(test)]
    pub(super) fn new(xs: &[f64], rx: f64, ry: f64) -> Self {
        let mut s = Self::default();
        s.fill(xs, rx, ry);
        s
    }

    /// [`Staircase::new`] into the existing buffers.
    pub(super) fn fill(&mut self, xs: &[f64], rx: f64, ry: f64) {
        self.x.clear();
        self.x.push(f64::NEG_INFINITY);
        self.x.extend_from_slice(xs);
        self.y.clear();
        self.y.resize(xs.len() + 1, 0.0);
        self.set.reset(xs.len() + 1);
        self.rx = rx;
        self.ry = ry;
    }

    /// Empty the staircase and put the wall (slot 0) at `wall_x`.
    pub(super) fn reset(&mut self, wall_x: f64) {
        self.set.clear();
        self.x[0] = wall_x;
    }

    /// Insert the point (x of `slot`, `y`); returns the area it adds to the union (0 if it
    /// is weakly dominated), removing the points it dominates.
    #[inline]
    pub(super) fn insert(&mut self, slot: usize, y: f64) -> f64 {
        let mut h = if self.set.contains(slot) {
            // Only the wall slot can be occupied: the same x, so the lower y wins.
            let y0 = self.y[slot];
            if y0 <= y {
                return 0.0;
            }
            y0
        } else {
            match self.set.prev_before(slot) {
                Some(p) => {
                    let yp = self.y[p];
                    if yp <= y {
                        return 0.0;
                    }
                    yp
                }
                None => self.ry,
            }
        };
        let mut cur = self.x[slot];
        let mut added = 0.0;
        let mut s = slot;
        loop {
            match self.set.next_after(s) {
                Some(nx) if self.y[nx] >= y => {
                    let xn = self.x[nx];
                    added += (xn - cur) * (h - y);
                    cur = xn;
                    h = self.y[nx];
                    self.set.remove(nx);
                    s = nx;
                }
                other => {
                    let end = other.map_or(self.rx, |nx| self.x[nx]);
                    added += (end - cur) * (h - y);
                    break;
                }
            }
        }
        self.set.insert(slot);
        self.y[slot] = y;
        added
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bitset_next_prev_match_a_linear_scan() {
        // Deterministic pseudo-random membership over three levels (n > 64 * 64).
        let n = 5000;
        let mut set = BitSet::new(n);
        let mut member = vec![false; n];
        let mut s: u64 = 0x9e37_79b9_7f4a_7c15;
        for step in 0..20_000 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            let i = (s % n as u64) as usize;
            if step % 3 == 0 {
                set.remove(i);
                member[i] = false;
            } else {
                set.insert(i);
                member[i] = true;
            }
            let q = ((s >> 20) % n as u64) as usize;
            let next = (q + 1..n).find(|&k| member[k]);
            let prev = (0..q).rev().find(|&k| member[k]);
            assert_eq!(set.next_after(q), next, "next_after({q})");
            assert_eq!(set.prev_before(q), prev, "prev_before({q})");
            assert_eq!(set.contains(q), member[q]);
        }
    }

    #[test]
    fn staircase_area_of_two_steps() {
        // Points (0,2) and (1,1) under the corner (3,3).
        let mut st = Staircase::new(&[0.0, 1.0, 2.0], 3.0, 3.0);
        st.reset(f64::NEG_INFINITY);
        let a1 = st.insert(1, 2.0); // [0,3) x [2,3): 3
        let a2 = st.insert(2, 1.0); // adds [1,3) x [1,2): 2
        assert_eq!(a1, 3.0);
        assert_eq!(a2, 2.0);
        // A dominated point adds nothing.
        assert_eq!(st.insert(3, 1.5), 0.0);
        // The wall at x = -1 with y = 2.5 adds [-1, 0) x [2.5, 3), then lowering it to 0.5
        // adds [-1, 3) x [0.5, ...) below the existing steps.
        st.reset(-1.0);
        st.insert(1, 2.0);
        st.insert(2, 1.0);
        assert_eq!(st.insert(0, 2.5), 0.5);
        // Union before: [-1,0)x[2.5,3) + [0,1)x[2,3) + [1,3)x[1,3) = 0.5 + 1 + 4 = 5.5;
        // after the wall drops to 0.5: [-1,3) x [0.5,3) = 10, so it adds 4.5.
        assert_eq!(st.insert(0, 0.5), 4.5);
    }
}
