//! Numeric helper shared by the hypervolume kernels and the exclusive contributions (a leaf
//! module: it imports none of them).

/// `x` clamped at 0 from below (rounding can leave a difference of equal volumes slightly
/// negative), keeping NaN: a NaN from overflowing intermediates (inf - inf) must reach
/// [`super::finite`] and become [`super::HypervolumeError::Overflow`], which `f64::max`
/// would hide.
#[inline]
pub(super) fn nonneg(x: f64) -> f64 {
    if x < 0.0 { 0.0 } else { x }
}
