//! The attitude command (angle of attack, bank angle) that every stage of the guidance path
//! produces and consumes. A leaf module: it depends on nothing but [`crate::scalar`], so
//! [`crate::interp`], [`crate::rate`], [`crate::link`] and [`crate::guidance`] can all use it
//! without importing each other.

use crate::scalar::Scalar;

/// Degrees to radians.
const DEG_TO_RAD: f64 = core::f64::consts::PI / 180.0;

/// An attitude command (or attitude) \[rad\].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Command<S> {
    /// Angle of attack \[rad\].
    pub alpha_rad: S,
    /// Bank angle \[rad\].
    pub sigma_rad: S,
}

impl<S: Scalar> Command<S> {
    /// This command in `f64` \[rad\] (each angle through [`Scalar::to_f64`]): how a command
    /// frame carries it.
    #[must_use]
    pub fn to_f64(self) -> Command<f64> {
        Command {
            alpha_rad: self.alpha_rad.to_f64(),
            sigma_rad: self.sigma_rad.to_f64(),
        }
    }

    /// Command from degrees (converted to radians); `None` if non-finite or not
    /// representable in `S`.
    #[must_use]
    pub fn from_deg(alpha_deg: f64, sigma_deg: f64) -> Option<Self> {
        Some(Self {
            alpha_rad: S::from_f64_checked(alpha_deg * DEG_TO_RAD)?,
            sigma_rad: S::from_f64_checked(sigma_deg * DEG_TO_RAD)?,
        })
    }

    /// True if both angles are finite.
    #[must_use]
    pub fn is_finite(&self) -> bool {
        self.alpha_rad.is_finite() && self.sigma_rad.is_finite()
    }
}

/// Sign of the bank angle imposed by a lateral logic (see [`crate::lateral`]): the command's
/// bank magnitude is kept and its sign set (positive bank turns the heading clockwise, to the
/// right).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum BankSign {
    /// Bank right, `sigma >= 0`.
    Positive,
    /// Bank left, `sigma <= 0`.
    Negative,
}

impl BankSign {
    /// `sigma_rad` \[rad\] with its magnitude kept and this sign (a NaN stays NaN: callers
    /// clamp afterwards).
    #[must_use]
    pub fn apply<S: Scalar>(self, sigma_rad: S) -> S {
        let m = sigma_rad.abs();
        match self {
            Self::Positive => m,
            Self::Negative => S::ZERO - m,
        }
    }

    /// The other sign.
    #[must_use]
    pub fn reversed(self) -> Self {
        match self {
            Self::Positive => Self::Negative,
            Self::Negative => Self::Positive,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Fixed;

    #[test]
    fn from_deg_converts_and_rejects() {
        let c = Command::<f64>::from_deg(40.0, -90.0).unwrap();
        assert_eq!(c.alpha_rad, 40.0_f64.to_radians());
        assert_eq!(c.sigma_rad, (-90.0_f64).to_radians());
        assert!(c.is_finite());
        assert!(Command::<f64>::from_deg(f64::NAN, 0.0).is_none());
        assert!(Command::<Fixed>::from_deg(1e15, 0.0).is_none());
    }

    #[test]
    fn bank_sign_keeps_the_magnitude() {
        assert_eq!(BankSign::Negative.apply(0.5_f64), -0.5);
        assert_eq!(BankSign::Negative.apply(-0.5_f64), -0.5);
        assert_eq!(BankSign::Positive.apply(-0.5_f64), 0.5);
        assert_eq!(BankSign::Positive.reversed(), BankSign::Negative);
        assert_eq!(
            BankSign::Negative.apply(Fixed::from_f64(0.25)),
            Fixed::from_f64(-0.25)
        );
    }
}
