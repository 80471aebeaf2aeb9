//! `x^(1/n)` for a whole `n` in 2..=[`MAX_N`] without `ln`/`exp`: the hot root of MOEA/D's
//! SBX variation (`u^(1/(eta + 1))`, eta 20, about 15 roots per child).
//!
//! Method: `x = 2^e m` with `m` in [1, 2) (from the bits); `e = q n + r` with `0 <= r < n`;
//! `m = c (1 + s)` with `c` the centre of the 1/128-wide cell of `m` (`|s| <= 2^-8`);
//! `x^(1/n) = 2^q 2^(r/n) c^(1/n) (1 + s)^(1/n)`, the last factor by its Taylor polynomial
//! of degree 4 (truncation below `|C(1/n, 5)| 2^-40 < 3e-14` relative) and the others from
//! tables built once per `n` with `powf` and `exp2` (process-wide, on first use). The same for
//! `x^(-1/n)` with tables of their own (truncation below `|C(-1/2, 5)| 2^-40 < 2.3e-13`), so
//! SBX's `(1 / y)^(1/n)` needs no division. Only `+ - *` and bit operations per root, so the
//! same bits on every run; relative error against `powf` below 1e-13 for `x^(1/n)` and 3e-13
//! for `x^(-1/n)` (tested over a dense sweep from subnormals to 1e300 for several `n`).
//! Zero, negative, NaN and infinite inputs, and any `n` outside the tables, go to `powf`.

use std::sync::OnceLock;

/// Largest `n` with tables (SBX indices up to 100 give `n = eta + 1` up to 101).
pub const MAX_N: u32 = 101;

/// Cells of the mantissa: 2^CELL_BITS.
const CELL_BITS: u32 = 7;
const CELLS: usize = 1 << CELL_BITS;

/// The tables of one sign of the exponent: `x^(1/n)` or `x^(-1/n)`.
#[derive(Debug)]
struct Side {
    /// `c^(+-1/n)` for each cell centre.
    root_centre: [f64; CELLS],
    /// `2^(+-r/n)` for `r` in 0..n.
    pow2: Vec<f64>,
    /// `C(+-1/n, k)` for k = 1..=4 (Taylor coefficients of `(1 + s)^(+-1/n)`).
    coeff: [f64; 4],
}

impl Side {
    fn new(n: u32, p: f64) -> Self {
        let mut root_centre = [0.0; CELLS];
        for (i, rc) in root_centre.iter_mut().enumerate() {
            *rc = centre(i).powf(p);
        }
        let pow2 = (0..n).map(|r| (f64::from(r) * p).exp2()).collect();
        let mut coeff = [0.0; 4];
        let mut c = 1.0;
        for (k, a) in coeff.iter_mut().enumerate() {
            // C(p, k + 1) = C(p, k) (p - k) / (k + 1)
            c *= (p - k as f64) / (k as f64 + 1.0);
            *a = c;
        }
        Self {
            root_centre,
            pow2,
            coeff,
        }
    }
}

/// Centre of mantissa cell `i`: `1 + (i + 1/2) / 128` (exact).
#[inline]
fn centre(i: usize) -> f64 {
    1.0 + (i as f64 + 0.5) * (1.0 / CELLS as f64)
}

/// Tables of `x^(1/n)` and `x^(-1/n)` for one `n`.
#[derive(Debug)]
pub struct RootTable {
    n: u32,
    /// Offset making every exponent (down to -1074 - 64) non-negative; a multiple of n.
    offset: u32,
    /// `offset / n`.
    offset_q: i64,
    /// `ceil(2^32 / n)`: `d / n == (d * magic) >> 32` for every `d` this table meets.
    magic: u64,
    /// `1 / c` for each cell centre `c`.
    inv_centre: [f64; CELLS],
    /// Exponent `1/n`, then `-1/n`.
    sides: [Side; 2],
}

impl RootTable {
    fn new(n: u32) -> Self {
        let inv_n = 1.0 / f64::from(n);
        let mut inv_centre = [0.0; CELLS];
        for (i, ic) in inv_centre.iter_mut().enumerate() {
            *ic = 1.0 / centre(i);
        }
        Self {
            n,
            offset: n * 1200_u32.div_ceil(n),
            offset_q: i64::from(1200_u32.div_ceil(n)),
            magic: (1_u64 << 32).div_ceil(u64::from(n)),
            inv_centre,
            sides: [Side::new(n, inv_n), Side::new(n, -inv_n)],
        }
    }

    /// `x^(1/n)` (see the module notes for accuracy and special values).
    #[inline]
    #[must_use]
    pub fn root(&self, x: f64) -> f64 {
        self.signed(x, false)
    }

    /// `x^(-1/n)`, without a division (`x = 0` gives infinity).
    #[inline]
    #[must_use]
    pub fn inv_root(&self, x: f64) -> f64 {
        self.signed(x, true)
    }

    /// `x^(-1/n)` if `inverse`, else `x^(1/n)`; the choice is a table index, not a branch.
    #[inline]
    #[must_use]
    pub fn signed(&self, x: f64, inverse: bool) -> f64 {
        let mut bits = x.to_bits();
        let mut biased = (bits >> 52) as u32; // sign bit included: negatives land above 0x7ff
        let mut shift = 0;
        if biased.wrapping_sub(1) >= 0x7fe {
            // Zero, subnormal, infinite, NaN or negative.
            let p = 1.0 / f64::from(self.n);
            if x == 0.0 || biased != 0 {
                return x.powf(if inverse { -p } else { p });
            }
            // Subnormal: scale by 2^64 into the normal range.
            bits = (x * f64::from_bits(0x43f0_0000_0000_0000)).to_bits();
            biased = (bits >> 52) as u32;
            shift = 64;
        }
        let side = &self.sides[usize::from(inverse)];
        // e + offset >= 0 with e = biased - 1023 - shift.
        let d = u64::from(biased + self.offset) - 1023 - shift;
        let qd = (d * self.magic) >> 32; // d / n
        let r = (d - qd * u64::from(self.n)) as usize;
        let q = qd as i64 - self.offset_q;
        // 2^(+-q): q lies in [-600, 512], a normal power of two either way.
        let q = if inverse { -q } else { q };
        let scale = f64::from_bits(((q + 1023) as u64) << 52);
        let mant = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
        let cell = ((bits >> (52 - CELL_BITS)) as usize) & (CELLS - 1);
        // Exact: both in [1, 2) and at most 2^-8 apart.
        let s = (mant - centre(cell)) * self.inv_centre[cell];
        let [a1, a2, a3, a4] = side.coeff;
        let s2 = s * s;
        let poly = 1.0 + (s * a1 + s2 * (a2 + s * a3 + s2 * a4));
        (scale * side.pow2[r]) * side.root_centre[cell] * poly
    }
}

/// The tables for `n` (built on first use, then shared by the process), if `n` is in
/// 2..=[`MAX_N`].
#[must_use]
pub fn table(n: u32) -> Option<&'static RootTable> {
    static TABLES: [OnceLock<RootTable>; MAX_N as usize - 1] =
        [const { OnceLock::new() }; MAX_N as usize - 1];
    let slot = TABLES.get(usize::try_from(n).ok()?.checked_sub(2)?)?;
    Some(slot.get_or_init(|| RootTable::new(n)))
}

/// `x^(1/n)` for a whole `n` in the tables' range; [`Root::Powf`] otherwise.
#[derive(Clone, Copy, Debug)]
pub enum Root {
    /// Table method for a whole `n`.
    Table(&'static RootTable),
    /// `x.powf(p)` with `p = 1 / n`.
    Powf(f64),
}

impl Root {
    /// The root of index `n` (`x^(1/n)`): tables when `n` is a whole number in 2..=[`MAX_N`].
    #[must_use]
    pub fn new(n: f64) -> Self {
        if n.fract() == 0.0
            && (2.0..=f64::from(MAX_N)).contains(&n)
            && let Some(t) = table(n as u32)
        {
            return Self::Table(t);
        }
        Self::Powf(1.0 / n)
    }

    /// `x^(1/n)`.
    #[inline]
    #[must_use]
    pub fn of(&self, x: f64) -> f64 {
        self.signed(x, false)
    }

    /// `x^(-1/n)` if `inverse`, else `x^(1/n)` (for the tables a table index, not a branch).
    #[inline]
    #[must_use]
    pub fn signed(&self, x: f64, inverse: bool) -> f64 {
        match self {
            Self::Table(t) => t.signed(x, inverse),
            Self::Powf(p) => x.powf(if inverse { -*p } else { *p }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        if a == b { 0.0 } else { ((a - b) / b).abs() }
    }

    /// Dense sweep: every cell of the mantissa, exponents from subnormal to 1e300, a few n,
    /// both signs of the exponent.
    #[test]
    fn table_root_matches_powf() {
        let mut worst = [0.0_f64; 2];
        for n in [2_u32, 3, 7, 11, 20, 21, 51, 100, 101] {
            let t = table(n).unwrap();
            for (inverse, tol) in [(false, 1e-13), (true, 3e-13)] {
                let p = if inverse { -1.0 } else { 1.0 } / f64::from(n);
                let mut check = |x: f64| {
                    let (a, b) = (t.signed(x, inverse), x.powf(p));
                    let e = rel(a, b);
                    worst[usize::from(inverse)] = worst[usize::from(inverse)].max(e);
                    assert!(e < tol, "n {n} inverse {inverse} x {x:e}: {a:e} vs {b:e}");
                };
                // From the smallest subnormal up, by a factor just above 1 (at least one
                // ulp) so the mantissas sweep every cell, with several points per cell below
                // 2 (where SBX's values lie).
                let mut x = 4.9e-324_f64;
                while x < 1e300 {
                    check(x);
                    let f = if (1e-3..2.0).contains(&x) {
                        1.000_9
                    } else {
                        1.031
                    };
                    x = (x * f).max(f64::from_bits(x.to_bits() + 1));
                }
                // The values SBX meets: u * alpha with u a multiple of 2^-53, and 2 - ra.
                let mut u = 0.0_f64;
                while u < 2.0 {
                    check(f64::from_bits(u.to_bits() | 1)); // odd last bit
                    u += 1.0 / 4099.0;
                }
                check(f64::MAX);
                check(1.0);
            }
            assert_eq!(t.root(0.0), 0.0);
            assert_eq!(t.inv_root(0.0), f64::INFINITY);
            assert!(t.root(-1.0).is_nan() && t.root(f64::NAN).is_nan());
            assert_eq!(t.root(f64::INFINITY), f64::INFINITY);
            assert_eq!(t.inv_root(f64::INFINITY), 0.0);
        }
        println!(
            "worst relative error: root {:e}, inverse root {:e}",
            worst[0], worst[1]
        );
    }

    #[test]
    fn root_uses_tables_for_whole_indices_only() {
        assert!(matches!(Root::new(21.0), Root::Table(_)));
        assert!(matches!(Root::new(2.0), Root::Table(_)));
        assert!(matches!(Root::new(21.5), Root::Powf(_)));
        assert!(matches!(Root::new(1.0), Root::Powf(_)));
        assert!(matches!(Root::new(102.0), Root::Powf(_)));
        assert_eq!(Root::new(21.5).of(0.3), 0.3_f64.powf(1.0 / 21.5));
        assert!(rel(Root::new(21.0).of(0.3), 0.3_f64.powf(1.0 / 21.0)) < 1e-13);
        let inv = Root::new(21.0).signed(0.3, true);
        assert!(rel(inv, 0.3_f64.powf(-1.0 / 21.0)) < 1e-13);
        assert_eq!(Root::new(21.5).signed(0.3, true), 0.3_f64.powf(-1.0 / 21.5));
    }
}
