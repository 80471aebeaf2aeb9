//! The navigation interface: Cartesian position and velocity from a navigation system
//! (inertial or planet-fixed) -> the guidance variables of [`NavState`] (radius, planet-relative
//! speed, flight-path angle, heading, latitude, longitude), in `f32` or `f64`, with nalgebra
//! vectors (no_std, libm).
//!
//! Frames (right-handed, origin at the planet centre, z along the spin axis, north):
//! * planet-fixed: x through longitude 0 on the equator; velocity planet-relative;
//! * inertial: coincides with the planet-fixed frame at the rotation angle 0; the planet has
//!   turned by `theta = theta0 + omega t` about z at time t ([`InertialFrame`]); velocity
//!   inertial (the planet-relative velocity is `v - omega x r` in planet-fixed axes).
//!
//! Outputs and limits (never NaN; every output finite):
//! * radius |r| > 0 \[m\]; speed |v_rel| > 0 \[m/s\];
//! * latitude in \[-pi/2, pi/2\], longitude in (-pi, pi] \[rad\] (geocentric);
//! * flight-path angle in \[-pi/2, pi/2\] \[rad\], positive up;
//! * heading in \[0, 2 pi) \[rad\], clockwise from north. **Documented limit:** in vertical
//!   flight (horizontal speed below [`Real::EPSILON`] times the speed) the heading is
//!   undefined and is returned as 0 (north); the flight-path angle is then +-pi/2.
//! * typed errors: non-finite input ([`NavConvError::NonFinite`]), position at the centre
//!   ([`NavConvError::ZeroPosition`]), position on the spin axis within 4 epsilon of the radius
//!   (longitude and the local east/north axes undefined: [`NavConvError::Pole`]), no
//!   planet-relative motion ([`NavConvError::ZeroVelocity`]), or a result that overflows the
//!   scalar type (components beyond ~1e19 in `f32`: [`NavConvError::OutOfRange`]).
//!
//! The operations are those of host-sim's own conversion (`dynamics::cartesian_to_spherical`),
//! in the same order, with the core's libm routing ([`crate::math`]) and `sqrt(x^2 + y^2)` for
//! `hypot`; in `f64` the two agree to 4 epsilon (measured 4.0e-16 relative, 8.9e-16 rad).
//! `f32` accuracy against the `f64` conversion (host-sim `tests/it/navconv.rs`), u = 2^-24:
//! radius 4 u |r| (about 3 m at Earth); latitude, longitude 8 u (1 + |theta|) rad; speed
//! 8 u (|v_inertial| + omega |r|) (about 8e-3 m/s: absolute, so relative to a slow
//! planet-relative speed it grows); flight-path angle and heading that speed error over the
//! (horizontal) speed plus 8 u rad. Measured largest error over bound: 0.85 (radius) or less.

use nalgebra::Vector3;

use crate::nav::NavState;
use crate::scalar::Real;

/// Why a Cartesian state has no guidance variables.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum NavConvError {
    /// A component, the time or the frame parameters are NaN or infinite.
    NonFinite,
    /// The position is the planet centre.
    ZeroPosition,
    /// The position is on the spin axis: longitude and heading undefined.
    Pole,
    /// No planet-relative motion: flight-path angle and heading undefined.
    ZeroVelocity,
    /// A result overflowed the scalar type.
    OutOfRange,
}

impl core::fmt::Display for NavConvError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            Self::NonFinite => "non-finite Cartesian navigation input",
            Self::ZeroPosition => "position at the planet centre",
            Self::Pole => "position on the spin axis (longitude and heading undefined)",
            Self::ZeroVelocity => "no planet-relative velocity (flight-path angle undefined)",
            Self::OutOfRange => "navigation state overflows the scalar type",
        })
    }
}

impl core::error::Error for NavConvError {}

/// The inertial frame's relation to the planet-fixed one.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct InertialFrame<S> {
    /// Planet rotation rate omega about +z \[rad/s\].
    pub rotation_rate_rad_s: S,
    /// Rotation angle theta0 at time 0 \[rad\].
    pub angle_at_zero_rad: S,
}

/// Position and velocity in one of the frames of the module docs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CartesianNav<S: Real + nalgebra::Scalar> {
    /// Mission time \[s\].
    pub time_s: S,
    /// Position \[m\].
    pub position_m: Vector3<S>,
    /// Velocity \[m/s\] (inertial or planet-relative, per the function called).
    pub velocity_m_s: Vector3<S>,
}

fn finite<S: Real + nalgebra::Scalar>(v: &Vector3<S>) -> bool {
    v.x.is_finite() && v.y.is_finite() && v.z.is_finite()
}

/// Rotate `v` by `angle` about z, given (sin, cos) of the angle.
fn rot_z<S: Real + nalgebra::Scalar>(s: S, c: S, v: &Vector3<S>) -> Vector3<S> {
    Vector3::new(c * v.x - s * v.y, s * v.x + c * v.y, v.z)
}

fn hypot<S: Real>(a: S, b: S) -> S {
    (a * a + b * b).sqrt_raw()
}

/// Guidance variables of an inertial state (position, inertial velocity) at `nav.time_s`,
/// the planet having turned by `frame.angle_at_zero_rad + frame.rotation_rate_rad_s * t`.
///
/// # Errors
/// [`NavConvError`] as in the module docs.
pub fn from_inertial<S: Real + nalgebra::Scalar>(
    nav: &CartesianNav<S>,
    frame: &InertialFrame<S>,
) -> Result<NavState<S>, NavConvError> {
    let w = frame.rotation_rate_rad_s;
    if !(nav.time_s.is_finite() && w.is_finite() && frame.angle_at_zero_rad.is_finite()) {
        return Err(NavConvError::NonFinite);
    }
    if !(finite(&nav.position_m) && finite(&nav.velocity_m_s)) {
        return Err(NavConvError::NonFinite);
    }
    let theta = frame.angle_at_zero_rad + w * nav.time_s;
    let minus = S::ZERO - theta;
    let (s, c) = (minus.sin(), minus.cos());
    let r = rot_z(s, c, &nav.position_m);
    let v = rot_z(s, c, &nav.velocity_m_s);
    // v - omega x r with omega = (0, 0, w): (vx + w ry, vy - w rx, vz).
    let v_rel = Vector3::new(v.x + w * r.y, v.y - w * r.x, v.z);
    let out = planet_relative(nav.time_s, &r, &v_rel)?;
    Ok(out)
}

/// Guidance variables of a planet-fixed state (position, planet-relative velocity).
///
/// # Errors
/// [`NavConvError`] as in the module docs.
pub fn from_planet_fixed<S: Real + nalgebra::Scalar>(
    nav: &CartesianNav<S>,
) -> Result<NavState<S>, NavConvError> {
    if !(nav.time_s.is_finite() && finite(&nav.position_m) && finite(&nav.velocity_m_s)) {
        return Err(NavConvError::NonFinite);
    }
    planet_relative(nav.time_s, &nav.position_m, &nav.velocity_m_s)
}

fn planet_relative<S: Real + nalgebra::Scalar>(
    time_s: S,
    r: &Vector3<S>,
    v: &Vector3<S>,
) -> Result<NavState<S>, NavConvError> {
    if !(finite(r) && finite(v)) {
        return Err(NavConvError::OutOfRange);
    }
    let radius = (r.x * r.x + r.y * r.y + r.z * r.z).sqrt_raw();
    if !radius.is_finite() {
        return Err(NavConvError::OutOfRange);
    }
    if radius <= S::ZERO {
        return Err(NavConvError::ZeroPosition);
    }
    let rho = hypot(r.x, r.y);
    if !(rho > S::from_f64(4.0) * S::EPSILON * radius) {
        return Err(NavConvError::Pole);
    }
    let tau = r.y.atan2(r.x);
    let delta = r.z.atan2(rho);
    let (st, ct) = (tau.sin(), tau.cos());
    let (sd, cd) = (delta.sin(), delta.cos());
    let up_e_n = [
        Vector3::new(cd * ct, cd * st, sd),
        Vector3::new(S::ZERO - st, ct, S::ZERO),
        Vector3::new(S::ZERO - sd * ct, S::ZERO - sd * st, cd),
    ];
    let dot = |a: &Vector3<S>| v.x * a.x + v.y * a.y + v.z * a.z;
    let [up, east, north] = &up_e_n;
    let (vu, ve, vn) = (dot(up), dot(east), dot(north));
    let speed = (v.x * v.x + v.y * v.y + v.z * v.z).sqrt_raw();
    if !speed.is_finite() {
        return Err(NavConvError::OutOfRange);
    }
    if speed <= S::ZERO {
        return Err(NavConvError::ZeroVelocity);
    }
    let vh = hypot(ve, vn);
    if !(vu.is_finite() && vh.is_finite()) {
        return Err(NavConvError::OutOfRange);
    }
    let gamma = vu.atan2(vh);
    let heading = if vh > S::EPSILON * speed {
        let chi = ve.atan2(vn);
        let two_pi = S::PI + S::PI;
        let wrapped = if chi < S::ZERO { chi + two_pi } else { chi };
        // -tiny + 2 pi rounds to 2 pi: that is north, 0.
        if wrapped >= two_pi { S::ZERO } else { wrapped }
    } else {
        S::ZERO
    };
    let half_pi = S::PI / S::from_f64(2.0);
    Ok(NavState {
        time_s,
        radius_m: radius,
        speed_m_s: speed,
        flight_path_angle_rad: gamma.max(S::ZERO - half_pi).min(half_pi),
        heading_rad: heading,
        latitude_rad: delta.max(S::ZERO - half_pi).min(half_pi),
        // atan2(-0, x < 0) = -pi: the same meridian as +pi, the end the range includes.
        longitude_rad: if tau <= S::ZERO - S::PI { S::PI } else { tau },
    })
}
