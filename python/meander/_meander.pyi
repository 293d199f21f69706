# Type stubs of the compiled module (python/meander_module.cpp), for editors and type
# checkers; the docstrings there say the same at run time (help(meander.curve)).
import os
from typing import Any, Callable, Literal, Sequence, overload

import numpy as np
import numpy.typing as npt

Float32Array = npt.NDArray[np.float32]
Int32Array = npt.NDArray[np.int32]
Path = str | os.PathLike[str]
Progress = Callable[[str, float | None], object]
Length = float | str  # a bare number in the model's units (mm with model_size), or "3mm", "0.5in"
Curves = list[Float32Array]

class MeshError(ValueError):
    """A mesh refused: malformed, or of a topology the job cannot take."""

class MeshWarning(UserWarning):
    """What was repaired in a mesh before the job, or worth telling about it."""

class Mesh:
    """A polygon mesh: vertices (N, 3) float32, faces as offsets into a flat index array."""

    def __init__(self, vertices: npt.ArrayLike, faces: npt.ArrayLike | Sequence[Sequence[int]], *,
                 offsets: npt.ArrayLike | None = None, name: str = "mesh") -> None: ...
    @property
    def vertices(self) -> Float32Array:
        """(N, 3) float32, read-only, sharing the mesh's memory."""
    @property
    def faces(self) -> Int32Array:
        """(F, k) int32 when every face has k corners (a ValueError otherwise)."""
    @property
    def offsets(self) -> Int32Array: ...
    @property
    def indices(self) -> Int32Array: ...
    @property
    def name(self) -> str: ...
    @property
    def num_vertices(self) -> int: ...
    @property
    def num_faces(self) -> int: ...

def read(path: Path) -> Mesh: ...
def read_curves(path: Path) -> Curves: ...
def generate(shape: Literal["sphere", "torus", "pretzel", "genus", "grid", "moebius"], faces: int = 6400,
             genus: int = 2) -> Mesh: ...

@overload
def curve(mesh: Mesh, *, certificate: Literal[False] = False, strict: bool = False, max_faces: int = 0,
          progress: Progress | None = None, model_size: Length | None = None, spacing: Length | None = None,
          relax: int = 20, quad: Literal["dual-simplest", "catmull-clark", "none"] = "dual-simplest",
          tree: Literal["random", "uniform", "bfs", "dfs", "shaped"] = "random", branches: float | None = None,
          seed: int = 1, smooth: Literal["bspline", "catmull-rom", "none"] = "bspline", samples: int = 4) -> Curves: ...
@overload
def curve(mesh: Mesh, *, certificate: Literal[True], strict: bool = False, max_faces: int = 0,
          progress: Progress | None = None, **parameters: Any) -> tuple[Curves, Mesh, Int32Array]: ...

def wire(mesh: Mesh, *, strict: bool = False, max_faces: int = 0, progress: Progress | None = None,
         method: Literal["constant", "variable"] = "constant", shape: Literal["wire", "ribbon"] = "wire",
         radius: Length | None = None, sides: int = 8, bridges: Length | None = None, s: float = 0.6, t: float = 0.6,
         thickness: Length = 0,
         cap_angle: float = 120, keep_faces: bool = False, levels: int = 2, min_thickness: Length = 0,
         nozzle: Length = 0.4, **curve_parameters: Any) -> tuple[Float32Array, Int32Array, dict[str, Any]]:
    """faces: (F, 4) quads or (F, 3) triangles, as the method makes them."""

def duotone(mesh: Mesh, *, strict: bool = False, max_faces: int = 0, progress: Progress | None = None,
            model_size: Length | None = None, spacing: Length | None = None,
            quad: Literal["catmull-clark", "dual-simplest", "none"] = "catmull-clark",
            rule: Literal["tree", "flip"] = "tree", tree: Literal["random", "uniform", "bfs", "dfs"] = "random",
            seed: int = 1, colors: str | Sequence[str] = "yellow,blue",
            tiles: Literal["truchet", "outline", "triangles", "stripes", "dots"] = "truchet", texture_size: int = 1024,
            subdivide: int = 0) -> tuple[Float32Array, Int32Array, Float32Array, npt.NDArray[np.uint8], Curves]: ...
def duotone_print(mesh: Mesh, *, strict: bool = False, max_faces: int = 0, progress: Progress | None = None,
                  shell: Length, min_thickness: Length = 0, clearance: Length = 0,
                  **duotone_parameters: Any) -> tuple[list[Mesh], str]: ...

def draw(what: Mesh | Curves | Float32Array, *, occluder: Mesh | None = None, view: str = "iso", fit: bool = False,
         camera: tuple[Sequence[float], Sequence[float], Sequence[float], float] | None = None, paper: str = "A4", landscape: bool = False, margin: float | str = 10.0, pen: float | str = 0.3,
         progress: Progress | None = None, **curve_parameters: Any) -> tuple[list[npt.NDArray[np.float64]], str]:
    """A pen plotter's drawing, as `meander draw`: (paths in millimetres, the SVG text)."""

def image(picture: Path | npt.ArrayLike, *, progress: Progress | None = None,
          **parameters: Any) -> tuple[list[npt.NDArray[np.float64]], str, str]:
    """A picture drawn with one closed line, as `meander image`: (paths in millimetres, the SVG, the duotone SVG)."""

def render(*, meshes: Mesh | Sequence[Mesh] = (), curves: Curves | Float32Array | None = None,
           occluder: Mesh | None = None, size: str = "1600x1200", view: str = "iso", background: str = "white",
           samples: int = 4, curve_width: float = 0.0, curve_style: Literal["tube", "ribbon"] = "tube",
           occluder_style: Literal["hidden", "faint", "shaded"] = "hidden", fit: bool = False) -> npt.NDArray[np.uint8]: ...

def write_mesh(path: Path, mesh: Mesh, *, millimetres: bool = False) -> None: ...
def write_curves(path: Path, curves: Curves | Float32Array, *, millimetres: bool = False) -> None: ...
def write_duotone(path: Path, vertices: npt.ArrayLike, faces: npt.ArrayLike, uv: npt.ArrayLike, texture: npt.ArrayLike, *,
                  millimetres: bool = False) -> None: ...
def write_print(path: Path, first: Mesh, second: Mesh, *, colors: str | Sequence[str] = "yellow,blue") -> None: ...
def write_png(path: Path, picture: npt.ArrayLike) -> None: ...
def _hold_next_job() -> None: ...
def parameters(job: Literal["curve", "wire", "duotone"]) -> list[dict[str, Any]]: ...
