//! The simulated IMU of a campaign case: what the onboard estimator receives instead of the
//! exact lift and drag accelerations of the simulated vehicle.
//!
//! Each axis (lift, drag) reads `a (1 + scale) + bias + noise`: a scale-factor error and a bias
//! constant over the flight (drawn per case, [`super::draw::CaseDraw`]), and white noise drawn
//! at every sensed sample (2 s guidance tick) from the case's own generator
//! ([`super::draw::case_seed`] of the campaign seed mixed with a stream constant and the case
//! index), so a case senses the same numbers whatever the thread count or order. A reading
//! below zero is clipped to zero (the accelerations are magnitudes).

use guidance_core::NavState;
use guidance_core::estimate::SensedAero;
use guidance_core::guidance::Command;

use super::draw::{CaseDraw, standard_normal_3};
use crate::optim::OptimRng;
use crate::sim::AttitudeSource;

/// Error model of the simulated IMU (SI units; scales as fractions).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImuModel {
    /// Bias of the lift and drag accelerations \[m/s^2\].
    pub bias_m_s2: [f64; 2],
    /// Scale-factor error of the lift and drag accelerations \[-\].
    pub scale: [f64; 2],
    /// Standard deviation of the white noise per sample \[m/s^2\] (normal, truncated at 3
    /// sigma).
    pub noise_m_s2: f64,
    /// Seed of the noise generator.
    pub noise_seed: u64,
}

impl ImuModel {
    /// The IMU of a case.
    #[must_use]
    pub fn of(d: &CaseDraw) -> Self {
        Self {
            bias_m_s2: [d.imu_lift_bias_m_s2, d.imu_drag_bias_m_s2],
            scale: [d.imu_lift_scale, d.imu_drag_scale],
            noise_m_s2: d.imu_noise_m_s2,
            noise_seed: d.imu_noise_seed,
        }
    }

    /// True if the IMU is exact.
    #[must_use]
    pub fn is_exact(&self) -> bool {
        self.bias_m_s2 == [0.0; 2] && self.scale == [0.0; 2] && self.noise_m_s2 == 0.0
    }
}

/// An [`AttitudeSource`] whose sensed accelerations go through an [`ImuModel`]; everything
/// else is passed on unchanged.
pub struct ImuSource<A: AttitudeSource> {
    /// The wrapped source.
    pub source: A,
    model: ImuModel,
    rng: OptimRng,
}

impl<A: AttitudeSource> ImuSource<A> {
    /// Wrap `source` with the IMU `model`.
    #[must_use]
    pub fn new(source: A, model: ImuModel) -> Self {
        Self {
            source,
            model,
            rng: OptimRng::new(model.noise_seed),
        }
    }

    /// One axis' reading of the true acceleration `a` \[m/s^2\].
    fn read(&mut self, axis: usize, a: f64) -> f64 {
        let m = &self.model;
        let (bias, scale) = (
            m.bias_m_s2.get(axis).copied().unwrap_or(0.0),
            m.scale.get(axis).copied().unwrap_or(0.0),
        );
        let noise = if m.noise_m_s2 > 0.0 {
            m.noise_m_s2 * standard_normal_3(&mut self.rng)
        } else {
            0.0
        };
        (a * (1.0 + scale) + bias + noise).max(0.0)
    }
}

impl<A: AttitudeSource> AttitudeSource for ImuSource<A> {
    type Error = A::Error;
    fn tick(&mut self, nav: &NavState<f64>) -> Result<(), Self::Error> {
        self.source.tick(nav)
    }
    fn sense(&mut self, nav: &NavState<f64>, sensed: &SensedAero<f64>) -> Result<(), Self::Error> {
        if self.model.is_exact() {
            return self.source.sense(nav, sensed);
        }
        let noisy = SensedAero {
            lift_m_s2: self.read(0, sensed.lift_m_s2),
            drag_m_s2: self.read(1, sensed.drag_m_s2),
        };
        self.source.sense(nav, &noisy)
    }
    fn senses(&self) -> bool {
        self.source.senses()
    }
    fn attitude_at(&self, time_s: f64) -> Command<f64> {
        self.source.attitude_at(time_s)
    }
    fn next_tick_s(&self) -> f64 {
        self.source.next_tick_s()
    }
    fn next_kink_s(&self, time_s: f64) -> f64 {
        self.source.next_kink_s(time_s)
    }
}
