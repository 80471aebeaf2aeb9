//! Frames and states of the simulator: the inertial Cartesian state it integrates, the
//! planet-relative spherical state it reports, and the conversions between them (frames as in
//! the parent module's documentation), and the layout of the integrated state.

use nalgebra::Vector3;

use crate::env::Planet;

/// Length of the integrated Cartesian state: `[x, y, z, vx, vy, vz, Q, theta]`.
pub const STATE_LEN: usize = 8;
/// Slot of the heat load `Q` \[J/m^2\] in the integrated state.
pub const HEAT_LOAD_SLOT: usize = 6;
/// Slot of the flown range angle `theta` \[rad\] in the integrated state.
pub const FLOWN_RANGE_SLOT: usize = 7;

/// Inertial Cartesian state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CartesianState {
    /// Position in the inertial frame \[m\].
    pub position_m: Vector3<f64>,
    /// Inertial velocity [m/s].
    pub velocity_m_s: Vector3<f64>,
}

/// Planet-relative spherical state (thesis eq. 3.4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphericalState {
    /// Distance from the planet centre r \[m\].
    pub radius_m: f64,
    /// Longitude tau \[rad\], positive east.
    pub longitude_rad: f64,
    /// Geocentric latitude delta \[rad\].
    pub latitude_rad: f64,
    /// Planet-relative speed V [m/s].
    pub speed_m_s: f64,
    /// Planet-relative flight-path angle gamma \[rad\].
    pub flight_path_angle_rad: f64,
    /// Planet-relative heading chi \[rad\], clockwise from north.
    pub heading_rad: f64,
}

impl SphericalState {
    /// As an array `[r, tau, delta, V, gamma, chi]`.
    #[must_use]
    pub fn to_array(&self) -> [f64; 6] {
        [
            self.radius_m,
            self.longitude_rad,
            self.latitude_rad,
            self.speed_m_s,
            self.flight_path_angle_rad,
            self.heading_rad,
        ]
    }

    /// From an array `[r, tau, delta, V, gamma, chi]`.
    #[must_use]
    pub fn from_array(a: &[f64; 6]) -> Self {
        Self {
            radius_m: a[0],
            longitude_rad: a[1],
            latitude_rad: a[2],
            speed_m_s: a[3],
            flight_path_angle_rad: a[4],
            heading_rad: a[5],
        }
    }
}

fn rot_z(angle: f64, v: &Vector3<f64>) -> Vector3<f64> {
    let (s, c) = angle.sin_cos();
    Vector3::new(c * v.x - s * v.y, s * v.x + c * v.y, v.z)
}

/// Local unit vectors (up, east, north) in the planet-fixed frame at longitude `tau`,
/// latitude `delta`.
pub(super) fn local_axes(tau: f64, delta: f64) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
    let (st, ct) = tau.sin_cos();
    let (sd, cd) = delta.sin_cos();
    (
        Vector3::new(cd * ct, cd * st, sd),
        Vector3::new(-st, ct, 0.0),
        Vector3::new(-sd * ct, -sd * st, cd),
    )
}

/// Planet-relative spherical state -> inertial Cartesian state at time `t_s` \[s\].
#[must_use]
pub fn spherical_to_cartesian(s: &SphericalState, planet: &Planet, t_s: f64) -> CartesianState {
    let (up, east, north) = local_axes(s.longitude_rad, s.latitude_rad);
    let r_r = up * s.radius_m;
    let (sg, cg) = s.flight_path_angle_rad.sin_cos();
    let (sc, cc) = s.heading_rad.sin_cos();
    let v_r = (north * (cg * cc) + east * (cg * sc) + up * sg) * s.speed_m_s;
    let omega = Vector3::new(0.0, 0.0, planet.rotation_rate_rad_s);
    let theta = planet.rotation_rate_rad_s * t_s;
    CartesianState {
        position_m: rot_z(theta, &r_r),
        velocity_m_s: rot_z(theta, &(v_r + omega.cross(&r_r))),
    }
}

/// Inertial Cartesian state at time `t_s` \[s\] -> planet-relative spherical state.
/// Longitude is wrapped to (-pi, pi], heading to [0, 2 pi).
#[must_use]
pub fn cartesian_to_spherical(c: &CartesianState, planet: &Planet, t_s: f64) -> SphericalState {
    let theta = planet.rotation_rate_rad_s * t_s;
    let r_r = rot_z(-theta, &c.position_m);
    let omega = Vector3::new(0.0, 0.0, planet.rotation_rate_rad_s);
    let v_r = rot_z(-theta, &c.velocity_m_s) - omega.cross(&r_r);
    let r = r_r.norm();
    let tau = r_r.y.atan2(r_r.x);
    let delta = r_r.z.atan2(r_r.x.hypot(r_r.y));
    let (up, east, north) = local_axes(tau, delta);
    let (vu, ve, vn) = (v_r.dot(&up), v_r.dot(&east), v_r.dot(&north));
    let v = v_r.norm();
    let gamma = vu.atan2(ve.hypot(vn));
    let mut chi = ve.atan2(vn);
    if chi < 0.0 {
        chi += std::f64::consts::TAU;
    }
    SphericalState {
        radius_m: r,
        longitude_rad: tau,
        latitude_rad: delta,
        speed_m_s: v,
        flight_path_angle_rad: gamma,
        heading_rad: chi,
    }
}

/// The Cartesian part of an integrated state.
#[must_use]
pub fn cartesian_of(y: &[f64; STATE_LEN]) -> CartesianState {
    CartesianState {
        position_m: Vector3::new(y[0], y[1], y[2]),
        velocity_m_s: Vector3::new(y[3], y[4], y[5]),
    }
}
