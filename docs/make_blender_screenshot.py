"""The screenshot of docs/blender.md: Blender with the add-on's panel open and a curve
made on a torus. Run under a display (Debian's xvfb):
  BLENDER_USER_SCRIPTS=$(mktemp -d) xvfb-run -s "-screen 0 1600x1000x24" \
    blender --factory-startup --enable-event-simulate --python docs/make_blender_screenshot.py -- \
    build/meander-blender.zip OUT.png"""

import sys

import bpy

zip_path, out = sys.argv[sys.argv.index("--") + 1:][:2]
bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
bpy.ops.preferences.addon_enable(module="meander")

bpy.ops.object.select_all(action="SELECT")
bpy.ops.object.delete()
bpy.ops.mesh.primitive_torus_add(major_segments=32, minor_segments=16)
torus = bpy.context.active_object
scene = bpy.context.scene
scene.meander_curve.seed = 7
bpy.ops.meander.curve()


def view():
    """The sidebar open, the view on the curve."""
    window = bpy.context.window_manager.windows[0]
    for area in window.screen.areas:
        if area.type == "VIEW_3D":
            space = area.spaces.active
            space.show_region_ui = True
            space.overlay.show_floor = False
            space.overlay.show_axis_x = space.overlay.show_axis_y = False
            with bpy.context.temp_override(window=window, area=area,
                                           region=next(r for r in area.regions if r.type == "WINDOW")):
                bpy.ops.view3d.view_selected()


def tab():
    """Blender 3.4 has no API for the sidebar's tab: Ctrl+wheel over the sidebar, as a user
    would, until the Meander tab shows (Blender runs with --enable-event-simulate)."""
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == "VIEW_3D")
    sidebar = next(r for r in area.regions if r.type == "UI")
    x, y = sidebar.x + sidebar.width // 2, sidebar.y + sidebar.height // 2
    window.event_simulate("ESC", "PRESS")  # the splash screen
    window.event_simulate("ESC", "RELEASE")
    window.event_simulate("MOUSEMOVE", "NOTHING", x=x, y=y)
    for _ in range(3):
        window.event_simulate("WHEELDOWNMOUSE", "PRESS", x=x, y=y, ctrl=True)


def shoot():
    window = bpy.context.window_manager.windows[0]
    with bpy.context.temp_override(window=window):
        bpy.ops.screen.screenshot(filepath=out)
    bpy.ops.wm.quit_blender()


bpy.app.timers.register(lambda: view() or None, first_interval=2)
bpy.app.timers.register(lambda: tab() or None, first_interval=3)
bpy.app.timers.register(lambda: shoot() or None, first_interval=5)
