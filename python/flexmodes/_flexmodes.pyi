"""Type stubs of the Rust extension (flexmodes' own wrappers in __init__.py are typed inline)."""

from typing import Any, Callable, Optional, TypedDict

import numpy as np
import numpy.typing as npt

__version__: str

def set_threads(threads: Optional[int] = None) -> int: ...
def threads() -> int: ...

Progress = Optional[Callable[[Optional[str], Optional[float]], Any]]
FloatArray = npt.NDArray[np.float64]
IndexArray = npt.NDArray[np.int64]

Triplets = tuple[tuple[int, int], IndexArray, IndexArray, FloatArray]

class BodyLayout(TypedDict):
    dofs: list[str]
    nodes: Optional[list[tuple[float, float, float]]]
    node_sets: dict[str, list[int]]
    interfaces: dict[
        str, tuple[str, str, Optional[tuple[float, float, float]], Optional[list[float]]]
    ]
    default_interface: Optional[str]
    units: tuple[str, str, str]

class ReduceRequest(TypedDict):
    method: str
    boundary: Optional[list[str]]
    modes: int
    interface_modes: Optional[int]
    exudyn: bool
    eigensolver: str
    residual_vectors: bool

class CompareRequest(TypedDict):
    methods: Optional[list[str]]
    modes: Optional[list[int]]
    boundary: Optional[list[str]]
    interface_modes: Optional[int]
    band_hz: Optional[float]
    tolerance: float

class SimulateRequest(TypedDict):
    drive: str
    methods: list[str]
    modes: list[int]
    full: bool
    boundary: list[str]
    outputs: list[str]
    rate: float
    ramp: float
    axis: tuple[float, float, float]
    end: float
    step: float
    output_every: int
    pinned: list[str]
    axis_point: Optional[tuple[float, float, float]]
    shake: Optional[tuple[tuple[float, float, float], float, float]]
    gravity: Optional[tuple[float, float, float]]
    spectral_radius: float
    mean_axes: bool
    stiffening: bool
    residual_vectors: bool

class CampbellRequest(TypedDict):
    drive: str
    rates: list[float]
    axis: tuple[float, float, float]
    axis_point: Optional[tuple[float, float, float]]
    count: int
    methods: list[str]
    modes: list[int]
    full: bool
    stiffening: bool
    residual_vectors: bool

class RustBody:
    @staticmethod
    def from_entries(name: str, k: Triplets, m: Triplets, layout: BodyLayout) -> RustBody: ...
    @staticmethod
    def from_file(path: str) -> RustBody: ...
    @property
    def name(self) -> str: ...
    @property
    def dofs(self) -> int: ...
    @property
    def nodes(self) -> Optional[FloatArray]: ...
    @property
    def node_sets(self) -> dict[str, list[int]]: ...
    @property
    def units(self) -> tuple[str, str, str]: ...
    def summary(self, eigensolver: str) -> dict[str, Any]: ...
    def free_modes(self, n: int) -> dict[str, Any]: ...
    def reduce(self, request: ReduceRequest) -> RustReducedModel: ...
    def compare(self, request: CompareRequest, progress: Progress) -> dict[str, Any]: ...
    def simulate(self, request: SimulateRequest, progress: Progress) -> dict[str, Any]: ...
    def campbell(self, request: CampbellRequest, progress: Progress) -> dict[str, Any]: ...

class RustReducedModel:
    @property
    def psi(self) -> FloatArray: ...
    @property
    def k_r(self) -> FloatArray: ...
    @property
    def m_r(self) -> FloatArray: ...
    @property
    def hz(self) -> FloatArray: ...
    @property
    def residuals(self) -> FloatArray: ...
    @property
    def zero_energy_modes(self) -> int: ...
    @property
    def labels(self) -> list[str]: ...
    @property
    def method(self) -> str: ...
    @property
    def boundary(self) -> list[int]: ...
    @property
    def timings(self) -> list[tuple[str, float]]: ...
    def document(self) -> dict[str, Any]: ...
    def save(self, folder: str, exudyn: bool) -> list[str]: ...
