//! Processor-in-the-loop (PIL) link frames: the one definition of the byte format shared by
//! the host simulator (`host-sim::pil`) and the firmware (`onboard-demo`'s `pil` binary).
//!
//! # Frame layout
//! Every frame is [`FRAME_LEN`] = 82 bytes, all integers and floats little-endian:
//!
//! | bytes  | field                                                            |
//! |--------|------------------------------------------------------------------|
//! | 0..2   | sync word [`SYNC`] (`0xA5, 0x5A`)                                |
//! | 2      | frame type ([`FrameType`])                                       |
//! | 3      | status ([`LinkStatus`]; 0 except in command frames)             |
//! | 4..8   | sequence number (`u32`; a command answers the nav frame's number) |
//! | 8..80  | payload: nine `f64` (unused slots are 0), or raw image bytes      |
//! | 80..82 | CRC-16/CCITT-FALSE over bytes 0..80 ([`crc16_ccitt`])             |
//!
//! Payloads (all `f64`, SI units, radians):
//! * nav: time \[s\], radius \[m\], speed \[m/s\], flight-path angle \[rad\], heading \[rad\],
//!   latitude \[rad\], longitude \[rad\] (the [`NavState`] field order), then the sensed lift
//!   and drag accelerations \[m/s^2\] (type [`FrameType::NavSensed`]; 0 in a
//!   [`FrameType::Nav`] frame, which carries no measurement);
//! * command: tick time \[s\], held alpha \[rad\], held sigma \[rad\], ramp-start alpha \[rad\],
//!   ramp-start sigma \[rad\], alpha rate limit \[rad/s\], sigma rate limit \[rad/s\], bank
//!   reversals made \[-\], re-plans run \[-\] (exact integers);
//! * end: none (all zero);
//! * set-up (protocol v1): slot 0 the item code, then the item's values
//!   ([`crate::setup::SetupItem`]; slots 7 and 8 are 0);
//! * image (set-up protocol v2, [`crate::setup::image`]): bytes 8..10 the chunk index, 10..12
//!   the chunk count (`u16`), 12..80 the [`CHUNK_BYTES`] image bytes of the chunk (raw, not
//!   floats).
//!
//! Why `f64` on the wire although the firmware runs `f32` guidance: the host's state goes over
//! unchanged and the firmware rounds it to `f32` itself (exactly where an `f32` SIL run would),
//! and every `f32` the firmware answers with is exactly representable in `f64`. One payload type
//! keeps the codec a few lines long; 66 bytes per frame is far below what the link can carry.
//!
//! Between ticks the host reproduces the attitude from a command frame: from the ramp start at
//! the tick time it moves towards the held command at the rate limits
//! ([`CommandFrame::attitude_at`], the same rule as [`crate::guidance::Guidance::attitude_at`]).
//!
//! Decoding rejects a wrong length, sync word, checksum, type or status and any non-finite
//! payload value, so nothing non-finite crosses the link.

use crate::command::Command;
use crate::error::{GuidanceError, NodeTableError};
use crate::estimate::SensedAero;
use crate::nav::NavState;
use crate::rate::{RampEnd, RateLimits, limit_command, ramp_end};
use crate::setup::image::{CHUNK_BYTES, ImageError};
use crate::setup::{SetupError, SetupItem};
use crate::stack::StackBuildError;

/// Length of every frame \[bytes\].
pub const FRAME_LEN: usize = 82;
/// Sync word at the start of every frame.
pub const SYNC: [u8; 2] = [0xA5, 0x5A];
/// Number of `f64` payload slots.
const SLOTS: usize = 9;
/// Offset of the payload \[bytes\].
const PAYLOAD: usize = 8;
/// Offset of the checksum \[bytes\].
const CRC_AT: usize = FRAME_LEN - 2;

/// Errors of decoding (and of encoding non-finite values).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum LinkError {
    /// The byte slice is not [`FRAME_LEN`] long.
    BadLength,
    /// The first two bytes are not [`SYNC`].
    BadSync,
    /// The checksum does not match the bytes.
    BadChecksum,
    /// Unknown frame type byte.
    BadType,
    /// Unknown status byte, or a non-zero status in a nav or end frame.
    BadStatus,
    /// An end frame whose payload is not all zero, or a set-up frame that is no item.
    BadPayload,
    /// A payload value is NaN or infinite.
    NonFinite,
}

impl core::fmt::Display for LinkError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            LinkError::BadLength => "frame has the wrong length",
            LinkError::BadSync => "frame has a bad sync word",
            LinkError::BadChecksum => "frame checksum mismatch",
            LinkError::BadType => "unknown frame type",
            LinkError::BadStatus => "unknown status code, or a status in a nav or end frame",
            LinkError::BadPayload => {
                "end frame with a non-zero payload, or a malformed set-up item"
            }
            LinkError::NonFinite => "frame carries a non-finite value",
        })
    }
}

impl core::error::Error for LinkError {}

/// Frame type byte.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u8)]
pub enum FrameType {
    /// Host -> firmware: navigation state.
    Nav = 1,
    /// Firmware -> host: command and ramp.
    Command = 2,
    /// Host -> firmware: end of run (the firmware exits 0).
    End = 3,
    /// Host -> firmware: one guidance set-up item ([`crate::setup`]); answered by a command
    /// frame whose status says whether it was taken.
    Setup = 4,
    /// Host -> firmware: one chunk of a set-up image ([`crate::setup::image`]); answered by
    /// a command frame whose status says whether it was taken (after the last chunk: whether
    /// the stack was built).
    Image = 5,
    /// Host -> firmware: navigation state with the sensed lift and drag accelerations.
    NavSensed = 6,
}

/// Outcome of one guidance update on the firmware, carried in command frames. Maps
/// [`GuidanceError`] one to one (see [`LinkStatus::from_error`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum LinkStatus {
    /// The sample was a tick; the command was recomputed.
    Ok,
    /// The sample was accepted but was not a tick (command held).
    NotTicked,
    /// [`GuidanceError::NonFiniteState`].
    NonFiniteState,
    /// [`GuidanceError::UnphysicalState`].
    UnphysicalState,
    /// [`GuidanceError::InvalidConfig`].
    InvalidConfig,
    /// [`GuidanceError::NodeTable`] (the detail stays on the firmware).
    NodeTable,
    /// [`GuidanceError::NonIncreasingTime`].
    NonIncreasingTime,
    /// The firmware received a frame it could not decode or did not expect.
    BadFrame,
    /// [`GuidanceError::ImplausibleTime`].
    ImplausibleTime,
    /// A set-up item was malformed, out of order, or the set-up incomplete at commit
    /// ([`crate::setup::SetupError`] other than a core error).
    BadSetup,
    /// A set-up image failed its CRC-32 ([`ImageError::BadCrc`]).
    ImageCrc,
    /// A set-up image of another format version, or not an image
    /// ([`ImageError::BadVersion`], [`ImageError::BadMagic`]).
    ImageVersion,
    /// A set-up image with a layer this build does not fly ([`ImageError::Unsupported`]).
    ImageLayer,
    /// A set-up image too large for the build, of the wrong size, or with more nodes than the
    /// build holds ([`ImageError::Size`], [`ImageError::TooManyNodes`]).
    ImageSize,
    /// A set-up image chunk out of order ([`ImageError::ChunkOrder`]).
    ImageOrder,
    /// A malformed set-up image field, or a value the firmware's scalar cannot hold
    /// ([`ImageError::Malformed`], [`ImageError::Range`]).
    ImageMalformed,
    /// The stack of a set-up image was rejected by the core's checks
    /// ([`crate::stack::FlightStack::new`]).
    StackRejected,
}

impl LinkStatus {
    /// Status of a set-up error: the core's error as [`LinkStatus::from_error`], anything
    /// else (malformed item, bad index, incomplete set-up) [`LinkStatus::BadSetup`].
    #[must_use]
    pub fn from_setup_error(e: SetupError) -> Self {
        match e {
            SetupError::Guidance(g) => Self::from_error(g),
            _ => LinkStatus::BadSetup,
        }
    }

    /// Status of a set-up image refusal.
    #[must_use]
    pub fn from_image_error(e: ImageError) -> Self {
        match e {
            ImageError::BadCrc => LinkStatus::ImageCrc,
            ImageError::BadMagic | ImageError::BadVersion { .. } => LinkStatus::ImageVersion,
            ImageError::Unsupported(_) => LinkStatus::ImageLayer,
            ImageError::Size | ImageError::TooManyNodes => LinkStatus::ImageSize,
            ImageError::ChunkOrder => LinkStatus::ImageOrder,
            ImageError::Malformed | ImageError::Range => LinkStatus::ImageMalformed,
        }
    }

    /// Status of a stack the core refused to build.
    #[must_use]
    pub fn from_stack_error(_: StackBuildError) -> Self {
        LinkStatus::StackRejected
    }

    /// Status of a guidance error.
    #[must_use]
    pub fn from_error(e: GuidanceError) -> Self {
        match e {
            GuidanceError::NonFiniteState => LinkStatus::NonFiniteState,
            GuidanceError::UnphysicalState => LinkStatus::UnphysicalState,
            GuidanceError::NodeTable(_) => LinkStatus::NodeTable,
            GuidanceError::NonIncreasingTime => LinkStatus::NonIncreasingTime,
            GuidanceError::ImplausibleTime => LinkStatus::ImplausibleTime,
            _ => LinkStatus::InvalidConfig,
        }
    }

    /// The guidance error a status stands for (`None` for [`LinkStatus::Ok`],
    /// [`LinkStatus::NotTicked`], [`LinkStatus::BadFrame`] and [`LinkStatus::BadSetup`]). A node-table error comes back
    /// as `NodeTable(TooFewNodes)`: the detail is not carried.
    #[must_use]
    pub fn to_error(self) -> Option<GuidanceError> {
        match self {
            LinkStatus::NonFiniteState => Some(GuidanceError::NonFiniteState),
            LinkStatus::UnphysicalState => Some(GuidanceError::UnphysicalState),
            LinkStatus::InvalidConfig => Some(GuidanceError::InvalidConfig),
            LinkStatus::NodeTable => Some(GuidanceError::NodeTable(NodeTableError::TooFewNodes)),
            LinkStatus::NonIncreasingTime => Some(GuidanceError::NonIncreasingTime),
            LinkStatus::ImplausibleTime => Some(GuidanceError::ImplausibleTime),
            LinkStatus::Ok
            | LinkStatus::NotTicked
            | LinkStatus::BadFrame
            | LinkStatus::BadSetup
            | LinkStatus::ImageCrc
            | LinkStatus::ImageVersion
            | LinkStatus::ImageLayer
            | LinkStatus::ImageSize
            | LinkStatus::ImageOrder
            | LinkStatus::ImageMalformed
            | LinkStatus::StackRejected => None,
        }
    }

    fn code(self) -> u8 {
        match self {
            LinkStatus::Ok => 0,
            LinkStatus::NotTicked => 1,
            LinkStatus::NonFiniteState => 2,
            LinkStatus::UnphysicalState => 3,
            LinkStatus::InvalidConfig => 4,
            LinkStatus::NodeTable => 5,
            LinkStatus::NonIncreasingTime => 6,
            LinkStatus::BadFrame => 7,
            LinkStatus::ImplausibleTime => 8,
            LinkStatus::BadSetup => 9,
            LinkStatus::ImageCrc => 10,
            LinkStatus::ImageVersion => 11,
            LinkStatus::ImageLayer => 12,
            LinkStatus::ImageSize => 13,
            LinkStatus::ImageOrder => 14,
            LinkStatus::ImageMalformed => 15,
            LinkStatus::StackRejected => 16,
        }
    }

    fn from_code(c: u8) -> Result<Self, LinkError> {
        Ok(match c {
            0 => LinkStatus::Ok,
            1 => LinkStatus::NotTicked,
            2 => LinkStatus::NonFiniteState,
            3 => LinkStatus::UnphysicalState,
            4 => LinkStatus::InvalidConfig,
            5 => LinkStatus::NodeTable,
            6 => LinkStatus::NonIncreasingTime,
            7 => LinkStatus::BadFrame,
            8 => LinkStatus::ImplausibleTime,
            9 => LinkStatus::BadSetup,
            10 => LinkStatus::ImageCrc,
            11 => LinkStatus::ImageVersion,
            12 => LinkStatus::ImageLayer,
            13 => LinkStatus::ImageSize,
            14 => LinkStatus::ImageOrder,
            15 => LinkStatus::ImageMalformed,
            16 => LinkStatus::StackRejected,
            _ => return Err(LinkError::BadStatus),
        })
    }
}

/// Host -> firmware: one navigation sample.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct NavFrame {
    /// Sequence number \[-\].
    pub seq: u32,
    /// Navigation state (SI units, radians).
    pub nav: NavState<f64>,
    /// The lift and drag accelerations \[m/s^2\] sensed at `nav` (`None`: no measurement).
    pub sensed: Option<SensedAero<f64>>,
}

/// Firmware -> host: the guidance answer to one [`NavFrame`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CommandFrame {
    /// Sequence number of the nav frame answered \[-\].
    pub seq: u32,
    /// Outcome of the update.
    pub status: LinkStatus,
    /// Time of the last tick \[s\] (start of the ramp).
    pub tick_time_s: f64,
    /// Held (rate-limited) command \[rad\].
    pub command: Command<f64>,
    /// Attitude at the last tick, where the ramp starts \[rad\].
    pub ramp_start: Command<f64>,
    /// Rate limits of the ramp \[rad/s\].
    pub rates: RateLimits<f64>,
    /// Bank reversals the firmware's stack has made \[-\] (0 without the lateral layer).
    pub reversals: u32,
    /// Re-plans the firmware's stack has run \[-\] (0 without the re-planner).
    pub replans: u32,
}

impl CommandFrame {
    /// Attitude at `time_s` \[s\]: the ramp start up to the tick time, then moving towards the
    /// held command at the rate limits (reaching it is final). Equal to the firmware's
    /// `Guidance::attitude_at` up to its `f32` rounding; a NaN time gives the held command.
    #[must_use]
    pub fn attitude_at(&self, time_s: f64) -> Command<f64> {
        let dt = time_s - self.tick_time_s;
        if dt.is_nan() {
            self.command
        } else if dt <= 0.0 {
            self.ramp_start
        } else {
            limit_command(self.ramp_start, self.command, self.rates, dt)
        }
    }

    /// When the ramp of [`CommandFrame::attitude_at`] reaches the command, per angle \[s\]
    /// (the firmware's `Guidance::ramp_end_s`, from the frame).
    #[must_use]
    pub fn ramp_end(&self) -> RampEnd<f64> {
        ramp_end(self.ramp_start, self.command, self.rates, self.tick_time_s)
    }
}

/// Any frame.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Frame {
    /// Navigation sample.
    Nav(NavFrame),
    /// Command answer.
    Command(CommandFrame),
    /// End of run, with its sequence number \[-\].
    End(u32),
    /// Guidance set-up item.
    Setup(SetupFrame),
    /// One chunk of a set-up image.
    Image(ImageFrame),
}

/// Host -> firmware: one chunk of a set-up image ([`crate::setup::image`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ImageFrame {
    /// Sequence number \[-\].
    pub seq: u32,
    /// Index of this chunk (from 0) \[-\].
    pub index: u16,
    /// Number of chunks of the image \[-\].
    pub count: u16,
    /// The chunk's image bytes (the last chunk padded with zeros).
    pub data: [u8; CHUNK_BYTES],
}

/// Host -> firmware: one guidance set-up item.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SetupFrame {
    /// Sequence number \[-\].
    pub seq: u32,
    /// The item.
    pub item: SetupItem,
}

/// CRC-16/CCITT-FALSE (polynomial 0x1021, initial value 0xFFFF, no reflection, no final xor;
/// check value 0x29B1 for `b"123456789"`).
#[must_use]
pub fn crc16_ccitt(bytes: &[u8]) -> u16 {
    let mut crc: u16 = 0xFFFF;
    for &b in bytes {
        crc ^= u16::from(b) << 8;
        for _ in 0..8 {
            crc = if crc & 0x8000 != 0 {
                (crc << 1) ^ 0x1021
            } else {
                crc << 1
            };
        }
    }
    crc
}

/// Write one frame into `out`.
///
/// # Errors
/// [`LinkError::NonFinite`] if a payload value is NaN or infinite (`out` is then unspecified
/// and must not be sent).
pub fn encode(frame: &Frame, out: &mut [u8; FRAME_LEN]) -> Result<(), LinkError> {
    let (ty, status, seq, vals) = match frame {
        Frame::Nav(f) => {
            let n = &f.nav;
            let (ty, l, d) = match f.sensed {
                Some(s) => (FrameType::NavSensed, s.lift_m_s2, s.drag_m_s2),
                None => (FrameType::Nav, 0.0, 0.0),
            };
            (
                ty,
                0,
                f.seq,
                [
                    n.time_s,
                    n.radius_m,
                    n.speed_m_s,
                    n.flight_path_angle_rad,
                    n.heading_rad,
                    n.latitude_rad,
                    n.longitude_rad,
                    l,
                    d,
                ],
            )
        }
        Frame::Command(f) => (
            FrameType::Command,
            f.status.code(),
            f.seq,
            [
                f.tick_time_s,
                f.command.alpha_rad,
                f.command.sigma_rad,
                f.ramp_start.alpha_rad,
                f.ramp_start.sigma_rad,
                f.rates.alpha_rad_s,
                f.rates.sigma_rad_s,
                f64::from(f.reversals),
                f64::from(f.replans),
            ],
        ),
        Frame::End(seq) => (FrameType::End, 0, *seq, [0.0; SLOTS]),
        Frame::Setup(f) => {
            let [a, b, c, d, e, g, h] = f.item.to_slots();
            (FrameType::Setup, 0, f.seq, [a, b, c, d, e, g, h, 0.0, 0.0])
        }
        Frame::Image(f) => {
            let (head, rest) = out.split_at_mut(PAYLOAD);
            head.copy_from_slice(&header(FrameType::Image, 0, f.seq));
            let (payload, _) = rest.split_at_mut(CRC_AT - PAYLOAD);
            let (ic, data) = payload.split_at_mut(4);
            let [i0, i1] = f.index.to_le_bytes();
            let [c0, c1] = f.count.to_le_bytes();
            ic.copy_from_slice(&[i0, i1, c0, c1]);
            data.copy_from_slice(&f.data);
            seal(out);
            return Ok(());
        }
    };
    if vals.iter().any(|v| !v.is_finite()) {
        return Err(LinkError::NonFinite);
    }
    let (head, rest) = out.split_at_mut(PAYLOAD);
    let (payload, _) = rest.split_at_mut(CRC_AT - PAYLOAD);
    head.copy_from_slice(&header(ty, status, seq));
    for (chunk, v) in payload.chunks_exact_mut(8).zip(vals.iter()) {
        chunk.copy_from_slice(&v.to_le_bytes());
    }
    seal(out);
    Ok(())
}

fn header(ty: FrameType, status: u8, seq: u32) -> [u8; PAYLOAD] {
    let q = seq.to_le_bytes();
    [SYNC[0], SYNC[1], ty as u8, status, q[0], q[1], q[2], q[3]]
}

fn seal(out: &mut [u8; FRAME_LEN]) {
    let crc = match out.get(..CRC_AT) {
        Some(body) => crc16_ccitt(body),
        None => 0,
    };
    if let Some(c) = out.get_mut(CRC_AT..) {
        c.copy_from_slice(&crc.to_le_bytes());
    }
}

/// A count slot of a command frame: an exact integer in `u32`.
fn count(v: f64) -> Result<u32, LinkError> {
    if v >= 0.0 && v <= f64::from(u32::MAX) && libm::floor(v) == v {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        Ok(v as u32)
    } else {
        Err(LinkError::BadPayload)
    }
}

/// Read one frame from `bytes` (exactly [`FRAME_LEN`] long).
///
/// # Errors
/// [`LinkError`]: wrong length, sync word, checksum, type or status, or a non-finite value.
pub fn decode(bytes: &[u8]) -> Result<Frame, LinkError> {
    let frame: &[u8; FRAME_LEN] = bytes.try_into().map_err(|_| LinkError::BadLength)?;
    let (body, crc_bytes) = frame.split_at(CRC_AT);
    let (head, payload) = body.split_at(PAYLOAD);
    let &[s0, s1, ty, status, q0, q1, q2, q3] = head else {
        return Err(LinkError::BadLength);
    };
    if [s0, s1] != SYNC {
        return Err(LinkError::BadSync);
    }
    let crc = match crc_bytes {
        &[lo, hi] => u16::from_le_bytes([lo, hi]),
        _ => return Err(LinkError::BadLength),
    };
    if crc != crc16_ccitt(body) {
        return Err(LinkError::BadChecksum);
    }
    let seq = u32::from_le_bytes([q0, q1, q2, q3]);
    // Only command frames carry a status; every other frame must say `Ok` (0).
    if ty != FrameType::Command as u8 && status != LinkStatus::Ok.code() {
        return Err(LinkError::BadStatus);
    }
    if ty == FrameType::Image as u8 {
        let (ic, data) = payload.split_at(4);
        let &[i0, i1, c0, c1] = ic else {
            return Err(LinkError::BadLength);
        };
        let data: [u8; CHUNK_BYTES] = data.try_into().map_err(|_| LinkError::BadLength)?;
        return Ok(Frame::Image(ImageFrame {
            seq,
            index: u16::from_le_bytes([i0, i1]),
            count: u16::from_le_bytes([c0, c1]),
            data,
        }));
    }
    let mut v = [0.0_f64; SLOTS];
    for (slot, chunk) in v.iter_mut().zip(payload.chunks_exact(8)) {
        let mut b = [0u8; 8];
        b.copy_from_slice(chunk);
        *slot = f64::from_le_bytes(b);
    }
    if v.iter().any(|x| !x.is_finite()) {
        return Err(LinkError::NonFinite);
    }
    let [a, b, c, d, e, f, g, h, i] = v;
    // An end frame carries no payload (all slots +0.0), a nav frame without a measurement
    // and a set-up frame nothing in slots 7 and 8, as the layout above specifies.
    let zero = |x: f64| x.to_bits() == 0;
    if ty == FrameType::End as u8 && !v.iter().all(|x| zero(*x)) {
        return Err(LinkError::BadPayload);
    }
    if (ty == FrameType::Nav as u8 || ty == FrameType::Setup as u8) && !(zero(h) && zero(i)) {
        return Err(LinkError::BadPayload);
    }
    let nav = NavState {
        time_s: a,
        radius_m: b,
        speed_m_s: c,
        flight_path_angle_rad: d,
        heading_rad: e,
        latitude_rad: f,
        longitude_rad: g,
    };
    match ty {
        1 => Ok(Frame::Nav(NavFrame {
            seq,
            nav,
            sensed: None,
        })),
        6 => Ok(Frame::Nav(NavFrame {
            seq,
            nav,
            sensed: Some(SensedAero {
                lift_m_s2: h,
                drag_m_s2: i,
            }),
        })),
        2 => Ok(Frame::Command(CommandFrame {
            seq,
            status: LinkStatus::from_code(status)?,
            tick_time_s: a,
            command: Command {
                alpha_rad: b,
                sigma_rad: c,
            },
            ramp_start: Command {
                alpha_rad: d,
                sigma_rad: e,
            },
            rates: RateLimits {
                alpha_rad_s: f,
                sigma_rad_s: g,
            },
            reversals: count(h)?,
            replans: count(i)?,
        })),
        3 => Ok(Frame::End(seq)),
        4 => Ok(Frame::Setup(SetupFrame {
            seq,
            item: SetupItem::from_slots(&[a, b, c, d, e, f, g])
                .map_err(|_| LinkError::BadPayload)?,
        })),
        _ => Err(LinkError::BadType),
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn crc_check_value() {
        assert_eq!(crc16_ccitt(b"123456789"), 0x29B1);
    }

    fn nav_frame() -> Frame {
        Frame::Nav(NavFrame {
            seq: 7,
            nav: NavState {
                time_s: 2.0,
                radius_m: 6.5e6,
                speed_m_s: 7400.0,
                flight_path_angle_rad: -0.02,
                heading_rad: 1.2,
                latitude_rad: -0.4,
                longitude_rad: -1.8,
            },
            sensed: None,
        })
    }

    #[test]
    fn each_corruption_is_named() {
        let mut buf = [0u8; FRAME_LEN];
        encode(&nav_frame(), &mut buf).unwrap();
        assert_eq!(decode(&buf), Ok(nav_frame()));
        assert_eq!(decode(&buf[..FRAME_LEN - 1]), Err(LinkError::BadLength));
        let mut b = buf;
        b[0] ^= 1;
        assert_eq!(decode(&b), Err(LinkError::BadSync));
        // Any single-bit flip in the body or checksum is detected by the CRC.
        for byte in 2..FRAME_LEN {
            for bit in 0..8 {
                let mut b = buf;
                b[byte] ^= 1 << bit;
                assert_eq!(decode(&b), Err(LinkError::BadChecksum), "{byte} {bit}");
            }
        }
        // A valid CRC over an unknown type, an unknown status or a NaN is still rejected.
        let reseal = |b: &mut [u8; FRAME_LEN]| {
            let c = crc16_ccitt(&b[..CRC_AT]).to_le_bytes();
            b[CRC_AT..].copy_from_slice(&c);
        };
        let mut b = buf;
        b[2] = 9;
        reseal(&mut b);
        assert_eq!(decode(&b), Err(LinkError::BadType));
        let mut b = buf;
        b[2] = FrameType::Command as u8;
        b[3] = 200;
        reseal(&mut b);
        assert_eq!(decode(&b), Err(LinkError::BadStatus));
        let mut b = buf;
        b[PAYLOAD..PAYLOAD + 8].copy_from_slice(&f64::NAN.to_le_bytes());
        reseal(&mut b);
        assert_eq!(decode(&b), Err(LinkError::NonFinite));
    }

    /// Issue 8.7: nav and end frames carry no status (only command frames do) and an end frame
    /// no payload; a frame that says otherwise is rejected even with a valid checksum.
    #[test]
    fn nav_and_end_frames_reject_a_status_or_payload() {
        let reseal = |b: &mut [u8; FRAME_LEN]| {
            let c = crc16_ccitt(&b[..CRC_AT]).to_le_bytes();
            b[CRC_AT..].copy_from_slice(&c);
        };
        let mut nav = [0u8; FRAME_LEN];
        encode(&nav_frame(), &mut nav).unwrap();
        let mut end = [0u8; FRAME_LEN];
        encode(&Frame::End(3), &mut end).unwrap();
        assert_eq!(decode(&end), Ok(Frame::End(3)));
        for base in [nav, end] {
            for status in 1..=255u8 {
                let mut b = base;
                b[3] = status;
                reseal(&mut b);
                assert_eq!(decode(&b), Err(LinkError::BadStatus), "status {status}");
            }
        }
        for slot in 0..SLOTS {
            let mut b = end;
            let at = PAYLOAD + 8 * slot;
            b[at..at + 8].copy_from_slice(&(-0.0_f64).to_le_bytes());
            reseal(&mut b);
            assert_eq!(decode(&b), Err(LinkError::BadPayload), "slot {slot}");
        }
    }

    #[test]
    fn image_frames_carry_raw_bytes_and_sensed_nav_its_measurement() {
        let mut data = [0u8; CHUNK_BYTES];
        for (i, d) in data.iter_mut().enumerate() {
            *d = u8::try_from(i * 37 % 256).unwrap();
        }
        // NaN bit patterns are image bytes, not floats: carried as they are.
        data[..8].copy_from_slice(&f64::NAN.to_le_bytes());
        let f = Frame::Image(ImageFrame {
            seq: 9,
            index: 3,
            count: 11,
            data,
        });
        let mut b = [0u8; FRAME_LEN];
        encode(&f, &mut b).unwrap();
        assert_eq!(decode(&b), Ok(f));
        let Frame::Nav(mut n) = nav_frame() else {
            unreachable!()
        };
        n.sensed = Some(SensedAero {
            lift_m_s2: 12.5,
            drag_m_s2: 30.25,
        });
        encode(&Frame::Nav(n), &mut b).unwrap();
        assert_eq!(b[2], FrameType::NavSensed as u8);
        assert_eq!(decode(&b), Ok(Frame::Nav(n)));
        // A plain nav frame with something in the measurement slots is refused.
        encode(&nav_frame(), &mut b).unwrap();
        b[PAYLOAD + 7 * 8..PAYLOAD + 8 * 8].copy_from_slice(&1.0f64.to_le_bytes());
        let c = crc16_ccitt(&b[..CRC_AT]).to_le_bytes();
        b[CRC_AT..].copy_from_slice(&c);
        assert_eq!(decode(&b), Err(LinkError::BadPayload));
    }

    #[test]
    fn non_finite_is_not_encoded() {
        let mut f = nav_frame();
        if let Frame::Nav(n) = &mut f {
            n.nav.speed_m_s = f64::INFINITY;
        }
        assert_eq!(encode(&f, &mut [0u8; FRAME_LEN]), Err(LinkError::NonFinite));
    }

    #[test]
    fn status_maps_guidance_errors() {
        for e in [
            GuidanceError::NonFiniteState,
            GuidanceError::UnphysicalState,
            GuidanceError::InvalidConfig,
            GuidanceError::NonIncreasingTime,
            GuidanceError::ImplausibleTime,
        ] {
            assert_eq!(LinkStatus::from_error(e).to_error(), Some(e));
        }
        assert_eq!(LinkStatus::Ok.to_error(), None);
    }

    #[test]
    fn ramp_matches_core_guidance() {
        use crate::energy::EnergyNormalizer;
        use crate::guidance::{Guidance, GuidanceConfig};
        use crate::interp::Interpolation;
        let table = crate::missions::horus2b_reference::<f64>().unwrap().table;
        let energy = EnergyNormalizer::new(3.986e14, 6.378e6, 6.5e6, 7435.5).unwrap();
        let init = Command::from_deg(40.0, 0.0).unwrap();
        let mut g = Guidance::new(
            GuidanceConfig::thesis_default(),
            table,
            Interpolation::Linear,
            energy,
            init,
        )
        .unwrap();
        let Frame::Nav(mut nav) = nav_frame() else {
            unreachable!()
        };
        for k in 0..200 {
            nav.nav.time_s = 2.0 * f64::from(k);
            g.update(&nav.nav).unwrap();
            let t_k = g.last_tick_s().unwrap();
            let cf = CommandFrame {
                seq: k,
                status: LinkStatus::Ok,
                tick_time_s: t_k,
                command: g.command(),
                ramp_start: g.attitude_at(t_k),
                rates: g.config().rates,
                reversals: 0,
                replans: 0,
            };
            assert_eq!(Some(cf.ramp_end()), g.ramp_end_s(), "tick {k}");
            for j in 0..=8 {
                let t = t_k + 0.25 * f64::from(j);
                let (a, b) = (cf.attitude_at(t), g.attitude_at(t));
                assert!((a.alpha_rad - b.alpha_rad).abs() < 1e-15, "t {t}");
                assert!((a.sigma_rad - b.sigma_rad).abs() < 1e-15, "t {t}");
            }
        }
    }

    fn finite() -> impl Strategy<Value = f64> {
        prop::num::f64::NORMAL | prop::num::f64::ZERO | prop::num::f64::SUBNORMAL
    }

    fn frame() -> impl Strategy<Value = Frame> {
        let vals = prop::array::uniform7(finite());
        let status = 0u8..17;
        (any::<u32>(), 0u8..3, status, vals).prop_map(|(seq, ty, st, v)| {
            let [a, b, c, d, e, f, g] = v;
            match ty {
                0 => Frame::Nav(NavFrame {
                    seq,
                    nav: NavState {
                        time_s: a,
                        radius_m: b,
                        speed_m_s: c,
                        flight_path_angle_rad: d,
                        heading_rad: e,
                        latitude_rad: f,
                        longitude_rad: g,
                    },
                    sensed: (seq % 2 == 1).then_some(SensedAero {
                        lift_m_s2: a,
                        drag_m_s2: b,
                    }),
                }),
                1 => Frame::Command(CommandFrame {
                    seq,
                    status: LinkStatus::from_code(st).unwrap(),
                    tick_time_s: a,
                    command: Command {
                        alpha_rad: b,
                        sigma_rad: c,
                    },
                    ramp_start: Command {
                        alpha_rad: d,
                        sigma_rad: e,
                    },
                    rates: RateLimits {
                        alpha_rad_s: f,
                        sigma_rad_s: g,
                    },
                    reversals: seq % 7,
                    replans: seq / 3,
                }),
                _ => Frame::End(seq),
            }
        })
    }

    proptest! {
        #[test]
        fn decode_inverts_encode(f in frame()) {
            let mut buf = [0u8; FRAME_LEN];
            encode(&f, &mut buf).unwrap();
            prop_assert_eq!(decode(&buf), Ok(f));
        }

        #[test]
        fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..80)) {
            let _ = decode(&bytes);
        }

        #[test]
        fn sealed_random_bytes_decode_or_fail_typed(mut body in prop::array::uniform32(any::<u8>())) {
            // Random body with a valid sync and CRC: decodes or returns a typed error, no panic,
            // and anything decoded re-encodes to the same bytes.
            body[0] = SYNC[0];
            body[1] = SYNC[1];
            let mut b = [0u8; FRAME_LEN];
            b[..32].copy_from_slice(&body);
            b[32..64].copy_from_slice(&body);
            let c = crc16_ccitt(&b[..CRC_AT]).to_le_bytes();
            b[CRC_AT..].copy_from_slice(&c);
            if let Ok(f) = decode(&b) {
                let mut again = [0u8; FRAME_LEN];
                encode(&f, &mut again).unwrap();
                if !matches!(f, Frame::End(_)) && (b[3] == 0 || matches!(f, Frame::Command(_))) {
                    prop_assert_eq!(&again[..], &b[..]);
                }
            }
        }
    }
}
