//! The dispersion campaign of host-sim (`host_sim::campaign`, `host-sim dispersions`) from
//! Python: the set-up (nominal flights, target, stored profile) built once per object, then
//! any subset of the `(mode, case index)` jobs flown on demand, each a pure function of the
//! set-up, the settings and the index (host-sim draws case `i` from a generator seeded by the
//! campaign seed and `i` only). So the cases can be split over Dask workers and gathered by
//! key into the same table, bit for bit, as the local run and as the CLI's.
//!
//! Case results cross into Python as JSON text (host-sim's `CaseResult`, serialised by serde
//! with shortest round-trip floats, so no bit is lost either way). A case whose flight fails
//! is no error: its job gives host-sim's `CaseFailure` (mode, index, draw, `error`) instead,
//! as `host-sim dispersions` records it, and the campaign goes on.

use std::path::PathBuf;

use host_sim::campaign::output::write_campaign;
use host_sim::campaign::{Campaign, DispersionSettings, JobOutcome, Mode, parse_settings};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use serde::{Deserialize, Serialize};

use crate::errors;
use crate::flight::{Source, resolve, source};

/// What rebuilds a campaign (pickling, Dask workers): the scenario's source and the settings.
#[derive(Clone, Debug, Serialize, Deserialize)]
struct Spec {
    builtin: Option<String>,
    path: Option<PathBuf>,
    toml: Option<String>,
    label: Option<String>,
    base_dir: Option<PathBuf>,
    settings: DispersionSettings,
    modes: Vec<String>,
}

/// A dispersion campaign: scenario, settings and modes, with its set-up built.
#[pyclass(
    name = "DispersionCampaign",
    module = "reentry._native",
    frozen,
    subclass
)]
pub struct PyCampaign {
    spec: Spec,
    campaign: Campaign,
}

fn mode_of(name: &str) -> PyResult<Mode> {
    Mode::by_name(name).map_err(|e| errors::campaign(&e))
}

fn json_error(e: &serde_json::Error) -> PyErr {
    errors::CampaignError::new_err(format!("case result: {e}"))
}

fn to_json<T: Serialize>(v: &T) -> PyResult<String> {
    serde_json::to_string(v).map_err(|e| json_error(&e))
}

impl PyCampaign {
    fn build(spec: Spec) -> PyResult<Self> {
        let src = source(
            spec.builtin.clone(),
            spec.path.clone(),
            spec.toml.clone(),
            spec.label.clone(),
            spec.base_dir.clone(),
        )?;
        let (sc, resolved) = resolve(&src).map_err(|e| errors::scenario(&e))?;
        // The CLI's name for a built-in scenario in messages.
        let file = match &src {
            Source::Builtin(name) => format!("builtin:{name}"),
            _ => resolved,
        };
        let modes = spec
            .modes
            .iter()
            .map(|m| mode_of(m))
            .collect::<PyResult<Vec<_>>>()?;
        // As the CLI: the scenario's guidance layers, the modes its stack can fly.
        let campaign = Campaign::new(&sc, &file, spec.settings.clone(), "command line", modes)
            .map_err(|e| errors::campaign(&e))?;
        Ok(Self { spec, campaign })
    }
}

#[pymethods]
impl PyCampaign {
    /// A campaign of a scenario (exactly one of `builtin`, `path`, `toml` (with `label`,
    /// `base_dir`), none: the HORUS-2B reference mission) with the `[dispersions]` settings of
    /// `settings_toml` (TOML text; `settings_label` names it in errors; none: host-sim's
    /// defaults), overridden by `cases`, `seed`, `interface_speed_m_s` as the CLI's flags do,
    /// flown in `modes` (names; none: all of them). `spec_json` (from [`PyCampaign::spec_json`])
    /// instead rebuilds a campaign and excludes the other arguments. Builds the set-up
    /// (nominal flights), GIL released.
    #[new]
    #[pyo3(signature = (*, builtin=None, path=None, toml=None, label=None, base_dir=None,
        settings_toml=None, settings_label=None, cases=None, seed=None,
        interface_speed_m_s=None, modes=None, spec_json=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        builtin: Option<String>,
        path: Option<PathBuf>,
        toml: Option<String>,
        label: Option<String>,
        base_dir: Option<PathBuf>,
        settings_toml: Option<String>,
        settings_label: Option<String>,
        cases: Option<u32>,
        seed: Option<u64>,
        interface_speed_m_s: Option<f64>,
        modes: Option<Vec<String>>,
        spec_json: Option<&str>,
    ) -> PyResult<Self> {
        if let Some(text) = spec_json {
            let given = builtin.is_some()
                || path.is_some()
                || toml.is_some()
                || settings_toml.is_some()
                || cases.is_some()
                || seed.is_some()
                || interface_speed_m_s.is_some()
                || modes.is_some();
            if given {
                return Err(PyValueError::new_err(
                    "spec_json rebuilds a campaign: give no other argument",
                ));
            }
            let spec: Spec = serde_json::from_str(text)
                .map_err(|e| PyValueError::new_err(format!("campaign spec: {e}")))?;
            return py.detach(|| Self::build(spec));
        }
        let mut settings = match &settings_toml {
            Some(text) => parse_settings(
                text,
                settings_label
                    .as_deref()
                    .unwrap_or("(settings TOML string)"),
            )
            .map_err(|e| errors::campaign(&e))?,
            None => DispersionSettings::default(),
        };
        if let Some(n) = cases {
            settings.cases = n;
        }
        if let Some(v) = interface_speed_m_s {
            settings.interface_speed_m_s = Some(v);
        }
        if let Some(s) = seed {
            settings.seed = s;
        }
        let spec = Spec {
            builtin,
            path,
            toml,
            label,
            base_dir,
            settings,
            modes: modes.unwrap_or_default(),
        };
        py.detach(|| Self::build(spec))
    }

    /// What rebuilds this campaign, as JSON text (scenario source, settings, modes).
    fn spec_json(&self) -> PyResult<String> {
        to_json(&self.spec)
    }

    /// The `[dispersions]` settings (after the overrides) as JSON text.
    fn settings_json(&self) -> PyResult<String> {
        to_json(&self.spec.settings)
    }

    /// Number of cases per mode.
    #[getter]
    fn cases(&self) -> u32 {
        self.spec.settings.cases
    }

    /// The modes flown, in report order.
    #[getter]
    fn modes(&self) -> Vec<&'static str> {
        self.campaign.modes().iter().map(|m| m.name()).collect()
    }

    /// The target: `(latitude_rad, longitude_rad, downrange_m)` along the entry great circle.
    fn target(&self) -> (f64, f64, f64) {
        let s = self.campaign.setup();
        (
            s.target().latitude_rad,
            s.target().longitude_rad,
            s.target_downrange_rad * s.planet_radius_m,
        )
    }

    /// The terminal interface speed \[m/s\].
    #[getter]
    fn interface_speed_m_s(&self) -> f64 {
        self.campaign.setup().interface_speed_m_s
    }

    /// Fly the jobs `[(mode, index), ...]` (serially, in order, GIL released); one JSON text
    /// of host-sim's `CaseResult` per job (`CaseFailure`, with an `error` field, for a case
    /// whose flight failed).
    fn fly(&self, py: Python<'_>, jobs: Vec<(String, u32)>) -> PyResult<Vec<String>> {
        let jobs = jobs
            .iter()
            .map(|(m, i)| mode_of(m).map(|m| (m, *i)))
            .collect::<PyResult<Vec<_>>>()?;
        let results = py
            .detach(|| {
                jobs.iter()
                    .map(|&(m, i)| self.campaign.fly_job(m, i))
                    .collect::<Result<Vec<_>, _>>()
            })
            .map_err(|e| errors::campaign(&e))?;
        results.iter().map(to_json).collect()
    }

    /// The nominal (undispersed) flight of each mode, JSON text of `CaseResult`s.
    fn nominal(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        let r = py
            .detach(|| self.campaign.nominal())
            .map_err(|e| errors::campaign(&e))?;
        r.iter().map(to_json).collect()
    }

    /// The whole campaign in this process: host-sim's own `run_campaign` (rayon, `threads`
    /// threads, default all cores; the result does not depend on it), nothing written. Every
    /// case of every mode, in mode order then index, as JSON texts of `CaseResult`s
    /// (`CaseFailure`s for failed flights).
    #[pyo3(signature = (threads=None))]
    fn run_local(&self, py: Python<'_>, threads: Option<usize>) -> PyResult<Vec<String>> {
        if threads.is_some_and(|t| t == 0 || t > host_sim::optim::evaluate::MAX_THREADS) {
            return Err(PyValueError::new_err(format!(
                "threads = {}: use 1 to {}",
                threads.unwrap_or(0),
                host_sim::optim::evaluate::MAX_THREADS
            )));
        }
        let all = py
            .detach(|| self.campaign.run_local(threads))
            .map_err(|e| errors::campaign(&e))?;
        all.iter().map(to_json).collect()
    }

    /// Write the campaign's files into `dir` exactly as `host-sim dispersions --out dir`
    /// does (summary.json with the statistics and the nominal flights, cases-<mode>.csv, the
    /// SVG plots; atomic writes) from gathered case results (JSON texts, any order). Every
    /// `(mode, index)` of the campaign must be present exactly once. Returns the files
    /// written.
    fn write(&self, py: Python<'_>, dir: PathBuf, results: Vec<String>) -> PyResult<Vec<PathBuf>> {
        let outcomes = results
            .iter()
            .map(|text| serde_json::from_str::<JobOutcome>(text).map_err(|e| json_error(&e)))
            .collect::<PyResult<Vec<_>>>()?;
        py.detach(|| {
            let out = self.campaign.assemble(outcomes)?;
            std::fs::create_dir_all(&dir).map_err(|source| host_sim::report::ReportError::Io {
                path: dir.clone(),
                source,
            })?;
            write_campaign(&dir, self.campaign.setup(), self.campaign.settings(), &out)
        })
        .map_err(|e| errors::campaign(&e))
    }
}

/// The guidance modes of a campaign, in report order.
#[pyfunction]
fn campaign_modes() -> Vec<&'static str> {
    Mode::ALL.iter().map(|m| m.name()).collect()
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyCampaign>()?;
    m.add_function(wrap_pyfunction!(campaign_modes, m)?)?;
    Ok(())
}
