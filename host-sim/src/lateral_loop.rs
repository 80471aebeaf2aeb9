//! Closed loop with lateral guidance: `guidance-core`'s [`BankReversalLogic`] decides the bank
//! sign at every guidance tick, before the tick's update of the wrapped guidance (stored
//! profile or re-planner, any [`FlightGuidance`]), which keeps the magnitude and rate-limits
//! the signed command (so a reversal is a ramp). Without a logic it is the plain
//! [`GuidanceSource`].

use guidance_core::NavState;
use guidance_core::estimate::SensedAero;
use guidance_core::guidance::Command;
use guidance_core::lateral::{BankReversalLogic, LateralStatus};

use crate::sim::{AttitudeSource, FlightGuidance, GuidanceSource, TickError};

/// A [`GuidanceSource`] with optional bank-reversal logic.
pub struct LateralSource<G: FlightGuidance> {
    /// The guidance and its reports.
    pub inner: GuidanceSource<G>,
    /// The lateral logic (`None`: the table's own sign).
    pub logic: Option<BankReversalLogic<f64>>,
    /// The last lateral decision.
    pub last: Option<LateralStatus<f64>>,
}

impl<G: FlightGuidance> LateralSource<G> {
    /// Wrap `guidance` with `logic`.
    #[must_use]
    pub fn new(guidance: G, logic: Option<BankReversalLogic<f64>>) -> Self {
        Self {
            inner: GuidanceSource::new(guidance),
            logic,
            last: None,
        }
    }

    /// Bank reversals made (0 without a logic).
    #[must_use]
    pub fn reversals(&self) -> u8 {
        self.logic.as_ref().map_or(0, BankReversalLogic::reversals)
    }
}

impl<G: FlightGuidance> AttitudeSource for LateralSource<G> {
    type Error = TickError;
    fn tick(&mut self, nav: &NavState<f64>) -> Result<(), TickError> {
        if let Some(logic) = &mut self.logic {
            let status = logic.update(nav)?;
            self.inner.guidance.set_bank_sign(Some(status.sign));
            self.last = Some(status);
        }
        self.inner.tick(nav)
    }
    fn sense(&mut self, nav: &NavState<f64>, sensed: &SensedAero<f64>) -> Result<(), TickError> {
        self.inner.sense(nav, sensed)
    }
    fn senses(&self) -> bool {
        self.inner.senses()
    }
    fn attitude_at(&self, time_s: f64) -> Command<f64> {
        self.inner.attitude_at(time_s)
    }
    fn next_tick_s(&self) -> f64 {
        self.inner.next_tick_s()
    }
    fn next_kink_s(&self, time_s: f64) -> f64 {
        self.inner.next_kink_s(time_s)
    }
}
