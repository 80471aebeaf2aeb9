//! The flight application, independent of the board: generic over the embedded-io link to the
//! navigation system / host ([`embedded_io::Read`] + [`embedded_io::Write`]), an
//! embedded-hal 1.0 status discrete ([`OutputPin`]), a monotonic microsecond tick timer
//! ([`TickTimer`]) and a pacing mode ([`Pacing`], free-running with an embedded-hal
//! `DelayNs`). The QEMU `pil` firmware runs it on semihosting FIFOs and SysTick, in lockstep;
//! `stm32f4-flight` (feature `stm32f4`, compile only) on an STM32F407's USART2 and timers with
//! stm32f4xx-hal, free-running.
//!
//! Protocol (`guidance_core::link`): image frames carry the whole flight-guidance stack
//! (set-up protocol v2, `guidance_core::setup::image`: profile, re-planner, lateral logic with
//! the terminal law, estimator, barrier and target, versioned and CRC-32-checked); after the
//! last chunk the application decodes it in its scalars and builds a
//! `guidance_core::stack::FlightStack` with the core's checks, answering a typed status for
//! every refusal (CRC, version, size, a layer the build cannot fly, a malformed field, a stack
//! the core rejects) and building nothing then. Set-up frames (protocol v1,
//! `guidance_core::setup::SetupItem`) still build the stored profile or `ReplanningGuidance`
//! alone. Each nav frame is one update (`FlightStack::tick` with the frame's sensed lift and
//! drag accelerations), answered with a command frame that carries the stack's reversal and
//! re-plan counts; an end frame ends the run. A frame that
//! does not decode, or a sample guidance rejects, is a counted fault: the held command keeps
//! flying and the answer carries the status. The status discrete is high while the last
//! update was accepted, low after a fault or before guidance exists.
//!
//! Clock ([`crate::clock`]): guidance time is the nav frame's time stamp (the navigation
//! system's clock; in lockstep PIL the host's simulated time, so runs stay deterministic). The
//! tick timer measures every guidance tick, from its nav frame read to its command frame
//! written, against the guidance period: overruns and the longest tick are counted in
//! [`Outcome::timing`]. Free-running, the application then waits out the rest of the period.

use embedded_hal::delay::DelayNs;
use embedded_hal::digital::OutputPin;
use embedded_io::{Read, ReadExactError, Write};
use guidance_core::estimate::SensedAero;
use guidance_core::guidance::{Command, Guidance, RateLimits};
use guidance_core::link::{
    CommandFrame, FRAME_LEN, Frame, ImageFrame, LinkStatus, NavFrame, SetupFrame, decode, encode,
};
use guidance_core::nodes::DEFAULT_NODE_CAPACITY;
use guidance_core::setup::image::{ImageReceiver, image_capacity};
use guidance_core::setup::{SetupBuilder, SetupGuidance, SetupItem};
use guidance_core::stack::{FlightStack, Layers};
use guidance_core::{Real, Scalar};

use crate::clock::{Pacing, TickMonitor, TickStats, TickTimer, pace, period_us};

/// How a run ended normally.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Outcome {
    /// Frames answered.
    pub frames: u32,
    /// Faults counted (undecodable frames, rejected samples).
    pub faults: u32,
    /// Guidance tick timing: ticks measured, overruns of the period, longest tick \[us\].
    pub timing: TickStats,
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

/// Bytes of the set-up image buffer: the largest image of a stack of
/// [`DEFAULT_NODE_CAPACITY`] nodes (a larger table is refused as `ImageSize`).
pub const IMAGE_BUFFER_BYTES: usize = image_capacity(DEFAULT_NODE_CAPACITY);

/// The layers this application flies (every layer the core has, on both targets).
pub const SUPPORTED_LAYERS: Layers = Layers::ALL;

/// What the application flies: the uploaded stack (protocol v2), or the v1 set-up's guidance.
// One per run, held for the whole run: no allocation.
#[allow(clippy::large_enum_variant)]
enum Flight<S, const N: usize, R> {
    /// Protocol v1 (or the compiled-in fallback).
    Legacy(SetupGuidance<S, N, R>),
    /// Protocol v2: the whole stack.
    Stack(FlightStack<S, N, R>),
}

impl<S: Scalar, const N: usize, R: Real> Flight<S, N, R> {
    fn guidance(&self) -> &Guidance<S, N> {
        match self {
            Flight::Legacy(g) => g.guidance(),
            Flight::Stack(s) => s.guidance(),
        }
    }

    /// (reversals, re-plans) so far.
    fn counts(&self) -> (u32, u32) {
        match self {
            Flight::Legacy(SetupGuidance::Replanning(r)) => (0, r.counts().replans),
            Flight::Legacy(SetupGuidance::Stored(_)) => (0, 0),
            Flight::Stack(s) => (
                u32::from(s.reversals()),
                s.replan_counts().map_or(0, |c| c.replans),
            ),
        }
    }
}

/// Take one image chunk; after the last one decode the image and build the stack into
/// `flight` (kept as it was on a refusal). Not inlined: the decoded configuration and the
/// stack under construction live in this frame only, not in the serving loop's for the whole
/// run.
#[inline(never)]
fn take_chunk<S: Scalar, const N: usize, R: Real>(
    rx: &mut ImageReceiver<IMAGE_BUFFER_BYTES>,
    f: &ImageFrame,
    flight: &mut Option<Flight<S, N, R>>,
) -> LinkStatus {
    let image = match rx.take(f.index, f.count, &f.data) {
        Ok(Some(image)) => image,
        Ok(None) => return LinkStatus::Ok,
        Err(e) => return LinkStatus::from_image_error(e),
    };
    let config = match guidance_core::setup::image::decode::<S, N, R>(image, SUPPORTED_LAYERS) {
        Ok(c) => c,
        Err(e) => return LinkStatus::from_image_error(e),
    };
    match FlightStack::new(&config) {
        Ok(stack) => {
            *flight = Some(Flight::Stack(stack));
            LinkStatus::Ok
        }
        Err(e) => LinkStatus::from_stack_error(e),
    }
}

/// Build the v1 set-up's guidance into `flight` (not inlined, as [`take_chunk`]).
#[inline(never)]
fn commit_v1<S: Scalar, const N: usize, R: Real>(
    setup: &SetupBuilder<S, N>,
    flight: &mut Option<Flight<S, N, R>>,
) -> LinkStatus {
    match setup.build_flight::<R>() {
        Ok(g) => {
            *flight = Some(Flight::Legacy(g));
            LinkStatus::Ok
        }
        Err(e) => LinkStatus::from_setup_error(e),
    }
}

fn answer<S: Scalar, const N: usize, R: Real>(
    flight: Option<&Flight<S, N, R>>,
    seq: u32,
    status: LinkStatus,
) -> CommandFrame {
    let (reversals, replans) = flight.map_or((0, 0), Flight::counts);
    let g = flight.map(Flight::guidance);
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
            reversals,
            replans,
        };
    };
    let tick = g.last_tick_s().unwrap_or(S::ZERO);
    let rates = g.config().rates;
    CommandFrame {
        seq,
        status,
        tick_time_s: tick.to_f64(),
        command: g.command().to_f64(),
        ramp_start: g.attitude_at(tick).to_f64(),
        rates: RateLimits {
            alpha_rad_s: rates.alpha_rad_s.to_f64(),
            sigma_rad_s: rates.sigma_rad_s.to_f64(),
        },
        reversals,
        replans,
    }
}

/// Serve the link until an end frame: guidance in scalar `S` with node capacity `N`, an
/// uploaded re-planner in scalar `R` (`f32` on both Cortex-M targets: hardware float on the
/// M4F, soft float beside the fixed-point guidance tick on the M3). `fallback` builds the
/// guidance flown when a nav frame arrives before any set-up. `timer` measures each tick
/// (a nav frame that made guidance tick: read to answer written) against the guidance period;
/// `pacing` says whether to wait out the rest of the period after it ([`crate::clock`]).
///
/// # Errors
/// [`AppError`] if the link fails or ends; guidance problems are statuses, not errors.
pub fn serve<S, const N: usize, R, L, D, T, P>(
    link: &mut L,
    status: &mut D,
    timer: &mut T,
    mut pacing: Pacing<P>,
    fallback: impl Fn() -> Option<Guidance<S, N>>,
) -> Result<Outcome, AppError<L::Error>>
where
    S: Scalar,
    R: Real,
    L: Read + Write,
    D: OutputPin,
    T: TickTimer,
    P: DelayNs,
{
    let mut setup = SetupBuilder::<S, N>::new();
    let mut image = ImageReceiver::<IMAGE_BUFFER_BYTES>::new();
    let mut guidance: Option<Flight<S, N, R>> = None;
    let mut inb = [0u8; FRAME_LEN];
    let mut outb = [0u8; FRAME_LEN];
    let mut out = Outcome {
        frames: 0,
        faults: 0,
        timing: TickStats::default(),
    };
    let mut monitor = TickMonitor::new(period_us(2.0));
    // A discrete that cannot be driven must not stop guidance: its error is ignored.
    let _ = status.set_low();
    loop {
        link.read_exact(&mut inb).map_err(|e| match e {
            ReadExactError::UnexpectedEof => AppError::EndOfLink,
            ReadExactError::Other(e) => AppError::Read(e),
        })?;
        let start_us = timer.now_us();
        let mut healthy = false;
        let mut ticked = false;
        let reply = match decode(&inb) {
            Ok(Frame::End(_)) => return Ok(out),
            Ok(Frame::Setup(SetupFrame { seq, item })) => {
                let st = match item {
                    SetupItem::Commit => commit_v1(&setup, &mut guidance),
                    other => match setup.apply(&other) {
                        Ok(()) => LinkStatus::Ok,
                        Err(e) => LinkStatus::from_setup_error(e),
                    },
                };
                answer(guidance.as_ref(), seq, st)
            }
            Ok(Frame::Image(f)) => {
                let st = take_chunk(&mut image, &f, &mut guidance);
                answer(guidance.as_ref(), f.seq, st)
            }
            Ok(Frame::Nav(NavFrame { seq, nav, sensed })) => {
                if guidance.is_none() {
                    guidance = Some(Flight::Legacy(SetupGuidance::Stored(
                        fallback().ok_or(AppError::NoGuidance)?,
                    )));
                }
                match guidance.as_mut() {
                    Some(g) => {
                        let nav_s = nav.to_scalar();
                        let updated = match g {
                            Flight::Legacy(l) => l.update(&nav_s).map(|o| o.ticked),
                            Flight::Stack(s) => {
                                let m = sensed.as_ref().map(SensedAero::to_real::<R>);
                                s.tick(&nav_s, m.as_ref()).map(|o| o.ticked)
                            }
                        };
                        let st = match updated {
                            Ok(true) => LinkStatus::Ok,
                            Ok(false) => LinkStatus::NotTicked,
                            Err(e) => {
                                out.faults = out.faults.wrapping_add(1);
                                LinkStatus::from_error(e)
                            }
                        };
                        healthy = matches!(st, LinkStatus::Ok | LinkStatus::NotTicked);
                        ticked = st == LinkStatus::Ok;
                        monitor.set_period_us(period_us(g.guidance().config().period_s.to_f64()));
                        answer(Some(&*g), seq, st)
                    }
                    None => answer::<S, N, R>(None, seq, LinkStatus::InvalidConfig),
                }
            }
            Ok(Frame::Command(c)) => answer(guidance.as_ref(), c.seq, LinkStatus::BadFrame),
            Err(_) => {
                out.faults = out.faults.wrapping_add(1);
                answer(guidance.as_ref(), 0, LinkStatus::BadFrame)
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
        if ticked {
            monitor.record(start_us, timer.now_us());
            out.timing = monitor.stats();
            pace(&mut pacing, timer, &monitor, start_us);
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing)]
mod tests {
    use super::*;
    use crate::clock::LOCKSTEP;
    use guidance_core::NavState;
    use guidance_core::energy::EARTH_RADIUS_M;
    use guidance_core::missions::{HORUS2B_ENTRY, horus2b_reference};
    use std::vec::Vec;

    /// Frames in, answers out.
    struct MemLink {
        input: Vec<u8>,
        pos: usize,
        output: Vec<u8>,
    }

    impl embedded_io::ErrorType for MemLink {
        type Error = core::convert::Infallible;
    }

    impl Read for MemLink {
        fn read(&mut self, buf: &mut [u8]) -> Result<usize, Self::Error> {
            let rest = &self.input[self.pos..];
            let n = rest.len().min(buf.len());
            buf[..n].copy_from_slice(&rest[..n]);
            self.pos += n;
            Ok(n)
        }
    }

    impl Write for MemLink {
        fn write(&mut self, buf: &[u8]) -> Result<usize, Self::Error> {
            self.output.extend_from_slice(buf);
            Ok(buf.len())
        }
        fn flush(&mut self) -> Result<(), Self::Error> {
            Ok(())
        }
    }

    struct Pin;
    impl embedded_hal::digital::ErrorType for Pin {
        type Error = core::convert::Infallible;
    }
    impl OutputPin for Pin {
        fn set_low(&mut self) -> Result<(), Self::Error> {
            Ok(())
        }
        fn set_high(&mut self) -> Result<(), Self::Error> {
            Ok(())
        }
    }

    /// Each reading returns the counter, then advances it by `step_us` (wrapping).
    struct SteppingTimer {
        now_us: u32,
        step_us: u32,
    }
    impl TickTimer for SteppingTimer {
        fn now_us(&mut self) -> u32 {
            let t = self.now_us;
            self.now_us = t.wrapping_add(self.step_us);
            t
        }
    }

    /// Records each delay \[ns\].
    struct Delays(Vec<u32>);
    impl DelayNs for Delays {
        fn delay_ns(&mut self, ns: u32) {
            self.0.push(ns);
        }
    }

    /// Ten nav samples 1 s apart (ticks at 0, 2, 4, 6, 8 s), then the end frame.
    fn link() -> MemLink {
        let mut input = Vec::new();
        let mut b = [0u8; FRAME_LEN];
        for k in 0..10u32 {
            let nav = NavState {
                time_s: f64::from(k),
                radius_m: EARTH_RADIUS_M + 120e3 - 100.0 * f64::from(k),
                speed_m_s: HORUS2B_ENTRY.speed_m_s,
                flight_path_angle_rad: HORUS2B_ENTRY.flight_path_angle_rad,
                heading_rad: HORUS2B_ENTRY.heading_rad,
                latitude_rad: HORUS2B_ENTRY.latitude_rad,
                longitude_rad: HORUS2B_ENTRY.longitude_rad,
            };
            encode(
                &Frame::Nav(NavFrame {
                    seq: k,
                    nav,
                    sensed: None,
                }),
                &mut b,
            )
            .unwrap();
            input.extend_from_slice(&b);
        }
        encode(&Frame::End(10), &mut b).unwrap();
        input.extend_from_slice(&b);
        MemLink {
            input,
            pos: 0,
            output: Vec::new(),
        }
    }

    const CAP: usize = guidance_core::nodes::DEFAULT_NODE_CAPACITY;

    fn reference() -> Option<Guidance<f64, CAP>> {
        let m = horus2b_reference::<f64>().ok()?;
        m.guidance(m.earth_energy_normalizer().ok()?).ok()
    }

    fn ok_answers(l: &MemLink) -> u32 {
        let n = l
            .output
            .chunks_exact(FRAME_LEN)
            .filter(|c| {
                matches!(
                    decode(c),
                    Ok(Frame::Command(CommandFrame {
                        status: LinkStatus::Ok,
                        ..
                    }))
                )
            })
            .count();
        u32::try_from(n).unwrap()
    }

    fn run<P: DelayNs>(step_us: u32, pacing: Pacing<P>) -> (Outcome, MemLink) {
        let mut l = link();
        // Start 3 s before the u32 wrap: the run's readings cross it.
        let mut t = SteppingTimer {
            now_us: u32::MAX - 3_000_000,
            step_us,
        };
        let o = serve::<f64, CAP, f64, _, _, _, _>(&mut l, &mut Pin, &mut t, pacing, reference)
            .unwrap();
        (o, l)
    }

    #[test]
    fn lockstep_ticks_within_the_period_have_no_overrun() {
        let (o, l) = run(1_000_000, LOCKSTEP);
        assert_eq!(o.frames, 10);
        assert_eq!(ok_answers(&l), 5);
        assert_eq!(
            o.timing,
            TickStats {
                ticks: 5,
                overruns: 0,
                max_tick_us: 1_000_000,
                last_tick_us: 1_000_000
            }
        );
    }

    #[test]
    fn lockstep_ticks_longer_than_the_period_are_overruns() {
        let (o, _) = run(2_000_001, LOCKSTEP);
        assert_eq!(o.timing.ticks, 5);
        assert_eq!(o.timing.overruns, 5);
        assert_eq!(o.timing.max_tick_us, 2_000_001);
    }

    #[test]
    fn free_running_waits_out_each_period() {
        // Tick read -> answer 0.5 s; the pacing reading 0.5 s later: 1 s of the period left.
        let mut d = Delays(Vec::new());
        let (o, _) = run(500_000, Pacing::FreeRunning(&mut d));
        assert_eq!(o.timing.ticks, 5);
        assert_eq!(o.timing.overruns, 0);
        // `delay_us` of embedded-hal's default implementation: in 1 ms (or shorter) chunks
        // of `delay_ns`; 1 s in total per tick.
        let total_ns: u64 = d.0.iter().map(|&n| u64::from(n)).sum();
        assert_eq!(total_ns, 5 * 1_000_000_000);
    }

    /// The reference mission's profile as a stack image (protocol v2).
    fn stack_image() -> Vec<u8> {
        use guidance_core::stack::{ProfileLayer, StackConfig};
        let m = horus2b_reference::<f64>().unwrap();
        let c: StackConfig<f64> = StackConfig {
            profile: ProfileLayer {
                guidance: m.config,
                table: m.table.clone(),
                interpolation: m.interpolation,
                energy: m.earth_energy_normalizer().unwrap(),
                initial: m.initial,
            },
            replan: None,
            lateral: None,
            estimator: None,
            barrier: None,
            target: None,
        };
        let mut b = [0u8; IMAGE_BUFFER_BYTES];
        let n = guidance_core::setup::image::encode(&c, &mut b).unwrap();
        b[..n].to_vec()
    }

    /// `image`'s chunks (in `order`), then the ten nav frames of [`link`]; the statuses of
    /// the chunk answers and the number of `Ok` nav answers.
    fn upload(image: &[u8], order: &[usize]) -> (Vec<LinkStatus>, u32, bool) {
        let chunks: Vec<_> = guidance_core::setup::image::chunks(image).collect();
        let mut l = link();
        let mut input = Vec::new();
        let mut b = [0u8; FRAME_LEN];
        for (seq, &k) in order.iter().enumerate() {
            let (index, count, data) = chunks[k];
            let f = ImageFrame {
                seq: 100 + u32::try_from(seq).unwrap(),
                index,
                count,
                data,
            };
            encode(&Frame::Image(f), &mut b).unwrap();
            input.extend_from_slice(&b);
        }
        let n = input.len();
        input.extend_from_slice(&l.input);
        l.input = input;
        let mut t = SteppingTimer {
            now_us: 0,
            step_us: 1,
        };
        // No fallback: with nothing built the first nav frame ends the run (`NoGuidance`).
        let built = serve::<f32, CAP, f32, _, _, _, _>(&mut l, &mut Pin, &mut t, LOCKSTEP, || None)
            .map_err(|e| assert_eq!(e, AppError::NoGuidance))
            .is_ok();
        let answers: Vec<_> = l
            .output
            .chunks_exact(FRAME_LEN)
            .map(|c| match decode(c) {
                Ok(Frame::Command(c)) => c.status,
                _ => LinkStatus::BadFrame,
            })
            .collect();
        let k = n / FRAME_LEN;
        let ok = answers[k..]
            .iter()
            .filter(|s| **s == LinkStatus::Ok)
            .count();
        (answers[..k].to_vec(), u32::try_from(ok).unwrap(), built)
    }

    /// A good image builds the stack (every chunk `Ok`, the nav frames fly it); a corrupted
    /// one is refused with `ImageCrc`, a chunk out of order with `ImageOrder`, and with
    /// nothing built no nav frame is flown (without a fallback the run stops), never with less.
    #[test]
    fn set_up_image_builds_the_stack_or_is_refused_typed() {
        let img = stack_image();
        let n = img.len().div_ceil(guidance_core::setup::image::CHUNK_BYTES);
        let all: Vec<usize> = (0..n).collect();
        let (st, ok, built) = upload(&img, &all);
        assert!(st.iter().all(|s| *s == LinkStatus::Ok), "{st:?}");
        assert!(built);
        assert_eq!(ok, 5);
        let mut bad = img.clone();
        bad[20] ^= 1;
        let (st, ok, built) = upload(&bad, &all);
        assert_eq!(st.last(), Some(&LinkStatus::ImageCrc));
        assert!(!built && ok == 0);
        let mut swapped = all.clone();
        swapped.swap(1, 2);
        let (st, _, built) = upload(&img, &swapped);
        assert_eq!(st[1], LinkStatus::ImageOrder);
        assert!(!built);
        // An image of the next protocol version is refused by its version.
        let mut newer = img.clone();
        let v = (guidance_core::setup::image::IMAGE_VERSION + 1).to_le_bytes();
        newer[4] = v[0];
        newer[5] = v[1];
        let (st, _, built) = upload(&newer, &all);
        assert_eq!(st.last(), Some(&LinkStatus::ImageVersion));
        assert!(!built);
    }
}
