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
    DesignError,
    ReentryError,
    "A re-entry design problem that cannot be built: bad setting, unknown preset, unreadable base (host-sim DesignError)."
);
create_exception!(
    reentry,
    CampaignError,
    ReentryError,
    "A dispersion campaign that cannot be set up or flown: bad setting, scenario, failed flight (host-sim CampaignError)."
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
    m.add("DesignError", py.get_type::<DesignError>())?;
    m.add("CampaignError", py.get_type::<CampaignError>())?;
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

/// A host-sim design-problem error as a Python `DesignError`.
pub(crate) fn design(e: &host_sim::design::DesignError) -> PyErr {
    DesignError::new_err(e.to_string())
}

/// A host-sim campaign error as a Python `CampaignError`.
pub(crate) fn campaign(e: &host_sim::campaign::CampaignError) -> PyErr {
    CampaignError::new_err(e.to_string())
}
