"""Meander: Hamiltonian cycle art from Python.

One closed curve that meanders over the whole surface of any polygon mesh, and the wire
and ribbon sculptures and two-colour (duotone) surfaces made from it, with numpy arrays
in and out. The parameters are the command line's, with the same names, ranges, defaults
and messages (``meander.parameters("curve")`` lists them). See docs/python.md.
"""

from ._meander import (
    Mesh,
    MeshError,
    MeshWarning,
    curve,
    duotone,
    generate,
    parameters,
    read,
    read_curves,
    render,
    wire,
    write_curves,
    write_duotone,
    write_mesh,
    write_png,
)
from ._meander import _hold_next_job  # for the tests

__all__ = [
    "Mesh",
    "MeshError",
    "MeshWarning",
    "curve",
    "duotone",
    "generate",
    "parameters",
    "read",
    "read_curves",
    "render",
    "wire",
    "write_curves",
    "write_duotone",
    "write_mesh",
    "write_png",
]
