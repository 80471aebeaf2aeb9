//! Exact hypervolume of a set of points (minimisation) with respect to a reference point,
//! each point's exclusive contribution, and the least contributor.
//!
//! Conventions:
//! * every objective is minimised; the hypervolume is the Lebesgue measure of the region
//!   dominated by the points and bounded above by the reference point `r`;
//! * a point that does not strictly dominate `r` (some coordinate `>= r`) dominates no
//!   volume: it contributes 0 and is otherwise ignored; weakly dominated points and duplicates
//!   change nothing (a duplicated point's copies each have exclusive contribution 0);
//! * an empty set has hypervolume 0;
//! * a zero-dimensional reference point, non-finite coordinates and points whose dimension
//!   differs from the reference point's are [`HypervolumeError`]s naming the point and
//!   coordinate. Nothing panics and no NaN is returned.
//!
//! Algorithms (see docs/reference/hypervolume.md): 1-D and 2-D by sorting (O(n log n)); 3-D by the HV3D
//! dimension sweep with a bit-set staircase (O(n log n)); 4-D by sweeping the fourth
//! coordinate and adding each point's exclusive 3-D contribution, computed locally (O(n^2));
//! 5-D and more by WFG slicing the last objective down to the 4-D case. Exclusive
//! contributions: a sweep in 2-D and a strip sweep in 3-D (both O(n log n)), and
//! `vol(box) - HV(limit set)` per point otherwise.
//!
//! Layout: the dimension dispatch (`hypervolume_of`) lives in `wfg`, the one kernel that
//! recurses through it, so no kernel imports this facade; the kernels share the clamp of
//! `num`, a leaf.

mod contrib3d;
mod contributions;
mod error;
mod hv2d;
mod hv3d;
mod hv4d;
mod num;
mod stair;
mod staircase;
mod wfg;

pub use contributions::{contributions, least_contributor};
pub use error::HypervolumeError;
use wfg::hypervolume_of;

/// The exact hypervolume of `points` with respect to `reference` (minimisation).
///
/// Points that do not strictly dominate `reference` contribute 0; an empty set gives 0.
///
/// # Errors
/// [`HypervolumeError`] for a zero-dimensional or non-finite reference point, a point with
/// the wrong number of coordinates or a non-finite coordinate, or a volume overflowing `f64`.
///
/// ```
/// use host_sim::optim::hypervolume::hypervolume;
/// // Two points in 2-D w.r.t. (4, 4): the union of [1, 4] x [3, 4] (area 3) and
/// // [2, 4] x [1, 4] (area 6), which overlap in [2, 4] x [3, 4] (area 2).
/// let hv = hypervolume(&[[1.0, 3.0], [2.0, 1.0]], &[4.0, 4.0])?;
/// assert_eq!(hv, 3.0 + 6.0 - 2.0);
/// # Ok::<(), host_sim::optim::hypervolume::HypervolumeError>(())
/// ```
pub fn hypervolume<P: AsRef<[f64]>>(
    points: &[P],
    reference: &[f64],
) -> Result<f64, HypervolumeError> {
    let (flat, _) = prepare(points, reference)?;
    finite(hypervolume_of(&flat, reference.len(), reference))
}

/// Check the inputs and gather the points that strictly dominate the reference point,
/// row-major, with their original indices.
fn prepare<P: AsRef<[f64]>>(
    points: &[P],
    reference: &[f64],
) -> Result<(Vec<f64>, Vec<usize>), HypervolumeError> {
    let d = reference.len();
    if d == 0 {
        return Err(HypervolumeError::ZeroDimension);
    }
    if let Some((coordinate, &value)) = reference.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(HypervolumeError::NonFiniteReference { coordinate, value });
    }
    let mut flat = Vec::with_capacity(points.len() * d);
    let mut index = Vec::with_capacity(points.len());
    for (i, p) in points.iter().enumerate() {
        let p = p.as_ref();
        if p.len() != d {
            return Err(HypervolumeError::DimensionMismatch {
                index: i,
                expected: d,
                found: p.len(),
            });
        }
        if let Some((coordinate, &value)) = p.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(HypervolumeError::NonFinitePoint {
                index: i,
                coordinate,
                value,
            });
        }
        if p.iter().zip(reference).all(|(a, r)| a < r) {
            flat.extend_from_slice(p);
            index.push(i);
        }
    }
    Ok((flat, index))
}

/// A finite result, or [`HypervolumeError::Overflow`].
fn finite(v: f64) -> Result<f64, HypervolumeError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(HypervolumeError::Overflow { value: v })
    }
}
