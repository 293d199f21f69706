# The Blender add-on's properties, operators and panel (docs/blender.md), a module of the
# package `meander` (which register() imports it from). Every job parameter becomes a
# Blender property under its own name, made from the one description the CLI and the
# studio use (meander.parameters), so they never disagree.

import json
import math
import os
import threading
import warnings

import bpy
import numpy as np

from . import _meander

JOBS = ("curve", "wire", "duotone")
# Defaults for the number of a "number or name" parameter once its box is ticked; lengths
# in metres (converted to the scene's units), the branches slider as a fraction.
FIRST_VALUES = {"model_size": 0.1, "spacing": 0.05, "radius": 0.005, "branches": 0.5, "bridges": 0.2, "shell": 0.002}


def _metres(context) -> float:
    """Metres in one Blender unit."""
    return context.scene.unit_settings.scale_length


def _method_changed(settings, _context):
    """As `meander wire` and the studio: the variable method starts from the shaped tree,
    the constant one from the random tree, unless another tree was chosen."""
    default = {"constant": "random", "variable": "shaped"}
    other = "constant" if settings.method == "variable" else "variable"
    if settings.tree == default[other]:
        settings.tree = default[settings.method]


def _property(p, update=None):
    """The Blender properties of one parameter: {name: property}."""
    name, kind, text = p["name"], p["type"], p["default"]
    options = {"name": name.replace("_", " ").capitalize(), "description": p["help"]}
    if update is not None:
        options["update"] = update
    bounds = {}
    if "min" in p:
        bounds["min"] = p["min"]
    if "max" in p:
        bounds["max"] = p["max"]
    # Lengths in the scene's units; the nozzle is a printer's, always in millimetres.
    length = {"subtype": "DISTANCE", "unit": "LENGTH"} if p["length"] and name != "nozzle" else {}
    if name == "nozzle":
        options["name"] += " (mm)"
    if kind == "boolean":
        return {name: bpy.props.BoolProperty(default=text == "true", **options)}
    if kind == "integer":
        return {name: bpy.props.IntProperty(default=int(text), min=int(bounds.get("min", 0)),
                                            max=int(bounds.get("max", 2**31 - 1)), **options)}
    if kind == "number":
        return {name: bpy.props.FloatProperty(default=float(text), **bounds, **length, **options)}
    if kind == "name":
        items = [(c, c.replace("-", " ").capitalize(), "") for c in p["choices"]]
        return {name: bpy.props.EnumProperty(items=items, default=text, **options)}
    if kind == "number or name":
        use = {"name": f"{options['name']}", "description": f"{p['help']} (unticked: {p['choices'][0]})"}
        return {f"use_{name}": bpy.props.BoolProperty(default=False, **use),
                name: bpy.props.FloatProperty(default=FIRST_VALUES.get(name, 1.0), min=bounds.get("min", 0.0),
                                              **({"max": bounds["max"]} if "max" in bounds else {}), **length, **options)}
    if kind == "colors":
        # "#rrggbb,#rrggbb": two colours of three components in 0..1.
        colours = [tuple(int(c[k:k + 2], 16) / 255 for k in (1, 3, 5)) for c in text.split(",")]
        return {f"{name}_{k}": bpy.props.FloatVectorProperty(default=colours[k - 1], subtype="COLOR_GAMMA", min=0, max=1,
                                                             name=f"Colour {k}", description=p["help"])
                for k in (1, 2)}
    raise ValueError(f"parameter {name}: unknown type {kind}")


def _settings_class(job):
    annotations = {}
    for p in _meander.parameters(job):
        annotations.update(_property(p, _method_changed if job == "wire" and p["name"] == "method" else None))
    return type(f"MEANDER_PG_{job}", (bpy.types.PropertyGroup,), {"__annotations__": annotations})


def job_arguments(context, job, sized=True):
    """The job's keyword arguments from the scene's settings, lengths in the job's units:
    the scene's, or millimetres with a model size (unless `sized` is False: then without
    one, as a drawing from the scene's own view needs)."""
    settings = getattr(context.scene, f"meander_{job}")
    described = _meander.parameters(job)
    sized = sized and getattr(settings, "use_model_size", False)
    millimetres = _metres(context) * 1000

    def length(value, name):
        return value * millimetres if sized and name != "nozzle" else value

    arguments = {}
    for p in described:
        name, kind = p["name"], p["type"]
        if kind == "number or name":
            value = getattr(settings, name) if getattr(settings, f"use_{name}") and (sized or name != "model_size") else None
            arguments[name] = length(value, name) if value is not None and p["length"] else value
        elif kind == "colors":
            arguments[name] = ["#" + "".join(f"{round(c * 255):02x}" for c in getattr(settings, f"{name}_{k}"))
                               for k in (1, 2)]
        else:
            value = getattr(settings, name)
            arguments[name] = length(value, name) if p["length"] else value
    return arguments


def source_mesh(context, source):
    """The evaluated mesh of `source` (modifiers applied) in world space, as a meander.Mesh."""
    evaluated = source.evaluated_get(context.evaluated_depsgraph_get())
    data = evaluated.to_mesh()
    try:
        vertices = np.empty(len(data.vertices) * 3, dtype=np.float32)
        data.vertices.foreach_get("co", vertices)
        offsets = np.empty(len(data.polygons), dtype=np.int32)
        data.polygons.foreach_get("loop_start", offsets)
        indices = np.empty(len(data.loops), dtype=np.int32)
        data.loops.foreach_get("vertex_index", indices)
    finally:
        evaluated.to_mesh_clear()
    matrix = np.array(source.matrix_world, dtype=np.float64)
    world = vertices.reshape(-1, 3) @ matrix[:3, :3].T + matrix[:3, 3]
    return _meander.Mesh(world.astype(np.float32), indices, offsets=np.append(offsets, len(indices)), name=source.name)


class Job:
    """One run of a job on a thread of its own: `stage` and `fraction` follow it, `cancel`
    stops it at its next check."""

    def __init__(self, job, mesh, arguments):
        self.job, self.mesh, self.arguments = job, mesh, arguments
        self.stage, self.fraction, self.cancel = "", None, False
        self.result, self.error, self.warnings = None, None, []

    def _progress(self, stage, fraction):
        self.stage, self.fraction = stage, fraction
        if self.cancel:
            raise InterruptedError("stopped")

    def run(self):
        # A duotone with a shell is a two-colour print: its two solids.
        function = "duotone_print" if self.arguments.get("shell") is not None else self.job
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always", _meander.MeshWarning)
                self.result = getattr(_meander, function)(self.mesh, progress=self._progress, **self.arguments)
            self.warnings = [str(w.message) for w in caught]
        except (ValueError, TypeError, OSError, RuntimeError, InterruptedError) as error:
            self.error = error


def _result_object(context, source, job, data):
    """The object that holds the job's result for `source`: the one made before, its data
    replaced (so re-running updates it), or a new one beside the source."""
    key = f"meander_{job}"
    obj = bpy.data.objects.get(source.get(key, ""))
    if obj is not None and obj.type == ("MESH" if isinstance(data, bpy.types.Mesh) else "CURVE"):
        old = obj.data
        obj.data = data
        if old.users == 0:
            (bpy.data.meshes if isinstance(old, bpy.types.Mesh) else bpy.data.curves).remove(old)
        return obj
    obj = bpy.data.objects.new(f"{source.name} {job}", data)
    (source.users_collection[0] if source.users_collection else context.scene.collection).objects.link(obj)
    source[key] = obj.name
    return obj


def _mesh_data(name, vertices, faces):
    data = bpy.data.meshes.new(name)
    data.vertices.add(len(vertices))
    data.vertices.foreach_set("co", vertices.ravel())
    data.loops.add(faces.size)
    data.loops.foreach_set("vertex_index", faces.ravel())
    data.polygons.add(len(faces))
    data.polygons.foreach_set("loop_start", np.arange(0, faces.size, faces.shape[1], dtype=np.int32))
    data.polygons.foreach_set("loop_total", np.full(len(faces), faces.shape[1], dtype=np.int32))
    data.polygons.foreach_set("use_smooth", np.ones(len(faces), dtype=bool))
    data.update()
    return data


def _colour_material(name, colour):
    """A plain material of an "#rrggbb" colour."""
    material = bpy.data.materials.get(name) or bpy.data.materials.new(name)
    rgba = tuple(int(colour[k:k + 2], 16) / 255 for k in (1, 3, 5)) + (1.0,)
    material.diffuse_color = rgba
    material.use_nodes = True
    shader = material.node_tree.nodes.get("Principled BSDF")
    if shader is not None:
        shader.inputs["Base Color"].default_value = rgba
    return material


def _duotone_material(name, texture):
    material = bpy.data.materials.get(name) or bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    image_node = next((n for n in nodes if n.type == "TEX_IMAGE"), None) or nodes.new("ShaderNodeTexImage")
    old = image_node.image
    height, width = texture.shape[:2]
    image = bpy.data.images.new(name, width, height, alpha=True)
    # Blender's rows go up from the bottom; the texture's go down from the top.
    image.pixels.foreach_set((np.flipud(texture).astype(np.float32) / 255).ravel())
    image.pack()
    image_node.image = image
    if old is not None and old.users == 0:
        bpy.data.images.remove(old)
    shader = nodes.get("Principled BSDF")
    if shader is not None:
        material.node_tree.links.new(image_node.outputs["Color"], shader.inputs["Base Color"])
    return material


def place_result(context, source, job, mesh, arguments, result):
    """Makes or updates the result object, in the scene's units, its box centred on the
    source's (a model size rescales it about the origin)."""
    sized = arguments.get("model_size") is not None
    scale = 1 / (_metres(context) * 1000) if sized else 1.0  # millimetres to scene units
    name = f"{source.name} {job}"
    if job == "curve":
        curves = [c * scale for c in result]
        data = bpy.data.curves.new(name, "CURVE")
        data.dimensions = "3D"
        for points in curves:
            spline = data.splines.new("POLY")
            spline.points.add(len(points) - 1)
            spline.points.foreach_set("co", np.hstack([points, np.ones((len(points), 1), np.float32)]).ravel())
            spline.use_cyclic_u = True
        # A wire's radius: a fifth of the spacing, or of the mean gap between passes, the
        # surface's area over the curve's length (k: result units per unit of the source).
        spacing = arguments.get("spacing")
        if spacing is not None:
            gap = spacing * scale
        else:
            k = _model_scale(mesh, arguments) * scale if sized else 1.0
            length = sum(float(np.linalg.norm(np.diff(c, axis=0, append=c[:1]), axis=1).sum()) for c in curves)
            gap = _area(mesh) * k * k / max(length, 1e-30)
        data.bevel_depth = gap / 5
        data.bevel_resolution = 2
        points = np.concatenate(curves)
    elif job == "wire":
        vertices, faces, report = result
        data = _mesh_data(name, vertices * scale, faces)
        points = vertices * scale
    elif arguments.get("shell") is not None:
        # A two-colour print: the first solid is the result object, the second its own
        # object beside it ("... duotone 2"), each in its colour.
        solids, _ = result
        parts = []
        for k, solid in enumerate(solids):
            data = _mesh_data(f"{name} {k + 1}", solid.vertices * scale, solid.faces)
            data.materials.append(_colour_material(f"{name} {k + 1}", arguments["colors"][k]))
            parts.append(data)
        points = np.concatenate([solid.vertices for solid in solids]) * scale
        second = _result_object(context, source, "duotone 2", parts[1])
        data = parts[0]
    else:
        vertices, faces, uv, texture, _ = result
        data = _mesh_data(name, vertices * scale, faces)
        layer = data.uv_layers.new(name="duotone")
        layer.data.foreach_set("uv", uv.ravel())
        data.materials.append(_duotone_material(name, texture))
        points = vertices * scale
    obj = _result_object(context, source, job, data)
    if sized:
        source_box = mesh.vertices.min(axis=0), mesh.vertices.max(axis=0)
        obj.location = (sum(source_box) - points.min(axis=0) - points.max(axis=0)) / 2
    else:
        obj.location = (0, 0, 0)
    if job == "duotone" and arguments.get("shell") is not None:
        second.location = obj.location
    return obj


def _area(mesh):
    v, offsets, indices = mesh.vertices.astype(np.float64), mesh.offsets, mesh.indices
    first = np.repeat(indices[offsets[:-1]], np.diff(offsets) - 2)
    corner = np.concatenate([np.arange(s + 1, e - 1) for s, e in zip(offsets[:-1], offsets[1:])])
    a, b, c = v[first], v[indices[corner]], v[indices[corner + 1]]
    return 0.5 * float(np.linalg.norm(np.cross(b - a, c - a), axis=1).sum())


def _model_scale(mesh, arguments):
    """Millimetres per unit of the source once scaled to the model size."""
    extent = (mesh.vertices.max(axis=0) - mesh.vertices.min(axis=0)).max()
    return arguments["model_size"] / extent


class _Make:
    bl_options = {"REGISTER", "UNDO"}
    job = ""

    @classmethod
    def poll(cls, context):
        return context.active_object is not None and context.active_object.type == "MESH"

    def _start(self, context):
        self.source = context.active_object
        self.mesh = source_mesh(context, self.source)
        self.run = Job(self.job, self.mesh, job_arguments(context, self.job))

    def _finish(self, context):
        run = self.run
        for line in run.warnings:
            self.report({"WARNING"}, line)
        if run.error is not None:
            self.report({"ERROR"} if not isinstance(run.error, InterruptedError) else {"INFO"},
                        str(run.error) if not isinstance(run.error, InterruptedError) else "Meander: stopped")
            return {"CANCELLED"}
        obj = place_result(context, self.source, self.job, self.mesh, run.arguments, run.result)
        if self.job == "duotone" and run.arguments.get("shell") is not None:
            self.report({"INFO"}, f"Meander: {obj.name}: " + run.result[1])
        if self.job == "wire":
            # The printability report, as `meander wire --report` writes it, on the object.
            report = run.result[2]
            obj["meander_report"] = json.dumps(report)
            self.report({"INFO"}, f"Meander: {obj.name}: " + ("printable" if report["printable"] else
                                                              "not printable (its report: the meander_report property)"))
        return {"FINISHED"}

    def execute(self, context):
        self._start(context)
        window_manager = context.window_manager
        window_manager.progress_begin(0, 1)
        try:
            self.run.run()
        finally:
            window_manager.progress_end()
        return self._finish(context)

    def invoke(self, context, event):
        if bpy.app.background:
            return self.execute(context)
        self._start(context)
        self.thread = threading.Thread(target=self.run.run, daemon=True)
        self.thread.start()
        self.timer = context.window_manager.event_timer_add(0.1, window=context.window)
        context.window_manager.progress_begin(0, 1)
        context.window_manager.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        if event.type == "ESC":
            self.run.cancel = True
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        fraction = self.run.fraction
        context.workspace.status_text_set(
            f"Meander {self.job}: {self.run.stage or 'starting'}" + (f" {fraction:.0%}" if fraction is not None else "")
            + "  (Esc stops)")
        if fraction is not None:
            context.window_manager.progress_update(fraction)
        if self.thread.is_alive():
            return {"RUNNING_MODAL"}
        context.window_manager.event_timer_remove(self.timer)
        context.window_manager.progress_end()
        context.workspace.status_text_set(None)
        return self._finish(context)


def view_camera(context):
    """(eye, target, up, vertical field of view in degrees) of the 3D view the operator
    runs in, or else of the scene's camera. An orthographic view is seen from far away
    through a narrow field, which draws it nearly parallel."""
    space = context.space_data
    if space is not None and space.type == "VIEW_3D":
        view = space.region_3d
        rotation = view.view_matrix.inverted().to_3x3()
        forward, up = -rotation.col[2].normalized(), rotation.col[1].normalized()
        tan_half = 1 / view.window_matrix[1][1]
        if view.is_perspective:
            eye = view.view_matrix.inverted().translation
            return tuple(eye), tuple(eye + forward), tuple(up), math.degrees(2 * math.atan(tan_half))
        far = 1000 * max(view.view_distance, 1e-3)
        target = view.view_location
        return tuple(target - forward * far), tuple(target), tuple(up), math.degrees(2 * math.atan(tan_half / far))
    camera = context.scene.camera
    if camera is None:
        raise ValueError("no 3D view and no scene camera to draw from")
    rotation = camera.matrix_world.to_3x3()
    eye = camera.matrix_world.translation
    forward = -rotation.col[2].normalized()
    return tuple(eye), tuple(eye + forward), tuple(rotation.col[1].normalized()), math.degrees(camera.data.angle_y)


class MEANDER_OT_export_svg(bpy.types.Operator):
    """Draw the active object's curve for a pen plotter, as seen from the 3D view (or the scene's camera): an SVG with
    the parts behind the surface removed (meander draw)"""

    bl_idname = "meander.export_svg"
    bl_label = "Export plotter SVG"
    filepath: bpy.props.StringProperty(subtype="FILE_PATH")
    filter_glob: bpy.props.StringProperty(default="*.svg", options={"HIDDEN"})
    paper: bpy.props.EnumProperty(name="Paper", items=[(p, p.capitalize() if p.islower() else p, "")
                                                       for p in ("A4", "A3", "A5", "letter", "legal")])
    landscape: bpy.props.BoolProperty(name="Landscape")
    margin: bpy.props.FloatProperty(name="Margin (mm)", default=10, min=0)
    pen: bpy.props.FloatProperty(name="Pen (mm)", description="the pen's width: the stroke, and the detail kept",
                                 default=0.3, min=0.01)

    @classmethod
    def poll(cls, context):
        return context.active_object is not None and context.active_object.type == "MESH"

    def invoke(self, context, event):
        if not self.filepath:
            self.filepath = bpy.path.ensure_ext(context.active_object.name, ".svg")
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        source = context.active_object
        path = bpy.path.ensure_ext(bpy.path.abspath(self.filepath), ".svg")
        try:
            camera = view_camera(context)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", _meander.MeshWarning)  # the curve's own operator says them
                paths, svg = _meander.draw(source_mesh(context, source), camera=camera, paper=self.paper,
                                           landscape=self.landscape, margin=self.margin, pen=self.pen,
                                           **job_arguments(context, "curve", sized=False))
            # Atomic, as the library's writers: a failed export leaves no partial file.
            with open(path + ".part", "w", encoding="utf-8") as out:
                out.write(svg)
            os.replace(path + ".part", path)
        except (ValueError, TypeError, OSError, RuntimeError) as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        self.report({"INFO"}, f"Meander: {path}: {len(paths)} paths")
        return {"FINISHED"}


def _operator(job):
    return type(f"MEANDER_OT_{job}", (_Make, bpy.types.Operator), {
        "bl_idname": f"meander.{job}",
        "bl_label": f"Make {job}",
        "bl_description": {"curve": "One closed curve per component over the active mesh, as a curve object with a bevel",
                           "wire": "A wire or ribbon along the curve, as a mesh ready to print",
                           "duotone": "The surface in two colours split by one curve, with its texture packed"}[job],
        "job": job,
    })


class MEANDER_PT_panel(bpy.types.Panel):
    bl_label = "Meander"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Meander"

    def draw(self, context):
        layout = self.layout
        scene = context.scene
        layout.row().prop(scene, "meander_job", expand=True)
        layout.use_property_split = True
        layout.use_property_decorate = False
        job = scene.meander_job
        settings = getattr(scene, f"meander_{job}")
        for p in _meander.parameters(job):
            name = p["name"]
            if p["type"] == "number or name":
                # A box to tick, unticked for the parameter's none or auto.
                row = layout.row(align=True, heading=name.replace("_", " ").capitalize())
                row.prop(settings, f"use_{name}", text="")
                sub = row.row(align=True)
                sub.active = getattr(settings, f"use_{name}")
                sub.prop(settings, name, text="")
            elif p["type"] == "colors":
                row = layout.row(align=True, heading="Colors")
                row.prop(settings, f"{name}_1", text="")
                row.prop(settings, f"{name}_2", text="")
            else:
                layout.prop(settings, name)
        layout.operator(f"meander.{job}", icon="CURVE_DATA" if job == "curve" else "MESH_DATA")
        if job == "curve":
            layout.operator("meander.export_svg", icon="EXPORT")


_classes = []


def register():
    _classes.clear()
    for job in JOBS:
        _classes.append(_settings_class(job))
    _classes.extend(_operator(job) for job in JOBS)
    _classes.append(MEANDER_OT_export_svg)
    _classes.append(MEANDER_PT_panel)
    for cls in _classes:
        bpy.utils.register_class(cls)
    for job, settings in zip(JOBS, _classes[:3]):
        setattr(bpy.types.Scene, f"meander_{job}", bpy.props.PointerProperty(type=settings))
    bpy.types.Scene.meander_job = bpy.props.EnumProperty(
        name="Make", items=[(job, job.capitalize(), f"Make a {job}") for job in JOBS], default="curve")


def unregister():
    for job in JOBS:
        delattr(bpy.types.Scene, f"meander_{job}")
    del bpy.types.Scene.meander_job
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
    _classes.clear()
