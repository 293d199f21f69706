"""The Blender add-on, headless (ctest `blender`):
blender -b --factory-startup --python-exit-code 1 --python tests/blender/run.py -- ZIP MESHES
installs and enables the zip, runs each operator on a generated mesh and a real one,
checks the objects made against the Python package, re-runs with new settings and checks
that the objects were updated, that a refusal is a report, and that undo and redo take a
run back and make it again. Any failure exits 1."""

import pathlib
import sys
import tempfile
import traceback

import bmesh
import bpy
import numpy as np

zip_path, meshes = sys.argv[sys.argv.index("--") + 1:][:2]
zip_path = str(pathlib.Path(zip_path).resolve())  # Blender 3.4 fails to install a zip named without a folder


def check(condition, message):
    if not condition:
        raise AssertionError(message)


def install():
    bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
    # The zip's copy, even where `make install-python` put another in site-packages (which
    # Blender's Python would find first: the same package, maybe of another build).
    addons = bpy.utils.user_resource("SCRIPTS", path="addons")
    sys.path.insert(0, addons)
    bpy.ops.preferences.addon_enable(module="meander")
    import meander  # the add-on, which is also the package
    check(pathlib.Path(meander.__file__).is_relative_to(addons), f"meander was imported from {meander.__file__}")
    return meander


def select(obj):
    for other in bpy.context.view_layer.objects:
        other.select_set(False)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)


def world_mesh(meander, obj):
    from meander import ui
    return ui.source_mesh(bpy.context, obj)


def check_curve(meander, source, result, **parameters):
    """One closed poly spline per component, whose points are meander.curve's."""
    check(result.type == "CURVE", f"{result.name}: not a curve object")
    expected = meander.curve(world_mesh(meander, source), **parameters)
    splines = result.data.splines
    check(len(splines) == len(expected), f"{result.name}: {len(splines)} splines, expected {len(expected)}")
    for spline, points in zip(splines, expected):
        check(spline.type == "POLY" and spline.use_cyclic_u, f"{result.name}: a spline is not a closed poly line")
        got = np.empty(len(spline.points) * 4, dtype=np.float32)
        spline.points.foreach_get("co", got)
        check(np.array_equal(got.reshape(-1, 4)[:, :3], points), f"{result.name}: the points differ from meander.curve's")
    check(result.data.bevel_depth > 0, f"{result.name}: no bevel: it would not render as a tube")


def check_closed_manifold(obj):
    mesh = bmesh.new()
    mesh.from_mesh(obj.data)
    try:
        check(len(mesh.faces) > 0, f"{obj.name}: no faces")
        check(all(len(e.link_faces) == 2 for e in mesh.edges), f"{obj.name}: an edge is not shared by exactly two faces")
        check(all(e.is_contiguous for e in mesh.edges), f"{obj.name}: faces wound against their neighbours")
    finally:
        mesh.free()


def run(meander):
    scene = bpy.context.scene
    # A generated mesh: Blender's own torus (genus 1, quads), moved and scaled so that the
    # world transform matters.
    bpy.ops.mesh.primitive_torus_add(major_segments=24, minor_segments=12, location=(1, 2, 3))
    torus = bpy.context.active_object
    torus.scale = (2, 2, 2)
    # A real one, through the package's reader.
    spot = meander.read(pathlib.Path(meshes) / "spot_control_mesh.obj")
    data = bpy.data.meshes.new("spot")
    data.from_pydata(spot.vertices.tolist(), [], [spot.indices[a:b].tolist() for a, b in zip(spot.offsets[:-1], spot.offsets[1:])])
    spot_object = bpy.data.objects.new("spot", data)
    scene.collection.objects.link(spot_object)

    for source in (torus, spot_object):
        select(source)
        objects = len(bpy.data.objects)
        scene.meander_curve.seed = 3
        check(bpy.ops.meander.curve() == {"FINISHED"}, "meander.curve did not finish")
        curve = bpy.data.objects[source["meander_curve"]]
        check_curve(meander, source, curve, seed=3)
        # Re-run with another seed: the same object, updated.
        select(source)
        scene.meander_curve.seed = 4
        bpy.ops.meander.curve()
        check(bpy.data.objects[source["meander_curve"]] == curve, "re-running made another object")
        check_curve(meander, source, curve, seed=4)
        check(len(bpy.data.objects) == objects + 1, "re-running piled up objects")

        select(source)
        scene.meander_wire.sides = 8
        check(bpy.ops.meander.wire() == {"FINISHED"}, "meander.wire did not finish")
        wire = bpy.data.objects[source["meander_wire"]]
        check(wire.type == "MESH", "the wire is not a mesh")
        check_closed_manifold(wire)
        faces = len(wire.data.polygons)
        select(source)
        scene.meander_wire.sides = 5
        bpy.ops.meander.wire()
        check(bpy.data.objects[source["meander_wire"]] == wire and len(wire.data.polygons) != faces,
              "the wire was not updated with 5 sides")
        check_closed_manifold(wire)
        # Bridges: the wire becomes one solid with handles (a free loop's Euler characteristic is 0).
        select(source)
        scene.meander_wire.use_bridges = True
        scene.meander_wire.bridges = 1.0
        check(bpy.ops.meander.wire() == {"FINISHED"}, "meander.wire with bridges did not finish")
        check_closed_manifold(wire)
        euler = len(wire.data.vertices) - len(wire.data.edges) + len(wire.data.polygons)
        check(euler < 0, f"the bridged wire's Euler characteristic is {euler}, not below 0")
        scene.meander_wire.use_bridges = False
        # The variable method starts from the shaped tree, as `meander wire` and Python do.
        scene.meander_wire.method = "variable"
        check(scene.meander_wire.tree == "shaped", f"a variable wire's tree is {scene.meander_wire.tree}")
        scene.meander_wire.method = "constant"
        check(scene.meander_wire.tree == "random", f"a constant wire's tree is {scene.meander_wire.tree}")

        select(source)
        scene.meander_duotone.texture_size = 256
        check(bpy.ops.meander.duotone() == {"FINISHED"}, "meander.duotone did not finish")
        duotone = bpy.data.objects[source["meander_duotone"]]
        check(len(duotone.data.uv_layers) == 1, "the duotone has no UV layer")
        material = duotone.data.materials[0]
        image = next(n.image for n in material.node_tree.nodes if n.type == "TEX_IMAGE")
        check(image.packed_file is not None, "the duotone's texture is not packed into the .blend")
        check(tuple(image.size) == (256, 128) or image.size[0] == 256, f"texture size {tuple(image.size)}")
        vertices, faces, uv, texture, _ = meander.duotone(world_mesh(meander, source), texture_size=256)
        got = np.empty(len(duotone.data.loops) * 2, dtype=np.float32)
        duotone.data.uv_layers[0].data.foreach_get("uv", got)
        check(np.array_equal(got.reshape(-1, 2), uv), "the UVs are not meander.duotone's")
        pixels = np.empty(image.size[0] * image.size[1] * 4, dtype=np.float32)
        image.pixels.foreach_get(pixels)
        check(np.abs(np.flipud(pixels.reshape(image.size[1], image.size[0], 4)) * 255 - texture).max() < 1,
              "the image is not the duotone's texture, top row first")

        # A two-colour print: the duotone's two solids, each closed, in its colour (of the
        # torus: Spot's control mesh crosses itself, which a shell refuses).
        if source != torus:
            continue
        select(source)
        scene.meander_duotone.use_shell = True
        scene.meander_duotone.shell = 0.02
        check(bpy.ops.meander.duotone() == {"FINISHED"}, "meander.duotone with a shell did not finish")
        first, second = bpy.data.objects[source["meander_duotone"]], bpy.data.objects[source["meander_duotone 2"]]
        for solid in (first, second):
            check_closed_manifold(solid)
        colour = tuple(first.data.materials[0].diffuse_color)[:3]
        check(np.allclose(colour, scene.meander_duotone.colors_1, atol=1 / 255), f"the first solid's colour is {colour}")
        scene.meander_duotone.use_shell = False

    # The scene's units: with 1 unit = 1 mm, a model size of 100 mm is 100 units wide.
    select(torus)
    scene.unit_settings.scale_length = 0.001
    scene.meander_wire.use_model_size = True
    scene.meander_wire.model_size = 100  # shown and stored in scene units: 100 mm
    bpy.ops.meander.wire()
    wire = bpy.data.objects[torus["meander_wire"]]
    # The model (the torus) is 100 mm wide; its wire follows the smoothed curve, which
    # cuts inside the outermost vertices, with a thin tube round it.
    check(95 <= max(wire.dimensions) <= 105, f"a wire of a 100 mm model is {max(wire.dimensions):.1f} mm wide")

    # A refusal is a report (an error from bpy.ops in the background), not a traceback.
    select(spot_object)
    scene.meander_curve.quad = "none"
    try:
        bpy.ops.meander.curve()
        raise AssertionError("quad none on a mesh of pentagons was not refused")
    except RuntimeError as error:
        check(str(error).startswith("Error: spot: face 36 has 5 vertices: quad none needs a mesh of quads only"),
              f"the refusal does not name the object and say why: {error}")

    scene.meander_curve.quad = "dual-simplest"
    # A plotter drawing of the torus from the scene's camera (no 3D view here), the same
    # as meander.draw's from that camera.
    bpy.ops.object.camera_add(location=(0, -8, 6))
    camera = bpy.context.active_object
    camera.rotation_euler = (torus.matrix_world.translation - camera.location).to_track_quat("-Z", "Y").to_euler()
    scene.camera = camera
    select(torus)
    scene.unit_settings.scale_length = 1
    svg_path = pathlib.Path(tempfile.mkdtemp()) / "torus.svg"
    check(bpy.ops.meander.export_svg(filepath=str(svg_path), paper="A5") == {"FINISHED"}, "export_svg did not finish")
    svg = svg_path.read_text()
    check('width="148mm" height="210mm"' in svg and svg.count("<path") > 1, "the drawing is not an A5 sheet of paths")
    from meander import ui
    paths, expected = meander.draw(world_mesh(meander, torus), camera=ui.view_camera(bpy.context), paper="A5",
                                   **ui.job_arguments(bpy.context, "curve", sized=False))
    check(svg == expected, "the exported SVG is not meander.draw's from the camera")

    # Undo takes a run back and redo makes it again (background mode starts without an
    # undo system until the first push; operators called from Python push only when asked).
    bpy.ops.ed.undo_push(message="before")
    bpy.ops.mesh.primitive_ico_sphere_add("EXEC_DEFAULT", True)
    bpy.ops.meander.curve("EXEC_DEFAULT", True)
    check("Icosphere curve" in bpy.data.objects, "no curve of the ico sphere")
    bpy.ops.ed.undo()
    check("Icosphere curve" not in bpy.data.objects and "Icosphere" in bpy.data.objects, "undo did not take the curve back")
    bpy.ops.ed.redo()
    check("Icosphere curve" in bpy.data.objects, "redo did not make the curve again")


try:
    run(install())
    print("blender test: all passed")
except Exception:  # noqa: BLE001  any failure fails the test
    traceback.print_exc()
    sys.exit(1)
