//! Flights, atmosphere queries and the vehicle list.
//!
//! A flight returns its trajectory column by column (SI units and radians, unit in each
//! column name), the event of each sample, and the summary document host-sim writes to
//! summary.json (same fields, same units, serialised by the same code), as JSON text that the
//! Python layer turns into a dict.

use std::path::{Path, PathBuf};

use host_sim::env::{Atmosphere, ExponentialAtmosphere, Us76};
use host_sim::scenario::{Scenario, fly, parse_scenario, read_scenario, scenario_to_toml};
use host_sim::sim::{Sample, SampleKind};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyByteArray, PyDict, PyList, PyString};

use crate::errors;

/// Trajectory column names, in order (SI units, radians).
const COLUMNS: [&str; 21] = [
    "time_s",
    "altitude_m",
    "longitude_rad",
    "latitude_rad",
    "speed_m_s",
    "flight_path_angle_rad",
    "heading_rad",
    "mach",
    "density_kg_m3",
    "dynamic_pressure_pa",
    "alpha_rad",
    "sigma_rad",
    "cl",
    "cd",
    "lift_n",
    "drag_n",
    "heat_flux_w_m2",
    "heat_load_j_m2",
    "g_load",
    "normalized_energy",
    "flown_range_rad",
];

fn row(p: &Sample) -> [f64; 21] {
    let c = &p.conditions;
    let s = &p.state;
    [
        p.time_s,
        c.altitude_m,
        s.longitude_rad,
        s.latitude_rad,
        s.speed_m_s,
        s.flight_path_angle_rad,
        s.heading_rad,
        c.mach,
        c.density_kg_m3,
        c.dynamic_pressure_pa,
        p.attitude.alpha_rad,
        p.attitude.sigma_rad,
        c.cl,
        c.cd,
        c.lift_n,
        c.drag_n,
        c.heat_flux_w_m2,
        p.heat_load_j_m2,
        c.g_load,
        p.normalized_energy,
        p.flown_range_rad,
    ]
}

/// The `events` strings, indexed by [`event_index`].
const EVENTS: [&str; 5] = ["start", "", "exit", "entry", "end"];

fn event_index(k: SampleKind) -> usize {
    match k {
        SampleKind::Start => 0,
        SampleKind::Output => 1,
        SampleKind::Exit => 2,
        SampleKind::Entry => 3,
        SampleKind::End => 4,
    }
}

/// A flown scenario: the trajectory as one column-major block of native-endian `f64` bytes
/// (`COLUMNS.len()` columns of `rows` values each), each sample's kind, and the summary.
struct FlownColumns {
    bytes: Vec<u8>,
    rows: usize,
    kinds: Vec<SampleKind>,
    summary_json: String,
}

/// Where a scenario comes from.
pub(crate) enum Source {
    Builtin(String),
    File(PathBuf),
    Toml {
        text: String,
        label: String,
        base_dir: PathBuf,
    },
}

pub(crate) fn resolve(
    src: &Source,
) -> Result<(Scenario, String), host_sim::scenario::ScenarioError> {
    match src {
        Source::Builtin(name) => Ok((
            Scenario::try_builtin(name)?,
            format!("(built-in scenario {name})"),
        )),
        Source::File(p) => Ok((read_scenario(p)?, p.display().to_string())),
        Source::Toml {
            text,
            label,
            base_dir,
        } => Ok((parse_scenario(text, label, base_dir)?, label.clone())),
    }
}

/// Fly one scenario (no Python involved: runs with the GIL released).
fn fly_source(src: &Source, summary_only: bool) -> Result<FlownColumns, PyErr> {
    let (sc, file) = resolve(src).map_err(|e| errors::scenario(&e))?;
    let flight = fly(&sc, &file, &mut |_| {}).map_err(|e| errors::scenario(&e))?;
    let summary = flight.summary(&sc, &sc.name);
    let summary_json = serde_json::to_string(&summary)
        .map_err(|e| errors::ReentryError::new_err(format!("summary: {e}")))?;
    let samples = if summary_only {
        &[][..]
    } else {
        &flight.result.samples[..]
    };
    // Column-major, written in one pass over the samples: column `c` of row `i` at byte
    // `8 * (c * rows + i)`.
    let rows = samples.len();
    let mut bytes = vec![0u8; 8 * COLUMNS.len() * rows];
    for (i, p) in samples.iter().enumerate() {
        for (c, v) in row(p).into_iter().enumerate() {
            let at = 8 * (c * rows + i);
            if let Some(dst) = bytes.get_mut(at..at + 8) {
                dst.copy_from_slice(&v.to_ne_bytes());
            }
        }
    }
    Ok(FlownColumns {
        bytes,
        rows,
        kinds: samples.iter().map(|p| p.kind).collect(),
        summary_json,
    })
}

fn to_python<'py>(py: Python<'py>, f: FlownColumns) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    // One `bytearray` (writable, so the numpy arrays viewing it are too) and one list that
    // refers to five strings: no Python object per value or per sample.
    out.set_item("columns", PyByteArray::new(py, &f.bytes))?;
    out.set_item("rows", f.rows)?;
    let names = EVENTS.map(|e| PyString::intern(py, e));
    let events = PyList::new(py, f.kinds.iter().map(|&k| &names[event_index(k)]))?;
    out.set_item("events", events)?;
    out.set_item("summary_json", f.summary_json)?;
    Ok(out)
}

pub(crate) fn source(
    builtin: Option<String>,
    path: Option<PathBuf>,
    toml: Option<String>,
    label: Option<String>,
    base_dir: Option<PathBuf>,
) -> PyResult<Source> {
    match (builtin, path, toml) {
        (Some(b), None, None) => Ok(Source::Builtin(b)),
        (None, Some(p), None) => Ok(Source::File(p)),
        (None, None, Some(text)) => Ok(Source::Toml {
            text,
            label: label.unwrap_or_else(|| "(TOML string)".to_string()),
            base_dir: base_dir.unwrap_or_else(|| Path::new(".").to_path_buf()),
        }),
        (None, None, None) => Ok(Source::Builtin("horus-2b-reference".to_string())),
        _ => Err(PyValueError::new_err(
            "give at most one of builtin, path and toml",
        )),
    }
}

/// Fly a scenario closed-loop (host-sim `scenario::fly`) and return
/// `{"columns": bytearray, "rows": int, "events": [str], "summary_json": str}`: `columns`
/// holds the trajectory column-major as native-endian `f64` (the columns of
/// `TRAJECTORY_COLUMNS` in order, `rows` values each; the Python layer views it as one
/// `(columns, rows)` numpy array), `events` the event of each sample.
///
/// Exactly one of `builtin` (a built-in scenario name), `path` (a scenario TOML file) or
/// `toml` (scenario TOML text; `label` names it in error messages, relative files resolve
/// against `base_dir`); none flies the HORUS-2B reference mission. With `summary_only` the
/// columns are empty. The GIL is released during the flight.
#[pyfunction]
#[pyo3(signature = (*, builtin=None, path=None, toml=None, label=None, base_dir=None, summary_only=false))]
fn fly_scenario<'py>(
    py: Python<'py>,
    builtin: Option<String>,
    path: Option<PathBuf>,
    toml: Option<String>,
    label: Option<String>,
    base_dir: Option<PathBuf>,
    summary_only: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let src = source(builtin, path, toml, label, base_dir)?;
    let flown = py.detach(|| fly_source(&src, summary_only))?;
    to_python(py, flown)
}

/// Convert a scenario given as JSON text (from a Python dict) into scenario TOML text.
#[pyfunction]
fn json_to_toml(json: &str) -> PyResult<String> {
    let v: toml::Value = serde_json::from_str(json)
        .map_err(|e| errors::ScenarioError::new_err(format!("(dict): {e}")))?;
    toml::to_string(&v).map_err(|e| errors::ScenarioError::new_err(format!("(dict): {e}")))
}

/// The scenario TOML of a built-in scenario (what `host-sim simulate --print-scenario` prints),
/// or of a scenario file when `path` is given.
#[pyfunction]
#[pyo3(signature = (builtin="horus-2b-reference", path=None))]
fn scenario_toml(builtin: &str, path: Option<PathBuf>) -> PyResult<String> {
    let sc = match path {
        Some(p) => read_scenario(&p),
        None => Scenario::try_builtin(builtin),
    }
    .map_err(|e| errors::scenario(&e))?;
    Ok(scenario_to_toml(&sc))
}

/// Names of the built-in scenarios.
#[pyfunction]
fn builtin_scenarios() -> Vec<&'static str> {
    Scenario::BUILTIN.to_vec()
}

/// Atmosphere state at altitudes in metres: `{"altitude_m", "temperature_k", "pressure_pa",
/// "density_kg_m3", "speed_of_sound_m_s"}` lists. `model`: "us76" or "exponential"
/// (rho0 = 1.225 kg/m^3, H = 7.2 km). Non-finite altitudes raise ValueError.
#[pyfunction]
#[pyo3(signature = (altitudes_m, model="us76"))]
fn atmosphere<'py>(
    py: Python<'py>,
    altitudes_m: Vec<f64>,
    model: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let m: Box<dyn Atmosphere> = match model.to_ascii_lowercase().as_str() {
        "us76" => Box::new(Us76::new()),
        "exponential" => Box::new(ExponentialAtmosphere::earth()),
        other => {
            return Err(PyValueError::new_err(format!(
                "atmosphere model {other:?}: unknown; use \"us76\" or \"exponential\""
            )));
        }
    };
    if let Some(bad) = altitudes_m.iter().find(|h| !h.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "altitude_m = {bad}: must be finite"
        )));
    }
    let states: Vec<_> = py.detach(|| altitudes_m.iter().map(|&h| m.state(h)).collect());
    let out = PyDict::new(py);
    out.set_item(
        "temperature_k",
        states.iter().map(|s| s.temperature_k).collect::<Vec<_>>(),
    )?;
    out.set_item(
        "pressure_pa",
        states.iter().map(|s| s.pressure_pa).collect::<Vec<_>>(),
    )?;
    out.set_item(
        "density_kg_m3",
        states.iter().map(|s| s.density_kg_m3).collect::<Vec<_>>(),
    )?;
    out.set_item(
        "speed_of_sound_m_s",
        states
            .iter()
            .map(|s| s.speed_of_sound_m_s)
            .collect::<Vec<_>>(),
    )?;
    out.set_item("altitude_m", altitudes_m)?;
    Ok(out)
}

/// The built-in vehicles: one dict per vehicle (name, mass_kg, reference_area_m2,
/// nose_radius_m, max_heat_flux_w_m2, max_g_load, max_g_load_rate_per_s).
#[pyfunction]
fn vehicles<'py>(py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let mut out = Vec::new();
    for name in host_sim::vehicle::list() {
        let v = host_sim::vehicle::by_name(name).map_err(|e| errors::vehicle(&e))?;
        let d = PyDict::new(py);
        d.set_item("name", &v.name)?;
        d.set_item("mass_kg", v.mass_kg)?;
        d.set_item("reference_area_m2", v.reference_area_m2)?;
        d.set_item("nose_radius_m", v.nose_radius_m)?;
        d.set_item("max_heat_flux_w_m2", v.limits.heat_flux_w_m2)?;
        d.set_item("max_g_load", v.limits.g_load)?;
        d.set_item("max_g_load_rate_per_s", v.limits.g_load_rate_per_s)?;
        out.push(d);
    }
    Ok(out)
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("TRAJECTORY_COLUMNS", COLUMNS.to_vec())?;
    m.add_function(wrap_pyfunction!(fly_scenario, m)?)?;
    m.add_function(wrap_pyfunction!(json_to_toml, m)?)?;
    m.add_function(wrap_pyfunction!(scenario_toml, m)?)?;
    m.add_function(wrap_pyfunction!(builtin_scenarios, m)?)?;
    m.add_function(wrap_pyfunction!(atmosphere, m)?)?;
    m.add_function(wrap_pyfunction!(vehicles, m)?)?;
    Ok(())
}
