# Type stub of the meshreuse package (editors complete the API from it); the docstrings are in
# __init__.py.
import os
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

PathLike = Union[str, os.PathLike]
Source = Union[PathLike, Sequence[PathLike], "Mesh", npt.NDArray[np.integer]]

ACCESS_DTYPE: np.dtype

class Mesh:
    name: str
    path: str
    def __init__(self, points: npt.ArrayLike, triangles: npt.ArrayLike, name: str = ...) -> None: ...
    @staticmethod
    def read(path: str) -> "Mesh": ...
    @property
    def num_vertices(self) -> int: ...
    @property
    def num_triangles(self) -> int: ...
    @property
    def num_boundary(self) -> int: ...
    @property
    def points(self) -> npt.NDArray[np.float64]: ...
    @property
    def triangles(self) -> npt.NDArray[np.int32]: ...
    @property
    def boundary(self) -> npt.NDArray[np.uint8]: ...
    @property
    def interior(self) -> npt.NDArray[np.int32]: ...
    @property
    def neighbours(self) -> Tuple[npt.NDArray[np.int64], npt.NDArray[np.int32]]: ...
    @property
    def vertex_triangles(self) -> Tuple[npt.NDArray[np.int64], npt.NDArray[np.int32]]: ...
    def quality(self) -> float: ...
    def triangle_qualities(self) -> npt.NDArray[np.float64]: ...
    def vertex_qualities(self) -> npt.NDArray[np.float64]: ...
    def ordering(self, spec: str, seed: int = ...) -> npt.NDArray[np.int32]: ...
    def permute(self, perm: npt.ArrayLike, triangle_order: str = ...) -> "Mesh": ...
    def write(self, path: str) -> List[str]: ...

def save_permutation(mesh: Mesh, perm: npt.ArrayLike, path: str, comment: str = ...) -> None: ...
def orderings() -> List[Dict[str, Any]]: ...

class SmoothResult:
    points: npt.NDArray[np.float64]
    quality: npt.NDArray[np.float64]
    improvement: npt.NDArray[np.float64]
    seconds: npt.NDArray[np.float64]
    cpu_seconds: npt.NDArray[np.float64]
    sweeps: int
    quality_before: float
    quality_after: float
    converged: bool

def smooth(mesh: Mesh, *, mode: str = ..., quality: str = ..., max_iters: int = ...,
           tol: float = ..., threads: int = ...) -> SmoothResult: ...
def trace(mesh: Mesh, *, ordering: str = ..., seed: int = ..., iterations: int = ...,
          threads: int = ..., mode: str = ..., triangle_order: str = ...) -> np.ndarray: ...

class Table(Dict[str, Any]):
    @property
    def nrows(self) -> int: ...
    def rows(self) -> List[Dict[str, Any]]: ...

class Results:
    tables: Dict[str, Table]
    table: Optional[Table]
    text: str
    configuration: Dict[str, Any]
    extra: Dict[str, Any]

class Stream:
    input: str
    ordering: str
    thread: int
    granularity: str
    accesses: int
    cold: int
    distinct: int
    sum: int
    max: int
    histogram: Tuple[npt.NDArray[np.uint64], npt.NDArray[np.uint64]]
    row: Optional[Dict[str, Any]]
    @property
    def mean(self) -> float: ...
    def __getattr__(self, name: str) -> Any: ...

class Analysis(Results):
    streams: List[Stream]
    def stream(self, granularity: Optional[str] = ..., thread: int = ...,
               input: Optional[str] = ..., ordering: Optional[str] = ...) -> Stream: ...
    def __getattr__(self, name: str) -> Any: ...

def analyze(source: Source, *, profile: bool = ..., progress: bool = ...,
            **options: Any) -> Optional[Analysis]: ...
def summarize(source: PathLike, chunk: Union[str, Tuple[int, int]], out: PathLike,
              **options: Any) -> None: ...
def merge(summaries: Sequence[PathLike], *, profile: bool = ..., progress: bool = ...,
          **options: Any) -> Analysis: ...
def simulate(source: Source, *, per_sweep: bool = ..., progress: bool = ...,
             **options: Any) -> Results: ...
def compare(meshes: Union[PathLike, Mesh, Sequence[Union[PathLike, Mesh]]], *,
            progress: bool = ..., **options: Any) -> Results: ...
