"""Type stubs of the native module `curvemesh._curvemesh` (python/src/lib.rs): the library
bound as it is; the public API is `curvemesh` (python/curvemesh/__init__.py)."""

from collections.abc import Callable
from os import PathLike
from typing import Any, Optional, Union

import numpy as np
import numpy.typing as npt

__version__: str

_Path = Union[str, PathLike[str]]
_Progress = Callable[[str, bool], Any]
_Blocks = list[tuple[str, npt.NDArray[np.int64]]]

class NativeCase:
    @property
    def name(self) -> str: ...
    @property
    def dimension(self) -> int: ...
    @property
    def order(self) -> int: ...
    @property
    def loops(self) -> list[str]: ...

class NativeMesh:
    @property
    def dimension(self) -> int: ...
    @property
    def order(self) -> int: ...
    @property
    def valid(self) -> bool: ...
    @property
    def triangles(self) -> bool: ...
    @property
    def report_json(self) -> str: ...
    @property
    def movable(self) -> bool: ...
    def points(self) -> npt.NDArray[np.float64]: ...
    def cells(self) -> _Blocks: ...
    def groups(self) -> dict[str, _Blocks]: ...
    def scaled_jacobian(self) -> npt.NDArray[np.float64]: ...
    def cell_layer(self) -> npt.NDArray[np.int64]: ...
    def sensitivities(self) -> Optional[tuple[list[str], npt.NDArray[np.float64]]]: ...
    def write(self, path: _Path, binary: bool = False) -> None: ...
    def check(self, name: str) -> str: ...

def load(spec: str) -> NativeCase: ...
def parse_case(text: str, origin: str, dir: _Path) -> NativeCase: ...
def airfoil_case(
    files: list[str],
    aoa: Optional[float] = None,
    farfield: Optional[float] = None,
    yplus: Optional[float] = None,
    re: Optional[float] = None,
    merge_walls: bool = False,
    first_height: Optional[float] = None,
    growth: Optional[float] = None,
    layers: Optional[int] = None,
) -> NativeCase: ...
def is_coordinate_file(spec: str) -> bool: ...
def builtin_cases() -> list[tuple[str, str]]: ...
def mesh(
    case: NativeCase,
    order: Optional[int] = None,
    triangles: bool = False,
    max_cells: Optional[int] = None,
    threads: Optional[int] = None,
    progress: Optional[_Progress] = None,
) -> NativeMesh: ...
def move_case(
    case: Optional[NativeCase],
    motions: str,
    start: Optional[NativeMesh] = None,
    order: Optional[int] = None,
    triangles: bool = False,
    method: str = "springs",
    kernel: str = "wendland-c2",
    radius: Optional[float] = None,
    smooth: bool = False,
    sensitivities: bool = False,
    max_cells: Optional[int] = None,
    threads: Optional[int] = None,
    progress: Optional[_Progress] = None,
) -> NativeMesh: ...
class NativePrepared:
    def move_by(
        self,
        motions: str,
        threads: Optional[int] = None,
        progress: Optional[_Progress] = None,
    ) -> NativeMesh: ...

def prepare(
    case: Optional[NativeCase],
    start: Optional[NativeMesh] = None,
    order: Optional[int] = None,
    triangles: bool = False,
    method: str = "springs",
    kernel: str = "wendland-c2",
    radius: Optional[float] = None,
    smooth: bool = False,
    sensitivities: bool = False,
    max_cells: Optional[int] = None,
    threads: Optional[int] = None,
    progress: Optional[_Progress] = None,
) -> NativePrepared: ...
def read_msh(path: _Path) -> NativeMesh: ...
def toml_of_json(json: str) -> str: ...
def debug_build() -> bool: ...
def _test_panic() -> None: ...
