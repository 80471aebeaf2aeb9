//! Processor-in-the-loop firmware: `f32` guidance on the target, driven by `host-sim::pil`.
//!
//! Link: two named FIFOs on the host opened through semihosting file I/O (`SYS_OPEN`,
//! `SYS_READ`, `SYS_WRITE`): `<dir>/nav` (host -> firmware, [`NavFrame`]s) and `<dir>/cmd`
//! (firmware -> host, [`CommandFrame`]s), frames as defined in `guidance_core::link`.
//! `<dir>` is the semihosting command line (QEMU `-append DIR`, read with `SYS_GET_CMDLINE`;
//! its last word; host-sim passes `.` and runs QEMU in the FIFO directory, so the path is always
//! short), or else the build-time `PIL_FIFO_DIR`, or else `.` (when the command line is too
//! long for the buffer, e.g. a very long ELF path).
//!
//! Guidance: `f32` on the Cortex-M4F (`thumbv7em-none-eabihf`), fixed point (`I32F32`) on the
//! Cortex-M3 (`thumbv7m-none-eabi`). The host first uploads its scenario's guidance as set-up
//! frames (`guidance_core::setup`: node table in either independent variable, interpolation,
//! bounds, period, rates, initial attitude, E-hat map); every item is answered with a typed
//! status, and the commit builds `Guidance` with the core's own checks. Without a set-up the
//! firmware flies the compiled-in HORUS-2B reference mission
//! (`guidance_core::missions::horus2b_reference`).
//!
//! Loop: read a frame; set-up items are collected; a nav frame is an `update`, answered with a
//! command frame (same sequence number); an end frame exits 0. A link failure, panic or
//! HardFault exits 1.
//!
//! Firmware only: built for the host (as `cargo test --workspace` and `cargo clippy
//! --workspace` do) this binary is a stub that says so and exits 2.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]
#![deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!(
        "pil: Cortex-M firmware, not a host program: build it with \
         --target thumbv7em-none-eabihf or thumbv7m-none-eabi (see README)"
    );
    std::process::exit(2);
}

/// The firmware (built for `target_os = "none"` only).
#[cfg(target_os = "none")]
mod firmware {
    use cortex_m_rt::{ExceptionFrame, entry, exception};
    use cortex_m_semihosting::{hprintln, nr};
    use guidance_core::guidance::{Command, Guidance};
    use guidance_core::link::{
        CommandFrame, FRAME_LEN, Frame, LinkStatus, NavFrame, SetupFrame, decode, encode,
    };
    use guidance_core::missions::horus2b_reference;
    use guidance_core::setup::{SetupBuilder, SetupItem};
    use guidance_core::{NavState, Scalar};

    /// Default FIFO directory when the command line names none.
    const DEFAULT_DIR: &str = match option_env!("PIL_FIFO_DIR") {
        Some(d) => d,
        // The host runs QEMU in the FIFO directory.
        None => ".",
    };

    /// Longest FIFO path \[bytes\] (including the terminating NUL).
    const PATH_MAX: usize = 256;

    /// Semihosting open modes ("rb", "wb").
    const MODE_RB: usize = 1;
    const MODE_WB: usize = 5;

    fn sys<const N: usize>(op: usize, args: &[usize; N]) -> isize {
        // SAFETY: `op` is a semihosting operation whose argument block is `args`; every pointer in
        // `args` points to a live buffer of the length passed next to it.
        #[allow(unsafe_code)]
        let r = unsafe { cortex_m_semihosting::syscall(op, args) };
        r as isize
    }

    /// The semihosting command line's last word, copied into `buf`; its length.
    fn cmdline_dir(buf: &mut [u8; PATH_MAX]) -> Option<usize> {
        let mut block = [buf.as_mut_ptr() as usize, PATH_MAX - 1];
        // SAFETY: GET_CMDLINE writes at most block[1] bytes into buf and updates block[1].
        #[allow(unsafe_code)]
        let r =
            unsafe { cortex_m_semihosting::syscall1(nr::GET_CMDLINE, block.as_mut_ptr() as usize) };
        if r != 0 {
            return None;
        }
        let len = block.get(1).copied()?.min(PATH_MAX - 1);
        let line = buf.get(..len)?;
        let line = line.split(|&b| b == 0).next()?;
        let mut words = line.split(|&b| b == b' ').filter(|w| !w.is_empty());
        let _kernel = words.next()?;
        let last = words.next_back()?;
        let n = last.len();
        let mut tmp = [0u8; PATH_MAX];
        tmp.get_mut(..n)?.copy_from_slice(last);
        buf.get_mut(..n)?.copy_from_slice(tmp.get(..n)?);
        Some(n)
    }

    /// `dir + "/" + name + NUL` into `out`; the length without the NUL.
    fn join(dir: &[u8], name: &[u8], out: &mut [u8; PATH_MAX]) -> Option<usize> {
        let n = dir.len() + 1 + name.len();
        if n + 1 > PATH_MAX {
            return None;
        }
        out.get_mut(..dir.len())?.copy_from_slice(dir);
        *out.get_mut(dir.len())? = b'/';
        out.get_mut(dir.len() + 1..n)?.copy_from_slice(name);
        *out.get_mut(n)? = 0;
        Some(n)
    }

    fn open(path: &[u8; PATH_MAX], len: usize, mode: usize) -> Result<usize, &'static str> {
        let fd = sys(nr::OPEN, &[path.as_ptr() as usize, mode, len]);
        if fd < 0 {
            Err("cannot open FIFO")
        } else {
            Ok(fd as usize)
        }
    }

    fn read_frame(fd: usize, buf: &mut [u8; FRAME_LEN]) -> Result<(), &'static str> {
        let mut got = 0;
        while got < FRAME_LEN {
            let rest = buf.get_mut(got..).ok_or("read overflow")?;
            // SYS_READ returns the number of bytes NOT read.
            let left = sys(nr::READ, &[fd, rest.as_mut_ptr() as usize, rest.len()]);
            if left < 0 {
                return Err("read failed");
            }
            let read = rest.len().saturating_sub(left as usize);
            if read == 0 {
                return Err("end of file on nav FIFO");
            }
            got += read;
        }
        Ok(())
    }

    fn write_frame(fd: usize, buf: &[u8; FRAME_LEN]) -> Result<(), &'static str> {
        let left = sys(nr::WRITE, &[fd, buf.as_ptr() as usize, buf.len()]);
        if left == 0 {
            Ok(())
        } else {
            Err("write to cmd FIFO failed")
        }
    }

    /// The guidance scalar: `f32` on the Cortex-M4F (hard float), fixed point on the Cortex-M3.
    #[cfg(target_abi = "eabihf")]
    type S = f32;
    /// The guidance scalar: `f32` on the Cortex-M4F (hard float), fixed point on the Cortex-M3.
    #[cfg(not(target_abi = "eabihf"))]
    type S = guidance_core::Fixed;

    /// Node capacity of uploaded tables.
    const CAPACITY: usize = guidance_core::nodes::DEFAULT_NODE_CAPACITY;

    fn narrow(n: &NavState<f64>) -> NavState<S> {
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

    fn wide(c: Command<S>) -> Command<f64> {
        Command {
            alpha_rad: c.alpha_rad.to_f64(),
            sigma_rad: c.sigma_rad.to_f64(),
        }
    }

    fn answer(g: Option<&Guidance<S>>, seq: u32, status: LinkStatus) -> CommandFrame {
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
                rates: guidance_core::guidance::RateLimits {
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
            rates: guidance_core::guidance::RateLimits {
                alpha_rad_s: rates.alpha_rad_s.to_f64(),
                sigma_rad_s: rates.sigma_rad_s.to_f64(),
            },
        }
    }

    /// The compiled-in HORUS-2B reference mission (flown when the host sends no set-up).
    fn reference() -> Result<Guidance<S>, &'static str> {
        let mission = horus2b_reference::<S>().map_err(|_| "reference mission rejected")?;
        // Time-indexed table: the energy normaliser is required but unused.
        let energy = mission
            .earth_energy_normalizer()
            .map_err(|_| "energy normaliser rejected")?;
        mission
            .guidance(energy)
            .map_err(|_| "guidance rejected its configuration")
    }

    fn run() -> Result<(u32, u32), &'static str> {
        let mut dir = [0u8; PATH_MAX];
        let dir_len = match cmdline_dir(&mut dir) {
            Some(n) => n,
            None => {
                let d = DEFAULT_DIR.as_bytes();
                dir.get_mut(..d.len())
                    .ok_or("PIL_FIFO_DIR too long")?
                    .copy_from_slice(d);
                d.len()
            }
        };
        let dir = dir.get(..dir_len).ok_or("FIFO directory")?;
        let mut path = [0u8; PATH_MAX];
        let n = join(dir, b"nav", &mut path).ok_or("FIFO path too long")?;
        let nav_fd = open(&path, n, MODE_RB)?;
        let n = join(dir, b"cmd", &mut path).ok_or("FIFO path too long")?;
        let cmd_fd = open(&path, n, MODE_WB)?;

        let mut setup = SetupBuilder::<S, CAPACITY>::new();
        let mut guidance: Option<Guidance<S>> = None;
        let mut inb = [0u8; FRAME_LEN];
        let mut outb = [0u8; FRAME_LEN];
        let mut frames = 0u32;
        // Link faults seen: frames that did not decode, nav samples guidance rejected.
        let mut faults = 0u32;
        loop {
            read_frame(nav_fd, &mut inb)?;
            let reply = match decode(&inb) {
                Ok(Frame::End(_)) => return Ok((frames, faults)),
                Ok(Frame::Setup(SetupFrame { seq, item })) => {
                    let status = match item {
                        SetupItem::Commit => match setup.build() {
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
                    answer(guidance.as_ref(), seq, status)
                }
                Ok(Frame::Nav(NavFrame { seq, nav })) => {
                    if guidance.is_none() {
                        guidance = Some(reference()?);
                    }
                    match guidance.as_mut() {
                        Some(g) => {
                            // A rejected sample leaves the held command flying.
                            let status = match g.update(&narrow(&nav)) {
                                Ok(o) if o.ticked => LinkStatus::Ok,
                                Ok(_) => LinkStatus::NotTicked,
                                Err(e) => {
                                    faults = faults.wrapping_add(1);
                                    LinkStatus::from_error(e)
                                }
                            };
                            answer(Some(g), seq, status)
                        }
                        None => answer(None, seq, LinkStatus::InvalidConfig),
                    }
                }
                Ok(Frame::Command(c)) => answer(guidance.as_ref(), c.seq, LinkStatus::BadFrame),
                Err(_) => {
                    faults = faults.wrapping_add(1);
                    answer(guidance.as_ref(), 0, LinkStatus::BadFrame)
                }
            };
            encode(&Frame::Command(reply), &mut outb).map_err(|_| "non-finite command")?;
            write_frame(cmd_fd, &outb)?;
            frames = frames.wrapping_add(1);
        }
    }

    #[entry]
    fn main() -> ! {
        // The whole run under stack painting: its deepest stack (guidance state, set-up
        // builder, frame buffers and every update) is printed at the end.
        let (stack, r) = onboard_demo::stack::max_stack_bytes(run);
        match r {
            Ok((n, faults)) => {
                hprintln!(
                    "pil: end of run after {} frames; faults {}; stack {} bytes{}",
                    n,
                    faults,
                    stack.bytes,
                    if stack.overflowed { " or more" } else { "" }
                );
                onboard_demo::exit(true)
            }
            Err(e) => {
                hprintln!("pil: FAIL: {}", e);
                onboard_demo::exit(false)
            }
        }
    }

    #[exception]
    #[allow(unsafe_code)] // cortex-m-rt requires HardFault handlers to be `unsafe fn`.
    unsafe fn HardFault(_frame: &ExceptionFrame) -> ! {
        hprintln!("pil: HardFault");
        onboard_demo::exit(false)
    }
}
