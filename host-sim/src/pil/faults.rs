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
//! in the [`super::PilRecord`], marked with its fault; the counts are in [`FaultCounts`]. The
//! injector is here; `faulty_link` flies a tick through it.

use guidance_core::NavState;
use guidance_core::link::FRAME_LEN;

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
    pub(super) pending: Option<NavState<f64>>,
}

/// What happens to one transmission.
pub(super) enum Fault {
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

    /// The fault of one transmission (only a first attempt may be delayed).
    pub(super) fn roll(&mut self, first_attempt: bool) -> Fault {
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
    pub(super) fn corrupt(&mut self, buf: &mut [u8; FRAME_LEN]) {
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
