//! `reentry._native`: the Python bindings of host-sim (PyO3, abi3).
//!
//! Wrappers only: every number comes from host-sim's library (`scenario::fly`,
//! `env` atmospheres, `vehicle` registry, `optim` algorithms and test problems, `design` problems (the robust one too), `campaign` dispersion cases). The GIL is
//! released while Rust runs a flight, a batch of evaluations or an ask/tell step. Errors
//! become Python exceptions (subclasses of [`ReentryError`]) whose message is the Rust
//! error's `Display`, the text the `host-sim` CLI prints after `error: `.
//!
//! The Python package `reentry` (python/reentry/) wraps this module: numpy arrays, pandas
//! DataFrames, pygmo user-defined problems, the Dask layer.

mod campaign;
mod design;
mod errors;
mod flight;
mod optim;
mod robust;
mod run;

use pyo3::prelude::*;

pub use errors::ReentryError;

/// The native module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    errors::register(m)?;
    flight::register(m)?;
    optim::register(m)?;
    design::register(m)?;
    campaign::register(m)?;
    robust::register(m)?;
    run::register(m)?;
    Ok(())
}
