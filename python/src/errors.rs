//! Python exceptions: one base class, one subclass per host-sim error family. The message is
//! the Rust error's `Display` (what `host-sim` prints after `error: `).

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(
    reentry,
    ReentryError,
    PyException,
    "Base class of every error raised by the reentry package."
);
create_exception!(
    reentry,
    ScenarioError,
    ReentryError,
    "A scenario that cannot be read, resolved or flown (host-sim ScenarioError)."
);
create_exception!(
    reentry,
    VehicleError,
    ReentryError,
    "An unknown vehicle or a bad vehicle file (host-sim VehicleFileError)."
);
create_exception!(
    reentry,
    OptimError,
    ReentryError,
    "An optimiser that refuses its settings, a misused ask/tell protocol or a failed evaluation (host-sim OptimError)."
);
create_exception!(
    reentry,
    ProblemError,
    ReentryError,
    "An unknown or ill-sized test problem (host-sim TestProblemError)."
);

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("ReentryError", py.get_type::<ReentryError>())?;
    m.add("ScenarioError", py.get_type::<ScenarioError>())?;
    m.add("VehicleError", py.get_type::<VehicleError>())?;
    m.add("OptimError", py.get_type::<OptimError>())?;
    m.add("ProblemError", py.get_type::<ProblemError>())?;
    Ok(())
}

/// A host-sim scenario error as a Python `ScenarioError`.
pub(crate) fn scenario(e: &host_sim::scenario::ScenarioError) -> PyErr {
    ScenarioError::new_err(e.to_string())
}

/// A host-sim vehicle error as a Python `VehicleError`.
pub(crate) fn vehicle(e: &host_sim::vehicle::VehicleFileError) -> PyErr {
    VehicleError::new_err(e.to_string())
}

/// A host-sim optimiser error (or anything convertible to one) as a Python `OptimError`.
pub(crate) fn optim(e: impl Into<host_sim::optim::OptimError>) -> PyErr {
    OptimError::new_err(e.into().to_string())
}
