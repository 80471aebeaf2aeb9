//! Constraint monitors (thesis sec. 2.1.2 and 4.2.3): Chapman stagnation heat flux (eq. 2.2),
//! g-load (eq. 2.1), g-load rate from successive samples, dynamic pressure, running peaks and
//! the constraint-violation measures of eq. 4.9-4.11.
//!
//! Units: density \[kg/m^3\], speed \[m/s\], nose radius \[m\], forces \[N\], mass \[kg\], time \[s\],
//! heat flux \[W/m^2\], dynamic pressure \[Pa\], g-load \[-\] (multiples of g0 = 9.80665 m/s^2),
//! g-load rate \[1/s\].
//!
//! # Non-finite and out-of-domain input
//! The `try_*` functions and the stateful monitors return
//! [`GuidanceError::NonFiniteState`] for NaN/infinite input (or a non-finite result, e.g.
//! overflow in `f32`) and [`GuidanceError::UnphysicalState`] for a negative density or speed, a
//! non-positive nose radius or mass; stateful monitors are unchanged on error. The plain
//! functions ([`chapman_heat_flux_w_m2`], [`g_load`], [`dynamic_pressure_pa`]) return **0** for
//! such input (documented behaviour, never NaN); use the `try_*` forms or [`ConstraintMonitor`]
//! on board, where a bad sample must be noticed.

use crate::error::GuidanceError;
use crate::scalar::{Real, Scalar};

/// Chapman constant c* of eq. 2.2 \[W/m^2 * m^0.5\] (ERRATA; with the nose radius in metres).
pub const CHAPMAN_C_STAR: f64 = 1.1097e8;
/// Sea-level reference density rho_0 of eq. 2.2 \[kg/m^3\].
pub const CHAPMAN_RHO0_KG_M3: f64 = 1.225;
/// Reference (circular) speed V_c of eq. 2.2 \[m/s\].
pub const CHAPMAN_VC_M_S: f64 = 7905.4;
/// Speed exponent m of eq. 2.2 \[-\] (the density exponent is 1 - n = 0.5, the nose-radius
/// exponent n = 0.5).
pub const CHAPMAN_SPEED_EXPONENT: f64 = 3.15;
/// Standard gravity g0 of eq. 2.1 \[m/s^2\].
pub const G0_M_S2: f64 = 9.80665;

fn finite<S: Scalar>(vals: &[S]) -> Result<(), GuidanceError> {
    if vals.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(GuidanceError::NonFiniteState)
    }
}

fn finite_out<S: Scalar>(v: S) -> Result<S, GuidanceError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(GuidanceError::NonFiniteState)
    }
}

/// Chapman stagnation-point heat flux, thesis eq. 2.2 with the ERRATA constants:
/// `q = c* / sqrt(R_N) * sqrt(rho / rho_0) * (V / V_c)^3.15` \[W/m^2\].
///
/// # Errors
/// Non-finite input or result; negative density or speed, non-positive nose radius.
pub fn try_chapman_heat_flux_w_m2<S: Real>(
    density_kg_m3: S,
    speed_m_s: S,
    nose_radius_m: S,
) -> Result<S, GuidanceError> {
    finite(&[density_kg_m3, speed_m_s, nose_radius_m])?;
    if density_kg_m3 < S::ZERO || speed_m_s < S::ZERO || nose_radius_m <= S::ZERO {
        return Err(GuidanceError::UnphysicalState);
    }
    let c = S::from_f64(CHAPMAN_C_STAR);
    let rho_ratio = density_kg_m3 / S::from_f64(CHAPMAN_RHO0_KG_M3);
    let v_ratio = speed_m_s / S::from_f64(CHAPMAN_VC_M_S);
    let q = c / Scalar::sqrt(nose_radius_m)
        * Scalar::sqrt(rho_ratio)
        * v_ratio.powf(S::from_f64(CHAPMAN_SPEED_EXPONENT));
    finite_out(q)
}

/// Chapman heat flux \[W/m^2\] as [`try_chapman_heat_flux_w_m2`]; 0 for invalid input.
#[must_use]
pub fn chapman_heat_flux_w_m2<S: Real>(density_kg_m3: S, speed_m_s: S, nose_radius_m: S) -> S {
    try_chapman_heat_flux_w_m2(density_kg_m3, speed_m_s, nose_radius_m).unwrap_or(S::ZERO)
}

/// g-load, thesis eq. 2.1: `n = sqrt(L^2 + D^2) / (m g0)` \[-\]. The root is formed as
/// `a sqrt(1 + (b/a)^2)` with `a = max(|L|, |D|)`, so large forces do not overflow in `f32`.
///
/// # Errors
/// Non-finite input or result; non-positive mass.
pub fn try_g_load<S: Real>(lift_n: S, drag_n: S, mass_kg: S) -> Result<S, GuidanceError> {
    finite(&[lift_n, drag_n, mass_kg])?;
    if mass_kg <= S::ZERO {
        return Err(GuidanceError::UnphysicalState);
    }
    let (l, d) = (Scalar::abs(lift_n), Scalar::abs(drag_n));
    let a = Scalar::max(l, d);
    if a == S::ZERO {
        return Ok(S::ZERO);
    }
    let b = Scalar::min(l, d) / a;
    let resultant = a * Scalar::sqrt(S::ONE + b * b);
    finite_out(resultant / (mass_kg * S::from_f64(G0_M_S2)))
}

/// g-load \[-\] as [`try_g_load`]; 0 for invalid input.
#[must_use]
pub fn g_load<S: Real>(lift_n: S, drag_n: S, mass_kg: S) -> S {
    try_g_load(lift_n, drag_n, mass_kg).unwrap_or(S::ZERO)
}

/// Dynamic pressure `q = rho V^2 / 2` \[Pa\].
///
/// # Errors
/// Non-finite input or result; negative density.
pub fn try_dynamic_pressure_pa<S: Real>(
    density_kg_m3: S,
    speed_m_s: S,
) -> Result<S, GuidanceError> {
    finite(&[density_kg_m3, speed_m_s])?;
    if density_kg_m3 < S::ZERO {
        return Err(GuidanceError::UnphysicalState);
    }
    finite_out((density_kg_m3 * speed_m_s * speed_m_s).half())
}

/// Dynamic pressure \[Pa\] as [`try_dynamic_pressure_pa`]; 0 for invalid input.
#[must_use]
pub fn dynamic_pressure_pa<S: Real>(density: S, speed: S) -> S {
    try_dynamic_pressure_pa(density, speed).unwrap_or(S::ZERO)
}

/// Constraint-violation measure of thesis eq. 4.9-4.11: 0 if `peak <= limit`, else
/// `peak / limit` (> 1). Non-finite `peak` or a non-finite or non-positive `limit` (an
/// unusable measurement or configuration) returns `S::MAX`, i.e. counts as violated; never NaN.
#[must_use]
pub fn violation<S: Scalar>(peak: S, limit: S) -> S {
    if !(peak.is_finite() && limit.is_finite()) || limit <= S::ZERO {
        return S::MAX;
    }
    if peak <= limit { S::ZERO } else { peak / limit }
}

/// g-load rate from successive samples: `(n_k - n_{k-1}) / (t_k - t_{k-1})` \[1/s\].
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct GLoadRateMonitor<S> {
    /// Previous (time \[s\], g-load \[-\]).
    previous: Option<(S, S)>,
}

impl<S: Scalar> GLoadRateMonitor<S> {
    /// A monitor with no samples yet.
    #[must_use]
    pub fn new() -> Self {
        Self { previous: None }
    }

    /// Add a sample (time \[s\], g-load \[-\]); returns the signed rate \[1/s\] against the previous
    /// sample (`None` for the first sample).
    ///
    /// # Errors
    /// [`GuidanceError::NonFiniteState`] for non-finite input or rate;
    /// [`GuidanceError::NonIncreasingTime`] if `time_s` is not after the previous sample.
    /// The monitor is unchanged on error.
    pub fn update(&mut self, time_s: S, g_load: S) -> Result<Option<S>, GuidanceError> {
        finite(&[time_s, g_load])?;
        let rate = match self.previous {
            None => None,
            Some((t0, n0)) => {
                if time_s <= t0 {
                    return Err(GuidanceError::NonIncreasingTime);
                }
                Some(finite_out((g_load - n0) / (time_s - t0))?)
            }
        };
        self.previous = Some((time_s, g_load));
        Ok(rate)
    }

    /// Forget the previous sample.
    pub fn reset(&mut self) {
        self.previous = None;
    }
}

/// Constraint limits (thesis table 2.1).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ConstraintLimits<S> {
    /// Largest heat flux \[W/m^2\].
    pub heat_flux_w_m2: S,
    /// Largest g-load \[-\].
    pub g_load: S,
    /// Largest |g-load rate| \[1/s\].
    pub g_load_rate_per_s: S,
}

impl<S: Scalar> ConstraintLimits<S> {
    /// HORUS-2B limits of thesis table 2.1: 500 kW/m^2, 3.0 g, 0.5 /s.
    #[must_use]
    pub fn thesis_default() -> Self {
        Self {
            heat_flux_w_m2: S::from_f64(500.0e3),
            g_load: S::from_f64(3.0),
            g_load_rate_per_s: S::from_f64(0.5),
        }
    }
}

/// Violation measures (eq. 4.9-4.11) of the three constraints; each 0 (satisfied) or the ratio
/// peak / limit (> 1).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Violations<S> {
    /// p_q, eq. 4.9 \[-\].
    pub heat_flux: S,
    /// p_g, eq. 4.10 \[-\].
    pub g_load: S,
    /// p_g-dot, eq. 4.11 \[-\].
    pub g_load_rate: S,
}

impl<S: Scalar> Violations<S> {
    /// True if no constraint is violated.
    #[must_use]
    pub fn feasible(&self) -> bool {
        self.heat_flux == S::ZERO && self.g_load == S::ZERO && self.g_load_rate == S::ZERO
    }
}

/// A running maximum and the time it occurred (starts at 0 at time 0): the one peak type of
/// the project; the host simulator reports its peaks with it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TimedPeak<S> {
    /// The peak value (units of the tracked quantity).
    pub value: S,
    /// When it occurred \[s\].
    pub time_s: S,
}

impl<S: Scalar> Default for TimedPeak<S> {
    fn default() -> Self {
        Self {
            value: S::ZERO,
            time_s: S::ZERO,
        }
    }
}

impl<S: Scalar> TimedPeak<S> {
    /// Take `value` at `time_s` \[s\] if it exceeds the peak so far (a NaN never does).
    pub fn update(&mut self, value: S, time_s: S) {
        if value > self.value {
            self.value = value;
            self.time_s = time_s;
        }
    }
}

/// Running peaks of heat flux, g-load and |g-load rate| (all start at 0).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PeakTracker<S> {
    heat_flux_w_m2: S,
    g_load: S,
    g_load_rate_per_s: S,
}

impl<S: Scalar> Default for PeakTracker<S> {
    fn default() -> Self {
        Self::new()
    }
}

impl<S: Scalar> PeakTracker<S> {
    /// All peaks 0.
    #[must_use]
    pub fn new() -> Self {
        Self {
            heat_flux_w_m2: S::ZERO,
            g_load: S::ZERO,
            g_load_rate_per_s: S::ZERO,
        }
    }

    /// Add one sample: heat flux \[W/m^2\], g-load \[-\], g-load rate \[1/s\] (signed; its magnitude
    /// is tracked; `None` if not yet available).
    ///
    /// # Errors
    /// [`GuidanceError::NonFiniteState`] if any value is non-finite (peaks unchanged).
    pub fn update(
        &mut self,
        heat_flux_w_m2: S,
        g_load: S,
        g_load_rate_per_s: Option<S>,
    ) -> Result<(), GuidanceError> {
        let rate = g_load_rate_per_s.unwrap_or(S::ZERO);
        finite(&[heat_flux_w_m2, g_load, rate])?;
        self.heat_flux_w_m2 = self.heat_flux_w_m2.max(heat_flux_w_m2);
        self.g_load = self.g_load.max(g_load);
        self.g_load_rate_per_s = self.g_load_rate_per_s.max(rate.abs());
        Ok(())
    }

    /// Peak heat flux \[W/m^2\].
    #[must_use]
    pub fn heat_flux_w_m2(&self) -> S {
        self.heat_flux_w_m2
    }

    /// Peak g-load \[-\].
    #[must_use]
    pub fn g_load(&self) -> S {
        self.g_load
    }

    /// Peak |g-load rate| \[1/s\].
    #[must_use]
    pub fn g_load_rate_per_s(&self) -> S {
        self.g_load_rate_per_s
    }

    /// Violation measures of the peaks against `limits` (eq. 4.9-4.11).
    #[must_use]
    pub fn violations(&self, limits: &ConstraintLimits<S>) -> Violations<S> {
        Violations {
            heat_flux: violation(self.heat_flux_w_m2, limits.heat_flux_w_m2),
            g_load: violation(self.g_load, limits.g_load),
            g_load_rate: violation(self.g_load_rate_per_s, limits.g_load_rate_per_s),
        }
    }
}

/// One evaluated sample of [`ConstraintMonitor`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ConstraintSample<S> {
    /// Chapman heat flux \[W/m^2\].
    pub heat_flux_w_m2: S,
    /// g-load \[-\].
    pub g_load: S,
    /// g-load rate against the previous sample \[1/s\] (`None` for the first).
    pub g_load_rate_per_s: Option<S>,
    /// Dynamic pressure \[Pa\].
    pub dynamic_pressure_pa: S,
}

/// All monitors for one vehicle: computes a [`ConstraintSample`] from the flight condition and
/// tracks the peaks.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ConstraintMonitor<S> {
    nose_radius_m: S,
    mass_kg: S,
    rate: GLoadRateMonitor<S>,
    peaks: PeakTracker<S>,
}

impl<S: Real> ConstraintMonitor<S> {
    /// Monitor for a vehicle with nose radius \[m\] and mass \[kg\] (both finite and > 0).
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] otherwise.
    pub fn new(nose_radius_m: S, mass_kg: S) -> Result<Self, GuidanceError> {
        let ok = |v: S| v.is_finite() && v > S::ZERO;
        if !(ok(nose_radius_m) && ok(mass_kg)) {
            return Err(GuidanceError::InvalidConfig);
        }
        Ok(Self {
            nose_radius_m,
            mass_kg,
            rate: GLoadRateMonitor::new(),
            peaks: PeakTracker::new(),
        })
    }

    /// Evaluate one sample: time \[s\], density \[kg/m^3\], speed \[m/s\], lift and drag \[N\].
    ///
    /// # Errors
    /// As the `try_*` functions and [`GLoadRateMonitor::update`]; the monitor (rate state and
    /// peaks) is unchanged on error.
    pub fn update(
        &mut self,
        time_s: S,
        density_kg_m3: S,
        speed_m_s: S,
        lift_n: S,
        drag_n: S,
    ) -> Result<ConstraintSample<S>, GuidanceError> {
        let heat = try_chapman_heat_flux_w_m2(density_kg_m3, speed_m_s, self.nose_radius_m)?;
        let n = try_g_load(lift_n, drag_n, self.mass_kg)?;
        let q = try_dynamic_pressure_pa(density_kg_m3, speed_m_s)?;
        let mut rate_monitor = self.rate;
        let rate = rate_monitor.update(time_s, n)?;
        let mut peaks = self.peaks;
        peaks.update(heat, n, rate)?;
        self.rate = rate_monitor;
        self.peaks = peaks;
        Ok(ConstraintSample {
            heat_flux_w_m2: heat,
            g_load: n,
            g_load_rate_per_s: rate,
            dynamic_pressure_pa: q,
        })
    }

    /// The running peaks.
    #[must_use]
    pub fn peaks(&self) -> PeakTracker<S> {
        self.peaks
    }

    /// Violation measures of the peaks so far (eq. 4.9-4.11).
    #[must_use]
    pub fn violations(&self, limits: &ConstraintLimits<S>) -> Violations<S> {
        self.peaks.violations(limits)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn timed_peak_keeps_the_first_maximum_and_its_time() {
        let mut p = TimedPeak::<f64>::default();
        for (v, t) in [
            (1.0, 0.5),
            (3.0, 1.0),
            (3.0, 2.0),
            (f64::NAN, 3.0),
            (2.0, 4.0),
        ] {
            p.update(v, t);
        }
        assert_eq!(
            p,
            TimedPeak {
                value: 3.0,
                time_s: 1.0
            }
        );
    }

    #[test]
    fn violation_measure_eq_4_9() {
        assert_eq!(violation(400.0e3, 500.0e3), 0.0);
        assert_eq!(violation(500.0e3, 500.0e3), 0.0);
        assert_eq!(violation(600.0e3, 500.0e3), 1.2);
        assert_eq!(violation(f64::NAN, 500.0e3), f64::MAX);
        assert_eq!(violation(1.0, 0.0), f64::MAX);
        let f = crate::Fixed::from_f64;
        assert!((violation(f(3.3), f(3.0)).to_f64() - 1.1).abs() < 1e-8);
        assert_eq!(violation(f(2.9), f(3.0)), crate::Fixed::ZERO);
    }

    #[test]
    fn rate_and_peaks() {
        let mut m = GLoadRateMonitor::<f64>::new();
        assert_eq!(m.update(0.0, 1.0), Ok(None));
        assert_eq!(m.update(2.0, 2.0), Ok(Some(0.5)));
        assert_eq!(m.update(2.0, 2.0), Err(GuidanceError::NonIncreasingTime));
        assert_eq!(m.update(f64::NAN, 2.0), Err(GuidanceError::NonFiniteState));
        assert_eq!(m.update(3.0, 1.0), Ok(Some(-1.0)));
        let mut p = PeakTracker::<f64>::new();
        p.update(1e5, 2.0, None).unwrap();
        p.update(6e5, 1.0, Some(-0.75)).unwrap();
        assert!(p.update(f64::INFINITY, 1.0, None).is_err());
        assert_eq!(
            (p.heat_flux_w_m2(), p.g_load(), p.g_load_rate_per_s()),
            (6e5, 2.0, 0.75)
        );
        let v = p.violations(&ConstraintLimits::thesis_default());
        assert_eq!(
            v,
            Violations {
                heat_flux: 1.2,
                g_load: 0.0,
                g_load_rate: 1.5
            }
        );
        assert!(!v.feasible());
    }

    #[test]
    fn invalid_input_is_an_error_or_zero_never_nan() {
        assert_eq!(
            try_chapman_heat_flux_w_m2(f64::NAN, 7000.0, 0.8),
            Err(GuidanceError::NonFiniteState)
        );
        assert_eq!(
            try_chapman_heat_flux_w_m2(1e-4, -1.0, 0.8),
            Err(GuidanceError::UnphysicalState)
        );
        assert_eq!(
            try_chapman_heat_flux_w_m2(1e-4, 7000.0, 0.0),
            Err(GuidanceError::UnphysicalState)
        );
        assert_eq!(chapman_heat_flux_w_m2(f64::NAN, 7000.0, 0.8), 0.0);
        assert_eq!(
            try_g_load(1.0, 1.0, 0.0),
            Err(GuidanceError::UnphysicalState)
        );
        assert_eq!(g_load(f64::INFINITY, 1.0, 1.0), 0.0);
        assert_eq!(
            try_dynamic_pressure_pa(-1.0, 1.0),
            Err(GuidanceError::UnphysicalState)
        );
        // f32: 1e30 N forces do not overflow the g-load (a sqrt(1 + (b/a)^2) form).
        let n = try_g_load(3e30_f32, 4e30_f32, 1.0).unwrap();
        // micromath's f32 sqrt: measured 2.5 % too large at 1.5625 (the 5e-3 of crate::math's
        // docs does not hold there), so 3e-2 with that feature.
        let rel = if cfg!(feature = "micromath") {
            3e-2
        } else {
            1e-6
        };
        assert!(
            (f64::from(n) - 5e30 / G0_M_S2).abs() < rel * 5e30 / G0_M_S2,
            "{n} {}",
            5e30 / G0_M_S2
        );
        // Overflow of the result is an error, not inf.
        assert_eq!(
            try_dynamic_pressure_pa(1.0_f32, 1e20),
            Err(GuidanceError::NonFiniteState)
        );
        let mut c = ConstraintMonitor::new(0.8, 26_029.0).unwrap();
        assert!(c.update(0.0, f64::NAN, 7000.0, 1e5, 1e5).is_err());
        assert_eq!(c.peaks(), PeakTracker::new());
        assert!(ConstraintMonitor::new(0.0, 1.0).is_err());
    }
}
