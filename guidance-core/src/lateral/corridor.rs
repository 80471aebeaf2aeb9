//! The heading-error corridor: a half-width that narrows linearly with speed or energy.

use crate::energy::EnergyNormalizer;
use crate::error::GuidanceError;
use crate::nav::NavState;
use crate::scalar::Real;

/// The variable the corridor narrows with.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum CorridorAxis<S> {
    /// Planet-relative speed \[m/s\].
    Speed,
    /// Normalised energy E-hat \[-\] from this normaliser.
    NormalizedEnergy(EnergyNormalizer<S>),
}

/// Corridor half-width on the heading error \[rad\] as a function of the corridor variable `x`
/// (speed \[m/s\] or E-hat \[-\]): `width_high_rad` at and above `x_high`, `width_low_rad` at
/// and below `x_low`, linear in between (typically `width_low_rad < width_high_rad`: the
/// corridor narrows as the vehicle slows down).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Corridor<S> {
    /// What `x` is.
    pub axis: CorridorAxis<S>,
    /// Upper end of the ramp (speed \[m/s\] or E-hat \[-\]).
    pub x_high: S,
    /// Half-width at and above `x_high` \[rad\], `> 0`.
    pub width_high_rad: S,
    /// Lower end of the ramp (speed \[m/s\] or E-hat \[-\]), `< x_high`.
    pub x_low: S,
    /// Half-width at and below `x_low` \[rad\], `> 0`.
    pub width_low_rad: S,
}

/// Default corridor half-width at the entry speed \[deg\] ([`Corridor::narrowing_with_speed`]).
pub const DEFAULT_WIDTH_ENTRY_DEG: f64 = 15.0;
/// Default corridor half-width near the final speed \[deg\].
pub const DEFAULT_WIDTH_FINAL_DEG: f64 = 3.0;
/// Default fraction of the entry-to-final speed span above the final speed where the
/// corridor reaches its final width \[-\].
pub const DEFAULT_LOW_SPEED_FRACTION: f64 = 0.05;

impl<S: Real> Corridor<S> {
    /// The default speed corridor from `entry_speed_m_s` to `final_speed_m_s` \[m/s\]
    /// (`final < entry`): [`DEFAULT_WIDTH_ENTRY_DEG`] at and above the entry speed, narrowing
    /// linearly to [`DEFAULT_WIDTH_FINAL_DEG`] at
    /// `final + DEFAULT_LOW_SPEED_FRACTION (entry - final)` (the dispersion campaigns'
    /// default).
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] for non-finite speeds or `final >= entry`.
    pub fn narrowing_with_speed(
        entry_speed_m_s: S,
        final_speed_m_s: S,
    ) -> Result<Self, GuidanceError> {
        let deg = S::PI / S::from_f64(180.0);
        let c = Self {
            axis: CorridorAxis::Speed,
            x_high: entry_speed_m_s,
            width_high_rad: S::from_f64(DEFAULT_WIDTH_ENTRY_DEG) * deg,
            x_low: final_speed_m_s
                + S::from_f64(DEFAULT_LOW_SPEED_FRACTION) * (entry_speed_m_s - final_speed_m_s),
            width_low_rad: S::from_f64(DEFAULT_WIDTH_FINAL_DEG) * deg,
        };
        c.validate()?;
        Ok(c)
    }

    /// Check the corridor: finite values, `x_low < x_high`, both widths in `(0, pi]`.
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] otherwise.
    pub fn validate(&self) -> Result<(), GuidanceError> {
        let all = [
            self.x_high,
            self.x_low,
            self.width_high_rad,
            self.width_low_rad,
        ];
        let ok_w = |w: S| w > S::ZERO && w <= S::PI;
        if all.iter().any(|v| !v.is_finite())
            || !(self.x_low < self.x_high)
            || !ok_w(self.width_high_rad)
            || !ok_w(self.width_low_rad)
        {
            return Err(GuidanceError::InvalidConfig);
        }
        Ok(())
    }

    /// The corridor variable at `nav` (speed \[m/s\] or E-hat \[-\]).
    ///
    /// # Errors
    /// As [`EnergyNormalizer::normalized`] (non-finite or unphysical state).
    pub fn variable(&self, nav: &NavState<S>) -> Result<S, GuidanceError> {
        match self.axis {
            CorridorAxis::Speed => Ok(nav.speed_m_s),
            CorridorAxis::NormalizedEnergy(n) => n.normalized(nav.radius_m, nav.speed_m_s),
        }
    }

    /// Half-width \[rad\] at `x` (clamped ramp, always between the two end widths, so
    /// positive for a valid corridor; a NaN `x` gives the narrower width).
    #[must_use]
    pub fn width_rad(&self, x: S) -> S {
        if x >= self.x_high {
            self.width_high_rad
        } else if x > self.x_low {
            let t = (x - self.x_low) / (self.x_high - self.x_low);
            let w = self.width_low_rad + t * (self.width_high_rad - self.width_low_rad);
            let lo = self.width_low_rad.min(self.width_high_rad);
            let hi = self.width_low_rad.max(self.width_high_rad);
            // Rounding can leave the ramp's range (e.g. 0 for a tiny end width): clamp into it,
            // so the width stays positive.
            if w.is_finite() { w.clamp(lo, hi) } else { lo }
        } else if x <= self.x_low {
            self.width_low_rad
        } else {
            self.width_low_rad.min(self.width_high_rad)
        }
    }
}
