"""Dispersion campaigns (host-sim ``campaign``, ``host-sim dispersions``, docs/reference/campaigns.md).

A :class:`DispersionCampaign` holds a scenario, the ``[dispersions]`` settings and the guidance
modes, with the campaign's set-up built in Rust (nominal flights, terminal interface, target,
stored profile). Its jobs are the ``(mode, case index)`` pairs; each job is a pure function of
the campaign and its key (case ``i`` draws its dispersions from a generator seeded by the
campaign seed and ``i`` only), so any subset can be flown anywhere (:meth:`fly`, a Dask task)
and gathered by key into the same table as :meth:`run_local` (host-sim's own
``run_campaign``) and as the CLI's files, bit for bit.

A case result is host-sim's ``CaseResult`` as JSON text (no bit lost); :meth:`table` turns a
list of them into a pandas DataFrame and :meth:`write` writes the CLI's files from them.
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

from . import _native
from .flight import ScenarioLike, _source

SettingsLike = Union[None, str, "os.PathLike[str]", Mapping]

Job = Tuple[str, int]
"""``(mode name, case index)``."""

LIMIT_RATIO_COLUMNS = ("heat_flux_ratio", "g_load_ratio", "g_load_rate_ratio")
"""Column names of ``CaseResult.limit_ratios`` (peak / vehicle limit) in :meth:`table`."""


def _settings_source(settings: SettingsLike) -> Dict[str, Any]:
    if settings is None:
        return {}
    if isinstance(settings, Mapping):
        d = dict(settings)
        if "dispersions" not in d:
            d = {"dispersions": d}
        return {"settings_toml": _native.json_to_toml(json.dumps(d)), "settings_label": "(dict)"}
    if isinstance(settings, (str, os.PathLike)) and (
        isinstance(settings, os.PathLike) or ("\n" not in settings and "=" not in settings)
    ):
        path = os.fspath(settings)
        try:
            with open(path, encoding="utf-8") as f:
                text = f.read()
        except OSError as e:
            raise _native.CampaignError(f"{path}: cannot read: {e}") from None
        return {"settings_toml": text, "settings_label": path}
    if isinstance(settings, str):
        return {"settings_toml": settings}
    raise TypeError(f"settings must be a path, TOML text or a dict, not {type(settings).__name__}")


def _from_spec(cls, spec_json: str):
    return cls(_spec=spec_json)


class DispersionCampaign(_native.DispersionCampaign):
    """A dispersion campaign (host-sim ``dispersions``).

    ``scenario``: a scenario file, TOML text or dict (as :func:`reentry.fly`), or ``builtin``
    (``"horus-2b-reference"`` when neither is given, ``"srm-glide"``); ``settings``: a TOML
    file or text with a ``[dispersions]`` section, or a dict of its fields (default:
    host-sim's documented defaults); ``cases``, ``seed``, ``interface_speed_m_s`` override
    them like the CLI's ``-n``, ``--seed``, ``--interface-speed``; ``modes``: names from
    ``"stored"``, ``"stored-reversals"``, ``"replan-reversals"``, ``"replan-estimation"``
    (default: those the scenario's guidance layers make). The campaign flies the scenario's
    onboard stack (its ``[guidance.<layer>]`` sections and ``[guidance.target]``; a settings
    file's former ``[dispersions.guidance]`` is refused). Building it
    flies the set-up (a few nominal flights). Raises :class:`reentry.CampaignError` /
    :class:`reentry.ScenarioError` with host-sim's messages. Pickles (rebuilt from its spec).

    ``DispersionCampaign(builtin="srm-glide", cases=1000)`` is
    ``host-sim dispersions --builtin srm-glide -n 1000``."""

    def __new__(
        cls,
        scenario: ScenarioLike = None,
        *,
        builtin: Optional[str] = None,
        settings: SettingsLike = None,
        cases: Optional[int] = None,
        seed: Optional[int] = None,
        interface_speed_m_s: Optional[float] = None,
        modes: Optional[Sequence[str]] = None,
        _spec: Optional[str] = None,
    ):
        if _spec is not None:
            return super().__new__(cls, spec_json=_spec)
        src = _source(scenario, builtin)
        if "path" in src:  # the spec travels to workers whose working folder may differ
            src["path"] = os.path.abspath(src["path"])
        return super().__new__(
            cls,
            **src,
            **_settings_source(settings),
            cases=cases,
            seed=seed,
            interface_speed_m_s=interface_speed_m_s,
            modes=None if modes is None else list(modes),
        )

    def __reduce__(self):
        return (_from_spec, (type(self), self.spec_json()))

    @property
    def settings(self) -> Dict[str, Any]:
        """The ``[dispersions]`` settings in force (after the overrides)."""
        return json.loads(self.settings_json())

    def jobs(self) -> List[Job]:
        """Every ``(mode, case index)``, in the table's order (mode order, then index)."""
        return [(m, i) for m in self.modes for i in range(self.cases)]

    def fly_jobs(self, jobs: Sequence[Job]) -> List[str]:
        """Fly these jobs here (serially, GIL released): one ``CaseResult`` JSON text each."""
        return list(self.fly([(str(m), int(i)) for m, i in jobs]))

    def run_local(self, threads: Optional[int] = None) -> List[str]:
        """Every job, flown by host-sim's ``run_campaign`` in this process (rayon,
        ``threads`` threads, default all cores; the result does not depend on it), in
        :meth:`jobs` order."""
        return list(super().run_local(threads))

    def table(self, results: Sequence[str]):
        """The results (JSON texts in :meth:`jobs` order) as a pandas DataFrame: one row per
        job, columns ``mode``, ``index``, the ``CaseResult`` fields (SI units, radians;
        ``limit_ratios`` as :data:`LIMIT_RATIO_COLUMNS`) and the case's dispersed values as
        ``draw.<field>``. Raises ``ValueError`` if a result is not the job at its position."""
        import pandas as pd

        jobs = self.jobs()
        if len(results) != len(jobs):
            raise ValueError(f"{len(results)} results for {len(jobs)} jobs")
        rows = []
        for (mode, index), text in zip(jobs, results):
            r = json.loads(text)
            if r["index"] != index:
                raise ValueError(f"result for case {r['index']} at the place of case {index}")
            row: Dict[str, Any] = {"mode": mode}
            for k, v in r.items():
                if k == "mode":
                    continue
                if k == "limit_ratios":
                    row.update(zip(LIMIT_RATIO_COLUMNS, v))
                elif k == "draw":
                    row.update({f"draw.{dk}": dv for dk, dv in (v or {}).items() if dk != "index"})
                else:
                    row[k] = v
            rows.append(row)
        return pd.DataFrame(rows)

    def write(self, directory, results: Sequence[str]) -> List[str]:
        """Write ``summary.json``, ``cases-<mode>.csv`` and the plots into ``directory`` as
        ``host-sim dispersions --out`` does (same code, same bytes), from results in any
        order; every job must be present exactly once. Returns the files written."""
        return [os.fspath(p) for p in super().write(os.fspath(directory), list(results))]


def campaign_modes() -> List[str]:
    """The guidance modes of a campaign, in report order."""
    return list(_native.campaign_modes())


__all__ = ["DispersionCampaign", "LIMIT_RATIO_COLUMNS", "campaign_modes"]
