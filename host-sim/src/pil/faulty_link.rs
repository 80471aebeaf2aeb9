//! One tick of [`PilGuidance`] through the faulty link: the injector's fault of each attempt
//! ([`super::faults`], which documents the faults and the retries) acted out on the frames and
//! recorded.

use guidance_core::NavState;
use guidance_core::link::{FRAME_LEN, Frame, LinkStatus, NavFrame, decode, encode};

use super::faults::{Fault, MAX_RETRIES, RejectedFault};
use super::{Exchange, PilError, PilGuidance};

impl PilGuidance {
    fn note(&self, seq: u32, nav: &NavState<f64>, fault: &str) {
        self.record.push(Exchange {
            seq,
            nav: *nav,
            reply: None,
            failure: None,
            fault: Some(fault.to_string()),
        });
    }

    /// One tick through the faulty link (see the module docs).
    pub(super) fn tick_with_faults(&mut self, nav: &NavState<f64>) -> Result<(), PilError> {
        let mut flown = None;
        for attempt in 0..=MAX_RETRIES {
            if attempt > 0 {
                self.stats.faults.retries += 1;
            }
            let Some(inj) = self.faults.as_mut() else {
                break;
            };
            match inj.roll(attempt == 0) {
                Fault::None => {
                    flown = Some(self.exchange(nav)?);
                    break;
                }
                Fault::Drop => {
                    self.stats.faults.dropped += 1;
                    let seq = self.next_seq();
                    self.note(seq, nav, "dropped");
                }
                Fault::Corrupt => {
                    self.stats.faults.corrupted += 1;
                    let seq = self.next_seq();
                    let mut buf = [0u8; FRAME_LEN];
                    encode(
                        &Frame::Nav(NavFrame {
                            seq,
                            nav: *nav,
                            sensed: None,
                        }),
                        &mut buf,
                    )
                    .map_err(PilError::Link)?;
                    if let Some(inj) = self.faults.as_mut() {
                        inj.corrupt(&mut buf);
                    }
                    self.note(seq, nav, "corrupted");
                    let answer = self.roundtrip(&buf)?;
                    match decode(&answer).map_err(PilError::Link)? {
                        Frame::Command(c) if c.status == LinkStatus::BadFrame => {
                            self.record.set_reply(c);
                        }
                        answer => {
                            return Err(PilError::FaultNotRejected {
                                seq,
                                fault: RejectedFault::Corrupted,
                                answer,
                            });
                        }
                    }
                }
                Fault::Delay => {
                    self.stats.faults.delayed += 1;
                    if let Some(inj) = self.faults.as_mut() {
                        inj.pending = Some(*nav);
                    }
                    let seq = self.next_seq();
                    self.note(seq, nav, "delayed past its tick");
                    break;
                }
            }
        }
        match flown {
            Some(c) => {
                self.next_tick_s = c.tick_time_s + self.period_s;
                self.last = Some(c);
                self.deliver_stale()?;
            }
            None => {
                // Hold: the firmware's command continues; the next tick is one period on.
                self.stats.faults.missed_ticks += 1;
                self.next_tick_s = nav.time_s + self.period_s;
            }
        }
        Ok(())
    }

    /// Deliver a delayed frame after a newer one: the firmware must reject it.
    fn deliver_stale(&mut self) -> Result<(), PilError> {
        let Some(stale) = self.faults.as_mut().and_then(|i| i.pending.take()) else {
            return Ok(());
        };
        let seq = self.next_seq();
        let mut buf = [0u8; FRAME_LEN];
        encode(
            &Frame::Nav(NavFrame {
                seq,
                nav: stale,
                sensed: None,
            }),
            &mut buf,
        )
        .map_err(PilError::Link)?;
        self.note(seq, &stale, "delivered late");
        let answer = self.roundtrip(&buf)?;
        match decode(&answer).map_err(PilError::Link)? {
            Frame::Command(c)
                if c.seq == seq
                    && matches!(
                        c.status,
                        LinkStatus::NonIncreasingTime | LinkStatus::ImplausibleTime
                    ) =>
            {
                self.record.set_reply(c);
                Ok(())
            }
            answer => Err(PilError::FaultNotRejected {
                seq,
                fault: RejectedFault::Stale,
                answer,
            }),
        }
    }
}
