//! Bounded numerical helpers shared by the closed forms: bracketing root finder, first sign
//! change on a scan, golden-section maximiser, and a cancellation-free `(e^x - 1 - x)/x^2`.
//!
//! Every loop here has a fixed maximum iteration count (stated on each function), so the
//! worst-case cost of every closed-form evaluation is bounded.

use super::error::VinhError;
use crate::scalar::Real;

/// `S` from an `f64` constant.
#[inline]
pub(crate) fn k<S: Real>(v: f64) -> S {
    S::from_f64(v)
}

/// Ok(v) if `v` is finite, else [`VinhError::NonFiniteResult`].
#[inline]
pub(crate) fn finite<S: Real>(v: S) -> Result<S, VinhError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(VinhError::NonFiniteResult)
    }
}

/// `(e^x - 1 - x) / x^2`, accurate for small `|x|` (series for `|x| < 1`, 14 terms:
/// truncation below `1/16! < 5e-14`).
pub(crate) fn expm1mx_over_x2<S: Real>(x: S) -> S {
    if x.abs() < S::ONE {
        // sum_{n>=0} x^n / (n+2)!
        let mut term = k::<S>(0.5);
        let mut sum = term;
        let mut n = 0.0_f64;
        while n < 14.0 {
            term = term * x / k(n + 3.0);
            sum = sum + term;
            n += 1.0;
        }
        sum
    } else {
        (x.exp() - S::ONE - x) / (x * x)
    }
}

/// Maximum bisection steps of [`bisect`]. 200 halvings shrink any finite `f64` interval below
/// one ulp of its end points, so the limit is never the binding stop for `f32`/`f64`.
pub(crate) const MAX_BISECTION_STEPS: u32 = 200;

/// Root of `f` in `[lo, hi]` given `f(lo)` and `f(hi)` of opposite sign (or one of them zero),
/// by bisection until the midpoint equals an end point (full precision) or
/// [`MAX_BISECTION_STEPS`].
pub(crate) fn bisect<S: Real, F: FnMut(S) -> Result<S, VinhError>>(
    mut f: F,
    mut lo: S,
    mut hi: S,
    mut f_lo: S,
    f_hi: S,
) -> Result<S, VinhError> {
    if f_lo == S::ZERO {
        return Ok(lo);
    }
    if f_hi == S::ZERO {
        return Ok(hi);
    }
    if (f_lo > S::ZERO) == (f_hi > S::ZERO) {
        return Err(VinhError::NoConvergence);
    }
    let mut i = 0;
    while i < MAX_BISECTION_STEPS {
        let mid = (lo + hi).half();
        if !(mid > lo && mid < hi) {
            return Ok(mid.clamp(lo, hi));
        }
        let fm = f(mid)?;
        if fm == S::ZERO {
            return Ok(mid);
        }
        if (fm > S::ZERO) == (f_lo > S::ZERO) {
            lo = mid;
            f_lo = fm;
        } else {
            hi = mid;
        }
        i += 1;
    }
    Ok((lo + hi).half())
}

/// Number of scan intervals of [`first_root`].
pub(crate) const SCAN_INTERVALS: u32 = 64;

/// First root of `f` in `(lo, hi]`, knowing `f(lo) > 0`: scans [`SCAN_INTERVALS`] equal
/// intervals for the first sign change, then [`bisect`]s it. `Ok(None)` if `f` stays positive on
/// the scan points. Cost: at most `SCAN_INTERVALS + MAX_BISECTION_STEPS` evaluations.
pub(crate) fn first_root<S: Real, F: FnMut(S) -> Result<S, VinhError>>(
    mut f: F,
    lo: S,
    hi: S,
    f_lo: S,
) -> Result<Option<S>, VinhError> {
    let n: S = k(f64::from(SCAN_INTERVALS));
    let mut a = lo;
    let mut fa = f_lo;
    let mut i = 1_u32;
    while i <= SCAN_INTERVALS {
        let b = if i == SCAN_INTERVALS {
            hi
        } else {
            lo + (hi - lo) * k::<S>(f64::from(i)) / n
        };
        let fb = f(b)?;
        if fb <= S::ZERO {
            return bisect(&mut f, a, b, fa, fb).map(Some);
        }
        a = b;
        fa = fb;
        i += 1;
    }
    Ok(None)
}

/// Golden-section iterations of [`maximize`] (interval shrinks by `0.618^60 < 3e-13`).
pub(crate) const GOLDEN_STEPS: u32 = 60;
/// Scan intervals of [`maximize`].
pub(crate) const MAX_SCAN_INTERVALS: u32 = 48;

/// Location and value of the maximum of `f` on `[a, b]`: scan [`MAX_SCAN_INTERVALS`] intervals,
/// then golden-section search around the best scan point ([`GOLDEN_STEPS`] steps). Finds the
/// global maximum when `f` is unimodal on each scan interval pair.
pub(crate) fn maximize<S: Real, F: FnMut(S) -> Result<S, VinhError>>(
    mut f: F,
    a: S,
    b: S,
) -> Result<(S, S), VinhError> {
    let n: S = k(f64::from(MAX_SCAN_INTERVALS));
    let h = (b - a) / n;
    let mut best_t = a;
    let mut best_f = f(a)?;
    let mut i = 1_u32;
    while i <= MAX_SCAN_INTERVALS {
        let t = if i == MAX_SCAN_INTERVALS {
            b
        } else {
            a + h * k::<S>(f64::from(i))
        };
        let ft = f(t)?;
        if ft > best_f {
            best_f = ft;
            best_t = t;
        }
        i += 1;
    }
    let mut lo = (best_t - h).max(a);
    let mut hi = (best_t + h).min(b);
    let g: S = k(0.618_033_988_749_894_8);
    let mut x1 = hi - g * (hi - lo);
    let mut x2 = lo + g * (hi - lo);
    let mut f1 = f(x1)?;
    let mut f2 = f(x2)?;
    let mut j = 0;
    while j < GOLDEN_STEPS {
        if f1 < f2 {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + g * (hi - lo);
            f2 = f(x2)?;
        } else {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - g * (hi - lo);
            f1 = f(x1)?;
        }
        j += 1;
    }
    let (t, v) = if f1 > f2 { (x1, f1) } else { (x2, f2) };
    if v >= best_f {
        Ok((t, v))
    } else {
        Ok((best_t, best_f))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn series_matches_direct_formula() {
        for &x in &[-0.9_f64, -0.3, 1e-3, 0.2, 0.99, 1.5, 5.0] {
            let direct = (crate::math::exp(x) - 1.0 - x) / (x * x);
            let s = expm1mx_over_x2(x);
            assert!((s - direct).abs() < 1e-9 * direct.abs().max(1.0), "{x}");
        }
        assert!((expm1mx_over_x2(0.0_f64) - 0.5).abs() < 1e-15);
    }

    #[test]
    fn bisect_and_scan_find_roots() {
        let r = first_root(|x: f64| Ok(2.0 - x * x), 0.0, 5.0, 2.0)
            .unwrap()
            .unwrap();
        assert!((r - crate::math::sqrt(2.0)).abs() < 1e-14);
        assert!(
            first_root(|x: f64| Ok(1.0 + x), 0.0, 5.0, 1.0)
                .unwrap()
                .is_none()
        );
        let (t, v) = maximize(|x: f64| Ok(-(x - 0.3) * (x - 0.3)), 0.0, 1.0).unwrap();
        assert!((t - 0.3).abs() < 1e-7 && v.abs() < 1e-13);
    }
}
