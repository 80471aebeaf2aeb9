//! Seeded link faults on the flight's nav frames (issue 13.5), injected by the host harness:
//!
//! * **dropped**: the frame never reaches the firmware; the host (which would time out) retries
//!   at once, up to [`MAX_RETRIES`] times;
//! * **corrupted**: 1 to 3 bits flipped (CRC-16 detects every such error): the firmware rejects
//!   the frame, counts it and answers `BadFrame` with its held command; the host retries;
//! * **delayed past its tick**: the frame is not delivered in time; the host flies the held
//!   command over this tick and delivers the stale frame after the next tick's frame, which the
//!   firmware's guidance rejects (non-increasing time), counts, and keeps flying its command
//!   (a delayed frame superseded by a newer delayed one before any frame got through is not
//!   delivered; it stays in the record, marked).
//!
//! A tick whose retries all fail is flown on the held command (a missed tick). Every attempt is
//! in the [`super::PilRecord`], marked with its fault; the counts are in [`FaultCounts`].

use guidance_core::NavState;
use guidance_core::link::{FRAME_LEN, Frame, LinkStatus, NavFrame, decode, encode};

use super::{Exchange, PilError, PilGuidance};

/// Retries of one tick's nav frame after a drop or corruption.
pub const MAX_RETRIES: u32 = 3;

/// Fault probabilities per nav frame transmission, and the seed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaultConfig {
    /// Seed of the injector's generator (the same seed gives the same faults).
    pub seed: u64,
    /// Probability that a transmission is dropped \[-\].
    pub p_drop: f64,
    /// Probability that a transmission is corrupted \[-\].
    pub p_corrupt: f64,
    /// Probability that a tick's frame is delayed past its tick \[-\].
    pub p_delay: f64,
}

/// Faults injected and their outcomes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FaultCounts {
    /// Transmissions dropped.
    pub dropped: u64,
    /// Transmissions corrupted (each rejected by the firmware).
    pub corrupted: u64,
    /// Frames delayed past their tick (each delivered late and rejected by the firmware).
    pub delayed: u64,
    /// Retransmissions.
    pub retries: u64,
    /// Ticks flown on the held command (delayed, or retries exhausted).
    pub missed_ticks: u64,
}

/// The seeded injector (splitmix64: portable, so a seed reproduces everywhere).
/// An injected fault the firmware must reject (answer with a fault status).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RejectedFault {
    /// A frame with corrupted bits (the firmware must answer `BadFrame`).
    Corrupted,
    /// A delayed frame delivered after a newer one (the firmware must answer
    /// `NonIncreasingTime` or `ImplausibleTime`).
    Stale,
}

impl std::fmt::Display for RejectedFault {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            RejectedFault::Corrupted => "corrupted",
            RejectedFault::Stale => "stale",
        })
    }
}

#[derive(Clone, Debug)]
pub struct FaultInjector {
    cfg: FaultConfig,
    state: u64,
    /// A delayed nav frame waiting to be delivered after the next tick's frame.
    pending: Option<NavState<f64>>,
}

enum Fault {
    None,
    Drop,
    Corrupt,
    Delay,
}

impl FaultInjector {
    /// An injector with `cfg`.
    #[must_use]
    pub fn new(cfg: FaultConfig) -> Self {
        Self {
            cfg,
            state: cfg.seed,
            pending: None,
        }
    }

    fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    fn roll(&mut self, first_attempt: bool) -> Fault {
        let u = self.uniform();
        let c = &self.cfg;
        if u < c.p_drop {
            Fault::Drop
        } else if u < c.p_drop + c.p_corrupt {
            Fault::Corrupt
        } else if first_attempt && u < c.p_drop + c.p_corrupt + c.p_delay {
            Fault::Delay
        } else {
            Fault::None
        }
    }

    /// Flip 1 to 3 distinct bits of `buf`.
    fn corrupt(&mut self, buf: &mut [u8; FRAME_LEN]) {
        let n = 1 + self.next_u64() % 3;
        let mut flipped = [usize::MAX; 3];
        let mut k = 0;
        while k < n as usize {
            let bit = (self.next_u64() % (8 * FRAME_LEN as u64)) as usize;
            if flipped.contains(&bit) {
                continue;
            }
            if let (Some(f), Some(b)) = (flipped.get_mut(k), buf.get_mut(bit / 8)) {
                *f = bit;
                *b ^= 1 << (bit % 8);
            }
            k += 1;
        }
    }
}

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
