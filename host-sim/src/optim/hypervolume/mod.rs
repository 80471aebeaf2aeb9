//! Exact hypervolume of a set of points (minimisation) with respect to a reference point.
//!
//! replaced by the hv branch: this is a small, simple and correct placeholder (2-D sweep,
//! slicing recursion above) with the agreed API, so that the optimisers compile and test
//! before the fast implementation merges. Points that do not strictly dominate the reference
//! point contribute nothing.

use thiserror::Error;

/// Bad hypervolume input. (replaced by the hv branch)
#[derive(Clone, Debug, PartialEq, Error)]
pub enum HypervolumeError {
    /// Empty reference point.
    #[error("hypervolume: the reference point is empty")]
    EmptyReference,
    /// A point of the wrong dimension.
    #[error("hypervolume: point {index} has {got} objectives, the reference point {expected}")]
    Dimension {
        /// Point index.
        index: usize,
        /// Reference dimension.
        expected: usize,
        /// Point dimension.
        got: usize,
    },
    /// A NaN or infinite coordinate.
    #[error("hypervolume: point {index} has a non-finite value")]
    NonFinite {
        /// Point index (`usize::MAX` for the reference point).
        index: usize,
    },
}

fn checked<P: AsRef<[f64]>>(
    points: &[P],
    reference: &[f64],
) -> Result<Vec<Vec<f64>>, HypervolumeError> {
    if reference.is_empty() {
        return Err(HypervolumeError::EmptyReference);
    }
    if reference.iter().any(|r| !r.is_finite()) {
        return Err(HypervolumeError::NonFinite { index: usize::MAX });
    }
    let mut kept = Vec::new();
    for (index, p) in points.iter().enumerate() {
        let p = p.as_ref();
        if p.len() != reference.len() {
            return Err(HypervolumeError::Dimension {
                index,
                expected: reference.len(),
                got: p.len(),
            });
        }
        if p.iter().any(|v| !v.is_finite()) {
            return Err(HypervolumeError::NonFinite { index });
        }
        if p.iter().zip(reference).all(|(a, r)| a < r) {
            kept.push(p.to_vec());
        }
    }
    Ok(kept)
}

fn hv_rec(mut pts: Vec<Vec<f64>>, reference: &[f64]) -> f64 {
    let d = reference.len();
    if pts.is_empty() {
        return 0.0;
    }
    if d == 1 {
        return pts.iter().map(|p| reference[0] - p[0]).fold(0.0, f64::max);
    }
    if d == 2 {
        pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
        let mut vol = 0.0;
        let mut y = reference[1];
        for p in &pts {
            if p[1] < y {
                vol += (reference[0] - p[0]) * (y - p[1]);
                y = p[1];
            }
        }
        return vol;
    }
    // Slice along the last objective.
    pts.sort_by(|a, b| a[d - 1].total_cmp(&b[d - 1]));
    let mut vol = 0.0;
    for k in 0..pts.len() {
        let top = if k + 1 < pts.len() {
            pts[k + 1][d - 1]
        } else {
            reference[d - 1]
        };
        let depth = top - pts[k][d - 1];
        if depth > 0.0 {
            let slice: Vec<Vec<f64>> = pts[..=k].iter().map(|p| p[..d - 1].to_vec()).collect();
            vol += depth * hv_rec(slice, &reference[..d - 1]);
        }
    }
    vol
}

/// Hypervolume dominated by `points` and bounded by `reference`.
///
/// # Errors
/// [`HypervolumeError`] for a wrong dimension or a non-finite value.
pub fn hypervolume<P: AsRef<[f64]>>(
    points: &[P],
    reference: &[f64],
) -> Result<f64, HypervolumeError> {
    Ok(hv_rec(checked(points, reference)?, reference))
}

/// Exclusive contribution of each point (0 for points that do not dominate the reference).
///
/// # Errors
/// As [`hypervolume`].
pub fn contributions<P: AsRef<[f64]>>(
    points: &[P],
    reference: &[f64],
) -> Result<Vec<f64>, HypervolumeError> {
    let total = hypervolume(points, reference)?;
    let all: Vec<&[f64]> = points.iter().map(AsRef::as_ref).collect();
    let mut out = Vec::with_capacity(all.len());
    for i in 0..all.len() {
        let mut rest = all.clone();
        rest.remove(i);
        out.push((total - hypervolume(&rest, reference)?).max(0.0));
    }
    Ok(out)
}

/// Index of the point with the smallest exclusive contribution (lowest index on ties).
///
/// # Errors
/// As [`hypervolume`]; [`HypervolumeError::EmptyReference`] also for an empty point set.
pub fn least_contributor<P: AsRef<[f64]>>(
    points: &[P],
    reference: &[f64],
) -> Result<usize, HypervolumeError> {
    let c = contributions(points, reference)?;
    let mut best: Option<(usize, f64)> = None;
    for (i, v) in c.into_iter().enumerate() {
        if best.is_none_or(|(_, b)| v < b) {
            best = Some((i, v));
        }
    }
    best.map(|(i, _)| i).ok_or(HypervolumeError::EmptyReference)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placeholder_small_cases() {
        let pts = [[1.0, 2.0], [2.0, 1.0]];
        assert_eq!(hypervolume(&pts, &[3.0, 3.0]).unwrap(), 3.0);
        let c = contributions(&pts, &[3.0, 3.0]).unwrap();
        assert_eq!(c, vec![1.0, 1.0]);
        let cube = [[0.0, 0.0, 0.0]];
        assert_eq!(hypervolume(&cube, &[1.0, 2.0, 3.0]).unwrap(), 6.0);
        let p3 = [[0.0, 1.0, 1.0], [1.0, 0.0, 1.0], [1.0, 1.0, 0.0]];
        // Three boxes of volume 2 whose pairwise and triple intersections are the cube
        // [1,2]^3: inclusion-exclusion gives 6 - 3 + 1.
        assert!((hypervolume(&p3, &[2.0, 2.0, 2.0]).unwrap() - (6.0 - 3.0 + 1.0)).abs() < 1e-12);
        assert_eq!(hypervolume(&[[5.0, 0.0]], &[3.0, 3.0]).unwrap(), 0.0);
    }
}
