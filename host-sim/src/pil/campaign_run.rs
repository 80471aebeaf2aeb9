//! The PIL leg of a campaign (what `host-sim dispersions --pil ELF --pil-cases K` calls):
//! after the SIL campaign, its nominal flight and its cases `0..K` are flown again by the
//! firmware in QEMU ([`super::fly_case_pil`]) in the campaign's fullest mode that has a stated
//! PIL-vs-SIL tolerance ([`pil_mode`]), and each is compared with its SIL record from the
//! campaign ([`PilSilComparison`]): every command frame against the host twin (tolerance 0),
//! the same reversal and re-plan counts, the same ending, and the miss within
//! [`miss_bound_m`]. One comparison for every caller: the CLI, and the PIL tests
//! (`host-sim/tests/it/pil_campaign.rs`, `pil_replanning.rs`).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::campaign::draw::draw_case;
use crate::campaign::run::CampaignOutput;
use crate::campaign::{CampaignError, CampaignSetup, CaseResult, DispersionSettings, Mode};
use crate::report::{ReportError, write_atomic};

use super::{PilCase, PilConfig, PilError, TwinCheck, fly_case_pil};

/// The file [`write_pil_checks`] writes in a campaign's output directory.
pub const PIL_CHECKS_FILE: &str = "pil-cases.csv";

/// The miss bound of a PIL flight against its `f64` SIL flight in `mode` \[m\]: the
/// re-planner's range tolerance (`tolerance_m`) plus the terminal law's crossrange tolerance
/// (`R tolerance_rad`; 0 without the law), 0 for a mode without re-planning. The `f32`
/// rounding moves where inside the sets the guidance accepts a flight ends, not its decisions
/// (the counts check that); docs/guides/pil.md has the measured cases, one of which exceeds
/// it (the bound is not a guarantee).
#[must_use]
pub fn miss_bound_m(setup: &CampaignSetup, mode: Mode) -> f64 {
    let c = setup.stack_of(mode);
    let range = c.replan.map_or(0.0, |r| r.solver.tolerance_m);
    let cross = c.lateral.and_then(|l| l.terminal).map_or(0.0, |t| {
        t.tolerance_rad * c.replan.map_or(0.0, |r| r.model.planet.radius_m)
    });
    range + cross
}

/// One PIL flight against its SIL flight.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PilSilComparison {
    /// Every command frame against the host twin (bit for bit: tolerance 0).
    pub twin: TwinCheck,
    /// PIL miss \[m\].
    pub pil_miss_m: f64,
    /// SIL miss \[m\].
    pub sil_miss_m: f64,
    /// PIL bank reversals (from the firmware's command frames).
    pub pil_reversals: u32,
    /// SIL bank reversals.
    pub sil_reversals: u32,
    /// PIL re-plans (from the firmware's command frames).
    pub pil_replans: u32,
    /// SIL re-plans.
    pub sil_replans: u32,
    /// Whether the PIL flight reached the terminal interface.
    pub pil_reached_interface: bool,
    /// Whether the SIL flight reached the terminal interface.
    pub sil_reached_interface: bool,
    /// Whether PIL and SIL have the same numbers of reversals and of re-plans.
    pub same_counts: bool,
    /// |PIL miss - SIL miss| \[m\].
    pub miss_diff_m: f64,
    /// The miss bound ([`miss_bound_m`]) \[m\].
    pub bound_m: f64,
    /// Whether `miss_diff_m <= bound_m`.
    pub within_bound: bool,
    /// Bytes of the set-up image uploaded.
    pub image_bytes: usize,
    /// Nav/command round trips.
    pub frames: u64,
    /// The firmware's deepest whole-run stack \[bytes\] (`None`: not reported).
    pub firmware_stack_bytes: Option<u64>,
}

impl PilSilComparison {
    /// Compare the PIL flight `pil` with the SIL flight `sil` of the same case and mode, the
    /// miss against `bound_m` \[m\] ([`miss_bound_m`]).
    #[must_use]
    pub fn new(pil: &PilCase, sil: &CaseResult, bound_m: f64) -> Self {
        let p = &pil.result;
        let miss_diff_m = (p.miss_m - sil.miss_m).abs();
        Self {
            twin: pil.twin.clone(),
            pil_miss_m: p.miss_m,
            sil_miss_m: sil.miss_m,
            pil_reversals: p.reversals,
            sil_reversals: sil.reversals,
            pil_replans: p.replans,
            sil_replans: sil.replans,
            pil_reached_interface: p.reached_interface,
            sil_reached_interface: sil.reached_interface,
            same_counts: p.reversals == sil.reversals && p.replans == sil.replans,
            miss_diff_m,
            bound_m,
            within_bound: miss_diff_m <= bound_m,
            image_bytes: pil.image_bytes,
            frames: pil.stats.frames,
            firmware_stack_bytes: pil.stats.firmware_stack_bytes,
        }
    }

    /// Whether the PIL flight is the SIL flight within the stated tolerances: every frame
    /// equal to the twin, the same counts, the same ending (both reach the interface or
    /// neither), the miss within the bound.
    #[must_use]
    pub fn passed(&self) -> bool {
        self.twin.mismatches == 0
            && self.same_counts
            && self.pil_reached_interface == self.sil_reached_interface
            && self.within_bound
    }
}

/// One flight of a campaign's PIL leg: its comparison, or why it could not be compared (the
/// PIL flight failed, or the case has no SIL record because its SIL flight failed).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PilCaseCheck {
    /// Guidance mode.
    pub mode: Mode,
    /// Case index (`None`: the nominal flight).
    pub index: Option<u32>,
    /// The comparison, or the error.
    pub outcome: Result<PilSilComparison, String>,
}

impl PilCaseCheck {
    /// Whether the flight was compared and passed ([`PilSilComparison::passed`]).
    #[must_use]
    pub fn passed(&self) -> bool {
        self.outcome.as_ref().is_ok_and(PilSilComparison::passed)
    }
}

/// The mode a campaign's PIL leg flies: the fullest of `modes` (in [`Mode::ALL`] order) with a
/// stated miss tolerance ([`miss_bound_m`] > 0, i.e. with re-planning).
///
/// # Errors
/// [`CampaignError::Setting`] (field `modes`) if no mode of `modes` re-plans: the stored
/// profile's PIL-vs-SIL miss has no bound from the guidance's tolerances (the reference
/// mission's stored-profile bound is measured: `host-sim simulate --pil`, test `pil`).
pub fn pil_mode(setup: &CampaignSetup, modes: &[Mode]) -> Result<Mode, CampaignError> {
    Mode::ALL
        .into_iter()
        .rev()
        .find(|m| modes.contains(m) && miss_bound_m(setup, *m) > 0.0)
        .ok_or_else(|| CampaignError::Setting {
            file: setup.file.clone(),
            field: "modes".into(),
            value: modes.iter().map(|m| m.name()).collect::<Vec<_>>().join(","),
            reason: "PIL compares a re-planning mode (replan-reversals or replan-estimation): \
                     the others have no stated PIL-vs-SIL miss tolerance"
                .into(),
        })
}

/// Check `cases` (K) for a campaign of `settings`: 1 to `settings.cases`.
///
/// # Errors
/// [`CampaignError::Setting`] (file `command line`, field `--pil-cases`) otherwise.
pub fn check_pil_cases(cases: u32, settings: &DispersionSettings) -> Result<(), CampaignError> {
    if (1..=settings.cases).contains(&cases) {
        return Ok(());
    }
    Err(CampaignError::Setting {
        file: "command line".into(),
        field: "--pil-cases".into(),
        value: cases.to_string(),
        reason: format!(
            "fly 1 to {} cases in PIL (the campaign's cases; -n sets them)",
            settings.cases
        ),
    })
}

/// Fly the PIL leg of a campaign flown in SIL as `output` (`setup`, `settings`): in `mode`
/// ([`pil_mode`]), the nominal flight and cases `0..cases` flown by the firmware `cfg.elf`
/// one after the other, each compared with its SIL record in `output`. A PIL flight that
/// fails, or a case without a SIL record, is a [`PilCaseCheck`] with its error, and the
/// others go on.
///
/// # Errors
/// [`PilError::QemuMissing`] or [`PilError::ElfMissing`] before any flight;
/// [`PilError::Campaign`] for a bad `cases` ([`check_pil_cases`]). A Ctrl-C (a stop request)
/// ends the leg with the flight's error.
pub fn fly_campaign_pil(
    setup: &CampaignSetup,
    settings: &DispersionSettings,
    output: &CampaignOutput,
    mode: Mode,
    cases: u32,
    cfg: &PilConfig,
) -> Result<Vec<PilCaseCheck>, PilError> {
    check_pil_cases(cases, settings).map_err(|e| PilError::Campaign(Box::new(e)))?;
    cfg.check_tools()?;
    let bound_m = miss_bound_m(setup, mode);
    let recorded = output
        .cases
        .iter()
        .find(|(m, _)| *m == mode)
        .map_or(&[][..], |(_, v)| v.as_slice());
    let mut checks = Vec::new();
    for index in std::iter::once(None).chain((0..cases).map(Some)) {
        let sil = match index {
            None => output.nominal.iter().find(|c| c.mode == mode),
            Some(i) => recorded.iter().find(|c| c.index == i),
        };
        let draw = index.map(|i| draw_case(settings, i));
        let outcome = match (sil, fly_case_pil(setup, draw.as_ref(), mode, cfg.clone())) {
            (_, Err(e)) if crate::sim::stop_requested() => return Err(e),
            (_, Err(e)) => Err(format!("PIL flight failed: {e}")),
            (None, Ok(_)) => Err("no SIL record (its SIL flight failed)".to_string()),
            (Some(sil), Ok(pil)) => Ok(PilSilComparison::new(&pil, sil, bound_m)),
        };
        checks.push(PilCaseCheck {
            mode,
            index,
            outcome,
        });
    }
    Ok(checks)
}

/// Write `checks` as `<dir>/`[`PIL_CHECKS_FILE`] (one line per flight: the twin check and
/// the comparison with SIL, misses in km; `error` for a flight not compared); returns the
/// file.
///
/// # Errors
/// [`ReportError`] naming the path.
pub fn write_pil_checks(dir: &Path, checks: &[PilCaseCheck]) -> Result<PathBuf, ReportError> {
    let mut csv = String::from(
        "mode,case,passed,twin_ticks,twin_mismatches,first_mismatch_s,pil_reversals,\
         sil_reversals,pil_replans,sil_replans,same_counts,pil_reached_interface,\
         sil_reached_interface,pil_miss_km,sil_miss_km,miss_diff_km,bound_km,within_bound,\
         image_bytes,frames,firmware_stack_bytes,error\n",
    );
    for c in checks {
        let case = c
            .index
            .map_or_else(|| "nominal".to_string(), |i| i.to_string());
        let _ = write!(csv, "{},{case},{},", c.mode.name(), c.passed());
        match &c.outcome {
            Ok(s) => {
                let _ = writeln!(
                    csv,
                    "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},",
                    s.twin.ticks,
                    s.twin.mismatches,
                    s.twin
                        .first
                        .as_ref()
                        .map_or_else(String::new, |(t, _)| t.to_string()),
                    s.pil_reversals,
                    s.sil_reversals,
                    s.pil_replans,
                    s.sil_replans,
                    s.same_counts,
                    s.pil_reached_interface,
                    s.sil_reached_interface,
                    s.pil_miss_m / 1e3,
                    s.sil_miss_m / 1e3,
                    s.miss_diff_m / 1e3,
                    s.bound_m / 1e3,
                    s.within_bound,
                    s.image_bytes,
                    s.frames,
                    s.firmware_stack_bytes
                        .map_or_else(String::new, |b| b.to_string()),
                );
            }
            Err(e) => {
                let e = e.replace(['"', '\n'], " ");
                let _ = writeln!(csv, "{}\"{e}\"", ",".repeat(18));
            }
        }
    }
    let p = dir.join(PIL_CHECKS_FILE);
    write_atomic(&p, csv.as_bytes())?;
    Ok(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ok() -> PilSilComparison {
        PilSilComparison {
            twin: TwinCheck {
                ticks: 650,
                mismatches: 0,
                first: None,
            },
            pil_miss_m: 1_560.0,
            sil_miss_m: 1_530.0,
            pil_reversals: 8,
            sil_reversals: 8,
            pil_replans: 101,
            sil_replans: 101,
            pil_reached_interface: true,
            sil_reached_interface: true,
            same_counts: true,
            miss_diff_m: 30.0,
            bound_m: 3_000.0,
            within_bound: true,
            image_bytes: 724,
            frames: 650,
            firmware_stack_bytes: Some(17_164),
        }
    }

    /// Each tolerance alone fails a flight; a flight not compared fails; the CSV has one
    /// line per flight with as many fields as its header.
    #[test]
    fn each_tolerance_fails_a_flight_and_the_csv_lines_match_the_header() {
        assert!(ok().passed());
        let broken: [fn(&mut PilSilComparison); 4] = [
            |c| c.twin.mismatches = 1,
            |c| c.same_counts = false,
            |c| c.pil_reached_interface = false,
            |c| c.within_bound = false,
        ];
        let mut checks = vec![PilCaseCheck {
            mode: Mode::ReplanEstimation,
            index: None,
            outcome: Ok(ok()),
        }];
        for (i, f) in broken.iter().enumerate() {
            let mut c = ok();
            f(&mut c);
            assert!(!c.passed(), "{i}");
            checks.push(PilCaseCheck {
                mode: Mode::ReplanEstimation,
                index: Some(u32::try_from(i).unwrap_or(0)),
                outcome: Ok(c),
            });
        }
        let failed = PilCaseCheck {
            mode: Mode::ReplanEstimation,
            index: Some(9),
            outcome: Err("PIL flight failed: \"x\"\nat y".into()),
        };
        assert!(!failed.passed());
        checks.push(failed);
        let dir = std::env::temp_dir().join(format!("host-sim-pil-checks-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap_or_default();
        let p = write_pil_checks(&dir, &checks).unwrap_or_default();
        let text = std::fs::read_to_string(&p).unwrap_or_default();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), checks.len() + 1, "{text}");
        let n = lines[0].split(',').count();
        for l in &lines {
            assert_eq!(l.split(',').count(), n, "{l}");
        }
        assert!(lines[1].starts_with("replan-estimation,nominal,true,650,0,"));
        assert!(lines[6].starts_with("replan-estimation,9,false,"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
