//! Generic multi-objective optimisation (issue 9): problems, ask/tell algorithms (MOEA/D,
//! NSGA-II, MHACO, SCEA), Pareto utilities, exact hypervolume and standard test problems.
//!
//! Layering rule: this module imports nothing else of `host-sim` (no simulator, no CLI); a test
//! enforces it. The re-entry problems live outside it and implement its `Problem` trait.

pub mod hypervolume;
