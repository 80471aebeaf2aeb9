//! Where the planar closed-form trajectory lies on the sphere: the great circle through the
//! entry position in the entry heading.

use nalgebra::Vector3;

use crate::dynamics::SphericalState;

/// Where the planar trajectory starts on the sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// Latitude \[rad\].
    pub latitude_rad: f64,
    /// Longitude \[rad\].
    pub longitude_rad: f64,
    /// Heading \[rad\], clockwise from north.
    pub heading_rad: f64,
}

impl Default for Placement {
    /// On the equator at longitude 0, heading east.
    fn default() -> Self {
        Self {
            latitude_rad: 0.0,
            longitude_rad: 0.0,
            heading_rad: std::f64::consts::FRAC_PI_2,
        }
    }
}

impl Placement {
    /// The placement part of a spherical state.
    #[must_use]
    pub fn of(s: &SphericalState) -> Self {
        Self {
            latitude_rad: s.latitude_rad,
            longitude_rad: s.longitude_rad,
            heading_rad: s.heading_rad,
        }
    }

    /// Latitude, longitude and heading [rad] after range angle `theta_rad` along the great
    /// circle.
    pub(super) fn along(&self, theta_rad: f64) -> (f64, f64, f64) {
        let (sl, cl) = self.latitude_rad.sin_cos();
        let (so, co) = self.longitude_rad.sin_cos();
        let up = Vector3::new(cl * co, cl * so, sl);
        let east = Vector3::new(-so, co, 0.0);
        let north = Vector3::new(-sl * co, -sl * so, cl);
        let (sh, ch) = self.heading_rad.sin_cos();
        let t0 = north * ch + east * sh;
        let (st, ct) = theta_rad.sin_cos();
        let p = up * ct + t0 * st;
        let t = t0 * ct - up * st;
        let lat = p.z.clamp(-1.0, 1.0).asin();
        let lon = p.y.atan2(p.x);
        let (slat, clat) = lat.sin_cos();
        let (slon, clon) = lon.sin_cos();
        let e = Vector3::new(-slon, clon, 0.0);
        let n = Vector3::new(-slat * clon, -slat * slon, clat);
        let mut heading = t.dot(&e).atan2(t.dot(&n));
        if heading < 0.0 {
            heading += std::f64::consts::TAU;
        }
        (lat, lon, heading)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placement_follows_the_great_circle() {
        let p = Placement::default();
        let (lat, lon, h) = p.along(0.3);
        assert!(lat.abs() < 1e-15);
        assert!((lon - 0.3).abs() < 1e-15);
        assert!((h - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        // Heading north from the equator: latitude grows with the range angle.
        let n = Placement {
            heading_rad: 0.0,
            ..Placement::default()
        };
        let (lat, lon, h) = n.along(0.2);
        assert!((lat - 0.2).abs() < 1e-12 && lon.abs() < 1e-12 && h.abs() < 1e-12);
    }
}
