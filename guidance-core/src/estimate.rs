//! Onboard aerodynamic estimation: the lift-to-drag ratio and the drag (density) scale of the
//! real vehicle and atmosphere relative to the predictor's model, from sensed aerodynamic
//! accelerations.
//!
//! An IMU senses the non-gravitational (specific) acceleration; resolved along and across the
//! air-relative velocity it gives the drag and lift accelerations `D/m`, `L/m` \[m/s^2\]
//! ([`SensedAero`]). The onboard model (exponential atmosphere, parabolic polar at the lift
//! parameter `lambda`, [`expected_aero`]) predicts the same accelerations at the navigated
//! radius and speed. Their ratios are two measurements:
//!
//! * L/D scale `s = (L/D)_sensed / (L/D)_model`: the error of the model's lift-to-drag ratio;
//! * drag scale `k = D_sensed / D_model`: density, drag coefficient and mass errors lumped
//!   together (accelerations cannot separate them; as FNPEG's and MSL's density filters, the
//!   estimate is applied as a density scale, see [`AeroScales::apply`]).
//!
//! [`AeroEstimator`] smooths each with a first-order fading-memory filter
//! `x <- x + g (clamp(z) - x)` (gain `g` per sample in `(0, 1]`: a time constant of about
//! `period / g`), clamped to configured bounds. Samples with a sensed drag below
//! [`EstimatorConfig::min_drag_m_s2`] (thin air at entry: the ratios are ill-conditioned and
//! IMU noise dominates) leave the estimate unchanged.
//!
//! The re-planner ([`crate::replan::ReplanningGuidance::with_estimator`]) predicts with the
//! model scaled by the current estimate: lift scaled by `s` (the polar's `K` divided by `s^2`,
//! so `C_L*` and `E*` scale by `s` and the drag at a given `lambda` is unchanged) and the
//! density by `k`.
//!
//! `no_std`, no allocation, no loops, no panics; `f32` and `f64` ([`Real`]). Every output is
//! finite and within the configured bounds whatever the input: a non-finite or negative
//! sensed value is a typed [`EstimateError`] and changes nothing.

use crate::scalar::Real;
use crate::vinh::nondim::{ExpAtmosphere, VehicleParams};

/// Aerodynamic accelerations \[m/s^2\]: sensed by the IMU, or expected by the onboard model.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SensedAero<S> {
    /// Lift acceleration magnitude `L/m` (perpendicular to the air-relative velocity)
    /// \[m/s^2\], `>= 0`.
    pub lift_m_s2: S,
    /// Drag acceleration magnitude `D/m` (opposite to the air-relative velocity) \[m/s^2\],
    /// `>= 0`.
    pub drag_m_s2: S,
}

impl SensedAero<f64> {
    /// These accelerations in the scalar `R` a flight computer flies (through
    /// [`crate::scalar::Scalar::from_f64`]; \[m/s^2\]).
    #[must_use]
    pub fn to_real<R: Real>(&self) -> SensedAero<R> {
        SensedAero {
            lift_m_s2: R::from_f64(self.lift_m_s2),
            drag_m_s2: R::from_f64(self.drag_m_s2),
        }
    }
}

impl<S: Real> SensedAero<S> {
    /// Check that both accelerations are finite and non-negative.
    ///
    /// # Errors
    /// [`EstimateError::NonFinite`], then [`EstimateError::Negative`].
    pub fn validate(&self) -> Result<(), EstimateError> {
        let all = [self.lift_m_s2, self.drag_m_s2];
        if all.iter().any(|v| !v.is_finite()) {
            return Err(EstimateError::NonFinite);
        }
        if all.iter().any(|v| *v < S::ZERO) {
            return Err(EstimateError::Negative);
        }
        Ok(())
    }
}

/// Estimated scales of the real aerodynamics over the model (1: the model is right).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AeroScales<S> {
    /// Lift-to-drag ratio scale `(L/D)_real / (L/D)_model` \[-\].
    pub lift_to_drag: S,
    /// Drag scale `D_real / D_model` at the same state \[-\] (density, drag coefficient and
    /// mass errors lumped).
    pub drag: S,
}

impl<S: Real> AeroScales<S> {
    /// Both scales 1 (the model as is).
    #[must_use]
    pub fn nominal() -> Self {
        Self {
            lift_to_drag: S::ONE,
            drag: S::ONE,
        }
    }

    /// The predictor model scaled by these estimates: the polar's induced-drag factor `K`
    /// divided by `lift_to_drag^2` (so `C_L* = sqrt(C_D0/K)` and `E*` scale by
    /// `lift_to_drag`, while the drag at a given `lambda` is unchanged) and the density
    /// `rho0` multiplied by `drag`. Both scales exactly 1 return the inputs unchanged.
    /// `None` if a scale is not finite and positive or a scaled value is not finite and
    /// positive.
    #[must_use]
    pub fn apply(
        &self,
        atmosphere: &ExpAtmosphere<S>,
        vehicle: &VehicleParams<S>,
    ) -> Option<(ExpAtmosphere<S>, VehicleParams<S>)> {
        let (s, k) = (self.lift_to_drag, self.drag);
        if !(s.is_finite() && k.is_finite() && s > S::ZERO && k > S::ZERO) {
            return None;
        }
        let mut atm = *atmosphere;
        let mut veh = *vehicle;
        if k != S::ONE {
            atm.rho0_kg_m3 = atmosphere.rho0_kg_m3 * k;
        }
        if s != S::ONE {
            veh.k_polar = vehicle.k_polar / (s * s);
        }
        let ok = |v: S| v.is_finite() && v > S::ZERO;
        (ok(atm.rho0_kg_m3) && ok(veh.k_polar)).then_some((atm, veh))
    }
}

/// Settings of [`AeroEstimator`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct EstimatorConfig<S> {
    /// Fading-memory gain of the L/D scale per accepted sample \[-\], in `(0, 1]` (1: the last
    /// measurement).
    pub lift_to_drag_gain: S,
    /// Fading-memory gain of the drag scale per accepted sample \[-\], in `(0, 1]`.
    pub drag_gain: S,
    /// Bounds of the L/D scale `(min, max)` \[-\], `0 < min <= 1 <= max`, finite.
    pub lift_to_drag_bounds: (S, S),
    /// Bounds of the drag scale `(min, max)` \[-\], `0 < min <= 1 <= max`, finite.
    pub drag_bounds: (S, S),
    /// Smallest sensed drag acceleration that updates the estimate \[m/s^2\], `>= 0`, finite.
    pub min_drag_m_s2: S,
}

/// Default [`EstimatorConfig::lift_to_drag_gain`] \[-\] (a time constant of about 20 s at
/// the 2 s guidance period).
pub const DEFAULT_LIFT_TO_DRAG_GAIN: f64 = 0.1;
/// Default [`EstimatorConfig::drag_gain`] \[-\] (about 10 s: it follows the altitude-varying
/// density).
pub const DEFAULT_DRAG_GAIN: f64 = 0.2;
/// Default [`EstimatorConfig::lift_to_drag_bounds`] \[-\].
pub const DEFAULT_LIFT_TO_DRAG_BOUNDS: (f64, f64) = (0.5, 2.0);
/// Default [`EstimatorConfig::drag_bounds`] \[-\].
pub const DEFAULT_DRAG_BOUNDS: (f64, f64) = (0.3, 3.0);
/// Default [`EstimatorConfig::min_drag_m_s2`] \[m/s^2\] (about 0.05 g).
pub const DEFAULT_MIN_DRAG_M_S2: f64 = 0.5;

impl<S: Real> Default for EstimatorConfig<S> {
    /// The dispersion campaigns' estimator: gains [`DEFAULT_LIFT_TO_DRAG_GAIN`] and
    /// [`DEFAULT_DRAG_GAIN`], bounds [`DEFAULT_LIFT_TO_DRAG_BOUNDS`] and
    /// [`DEFAULT_DRAG_BOUNDS`], threshold [`DEFAULT_MIN_DRAG_M_S2`].
    ///
    /// ```
    /// use guidance_core::estimate::{AeroEstimator, EstimatorConfig};
    /// let estimator = AeroEstimator::new(EstimatorConfig::<f32>::default())?;
    /// assert_eq!(estimator.scales().lift_to_drag, 1.0);
    /// # Ok::<(), guidance_core::GuidanceError>(())
    /// ```
    fn default() -> Self {
        let pair = |(a, b): (f64, f64)| (S::from_f64(a), S::from_f64(b));
        Self {
            lift_to_drag_gain: S::from_f64(DEFAULT_LIFT_TO_DRAG_GAIN),
            drag_gain: S::from_f64(DEFAULT_DRAG_GAIN),
            lift_to_drag_bounds: pair(DEFAULT_LIFT_TO_DRAG_BOUNDS),
            drag_bounds: pair(DEFAULT_DRAG_BOUNDS),
            min_drag_m_s2: S::from_f64(DEFAULT_MIN_DRAG_M_S2),
        }
    }
}

/// Why [`AeroEstimator::update`] rejected a sample (the estimate is unchanged).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum EstimateError {
    /// A sensed or expected acceleration is NaN or infinite.
    NonFinite,
    /// A sensed or expected acceleration is negative (they are magnitudes).
    Negative,
}

impl core::fmt::Display for EstimateError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            EstimateError::NonFinite => f.write_str("aerodynamic acceleration is not finite"),
            EstimateError::Negative => f.write_str("aerodynamic acceleration is negative"),
        }
    }
}

impl core::error::Error for EstimateError {}

/// What [`AeroEstimator::update`] did with an accepted sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum EstimateStatus {
    /// Both scales were updated.
    Updated,
    /// The sensed drag is below [`EstimatorConfig::min_drag_m_s2`]: nothing changed.
    BelowThreshold,
    /// The model expects no drag or no lift-to-drag ratio here (or the ratio is not
    /// representable): nothing changed.
    NoModel,
}

/// The first-order fading-memory estimator of [`AeroScales`] (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AeroEstimator<S> {
    config: EstimatorConfig<S>,
    scales: AeroScales<S>,
    updates: u32,
}

/// A bound pair `0 < min <= 1 <= max`, finite.
fn bounds_ok<S: Real>((lo, hi): (S, S)) -> bool {
    lo.is_finite() && hi.is_finite() && lo > S::ZERO && lo <= S::ONE && hi >= S::ONE
}

/// A gain in `(0, 1]`.
fn gain_ok<S: Real>(g: S) -> bool {
    g.is_finite() && g > S::ZERO && g <= S::ONE
}

impl<S: Real> AeroEstimator<S> {
    /// An estimator at the nominal scales (1, 1).
    ///
    /// # Errors
    /// [`crate::GuidanceError::InvalidConfig`] for a gain outside `(0, 1]`, bounds that are
    /// not `0 < min <= 1 <= max` and finite, or a negative or non-finite drag threshold.
    pub fn new(config: EstimatorConfig<S>) -> Result<Self, crate::GuidanceError> {
        let ok = gain_ok(config.lift_to_drag_gain)
            && gain_ok(config.drag_gain)
            && bounds_ok(config.lift_to_drag_bounds)
            && bounds_ok(config.drag_bounds)
            && config.min_drag_m_s2.is_finite()
            && config.min_drag_m_s2 >= S::ZERO;
        if !ok {
            return Err(crate::GuidanceError::InvalidConfig);
        }
        Ok(Self {
            config,
            scales: AeroScales::nominal(),
            updates: 0,
        })
    }

    /// Feed one sample: `sensed` accelerations and the model's `expected` ones at the same
    /// state ([`expected_aero`]). Returns what was done; the current estimate is
    /// [`AeroEstimator::scales`].
    ///
    /// # Errors
    /// [`EstimateError::NonFinite`] if any of the four accelerations is not finite, else
    /// [`EstimateError::Negative`] if any is negative; the estimate is unchanged.
    pub fn update(
        &mut self,
        sensed: &SensedAero<S>,
        expected: &SensedAero<S>,
    ) -> Result<EstimateStatus, EstimateError> {
        let all = [
            sensed.lift_m_s2,
            sensed.drag_m_s2,
            expected.lift_m_s2,
            expected.drag_m_s2,
        ];
        if all.iter().any(|v| !v.is_finite()) {
            return Err(EstimateError::NonFinite);
        }
        if all.iter().any(|v| *v < S::ZERO) {
            return Err(EstimateError::Negative);
        }
        let c = &self.config;
        if !(sensed.drag_m_s2 >= c.min_drag_m_s2 && sensed.drag_m_s2 > S::ZERO) {
            return Ok(EstimateStatus::BelowThreshold);
        }
        if !(expected.drag_m_s2 > S::ZERO && expected.lift_m_s2 > S::ZERO) {
            return Ok(EstimateStatus::NoModel);
        }
        // Ratios of positive finite values: positive or +inf/0 on over/underflow.
        let ld_sensed = sensed.lift_m_s2 / sensed.drag_m_s2;
        let ld_model = expected.lift_m_s2 / expected.drag_m_s2;
        let z_ld = ld_sensed / ld_model;
        let z_d = sensed.drag_m_s2 / expected.drag_m_s2;
        if !(z_ld.is_finite() && z_d.is_finite()) {
            return Ok(EstimateStatus::NoModel);
        }
        let filt = |x: S, z: S, g: S, (lo, hi): (S, S)| -> S {
            let x1 = x + g * (z.clamp(lo, hi) - x);
            // A convex combination of two values in [lo, hi]; the clamp guards rounding.
            if x1.is_finite() { x1.clamp(lo, hi) } else { x }
        };
        self.scales = AeroScales {
            lift_to_drag: filt(
                self.scales.lift_to_drag,
                z_ld,
                c.lift_to_drag_gain,
                c.lift_to_drag_bounds,
            ),
            drag: filt(self.scales.drag, z_d, c.drag_gain, c.drag_bounds),
        };
        self.updates = self.updates.saturating_add(1);
        Ok(EstimateStatus::Updated)
    }

    /// The current estimate (finite, within the configured bounds).
    #[must_use]
    pub fn scales(&self) -> AeroScales<S> {
        self.scales
    }

    /// Samples that updated the estimate (saturating).
    #[must_use]
    pub fn updates(&self) -> u32 {
        self.updates
    }

    /// The settings.
    #[must_use]
    pub fn config(&self) -> &EstimatorConfig<S> {
        &self.config
    }
}

/// The model's lift and drag accelerations \[m/s^2\] at `radius_m` \[m\] and air-relative
/// `speed_m_s` \[m/s\] with the lift parameter `lambda` \[-\] (`C_L = lambda C_L*`,
/// `C_D = C_D0 (1 + lambda^2)`): `q S C / m` with `q = rho(r) V^2 / 2` of the exponential
/// atmosphere. `None` for invalid model or state (non-finite, non-positive mass, area or
/// polar, negative `lambda` or speed) or a non-finite result.
#[must_use]
pub fn expected_aero<S: Real>(
    atmosphere: &ExpAtmosphere<S>,
    vehicle: &VehicleParams<S>,
    lambda: S,
    radius_m: S,
    speed_m_s: S,
) -> Option<SensedAero<S>> {
    let pos = |v: S| v.is_finite() && v > S::ZERO;
    let ok = pos(atmosphere.rho0_kg_m3)
        && pos(atmosphere.scale_height_m)
        && atmosphere.ref_radius_m.is_finite()
        && pos(vehicle.mass_kg)
        && pos(vehicle.reference_area_m2)
        && pos(vehicle.cd0)
        && pos(vehicle.k_polar)
        && lambda.is_finite()
        && lambda >= S::ZERO
        && radius_m.is_finite()
        && speed_m_s.is_finite()
        && speed_m_s >= S::ZERO;
    if !ok {
        return None;
    }
    let rho = atmosphere.rho0_kg_m3
        * (-(radius_m - atmosphere.ref_radius_m) / atmosphere.scale_height_m).exp();
    let q_s_m = rho * speed_m_s * speed_m_s * vehicle.reference_area_m2.half() / vehicle.mass_kg;
    let cl = lambda * (vehicle.cd0 / vehicle.k_polar).sqrt_raw();
    let cd = vehicle.cd0 * (S::ONE + lambda * lambda);
    let a = SensedAero {
        lift_m_s2: q_s_m * cl,
        drag_m_s2: q_s_m * cd,
    };
    (a.lift_m_s2.is_finite() && a.drag_m_s2.is_finite()).then_some(a)
}
