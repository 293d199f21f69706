# Meander's Blender add-on (docs/blender.md): Curve, Wire and Duotone on the active mesh
# object, from a panel in the 3D view's sidebar. The jobs run in the compiled module
# beside this file (the Python package's, built by `make blender-addon`), so this package
# is also `import meander` in Blender's console, with the package's whole API.

bl_info = {
    "name": "Meander",
    "author": "The Meander authors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > Meander",
    "description": "One closed curve over the whole surface, and the wires, ribbons and duotones made from it",
    "category": "Object",
}

from ._meander import *  # noqa: F401,F403  the package's API, as `import meander` outside Blender
from . import ui


def register():
    ui.register()


def unregister():
    ui.unregister()
