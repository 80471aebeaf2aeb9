//! The optimisers through ask/tell, the test problems and the hypervolume.
//!
//! [`Optimizer`] holds a host-sim algorithm built from an `AlgorithmSpec` (a `RealAlgorithm`:
//! MOEA/D with DE or SBX, NSGA-II, MHACO; or a `ChromosomeAlgorithm`: SCEA, the
//! variable-length MHACO, run on the real vectors as chromosomes of fixed genes only, host-sim's
//! `FixedLength`, as `host-sim optimize scea` runs SCEA on the test problems) and the shape of
//! the problem it runs on
//! ([`OpenProblem`]: bounds, objectives, constraints), read from any Python object with
//! pygmo's user-defined-problem methods (`get_bounds`, `get_nobj`, `get_nic`). Evaluations
//! happen outside (in Python, in Rust through [`PyTestProblem`], or on Dask workers) and come
//! back by index through `tell`, so the run is the algorithm's, bit for bit, whoever evaluates.

use std::path::PathBuf;

use host_sim::optim::chromosome::{Chromosome, FixedLength};
use host_sim::optim::hypervolume::hypervolume as hv;
use host_sim::optim::problems::{NAMES, TestProblem, VL_NAMES, Vlmop};
use host_sim::optim::run::{RunResult, RunSettings, real_run_report, run_report};
use host_sim::optim::spec::RunOptions;
use host_sim::optim::variable_length_run::VariableLengthRun;
use host_sim::optim::{
    Algorithm, AlgorithmSpec, BatchEvaluator, Bounds, BuiltAlgorithm, ChromosomeAlgorithm,
    EvalError, Evaluation, External, Individual, NoObserver, Problem, RealAlgorithm, RealProblem,
    SPEC_NAMES, Serial, Threads, evolve,
};
use host_sim::report::{write_chromosome_run_report, write_run_report};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyType;
use serde::{Deserialize, Serialize};

use crate::errors;

/// The shape of a problem evaluated elsewhere: the algorithms need its bounds and sizes only.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct OpenProblem {
    bounds: Bounds,
    objectives: usize,
    constraints: usize,
}

/// Returned if an algorithm ever evaluated an [`OpenProblem`] itself (the ask/tell algorithms
/// never do).
#[derive(Debug)]
struct EvaluatedOutside;

impl std::fmt::Display for EvaluatedOutside {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("this problem is evaluated by the caller (ask/tell)")
    }
}

impl std::error::Error for EvaluatedOutside {}

impl Problem for OpenProblem {
    type Decision = Vec<f64>;

    fn objectives(&self) -> usize {
        self.objectives
    }

    fn constraints(&self) -> usize {
        self.constraints
    }

    fn evaluate(&self, _x: &Vec<f64>) -> Result<Evaluation, EvalError> {
        Err(EvalError::Failed(Box::new(EvaluatedOutside)))
    }
}

impl RealProblem for OpenProblem {
    fn bounds(&self) -> &Bounds {
        &self.bounds
    }
}

/// Read the problem's shape through pygmo's UDP protocol.
fn open_problem(problem: &Bound<'_, PyAny>) -> PyResult<OpenProblem> {
    let (lower, upper): (Vec<f64>, Vec<f64>) = problem.call_method0("get_bounds")?.extract()?;
    let count = |name: &str, default: usize| -> PyResult<usize> {
        if problem.hasattr(name)? {
            problem.call_method0(name)?.extract()
        } else {
            Ok(default)
        }
    };
    let nec = count("get_nec", 0)?;
    if nec != 0 {
        return Err(PyValueError::new_err(format!(
            "get_nec() = {nec}: equality constraints are not supported; write them as two inequalities"
        )));
    }
    Ok(OpenProblem {
        bounds: Bounds::new(lower, upper).map_err(errors::optim)?,
        objectives: count("get_nobj", 1)?,
        constraints: count("get_nic", 0)?,
    })
}

/// The algorithm an [`Optimizer`] holds.
#[derive(Clone, Debug)]
enum Held {
    /// On the real vectors.
    Real(RealAlgorithm),
    /// On the real vectors as chromosomes of fixed genes only ([`FixedLength`]).
    Fixed(ChromosomeAlgorithm),
}

/// `$body` with `$a` the algorithm of `$held` and `$P` the problem type it runs on.
macro_rules! each {
    ($held:expr, $a:ident, $P:ident => $body:expr) => {
        match $held {
            Held::Real($a) => {
                type $P = OpenProblem;
                $body
            }
            Held::Fixed($a) => {
                type $P = FixedLength<OpenProblem>;
                $body
            }
        }
    };
}

impl Held {
    fn built(b: BuiltAlgorithm) -> Self {
        match b {
            BuiltAlgorithm::Real(a) => Self::Real(a),
            BuiltAlgorithm::Chromosome(a) => Self::Fixed(a),
        }
    }

    fn validate(&self, p: &OpenProblem) -> Result<(), host_sim::optim::StateError> {
        match self {
            Self::Real(a) => a.validate(p),
            Self::Fixed(a) => a.validate(&FixedLength::new(p.clone())),
        }
    }

    fn generation(&self) -> u64 {
        each!(self, a, P => Algorithm::<P>::generation(a))
    }

    fn evaluations(&self) -> u64 {
        each!(self, a, P => Algorithm::<P>::evaluations(a))
    }

    fn is_initialised(&self) -> bool {
        each!(self, a, P => Algorithm::<P>::is_initialised(a))
    }

    fn is_finished(&self) -> bool {
        each!(self, a, P => Algorithm::<P>::is_finished(a))
    }

    fn is_told(&self, index: usize) -> bool {
        each!(self, a, P => Algorithm::<P>::is_told(a, index))
    }

    fn name(&self) -> &'static str {
        each!(self, a, P => Algorithm::<P>::name(a))
    }

    /// The population and the external archive (if any) as real vectors.
    fn individuals(&self) -> (Vec<RealIndividual>, Option<Vec<RealIndividual>>) {
        match self {
            Self::Real(a) => (
                Algorithm::<OpenProblem>::population(a).to_vec(),
                Algorithm::<OpenProblem>::external_archive(a).map(<[_]>::to_vec),
            ),
            Self::Fixed(a) => {
                type P = FixedLength<OpenProblem>;
                (
                    real(Algorithm::<P>::population(a)),
                    Algorithm::<P>::external_archive(a).map(real),
                )
            }
        }
    }
}

/// An individual of the real vectors.
type RealIndividual = Individual<Vec<f64>>;

/// Chromosomes of fixed genes only as their real vectors.
fn real(individuals: &[Individual<Chromosome>]) -> Vec<Individual<Vec<f64>>> {
    individuals
        .iter()
        .map(|i| Individual {
            decision: i.decision.fixed.clone(),
            objectives: i.objectives.clone(),
            constraints: i.constraints.clone(),
            violation: i.violation,
        })
        .collect()
}

/// What [`Optimizer::to_json`] writes: the algorithm's whole state (`algorithm` a real-vector
/// one, `chromosome_algorithm` SCEA or the variable-length MHACO) and the problem shape.
#[derive(Serialize, Deserialize)]
struct Checkpoint {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    algorithm: Option<RealAlgorithm>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    chromosome_algorithm: Option<ChromosomeAlgorithm>,
    problem: Option<OpenProblem>,
}

/// An ask/tell optimiser (host-sim MOEA/D, NSGA-II, MHACO, SCEA or the variable-length MHACO).
#[pyclass(module = "reentry._native")]
pub struct Optimizer {
    algo: Held,
    problem: Option<OpenProblem>,
    /// Rebuilt from a checkpoint (checked against the first problem); a new algorithm's
    /// settings are checked by its first `ask`, with the algorithm's own message.
    restored: bool,
}

impl Optimizer {
    /// Take the problem's shape at the first call; refuse a different one later.
    fn adopt(&mut self, shape: OpenProblem) -> PyResult<()> {
        match &self.problem {
            Some(p) if *p != shape => Err(PyValueError::new_err(
                "ask: the problem's bounds, objectives or constraints changed during the run",
            )),
            Some(_) => Ok(()),
            None => {
                // A state restored without a problem is checked against the first one.
                if self.restored {
                    self.algo.validate(&shape).map_err(state_error)?;
                }
                self.problem = Some(shape);
                Ok(())
            }
        }
    }

    fn problem(&self) -> PyResult<&OpenProblem> {
        self.problem
            .as_ref()
            .ok_or_else(|| errors::optim(host_sim::optim::TellError::NoBatch))
    }
}

fn state_error(e: host_sim::optim::StateError) -> PyErr {
    PyValueError::new_err(format!("checkpoint: {e}"))
}

fn config_error(e: &serde_json::Error) -> PyErr {
    PyValueError::new_err(format!("optimiser settings: {e}"))
}

#[pymethods]
impl Optimizer {
    /// The algorithm `name` (`moead`, `moead-sbx`, `nsga2`, `mhaco`, `scea`, `vl-mhaco`:
    /// host-sim's `AlgorithmSpec`; for `scea` the table `moead` over its defaults) with the settings of `config_json` over its defaults (pagmo's; for
    /// `moead-sbx` the tables `moead` and `sbx`, each over its defaults) and the run's seed.
    #[staticmethod]
    fn from_spec(name: &str, config_json: &str, seed: u64) -> PyResult<Self> {
        let Some(defaults) = AlgorithmSpec::defaults(name) else {
            return Err(PyValueError::new_err(format!(
                "optimiser settings: algorithm {name:?}: use one of {}",
                SPEC_NAMES.join(", ")
            )));
        };
        let mut over: serde_json::Value =
            serde_json::from_str(config_json).map_err(|e| config_error(&e))?;
        let mut full = serde_json::to_value(&defaults).map_err(|e| config_error(&e))?;
        if let Some(o) = over.as_object_mut() {
            // The spec's own tag; the nested tables of moead-sbx merge table by table.
            o.remove("algorithm");
            for table in ["moead", "sbx"] {
                if let (Some(b), Some(t)) = (full.get_mut(table), o.remove(table)) {
                    let mut t = t;
                    merge(b, &mut t);
                }
            }
        }
        merge(&mut full, &mut over);
        let spec: AlgorithmSpec = serde_json::from_value(full).map_err(|e| config_error(&e))?;
        Ok(Self {
            algo: Held::built(spec.build(seed)),
            problem: None,
            restored: false,
        })
    }

    /// The algorithm of `host-sim optimize`'s algorithm flags on the test problems
    /// (`options_json`: host-sim `RunOptions` fields, the flags' names with underscores and
    /// their defaults: `algorithm` moead, nsga2, mhaco or scea, `moead_operator`,
    /// `population`, `weights`, `neighbours`, `mutation_probability`, `batch_size`,
    /// `archive`, `resource_allocation`, `ker`, `n_gen_mark`, `mhaco_constraints`,
    /// `scea_genes`), mapped onto its `AlgorithmSpec` as the CLI maps them, and the run's
    /// seed.
    #[staticmethod]
    fn from_options(options_json: &str, seed: u64) -> PyResult<Self> {
        let options = run_options(options_json)?;
        Ok(Self {
            algo: Held::built(options.spec().build(seed)),
            problem: None,
            restored: false,
        })
    }

    /// The generations `host-sim optimize --evaluations E` runs with these options on a
    /// problem of `objectives` objectives: the fewest whole generations whose evaluations,
    /// initial population included, reach `evaluations`.
    #[staticmethod]
    fn generations_for(options_json: &str, evaluations: u64, objectives: usize) -> PyResult<u64> {
        run_options(options_json)?
            .generations_for(evaluations, objectives)
            .map_err(|why| PyValueError::new_err(format!("--evaluations {evaluations}: {why}")))
    }

    /// The finished run's summary line (as `host-sim optimize` prints it), and with `out`
    /// its run directory written by host-sim (population.csv, front.csv, summary.json, as
    /// `host-sim optimize --out`). `problem`: the test problem run (its name, reference
    /// point and true front by default), or any other problem with `name` and `reference`
    /// given (no true front). `generations`: default the algorithm's completed generations;
    /// `threads`: the evaluation threads or workers the summary reports.
    #[pyo3(signature = (problem, seed, wall_time_s, reference=None, threads=1, name=None, generations=None, out=None))]
    #[allow(clippy::too_many_arguments)]
    fn run_report(
        &self,
        py: Python<'_>,
        problem: &Bound<'_, PyAny>,
        seed: u64,
        wall_time_s: f64,
        reference: Option<Vec<f64>>,
        threads: usize,
        name: Option<String>,
        generations: Option<u64>,
        out: Option<PathBuf>,
    ) -> PyResult<String> {
        let test_problem = problem.cast::<PyTestProblem>().ok();
        let test = test_problem.as_ref().map(|p| p.get());
        let shape = self.problem()?;
        let Some(name) = name.or_else(|| test.map(|t| t.name.clone())) else {
            return Err(PyValueError::new_err(
                "run_report: name: required for a problem other than a TestProblem",
            ));
        };
        let Some(reference) = reference.or_else(|| test.map(|t| t.inner.reference_point())) else {
            return Err(PyValueError::new_err(
                "run_report: reference: required for a problem other than a TestProblem",
            ));
        };
        let generations = generations.unwrap_or_else(|| self.algo.generation());
        let settings = match &self.algo {
            Held::Real(a) => {
                RunSettings::of_algorithm(a, &name, generations, seed, &reference, threads)
            }
            Held::Fixed(a) => RunSettings::of_chromosome_algorithm(
                a,
                &name,
                generations,
                seed,
                &reference,
                threads,
            ),
        };
        let (population, archive) = self.algo.individuals();
        let result = RunResult {
            population: &population,
            archive: archive.as_deref(),
            evaluations: self.algo.evaluations(),
            wall_time_s,
        };
        py.detach(|| {
            let report = match test {
                Some(t) => run_report(&t.inner, &settings, result),
                None => real_run_report(shape, None, &settings, result),
            }
            .map_err(|e| errors::OptimError::new_err(format!("run_report: {e}")))?;
            if let Some(dir) = &out {
                write_run_report(dir, &report)
                    .map_err(|e| errors::ReentryError::new_err(e.to_string()))?;
            }
            Ok(report.summary.line())
        })
    }

    /// MHACO with the settings of `config_json` (host-sim `MhacoConfig` fields; missing fields
    /// take pagmo's `maco` defaults) and the run's seed.
    #[staticmethod]
    fn mhaco(config_json: &str, seed: u64) -> PyResult<Self> {
        Self::from_spec("mhaco", config_json, seed)
    }

    /// MOEA/D with the settings of `config_json` (host-sim `MoeadConfig` fields; missing
    /// fields take pagmo's defaults) and the run's seed.
    #[staticmethod]
    fn moead(config_json: &str, seed: u64) -> PyResult<Self> {
        Self::from_spec("moead", config_json, seed)
    }

    /// NSGA-II with the settings of `config_json` (host-sim `Nsga2Config` fields; missing
    /// fields take pagmo's defaults) and the run's seed.
    #[staticmethod]
    fn nsga2(config_json: &str, seed: u64) -> PyResult<Self> {
        Self::from_spec("nsga2", config_json, seed)
    }

    /// The next batch of decisions to evaluate (the same batch again until all are told).
    /// `problem`: any object with `get_bounds()` (and optionally `get_nobj()`, `get_nic()`);
    /// it must keep the same shape for the whole run.
    fn ask(&mut self, py: Python<'_>, problem: &Bound<'_, PyAny>) -> PyResult<Vec<Vec<f64>>> {
        self.adopt(open_problem(problem)?)?;
        let Self { algo, problem, .. } = self;
        let Some(p) = problem.as_ref() else {
            return Ok(Vec::new());
        };
        py.detach(|| match algo {
            Held::Real(a) => a.ask(p).map(<[Vec<f64>]>::to_vec),
            Held::Fixed(a) => a
                .ask(&FixedLength::new(p.clone()))
                .map(|cs| cs.iter().map(|c| c.fixed.clone()).collect()),
        })
        .map_err(errors::optim)
    }

    /// Tell the evaluation of decision `index` of the current batch (objectives minimised,
    /// constraints `<= 0` satisfied; NaN values mark a failed evaluation).
    #[pyo3(signature = (index, objectives, constraints=Vec::new()))]
    fn tell(
        &mut self,
        py: Python<'_>,
        index: usize,
        objectives: Vec<f64>,
        constraints: Vec<f64>,
    ) -> PyResult<()> {
        let p = self.problem()?.clone();
        let e = Evaluation::with_constraints(objectives, constraints);
        py.detach(|| match &mut self.algo {
            Held::Real(a) => a.tell(&p, index, e),
            Held::Fixed(a) => a.tell(&FixedLength::new(p), index, e),
        })
        .map_err(errors::optim)
    }

    /// host-sim's `evolve` loop with every batch evaluated by `map_batch(xs) -> [(f, g), ...]`
    /// (a Python callable: in process, or over a Dask cluster): the initial population if
    /// needed, then `generations` more, resuming an open batch by evaluating only its untold
    /// decisions; `observer()` is called after each completed generation (the initial
    /// population's included). An exception of `map_batch` or `observer` stops the run at that
    /// batch (the evaluations told before it are kept) and is raised as `OptimError` with its
    /// message (`observer`'s as itself).
    #[pyo3(signature = (problem, generations, map_batch, observer=None))]
    fn evolve_batches(
        slf: &Bound<'_, Self>,
        problem: &Bound<'_, PyAny>,
        generations: u64,
        map_batch: Py<PyAny>,
        observer: Option<Py<PyAny>>,
    ) -> PyResult<()> {
        let py = slf.py();
        let shape = open_problem(problem)?;
        slf.borrow_mut().adopt(shape.clone())?;
        let evaluate = |xs: &[Vec<f64>]| crate::run::call_map_batch(&map_batch, xs);
        let external = External(&evaluate as &dyn BatchEvaluator<Vec<f64>>);
        let evaluate_fixed = |cs: &[Chromosome]| {
            let xs: Vec<Vec<f64>> = cs.iter().map(|c| c.fixed.clone()).collect();
            crate::run::call_map_batch(&map_batch, &xs)
        };
        let external_fixed = External(&evaluate_fixed as &dyn BatchEvaluator<Chromosome>);
        let fixed = FixedLength::new(shape.clone());
        let target = {
            let a = &slf.borrow().algo;
            if a.is_initialised() {
                a.generation() + generations
            } else {
                generations
            }
        };
        loop {
            let moved = {
                let mut me = slf.borrow_mut();
                let a = &mut me.algo;
                let done = a.is_initialised() && a.generation() >= target;
                if done || a.is_finished() {
                    return Ok(());
                }
                // One generation (or the initial population) at a time, so the observer may
                // read the algorithm between them.
                let before = a.generation();
                let step = u64::from(a.is_initialised());
                match a {
                    Held::Real(r) => evolve(r, &shape, &external, step, &mut NoObserver),
                    Held::Fixed(c) => evolve(c, &fixed, &external_fixed, step, &mut NoObserver),
                }
                .map_err(errors::optim)?;
                step == 0 || a.generation() != before
            };
            if let (true, Some(o)) = (moved, &observer) {
                o.call0(py)?;
            }
        }
    }

    /// Whether decision `index` of the open batch has been told.
    fn is_told(&self, index: usize) -> bool {
        self.algo.is_told(index)
    }

    /// The population: `(decisions, objectives, constraints, violations)`.
    #[allow(clippy::type_complexity)]
    fn population(&self) -> (Vec<Vec<f64>>, Vec<Vec<f64>>, Vec<Vec<f64>>, Vec<f64>) {
        let (pop, _) = self.algo.individuals();
        (
            pop.iter().map(|i| i.decision.clone()).collect(),
            pop.iter().map(|i| i.objectives.clone()).collect(),
            pop.iter().map(|i| i.constraints.clone()).collect(),
            pop.iter().map(|i| i.violation).collect(),
        )
    }

    /// Completed generations (0 until the initial population is complete).
    #[getter]
    fn generation(&self) -> u64 {
        self.algo.generation()
    }

    /// Evaluations told so far.
    #[getter]
    fn evaluations(&self) -> u64 {
        self.algo.evaluations()
    }

    /// Whether the initial population is complete.
    #[getter]
    fn is_initialised(&self) -> bool {
        self.algo.is_initialised()
    }

    /// "moead", "moead-sbx", "nsga2", "mhaco", "scea" or "vl-mhaco".
    #[getter]
    fn name(&self) -> &'static str {
        self.algo.name()
    }

    /// Run `generations` generations on a test problem inside Rust (host-sim `evolve`, serial
    /// evaluator; the initial population first if needed), GIL released.
    fn evolve_test_problem(
        &mut self,
        py: Python<'_>,
        problem: &PyTestProblem,
        generations: u64,
    ) -> PyResult<()> {
        let p = &problem.inner;
        let shape = OpenProblem {
            bounds: p.bounds().clone(),
            objectives: p.objectives(),
            constraints: p.constraints(),
        };
        self.adopt(shape)?;
        py.detach(|| match &mut self.algo {
            Held::Real(a) => evolve(a, p, &Serial, generations, &mut NoObserver),
            Held::Fixed(a) => {
                let fixed = FixedLength::new(p.clone());
                evolve(a, &fixed, &Serial, generations, &mut NoObserver)
            }
        })
        .map_err(errors::optim)
    }

    /// The whole state as JSON (algorithm, RNG, open batch, problem shape): resuming from it
    /// gives the bit-identical run.
    fn to_json(&self) -> PyResult<String> {
        let (algorithm, chromosome_algorithm) = match &self.algo {
            Held::Real(a) => (Some(a.clone()), None),
            Held::Fixed(a) => (None, Some(a.clone())),
        };
        serde_json::to_string(&Checkpoint {
            algorithm,
            chromosome_algorithm,
            problem: self.problem.clone(),
        })
        .map_err(|e| errors::ReentryError::new_err(format!("checkpoint: {e}")))
    }

    /// Rebuild from [`Optimizer::to_json`]'s text.
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        let mut de = serde_json::Deserializer::from_str(text);
        let c: Checkpoint = serde_path_to_error::deserialize(&mut de).map_err(|e| {
            PyValueError::new_err(format!("checkpoint: field `{}`: {}", e.path(), e.inner()))
        })?;
        let algo = match (c.algorithm, c.chromosome_algorithm) {
            (Some(a), None) => Held::Real(a),
            (None, Some(a)) => Held::Fixed(a),
            _ => {
                return Err(PyValueError::new_err(
                    "checkpoint: give one of the fields `algorithm`, `chromosome_algorithm`",
                ));
            }
        };
        // A tampered or corrupt state must not panic or hang later: it is checked against
        // itself and its problem (or, saved before the first ask, against the first problem).
        if let Some(p) = &c.problem {
            algo.validate(p).map_err(state_error)?;
        }
        Ok(Self {
            algo,
            problem: c.problem,
            restored: true,
        })
    }
}

/// Refuse a hypervolume reference point that has not one value per objective of a problem
/// of `objectives` objectives (host-sim's check, made before a run rather than at its end).
#[pyfunction]
fn check_reference(reference: Vec<f64>, objectives: usize) -> PyResult<()> {
    host_sim::optim::run::check_reference(&reference, objectives)
        .map_err(|e| errors::OptimError::new_err(format!("--ref: {e}")))
}

/// The reference point of the text of a `--ref` argument (`"1.1,1.1"`: comma-separated
/// finite numbers), host-sim's parser; `ValueError` naming the coordinate otherwise.
#[pyfunction]
fn parse_reference(text: &str) -> PyResult<Vec<f64>> {
    host_sim::optim::reference::parse_reference(text)
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))
}

/// host-sim `RunOptions` from JSON (missing fields: `host-sim optimize`'s defaults).
fn run_options(options_json: &str) -> PyResult<RunOptions> {
    let mut de = serde_json::Deserializer::from_str(options_json);
    serde_path_to_error::deserialize(&mut de).map_err(|e| {
        PyValueError::new_err(format!(
            "optimiser options: field `{}`: {}",
            e.path(),
            e.inner()
        ))
    })
}

/// Overwrite the fields of `base` (an object) with those of `over`.
fn merge(base: &mut serde_json::Value, over: &mut serde_json::Value) {
    if let (Some(b), Some(o)) = (base.as_object_mut(), over.as_object_mut()) {
        for (k, v) in std::mem::take(o) {
            b.insert(k, v);
        }
    }
}

/// Most points `pareto_front` samples (larger counts would fail on allocation).
const MAX_FRONT_POINTS: usize = 10_000_000;

/// A host-sim test problem (ZDT1-4, 6, DTLZ1-7, CONSTR) evaluated in Rust.
#[pyclass(name = "TestProblem", module = "reentry._native", frozen, subclass)]
pub struct PyTestProblem {
    inner: TestProblem,
    name: String,
    objectives_arg: usize,
}

#[pymethods]
impl PyTestProblem {
    /// The problem called `name` (zdt1, zdt2, zdt3, zdt4, zdt6, dtlz1 ... dtlz7, constr) with
    /// its standard size; DTLZ problems take `objectives`.
    #[new]
    #[pyo3(signature = (name, objectives=3))]
    fn new(name: &str, objectives: usize) -> PyResult<Self> {
        let inner = TestProblem::by_name(name, objectives)
            .map_err(|e| errors::ProblemError::new_err(e.to_string()))?
            .ok_or_else(|| {
                errors::ProblemError::new_err(format!(
                    "problem {name}: unknown; use one of {}",
                    NAMES.join(", ")
                ))
            })?;
        Ok(Self {
            inner,
            name: name.to_ascii_lowercase(),
            objectives_arg: objectives,
        })
    }

    /// Pickle support: rebuilt from its name and objectives.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> (Bound<'py, PyType>, (String, usize)) {
        let me = slf.get();
        (slf.get_type(), (me.name.clone(), me.objectives_arg))
    }

    /// The problem's name.
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// `(lower, upper)` bounds of the decision variables.
    fn get_bounds(&self) -> (Vec<f64>, Vec<f64>) {
        crate::design::bounds_pair(&self.inner)
    }

    /// Number of objectives (minimised).
    fn get_nobj(&self) -> usize {
        self.inner.objectives()
    }

    /// Number of inequality constraints (`<= 0` satisfied).
    fn get_nic(&self) -> usize {
        self.inner.constraints()
    }

    /// Number of equality constraints (always 0).
    fn get_nec(&self) -> usize {
        0
    }

    /// `(objectives, constraints)` of one decision.
    fn evaluate(&self, py: Python<'_>, x: Vec<f64>) -> PyResult<(Vec<f64>, Vec<f64>)> {
        crate::design::evaluate_real(py, &self.inner, x)
    }

    /// `(objectives, constraints)` of each decision, in order, GIL released.
    fn evaluate_batch(
        &self,
        py: Python<'_>,
        xs: Vec<Vec<f64>>,
    ) -> PyResult<Vec<(Vec<f64>, Vec<f64>)>> {
        py.detach(|| {
            xs.iter()
                .enumerate()
                .map(|(index, x)| {
                    self.inner
                        .evaluate(x)
                        .map(|e| (e.objectives, e.constraints))
                        .map_err(|e| format!("decision {index}: {e}"))
                })
                .collect::<Result<Vec<_>, _>>()
        })
        .map_err(errors::OptimError::new_err)
    }

    /// The reference point of its hypervolume.
    fn reference_point(&self) -> Vec<f64> {
        self.inner.reference_point()
    }

    /// About `n` points of the true front.
    fn pareto_front(&self, n: usize) -> PyResult<Vec<Vec<f64>>> {
        if n > MAX_FRONT_POINTS {
            return Err(PyValueError::new_err(format!(
                "pareto_front: n = {n}: use at most {MAX_FRONT_POINTS} points"
            )));
        }
        Ok(self.inner.pareto_front(n))
    }

    /// Hypervolume of the true front (exact where known, else of `samples` front points).
    #[pyo3(signature = (reference, samples=10_000))]
    fn front_hypervolume(&self, reference: Vec<f64>, samples: usize) -> PyResult<Option<f64>> {
        if samples > MAX_FRONT_POINTS {
            return Err(PyValueError::new_err(format!(
                "front_hypervolume: samples = {samples}: use at most {MAX_FRONT_POINTS}"
            )));
        }
        Ok(self.inner.front_hypervolume(&reference, samples))
    }
}

/// Exact hypervolume of `points` (minimised objectives) against `reference`.
#[pyfunction]
fn hypervolume(py: Python<'_>, points: Vec<Vec<f64>>, reference: Vec<f64>) -> PyResult<f64> {
    py.detach(|| hv(&points, &reference))
        .map_err(|e| errors::OptimError::new_err(e.to_string()))
}

/// Names of the test problems.
#[pyfunction]
fn test_problems() -> Vec<&'static str> {
    NAMES.to_vec()
}

/// Names of the variable-length test problems (`vlmop1` ... `vlmop5`).
#[pyfunction]
fn variable_length_problems() -> Vec<&'static str> {
    VL_NAMES.to_vec()
}

/// `host-sim optimize --problem NAME {scea,mhaco} ...` on a variable-length test problem,
/// in this process (host-sim's `VariableLengthRun`, `threads` evaluation threads, GIL
/// released): `options_json` as for `Optimizer.from_options` (`algorithm` scea or mhaco),
/// `evaluations` (instead of `generations`, as `--evaluations`: the fewest whole generations
/// that reach it), `reference` by default the problem's. Returns the summary line; with `out`
/// the run directory is written as `host-sim optimize --out` writes it.
#[pyfunction]
#[pyo3(signature = (problem, options_json, seed, generations, evaluations=None, reference=None, threads=1, out=None))]
#[allow(clippy::too_many_arguments)]
fn run_variable_length(
    py: Python<'_>,
    problem: &str,
    options_json: &str,
    seed: u64,
    generations: u64,
    evaluations: Option<u64>,
    reference: Option<Vec<f64>>,
    threads: usize,
    out: Option<PathBuf>,
) -> PyResult<String> {
    let Some(vl) = Vlmop::by_name(problem) else {
        return Err(PyValueError::new_err(format!(
            "problem {problem:?}: not a variable-length problem; use one of {}",
            VL_NAMES.join(", ")
        )));
    };
    let options = run_options(options_json)?;
    let generations = match evaluations {
        Some(e) => options
            .generations_for(e, vl.objectives())
            .map_err(|why| errors::OptimError::new_err(format!("--evaluations {e}: {why}")))?,
        None => generations,
    };
    let reference = reference.unwrap_or_else(|| vl.reference_point());
    let pool = Threads::new(threads).map_err(|e| PyValueError::new_err(format!("threads: {e}")))?;
    py.detach(|| {
        let run = VariableLengthRun::evolve(&vl, &options, seed, generations, pool)
            .map_err(|e| errors::OptimError::new_err(e.to_string()))?;
        let report = run
            .report(&vl, problem, seed, &reference, threads)
            .map_err(|e| errors::OptimError::new_err(format!("run_report: {e}")))?;
        if let Some(dir) = &out {
            write_chromosome_run_report(dir, &report)
                .map_err(|e| errors::ReentryError::new_err(e.to_string()))?;
        }
        Ok(report.summary.line())
    })
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Optimizer>()?;
    m.add_class::<PyTestProblem>()?;
    m.add_function(wrap_pyfunction!(hypervolume, m)?)?;
    m.add_function(wrap_pyfunction!(test_problems, m)?)?;
    m.add_function(wrap_pyfunction!(variable_length_problems, m)?)?;
    m.add_function(wrap_pyfunction!(run_variable_length, m)?)?;
    m.add_function(wrap_pyfunction!(check_reference, m)?)?;
    m.add_function(wrap_pyfunction!(parse_reference, m)?)?;
    Ok(())
}
