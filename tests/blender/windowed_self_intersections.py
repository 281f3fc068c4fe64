"""Avoid Self-Intersections in a real window, as an artist uses it: the checkbox ticked in the Solver
panel, a live run (the Stylize operator invoked in the 3D view) and a pin handle dragged into another
part of the mesh. Run by run_windowed.sh, with windowed_kit.py's helpers:

    blender --factory-startup --enable-event-simulate -P tests/blender/windowed_self_intersections.py -- BUILD_DIR

Crossings are counted as Blender's 3D-Print toolbox counts them (helpers.crossing_pairs). Each case is
run without the option first and must cross itself there, so the checks with the option can fail:
- Spot (Cube style, Lambda 20 typed into the panel): without the option the live run crosses itself
  before it converges (watched until it does); with it, run until converged, no crossing pair, and the
  status text says while the guard holds vertices back;
- a post above a plate, both pinned, the post's handle dragged down through the plate: crossing pairs
  without the option, none with it.
Once the guard has held Spot's vertices back, Select Held Faces in the Solver panel selects the faces
around every vertex held in the run, and the run goes on.
Square Flat Regions, the panel's other option on shapes, is clicked on during a live run on a capped
cylinder under the Cubic method, whose round cap it squares.
Esc must restore the mesh bit for bit, Enter keep it and one Ctrl+Z undo it. The screenshot
self_intersections.png (the 3D view with its header and the sidebar) is taken while vertices are held.
The summary goes to BUILD_DIR/screenshots/windowed_self_intersections_result.txt.
"""

import os
import sys
import time

import bmesh
import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import windowed_kit as kit  # noqa: E402  (also sets up the paths and the window options)
from windowed_kit import check, coords, end_with, live_operator, press, viewport_point, window  # noqa: E402
from windowed_actions import (  # noqa: E402
    area_screenshot, find_sidebar_button, find_sidebar_field, found, type_into_field)
import helpers  # noqa: E402
from helpers import crossing_pairs  # noqa: E402

from gauss_stylization import ui  # noqa: E402  (windowed_kit put the add-on on sys.path)
from gauss_stylization.handles import handles  # noqa: E402

TIME_LIMIT = 420.0  # seconds: a busy 2-core machine redraws a window slowly
AVOID_PATH = "gauss_stylization.avoid_self_intersections"
SQUARE_PATH = "gauss_stylization.square_flat_regions"
LAMBDA_PATH = "gauss_stylization.lam"
HELD_TEXT = "vertices held back from passing through"  # the status text's words (live_run.status_text)
RUN_STEPS = 150  # a live run is watched until it converges or has done this many steps
RUN_SECONDS = 60.0
POST_DROP = 0.45  # how far the post's handle is dragged down: its middle ends in the plate


# -- what the artist does -------------------------------------------------------------

def scroll_sidebar_down(clicks=30):
    """Generator: the mouse wheel over the sidebar, so the Solver panel's lower rows come into view."""
    ui = kit.view3d()[1]['UI']
    x, y = ui.x + ui.width // 2, ui.y + ui.height // 2
    window().event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
    for _ in range(clicks):
        window().event_simulate(type='WHEELDOWNMOUSE', value='PRESS', x=x, y=y)
    yield 0.4


def click_checkbox(path):
    """Generator: click the sidebar checkbox of ``path`` (found by hovering, as type_into_field does)."""
    yield from scroll_sidebar_down()
    yield from find_sidebar_field(path)
    check("the Solver panel shows the checkbox %s" % path, found["at"] is not None)
    if found["at"] is not None:
        press('LEFTMOUSE', *found["at"])
        yield 0.4


def ctrl_z():
    """Generator: Ctrl+Z over the viewport, typed as on a keyboard: Ctrl down, Z, Ctrl up (a Z sent with
    ctrl alone leaves Ctrl down for the next click, which then toggles nothing)."""
    x, y = viewport_point()
    win = window()
    win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
    win.event_simulate(type='LEFT_CTRL', value='PRESS', x=x, y=y)
    win.event_simulate(type='Z', value='PRESS', x=x, y=y, ctrl=True)
    win.event_simulate(type='Z', value='RELEASE', x=x, y=y, ctrl=True)
    win.event_simulate(type='LEFT_CTRL', value='RELEASE', x=x, y=y)
    yield 0.6


def run_until_converged(seen, shot=None, until=None, on_held=None):
    """Generator: a live run started from the 3D view, watched until it is at rest (converged or held
    back by the guard), has done RUN_STEPS
    steps or ``until()`` is true; seen["held"] = whether its status text ever said it held vertices
    back (the first time it does, the sidebar is scrolled to the Solver panel and the 3D view saved to
    ``shot`` if given)."""
    seen["held"] = False
    kit.start_live_run()
    deadline = time.monotonic() + RUN_SECONDS
    while time.monotonic() < deadline:
        op = live_operator()
        if op is not None and op.session is not None:
            if HELD_TEXT in op.live.status_text() and not seen["held"]:
                seen["held"] = True
                if shot:
                    yield from scroll_sidebar_down(30)  # the run's box above pushed the checkbox down
                    area_screenshot(os.path.join(kit.SHOTS, shot))
                if on_held:
                    yield from on_held()
            if op.session.steps >= RUN_STEPS or op.session.at_rest or (until and until()):
                break
        yield 0.05
    op = live_operator()
    seen["steps"] = op.session.steps if op is not None and op.session is not None else None


def keep_and_undo(name, original, what):
    """Generator: Enter keeps the run's result, one Ctrl+Z brings back ``original`` bit for bit."""
    press('RET', *viewport_point())
    yield from kit.wait_stopped()
    kept = coords(bpy.data.objects[name])
    check("Enter keeps the %s" % what, live_operator() is None and not np.array_equal(kept, original))
    yield from ctrl_z()
    check("... and one Ctrl+Z undoes it bit-exactly", np.array_equal(coords(bpy.data.objects[name]), original))


# -- a live run on Spot ---------------------------------------------------------------

def live_run_on_spot(name, _prepared):
    obj = bpy.data.objects[name]
    obj.gauss_stylization.resolution_independent = False  # the paper's strength, at which Spot crosses itself
    original = coords(obj)
    check("Spot does not cross itself before the run", crossing_pairs(obj) == 0)
    yield from scroll_sidebar_down()  # the Solver panel is below the Styles panel's rows
    yield from type_into_field(LAMBDA_PATH, "20")
    check("Lambda 20 typed into the Solver panel", bpy.data.objects[name].gauss_stylization.lam == 20.0)
    seen = {}
    started = time.monotonic()
    yield from run_until_converged(seen, until=lambda: crossing_pairs(obj) > 0)  # no need to wait longer
    without = crossing_pairs(obj)
    check("without the option the live run makes Spot cross itself (before converging)", without > 0,
          "%d pairs after %s steps (%.1f s)" % (without, seen["steps"], time.monotonic() - started))
    yield from end_with('ESC', "Esc restores Spot bit-exactly", name, original)

    yield from click_checkbox(AVOID_PATH)
    check("a click ticks Avoid Self-Intersections", obj.gauss_stylization.avoid_self_intersections)
    started = time.monotonic()
    yield from run_until_converged(seen, shot="self_intersections.png", on_held=lambda: select_held_faces(obj))
    op = live_operator()
    with_option = crossing_pairs(obj)
    check("with the option the same run leaves Spot without a crossing pair", with_option == 0,
          "%d pairs after %s steps (%.1f s)" % (with_option, seen["steps"], time.monotonic() - started))
    check("... and the status text said vertices were held back", seen["held"])
    check("... and the run went on while holding them", op is not None and seen["steps"] and seen["steps"] > 10)
    yield from keep_and_undo(name, original, "clean result")
    obj = bpy.data.objects[name]  # undo replaced the object's data
    check("the undone run leaves the option ticked", obj.gauss_stylization.avoid_self_intersections)


# -- checking a print: Select Crossing Faces ------------------------------------------------

def crossing_faces_button(name, _prepared):
    """An artist checks a print before exporting it. Spot stylized at lambda 20 without the
    guard crosses itself: the Solver panel's Select Crossing Faces opens Edit Mode with exactly the
    crossing faces selected (a screenshot: crossing_faces.png); with the guard, it finds none."""
    from gauss_stylization.mesh import crossings
    from gauss_stylization import native
    obj = kit.activate(bpy.data.objects[name])
    original = coords(obj)
    obj.gauss_stylization.avoid_self_intersections = False
    obj.gauss_stylization.resolution_independent = False  # the paper's strength, at which Spot crosses itself
    obj.gauss_stylization.lam = 20.0
    with kit.override():
        bpy.ops.object.gauss_stylize(iterations=0)
    expected = crossings.find(native.core(), obj, bpy.context.evaluated_depsgraph_get())
    yield from scroll_sidebar_down()
    yield from find_sidebar_button("gauss_select_intersections")
    check("the Solver panel has the Select Crossing Faces button", found["button"] is not None)
    if found["button"] is None:
        return
    press('LEFTMOUSE', *found["button"])
    yield 0.8
    edit_faces = set()
    if obj.mode == 'EDIT':
        edit_faces = {face.index for face in bmesh.from_edit_mesh(obj.data).faces if face.select}
    check("a click opens Edit Mode with the crossing faces selected", obj.mode == 'EDIT' and len(expected.pairs)
          and edit_faces == set(expected.polygons.tolist()),
          "%s, %d selected, %d expected" % (obj.mode, len(edit_faces), len(expected.polygons)))
    with kit.override():
        bpy.ops.view3d.view_selected()
    yield 0.5
    area_screenshot(os.path.join(kit.SHOTS, "crossing_faces.png"))
    with kit.override():
        bpy.ops.object.mode_set(mode='OBJECT')
    helpers.mesh_io.write_vertex_coords(obj.data, original)
    obj.data.update()
    obj.gauss_stylization.avoid_self_intersections = True
    with kit.override():
        bpy.ops.object.gauss_stylize(iterations=0)
    press('LEFTMOUSE', *found["button"])
    yield 0.8
    selected = np.zeros(len(obj.data.polygons), bool)
    obj.data.polygons.foreach_get("select", selected)
    check("with Avoid Self-Intersections none is selected, and Object Mode stays", obj.mode == 'OBJECT'
          and not selected.any())
    helpers.mesh_io.write_vertex_coords(obj.data, original)
    obj.data.update()


# -- a handle dragged into the mesh -------------------------------------------------------

def post_and_plate():
    """One object: a plate (1 by 1, 0.05 thick) at the origin and a post (0.1 by 0.1, 0.4 high) standing
    0.225 above it, triangulated. Pin Group "Handles": the whole post and the plate's bottom."""
    bm = bmesh.new()
    for size, centre in (((1.0, 1.0, 0.05), (0.0, 0.0, 0.0)), ((0.1, 0.1, 0.4), (0.0, 0.0, 0.45))):
        verts = bmesh.ops.create_cube(bm, size=1.0)["verts"]
        bmesh.ops.scale(bm, vec=size, verts=verts)
        bmesh.ops.translate(bm, vec=centre, verts=verts)
    bmesh.ops.triangulate(bm, faces=bm.faces[:])
    obj = helpers.object_from_bmesh(bm, "PostAndPlate")
    z = coords(obj)[:, 2]
    pinned = np.flatnonzero((z > 0.1) | (z < 0.0))
    helpers.add_group(obj, "Handles", [int(i) for i in pinned])
    obj.gauss_stylization.pin_group = "Handles"
    return obj


def _post_pins_and_pixels(obj):
    """(the post's pins, its middle's window pixel, the pixel POST_DROP below it)."""
    found_handles = handles.Handles(live_operator().session)
    heights = [found_handles.targets[part][:, 2].mean() for part in found_handles.parts]
    part = found_handles.parts[int(np.argmax(heights))]
    area, regions = kit.view3d()
    region = regions['WINDOW']
    middle = found_handles.targets[part].mean(axis=0)
    ends = handles.project(np.array([middle, middle - [0.0, 0.0, POST_DROP]]), obj.matrix_world, region,
                           region.data) + [region.x, region.y]
    pixels = handles.project(found_handles.targets[part], obj.matrix_world, region, region.data) + [region.x, region.y]
    grab = pixels[int(np.argmin(np.hypot(*(pixels - ends[0]).T)))]
    return found_handles.pins[part], grab, ends[1] - ends[0]


def _drag_post_down(obj, moves=10):
    """Generator: press on a pin of the post, move the mouse POST_DROP down (in the view), release,
    and let the run step; returns the post's pins."""
    pins, grab, offset = _post_pins_and_pixels(obj)
    win = window()
    x0, y0 = int(round(grab[0])), int(round(grab[1]))
    win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x0, y=y0)
    win.event_simulate(type='LEFTMOUSE', value='PRESS', x=x0, y=y0)
    for k in range(1, moves + 1):
        yield 0.05
        win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x0 + int(offset[0] * k / moves),
                           y=y0 + int(offset[1] * k / moves))
    yield 0.3
    win.event_simulate(type='LEFTMOUSE', value='RELEASE', x=x0 + int(offset[0]), y=y0 + int(offset[1]))
    yield 1.0  # the drop taken and stepped on
    steps = live_operator().session.steps
    yield from kit.wait_steps(steps + 5)
    return pins


def handle_drag_into_the_plate(name, _prepared):
    bpy.data.objects.remove(bpy.data.objects[name])  # Spot is done with; the view shows the new object
    obj = post_and_plate()
    with kit.override():
        bpy.ops.view3d.view_axis(type='FRONT')
        bpy.ops.view3d.view_selected()
    kit.push_undo("Post and plate")
    name = obj.name
    original = coords(obj)
    check("the post and the plate do not cross to begin with", crossing_pairs(obj) == 0)
    yield 0.5

    kit.start_live_run()
    yield from kit.wait_steps(1)
    pins = yield from _drag_post_down(obj)
    dropped = original[pins, 2].mean() - coords(obj)[pins, 2].mean()
    without = crossing_pairs(obj)
    check("without the option the post dragged down passes through the plate", without > 0,
          "%d pairs, the post %.3f lower" % (without, dropped))
    yield from end_with('ESC', "Esc after the drag restores the mesh bit-exactly", name, original)

    found.pop(AVOID_PATH, None)  # this object's panel is laid out differently: Spot's place may mislead
    yield from click_checkbox(AVOID_PATH)
    check("a click ticks Avoid Self-Intersections on the new object", obj.gauss_stylization.avoid_self_intersections)
    kit.start_live_run()
    yield from kit.wait_steps(1)
    pins = yield from _drag_post_down(obj)
    held = live_operator().session.solver.held_vertices
    dropped = original[pins, 2].mean() - coords(obj)[pins, 2].mean()
    with_option = crossing_pairs(obj)
    check("with the option the dragged post stops at the plate: no crossing pair", with_option == 0,
          "%d pairs, the post %.3f lower, %d vertices held" % (with_option, dropped, held))
    check("... after moving towards it (the drag reached the solver)", dropped > 0.1, "%.3f" % dropped)
    yield from keep_and_undo(name, original, "dragged result")


def square_flat_regions_checkbox(name, _prepared):
    """Square Flat Regions, the Solver panel's other option on shapes: the capped cylinder of its tests
    under the Cubic method in a live run keeps a round cap until converged; a click on the checkbox
    mid-run squares it (squareness from below 0.9 to at least 0.9; screenshot square_flat_regions.png,
    looked at), Esc restores the mesh bit for bit."""
    from measures import squareness
    for obj in list(bpy.data.objects):
        if obj.type == 'MESH':
            bpy.data.objects.remove(obj)
    obj = helpers.capped_cylinder()
    kit.addon().settings_io.add_slot(obj.gauss_stylization, {"preset": 'CUBE'})
    obj.gauss_stylization.method = 'CUBIC'
    with kit.override():
        bpy.ops.view3d.view_axis(type='TOP')
        bpy.ops.view3d.view_selected()
    kit.push_undo("Capped cylinder")
    name, original = obj.name, coords(obj)
    tris = helpers.triangles(obj)[0]
    kit.start_live_run()
    deadline = time.monotonic() + 60.0
    while time.monotonic() < deadline and not (live_operator() and live_operator().session
                                               and live_operator().session.at_rest):
        yield 0.2
    round_cap = squareness(coords(obj).reshape(-1, 3), tris)
    check("without the option the live run converges with a round cap", round_cap < 0.9, "%.3f" % round_cap)
    found.pop(SQUARE_PATH, None)
    yield from click_checkbox(SQUARE_PATH)
    check("a click ticks Square Flat Regions during the run", obj.gauss_stylization.square_flat_regions)
    deadline = time.monotonic() + 60.0
    squared = round_cap
    while time.monotonic() < deadline and squared < 0.9:
        yield 0.3
        squared = squareness(coords(obj).reshape(-1, 3), tris)
    check("... the run goes on and squares the cap", live_operator() is not None and squared >= 0.9,
          "%.3f -> %.3f" % (round_cap, squared))
    yield 0.5
    area_screenshot(os.path.join(kit.SHOTS, "square_flat_regions.png"))
    yield from end_with('ESC', "Esc restores the cylinder bit-exactly", name, original)


def select_held_faces(obj):
    """Generator: once the guard has held vertices back in a live run, the Solver panel's Select Held
    Faces stays in it (the vertices of one step come and go) and selects the faces around every vertex
    held so far; the run goes on."""
    from gauss_stylization.mesh import crossings
    session = live_operator().session
    yield from find_sidebar_button("gauss_select_held")
    check("once vertices were held the Solver panel has Select Held Faces", found["button"] is not None)
    if found["button"] is None:
        return
    yield 1.5  # a few more steps: the button must still be there when the last one held nothing
    obj.data.polygons.foreach_set("select", np.zeros(len(obj.data.polygons), bool))
    before = session.held_anywhere
    press('LEFTMOUSE', *found["button"])
    yield 0.8
    after = session.held_anywhere
    selected = np.zeros(len(obj.data.polygons), bool)
    obj.data.polygons.foreach_get("select", selected)
    picked = np.flatnonzero(selected)
    # The run steps meanwhile: the selection is what was held by the click, between the two readings.
    low, high = (crossings.polygons_with_vertices(session.arrays, held) for held in (before, after))
    check("a click selects the faces around every vertex held so far", len(low) > 0
          and np.isin(low, picked).all() and np.isin(picked, high).all(),
          "%d selected, %d to %d around the held vertices" % (len(picked), len(low), len(high)))
    check("... and the live run goes on", live_operator() is not None)


def run_scenario(scenario_name, name, prepared):
    return globals()[scenario_name](name, prepared)


# Avoid Self-Intersections is in the Solver panel, closed by default: registered open before the sidebar
# first draws it (the panel itself is the add-on's).
ui.VIEW3D_PT_gauss_solver.bl_options = set()
kit.start(kit.cube_style_scenarios(("live_run_on_spot", "crossing_faces_button", "handle_drag_into_the_plate",
                                    "square_flat_regions_checkbox"),
                                   run_scenario),
          "windowed_self_intersections_result.txt", time_limit=TIME_LIMIT)
