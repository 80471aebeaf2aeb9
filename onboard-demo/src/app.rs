//! The flight application, independent of the board: generic over the embedded-io link to the
//! navigation system / host ([`embedded_io::Read`] + [`embedded_io::Write`]) and an
//! embedded-hal 1.0 status discrete ([`OutputPin`]). The QEMU `pil` firmware runs it on
//! semihosting FIFOs; `stm32f4-flight` (feature `stm32f4`, compile only) on an STM32F407's
//! USART2 with stm32f4xx-hal.
//!
//! Protocol (`guidance_core::link`): set-up frames build the guidance (`guidance_core::setup`:
//! the stored profile, or with onboard re-planning when its items were uploaded; the core's
//! own checks at commit, a typed status answering each item); each nav frame is one guidance
//! update, answered with a command frame; an end frame ends the run. A frame that
//! does not decode, or a sample guidance rejects, is a counted fault: the held command keeps
//! flying and the answer carries the status. The status discrete is high while the last
//! update was accepted, low after a fault or before guidance exists.
//!
//! Guidance time is the nav frame's time stamp (the navigation system's clock), so the
//! application needs no timer of its own.

use embedded_hal::digital::OutputPin;
use embedded_io::{Read, ReadExactError, Write};
use guidance_core::guidance::{Command, Guidance, RateLimits};
use guidance_core::link::{
    CommandFrame, FRAME_LEN, Frame, LinkStatus, NavFrame, SetupFrame, decode, encode,
};
use guidance_core::setup::{SetupBuilder, SetupGuidance, SetupItem};
use guidance_core::{NavState, Real, Scalar};

/// How a run ended normally.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Outcome {
    /// Frames answered.
    pub frames: u32,
    /// Faults counted (undecodable frames, rejected samples).
    pub faults: u32,
}

/// Why a run stopped early.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AppError<E> {
    /// The link failed while reading.
    Read(E),
    /// The link ended in the middle of (or before) a frame.
    EndOfLink,
    /// The link failed while writing.
    Write(E),
    /// A command would not encode (non-finite; never expected).
    Encode,
    /// The fallback guidance (no set-up received) could not be built.
    NoGuidance,
}

fn narrow<S: Scalar>(n: &NavState<f64>) -> NavState<S> {
    NavState {
        time_s: S::from_f64(n.time_s),
        radius_m: S::from_f64(n.radius_m),
        speed_m_s: S::from_f64(n.speed_m_s),
        flight_path_angle_rad: S::from_f64(n.flight_path_angle_rad),
        heading_rad: S::from_f64(n.heading_rad),
        latitude_rad: S::from_f64(n.latitude_rad),
        longitude_rad: S::from_f64(n.longitude_rad),
    }
}

fn wide<S: Scalar>(c: Command<S>) -> Command<f64> {
    Command {
        alpha_rad: c.alpha_rad.to_f64(),
        sigma_rad: c.sigma_rad.to_f64(),
    }
}

fn answer<S: Scalar, const N: usize>(
    g: Option<&Guidance<S, N>>,
    seq: u32,
    status: LinkStatus,
) -> CommandFrame {
    let zero = Command {
        alpha_rad: 0.0,
        sigma_rad: 0.0,
    };
    let Some(g) = g else {
        return CommandFrame {
            seq,
            status,
            tick_time_s: 0.0,
            command: zero,
            ramp_start: zero,
            rates: RateLimits {
                alpha_rad_s: 0.0,
                sigma_rad_s: 0.0,
            },
        };
    };
    let tick = g.last_tick_s().unwrap_or(S::ZERO);
    let rates = g.config().rates;
    CommandFrame {
        seq,
        status,
        tick_time_s: tick.to_f64(),
        command: wide(g.command()),
        ramp_start: wide(g.attitude_at(tick)),
        rates: RateLimits {
            alpha_rad_s: rates.alpha_rad_s.to_f64(),
            sigma_rad_s: rates.sigma_rad_s.to_f64(),
        },
    }
}

/// Serve the link until an end frame: guidance in scalar `S` with node capacity `N`, an
/// uploaded re-planner in scalar `R` (`f32` on both Cortex-M targets: hardware float on the
/// M4F, soft float beside the fixed-point guidance tick on the M3). `fallback` builds the
/// guidance flown when a nav frame arrives before any set-up.
///
/// # Errors
/// [`AppError`] if the link fails or ends; guidance problems are statuses, not errors.
pub fn serve<S, const N: usize, R, L, D>(
    link: &mut L,
    status: &mut D,
    fallback: impl Fn() -> Option<Guidance<S, N>>,
) -> Result<Outcome, AppError<L::Error>>
where
    S: Scalar,
    R: Real,
    L: Read + Write,
    D: OutputPin,
{
    let mut setup = SetupBuilder::<S, N>::new();
    let mut guidance: Option<SetupGuidance<S, N, R>> = None;
    let mut inb = [0u8; FRAME_LEN];
    let mut outb = [0u8; FRAME_LEN];
    let mut out = Outcome {
        frames: 0,
        faults: 0,
    };
    // A discrete that cannot be driven must not stop guidance: its error is ignored.
    let _ = status.set_low();
    loop {
        link.read_exact(&mut inb).map_err(|e| match e {
            ReadExactError::UnexpectedEof => AppError::EndOfLink,
            ReadExactError::Other(e) => AppError::Read(e),
        })?;
        let mut healthy = false;
        let reply = match decode(&inb) {
            Ok(Frame::End(_)) => return Ok(out),
            Ok(Frame::Setup(SetupFrame { seq, item })) => {
                let st = match item {
                    SetupItem::Commit => match setup.build_flight::<R>() {
                        Ok(g) => {
                            guidance = Some(g);
                            LinkStatus::Ok
                        }
                        Err(e) => LinkStatus::from_setup_error(e),
                    },
                    other => match setup.apply(&other) {
                        Ok(()) => LinkStatus::Ok,
                        Err(e) => LinkStatus::from_setup_error(e),
                    },
                };
                answer(guidance.as_ref().map(SetupGuidance::guidance), seq, st)
            }
            Ok(Frame::Nav(NavFrame { seq, nav })) => {
                if guidance.is_none() {
                    guidance = Some(SetupGuidance::Stored(
                        fallback().ok_or(AppError::NoGuidance)?,
                    ));
                }
                match guidance.as_mut() {
                    Some(g) => {
                        let st = match g.update(&narrow(&nav)) {
                            Ok(o) if o.ticked => LinkStatus::Ok,
                            Ok(_) => LinkStatus::NotTicked,
                            Err(e) => {
                                out.faults = out.faults.wrapping_add(1);
                                LinkStatus::from_error(e)
                            }
                        };
                        healthy = matches!(st, LinkStatus::Ok | LinkStatus::NotTicked);
                        answer(Some(g.guidance()), seq, st)
                    }
                    None => answer::<S, N>(None, seq, LinkStatus::InvalidConfig),
                }
            }
            Ok(Frame::Command(c)) => answer(
                guidance.as_ref().map(SetupGuidance::guidance),
                c.seq,
                LinkStatus::BadFrame,
            ),
            Err(_) => {
                out.faults = out.faults.wrapping_add(1);
                answer(
                    guidance.as_ref().map(SetupGuidance::guidance),
                    0,
                    LinkStatus::BadFrame,
                )
            }
        };
        let _ = if healthy {
            status.set_high()
        } else {
            status.set_low()
        };
        encode(&Frame::Command(reply), &mut outb).map_err(|_| AppError::Encode)?;
        link.write_all(&outb).map_err(AppError::Write)?;
        link.flush().map_err(AppError::Write)?;
        out.frames = out.frames.wrapping_add(1);
    }
}
