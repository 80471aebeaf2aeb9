//! [`LiftSchedule`]: the lift parameter of the numerical predictor as a function of speed, for a
//! vehicle whose stored angle-of-attack profile changes along the flight (HORUS-2B: 40 deg down
//! to 4.2 km/s, then a ramp to 11.5 deg at the interface). The closed forms keep the solver's
//! constant [`super::ReplanConfig::lambda`].

use crate::scalar::Real;

/// Lift parameter `lambda = C_L / C_L*` \[-\] against speed \[m/s\]: `lambda_high` at and
/// above `speed_high_m_s`, linear in speed down to `lambda_low` at `speed_low_m_s`,
/// `lambda_low` below.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LiftSchedule<S> {
    /// Speed from which `lambda_high` holds \[m/s\].
    pub speed_high_m_s: S,
    /// Lift parameter at and above `speed_high_m_s` \[-\].
    pub lambda_high: S,
    /// Speed below which `lambda_low` holds \[m/s\] (`< speed_high_m_s`).
    pub speed_low_m_s: S,
    /// Lift parameter at and below `speed_low_m_s` \[-\].
    pub lambda_low: S,
}

impl<S: Real> LiftSchedule<S> {
    /// Whether the schedule is usable: finite, `0 <= speed_low < speed_high`, both lift
    /// parameters finite and non-negative.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        let all = [
            self.speed_high_m_s,
            self.lambda_high,
            self.speed_low_m_s,
            self.lambda_low,
        ];
        all.iter().all(|v| v.is_finite())
            && self.speed_low_m_s >= S::ZERO
            && self.speed_low_m_s < self.speed_high_m_s
            && self.lambda_high >= S::ZERO
            && self.lambda_low >= S::ZERO
    }

    /// The lift parameter at speed `speed_m_s` \[m/s\] \[-\]; between `lambda_low` and
    /// `lambda_high` for any input (a NaN speed gives `lambda_low`).
    #[must_use]
    pub fn lambda_at(&self, speed_m_s: S) -> S {
        let span = self.speed_high_m_s - self.speed_low_m_s;
        let w = (speed_m_s - self.speed_low_m_s) / span;
        // NaN (a NaN speed or an invalid schedule) -> 0: lambda_low.
        let w = if w.is_finite() || w > S::ZERO {
            w.clamp(S::ZERO, S::ONE)
        } else {
            S::ZERO
        };
        let (lo, hi) = (self.lambda_low, self.lambda_high);
        // Clamped: rounding must not carry the interpolation past an end.
        (lo + w * (hi - lo)).clamp(lo.min(hi), lo.max(hi))
    }
}
