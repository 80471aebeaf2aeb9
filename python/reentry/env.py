"""Atmosphere queries and the built-in vehicles."""

from __future__ import annotations

from typing import Dict, List

import numpy as np

from . import _native


def atmosphere(altitude_m, model: str = "us76") -> Dict[str, np.ndarray]:
    """Atmosphere state at one or more altitudes [m].

    ``model``: ``"us76"`` (U.S. Standard Atmosphere 1976) or ``"exponential"``
    (rho0 = 1.225 kg/m^3, H = 7.2 km). Returns numpy arrays ``altitude_m``,
    ``temperature_k``, ``pressure_pa``, ``density_kg_m3``, ``speed_of_sound_m_s``.
    Raises ValueError for an unknown model or a non-finite altitude.
    """
    h = np.atleast_1d(np.asarray(altitude_m, dtype=float))
    out = _native.atmosphere(h.tolist(), model)
    return {k: np.asarray(v, dtype=float) for k, v in out.items()}


def vehicles() -> List[dict]:
    """The built-in vehicles (what ``host-sim vehicles`` lists), SI units: name, mass_kg,
    reference_area_m2, nose_radius_m, max_heat_flux_w_m2, max_g_load, max_g_load_rate_per_s."""
    return list(_native.vehicles())
