//! Property tests of the guidance path (nodes, interpolation, rate limit, clock, monitors).
