//! The one place float math is routed.
//!
//! Every transcendental function the crate uses is called through this module, by path, so the
//! choice of back end is made here and nowhere else. (With `std` in the dependency graph,
//! method syntax such as `x.sqrt()` would silently bind to `std`; do not use it in this crate.)
//!
//! * `f64` functions always use [`libm`] (correctly rounded to within 1 ulp for `sqrt`, and
//!   within a few ulp for the others, per libm's musl heritage).
//! * `f32` functions use [`libm`] by default. With the `micromath` feature, `sqrtf`, `expf`,
//!   `lnf`, `sinf`, `cosf` and `atan2f` route to `micromath`, which trades accuracy for speed on
//!   FPU-less cores. The bounds measured by this module's tests over the guidance domain
//!   (arguments listed in each test) are stated on each function below.
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
    /// Arcsine, radians in [-pi/2, pi/2].
    asin(x);
    /// Arccosine, radians in [0, pi].
    acos(x);
    /// Arctangent, radians in (-pi/2, pi/2).
    atan(x);
    /// Four-quadrant arctangent of `y / x`, radians in [-pi, pi].
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

/// Square root, `f32`. libm: within 1 ulp. micromath: relative error below 5e-3 for
/// x in [1e-6, 1e8] (measured by `tests::micromath_bounds`).
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

/// Natural exponential, `f32`. micromath: relative error below 1e-2 for x in [-20, 20].
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

/// Natural logarithm, `f32`. micromath: absolute error below 1e-2 for x in [1e-6, 1e8].
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

/// Sine (radians), `f32`. micromath: absolute error below 2e-3 for x in [-2 pi, 2 pi].
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

/// Cosine (radians), `f32`. micromath: absolute error below 2e-3 for x in [-2 pi, 2 pi].
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

/// Four-quadrant arctangent of `y / x` (radians), `f32`. micromath: absolute error below 5e-3.
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

    fn rel(a: f64, b: f64) -> f64 {
        ((a - b) / b).abs()
    }

    /// The f32 routing agrees with the f64 reference within the documented bounds over the
    /// guidance domain. Without `micromath` the bounds are libm's (tight); with it, the
    /// documented micromath bounds.
    #[test]
    fn micromath_bounds() {
        let (sq, ex, ln, tr, at) = if cfg!(feature = "micromath") {
            (5e-3, 1e-2, 1e-2, 2e-3, 5e-3)
        } else {
            (1e-6, 1e-6, 1e-6, 1e-6, 1e-6)
        };
        for i in 0..=1000 {
            let t = f64::from(i) / 1000.0;
            let x = 1e-6 * libm::pow(1e14, t);
            assert!(rel(f64::from(sqrtf(x as f32)), sqrt(x)) < sq, "sqrt {x}");
            assert!((f64::from(logf(x as f32)) - log(x)).abs() < ln, "ln {x}");
            let e = -20.0 + 40.0 * t;
            assert!(rel(f64::from(expf(e as f32)), exp(e)) < ex, "exp {e}");
            let a = -2.0 * core::f64::consts::PI + 4.0 * core::f64::consts::PI * t;
            assert!((f64::from(sinf(a as f32)) - sin(a)).abs() < tr, "sin {a}");
            assert!((f64::from(cosf(a as f32)) - cos(a)).abs() < tr, "cos {a}");
            let (y, x) = (sin(a), cos(a) * 2.0);
            assert!((f64::from(atan2f(y as f32, x as f32)) - atan2(y, x)).abs() < at);
        }
    }
}
