"""Typed interface of the dcfm Python module (``dcfm._dcfm``, Rust via pyo3)."""

from collections.abc import Callable
from os import PathLike
from typing import Any, Literal

import numpy as np
import numpy.typing as npt

__version__: str

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]
PairStateName = Literal["bonded", "stick", "sliding", "separated"]

class DcfmError(Exception):
    """An error of the dcfm core; ``str(e)`` is the core's message
    (``file: field = value: expected``)."""

    kind: str
    file: str | None
    field: str | None
    value: str | None
    expected: str | None

class Case:
    """A case loaded and validated like a case file."""

    @staticmethod
    def from_file(path: str | PathLike[str]) -> Case: ...
    @staticmethod
    def from_toml(text: str, label: str = "<toml>", base_dir: str | PathLike[str] = ".") -> Case: ...
    @staticmethod
    def from_dict(case: dict[str, Any], label: str = "<dict>", base_dir: str | PathLike[str] = ".") -> Case: ...
    @property
    def toml(self) -> str: ...
    @property
    def label(self) -> str: ...
    @property
    def title(self) -> str: ...
    @property
    def dt(self) -> float: ...
    @property
    def end(self) -> float: ...
    @property
    def safety(self) -> float: ...
    @property
    def critical_dt(self) -> float: ...
    @property
    def limiting_element(self) -> int: ...
    @property
    def n_steps(self) -> int: ...
    @property
    def n_nodes(self) -> int: ...
    @property
    def n_elements(self) -> int: ...
    @property
    def coords(self) -> FloatArray: ...
    @property
    def elements(self) -> IntArray: ...
    @property
    def element_region(self) -> IntArray: ...
    @property
    def region_names(self) -> list[str]: ...
    @property
    def mass(self) -> FloatArray: ...
    @property
    def set_names(self) -> list[str]: ...
    def nodes_of(self, set: str) -> IntArray: ...
    @property
    def output_nodes(self) -> list[int]: ...
    @property
    def output_elements(self) -> list[int]: ...
    @property
    def output(self) -> dict[str, Any]: ...
    def start(self, dt: float | None = None) -> Simulation: ...
    def run(
        self,
        *,
        end: float | None = None,
        steps: int | None = None,
        record_every: int = 1,
        nodes: list[int] | None = None,
        elements: list[int] | None = None,
        callback: Callable[[int, float, dict[str, float]], bool | None] | None = None,
        callback_every: int = 100,
        threads: int | None = None,
        dt: float | None = None,
    ) -> RunResult: ...

class Simulation:
    """A case in motion (central difference with the dynamic contact force method)."""

    @property
    def dt(self) -> float: ...
    @property
    def time(self) -> float: ...
    @property
    def step_count(self) -> int: ...
    @property
    def displacement(self) -> FloatArray: ...
    @property
    def velocity(self) -> FloatArray: ...
    @property
    def acceleration(self) -> FloatArray: ...
    @property
    def mass(self) -> FloatArray: ...
    @property
    def energies(self) -> dict[str, float]: ...
    def elastic_strain_energy(self) -> float: ...
    def set_velocity(self, velocity: npt.ArrayLike) -> None: ...
    def step(self, n: int = 1, threads: int | None = None) -> None: ...
    def run(
        self,
        *,
        end: float | None = None,
        steps: int | None = None,
        record_every: int = 1,
        nodes: list[int] | None = None,
        elements: list[int] | None = None,
        callback: Callable[[int, float, dict[str, float]], bool | None] | None = None,
        callback_every: int = 100,
        threads: int | None = None,
    ) -> RunResult: ...
    def fields(self) -> dict[str, FloatArray]: ...

class RunResult:
    """Histories (one entry per record) and the final fields of a run."""

    time: FloatArray
    step: FloatArray
    energies: dict[str, FloatArray]
    nodes: list[int]
    elements: list[int]
    displacement: FloatArray
    velocity: FloatArray
    acceleration: FloatArray
    stress: FloatArray
    fields: dict[str, FloatArray]
    steps: int
    stopped: bool
    wall_s: float
    element_updates_per_s: float

class Mesh:
    """A hex8 mesh with regions and named sets."""

    @property
    def n_nodes(self) -> int: ...
    @property
    def n_elements(self) -> int: ...
    @property
    def coords(self) -> FloatArray: ...
    @property
    def elements(self) -> IntArray: ...
    @property
    def element_region(self) -> IntArray: ...
    @property
    def region_names(self) -> list[str]: ...
    @property
    def node_sets(self) -> dict[str, IntArray]: ...
    @property
    def element_sets(self) -> dict[str, IntArray]: ...
    @property
    def face_sets(self) -> dict[str, IntArray]: ...

def box_mesh(
    blocks: list[dict[str, Any]],
    split: list[list[str]] | None = None,
    merge_tolerance: float | None = None,
) -> Mesh: ...
def material_point(
    material: dict[str, Any],
    strain: npt.ArrayLike,
    *,
    char_length: float = 1.0,
    dt: float = 0.0,
    name: str = "material",
) -> dict[str, FloatArray]: ...
def contact_pair_step(
    *,
    state: PairStateName,
    normal: npt.ArrayLike,
    w_sum: float,
    dt: float,
    rel_pred: npt.ArrayLike,
    rel_old: npt.ArrayLike,
    mu_s: float,
    mu_d: float,
    shear_capacity: float = 0.0,
    tensile_capacity: float = 0.0,
) -> dict[str, Any]: ...
def to_toml(case: dict[str, Any]) -> str: ...
