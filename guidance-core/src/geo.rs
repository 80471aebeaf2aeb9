//! Great-circle geometry on a sphere: the one home of the central angle, the initial bearing
//! and the wrapping of angle differences (used by [`crate::replan`] for the range to go and the
//! odometer, and by [`crate::lateral`] for the heading error to the target).
//!
//! Angles in radians; latitudes geocentric; bearings clockwise from north. Every function
//! returns `None` for non-finite input or result and never panics.

use crate::scalar::Real;

/// Great-circle angle \[rad\] between two points (haversine form, accurate for small and large
/// angles), in `[0, pi]`; `None` if non-finite.
#[must_use]
pub fn central_angle<S: Real>(lat1: S, lon1: S, lat2: S, lon2: S) -> Option<S> {
    let two = S::ONE + S::ONE;
    let s_dlat = ((lat2 - lat1) / two).sin();
    let s_dlon = ((lon2 - lon1) / two).sin();
    let a = s_dlat * s_dlat + lat1.cos() * lat2.cos() * s_dlon * s_dlon;
    if !a.is_finite() {
        return None;
    }
    let a = a.clamp(S::ZERO, S::ONE);
    let theta = two * a.sqrt_raw().atan2((S::ONE - a).sqrt_raw());
    theta.is_finite().then_some(theta)
}

/// Initial bearing \[rad\] of the great circle from point 1 to point 2, clockwise from north,
/// in `(-pi, pi]`; `Some(0)` when the points coincide; `None` if non-finite.
#[must_use]
pub fn initial_bearing<S: Real>(lat1: S, lon1: S, lat2: S, lon2: S) -> Option<S> {
    let dlon = lon2 - lon1;
    let (c1, c2) = (lat1.cos(), lat2.cos());
    let y = dlon.sin() * c2;
    let x = c1 * lat2.sin() - lat1.sin() * c2 * dlon.cos();
    if !(x.is_finite() && y.is_finite()) {
        return None;
    }
    if x == S::ZERO && y == S::ZERO {
        return Some(S::ZERO);
    }
    let b = y.atan2(x);
    b.is_finite().then_some(b)
}

/// `angle` \[rad\] wrapped into `[-pi, pi]` (by `atan2(sin, cos)`, no loop); `None` if
/// non-finite.
#[must_use]
pub fn wrap_pi<S: Real>(angle: S) -> Option<S> {
    if !angle.is_finite() {
        return None;
    }
    let w = angle.sin().atan2(angle.cos());
    w.is_finite().then_some(w)
}

/// Along-track and cross-track angles \[rad\] of point `p` relative to the great circle from
/// `a` to `b`: along-track measured from `a` towards `b` (negative behind `a`), cross-track
/// positive to the right of the direction of travel. `None` if non-finite or `a == b`.
#[must_use]
pub fn along_cross_track<S: Real>(a: (S, S), b: (S, S), p: (S, S)) -> Option<(S, S)> {
    let d_ap = central_angle(a.0, a.1, p.0, p.1)?;
    let brg_ab = initial_bearing(a.0, a.1, b.0, b.1)?;
    let brg_ap = initial_bearing(a.0, a.1, p.0, p.1)?;
    if central_angle(a.0, a.1, b.0, b.1)? == S::ZERO {
        return None;
    }
    let xt = (d_ap.sin() * (brg_ap - brg_ab).sin())
        .clamp(-S::ONE, S::ONE)
        .asin();
    let cx = xt.cos();
    let at = if cx == S::ZERO {
        S::ZERO
    } else {
        (d_ap.cos() / cx).clamp(-S::ONE, S::ONE).acos()
    };
    // Behind the start point: the bearing to p points backwards.
    let at = if (brg_ap - brg_ab).cos() < S::ZERO && d_ap > S::ZERO {
        -at
    } else {
        at
    };
    (xt.is_finite() && at.is_finite()).then_some((at, xt))
}

#[cfg(test)]
mod tests {
    use super::*;

    const D: f64 = core::f64::consts::PI / 180.0;

    #[test]
    fn angles_and_bearings() {
        let q = central_angle(0.0, 0.0, 0.0, 90.0 * D).unwrap();
        assert!((q - 90.0 * D).abs() < 1e-12);
        assert!((initial_bearing(0.0, 0.0, 0.0, 10.0 * D).unwrap() - 90.0 * D).abs() < 1e-12);
        assert!((initial_bearing(0.0, 0.0, 10.0 * D, 0.0).unwrap()).abs() < 1e-12);
        assert_eq!(initial_bearing(0.1, 0.2, 0.1, 0.2), Some(0.0));
        assert!(central_angle(f64::NAN, 0.0, 0.0, 0.0).is_none());
        assert!(
            (wrap_pi(3.0 * core::f64::consts::PI / 2.0).unwrap() + core::f64::consts::PI / 2.0)
                .abs()
                < 1e-12
        );
    }

    #[test]
    fn along_and_cross_track_on_the_equator() {
        // Track east along the equator; a point 1 deg north at 5 deg east is left of track.
        let (at, xt) = along_cross_track((0.0, 0.0), (0.0, 20.0 * D), (1.0 * D, 5.0 * D)).unwrap();
        assert!((xt + 1.0 * D).abs() < 1e-9, "{xt}");
        assert!((at - 5.0 * D).abs() < 1e-3, "{at}");
        let (at, _) = along_cross_track((0.0, 0.0), (0.0, 20.0 * D), (0.0, -5.0 * D)).unwrap();
        assert!((at + 5.0 * D).abs() < 1e-9, "{at}");
    }
}
