"""reentry: the reentry-guidance simulator, optimisers and test problems from Python.

A thin layer over the Rust crate host-sim (PyO3, abi3): every number is computed in Rust,
with the GIL released. SI units and radians throughout (unit in each name).

* :func:`fly` flies a scenario (built-in name, TOML file, TOML text or dict) and returns a
  :class:`Flight` (trajectory as numpy arrays or a pandas DataFrame, summary as a dict);
* :func:`atmosphere`, :func:`vehicles`;
* :class:`Moead`, :class:`Nsga2`, :class:`Mhaco` (ask/tell), :class:`TestProblem`, :func:`evolve`,
  :func:`hypervolume`, :class:`PygmoProblem` (any of our problems as a pygmo UDP);
* :class:`DesignProblem`, :class:`VariableDesignProblem` (the thesis' re-entry design
  problems as pygmo UDPs), :class:`RobustDesignProblem` (profiles judged by dispersion
  campaigns), :func:`pymoo_problem`;
* :class:`DispersionCampaign` (host-sim's dispersion campaign, case by case);
* :mod:`reentry.distributed`: optimisation, dispersion and flight campaigns on Dask.

Errors are :class:`ReentryError` subclasses carrying host-sim's message.
"""

from ._native import (
    TRAJECTORY_COLUMNS,
    CampaignError,
    DesignError,
    OptimError,
    ProblemError,
    ReentryError,
    ScenarioError,
    VehicleError,
    builtin_scenarios,
    hypervolume,
    test_problems,
)
from .design import (
    DesignProblem,
    RobustDesignProblem,
    VariableDesignProblem,
    design_presets,
    design_run_config,
    design_run_config_of_flags,
    pymoo_problem,
    run_design,
)
from .dispersions import DispersionCampaign, campaign_modes
from .env import atmosphere, vehicles
from .flight import Flight, fly, fly_summary, scenario_dict, scenario_toml
from .optim import (
    Mhaco,
    Moead,
    Nsga2,
    Population,
    PygmoProblem,
    TestProblem,
    evaluate_batch,
    evolve,
    from_options,
    generations_for,
    run_variable_length,
    variable_length_problems,
)

__all__ = [
    "TRAJECTORY_COLUMNS",
    "CampaignError",
    "DesignError",
    "DesignProblem",
    "RobustDesignProblem",
    "DispersionCampaign",
    "Flight",
    "Mhaco",
    "Moead",
    "Nsga2",
    "OptimError",
    "Population",
    "ProblemError",
    "PygmoProblem",
    "ReentryError",
    "ScenarioError",
    "TestProblem",
    "VariableDesignProblem",
    "VehicleError",
    "atmosphere",
    "builtin_scenarios",
    "campaign_modes",
    "design_presets",
    "design_run_config",
    "design_run_config_of_flags",
    "evaluate_batch",
    "evolve",
    "fly",
    "fly_summary",
    "from_options",
    "generations_for",
    "hypervolume",
    "pymoo_problem",
    "run_design",
    "run_variable_length",
    "scenario_dict",
    "scenario_toml",
    "test_problems",
    "variable_length_problems",
    "vehicles",
]
