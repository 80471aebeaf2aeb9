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
//! status, and the commit builds `Guidance` with the core's own checks. Or it uploads a whole
//! flight-guidance stack as a set-up image (protocol v2, `guidance_core::setup::image`, 68-byte
//! image frames): the firmware builds a `FlightStack` (every layer: re-planner, lateral logic,
//! estimator, barrier) and ticks it with the nav frames' sensed accelerations; a refused image
//! is answered with its typed status. Without a set-up the
//! firmware flies the compiled-in HORUS-2B reference mission
//! (`guidance_core::missions::horus2b_reference`).
//!
//! Loop: read a frame; set-up items are collected; a nav frame is an `update`, answered with a
//! command frame (same sequence number); an end frame exits 0. A link failure, panic or
//! HardFault exits 1.
//!
//! Clock: lockstep. Guidance time is the nav frame's time stamp (the host's simulated time,
//! so PIL runs are deterministic); SysTick (`onboard_demo::systick`) times every guidance
//! tick against the period, and the summary line reports the overruns and the longest tick
//! (QEMU wall-clock microseconds, not a real core's time).
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
    use guidance_core::guidance::Guidance;
    use guidance_core::missions::horus2b_reference;
    use onboard_demo::app::{AppError, serve};
    use onboard_demo::clock::{LOCKSTEP, TickStats};
    use onboard_demo::systick::SysTickTimer;

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

    /// The link: semihosting reads from the nav FIFO, writes to the cmd FIFO.
    struct SemihostingLink {
        nav_fd: usize,
        cmd_fd: usize,
    }

    /// A semihosting call failed.
    #[derive(Clone, Copy, Debug)]
    struct SemihostingError;

    impl embedded_io::Error for SemihostingError {
        fn kind(&self) -> embedded_io::ErrorKind {
            embedded_io::ErrorKind::Other
        }
    }

    impl embedded_io::ErrorType for SemihostingLink {
        type Error = SemihostingError;
    }

    impl embedded_io::Read for SemihostingLink {
        fn read(&mut self, buf: &mut [u8]) -> Result<usize, SemihostingError> {
            if buf.is_empty() {
                return Ok(0);
            }
            // SYS_READ returns the number of bytes NOT read (all of them: end of file).
            let left = sys(
                nr::READ,
                &[self.nav_fd, buf.as_mut_ptr() as usize, buf.len()],
            );
            if left < 0 {
                return Err(SemihostingError);
            }
            Ok(buf.len().saturating_sub(left as usize))
        }
    }

    impl embedded_io::Write for SemihostingLink {
        fn write(&mut self, buf: &[u8]) -> Result<usize, SemihostingError> {
            let left = sys(nr::WRITE, &[self.cmd_fd, buf.as_ptr() as usize, buf.len()]);
            if left < 0 {
                return Err(SemihostingError);
            }
            Ok(buf.len().saturating_sub(left as usize))
        }
        fn flush(&mut self) -> Result<(), SemihostingError> {
            Ok(())
        }
    }

    /// The status discrete: QEMU's machines have none wired here, so the level is only kept
    /// (a real board passes a GPIO pin).
    struct StatusLevel(bool);

    impl embedded_hal::digital::ErrorType for StatusLevel {
        type Error = core::convert::Infallible;
    }

    impl embedded_hal::digital::OutputPin for StatusLevel {
        fn set_low(&mut self) -> Result<(), Self::Error> {
            self.0 = false;
            Ok(())
        }
        fn set_high(&mut self) -> Result<(), Self::Error> {
            self.0 = true;
            Ok(())
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

    /// The compiled-in HORUS-2B reference mission (flown when the host sends no set-up).
    fn reference() -> Option<Guidance<S, CAPACITY>> {
        let mission = horus2b_reference::<S>().ok()?;
        // Time-indexed table: the energy normaliser is required but unused.
        let energy = mission.earth_energy_normalizer().ok()?;
        mission.guidance(energy).ok()
    }

    /// A run's counters: frames answered, faults counted, tick timing.
    type RunCounts = (u32, u32, TickStats);

    fn run() -> Result<RunCounts, &'static str> {
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
        let mut link = SemihostingLink { nav_fd, cmd_fd };
        let mut status = StatusLevel(false);
        let syst = cortex_m::Peripherals::take()
            .ok_or("core peripherals taken twice")?
            .SYST;
        let mut timer = SysTickTimer::start(syst);
        let r = serve::<S, CAPACITY, f32, _, _, _, _>(
            &mut link,
            &mut status,
            &mut timer,
            LOCKSTEP,
            reference,
        );
        let _ = timer.free();
        match r {
            Ok(o) => Ok((o.frames, o.faults, o.timing)),
            Err(AppError::EndOfLink) => Err("end of file on nav FIFO"),
            Err(AppError::Read(_)) => Err("read failed"),
            Err(AppError::Write(_)) => Err("write to cmd FIFO failed"),
            Err(AppError::Encode) => Err("non-finite command"),
            Err(AppError::NoGuidance) => Err("reference mission rejected"),
        }
    }

    #[entry]
    fn main() -> ! {
        // The whole run under stack painting: its deepest stack (guidance state, set-up
        // builder, frame buffers and every update) is printed at the end.
        let (stack, r) = onboard_demo::stack::max_stack_bytes(run);
        match r {
            Ok((n, faults, timing)) => {
                hprintln!(
                    "pil: end of run after {} frames; faults {}; ticks {}; overruns {}; max tick {} us; stack {} bytes{}",
                    n,
                    faults,
                    timing.ticks,
                    timing.overruns,
                    timing.max_tick_us,
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

    /// SysTick wrapped: extend the tick timer.
    #[exception]
    fn SysTick() {
        onboard_demo::systick::on_wrap();
    }

    #[exception]
    #[allow(unsafe_code)] // cortex-m-rt requires HardFault handlers to be `unsafe fn`.
    unsafe fn HardFault(_frame: &ExceptionFrame) -> ! {
        hprintln!("pil: HardFault");
        onboard_demo::exit(false)
    }
}
