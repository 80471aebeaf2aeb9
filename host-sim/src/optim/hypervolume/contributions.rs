//! Exclusive contributions (the volume dominated by one point and by no other) and the least
//! contributor.

use super::num::nonneg;
use super::wfg::{self, hypervolume_of};
use super::{HypervolumeError, contrib3d, finite, hv2d, prepare};

/// The exclusive contribution of each point, in the order given: the hypervolume lost when
/// that point alone is removed. Points that do not strictly dominate `reference`, weakly
/// dominated points and each copy of a duplicated point contribute 0.
///
/// # Errors
/// As [`super::hypervolume`].
pub fn contributions<P: AsRef<[f64]>>(
    points: &[P],
    reference: &[f64],
) -> Result<Vec<f64>, HypervolumeError> {
    let (flat, index) = prepare(points, reference)?;
    let d = reference.len();
    let inner = match d {
        1 => contributions_1d(&flat, reference[0]),
        2 => hv2d::contributions(&flat, reference),
        3 => contrib3d::contributions(&flat, reference),
        _ => contributions_generic(&flat, d, reference),
    };
    let mut out = vec![0.0; points.len()];
    for (c, i) in inner.into_iter().zip(index) {
        out[i] = finite(c)?;
    }
    Ok(out)
}

/// Index of the point with the smallest exclusive contribution (the first of equals).
///
/// # Errors
/// [`HypervolumeError::EmptySet`] for no points; otherwise as [`super::hypervolume`].
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
    best.map(|(i, _)| i).ok_or(HypervolumeError::EmptySet)
}

/// One objective: only a unique minimum contributes, up to the second smallest value.
fn contributions_1d(pts: &[f64], r: f64) -> Vec<f64> {
    let mut out = vec![0.0; pts.len()];
    let Some((imin, &min)) = pts.iter().enumerate().min_by(|a, b| a.1.total_cmp(b.1)) else {
        return out;
    };
    let second = pts
        .iter()
        .enumerate()
        .filter(|&(i, _)| i != imin)
        .map(|(_, &v)| v)
        .fold(r, f64::min);
    out[imin] = second - min;
    out
}

/// Any dimension: each point's box minus the hypervolume of the other points clipped to it.
fn contributions_generic(pts: &[f64], d: usize, r: &[f64]) -> Vec<f64> {
    let n = pts.len() / d;
    let mut out = vec![0.0; n];
    let mut limited = Vec::with_capacity(pts.len());
    for (i, o) in out.iter_mut().enumerate() {
        let p = &pts[d * i..d * i + d];
        limited.clear();
        let mut dominated = false;
        for j in (0..n).filter(|&j| j != i) {
            let q = &pts[d * j..d * j + d];
            let mut same = true;
            for c in 0..d {
                let v = p[c].max(q[c]);
                same &= v == p[c];
                limited.push(v);
            }
            if same {
                dominated = true;
                break;
            }
        }
        if dominated {
            continue;
        }
        let vol: f64 = p.iter().zip(r).map(|(a, b)| b - a).product();
        let nd = wfg::nondominated(&limited, d);
        *o = nonneg(vol - hypervolume_of(&nd, d, r));
    }
    out
}
