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
//! Guidance: `Guidance<f32>` of the HORUS-2B reference mission compiled in
//! (`guidance_core::missions::horus2b_reference`: time-indexed table of thesis eq. 2.3, thesis
//! bounds, linear interpolation, 2 s period, rate limits, initial attitude 40 deg / 0 deg; E-hat
//! of the thesis' spherical Earth), the same mission host-sim flies in SIL.
//!
//! Loop: read a nav frame, `update`, answer with a command frame (same sequence number) until
//! an end frame arrives, then exit 0. A link failure, panic or HardFault exits 1.
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
        CommandFrame, FRAME_LEN, Frame, LinkStatus, NavFrame, decode, encode,
    };
    use guidance_core::missions::horus2b_reference;
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

    fn to_f32(n: &NavState<f64>) -> NavState<f32> {
        NavState {
            time_s: n.time_s as f32,
            radius_m: n.radius_m as f32,
            speed_m_s: n.speed_m_s as f32,
            flight_path_angle_rad: n.flight_path_angle_rad as f32,
            heading_rad: n.heading_rad as f32,
            latitude_rad: n.latitude_rad as f32,
            longitude_rad: n.longitude_rad as f32,
        }
    }

    fn wide(c: Command<f32>) -> Command<f64> {
        Command {
            alpha_rad: f64::from(c.alpha_rad),
            sigma_rad: f64::from(c.sigma_rad),
        }
    }

    fn answer(g: &Guidance<f32>, seq: u32, status: LinkStatus) -> CommandFrame {
        let tick = g.last_tick_s().unwrap_or(f32::ZERO);
        let rates = g.config().rates;
        CommandFrame {
            seq,
            status,
            tick_time_s: f64::from(tick),
            command: wide(g.command()),
            ramp_start: wide(g.attitude_at(tick)),
            rates: guidance_core::guidance::RateLimits {
                alpha_rad_s: f64::from(rates.alpha_rad_s),
                sigma_rad_s: f64::from(rates.sigma_rad_s),
            },
        }
    }

    fn run() -> Result<u32, &'static str> {
        let mission = horus2b_reference::<f32>().map_err(|_| "reference mission rejected")?;
        // Time-indexed table: the energy normaliser is required but unused.
        let energy = mission
            .earth_energy_normalizer()
            .map_err(|_| "energy normaliser rejected")?;
        let mut g = mission
            .guidance(energy)
            .map_err(|_| "guidance rejected its configuration")?;

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

        let mut inb = [0u8; FRAME_LEN];
        let mut outb = [0u8; FRAME_LEN];
        let mut frames = 0u32;
        loop {
            read_frame(nav_fd, &mut inb)?;
            let reply = match decode(&inb) {
                Ok(Frame::End(_)) => return Ok(frames),
                Ok(Frame::Nav(NavFrame { seq, nav })) => {
                    let status = match g.update(&to_f32(&nav)) {
                        Ok(o) if o.ticked => LinkStatus::Ok,
                        Ok(_) => LinkStatus::NotTicked,
                        Err(e) => LinkStatus::from_error(e),
                    };
                    answer(&g, seq, status)
                }
                Ok(Frame::Command(c)) => answer(&g, c.seq, LinkStatus::BadFrame),
                Err(_) => answer(&g, 0, LinkStatus::BadFrame),
            };
            encode(&Frame::Command(reply), &mut outb).map_err(|_| "non-finite command")?;
            write_frame(cmd_fd, &outb)?;
            frames = frames.wrapping_add(1);
        }
    }

    #[entry]
    fn main() -> ! {
        match run() {
            Ok(n) => {
                hprintln!("pil: end of run after {} frames", n);
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
