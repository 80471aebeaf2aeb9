//! Validation of the environment and vehicle models (US76, gravity/J2, HORUS-2B, SRM).
