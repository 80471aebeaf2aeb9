//! Exact hypervolume of a set of points (minimisation) with respect to a reference point.
