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
    def from_file(path: str | PathLike[str], *, motions: dict[str, Motion] | None = None) -> Case: ...
    @staticmethod
    def from_toml(
        text: str,
        label: str = "<toml>",
        base_dir: str | PathLike[str] = ".",
        *,
        motions: dict[str, Motion] | None = None,
    ) -> Case: ...
    @staticmethod
    def from_dict(
        case: dict[str, Any],
        label: str = "<dict>",
        base_dir: str | PathLike[str] = ".",
        *,
        motions: dict[str, Motion] | None = None,
    ) -> Case: ...
    @property
    def has_static(self) -> bool: ...
    @property
    def motion_names(self) -> list[str]: ...
    def static(self, *, threads: int | None = None) -> dict[str, Any]: ...
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
        free_field: bool = False,
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
        free_field: bool = False,
    ) -> RunResult: ...
    def free_field_column(self) -> dict[str, FloatArray] | None: ...
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
    free_field: dict[str, FloatArray] | None
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

class Motion:
    """A ground motion: one to three acceleration components (m/s²) on one uniform grid,
    with their exact integrals from rest and the provenance of every step."""

    @staticmethod
    def from_arrays(
        acceleration: npt.ArrayLike,
        dt: float,
        units: str,
        *,
        components: list[str] | None = None,
        axes: list[str | None] | None = None,
        name: str = "arrays",
        station: str = "",
        description: str = "",
        source: str = "arrays",
    ) -> Motion: ...
    @staticmethod
    def from_obspy(
        data: Any,
        units: str | None = None,
        *,
        axes: list[str | None] | None = None,
        name: str | None = None,
        apply_calib: bool = True,
    ) -> Motion: ...
    @property
    def name(self) -> str: ...
    @property
    def source(self) -> str: ...
    @property
    def format(self) -> str: ...
    @property
    def station(self) -> str: ...
    @property
    def description(self) -> str: ...
    @property
    def units(self) -> str: ...
    @property
    def dt(self) -> float: ...
    @property
    def npts(self) -> int: ...
    @property
    def duration(self) -> float: ...
    @property
    def components(self) -> list[str]: ...
    @property
    def axes(self) -> list[str | None]: ...
    @property
    def provenance(self) -> list[str]: ...
    @property
    def time(self) -> FloatArray: ...
    @property
    def acceleration(self) -> FloatArray: ...
    def velocity(self) -> FloatArray: ...
    def displacement(self) -> FloatArray: ...
    def process(
        self,
        *,
        window: tuple[float, float] | list[float] | None = None,
        baseline: Literal["none", "mean", "polynomial"] | None = None,
        baseline_order: int = 1,
        taper: float = 0.0,
        highpass: float | None = None,
        lowpass: float | None = None,
        filter_order: int = 4,
        zero_phase: bool = True,
        pad: float | None = None,
        resample_dt: float | None = None,
        zero_end: bool = False,
        target_pga: float | dict[str, float] | None = None,
    ) -> Motion: ...
    def component(self, name: str) -> Motion: ...
    def summary(self) -> dict[str, dict[str, Any]]: ...
    def husid(self, component: str | None = None) -> FloatArray: ...
    def fourier_amplitude(self, component: str | None = None) -> tuple[FloatArray, FloatArray]: ...

def read_motion(
    path: str | PathLike[str],
    format: str | None = None,
    *,
    units: str | None = None,
    dt: float | None = None,
    components: list[str] | None = None,
    name: str | None = None,
) -> Motion: ...
def synthetic_motion(spec: dict[str, Any], name: str = "synthetic") -> Motion: ...
def response_spectrum(
    motion: Motion,
    periods: npt.ArrayLike,
    damping: float = 0.05,
    *,
    component: str | None = None,
) -> dict[str, FloatArray]: ...
