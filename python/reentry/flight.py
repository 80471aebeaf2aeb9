"""Flying scenarios: the trajectory as numpy arrays or a pandas DataFrame, the summary as a dict."""

from __future__ import annotations

import json
import os
from collections.abc import Mapping
from typing import Any, Dict, List, Optional, Union

import numpy as np

from . import _native

ScenarioLike = Union[None, str, "os.PathLike[str]", Mapping]


def _toml_loads(text: str) -> dict:
    try:
        import tomllib  # Python >= 3.11
    except ModuleNotFoundError:  # pragma: no cover - Python 3.9/3.10
        import tomli as tomllib  # type: ignore[no-redef]
    return tomllib.loads(text)


def _source(scenario: ScenarioLike, builtin: Optional[str]) -> Dict[str, Any]:
    if builtin is not None:
        if scenario is not None:
            raise ValueError("give a scenario or a builtin name, not both")
        return {"builtin": builtin}
    if scenario is None:
        return {}
    if isinstance(scenario, Mapping):
        return {"toml": _native.json_to_toml(json.dumps(scenario)), "label": "(dict)"}
    if isinstance(scenario, os.PathLike):
        return {"path": os.fspath(scenario)}
    if isinstance(scenario, str):
        if "\n" in scenario or "=" in scenario:
            return {"toml": scenario}
        return {"path": scenario}
    raise TypeError(
        f"scenario must be a path, TOML text or a dict, not {type(scenario).__name__}"
    )


class Flight:
    """A flown scenario.

    * ``arrays``: dict of numpy arrays, one per column of :data:`TRAJECTORY_COLUMNS`
      (SI units and radians, unit in the name), one entry per sample;
    * ``events``: the event of each sample (``"start"``, ``""``, ``"exit"``, ``"entry"``,
      ``"end"``);
    * ``summary``: the document host-sim writes to summary.json (same fields and units).
    """

    def __init__(self, raw: dict):
        # One (columns, rows) array over the native bytearray, no copy; each column a row view.
        names = _native.TRAJECTORY_COLUMNS
        block = np.frombuffer(raw["columns"], dtype=np.float64).reshape(len(names), raw["rows"])
        self.arrays: Dict[str, np.ndarray] = dict(zip(names, block))
        self.events: List[str] = raw["events"]
        self.summary: Dict[str, Any] = json.loads(raw["summary_json"])

    def __len__(self) -> int:
        return len(self.events)

    def __repr__(self) -> str:
        s = self.summary
        return (
            f"<Flight {s['scenario']}: {len(self)} samples, {s['termination']} after "
            f"{s['flight_time_s']:.1f} s>"
        )

    def to_dataframe(self):
        """The trajectory as a pandas DataFrame (one row per sample, plus an ``event`` column)."""
        import pandas as pd

        df = pd.DataFrame({k: self.arrays[k] for k in _native.TRAJECTORY_COLUMNS})
        df["event"] = self.events
        return df

    @property
    def trajectory(self):
        """Same as :meth:`to_dataframe`."""
        return self.to_dataframe()


def fly(scenario: ScenarioLike = None, *, builtin: Optional[str] = None) -> Flight:
    """Fly a scenario closed-loop with guidance-core's guidance (host-sim ``scenario::fly``).

    ``scenario``: a scenario TOML file (``str`` without ``=`` or newline, or ``os.PathLike``),
    scenario TOML text, or a dict with the scenario file's structure; ``builtin``: a built-in
    scenario name (:func:`builtin_scenarios`). Neither flies the HORUS-2B reference mission
    (``host-sim simulate``). Raises :class:`ScenarioError` with host-sim's message.
    """
    return Flight(_native.fly_scenario(**_source(scenario, builtin)))


def fly_summary(scenario: ScenarioLike = None, *, builtin: Optional[str] = None) -> Dict[str, Any]:
    """The summary dict of a flight only (no trajectory is copied to Python)."""
    raw = _native.fly_scenario(summary_only=True, **_source(scenario, builtin))
    return json.loads(raw["summary_json"])


def scenario_toml(builtin: str = "horus-2b-reference", path: Optional[str] = None) -> str:
    """The scenario TOML of a built-in scenario or a scenario file (``--print-scenario``)."""
    return _native.scenario_toml(builtin, path)


def scenario_dict(builtin: str = "horus-2b-reference", path: Optional[str] = None) -> dict:
    """:func:`scenario_toml` parsed into a dict: edit it and pass it to :func:`fly`.

    Note: a built-in scenario flown from its dict is a scenario *file*; the reference
    mission's file holds the nodes to the file bounds (banking to either side) where the
    built-in holds them to the mission's (0..90 deg), which only matters for nodes outside.
    """
    return _toml_loads(scenario_toml(builtin, path))
