//! The one place float math is routed.
//!
//! Every transcendental function the crate uses is called through this module, by path, so the
//! choice of back end is made here and nowhere else. (With `std` in the dependency graph,
//! method syntax such as `x.sqrt()` would silently bind to `std`; do not use it in this crate.)
//!
//! * `f64` functions always use [`libm`] (correctly rounded to within 1 ulp for `sqrt`, and
//!   within a few ulp for the others, per libm's musl heritage).
//! * `f32` functions use [`libm`] by default. With the `micromath` feature, `sqrtf`, `expf`,
//!   `logf`, `sinf`, `cosf` and `atan2f` route to `micromath`, which trades accuracy for speed.
//!   Its errors, measured by `tests::micromath_bounds` over the guidance domain
//!   (`cargo test -p guidance-core --features micromath --lib math -- --nocapture`), are the
//!   `MICROMATH_*` constants below: up to 6 % relative for `sqrt` and 0.12 absolute for `ln`.
//!   That is acceptable for the guidance path (which uses no transcendental functions: node
//!   interpolation, rate limiting and the clock are arithmetic only) but **not** for the
//!   constraint monitors or the Vinh closed forms, which are validated with libm only. Flight
//!   builds that use the closed forms should leave `micromath` off.
//!
//! Naming follows libm: `name` takes `f64`, `namef` takes `f32`.

macro_rules! libm_f64 {
    ($($(#[$doc:meta])* $name:ident($($arg:ident),+);)+) => {$(
        $(#[$doc])*
        #[inline]
        #[must_use]
        pub fn $name($($arg: f64),+) -> f64 {
            libm::$name($($arg),+)
        }
    )+};
}

libm_f64! {
    /// Square root. Unitless routing of [`libm::sqrt`].
    sqrt(x);
    /// Natural exponential.
    exp(x);
    /// Natural logarithm (`log` in libm).
    log(x);
    /// Sine of an angle in radians.
    sin(x);
    /// Cosine of an angle in radians.
    cos(x);
    /// Tangent of an angle in radians.
    tan(x);
    /// Arcsine, radians in \[-pi/2, pi/2\].
    asin(x);
    /// Arccosine, radians in [0, pi].
    acos(x);
    /// Arctangent, radians in (-pi/2, pi/2).
    atan(x);
    /// Four-quadrant arctangent of `y / x`, radians in \[-pi, pi\].
    atan2(y, x);
    /// `x` raised to the power `y`.
    pow(x, y);
    /// Hyperbolic sine.
    sinh(x);
    /// Hyperbolic cosine.
    cosh(x);
    /// `exp(x) - 1`, accurate for small `x`.
    expm1(x);
    /// `ln(1 + x)`, accurate for small `x`.
    log1p(x);
    /// Cube root.
    cbrt(x);
    /// Euclidean distance `sqrt(x^2 + y^2)` without undue overflow.
    hypot(x, y);
}

macro_rules! libm_f32 {
    ($($(#[$doc:meta])* $name:ident($($arg:ident),+);)+) => {$(
        $(#[$doc])*
        #[inline]
        #[must_use]
        pub fn $name($($arg: f32),+) -> f32 {
            libm::$name($($arg),+)
        }
    )+};
}

libm_f32! {
    /// Tangent (radians), `f32`.
    tanf(x);
    /// Arcsine (radians), `f32`.
    asinf(x);
    /// Arccosine (radians), `f32`.
    acosf(x);
    /// Arctangent (radians), `f32`.
    atanf(x);
    /// Power, `f32`.
    powf(x, y);
    /// Hyperbolic sine, `f32`.
    sinhf(x);
    /// Hyperbolic cosine, `f32`.
    coshf(x);
    /// `exp(x) - 1`, `f32`.
    expm1f(x);
    /// `ln(1 + x)`, `f32`.
    log1pf(x);
    /// Cube root, `f32`.
    cbrtf(x);
    /// Euclidean distance, `f32`.
    hypotf(x, y);
}

/// Measured bound of micromath's `sqrt` relative error over [1e-6, 1e8] (see tests).
pub const MICROMATH_SQRT_REL: f64 = 6.5e-2;
/// Measured bound of micromath's `exp` relative error over \[-20, 20\].
pub const MICROMATH_EXP_REL: f64 = 2.5e-3;
/// Measured bound of micromath's `ln` absolute error over [1e-6, 1e8].
pub const MICROMATH_LN_ABS: f64 = 0.12;
/// Measured bound of micromath's `sin`/`cos` absolute error over \[-2 pi, 2 pi\].
pub const MICROMATH_TRIG_ABS: f64 = 1.2e-3;
/// Measured bound of micromath's `atan2` absolute error \[rad\].
pub const MICROMATH_ATAN2_ABS: f64 = 3e-3;

/// Square root, `f32`. libm: within 1 ulp. micromath: see [`MICROMATH_SQRT_REL`].
#[inline]
#[must_use]
pub fn sqrtf(x: f32) -> f32 {
    #[cfg(feature = "micromath")]
    {
        micromath::F32Ext::sqrt(x)
    }
    #[cfg(not(feature = "micromath"))]
    {
        libm::sqrtf(x)
    }
}

/// Square root, `f32`, correctly rounded, in single-precision and 32-bit integer arithmetic
/// (for the Vinh closed forms' inner loops): libm's `sqrtf` is a bit-by-bit software routine
/// (84 instructions per call on the Cortex-M4F, whose FPU `vsqrt` stable Rust cannot reach
/// without `unsafe`); this kernel takes an inverse-square-root estimate from the exponent
/// bits, two Newton steps on it and one correction on the square root itself (within 1 ulp),
/// then rounds exactly: the result moves to a neighbour when `x` lies beyond the square of
/// the midpoint between them (an exact integer comparison, `beyond_midpoint`). So it is
/// bit for bit libm's correctly rounded `sqrtf` (`tests::sqrtf_kernel_is_libm_bit_for_bit`),
/// and a Cortex-M4F, a Cortex-M3 and the host replaying either compute the same bits. Zero,
/// subnormal, infinite, NaN and negative inputs go to [`sqrtf`] (so negative -> NaN, as
/// libm). On ARM without a hardware FPU (soft-float ABI: the Cortex-M3) every float
/// operation of the kernel is a library call and libm's integer routine is cheaper: there
/// this is [`sqrtf`] (measured: the glide benchmark 48.8 k with libm against 58.6 k with
/// the kernel), with the same results.
#[inline]
#[must_use]
pub fn sqrtf_kernel(x: f32) -> f32 {
    if cfg!(all(target_arch = "arm", not(target_abi = "eabihf")))
        || !(f32::MIN_POSITIVE..=f32::MAX).contains(&x)
    {
        return sqrtf(x);
    }
    // 1/sqrt(x) to about 3.4 % from the bits (x is normal and positive: the shift cannot
    // borrow), two Newton steps (3.4e-2 -> 1.7e-3 -> 4.5e-6), then s = x y with one Newton
    // step on s^2 = x, which brings the square root within 1 ulp.
    let y0 = f32::from_bits(0x5f37_5a86_u32.wrapping_sub(x.to_bits() >> 1));
    let hx = 0.5 * x;
    let y1 = y0 * (1.5 - hx * y0 * y0);
    let y2 = y1 * (1.5 - hx * y1 * y1);
    let s = x * y2;
    let s = s + 0.5 * y2 * (x - s * s);
    // Exact rounding. sqrt(x) of a normal x is normal (>= 1.08e-19), so s and its
    // neighbours are normal positive floats and their bit patterns are consecutive. The sign
    // of the rounded residual x - s^2 says on which side of s the root lies whenever it is
    // farther than half an ulp (the only case in which s is not the answer), so one exact
    // midpoint comparison decides (checked on every normal float: `sqrtf_kernel_exhaustive`).
    let bits = s.to_bits();
    let answer = if x - s * s >= 0.0 {
        beyond_midpoint(x, s).map(|up| if up { bits.wrapping_add(1) } else { bits })
    } else {
        let below = bits.wrapping_sub(1);
        beyond_midpoint(x, f32::from_bits(below)).map(|up| if up { bits } else { below })
    };
    // `None` is not reached for normal x (the exponents always align); libm decides then.
    answer.map_or_else(|| sqrtf(x), f32::from_bits)
}

/// Whether `x > m^2` for `m` the midpoint between the normal positive `t` and the next
/// float up, compared exactly in integers (`None` when the exponents do not align as they do
/// for `t` within a few ulp of `sqrt(x)`). With `t = mt 2^(et-150)` (`mt` the 24-bit
/// significand, `et` the biased exponent), `m = (2 mt + 1) 2^(et-151)` (also across a binade
/// boundary) and `m^2 = (2 mt + 1)^2 2^(2 et - 302)`, against `x = mx 2^(ex-150)`: compare
/// `(2 mt + 1)^2` (< 2^50) with `mx 2^(ex - 2 et + 152)`. Equality cannot occur (an odd
/// square of at least 49 bits is no float), so `false` means `x < m^2`.
#[inline]
fn beyond_midpoint(x: f32, t: f32) -> Option<bool> {
    let (bx, bt) = (x.to_bits(), t.to_bits());
    let mx = u64::from((bx & 0x007f_ffff) | 0x0080_0000);
    let mt = (bt & 0x007f_ffff) | 0x0080_0000;
    let k = i64::from(bx >> 23) - 2 * i64::from(bt >> 23) + 152;
    // mx < 2^24, so mx << k stays below 2^64 for k <= 39; in practice k is 23 to 26.
    let k = u32::try_from(k).ok().filter(|k| *k <= 39)?;
    let odd = u64::from(2 * mt + 1);
    Some(mx << k > odd * odd)
}

/// Natural exponential, `f32`. micromath: see [`MICROMATH_EXP_REL`].
#[inline]
#[must_use]
pub fn expf(x: f32) -> f32 {
    #[cfg(feature = "micromath")]
    {
        micromath::F32Ext::exp(x)
    }
    #[cfg(not(feature = "micromath"))]
    {
        libm::expf(x)
    }
}

/// Natural logarithm, `f32`. micromath: see [`MICROMATH_LN_ABS`].
#[inline]
#[must_use]
pub fn logf(x: f32) -> f32 {
    #[cfg(feature = "micromath")]
    {
        micromath::F32Ext::ln(x)
    }
    #[cfg(not(feature = "micromath"))]
    {
        libm::logf(x)
    }
}

/// Sine (radians), `f32`. micromath: see [`MICROMATH_TRIG_ABS`].
#[inline]
#[must_use]
pub fn sinf(x: f32) -> f32 {
    #[cfg(feature = "micromath")]
    {
        micromath::F32Ext::sin(x)
    }
    #[cfg(not(feature = "micromath"))]
    {
        libm::sinf(x)
    }
}

/// Cosine (radians), `f32`. micromath: see [`MICROMATH_TRIG_ABS`].
#[inline]
#[must_use]
pub fn cosf(x: f32) -> f32 {
    #[cfg(feature = "micromath")]
    {
        micromath::F32Ext::cos(x)
    }
    #[cfg(not(feature = "micromath"))]
    {
        libm::cosf(x)
    }
}

/// Four-quadrant arctangent of `y / x` (radians), `f32`. micromath: see
/// [`MICROMATH_ATAN2_ABS`] (compared modulo 2 pi).
#[inline]
#[must_use]
pub fn atan2f(y: f32, x: f32) -> f32 {
    #[cfg(feature = "micromath")]
    {
        micromath::F32Ext::atan2(y, x)
    }
    #[cfg(not(feature = "micromath"))]
    {
        libm::atan2f(y, x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `sqrtf_kernel` against libm's correctly rounded `sqrtf`: bit for bit over 2e5
    /// log-spaced points of the whole normal range, around every power of two (where the bit
    /// estimate is worst), over every float of [1, 4) in steps of 7 ulp (every significand
    /// pattern class of both exponent parities) and on the special inputs (which go to
    /// [`sqrtf`]: libm, not micromath, hence the feature gate, as for the closed forms' other
    /// kernels).
    #[test]
    #[cfg(not(feature = "micromath"))]
    fn sqrtf_kernel_is_libm_bit_for_bit() {
        let mut worst = 0_u32;
        let mut check = |x: f32| {
            let (a, b) = (sqrtf_kernel(x), libm::sqrtf(x));
            let d = a.to_bits().abs_diff(b.to_bits());
            worst = worst.max(d);
        };
        for i in 0..200_000_u32 {
            let e = -125.9 + 253.8 * f64::from(i) / 200_000.0;
            check(libm::exp2(e) as f32);
        }
        for p in -125_i32..127 {
            let x = libm::exp2f(p as f32);
            for d in [-2_i32, -1, 0, 1, 2] {
                check(f32::from_bits(x.to_bits().wrapping_add_signed(d)));
            }
        }
        let mut b = 1.0_f32.to_bits();
        while b < 4.0_f32.to_bits() {
            check(f32::from_bits(b));
            b += 7;
        }
        assert_eq!(worst, 0, "{worst} ulp");
        assert_eq!(sqrtf_kernel(0.0), 0.0);
        assert!(sqrtf_kernel(-1.0).is_nan());
        assert!(sqrtf_kernel(f32::NAN).is_nan());
        assert_eq!(sqrtf_kernel(f32::INFINITY), f32::INFINITY);
        assert_eq!(sqrtf_kernel(1e-40), libm::sqrtf(1e-40));
    }

    /// Every positive normal float (2.1e9 of them): `sqrtf_kernel` is libm's `sqrtf` bit for
    /// bit. About a minute in release, so ignored; run by hand:
    /// `cargo test -p guidance-core --release --lib sqrtf_kernel_exhaustive -- --ignored`.
    #[test]
    #[ignore = "exhaustive, about a minute in release"]
    #[cfg(not(feature = "micromath"))]
    fn sqrtf_kernel_exhaustive() {
        let mut differ = 0_u64;
        for b in f32::MIN_POSITIVE.to_bits()..=f32::MAX.to_bits() {
            let x = f32::from_bits(b);
            differ += u64::from(sqrtf_kernel(x).to_bits() != libm::sqrtf(x).to_bits());
        }
        assert_eq!(differ, 0);
    }

    fn rel(a: f64, b: f64) -> f64 {
        ((a - b) / b).abs()
    }

    /// The f32 routing agrees with the f64 reference within the documented bounds over the
    /// guidance domain. Without `micromath` the bounds are libm's (tight); with it, the
    /// documented micromath bounds. Prints the measured maxima (`--nocapture`).
    #[test]
    fn micromath_bounds() {
        let (sq, ex, ln, tr, at) = if cfg!(feature = "micromath") {
            (
                MICROMATH_SQRT_REL,
                MICROMATH_EXP_REL,
                MICROMATH_LN_ABS,
                MICROMATH_TRIG_ABS,
                MICROMATH_ATAN2_ABS,
            )
        } else {
            (1e-6, 1e-6, 1e-6, 1e-6, 1e-6)
        };
        let mut worst = [0.0f64; 6];
        for i in 0..=20_000 {
            let t = f64::from(i) / 20_000.0;
            let x = 1e-6 * libm::pow(1e14, t);
            let xf = f64::from(x as f32);
            let e = -20.0 + 40.0 * t;
            let ef = f64::from(e as f32);
            let a = -2.0 * core::f64::consts::PI + 4.0 * core::f64::consts::PI * t;
            let af = f64::from(a as f32);
            let (yy, xx) = (sin(af), cos(af) * 2.0);
            let errs = [
                rel(f64::from(sqrtf(xf as f32)), sqrt(xf)),
                (f64::from(logf(xf as f32)) - log(xf)).abs(),
                rel(f64::from(expf(ef as f32)), exp(ef)),
                (f64::from(sinf(af as f32)) - sin(af)).abs(),
                (f64::from(cosf(af as f32)) - cos(af)).abs(),
                {
                    // Compare angles modulo 2 pi (back ends may differ in branch).
                    let d = f64::from(atan2f(yy as f32, xx as f32))
                        - atan2(f64::from(yy as f32), f64::from(xx as f32));
                    let tau = 2.0 * core::f64::consts::PI;
                    (d - tau * libm::round(d / tau)).abs()
                },
            ];
            for (w, e) in worst.iter_mut().zip(errs) {
                *w = w.max(e);
            }
        }
        extern crate std;
        std::println!(
            "max errors: sqrt rel {:e}, ln abs {:e}, exp rel {:e}, sin abs {:e}, cos abs {:e}, atan2 abs {:e}",
            worst[0],
            worst[1],
            worst[2],
            worst[3],
            worst[4],
            worst[5]
        );
        assert!(worst[0] < sq && worst[1] < ln && worst[2] < ex, "{worst:?}");
        assert!(worst[3] < tr && worst[4] < tr && worst[5] < at, "{worst:?}");
    }
}
