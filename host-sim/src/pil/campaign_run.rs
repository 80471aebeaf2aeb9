//! A whole campaign in PIL ([`run_campaign_pil`], what `host-sim dispersions --pil` calls):
//! every case of every requested mode, the nominal flights included, flown by the firmware in
//! QEMU ([`super::fly_case_pil`]) through the campaign's own loop
//! ([`crate::campaign::run::run_campaign_with`]: the same records, resume, failure handling
//! and stop requests as a SIL campaign). Each flight is also flown in SIL
//! ([`crate::campaign::flight::fly_case`]) and compared: its twin check (every command frame
//! against the host twin, bit for bit) and its PIL-vs-SIL comparison ([`PilCaseCheck`]),
//! written per case to `<out>/`[`PIL_CASES_DIR`]`/<mode>/<index>.json` (read back for a
//! resumed case) and for the whole campaign to `<out>/pil-cases.csv` ([`write_pil_checks`]).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, PoisonError};

use serde::{Deserialize, Serialize};

use crate::campaign::draw::CaseDraw;
use crate::campaign::flight::fly_case;
use crate::campaign::run::{CampaignOutput, RunOptions, run_campaign_with};
use crate::campaign::{CampaignError, CampaignSetup, CaseResult, DispersionSettings, Mode};
use crate::report::{ReportError, write_atomic};

use super::{PilConfig, PilError, TwinCheck, fly_case_pil};

/// Where a PIL campaign keeps each case's [`PilCaseCheck`] in its output directory:
/// `<out>/pil-cases/<mode>/<index>.json` (the index as in `cases/`).
pub const PIL_CASES_DIR: &str = "pil-cases";

impl From<CampaignError> for PilError {
    fn from(e: CampaignError) -> Self {
        PilError::CampaignRun(Box::new(e))
    }
}

/// A flight's SIL counterpart and how the PIL flight compares with it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SilComparison {
    /// SIL miss \[m\].
    pub miss_m: f64,
    /// SIL bank reversals.
    pub reversals: u32,
    /// SIL re-plans.
    pub replans: u32,
    /// Whether PIL and SIL have the same numbers of reversals and of re-plans.
    pub same_counts: bool,
    /// |PIL miss - SIL miss| \[m\].
    pub miss_diff_m: f64,
    /// The mode's miss bound ([`miss_bound_m`]) \[m\].
    pub bound_m: f64,
    /// Whether `miss_diff_m <= bound_m`.
    pub within_bound: bool,
}

/// One flight of a PIL campaign checked: against its host twin and against its SIL flight.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PilCaseCheck {
    /// Guidance mode.
    pub mode: Mode,
    /// Case index (`None`: the nominal flight).
    pub index: Option<u32>,
    /// PIL miss \[m\] (the case's record).
    pub miss_m: f64,
    /// PIL bank reversals (from the firmware's command frames).
    pub reversals: u32,
    /// PIL re-plans (from the firmware's command frames).
    pub replans: u32,
    /// Every command frame against the host twin.
    pub twin: TwinCheck,
    /// The SIL flight of the same case and mode, compared.
    pub sil: SilComparison,
    /// Bytes of the set-up image uploaded.
    pub image_bytes: usize,
    /// Nav/command round trips.
    pub frames: u64,
    /// The firmware's deepest whole-run stack \[bytes\] (`None`: not reported).
    pub firmware_stack_bytes: Option<u64>,
}

impl PilCaseCheck {
    /// Whether the flight passed: twin equal at every tick, SIL's counts, miss within bound.
    #[must_use]
    pub fn passed(&self) -> bool {
        self.twin.mismatches == 0 && self.sil.same_counts && self.sil.within_bound
    }
}

/// The miss bound of a PIL flight against its `f64` SIL flight in `mode` \[m\]: the
/// re-planner's range tolerance (`tolerance_m`) plus the terminal law's crossrange tolerance
/// (`R tolerance_rad`), 0 for a layer the mode does not fly. The `f32` rounding moves where
/// inside what the guidance accepts a flight ends (docs/guides/pil.md); a mode without either
/// layer (the stored profile flown open loop) has bound 0.
#[must_use]
pub fn miss_bound_m(setup: &CampaignSetup, mode: Mode) -> f64 {
    let c = setup.stack_of(mode);
    let range = c.replan.map_or(0.0, |r| r.solver.tolerance_m);
    let cross = c.lateral.and_then(|l| l.terminal).map_or(0.0, |t| {
        t.tolerance_rad * c.replan.map_or(0.0, |r| r.model.planet.radius_m)
    });
    range + cross
}

/// A campaign flown in PIL ([`run_campaign_pil`]).
#[derive(Clone, Debug)]
pub struct PilCampaign {
    /// The campaign, as a SIL campaign reports it (its records are the PIL flights'; the
    /// link does not carry fall-backs and the final estimate: 0 and `None`).
    pub output: CampaignOutput,
    /// Per mode (in the run's order): its nominal flight, then its cases by index. A case
    /// resumed without its check on disk has none.
    pub checks: Vec<PilCaseCheck>,
}

fn check_path(dir: &Path, mode: Mode, index: u32) -> PathBuf {
    dir.join(PIL_CASES_DIR)
        .join(mode.name())
        .join(format!("{index:06}.json"))
}

/// Fly the campaign (`setup`, `settings`, `opts`) in PIL on the firmware `cfg.elf`: every
/// flight as [`super::fly_case_pil`] flies it, on `opts.threads` threads (`None`: 1), each
/// flight with its own QEMU; each flight also flown in SIL and compared ([`PilCaseCheck`]).
/// With `opts.out_dir`, the records go to `cases/` as a SIL campaign writes them (a run into
/// the same directory resumes them; a SIL campaign's directory is refused by the
/// fingerprint's nominal flights) and each check to [`PIL_CASES_DIR`]. QEMU and the ELF are
/// checked before the first flight ([`PilConfig::check_tools`]). A Ctrl-C (the CLI's handler,
/// [`crate::sim::request_stop`]) stops the flights at their next breakpoint, each QEMU
/// stopped and its FIFO directory removed as its flight ends ([`super::interrupt_cleanup`]
/// at a second one).
///
/// # Errors
/// [`PilError::QemuMissing`], [`PilError::ElfMissing`] before any flight; a failed nominal
/// flight's error; [`PilError::CampaignRun`] for the campaign's own errors
/// ([`crate::campaign::run::run_campaign`]'s). A failed dispersed flight is recorded in
/// [`CampaignOutput::failed`] and the other cases go on.
pub fn run_campaign_pil(
    setup: &CampaignSetup,
    settings: &DispersionSettings,
    opts: &RunOptions,
    cfg: &PilConfig,
) -> Result<PilCampaign, PilError> {
    cfg.check_tools()?;
    let mut opts = opts.clone();
    opts.threads = Some(opts.threads.unwrap_or(1));
    let checks: Mutex<Vec<PilCaseCheck>> = Mutex::default();
    let dir = opts.out_dir.clone();
    let fly = |draw: Option<&CaseDraw>, mode: Mode| -> Result<CaseResult, PilError> {
        let pil = fly_case_pil(setup, draw, mode, cfg.clone())?;
        let sil = fly_case(setup, draw, mode).map_err(|e| PilError::Campaign(Box::new(e)))?;
        let p = &pil.result;
        let miss_diff_m = (p.miss_m - sil.miss_m).abs();
        let bound_m = miss_bound_m(setup, mode);
        let check = PilCaseCheck {
            mode,
            index: draw.map(|d| d.index),
            miss_m: p.miss_m,
            reversals: p.reversals,
            replans: p.replans,
            twin: pil.twin.clone(),
            sil: SilComparison {
                miss_m: sil.miss_m,
                reversals: sil.reversals,
                replans: sil.replans,
                same_counts: p.reversals == sil.reversals && p.replans == sil.replans,
                miss_diff_m,
                bound_m,
                within_bound: miss_diff_m <= bound_m,
            },
            image_bytes: pil.image_bytes,
            frames: pil.stats.frames,
            firmware_stack_bytes: pil.stats.firmware_stack_bytes,
        };
        // The check before the record: a resumed record always has its check.
        if let (Some(dir), Some(index)) = (&dir, check.index) {
            let path = check_path(dir, mode, index);
            if let Some(parent) = path.parent() {
                std::fs::create_dir_all(parent).map_err(|source| {
                    PilError::from(CampaignError::from(ReportError::Io {
                        path: parent.to_path_buf(),
                        source,
                    }))
                })?;
            }
            let json = serde_json::to_vec_pretty(&check)
                .map_err(|e| PilError::from(CampaignError::from(ReportError::from(e))))?;
            write_atomic(&path, &json).map_err(|e| PilError::from(CampaignError::from(e)))?;
        }
        checks
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .push(check);
        Ok(pil.result)
    };
    let output = run_campaign_with(setup, settings, &opts, fly)?;
    let flown = checks.into_inner().unwrap_or_else(PoisonError::into_inner);
    let find = |mode: Mode, index: Option<u32>| {
        flown
            .iter()
            .find(|c| c.mode == mode && c.index == index)
            .cloned()
    };
    let mut ordered = Vec::new();
    for &mode in &opts.modes {
        ordered.extend(find(mode, None));
        let cases = output
            .cases
            .iter()
            .find(|(m, _)| *m == mode)
            .map_or(&[][..], |(_, v)| v.as_slice());
        for c in cases {
            let stored = || -> Option<PilCaseCheck> {
                let text = std::fs::read_to_string(check_path(dir.as_ref()?, mode, c.index));
                serde_json::from_str(&text.ok()?).ok()
            };
            ordered.extend(find(mode, Some(c.index)).or_else(stored));
        }
    }
    Ok(PilCampaign {
        output,
        checks: ordered,
    })
}

/// Write `checks` as `<dir>/pil-cases.csv` (one line per flight: the twin check and the
/// comparison with SIL); returns the file.
///
/// # Errors
/// [`ReportError`] naming the path.
pub fn write_pil_checks(dir: &Path, checks: &[PilCaseCheck]) -> Result<PathBuf, ReportError> {
    let mut csv = String::from(
        "mode,index,twin_ticks,twin_mismatches,first_mismatch_s,pil_miss_km,sil_miss_km,\
         miss_diff_km,bound_km,pil_reversals,sil_reversals,pil_replans,sil_replans,\
         same_counts,within_bound,image_bytes,frames,firmware_stack_bytes\n",
    );
    for c in checks {
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            c.mode.name(),
            c.index.map_or_else(|| "nominal".to_string(), |i| i.to_string()),
            c.twin.ticks,
            c.twin.mismatches,
            c.twin
                .first
                .as_ref()
                .map_or_else(String::new, |(t, _)| t.to_string()),
            c.miss_m / 1e3,
            c.sil.miss_m / 1e3,
            c.sil.miss_diff_m / 1e3,
            c.sil.bound_m / 1e3,
            c.reversals,
            c.sil.reversals,
            c.replans,
            c.sil.replans,
            c.sil.same_counts,
            c.sil.within_bound,
            c.image_bytes,
            c.frames,
            c.firmware_stack_bytes
                .map_or_else(String::new, |b| b.to_string()),
        );
    }
    let p = dir.join("pil-cases.csv");
    write_atomic(&p, csv.as_bytes())?;
    Ok(p)
}
