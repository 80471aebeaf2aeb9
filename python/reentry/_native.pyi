"""Type stubs of the native module (python/src/*.rs). Wrappers only; SI units and radians."""

from os import PathLike
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

TRAJECTORY_COLUMNS: List[str]

class ReentryError(Exception): ...
class ScenarioError(ReentryError): ...
class VehicleError(ReentryError): ...
class OptimError(ReentryError): ...
class ProblemError(ReentryError): ...
class DesignError(ReentryError): ...
class CampaignError(ReentryError): ...

def fly_scenario(
    *,
    builtin: Optional[str] = None,
    path: Optional[Union[str, PathLike[str]]] = None,
    toml: Optional[str] = None,
    label: Optional[str] = None,
    base_dir: Optional[Union[str, PathLike[str]]] = None,
    summary_only: bool = False,
) -> Dict[str, Any]:
    """Fly a scenario; ``{"columns": bytearray, "rows": int, "events": [str], "summary_json": str}``.

    ``columns``: the trajectory column-major, native-endian float64, the columns of
    ``TRAJECTORY_COLUMNS`` in order with ``rows`` values each (empty with ``summary_only``)."""

def json_to_toml(json: str) -> str: ...
def run_file_info(path: str) -> Tuple[str, PathLike[str]]: ...
def check_reference(reference: Sequence[float], objectives: int) -> None: ...
def parse_reference(text: str) -> List[float]: ...
def run_config_toml(preset: str, overrides_json: str) -> str: ...
def scenario_toml(builtin: str = "horus-2b-reference", path: Optional[str] = None) -> str: ...
def builtin_scenarios() -> List[str]: ...
def atmosphere(altitudes_m: Sequence[float], model: str = "us76") -> Dict[str, List[float]]: ...
def vehicles() -> List[Dict[str, Any]]: ...
def hypervolume(points: Sequence[Sequence[float]], reference: Sequence[float]) -> float: ...
def test_problems() -> List[str]: ...
def variable_length_problems() -> List[str]: ...
def run_variable_length(
    problem: str,
    options_json: str,
    seed: int,
    generations: int,
    evaluations: Optional[int] = ...,
    reference: Optional[Sequence[float]] = ...,
    threads: int = ...,
    out: Optional[str] = ...,
) -> str: ...

class Optimizer:
    """host-sim MOEA/D, NSGA-II or MHACO behind ask/tell."""

    @staticmethod
    def from_spec(name: str, config_json: str, seed: int) -> Optimizer: ...
    @staticmethod
    def moead(config_json: str, seed: int) -> Optimizer: ...
    @staticmethod
    def nsga2(config_json: str, seed: int) -> Optimizer: ...
    @staticmethod
    def mhaco(config_json: str, seed: int) -> Optimizer: ...
    @staticmethod
    def from_options(options_json: str, seed: int) -> Optimizer: ...
    @staticmethod
    def generations_for(options_json: str, evaluations: int, objectives: int) -> int: ...
    @staticmethod
    def from_json(text: str) -> Optimizer: ...
    def evolve_batches(
        self,
        problem: Any,
        generations: int,
        map_batch: Callable[[List[List[float]]], Sequence[Tuple[Sequence[float], Sequence[float]]]],
        observer: Optional[Callable[[], None]] = None,
    ) -> None: ...
    def ask(self, problem: Any) -> List[List[float]]: ...
    def tell(
        self, index: int, objectives: Sequence[float], constraints: Sequence[float] = ...
    ) -> None: ...
    def is_told(self, index: int) -> bool: ...
    def population(
        self,
    ) -> Tuple[List[List[float]], List[List[float]], List[List[float]], List[float]]: ...
    @property
    def generation(self) -> int: ...
    @property
    def evaluations(self) -> int: ...
    @property
    def is_initialised(self) -> bool: ...
    @property
    def name(self) -> str: ...
    def evolve_test_problem(self, problem: TestProblem, generations: int) -> None: ...
    def run_report(
        self,
        problem: Any,
        seed: int,
        wall_time_s: float,
        reference: Optional[Sequence[float]] = ...,
        threads: int = ...,
        name: Optional[str] = ...,
        generations: Optional[int] = ...,
        out: Optional[str] = ...,
    ) -> str: ...
    def to_json(self) -> str: ...

class TestProblem:
    """ZDT1-4, 6, DTLZ1-7, CONSTR evaluated in Rust."""

    def __init__(self, name: str, objectives: int = 3) -> None: ...
    @property
    def name(self) -> str: ...
    def get_bounds(self) -> Tuple[List[float], List[float]]: ...
    def get_nobj(self) -> int: ...
    def get_nic(self) -> int: ...
    def get_nec(self) -> int: ...
    def evaluate(self, x: Sequence[float]) -> Tuple[List[float], List[float]]: ...
    def evaluate_batch(
        self, xs: Sequence[Sequence[float]]
    ) -> List[Tuple[List[float], List[float]]]: ...
    def reference_point(self) -> List[float]: ...
    def pareto_front(self, n: int) -> List[List[float]]: ...
    def front_hypervolume(self, reference: Sequence[float], samples: int = 10000) -> Optional[float]: ...

def design_presets() -> List[str]: ...
def run_design(
    out: str,
    config: Optional[str] = None,
    *,
    resume: bool = False,
    generations: Optional[int] = None,
    map_batch: Optional[Callable[[List[List[float]]], List[Tuple[List[float], List[float]]]]] = None,
    label: Optional[str] = None,
) -> str: ...

class DesignProblem:
    """A fixed-length re-entry design problem (host-sim design::ReentryProblem)."""

    def __new__(
        cls,
        preset: Optional[str] = None,
        *,
        toml: Optional[str] = None,
        path: Optional[Union[str, PathLike[str]]] = None,
        base_dir: Optional[Union[str, PathLike[str]]] = None,
    ) -> DesignProblem: ...
    def config_toml(self) -> str:
        """The [problem] settings as TOML text."""
    @property
    def base_dir(self) -> str: ...
    def get_bounds(self) -> Tuple[List[float], List[float]]:
        """Per free node: E-hat, alpha [deg] if free, sigma [deg]; then the entry altitude [km] if a variable."""
    def get_nobj(self) -> int: ...
    def get_nic(self) -> int: ...
    def get_nec(self) -> int: ...
    def evaluate(self, x: Sequence[float]) -> Tuple[List[float], List[float]]:
        """(objectives, constraints) of one decision: one closed-loop flight; NaN if it failed."""
    def evaluate_batch(
        self, xs: Sequence[Sequence[float]]
    ) -> List[Tuple[List[float], List[float]]]: ...
    def decode(self, x: Sequence[float]) -> Tuple[List[List[float]], Optional[float]]:
        """Node table [[E-hat, alpha_rad, sigma_rad], ...] and entry altitude [m] (or None)."""
    def scenario_toml(self, x: Sequence[float]) -> str:
        """The scenario TOML a decision flies (for reentry.fly)."""

class RobustDesignProblem:
    """The robust re-entry design problem (host-sim design::RobustProblem)."""

    def __new__(
        cls,
        *,
        toml: Optional[str] = None,
        path: Optional[Union[str, PathLike[str]]] = None,
        base_dir: Optional[Union[str, PathLike[str]]] = None,
    ) -> RobustDesignProblem: ...
    def config_toml(self) -> str:
        """The [problem] and [robust] settings as TOML text."""
    @property
    def base_dir(self) -> str: ...
    @property
    def cases(self) -> int:
        """Flights per candidate (robust.dispersions.cases)."""
    @property
    def mode(self) -> str:
        """The guidance mode every candidate flies."""
    def get_bounds(self) -> Tuple[List[float], List[float]]: ...
    def get_nobj(self) -> int: ...
    def get_nic(self) -> int: ...
    def get_nec(self) -> int: ...
    def evaluate(self, x: Sequence[float]) -> Tuple[List[float], List[float]]:
        """(objectives, constraints) of one decision: its whole campaign; NaN if it failed."""
    def evaluate_batch(
        self, xs: Sequence[Sequence[float]]
    ) -> List[Tuple[List[float], List[float]]]: ...
    def fly_cases(self, x: Sequence[float], indices: Sequence[int]) -> Optional[str]:
        """Cases `indices` of the decision's campaign as JSON outcomes; None if it cannot be set up."""
    def evaluate_parts(self, parts: Sequence[Optional[str]]) -> Tuple[List[float], List[float]]:
        """The decision's evaluation from its parts (any order, every case once)."""
    def scenario_toml(self, x: Sequence[float]) -> str:
        """The scenario TOML a decision flies (the base stack with its nodes)."""

class VariableDesignProblem:
    """The variable-length re-entry design problem (host-sim design::VariableReentry)."""

    def __new__(
        cls,
        preset: Optional[str] = None,
        *,
        toml: Optional[str] = None,
        path: Optional[Union[str, PathLike[str]]] = None,
        base_dir: Optional[Union[str, PathLike[str]]] = None,
        nodes: Optional[Tuple[int, int]] = None,
    ) -> VariableDesignProblem: ...
    def config_toml(self) -> str: ...
    @property
    def base_dir(self) -> str: ...
    @property
    def nodes(self) -> Tuple[int, int]:
        """(min, max) table nodes, fixed end nodes included."""
    @property
    def node_genes(self) -> int:
        """Genes per free node: 3 ([E-hat, alpha_deg, sigma_deg]) or 2 ([E-hat, sigma_deg])."""
    def get_bounds(self) -> Tuple[List[float], List[float]]:
        """Padded decision: max-2 nodes' genes, entry altitude [km] if a variable, free-node count."""
    def get_nobj(self) -> int: ...
    def get_nic(self) -> int: ...
    def get_nec(self) -> int: ...
    def get_nix(self) -> int:
        """1: the free-node count (last variable) is an integer."""
    def chromosome(self, x: Sequence[float]) -> Tuple[List[List[float]], Optional[float]]:
        """(free nodes, entry altitude [km] or None) of a padded decision."""
    def evaluate(self, x: Sequence[float]) -> Tuple[List[float], List[float]]: ...
    def evaluate_batch(
        self, xs: Sequence[Sequence[float]]
    ) -> List[Tuple[List[float], List[float]]]: ...
    def evaluate_chromosome(
        self, nodes: Sequence[Sequence[float]], altitude_km: Optional[float] = None
    ) -> Tuple[List[float], List[float]]: ...
    def table(
        self, nodes: Sequence[Sequence[float]], altitude_km: Optional[float] = None
    ) -> Tuple[List[List[float]], Optional[float]]:
        """Node table [[E-hat, alpha_rad, sigma_rad], ...] and entry altitude [m] of a chromosome."""

def campaign_modes() -> List[str]: ...

class DispersionCampaign:
    """A dispersion campaign (host-sim campaign): set-up built, jobs (mode, index) flown on demand."""

    def __new__(
        cls,
        *,
        builtin: Optional[str] = None,
        path: Optional[Union[str, PathLike[str]]] = None,
        toml: Optional[str] = None,
        label: Optional[str] = None,
        base_dir: Optional[Union[str, PathLike[str]]] = None,
        settings_toml: Optional[str] = None,
        settings_label: Optional[str] = None,
        cases: Optional[int] = None,
        seed: Optional[int] = None,
        interface_speed_m_s: Optional[float] = None,
        modes: Optional[Sequence[str]] = None,
        spec_json: Optional[str] = None,
    ) -> DispersionCampaign: ...
    def spec_json(self) -> str:
        """What rebuilds the campaign (scenario source, settings, modes) as JSON."""
    def settings_json(self) -> str: ...
    @property
    def cases(self) -> int: ...
    @property
    def modes(self) -> List[str]: ...
    @property
    def interface_speed_m_s(self) -> float: ...
    def target(self) -> Tuple[float, float, float]:
        """(latitude_rad, longitude_rad, downrange_m) of the target."""
    def fly(self, jobs: Sequence[Tuple[str, int]]) -> List[str]:
        """CaseResult JSON text of each (mode, index) job, flown serially, GIL released."""
    def nominal(self) -> List[str]:
        """CaseResult JSON text of each mode's undispersed flight."""
    def run_local(self, threads: Optional[int] = None) -> List[str]:
        """Every job by host-sim run_campaign (rayon), in mode then index order."""
    def write(self, dir: Union[str, PathLike[str]], results: Sequence[str]) -> List[str]:
        """host-sim dispersions' files (summary.json, cases-<mode>.csv, plots) from gathered results."""
