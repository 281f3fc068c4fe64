"""The live run in a real window, second part: undo, clicks, several objects, messages, converging.
Run by run_windowed.sh after windowed_driver.py, with windowed_kit.py's helpers:

    blender --factory-startup --enable-event-simulate -P tests/blender/windowed_live_run.py -- BUILD_DIR

Everything is done as a person would: typing into the sidebar's Sigma field, G and a
click to move, Ctrl+Z, drags on the navigation gizmo, clicks in headers and the outliner.
How runs end and what they give back: windowed_run_endings.py. GAUSS_WINDOWED_ONLY=name,name runs
only those scenarios. The summary goes to BUILD_DIR/screenshots/windowed_live_run_result.txt.
"""

import os
import sys
import time

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import windowed_kit as kit  # noqa: E402  (also sets up the paths and the window options)
from windowed_kit import (  # noqa: E402
    addon, check, coords, live_operator, live_run, new_reports, press, push_undo, view3d, viewport_point,
    wait_steps, wait_stopped, window)
from scene_kit import activate  # noqa: E402
from windowed_actions import drag, key, move_with_g, navigation_gizmo_buttons, type_into_field  # noqa: E402
import helpers  # noqa: E402

SIGMA_PATH = "gauss_stylization.styles[0].sigma"
TIME_LIMIT = 900.0  # seconds: a 2-core machine busy with other builds redraws a window slowly (idle: ~1 min)


def selection_state(obj):
    return coords(obj), tuple(obj.location), obj.gauss_stylization.styles[0].sigma


# -- undo ----------------------------------------------------------------------------------

def edit_during_a_run(name, sigma, ending, states):
    """Generator: a live run in which Sigma is typed into the sidebar and the object is moved
    with G and a click, ended by the key ``ending``; states["before"] / ["after"]: the object's
    selection_state() before the run (an undo step) and after it ended."""
    obj = activate(bpy.data.objects[name])
    push_undo("Before the run")
    states["before"] = selection_state(obj)
    yield from live_run(5)
    yield from type_into_field(SIGMA_PATH, sigma)
    check("Sigma typed into the sidebar during a run reaches the run",
          live_operator() is not None and obj.gauss_stylization.styles[0].sigma == float(sigma))
    location = tuple(obj.location)
    yield from move_with_g()
    check("G and a click during a run move the object and leave the run going",
          live_operator() is not None and tuple(obj.location) != location)
    yield from wait_steps(live_operator().session.steps + 3 if live_operator() else 0)
    yield from key(ending)
    yield from wait_stopped()
    states["after"] = selection_state(bpy.data.objects[name])


def sigma_and_move_during_a_kept_run(name):
    """Sigma typed into the sidebar and a G move during a run, then Enter: one Ctrl+Z gives
    back exactly the mesh (and settings, and place) from before the run."""
    states = {}
    yield from edit_during_a_run(name, "8", 'RET', states)
    before, kept = states["before"], states["after"]
    check("Enter keeps the run (with the edits made during it)",
          live_operator() is None and not np.array_equal(kept[0], before[0]) and kept[2] == 8.0)
    yield from key('Z', ctrl=True)
    obj = bpy.data.objects[name]
    now = selection_state(obj)
    check("one Ctrl+Z after a kept run with edits gives the mesh from before the run bit-exactly",
          np.array_equal(now[0], before[0]), "max diff %.3g" % np.abs(now[0] - before[0]).max())
    check("... and the settings and place from before the run (the edits belong to the run's step)",
          now[1:] == before[1:], "now %s before %s" % (now[1:], before[1:]))
    yield from key('Z', ctrl=True, shift=True)
    obj = bpy.data.objects[name]
    check("Ctrl+Shift+Z then brings the kept result back, edits included",
          np.array_equal(coords(obj), kept[0]) and selection_state(obj)[1:] == kept[1:])
    yield from key('Z', ctrl=True)  # back to before the run for the next scenario


def sigma_and_move_during_a_cancelled_run(name):
    """The same edits, then Esc: neither redo nor undo shows a cancelled shape; the edits
    are one undo step."""
    states = {}
    yield from edit_during_a_run(name, "7", 'ESC', states)
    before, after_esc = states["before"], states["after"]
    check("Esc restores the mesh bit-exactly and keeps the edits",
          np.array_equal(after_esc[0], before[0]) and after_esc[2] == 7.0 and after_esc[1] != before[1])
    never = []
    for keys in (dict(ctrl=True, shift=True), dict(ctrl=True), dict(ctrl=True, shift=True), dict(ctrl=True)):
        yield from key('Z', **keys)
        never.append(np.array_equal(coords(bpy.data.objects[name]), before[0]))
    check("after Esc, Ctrl+Shift+Z / Ctrl+Z / Ctrl+Shift+Z / Ctrl+Z never show a cancelled shape", all(never),
          str(never))
    check("... and the edits made during the cancelled run are one undo step",
          selection_state(bpy.data.objects[name])[1:] == before[1:])
    yield from key('Z', ctrl=True, shift=True)
    check("... which redo brings back (with the original mesh)",
          selection_state(bpy.data.objects[name])[1:] == after_esc[1:]
          and np.array_equal(coords(bpy.data.objects[name]), before[0]))


# -- clicks --------------------------------------------------------------------------------

def gizmo_and_header_clicks(name):
    obj = bpy.data.objects[name]
    activate(obj)
    original = coords(obj)
    region_3d = view3d()[0].spaces.active.region_3d
    # The checks below need a run that keeps stepping: at the default tolerance the accelerated
    # iteration converges (and the run stops stepping) within ~70 steps on Spot, before the last click.
    tolerance = obj.gauss_stylization.tolerance
    obj.gauss_stylization.tolerance = obj.gauss_stylization.bl_rna.properties["tolerance"].hard_min
    yield from live_run(3)
    rotate, zoom = navigation_gizmo_buttons()
    distance = region_3d.view_distance
    yield from drag(*zoom, 0, -60)
    check("a drag on the navigation gizmo's zoom button zooms", region_3d.view_distance != distance,
          "%.3f -> %.3f" % (distance, region_3d.view_distance))
    yield from kit.goes_on("... and the run goes on")
    rotation = tuple(region_3d.view_rotation)
    yield from drag(*rotate, 40, 0)
    check("a drag on the rotation gizmo turns the view", tuple(region_3d.view_rotation) != rotation)
    yield from kit.goes_on("... and the run goes on")
    area, regions = view3d()
    tool_header = regions['TOOL_HEADER']
    press('LEFTMOUSE', tool_header.x + tool_header.width // 2, tool_header.y + tool_header.height // 2)
    ui = regions['UI']
    press('LEFTMOUSE', ui.x + ui.width // 2, ui.y + 10)  # the empty foot of the sidebar
    toolbar = regions['TOOLS']
    press('LEFTMOUSE', toolbar.x + toolbar.width // 2, toolbar.y + toolbar.height - 30)  # a tool button
    yield 0.3
    yield from kit.goes_on("clicks in the tool header, the sidebar and the toolbar leave the run going")
    x, y = viewport_point()
    yield from drag(x - 150, y + 100, 80, -60)  # a box selection in the free viewport
    yield from kit.goes_on("a drag in the free viewport (box select) leaves the run going")
    yield from kit.end_with('ESC', "Esc after those clicks restores the mesh bit-exactly", name, original)
    obj.gauss_stylization.tolerance = tolerance


def outliner_selection(name, other):
    """Selecting another object in the outliner does not end the run (its objects are fixed)."""
    obj = bpy.data.objects[name]
    activate(obj)
    original = coords(obj)
    yield from live_run(3)
    outliner = next(a for a in window().screen.areas if a.type == 'OUTLINER')
    region = next(r for r in outliner.regions if r.type == 'WINDOW')
    row = 20 * bpy.context.preferences.system.ui_scale
    x = region.x + region.width // 2
    for i in range(1, 10):  # click rows from the top until the other object is the active one
        press('LEFTMOUSE', x, int(region.y + region.height - row * (i + 0.5)))
        yield 0.2
        if bpy.context.view_layer.objects.active == bpy.data.objects[other]:
            break
    check("a click in the outliner selects another object",
          bpy.context.view_layer.objects.active == bpy.data.objects[other])
    yield from kit.goes_on("... and the run goes on")
    op = live_operator()
    check("... on the object it started with", op is not None and [s.obj.name for s in op.sessions] == [name])
    activate(bpy.data.objects[name])
    yield from kit.end_with('ESC', "Esc then restores the mesh bit-exactly", name, original)


# -- several objects -----------------------------------------------------------------------

def several_objects(name, other):
    first, second = bpy.data.objects[name], bpy.data.objects[other]
    activate(first)
    second.select_set(True)
    originals = coords(first), coords(second)
    yield from live_run(4)
    op = live_operator()
    check("a live run with two selected meshes stylizes both",
          op is not None and sorted(s.obj.name for s in op.sessions) == sorted([name, other]))
    yield from wait_steps(8)
    moved = [not np.array_equal(coords(o), start) for o, start in zip((first, second), originals)]
    check("... both move", all(moved), str(moved))
    yield from key('ESC')
    yield from wait_stopped()
    check("Esc restores both meshes bit-exactly", all(
        np.array_equal(coords(bpy.data.objects[n]), start) for n, start in zip((name, other), originals)))
    push_undo("Before the two-object run")
    yield from live_run(6)
    yield from key('RET')
    yield from wait_stopped()
    kept = [not np.array_equal(coords(bpy.data.objects[n]), s) for n, s in zip((name, other), originals)]
    yield from key('Z', ctrl=True)
    check("Enter keeps both, and one Ctrl+Z gives both back bit-exactly", all(kept) and all(
        np.array_equal(coords(bpy.data.objects[n]), start) for n, start in zip((name, other), originals)))
    activate(bpy.data.objects[name])


# -- messages ------------------------------------------------------------------------------

def region_group_deleted(name):
    obj = bpy.data.objects[name]
    activate(obj)
    original = coords(obj)
    group = obj.vertex_groups.new(name="Top")
    group.add([i for i, co in enumerate(original) if co[2] > original[:, 2].mean()], 1.0, 'REPLACE')
    obj.gauss_stylization.styles[0].vertex_group = "Top"
    new_reports()
    yield from live_run(3)
    obj.vertex_groups.active_index = group.index
    area, regions = view3d()
    with bpy.context.temp_override(window=window(), area=area, region=regions['WINDOW'], object=obj):
        bpy.ops.object.vertex_group_remove()  # the minus button of the Vertex Groups panel
    yield 0.3
    text = new_reports()
    check("deleting the Region's group during a run says so at once",
          "'Top' was deleted while Stylize was running" in text, repr(text[-300:]))
    op = live_operator()
    steps = op.session.steps if op else None
    yield 0.5
    check("... and pauses the run", op is not None and live_operator() is op and op.session.steps == steps)
    obj.gauss_stylization.styles[0].vertex_group = ""
    yield from kit.goes_on("picking no group resumes it")
    yield from kit.end_with('ESC', "Esc then restores the mesh bit-exactly", name, original)


# -- converged: stop when converged --------------------------------------------------------

def converged_then_sigma_resumes(name):
    """A live run whose object reaches its Tolerance stops stepping and says Converged; a Sigma typed
    into the sidebar makes it step again; Esc restores the mesh."""
    obj = bpy.data.objects[name]
    activate(obj)
    settings = obj.gauss_stylization
    original, before = coords(obj), (settings.tolerance, settings.styles[0].sigma)
    settings.tolerance = 0.05  # converges within a few dozen steps
    yield from live_run(1)
    op = live_operator()
    deadline = time.monotonic() + 30.0
    while op is not None and not op.live.converged and time.monotonic() < deadline:
        yield 0.1
    check("a live run that converged says so (status bar and panel)",
          op is not None and "Converged" in op.live.status_text() and op.live.panel_title() == "Converged",
          op.live.status_text() if op else "no run")
    steps = op.session.steps if op else None
    yield 0.5
    check("... and stops stepping", op is not None and live_operator() is op and op.session.steps == steps,
          "steps %s -> %s" % (steps, op.session.steps if op else None))
    yield from type_into_field(SIGMA_PATH, "11")
    deadline = time.monotonic() + 10.0
    while op is not None and op.session.steps == steps and time.monotonic() < deadline:
        yield 0.05
    check("a Sigma typed into the sidebar makes it step again",
          op is not None and live_operator() is op and op.session.steps > steps
          and op.session.applied["styles"][0]["sigma"] == 11.0)
    yield from kit.end_with('ESC', "Esc then restores the mesh bit-exactly", name, original)
    settings.tolerance, settings.styles[0].sigma = before


def cubic_converges_accelerated(name):
    """The cubic method in a live run reaches the default Tolerance and says Converged, in fewer
    than half the steps of the plain iteration on the same mesh and settings (the acceleration
    serves the cubic method too); Esc restores the mesh."""
    obj = bpy.data.objects[name]
    activate(obj)
    settings = obj.gauss_stylization
    original, before = coords(obj), settings.method
    settings.method = 'CUBIC'
    yield from live_run(1)
    op = live_operator()
    deadline = time.monotonic() + 120.0
    while op is not None and not op.live.converged and time.monotonic() < deadline:
        yield 0.1
    steps = op.session.steps if op else None
    check("a cubic live run converges and says so",
          op is not None and op.live.converged and "Converged" in op.live.status_text(),
          op.live.status_text() if op else "no run")
    # The plain iteration from the same start, on the triangles the solver sees.
    core = addon().native.core()
    plain = core.Solver(original.reshape(-1, 3).astype(np.float64), helpers.triangles(obj)[0],
                        method="cubic", acceleration=False,
                        resolution_independent=settings.resolution_independent)
    plain.cubic_lambda = settings.cubic_lambda
    plain.set_styles([core.Style.preset("cube")])
    plain_steps = plain.step_until(settings.tolerance, 2000)
    check("... in fewer than half the plain iteration's steps",
          steps is not None and plain.converged and steps < 0.5 * plain_steps,
          "live %s, plain %s" % (steps, plain_steps))
    print("cubic live run converged in %s steps, plain %s" % (steps, plain_steps), flush=True)
    yield from kit.end_with('ESC', "Esc then restores the mesh bit-exactly", name, original)
    settings.method = before


def unstable_run_says_so(name):
    """A mesh whose steps run away (a cube with a corner pulled far out, at 20 ADMM Iterations) stays in
    place in the viewport, the header says the run is unstable and what to lower (screenshot
    unstable.png), and Esc restores it bit-exactly."""
    import bmesh
    from windowed_actions import area_screenshot
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=1.0)
    bmesh.ops.triangulate(bm, faces=bm.faces[:])
    min(bm.verts, key=lambda v: tuple(v.co)).co.z -= 4.3
    spiked = helpers.object_from_bmesh(bm, "Spiked")
    spiked.location = (0.0, -3.0, 0.0)
    addon().settings_io.add_slot(spiked.gauss_stylization, {"preset": 'CUBE'})
    spiked.gauss_stylization.admm_iterations = 20
    hidden = [o for o in bpy.data.objects if o is not spiked]
    for other in hidden:
        other.hide_set(True)
    with kit.override():
        bpy.ops.view3d.view_selected()
    push_undo("Spiked cube")
    original = coords(spiked)
    yield from live_run(1)
    op = live_operator()
    deadline = time.monotonic() + 60.0
    while op is not None and "unstable" not in op.live.status_text() and time.monotonic() < deadline:
        yield 0.1
    text = op.live.status_text() if op else "no run"
    yield 0.5  # the header redrawn with it
    area_screenshot(os.path.join(kit.SHOTS, "unstable.png"))
    check("a run whose steps run away says 'unstable: lower Lambda or ADMM Iterations'",
          "unstable: lower Lambda or ADMM Iterations" in text, text)
    check("... in the sidebar's box too", op is not None and any(
        line[0] == "unstable: lower Lambda or ADMM Iterations" for line in op.live.panel_lines()))
    now = coords(spiked).reshape(-1, 3)
    size = np.ptp(original.reshape(-1, 3), axis=0).max()
    check("... and the mesh on screen stays within a few sizes of where it was",
          np.isfinite(now).all() and np.abs(now - original.reshape(-1, 3).mean(axis=0)).max() < 5 * size)
    yield from kit.end_with('ESC', "Esc then restores it bit-exactly", "Spiked", original)
    bpy.data.objects.remove(bpy.data.objects["Spiked"])
    for other in hidden:
        other.hide_set(False)
    activate(bpy.data.objects[name])
    with kit.override():
        bpy.ops.view3d.view_selected()
    push_undo("Spiked cube removed")


def replay_button(name):
    """A live run kept with Enter, then the mesh edited: the sidebar's Replay button (shown once a run
    is kept) re-runs the kept run from the shape it started from, bit for bit, and one Ctrl+Z brings
    the edit back."""
    from windowed_actions import find_sidebar_button, found
    obj = bpy.data.objects[name]
    activate(obj)
    original = coords(obj)
    yield from live_run(15)
    press('RET', *viewport_point())
    yield from wait_stopped()
    kept = coords(obj)
    check("Enter keeps the live run", live_operator() is None and not np.array_equal(kept, original))
    edited = kept.copy()
    edited[:30] += 0.02  # an edit after the run
    helpers.mesh_io.write_vertex_coords(obj.data, edited)
    obj.data.update()
    push_undo("Edit after the run")
    yield 0.5
    yield from find_sidebar_button("gauss_replay")
    check("the sidebar shows Replay once a run is kept", found["button"] is not None)
    if found["button"] is None:
        return
    press('LEFTMOUSE', *found["button"])
    yield 1.0
    check("a click on Replay gives the kept run's result bit for bit", np.array_equal(coords(obj), kept))
    press('Z', *viewport_point(), ctrl=True)
    yield 1.0
    obj = bpy.data.objects[name]  # undo replaced the object's data
    check("... and one Ctrl+Z brings the edit back", np.array_equal(coords(obj), edited))
    helpers.mesh_io.write_vertex_coords(obj.data, original)
    obj.data.update()
    push_undo("Replay scenario undone")


def sheet_metal_from_the_style_menu(name):
    """During a live run the slot's Style is turned to Sheet Metal with Ctrl+wheel over the menu, as an
    artist scrolls through a dropdown: the Sigma becomes the style's own, the Styles panel names the
    Lambda it shows from (screenshot sheet_metal_hint.png), typed in it unbends the mesh, and Esc
    restores it bit-exactly."""
    from windowed_actions import area_screenshot, find_sidebar_field
    from measures import developability
    obj = activate(bpy.data.objects[name])
    slot = obj.gauss_stylization.styles[0]
    slot.sigma = addon().settings.schema.FACTS.defaults["sigma"]  # earlier scenarios typed their own Sigma
    original, lam = coords(obj), obj.gauss_stylization.lam
    push_undo("Before Sheet Metal")
    look = addon().settings.schema.LOOK_LAMBDA["sheet_metal"]
    yield from live_run(3)
    yield from find_sidebar_field("gauss_stylization.styles[0].preset")
    check("the sidebar shows the slot's Style menu", found_at() is not None)
    if found_at() is None:
        yield from kit.end_with('ESC', "Esc then restores the mesh bit-exactly", name, original)
        return
    for _ in range(2 * len(addon().settings.schema._preset_items())):  # Ctrl+wheel steps through the items
        if slot.preset == 'SHEET_METAL':
            break
        yield from find_sidebar_field("gauss_stylization.styles[0].preset")  # rows come and go with the style
        if found_at() is None:
            break
        x, y = found_at()
        window().event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
        yield 0.05
        window().event_simulate(type='WHEELDOWNMOUSE', value='PRESS', x=x, y=y, ctrl=True)
        yield 0.3
    check("Ctrl+wheel over the Style menu reaches Sheet Metal", slot.preset == 'SHEET_METAL', slot.preset)
    own = addon().native.preset_strengths()["sheet_metal"][0]
    check("... and the slot's Sigma becomes the style's own", slot.sigma == own, str(slot.sigma))
    op = live_operator()
    check("the run goes on with the new style", op is not None)
    ui = view3d()[1]['UI']
    for _ in range(10):  # the hint is under the slot's rows: scroll the sidebar down to it
        press('WHEELDOWNMOUSE', ui.x + ui.width // 2, ui.y + ui.height // 2)
        yield 0.2
    yield 0.5
    area_screenshot(os.path.join(kit.SHOTS, "sheet_metal_hint.png"))
    check("the Styles panel says which Lambda it shows from", op is not None and any(
        "Sheet Metal shows from Lambda about %g" % look in " ".join(text) for text in [_drawn_labels()]))
    # The Solver panel starts closed; typing into its fields is windowed_self_intersections' part.
    obj.gauss_stylization.lam = look
    op = live_operator()
    yield from wait_steps((op.session.steps if op and op.session else 0) + 60, limit=120.0)
    tris, _ = helpers.triangles(obj)
    before, after = developability(original.reshape(-1, 3), tris), developability(coords(obj).reshape(-1, 3), tris)
    check("the mesh on screen unbends (developability at least halved)", after < 0.5 * before,
          "%.5f -> %.5f" % (before, after))
    yield from kit.end_with('ESC', "Esc then restores it bit-exactly", name, original)
    for _ in range(10):
        press('WHEELUPMOUSE', ui.x + ui.width // 2, ui.y + ui.height // 2)
        yield 0.1
    slot = bpy.data.objects[name].gauss_stylization.styles[0]
    slot.preset, slot.sigma = 'CUBE', addon().settings.schema.FACTS.defaults["sigma"]
    bpy.data.objects[name].gauss_stylization.lam = lam
    push_undo("Sheet Metal scenario undone")


def style_reach_overlay(name):
    """Style Reach switched on with a click on its checkbox: the faces are coloured by their angle to the
    Cube style's normals, the scale drawn in the corner (screenshots style_reach_before.png and
    style_reach_live.png, looked at); during a live run the colours follow the mesh (the drawn angles
    fall), and a click on Select Unreached after Esc selects the faces 15 degrees or more away."""
    from windowed_actions import area_screenshot, find_sidebar_button, found
    from gauss_stylization.sphere import reach_overlay
    obj = activate(bpy.data.objects[name])
    original = coords(obj)
    yield from find_sidebar_field_click("gauss_stylization.show_style_reach")
    check("a click on the Style Reach checkbox switches it on", obj.gauss_stylization.show_style_reach)
    yield 1.0
    area_screenshot(os.path.join(kit.SHOTS, "style_reach_before.png"))
    drawn = reach_overlay._cache.get(obj.as_pointer(), {})
    before = np.nanmean(drawn["angles"]) if drawn.get("angles") is not None else None
    check("the overlay is drawn with every face's angle", before is not None and np.isfinite(before),
          str(drawn.get("problem")))
    yield from live_run(40)
    yield 1.0  # a redraw after the last refresh
    area_screenshot(os.path.join(kit.SHOTS, "style_reach_live.png"))
    drawn = reach_overlay._cache.get(obj.as_pointer(), {})
    during = np.nanmean(drawn["angles"]) if drawn.get("angles") is not None else None
    check("during the run the drawn angles follow the mesh (their mean falls)",
          before is not None and during is not None and during < 0.7 * before, "%s -> %s" % (before, during))
    yield from kit.end_with('ESC', "Esc restores the mesh bit-exactly", name, original)
    yield from find_sidebar_button("gauss_select_unreached")
    check("the sidebar shows Select Unreached while Style Reach is on", found["button"] is not None)
    if found["button"] is not None:
        press('LEFTMOUSE', *found["button"])
        yield 1.0
        obj = bpy.data.objects[name]
        if obj.mode == 'EDIT':
            obj.update_from_editmode()
        selected = np.zeros(len(obj.data.polygons), bool)
        obj.data.polygons.foreach_get("select", selected)
        from gauss_stylization import reach_operators
        expected = np.nan_to_num(reach_operators.polygon_angles(obj), nan=-1.0) >= 15.0
        check("a click on it selects the faces 15 degrees or more from the Cube style's normals",
              selected.any() and np.array_equal(selected, expected), "%d of %d" % (selected.sum(), expected.sum()))
        if obj.mode == 'EDIT':
            with kit.override():
                bpy.ops.object.mode_set(mode='OBJECT')
    check("the overlay's draw handlers raised nothing", not reach_overlay.failures(), str(reach_overlay.failures()))
    bpy.data.objects[name].gauss_stylization.show_style_reach = False
    push_undo("Style Reach scenario undone")


def from_gauss_map_button(name):
    """From Gauss Map as an artist uses it: an icosahedron beside Spot selected, Spot active, a click on
    the Styles panel's button and Enter in its dialog add a Gauss Map slot of the icosahedron's 20 face
    directions; a live run then turns Spot's faces towards them (the share within 10 degrees of them
    grows) and Esc restores Spot bit-exactly."""
    import bmesh
    from windowed_actions import find_sidebar_button, found
    from measures import aligned_share
    obj = bpy.data.objects[name]
    bm = bmesh.new()
    bmesh.ops.create_icosphere(bm, subdivisions=1, radius=0.5)
    example = helpers.object_from_bmesh(bm, "Icosahedron")
    bm.free()
    example.location = (obj.dimensions.x * 1.5, 0.0, 0.0)
    activate(example)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj
    push_undo("Icosahedron beside")
    slots_before = len(obj.gauss_stylization.styles)
    original = coords(obj)
    yield from find_sidebar_button("gauss_style_from_gauss_map")
    check("the Styles panel shows From Gauss Map", found["button"] is not None)
    if found["button"] is None:
        return
    press('LEFTMOUSE', *found["button"])
    yield 1.0
    press('RET', *found["button"])  # the dialog's OK: the example is the other selected mesh
    yield 1.0
    settings = obj.gauss_stylization
    added = len(settings.styles) == slots_before + 1 and settings.styles[-1].preset == 'GAUSS_MAP'
    check("a click and Enter add a Gauss Map slot of the example", added,
          "%d slots, last %s" % (len(settings.styles), settings.styles[-1].preset if settings.styles else None))
    if not added:
        return
    for _ in range(slots_before):  # only the new slot (a slot without a Region acts where it is the first)
        settings.styles.remove(0)
    stored = settings.styles[-1].gauss_map  # the example's directions, turned into Spot's object space
    directions = np.empty((len(stored), 3), np.float32)
    stored.foreach_get("vector", directions.reshape(-1))
    check("... holding the icosahedron's 20 face directions", len(directions) == 20, str(len(directions)))
    tris = helpers.triangles(obj)[0]
    before = aligned_share(original.reshape(-1, 3), tris, directions)
    yield from live_run(40)
    after = aligned_share(coords(obj).reshape(-1, 3), tris, directions)
    check("the live run turns Spot's faces towards the example's directions", after > before + 0.1,
          "%.3f -> %.3f" % (before, after))
    yield from kit.end_with('ESC', "Esc restores Spot bit-exactly", name, original)
    obj = bpy.data.objects[name]
    obj.gauss_stylization.styles.clear()
    kit.addon().settings_io.add_slot(obj.gauss_stylization, {"preset": 'CUBE'})
    bpy.data.objects.remove(bpy.data.objects["Icosahedron"])
    activate(obj)
    push_undo("From Gauss Map scenario undone")


def find_sidebar_field_click(data_path):
    """Generator: a click on the sidebar field (a checkbox) of ``data_path``."""
    from windowed_actions import find_sidebar_field
    yield from find_sidebar_field(data_path)
    check("the sidebar shows %s" % data_path, found_at() is not None)
    if found_at() is not None:
        x, y = found_at()
        ui = view3d()[1]['UI']
        press('LEFTMOUSE', ui.x + ui.width // 2 - 60, y)  # the checkbox is left of the value column
        yield 0.5


def found_at():
    from windowed_actions import found
    return found.get("at")


def _drawn_labels():
    """The labels the Styles panel draws now (panel_recorder)."""
    from panel_recorder import draw, labels
    with kit.override():
        return labels(draw(addon().ui.VIEW3D_PT_gauss_styles, bpy.context))


# -- scenario -------------------------------------------------------------------------------

def make_other(name):
    """A second mesh beside the first (its own copy of the mesh)."""
    source = bpy.data.objects[name]
    other = source.copy()
    other.data = source.data.copy()
    other.name = "Other"
    other.location = (source.dimensions.x * 1.5, 0.0, 0.0)
    bpy.context.scene.collection.objects.link(other)
    activate(source)
    push_undo("Second object")
    return other.name


SCENARIOS = ("sigma_and_move_during_a_kept_run", "sigma_and_move_during_a_cancelled_run",
             "gizmo_and_header_clicks", "outliner_selection", "several_objects", "region_group_deleted",
             "converged_then_sigma_resumes", "cubic_converges_accelerated", "unstable_run_says_so", "replay_button",
             "sheet_metal_from_the_style_menu", "style_reach_overlay", "from_gauss_map_button")


def run_scenario(scenario_name, name, other):
    function = globals()[scenario_name]
    return function(name, other) if function.__code__.co_argcount == 2 else function(name)


kit.start(kit.cube_style_scenarios(SCENARIOS, run_scenario, prepare=make_other), "windowed_live_run_result.txt",
          time_limit=TIME_LIMIT)
