//! Navigation state handed to guidance.

use crate::error::GuidanceError;
use crate::scalar::Scalar;

/// Navigation state at one instant, planet-relative, spherical coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct NavState<S> {
    /// Mission time since entry interface \[s\].
    pub time_s: S,
    /// Distance from the planet centre \[m\].
    pub radius_m: S,
    /// Planet-relative speed \[m/s\].
    pub speed_m_s: S,
    /// Planet-relative flight-path angle \[rad\], positive above the local horizontal.
    pub flight_path_angle_rad: S,
    /// Planet-relative heading \[rad\], clockwise from north.
    pub heading_rad: S,
    /// Geocentric latitude \[rad\].
    pub latitude_rad: S,
    /// Longitude \[rad\], positive east.
    pub longitude_rad: S,
}

impl NavState<f64> {
    /// This state in the scalar `S` a flight computer flies (each field through
    /// [`Scalar::from_f64`]; units unchanged): how the firmware and its PIL twin narrow the
    /// simulator's navigation frame.
    #[must_use]
    pub fn to_scalar<S: Scalar>(&self) -> NavState<S> {
        NavState {
            time_s: S::from_f64(self.time_s),
            radius_m: S::from_f64(self.radius_m),
            speed_m_s: S::from_f64(self.speed_m_s),
            flight_path_angle_rad: S::from_f64(self.flight_path_angle_rad),
            heading_rad: S::from_f64(self.heading_rad),
            latitude_rad: S::from_f64(self.latitude_rad),
            longitude_rad: S::from_f64(self.longitude_rad),
        }
    }
}

impl<S: Scalar> NavState<S> {
    /// Check that every field is finite and the radius and speed are positive.
    ///
    /// # Errors
    /// [`GuidanceError::NonFiniteState`] if any field is NaN or infinite;
    /// [`GuidanceError::UnphysicalState`] if the radius or speed is not positive.
    pub fn validate(&self) -> Result<(), GuidanceError> {
        let all = [
            self.time_s,
            self.radius_m,
            self.speed_m_s,
            self.flight_path_angle_rad,
            self.heading_rad,
            self.latitude_rad,
            self.longitude_rad,
        ];
        if all.iter().any(|v| !v.is_finite()) {
            return Err(GuidanceError::NonFiniteState);
        }
        if self.radius_m <= S::ZERO || self.speed_m_s < S::ZERO {
            return Err(GuidanceError::UnphysicalState);
        }
        Ok(())
    }
}
