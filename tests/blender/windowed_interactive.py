"""The live run in a real window, third part: the interactive tools: the Gauss
sphere overlay, editing on it, and dragging pin handles during a live run. Run by
run_windowed.sh after windowed_run_endings.py; windowed_kit.py's helpers (check, press, window, view3d,
live_run, wait_steps, ...) the scenarios use as ``d``; every press and drag is simulated:

    blender --factory-startup --enable-event-simulate -P tests/blender/windowed_interactive.py -- BUILD_DIR

The summary goes to BUILD_DIR/screenshots/windowed_interactive_result.txt.
"""

import json
import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import windowed_kit as d  # noqa: E402  (also sets up the paths and the window options)
from windowed_actions import area_screenshot  # noqa: E402

from gauss_stylization import native, settings_io, styles  # noqa: E402  (windowed_kit put the add-on on sys.path)
from gauss_stylization.handles import handle_tool, handles  # noqa: E402
from gauss_stylization.sphere import gauss_sphere, sphere_overlay  # noqa: E402

TIME_LIMIT = 480.0  # seconds (idle: about 1 minute; a busy 2-core machine redraws slowly)


# -- where things are on screen ---------------------------------------------------------

def _main_region(d):
    area, regions = d.view3d()
    return area, regions['WINDOW']


def sphere_frame(d):
    """The sphere's Frame in window pixels."""
    area, region = _main_region(d)
    where = sphere_overlay.placement(area, region)
    return gauss_sphere.Frame(where.x + region.x, where.y + region.y, where.radius)


def direction_pixel(d, obj, direction):
    """Window pixel where an object-space direction shows on the sphere (and whether it faces us)."""
    area, region = _main_region(d)
    seen = sphere_overlay.view_rotation(region.data, obj) @ np.asarray(direction, float)
    seen /= np.linalg.norm(seen)
    x, y = gauss_sphere.to_pixels(seen[None], sphere_frame(d))[0]
    return (x, y), seen[2] > 0


def shown_normals(obj):
    slot = styles.active_slot(obj.gauss_stylization)
    normals = np.array(slot.custom_normal_list(), float).reshape(-1, 3)
    return normals @ styles.rotation_matrix(slot).T


def pixels_of(d, obj):
    return [direction_pixel(d, obj, n)[0] for n in shown_normals(obj)]


def free_spot(d, obj):
    """A pixel on the sphere far from every dot of the active Custom slot."""
    where = sphere_frame(d)
    angles = np.radians(np.arange(0, 360, 30))
    spots = [(where.x + 0.5 * where.radius * np.cos(a), where.y + 0.5 * where.radius * np.sin(a)) for a in angles]
    dots = pixels_of(d, obj)
    return max(spots, key=lambda p: min(np.hypot(p[0] - x, p[1] - y) for x, y in dots))


def near(a, b, tolerance=1.5):
    return np.hypot(a[0] - b[0], a[1] - b[1]) <= tolerance


def drag(d, start, end, moves=6, button='LEFTMOUSE'):
    """Press at ``start``, move to ``end`` in ``moves`` steps, release there (window pixels)."""
    win = d.window()
    x0, y0 = (int(round(v)) for v in start)
    x1, y1 = (int(round(v)) for v in end)
    win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x0, y=y0)
    win.event_simulate(type=button, value='PRESS', x=x0, y=y0)
    for k in range(1, moves + 1):
        win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x0 + (x1 - x0) * k // moves,
                           y=y0 + (y1 - y0) * k // moves)
    win.event_simulate(type=button, value='RELEASE', x=x1, y=y1)


def disc_mask(d, shape, grow=1.0):
    """Pixels of an area screenshot inside the sphere's outline (``grow`` times its radius)."""
    area, _ = d.view3d()
    where = sphere_frame(d)
    rows, cols = np.mgrid[0:shape[0], 0:shape[1]]
    return np.hypot(cols + area.x - where.x, rows + area.y - where.y) <= grow * where.radius


# -- scenarios ----------------------------------------------------------------------------

def sphere_is_drawn(d, name):
    """The overlay appears in the corner when switched on, and nowhere else."""
    obj = d.activate(bpy.data.objects[name])
    settings = obj.gauss_stylization
    settings_io.apply_dict(settings, {"styles": [{"preset": 'CUBE'}], "active_style_index": 0,
                                      "show_gauss_sphere": False})
    yield 0.5
    off = area_screenshot(os.path.join(d.SHOTS, "sphere_off.png"))
    settings.show_gauss_sphere = True
    yield 0.5
    on = area_screenshot(os.path.join(d.SHOTS, "sphere_overlay.png"))
    area, _ = d.view3d()
    d.check("screenshot of the Gauss sphere has the 3D view's size",
            on.shape[:2] == (area.height, area.width), "%s vs %dx%d" % (on.shape, area.height, area.width))
    changed = np.abs(on[..., :3] - off[..., :3]).sum(axis=2) > 0.05
    inside, around = disc_mask(d, on.shape), ~disc_mask(d, on.shape, grow=1.6)
    d.check("the Gauss sphere is drawn in its corner", changed[inside].mean() > 0.9,
            "%.2f of the disc changed" % changed[inside].mean())
    d.check("... and nothing else in the view changes", changed[around].mean() < 0.01,
            "%.4f changed elsewhere" % changed[around].mean())
    dots = [p for p, front in (direction_pixel(d, obj, n) for n in styles.make_style(
        native.core(), settings.styles[0]).normals) if front]
    white = [on[int(round(y)) - area.y, int(round(x)) - area.x, :3].min() > 0.9 for x, y in dots]
    d.check("the Cube style's preferred normals facing the viewer are white dots",
            dots and all(white), "%d of %d dots white" % (sum(white), len(dots)))


def _custom(obj, normals):
    settings_io.apply_dict(obj.gauss_stylization, {"styles": [{"preset": 'CUSTOM', "custom_normals": normals}],
                                                   "active_style_index": 0, "show_gauss_sphere": True})


def sphere_editing(d, name):
    obj = d.activate(bpy.data.objects[name])
    _custom(obj, [(0.0, 0.0, 1.0)])
    d.push_undo("Custom style for sphere editing")
    yield 0.5
    where = sphere_frame(d)
    # Presses away from the sphere keep their meaning: a click deselects, a drag box-selects.
    # (Before any Ctrl+Z here: a simulated Ctrl stays down for the next drag, which then subtracts.)
    d.press('LEFTMOUSE', int(where.x), int(where.y + 1.6 * where.radius))
    yield 0.5
    deselected = not obj.select_get()
    area, region = _main_region(d)
    drag(d, (region.x + 0.3 * region.width, region.y + region.height - 60),
         (region.x + 0.75 * region.width, region.y + 60), moves=8)
    yield 0.6
    d.check("with the sphere editable, a drag beside it still box-selects",
            deselected and obj.select_get() and len(pixels_of(d, obj)) == 1)
    target = free_spot(d, obj)
    d.press('LEFTMOUSE', int(target[0]), int(target[1]))
    yield 0.4
    pixels = pixels_of(d, obj)
    d.check("a click on the Gauss sphere adds a normal where it was clicked",
            len(pixels) == 2 and near(pixels[1], (int(target[0]), int(target[1]))), str(pixels))

    start = pixels[-1]
    end = (start[0] + 25, start[1] + 20)
    drag(d, start, end)
    yield 0.4
    moved = pixels_of(d, obj)
    d.check("dragging a dot moves its normal under the mouse",
            len(moved) == 2 and near(moved[1], (int(end[0]), int(end[1]))) and near(moved[0], pixels[0]),
            str(moved))

    d.press('Z', *d.viewport_point(), ctrl=True)
    yield 0.5
    obj = bpy.data.objects[name]  # undo replaced the object's data
    undone = pixels_of(d, obj)
    d.check("Ctrl+Z undoes the drag (one step)", len(undone) == 2 and near(undone[1], pixels[1]), str(undone))

    first = pixels_of(d, obj)[0]
    d.press('RIGHTMOUSE', int(first[0]) + 3, int(first[1]) - 2)
    yield 0.4
    left = pixels_of(d, obj)
    d.check("a right-click on the sphere removes the nearest normal",
            len(left) == 1 and near(left[0], pixels[1]), str(left))
    d.press('RIGHTMOUSE', int(left[0][0]), int(left[0][1]))
    yield 0.4
    d.check("... but never the last one", len(pixels_of(d, obj)) == 1)

    empty = (where.x, where.y + 1.6 * where.radius)  # the grid above the sphere, left of the mesh
    d.press('LEFTMOUSE', int(empty[0]), int(empty[1]))
    yield 0.4
    d.check("a click beside the sphere keeps its meaning (deselects) and edits nothing",
            not obj.select_get() and len(pixels_of(d, obj)) == 1)
    d.activate(obj)
    settings_io.apply_dict(obj.gauss_stylization, {"styles": [{"preset": 'CUBE'}]})
    d.press('LEFTMOUSE', int(where.x), int(where.y))
    yield 0.4
    d.check("with a preset style active a click on the sphere is an ordinary click (deselects)",
            not obj.select_get() and obj.gauss_stylization.styles[0].preset == 'CUBE')
    d.activate(obj)


def sphere_editing_during_a_run(d, name):
    obj = d.activate(bpy.data.objects[name])
    _custom(obj, [(0.0, 0.0, 1.0), (1.0, 0.0, 0.0)])
    original = d.coords(obj)
    yield from d.live_run(3)
    free = free_spot(d, obj)
    d.press('LEFTMOUSE', int(free[0]), int(free[1]))
    yield 0.3
    op = d.live_operator()
    d.check("a click on the sphere during a run adds a normal and leaves the run going",
            op is not None and len(obj.gauss_stylization.styles[0].custom_normals) == 3)
    steps = op.session.steps if op else 0
    yield from d.wait_steps(steps + 3)
    op = d.live_operator()
    d.check("... and the running solver takes it at its next steps",
            op is not None and len(op.session.applied["styles"][0]["custom_normals"]) == 3)
    yield from d.end_with('ESC', "Esc after editing on the sphere restores the mesh bit-exactly", name, original)
    obj.gauss_stylization.show_gauss_sphere = False


# -- pin handles ---------------------------------------------------------------------------

def _pin_top_and_bottom(d, obj, share=0.06):
    """Pin Group "Handles": the top and bottom ``share`` of the world-space height (ears, feet)."""
    world = np.array(obj.matrix_world)
    z = d.coords(obj) @ world[2, :3] + world[2, 3]
    low, high = z.min(), z.max()
    chosen = np.flatnonzero((z < low + share * (high - low)) | (z > high - share * (high - low)))
    if "Handles" in obj.vertex_groups:
        obj.vertex_groups.remove(obj.vertex_groups["Handles"])
    obj.vertex_groups.new(name="Handles").add([int(i) for i in chosen], 1.0, 'REPLACE')
    settings_io.apply_dict(obj.gauss_stylization, {"pin_group": "Handles", "show_gauss_sphere": False,
                                                   "styles": [{"preset": 'CUBE'}], "active_style_index": 0})


def _pixels(d, obj, points):
    """Window pixels (N by 2) of object-space points in the 3D view."""
    area, region = _main_region(d)
    return handles.project(np.asarray(points, float), obj.matrix_world, region, region.data) + [region.x, region.y]


def _top_handle(d, obj):
    """(pins of the highest handle, the window pixel of its pin nearest to its middle)."""
    session = d.live_operator().session
    found = handles.Handles(session)
    world_z = [np.mean(found.targets[part] @ np.array(obj.matrix_world)[2, :3]) for part in found.parts]
    part = found.parts[int(np.argmax(world_z))]
    pins = found.pins[part]
    pixels = _pixels(d, obj, found.targets[part])
    middle = pixels.mean(axis=0)
    return pins, pixels[int(np.argmin(np.hypot(*(pixels - middle).T)))]


def _drag_handle(d, start, offset, key=None, moves=10):
    """Press on a pin at ``start``, move by ``offset`` pixels (pressing ``key`` first), release."""
    win = d.window()
    x0, y0 = int(round(start[0])), int(round(start[1]))
    win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x0, y=y0)
    win.event_simulate(type='LEFTMOUSE', value='PRESS', x=x0, y=y0)
    if key:
        win.event_simulate(type=key, value='PRESS', x=x0, y=y0)
        win.event_simulate(type=key, value='RELEASE', x=x0, y=y0)
    for k in range(1, moves + 1):
        win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x0 + int(offset[0] * k / moves),
                           y=y0 + int(offset[1] * k / moves))


def _release(d, at):
    d.window().event_simulate(type='LEFTMOUSE', value='RELEASE', x=int(round(at[0])), y=int(round(at[1])))


def header_fits(d, name):
    """Issue 26: during a drag the header was cut off and named two meanings of Esc. Checks ``name`` =
    the header's text (the live operator's status line) has one Esc and fits the 3D view's header at
    the window's width; a screenshot of the header goes to BUILD/screenshots/handle_drag_header.png."""
    from gauss_stylization.view.sidebar import text_width
    op = d.live_operator()
    area, regions = d.view3d()
    header = regions['HEADER']
    text = op.status_line() if op is not None else ""
    with bpy.context.temp_override(window=d.window(), area=area, region=header):
        wide = text_width(text)
    room = header.width - 2 * 20.0 * bpy.context.preferences.system.ui_scale
    pixels = area_screenshot(os.path.join(d.SHOTS, "area_header.png"), keep=False)
    top = header.y - area.y
    shot = pixels[top:top + header.height]
    image = bpy.data.images.new("header", shot.shape[1], shot.shape[0], alpha=True)
    image.pixels.foreach_set(np.ascontiguousarray(shot, np.float32).ravel())
    image.filepath_raw = os.path.join(d.SHOTS, "handle_drag_header.png")
    image.file_format = 'PNG'
    image.save()
    bpy.data.images.remove(image)
    d.check(name, text.count("Esc") == 1 and "cancel" not in text and wide <= room,
            "%r: %.0f px for %.0f px" % (text, wide, room))


def handle_dragging(d, name):
    obj = d.activate(bpy.data.objects[name])
    _pin_top_and_bottom(d, obj)
    d.push_undo("Handles")
    original = d.coords(obj)
    yield from d.live_run(3)
    pins, grab = _top_handle(d, obj)
    before = d.coords(obj)
    others = np.setdiff1d(np.array(d.live_operator().session.solver.pinned), pins)
    start_pixels = _pixels(d, obj, before[pins])
    steps = d.live_operator().session.steps
    _drag_handle(d, grab, (100, 0))
    yield from d.wait_steps(steps + 3)  # still holding the button
    area_screenshot(os.path.join(d.SHOTS, "handle_drag.png"))
    header_fits(d, "while a handle is dragged, the header says what the keys do to it, once, and fits")
    op = d.live_operator()
    d.check("a press on a pin grabs its handle and the run keeps stepping while it is dragged",
            op is not None and handle_tool.tool_of(op).drag is not None and op.session.steps > steps + 2,
            "steps %d -> %s" % (steps, op.session.steps if op else None))
    _release(d, (grab[0] + 100, grab[1]))
    yield from d.wait_steps(d.live_operator().session.steps + 5)
    now = d.coords(obj)
    area, region = _main_region(d)
    moved = _pixels(d, obj, now[pins]) - start_pixels
    error = np.abs(moved - [100, 0]).max()
    d.check("the dragged handle's pins end where the mouse says (100 px), within 1% of the view's width",
            error <= 0.01 * region.width, "largest error %.2f px (width %d)" % (error, region.width))
    near_top = np.setdiff1d(np.flatnonzero(_pixels(d, obj, before)[:, 1] > start_pixels[:, 1].min() - 60), pins)
    follow = (_pixels(d, obj, now[near_top]) - _pixels(d, obj, before[near_top]))[:, 0].mean()
    d.check("the rest of the mesh follows the handle", follow > 10.0, "vertices near it moved %.1f px" % follow)
    d.check("the other handles stay where they are", np.array_equal(now[others], before[others]))
    d.check("dragging does not re-factor", d.live_operator().session.solver.factorization_count == 1)

    pins, grab = _top_handle(d, obj)
    world = np.array(obj.matrix_world)
    held = (d.coords(obj)[pins] @ world[:3, :3].T)
    _drag_handle(d, grab, (-60, 40), key='Z')
    yield 0.4
    header_fits(d, "... also along an axis")
    _release(d, (grab[0] - 60, grab[1] + 40))
    yield from d.wait_steps(d.live_operator().session.steps + 3)
    along = d.coords(obj)[pins] @ world[:3, :3].T - held
    d.check("Z while dragging moves the handle along the global Z axis only",
            np.abs(along[:, :2]).max() < 1e-4 and np.abs(along[:, 2]).min() > 1e-3,
            "x/y drift %.2g, z moved %.3g" % (np.abs(along[:, :2]).max(), np.abs(along[:, 2]).min()))

    pins, grab = _top_handle(d, obj)
    targets = np.array(d.live_operator().session.solver.pin_positions)
    _drag_handle(d, grab, (40, 40))
    yield 0.3
    d.press('RIGHTMOUSE', int(grab[0]) + 40, int(grab[1]) + 40)
    yield 0.3
    op = d.live_operator()
    d.check("a right-click during a drag puts the handle back and the run goes on",
            op is not None and np.array_equal(op.session.solver.pin_positions, targets))
    d.window().event_simulate(type='LEFTMOUSE', value='RELEASE', x=int(grab[0]) + 40, y=int(grab[1]) + 40)
    yield from d.end_with('ESC', "Esc after dragging handles restores the mesh bit-exactly", name, original)

    yield from d.live_run(3)
    pins, grab = _top_handle(d, obj)
    _drag_handle(d, grab, (50, -30))
    _release(d, (grab[0] + 50, grab[1] - 30))
    yield from d.wait_steps(d.live_operator().session.steps + 5)
    d.press('RET', *d.viewport_point())
    yield from d.wait_stopped()
    kept = d.coords(bpy.data.objects[name])
    d.check("Enter keeps the dragged result", d.live_operator() is None and not np.array_equal(kept, original))
    last = bpy.context.window_manager.operators[-1]
    d.check("... and the redo panel's operator holds where the handles were left",
            last.bl_idname == "OBJECT_OT_gauss_stylize" and name in json.loads(last.properties.pin_targets or "{}"))
    d.press('Z', *d.viewport_point(), ctrl=True)
    yield 0.5
    d.check("one Ctrl+Z then brings the mesh back bit-exactly",
            np.array_equal(d.coords(bpy.data.objects[name]), original))
    obj = bpy.data.objects[name]
    obj.gauss_stylization.pin_group = ""


def scenario():
    name = d.set_up()
    yield 1.0  # first redraws
    yield from d.open_gauss_tab()
    yield from sphere_is_drawn(d, name)
    yield from sphere_editing(d, name)
    yield from sphere_editing_during_a_run(d, name)
    yield from handle_dragging(d, name)


d.start(scenario(), "windowed_interactive_result.txt", time_limit=TIME_LIMIT)
