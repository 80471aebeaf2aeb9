//! The closed loop flies `guidance-core`'s [`FlightStack`](guidance_core::stack::FlightStack): the attitude source of
//! [`crate::sim::simulate`] that hands each guidance tick's navigation state and sensed
//! accelerations to [`FlightStack::tick`](guidance_core::stack::FlightStack::tick) (the one entry the firmware calls too). The host
//! assembles no layer itself: it builds a [`guidance_core::stack::StackConfig`] (the scenario's,
//! [`crate::scenario::build_stack`], or a campaign mode's, `CampaignSetup::stack_of`).
//!
//! Every re-plan report is kept ([`StackSource::reports`]) with the context of its tick
//! ([`ReportContext`]), so a run can be checked for the re-planning rate and its predictions
//! recomputed.

use guidance_core::NavState;
use guidance_core::estimate::SensedAero;
use guidance_core::guidance::Command;
use guidance_core::lateral::LateralStatus;
use guidance_core::replan::ReplanReport;
use guidance_core::stack::HostFlightStack;

use crate::sim::{AttitudeSource, ReportContext, TickError};

/// A [`HostFlightStack`] in `f64` as the closed loop's attitude source.
#[derive(Clone, Debug)]
pub struct StackSource {
    /// The stack.
    pub stack: HostFlightStack<f64>,
    /// Every re-plan report of the run, in order.
    pub reports: Vec<ReplanReport<f64>>,
    /// The context of each report (same index).
    pub contexts: Vec<ReportContext>,
    /// The last lateral decision (`None` without the lateral layer).
    pub last_lateral: Option<LateralStatus<f64>>,
    /// The measurement of the coming tick ([`AttitudeSource::sense`] comes just before
    /// [`AttitudeSource::tick`] with the same state).
    sensed: Option<SensedAero<f64>>,
}

impl StackSource {
    /// Fly `stack`.
    #[must_use]
    pub fn new(stack: HostFlightStack<f64>) -> Self {
        Self {
            stack,
            reports: Vec::new(),
            contexts: Vec::new(),
            last_lateral: None,
            sensed: None,
        }
    }

    /// Bank reversals made (0 without the lateral layer).
    #[must_use]
    pub fn reversals(&self) -> u8 {
        self.stack.reversals()
    }
}

impl AttitudeSource for StackSource {
    type Error = TickError;
    fn tick(&mut self, nav: &NavState<f64>) -> Result<(), TickError> {
        let sensed = self.sensed.take();
        let out = self.stack.tick(nav, sensed.as_ref())?;
        // The simulator's sensed accelerations are valid by construction: a rejected one is
        // a simulator fault, not a flight condition.
        if let Some(e) = out.sensed_rejected {
            return Err(TickError::Estimate(e));
        }
        if out.lateral.is_some() {
            self.last_lateral = out.lateral;
        }
        if let Some(r) = out.replan {
            self.reports.push(r);
            self.contexts.push(ReportContext {
                nav: *nav,
                aero_scales: out.aero_scales,
            });
        }
        if out.ticked {
            Ok(())
        } else {
            Err(TickError::NoTick {
                time_s: nav.time_s,
                next_tick_s: self.stack.next_tick_s(),
            })
        }
    }
    fn sense(&mut self, _nav: &NavState<f64>, sensed: &SensedAero<f64>) -> Result<(), TickError> {
        self.sensed = Some(*sensed);
        Ok(())
    }
    fn senses(&self) -> bool {
        self.stack.uses_sensed()
    }
    fn attitude_at(&self, time_s: f64) -> Command<f64> {
        self.stack.attitude_at(time_s)
    }
    fn next_tick_s(&self) -> f64 {
        self.stack.next_tick_s()
    }
    fn next_kink_s(&self, time_s: f64) -> f64 {
        self.stack.next_ramp_kink_s(time_s).unwrap_or(f64::INFINITY)
    }
}
