//! Set-up protocol v2: the whole flight-guidance stack ([`StackConfig`]) as one byte image,
//! versioned and CRC-checked, uploaded in fixed chunks of [`CHUNK_BYTES`] bytes
//! ([`crate::link::Frame::Image`]) and rebuilt on the firmware in its own scalars.
//!
//! # Image layout
//! Little-endian throughout; every real is an `f64` (the host's value goes over unchanged and
//! the firmware rounds it to its scalar, exactly where a host run of the same scalar rounds).
//!
//! | bytes      | field                                                               |
//! |------------|---------------------------------------------------------------------|
//! | 0..4       | magic [`IMAGE_MAGIC`] (`"RGS2"`)                                    |
//! | 4..6       | version (`u16`, [`IMAGE_VERSION`])                                  |
//! | 6..8       | layer mask (`u16`: bit 0 re-planner, 1 lateral, 2 estimator, 3 barrier, 4 target) |
//! | 8..12      | image length in bytes, CRC included (`u32`)                         |
//! | 12..len-4  | the layers, in this order: profile, re-planner, lateral, estimator, barrier, target (each present layer only) |
//! | len-4..len | CRC-32 (IEEE 802.3, [`crc32`]) of bytes `0..len-4`                  |
//!
//! The profile: period \[s\], alpha and sigma rate limits \[rad/s\]; independent variable
//! (`u8`: 0 E-hat, 1 time); interpolation (`u8`: 0 linear, 1 natural cubic, 2 cardinal
//! Hermite) and its tension \[-\]; angle bounds (alpha min, max, sigma min, max \[rad\]);
//! node count (`u16`) and the nodes (x, alpha, sigma); the E-hat map's parts
//! ([`EnergyNormalizer::parts`]: circular speed \[m/s\], planet radius \[m\], inverse span
//! \[-\]); the initial attitude (alpha, sigma \[rad\]).
//!
//! The re-planner ([`ReplanLayer`]): every N ticks (`u16`); heat-flux \[W/m^2\] and g-load
//! \[-\] limits; lambda, vertical-fraction interval, tolerance \[m\]; iterations (`u8`);
//! predictor final speed \[m/s\], skips (`u8`), mode (`u8`, the order of
//! [`PredictorMode`]); planet (mu \[m^3/s^2\], radius \[m\]), atmosphere (rho0 \[kg/m^3\],
//! scale height \[m\], reference radius \[m\]), vehicle (mass \[kg\], area \[m^2\], `C_D0`, `K`,
//! nose radius \[m\]), rotation rate \[rad/s\]; apply out of reach, steps per tick (`u8`
//! each); lift schedule (`u8` node count, 0: none; speed \[m/s\], lambda, drag scale per node);
//! start energy (`u8` flag, E-hat); numerical rotation (`u8`); final energy (`u8` flag,
//! \[J/kg\]); bank shape (`u8`).
//!
//! Lateral ([`LateralLayer`]): corridor axis (`u8`: 0 speed, 1 E-hat with its map's three
//! parts), x high, width high \[rad\], x low, width low \[rad\]; hysteresis \[rad\]; most
//! reversals (`u8`); freeze angle \[rad\]; terminal law (`u8` flag; start angle \[rad\],
//! tolerance \[rad\], reversal lead \[s\]).
//!
//! Estimator ([`EstimatorConfig`]): the two gains, L/D bounds, drag bounds, least drag
//! \[m/s^2\]. Barrier ([`BarrierLayer`]): limits, descent time \[s\], frequency \[rad/s\],
//! damping \[-\], predicted (`u8`). Target: kind (`u8`: 0 point, then latitude and longitude
//! \[rad\]; 1 flown range angle, then the total \[rad\] and 0).
//!
//! # Refusals
//! [`decode`] refuses with a typed [`ImageError`] (bad magic, version, CRC, size, a malformed
//! field, a table or schedule larger than the build holds, a value the scalar cannot hold, a
//! layer the build does not fly); the firmware then builds nothing and answers the status
//! (`crate::link::LinkStatus`), never flying less than the image says.

use crate::command::Command;
use crate::energy::EnergyNormalizer;
use crate::estimate::EstimatorConfig;
use crate::guidance::{GuidanceConfig, RateLimits};
use crate::interp::Interpolation;
use crate::lateral::{Corridor, CorridorAxis, TerminalLateral};
use crate::nodes::{AngleBounds, Independent, Node, NodeTable};
use crate::replan::{
    LiftSchedule, PathBound, PredictorMode, PredictorModel, RangeTarget, ReplanConfig,
    ReplanLimits, SCHEDULE_NODES, ScheduleNode, TargetPoint,
};
use crate::scalar::{Real, Scalar};
use crate::stack::{
    BarrierLayer, LateralLayer, Layer, Layers, ProfileLayer, ReplanLayer, StackConfig,
};
use crate::vinh::PredictorConfig;
use crate::vinh::nondim::{ExpAtmosphere, Planet, VehicleParams};

/// The image's first four bytes.
pub const IMAGE_MAGIC: [u8; 4] = *b"RGS2";
/// The image format version this build writes and reads.
pub const IMAGE_VERSION: u16 = 3;
/// Image bytes carried by one image frame.
pub const CHUNK_BYTES: usize = 68;
/// Header bytes (magic, version, layer mask, length).
const HEADER: usize = 12;

/// Largest image of a stack with at most `nodes` profile nodes \[bytes\] (every layer on, a
/// full lift schedule, an E-hat corridor).
#[must_use]
pub const fn image_capacity(nodes: usize) -> usize {
    let profile = 3 * 8 + 1 + 1 + 8 + 4 * 8 + 2 + 24 * nodes + 3 * 8 + 2 * 8;
    let replan = 2
        + 2 * 8
        + 4 * 8
        + 1
        + 8
        + 1
        + 1
        + 2 * 8
        + 3 * 8
        + 5 * 8
        + 8
        + 1
        + 1
        + 1
        + 24 * SCHEDULE_NODES
        + 1
        + 8
        + 1
        + 1
        + 8
        + 1;
    let lateral = 1 + 3 * 8 + 4 * 8 + 8 + 1 + 8 + 1 + 3 * 8;
    let estimator = 6 * 8 + 8;
    let barrier = 5 * 8 + 1;
    let target = 1 + 2 * 8;
    HEADER + profile + replan + lateral + estimator + barrier + target + 4
}

/// Why an image cannot be written or flown.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ImageError {
    /// The first bytes are not [`IMAGE_MAGIC`].
    BadMagic,
    /// The image is of another format version.
    BadVersion {
        /// The version the image says.
        found: u16,
    },
    /// The CRC-32 does not match the bytes.
    BadCrc,
    /// The image is shorter than its header says or than a field, longer than the build's
    /// buffer, or its chunks do not add up to its length.
    Size,
    /// A chunk arrived out of order (its index is not the next one).
    ChunkOrder,
    /// An enumeration or flag byte out of range, a non-finite value, a layer mask that
    /// disagrees with the layers, or bytes left after the last layer.
    Malformed,
    /// The profile table or the lift schedule has more nodes than the build holds.
    TooManyNodes,
    /// A value does not fit the firmware's scalar (fixed point).
    Range,
    /// The image has a layer this build does not fly.
    Unsupported(Layer),
}

impl core::fmt::Display for ImageError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::BadMagic => f.write_str("not a set-up image (bad magic)"),
            Self::BadVersion { found } => {
                write!(
                    f,
                    "set-up image version {found}, this build reads {IMAGE_VERSION}"
                )
            }
            Self::BadCrc => f.write_str("set-up image CRC-32 mismatch"),
            Self::Size => f.write_str("set-up image size wrong or too large for the build"),
            Self::ChunkOrder => f.write_str("set-up image chunk out of order"),
            Self::Malformed => f.write_str("malformed set-up image field"),
            Self::TooManyNodes => f.write_str("more nodes than the build holds"),
            Self::Range => f.write_str("a value does not fit the firmware's scalar"),
            Self::Unsupported(l) => write!(f, "{l:?} layer not flown by this build"),
        }
    }
}

impl core::error::Error for ImageError {}

/// CRC-32 (IEEE 802.3: reflected polynomial 0xEDB88320, initial value and final xor
/// 0xFFFFFFFF; check value 0xCBF43926 for `b"123456789"`). Bitwise: no table in flash.
#[must_use]
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = u32::MAX;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            let mask = (crc & 1).wrapping_neg();
            crc = (crc >> 1) ^ (0xEDB8_8320 & mask);
        }
    }
    !crc
}

/// Bytes written into a buffer.
struct Writer<'a> {
    out: &'a mut [u8],
    at: usize,
}

impl Writer<'_> {
    fn bytes(&mut self, b: &[u8]) -> Result<(), ImageError> {
        let end = self.at.checked_add(b.len()).ok_or(ImageError::Size)?;
        self.out
            .get_mut(self.at..end)
            .ok_or(ImageError::Size)?
            .copy_from_slice(b);
        self.at = end;
        Ok(())
    }
    fn u8(&mut self, v: u8) -> Result<(), ImageError> {
        self.bytes(&[v])
    }
    fn flag(&mut self, v: bool) -> Result<(), ImageError> {
        self.u8(u8::from(v))
    }
    fn u16(&mut self, v: u16) -> Result<(), ImageError> {
        self.bytes(&v.to_le_bytes())
    }
    fn f(&mut self, v: f64) -> Result<(), ImageError> {
        if !v.is_finite() {
            return Err(ImageError::Malformed);
        }
        self.bytes(&v.to_le_bytes())
    }
    fn fs(&mut self, v: &[f64]) -> Result<(), ImageError> {
        v.iter().try_for_each(|&x| self.f(x))
    }
}

/// Bytes read from an image.
struct Reader<'a> {
    b: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take<const K: usize>(&mut self) -> Result<[u8; K], ImageError> {
        let end = self.at.checked_add(K).ok_or(ImageError::Size)?;
        let s = self.b.get(self.at..end).ok_or(ImageError::Size)?;
        let mut a = [0u8; K];
        a.copy_from_slice(s);
        self.at = end;
        Ok(a)
    }
    fn u8(&mut self) -> Result<u8, ImageError> {
        self.take::<1>().map(|[b]| b)
    }
    fn enum_u8(&mut self, max: u8) -> Result<u8, ImageError> {
        let v = self.u8()?;
        if v > max {
            return Err(ImageError::Malformed);
        }
        Ok(v)
    }
    fn flag(&mut self) -> Result<bool, ImageError> {
        self.enum_u8(1).map(|v| v == 1)
    }
    fn u16(&mut self) -> Result<u16, ImageError> {
        self.take::<2>().map(u16::from_le_bytes)
    }
    fn f(&mut self) -> Result<f64, ImageError> {
        let v = f64::from_le_bytes(self.take::<8>()?);
        if v.is_finite() {
            Ok(v)
        } else {
            Err(ImageError::Malformed)
        }
    }
    /// A guidance-scalar value (checked: the fixed point has a narrow range).
    fn s<S: Scalar>(&mut self) -> Result<S, ImageError> {
        S::from_f64_checked(self.f()?).ok_or(ImageError::Range)
    }
    /// A predictor-scalar value.
    fn p<P: Real>(&mut self) -> Result<P, ImageError> {
        P::from_f64_checked(self.f()?).ok_or(ImageError::Range)
    }
}

fn w<S: Scalar>(x: S) -> f64 {
    x.to_f64()
}

fn mode_code(m: PredictorMode) -> u8 {
    match m {
        PredictorMode::Chain => 0,
        PredictorMode::Glide => 1,
        PredictorMode::Auto => 2,
        PredictorMode::AutoSink => 3,
        PredictorMode::Numerical => 4,
        PredictorMode::Hybrid => 5,
        PredictorMode::HybridSink => 6,
    }
}

fn mode_of(c: u8) -> PredictorMode {
    match c {
        0 => PredictorMode::Chain,
        1 => PredictorMode::Glide,
        2 => PredictorMode::Auto,
        3 => PredictorMode::AutoSink,
        4 => PredictorMode::Numerical,
        5 => PredictorMode::Hybrid,
        _ => PredictorMode::HybridSink,
    }
}

fn mask_of(l: Layers, target: bool) -> u16 {
    u16::from(l.replan)
        | u16::from(l.lateral) << 1
        | u16::from(l.estimator) << 2
        | u16::from(l.barrier) << 3
        | u16::from(target) << 4
}

/// Write the image of `config` (any scalars, node capacity `M`) into `out`; its length
/// \[bytes\].
///
/// # Errors
/// [`ImageError::Size`] if `out` is too short ([`image_capacity`] of the table's nodes is
/// always enough), [`ImageError::Malformed`] for a non-finite value.
pub fn encode<S: Scalar, const M: usize, P: Real>(
    config: &StackConfig<S, M, P>,
    out: &mut [u8],
) -> Result<usize, ImageError> {
    let mut wr = Writer { out, at: 0 };
    wr.bytes(&IMAGE_MAGIC)?;
    wr.u16(IMAGE_VERSION)?;
    wr.u16(mask_of(config.layers(), config.target.is_some()))?;
    wr.bytes(&[0; 4])?;
    let p = &config.profile;
    let g = &p.guidance;
    wr.fs(&[
        w(g.period_s),
        w(g.rates.alpha_rad_s),
        w(g.rates.sigma_rad_s),
    ])?;
    wr.u8(match p.table.independent() {
        Independent::NormalizedEnergy => 0,
        Independent::TimeS => 1,
    })?;
    let (k, tension) = match p.interpolation {
        Interpolation::Linear => (0, 0.0),
        Interpolation::NaturalCubic => (1, 0.0),
        Interpolation::CardinalHermite { tension } => (2, w(tension)),
    };
    wr.u8(k)?;
    wr.f(tension)?;
    let b = p.table.bounds();
    wr.fs(&[
        w(b.alpha_min_rad),
        w(b.alpha_max_rad),
        w(b.sigma_min_rad),
        w(b.sigma_max_rad),
    ])?;
    let nodes = p.table.nodes();
    wr.u16(u16::try_from(nodes.len()).map_err(|_| ImageError::TooManyNodes)?)?;
    for n in nodes {
        wr.fs(&[w(n.x), w(n.alpha_rad), w(n.sigma_rad)])?;
    }
    wr.fs(&p.energy.parts().map(w))?;
    wr.fs(&[w(p.initial.alpha_rad), w(p.initial.sigma_rad)])?;
    if let Some(r) = &config.replan {
        wr.u16(r.every_n_ticks)?;
        wr.fs(&[w(r.limits.heat_flux_w_m2), w(r.limits.g_load)])?;
        let s = &r.solver;
        wr.fs(&[
            w(s.lambda),
            w(s.min_vertical_fraction),
            w(s.max_vertical_fraction),
            w(s.tolerance_m),
        ])?;
        wr.u8(s.max_iterations)?;
        wr.f(w(s.predictor.final_speed_m_s))?;
        wr.u8(s.predictor.max_skips)?;
        wr.u8(mode_code(s.mode))?;
        let m = &r.model;
        wr.fs(&[
            w(m.planet.mu_m3_s2),
            w(m.planet.radius_m),
            w(m.atmosphere.rho0_kg_m3),
            w(m.atmosphere.scale_height_m),
            w(m.atmosphere.ref_radius_m),
            w(m.vehicle.mass_kg),
            w(m.vehicle.reference_area_m2),
            w(m.vehicle.cd0),
            w(m.vehicle.k_polar),
            w(m.vehicle.nose_radius_m),
            w(m.rotation_rate_rad_s),
        ])?;
        wr.flag(r.apply_out_of_reach)?;
        wr.u8(r.steps_per_tick)?;
        match &r.lift_schedule {
            None => wr.u8(0)?,
            Some(ls) => {
                let used = ls.nodes.get(..ls.len).ok_or(ImageError::TooManyNodes)?;
                wr.u8(u8::try_from(used.len()).map_err(|_| ImageError::TooManyNodes)?)?;
                for n in used {
                    wr.fs(&[w(n.speed_m_s), w(n.lambda), w(n.drag_scale)])?;
                }
            }
        }
        wr.flag(r.start_normalized_energy.is_some())?;
        if let Some(e) = r.start_normalized_energy {
            wr.f(w(e))?;
        }
        wr.flag(r.numerical_rotation)?;
        wr.flag(r.final_energy_j_kg.is_some())?;
        if let Some(e) = r.final_energy_j_kg {
            wr.f(w(e))?;
        }
        wr.flag(r.bank_shape)?;
    }
    if let Some(l) = &config.lateral {
        let c = &l.corridor;
        match &c.axis {
            CorridorAxis::Speed => wr.u8(0)?,
            CorridorAxis::NormalizedEnergy(e) => {
                wr.u8(1)?;
                wr.fs(&e.parts().map(w))?;
            }
        }
        wr.fs(&[
            w(c.x_high),
            w(c.width_high_rad),
            w(c.x_low),
            w(c.width_low_rad),
            w(l.hysteresis_rad),
        ])?;
        wr.u8(l.max_reversals)?;
        wr.f(w(l.freeze_angle_rad))?;
        wr.flag(l.terminal.is_some())?;
        if let Some(t) = &l.terminal {
            wr.fs(&[
                w(t.start_angle_rad),
                w(t.tolerance_rad),
                w(t.reversal_lead_s),
            ])?;
        }
    }
    if let Some(e) = &config.estimator {
        wr.fs(&[
            w(e.lift_to_drag_gain),
            w(e.drag_gain),
            w(e.lift_to_drag_bounds.0),
            w(e.lift_to_drag_bounds.1),
            w(e.drag_bounds.0),
            w(e.drag_bounds.1),
            w(e.min_drag_m_s2),
        ])?;
    }
    if let Some(b) = &config.barrier {
        let pb = &b.bound;
        wr.fs(&[
            w(pb.limits.heat_flux_w_m2),
            w(pb.limits.g_load),
            w(pb.descent_time_s),
            w(pb.barrier_frequency_rad_s),
            w(pb.barrier_damping),
        ])?;
        wr.flag(b.predicted)?;
    }
    if let Some(t) = &config.target {
        match t {
            RangeTarget::Point(p) => {
                wr.u8(0)?;
                wr.fs(&[w(p.latitude_rad), w(p.longitude_rad)])?;
            }
            RangeTarget::FlownRangeAngle { total_rad } => {
                wr.u8(1)?;
                wr.fs(&[w(*total_rad), 0.0])?;
            }
        }
    }
    let len = wr.at.checked_add(4).ok_or(ImageError::Size)?;
    let len32 = u32::try_from(len).map_err(|_| ImageError::Size)?;
    let out = wr.out;
    out.get_mut(8..12)
        .ok_or(ImageError::Size)?
        .copy_from_slice(&len32.to_le_bytes());
    let crc = crc32(out.get(..len - 4).ok_or(ImageError::Size)?);
    out.get_mut(len - 4..len)
        .ok_or(ImageError::Size)?
        .copy_from_slice(&crc.to_le_bytes());
    Ok(len)
}

/// The image's length from its header (`None` if fewer than 12 bytes).
#[must_use]
pub fn declared_len(head: &[u8]) -> Option<usize> {
    let b = head.get(8..12)?;
    let mut a = [0u8; 4];
    a.copy_from_slice(b);
    usize::try_from(u32::from_le_bytes(a)).ok()
}

/// Check an image (magic, version, length, CRC, layer mask against `supported`) and read it
/// into a [`StackConfig`] of guidance scalar `S`, node capacity `N` and predictor scalar `P`.
/// The layers' own checks run when a [`crate::stack::FlightStack`] is built from it.
///
/// # Errors
/// [`ImageError`] naming the first problem, in the order: size, magic, version, CRC, layers,
/// fields.
pub fn decode<S: Scalar, const N: usize, P: Real>(
    bytes: &[u8],
    supported: Layers,
) -> Result<StackConfig<S, N, P>, ImageError> {
    if bytes.len() < HEADER + 4 {
        return Err(ImageError::Size);
    }
    if bytes.get(..4) != Some(IMAGE_MAGIC.as_slice()) {
        return Err(ImageError::BadMagic);
    }
    let mut r = Reader { b: bytes, at: 4 };
    let version = r.u16()?;
    if version != IMAGE_VERSION {
        return Err(ImageError::BadVersion { found: version });
    }
    let mask = r.u16()?;
    if declared_len(bytes) != Some(bytes.len()) {
        return Err(ImageError::Size);
    }
    let (body, crc_bytes) = bytes.split_at(bytes.len() - 4);
    let mut c = [0u8; 4];
    c.copy_from_slice(crc_bytes);
    if crc32(body) != u32::from_le_bytes(c) {
        return Err(ImageError::BadCrc);
    }
    if mask >> 5 != 0 {
        return Err(ImageError::Malformed);
    }
    let has = |bit: u16| mask & (1 << bit) != 0;
    let layers = Layers {
        replan: has(0),
        lateral: has(1),
        estimator: has(2),
        barrier: has(3),
    };
    for (on, ok, layer) in [
        (layers.replan, supported.replan, Layer::Replan),
        (layers.lateral, supported.lateral, Layer::Lateral),
        (layers.estimator, supported.estimator, Layer::Estimator),
        (layers.barrier, supported.barrier, Layer::Barrier),
    ] {
        if on && !ok {
            return Err(ImageError::Unsupported(layer));
        }
    }
    // Fields, from byte 12, within the CRC-covered body.
    let mut r = Reader {
        b: body,
        at: HEADER,
    };
    let guidance = GuidanceConfig {
        period_s: r.s()?,
        rates: RateLimits {
            alpha_rad_s: r.s()?,
            sigma_rad_s: r.s()?,
        },
    };
    let independent = match r.enum_u8(1)? {
        0 => Independent::NormalizedEnergy,
        _ => Independent::TimeS,
    };
    let kind = r.enum_u8(2)?;
    let tension: S = r.s()?;
    let interpolation = match kind {
        0 => Interpolation::Linear,
        1 => Interpolation::NaturalCubic,
        _ => Interpolation::CardinalHermite { tension },
    };
    let bounds = AngleBounds {
        alpha_min_rad: r.s()?,
        alpha_max_rad: r.s()?,
        sigma_min_rad: r.s()?,
        sigma_max_rad: r.s()?,
    };
    let count = usize::from(r.u16()?);
    if count > N {
        return Err(ImageError::TooManyNodes);
    }
    let zero = Node {
        x: S::ZERO,
        alpha_rad: S::ZERO,
        sigma_rad: S::ZERO,
    };
    let mut nodes = [zero; N];
    for n in nodes.iter_mut().take(count) {
        *n = Node {
            x: r.s()?,
            alpha_rad: r.s()?,
            sigma_rad: r.s()?,
        };
    }
    let used = nodes.get(..count).ok_or(ImageError::TooManyNodes)?;
    // A table the core rejects is flown by nobody: reported as malformed.
    let table = NodeTable::new(independent, used, bounds).map_err(|_| ImageError::Malformed)?;
    let energy =
        EnergyNormalizer::from_parts([r.f()?, r.f()?, r.f()?]).map_err(|_| ImageError::Range)?;
    let initial = Command {
        alpha_rad: r.s()?,
        sigma_rad: r.s()?,
    };
    let profile = ProfileLayer {
        guidance,
        table,
        interpolation,
        energy,
        initial,
    };
    let replan = if layers.replan {
        let every_n_ticks = r.u16()?;
        let limits = ReplanLimits {
            heat_flux_w_m2: r.p()?,
            g_load: r.p()?,
        };
        let lambda = r.p()?;
        let min_vertical_fraction = r.p()?;
        let max_vertical_fraction = r.p()?;
        let tolerance_m = r.p()?;
        let max_iterations = r.u8()?;
        let final_speed_m_s = r.p()?;
        let max_skips = r.u8()?;
        let mode = mode_of(r.enum_u8(6)?);
        let model = PredictorModel {
            planet: Planet {
                mu_m3_s2: r.p()?,
                radius_m: r.p()?,
            },
            atmosphere: ExpAtmosphere {
                rho0_kg_m3: r.p()?,
                scale_height_m: r.p()?,
                ref_radius_m: r.p()?,
            },
            vehicle: VehicleParams {
                mass_kg: r.p()?,
                reference_area_m2: r.p()?,
                cd0: r.p()?,
                k_polar: r.p()?,
                nose_radius_m: r.p()?,
            },
            rotation_rate_rad_s: r.p()?,
        };
        let apply_out_of_reach = r.flag()?;
        let steps_per_tick = r.u8()?;
        let len = usize::from(r.u8()?);
        let lift_schedule = if len == 0 {
            None
        } else {
            if len > SCHEDULE_NODES {
                return Err(ImageError::TooManyNodes);
            }
            let zero = ScheduleNode {
                speed_m_s: P::ZERO,
                lambda: P::ZERO,
                drag_scale: P::ONE,
            };
            let mut ls = LiftSchedule {
                nodes: [zero; SCHEDULE_NODES],
                len,
            };
            for n in ls.nodes.iter_mut().take(len) {
                *n = ScheduleNode {
                    speed_m_s: r.p()?,
                    lambda: r.p()?,
                    drag_scale: r.p()?,
                };
            }
            // Unused nodes repeat the last, as `LiftSchedule::from_nodes` leaves them.
            let last = ls.nodes.get(len - 1).copied().unwrap_or(zero);
            for n in ls.nodes.iter_mut().skip(len) {
                *n = last;
            }
            Some(ls)
        };
        let start_normalized_energy = if r.flag()? { Some(r.p()?) } else { None };
        let numerical_rotation = r.flag()?;
        let final_energy_j_kg = if r.flag()? { Some(r.p()?) } else { None };
        let bank_shape = r.flag()?;
        Some(ReplanLayer {
            every_n_ticks,
            limits,
            solver: ReplanConfig {
                lambda,
                min_vertical_fraction,
                max_vertical_fraction,
                tolerance_m,
                max_iterations,
                predictor: PredictorConfig {
                    final_speed_m_s,
                    max_skips,
                },
                mode,
            },
            model,
            apply_out_of_reach,
            steps_per_tick,
            lift_schedule,
            start_normalized_energy,
            numerical_rotation,
            bank_shape,
            final_energy_j_kg,
        })
    } else {
        None
    };
    let lateral = if layers.lateral {
        let axis = match r.enum_u8(1)? {
            0 => CorridorAxis::Speed,
            _ => CorridorAxis::NormalizedEnergy(
                EnergyNormalizer::from_parts([r.f()?, r.f()?, r.f()?])
                    .map_err(|_| ImageError::Range)?,
            ),
        };
        let corridor = Corridor {
            axis,
            x_high: r.p()?,
            width_high_rad: r.p()?,
            x_low: r.p()?,
            width_low_rad: r.p()?,
        };
        let hysteresis_rad = r.p()?;
        let max_reversals = r.u8()?;
        let freeze_angle_rad = r.p()?;
        let terminal = if r.flag()? {
            Some(TerminalLateral {
                start_angle_rad: r.p()?,
                tolerance_rad: r.p()?,
                reversal_lead_s: r.p()?,
            })
        } else {
            None
        };
        Some(LateralLayer {
            corridor,
            hysteresis_rad,
            max_reversals,
            freeze_angle_rad,
            terminal,
        })
    } else {
        None
    };
    let estimator = if layers.estimator {
        Some(EstimatorConfig {
            lift_to_drag_gain: r.p()?,
            drag_gain: r.p()?,
            lift_to_drag_bounds: (r.p()?, r.p()?),
            drag_bounds: (r.p()?, r.p()?),
            min_drag_m_s2: r.p()?,
        })
    } else {
        None
    };
    let barrier = if layers.barrier {
        Some(BarrierLayer {
            bound: PathBound {
                limits: ReplanLimits {
                    heat_flux_w_m2: r.p()?,
                    g_load: r.p()?,
                },
                descent_time_s: r.p()?,
                barrier_frequency_rad_s: r.p()?,
                barrier_damping: r.p()?,
            },
            predicted: r.flag()?,
        })
    } else {
        None
    };
    let target = if has(4) {
        let kind = r.enum_u8(1)?;
        let (a, b) = (r.p()?, r.p()?);
        Some(match kind {
            0 => RangeTarget::Point(TargetPoint {
                latitude_rad: a,
                longitude_rad: b,
            }),
            _ => {
                if b != P::ZERO {
                    return Err(ImageError::Malformed);
                }
                RangeTarget::FlownRangeAngle { total_rad: a }
            }
        })
    } else {
        None
    };
    if r.at != body.len() {
        return Err(ImageError::Malformed);
    }
    Ok(StackConfig {
        profile,
        replan,
        lateral,
        estimator,
        barrier,
        target,
    })
}

/// Collects an image from its chunks on the firmware (`CAP` bytes of buffer, at least
/// [`image_capacity`] of the build's node capacity).
#[derive(Clone, Debug)]
pub struct ImageReceiver<const CAP: usize> {
    buf: [u8; CAP],
    /// Bytes received.
    len: usize,
    /// Index of the next chunk.
    next: u16,
}

impl<const CAP: usize> Default for ImageReceiver<CAP> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const CAP: usize> ImageReceiver<CAP> {
    /// Nothing received.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            buf: [0; CAP],
            len: 0,
            next: 0,
        }
    }

    /// Take chunk `index` of `count` (index 0 starts a new image). `Some(image)` once the
    /// last chunk arrived (the image's bytes, its declared length, unchecked: see
    /// [`decode`]).
    ///
    /// # Errors
    /// [`ImageError::ChunkOrder`] for a chunk that is not the next one (the image is then
    /// dropped), [`ImageError::Size`] for an image longer than `CAP`, or chunks that do not
    /// add up to the length its header says.
    pub fn take(
        &mut self,
        index: u16,
        count: u16,
        data: &[u8; CHUNK_BYTES],
    ) -> Result<Option<&[u8]>, ImageError> {
        if index == 0 {
            self.len = 0;
            self.next = 0;
        }
        if index != self.next || index >= count {
            self.next = 0;
            self.len = 0;
            return Err(ImageError::ChunkOrder);
        }
        let end = self.len + CHUNK_BYTES;
        let Some(dst) = self.buf.get_mut(self.len..end) else {
            self.next = 0;
            self.len = 0;
            return Err(ImageError::Size);
        };
        dst.copy_from_slice(data);
        self.len = end;
        self.next = index + 1;
        if self.next < count {
            return Ok(None);
        }
        self.next = 0;
        let total = declared_len(&self.buf).ok_or(ImageError::Size)?;
        // The chunks cover the image, the last one padded with fewer than a chunk of zeros.
        if total > self.len || self.len - total >= CHUNK_BYTES || total < HEADER + 4 {
            return Err(ImageError::Size);
        }
        self.buf.get(..total).map(Some).ok_or(ImageError::Size)
    }
}

/// The chunks of an image: (index, count, 68 bytes, the last padded with zeros).
pub fn chunks(image: &[u8]) -> impl Iterator<Item = (u16, u16, [u8; CHUNK_BYTES])> + '_ {
    let count = u16::try_from(image.len().div_ceil(CHUNK_BYTES)).unwrap_or(u16::MAX);
    image.chunks(CHUNK_BYTES).zip(0u16..).map(move |(c, i)| {
        let mut a = [0u8; CHUNK_BYTES];
        if let Some(d) = a.get_mut(..c.len()) {
            d.copy_from_slice(c);
        }
        (i, count, a)
    })
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing)]
mod tests {
    use super::*;

    #[test]
    fn crc32_check_value() {
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
    }

    /// The figure docs/reference/guidance-stack.md states.
    #[test]
    fn capacity_of_the_firmware_table() {
        assert_eq!(image_capacity(16), 1181);
        assert_eq!(image_capacity(16).div_ceil(CHUNK_BYTES), 18);
    }
}
