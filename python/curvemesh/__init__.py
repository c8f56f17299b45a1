"""curvemesh: curved (high-order) viscous meshes, their movement and sensitivities, from Python.

The Rust library ``curvemesh`` (the whole pipeline of the ``curvemesh`` command) in-process:
a case — a built-in name, a case file (``.toml``), airfoil coordinates (``.dat``), a closed
surface (``.stl``) or a dict shaped like the case file — is meshed, every cell certified,
and handed back as NumPy arrays with its JSON report::

    import curvemesh

    mesh = curvemesh.mesh("naca0012", order=3)
    assert mesh.valid
    mesh.points        # N x 2 float64 (N x 3 in 3D)
    mesh.cells         # [("quad16", array), ("triangle10", array)], Gmsh's node order
    mesh.groups        # {"naca0012": [("line4", array)], "farfield": [...]}
    mesh.report        # the report of `curvemesh mesh --report`, as a dict
    mesh.write("naca0012.msh")

    moved = curvemesh.move(mesh, [{"loop": "naca0012", "rotate_deg": 5.0}], sensitivities=True)
    moved.sensitivities          # nodes x 2 x design variables
    moved.design_variables       # ["naca0012.rotate_deg"]

Bad input raises ``ValueError`` (a missing file ``FileNotFoundError``) with the command
line's one-line message. The GIL is released while a mesh is made.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable, Mapping, Sequence
from functools import cached_property
from typing import TYPE_CHECKING, Any, Optional, Union

import numpy as np

from . import _curvemesh

if TYPE_CHECKING:
    import meshio

__version__: str = _curvemesh.__version__

__all__ = [
    "Case",
    "Mesh",
    "Prepared",
    "builtin_cases",
    "load",
    "mesh",
    "move",
    "prepare",
    "quality",
    "read",
]

PathLike = Union[str, "os.PathLike[str]"]
Progress = Callable[[str, bool], Any]

_AIRFOIL_OPTIONS = ("aoa", "farfield", "yplus", "re", "merge_walls", "first_height", "growth",
                    "layers")

# Gmsh's node order → meshio's, for the cell types where meshio's differs (as its own Gmsh
# reader permutes them); every other type is the same in both.
_MESHIO_ORDER = {
    "tetra10": [0, 1, 2, 3, 4, 5, 6, 7, 9, 8],
    "hexahedron27": [0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15,
                     22, 23, 21, 24, 20, 25, 26],
}


def builtin_cases() -> dict[str, str]:
    """The built-in cases, name → what it is (as ``curvemesh mesh --list``)."""
    return dict(_curvemesh.builtin_cases())


class Case:
    """A loaded case, 2D or 3D: what :func:`mesh` and :func:`move` take. Made by :func:`load`."""

    def __init__(self, native: _curvemesh.NativeCase):
        self._native = native

    @property
    def name(self) -> str:
        """The case's name (it names the mesh's report)."""
        return self._native.name

    @property
    def dimension(self) -> int:
        """2 or 3."""
        return self._native.dimension

    @property
    def order(self) -> int:
        """The case's own order (``[curving] order``), used when a run gives none."""
        return self._native.order

    @property
    def loops(self) -> list[str]:
        """The names of the loops of a 2D case (what a motion's ``loop`` names); [] in 3D."""
        return self._native.loops

    def __repr__(self) -> str:
        return f"<curvemesh.Case {self.name!r} ({self.dimension}D)>"


def _drop_none(value: Any) -> Any:
    """A dict or list with its ``None`` values left out (TOML has no null: a key not given)."""
    if isinstance(value, Mapping):
        return {str(k): _drop_none(v) for k, v in value.items() if v is not None}
    if isinstance(value, (list, tuple)):
        return [_drop_none(v) for v in value]
    if isinstance(value, np.ndarray):
        return _drop_none(value.tolist())
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    return value


def _toml(document: Mapping[str, Any], what: str) -> str:
    """``document`` as TOML text (through JSON, which the native side turns into TOML)."""
    try:
        text = json.dumps(_drop_none(document), allow_nan=False)
    except (TypeError, ValueError) as e:
        raise ValueError(f"{what}: {e}") from None
    return _curvemesh.toml_of_json(text)


def load(case: Union[Case, PathLike, Mapping[str, Any], Sequence[PathLike]], *,
         aoa: Optional[float] = None, farfield: Optional[float] = None,
         yplus: Optional[float] = None, re: Optional[float] = None,
         merge_walls: bool = False, first_height: Optional[float] = None,
         growth: Optional[float] = None, layers: Optional[int] = None) -> Case:
    """Loads a case without meshing it.

    ``case`` is a built-in name (``"naca0012"``, ``"30p30n"``, ``"sphere"``, …, see
    :func:`builtin_cases`), a case file (``.toml``), airfoil coordinates (a ``.dat`` or ``.txt``
    file, Selig or Lednicer, or a list of them for a multi-element airfoil), a closed surface
    (``.stl``: a 3D case with the default layers), or a dict shaped like the case file (its
    relative file names are relative to the current folder). The airfoil options are those of
    ``curvemesh mesh FILE.dat``: angle of attack in degrees, far-field radius in chords, the
    first height from a target y+ and Reynolds number (or ``first_height``), ``growth``,
    ``layers``, ``merge_walls``; they apply to coordinate files only.
    """
    if isinstance(case, Case):
        native = case._native
        given = None
    else:
        given = case
    airfoil = {k: v for k, v in dict(aoa=aoa, farfield=farfield, yplus=yplus, re=re,
                                     first_height=first_height, growth=growth,
                                     layers=layers).items() if v is not None}
    if merge_walls:
        airfoil["merge_walls"] = True
    if given is None:
        pass
    elif isinstance(given, Mapping):
        text = _toml(given, "case dict")
        native = _curvemesh.parse_case(text, "case dict", os.getcwd())
    elif isinstance(given, (list, tuple)):
        files = [os.fspath(f) for f in given]
        if not files or not all(_curvemesh.is_coordinate_file(f) for f in files):
            raise ValueError("a list of cases is a list of airfoil coordinate files (.dat, .txt): "
                             + " ".join(files))
        native = _curvemesh.airfoil_case(files, **airfoil)
        airfoil = {}
    elif isinstance(given, (str, os.PathLike)):
        spec = os.fspath(given)
        if _curvemesh.is_coordinate_file(spec):
            native = _curvemesh.airfoil_case([spec], **airfoil)
            airfoil = {}
        elif spec.lower().endswith(".stl"):
            stem = os.path.splitext(os.path.basename(spec))[0]
            document = {"name": stem, "dimension": 3,
                        "surface": {"file": os.path.abspath(spec)}}
            native = _curvemesh.parse_case(_toml(document, spec), spec, os.getcwd())
        else:
            native = _curvemesh.load(spec)
    else:
        raise TypeError(f"case: give a name, a path, a dict or a Case, not {type(given).__name__}")
    if airfoil:
        flag = next(iter(airfoil))
        raise ValueError(f"{flag} applies to airfoil coordinate files (.dat, .txt) only "
                         "(a case file sets its own geometry)")
    return Case(native)


class Mesh:
    """A certified mesh with its report: what :func:`mesh`, :func:`move` and :func:`read` return.

    Arrays are made on first use and kept. Node indices count from 0; each cell's nodes are in
    Gmsh's order (corners, then edge nodes edge by edge, then interior nodes), as in the
    ``.msh`` file :meth:`write` makes.
    """

    def __init__(self, native: _curvemesh.NativeMesh):
        self._native = native

    def __repr__(self) -> str:
        state = "valid" if self.valid else "NOT valid"
        return (f"<curvemesh.Mesh {self.report.get('case', '')!r}: {self.dimension}D P{self.order}, "
                f"{len(self.points)} nodes, {sum(len(c) for _, c in self.cells)} cells, {state}>")

    @property
    def dimension(self) -> int:
        """2 or 3."""
        return self._native.dimension

    @property
    def order(self) -> int:
        """The cells' polynomial order, 1 to 3."""
        return self._native.order

    @property
    def valid(self) -> bool:
        """Whether the mesh passed validation: every cell certified valid (a Bernstein bound of
        its Jacobian), conforming and positively oriented. A mesh that fails is still returned,
        its problems in ``report["problems"]``."""
        return self._native.valid

    @cached_property
    def points(self) -> np.ndarray:
        """The nodes, N x 2 (2D) or N x 3 (3D), float64."""
        return self._native.points()

    @cached_property
    def cells(self) -> list[tuple[str, np.ndarray]]:
        """The domain cells as blocks ``(element name, int64 array cells x nodes)``, one block per
        type in the order each first appears. Names as meshio's (Gmsh's elements):
        ``triangle``, ``triangle6``, ``triangle10``, ``quad``, ``quad9``, ``quad16``,
        ``tetra``, ``tetra10``, ``pyramid``, ``pyramid14``, ``wedge``, ``wedge18``,
        ``hexahedron``, ``hexahedron27``."""
        return self._native.cells()

    @cached_property
    def groups(self) -> dict[str, list[tuple[str, np.ndarray]]]:
        """The boundary groups — the ``.msh`` file's physical groups, the ``.su2`` markers: one
        per wall body named after it (``slat``, ``main``, ``flap``) or ``wall``, and
        ``farfield`` — each as blocks of facets ``(element name, int64 array)``: ``line``,
        ``line3``, ``line4`` in 2D (the domain on their left), ``triangle``/``quad`` (and
        ``triangle6``/``quad9``) in 3D."""
        return self._native.groups()

    @cached_property
    def report(self) -> dict[str, Any]:
        """The run's report, as ``curvemesh mesh --report FILE.json`` writes it."""
        return json.loads(self._native.report_json)

    @cached_property
    def scaled_jacobian(self) -> np.ndarray:
        """2D: each cell's certified least scaled Jacobian, the cells in the order of
        :attr:`cells`' blocks one after the other (empty in 3D)."""
        return self._native.scaled_jacobian()

    @cached_property
    def cell_layer(self) -> np.ndarray:
        """Each cell's layer counted from the boundary it grew from (0 touching it; -1 a fill
        cell), the cells in the order of :attr:`cells`' blocks (empty when unknown)."""
        return self._native.cell_layer()

    @cached_property
    def _sensitivities(self) -> Optional[tuple[list[str], np.ndarray]]:
        return self._native.sensitivities()

    @property
    def sensitivities(self) -> Optional[np.ndarray]:
        """After ``move(..., sensitivities=True)``: every node's derivative with respect to each
        design variable, nodes x 2 x variables (float64), in :attr:`design_variables`' order;
        else ``None``. The values of ``curvemesh move --sensitivities FILE.csv``."""
        s = self._sensitivities
        return None if s is None else s[1]

    @property
    def design_variables(self) -> list[str]:
        """The design variables of :attr:`sensitivities`: for each moved loop
        ``LOOP.rotate_deg``, ``LOOP.translate_x``, ``LOOP.translate_y``, ``LOOP.scale`` (with a
        rigid motion) and ``LOOP.bump1``, … (each bump's amplitude); [] without."""
        s = self._sensitivities
        return [] if s is None else list(s[0])

    def sensitivities_transposed(self, v: np.ndarray) -> np.ndarray:
        """The transposed product for adjoints: for a nodes x 2 array ``v`` (say dJ/dX), one
        number per design variable, ``sum over nodes of v . dX/dalpha`` (dJ/dalpha), in
        :attr:`design_variables`' order."""
        s = self.sensitivities
        if s is None:
            raise ValueError("no sensitivities: move with sensitivities=True")
        v = np.asarray(v, dtype=np.float64)
        if v.shape != s.shape[:2]:
            raise ValueError(f"v has shape {v.shape}: give one row (dx, dy) per node, "
                             f"{s.shape[:2]}")
        return np.einsum("ij,ijk->k", v, s)

    def write(self, path: PathLike, *, binary: bool = False) -> None:
        """Writes the mesh in the format of the extension — ``.msh`` (Gmsh MSH 4.1, ASCII or
        ``binary``), ``.vtu`` (VTK, Lagrange cells at P2/P3), ``.su2`` (the linear mesh) — or
        the report (``.json``); atomically (a failed write leaves no file)."""
        self._native.write(os.fspath(path), binary)

    def to_meshio(self) -> "meshio.Mesh":
        """The mesh as a ``meshio.Mesh`` (meshio must be installed): the domain cells, then the
        boundary facets of each group, with ``cell_sets`` ``fluid`` and one per group (as
        meshio's Gmsh reader names the physical groups). High-order cells in meshio's node
        order."""
        try:
            import meshio
        except ImportError as e:
            raise ImportError("to_meshio needs meshio: pip install meshio") from e
        cells = [(n, _to_meshio_order(n, c)) for n, c in self.cells]
        domain = len(cells)
        facet_blocks = []
        for group, blocks in self.groups.items():
            for name, facets in blocks:
                facet_blocks.append((group, len(cells), len(facets)))
                cells.append((name, _to_meshio_order(name, facets)))
        empty = np.empty(0, dtype=np.int64)
        cell_sets = {"fluid": [np.arange(len(c)) if k < domain else empty
                               for k, (_, c) in enumerate(cells)]}
        for group, k, count in facet_blocks:
            cell_sets.setdefault(group, [empty] * len(cells))[k] = np.arange(count)
        return meshio.Mesh(self.points, cells, cell_sets=cell_sets)


def _to_meshio_order(name: str, cells: np.ndarray) -> np.ndarray:
    perm = _MESHIO_ORDER.get(name)
    return cells if perm is None else cells[:, perm]


def mesh(case: Union[Case, PathLike, Mapping[str, Any], Sequence[PathLike]],
         order: Optional[int] = None, progress: Optional[Progress] = None, *,
         triangles: bool = False, max_cells: Optional[int] = None,
         threads: Optional[int] = None, **airfoil: Any) -> Mesh:
    """Meshes a case and certifies every cell, as ``curvemesh mesh`` does.

    ``case``: see :func:`load` (a :class:`Case`, a built-in name, a path, a dict or a list of
    ``.dat`` files; ``airfoil`` are :func:`load`'s airfoil options, for coordinate files).
    ``order``: 1, 2 or 3 (2D) or 1, 2 (3D); default the case's own. ``triangles``: cut every
    quad along its shorter diagonal (2D). ``max_cells``: refuse a case expected to make more
    cells (default 20 million). ``threads``: the threads of the run (default one per core).
    ``progress``: called as ``progress(stage, done)`` when each stage begins (``done`` False)
    and ends (True); notes (a very large expected mesh) go to the ``curvemesh`` logger.

    Returns the mesh even when it fails validation (``mesh.valid`` is then False and
    ``mesh.report["problems"]`` says why); bad input raises ``ValueError``.
    """
    unknown = set(airfoil) - set(_AIRFOIL_OPTIONS)
    if unknown:
        raise TypeError(f"mesh() got an unexpected keyword argument {sorted(unknown)[0]!r}")
    loaded = load(case, **airfoil)
    return Mesh(_curvemesh.mesh(loaded._native, order=_order(order), triangles=triangles,
                                max_cells=max_cells, threads=threads, progress=progress))


def _order(order: Optional[int]) -> Optional[int]:
    if order is not None and (not isinstance(order, (int, np.integer)) or not 0 <= order <= 255):
        raise ValueError(f"order={order!r}: give 1, 2 or 3")
    return None if order is None else int(order)


def move(case_or_mesh: Union[Mesh, Case, PathLike, Mapping[str, Any], Sequence[PathLike]],
         motions: Union[Mapping[str, Any], Sequence[Mapping[str, Any]]],
         order: Optional[int] = None, sensitivities: bool = False, *,
         method: str = "springs", kernel: str = "wendland-c2", radius: Optional[float] = None,
         smooth: bool = False, triangles: Optional[bool] = None,
         max_cells: Optional[int] = None, threads: Optional[int] = None,
         progress: Optional[Progress] = None) -> Mesh:
    """Moves the bodies of a 2D case, as ``curvemesh move`` does, and re-curves and certifies
    the moved mesh (same nodes, cells and topology).

    ``case_or_mesh``: a :class:`Mesh` made by :func:`mesh` (moved from its own linear mesh,
    at its order and with its ``triangles`` unless given), or a case as :func:`mesh` takes it
    (meshed first). ``motions``: one dict per moving loop, shaped like a motion file's
    ``[[motion]]`` tables — ``{"loop": "flap", "rotate_deg": 5.0, "about": [0.93, -0.045],
    "scale": 1.0, "translate": [0.0, 0.0], "bump": [{"position": 0.4, "amplitude": 0.004,
    "width": 3.0, "surface": "upper"}]}`` — or ``{"motion": [...]}`` as a whole file.
    ``method``: ``"springs"`` (the default), ``"idw"`` or ``"rbf"`` (``kernel``
    ``"wendland-c2"`` with ``radius``, or ``"thin-plate"``); ``smooth``: the smooth spring
    mover. ``sensitivities``: also compute every node's derivative with respect to each design
    variable (implies ``smooth``; springs only): :attr:`Mesh.sensitivities`.
    """
    case, start, common = _move_from(case_or_mesh, order, sensitivities, method, kernel,
                                      radius, smooth, triangles, max_cells)
    native = _curvemesh.move_case(case, _motions_text(motions), start=start, threads=threads,
                                  progress=progress, **common)
    return Mesh(native)


class Prepared:
    """A 2D case prepared for many moves (a shape optimisation's designs, a solver's motions
    one at a time), made by :func:`prepare`: its unmoved mesh, the spring mover's shape field
    and its Newton workspace are made once, and each :meth:`move` moves from that same
    unmoved mesh (no drift), as :func:`move` would, without making them again."""

    def __init__(self, native: _curvemesh.NativePrepared):
        self._native = native

    def move(self, motions: Union[Mapping[str, Any], Sequence[Mapping[str, Any]]], *,
             threads: Optional[int] = None, progress: Optional[Progress] = None) -> Mesh:
        """The case moved by ``motions`` (as :func:`move` takes them) from its unmoved mesh."""
        return Mesh(self._native.move_by(_motions_text(motions), threads=threads,
                                         progress=progress))


def prepare(case_or_mesh: Union[Mesh, Case, PathLike, Mapping[str, Any], Sequence[PathLike]],
            order: Optional[int] = None, sensitivities: bool = False, *,
            method: str = "springs", kernel: str = "wendland-c2",
            radius: Optional[float] = None, smooth: bool = False,
            triangles: Optional[bool] = None, max_cells: Optional[int] = None,
            threads: Optional[int] = None, progress: Optional[Progress] = None) -> Prepared:
    """A 2D case prepared for moves with :func:`move`'s arguments (but the motions)::

        prepared = curvemesh.prepare(mesh)
        for deg in (2.0, 4.0, 6.0):
            moved = prepared.move({"loop": "naca0012", "rotate_deg": deg})
    """
    case, start, common = _move_from(case_or_mesh, order, sensitivities, method, kernel,
                                      radius, smooth, triangles, max_cells)
    return Prepared(_curvemesh.prepare(case, start=start, threads=threads, progress=progress,
                                       **common))


def _motions_text(motions: Union[Mapping[str, Any], Sequence[Mapping[str, Any]]]) -> str:
    """The motion file's text of ``motions`` (one dict per loop, or a whole file's dict)."""
    if isinstance(motions, Mapping):
        document = motions if "motion" in motions else {"motion": [motions]}
    else:
        document = {"motion": list(motions)}
    return _toml(document, "motions")


def _move_from(case_or_mesh, order, sensitivities, method, kernel, radius, smooth, triangles,
               max_cells):
    """What a move starts from — the native case (``None`` for a mesh), the mesh (or
    ``None``) — and the native call's options."""
    common = dict(order=_order(order), method=method, kernel=kernel, radius=radius,
                  smooth=smooth, sensitivities=sensitivities, max_cells=max_cells)
    if isinstance(case_or_mesh, Mesh):
        start = case_or_mesh._native
        if not start.movable:
            raise ValueError("this mesh cannot be moved: give a 2D case, or a mesh made by "
                             "curvemesh.mesh of one")
        if common["order"] is None:
            common["order"] = start.order
        common["triangles"] = start.triangles if triangles is None else triangles
        return None, start, common
    common["triangles"] = bool(triangles)
    return load(case_or_mesh)._native, None, common


def read(path: PathLike) -> Mesh:
    """Reads a Gmsh ``.msh`` file (2D or 3D, any writer) and checks it as ``curvemesh quality``
    does: its :attr:`Mesh.report` is the quality report."""
    return Mesh(_curvemesh.read_msh(os.fspath(path)))


def quality(path_or_mesh: Union[Mesh, PathLike]) -> dict[str, Any]:
    """The report of ``curvemesh quality``: any ``.msh`` file (or a :class:`Mesh`) described and
    every cell certified; ``report["problems"]`` is empty when it is valid."""
    if isinstance(path_or_mesh, Mesh):
        name = str(path_or_mesh.report.get("case") or "mesh")
        return json.loads(path_or_mesh._native.check(name))
    return read(path_or_mesh).report

