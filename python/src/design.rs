//! The re-entry mission-design problems of host-sim (`host_sim::design`, issue 11) as Python
//! problems with pygmo's user-defined-problem methods.
//!
//! * [`PyDesignProblem`]: the fixed-length [`ReentryProblem`] (a decision is the free nodes'
//!   genes and, when it is a variable, the entry altitude in km);
//! * [`PyVariableDesignProblem`]: the variable-length [`VariableReentry`] (SCEA's problem) over
//!   chromosomes of 2 to 6 free nodes, and, for pygmo and the ask/tell algorithms, the same
//!   problem over a fixed-size "padded" vector: the genes of the largest number of free nodes,
//!   the entry altitude if it is a variable, and the number of free nodes used as the last
//!   (integer) variable. Only the first `count` nodes of the padded vector reach the library's
//!   chromosome; the rest are ignored.
//!
//! Every evaluation is the library's: a closed-loop flight through `scenario::fly`, failures
//! (rejected flights, time limit, ground) coming back as NaN objectives and constraints
//! ([`Evaluation::failure`]). The GIL is released while flights run.

use std::path::{Path, PathBuf};

use host_sim::design::{DesignConfig, ReentryProblem, VariableReentry};
use host_sim::optim::chromosome::Chromosome;
use host_sim::optim::{Evaluation, Problem, RealProblem};
use host_sim::scenario::scenario_to_toml;
use pyo3::prelude::*;

use crate::errors;

/// The design problem's settings from a preset name, TOML text (a `[problem]`-section body, or
/// a whole run configuration with a `[problem]` table) or a TOML file; and the folder that a
/// scenario-file base is relative to.
fn design_config(
    preset: Option<&str>,
    toml_text: Option<&str>,
    path: Option<&Path>,
    base_dir: Option<PathBuf>,
) -> PyResult<(DesignConfig, PathBuf)> {
    let from_text = |text: &str, label: &str| -> PyResult<DesignConfig> {
        let bad = |e: &dyn std::fmt::Display| errors::DesignError::new_err(format!("{label}: {e}"));
        let mut v: toml::Table = toml::from_str(text).map_err(|e| bad(&e))?;
        let table = match v.remove("problem") {
            Some(toml::Value::Table(t)) => t,
            Some(_) => return Err(bad(&"field `problem` must be a table")),
            None => v,
        };
        toml::Value::Table(table).try_into().map_err(|e| bad(&e))
    };
    match (preset, toml_text, path) {
        (Some(name), None, None) => Ok((
            DesignConfig::preset(name).map_err(|e| errors::design(&e))?,
            base_dir.unwrap_or_else(|| PathBuf::from(".")),
        )),
        (None, Some(text), None) => Ok((
            from_text(text, "(TOML string)")?,
            base_dir.unwrap_or_else(|| PathBuf::from(".")),
        )),
        (None, None, Some(p)) => {
            let text = std::fs::read_to_string(p).map_err(|e| {
                errors::DesignError::new_err(format!("{}: cannot read: {e}", p.display()))
            })?;
            let dir = base_dir
                .or_else(|| p.parent().map(Path::to_path_buf))
                .unwrap_or_else(|| PathBuf::from("."));
            Ok((from_text(&text, &p.display().to_string())?, dir))
        }
        (None, None, None) => Ok((
            DesignConfig::preset("horus-2b").map_err(|e| errors::design(&e))?,
            base_dir.unwrap_or_else(|| PathBuf::from(".")),
        )),
        _ => Err(pyo3::exceptions::PyValueError::new_err(
            "give at most one of preset, toml and path",
        )),
    }
}

/// `(objectives, constraints)` of an evaluation.
fn pair(e: Evaluation) -> (Vec<f64>, Vec<f64>) {
    (e.objectives, e.constraints)
}

/// `(lower, upper)` of a problem's bounds.
pub(crate) fn bounds_pair<P: RealProblem>(p: &P) -> (Vec<f64>, Vec<f64>) {
    let b = p.bounds();
    (b.lower().to_vec(), b.upper().to_vec())
}

/// `(objectives, constraints)` of one decision of a real problem, GIL released.
pub(crate) fn evaluate_real<P: RealProblem>(
    py: Python<'_>,
    p: &P,
    x: Vec<f64>,
) -> PyResult<(Vec<f64>, Vec<f64>)> {
    py.detach(|| p.evaluate(&x))
        .map(pair)
        .map_err(|e| errors::OptimError::new_err(e.to_string()))
}

/// `(objectives, constraints)` of each decision of a real problem, in order, GIL released.
pub(crate) fn evaluate_real_batch<P: RealProblem>(
    py: Python<'_>,
    p: &P,
    xs: Vec<Vec<f64>>,
) -> PyResult<Vec<(Vec<f64>, Vec<f64>)>> {
    py.detach(|| {
        xs.iter()
            .enumerate()
            .map(|(index, x)| {
                p.evaluate(x)
                    .map(pair)
                    .map_err(|e| format!("decision {index}: {e}"))
            })
            .collect::<Result<Vec<_>, _>>()
    })
    .map_err(errors::OptimError::new_err)
}

/// The settings as TOML text (for pickling and inspection).
fn config_toml(c: &DesignConfig) -> PyResult<String> {
    toml::to_string(c).map_err(|e| errors::DesignError::new_err(format!("problem settings: {e}")))
}

/// A fixed-length re-entry design problem (host-sim `design::ReentryProblem`).
#[pyclass(name = "DesignProblem", module = "reentry._native", frozen, subclass)]
pub struct PyDesignProblem {
    inner: ReentryProblem,
    config: DesignConfig,
    base_dir: PathBuf,
}

#[pymethods]
impl PyDesignProblem {
    /// The problem of a preset (`horus-2b`, `srm`, `srm-altitude`; default `horus-2b`), of TOML
    /// text (`[problem]` fields, or a run configuration with a `[problem]` table) or of a TOML
    /// file; `base_dir` resolves a scenario-file base (default: the file's folder, or `.`).
    #[new]
    #[pyo3(signature = (preset=None, *, toml=None, path=None, base_dir=None))]
    fn new(
        preset: Option<&str>,
        toml: Option<&str>,
        path: Option<PathBuf>,
        base_dir: Option<PathBuf>,
    ) -> PyResult<Self> {
        let (config, base_dir) = design_config(preset, toml, path.as_deref(), base_dir)?;
        let inner = config.problem(&base_dir).map_err(|e| errors::design(&e))?;
        Ok(Self {
            inner,
            config,
            base_dir,
        })
    }

    /// The settings as TOML text (`[problem]` fields: base, encoding, limits, objectives).
    fn config_toml(&self) -> PyResult<String> {
        config_toml(&self.config)
    }

    /// The folder a scenario-file base is relative to.
    #[getter]
    fn base_dir(&self) -> PathBuf {
        self.base_dir.clone()
    }

    /// `(lower, upper)` bounds of the decision (per free node: normalised energy, angle of
    /// attack \[deg\] if free, bank angle \[deg\]; then the entry altitude \[km\] if a variable).
    fn get_bounds(&self) -> (Vec<f64>, Vec<f64>) {
        bounds_pair(&self.inner)
    }

    /// Number of objectives (range `-theta/pi`, heat load `Q / Q_scale`, optionally skips).
    fn get_nobj(&self) -> usize {
        self.inner.objectives()
    }

    /// Number of inequality constraints (`<= 0` feasible: heat flux, g-load, g-load rate,
    /// optionally skips).
    fn get_nic(&self) -> usize {
        self.inner.constraints()
    }

    /// Number of equality constraints (always 0).
    fn get_nec(&self) -> usize {
        0
    }

    /// `(objectives, constraints)` of one decision (one closed-loop flight, GIL released);
    /// a failed flight gives NaN values.
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

    /// The node table `[[E-hat, alpha_rad, sigma_rad], ...]` (flight order, fixed end nodes
    /// included) and the entry altitude \[m\] (None when not a variable) of a decision.
    fn decode(&self, x: Vec<f64>) -> PyResult<(Vec<[f64; 3]>, Option<f64>)> {
        self.inner
            .encoding()
            .decode(&x)
            .map_err(|e| errors::design(&e))
    }

    /// The scenario TOML that a decision flies (the base with its nodes and entry altitude
    /// replaced): `reentry.fly(problem.scenario_toml(x))` gives its trajectory. The text
    /// stores degrees, so the flight matches the evaluation to round-off, not bit for bit.
    fn scenario_toml(&self, x: Vec<f64>) -> PyResult<String> {
        let sc = self.inner.scenario_of(&x).map_err(|e| errors::design(&e))?;
        Ok(scenario_to_toml(&sc))
    }
}

/// A variable-length re-entry design problem (host-sim `design::VariableReentry`, SCEA's).
#[pyclass(
    name = "VariableDesignProblem",
    module = "reentry._native",
    frozen,
    subclass
)]
pub struct PyVariableDesignProblem {
    inner: VariableReentry,
    config: DesignConfig,
    base_dir: PathBuf,
}

impl PyVariableDesignProblem {
    /// The chromosome of a padded decision (the library's padded encoding).
    fn chromosome_of_padded(&self, x: &[f64]) -> Result<Chromosome, String> {
        self.inner
            .chromosome_of_padded(x)
            .map_err(|e| e.to_string())
    }

    fn evaluate_chromosome_inner(&self, c: &Chromosome) -> Result<Evaluation, String> {
        self.inner.evaluate(c).map_err(|e| e.to_string())
    }
}

#[pymethods]
impl PyVariableDesignProblem {
    /// The variable-length problem of a preset, TOML text or file (as `DesignProblem`) with
    /// `nodes = (min, max)` table nodes, fixed ends included (default: 4 to the encoding's
    /// node count, as `host-sim optimize scea`).
    #[new]
    #[pyo3(signature = (preset=None, *, toml=None, path=None, base_dir=None, nodes=None))]
    fn new(
        preset: Option<&str>,
        toml: Option<&str>,
        path: Option<PathBuf>,
        base_dir: Option<PathBuf>,
        nodes: Option<(usize, usize)>,
    ) -> PyResult<Self> {
        let (config, base_dir) = design_config(preset, toml, path.as_deref(), base_dir)?;
        let fixed = config.problem(&base_dir).map_err(|e| errors::design(&e))?;
        let n = config.encoding.nodes;
        let nodes = nodes.map_or([4.min(n), n], |(a, b)| [a, b]);
        let inner = VariableReentry::new(fixed, nodes).map_err(|e| errors::design(&e))?;
        Ok(Self {
            inner,
            config,
            base_dir,
        })
    }

    /// The settings as TOML text (`[problem]` fields).
    fn config_toml(&self) -> PyResult<String> {
        config_toml(&self.config)
    }

    /// The folder a scenario-file base is relative to.
    #[getter]
    fn base_dir(&self) -> PathBuf {
        self.base_dir.clone()
    }

    /// `(min, max)` table nodes, fixed end nodes included.
    #[getter]
    fn nodes(&self) -> (usize, usize) {
        let [lo, hi] = self.inner.nodes();
        (lo, hi)
    }

    /// Genes per free node: `[E-hat, alpha_deg, sigma_deg]` (3) or `[E-hat, sigma_deg]` (2).
    #[getter]
    fn node_genes(&self) -> usize {
        self.inner.inner().encoding().genes_per_node()
    }

    /// Bounds of the padded decision: `max - 2` free nodes' genes, the entry altitude \[km\]
    /// if a variable, then the free-node count in `[min - 2, max - 2]`.
    fn get_bounds(&self) -> (Vec<f64>, Vec<f64>) {
        self.inner.padded_bounds()
    }

    /// Number of objectives.
    fn get_nobj(&self) -> usize {
        self.inner.objectives()
    }

    /// Number of inequality constraints (`<= 0` feasible).
    fn get_nic(&self) -> usize {
        self.inner.constraints()
    }

    /// Number of equality constraints (always 0).
    fn get_nec(&self) -> usize {
        0
    }

    /// Number of integer variables (pygmo): 1, the free-node count (the last variable).
    fn get_nix(&self) -> usize {
        1
    }

    /// The chromosome of a padded decision: `(free nodes, entry altitude [km] or None)`.
    fn chromosome(&self, x: Vec<f64>) -> PyResult<(Vec<Vec<f64>>, Option<f64>)> {
        let c = self
            .chromosome_of_padded(&x)
            .map_err(errors::OptimError::new_err)?;
        Ok((
            c.legs.into_iter().flatten().collect(),
            c.fixed.first().copied(),
        ))
    }

    /// `(objectives, constraints)` of a padded decision (GIL released).
    fn evaluate(&self, py: Python<'_>, x: Vec<f64>) -> PyResult<(Vec<f64>, Vec<f64>)> {
        py.detach(|| {
            self.chromosome_of_padded(&x)
                .and_then(|c| self.evaluate_chromosome_inner(&c))
        })
        .map(pair)
        .map_err(errors::OptimError::new_err)
    }

    /// `(objectives, constraints)` of each padded decision, in order, GIL released.
    fn evaluate_batch(
        &self,
        py: Python<'_>,
        xs: Vec<Vec<f64>>,
    ) -> PyResult<Vec<(Vec<f64>, Vec<f64>)>> {
        py.detach(|| {
            xs.iter()
                .enumerate()
                .map(|(index, x)| {
                    self.chromosome_of_padded(x)
                        .and_then(|c| self.evaluate_chromosome_inner(&c))
                        .map(pair)
                        .map_err(|e| format!("decision {index}: {e}"))
                })
                .collect::<Result<Vec<_>, _>>()
        })
        .map_err(errors::OptimError::new_err)
    }

    /// `(objectives, constraints)` of a chromosome: its free nodes (each `node_genes` genes,
    /// any order) and the entry altitude \[km\] when it is a variable (GIL released).
    #[pyo3(signature = (nodes, altitude_km=None))]
    fn evaluate_chromosome(
        &self,
        py: Python<'_>,
        nodes: Vec<Vec<f64>>,
        altitude_km: Option<f64>,
    ) -> PyResult<(Vec<f64>, Vec<f64>)> {
        let c = Chromosome {
            fixed: altitude_km.into_iter().collect(),
            legs: vec![nodes],
        };
        py.detach(|| self.evaluate_chromosome_inner(&c))
            .map(pair)
            .map_err(errors::OptimError::new_err)
    }

    /// The node table `[[E-hat, alpha_rad, sigma_rad], ...]` and entry altitude \[m\] of a
    /// chromosome (free nodes, altitude \[km\]).
    #[pyo3(signature = (nodes, altitude_km=None))]
    fn table(
        &self,
        nodes: Vec<Vec<f64>>,
        altitude_km: Option<f64>,
    ) -> PyResult<(Vec<[f64; 3]>, Option<f64>)> {
        let c = Chromosome {
            fixed: altitude_km.into_iter().collect(),
            legs: vec![nodes],
        };
        self.inner
            .table_of(&c)
            .map_err(|e| errors::OptimError::new_err(e.to_string()))
    }
}

/// Preset names of the design problems.
#[pyfunction]
fn design_presets() -> Vec<&'static str> {
    host_sim::design::PRESETS.to_vec()
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyDesignProblem>()?;
    m.add_class::<PyVariableDesignProblem>()?;
    m.add_function(wrap_pyfunction!(design_presets, m)?)?;
    Ok(())
}
