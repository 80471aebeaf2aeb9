//! Scalar abstraction: the guidance path runs in `f32`, `f64` or fixed point.
//!
//! * [`Scalar`] is what the guidance path needs (arithmetic, comparison, conversion, finiteness).
//!   It is implemented for `f32`, `f64` and [`Fixed`].
//! * [`Real`] adds the transcendental functions the closed forms need; `f32` and `f64` only.
//!
//! [`Fixed`] wraps `fixed::types::I32F32` (range +-2.1e9, resolution 2.3e-10) with
//! *saturating* arithmetic: no operation on it can panic or wrap, and division by zero
//! saturates to the signed extreme. It needs no FPU and runs on Cortex-M0/M3.
//!
//! Range notes for `Fixed`: the guidance path only handles radii (< 1e8 m), speeds,
//! normalised energy, time (< 1e6 s) and angles; the gravitational parameter itself never
//! appears (see [`crate::energy`]), so nothing on the path leaves the I32F32 range.

use core::fmt::Debug;
use core::ops::{Add, Div, Mul, Neg, Sub};
use fixed::types::I32F32;

/// Arithmetic the guidance path needs. Implemented for `f32`, `f64` and [`Fixed`].
///
/// Operators on floats follow IEEE 754; on [`Fixed`] they saturate. Callers validate inputs
/// with [`Scalar::is_finite`] at the boundary, so NaN never reaches the operators.
pub trait Scalar:
    Copy
    + PartialOrd
    + Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// Largest finite value.
    const MAX: Self;
    /// Convert from `f64`, saturating at the type's range; NaN converts to zero (callers check
    /// finiteness first, see [`Scalar::from_f64_checked`]).
    fn from_f64(v: f64) -> Self;
    /// Convert from `f64`, returning `None` for a non-finite value or one outside the range.
    fn from_f64_checked(v: f64) -> Option<Self>;
    /// Convert a count (a tick index), saturating at the type's range. Exact for `f64` and
    /// `Fixed` below 2^31; `f32` rounds above 2^24. [`Fixed`] converts without going through
    /// `f64` (which is soft float on an FPU-less core).
    #[inline]
    fn from_u32(v: u32) -> Self {
        Self::from_f64(f64::from(v))
    }
    /// Convert to `f64` (exact for `f32`, `f64` and `Fixed`).
    fn to_f64(self) -> f64;
    /// False for NaN and infinities (always true for [`Fixed`]).
    fn is_finite(self) -> bool;
    /// Square root; negative input returns zero. Used by monitors and energy only.
    fn sqrt(self) -> Self;

    /// Absolute value.
    #[inline]
    fn abs(self) -> Self {
        if self < Self::ZERO { -self } else { self }
    }
    /// The smaller of two values (NaN-free inputs assumed).
    #[inline]
    fn min(self, other: Self) -> Self {
        if other < self { other } else { self }
    }
    /// The larger of two values (NaN-free inputs assumed).
    #[inline]
    fn max(self, other: Self) -> Self {
        if other > self { other } else { self }
    }
    /// Clamp into `[lo, hi]` (requires `lo <= hi`; if not, returns `lo`).
    #[inline]
    fn clamp(self, lo: Self, hi: Self) -> Self {
        if self < lo {
            lo
        } else if self > hi {
            if hi < lo { lo } else { hi }
        } else {
            self
        }
    }
    /// Half the value.
    #[inline]
    fn half(self) -> Self {
        self / (Self::ONE + Self::ONE)
    }
}

/// Transcendental functions needed by the closed forms (`f32`, `f64`), routed through
/// [`crate::math`].
pub trait Real: Scalar {
    /// pi.
    const PI: Self;
    /// Machine epsilon.
    const EPSILON: Self;
    /// Natural exponential.
    fn exp(self) -> Self;
    /// Natural logarithm.
    fn ln(self) -> Self;
    /// Sine (radians).
    fn sin(self) -> Self;
    /// Cosine (radians).
    fn cos(self) -> Self;
    /// Tangent (radians).
    fn tan(self) -> Self;
    /// Arcsine (radians).
    fn asin(self) -> Self;
    /// Arccosine (radians).
    fn acos(self) -> Self;
    /// Arctangent (radians).
    fn atan(self) -> Self;
    /// Four-quadrant arctangent of `self / x` (radians).
    fn atan2(self, x: Self) -> Self;
    /// Power.
    fn powf(self, y: Self) -> Self;
    /// Square root with NaN for negative input (unlike [`Scalar::sqrt`]); callers check domain.
    fn sqrt_raw(self) -> Self;
    /// Square root for the closed forms' inner loops, NaN for negative input like
    /// [`Real::sqrt_raw`]: `f64` libm; `f32` [`crate::math::sqrtf_kernel`] (single-precision
    /// arithmetic, bit for bit libm's correctly rounded `sqrtf`, about half its cost on the
    /// Cortex-M4F).
    fn sqrt_fast(self) -> Self;
}

macro_rules! float_scalar {
    ($t:ty, $sqrt:path, $sqrt_fast:path, $exp:path, $ln:path, $sin:path, $cos:path, $tan:path, $asin:path,
     $acos:path, $atan:path, $atan2:path, $pow:path) => {
        impl Scalar for $t {
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const MAX: Self = <$t>::MAX;
            #[inline]
            #[allow(clippy::cast_precision_loss)]
            fn from_u32(v: u32) -> Self {
                // One rounding, as `(v as f64) as f32`, without the f64 step (soft float on a
                // single-precision FPU).
                v as $t
            }
            #[inline]
            #[allow(clippy::cast_possible_truncation)]
            fn from_f64(v: f64) -> Self {
                if v.is_nan() { 0.0 } else { v as $t }
            }
            #[inline]
            #[allow(clippy::cast_possible_truncation)]
            fn from_f64_checked(v: f64) -> Option<Self> {
                let x = v as $t;
                if x.is_finite() { Some(x) } else { None }
            }
            #[inline]
            fn to_f64(self) -> f64 {
                f64::from(self)
            }
            #[inline]
            fn is_finite(self) -> bool {
                <$t>::is_finite(self)
            }
            #[inline]
            fn sqrt(self) -> Self {
                if self > 0.0 { $sqrt(self) } else { 0.0 }
            }
        }
        impl Real for $t {
            const PI: Self = core::f64::consts::PI as $t;
            const EPSILON: Self = <$t>::EPSILON;
            #[inline]
            fn exp(self) -> Self {
                $exp(self)
            }
            #[inline]
            fn ln(self) -> Self {
                $ln(self)
            }
            #[inline]
            fn sin(self) -> Self {
                $sin(self)
            }
            #[inline]
            fn cos(self) -> Self {
                $cos(self)
            }
            #[inline]
            fn tan(self) -> Self {
                $tan(self)
            }
            #[inline]
            fn asin(self) -> Self {
                $asin(self)
            }
            #[inline]
            fn acos(self) -> Self {
                $acos(self)
            }
            #[inline]
            fn atan(self) -> Self {
                $atan(self)
            }
            #[inline]
            fn atan2(self, x: Self) -> Self {
                $atan2(self, x)
            }
            #[inline]
            fn powf(self, y: Self) -> Self {
                $pow(self, y)
            }
            #[inline]
            fn sqrt_raw(self) -> Self {
                $sqrt(self)
            }
            #[inline]
            fn sqrt_fast(self) -> Self {
                $sqrt_fast(self)
            }
        }
    };
}

use crate::math as m;
float_scalar!(
    f64,
    m::sqrt,
    m::sqrt,
    m::exp,
    m::log,
    m::sin,
    m::cos,
    m::tan,
    m::asin,
    m::acos,
    m::atan,
    m::atan2,
    m::pow
);
float_scalar!(
    f32,
    m::sqrtf,
    m::sqrtf_kernel,
    m::expf,
    m::logf,
    m::sinf,
    m::cosf,
    m::tanf,
    m::asinf,
    m::acosf,
    m::atanf,
    m::atan2f,
    m::powf
);

/// Fixed-point scalar: `I32F32` with saturating arithmetic (no panics, no wrap-around).
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd, Eq, Ord, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Fixed(pub I32F32);

impl Fixed {
    /// From the raw two's-complement bits of the I32F32 value (value = bits / 2^32).
    #[must_use]
    pub const fn from_bits(bits: i64) -> Self {
        Fixed(I32F32::from_bits(bits))
    }
    /// The raw two's-complement bits of the I32F32 value (value = bits / 2^32).
    #[must_use]
    pub const fn to_bits(self) -> i64 {
        self.0.to_bits()
    }
}

impl Add for Fixed {
    type Output = Self;
    #[inline]
    fn add(self, rhs: Self) -> Self {
        Fixed(self.0.saturating_add(rhs.0))
    }
}
impl Sub for Fixed {
    type Output = Self;
    #[inline]
    fn sub(self, rhs: Self) -> Self {
        Fixed(self.0.saturating_sub(rhs.0))
    }
}
impl Mul for Fixed {
    type Output = Self;
    #[inline]
    fn mul(self, rhs: Self) -> Self {
        Fixed(self.0.saturating_mul(rhs.0))
    }
}
impl Div for Fixed {
    type Output = Self;
    /// Saturating division; division by zero gives the signed extreme (zero for `0 / 0`).
    #[inline]
    fn div(self, rhs: Self) -> Self {
        match self.0.checked_div(rhs.0) {
            Some(q) => Fixed(q),
            None => {
                if self.0 == I32F32::ZERO {
                    Fixed(I32F32::ZERO)
                } else if (self.0 < I32F32::ZERO) == (rhs.0 < I32F32::ZERO) {
                    Fixed(I32F32::MAX)
                } else {
                    Fixed(I32F32::MIN)
                }
            }
        }
    }
}
impl Neg for Fixed {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Fixed(self.0.saturating_neg())
    }
}

impl Scalar for Fixed {
    const ZERO: Self = Fixed(I32F32::ZERO);
    const ONE: Self = Fixed(I32F32::ONE);
    const MAX: Self = Fixed(I32F32::MAX);
    #[inline]
    fn from_u32(v: u32) -> Self {
        Fixed(I32F32::saturating_from_num(v))
    }
    #[inline]
    fn from_f64(v: f64) -> Self {
        if v.is_nan() {
            Self::ZERO
        } else {
            Fixed(I32F32::saturating_from_num(v))
        }
    }
    #[inline]
    fn from_f64_checked(v: f64) -> Option<Self> {
        if v.is_finite() {
            I32F32::checked_from_num(v).map(Fixed)
        } else {
            None
        }
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self.0.to_num::<f64>()
    }
    #[inline]
    fn is_finite(self) -> bool {
        true
    }
    #[inline]
    fn sqrt(self) -> Self {
        if self.0 <= I32F32::ZERO {
            Self::ZERO
        } else {
            // Integer square root via the unsigned bit representation: no FPU needed.
            // sqrt(b / 2^32) = sqrt(b * 2^32) / 2^32, computed on u128 to keep all bits.
            let bits = self.0.to_bits().unsigned_abs();
            let root = isqrt_u128(u128::from(bits) << 32);
            Fixed(I32F32::from_bits(i64::try_from(root).unwrap_or(i64::MAX)))
        }
    }
}

/// Integer square root (floor) of a `u128`, by bitwise Newton-free digit recurrence.
fn isqrt_u128(n: u128) -> u128 {
    let mut x = n;
    let mut result: u128 = 0;
    let mut bit: u128 = 1 << 126;
    while bit > n {
        bit >>= 2;
    }
    while bit != 0 {
        if x >= result + bit {
            x -= result + bit;
            result = (result >> 1) + bit;
        } else {
            result >>= 1;
        }
        bit >>= 2;
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `from_u32` agrees with the `f64` route (exact for `f64` and `Fixed`; rounded for `f32`).
    #[test]
    fn from_u32_matches_from_f64() {
        for v in [0, 1, 2, 1000, 1 << 24, (1 << 31) - 1, 1 << 31, u32::MAX] {
            assert_eq!(Fixed::from_u32(v), Fixed::from_f64(f64::from(v)), "{v}");
            assert_eq!(f64::from_u32(v), f64::from(v));
            assert_eq!(f32::from_u32(v), f32::from_f64(f64::from(v)));
        }
    }

    #[test]
    fn fixed_saturates_instead_of_panicking() {
        let big = Fixed::from_f64(2.0e9);
        assert_eq!((big + big), Fixed::MAX);
        assert_eq!((big * big), Fixed::MAX);
        assert_eq!(Fixed::ONE / Fixed::ZERO, Fixed::MAX);
        assert_eq!((-Fixed::ONE) / Fixed::ZERO, Fixed(I32F32::MIN));
        assert_eq!(Fixed::ZERO / Fixed::ZERO, Fixed::ZERO);
        assert_eq!(Fixed::from_f64(f64::NAN), Fixed::ZERO);
        assert!(Fixed::from_f64_checked(f64::INFINITY).is_none());
        assert!(Fixed::from_f64_checked(1e12).is_none());
    }

    #[test]
    fn fixed_sqrt_matches_f64() {
        for &v in &[1e-6, 0.25, 1.0, 2.0, 6.378e6, 1.21e8, 2.0e9] {
            let x = Fixed::from_f64(v);
            let s = x.sqrt().to_f64();
            // Reference: sqrt of the quantised input; the result is floor-rounded to 1 LSB.
            let r = crate::math::sqrt(x.to_f64());
            assert!((s - r).abs() <= 1e-9 * r.max(1.0), "{v}: {s} vs {r}");
        }
        assert_eq!(Fixed::from_f64(-4.0).sqrt(), Fixed::ZERO);
    }

    #[test]
    fn float_sqrt_of_negative_is_zero() {
        assert_eq!(Scalar::sqrt(-1.0_f64), 0.0);
        assert_eq!(Scalar::sqrt(-1.0_f32), 0.0);
    }
}
