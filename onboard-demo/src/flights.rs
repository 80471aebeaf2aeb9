//! The recorded flights of the full-stack benchmarks (`insn-bench`, `stack-bench`): each
//! vehicle's campaign stack as the set-up image the host uploads in PIL, and every guidance
//! tick's inputs of its nominal SIL flight (`bench-data/*.bin`, written and checked by
//! host-sim's `firmware_bench_flights` test, whose docs give the layout and how to regenerate
//! them).

use guidance_core::NavState;
use guidance_core::estimate::SensedAero;

/// The nominal HORUS-2B reference flight (`bench-data/horus-2b-reference.bin`).
pub static HORUS: &[u8] = include_bytes!("../bench-data/horus-2b-reference.bin");
/// The nominal SRM glide flight (`bench-data/srm-glide.bin`).
pub static SRM: &[u8] = include_bytes!("../bench-data/srm-glide.bin");

/// The flights by vehicle: ("horus", [`HORUS`]), ("srm", [`SRM`]).
pub const VEHICLES: [(&str, &[u8]); 2] = [("horus", HORUS), ("srm", SRM)];

/// Bytes of one recorded tick: 9 `f32`.
pub const TICK_BYTES: usize = 36;

/// A recorded flight: the set-up image and the ticks' bytes.
#[derive(Clone, Copy, Debug)]
pub struct Recorded {
    /// The set-up image (`guidance_core::setup::image`).
    pub image: &'static [u8],
    /// The ticks, [`TICK_BYTES`] each ([`tick_of`]).
    pub ticks: &'static [u8],
}

impl Recorded {
    /// Parse a flight file; `None` if it is malformed (magic, lengths).
    #[must_use]
    pub fn parse(b: &'static [u8]) -> Option<Self> {
        let rest = b.strip_prefix(b"FSB1")?;
        let (n, rest) = u32_at(rest)?;
        let (image, rest) = rest.split_at_checked(n)?;
        let (count, ticks) = u32_at(rest)?;
        (ticks.len() == count.checked_mul(TICK_BYTES)?).then_some(Self { image, ticks })
    }

    /// The recorded ticks in order ([`tick_of`] each).
    pub fn ticks(&self) -> impl Iterator<Item = (NavState<f64>, Option<SensedAero<f32>>)> {
        self.ticks.chunks_exact(TICK_BYTES).map(tick_of)
    }

    /// Number of recorded ticks.
    #[must_use]
    pub fn len(&self) -> usize {
        self.ticks.len() / TICK_BYTES
    }

    /// No tick recorded.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.ticks.is_empty()
    }
}

fn u32_at(b: &'static [u8]) -> Option<(usize, &'static [u8])> {
    let (n, rest) = b.split_first_chunk::<4>()?;
    Some((usize::try_from(u32::from_le_bytes(*n)).ok()?, rest))
}

/// One recorded tick: the navigation state \[s, m, m/s, rad\] (in `f64`, to be narrowed as
/// the PIL link narrows it, `NavState::to_scalar`) and the sensed lift and drag \[m/s^2\]
/// (`None` when not recorded).
#[must_use]
pub fn tick_of(bytes: &[u8]) -> (NavState<f64>, Option<SensedAero<f32>>) {
    let mut x = [0.0_f32; 9];
    for (v, c) in x.iter_mut().zip(bytes.chunks_exact(4)) {
        if let Ok(a) = <[u8; 4]>::try_from(c) {
            *v = f32::from_le_bytes(a);
        }
    }
    let [t, r, v, g, psi, lat, lon, lift, drag] = x.map(f64::from);
    let nav = NavState {
        time_s: t,
        radius_m: r,
        speed_m_s: v,
        flight_path_angle_rad: g,
        heading_rad: psi,
        latitude_rad: lat,
        longitude_rad: lon,
    };
    let sensed = (lift.is_finite() && drag.is_finite()).then(|| {
        SensedAero {
            lift_m_s2: lift,
            drag_m_s2: drag,
        }
        .to_real::<f32>()
    });
    (nav, sensed)
}
