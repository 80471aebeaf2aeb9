//! The re-entry design run of host-sim (`host_sim::design::run`) from Python: the run
//! directory `host-sim optimize --config FILE --out DIR` writes (config.toml, a checkpoint
//! after every generation, records, populations, the front and its member scenarios), and
//! `--resume DIR [--generations G]`, with the batches evaluated by a Python callable when one
//! is given (the Dask layer's). The run, its checkpoints and its files are the library's: a
//! run started here resumes in the CLI and the other way round.

use std::path::{Path, PathBuf};

use host_sim::design::run::{ReentryRunConfig, RunFlags, check, parse_toml, resumed_config, run};
use host_sim::optim::{BatchEvaluator, EvalError, Evaluation};
use pyo3::prelude::*;

use crate::errors;

/// The evaluations a Python `map_batch(xs) -> [(f, g), ...]` returns for a batch; its
/// exception (or a malformed answer) fails every decision of the batch, with its message.
pub(crate) fn call_map_batch(f: &Py<PyAny>, xs: &[Vec<f64>]) -> Vec<Result<Evaluation, EvalError>> {
    let answer = Python::attach(|py| -> PyResult<Vec<(Vec<f64>, Vec<f64>)>> {
        f.call1(py, (xs.to_vec(),))?.extract(py)
    });
    match answer {
        Ok(pairs) => pairs
            .into_iter()
            .map(|(objectives, constraints)| {
                Ok(Evaluation {
                    objectives,
                    constraints,
                })
            })
            .collect(),
        Err(e) => (0..xs.len())
            .map(|_| Err(EvalError::Failed(format!("map_batch: {e}").into())))
            .collect(),
    }
}

/// Run the design run file `config` into the run directory `out` (a previous run there is
/// replaced), or with `resume` continue the run in `out` from its checkpoint (`generations`:
/// a new total; by default the run's own). `map_batch(xs)` evaluates each batch (a list of
/// decisions) into `(f, g)` pairs in order; default: host-sim's threads (`threads` of the
/// run file). Returns the last generation's record as JSON (`generation`, `evaluations`,
/// `feasible_fraction`, `hypervolume`, `front`, ...) with the run's `wall_time_s` and `line`,
/// the result line `host-sim optimize` prints. `label`: what the run's errors call the run
/// file (default its path; a front end that wrote it from flags names those). The GIL is
/// released while the run goes.
#[pyfunction]
#[pyo3(signature = (out, config=None, *, resume=false, generations=None, map_batch=None, label=None))]
fn run_design(
    py: Python<'_>,
    out: PathBuf,
    config: Option<PathBuf>,
    resume: bool,
    generations: Option<u64>,
    map_batch: Option<Py<PyAny>>,
    label: Option<String>,
) -> PyResult<String> {
    let bad = |e: &dyn std::fmt::Display| errors::DesignError::new_err(e.to_string());
    let (c, src, base_dir) = match (&config, resume) {
        (Some(path), false) => {
            if generations.is_some() {
                return Err(pyo3::exceptions::PyValueError::new_err(
                    "generations: only with resume=True (a new run takes the run file's)",
                ));
            }
            let c = parse_toml(path).map_err(|e| bad(&e))?;
            let base = path.parent().unwrap_or(Path::new(".")).to_path_buf();
            let src = label.unwrap_or_else(|| path.display().to_string());
            (c, src, base)
        }
        (None, true) => {
            let c = resumed_config(&out, generations).map_err(|e| bad(&e))?;
            (
                c,
                out.join("config.toml").display().to_string(),
                PathBuf::from("."),
            )
        }
        (Some(_), true) => {
            return Err(pyo3::exceptions::PyValueError::new_err(
                "config: a resumed run keeps the settings of its config.toml; drop config",
            ));
        }
        (None, false) => {
            return Err(pyo3::exceptions::PyValueError::new_err(
                "give config (a new run) or resume=True (continue the run in out)",
            ));
        }
    };
    let external = map_batch.map(|f| {
        move |xs: &[Vec<f64>]| -> Vec<Result<Evaluation, EvalError>> { call_map_batch(&f, xs) }
    });
    let done = py
        .detach(|| {
            run(
                &c,
                &src,
                &out,
                resume,
                &base_dir,
                &mut (),
                external
                    .as_ref()
                    .map(|f| f as &dyn BatchEvaluator<Vec<f64>>),
            )
        })
        .map_err(|e| bad(&e))?;
    let mut v = serde_json::to_value(&done.last).map_err(|e| bad(&e))?;
    if let Some(m) = v.as_object_mut() {
        m.insert("wall_time_s".into(), done.wall_time_s.into());
        m.insert("line".into(), done.line(&c, &out).into());
    }
    Ok(v.to_string())
}

/// The run file of the design preset `preset` (the thesis' settings: `host-sim optimize
/// --problem PRESET --print-config`) with the top-level settings of `overrides_json` (e.g.
/// `{"population": 6, "generations": 1}`) over them, checked as a run file is, as TOML text.
#[pyfunction]
fn run_config_toml(preset: &str, overrides_json: &str) -> PyResult<String> {
    let bad = |e: &dyn std::fmt::Display| errors::DesignError::new_err(e.to_string());
    let base = ReentryRunConfig::thesis(preset).map_err(|e| errors::design(&e))?;
    let mut v = serde_json::to_value(&base).map_err(|e| bad(&e))?;
    let over: serde_json::Map<String, serde_json::Value> =
        serde_json::from_str(overrides_json).map_err(|e| bad(&e))?;
    if let Some(m) = v.as_object_mut() {
        m.extend(over);
    }
    let c: ReentryRunConfig = serde_path_to_error::deserialize(v).map_err(|e| {
        bad(&format!(
            "run settings: field `{}`: {}",
            e.path(),
            e.inner()
        ))
    })?;
    check(&c, "run settings").map_err(|e| bad(&e))?;
    toml::to_string(&c).map_err(|e| bad(&e))
}

/// The run file of `host-sim optimize`'s flags on a preset problem, as `--print-config`
/// prints it (`flags_json`: host-sim `RunFlags`: `preset`, `options` (host-sim `RunOptions`,
/// as for `Optimizer.from_options`), `generations`, `seed`, `threads`, `reference`; missing
/// ones at the flags' defaults), checked as a run file is, as TOML text.
#[pyfunction]
fn run_config_of_flags(flags_json: &str) -> PyResult<String> {
    let bad = |e: &dyn std::fmt::Display| errors::DesignError::new_err(e.to_string());
    let mut de = serde_json::Deserializer::from_str(flags_json);
    let flags: RunFlags = serde_path_to_error::deserialize(&mut de)
        .map_err(|e| bad(&format!("run flags: field `{}`: {}", e.path(), e.inner())))?;
    let c = ReentryRunConfig::of_flags(&flags).map_err(|e| errors::design(&e))?;
    check(&c, "run flags").map_err(|e| bad(&e))?;
    c.to_toml("run flags").map_err(|e| bad(&e))
}

/// What the Dask layer needs of the run file `path` before the run: whether it is a robust
/// run (`"robust"`: a `[robust]` section, split over decisions and flights) or a nominal one
/// (`"nominal"`), and the run directory it writes when none is named
/// (`ReentryRunConfig::default_dir`, the CLI's default).
#[pyfunction]
fn run_file_info(path: PathBuf) -> PyResult<(&'static str, PathBuf)> {
    let c = parse_toml(&path).map_err(|e| errors::DesignError::new_err(e.to_string()))?;
    let kind = if c.robust.is_some() {
        "robust"
    } else {
        "nominal"
    };
    Ok((kind, c.default_dir()))
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(run_design, m)?)?;
    m.add_function(wrap_pyfunction!(run_file_info, m)?)?;
    m.add_function(wrap_pyfunction!(run_config_toml, m)?)?;
    m.add_function(wrap_pyfunction!(run_config_of_flags, m)?)?;
    Ok(())
}
