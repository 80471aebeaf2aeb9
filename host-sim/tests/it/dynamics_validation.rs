//! Validation of integrators and dynamics (Kepler orbit, Cartesian vs spherical, ballistic entry).
