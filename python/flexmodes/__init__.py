"""flexmodes: model order reduction of restrained deformable bodies, from Python.

A body from SciPy matrices (scikit-fem, FElupe, pyNastran, ...) or a body file, reduced by
any of the classical methods (Guyan, modal truncation, Craig-Bampton, mode condensation,
Eitelberg, MacNeal-Rubin, Benfield-Hruda, moment matching, balanced truncation) on node
sets and rigid (RBE2) or averaging (RBE3) interfaces; every eigenpair's residual checked,
every check failure raised. The numerics run in Rust with the GIL released.

The kernels use every core (``flexmodes.threads()``; ``flexmodes.set_threads(n)`` lowers it).
Units are the body's own (say SI: m, kg, N, so Hz and s); node numbers in node sets are
1-based, as in body files and on the command line.
"""

from __future__ import annotations

import os
from typing import Any, Callable, Iterable, Mapping, Optional, Sequence, Union

import numpy as np

from . import errors
from ._flexmodes import RustBody, RustReducedModel, __version__, set_threads, threads
from .errors import (
    BodyFileError,
    Cancelled,
    DynamicsError,
    FileError,
    FlexmodesError,
    InputError,
    LinalgError,
    MechanismError,
    ReductionError,
)

#: Ids of the reduction methods (as ``flexmodes export --method`` takes them).
METHODS = ("gr", "mt", "cb", "mc", "eit", "mr", "bh", "mm", "bt")

Progress = Optional[Callable[[Optional[str], Optional[float]], Any]]


def _entries(matrix: Any, what: str, vector_ok: bool) -> tuple:
    """(shape, rows, cols, values) of a SciPy sparse matrix (any format), or of a 1-D NumPy
    vector when ``vector_ok`` (a lumped mass)."""
    import scipy.sparse as sp

    if sp.issparse(matrix):
        coo = matrix.tocoo()
        if np.iscomplexobj(coo.data):
            raise InputError(f"{what} is complex: flexmodes takes real matrices")
        return (
            tuple(int(x) for x in coo.shape),
            np.ascontiguousarray(coo.row, dtype=np.int64),
            np.ascontiguousarray(coo.col, dtype=np.int64),
            np.ascontiguousarray(coo.data, dtype=np.float64),
        )
    array = np.asarray(matrix) if not isinstance(matrix, np.ndarray) else matrix
    if array.ndim == 1 and vector_ok:
        n = array.shape[0]
        return (
            (n, 1),
            np.arange(n, dtype=np.int64),
            np.zeros(n, dtype=np.int64),
            np.ascontiguousarray(array, dtype=np.float64),
        )
    if array.ndim == 2:
        raise InputError(
            f"{what} is a dense {array.shape[0]} × {array.shape[1]} array: pass a SciPy sparse "
            f"matrix (scipy.sparse.csr_array({what})){' or, for a lumped mass, a 1-D vector' if vector_ok else ''}"
        )
    raise InputError(
        f"{what} is a {type(matrix).__name__} of {array.ndim} dimension(s): pass a SciPy sparse "
        "matrix"
    )


def _items(boundary: Union[None, str, int, Iterable[Union[str, int]]]) -> Optional[list]:
    """Interface items as ``--boundary`` takes them: set names, 1-based node numbers,
    ``rbe2:SET``, ``rbe3:SET``."""
    if boundary is None:
        return None
    if isinstance(boundary, (str, int, np.integer)):
        return [str(boundary)]
    return [str(b) for b in boundary]


class Body:
    """A deformable body, checked as ``flexmodes import`` checks a body file.

    Parameters
    ----------
    K, M:
        Stiffness and mass, SciPy sparse (CSR, CSC, COO, ...; the full matrix or one
        triangle), node-major (node 1's DOF, then node 2's). ``M`` may be a 1-D NumPy vector
        (lumped). Dense 2-D arrays are refused (``InputError``).
    nodes:
        Node coordinates, ``(nodes, 3)`` or ``(nodes, 2)``, in the length unit. Needed for
        rigid interfaces, drawing, rigid-body motions and simulation.
    node_sets:
        ``{name: 1-based node numbers}``.
    interfaces:
        ``{name: {"kind": "rbe2" | "rbe3", "node_set": SET, "master": (x, y, z) or None,
        "weights": [...] or None}}``.
    units:
        ``(length, mass, force)``, default ``("m", "kg", "N")``.
    dofs:
        DOF per node, of x, y, z, rx, ry, rz (default x, y, z).
    default_interface:
        The node set used when a call names no boundary.

    Raises ``BodyFileError`` (not symmetric, mass not positive at a DOF, a NaN, nodes that
    do not divide the DOF, a node set out of range) and ``InputError`` (shapes, types).
    """

    def __init__(
        self,
        K: Any,
        M: Any,
        nodes: Any = None,
        node_sets: Optional[Mapping[str, Iterable[int]]] = None,
        interfaces: Optional[Mapping[str, Mapping[str, Any]]] = None,
        units: Optional[Sequence[str]] = None,
        dofs: Sequence[str] = ("x", "y", "z"),
        name: str = "body",
        default_interface: Optional[str] = None,
    ) -> None:
        k_shape, k_rows, k_cols, k_values = _entries(K, "K", vector_ok=False)
        m_shape, m_rows, m_cols, m_values = _entries(M, "M", vector_ok=True)
        xyz = None
        if nodes is not None:
            array = np.asarray(nodes, dtype=np.float64)
            if array.ndim != 2 or array.shape[1] not in (2, 3):
                raise InputError(
                    f"nodes has shape {array.shape}: give (nodes, 3) or (nodes, 2) coordinates"
                )
            if array.shape[1] == 2:
                array = np.column_stack([array, np.zeros(array.shape[0])])
            xyz = [tuple(row) for row in array.tolist()]
        sets = {}
        for set_name, members in (node_sets or {}).items():
            numbers = np.asarray(list(members) if not isinstance(members, np.ndarray) else members)
            if numbers.size and not np.issubdtype(numbers.dtype, np.integer):
                raise InputError(f"node set `{set_name}` holds {numbers.dtype} values: give node numbers")
            sets[str(set_name)] = [int(x) for x in numbers.ravel()]
        given = {}
        for iname, spec in (interfaces or {}).items():
            master = spec.get("master")
            weights = spec.get("weights")
            given[str(iname)] = (
                str(spec.get("kind", "rbe2")),
                str(spec["node_set"]),
                None if master is None else tuple(float(x) for x in master),
                None if weights is None else [float(w) for w in weights],
            )
        length, mass, force = tuple(units) if units is not None else ("m", "kg", "N")
        self._inner = RustBody.from_entries(
            name,
            (k_shape, k_rows, k_cols, k_values),
            (m_shape, m_rows, m_cols, m_values),
            dict(
                dofs=[str(d) for d in dofs],
                nodes=xyz,
                node_sets=sets,
                interfaces=given,
                default_interface=default_interface,
                units=(str(length), str(mass), str(force)),
            ),
        )

    @classmethod
    def from_file(cls, path: Union[str, "os.PathLike[str]"]) -> "Body":
        """A body file (TOML naming Matrix Market, Harwell-Boeing, Abaqus, DMIG, OP4 or
        CalculiX matrices), or ``builtin:NAME``, as ``flexmodes import`` reads it."""
        body = cls.__new__(cls)
        body._inner = RustBody.from_file(str(path))
        return body

    @property
    def name(self) -> str:
        return self._inner.name

    @property
    def dofs(self) -> int:
        """Number of DOF."""
        return self._inner.dofs

    @property
    def nodes(self) -> Optional[np.ndarray]:
        """Node coordinates ``(nodes, 3)`` in the length unit, or None."""
        return self._inner.nodes

    @property
    def node_sets(self) -> dict:
        """``{name: 1-based node numbers}``."""
        return self._inner.node_sets

    @property
    def units(self) -> tuple:
        """``(length, mass, force)``."""
        return self._inner.units

    def summary(self, eigensolver: str = "lanczos") -> dict:
        """What ``flexmodes import`` prints: DOF, mass and inertia, zero-energy modes, modes
        the Sturm count says were missed, the lowest elastic Hz and their residuals. A
        mechanism raises ``MechanismError``. ``eigensolver``: ``"lanczos"`` (shift-invert
        Lanczos) or ``"amls"`` (multi-level substructuring, refined and Sturm-counted); the
        dict's ``eigensolver`` and ``amls`` say which made the pairs."""
        return self._inner.summary(str(eigensolver))

    def free_modes(self, n: int = 10) -> dict:
        """The ``n`` lowest elastic free-free modes: ``hz``, ``residuals``, ``vectors``
        (DOF × n, mass-normalised), the zero-energy ones and the Sturm count's
        ``missed_modes``. Every pair's residual is checked; a failed check raises
        ``LinalgError``."""
        return self._inner.free_modes(int(n))

    def reduce(
        self,
        method: str = "cb",
        boundary: Union[None, str, int, Iterable[Union[str, int]]] = None,
        modes: int = 10,
        interface_modes: Optional[int] = None,
        exudyn: bool = False,
        eigensolver: str = "lanczos",
        residual_vectors: bool = True,
    ) -> "ReducedModel":
        """Reduces the body as ``flexmodes export`` does.

        ``method``: one of :data:`METHODS` (``"nr"``: no reduction). ``boundary``: set
        names, 1-based node numbers, ``"rbe2:SET"`` (the set tied rigidly to one master at
        its centroid: six coordinates), ``"rbe3:SET"`` (averaged); default the body's
        default interface. ``modes``: kept normal modes. ``interface_modes``: reduce the
        constraint modes to this many characteristic constraint modes. ``exudyn``: also
        build the Exudyn body (floating frame on the first rigid interface).
        ``eigensolver``: the fixed-interface (and free-free) pairs by ``"lanczos"`` or
        ``"amls"``, as ``export --eigensolver``. ``residual_vectors``: append the static
        responses to the frame's twelve unit inertia loads to a fixed-interface basis (GR,
        MT, CB, MC), as ``export --residual-vectors on`` (their labels say
        ``residual vector``)."""
        return ReducedModel(
            self._inner.reduce(
                dict(
                    method=str(method),
                    boundary=_items(boundary),
                    modes=int(modes),
                    interface_modes=interface_modes,
                    exudyn=bool(exudyn),
                    eigensolver=str(eigensolver),
                    residual_vectors=bool(residual_vectors),
                )
            )
        )

    def simulate(
        self,
        drive: str,
        methods: Sequence[str] = ("nr", "cb"),
        modes: Sequence[int] = (10,),
        boundary: Sequence[str] = (),
        outputs: Sequence[str] = (),
        rate: float = 100.0,
        ramp: float = 0.5,
        axis: Sequence[float] = (0.0, 0.0, 1.0),
        end: float = 1.0,
        step: float = 1e-3,
        output_every: int = 10,
        progress: Progress = None,
        pinned: Sequence[str] = (),
        axis_point: Optional[Sequence[float]] = None,
        shake: Optional[tuple] = None,
        gravity: Optional[Sequence[float]] = None,
        spectral_radius: float = 0.9,
        axes: str = "nodal_fixed",
        stiffening: bool = True,
        residual_vectors: bool = True,
    ) -> dict:
        """The driven body of ``flexmodes simulate --body``: the interface ``drive``
        (``"rbe2:SET"`` or a declared rbe2 interface) spun up about ``axis`` to ``rate``
        rad/s over ``ramp`` s, integrated by generalized-α with ``step`` s to ``end`` s.
        ``methods``: ``"nr"`` (the full body, sparse) and reduction ids, each at every count
        of ``modes``. Returns ``times`` (s) and ``runs``: per model its ``label``,
        ``outputs`` (samples × output sets × 3, the sets' mean displacement in frame axes),
        ``reaction`` (samples × 6 at the drive), costs and, against the full body, its
        ``history_error`` and ``reaction_error``.

        ``pinned``: rbe2 sets whose masters' translations the frame holds; ``axis_point``: a
        point of the spin axis (length unit; default the drive's master, else the drive orbits);
        ``shake``: ``((dx, dy, dz), amplitude m, frequency Hz)`` of the drive; ``gravity``:
        m/s² in ground axes; ``spectral_radius``: generalized-α's ρ∞; ``axes``:
        ``"nodal_fixed"`` (the drive's frame) or ``"mean"``; ``stiffening``: the dynamic
        stiffening of the body file's ``[preload]``, when it has one (``stiffened`` in the
        result says whether the runs carried it); ``residual_vectors``: the static responses to
        the frame's inertia loads in every reduced basis (each run's ``residual_vectors`` and
        ``a_priori_estimate``, the share of the drive's static response the basis misses)."""
        if axes not in ("nodal_fixed", "mean"):
            raise InputError(f"axes {axes!r}: a driven body is seen from 'nodal_fixed' or 'mean' axes")
        ids = [str(m) for m in methods]
        return self._inner.simulate(
            dict(
                drive=str(drive),
                methods=[m for m in ids if m != "nr"],
                modes=[int(k) for k in modes],
                full="nr" in ids,
                boundary=[str(b) for b in boundary],
                outputs=[str(o) for o in outputs],
                rate=float(rate),
                ramp=float(ramp),
                axis=tuple(float(a) for a in axis),
                end=float(end),
                step=float(step),
                output_every=int(output_every),
                pinned=[str(p) for p in pinned],
                axis_point=None if axis_point is None else tuple(float(x) for x in axis_point),
                shake=None
                if shake is None
                else (tuple(float(x) for x in shake[0]), float(shake[1]), float(shake[2])),
                gravity=None if gravity is None else tuple(float(g) for g in gravity),
                spectral_radius=float(spectral_radius),
                mean_axes=axes == "mean",
                stiffening=bool(stiffening),
                residual_vectors=bool(residual_vectors),
            ),
            progress,
        )

    def campbell(
        self,
        drive: str,
        rates: Sequence[float],
        axis: Sequence[float] = (0.0, 0.0, 1.0),
        axis_point: Optional[Sequence[float]] = None,
        count: int = 4,
        methods: Sequence[str] = ("nr", "cb"),
        modes: Sequence[int] = (10,),
        stiffening: bool = True,
        progress: Progress = None,
        residual_vectors: bool = True,
    ) -> dict:
        """The Campbell table of ``flexmodes campbell``: the body spun about ``axis``
        (through ``axis_point``, default the drive's master) with the interface ``drive``
        clamped in the turning frame; the lowest ``count`` frequencies (Hz) at each of
        ``rates`` (rad/s), Coriolis coupling left out, for ``"nr"`` (the full body) and each
        reduction id at every count of ``modes``. ``stiffening``: the dynamic stiffening of
        the body file's ``[preload]`` (CalculiX's stiffness of the body spun), when it has
        one. Returns ``rates``, ``stiffened`` and ``curves``: per model its ``method``,
        ``modes``, ``coordinates``, ``residual_vectors``, ``hz`` (rates × count, each column
        one mode shape carried from rate to rate by MAC; a negative value is an unstable
        pair), ``mac`` and ``unstable`` (negative eigenvalues per rate). The full body is
        solved only when ``methods`` names ``"nr"``."""
        ids = [str(m) for m in methods]
        return self._inner.campbell(
            dict(
                drive=str(drive),
                rates=[float(r) for r in rates],
                axis=tuple(float(a) for a in axis),
                axis_point=None if axis_point is None else tuple(float(x) for x in axis_point),
                count=int(count),
                methods=[m for m in ids if m != "nr"],
                modes=[int(k) for k in modes],
                full="nr" in ids,
                stiffening=bool(stiffening),
                residual_vectors=bool(residual_vectors),
            ),
            progress,
        )

    def __repr__(self) -> str:
        return f"flexmodes.Body({self.name!r}, {self.dofs} DOF)"


class ReducedModel:
    """A reduced model: ``psi`` (DOF × coordinates), ``k_r``, ``m_r``, the reduced model's
    checked elastic ``hz`` and ``residuals``, column ``labels``, and ``save``."""

    def __init__(self, inner: RustReducedModel) -> None:
        self._inner = inner

    @property
    def psi(self) -> np.ndarray:
        """Ψ, DOF × reduced coordinates (δ = Ψ z)."""
        return self._inner.psi

    @property
    def k_r(self) -> np.ndarray:
        """ΨᵀKΨ."""
        return self._inner.k_r

    @property
    def m_r(self) -> np.ndarray:
        """ΨᵀMΨ."""
        return self._inner.m_r

    @property
    def hz(self) -> np.ndarray:
        """Elastic frequencies of the reduced model, Hz (each pair's residual checked)."""
        return self._inner.hz

    @property
    def residuals(self) -> np.ndarray:
        """Relative residual of each of :attr:`hz`."""
        return self._inner.residuals

    @property
    def zero_energy_modes(self) -> int:
        return self._inner.zero_energy_modes

    @property
    def labels(self) -> list:
        """One label per column of Ψ (``constraint node 5 x``, ``normal 2 (12.3 Hz)``,
        ``rbe2 bore rx``, ...)."""
        return self._inner.labels

    @property
    def method(self) -> str:
        return self._inner.method

    @property
    def boundary(self) -> list:
        """Interface nodes, 1-based."""
        return self._inner.boundary

    @property
    def timings(self) -> list:
        """``(phase, seconds)`` of the reduction."""
        return self._inner.timings

    def document(self) -> dict:
        """What ``model.json`` holds: columns, interfaces and their masters, inertia
        invariants, the free-free Sturm check."""
        return self._inner.document()

    def save(self, folder: Union[str, "os.PathLike[str]"], exudyn: bool = False) -> list:
        """Writes what ``flexmodes export`` writes (``psi.npy``, ``k_r.mtx``, ``m_r.mtx``,
        ``model.json`` and, with ``exudyn``, ``exudyn/``) into ``folder``, atomically: the
        folder is the old one or the complete new one. Returns the files written."""
        import os

        return self._inner.save(os.fspath(folder), bool(exudyn))

    def __repr__(self) -> str:
        rows, cols = self._inner.psi.shape
        return f"flexmodes.ReducedModel({self.method!r}, Ψ {rows} × {cols})"


def compare(
    body: Body,
    methods: Optional[Sequence[str]] = None,
    modes: Optional[Sequence[int]] = None,
    boundary: Union[None, str, int, Iterable[Union[str, int]]] = None,
    interface_modes: Optional[int] = None,
    band_hz: Optional[float] = None,
    tolerance: float = 0.01,
    progress: Progress = None,
) -> dict:
    """What ``flexmodes bench modes --body`` measures: every method (default all eight) at
    every kept-mode count (default 4, 8, 16, 32) against the full body's own checked modes.
    Returns ``reference_hz``, ``points`` (per model: offline seconds, peak memory, largest
    frequency error, smallest MAC, static-compliance error, FRF error with a band, Pareto
    flag), ``not_applicable`` and ``advice``. ``progress(phase, fraction)`` is called about
    every 0.2 s; if it raises, the work stops and its exception is re-raised."""
    return body._inner.compare(
        dict(
            methods=None if methods is None else [str(m) for m in methods],
            modes=None if modes is None else [int(k) for k in modes],
            boundary=_items(boundary),
            interface_modes=interface_modes,
            band_hz=band_hz,
            tolerance=float(tolerance),
        ),
        progress,
    )


__all__ = [
    "Body",
    "ReducedModel",
    "compare",
    "METHODS",
    "errors",
    "FlexmodesError",
    "InputError",
    "BodyFileError",
    "MechanismError",
    "LinalgError",
    "ReductionError",
    "DynamicsError",
    "FileError",
    "Cancelled",
    "__version__",
    "set_threads",
    "threads",
]
