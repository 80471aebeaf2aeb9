//! Bounded numerical helpers shared by the closed forms: Brent's bracketing root finder (a
//! resumable state machine, [`Zeroin`]), first sign change on a scan, golden-section maximiser
//! (kept as the dense reference of the tests), and a cancellation-free `(e^x - 1 - x)/x^2`.
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

/// Whether `S` is a single-precision type (`EPSILON` above 1e-10): the closed forms then use
/// the polynomial kernels below instead of libm's `sinf`/`cosf`/`asinf`, which compute in
/// `f64` (software floating point on a single-precision FPU such as the Cortex-M4F's).
#[inline]
fn single<S: Real>() -> bool {
    S::EPSILON > k::<S>(1e-10)
}

/// `(sin x, cos x)` for `|x| <= pi/2`. Single precision: Taylor polynomials to `x^13` and
/// `x^14` in the type's own arithmetic (truncation below `(pi/2)^15/15! < 7e-10` and
/// `(pi/2)^16/16! < 1.1e-10`; tested against libm: sine within 2 ulp, cosine within
/// 2 `EPSILON` absolute and 8 ulp where it is above 0.1). Double precision, or `|x|` beyond
/// `pi/2 + 0.01`: libm's `sin` and `cos`.
pub(crate) fn sin_cos_reduced<S: Real>(x: S) -> (S, S) {
    if !single::<S>() || !(x.abs() <= k(1.580_796_326_794_896_6)) {
        return (x.sin(), x.cos());
    }
    let x2 = x * x;
    // sin: x (1 - x2/(2 3) (1 - x2/(4 5) (1 - ... (1 - x2/(12 13)))))
    let mut p = S::ONE - x2 * k::<S>(1.0 / 156.0);
    p = S::ONE - x2 * k::<S>(1.0 / 110.0) * p;
    p = S::ONE - x2 * k::<S>(1.0 / 72.0) * p;
    p = S::ONE - x2 * k::<S>(1.0 / 42.0) * p;
    p = S::ONE - x2 * k::<S>(1.0 / 20.0) * p;
    p = S::ONE - x2 * k::<S>(1.0 / 6.0) * p;
    (x * p, cos_poly(x2))
}

/// The cosine polynomial of [`sin_cos_reduced`] at `x2 = x^2`:
/// `1 - x2/(1 2) (1 - x2/(3 4) (1 - ... (1 - x2/(13 14))))`.
#[inline(always)]
fn cos_poly<S: Real>(x2: S) -> S {
    let mut q = S::ONE - x2 * k::<S>(1.0 / 182.0);
    q = S::ONE - x2 * k::<S>(1.0 / 132.0) * q;
    q = S::ONE - x2 * k::<S>(1.0 / 90.0) * q;
    q = S::ONE - x2 * k::<S>(1.0 / 56.0) * q;
    q = S::ONE - x2 * k::<S>(1.0 / 30.0) * q;
    q = S::ONE - x2 * k::<S>(1.0 / 12.0) * q;
    S::ONE - x2.half() * q
}

/// `cos(x)` for `|x| <= pi/2 + 0.01` by the cosine polynomial of [`sin_cos_reduced`] (same
/// accuracy; the sine not computed); libm's `cos` otherwise and in double precision.
pub(crate) fn cos_reduced<S: Real>(x: S) -> S {
    if !single::<S>() || !(x.abs() <= k(1.580_796_326_794_896_6)) {
        return x.cos();
    }
    cos_poly(x * x)
}

/// `asin(a)` for `a` in `[-1, 1]` by [`asin_unit`] (odd symmetry); libm otherwise.
pub(crate) fn asin_signed<S: Real>(a: S) -> S {
    if a < S::ZERO {
        -asin_unit(-a)
    } else {
        asin_unit(a)
    }
}

/// `(sin x, cos x)` for any finite `x`. Single precision with `|x| <= 64`: directly
/// [`sin_cos_reduced`] for `|x| <= pi/4`, else reduction by `pi/2` in three parts
/// (Cody-Waite, the constants of Cephes' `sinf`: `n * P1` exact), [`sin_cos_reduced`] and the
/// quadrant; within 4 `EPSILON` of libm (tested). Otherwise libm.
pub(crate) fn sin_cos<S: Real>(x: S) -> (S, S) {
    if !(single::<S>() && x.abs() <= k(64.0)) {
        return (x.sin(), x.cos());
    }
    if x.abs() <= k(core::f64::consts::FRAC_PI_4) {
        return sin_cos_reduced(x);
    }
    let two_over_pi: S = k(core::f64::consts::FRAC_2_PI);
    // n = nearest integer of x 2/pi (|x 2/pi| < 41), by subtracting powers of two: no
    // float-to-integer conversion (a software routine on some targets); q = n as an integer.
    let t = x * two_over_pi;
    let mut acc = t.abs() + S::ONE.half();
    let mut n = S::ZERO;
    let mut q = 0_i32;
    let mut pf: S = k(32.0);
    let mut p2 = 32_i32;
    while p2 >= 1 {
        if acc >= pf {
            acc = acc - pf;
            n = n + pf;
            q += p2;
        }
        pf = pf.half();
        p2 /= 2;
    }
    if t < S::ZERO {
        n = -n;
        q = -q;
    }
    let r = ((x - n * k::<S>(1.570_312_5)) - n * k::<S>(4.837_512_969_970_703e-4))
        - n * k::<S>(7.549_789_954_891_882e-8);
    let (sr, cr) = sin_cos_reduced(r);
    match q.rem_euclid(4) {
        0 => (sr, cr),
        1 => (cr, -sr),
        2 => (-sr, -cr),
        _ => (-cr, sr),
    }
}

/// `asin(a)` for `a` in `[0, 1]`. Single precision: the series
/// `sum (2n)!/(4^n (n!)^2 (2n+1)) z^(2n+1)` to `n = 10` on `z <= 1/2` (truncation below
/// `1.5e-9` relative), with `asin(a) = pi/2 - 2 asin(sqrt((1 - a)/2))` above 1/2 (`1 - a` is
/// exact there); tested against libm to 4 ulp. Double precision or outside `[0, 1]`: libm.
pub(crate) fn asin_unit<S: Real>(a: S) -> S {
    if !(single::<S>() && a >= S::ZERO && a <= S::ONE) {
        return a.asin();
    }
    // Coefficients (2n)!/(4^n (n!)^2 (2n+1)), n = 0..10, as literals (each `k` folds to an
    // `S` constant; a loop over an `f64` array would convert at run time).
    let series = |z: S| -> S {
        let z2 = z * z;
        let mut p = k::<S>(654_729_075.0 / 78_033_715_200.0);
        p = p * z2 + k::<S>(34_459_425.0 / 3_530_096_640.0);
        p = p * z2 + k::<S>(2_027_025.0 / 175_472_640.0);
        p = p * z2 + k::<S>(135_135.0 / 9_676_800.0);
        p = p * z2 + k::<S>(10395.0 / 599_040.0);
        p = p * z2 + k::<S>(945.0 / 42240.0);
        p = p * z2 + k::<S>(105.0 / 3456.0);
        p = p * z2 + k::<S>(15.0 / 336.0);
        p = p * z2 + k::<S>(3.0 / 40.0);
        p = p * z2 + k::<S>(1.0 / 6.0);
        p = p * z2 + S::ONE;
        z * p
    };
    if a <= k(0.5) {
        series(a)
    } else {
        let z = ((S::ONE - a).half()).sqrt_fast();
        k::<S>(core::f64::consts::FRAC_PI_2) - series(z) - series(z)
    }
}

/// Largest number of function evaluations of one [`Zeroin`] search ([`brent`]). Brent's method
/// falls back to bisection whenever interpolation is slow, so it needs at most about twice the
/// bisection count to reach the working precision (< 2 x 64 for `f64` from any finite bracket
/// whose ends differ by less than 2^64 ulps, far fewer for `f32`); the cap only bounds the loop.
pub(crate) const MAX_BRENT_EVALS: u32 = 128;

/// What a [`Zeroin`] search wants next.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) enum ZeroinStep<S> {
    /// Evaluate the function here and [`Zeroin::supply`] the value.
    Eval(S),
    /// Converged: the bracket is below the tolerance (or a zero was hit); the best point.
    Done(S),
}

/// Brent's root finder (zeroin: bisection, secant and inverse quadratic interpolation on a
/// bracket that always contains a sign change), written as a resumable state machine so a caller
/// can spread the evaluations over several calls (the re-planner does, one prediction per step).
///
/// Stops when the bracket is below `2 EPSILON |b| + tol_abs/2` (the working precision of `S`
/// when `tol_abs` is 0: `f32` stops after far fewer steps than `f64`) or a zero is hit.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Zeroin<S> {
    a: S,
    b: S,
    c: S,
    fa: S,
    fb: S,
    fc: S,
    d: S,
    e: S,
    tol_abs: S,
    evals: u32,
}

impl<S: Real> Zeroin<S> {
    /// Search on `[a, b]` with `f(a) = fa`, `f(b) = fb` of opposite signs (or one zero).
    ///
    /// # Errors
    /// [`VinhError::NoConvergence`] if the ends do not bracket a sign change or are not finite.
    #[inline(always)]
    pub(crate) fn new(a: S, fa: S, b: S, fb: S, tol_abs: S) -> Result<Self, VinhError> {
        let all = [a, fa, b, fb, tol_abs];
        if all.iter().any(|v| !v.is_finite()) {
            return Err(VinhError::NoConvergence);
        }
        if fa != S::ZERO && fb != S::ZERO && (fa > S::ZERO) == (fb > S::ZERO) {
            return Err(VinhError::NoConvergence);
        }
        Ok(Self {
            a,
            b,
            c: a,
            fa,
            fb,
            fc: fa,
            d: b - a,
            e: b - a,
            tol_abs: tol_abs.abs(),
            evals: 0,
        })
    }

    /// Next point to evaluate, or the converged root.
    pub(crate) fn next(&mut self) -> ZeroinStep<S> {
        let two: S = k(2.0);
        let opposite = |x: S, y: S| (x > S::ZERO && y < S::ZERO) || (x < S::ZERO && y > S::ZERO);
        if !opposite(self.fb, self.fc) {
            self.c = self.a;
            self.fc = self.fa;
            self.d = self.b - self.a;
            self.e = self.d;
        }
        if self.fc.abs() < self.fb.abs() {
            self.a = self.b;
            self.b = self.c;
            self.c = self.a;
            self.fa = self.fb;
            self.fb = self.fc;
            self.fc = self.fa;
        }
        let tol = two * S::EPSILON * self.b.abs() + self.tol_abs.half();
        let m = (self.c - self.b).half();
        if !(m.abs() > tol) || self.fb == S::ZERO || self.evals >= MAX_BRENT_EVALS {
            return ZeroinStep::Done(self.b);
        }
        if self.e.abs() >= tol && self.fa.abs() > self.fb.abs() {
            let s = self.fb / self.fa;
            let (mut p, mut q);
            if self.a == self.c {
                p = two * m * s;
                q = S::ONE - s;
            } else {
                let qq = self.fa / self.fc;
                let r = self.fb / self.fc;
                p = s * (two * m * qq * (qq - r) - (self.b - self.a) * (r - S::ONE));
                q = (qq - S::ONE) * (r - S::ONE) * (s - S::ONE);
            }
            if p > S::ZERO {
                q = -q;
            } else {
                p = -p;
            }
            let three: S = k(3.0);
            if two * p < three * m * q - (tol * q).abs() && p < (self.e * q).half().abs() {
                self.e = self.d;
                self.d = p / q;
            } else {
                self.d = m;
                self.e = m;
            }
        } else {
            self.d = m;
            self.e = m;
        }
        self.a = self.b;
        self.fa = self.fb;
        let step = if self.d.abs() > tol {
            self.d
        } else if m > S::ZERO {
            tol
        } else {
            -tol
        };
        let x = self.b + step;
        self.b = if x.is_finite() { x } else { self.b + m };
        self.evals += 1;
        ZeroinStep::Eval(self.b)
    }

    /// Supply `f` at the point returned by the last [`Zeroin::next`].
    pub(crate) fn supply(&mut self, fx: S) {
        self.fb = fx;
    }
}

/// Root of `f` on `[a, b]` (`fa`, `fb` of opposite signs) by [`Zeroin`], to the working precision
/// plus `tol_abs/2`. At most [`MAX_BRENT_EVALS`] evaluations.
///
/// # Errors
/// [`VinhError::NoConvergence`] without a sign change; errors of `f`; a non-finite value of `f`
/// is [`VinhError::NonFiniteResult`].
pub(crate) fn brent<S: Real, F: FnMut(S) -> Result<S, VinhError>>(
    mut f: F,
    a: S,
    b: S,
    fa: S,
    fb: S,
    tol_abs: S,
) -> Result<S, VinhError> {
    let mut z = Zeroin::new(a, fa, b, fb, tol_abs)?;
    loop {
        match z.next() {
            ZeroinStep::Done(x) => return Ok(x),
            ZeroinStep::Eval(x) => z.supply(finite(f(x)?)?),
        }
    }
}

/// First root of `f` in `(lo, hi]` on the grid `lo + j h` (`j = 1, 2, ...`, the last point
/// `hi`), knowing `f(lo) > 0`: the first grid point where `f <= 0` closes the bracket, which
/// [`brent`] then solves. `Ok(None)` if `f` stays positive up to `hi`. At most
/// [`SCAN_INTERVALS`] grid points (`h` is raised to `(hi - lo)/SCAN_INTERVALS` if smaller).
pub(crate) fn first_root_from<S: Real, F: FnMut(S) -> Result<S, VinhError>>(
    mut f: F,
    lo: S,
    hi: S,
    f_lo: S,
    h: S,
) -> Result<Option<S>, VinhError> {
    let h_min = (hi - lo) / k::<S>(f64::from(SCAN_INTERVALS));
    let h = if h.is_finite() && h > h_min { h } else { h_min };
    let mut a = lo;
    let mut fa = f_lo;
    let mut i = 1_u32;
    while i <= SCAN_INTERVALS {
        let mut b = lo + h * k::<S>(f64::from(i));
        if !(b < hi) {
            b = hi;
        }
        let fb = finite(f(b)?)?;
        if fb <= S::ZERO {
            return brent(&mut f, a, b, fa, fb, S::ZERO).map(Some);
        }
        if b == hi {
            return Ok(None);
        }
        a = b;
        fa = fb;
        i += 1;
    }
    Ok(None)
}

/// Largest number of function evaluations of one [`brent_max`].
pub(crate) const MAX_BRENT_MAX_EVALS: u32 = 64;

/// Local maximum of `f` on `[a, b]` by Brent's method (golden section with parabolic
/// interpolation, no derivatives), started at `x0` in `[a, b]` with `f(x0) = f0`; stops when the
/// bracket is within `2 (sqrt(EPSILON) |x| + tol_abs)` of the best point (the peak value is then
/// within the working precision: the function is flat there), or after
/// [`MAX_BRENT_MAX_EVALS`] evaluations. Returns `(x, f(x))` with the largest `f` seen.
///
/// # Errors
/// Errors of `f`; [`VinhError::NonFiniteResult`] for a non-finite value.
pub(crate) fn brent_max<S: Real, F: FnMut(S) -> Result<S, VinhError>>(
    mut f: F,
    mut a: S,
    mut b: S,
    x0: S,
    f0: S,
    tol_abs: S,
) -> Result<(S, S), VinhError> {
    let golden: S = k(0.381_966_011_250_105_1);
    let two: S = k(2.0);
    let rel = S::EPSILON.sqrt_fast();
    // Minimise g = -f.
    let (mut x, mut w, mut v) = (x0, x0, x0);
    let (mut fx, mut fw, mut fv) = (-f0, -f0, -f0);
    let (mut d, mut e) = (S::ZERO, S::ZERO);
    let mut n = 0_u32;
    while n < MAX_BRENT_MAX_EVALS {
        let m = (a + b).half();
        let tol = rel * x.abs() + tol_abs;
        let t2 = two * tol;
        if !((x - m).abs() > t2 - (b - a).half()) {
            break;
        }
        let mut golden_step = true;
        if e.abs() > tol {
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = two * (q - r);
            if q > S::ZERO {
                p = -p;
            } else {
                q = -q;
            }
            let e_old = e;
            if p.abs() < (q * e_old).half().abs() && p > q * (a - x) && p < q * (b - x) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - a < t2 || b - u < t2 {
                    d = if x < m { tol } else { -tol };
                }
                golden_step = false;
            }
        }
        if golden_step {
            e = if x < m { b - x } else { a - x };
            d = golden * e;
        }
        let u = if d.abs() >= tol {
            x + d
        } else if d > S::ZERO {
            x + tol
        } else {
            x - tol
        };
        let fu = -finite(f(u)?)?;
        n += 1;
        if fu <= fx {
            if u < x {
                b = x;
            } else {
                a = x;
            }
            v = w;
            fv = fw;
            w = x;
            fw = fx;
            x = u;
            fx = fu;
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                v = w;
                fv = fw;
                w = u;
                fw = fu;
            } else if fu <= fv || v == x || v == w {
                v = u;
                fv = fu;
            }
        }
    }
    Ok((x, -fx))
}

/// Largest number of function evaluations of one [`parabolic_max`].
pub(crate) const MAX_PARABOLIC_EVALS: u32 = 40;

/// Maximum of `f` on `[a, b]` from three scan samples `a < x0 < b` with `f(x0) = f0` not below
/// `fa = f(a)`, `fb = f(b)`, by successive parabolic interpolation on a bracket (the vertex of
/// the parabola through the best point and its two bracketing neighbours; a golden-section
/// step into the larger side when the vertex is outside the bracket or too close to a sample).
/// `f` returns its value and a payload (`p0` for `x0`), handed back with the best sample, so
/// the caller need not recompute what `f` computed there.
///
/// Stops when the parabola predicts a gain over the best sample of at most `tol_f` (the value
/// is then known to that tolerance without evaluating the vertex: for a peak the value, not its
/// location, is what is wanted), when the bracket is below `sqrt(EPSILON) (|x| + |b - a|)`, or
/// after [`MAX_PARABOLIC_EVALS`] evaluations. Returns the best sample `(x, f(x), payload)`.
///
/// # Errors
/// Errors of `f`; [`VinhError::NonFiniteResult`] for a non-finite value;
/// [`VinhError::NoConvergence`] if the samples are not ordered or `x0` is not the best.
pub(crate) fn parabolic_max<S: Real, P: Copy, F: FnMut(S) -> Result<(S, P), VinhError>>(
    mut f: F,
    (mut a, mut fa): (S, S),
    (mut x, mut fx, mut px): (S, S, P),
    (mut b, mut fb): (S, S),
    tol_f: S,
) -> Result<(S, S, P), VinhError> {
    let all = [a, fa, x, fx, b, fb, tol_f];
    if all.iter().any(|v| !v.is_finite()) || !(a < x && x < b) || fa > fx || fb > fx {
        return Err(VinhError::NoConvergence);
    }
    let golden: S = k(0.381_966_011_250_105_1);
    let rel = S::EPSILON.sqrt_fast();
    let tol_x = rel * (x.abs() + (b - a).abs());
    let mut n = 0_u32;
    while n < MAX_PARABOLIC_EVALS {
        if !(b - a > tol_x + tol_x) {
            break;
        }
        // Vertex of the parabola through (a, fa), (x, fx), (b, fb):
        // u = x - ((x-a)^2 (fx-fb) - (x-b)^2 (fx-fa)) / (2 ((x-a)(fx-fb) - (x-b)(fx-fa))).
        let (da, db) = (x - a, x - b);
        let (ga, gb) = (fx - fa, fx - fb);
        let num = da * da * gb - db * db * ga;
        let den = (da * gb - db * ga) * k::<S>(2.0);
        let mut parabolic = false;
        let mut u = x;
        if den != S::ZERO {
            let step = num / den;
            // Predicted gain of the parabola at its vertex over fx: p(u) - fx = -p'' step^2/2
            // with p'' = 2 ((fb-fx)/(b-x) - (fx-fa)/(x-a)) / (b - a) <= 0 (x is the best
            // sample); `neg_curv` is -p''.
            let neg_curv = k::<S>(2.0) * (ga / da - gb / db) / (b - a);
            let gain = neg_curv * step * step / k::<S>(2.0);
            if gain.is_finite() && !(gain > tol_f) {
                break;
            }
            let cand = x - step;
            let gap = tol_x.half();
            if cand.is_finite() && cand > a + gap && cand < b - gap && (cand - x).abs() > gap {
                u = cand;
                parabolic = true;
            }
        }
        if !parabolic {
            u = if x - a > b - x {
                x - golden * (x - a)
            } else {
                x + golden * (b - x)
            };
        }
        let (fu, pu) = f(u)?;
        let fu = finite(fu)?;
        n += 1;
        if fu > fx {
            // u becomes the best point; x becomes the bracket end on its side.
            if u < x {
                (b, fb) = (x, fx);
            } else {
                (a, fa) = (x, fx);
            }
            (x, fx, px) = (u, fu, pu);
        } else if u < x {
            (a, fa) = (u, fu);
        } else {
            (b, fb) = (u, fu);
        }
    }
    Ok((x, fx, px))
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

    /// The kernels' accuracy with the default back end: with `micromath`, `S::sqrt` (used by
    /// `asin_unit` above 1/2) and the libm fall-backs route to micromath, which the closed
    /// forms are not validated with (see `crate::math`).
    #[test]
    #[cfg(not(feature = "micromath"))]
    fn single_precision_kernels_match_libm() {
        let ulp = |x: f32| f32::EPSILON * x.abs().max(f32::MIN_POSITIVE);
        let mut worst = (0.0_f32, 0.0_f32, 0.0_f32);
        for i in -2000_i32..=2000 {
            let x = 1.5807_f32 * i as f32 / 2000.0;
            let (s, c) = sin_cos_reduced(x);
            let (s_ref, c_ref) = (libm::sinf(x), libm::cosf(x));
            let es = (s - s_ref).abs() / ulp(s_ref).max(f32::EPSILON * 1e-3);
            let ec = (c - c_ref).abs() / ulp(c_ref).max(f32::EPSILON * 1e-3);
            worst.0 = worst.0.max(es);
            worst.1 = worst.1.max(if c_ref > 0.1 { ec } else { 0.0 });
            assert!(
                (c - c_ref).abs() <= 2.0 * f32::EPSILON,
                "cos {x}: {c} vs {c_ref}"
            );
            let a = i.unsigned_abs() as f32 / 2000.0;
            let e = (asin_unit(a) - libm::asinf(a)).abs() / ulp(libm::asinf(a).max(1e-30));
            worst.2 = worst.2.max(if a > 0.0 { e } else { 0.0 });
        }
        assert!(
            worst.0 <= 2.0 && worst.1 <= 8.0 && worst.2 <= 4.0,
            "{worst:?} ulp"
        );
        let mut worst_any = 0.0_f32;
        for i in -5700_i32..=5700 {
            let x = 0.011 * i as f32 + 0.003;
            let (s, c) = sin_cos(x);
            let e = (s - libm::sinf(x)).abs().max((c - libm::cosf(x)).abs());
            worst_any = worst_any.max(e);
        }
        assert!(worst_any <= 4.0 * f32::EPSILON, "{worst_any}");
        // f64 goes to libm unchanged.
        assert_eq!(sin_cos_reduced(0.3_f64).0, crate::math::sin(0.3));
        assert_eq!(asin_unit(0.3_f64), crate::math::asin(0.3));
    }

    #[test]
    fn brent_reaches_working_precision_in_few_steps() {
        let mut n = 0;
        let r = brent(
            |x: f64| {
                n += 1;
                Ok(x * x - 2.0)
            },
            0.0,
            5.0,
            -2.0,
            23.0,
            0.0,
        )
        .unwrap();
        assert!(
            (r - crate::math::sqrt(2.0)).abs() <= 4.0 * f64::EPSILON,
            "{r}"
        );
        assert!(n < 15, "{n} evaluations");
        let mut n32 = 0;
        let r32 = brent(
            |x: f32| {
                n32 += 1;
                Ok(x * x - 2.0)
            },
            0.0,
            5.0,
            -2.0,
            23.0,
            0.0,
        )
        .unwrap();
        assert!((r32 - core::f32::consts::SQRT_2).abs() <= 4.0 * f32::EPSILON);
        assert!(n32 <= n, "{n32} f32 vs {n} f64 evaluations");
        // A step function: Brent degrades to bisection but stays bounded.
        let mut m = 0;
        let s = brent(
            |x: f64| {
                m += 1;
                Ok(if x < 0.3 { -1.0 } else { 1.0 })
            },
            0.0,
            1.0,
            -1.0,
            1.0,
            0.0,
        )
        .unwrap();
        assert!((s - 0.3).abs() < 1e-12 && m <= MAX_BRENT_EVALS as usize);
        assert!(brent(|x: f64| Ok(x), 1.0, 2.0, 1.0, 2.0, 0.0).is_err());
        let mut k = 0;
        let (t, v) = brent_max(
            |x: f64| {
                k += 1;
                Ok(-(x - 0.3) * (x - 0.3) + (x - 0.3).powi(3))
            },
            0.0,
            1.0,
            0.5,
            -0.04 + 0.008,
            0.0,
        )
        .unwrap();
        assert!(
            (t - 0.3).abs() < 1e-7 && v.abs() < 1e-13 && k < 20,
            "{t} {v} {k}"
        );
        let first = first_root_from(|x: f64| Ok(2.0 - x * x), 0.0, 5.0, 2.0, 0.5)
            .unwrap()
            .unwrap();
        assert!((first - crate::math::sqrt(2.0)).abs() < 1e-14);
    }
}
