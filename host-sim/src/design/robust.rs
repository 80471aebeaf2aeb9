//! The robust design problem (issue 25 item 1): a decision is the stored profile's node table
//! (the fixed-length [`Encoding`](super::Encoding) of [`ReentryProblem`]), followed by one gene
//! per named guidance setting of the base's stack (`[[robust.settings]]`,
//! [`super::robust_settings`]); its evaluation flies a dispersion
//! campaign of `K` flights of the base scenario's whole guidance stack with that profile, and
//! takes its objectives and constraint from the campaign's statistics
//! ([`crate::campaign::ModeStats`], the figures `host-sim dispersions` reports).
//!
//! * **Common random numbers**: case `i` of every candidate draws the same dispersions (the
//!   campaign's draw is a function of `(dispersions.seed, i)` alone,
//!   [`crate::campaign::draw::draw_case`]), so two candidates differ only by their profiles.
//! * **Target**: the base scenario must name a fixed target (`[guidance.target]` latitude and
//!   longitude, or downrange and crossrange): a target placed at the nominal end would move
//!   with every candidate's profile.
//! * **Objectives** (minimised, 1 to 4): [`Statistic`]s of the flights flown (a failed flight,
//!   one the simulator could not fly, is not in them, as in the campaign report).
//! * **Constraint** (`g <= 0` feasible): `v / K - max_violation_fraction`, with `v` the
//!   flights that failed, ended before the terminal interface, or exceeded any limit of the
//!   vehicle (peak heat flux, g-load or g-load rate above its limit).
//! * A candidate whose nominal flight cannot be flown (the campaign set-up fails), or whose
//!   flights all failed, is a failed evaluation ([`Evaluation::failure`]: it loses every
//!   comparison); no objective is ever NaN otherwise.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::robust_settings::{SettingVariable, StackSettings};
use super::{DesignError, ReentryProblem};
use crate::campaign::jobs::place_outcomes;
use crate::campaign::{
    Campaign, CampaignError, CaseResult, DispersionSettings, JobOutcome, Mode, ModeStats,
};
use crate::optim::rows::read_population;
use crate::optim::{Bounds, EvalError, Evaluation, Problem, RealProblem};
use crate::scenario::{Scenario, TargetSpec};

/// A statistic of a campaign, as an objective (minimised).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Statistic {
    /// Median miss distance \[km\].
    MissP50Km,
    /// 99th-percentile miss distance \[km\] (nearest rank).
    MissP99Km,
    /// Mean miss distance \[km\].
    MissMeanKm,
    /// Largest miss distance \[km\].
    MissWorstKm,
    /// 99th percentile of peak heat flux / limit \[-\].
    HeatFluxRatioP99,
    /// 99th percentile of peak g-load / limit \[-\].
    GLoadRatioP99,
    /// 99th percentile of peak g-load rate / limit \[-\].
    GLoadRateRatioP99,
}

impl Statistic {
    /// Its axis label, with units.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Self::MissP50Km => "median miss [km]",
            Self::MissP99Km => "p99 miss [km]",
            Self::MissMeanKm => "mean miss [km]",
            Self::MissWorstKm => "largest miss [km]",
            Self::HeatFluxRatioP99 => "p99 heat flux / limit [-]",
            Self::GLoadRatioP99 => "p99 g-load / limit [-]",
            Self::GLoadRateRatioP99 => "p99 g-load rate / limit [-]",
        }
    }

    /// Its value in the campaign's figures.
    #[must_use]
    pub fn of(self, s: &ModeStats) -> f64 {
        match self {
            Self::MissP50Km => s.miss_km.p50,
            Self::MissP99Km => s.miss_km.p99,
            Self::MissMeanKm => s.miss_km.mean,
            Self::MissWorstKm => s.miss_km.worst,
            Self::HeatFluxRatioP99 => s.heat_flux_ratio.p99,
            Self::GLoadRatioP99 => s.g_load_ratio.p99,
            Self::GLoadRateRatioP99 => s.g_load_rate_ratio.p99,
        }
    }
}

/// The `[robust]` section of a run file: the campaign every candidate flies and the
/// statistics it is judged by.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobustConfig {
    /// The campaign's dispersions (the `[dispersions]` keys of `host-sim dispersions`,
    /// defaults as there): `cases` is `K`, `seed` fixes the common random numbers.
    #[serde(default)]
    pub dispersions: DispersionSettings,
    /// The guidance mode flown (`stored`, `stored-reversals`, `replan-reversals`,
    /// `replan-estimation`); absent: the most complete mode the base scenario's stack flies
    /// (the last of its modes in report order).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mode: Option<String>,
    /// The objectives, 1 to 4 distinct statistics (default: 99th-percentile miss and
    /// 99th-percentile heat-flux ratio).
    #[serde(default = "default_objectives")]
    pub objectives: Vec<Statistic>,
    /// The constraint: at most this fraction of the `K` flights may fail, end before the
    /// terminal interface or exceed a limit, in `[0, 1)` (default 0: every flight holds
    /// every limit).
    #[serde(default)]
    pub max_violation_fraction: f64,
    /// A nominal run's front.csv (of the same `[problem]` encoding; a path relative to the
    /// run file's folder, as `problem.base`): after the run its members fly this campaign
    /// too, for the robust front against the nominal one (nominal-front.csv,
    /// robust-vs-nominal.svg). Absent: no comparison.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nominal_front: Option<String>,
    /// Guidance settings of the base scenario's stack that are decision variables too
    /// (`[[robust.settings]]`, [`SettingVariable`]): one gene each, after the encoding's,
    /// in this order. Empty: the base's settings are flown as they are.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub settings: Vec<SettingVariable>,
}

fn default_objectives() -> Vec<Statistic> {
    vec![Statistic::MissP99Km, Statistic::HeatFluxRatioP99]
}

impl Default for RobustConfig {
    fn default() -> Self {
        Self {
            dispersions: DispersionSettings::default(),
            mode: None,
            objectives: default_objectives(),
            max_violation_fraction: 0.0,
            nominal_front: None,
            settings: Vec::new(),
        }
    }
}

impl RobustConfig {
    /// Check the objectives, the fraction and the dispersions.
    ///
    /// # Errors
    /// [`DesignError::Robust`] naming the `robust.` field.
    pub fn validate(&self) -> Result<(), DesignError> {
        let bad = |field: &str, value: String, reason: &str| {
            Err(DesignError::Robust {
                field: field.to_string(),
                value,
                reason: reason.to_string(),
            })
        };
        let n = self.objectives.len();
        let distinct = self
            .objectives
            .iter()
            .enumerate()
            .all(|(i, s)| !self.objectives[..i].contains(s));
        if !(1..=4).contains(&n) || !distinct {
            return bad(
                "robust.objectives",
                format!("{:?}", self.objectives),
                "give 1 to 4 distinct statistics",
            );
        }
        let f = self.max_violation_fraction;
        if !(0.0..1.0).contains(&f) {
            return bad(
                "robust.max_violation_fraction",
                crate::num_fmt::compact(f),
                "use a fraction in [0, 1)",
            );
        }
        match self.dispersions.validate("robust") {
            Err(CampaignError::Setting {
                field,
                value,
                reason,
                ..
            }) => bad(&format!("robust.{field}"), value, &reason),
            Err(e) => Err(DesignError::RobustBase(Box::new(e))),
            Ok(()) => Ok(()),
        }
    }
}

/// What one candidate's campaign gave.
#[derive(Clone, Debug, PartialEq)]
pub struct RobustOutcome {
    /// The figures of the flights flown.
    pub stats: ModeStats,
    /// Flights that failed, ended before the interface or exceeded a limit.
    pub violations: u32,
    /// Flights in the campaign (`K`).
    pub cases: u32,
}

/// The robust design problem: [`ReentryProblem`]'s encoding and bounds, each candidate judged
/// by a campaign of the base scenario's stack (module docs).
#[derive(Clone, Debug)]
pub struct RobustProblem {
    inner: ReentryProblem,
    stack: Scenario,
    config: RobustConfig,
    mode: Mode,
    file: String,
    /// The `[[robust.settings]]` checked against the stack.
    settings: StackSettings,
    /// The encoding's bounds and then each setting's range.
    bounds: Bounds,
}

impl RobustProblem {
    /// The robust problem of `inner` (its encoding and bounds; its objectives and limits are
    /// not used) flying `stack` (the base scenario with its guidance layers and a fixed
    /// target; its nodes are replaced by each decision's) under `config`. `file` names the
    /// base in errors.
    ///
    /// # Errors
    /// [`DesignError::Robust`] naming the field: an analytical `inner`, nominal `limits` or
    /// `objectives` other than the defaults, no layers or no fixed target in the base, a mode
    /// its stack cannot fly, bad objectives, fraction or dispersions;
    /// [`DesignError::RobustBase`] when the base's campaign cannot be set up.
    pub fn new(
        inner: ReentryProblem,
        stack: Scenario,
        config: RobustConfig,
        file: &str,
    ) -> Result<Self, DesignError> {
        let bad = |field: &str, value: String, reason: &str| {
            Err(DesignError::Robust {
                field: field.to_string(),
                value,
                reason: reason.to_string(),
            })
        };
        if inner.analytical().is_some() {
            return bad(
                "problem.simulator",
                "analytical".into(),
                "a robust problem flies the numerical closed loop: leave simulator out",
            );
        }
        if inner.limits() != &super::Limits::default() {
            return bad(
                "problem.limits",
                format!("{:?}", inner.limits()),
                "not used by a robust problem (its constraint is on the vehicle's limits, \
                 robust.max_violation_fraction): leave it out",
            );
        }
        if inner.objective_settings() != &super::Objectives::default() {
            return bad(
                "problem.objectives",
                format!("{:?}", inner.objective_settings()),
                "not used by a robust problem (its objectives are robust.objectives): leave it \
                 out",
            );
        }
        let Some(layers) = &stack.layers else {
            return bad(
                "problem.base",
                file.into(),
                "a robust problem flies the base scenario's guidance stack: give a scenario \
                 file with [guidance.*] layers and a [guidance.target]",
            );
        };
        if layers.target == TargetSpec::Nominal {
            return bad(
                "problem.base",
                file.into(),
                "a robust problem needs a fixed target: [guidance.target] latitude_deg and \
                 longitude_deg, or downrange_km and crossrange_km (a nominal target would move \
                 with every candidate)",
            );
        }
        config.validate()?;
        let settings = StackSettings::new(&stack, &config.settings, file)?;
        let (mut lower, mut upper) = (
            inner.bounds().lower().to_vec(),
            inner.bounds().upper().to_vec(),
        );
        for s in &config.settings {
            lower.push(s.range[0]);
            upper.push(s.range[1]);
        }
        let bounds = Bounds::new(lower, upper)?;
        let modes = match &config.mode {
            Some(name) => {
                vec![
                    Mode::by_name(name).map_err(|_| DesignError::Robust {
                        field: "robust.mode".into(),
                        value: name.clone(),
                        reason:
                            "use stored, stored-reversals, replan-reversals or replan-estimation"
                                .into(),
                    })?,
                ]
            }
            None => Vec::new(),
        };
        // The mode checked against what the stack flies, with the base's own profile.
        let campaign = Campaign::new(&stack, file, config.dispersions.clone(), "robust", modes)
            .map_err(|e| match e {
                CampaignError::Setting {
                    field,
                    value,
                    reason,
                    ..
                } => DesignError::Robust {
                    field: format!("robust.{field}"),
                    value,
                    reason,
                },
                e => DesignError::RobustBase(Box::new(e)),
            })?;
        let mode = *campaign.modes().last().unwrap_or(&Mode::Stored);
        Ok(Self {
            inner,
            stack,
            config,
            mode,
            file: file.to_string(),
            settings,
            bounds,
        })
    }

    /// The fixed-length problem whose encoding and bounds this one uses.
    #[must_use]
    pub fn inner(&self) -> &ReentryProblem {
        &self.inner
    }

    /// The guidance mode every candidate flies.
    #[must_use]
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// The settings.
    #[must_use]
    pub fn config(&self) -> &RobustConfig {
        &self.config
    }

    /// The base scenario's value of each `[[robust.settings]]` entry (file units): what a
    /// decision of the encoding alone flies ([`RobustProblem::with_base_settings`]).
    #[must_use]
    pub fn base_setting_values(&self) -> &[f64] {
        self.settings.base_values()
    }

    /// A decision of the encoding alone (a nominal run's front member) completed with the
    /// base scenario's setting values.
    #[must_use]
    pub fn with_base_settings(&self, x: &[f64]) -> Vec<f64> {
        let mut v = x.to_vec();
        v.extend_from_slice(self.settings.base_values());
        v
    }

    /// The scenario a decision flies: the base stack with the decision's nodes (and entry
    /// altitude) from the encoding's genes, and each `[[robust.settings]]` value from the
    /// genes after them, written into the base's file model and resolved by the scenario's
    /// own checks.
    ///
    /// # Errors
    /// [`DesignError::Dimension`]; [`DesignError::Scenario`] for a setting value the
    /// scenario refuses.
    pub fn scenario_of(&self, x: &[f64]) -> Result<Scenario, DesignError> {
        let n = self.inner.bounds().dim();
        if x.len() != self.bounds.dim() {
            return Err(DesignError::Dimension {
                expected: self.bounds.dim(),
                got: x.len(),
            });
        }
        let (table, h) = self.inner.encoding().decode(&x[..n])?;
        let mut sc = self.stack.clone();
        sc.guidance.nodes = table;
        if let Some(h) = h {
            sc.entry.radius_m = sc.environment.planet.radius_m + h;
        }
        if !self.settings.is_empty()
            && let Some(layers) = sc.layers.as_mut()
        {
            layers.settings = self.settings.resolve(&x[n..])?;
        }
        Ok(sc)
    }

    /// The campaign a scenario of this problem flies (its set-up flies the nominal flight).
    ///
    /// # Errors
    /// [`CampaignError`] when the campaign cannot be set up (the nominal flight fails).
    pub fn campaign(&self, sc: &Scenario) -> Result<Campaign, CampaignError> {
        Campaign::new(
            sc,
            &self.file,
            self.config.dispersions.clone(),
            "robust",
            vec![self.mode],
        )
    }

    /// Fly the campaign of scenario `sc` whole (serially: the optimiser spreads candidates
    /// over its threads).
    ///
    /// # Errors
    /// [`CampaignError`] when the campaign cannot be set up (the nominal flight fails).
    pub fn campaign_of(&self, sc: &Scenario) -> Result<RobustOutcome, CampaignError> {
        let all = 0..self.config.dispersions.cases;
        let outcomes = self.fly_cases(sc, all)?;
        self.outcome_of(outcomes)
    }

    /// Fly cases `indices` of the campaign of scenario `sc`: one part of a candidate's
    /// evaluation, for evaluations split over flights as well as candidates (each case is a
    /// pure function of the scenario, the settings and its index, so the parts flown anywhere
    /// and in any order give the whole campaign's outcomes: [`RobustProblem::outcome_of`]).
    ///
    /// # Errors
    /// [`CampaignError`] when the campaign cannot be set up, or for an index outside it.
    pub fn fly_cases(
        &self,
        sc: &Scenario,
        indices: impl IntoIterator<Item = u32>,
    ) -> Result<Vec<JobOutcome>, CampaignError> {
        let campaign = self.campaign(sc)?;
        indices
            .into_iter()
            .map(|i| campaign.fly_job(self.mode, i))
            .collect()
    }

    /// The outcome of a candidate's campaign from its cases' outcomes, gathered in any order.
    ///
    /// # Errors
    /// [`CampaignError::Job`] for an outcome of another mode or outside the campaign, one
    /// given twice, or a case missing.
    pub fn outcome_of(
        &self,
        outcomes: impl IntoIterator<Item = JobOutcome>,
    ) -> Result<RobustOutcome, CampaignError> {
        let cases = self.config.dispersions.cases;
        let mut flown: Vec<CaseResult> = Vec::new();
        let mut failed = 0_u32;
        for (_, placed) in place_outcomes(&[self.mode], cases, outcomes)? {
            for o in placed {
                match o {
                    JobOutcome::Flown(c) => flown.push(c),
                    JobOutcome::Failed(_) => failed += 1,
                }
            }
        }
        let violating = flown
            .iter()
            .filter(|c| {
                !c.reached_interface || c.limit_ratios.iter().any(|r| r.is_nan() || *r > 1.0)
            })
            .count();
        Ok(RobustOutcome {
            stats: ModeStats::of(self.mode, &flown, failed as usize),
            violations: failed + u32::try_from(violating).unwrap_or(u32::MAX),
            cases,
        })
    }

    /// Objectives and constraint of a campaign's outcome (module docs).
    #[must_use]
    pub fn evaluation_of(&self, o: &RobustOutcome) -> Evaluation {
        let f: Vec<f64> = self
            .config
            .objectives
            .iter()
            .map(|s| s.of(&o.stats))
            .collect();
        if o.stats.cases == 0 || !f.iter().all(|v| v.is_finite()) {
            return Evaluation::failure(self.objectives(), self.constraints());
        }
        let fraction = f64::from(o.violations) / f64::from(o.cases.max(1));
        Evaluation::with_constraints(f, vec![fraction - self.config.max_violation_fraction])
    }
}

/// The decisions of a nominal run's front file `path` (`robust.nominal_front`), each of
/// `dimension` genes.
///
/// # Errors
/// [`DesignError::Robust`] naming `robust.nominal_front` and the file: unreadable, not a
/// population file (the line and column), or decisions of another length.
pub fn read_nominal_front(path: &Path, dimension: usize) -> Result<Vec<Vec<f64>>, DesignError> {
    let bad = |reason: String| DesignError::Robust {
        field: "robust.nominal_front".into(),
        value: path.display().to_string(),
        reason,
    };
    let text = std::fs::read_to_string(path).map_err(|e| bad(format!("cannot read it: {e}")))?;
    let (rows, [n, ..]) = read_population(&text).map_err(|e| bad(e.to_string()))?;
    if n != dimension {
        return Err(bad(format!(
            "its decisions have {n} genes (x1..x{n}); this problem's have {dimension}: the \
             front of a run with the same [problem] encoding"
        )));
    }
    rows.into_iter()
        .enumerate()
        .map(|(k, r)| {
            r.x.iter()
                .map(|v| v.map(|e| e.0).filter(|x| x.is_finite()))
                .collect::<Option<Vec<f64>>>()
                .ok_or_else(|| bad(format!("member {k} has a missing or non-finite gene")))
        })
        .collect()
}

/// The robust problem of a run file's text (`label` names it in errors): its `[problem]` and
/// `[robust]` tables (other keys, the algorithm's, are not read), a scenario-file base relative
/// to `base_dir`. The Python package builds its `RobustDesignProblem` with it.
///
/// # Errors
/// [`DesignError::Toml`] for text that is not TOML or tables of the wrong shape (naming the
/// field), [`DesignError`] as [`RobustProblem::new`].
pub fn problem_of_run_text(
    text: &str,
    label: &str,
    base_dir: &Path,
) -> Result<(super::DesignConfig, RobustConfig, RobustProblem), DesignError> {
    let bad = |message: String| DesignError::Toml {
        label: label.to_string(),
        message,
    };
    let mut table: toml::Table = toml::from_str(text).map_err(|e| bad(e.to_string()))?;
    let mut take = |key: &str| match table.remove(key) {
        Some(toml::Value::Table(t)) => Ok(t),
        Some(_) => Err(bad(format!("field `{key}` must be a table"))),
        None => Err(bad(format!(
            "field `{key}` is missing (a robust run file has [{key}])"
        ))),
    };
    let (problem, robust) = (take("problem")?, take("robust")?);
    let design: super::DesignConfig = toml::Value::Table(problem)
        .try_into()
        .map_err(|e: toml::de::Error| bad(format!("[problem]: {e}")))?;
    let config: RobustConfig = toml::Value::Table(robust)
        .try_into()
        .map_err(|e: toml::de::Error| bad(format!("[robust]: {e}")))?;
    let inner = design.problem(base_dir)?;
    let stack = design.stack_scenario(base_dir)?;
    let p =
        RobustProblem::new(inner, stack, config.clone(), &design.base).map_err(|e| match e {
            e @ DesignError::Robust { .. } => bad(e.to_string()),
            e => e,
        })?;
    Ok((design, config, p))
}

impl Problem for RobustProblem {
    type Decision = Vec<f64>;

    fn objectives(&self) -> usize {
        self.config.objectives.len()
    }

    fn constraints(&self) -> usize {
        1
    }

    fn evaluate(&self, x: &Vec<f64>) -> Result<Evaluation, EvalError> {
        self.bounds.check_dim(x)?;
        let sc = self
            .scenario_of(x)
            .map_err(|e| EvalError::Failed(Box::new(e)))?;
        let e = match self.campaign_of(&sc) {
            Ok(o) => self.evaluation_of(&o),
            Err(_) => Evaluation::failure(self.objectives(), self.constraints()),
        };
        if crate::sim::stop_requested() {
            return Err(EvalError::Interrupted);
        }
        Ok(e)
    }
}

impl RealProblem for RobustProblem {
    fn bounds(&self) -> &Bounds {
        &self.bounds
    }
}
