//! The robust design problem of host-sim (`host_sim::design::RobustProblem`, issue 25) as a
//! Python problem with pygmo's user-defined-problem methods, and its evaluation split over
//! flights ([`PyRobustDesignProblem::fly_cases`], [`PyRobustDesignProblem::evaluate_parts`])
//! for the Dask layer. Every number is the library's; the GIL is released while flights run.

use std::path::{Path, PathBuf};

use host_sim::campaign::JobOutcome;
use host_sim::design::robust::problem_of_run_text;
use host_sim::design::{DesignConfig, RobustConfig, RobustProblem};
use host_sim::optim::{Evaluation, Problem};
use host_sim::scenario::scenario_to_toml;
use pyo3::prelude::*;

use crate::design::{bounds_pair, evaluate_real, evaluate_real_batch};
use crate::errors;

fn pair(e: Evaluation) -> (Vec<f64>, Vec<f64>) {
    (e.objectives, e.constraints)
}

/// A robust re-entry design problem (host-sim `design::RobustProblem`).
#[pyclass(
    name = "RobustDesignProblem",
    module = "reentry._native",
    frozen,
    subclass
)]
pub struct PyRobustDesignProblem {
    inner: RobustProblem,
    design: DesignConfig,
    robust: RobustConfig,
    base_dir: PathBuf,
}

#[pymethods]
impl PyRobustDesignProblem {
    /// The problem of a run file's `[problem]` and `[robust]` tables, from TOML text or a
    /// file; `base_dir` resolves the scenario-file base (default: the file's folder, or `.`).
    #[new]
    #[pyo3(signature = (*, toml=None, path=None, base_dir=None))]
    fn new(toml: Option<&str>, path: Option<PathBuf>, base_dir: Option<PathBuf>) -> PyResult<Self> {
        let (text, label, dir) = match (toml, path) {
            (Some(t), None) => (
                t.to_string(),
                "(TOML string)".to_string(),
                base_dir.unwrap_or_else(|| PathBuf::from(".")),
            ),
            (None, Some(p)) => {
                let text = std::fs::read_to_string(&p).map_err(|e| {
                    errors::DesignError::new_err(format!("{}: cannot read: {e}", p.display()))
                })?;
                let dir = base_dir
                    .or_else(|| p.parent().map(Path::to_path_buf))
                    .unwrap_or_else(|| PathBuf::from("."));
                (text, p.display().to_string(), dir)
            }
            _ => {
                return Err(pyo3::exceptions::PyValueError::new_err(
                    "give one of toml and path",
                ));
            }
        };
        let (design, robust, inner) =
            problem_of_run_text(&text, &label, &dir).map_err(|e| errors::design(&e))?;
        Ok(Self {
            inner,
            design,
            robust,
            base_dir: dir,
        })
    }

    /// The settings as TOML text (`[problem]` and `[robust]` tables).
    fn config_toml(&self) -> PyResult<String> {
        #[derive(serde::Serialize)]
        struct Run<'a> {
            problem: &'a DesignConfig,
            robust: &'a RobustConfig,
        }
        toml::to_string(&Run {
            problem: &self.design,
            robust: &self.robust,
        })
        .map_err(|e| errors::DesignError::new_err(format!("problem settings: {e}")))
    }

    /// The folder the scenario-file base is relative to.
    #[getter]
    fn base_dir(&self) -> PathBuf {
        self.base_dir.clone()
    }

    /// Flights per candidate (`robust.dispersions.cases`).
    #[getter]
    fn cases(&self) -> u32 {
        self.robust.dispersions.cases
    }

    /// The guidance mode every candidate flies.
    #[getter]
    fn mode(&self) -> &'static str {
        self.inner.mode().name()
    }

    /// `(lower, upper)` bounds of the decision (per free node: normalised energy, angle of
    /// attack \[deg\] if free, bank angle \[deg\]; then the entry altitude \[km\] if a variable).
    fn get_bounds(&self) -> (Vec<f64>, Vec<f64>) {
        bounds_pair(&self.inner)
    }

    /// Number of objectives (the `robust.objectives` statistics).
    fn get_nobj(&self) -> usize {
        self.inner.objectives()
    }

    /// Number of inequality constraints (1: the violation fraction over its maximum).
    fn get_nic(&self) -> usize {
        self.inner.constraints()
    }

    /// Number of equality constraints (always 0).
    fn get_nec(&self) -> usize {
        0
    }

    /// `(objectives, constraints)` of one decision: its whole campaign, GIL released; NaN
    /// values when it failed (module docs of host-sim's `design::robust`).
    fn evaluate(&self, py: Python<'_>, x: Vec<f64>) -> PyResult<(Vec<f64>, Vec<f64>)> {
        evaluate_real(py, &self.inner, x)
    }

    /// `(objectives, constraints)` of each decision, in order, GIL released.
    fn evaluate_batch(
        &self,
        py: Python<'_>,
        xs: Vec<Vec<f64>>,
    ) -> PyResult<Vec<(Vec<f64>, Vec<f64>)>> {
        evaluate_real_batch(py, &self.inner, xs)
    }

    /// One part of a decision's evaluation: cases `indices` of its campaign flown here (the
    /// campaign set up again), as a JSON text of their outcomes; `None` when the campaign
    /// cannot be set up (the decision is then a failed evaluation). GIL released.
    fn fly_cases(
        &self,
        py: Python<'_>,
        x: Vec<f64>,
        indices: Vec<u32>,
    ) -> PyResult<Option<String>> {
        let sc = self.inner.scenario_of(&x).map_err(|e| errors::design(&e))?;
        let parts = py.detach(|| self.inner.fly_cases(&sc, indices));
        match parts {
            Ok(outcomes) => serde_json::to_string(&outcomes)
                .map(Some)
                .map_err(|e| errors::CampaignError::new_err(e.to_string())),
            Err(host_sim::campaign::CampaignError::Job {
                mode,
                index,
                reason,
            }) => Err(errors::CampaignError::new_err(format!(
                "{mode} case {index}: {reason}"
            ))),
            Err(_) => Ok(None),
        }
    }

    /// `(objectives, constraints)` of a decision from the parts [`fly_cases`] gave for it,
    /// in any order (every case exactly once): the whole evaluation, bit for bit. A `None`
    /// part (a campaign that could not be set up) makes it a failed evaluation (NaN).
    fn evaluate_parts(&self, parts: Vec<Option<String>>) -> PyResult<(Vec<f64>, Vec<f64>)> {
        let mut outcomes: Vec<JobOutcome> = Vec::new();
        for p in parts {
            let Some(text) = p else {
                return Ok(pair(Evaluation::failure(
                    self.inner.objectives(),
                    self.inner.constraints(),
                )));
            };
            let part: Vec<JobOutcome> = serde_json::from_str(&text)
                .map_err(|e| errors::CampaignError::new_err(format!("case outcomes: {e}")))?;
            outcomes.extend(part);
        }
        let o = self
            .inner
            .outcome_of(outcomes)
            .map_err(|e| errors::campaign(&e))?;
        Ok(pair(self.inner.evaluation_of(&o)))
    }

    /// The scenario TOML a decision flies (the base stack with its nodes): fly it with
    /// `reentry.fly`, or as a campaign with `reentry.DispersionCampaign`.
    fn scenario_toml(&self, x: Vec<f64>) -> PyResult<String> {
        let sc = self.inner.scenario_of(&x).map_err(|e| errors::design(&e))?;
        Ok(scenario_to_toml(&sc))
    }
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyRobustDesignProblem>()?;
    Ok(())
}
