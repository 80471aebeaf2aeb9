//! [`PilRecord`]: every frame exchanged with the firmware, kept by a handle the caller holds, so a
//! run that fails (a rejected frame, a dead link) still has its record up to the failure.

use std::fmt::Write as _;
use std::sync::{Arc, Mutex, PoisonError};

use guidance_core::NavState;
use guidance_core::link::CommandFrame;

/// One nav frame and what came back.
#[derive(Clone, Debug, PartialEq)]
pub struct Exchange {
    /// Sequence number of the nav frame.
    pub seq: u32,
    /// Navigation state sent.
    pub nav: NavState<f64>,
    /// The command frame received (`None`: none arrived).
    pub reply: Option<CommandFrame>,
    /// Why the exchange failed and ended the run (`None`: accepted).
    pub failure: Option<String>,
    /// The link fault injected into this exchange (`None`: none).
    pub fault: Option<String>,
}

/// Shared, append-only record of a PIL run (clone the handle before the run).
#[derive(Clone, Debug, Default)]
pub struct PilRecord(Arc<Mutex<Vec<Exchange>>>);

impl PilRecord {
    pub(super) fn push(&self, e: Exchange) {
        self.0
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .push(e);
    }

    /// Store the reply of the last exchange.
    pub(super) fn set_reply(&self, c: CommandFrame) {
        if let Some(last) = self
            .0
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .last_mut()
        {
            last.reply = Some(c);
        }
    }

    /// Mark the last exchange as the one that ended the run.
    pub(super) fn mark_failed(&self, why: String) {
        if let Some(last) = self
            .0
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .last_mut()
        {
            last.failure = Some(why);
        }
    }

    /// A copy of the exchanges so far.
    #[must_use]
    pub fn exchanges(&self) -> Vec<Exchange> {
        self.0
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .clone()
    }

    /// The record as CSV (SI units, radians): one row per exchange, the failure (if any) in the
    /// last column of the row that ended the run.
    #[must_use]
    pub fn to_csv(&self) -> String {
        let mut s = String::from(
            "seq,time_s,radius_m,speed_m_s,gamma_rad,heading_rad,latitude_rad,longitude_rad,status,tick_time_s,alpha_rad,sigma_rad,ramp_alpha_rad,ramp_sigma_rad,fault,failure\n",
        );
        for e in self.exchanges() {
            let n = &e.nav;
            let _ = write!(
                s,
                "{},{:e},{:e},{:e},{:e},{:e},{:e},{:e}",
                e.seq,
                n.time_s,
                n.radius_m,
                n.speed_m_s,
                n.flight_path_angle_rad,
                n.heading_rad,
                n.latitude_rad,
                n.longitude_rad
            );
            match e.reply {
                Some(c) => {
                    let _ = write!(
                        s,
                        ",{:?},{:e},{:e},{:e},{:e},{:e}",
                        c.status,
                        c.tick_time_s,
                        c.command.alpha_rad,
                        c.command.sigma_rad,
                        c.ramp_start.alpha_rad,
                        c.ramp_start.sigma_rad
                    );
                }
                None => s.push_str(",none,,,,,"),
            }
            let fault = e.fault.unwrap_or_default();
            let why = e.failure.unwrap_or_default().replace([',', '\n'], ";");
            let _ = writeln!(s, ",{fault},{why}");
        }
        s
    }
}
