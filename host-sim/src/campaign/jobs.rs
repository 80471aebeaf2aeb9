//! A campaign as jobs: [`Campaign`] (the set-up, the settings and the modes, checked once),
//! its `(mode, case index)` jobs, flying one job ([`Campaign::fly_job`]: a pure function of
//! the set-up, the settings and the index), and assembling gathered [`JobOutcome`]s, in any
//! order, into the [`CampaignOutput`] that `run_campaign` gives and `write_campaign` writes
//! ([`Campaign::assemble`]). The CLI's local run, the Python package and its Dask
//! distribution all go through it, so a campaign split over workers writes the same files,
//! bit for bit, as one run on one machine.

use serde::{Deserialize, Serialize};

use super::draw::draw_case;
use super::flight::fly_case;
use super::run::{CaseFailure, RunOptions};
use super::{
    CampaignError, CampaignOutput, CampaignSetup, CaseResult, DispersionSettings, Mode,
    run_campaign,
};
use crate::scenario::Scenario;

/// What one job gives: the flight's result, or the record of its failure (serde untagged: a
/// failure's JSON has an `error` field, a result's has not; failures are tried first).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(untagged)]
#[allow(clippy::large_enum_variant)] // short-lived, one per job: boxing buys nothing
pub enum JobOutcome {
    /// The flight failed; the campaign goes on (as `host-sim dispersions` records it).
    Failed(CaseFailure),
    /// The flight's result.
    Flown(CaseResult),
}

impl JobOutcome {
    /// The job: `(mode, case index)`.
    #[must_use]
    pub fn key(&self) -> (Mode, u32) {
        match self {
            Self::Failed(f) => (f.mode, f.index),
            Self::Flown(c) => (c.mode, c.index),
        }
    }
}

/// A dispersion campaign: a scenario's set-up, the settings and the modes to fly.
#[derive(Clone, Debug)]
pub struct Campaign {
    setup: CampaignSetup,
    settings: DispersionSettings,
    modes: Vec<Mode>,
}

impl Mode {
    /// The mode called `name` ([`Mode::name`]).
    ///
    /// # Errors
    /// [`CampaignError::Setting`] naming `modes` and the known names.
    pub fn by_name(name: &str) -> Result<Self, CampaignError> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == name)
            .ok_or_else(|| CampaignError::Setting {
                file: "command line".into(),
                field: "modes".into(),
                value: name.into(),
                reason: format!("unknown mode ({})", Self::ALL.map(Self::name).join(", ")),
            })
    }
}

impl Campaign {
    /// The campaign of scenario `scenario` (named `file` in messages: a path or
    /// `builtin:NAME`) with `settings` (checked, errors naming `source`: the settings file or
    /// "command line") and `modes` (empty: every mode the scenario's stack can fly).
    ///
    /// # Errors
    /// [`CampaignError`] for a bad setting, a set-up that cannot be built, or a mode the
    /// scenario's stack cannot fly.
    pub fn new(
        scenario: &Scenario,
        file: &str,
        settings: DispersionSettings,
        source: &str,
        modes: Vec<Mode>,
    ) -> Result<Self, CampaignError> {
        settings.validate(source)?;
        let setup = CampaignSetup::new(scenario, file, settings.interface_speed_m_s)?;
        let modes = if modes.is_empty() {
            setup.modes()
        } else {
            modes
        };
        setup.check_modes(&modes)?;
        Ok(Self {
            setup,
            settings,
            modes,
        })
    }

    /// The set-up (nominal flights, target, stored profile).
    #[must_use]
    pub fn setup(&self) -> &CampaignSetup {
        &self.setup
    }

    /// The settings.
    #[must_use]
    pub fn settings(&self) -> &DispersionSettings {
        &self.settings
    }

    /// The modes, in report order.
    #[must_use]
    pub fn modes(&self) -> &[Mode] {
        &self.modes
    }

    /// Every job, in the order of the report: mode order, then case index.
    #[must_use]
    pub fn jobs(&self) -> Vec<(Mode, u32)> {
        self.modes
            .iter()
            .flat_map(|&m| (0..self.settings.cases).map(move |i| (m, i)))
            .collect()
    }

    /// Fly case `index` of `mode` (a failed flight is a [`JobOutcome::Failed`], not an error).
    ///
    /// # Errors
    /// [`CampaignError::Job`] for a mode or index that is not a job of this campaign.
    pub fn fly_job(&self, mode: Mode, index: u32) -> Result<JobOutcome, CampaignError> {
        self.check_job(mode, index)?;
        let draw = draw_case(&self.settings, index);
        Ok(match fly_case(&self.setup, Some(&draw), mode) {
            Ok(c) => JobOutcome::Flown(c),
            Err(e) => JobOutcome::Failed(CaseFailure::new(mode, index, draw, &e)),
        })
    }

    /// The nominal (undispersed) flight of each mode.
    ///
    /// # Errors
    /// [`CampaignError`] if a nominal flight fails.
    pub fn nominal(&self) -> Result<Vec<CaseResult>, CampaignError> {
        self.modes
            .iter()
            .map(|&m| fly_case(&self.setup, None, m))
            .collect()
    }

    /// The whole campaign in this process: every job on `threads` threads (default all
    /// cores; the result does not depend on it), with `out_dir` the run directory whose case
    /// records are resumed and written as the cases complete (`None`: nothing written), a
    /// progress bar on stderr if `progress` ([`run_campaign`]).
    ///
    /// # Errors
    /// [`CampaignError`] as [`run_campaign`].
    pub fn run(
        &self,
        out_dir: Option<std::path::PathBuf>,
        threads: Option<usize>,
        progress: bool,
    ) -> Result<CampaignOutput, CampaignError> {
        let opts = RunOptions {
            modes: self.modes.clone(),
            out_dir,
            threads,
            progress,
        };
        run_campaign(&self.setup, &self.settings, &opts)
    }

    /// The whole campaign in this process (`run_campaign` on `threads` threads, default all
    /// cores; the result does not depend on it), nothing written: every job's outcome in
    /// [`Campaign::jobs`] order.
    ///
    /// # Errors
    /// [`CampaignError`] as `run_campaign`.
    pub fn run_local(&self, threads: Option<usize>) -> Result<Vec<JobOutcome>, CampaignError> {
        let out = self.run(None, threads, false)?;
        let mut all: Vec<JobOutcome> = out
            .cases
            .into_iter()
            .flat_map(|(_, v)| v.into_iter().map(JobOutcome::Flown))
            .chain(out.failed.into_iter().map(JobOutcome::Failed))
            .collect();
        all.sort_by_key(|o| {
            let (m, i) = o.key();
            (self.rank(m), i)
        });
        Ok(all)
    }

    /// The campaign's output from gathered job outcomes (any order; every job exactly once),
    /// with the nominal flights flown here: what `run_campaign` gives for the same settings.
    ///
    /// # Errors
    /// [`CampaignError::Job`] for an outcome that is not a job of this campaign, one given
    /// twice, or a job missing; [`CampaignError`] if a nominal flight fails.
    pub fn assemble(
        &self,
        outcomes: impl IntoIterator<Item = JobOutcome>,
    ) -> Result<CampaignOutput, CampaignError> {
        // As `run_campaign` gathers them: flown cases by mode then index, failures apart.
        let mut cases = Vec::new();
        let mut failed = Vec::new();
        for (m, v) in place_outcomes(&self.modes, self.settings.cases, outcomes)? {
            let mut flown = Vec::with_capacity(v.len());
            for c in v {
                match c {
                    JobOutcome::Flown(c) => flown.push(c),
                    JobOutcome::Failed(f) => failed.push(f),
                }
            }
            cases.push((m, flown));
        }
        Ok(CampaignOutput::new(self.nominal()?, cases, failed, 0))
    }

    fn rank(&self, m: Mode) -> usize {
        self.modes
            .iter()
            .position(|x| *x == m)
            .unwrap_or(usize::MAX)
    }

    fn check_job(&self, mode: Mode, index: u32) -> Result<(), CampaignError> {
        if !self.modes.contains(&mode) {
            return Err(job_error(mode, index, "not a mode of this campaign"));
        }
        if index >= self.settings.cases {
            return Err(CampaignError::Job {
                mode: mode.name(),
                index,
                reason: format!(
                    "outside the campaign (0 ..= {})",
                    self.settings.cases.saturating_sub(1)
                ),
            });
        }
        Ok(())
    }
}

/// Gathered job outcomes (any order) placed by job: for each of `modes`, in order, the
/// outcomes of its cases `0..cases` in index order.
///
/// # Errors
/// [`CampaignError::Job`] for an outcome of another mode or outside `0..cases`, one given
/// twice, or a job missing.
pub fn place_outcomes(
    modes: &[Mode],
    cases: u32,
    outcomes: impl IntoIterator<Item = JobOutcome>,
) -> Result<Vec<(Mode, Vec<JobOutcome>)>, CampaignError> {
    let mut by_mode: Vec<(Mode, Vec<Option<JobOutcome>>)> = modes
        .iter()
        .map(|&m| (m, vec![None; cases as usize]))
        .collect();
    for c in outcomes {
        let (mode, index) = c.key();
        let slot = by_mode
            .iter_mut()
            .find(|(m, _)| *m == mode)
            .and_then(|(_, v)| v.get_mut(index as usize))
            .ok_or_else(|| job_error(mode, index, "not a job of this campaign"))?;
        if slot.is_some() {
            return Err(job_error(mode, index, "given twice"));
        }
        *slot = Some(c);
    }
    by_mode
        .into_iter()
        .map(|(m, v)| {
            let placed = (0_u32..)
                .zip(v)
                .map(|(i, c)| c.ok_or_else(|| job_error(m, i, "missing")))
                .collect::<Result<Vec<_>, _>>()?;
            Ok((m, placed))
        })
        .collect()
}

fn job_error(mode: Mode, index: u32, reason: &str) -> CampaignError {
    CampaignError::Job {
        mode: mode.name(),
        index,
        reason: reason.into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small() -> Campaign {
        let settings = DispersionSettings {
            cases: 3,
            ..DispersionSettings::default()
        };
        let sc = Scenario::try_builtin("srm-glide").unwrap();
        Campaign::new(
            &sc,
            "builtin:srm-glide",
            settings,
            "test",
            vec![Mode::ALL[0]],
        )
        .unwrap()
    }

    /// Jobs flown one by one in any order assemble into the local run's output, bit for bit;
    /// a job outside, twice or missing is refused with its mode and index.
    #[test]
    fn jobs_in_any_order_assemble_into_the_local_run() {
        let c = small();
        assert_eq!(c.jobs().len(), 3);
        let local = c.run_local(Some(1)).unwrap();
        let mut flown: Vec<JobOutcome> = c
            .jobs()
            .into_iter()
            .rev()
            .map(|(m, i)| c.fly_job(m, i).unwrap())
            .collect();
        let (a, b) = (
            c.assemble(flown.clone()).unwrap(),
            c.assemble(local).unwrap(),
        );
        let json = |o: &CampaignOutput| {
            serde_json::to_string(&(&o.nominal, &o.cases, &o.stats, &o.failed)).unwrap()
        };
        assert_eq!(json(&a), json(&b));
        assert_eq!(a.cases[0].1.len(), 3);
        let e = c.fly_job(Mode::ALL[0], 3).unwrap_err().to_string();
        assert!(
            e.contains("case 3") && e.contains("outside the campaign (0 ..= 2)"),
            "{e}"
        );
        let e = c.fly_job(Mode::ALL[3], 0).unwrap_err().to_string();
        assert!(e.contains("not a mode of this campaign"), "{e}");
        let extra = flown[0].clone();
        flown.push(extra);
        let e = c.assemble(flown.clone()).unwrap_err().to_string();
        assert!(e.contains("given twice"), "{e}");
        flown.truncate(2);
        let e = c.assemble(flown).unwrap_err().to_string();
        assert!(e.contains("missing"), "{e}");
        assert!(Mode::by_name("replan-estimation").is_ok());
        let e = Mode::by_name("replan").unwrap_err().to_string();
        assert!(e.contains("unknown mode (stored, "), "{e}");
    }
}
