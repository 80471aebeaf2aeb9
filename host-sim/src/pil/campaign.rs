//! A campaign case in PIL (and, through [`start_stack`], any scenario's stack:
//! `super::fly_scenario_pil`): the mode's whole stack (`CampaignSetup::stack_of`) uploaded to
//! the firmware as one set-up image (protocol v2, `guidance_core::setup::image`) and flown in
//! the case's dispersed world, with the case's IMU feeding sensed accelerations through the
//! nav frames ([`fly_case_pil`]).
//!
//! Beside the firmware flies its twin: the same image decoded on the host in the firmware's
//! scalars (`f32` for the Cortex-M4F, the fixed-point tick with `f32` layers for the
//! Cortex-M3) and ticked with the same narrowed inputs. Every command frame is compared with
//! the twin bit for bit ([`TwinCheck`]): what the board computes is what the host computes in
//! its arithmetic, so the PIL-to-SIL difference is exactly the `f32`-to-`f64` difference of the
//! stack.

use guidance_core::estimate::SensedAero;
use guidance_core::guidance::Command;
use guidance_core::nodes::DEFAULT_NODE_CAPACITY;
use guidance_core::setup::image::{decode, encode, image_capacity};
use guidance_core::stack::{FlightStack, HostStackConfig, Layers};
use guidance_core::{Fixed, NavState, Scalar};
use onboard_spec::machines::CORTEX_M4F;

use crate::campaign::draw::CaseDraw;
use crate::campaign::flight::{CaseCounts, CaseSource, fly_case_with};
use crate::campaign::{CampaignError, CampaignSetup, CaseResult, Mode};
use crate::sim::{AttitudeSource, SimResult};

use super::{
    FrameLimits, PilConfig, PilError, PilGuidance, PilRecord, PilStats, machine_of_elf,
    unwrap_pil_error,
};

/// Node capacity of the firmware's tables (the `pil` binary's).
const CAPACITY: usize = DEFAULT_NODE_CAPACITY;

/// The firmware's stack on the host, in the firmware's scalars.
#[derive(Clone, Debug)]
#[allow(clippy::large_enum_variant)]
enum Twin {
    /// Cortex-M4F: `f32` throughout.
    F32(FlightStack<f32, CAPACITY, f32>),
    /// Cortex-M3: fixed-point tick, `f32` layers.
    Fixed(FlightStack<Fixed, CAPACITY, f32>),
}

/// What the twin answered at one tick: (held command, ramp start, tick time \[s\],
/// reversals, re-plans).
type TwinAnswer = (Command<f64>, Command<f64>, f64, u32, u32);

impl Twin {
    fn tick(
        &mut self,
        nav: &NavState<f64>,
        sensed: Option<&SensedAero<f64>>,
    ) -> Result<TwinAnswer, guidance_core::GuidanceError> {
        let m = sensed.map(|s| s.to_real::<f32>());
        match self {
            Twin::F32(s) => {
                s.tick(&nav.to_scalar(), m.as_ref())?;
                let t = s.guidance().last_tick_s().unwrap_or(0.0);
                Ok((
                    s.command().to_f64(),
                    s.attitude_at(t).to_f64(),
                    f64::from(t),
                    u32::from(s.reversals()),
                    s.replan_counts().map_or(0, |c| c.replans),
                ))
            }
            Twin::Fixed(s) => {
                s.tick(&nav.to_scalar(), m.as_ref())?;
                let t = s.guidance().last_tick_s().unwrap_or(Fixed::ZERO);
                Ok((
                    s.command().to_f64(),
                    s.attitude_at(t).to_f64(),
                    t.to_f64(),
                    u32::from(s.reversals()),
                    s.replan_counts().map_or(0, |c| c.replans),
                ))
            }
        }
    }

    fn uses_sensed(&self) -> bool {
        match self {
            Twin::F32(s) => s.uses_sensed(),
            Twin::Fixed(s) => s.uses_sensed(),
        }
    }
}

/// The comparison of every command frame with the host twin ([`fly_case_pil`]).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TwinCheck {
    /// Ticks compared.
    pub ticks: u32,
    /// Ticks whose frame differed from the twin in any bit (command, ramp start, tick time,
    /// reversal or re-plan count).
    pub mismatches: u32,
    /// The first difference: time \[s\] and a description.
    pub first: Option<(f64, String)>,
}

/// The firmware and its twin as a flight's guidance (a campaign case's or a scenario's).
pub(super) struct PilCaseSource {
    pub(super) pil: PilGuidance,
    twin: Twin,
    sensed: Option<SensedAero<f64>>,
    pub(super) check: TwinCheck,
    counts: (u32, u32),
}

impl AttitudeSource for PilCaseSource {
    type Error = PilError;
    fn tick(&mut self, nav: &NavState<f64>) -> Result<(), PilError> {
        let sensed = self.sensed.take();
        self.pil.tick(nav)?;
        let Some(frame) = self.pil.last else {
            return Err(PilError::QemuNotRunning);
        };
        self.counts = (frame.reversals, frame.replans);
        self.check.ticks += 1;
        let got = (
            frame.command,
            frame.ramp_start,
            frame.tick_time_s,
            frame.reversals,
            frame.replans,
        );
        let differs = match self.twin.tick(nav, sensed.as_ref()) {
            Ok(want) => {
                let same = |a: Command<f64>, b: Command<f64>| {
                    a.alpha_rad.to_bits() == b.alpha_rad.to_bits()
                        && a.sigma_rad.to_bits() == b.sigma_rad.to_bits()
                };
                let equal = same(got.0, want.0)
                    && same(got.1, want.1)
                    && got.2.to_bits() == want.2.to_bits()
                    && got.3 == want.3
                    && got.4 == want.4;
                (!equal).then(|| format!("firmware {got:?}, host twin {want:?}"))
            }
            Err(e) => Some(format!("host twin refused the sample: {e}")),
        };
        if let Some(what) = differs {
            self.check.mismatches += 1;
            if self.check.first.is_none() {
                self.check.first = Some((nav.time_s, what));
            }
        }
        Ok(())
    }
    fn sense(&mut self, nav: &NavState<f64>, sensed: &SensedAero<f64>) -> Result<(), PilError> {
        self.sensed = Some(*sensed);
        self.pil.sense(nav, sensed)
    }
    fn senses(&self) -> bool {
        self.pil.senses()
    }
    fn attitude_at(&self, time_s: f64) -> Command<f64> {
        self.pil.attitude_at(time_s)
    }
    fn next_tick_s(&self) -> f64 {
        self.pil.next_tick_s()
    }
    fn next_kink_s(&self, time_s: f64) -> f64 {
        self.pil.next_kink_s(time_s)
    }
}

impl CaseSource for PilCaseSource {
    fn counts(&self) -> CaseCounts {
        CaseCounts {
            reversals: self.counts.0,
            replans: self.counts.1,
            // Not carried by the link: fall-backs and the estimate stay on the board.
            fall_backs: 0,
            estimated_scales: None,
        }
    }
}

/// A campaign case flown in PIL ([`fly_case_pil`]).
#[derive(Clone, Debug)]
pub struct PilCase {
    /// The case's record, as the campaign writes it (reversals and re-plans from the
    /// firmware's command frames; fall-backs and the final estimate are not carried: 0 and
    /// `None`).
    pub result: CaseResult,
    /// Every command frame against the host twin.
    pub twin: TwinCheck,
    /// The link counters and the firmware's summary (stack, ticks, overruns).
    pub stats: PilStats,
    /// Bytes of the set-up image uploaded.
    pub image_bytes: usize,
}

/// The set-up image of `config` (protocol v2, `guidance_core::setup::image`).
///
/// # Errors
/// [`PilError::Image`] if the stack has no image for the firmware (e.g. more than its
/// [`DEFAULT_NODE_CAPACITY`] nodes).
pub(super) fn stack_image(config: &HostStackConfig<f64>) -> Result<Vec<u8>, PilError> {
    let mut buf = vec![0u8; image_capacity(config.profile.table.len())];
    let n = encode(config, &mut buf).map_err(PilError::Image)?;
    buf.truncate(n);
    Ok(buf)
}

/// The frame limits of a stack: its profile's bounds, rates, initial attitude and period.
pub(super) fn stack_limits(config: &HostStackConfig<f64>) -> FrameLimits {
    let p = &config.profile;
    FrameLimits {
        bounds: p.table.bounds(),
        rates: p.guidance.rates,
        initial: p.initial,
        period_s: p.guidance.period_s,
    }
}

/// Start the firmware `cfg.elf` on the stack `config` (its set-up image uploaded) beside its
/// host twin, as a flight's guidance; `file` names the scenario in errors. Also returns the
/// image's size \[bytes\].
pub(super) fn start_stack(
    config: &HostStackConfig<f64>,
    cfg: PilConfig,
    file: &str,
) -> Result<(PilCaseSource, usize), PilError> {
    let image = stack_image(config)?;
    let machine = cfg.machine.unwrap_or_else(|| machine_of_elf(&cfg.elf));
    let refused = |source| {
        PilError::Campaign(Box::new(CampaignError::Stack {
            file: file.to_string(),
            source,
        }))
    };
    let twin = if machine == CORTEX_M4F {
        let c = decode(&image, Layers::ALL).map_err(PilError::Image)?;
        Twin::F32(FlightStack::new(&c).map_err(refused)?)
    } else {
        let c = decode(&image, Layers::ALL).map_err(PilError::Image)?;
        Twin::Fixed(FlightStack::new(&c).map_err(refused)?)
    };
    let senses = twin.uses_sensed();
    let pil = PilGuidance::start_with_image(cfg, stack_limits(config), &image, senses)?;
    Ok((
        PilCaseSource {
            pil,
            twin,
            sensed: None,
            check: TwinCheck::default(),
            counts: (0, 0),
        },
        image.len(),
    ))
}

/// Fly case `draw` (`None`: the nominal world) of the campaign `setup` in `mode` in PIL: the
/// mode's stack uploaded to the firmware `cfg.elf` as a set-up image, the case's world, IMU
/// and terminal interface as [`crate::campaign::flight::fly_case`] flies them in SIL.
///
/// # Errors
/// [`PilError::Image`] if the stack has no image for the firmware (e.g. more than its
/// [`DEFAULT_NODE_CAPACITY`] nodes), [`PilError::ImageRejected`] if the firmware refuses it,
/// [`PilError::Campaign`] if the case cannot be set up, and the link's and QEMU's errors.
pub fn fly_case_pil(
    setup: &CampaignSetup,
    draw: Option<&CaseDraw>,
    mode: Mode,
    cfg: PilConfig,
) -> Result<PilCase, PilError> {
    let mut record = PilRecord::default();
    fly_case_pil_run(setup, draw, mode, cfg, 0.0, &mut record).map(|(case, _)| case)
}

/// [`fly_case_pil`], also returning the run (samples every `output_interval_s`, or at the
/// guidance ticks for 0); `record` becomes the handle of the frame record (complete up to a
/// failure, whose exchange is marked) once the firmware is started.
///
/// # Errors
/// As [`fly_case_pil`].
pub(super) fn fly_case_pil_run(
    setup: &CampaignSetup,
    draw: Option<&CaseDraw>,
    mode: Mode,
    cfg: PilConfig,
    output_interval_s: f64,
    record: &mut PilRecord,
) -> Result<(PilCase, SimResult), PilError> {
    let (source, image_bytes) = start_stack(&setup.stack_of(mode), cfg, &setup.file)?;
    *record = source.pil.record();
    let (result, source, run) = fly_case_with(
        setup,
        draw,
        mode,
        output_interval_s,
        &mut |_| {},
        move |_| Ok(source),
    )
    .map_err(|e| match e {
        CampaignError::Sim { source, .. } => unwrap_pil_error(source),
        e => PilError::Campaign(Box::new(e)),
    })?;
    let stats = source.pil.finish()?;
    Ok((
        PilCase {
            result,
            twin: source.check,
            stats,
            image_bytes,
        },
        run,
    ))
}
