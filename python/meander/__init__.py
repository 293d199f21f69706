"""Meander: Hamiltonian cycle art from Python.

One closed curve that meanders over the whole surface of any polygon mesh, and the wire
and ribbon sculptures and two-colour (duotone) surfaces made from it, with numpy arrays
in and out. The parameters are the command line's, with the same names, ranges, defaults
and messages (``meander.parameters("curve")`` lists them). See docs/python.md.

The package is also Meander's Blender add-on (docs/blender.md): Blender reads `bl_info`
and calls `register()`, which adds the panel of `ui.py` (imported only then). Being one
package, the add-on and a copy installed by `make install-python` cannot shadow each
other in Blender's Python.
"""

bl_info = {
    "name": "Meander",
    "author": "The Meander authors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > Meander",
    "description": "One closed curve over the whole surface, and the wires, ribbons and duotones made from it",
    "category": "Object",
}

from ._meander import (
    Mesh,
    MeshError,
    MeshWarning,
    curve,
    draw,
    duotone,
    duotone_print,
    generate,
    image,
    parameters,
    read,
    read_curves,
    render,
    wire,
    write_curves,
    write_duotone,
    write_mesh,
    write_png,
    write_print,
)
from ._meander import _hold_next_job  # for the tests

__all__ = [
    "Mesh",
    "MeshError",
    "MeshWarning",
    "curve",
    "draw",
    "duotone",
    "duotone_print",
    "generate",
    "image",
    "parameters",
    "read",
    "read_curves",
    "render",
    "wire",
    "write_curves",
    "write_duotone",
    "write_mesh",
    "write_png",
    "write_print",
]


def register():
    from . import ui

    ui.register()


def unregister():
    from . import ui

    ui.unregister()
