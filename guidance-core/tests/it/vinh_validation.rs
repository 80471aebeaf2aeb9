//! Validation of the Vinh closed forms against numerical integration.
